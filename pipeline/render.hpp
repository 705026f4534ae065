#pragma once
// A small software renderer for looking at meshes and segmentations without a viewer:
// orthographic camera, z-buffer, flat two-sided Lambert shading, supersampling, PNG output.

#include <array>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "geometry/mesh.hpp"

namespace geotex {

/// An 8-bit RGB picture.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<unsigned char>
        rgb;  ///< height * width * 3, rows from the top, pixels from the left

    /// Colour of pixel (x, y), x from the left, y from the top; no bounds check beyond assert.
    std::array<unsigned char, 3> pixel(int x, int y) const;
};

/// Camera direction. The camera sits on the unit vector
///   (cos(elevation) sin(azimuth), sin(elevation), cos(elevation) cos(azimuth))
/// from the mesh centre, looking back at it; +Y is "up" (the OBJ/PLY and MeshLab habit).
/// Azimuth 0, elevation 0 is the front view: camera on +Z, +X to the right, +Y up.
struct ViewAngles {
    double azimuth_deg = 0;    ///< degrees about +Y: 0 camera on +Z, 90 on +X, -90 on -X, 180 on -Z
    double elevation_deg = 0;  ///< degrees in [-90, 90]: 90 camera on +Y looking down, -90 on -Y
};

/// The named views: front (camera on +Z), back (-Z), right (+X), left (-X), top (+Y, with -Z
/// at the top of the picture), bottom (-Y, +Z at the top), iso (azimuth 45, elevation
/// 35.26: camera on (1, 1, 1), the front-right-top corner). nullopt for any other name.
std::optional<ViewAngles> named_view(const std::string& name);

/// The names named_view knows, in the order of the documentation: "front, back, ..., iso".
std::string view_names();

/// Largest width or height render_mesh draws, in pixels.
constexpr int kMaxRenderSide = 8192;

/// How to render.
struct RenderOptions {
    int width = 1024;     ///< pixels, 1..kMaxRenderSide
    int height = 1024;    ///< pixels, 1..kMaxRenderSide
    ViewAngles view;      ///< camera direction
    int supersample = 3;  ///< samples per pixel side, 1..4 (3: 3x3 samples averaged per pixel)
    std::array<unsigned char, 3> background = {255, 255, 255};  ///< where no face is seen
    /// Light every visible face gets, fraction of its colour, in [0, 1]; the rest comes from
    /// the light (Lambert, two-sided).
    double ambient = 0.25;
    /// Light direction relative to the camera, by the formula of ViewAngles with the camera's
    /// right, up and towards-the-viewer axes for X, Y and Z: degrees to the right (negative:
    /// left) and above the view direction. {0, 0} is a headlight; the default, a little above
    /// and left, sets apart faces that make the same angle with the view.
    ViewAngles light = {-20, 20};
    /// Empty border around the bounding sphere, fraction of the shorter picture side on each
    /// side, in [0, 0.45].
    double margin = 0.03;
    double outline_darkening = 0.45;  ///< colour factor on region outlines, in [0, 1] (1: none)
};

/// Renders the mesh seen from options.view with an orthographic camera that frames the
/// bounding sphere of the vertices used by faces (centre of the bounding box, radius of the
/// farthest such vertex), the same scale for every view. Each face is flat-shaded with its
/// colour: ambient + (1 - ambient) max(0, n . l) of it, n its unit normal turned towards the
/// camera (two-sided, so open meshes show their inside too) and l the light, which moves
/// with the camera. Nearer faces hide farther ones (z-buffer); ties go to the lower face
/// index. When `face_region` (#F) is given, samples where the region of the visible face
/// changes (texel boundaries, and a region in front of another) are darkened into a thin
/// outline; face_region empty: no outline. Deterministic: same input, same bytes.
/// face_colour: #F. Throws InvalidInput when face_colour or face_region has the wrong size, a
/// face index is out of range, a position used by a face is not finite, or an option is out
/// of its range.
Image render_mesh(const Mesh& mesh, const std::vector<std::array<unsigned char, 3>>& face_colour,
                  const RenderOptions& options, const std::vector<int>& face_region = {});

/// Polygons as the triangles render_mesh draws, with the polygon each triangle comes from.
struct TriangleFans {
    Mesh mesh;                      ///< the soup's positions, and #F triangles
    std::vector<int> face_polygon;  ///< #F: index of the polygon of each triangle
};

/// Splits each polygon c0 c1 ... c(n-1) of the soup into the fan (c0, ck, c(k+1)), k = 1..n-2,
/// keeping the polygons' order and orientation; a polygon of fewer than 3 corners gives no
/// triangle. A fan looks at no position (unlike repair_soup's triangulation), which is enough
/// to draw convex polygons, the common case, at the cost of overlaps in concave ones. Vertex
/// indices are copied as they are: render_mesh checks them.
TriangleFans triangle_fans(const PolygonSoup& soup);

/// The same fans walked without a copy of the mesh: f(polygon, a, b, c) for each triangle, in
/// triangle_fans' order (a, b, c: vertex indices as the soup has them).
template <typename F>
void for_each_fan_triangle(const PolygonSoup& soup, F&& f) {
    for (int p = 0; p < soup.num_polygons(); ++p) {
        const int begin = soup.face_offsets[p], end = soup.face_offsets[p + 1];
        for (int k = begin + 1; k + 1 < end; ++k)
            f(p, soup.face_indices[begin], soup.face_indices[k], soup.face_indices[k + 1]);
    }
}

/// The pictures next to each other, left to right. Throws InvalidInput when the list is empty
/// or the heights differ.
Image side_by_side(const std::vector<Image>& images);

/// Writes the image as PNG: 8-bit RGB, no interlacing, no time or text chunk, so the same
/// image always gives the same bytes. Throws InvalidInput when rgb is not width * height * 3
/// bytes or a side is not positive, IoError when libpng fails or the stream refuses the bytes.
void write_png(std::ostream& out, const Image& image);

}  // namespace geotex
