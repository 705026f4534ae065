#include "pipeline/render.hpp"

#include <png.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <ostream>
#include <utility>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"

namespace geotex {

std::array<unsigned char, 3> Image::pixel(int x, int y) const {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

namespace {

const std::pair<const char*, ViewAngles> kViews[] = {
    {"front", {0, 0}},
    {"back", {180, 0}},
    {"left", {-90, 0}},
    {"right", {90, 0}},
    {"top", {0, 90}},
    {"bottom", {0, -90}},
    // The camera on (1, 1, 1): elevation atan(1 / sqrt(2)).
    {"iso", {45, 35.26438968275466}},
};

// Screen positions are fixed point, in 1/256 of a sample, so that the coverage test is exact
// integer arithmetic: faces sharing an edge neither overlap nor leave a crack.
constexpr int kSubBits = 8;
constexpr std::int64_t kSub = std::int64_t{1} << kSubBits;
// Output rows rasterised together: memory stays bounded whatever the size, and the band's
// buffers stay in cache.
constexpr int kBandRows = 32;

// (sin, cos) of an angle in degrees, exact at multiples of 90 so the named views are exact.
std::pair<double, double> sin_cos_deg(double deg) {
    double r = std::fmod(deg, 360.0);
    if (r < 0) r += 360.0;
    if (r == 0) return {0.0, 1.0};
    if (r == 90) return {1.0, 0.0};
    if (r == 180) return {0.0, -1.0};
    if (r == 270) return {-1.0, 0.0};
    const double rad = r * (kPi / 180.0);
    return {std::sin(rad), std::cos(rad)};
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
    return q;
}

std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return -floor_div(-a, b); }

void check_options(const RenderOptions& o) {
    auto fail = [](const std::string& what) { throw InvalidInput("render_mesh: " + what); };
    if (o.width < 1 || o.width > kMaxRenderSide || o.height < 1 || o.height > kMaxRenderSide)
        fail("picture size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
             " is outside 1.." + std::to_string(kMaxRenderSide) + " pixels per side");
    if (o.supersample < 1 || o.supersample > 4)
        fail("supersample " + std::to_string(o.supersample) +
             " is outside 1..4 samples per pixel side");
    if (!std::isfinite(o.view.azimuth_deg)) fail("the azimuth is not a finite number of degrees");
    if (!(o.view.elevation_deg >= -90 && o.view.elevation_deg <= 90))
        fail("elevation " + std::to_string(o.view.elevation_deg) + " is outside -90...90 degrees");
    if (!std::isfinite(o.light.azimuth_deg) ||
        !(o.light.elevation_deg >= -90 && o.light.elevation_deg <= 90))
        fail("the light direction needs a finite azimuth and an elevation in -90...90 degrees");
    if (!(o.ambient >= 0 && o.ambient <= 1))
        fail("ambient " + std::to_string(o.ambient) + " is outside 0...1");
    if (!(o.margin >= 0 && o.margin <= 0.45))
        fail("margin " + std::to_string(o.margin) + " is outside 0...0.45 of the shorter side");
    if (!(o.outline_darkening >= 0 && o.outline_darkening <= 1))
        fail("outline darkening " + std::to_string(o.outline_darkening) + " is outside 0...1");
}

// A face in sample space: fixed-point corners (either orientation) and their depths.
struct ScreenTriangle {
    std::int64_t x[3], y[3];
    double z[3];
};

// Sample rows and columns (inclusive ranges).
struct SampleBox {
    std::int64_t col0, col1, row0, row1;
};

// The samples whose centres lie in the triangle's bounding box, clipped to the picture;
// nullopt when there are none or the triangle has no area on screen.
std::optional<SampleBox> sample_box(const ScreenTriangle& t, std::int64_t num_cols,
                                    std::int64_t num_rows) {
    const std::int64_t area =
        (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
    if (area == 0) return std::nullopt;
    const std::int64_t half = kSub / 2;
    SampleBox box;
    const auto [xmin, xmax] = std::minmax({t.x[0], t.x[1], t.x[2]});
    const auto [ymin, ymax] = std::minmax({t.y[0], t.y[1], t.y[2]});
    box.col0 = std::max<std::int64_t>(0, ceil_div(xmin - half, kSub));
    box.col1 = std::min<std::int64_t>(num_cols - 1, floor_div(xmax - half, kSub));
    box.row0 = std::max<std::int64_t>(0, ceil_div(ymin - half, kSub));
    box.row1 = std::min<std::int64_t>(num_rows - 1, floor_div(ymax - half, kSub));
    if (box.col0 > box.col1 || box.row0 > box.row1) return std::nullopt;
    return box;
}

// Per-band sample buffers: the depth and the face seen at each sample (-1: none).
struct Band {
    std::int64_t first_row = 0;  // sample row of buffer row 0 (may be -1: the apron)
    int num_rows = 0;
    int num_cols = 0;
    std::vector<float> depth;
    std::vector<int> face;
};

// Draws triangle f into the band's rows [row_lo, row_hi] (sample rows, inclusive).
void rasterise(const ScreenTriangle& in, int f, const SampleBox& box, std::int64_t row_lo,
               std::int64_t row_hi, Band& band) {
    ScreenTriangle t = in;
    const std::int64_t area =
        (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
    if (area < 0) {  // two-sided: draw either orientation
        std::swap(t.x[1], t.x[2]);
        std::swap(t.y[1], t.y[2]);
        std::swap(t.z[1], t.z[2]);
    }
    // Edge functions E = A x + B y + C, positive inside. A sample exactly on an edge belongs
    // to the triangle that "owns" the edge by the sign of (A, B); the neighbour across the
    // edge sees (-A, -B), so exactly one of the two draws it.
    std::int64_t a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) {
        const int i = k, j = (k + 1) % 3;
        a[k] = t.y[i] - t.y[j];
        b[k] = t.x[j] - t.x[i];
        c[k] = (t.y[j] - t.y[i]) * t.x[i] - (t.x[j] - t.x[i]) * t.y[i];
        const bool owns = a[k] > 0 || (a[k] == 0 && b[k] > 0);
        if (!owns) c[k] -= 1;  // E >= 1, i.e. strictly inside, for edges it does not own
    }
    // Depth plane z = z0 + zx (x - x0) + zy (y - y0) over the snapped corners.
    const double dx1 = double(t.x[1] - t.x[0]), dy1 = double(t.y[1] - t.y[0]);
    const double dx2 = double(t.x[2] - t.x[0]), dy2 = double(t.y[2] - t.y[0]);
    const double dz1 = t.z[1] - t.z[0], dz2 = t.z[2] - t.z[0];
    const double det = dx1 * dy2 - dx2 * dy1;
    const double zx = (dz1 * dy2 - dz2 * dy1) / det, zy = (dx1 * dz2 - dx2 * dz1) / det;
    const double z_step = zx * double(kSub);

    const std::int64_t r0 = std::max(box.row0, row_lo), r1 = std::min(box.row1, row_hi);
    const std::int64_t px0 = box.col0 * kSub + kSub / 2;
    for (std::int64_t row = r0; row <= r1; ++row) {
        const std::int64_t py = row * kSub + kSub / 2;
        std::int64_t e0 = a[0] * px0 + b[0] * py + c[0];
        std::int64_t e1 = a[1] * px0 + b[1] * py + c[1];
        std::int64_t e2 = a[2] * px0 + b[2] * py + c[2];
        const double z_row = t.z[0] + zx * double(px0 - t.x[0]) + zy * double(py - t.y[0]);
        const std::size_t offset = static_cast<std::size_t>(row - band.first_row) * band.num_cols;
        float* depth = band.depth.data() + offset;
        int* face = band.face.data() + offset;
        for (std::int64_t col = box.col0; col <= box.col1; ++col) {
            if ((e0 | e1 | e2) >= 0) {
                const float z = static_cast<float>(z_row + z_step * double(col - box.col0));
                if (z > depth[col]) {
                    depth[col] = z;
                    face[col] = f;
                }
            }
            e0 += a[0] * kSub;
            e1 += a[1] * kSub;
            e2 += a[2] * kSub;
        }
    }
}

// ---- The steps of render_mesh ------------------------------------------------------------------

// The per-face data must match the mesh before anything is drawn: a wrong call fails with a
// message instead of drawing colours that belong to other faces.
void check_face_data(const Mesh& mesh, const std::vector<std::array<unsigned char, 3>>& face_colour,
                     const std::vector<int>& face_region) {
    const int num_faces = mesh.num_faces();
    if (face_colour.size() != mesh.faces.size())
        throw InvalidInput("render_mesh: " + std::to_string(face_colour.size()) +
                           " face colours for " + std::to_string(num_faces) +
                           " faces; give one colour per face");
    if (!face_region.empty() && face_region.size() != mesh.faces.size())
        throw InvalidInput("render_mesh: " + std::to_string(face_region.size()) +
                           " face regions for " + std::to_string(num_faces) +
                           " faces; give one per face, or none for no outline");
}

// 1 for the vertices that faces use, 0 for the others (#V). Only used vertices are framed,
// checked and projected: a stray vertex that no face draws must neither shrink the picture
// nor fail it with a coordinate that is not finite.
std::vector<char> used_vertices(const Mesh& mesh) {
    const int num_faces = mesh.num_faces(), num_vertices = mesh.num_vertices();
    std::vector<char> used(num_vertices, 0);
    for (int f = 0; f < num_faces; ++f)
        for (int v : mesh.faces[f]) {
            if (v < 0 || v >= num_vertices)
                throw InvalidInput("render_mesh: face " + std::to_string(f) + " has vertex index " +
                                   std::to_string(v) + ", outside 0.." +
                                   std::to_string(num_vertices - 1));
            used[v] = 1;
        }
    return used;
}

// The picture before any face is drawn: every later step only overwrites it, band by band.
Image background_image(const RenderOptions& options) {
    Image image;
    image.width = options.width;
    image.height = options.height;
    image.rgb.resize(static_cast<std::size_t>(options.width) * options.height * 3);
    for (std::size_t i = 0; i < image.rgb.size(); i += 3)
        for (int k = 0; k < 3; ++k) image.rgb[i + k] = options.background[k];
    return image;
}

// An orthographic camera over the sample grid (the picture's pixels times supersample per side).
struct Camera {
    Eigen::Vector3d right, up, toward;        // screen axes in world space, right x up = toward
    Eigen::Vector3d centre;                   // the world point at the middle of the picture
    double scale = 1;                         // samples per mesh unit
    std::int64_t num_cols = 0, num_rows = 0;  // size of the sample grid
};

// Frames the bounding sphere of the used vertices (centre of their bounding box, radius of the
// farthest one) rather than what the camera sees of the mesh: every view of one mesh then has
// the same scale, so views side by side compare. The axes come from sin_cos_deg, exact at
// multiples of 90 degrees, so the named views put vertices exactly on sample positions.
Camera frame_camera(const Mesh& mesh, const std::vector<char>& used, const RenderOptions& options) {
    const int num_vertices = mesh.num_vertices();
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (int v = 0; v < num_vertices; ++v) {
        if (!used[v]) continue;
        if (!mesh.positions[v].allFinite())
            throw InvalidInput("render_mesh: vertex " + std::to_string(v) +
                               " has a coordinate that is not finite");
        lo = lo.cwiseMin(mesh.positions[v]);
        hi = hi.cwiseMax(mesh.positions[v]);
    }

    Camera camera;
    camera.num_cols = std::int64_t{options.width} * options.supersample;
    camera.num_rows = std::int64_t{options.height} * options.supersample;
    const auto [sin_az, cos_az] = sin_cos_deg(options.view.azimuth_deg);
    const auto [sin_el, cos_el] = sin_cos_deg(options.view.elevation_deg);
    camera.toward = Eigen::Vector3d(cos_el * sin_az, sin_el, cos_el * cos_az);
    camera.right = Eigen::Vector3d(cos_az, 0, -sin_az);
    camera.up = Eigen::Vector3d(-sin_el * sin_az, cos_el, -sin_el * cos_az);

    camera.centre = 0.5 * lo + 0.5 * hi;  // no overflow near the double range
    double radius = 0;
    for (int v = 0; v < num_vertices; ++v)
        if (used[v]) radius = std::max(radius, (mesh.positions[v] - camera.centre).stableNorm());
    if (!std::isfinite(radius))
        throw InvalidInput(
            "render_mesh: the mesh is too large for double precision (its bounding "
            "radius overflows); scale it down");
    const double half_side =
        0.5 * double(std::min(camera.num_cols, camera.num_rows)) * (1 - 2 * options.margin);
    // A single point, or a mesh far below the double range: any scale shows it.
    if (!(radius > 0) || !std::isfinite(half_side / radius)) radius = 1;
    camera.scale = half_side / radius;
    return camera;
}

// The used vertices in sample space (#V each; unused ones stay 0): x to the right and y down in
// fixed point (1/kSub of a sample), rounded once per vertex so that faces sharing a vertex
// share its screen position exactly; z towards the viewer (larger: nearer), kept in double
// for the depth planes.
struct ScreenVertices {
    std::vector<std::int64_t> x, y;
    std::vector<double> z;
};

ScreenVertices project_vertices(const Mesh& mesh, const std::vector<char>& used,
                                const Camera& camera) {
    const int num_vertices = mesh.num_vertices();
    ScreenVertices s;
    s.x.assign(num_vertices, 0);
    s.y.assign(num_vertices, 0);
    s.z.assign(num_vertices, 0);
    for (int v = 0; v < num_vertices; ++v) {
        if (!used[v]) continue;
        const Eigen::Vector3d p = mesh.positions[v] - camera.centre;
        s.x[v] = std::llround((0.5 * double(camera.num_cols) + camera.scale * p.dot(camera.right)) *
                              double(kSub));
        s.y[v] = std::llround((0.5 * double(camera.num_rows) - camera.scale * p.dot(camera.up)) *
                              double(kSub));
        s.z[v] = p.dot(camera.toward);
    }
    return s;
}

// Face corners looked up when needed rather than stored per face: on a mesh of a million faces
// a copy per face would cost more memory than the vertices themselves.
ScreenTriangle screen_triangle(const ScreenVertices& s, const std::array<int, 3>& face) {
    ScreenTriangle t;
    for (int k = 0; k < 3; ++k) {
        t.x[k] = s.x[face[k]];
        t.y[k] = s.y[face[k]];
        t.z[k] = s.z[face[k]];
    }
    return t;
}

// Each face's two possible colours (#F each): lit, and darkened for samples on an outline.
struct FaceShades {
    std::vector<std::array<unsigned char, 3>> lit, dark;
};

// Flat two-sided Lambert shading, once per face rather than once per sample: ambient plus the
// cosine between the light and the normal turned towards the camera, so that open meshes show
// their inside lit too. The light is given in the camera's (right, up, toward) frame, so it
// moves with the camera and every view is lit alike.
FaceShades shade_faces(const Mesh& mesh,
                       const std::vector<std::array<unsigned char, 3>>& face_colour,
                       const Camera& camera, const RenderOptions& options) {
    const auto [sin_light_az, cos_light_az] = sin_cos_deg(options.light.azimuth_deg);
    const auto [sin_light_el, cos_light_el] = sin_cos_deg(options.light.elevation_deg);
    const Eigen::Vector3d light = (cos_light_el * sin_light_az) * camera.right +
                                  sin_light_el * camera.up +
                                  (cos_light_el * cos_light_az) * camera.toward;

    const int num_faces = mesh.num_faces();
    const double outline_factor = options.outline_darkening;
    FaceShades shades;
    shades.lit.resize(num_faces);
    shades.dark.resize(num_faces);
    for (int f = 0; f < num_faces; ++f) {
        const auto& p = mesh.positions;
        const auto& fv = mesh.faces[f];
        const Eigen::Vector3d n = (p[fv[1]] - p[fv[0]]).cross(p[fv[2]] - p[fv[0]]);
        const double length = n.norm();
        const double facing = n.dot(camera.toward) < 0 ? -1.0 : 1.0;
        const double cosine =
            length > 0 ? std::clamp(facing * n.dot(light) / length, 0.0, 1.0) : 0.0;
        const double brightness = options.ambient + (1 - options.ambient) * cosine;
        for (int k = 0; k < 3; ++k) {
            const double value = face_colour[f][k] * brightness;
            shades.lit[f][k] = static_cast<unsigned char>(std::lround(std::min(255.0, value)));
            shades.dark[f][k] =
                static_cast<unsigned char>(std::lround(std::min(255.0, value * outline_factor)));
        }
    }
    return shades;
}

// How the sample rows split into bands of kBandRows output rows.
struct BandLayout {
    int apron = 0;                 // sample rows beyond each end of a band the outline test reads
    std::int64_t sample_rows = 0;  // sample rows of a band, apron excluded
    int num_bands = 0;
};

BandLayout band_layout(const RenderOptions& options, bool outline) {
    BandLayout layout;
    // The outline test compares a sample with the one above and below it, which for the first
    // and last row of a band lie in the neighbouring bands: those rows are drawn twice.
    layout.apron = outline ? 1 : 0;
    layout.sample_rows = std::int64_t{kBandRows} * options.supersample;
    layout.num_bands = static_cast<int>((options.height + kBandRows - 1) / kBandRows);
    return layout;
}

// Calls visit(f, b) for each face f, in index order, and each band b that the face's samples
// touch, apron included. Faces without area on screen or outside the picture touch none.
template <typename Visit>
void for_each_face_band(const Mesh& mesh, const ScreenVertices& screen, const Camera& camera,
                        const BandLayout& layout, Visit&& visit) {
    const int num_faces = mesh.num_faces();
    for (int f = 0; f < num_faces; ++f) {
        const auto box =
            sample_box(screen_triangle(screen, mesh.faces[f]), camera.num_cols, camera.num_rows);
        if (!box) continue;
        const std::int64_t first =
            std::max<std::int64_t>(0, floor_div(box->row0 - layout.apron, layout.sample_rows));
        const std::int64_t last = std::min<std::int64_t>(
            layout.num_bands - 1, floor_div(box->row1 + layout.apron, layout.sample_rows));
        for (int b = static_cast<int>(first); b <= static_cast<int>(last); ++b) visit(f, b);
    }
}

// The faces each band must draw, as compressed rows: band b draws faces[start[b] ..
// start[b + 1]). A face goes to every band it touches, so each band is drawn alone with
// buffers of its own size; within a band the faces keep their index order, which makes depth
// ties go to the lower face index whatever the band.
struct BandBins {
    std::vector<std::size_t> start;  // #bands + 1
    std::vector<int> faces;
};

BandBins bin_faces(const Mesh& mesh, const ScreenVertices& screen, const Camera& camera,
                   const BandLayout& layout) {
    BandBins bins;
    // Two passes, counting then filling, so the lists take one allocation of the exact size.
    bins.start.assign(layout.num_bands + 1, 0);
    for_each_face_band(mesh, screen, camera, layout, [&](int, int b) { ++bins.start[b + 1]; });
    for (int b = 0; b < layout.num_bands; ++b) bins.start[b + 1] += bins.start[b];
    bins.faces.resize(bins.start[layout.num_bands]);
    std::vector<std::size_t> fill(bins.start.begin(), bins.start.end() - 1);
    for_each_face_band(mesh, screen, camera, layout,
                       [&](int f, int b) { bins.faces[fill[b]++] = f; });
    return bins;
}

// Buffers for one band with its apron, allocated once and reused by every band.
Band make_band(const Camera& camera, const BandLayout& layout) {
    Band band;
    band.num_cols = static_cast<int>(camera.num_cols);
    band.num_rows = static_cast<int>(layout.sample_rows) + 2 * layout.apron;
    band.depth.resize(static_cast<std::size_t>(band.num_rows) * band.num_cols);
    band.face.resize(band.depth.size());
    return band;
}

// The depth test of band b: clears the band's buffers and draws its faces into them, so that
// each sample ends up with the nearest face (-1 where none is).
// Out of line on purpose: inlined into render_mesh beside the other steps, the per-sample loop
// of rasterise ran short of registers (callgrind: about 10% more instructions per picture).
[[gnu::noinline]] void rasterise_band(int b, const Mesh& mesh, const ScreenVertices& screen,
                                      const BandBins& bins, const Camera& camera,
                                      const BandLayout& layout, Band& band) {
    band.first_row = b * layout.sample_rows - layout.apron;
    std::fill(band.depth.begin(), band.depth.end(), -std::numeric_limits<float>::infinity());
    std::fill(band.face.begin(), band.face.end(), -1);
    const std::int64_t row_lo = std::max<std::int64_t>(0, band.first_row);
    const std::int64_t row_hi =
        std::min<std::int64_t>(camera.num_rows - 1, band.first_row + band.num_rows - 1);
    for (std::size_t i = bins.start[b]; i < bins.start[b + 1]; ++i) {
        const int f = bins.faces[i];
        const ScreenTriangle t = screen_triangle(screen, mesh.faces[f]);
        rasterise(t, f, *sample_box(t, camera.num_cols, camera.num_rows), row_lo, row_hi, band);
    }
}

// A sample is on an outline when one of its 4 neighbours shows a face of another region; a
// neighbour with no face does not count, so the silhouette against the background stays
// undarkened. Band buffer coordinates (r, c), f the face seen there.
bool on_outline(const Band& band, const int* face_region, int r, int c, int f) {
    const int region = face_region[f];
    const int* face = band.face.data();
    const int num_rows = band.num_rows, num_cols = band.num_cols;
    auto differs = [&](int rr, int cc) {
        if (rr < 0 || rr >= num_rows || cc < 0 || cc >= num_cols) return false;
        const int g = face[static_cast<std::size_t>(rr) * num_cols + cc];
        return g >= 0 && face_region[g] != region;
    };
    return differs(r - 1, c) || differs(r + 1, c) || differs(r, c - 1) || differs(r, c + 1);
}

// Band b's output rows: each pixel is the rounded mean of its supersample x supersample
// samples, each the background, the face's lit colour or, on an outline, its dark one. Integer
// sums, so the result does not depend on the order of the additions. The pixels are written
// through unsigned char, which may alias anything, so what the loop reads is first copied to
// locals that the writes cannot change.
void resolve_band(int b, const Band& band, const FaceShades& shades,
                  const std::vector<int>& face_region, const RenderOptions& options, Image& image) {
    const int ss = options.supersample;
    const int samples_per_pixel = ss * ss;
    const bool outline = !face_region.empty();
    const int width = options.width;
    const std::array<unsigned char, 3> background = options.background;
    const std::array<unsigned char, 3>* lit = shades.lit.data();
    const std::array<unsigned char, 3>* dark = shades.dark.data();
    const int* region = face_region.data();
    const int* face = band.face.data();
    const int num_cols = band.num_cols;
    const int y_end = std::min(options.height, (b + 1) * kBandRows);
    for (int y = b * kBandRows; y < y_end; ++y) {
        unsigned char* out = image.rgb.data() + static_cast<std::size_t>(y) * width * 3;
        const int r_base = static_cast<int>(std::int64_t{y} * ss - band.first_row);
        for (int x = 0; x < width; ++x) {
            int sum[3] = {0, 0, 0};
            for (int dy = 0; dy < ss; ++dy) {
                const int r = r_base + dy;
                const int* face_row = face + static_cast<std::size_t>(r) * num_cols;
                for (int dx = 0; dx < ss; ++dx) {
                    const int c = x * ss + dx;
                    const int f = face_row[c];
                    const std::array<unsigned char, 3>& colour =
                        f < 0 ? background
                              : (outline && on_outline(band, region, r, c, f) ? dark[f] : lit[f]);
                    for (int k = 0; k < 3; ++k) sum[k] += colour[k];
                }
            }
            for (int k = 0; k < 3; ++k)
                out[3 * x + k] = static_cast<unsigned char>((sum[k] + samples_per_pixel / 2) /
                                                            samples_per_pixel);
        }
    }
}
}  // namespace

std::optional<ViewAngles> named_view(const std::string& name) {
    for (const auto& [n, angles] : kViews)
        if (name == n) return angles;
    return std::nullopt;
}

std::string view_names() {
    std::string out;
    for (const auto& [n, angles] : kViews) out += (out.empty() ? "" : ", ") + std::string(n);
    return out;
}

Image render_mesh(const Mesh& mesh, const std::vector<std::array<unsigned char, 3>>& face_colour,
                  const RenderOptions& options, const std::vector<int>& face_region) {
    check_options(options);
    check_face_data(mesh, face_colour, face_region);
    const std::vector<char> used = used_vertices(mesh);
    Image image = background_image(options);
    if (mesh.faces.empty()) return image;

    const Camera camera = frame_camera(mesh, used, options);
    const ScreenVertices screen = project_vertices(mesh, used, camera);
    const FaceShades shades = shade_faces(mesh, face_colour, camera, options);
    const BandLayout layout = band_layout(options, !face_region.empty());
    const BandBins bins = bin_faces(mesh, screen, camera, layout);
    Band band = make_band(camera, layout);
    for (int b = 0; b < layout.num_bands; ++b) {
        rasterise_band(b, mesh, screen, bins, camera, layout, band);
        resolve_band(b, band, shades, face_region, options, image);
    }
    return image;
}

TriangleFans triangle_fans(const PolygonSoup& soup) {
    TriangleFans fans;
    fans.mesh.positions = soup.positions;
    for_each_fan_triangle(soup, [&](int p, int a, int b, int c) {
        fans.mesh.faces.push_back({a, b, c});
        fans.face_polygon.push_back(p);
    });
    return fans;
}

Image side_by_side(const std::vector<Image>& images) {
    if (images.empty()) throw InvalidInput("side_by_side: no picture to place");
    Image out;
    out.height = images.front().height;
    for (const Image& im : images) {
        if (im.height != out.height)
            throw InvalidInput("side_by_side: pictures of heights " + std::to_string(out.height) +
                               " and " + std::to_string(im.height) +
                               "; give pictures of one height");
        if (im.width < 0 || im.rgb.size() != static_cast<std::size_t>(im.width) * im.height * 3)
            throw InvalidInput("side_by_side: a picture has " + std::to_string(im.rgb.size()) +
                               " bytes for " + std::to_string(im.width) + "x" +
                               std::to_string(im.height) + " pixels");
        out.width += im.width;
    }
    out.rgb.resize(static_cast<std::size_t>(out.width) * out.height * 3);
    for (int y = 0; y < out.height; ++y) {
        unsigned char* dst = out.rgb.data() + static_cast<std::size_t>(y) * out.width * 3;
        for (const Image& im : images) {
            const std::size_t row_bytes = static_cast<std::size_t>(im.width) * 3;
            std::copy_n(im.rgb.data() + y * row_bytes, row_bytes, dst);
            dst += row_bytes;
        }
    }
    return out;
}

// ---- PNG ---------------------------------------------------------------------------------------

namespace {

// What libpng's callbacks share. Trivially destructible: libpng leaves by longjmp.
struct PngSink {
    std::ostream* out;
    char message[256];
};

bool write_bytes(std::ostream& out, const unsigned char* data, std::size_t n) noexcept {
    try {
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n));
        return static_cast<bool>(out);
    } catch (...) {
        return false;
    }
}

void png_sink_write(png_structp png, png_bytep data, std::size_t n) {
    auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
    if (!write_bytes(*sink->out, data, n))
        png_error(png, "the bytes were refused (disk full or file too large?)");
}

void png_sink_flush(png_structp png) {
    auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
    bool ok = true;
    try {
        ok = static_cast<bool>(sink->out->flush());
    } catch (...) {
        ok = false;
    }
    if (!ok) png_error(png, "the output stream cannot be flushed");
}

[[noreturn]] void png_sink_error(png_structp png, png_const_charp message) {
    auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
    std::snprintf(sink->message, sizeof sink->message, "%s", message);
    png_longjmp(png, 1);
}

// libpng warnings concern unusual settings we do not make; a library stays silent.
void png_sink_warning(png_structp, png_const_charp) {}

// Everything libpng may leave by longjmp: only trivially destructible locals from here down.
void encode_png(png_structp png, png_infop info, const Image& image) {
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const std::size_t row_bytes = static_cast<std::size_t>(image.width) * 3;
    for (int y = 0; y < image.height; ++y) png_write_row(png, image.rgb.data() + y * row_bytes);
    png_write_end(png, info);
}

bool encode_png_guarded(png_structp png, png_infop info, const Image& image) {
    if (setjmp(png_jmpbuf(png))) return false;
    encode_png(png, info, image);
    return true;
}

}  // namespace

void write_png(std::ostream& out, const Image& image) {
    if (image.width < 1 || image.height < 1 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
        throw InvalidInput("write_png: a " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " picture with " +
                           std::to_string(image.rgb.size()) +
                           " bytes; a PNG needs positive sides and 3 bytes per pixel");
    PngSink sink{&out, {}};
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_sink_error, png_sink_warning);
    if (png == nullptr)
        throw IoError("cannot write the PNG: libpng could not start (out of memory?)");
    png_infop info = png_create_info_struct(png);
    if (info == nullptr) {
        png_destroy_write_struct(&png, nullptr);
        throw IoError("cannot write the PNG: libpng could not start (out of memory?)");
    }
    png_set_write_fn(png, &sink, png_sink_write, png_sink_flush);
    const bool ok = encode_png_guarded(png, info, image);
    png_destroy_write_struct(&png, &info);
    if (!ok) throw IoError(std::string("cannot write the PNG: ") + sink.message);
}

}  // namespace geotex
