#pragma once
/// 3D texel extraction, paper §3.2: seeds at local maxima of the depth, global Otsu
/// selection of the salient seeds, one region per seed from a local Otsu threshold, and the
/// merging of regions with similar depth.

#include <vector>

#include "geometry/depth_map.hpp"
#include "geometry/diagnostics.hpp"
#include "geometry/mesh.hpp"
#include "geometry/otsu.hpp"
#include "geometry/topology.hpp"

namespace geotex {

struct TexelParams {
    double radius = 0;            ///< r, mesh units (> 0): the disc of the local maxima; the
                                  ///< local threshold uses the 2r disc
    double merge_overlap = 0.5;   ///< two touching regions merge when their depth intervals
                                  ///< ]mu - sigma, mu + sigma[ overlap by at least this
                                  ///< fraction of the narrower interval (0..1)
    double min_depth_rel = 0.01;  ///< a seed shallower than this fraction of r is never
                                  ///< salient, whatever Otsu says (a perfect sphere or plane
                                  ///< has only numerical depth)
    int min_faces = 3;            ///< regions with fewer faces are dropped
};

/// One salient region.
struct Texel {
    std::vector<int> faces;  ///< sorted face indices
    int seed = -1;           ///< the deepest seed vertex that produced it
    DetailOrientation orientation = DetailOrientation::Positive;
    double threshold = 0;   ///< the local Otsu threshold of that seed, mesh units
    double depth_mean = 0;  ///< mean face depth, mesh units
    double depth_std = 0;   ///< population standard deviation of the face depths
};

struct TexelSet {
    std::vector<Texel> texels;    ///< ordered by their smallest face index
    std::vector<int> face_texel;  ///< #F, texel index or -1
    double global_threshold = 0;  ///< Otsu threshold of the vertex depths (after the floor)
    int num_local_maxima = 0;     ///< local maxima at or above the global threshold (= seeds)
    int num_regions = 0;          ///< regions grown, before merging
    int num_merges = 0;           ///< merges performed
    Diagnostics diagnostics;
};

/// Overlap of the depth intervals ]mu_a - sigma_a, mu_a + sigma_a[ and ]mu_b - sigma_b,
/// mu_b + sigma_b[ as a fraction of the narrower one, in [0, 1] (the merge test of
/// make_texels). A zero-width interval scores 1 inside the other closed interval, else 0.
double depth_interval_overlap(double mu_a, double sigma_a, double mu_b, double sigma_b);

/// The seeds' threshold of make_texels (§3.2.1): Otsu's threshold of the vertex depths of the
/// whole mesh (#V, in any order: Otsu sorts them), at least min_depth_rel * r. Taken by value,
/// as Otsu sorts a copy: a caller that moves its depths in spares one. Throws InvalidInput on
/// a non-finite depth.
double texel_global_threshold(std::vector<double> vertex_depth, const TexelParams& params);
/// The same threshold from Otsu's split of those depths, computed elsewhere (a tiled run's
/// texel jobs merge every tile's sorted depths: otsu_threshold_merged).
double texel_global_threshold(const OtsuResult& otsu, const TexelParams& params);

/// The region grown from one seed (§3.2.2), before the merging.
struct TexelRegion {
    int seed = -1;
    double threshold = 0;      ///< the seed's local Otsu threshold, mesh units
    double mean = 0, std = 0;  ///< of the region's face depths
    std::vector<int> faces;    ///< sorted; empty when no face reaches the threshold
    std::vector<int> touch;    ///< sorted: the faces and every face next to one (a tiled
                               ///< run's join keeps only those next to one: TexelRegionJoin)
};
struct TexelRegions {
    std::vector<TexelRegion> regions;  ///< deepest seed first (equal depths: lower id first)
    int num_seeds = 0;
};

/// The first two steps of make_texels: the seeds above `global_threshold` among the vertices
/// flagged in `seed_vertices` (#V, or empty: all), and the region of each. With the whole
/// mesh's threshold, a tile (tiles.hpp) grows the regions of the seeds it owns, and
/// merge_texel_regions joins those of every tile. Throws as make_texels.
TexelRegions grow_texel_regions(const Mesh& mesh, const MeshTopology& topology,
                                const DepthMap& depth, const TexelParams& params,
                                double global_threshold, const std::vector<char>& seed_vertices);

/// The last step of make_texels: regions (ordered deepest seed first, over the faces of a mesh
/// with the face depths `face_depth`, #F) merged and turned into texels; the regions' `touch`
/// lists tell which regions meet (a list may leave out its region's own faces). Equal to
/// make_texels when the regions are those of the whole mesh. The regions are taken by value and
/// their lists released as the merge goes, so that a caller that moves them in holds them no longer
/// than needed. Throws InvalidInput when a face id is not below #F.
TexelSet merge_texel_regions(TexelRegions regions, const std::vector<double>& face_depth,
                             const TexelParams& params, DetailOrientation orientation,
                             double global_threshold);

/// Texels of one oriented depth map. Deterministic. Throws InvalidInput when the radius is
/// not positive or the depth map does not match the mesh.
///
/// Merge rule (the paper only says "overlap enough"): regions A and B are candidates when
/// they share a face or a face of A shares an edge with a face of B. With I = ]mu - sigma,
/// mu + sigma[ of each region's face depths, they merge when
///     |I_A ∩ I_B| >= merge_overlap * min(|I_A|, |I_B|),
/// where a zero-width interval counts as fully overlapped when its point lies in the other
/// closed interval. Decisions use the statistics of the regions as grown (not of merged
/// groups) and merging is transitive (union-find), so the result does not depend on order.
/// A face claimed by two regions that do not merge goes to the region of the deeper seed.
TexelSet make_texels(const Mesh& mesh, const MeshTopology& topology, const DepthMap& depth,
                     const TexelParams& params);

}  // namespace geotex
