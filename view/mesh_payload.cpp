#include "view/mesh_payload.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "common/errors.hpp"
#include "pipeline/render.hpp"

namespace geotex::view {

static_assert(std::numeric_limits<float>::is_iec559, "GTXM holds IEEE 754 floats");

namespace {

// Vertices of the payload: the file's vertices, and copies of those shared by faces of
// different texels. A vertex keeps its own index for the texel that uses it first (in
// triangle order); each further texel at that vertex gets a copy appended after the file's
// vertices, in the order of first use, so the result does not depend on hashing.
struct SplitVertices {
    std::vector<std::uint32_t> source;   ///< #payload vertices: the file's vertex of each
    std::vector<std::uint32_t> corners;  ///< 3 #triangles: payload vertex of each corner
};

SplitVertices split_at_texel_borders(const PolygonSoup& soup, const std::vector<int>& polygon_texel,
                                     std::size_t num_triangles, const std::string& name) {
    const std::size_t nv = soup.positions.size();
    constexpr int kUnused = std::numeric_limits<int>::min();
    std::vector<int> first_texel(nv, kUnused);
    // (vertex << 32 | texel as 32 bits) -> its copy; few vertices lie on texel borders.
    std::unordered_map<std::uint64_t, std::uint32_t> copies;
    SplitVertices out;
    out.source.resize(nv);
    for (std::size_t v = 0; v < nv; ++v) out.source[v] = static_cast<std::uint32_t>(v);
    out.corners.reserve(3 * num_triangles);
    const auto corner = [&](int v, int texel) {
        if (v < 0 || static_cast<std::size_t>(v) >= nv)
            throw InvalidInput(
                "a face uses vertex " + std::to_string(v) + " of " + std::to_string(nv), name);
        const auto vu = static_cast<std::uint32_t>(v);
        int& first = first_texel[vu];
        if (first == kUnused) first = texel;
        if (first == texel) return out.corners.push_back(vu);
        const std::uint64_t key = (std::uint64_t{vu} << 32) | static_cast<std::uint32_t>(texel);
        const auto [it, added] =
            copies.try_emplace(key, static_cast<std::uint32_t>(out.source.size()));
        if (added) out.source.push_back(vu);
        out.corners.push_back(it->second);
    };
    for_each_fan_triangle(soup, [&](int p, int a, int b, int c) {
        const int texel = polygon_texel[static_cast<std::size_t>(p)];
        corner(a, texel);
        corner(b, texel);
        corner(c, texel);
    });
    return out;
}

// The texture of each texel, from its faces' `texture` property: -1 for a texel without
// faces. Throws when the faces of one texel name different textures, or a face outside
// every texel names one: the page colours by texel and could not show both.
std::vector<int> texel_textures(const std::vector<int>& polygon_texel,
                                const std::vector<int>& polygon_texture, std::size_t num_texels,
                                const std::string& name) {
    std::vector<int> texture(num_texels, -1);
    std::vector<bool> seen(num_texels, false);
    for (std::size_t p = 0; p < polygon_texel.size(); ++p) {
        const int texel = polygon_texel[p], t = polygon_texture[p];
        if (texel < 0) {
            if (t >= 0)
                throw InvalidInput("polygon " + std::to_string(p) + " is in texture " +
                                       std::to_string(t) + " but in no texel",
                                   name);
            continue;
        }
        const auto k = static_cast<std::size_t>(texel);
        if (!seen[k]) {
            seen[k] = true;
            texture[k] = t;
        } else if (texture[k] != t) {
            throw InvalidInput("texel " + std::to_string(texel) + " has faces in textures " +
                                   std::to_string(texture[k]) + " and " + std::to_string(t),
                               name);
        }
    }
    return texture;
}

// Writes 32-bit values little-endian into a buffer sized in advance; the page reads them
// through typed arrays, which use the machine's order, and every browser's machine is
// little-endian.
class Writer {
  public:
    explicit Writer(std::size_t size) : bytes_(size, '\0') {}

    template <typename T>
    void put(T value) {
        static_assert(sizeof(T) == 4, "GTXM fields are 32 bits");
        std::uint32_t bits = 0;
        std::memcpy(&bits, &value, 4);
        char* out = &bytes_[at_];
        for (int k = 0; k < 4; ++k) out[k] = static_cast<char>((bits >> (8 * k)) & 0xff);
        at_ += 4;
    }
    void put_magic() {
        bytes_.replace(0, 4, "GTXM");
        at_ = 4;
    }
    std::string take() {
        assert(at_ == bytes_.size());
        return std::move(bytes_);
    }

  private:
    std::string bytes_;
    std::size_t at_ = 0;
};

}  // namespace

std::vector<int> face_property_ids(const MeshFile& file, const char* property,
                                   const std::string& name) {
    const std::size_t n = static_cast<std::size_t>(file.soup.num_polygons());
    for (const FaceProperty& p : file.face_properties) {
        if (p.name != property) continue;
        std::vector<int> ids(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double v = p.values[i];
            if (!(v >= -1 && v < 2147483647.0) || v != std::floor(v))
                throw InvalidInput("face property '" + std::string(property) + "' of polygon " +
                                       std::to_string(i) + " is not an id (-1 or more)",
                                   name);
            ids[i] = static_cast<int>(v);
        }
        return ids;
    }
    return std::vector<int>(n, -1);
}

std::string make_mesh_payload(const MeshFile& segmentation, const std::vector<double>& texel_depth,
                              const std::string& name) {
    const PolygonSoup& soup = segmentation.soup;
    const std::vector<int> polygon_texel = face_property_ids(segmentation, "texel", name);
    const std::vector<int> polygon_texture = face_property_ids(segmentation, "texture", name);
    const std::size_t nt = texel_depth.size();
    std::size_t nf = 0;
    for (int p = 0; p < soup.num_polygons(); ++p) {
        const int texel = polygon_texel[static_cast<std::size_t>(p)];
        if (texel >= static_cast<int>(nt))
            throw InvalidInput("texel " + std::to_string(texel) +
                                   " of a face, but the report has " + std::to_string(nt) +
                                   " texels",
                               name);
        nf += static_cast<std::size_t>(
            std::max(0, soup.face_offsets[p + 1] - soup.face_offsets[p] - 2));
    }
    const std::vector<int> texture = texel_textures(polygon_texel, polygon_texture, nt, name);
    const SplitVertices split = split_at_texel_borders(soup, polygon_texel, nf, name);
    const std::size_t nv = split.source.size();
    constexpr std::size_t kMax = std::numeric_limits<std::uint32_t>::max();
    if (nv > kMax || nf > kMax / 3 || nt > kMax)
        throw InvalidInput("too large for GTXM's 32-bit counts", name);

    Writer out(20 + 12 * nv + 16 * nf + 8 * nt);
    out.put_magic();
    out.put<std::uint32_t>(kMeshPayloadVersion);
    out.put<std::uint32_t>(static_cast<std::uint32_t>(nv));
    out.put<std::uint32_t>(static_cast<std::uint32_t>(nf));
    out.put<std::uint32_t>(static_cast<std::uint32_t>(nt));
    for (const std::uint32_t v : split.source)
        for (int k = 0; k < 3; ++k) {
            const float x = static_cast<float>(soup.positions[v][k]);
            if (!std::isfinite(x))
                throw InvalidInput("vertex " + std::to_string(v) + " is not finite as a float",
                                   name);
            out.put<float>(x);
        }
    for (const std::uint32_t corner : split.corners) out.put<std::uint32_t>(corner);
    for_each_fan_triangle(soup, [&](int p, int, int, int) {
        out.put<std::int32_t>(polygon_texel[static_cast<std::size_t>(p)]);
    });
    for (const int t : texture) out.put<std::int32_t>(t);
    for (const double d : texel_depth) out.put<float>(static_cast<float>(d));
    return out.take();
}

}  // namespace geotex::view
