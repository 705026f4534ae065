// geotex synth: the synthetic benchmark of paper §4.1.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "cli/report.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/synth.hpp"

namespace geotex::cli {

namespace {

struct SynthOptions {
    CommonOptions common;
    SynthParams params;
    std::string output;
    std::string truth;
    bool ascii = false;
    bool soup = false;
};

// The mesh with each face given three vertices of its own, in the order of its corners: the
// unindexed triangles some exporters write (an STL's layout in a PLY), which the repair merges
// back into the mesh, and the merge's worst case, every vertex repeated (bench/RESULTS.md).
Mesh unindexed(const Mesh& mesh) {
    Mesh soup;
    soup.positions.reserve(3 * mesh.faces.size());
    soup.faces.reserve(mesh.faces.size());
    for (const auto& fv : mesh.faces) {
        const int first = static_cast<int>(soup.positions.size());
        for (int v : fv) soup.positions.push_back(mesh.positions[static_cast<std::size_t>(v)]);
        soup.faces.push_back({first, first + 1, first + 2});
    }
    return soup;
}

std::string default_truth_path(const std::string& mesh_path) {
    const auto dot = mesh_path.find_last_of('.');
    const auto slash = mesh_path.find_last_of('/');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (has_ext ? mesh_path.substr(0, dot) : mesh_path) + ".truth.json";
}

int run_synth(const SynthOptions& o) {
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    const std::string truth = o.truth.empty() ? default_truth_path(o.output) : o.truth;
    check_output_paths({{"--output", o.output, true}, {"--truth", truth}});
    SyntheticMesh synth = timed_stage(progress, "synthesis", [&] {
        return in_phase(kExitUsage, "synth", [&] { return make_synthetic_sphere(o.params); });
    });
    const int num_vertices = synth.mesh.num_vertices();
    if (o.soup) synth.mesh = unindexed(synth.mesh);
    OutputSet outputs;
    timed_stage(progress, "writing", [&] {
        PlyWriteOptions w;
        w.binary = !o.ascii;
        w.comments = {"geotex synthetic sphere: level " + std::to_string(o.params.level) + ", " +
                      std::to_string(synth.shapes.size()) + " shapes, noise " +
                      std::to_string(o.params.noise_percent) + "% of the radius" +
                      (o.soup ? ", each face with vertices of its own" : "")};
        outputs.add(o.output, [&](std::ostream& out) { write_ply(out, synth.mesh, {}, w); });
        const auto slash = o.output.find_last_of('/');
        const std::string mesh_name =
            slash == std::string::npos ? o.output : o.output.substr(slash + 1);
        outputs.add(truth, [&](std::ostream& out) {
            write_json(out, ground_truth_json(mesh_name, o.params, synth));
        });
        outputs.commit();
    });
    int fg = 0;
    for (int s : synth.face_shape) fg += s >= 0 ? 1 : 0;
    const std::string written =
        o.soup ? " written as " + std::to_string(synth.mesh.num_vertices()) : "";
    std::printf(
        "synthetic sphere: %d vertices%s, %d faces, %zu shapes (%d big discs, %d small discs, %d "
        "squares, "
        "%d rectangles), %d foreground faces\n",
        num_vertices, written.c_str(), synth.mesh.num_faces(), synth.shapes.size(),
        o.params.num_big_discs, o.params.num_small_discs, o.params.num_squares,
        o.params.num_rectangles, fg);
    std::printf("wrote %s and %s\n", o.output.c_str(), truth.c_str());
    return 0;
}

}  // namespace

Runner add_synth(CLI::App& sub) {
    auto o = std::make_shared<SynthOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Generate the synthetic benchmark of the paper (section 4.1): an icosphere displaced "
        "outward by\n"
        "a map of shapes (big discs, small discs, squares, rectangles; 'sphere-1' by default: 18 "
        "rectangles,\n"
        "16 squares, 17 big discs, 37 small discs, typical diameter 5% of the bounding box, "
        "displacement\n"
        "2% of the radius, soft edges). Writes the mesh (PLY) and its ground truth (JSON: per face "
        "the\n"
        "shape id or -1, per shape its kind), which 'geotex evaluate' reads.");
    sub.add_option("-o,--output", o->output, "Mesh to write (.ply)")->required();
    sub.add_option("--truth", o->truth,
                   "Ground truth to write (default: <output without .ply>.truth.json)");
    sub.add_option("--level", o->params.level,
                   "Icosphere subdivision level: 20*4^level faces (7: 327,680; 11: 83,886,080, "
                   "2 GB of PLY)")
        ->check(CLI::Range(0, 11));
    sub.add_option("--noise", o->params.noise_percent,
                   "Uniform radial noise intensity I, percent of the radius (paper: 0.05 to 0.3)")
        ->check(CLI::Range(0.0, 50.0));
    sub.add_option("--noise-seed", o->params.noise_seed, "Seed of the noise draw");
    sub.add_option("--layout-seed", o->params.layout_seed, "Seed of the shape placement");
    sub.add_option("--big-discs", o->params.num_big_discs, "Number of big discs")
        ->check(CLI::Range(0, 10000));
    sub.add_option("--small-discs", o->params.num_small_discs, "Number of small discs")
        ->check(CLI::Range(0, 10000));
    sub.add_option("--squares", o->params.num_squares, "Number of squares")
        ->check(CLI::Range(0, 10000));
    sub.add_option("--rectangles", o->params.num_rectangles, "Number of rectangles")
        ->check(CLI::Range(0, 10000));
    sub.add_option("--displacement", o->params.displacement_rel,
                   "Largest displacement, fraction of the radius")
        ->check(CLI::Range(0.0, 0.5));
    sub.add_option("--engraved", o->params.engraved_fraction,
                   "Fraction of the shapes engraved (displaced inward)")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
    sub.add_flag("--soup", o->soup,
                 "Write each face with three vertices of its own (unindexed triangles, as an "
                 "STL holds them),\n"
                 "which the repair merges back: the same faces and ground truth, 3 vertices a "
                 "face");
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_synth(*o); };
}

}  // namespace geotex::cli
