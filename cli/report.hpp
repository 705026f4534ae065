#pragma once
// JSON documents of the command line: the segmentation report and the synthetic ground
// truth. Key order is fixed and numbers use the shortest exact form, so the same run gives
// byte-identical files.

#include <nlohmann/json.hpp>
#include <string>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "geometry/evaluation.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"
#include "pipeline/parameters_json.hpp"

namespace geotex::cli {

using Json = nlohmann::ordered_json;

/// Input description: file name, format, counts and what repair did.
Json input_json(const std::string& file, const std::string& format, const MeshRepairReport& report);

/// The segmentation report: parameters, per texel its faces, 18 features and texture, per
/// texture its texels, and the diagnostics.
Json segmentation_json(const Json& input, const SegmentationParams& params, const Segmentation& seg);

/// The annotation of every texture: dictionary (id, version, digest), and per texture every
/// feature's value, significance and rank, the concept holding it, and the chosen ones.
Json annotation_json(const Dictionary& dictionary, const std::vector<TextureDescription>& descriptions,
                     const DescriptionParams& params, const std::string& lang);

/// Ground truth of a synthetic mesh (per face shape id or -1, per shape its kind).
Json ground_truth_json(const std::string& mesh_file, const SynthParams& params, const SyntheticMesh& synth);

/// Reads a ground truth written by ground_truth_json. Throws ParseError naming `file`.
GroundTruth read_ground_truth(const std::string& file, std::vector<std::string>* kind_names = nullptr);

/// The evaluation scores.
Json score_json(const SegmentationScore& score);

/// Writes `json` with two-space indentation and a final newline.
void write_json(std::ostream& out, const Json& json);

}  // namespace geotex::cli
