#include "tests/fixtures.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "common/detail/numbers.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/synth.hpp"

namespace geotex::test {

Mesh make_grid(int n, double size, const std::function<double(double, double)>& height) {
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = size * (static_cast<double>(i) / n - 0.5),
                         y = size * (static_cast<double>(j) / n - 0.5);
            m.positions.emplace_back(x, y, height ? height(x, y) : 0.0);
        }
    auto id = [n](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            // Alternate the diagonal so that the grid has no preferred direction.
            if ((i + j) % 2 == 0) {
                m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            } else {
                m.faces.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
                m.faces.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
            }
        }
    return m;
}

Mesh make_cylinder(double radius, double length, int around, int rings) {
    Mesh m;
    for (int r = 0; r < rings; ++r)
        for (int a = 0; a < around; ++a) {
            // Every other ring turned by half a step: near-equilateral triangles.
            const double t = 2 * kPi * (a + 0.5 * (r % 2)) / around;
            m.positions.emplace_back(radius * std::cos(t), radius * std::sin(t),
                                     length * r / (rings - 1) - length / 2);
        }
    auto id = [around](int r, int a) { return r * around + (a % around); };
    for (int r = 0; r + 1 < rings; ++r)
        for (int a = 0; a < around; ++a) {
            if (r % 2 == 0) {
                m.faces.push_back({id(r, a), id(r, a + 1), id(r + 1, a)});
                m.faces.push_back({id(r, a + 1), id(r + 1, a + 1), id(r + 1, a)});
            } else {
                m.faces.push_back({id(r, a), id(r, a + 1), id(r + 1, a + 1)});
                m.faces.push_back({id(r, a), id(r + 1, a + 1), id(r + 1, a)});
            }
        }
    return m;
}

Mesh make_sphere(double radius, int level, const Eigen::Vector3d& center) {
    Mesh m = make_icosphere(level);
    for (auto& p : m.positions) p = center + radius * p;
    return m;
}

Mesh make_disc(int rings) {
    Mesh m;
    m.positions.emplace_back(0, 0, 0);
    std::vector<int> ring_start{0};
    for (int r = 1; r <= rings; ++r) {
        ring_start.push_back(m.num_vertices());
        const int count = 6 * r;
        for (int k = 0; k < count; ++k) {
            const double t = 2 * kPi * k / count;
            m.positions.emplace_back(std::cos(t) * r / rings, std::sin(t) * r / rings, 0);
        }
    }
    // Between ring r-1 (6(r-1) vertices, or the centre) and ring r (6r vertices): walk both
    // rings by angle and emit the triangle that advances the one behind.
    for (int r = 1; r <= rings; ++r) {
        const int inner_n = r == 1 ? 1 : 6 * (r - 1), outer_n = 6 * r;
        const int inner0 = ring_start[r - 1], outer0 = ring_start[r];
        int i = 0, o = 0;
        while (o < outer_n || (inner_n > 1 && i < inner_n)) {
            const double ti = inner_n == 1 ? 2.0 : static_cast<double>(i + 1) / inner_n;
            const double to = static_cast<double>(o + 1) / outer_n;
            const int a = inner0 + i % inner_n, b = outer0 + o % outer_n;
            if (o < outer_n && (to <= ti || i >= inner_n)) {
                m.faces.push_back({a, b, outer0 + (o + 1) % outer_n});
                ++o;
            } else {
                m.faces.push_back({a, b, inner0 + (i + 1) % inner_n});
                ++i;
            }
        }
    }
    return m;
}

Mesh scaled(Mesh mesh, double k) {
    for (auto& p : mesh.positions) p *= k;
    return mesh;
}

Mesh combined(const Mesh& a, const Mesh& b) {
    Mesh m = a;
    const int shift = a.num_vertices();
    m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
    for (auto f : b.faces) m.faces.push_back({f[0] + shift, f[1] + shift, f[2] + shift});
    return m;
}

namespace {

double segment_squared_distance(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (q - (a + t * ab)).squaredNorm();
}

}  // namespace

double triangle_squared_distance(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const Eigen::Vector3d foot = q - (q - a).dot(n) / n.squaredNorm() * n;
    const bool inside = (b - a).cross(foot - a).dot(n) >= 0 &&
                        (c - b).cross(foot - b).dot(n) >= 0 && (a - c).cross(foot - c).dot(n) >= 0;
    if (inside) return (q - foot).squaredNorm();
    return std::min({segment_squared_distance(q, a, b), segment_squared_distance(q, b, c),
                     segment_squared_distance(q, c, a)});
}

double signed_volume(const Mesh& mesh) {
    double v = 0;
    for (const auto& f : mesh.faces)
        v += mesh.positions[f[0]].dot(mesh.positions[f[1]].cross(mesh.positions[f[2]])) / 6.0;
    return v;
}

std::vector<int> all_faces(const Mesh& mesh) {
    std::vector<int> out(mesh.num_faces());
    for (int f = 0; f < mesh.num_faces(); ++f) out[f] = f;
    return out;
}

Mesh half_engraved_sphere(int level) {
    SynthParams p;
    p.level = level;
    p.engraved_fraction = 0.5;
    return make_synthetic_sphere(p).mesh;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void write_file(const std::filesystem::path& path, const std::string& bytes) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

TempDir::TempDir(const std::string& name) {
    static int count = 0;
    path_ =
        std::filesystem::temp_directory_path() /
        ("geotex-test-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(count++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::size_t binary_arrays_start(const std::string& bytes) {
    const std::size_t magic = bytes.find('\n') + 1;
    std::uint64_t length = 0;
    for (int k = 0; k < 8; ++k)
        length |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[magic + k]))
                  << (8 * k);
    return magic + 8 + length;
}

}  // namespace geotex::test
