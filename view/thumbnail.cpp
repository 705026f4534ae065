#include "view/thumbnail.hpp"

#include <sstream>

#include "common/errors.hpp"
#include "pipeline/render.hpp"
#include "pipeline/texture_colour.hpp"
#include "view/mesh_payload.hpp"

namespace geotex::view {

std::string make_thumbnail(const MeshFile& segmentation, const std::string& name) {
    const std::vector<int> texture = face_property_ids(segmentation, "texture", name);
    const std::vector<int> texel = face_property_ids(segmentation, "texel", name);
    const TriangleFans fans = triangle_fans(segmentation.soup);
    std::vector<std::array<unsigned char, 3>> colour(fans.mesh.faces.size());
    std::vector<int> region(fans.mesh.faces.size());
    for (std::size_t t = 0; t < colour.size(); ++t) {
        const auto p = static_cast<std::size_t>(fans.face_polygon[t]);
        colour[t] = texture_colour(texture[p]);
        region[t] = texel[p];
    }
    RenderOptions options;
    options.width = kThumbnailSide;
    options.height = kThumbnailSide;
    options.view = *named_view("iso");
    options.supersample = 2;  // enough at this size, and a 1.3M-face list stays quick
    const Image image = render_mesh(fans.mesh, colour, options, region);
    std::ostringstream png;
    write_png(png, image);
    return png.str();
}

}  // namespace geotex::view
