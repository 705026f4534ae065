#pragma once
// JSON documents of the command line alone: the synthetic ground truth and the evaluation
// scores (the segmentation and annotation reports are the library's, pipeline/report_json.hpp).
// Key order is fixed and numbers use the shortest exact form, so the same run gives
// byte-identical files.

#include <nlohmann/json.hpp>
#include <string>

#include "geometry/evaluation.hpp"
#include "geometry/synth.hpp"

namespace geotex::cli {

using Json = nlohmann::ordered_json;

/// Ground truth of a synthetic mesh (per face shape id or -1, per shape its kind).
Json ground_truth_json(const std::string& mesh_file, const SynthParams& params,
                       const SyntheticMesh& synth);

/// Reads a ground truth written by ground_truth_json. Throws ParseError naming `file`.
GroundTruth read_ground_truth(const std::string& file,
                              std::vector<std::string>* kind_names = nullptr);

/// The evaluation scores.
Json score_json(const SegmentationScore& score);

/// Writes `json` with two-space indentation and a final newline.
void write_json(std::ostream& out, const Json& json);

}  // namespace geotex::cli
