// geotex segment: texels and textures of one mesh (paper §3).

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/mesh_input.hpp"
#include "cli/output.hpp"
#include "cli/report.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/segmentation.hpp"

namespace geotex::cli {

namespace {

struct SegmentOptions {
    CommonOptions common;
    SegmentationParams params;
    std::string mesh;
    std::string output;
    std::string json;
    double scale = 0;
    double radius = 0;
    bool ascii = false;
    bool vertex_mean = false;
};

const std::map<std::string, OrientationMode> kOrientations = {
    {"positive", OrientationMode::Positive}, {"negative", OrientationMode::Negative}, {"both", OrientationMode::Both}};
const std::map<std::string, SmoothingMethod> kSmoothings = {{"twicing", SmoothingMethod::Twicing},
                                                            {"mean", SmoothingMethod::Mean}};

int run_segment(SegmentOptions& o) {
    if ((o.scale != 0) == (o.radius != 0))
        throw CliError(kExitUsage, "segment: give exactly one of --scale (fraction of the largest bounding-box side) or --radius (mesh units)");
    if (o.scale != 0 && !(o.scale > 0 && o.scale < 1))
        throw CliError(kExitUsage, "segment: --scale must be in (0, 1), a fraction of the largest bounding-box side (got " +
                                       std::to_string(o.scale) + ")");
    if (o.radius != 0 && !(o.radius > 0))
        throw CliError(kExitUsage, "segment: --radius must be positive (got " + std::to_string(o.radius) + ")");
    o.params.radius_rel = o.scale != 0 ? o.scale : o.params.radius_rel;
    o.params.radius = o.radius;
    o.params.area_weighted = !o.vertex_mean;

    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    const InputMesh in = load_mesh(o.mesh, progress);
    const Mesh& mesh = in.repaired.mesh;
    const Segmentation seg = in_phase(kExitProcessing, o.mesh, [&] {
        return run_segmentation(mesh, o.params, [&](const StageEvent& e) { progress(e); });
    });
    for (const auto& d : seg.diagnostics) progress.note(o.mesh + ": " + d.stage + ": " + d.message);
    if (seg.texels.empty())
        warn(o.mesh + ": no salient detail at radius " + std::to_string(seg.radius) +
             " (mesh units); the outputs list zero texels. Try another --scale or --orientation.");

    OutputSet outputs;
    timed_stage(progress, "writing", [&] {
        std::vector<FaceAttribute> attributes(5);
        attributes[0] = {"texel", PlyScalarType::Int32, seg.face_texel};
        attributes[1] = {"texture", PlyScalarType::Int32, seg.face_texture};
        for (int c = 0; c < 3; ++c) {
            attributes[2 + c].name = c == 0 ? "red" : (c == 1 ? "green" : "blue");
            attributes[2 + c].type = PlyScalarType::UInt8;
            attributes[2 + c].values.resize(seg.face_texture.size());
        }
        for (std::size_t f = 0; f < seg.face_texture.size(); ++f) {
            const auto rgb = texture_colour(seg.face_texture[f]);
            for (int c = 0; c < 3; ++c) attributes[2 + c].values[f] = rgb[c];
        }
        PlyWriteOptions w;
        w.binary = !o.ascii;
        w.comments = {"geotex segmentation of " + o.mesh, "face texel: texel id, -1 = background",
                      "face texture: texture id, -1 = background; red green blue: texture colour"};
        outputs.add(o.output, [&](std::ostream& out) { write_ply(out, mesh, attributes, w); });
        if (!o.json.empty()) {
            const Json input = input_json(o.mesh, in.format, in.repaired.report);
            outputs.add(o.json, [&](std::ostream& out) { write_json(out, segmentation_json(input, o.params, seg)); });
        }
        outputs.commit();
    });

    std::printf("%s: %d texels in %d textures (radius %.6g mesh units, %s details)\n", o.mesh.c_str(),
                static_cast<int>(seg.texels.size()), seg.num_textures, seg.radius, orientation_name(o.params.orientation));
    for (int k = 0; k < seg.num_textures; ++k) {
        int count = 0;
        long faces = 0;
        for (std::size_t i = 0; i < seg.texels.size(); ++i)
            if (seg.texel_texture[i] == k) {
                ++count;
                faces += static_cast<long>(seg.texels[i].faces.size());
            }
        std::printf("  texture %d (%s, %s): %d texels, %ld faces\n", k, orientation_name(seg.texture_orientation[k]),
                    hex_colour(texture_colour(k)).c_str(), count, faces);
    }
    return 0;
}

}  // namespace

Runner add_segment(CLI::App& sub) {
    auto o = std::make_shared<SegmentOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Find the salient details (3D texels) of MESH at the scale r and group them into geometric textures\n"
        "(paper section 3): oriented depth map over geodesic discs of radius r, seeds at local maxima, local\n"
        "Otsu regions, 18 features per texel, self-tuning spectral clustering. Writes the mesh as PLY with\n"
        "per-face int 'texel' and 'texture' (-1 = background) and uchar red/green/blue (one colour per\n"
        "texture, grey background), which MeshLab shows directly; --json adds a full report.");
    sub.add_option("mesh", o->mesh, "Input mesh: .ply (ASCII or binary), .off, .obj or .stl")->required();
    sub.add_option("-o,--output", o->output, "Segmentation PLY to write")->required();
    sub.add_option("-s,--scale", o->scale, "Scale r as a fraction of the largest bounding-box side, in (0, 1); paper: 0.04");
    sub.add_option("-r,--radius", o->radius, "Scale r in mesh units (instead of --scale)");
    sub.add_option("--orientation", o->params.orientation,
                   "Details above the surface (positive), below it (negative: engravings), or both")
        ->transform(CLI::CheckedTransformer(kOrientations, CLI::ignore_case))
        ->default_str("positive");
    sub.add_option("--json", o->json, "Also write a JSON report: per texel its faces, 18 features and texture");
    sub.add_option("--smoothing", o->params.smoothing,
                   "twicing: bias-corrected disc mean (a sphere has zero depth); mean: the paper's eq. 1")
        ->transform(CLI::CheckedTransformer(kSmoothings, CLI::ignore_case))
        ->default_str("twicing");
    sub.add_flag("--vertex-mean", o->vertex_mean, "Plain vertex mean in the discs (paper eq. 1) instead of area weights");
    sub.add_option("--merge-overlap", o->params.merge_overlap,
                   "Merge touching regions whose depth intervals mu +- sigma overlap by this fraction of the narrower")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_option("--min-depth", o->params.min_depth_rel, "Depth below this fraction of r is never salient")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_option("--min-faces", o->params.min_faces, "Drop texels with fewer faces")->check(CLI::Range(1, 1000000));
    sub.add_option("--max-textures", o->params.clustering.max_clusters, "Largest number of textures tried")
        ->check(CLI::Range(1, 100));
    sub.add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
    add_common_options(sub, o->common);
    return [o] { return run_segment(*o); };
}

}  // namespace geotex::cli
