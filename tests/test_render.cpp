#include <png.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <streambuf>
#include <string>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "pipeline/render.hpp"

using namespace geotex;

namespace {

using Rgb = std::array<unsigned char, 3>;

const Rgb kRed = {255, 0, 0}, kGreen = {0, 255, 0}, kBlue = {0, 0, 255};
const Rgb kYellow = {255, 255, 0}, kCyan = {0, 255, 255}, kMagenta = {255, 0, 255};
const Rgb kWhite = {255, 255, 255};

// Appends the quad a b c d (in order round it) as two triangles, both with `colour`.
void add_quad(Mesh& m, std::vector<Rgb>& colours, const Rgb& colour, const Eigen::Vector3d& a,
              const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
    const int base = m.num_vertices();
    for (const auto& p : {a, b, c, d}) m.positions.push_back(p);
    m.faces.push_back({base, base + 1, base + 2});
    m.faces.push_back({base, base + 2, base + 3});
    colours.push_back(colour);
    colours.push_back(colour);
}

// The cube [0, 1]^3, faces outward, coloured by side: +X red, -X yellow, +Y green, -Y cyan,
// +Z blue, -Z magenta.
Mesh make_cube(std::vector<Rgb>& colours) {
    Mesh m;
    using V = Eigen::Vector3d;
    add_quad(m, colours, kRed, V(1, 0, 0), V(1, 1, 0), V(1, 1, 1), V(1, 0, 1));
    add_quad(m, colours, kYellow, V(0, 0, 0), V(0, 0, 1), V(0, 1, 1), V(0, 1, 0));
    add_quad(m, colours, kGreen, V(0, 1, 0), V(0, 1, 1), V(1, 1, 1), V(1, 1, 0));
    add_quad(m, colours, kCyan, V(0, 0, 0), V(1, 0, 0), V(1, 0, 1), V(0, 0, 1));
    add_quad(m, colours, kBlue, V(0, 0, 1), V(1, 0, 1), V(1, 1, 1), V(0, 1, 1));
    add_quad(m, colours, kMagenta, V(0, 0, 0), V(0, 1, 0), V(1, 1, 0), V(1, 0, 0));
    return m;
}

// Which pure colour a shaded pixel comes from: the pattern of its non-zero channels.
Rgb hue(const Rgb& c) {
    Rgb out;
    for (int k = 0; k < 3; ++k) out[k] = c[k] > 0 ? 255 : 0;
    return out;
}

Rgb centre(const Image& im) { return im.pixel(im.width / 2, im.height / 2); }

// A small picture lit by a headlight, so that faces seen face-on keep their exact colour.
RenderOptions small(int width, int height, const std::string& view = "front") {
    RenderOptions o;
    o.width = width;
    o.height = height;
    o.view = *named_view(view);
    o.light = {0, 0};
    return o;
}

// Decodes a PNG from memory with libpng's simplified reader, as 8-bit RGB.
Image decode_png(const std::string& bytes) {
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    REQUIRE(png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()) != 0);
    png.format = PNG_FORMAT_RGB;
    Image out;
    out.width = static_cast<int>(png.width);
    out.height = static_cast<int>(png.height);
    out.rgb.resize(PNG_IMAGE_SIZE(png));
    REQUIRE(png_image_finish_read(&png, nullptr, out.rgb.data(), 0, nullptr) != 0);
    return out;
}

std::uint32_t big_endian(const std::string& s, std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
    return v;
}

// A stream buffer that takes nothing: every write fails.
struct RefusingBuffer : std::streambuf {
    int_type overflow(int_type) override { return traits_type::eof(); }
};

}  // namespace

namespace Catch {
template <>
struct StringMaker<std::array<unsigned char, 3>> {
    static std::string convert(const std::array<unsigned char, 3>& c) {
        return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
               std::to_string(c[2]) + ")";
    }
};
}  // namespace Catch

TEST_CASE("render_mesh: a red triangle seen from the front covers its pixels",
          "[pipeline][render]") {
    // Corners (-1,-1), (1,-1), (0,1): bounding sphere centre (0,0,0), radius sqrt(2); with
    // no margin a 100-pixel picture shows 100 / (2 sqrt 2) = 35.36 pixels per unit.
    Mesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    m.faces = {{0, 1, 2}};
    RenderOptions o = small(100, 100);
    o.margin = 0;
    const Image im = render_mesh(m, {kRed}, o);
    REQUIRE(im.width == 100);
    REQUIRE(im.height == 100);
    REQUIRE(im.rgb.size() == 100 * 100 * 3);
    // Facing the headlight: full colour.
    CHECK(centre(im) == kRed);
    CHECK(im.pixel(50, 80) == kRed);  // y = -(80.5 - 50) / 35.36 = -0.86, inside
    for (auto [x, y] : {std::pair{0, 0}, {99, 0}, {0, 99}, {99, 99}, {50, 5}, {20, 40}, {80, 40}})
        CHECK(im.pixel(x, y) == kWhite);
    // The triangle covers half of its 2 x 2 box: 2 * 35.36^2 = 2500 pixels; only the edge
    // pixels blend, so the count of pure red pixels is within a perimeter (~250) of it.
    int red = 0, coloured = 0;
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x) {
            red += im.pixel(x, y) == kRed;
            coloured += im.pixel(x, y) != kWhite;
        }
    CHECK(red > 2500 - 250);
    CHECK(red < 2500);
    CHECK(coloured > 2500);
    CHECK(coloured < 2500 + 250);
}

TEST_CASE("render_mesh: Lambert shading is ambient plus the cosine to the camera",
          "[pipeline][render]") {
    Mesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.faces = {{0, 1, 2}, {0, 2, 3}};
    RenderOptions o = small(64, 64);
    o.ambient = 0.25;
    o.light = {0, 0};  // a headlight
    o.view = {60, 0};  // cos 60 = 0.5: 0.25 + 0.75 * 0.5 = 0.625 of 255 = 159.4
    CHECK(centre(render_mesh(m, {kRed, kRed}, o)) == Rgb{159, 0, 0});
    // Two-sided: the back of the square is lit the same way.
    o.view = {180 + 60, 0};
    CHECK(centre(render_mesh(m, {kRed, kRed}, o)) == Rgb{159, 0, 0});
    // Seen face-on with the light 60 degrees to the side: the same cosine.
    o.view = {0, 0};
    o.light = {0, 60};
    CHECK(centre(render_mesh(m, {kRed, kRed}, o)) == Rgb{159, 0, 0});
    // A light behind the face leaves the ambient term only: 0.25 of 255 = 63.75.
    o.light = {180, 0};
    CHECK(centre(render_mesh(m, {kRed, kRed}, o)) == Rgb{64, 0, 0});
}

TEST_CASE("render_mesh: the default light sets apart faces at equal angles to the view",
          "[pipeline][render]") {
    // In the iso view the three visible faces of a cube make the same angle with the view;
    // the light above and left of the camera makes the top brightest and the right darkest.
    std::vector<Rgb> colours;
    const Mesh cube = make_cube(colours);
    const std::vector<Rgb> grey(colours.size(), Rgb{200, 200, 200});
    RenderOptions o = small(100, 100, "iso");
    o.light = RenderOptions{}.light;
    const Image im = render_mesh(cube, grey, o);
    const int top = im.pixel(50, 30)[0], left = im.pixel(35, 60)[0], right = im.pixel(65, 60)[0];
    CHECK(top > left);
    CHECK(left > right);
}

TEST_CASE("render_mesh: a unit cube shows the faces towards each view", "[pipeline][render]") {
    std::vector<Rgb> colours;
    const Mesh cube = make_cube(colours);
    const std::pair<const char*, Rgb> expected[] = {{"front", kBlue}, {"back", kMagenta},
                                                    {"right", kRed},  {"left", kYellow},
                                                    {"top", kGreen},  {"bottom", kCyan}};
    for (const auto& [view, colour] : expected) {
        INFO(view);
        CHECK(centre(render_mesh(cube, colours, small(64, 64, view))) == colour);
    }
    // Iso: exactly the +X, +Y and +Z faces are seen; with one sample per pixel every pixel is
    // one of them, shaded, or the background.
    RenderOptions o = small(200, 200, "iso");
    o.supersample = 1;
    const Image im = render_mesh(cube, colours, o);
    int count_red = 0, count_green = 0, count_blue = 0, other = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const Rgb c = im.pixel(x, y);
            if (c == kWhite) continue;
            const Rgb h = hue(c);
            count_red += h == kRed;
            count_green += h == kGreen;
            count_blue += h == kBlue;
            other += h != kRed && h != kGreen && h != kBlue;
        }
    CHECK(other == 0);
    // Equal projected areas (by symmetry), to within an edge of pixels.
    CHECK(count_red > 1000);
    CHECK(std::abs(count_red - count_green) < 200);
    CHECK(std::abs(count_red - count_blue) < 200);
}

TEST_CASE("render_mesh: a near face hides a far one in either drawing order",
          "[pipeline][render]") {
    using V = Eigen::Vector3d;
    for (bool near_first : {true, false}) {
        Mesh m;
        std::vector<Rgb> colours;
        auto add_near = [&] {
            add_quad(m, colours, kRed, V(-1, -1, 0.5), V(1, -1, 0.5), V(1, 1, 0.5), V(-1, 1, 0.5));
        };
        auto add_far = [&] {
            add_quad(m, colours, kBlue, V(-1, -1, -0.5), V(1, -1, -0.5), V(1, 1, -0.5),
                     V(-1, 1, -0.5));
        };
        if (near_first)
            add_near(), add_far();
        else
            add_far(), add_near();
        INFO("near square drawn first: " << near_first);
        CHECK(centre(render_mesh(m, colours, small(50, 50, "front"))) == kRed);
        CHECK(centre(render_mesh(m, colours, small(50, 50, "back"))) == kBlue);
    }
}

TEST_CASE("render_mesh: top view puts -Z at the top of the picture", "[pipeline][render]") {
    using V = Eigen::Vector3d;
    Mesh m;
    std::vector<Rgb> colours;
    add_quad(m, colours, kRed, V(-1, 0, -1), V(1, 0, -1), V(1, 0, -0.2), V(-1, 0, -0.2));
    add_quad(m, colours, kBlue, V(-1, 0, 0.2), V(1, 0, 0.2), V(1, 0, 1), V(-1, 0, 1));
    const Image top = render_mesh(m, colours, small(80, 80, "top"));
    CHECK(top.pixel(40, 20) == kRed);
    CHECK(top.pixel(40, 60) == kBlue);
    const Image bottom = render_mesh(m, colours, small(80, 80, "bottom"));
    CHECK(bottom.pixel(40, 20) == kBlue);
    CHECK(bottom.pixel(40, 60) == kRed);
    // Right view: +Z (blue) on the left of the picture, as the camera on +X looks towards -X.
    RenderOptions o = small(80, 80);
    o.view = {90, 30};
    const Image right = render_mesh(m, colours, o);
    CHECK(hue(right.pixel(20, 40)) == kBlue);
    CHECK(hue(right.pixel(60, 40)) == kRed);
}

TEST_CASE("render_mesh: the same mesh scaled by a power of two gives the same picture",
          "[pipeline][render]") {
    std::vector<Rgb> colours;
    const Mesh cube = make_cube(colours);
    Mesh big = cube;
    for (auto& p : big.positions) p = p * 1024.0 + Eigen::Vector3d(2048, -4096, 512);
    const RenderOptions o = small(120, 90, "iso");
    // Powers of two scale every intermediate exactly, so the pictures match bit for bit.
    CHECK(render_mesh(cube, colours, o).rgb == render_mesh(big, colours, o).rgb);
    // Scaled by 1000 the rounding differs in the last bits: at most an edge pixel here and there.
    Mesh odd = cube;
    for (auto& p : odd.positions) p = p * 1000.0 + Eigen::Vector3d(3, 7, -11);
    const Image a = render_mesh(cube, colours, o), b = render_mesh(odd, colours, o);
    int differ = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        differ += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 40;
    CHECK(differ < 30);
}

TEST_CASE("render_mesh: two renders are byte-identical", "[pipeline][render]") {
    std::vector<Rgb> colours;
    const Mesh cube = make_cube(colours);
    std::vector<int> region(cube.num_faces());
    for (int f = 0; f < cube.num_faces(); ++f) region[f] = f / 4;
    RenderOptions o = small(300, 200, "iso");
    o.view.azimuth_deg = 33;
    const Image a = render_mesh(cube, colours, o, region);
    const Image b = render_mesh(cube, colours, o, region);
    CHECK(a.rgb == b.rgb);
    std::ostringstream pa, pb;
    write_png(pa, a);
    write_png(pb, b);
    CHECK(pa.str() == pb.str());
}

TEST_CASE("render_mesh: outlines darken region boundaries only", "[pipeline][render]") {
    // A flat square of 4 x 4 cells facing the camera; regions: the left half 0, the right 1.
    Mesh m;
    std::vector<Rgb> colours;
    std::vector<int> region;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const double x = -1 + 0.5 * i, y = -1 + 0.5 * j;
            add_quad(m, colours, kGreen, {x, y, 0}, {x + 0.5, y, 0}, {x + 0.5, y + 0.5, 0},
                     {x, y + 0.5, 0});
            region.push_back(i < 2 ? 0 : 1);
            region.push_back(i < 2 ? 0 : 1);
        }
    const RenderOptions o = small(90, 90);
    const Image plain = render_mesh(m, colours, o);
    const Image one_region = render_mesh(m, colours, o, std::vector<int>(region.size(), 7));
    CHECK(plain.rgb == one_region.rgb);  // no boundary, no outline: cell diagonals stay unmarked
    const Image outlined = render_mesh(m, colours, o, region);
    // x = 0 lies on the pixel border between 44 and 45: one sample column of three is darkened
    // on each side, (255 + 255 + 115) / 3 = 208.
    CHECK(outlined.pixel(45, 45)[1] < 220);
    CHECK(outlined.pixel(44, 45)[1] < 220);
    CHECK(outlined.pixel(30, 45) == kGreen);
    CHECK(outlined.pixel(60, 45) == kGreen);
    CHECK(outlined.pixel(45, 70)[1] < 220);
}

TEST_CASE("render_mesh: an empty mesh gives the background", "[pipeline][render]") {
    RenderOptions o = small(7, 5);
    o.background = {1, 2, 3};
    const Image im = render_mesh(Mesh{}, {}, o);
    REQUIRE(im.rgb.size() == 7 * 5 * 3);
    CHECK(im.pixel(6, 4) == Rgb{1, 2, 3});
}

TEST_CASE("render_mesh: bad options and data are rejected", "[pipeline][render]") {
    std::vector<Rgb> colours;
    const Mesh cube = make_cube(colours);
    auto with = [](auto change) {
        RenderOptions o = small(10, 10);
        change(o);
        return o;
    };
    REQUIRE_THROWS_AS(render_mesh(cube, colours, with([](RenderOptions& o) { o.width = 0; })),
                      InvalidInput);
    REQUIRE_THROWS_AS(
        render_mesh(cube, colours, with([](RenderOptions& o) { o.height = kMaxRenderSide + 1; })),
        InvalidInput);
    REQUIRE_THROWS_AS(render_mesh(cube, colours, with([](RenderOptions& o) { o.supersample = 0; })),
                      InvalidInput);
    REQUIRE_THROWS_AS(render_mesh(cube, colours, with([](RenderOptions& o) { o.supersample = 5; })),
                      InvalidInput);
    REQUIRE_THROWS_AS(
        render_mesh(cube, colours, with([](RenderOptions& o) { o.view.elevation_deg = 91; })),
        InvalidInput);
    REQUIRE_THROWS_AS(render_mesh(cube, colours, with([](RenderOptions& o) {
                                      o.view.azimuth_deg = std::numeric_limits<double>::quiet_NaN();
                                  })),
                      InvalidInput);
    REQUIRE_THROWS_AS(render_mesh(cube, colours, with([](RenderOptions& o) { o.ambient = 1.5; })),
                      InvalidInput);
    REQUIRE_THROWS_AS(
        render_mesh(cube, colours, with([](RenderOptions& o) { o.light.elevation_deg = -95; })),
        InvalidInput);
    REQUIRE_THROWS_AS(render_mesh(cube, colours, with([](RenderOptions& o) { o.margin = 0.5; })),
                      InvalidInput);
    REQUIRE_THROWS_AS(
        render_mesh(cube, colours, with([](RenderOptions& o) { o.outline_darkening = -0.1; })),
        InvalidInput);
    const RenderOptions ok = small(10, 10);
    REQUIRE_THROWS_AS(render_mesh(cube, std::vector<Rgb>(3), ok), InvalidInput);
    REQUIRE_THROWS_AS(render_mesh(cube, colours, ok, std::vector<int>(5)), InvalidInput);
    Mesh bad_index = cube;
    bad_index.faces[3][1] = cube.num_vertices();
    REQUIRE_THROWS_AS(render_mesh(bad_index, colours, ok), InvalidInput);
    Mesh bad_point = cube;
    bad_point.positions[0].x() = std::numeric_limits<double>::infinity();
    REQUIRE_THROWS_AS(render_mesh(bad_point, colours, ok), InvalidInput);
}

TEST_CASE("named_view: the documented names and nothing else", "[pipeline][render]") {
    CHECK(named_view("front")->azimuth_deg == 0);
    CHECK(named_view("right")->azimuth_deg == 90);
    CHECK(named_view("top")->elevation_deg == 90);
    CHECK(named_view("iso")->elevation_deg == Approx(35.26438968));
    CHECK_FALSE(named_view("Front"));
    CHECK_FALSE(named_view(""));
    CHECK(view_names() == "front, back, left, right, top, bottom, iso");
}

TEST_CASE("side_by_side: pictures placed left to right", "[pipeline][render]") {
    Image a{2, 1, {1, 1, 1, 2, 2, 2}}, b{1, 1, {3, 3, 3}};
    const Image ab = side_by_side({a, b});
    CHECK(ab.width == 3);
    CHECK(ab.height == 1);
    CHECK(ab.pixel(2, 0) == Rgb{3, 3, 3});
    REQUIRE_THROWS_AS(side_by_side({}), InvalidInput);
    REQUIRE_THROWS_AS(side_by_side({a, Image{1, 2, std::vector<unsigned char>(6)}}), InvalidInput);
}

TEST_CASE("write_png: a round trip through libpng's reader gives the pixels back",
          "[pipeline][render]") {
    std::vector<Rgb> colours;
    const Mesh cube = make_cube(colours);
    const Image im = render_mesh(cube, colours, small(37, 21, "iso"));
    std::ostringstream out;
    write_png(out, im);
    const std::string bytes = out.str();
    REQUIRE(bytes.size() > 33);
    CHECK(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
    CHECK(bytes.compare(12, 4, "IHDR") == 0);
    CHECK(big_endian(bytes, 16) == 37);  // width
    CHECK(big_endian(bytes, 20) == 21);  // height
    CHECK(bytes[24] == 8);               // bit depth
    CHECK(bytes[25] == 2);               // colour type: RGB
    CHECK(bytes.find("tIME") == std::string::npos);
    const Image back = decode_png(bytes);
    CHECK(back.width == 37);
    CHECK(back.height == 21);
    CHECK(back.rgb == im.rgb);
}

TEST_CASE("write_png: bad images and failing streams throw", "[pipeline][render]") {
    std::ostringstream out;
    REQUIRE_THROWS_AS(write_png(out, Image{}), InvalidInput);
    REQUIRE_THROWS_AS(write_png(out, Image{2, 2, std::vector<unsigned char>(5)}), InvalidInput);
    RefusingBuffer refusing;
    std::ostream closed(&refusing);
    REQUIRE_THROWS_AS(write_png(closed, Image{2, 2, std::vector<unsigned char>(12)}), IoError);
}

TEST_CASE("triangle_fans: each polygon becomes its fan from the first corner, in order",
          "[pipeline][render]") {
    PolygonSoup soup;
    for (int k = 0; k < 8; ++k) soup.positions.emplace_back(k, k * k, 0);
    // A triangle, a quad and a pentagon, corners in no particular index order.
    soup.face_indices = {2, 0, 1, 4, 5, 6, 7, 3, 1, 2, 5, 6};
    soup.face_offsets = {0, 3, 7, 12};
    const TriangleFans fans = triangle_fans(soup);
    const std::vector<std::array<int, 3>> expected = {{2, 0, 1}, {4, 5, 6}, {4, 6, 7},
                                                      {3, 1, 2}, {3, 2, 5}, {3, 5, 6}};
    CHECK(fans.mesh.faces == expected);
    CHECK(fans.face_polygon == std::vector<int>{0, 1, 1, 2, 2, 2});
    CHECK(fans.mesh.positions == soup.positions);
    CHECK(triangle_fans(PolygonSoup{}).mesh.faces.empty());
}

TEST_CASE("triangle_fans: the fan of a convex polygon covers its area with its orientation",
          "[pipeline][render]") {
    // A regular hexagon of circumradius 2 in the plane z = 1, counter-clockwise seen from +Z:
    // area 3 sqrt(3) / 2 r^2 = 6 sqrt(3).
    PolygonSoup soup;
    for (int k = 0; k < 6; ++k) {
        const double a = k * kPi / 3;
        soup.positions.emplace_back(2 * std::cos(a), 2 * std::sin(a), 1);
        soup.face_indices.push_back(k);
    }
    soup.face_offsets = {0, 6};
    const TriangleFans fans = triangle_fans(soup);
    REQUIRE(fans.mesh.num_faces() == 4);
    double area = 0;
    for (const auto& t : fans.mesh.faces) {
        const auto& p = fans.mesh.positions;
        const Eigen::Vector3d n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
        CHECK(n.z() > 0);  // every triangle faces +Z, as the polygon does
        area += 0.5 * n.norm();
    }
    // A few roundings of cos and sin of multiples of pi/3 in a sum of 4 terms.
    CHECK(area == Approx(6 * std::sqrt(3.0)).epsilon(1e-12));
}
