// The steps of a tile that a tiled segmentation's passes (tiled_segmentation.cpp) and the jobs
// that make a tile's parts alone (tile_alone.cpp) share, beside those of the depth maps and
// texels (tiles.cpp, tile_texels.cpp): a tile's rims and feature rows, the rims' flags joined, and
// the checks that a part read back fits the run.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/topology.hpp"

namespace geotex {

namespace detail {

// Both orientations when rims are removed: the whole run's rim check is a bound that only
// spares work, and make_rims leaves nothing out wherever it says no.
std::vector<DetailOrientation> first_depth_orientations(const SegmentationParams& params) {
    if (params.remove_rims) return {DetailOrientation::Positive, DetailOrientation::Negative};
    return detail::orientations_of(params.orientation);
}

TilePart feature_part(const MeshTile& tile, const std::vector<Texel>& texels,
                      const std::vector<int>& ids, const DepthMap* positive,
                      const DepthMap* negative, double largest_side, double rho) {
    TilePart part;
    part.texels = ids;
    if (ids.empty()) return part;
    // The curvature and the features walk the vertices' rows and take the vertices' normals
    // alone: neither the faces' neighbours nor the other metrics are held beside them. The
    // normals are made first, a face at a time, the same bits as over the topology: made over
    // it they held every face's normal, area and perimeter (40 bytes a face) beside it, the
    // features job's peak.
    const std::vector<Eigen::Vector3d> vertex_normal = make_mesh_metrics(tile.mesh).vertex_normal;
    const MeshTopology topology = make_topology(tile.mesh, TopologyRows::WithoutFaceNeighbours);
    std::vector<Texel> local_texels;
    CurvatureParams cp;
    cp.radius = rho;
    cp.only.assign(tile.vertex.size(), 0);
    for (int t : ids) {
        Texel local_texel = texels[static_cast<std::size_t>(t)];
        for (int& f : local_texel.faces) {
            f = index_in(tile.face, f);
            if (f < 0)
                throw InvalidInput("tiles: texel " + std::to_string(t + 1) +
                                   " has a face past its tile's halo");
            for (int v : tile.mesh.faces[f]) cp.only[v] = 1;
        }
        local_texel.seed = -1;
        local_texels.push_back(std::move(local_texel));
    }
    const CurvatureField curvature = make_curvature(tile.mesh, topology, vertex_normal, cp);
    for (std::size_t v = 0; v < tile.vertex.size(); ++v)
        if (cp.only[v]) {
            part.curvature_vertices.push_back(tile.vertex[v]);
            part.curvature.gaussian.push_back(curvature.gaussian[v]);
            part.curvature.mean.push_back(curvature.mean[v]);
            part.curvature.shape_index.push_back(curvature.shape_index[v]);
            part.curvature.curvedness.push_back(curvature.curvedness[v]);
        }
    FeatureInputs in;
    in.mesh = &tile.mesh;
    in.topology = &topology;
    in.curvature = &curvature;
    in.positive_depth = positive;
    in.negative_depth = negative;
    in.largest_side = largest_side;
    part.rows = make_feature_rows(in, local_texels);
    return part;
}

TexelSet texels_in_tile(const TexelSet& whole, const MeshTile& tile) {
    TexelSet out;
    out.texels.resize(whole.texels.size());
    for (std::size_t t = 0; t < whole.texels.size(); ++t) {
        Texel& local = out.texels[t];
        local.orientation = whole.texels[t].orientation;
        // A search per face, never an array over the whole mesh's faces, nor a walk over the
        // tile's faces per texel (millions, for each of hundreds of texels at level 11).
        for (int f : whole.texels[t].faces)
            if (const int g = index_in(tile.face, f); g >= 0) local.faces.push_back(g);
    }
    return out;
}

RimFlags rim_part(const MeshTile& tile, const std::array<const TexelSet*, 2>& texels,
                  const std::array<const std::vector<double>*, 2>& texel_depth,
                  const RimParams& params) {
    if (tile.mesh.faces.empty())  // it owns nothing: no flag
        return no_rim_flags(texels[0]->texels.size(), texels[1]->texels.size());
    const MeshTopology topology = make_topology(tile.mesh);
    return find_rims(tile.mesh, topology, texels_in_tile(*texels[0], tile), *texel_depth[0],
                     texels_in_tile(*texels[1], tile), *texel_depth[1], params, tile.owned_vertex);
}

void expect_texel_part(const TilePart& part, TilePass pass, int tile, std::size_t n,
                       int num_vertices, int num_faces) {
    expect_part(part.pass == pass && part.tile == tile, pass, tile,
                "it is the part of another pass or tile");
    expect_part(
        part.regions.size() == n && part.region_depths.size() == n && part.thresholds.size() == n,
        pass, tile,
        "it has regions of " + std::to_string(part.regions.size()) + " orientations, not " +
            std::to_string(n));
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t faces = 0;
        for (const TexelRegion& r : part.regions[i].regions) {
            expect_part(r.seed >= 0 && r.seed < num_vertices && ascending_ids(r.faces, num_faces) &&
                            ascending_ids(r.touch, num_faces),
                        pass, tile, "a region's seed or faces are not the mesh's");
            faces += r.faces.size();
        }
        const RegionDepths& d = part.region_depths[i];
        expect_part(d.seed.size() == part.regions[i].regions.size() && d.face.size() == faces &&
                        d.peak.size() == faces,
                    pass, tile, "its depths do not match its regions");
    }
}

TileExclusion rim_exclusion(const std::array<const TexelSet*, 2>& texels,
                            const std::array<std::vector<char>, 2>& use, const RimParams& params) {
    return [texels, &use, params](const MeshTile& tile, const MeshTopology& topology,
                                  DetailOrientation o) {
        const std::size_t own = index_of(o);
        return rim_detail_vertices(tile.mesh, topology, texels_in_tile(*texels[1 - own], tile),
                                   use[own], params);
    };
}

void add_rim_part(const TilePart& part, int tile, RimFlags& flags) {
    expect_part(part.pass == TilePass::Rims && part.tile == tile, TilePass::Rims, tile,
                "it is the part of another pass or tile");
    const auto merge = [&](std::vector<char>& into, const std::vector<char>& from) {
        expect_part(from.size() == into.size(), TilePass::Rims, tile,
                    "it has flags of " + std::to_string(from.size()) + " texels, not " +
                        std::to_string(into.size()));
        for (std::size_t t = 0; t < into.size(); ++t) into[t] = into[t] || from[t];
    };
    merge(flags.positive_rim, part.rims.positive_rim);
    merge(flags.negative_rim, part.rims.negative_rim);
    merge(flags.positive_makes_rim, part.rims.positive_makes_rim);
    merge(flags.negative_makes_rim, part.rims.negative_makes_rim);
}

std::array<std::vector<char>, 2> rim_exclusions(const RimFlags& flags,
                                                const std::vector<DetailOrientation>& runs,
                                                std::vector<int>& counts,
                                                std::vector<DetailOrientation>& again) {
    std::array<std::vector<char>, 2> use;
    counts.assign(runs.size(), 0);
    again.clear();
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const bool positive = runs[r] == DetailOrientation::Positive;
        const std::vector<char>& makes =
            positive ? flags.negative_makes_rim : flags.positive_makes_rim;
        const std::vector<char>& rim = positive ? flags.negative_rim : flags.positive_rim;
        std::vector<char>& u = use[index_of(runs[r])];
        u.assign(makes.size(), 0);
        for (std::size_t t = 0; t < makes.size(); ++t) {
            u[t] = makes[t] && !rim[t] ? 1 : 0;
            counts[r] += u[t];
        }
        if (counts[r] > 0) again.push_back(runs[r]);
    }
    return use;
}

// Throws InvalidInput about tile `tile`'s part of `pass` unless `ok`.
void expect_part(bool ok, TilePass pass, int tile, const std::string& what) {
    if (!ok)
        throw InvalidInput("tiles: tile " + std::to_string(tile + 1) + "'s part of pass " +
                           name_of(pass) + " does not fit this run: " + what);
}

// Whether `ids` ascend strictly within [0, size).
bool ascending_ids(const std::vector<int>& ids, int size) {
    for (std::size_t i = 0; i < ids.size(); ++i)
        if (ids[i] < 0 || ids[i] >= size || (i > 0 && ids[i] <= ids[i - 1])) return false;
    return true;
}

// Throws InvalidInput unless `part` is tile `tile`'s part of depth pass `pass`, with the
// depths of `n` orientations over ascending vertex ids below `num_vertices`.
void expect_depth_part(const TilePart& part, TilePass pass, int tile, std::size_t n,
                       int num_vertices) {
    expect_part(part.pass == pass && part.tile == tile, pass, tile,
                "it is the part of another pass or tile");
    expect_part(part.depths.size() == n && part.moved.size() == n, pass, tile,
                "it has depths of " + std::to_string(part.depths.size()) + " orientations, not " +
                    std::to_string(n));
    expect_part(ascending_ids(part.vertices, num_vertices), pass, tile,
                "its vertex ids are not ascending ids of the mesh's vertices");
    for (std::size_t i = 0; i < n; ++i)
        expect_part(part.depths[i].size() == part.vertices.size() && part.moved[i] >= 0 &&
                        part.moved[i] <= static_cast<int>(part.vertices.size()),
                    pass, tile, "its depths do not match its vertices");
}

}  // namespace detail

}  // namespace geotex
