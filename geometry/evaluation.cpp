#include "geometry/evaluation.hpp"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/rand_index.hpp"

namespace geotex {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Traits = CGAL::Search_traits_3<Kernel>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Tree = Search::Tree;

Point barycentre(const Mesh& mesh, int f) {
    const auto& fv = mesh.faces[f];
    const Eigen::Vector3d c =
        (mesh.positions[fv[0]] + mesh.positions[fv[1]] + mesh.positions[fv[2]]) / 3.0;
    return Point(c.x(), c.y(), c.z());
}

// Largest distance from a face of `from` to the nearest face of `to` (both non-empty).
double directed_hausdorff(const Mesh& mesh, const std::vector<int>& from,
                          const std::vector<int>& to) {
    std::vector<Point> points;
    points.reserve(to.size());
    for (int f : to) points.push_back(barycentre(mesh, f));
    Tree tree(points.begin(), points.end());
    tree.build();  // before the parallel queries, which only read it
    std::vector<double> nearest(from.size());
    detail::parallel_for(static_cast<int>(from.size()), [&](int i) {
        Search search(tree, barycentre(mesh, from[i]), 1);
        nearest[i] = std::sqrt(search.begin()->second);
    });
    double worst = 0;
    for (double d : nearest) worst = std::max(worst, d);
    return worst;
}

}  // namespace

double surfacic_hausdorff(const Mesh& mesh, const std::vector<int>& a, const std::vector<int>& b) {
    for (const auto* set : {&a, &b})
        for (int f : *set)
            if (f < 0 || f >= mesh.num_faces())
                throw InvalidInput("Hausdorff distance: face index out of range");
    if (a.empty() && b.empty()) return 0;
    if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
    return std::max(directed_hausdorff(mesh, a, b), directed_hausdorff(mesh, b, a));
}

SegmentationScore evaluate_segmentation(const Mesh& mesh, const std::vector<int>& face_texel,
                                        const std::vector<int>& face_texture,
                                        const GroundTruth& truth) {
    const int nf = mesh.num_faces();
    if (static_cast<int>(face_texel.size()) != nf || static_cast<int>(face_texture.size()) != nf ||
        static_cast<int>(truth.face_shape.size()) != nf)
        throw InvalidInput("evaluation: the segmentation has " + std::to_string(face_texel.size()) +
                           " faces, the ground truth " + std::to_string(truth.face_shape.size()) +
                           " and the mesh " + std::to_string(nf) +
                           ": they must describe the same mesh");
    const int num_shapes = static_cast<int>(truth.shape_kind.size());
    int num_texels = 0;
    for (int f = 0; f < nf; ++f) {
        if (truth.face_shape[f] < -1 || truth.face_shape[f] >= num_shapes)
            throw InvalidInput("evaluation: face " + std::to_string(f) + " has shape " +
                               std::to_string(truth.face_shape[f]) +
                               " but the ground truth lists " + std::to_string(num_shapes) +
                               " shapes");
        if (face_texel[f] < -1)
            throw InvalidInput("evaluation: face " + std::to_string(f) +
                               " has a negative texel id");
        num_texels = std::max(num_texels, face_texel[f] + 1);
    }
    if (!truth.shape_family.empty() && static_cast<int>(truth.shape_family.size()) != num_shapes)
        throw InvalidInput("evaluation: shape_family must list every shape");

    SegmentationScore s;
    s.num_texels = num_texels;
    s.largest_side = mesh.positions.empty() ? 0.0 : bounding_box(mesh.positions).sizes().maxCoeff();
    const double scale = s.largest_side > 0 ? 1.0 / s.largest_side : 0.0;

    // Shared faces between texels and shapes; a texel covers its best shape.
    std::map<std::pair<int, int>, int> shared;  // (texel, shape) -> faces; few entries
    std::vector<int> texel_texture(num_texels, -1);
    std::vector<char> shape_present(num_shapes, 0);
    for (int f = 0; f < nf; ++f) {
        if (truth.face_shape[f] >= 0) shape_present[truth.face_shape[f]] = 1;
        if (face_texel[f] >= 0) {
            texel_texture[face_texel[f]] = face_texture[f];
            if (truth.face_shape[f] >= 0) ++shared[{face_texel[f], truth.face_shape[f]}];
        }
    }
    std::vector<int> texel_shape(num_texels, -1), best_count(num_texels, 0);
    for (const auto& [key, count] : shared)
        if (count > best_count[key.first]) {  // map order: ties go to the smaller shape id
            best_count[key.first] = count;
            texel_shape[key.first] = key.second;
        }
    std::vector<int> cover(num_shapes, 0);
    std::vector<char> texel_exists(num_texels, 0);
    for (int f = 0; f < nf; ++f)
        if (face_texel[f] >= 0) texel_exists[face_texel[f]] = 1;
    std::vector<int> labels_texture, labels_kind, labels_family;
    for (int t = 0; t < num_texels; ++t) {
        if (!texel_exists[t]) continue;
        if (texel_shape[t] < 0) {
            ++s.num_spurious;
            continue;
        }
        ++cover[texel_shape[t]];
        labels_texture.push_back(texel_texture[t]);
        labels_kind.push_back(truth.shape_kind[texel_shape[t]]);
        if (!truth.shape_family.empty())
            labels_family.push_back(truth.shape_family[texel_shape[t]]);
    }
    for (int k = 0; k < num_shapes; ++k) {
        if (!shape_present[k]) continue;
        ++s.num_shapes;
        if (cover[k] == 0)
            ++s.num_missed;
        else if (cover[k] == 1)
            ++s.num_matched;
        else
            ++s.num_split;
    }
    if (!labels_texture.empty()) {
        s.ari_kind = adjusted_rand_index(labels_texture, labels_kind);
        if (!labels_family.empty())
            s.ari_family = adjusted_rand_index(labels_texture, labels_family);
    }

    std::vector<int> seg, seg_matched, gt;
    for (int f = 0; f < nf; ++f) {
        if (face_texel[f] >= 0) {
            seg.push_back(f);
            if (texel_shape[face_texel[f]] >= 0) seg_matched.push_back(f);
        }
        if (truth.face_shape[f] >= 0) gt.push_back(f);
    }
    s.hausdorff = surfacic_hausdorff(mesh, seg, gt) * scale;
    s.hausdorff_matched = surfacic_hausdorff(mesh, seg_matched, gt) * scale;

    // delta_t: every pair of faces sharing an edge, once.
    double sum = 0;
    long pairs = 0;
    {
        std::vector<std::pair<std::uint64_t, int>> edges;
        edges.reserve(static_cast<std::size_t>(nf) * 3);
        for (int f = 0; f < nf; ++f) {
            const auto& fv = mesh.faces[f];
            for (int k = 0; k < 3; ++k) {
                const auto a = static_cast<std::uint64_t>(std::min(fv[k], fv[(k + 1) % 3]));
                const auto b = static_cast<std::uint64_t>(std::max(fv[k], fv[(k + 1) % 3]));
                edges.emplace_back((a << 32) | b, f);
            }
        }
        std::sort(edges.begin(), edges.end());
        for (std::size_t i = 0; i + 1 < edges.size(); ++i)
            if (edges[i].first == edges[i + 1].first) {
                const Point p = barycentre(mesh, edges[i].second),
                            q = barycentre(mesh, edges[i + 1].second);
                sum += std::sqrt(CGAL::squared_distance(p, q));
                ++pairs;
            }
    }
    s.delta_t = pairs > 0 ? sum / static_cast<double>(pairs) * scale : 0.0;
    return s;
}

}  // namespace geotex
