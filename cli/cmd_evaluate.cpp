// geotex evaluate: segmentation scores against a ground truth (paper §4.1.1).

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/output.hpp"
#include "cli/report.hpp"
#include "geometry/evaluation.hpp"
#include "geometry/mesh_io.hpp"

namespace geotex::cli {

namespace {

struct EvaluateOptions {
    CommonOptions common;
    std::string segmentation;
    std::string truth;
    std::string json;
};

// The integer face property `name` of a segmentation PLY.
std::vector<int> face_ints(const MeshFile& file, const std::string& name, const std::string& path) {
    for (const auto& p : file.face_properties)
        if (p.name == name) {
            std::vector<int> out(p.values.size());
            for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<int>(p.values[i]);
            return out;
        }
    throw CliError(kExitInput,
                   path + ": no face property '" + name + "' (not a geotex segmentation PLY)");
}

int run_evaluate(const EvaluateOptions& o) {
    check_output_paths({{"--json", o.json}},
                       {{"SEGMENTATION", o.segmentation}, {"GROUND_TRUTH", o.truth}});
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    const MeshFile file = timed_stage(progress, "reading", [&] {
        return in_phase(kExitInput, o.segmentation, [&] { return read_mesh_file(o.segmentation); });
    });
    // The faces must keep their indices: build the mesh without repair.
    Mesh mesh;
    mesh.positions = file.soup.positions;
    for (int p = 0; p < file.soup.num_polygons(); ++p) {
        const int begin = file.soup.face_offsets[p], end = file.soup.face_offsets[p + 1];
        if (end - begin != 3)
            throw CliError(kExitInput, o.segmentation + ": polygon " + std::to_string(p) +
                                           " is not a triangle (not a geotex segmentation)");
        mesh.faces.push_back({file.soup.face_indices[begin], file.soup.face_indices[begin + 1],
                              file.soup.face_indices[begin + 2]});
    }
    const std::vector<int> texel = face_ints(file, "texel", o.segmentation);
    const std::vector<int> texture = face_ints(file, "texture", o.segmentation);
    const GroundTruth truth =
        in_phase(kExitInput, o.truth, [&] { return read_ground_truth(o.truth); });
    if (truth.face_shape.size() != texel.size())
        throw CliError(kExitInput, o.truth + ": the ground truth has " +
                                       std::to_string(truth.face_shape.size()) + " faces but " +
                                       o.segmentation + " has " + std::to_string(texel.size()));
    const SegmentationScore s = timed_stage(progress, "evaluation", [&] {
        return in_phase(kExitInput, o.truth,
                        [&] { return evaluate_segmentation(mesh, texel, texture, truth); });
    });
    if (!o.json.empty()) {
        OutputSet outputs;
        outputs.add(o.json, [&](std::ostream& out) { write_json(out, score_json(s)); });
        outputs.commit();
    }
    std::printf("shapes %d, texels %d: matched %d, missed %d, split %d, spurious %d\n",
                s.num_shapes, s.num_texels, s.num_matched, s.num_missed, s.num_split,
                s.num_spurious);
    std::printf(
        "Hausdorff distance %.6g (matched texels only %.6g), delta_t %.6g, Hausdorff / delta_t "
        "%.3g\n",
        s.hausdorff, s.hausdorff_matched, s.delta_t, s.delta_t > 0 ? s.hausdorff / s.delta_t : NAN);
    std::printf("adjusted Rand index of textures vs shape kinds %.4f, vs families %.4f\n",
                s.ari_kind, s.ari_family);
    return 0;
}

}  // namespace

Runner add_evaluate(CLI::App& sub) {
    auto o = std::make_shared<EvaluateOptions>();
    sub.description(
        "Score a segmentation PLY (from 'geotex segment') against a ground truth JSON (from "
        "'geotex synth'):\n"
        "the paper's surfacic Hausdorff distance between the foregrounds (section 4.1.1) and "
        "delta_t, the mean\n"
        "distance between barycentres of adjacent faces, both divided by the largest bounding-box "
        "side; the\n"
        "texels matched to shapes, missed, split or spurious; and the adjusted Rand index of the "
        "textures\n"
        "against the shape kinds and families.");
    sub.add_option("segmentation", o->segmentation,
                   "Segmentation PLY with face properties texel and texture")
        ->required();
    sub.add_option("ground_truth", o->truth, "Ground truth JSON")->required();
    sub.add_option("--json", o->json, "Also write the scores as JSON");
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_evaluate(*o); };
}

}  // namespace geotex::cli
