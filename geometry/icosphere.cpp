#include "geometry/icosphere.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "common/errors.hpp"

namespace geotex {

Mesh make_icosphere(int level) {
    if (level < 0 || level > 11)
        throw InvalidInput("icosphere: level must be in [0, 11] (got " + std::to_string(level) +
                           ")");
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    Mesh m;
    m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (auto& p : m.positions) p.normalize();
    for (int l = 0; l < level; ++l) {
        // New vertex per edge, numbered by the rank of the edge key: deterministic and
        // without a hash map.
        std::vector<std::uint64_t> keys;
        keys.reserve(m.faces.size() * 3);
        auto key = [](int a, int b) {
            return (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                   static_cast<std::uint32_t>(std::max(a, b));
        };
        for (const auto& f : m.faces)
            for (int k = 0; k < 3; ++k) keys.push_back(key(f[k], f[(k + 1) % 3]));
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        const int base = m.num_vertices();
        m.positions.resize(base + keys.size());
        for (std::size_t e = 0; e < keys.size(); ++e) {
            const int a = static_cast<int>(keys[e] >> 32),
                      b = static_cast<int>(keys[e] & 0xffffffffu);
            m.positions[base + e] = (m.positions[a] + m.positions[b]).normalized();
        }
        auto mid = [&](int a, int b) {
            return base + static_cast<int>(std::lower_bound(keys.begin(), keys.end(), key(a, b)) -
                                           keys.begin());
        };
        std::vector<std::array<int, 3>> faces;
        faces.reserve(m.faces.size() * 4);
        for (const auto& f : m.faces) {
            const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
            faces.push_back({f[0], ab, ca});
            faces.push_back({f[1], bc, ab});
            faces.push_back({f[2], ca, bc});
            faces.push_back({ab, bc, ca});
        }
        m.faces = std::move(faces);
    }
    return m;
}

}  // namespace geotex
