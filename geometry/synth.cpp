#include "geometry/synth.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/icosphere.hpp"

namespace geotex {

namespace {

// Uniform double in [0, 1) from the top 53 bits: the same on every standard library
// (std::uniform_real_distribution is implementation-defined).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Sizes in sphere radii (the bounding box side is about 2): "typical diameter 5% of the
// bounding box" (paper §4.1.2). Rectangles have aspect 4, which gives the paper's
// perimeter^2 / area of about 25.
void shape_size(ShapeKind kind, double& half_length, double& half_width) {
    switch (kind) {
        case ShapeKind::BigDisc:
            half_length = half_width = 0.06;
            break;
        case ShapeKind::SmallDisc:
            half_length = half_width = 0.035;
            break;
        case ShapeKind::Square:
            half_length = half_width = 0.045;
            break;
        case ShapeKind::Rectangle:
            half_length = 0.1;
            half_width = 0.025;
            break;
    }
}

// Tangent frame at a unit direction.
void tangent_frame(const Eigen::Vector3d& c, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
    const Eigen::Vector3d helper =
        std::abs(c.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    e1 = c.cross(helper).normalized();
    e2 = c.cross(e1);
}

// Signed distance (sphere radii, along the surface) from unit direction p to the shape:
// azimuthal equidistant coordinates around the shape centre, then the disc or box distance.
double signed_distance(const SynthShape& s, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                       const Eigen::Vector3d& p) {
    const double cos_t = std::max(-1.0, std::min(1.0, p.dot(s.center)));
    const double theta = std::acos(cos_t);
    const Eigen::Vector3d tangent = p - cos_t * s.center;
    const double tn = tangent.norm();
    double u = 0, v = 0;
    if (tn > 0) {
        u = theta * tangent.dot(e1) / tn;
        v = theta * tangent.dot(e2) / tn;
    }
    const double ca = std::cos(s.angle), sa = std::sin(s.angle);
    const double x = ca * u + sa * v, y = -sa * u + ca * v;
    if (s.kind == ShapeKind::BigDisc || s.kind == ShapeKind::SmallDisc)
        return std::hypot(x, y) - s.half_length;
    const double qx = std::abs(x) - s.half_length, qy = std::abs(y) - s.half_width;
    return std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0);
}

}  // namespace

const char* shape_kind_name(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::BigDisc:
            return "big_disc";
        case ShapeKind::SmallDisc:
            return "small_disc";
        case ShapeKind::Square:
            return "square";
        case ShapeKind::Rectangle:
            return "rectangle";
    }
    return "unknown";
}

const char* shape_kind_family(ShapeKind kind) {
    return kind == ShapeKind::BigDisc || kind == ShapeKind::SmallDisc ? "disc"
                                                                      : shape_kind_name(kind);
}

SyntheticMesh make_synthetic_sphere(const SynthParams& params) {
    const int counts[4] = {params.num_big_discs, params.num_small_discs, params.num_squares,
                           params.num_rectangles};
    for (int c : counts)
        if (c < 0 || c > 10000) throw InvalidInput("synth: shape counts must be in [0, 10000]");
    if (!(params.displacement_rel > -1 && params.displacement_rel < 1))
        throw InvalidInput("synth: displacement must be in (-1, 1) radii");
    if (!(params.edge_width_rel >= 0 && params.edge_width_rel < 0.5))
        throw InvalidInput("synth: edge width must be in [0, 0.5) radii");
    if (!(params.noise_percent >= 0 && params.noise_percent <= 50))
        throw InvalidInput("synth: noise must be in [0, 50] percent of the radius");
    if (!(params.engraved_fraction >= 0 && params.engraved_fraction <= 1))
        throw InvalidInput("synth: engraved fraction must be in [0, 1]");
    if (!(params.gap_rel >= 0)) throw InvalidInput("synth: gap must be >= 0");

    SyntheticMesh out;
    out.mesh = make_icosphere(params.level);

    // Placement by random sequential addition, largest shapes first; a candidate is kept
    // when its bounding circle keeps the gap to every placed one.
    std::mt19937_64 rng(params.layout_seed);
    const ShapeKind order[4] = {ShapeKind::Rectangle, ShapeKind::BigDisc, ShapeKind::Square,
                                ShapeKind::SmallDisc};
    const int count_of[4] = {params.num_rectangles, params.num_big_discs, params.num_squares,
                             params.num_small_discs};
    std::vector<double> bounding;  // bounding circle radius of each placed shape
    for (int k = 0; k < 4; ++k) {
        for (int n = 0; n < count_of[k]; ++n) {
            SynthShape s;
            s.kind = order[k];
            shape_size(s.kind, s.half_length, s.half_width);
            const double rho = std::hypot(
                s.half_length, s.kind == ShapeKind::BigDisc || s.kind == ShapeKind::SmallDisc
                                   ? 0.0
                                   : s.half_width);
            bool placed = false;
            for (int attempt = 0; attempt < 200000 && !placed; ++attempt) {
                const double z = 2 * uniform01(rng) - 1, phi = 2 * kPi * uniform01(rng);
                const double rxy = std::sqrt(std::max(0.0, 1 - z * z));
                const Eigen::Vector3d c(rxy * std::cos(phi), rxy * std::sin(phi), z);
                const double angle = kPi * uniform01(rng);
                bool fits = true;
                for (std::size_t j = 0; j < out.shapes.size() && fits; ++j) {
                    const double dist =
                        std::acos(std::max(-1.0, std::min(1.0, c.dot(out.shapes[j].center))));
                    fits = dist >= rho + bounding[j] + params.gap_rel;
                }
                if (fits) {
                    s.center = c;
                    s.angle = angle;
                    placed = true;
                }
            }
            if (!placed)
                throw InvalidInput("synth: could not place " + std::to_string(count_of[k] - n) +
                                   " more " + shape_kind_name(s.kind) +
                                   " shapes; use fewer shapes or a smaller gap");
            s.id = static_cast<int>(out.shapes.size());
            out.shapes.push_back(s);
            bounding.push_back(rho);
        }
    }
    // Engraved shapes: a fixed pseudo-random subset, drawn after placement.
    const int num_engraved =
        static_cast<int>(std::lround(params.engraved_fraction * out.shapes.size()));
    {
        std::vector<int> ids(out.shapes.size());
        for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
        for (std::size_t i = ids.size(); i > 1; --i)
            std::swap(ids[i - 1],
                      ids[static_cast<std::size_t>(uniform01(rng) * static_cast<double>(i))]);
        for (int i = 0; i < num_engraved; ++i) out.shapes[ids[i]].engraved = true;
    }

    // Grey value and owner of each vertex, then displacement along the radius.
    const int nv = out.mesh.num_vertices();
    std::vector<Eigen::Vector3d> e1(out.shapes.size()), e2(out.shapes.size());
    for (std::size_t j = 0; j < out.shapes.size(); ++j)
        tangent_frame(out.shapes[j].center, e1[j], e2[j]);
    out.vertex_grey.assign(nv, 0.0);
    std::vector<int> owner(nv, -1);
    const double w = params.edge_width_rel;
    detail::parallel_for(nv, [&](int v) {
        const Eigen::Vector3d& p = out.mesh.positions[v];
        for (std::size_t j = 0; j < out.shapes.size(); ++j) {
            if (p.dot(out.shapes[j].center) < std::cos(std::min(kPi, bounding[j] + w))) continue;
            const double sd = signed_distance(out.shapes[j], e1[j], e2[j], p);
            const double g =
                w > 0 ? std::max(0.0, std::min(1.0, 0.5 - sd / w)) : (sd <= 0 ? 1.0 : 0.0);
            if (g > out.vertex_grey[v]) {
                out.vertex_grey[v] = g;
                owner[v] = static_cast<int>(j);
            }
        }
    });
    std::mt19937_64 noise_rng(params.noise_seed);
    const double amplitude = params.noise_percent / 100.0;
    for (int v = 0; v < nv; ++v) {
        const double sign = owner[v] >= 0 && out.shapes[owner[v]].engraved ? -1.0 : 1.0;
        double radius = 1 + sign * params.displacement_rel * out.vertex_grey[v];
        if (amplitude > 0) radius += amplitude * (2 * uniform01(noise_rng) - 1);
        out.mesh.positions[v] *= radius;
    }
    // Ground truth (paper §4.1): a face is foreground when the mean grey of its vertices
    // exceeds half the range; it belongs to the shape of its greyest vertex.
    out.face_shape.assign(out.mesh.num_faces(), -1);
    for (int f = 0; f < out.mesh.num_faces(); ++f) {
        const auto& fv = out.mesh.faces[f];
        const double mean =
            (out.vertex_grey[fv[0]] + out.vertex_grey[fv[1]] + out.vertex_grey[fv[2]]) / 3.0;
        if (mean <= 0.5) continue;
        int best = fv[0];
        for (int v : fv)
            if (out.vertex_grey[v] > out.vertex_grey[best]) best = v;
        out.face_shape[f] = owner[best];
    }
    out.vertex_shape = std::move(owner);
    return out;
}

}  // namespace geotex
