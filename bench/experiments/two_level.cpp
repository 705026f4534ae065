// geotex_two_level: the scale experiment of paper §4.2.2 (Figs. 14-15): a sphere with two
// superimposed levels of smooth detail, large bumps carrying small strokes, and one ground
// truth per level, so that `geotex evaluate` can score a small-scale run against the
// strokes and a large-scale run against the bumps.
//
//   geotex_two_level LEVEL smooth|sharp OUT.ply SMALL.truth.json LARGE.truth.json
//
// The unit icosphere of LEVEL (7: 327,680 faces) is displaced outward by
//   bumps:   8 caps of angular radius 0.16, height 0.05 (radii), profile cos^2(pi/2 d/R):
//            smooth, grey = height / 0.05;
//   strokes: 48 rectangles 0.14 x 0.03 with a linear ramp at their edges (as in
//            `geotex synth`); smooth (Fig. 15a): height 0.004, ramp 0.02; sharp (Fig. 15b):
//            height 0.01, ramp 0.004; one on the top of each bump, one on each bump's
//            flank, the rest on the base sphere away from the bumps.
// Ground truth per level as in `geotex synth`: a face belongs to a detail of that level when
// the mean grey of its vertices for that level exceeds 0.5 (owner: its greyest vertex).
// Deterministic (fixed seed, std::mt19937_64 and our own conversion to doubles).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/detail/numbers.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/mesh_io.hpp"

namespace {

using geotex::kPi;
constexpr int kNumBumps = 8;
constexpr double kBumpRadius = 0.16, kBumpHeight = 0.05;
constexpr int kNumStrokes = 48;
constexpr double kStrokeHalfLength = 0.07, kStrokeHalfWidth = 0.015;
// The stroke profile of the variant: smooth by default, set in run() for sharp.
double stroke_ramp = 0.02, stroke_height = 0.004;

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

Eigen::Vector3d random_direction(std::mt19937_64& rng) {
    const double z = 2 * uniform01(rng) - 1, phi = 2 * kPi * uniform01(rng);
    const double rxy = std::sqrt(std::max(0.0, 1 - z * z));
    return {rxy * std::cos(phi), rxy * std::sin(phi), z};
}

double arc(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::max(-1.0, std::min(1.0, a.dot(b))));
}

struct Stroke {
    Eigen::Vector3d center, e1, e2;  // e1: along the stroke
};

Stroke make_stroke(const Eigen::Vector3d& c, double angle) {
    const Eigen::Vector3d helper =
        std::abs(c.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t1 = c.cross(helper).normalized(), t2 = c.cross(t1);
    Stroke s;
    s.center = c;
    s.e1 = std::cos(angle) * t1 + std::sin(angle) * t2;
    s.e2 = c.cross(s.e1);
    return s;
}

// Signed distance (radii, azimuthal equidistant coordinates) from unit direction p to the stroke.
double stroke_distance(const Stroke& s, const Eigen::Vector3d& p) {
    const double cos_t = std::max(-1.0, std::min(1.0, p.dot(s.center)));
    const double theta = std::acos(cos_t);
    const Eigen::Vector3d tangent = p - cos_t * s.center;
    const double tn = tangent.norm();
    const double x = tn > 0 ? theta * tangent.dot(s.e1) / tn : 0,
                 y = tn > 0 ? theta * tangent.dot(s.e2) / tn : 0;
    const double qx = std::abs(x) - kStrokeHalfLength, qy = std::abs(y) - kStrokeHalfWidth;
    return std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0);
}

nlohmann::json truth_json(const std::string& mesh_file, const geotex::Mesh& mesh, int level,
                          const char* kind, int num_shapes, const std::vector<int>& face_shape) {
    nlohmann::json j;
    j["geotex"] = {{"document", "ground_truth"}, {"schema", 1}, {"generator", "geotex_two_level"}};
    j["mesh"] = {
        {"file", mesh_file}, {"vertices", mesh.num_vertices()}, {"faces", mesh.num_faces()}};
    j["parameters"] = {{"level", level},
                       {"bumps", kNumBumps},
                       {"bump_radius", kBumpRadius},
                       {"bump_height", kBumpHeight},
                       {"strokes", kNumStrokes},
                       {"variant", stroke_height < 0.005 ? "smooth" : "sharp"},
                       {"stroke_half_length", kStrokeHalfLength},
                       {"stroke_half_width", kStrokeHalfWidth},
                       {"stroke_ramp", stroke_ramp},
                       {"stroke_height", stroke_height}};
    nlohmann::json shapes = nlohmann::json::array();
    for (int i = 0; i < num_shapes; ++i)
        shapes.push_back({{"id", i}, {"kind", kind}, {"family", kind}});
    j["shapes"] = shapes;
    j["face_shape"] = face_shape;
    return j;
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    if (!(out << text)) throw std::runtime_error(path + ": cannot write");
}

int run(int argc, char** argv) {
    if (argc != 6 || (std::string(argv[2]) != "smooth" && std::string(argv[2]) != "sharp")) {
        std::fprintf(stderr,
                     "usage: geotex_two_level LEVEL smooth|sharp OUT.ply SMALL.truth.json "
                     "LARGE.truth.json\n");
        return 1;
    }
    const std::string variant = argv[2];
    if (variant == "sharp") stroke_ramp = 0.004, stroke_height = 0.01;
    const int level = std::atoi(argv[1]);
    if (level < 3 || level > 9) {
        std::fprintf(stderr, "geotex_two_level: LEVEL must be in [3, 9]\n");
        return 1;
    }
    const std::string out_mesh = argv[3], small_truth = argv[4], large_truth = argv[5];
    geotex::Mesh mesh = geotex::make_icosphere(level);
    std::mt19937_64 rng(2019);

    // Bumps far apart (random sequential addition).
    std::vector<Eigen::Vector3d> bumps;
    while (static_cast<int>(bumps.size()) < kNumBumps) {
        const Eigen::Vector3d c = random_direction(rng);
        bool fits = true;
        for (const auto& b : bumps) fits = fits && arc(c, b) >= 2 * kBumpRadius + 0.3;
        if (fits) bumps.push_back(c);
    }
    // Strokes: on each bump's top, on each bump's flank, then on the base sphere.
    const double stroke_rho = std::hypot(kStrokeHalfLength, kStrokeHalfWidth) + stroke_ramp;
    std::vector<Stroke> strokes;
    for (const auto& b : bumps) {
        strokes.push_back(make_stroke(b, kPi * uniform01(rng)));
        // Flank: 0.6 R from the centre, across the slope.
        const Stroke frame = make_stroke(b, 2 * kPi * uniform01(rng));
        const Eigen::Vector3d c =
            (std::cos(0.6 * kBumpRadius) * b + std::sin(0.6 * kBumpRadius) * frame.e1).normalized();
        Stroke flank;  // along the contour line of the bump
        flank.center = c;
        flank.e1 = b.cross(c).normalized();
        flank.e2 = c.cross(flank.e1);
        strokes.push_back(flank);
    }
    for (int attempt = 0; static_cast<int>(strokes.size()) < kNumStrokes; ++attempt) {
        if (attempt > 1000000) throw std::runtime_error("cannot place the strokes");
        const Eigen::Vector3d c = random_direction(rng);
        bool fits = true;
        for (const auto& b : bumps) fits = fits && arc(c, b) >= kBumpRadius + stroke_rho + 0.05;
        for (const auto& s : strokes) fits = fits && arc(c, s.center) >= 2 * stroke_rho + 0.05;
        if (fits) strokes.push_back(make_stroke(c, kPi * uniform01(rng)));
    }

    const int nv = mesh.num_vertices();
    std::vector<double> grey_bump(nv, 0.0), grey_stroke(nv, 0.0);
    std::vector<int> owner_bump(nv, -1), owner_stroke(nv, -1);
    for (int v = 0; v < nv; ++v) {
        const Eigen::Vector3d p = mesh.positions[v];
        for (int b = 0; b < kNumBumps; ++b) {
            const double d = arc(p, bumps[b]);
            if (d >= kBumpRadius) continue;
            const double c = std::cos(0.5 * kPi * d / kBumpRadius), g = c * c;
            if (g > grey_bump[v]) grey_bump[v] = g, owner_bump[v] = b;
        }
        for (int s = 0; s < kNumStrokes; ++s) {
            if (arc(p, strokes[s].center) > stroke_rho + stroke_ramp) continue;
            const double g =
                std::max(0.0, std::min(1.0, 0.5 - stroke_distance(strokes[s], p) / stroke_ramp));
            if (g > grey_stroke[v]) grey_stroke[v] = g, owner_stroke[v] = s;
        }
        mesh.positions[v] = p * (1 + kBumpHeight * grey_bump[v] + stroke_height * grey_stroke[v]);
    }
    auto labels = [&](const std::vector<double>& grey, const std::vector<int>& owner) {
        std::vector<int> face_shape(mesh.faces.size(), -1);
        for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
            const auto& fv = mesh.faces[f];
            if ((grey[fv[0]] + grey[fv[1]] + grey[fv[2]]) / 3.0 <= 0.5) continue;
            int best = fv[0];
            for (int v : fv)
                if (grey[v] > grey[best]) best = v;
            face_shape[f] = owner[best];
        }
        return face_shape;
    };
    {
        std::ofstream out(out_mesh, std::ios::binary);
        if (!out) throw std::runtime_error(out_mesh + ": cannot write");
        geotex::PlyWriteOptions w;
        w.comments = {"geotex_two_level: bumps carrying " + variant + " strokes, level " +
                      std::to_string(level)};
        geotex::write_ply(out, mesh, {}, w);
    }
    const auto slash = out_mesh.find_last_of('/');
    const std::string name = slash == std::string::npos ? out_mesh : out_mesh.substr(slash + 1);
    write_text(small_truth, truth_json(name, mesh, level, "stroke", kNumStrokes,
                                       labels(grey_stroke, owner_stroke))
                                    .dump() +
                                "\n");
    write_text(
        large_truth,
        truth_json(name, mesh, level, "bump", kNumBumps, labels(grey_bump, owner_bump)).dump() +
            "\n");
    std::printf("two-level sphere: %d faces, %d bumps, %d strokes; wrote %s, %s, %s\n",
                mesh.num_faces(), kNumBumps, kNumStrokes, out_mesh.c_str(), small_truth.c_str(),
                large_truth.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geotex_two_level: error: %s\n", e.what());
        return 3;
    }
}
