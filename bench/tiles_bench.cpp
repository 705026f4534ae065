// Depth maps and texels of one mesh made whole or tile by tile (geometry/tiles.hpp): the time,
// the peak memory of the process, and a digest of the texels' faces so that runs can be
// compared. Not a test: one line per run; run each tile count in its own process, since the
// peak is the process's.
//
//   geotex_tiles_bench MESH [--scale 0.04] [--tiles N] [--negative] [--segment]
//
// N = 0: the whole mesh at once; --negative: engraved details instead of raised ones;
// --segment: the whole segmentation (run_segmentation or run_tiled_segmentation, rims removed,
// textures) instead of the depth map and texels only, and the digest is of the face textures.

#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/smoothed_surface.hpp"
#include "geometry/texels.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "geometry/topology.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;
}

// FNV-1a over the face labelling: equal labellings give equal digests.
std::uint64_t digest(const std::vector<int>& labels) {
    std::uint64_t h = 1469598103934665603ull;
    for (int x : labels) {
        h ^= static_cast<std::uint32_t>(x);
        h *= 1099511628211ull;
    }
    return h;
}

}  // namespace

int main(int argc, char** argv) {
    std::string path;
    double scale = 0.04;
    int tiles = 0;
    geotex::DetailOrientation orientation = geotex::DetailOrientation::Positive;
    bool segment = false;
    bool usage_error = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--scale" && i + 1 < argc)
            scale = std::atof(argv[++i]);
        else if (a == "--tiles" && i + 1 < argc)
            tiles = std::atoi(argv[++i]);
        else if (a == "--segment")
            segment = true;
        else if (a == "--negative")
            orientation = geotex::DetailOrientation::Negative;
        else if (path.empty() && a[0] != '-')
            path = a;
        else
            usage_error = true;
    }
    if (usage_error || path.empty()) {
        std::fprintf(
            stderr,
            "usage: geotex_tiles_bench MESH [--scale S] [--tiles N] [--negative] [--segment]\n");
        return 2;
    }
    const geotex::Mesh mesh = geotex::repair_soup(geotex::read_mesh_file(path).soup).mesh;
    const double before_mb = peak_rss_mb();
    Eigen::Vector3d lo = mesh.positions.front(), hi = lo;
    for (const auto& p : mesh.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    geotex::SmoothingParams sp;
    sp.radius = scale * (hi - lo).maxCoeff();
    geotex::TexelParams tp;
    tp.radius = sp.radius;
    const std::vector<geotex::DetailOrientation> which = {orientation};

    const auto start = Clock::now();
    geotex::TexelSet texels;
    std::vector<int> labels;
    int textures = 0;
    if (segment) {
        geotex::SegmentationParams p;
        p.radius_rel = scale;
        p.orientation = orientation == geotex::DetailOrientation::Positive
                            ? geotex::OrientationMode::Positive
                            : geotex::OrientationMode::Negative;
        geotex::Segmentation seg = tiles == 0 ? geotex::run_segmentation(mesh, p)
                                              : geotex::run_tiled_segmentation(mesh, p, tiles);
        texels.texels = std::move(seg.texels);
        labels = std::move(seg.face_texture);
        textures = seg.num_textures;
    } else if (tiles == 0) {
        const geotex::MeshTopology topology = geotex::make_topology(mesh);
        const geotex::MeshMetrics metrics = geotex::make_mesh_metrics(mesh, topology);
        const geotex::SmoothedSurface smoothed =
            geotex::make_smoothed_surface(mesh, topology, metrics, sp);
        const geotex::DepthMap depth =
            geotex::make_depth_map(mesh, metrics.vertex_normal, smoothed, orientation);
        texels = geotex::make_texels(mesh, topology, depth, tp);
        labels = texels.face_texel;
    } else {
        const auto depth = geotex::make_tiled_depth_maps(mesh, sp, which, tiles);
        texels = std::move(geotex::make_tiled_texels(mesh, depth, tp, tiles).front());
        labels = texels.face_texel;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("| %s | %d | %d | %.2f s | %.0f MB | %.0f MB | %zu | %d | %016llx |\n",
                path.c_str(), mesh.num_faces(), tiles, seconds, before_mb, peak_rss_mb(),
                texels.texels.size(), textures, static_cast<unsigned long long>(digest(labels)));
    return 0;
}
