// Stage timings and peak memory of the pipeline on synthetic spheres, beside the stock
// CGAL path the paper's implementation would take (read_polygon_mesh, AABB tree, closest
// point of every vertex on one thread). Not a test: prints a Markdown table.
//
//   geotex_bench [--levels 5,6,7,8] [--scale 0.04] [--threads N] [--stock] [--dir DIR]

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;
}

// The stock path: CGAL reads the PLY into a Surface_mesh, builds an AABB tree over its
// faces and queries the closest point of every vertex, single-threaded.
double stock_cgal_seconds(const std::string& path) {
    using K = CGAL::Simple_cartesian<double>;
    using SM = CGAL::Surface_mesh<K::Point_3>;
    using Primitive = CGAL::AABB_face_graph_triangle_primitive<SM>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
    const auto t0 = Clock::now();
    SM sm;
    if (!CGAL::IO::read_polygon_mesh(path, sm)) return -1;
    Tree tree(faces(sm).first, faces(sm).second, sm);
    tree.accelerate_distance_queries();
    double sum = 0;
    for (auto v : vertices(sm))
        sum += CGAL::squared_distance(tree.closest_point(sm.point(v)), sm.point(v));
    if (sum < 0) std::puts("");  // keep the loop
    return since(t0);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> levels = {5, 6, 7, 8};
    double scale = 0.04;
    int threads = 0;
    bool stock = false;
    std::string dir = "/tmp";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
        if (a == "--levels") {
            levels.clear();
            std::stringstream ss(next());
            for (std::string x; std::getline(ss, x, ',');) levels.push_back(std::stoi(x));
        } else if (a == "--scale")
            scale = std::stod(next());
        else if (a == "--threads")
            threads = std::stoi(next());
        else if (a == "--stock")
            stock = true;
        else if (a == "--dir")
            dir = next();
        else {
            std::fprintf(stderr,
                         "usage: geotex_bench [--levels 5,6,7] [--scale 0.04] [--threads N] "
                         "[--stock] [--dir DIR]\n");
            return 1;
        }
    }
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      threads);

    std::printf(
        "| level | faces | scale | read | repair | topology | smoothing | depth | texels | "
        "curvature | features | clustering | total | texels | textures | peak RSS MB |%s\n",
        stock ? " stock CGAL read+AABB+queries |" : "");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|%s\n",
                stock ? "---|" : "");
    for (int level : levels) {
        geotex::SynthParams sp;
        sp.level = level;
        const auto synth = geotex::make_synthetic_sphere(sp);
        const std::string path = dir + "/geotex-bench-level" + std::to_string(level) + ".ply";
        {
            std::ofstream out(path, std::ios::binary);
            geotex::write_ply(out, synth.mesh, {});
        }
        const auto t_read = Clock::now();
        auto file = geotex::read_mesh_file(path);
        const double read_s = since(t_read);
        const auto t_repair = Clock::now();
        const auto repaired = geotex::repair_soup(std::move(file.soup));  // as the command does
        const double repair_s = since(t_repair);
        std::vector<std::pair<std::string, double>> stages;
        geotex::SegmentationParams p;
        p.radius_rel = scale;
        const auto seg =
            geotex::run_segmentation(repaired.mesh, p, [&](const geotex::StageEvent& e) {
                if (e.seconds >= 0) stages.emplace_back(e.stage, e.seconds);
            });
        auto stage = [&](const std::string& prefix) {
            double s = 0;
            for (const auto& [name, t] : stages)
                if (name.rfind(prefix, 0) == 0) s += t;
            return s;
        };
        double total = read_s + repair_s;
        for (const auto& st : stages) total += st.second;
        std::printf(
            "| %d | %d | %.3g | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | "
            "%.3f | %zu | %d | %.0f |",
            level, synth.mesh.num_faces(), scale, read_s, repair_s, stage("topology"),
            stage("smoothing"), stage("depth map"), stage("texels"), stage("curvature"),
            stage("features"), stage("clustering"), total, seg.texels.size(), seg.num_textures,
            peak_rss_mb());
        if (stock) std::printf(" %.3f |", stock_cgal_seconds(path));
        std::printf("\n");
        std::fflush(stdout);
        std::remove(path.c_str());
    }
    return 0;
}
