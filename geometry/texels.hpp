#pragma once
/// 3D texel extraction, paper §3.2: seeds at local maxima of the depth, global Otsu
/// selection of the salient seeds, one region per seed from a local Otsu threshold, and the
/// merging of regions with similar depth.

#include <vector>

#include "geometry/depth_map.hpp"
#include "geometry/diagnostics.hpp"
#include "geometry/mesh.hpp"
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
