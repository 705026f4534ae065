#include "view/mesh_payload.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "common/errors.hpp"
#include "pipeline/render.hpp"

namespace geotex::view {

namespace {

static_assert(std::numeric_limits<float>::is_iec559, "GTXM holds IEEE 754 floats");

// Appends the little-endian bytes of a 32-bit value; the page reads them through typed
// arrays, which use the machine's order, and every browser's machine is little-endian.
template <typename T>
void put(std::string& out, T value) {
    static_assert(sizeof(T) == 4, "GTXM fields are 32 bits");
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, 4);
    const char bytes[4] = {static_cast<char>(bits & 0xff), static_cast<char>((bits >> 8) & 0xff),
                           static_cast<char>((bits >> 16) & 0xff),
                           static_cast<char>((bits >> 24) & 0xff)};
    out.append(bytes, 4);
}

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
    const std::vector<int> polygon_texel = face_property_ids(segmentation, "texel", name);
    const std::vector<int> polygon_texture = face_property_ids(segmentation, "texture", name);
    const TriangleFans fans = triangle_fans(segmentation.soup);
    const std::size_t nv = fans.mesh.positions.size();
    const std::size_t nf = fans.mesh.faces.size();
    if (nv > std::numeric_limits<std::uint32_t>::max() ||
        nf > std::numeric_limits<std::uint32_t>::max() / 3)
        throw InvalidInput("too large for GTXM's 32-bit counts", name);

    std::string out;
    out.reserve(16 + nv * 12 + nf * 24);
    out.append("GTXM", 4);
    put<std::uint32_t>(out, kMeshPayloadVersion);
    put<std::uint32_t>(out, static_cast<std::uint32_t>(nv));
    put<std::uint32_t>(out, static_cast<std::uint32_t>(nf));
    for (std::size_t v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k) {
            const float x = static_cast<float>(fans.mesh.positions[v][k]);
            if (!std::isfinite(x))
                throw InvalidInput("vertex " + std::to_string(v) + " is not finite as a float",
                                   name);
            put<float>(out, x);
        }
    for (const auto& f : fans.mesh.faces)
        for (int k = 0; k < 3; ++k) {
            if (f[k] < 0 || static_cast<std::size_t>(f[k]) >= nv)
                throw InvalidInput(
                    "a face uses vertex " + std::to_string(f[k]) + " of " + std::to_string(nv),
                    name);
            put<std::uint32_t>(out, static_cast<std::uint32_t>(f[k]));
        }
    for (std::size_t t = 0; t < nf; ++t) {
        const int texel = polygon_texel[static_cast<std::size_t>(fans.face_polygon[t])];
        if (texel >= static_cast<int>(texel_depth.size()))
            throw InvalidInput("texel " + std::to_string(texel) +
                                   " of a face, but the report has " +
                                   std::to_string(texel_depth.size()) + " texels",
                               name);
        put<std::int32_t>(out, texel);
    }
    for (std::size_t t = 0; t < nf; ++t)
        put<std::int32_t>(out, polygon_texture[static_cast<std::size_t>(fans.face_polygon[t])]);
    for (std::size_t t = 0; t < nf; ++t) {
        const int texel = polygon_texel[static_cast<std::size_t>(fans.face_polygon[t])];
        put<float>(out, texel >= 0
                            ? static_cast<float>(texel_depth[static_cast<std::size_t>(texel)])
                            : std::numeric_limits<float>::quiet_NaN());
    }
    return out;
}

}  // namespace geotex::view
