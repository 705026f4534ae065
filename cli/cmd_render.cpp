// geotex render: a picture (PNG) of a mesh or a segmentation, without a viewer.
//
// Registered in cli/commands.hpp as
//   Runner add_render(CLI::App& app);

#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "geometry/mesh_io.hpp"
#include "pipeline/render.hpp"
#include "pipeline/texture_colour.hpp"

namespace geotex::cli {

namespace {

constexpr int kMaxViews = 8;
// Faces of a mesh without colours: light enough for the shading to show the relief.
constexpr std::array<unsigned char, 3> kPlainGrey = {200, 200, 200};

struct RenderCliOptions {
    CommonOptions common;
    std::string mesh;
    std::string output;
    std::string by = "colour";
    std::string views = "front";
    double azimuth_deg = 0;
    double elevation_deg = 0;
    std::string size = "1024x1024";
    std::string background = "ffffff";
    int supersample = 3;
    bool outline = false;
    CLI::Option* azimuth_option = nullptr;
    CLI::Option* elevation_option = nullptr;
};

[[noreturn]] void bad_size(const std::string& text) {
    throw CliError(kExitUsage, "render: --size must be WIDTHxHEIGHT in pixels, each side 1.." +
                                   std::to_string(kMaxRenderSide) + " (got '" + text + "')");
}

// "WxH" with each side in 1..kMaxRenderSide.
std::pair<int, int> parse_size(const std::string& text) {
    const auto x = text.find_first_of("xX");
    if (x == std::string::npos) bad_size(text);
    auto side = [&](const std::string& digits) {
        if (digits.empty() || digits.size() > 5) bad_size(text);
        for (char c : digits)
            if (!std::isdigit(static_cast<unsigned char>(c))) bad_size(text);
        const int value = std::stoi(digits);
        if (value < 1 || value > kMaxRenderSide) bad_size(text);
        return value;
    };
    return {side(text.substr(0, x)), side(text.substr(x + 1))};
}

// "RRGGBB" or "#RRGGBB", hexadecimal.
std::array<unsigned char, 3> parse_colour(const std::string& text) {
    const std::string hex = !text.empty() && text[0] == '#' ? text.substr(1) : text;
    bool ok = hex.size() == 6;
    for (char c : hex) ok = ok && std::isxdigit(static_cast<unsigned char>(c));
    if (!ok)
        throw CliError(
            kExitUsage,
            "render: --background must be a colour RRGGBB in hexadecimal, e.g. ffffff (got '" +
                text + "')");
    std::array<unsigned char, 3> rgb{};
    for (int k = 0; k < 3; ++k)
        rgb[k] = static_cast<unsigned char>(std::stoi(hex.substr(2 * k, 2), nullptr, 16));
    return rgb;
}

std::vector<ViewAngles> parse_views(const std::string& text) {
    std::vector<ViewAngles> out;
    std::size_t begin = 0;
    while (true) {
        const std::size_t comma = text.find(',', begin);
        const std::string name =
            text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
        const auto angles = named_view(name);
        if (!angles)
            throw CliError(kExitUsage, "render: unknown view '" + name +
                                           "' in --view (known: " + view_names() + ")");
        out.push_back(*angles);
        if (comma == std::string::npos) break;
        begin = comma + 1;
    }
    if (out.size() > kMaxViews)
        throw CliError(kExitUsage, "render: " + std::to_string(out.size()) + " views; at most " +
                                       std::to_string(kMaxViews) + " side by side");
    return out;
}

const FaceProperty* find_property(const MeshFile& file, const std::string& name) {
    for (const auto& p : file.face_properties)
        if (p.name == name) return &p;
    return nullptr;
}

// An integer face property (texel, texture) of a segmentation PLY, per polygon.
std::vector<int> face_ids(const MeshFile& file, const std::string& name, const std::string& path,
                          const std::string& why) {
    const FaceProperty* p = find_property(file, name);
    if (p == nullptr)
        throw CliError(kExitInput, path + ": no face property '" + name + "' for " + why +
                                       " (not a geotex segmentation PLY; try --by colour)");
    std::vector<int> out(p->values.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const double v = p->values[i];
        if (!(std::abs(v) < 2147483647.0) || v != std::floor(v))
            throw CliError(kExitInput, path + ": face property '" + name + "' of polygon " +
                                           std::to_string(i) + " is " + std::to_string(v) +
                                           ", not an int");
        out[i] = static_cast<int>(v);
    }
    return out;
}

// The colour of each polygon: its red/green/blue properties, or the palette of texture or
// texel ids, or plain grey.
std::vector<std::array<unsigned char, 3>> polygon_colours(const MeshFile& file,
                                                          const RenderCliOptions& o) {
    const std::size_t n = static_cast<std::size_t>(file.soup.num_polygons());
    if (o.by == "texture" || o.by == "texel") {
        const std::vector<int> ids = face_ids(file, o.by, o.mesh, "--by " + o.by);
        std::vector<std::array<unsigned char, 3>> out(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = texture_colour(ids[i]);
        return out;
    }
    const FaceProperty* channel[3] = {find_property(file, "red"), find_property(file, "green"),
                                      find_property(file, "blue")};
    const int present = (channel[0] != nullptr) + (channel[1] != nullptr) + (channel[2] != nullptr);
    if (present < 3) {
        if (present > 0)
            warn(o.mesh + ": face colours need all of red, green and blue; drawing the faces grey");
        return std::vector<std::array<unsigned char, 3>>(n, kPlainGrey);
    }
    std::vector<std::array<unsigned char, 3>> out(n);
    for (int k = 0; k < 3; ++k)
        for (std::size_t i = 0; i < n; ++i) {
            const double v = channel[k]->values[i];
            if (!(v >= 0 && v <= 255))
                throw CliError(kExitInput, o.mesh + ": face property '" + channel[k]->name +
                                               "' of polygon " + std::to_string(i) + " is " +
                                               std::to_string(v) + ", outside 0..255");
            out[i][k] = static_cast<unsigned char>(std::lround(v));
        }
    return out;
}

// The picture's size, background and anti-aliasing; the rest keeps render_mesh's defaults.
RenderOptions render_options(const RenderCliOptions& o) {
    const auto [width, height] = parse_size(o.size);
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.background = parse_colour(o.background);
    options.supersample = o.supersample;
    return options;
}

// The views to draw left to right: --azimuth and --elevation give one (the other one 0 when
// only one is given), else the names of --view.
std::vector<ViewAngles> requested_views(const RenderCliOptions& o) {
    if (o.azimuth_option->count() > 0 || o.elevation_option->count() > 0)
        return {{o.azimuth_deg, o.elevation_deg}};
    return parse_views(o.views);
}

// What render_mesh draws: the file's polygons as triangle fans, each triangle with its
// polygon's colour and, for --outline, its polygon's texel.
struct Scene {
    Mesh mesh;
    std::vector<std::array<unsigned char, 3>> face_colour;  // #F
    std::vector<int> face_texel;                            // #F, empty without --outline
};

// The file is read here and let go on return, so that it does not stay in memory beside the
// triangles while they are drawn.
Scene read_scene(const RenderCliOptions& o, Progress& progress) {
    const MeshFile file = timed_stage(progress, "reading", [&] {
        return in_phase(kExitInput, o.mesh, [&] { return read_mesh_file(o.mesh); });
    });
    const std::vector<std::array<unsigned char, 3>> colour = polygon_colours(file, o);
    const std::vector<int> texel =
        o.outline ? face_ids(file, "texel", o.mesh, "--outline") : std::vector<int>{};
    TriangleFans fans = triangle_fans(file.soup);
    if (fans.mesh.faces.empty()) throw CliError(kExitInput, o.mesh + ": no faces to draw");

    Scene scene;
    scene.mesh = std::move(fans.mesh);
    scene.face_colour.reserve(fans.face_polygon.size());
    for (int p : fans.face_polygon) scene.face_colour.push_back(colour[p]);
    if (o.outline) {
        scene.face_texel.reserve(fans.face_polygon.size());
        for (int p : fans.face_polygon) scene.face_texel.push_back(texel[p]);
    }
    return scene;
}

// One picture per view, placed left to right.
Image render_views(const Scene& scene, RenderOptions options, const std::vector<ViewAngles>& views,
                   const std::string& path) {
    std::vector<Image> pictures;
    for (const ViewAngles& view : views) {
        options.view = view;
        pictures.push_back(in_phase(kExitProcessing, path, [&] {
            return render_mesh(scene.mesh, scene.face_colour, options, scene.face_texel);
        }));
    }
    return pictures.size() == 1 ? std::move(pictures.front()) : side_by_side(pictures);
}

int run_render(const RenderCliOptions& o) {
    check_output_paths({{"--output", o.output, true}}, {{"MESH", o.mesh}});
    const RenderOptions options = render_options(o);
    const std::vector<ViewAngles> views = requested_views(o);

    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    const Scene scene = read_scene(o, progress);
    const Image picture = timed_stage(progress, "rendering",
                                      [&] { return render_views(scene, options, views, o.mesh); });
    OutputSet outputs;
    timed_stage(progress, "writing", [&] {
        outputs.add(o.output, [&](std::ostream& out) { write_png(out, picture); });
        outputs.commit();
    });
    progress.note("wrote " + o.output + " (" + std::to_string(picture.width) + "x" +
                  std::to_string(picture.height) + " pixels, " +
                  std::to_string(scene.mesh.num_faces()) + " triangles)");
    return 0;
}

}  // namespace

Runner add_render(CLI::App& sub) {
    auto o = std::make_shared<RenderCliOptions>();
    sub.description(
        "Draw a mesh, or the segmentation PLY of 'geotex segment', to a PNG picture. Orthographic\n"
        "camera framing the mesh's bounding sphere (the same scale for every view), hidden faces\n"
        "removed, flat shading from a light that moves with the camera, a little above and\n"
        "left of it (faces lit on both sides, so open meshes look right), anti-aliased.\n"
        "Faces take the colours of the PLY face properties red, green, blue when present, else\n"
        "light grey.\n"
        "Axes: +Y is up; the front view looks from +Z towards -Z, with +X to the right.\n"
        "The same inputs always give the same bytes.");
    sub.add_option("mesh", o->mesh,
                   "Mesh to draw (.ply .off .obj .stl); polygons are drawn as triangle fans")
        ->required();
    sub.add_option("-o,--output", o->output, "Picture to write (PNG, 8-bit RGB)")->required();
    sub.add_option(
           "--by", o->by,
           "Face colours: colour = the red/green/blue face properties (grey without them);\n"
           "texture or texel = a fixed palette over the int face property of that name (-1 grey)")
        ->check(CLI::IsMember({"colour", "texture", "texel"}))
        ->default_str("colour");
    CLI::Option* view = sub.add_option(
        "--view,--views", o->views,
        "Camera side, or several separated by commas, drawn left to right (e.g. front,iso):\n"
        "front (camera on +Z), back (-Z), right (+X), left (-X),\n"
        "top (+Y, with -Z at the top of the picture), bottom (-Y, +Z at the top),\n"
        "iso (camera on (1,1,1): front, right and top at once)");
    view->default_str("front");
    o->azimuth_option =
        sub.add_option("--azimuth", o->azimuth_deg,
                       "Camera direction instead of --view: degrees about +Y from the front view\n"
                       "(90 = camera on +X, i.e. the right view); default 0")
            ->check(CLI::Range(-360.0, 360.0))
            ->excludes(view);
    o->elevation_option =
        sub.add_option("--elevation", o->elevation_deg,
                       "Camera height instead of --view: degrees above the horizontal plane\n"
                       "(90 = camera on +Y, the top view; -90 = bottom); default 0")
            ->check(CLI::Range(-90.0, 90.0))
            ->excludes(view);
    sub.add_option("--size", o->size,
                   "Picture size WIDTHxHEIGHT in pixels, each side 1.." +
                       std::to_string(kMaxRenderSide) + " (per view when several)")
        ->default_str("1024x1024");
    sub.add_option("--background", o->background,
                   "Colour where no face is seen, RRGGBB in hexadecimal")
        ->default_str("ffffff");
    sub.add_option("--supersample", o->supersample,
                   "Anti-aliasing: N x N samples averaged per pixel (1 = none)")
        ->check(CLI::Range(1, 4))
        ->default_str("3");
    sub.add_flag(
        "--outline", o->outline,
        "Darken a thin line where the texel seen changes (texel boundaries, and a texel in front\n"
        "of another); needs the int face property texel");
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_render(*o); };
}

}  // namespace geotex::cli
