#pragma once
/// Rims: texels that a detail of the other orientation makes in its surroundings by pulling
/// the disc means (an engraving drags the smoothed surface down, so the untouched
/// background around it stands above it), and the vertices to leave out of a second
/// smoothing so that they disappear. docs/rims.md explains the method; not in the paper.

#include <vector>

#include "geometry/depth_map.hpp"
#include "geometry/mesh.hpp"
#include "geometry/texels.hpp"
#include "geometry/topology.hpp"

namespace geotex {

struct RimParams {
    double radius = 0;         ///< r, mesh units (> 0)
    double reach_rel = 2.0;    ///< a texel is a rim when a deeper texel of the other orientation
                               ///< lies within reach_rel * r of it along mesh edges (the twiced
                               ///< disc mean reaches 2r)
    double margin_rel = 0.25;  ///< left out of the second smoothing: the vertices within
                               ///< margin_rel * r of a detail (its texel stops at the local
                               ///< threshold, part-way down its walls, which still pull)
};

struct Rims {
    std::vector<char> positive_rim;  ///< #positive texels: 1 when the texel is a rim
    std::vector<char> negative_rim;  ///< #negative texels: 1 when the texel is a rim
    /// #V: 1 within RimParams::margin_rel * r of the negative texels that make a rim and are
    /// not rims themselves, the details that must not pull the smoothing of positive details
    /// (empty when there is none: the positive texels need no second smoothing)
    std::vector<char> exclude_for_positive;
    std::vector<char> exclude_for_negative;  ///< #V: likewise, of the positive texels
    int num_excluded_for_positive = 0;       ///< negative texels behind exclude_for_positive
    int num_excluded_for_negative = 0;       ///< positive texels behind exclude_for_negative
};

/// Whether some texel of `set` (the texels of `depth`'s orientation) can be a rim of a detail
/// of the other orientation that make_rims would leave out of a second smoothing, decided
/// without that orientation's depth map: a vertex that
/// stands out on the other side is measured to that side's oriented surface, so its depth
/// there is at most its distance to any vertex of that surface: its own smoothed position,
/// or a nearer one found by walking over `topology` from it. When no such distance reaches
/// the shallowest texel of `set`, no texel of the other orientation is deeper than a texel
/// of `set`, and make_rims would leave nothing out for this orientation: the other depth
/// map need not be built (plain sphere-1: the raised shapes' own rims are shallower than
/// every shape). Where some do, the texels of `set` within `params`' reach of the faces
/// that may hold such a texel are compared with their bound: a deep rim far from every
/// shallower texel makes no rim either, and nor does one whose deepest vertices all lie
/// nearer to a deeper texel of `set` than to any other (a tall detail's own rim, itself a
/// rim). So false means that make_rims would leave nothing out for `set`'s orientation,
/// although it may still call some texels rims. O(#V + #F + the walks of the few vertices
/// whose own smoothed position is not near enough, and of the reach around them). Throws
/// InvalidInput when the sizes do not match the mesh, or on make_rims' conditions on `params`.
bool rims_possible(const Mesh& mesh, const MeshTopology& topology,
                   const std::vector<Eigen::Vector3d>& vertex_normal,
                   const SmoothedSurface& smoothed, const TexelSet& set, const DepthMap& depth,
                   const RimParams& params);

/// The greatest vertex depth of each texel of `set` in `depth` (#texels): what make_rims
/// compares.
std::vector<double> texel_depths(const Mesh& mesh, const TexelSet& set, const DepthMap& depth);

/// make_rims' flags, in parts that a tile (tiles.hpp) can compute.
struct RimFlags {
    std::vector<char> positive_rim;        ///< #positive texels: the texel is a rim
    std::vector<char> negative_rim;        ///< #negative texels: the texel is a rim
    std::vector<char> positive_makes_rim;  ///< #positive texels: some negative texel is its rim
    std::vector<char> negative_makes_rim;  ///< #negative texels: some positive texel is its rim
};

/// Flags all clear for `positive` and `negative` texels: what a part of the mesh with no
/// texel vertex gives, and where or-ing every part's flags starts.
RimFlags no_rim_flags(std::size_t positive, std::size_t negative);

/// The flags make_rims sets, counting only the vertices of texels where `evaluate` (#V, or
/// empty: all) is nonzero: a texel is a rim when one of those vertices has, within the reach,
/// a nearest texel of the other orientation that is deeper. `positive_depths` and
/// `negative_depths` are the texels' depths over the whole mesh (texel_depths), so that a tile
/// holding part of a texel compares what the whole mesh would; each tile evaluates the vertices
/// it owns, and the flags of every tile or-ed together are make_rims'. Throws InvalidInput on
/// sizes that do not match.
RimFlags find_rims(const Mesh& mesh, const MeshTopology& topology, const TexelSet& positive,
                   const std::vector<double>& positive_depths, const TexelSet& negative,
                   const std::vector<double>& negative_depths, const RimParams& params,
                   const std::vector<char>& evaluate);

/// The vertices (#V flags) within margin_rel * r, along mesh edges, of the texels of `set`
/// where `use` (#texels) is nonzero: make_rims' exclude_for_* of the other orientation when
/// `use` flags the texels that make a rim and are not rims. Throws InvalidInput when `use`
/// does not have one flag per texel.
std::vector<char> rim_detail_vertices(const Mesh& mesh, const MeshTopology& topology,
                                      const TexelSet& set, const std::vector<char>& use,
                                      const RimParams& params);

/// Classifies the texels of the two oriented depth maps of one smoothing: a texel is a rim
/// when a texel of the other orientation with a larger greatest vertex depth lies within
/// reach_rel * r of it (geodesic distance along mesh edges). A rim is never deeper than the
/// detail that makes it: the detail's own depth is its full height less the pull, the rim's is
/// the pull alone. Only a detail that makes a rim is to be left out: where no texel is a rim
/// (one orientation only, or shallow noise beside deeper details) nothing changes.
/// Deterministic (the two orientations walk in parallel, each sequentially), O(#V log #V).
/// Throws InvalidInput when the radius is not positive and finite, a depth map does not match the
/// mesh, or a depth map has the wrong orientation.
Rims make_rims(const Mesh& mesh, const MeshTopology& topology, const TexelSet& positive,
               const DepthMap& positive_depth, const TexelSet& negative,
               const DepthMap& negative_depth, const RimParams& params);

}  // namespace geotex
