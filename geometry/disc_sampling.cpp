// make_disc_sampling: which vertices of the whole mesh the fast mode samples, and where its
// grid starts. A tiled run makes it once for the whole mesh so that every tile samples the
// same vertices on the same grid; DiscAverager (disc_means.cpp) averages with it.

#include <algorithm>
#include <cmath>
#include <string>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "geometry/disc_means.hpp"

namespace geotex {

namespace {

// Sampling cells more than this many per axis mean the radius is far below the mesh's
// resolution: every disc is a vertex or two and the exact walk is as cheap as anything.
constexpr double kMaxCellsPerAxis = 1e9;

// The vertices whose discs are sampled: those of every component with an area in Fast mode;
// in Auto mode, only where a disc holds about auto_min_disc_vertices vertices or more. The
// faces come from each_block(fn), which hands them to fn in order, a block at a time.
template <class EachBlock>
std::vector<char> fast_vertices(PositionSpan p, EachBlock&& each_block,
                                const DiscMeanParams& params, const VertexComponents& components) {
    const int nv = static_cast<int>(p.size());
    // Connected components, their vertex counts and areas (for Auto's estimate of the disc size).
    const std::vector<int>& component = components.component;
    std::vector<double> component_area(components.num_components, 0.0);
    std::vector<int> component_size(components.num_components, 0);
    for (int v = 0; v < nv; ++v) ++component_size[component[v]];
    each_block([&](const std::vector<std::array<int, 3>>& faces) {
        for (const auto& f : faces)
            component_area[component[f[0]]] +=
                0.5 * (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).norm();
    });
    std::vector<char> fast(nv, 0);
    const double r = params.radius;
    for (int v = 0; v < nv; ++v) {
        const int c = component[v];
        if (component_area[c] <= 0) continue;  // isolated vertices, degenerate pieces
        if (params.mode == DiscMode::Auto) {
            const double disc = std::min(kPi * r * r * component_size[c] / component_area[c],
                                         static_cast<double>(component_size[c]));
            if (disc < params.auto_min_disc_vertices) continue;
        }
        fast[v] = 1;
    }
    return fast;
}

void check_sampling_radius(const DiscMeanParams& params) {
    if (!(params.radius > 0) || !std::isfinite(params.radius))
        throw InvalidInput("disc sampling: the radius must be positive and finite (got " +
                           std::to_string(params.radius) + ")");
}

void check_components(const VertexComponents& components, std::size_t num_vertices) {
    if (components.component.size() != num_vertices)
        throw InvalidInput("disc sampling: the components have " +
                           std::to_string(components.component.size()) + " vertices, the mesh " +
                           std::to_string(num_vertices));
}

// The grid's corner and whether it has few enough cells, from the positions' bounds.
void place_sampling_grid(PositionSpan p, const DiscMeanParams& params, DiscSampling& sampling) {
    const Eigen::AlignedBox3d box = bounding_box(p);
    sampling.origin = box.min();
    sampling.grid =
        !(box.sizes().maxCoeff() / (params.sample_spacing_rel * params.radius) > kMaxCellsPerAxis);
}

}  // namespace

DiscSampling make_disc_sampling(const Mesh& mesh, const DiscMeanParams& params,
                                const VertexComponents* components) {
    check_sampling_radius(params);
    DiscSampling sampling;
    const std::vector<Eigen::Vector3d>& p = mesh.positions;
    if (p.empty()) return sampling;
    const auto each_block = [&](auto&& fn) { fn(mesh.faces); };
    if (params.mode == DiscMode::Exact)
        sampling.fast.assign(p.size(), 0);
    else if (components) {
        check_components(*components, p.size());
        sampling.fast = fast_vertices(p, each_block, params, *components);
    } else
        sampling.fast = fast_vertices(p, each_block, params, vertex_components(mesh));
    place_sampling_grid(p, params, sampling);
    return sampling;
}

DiscSampling make_disc_sampling(PositionSpan positions, const FaceBlockReader& faces,
                                std::size_t num_faces, const DiscMeanParams& params,
                                const VertexComponents& components) {
    check_sampling_radius(params);
    DiscSampling sampling;
    if (positions.empty()) return sampling;
    if (params.mode == DiscMode::Exact)
        sampling.fast.assign(positions.size(), 0);
    else {
        check_components(components, positions.size());
        sampling.fast = fast_vertices(
            positions,
            [&](auto&& fn) {
                for_each_face_block(faces, num_faces,
                                    [&](std::size_t, const auto& block) { fn(block); });
            },
            params, components);
    }
    place_sampling_grid(positions, params, sampling);
    return sampling;
}

}  // namespace geotex
