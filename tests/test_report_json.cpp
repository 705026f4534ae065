// annotation_report and segmentation_report: the JSON report of the command, from the
// library, against what is known apart from it (the result it describes, the repair of a soup
// built here, the dictionary's bytes) and against its own text read back.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/synth.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/report_json.hpp"
#include "tests/dictionary_fixtures.hpp"

using namespace geotex;
using Json = nlohmann::ordered_json;

namespace {

struct Case {
    MeshRepairResult repaired;
    Annotation annotation;
    std::string dictionary_text;
};

/// A synthetic sphere with one face given twice: its repair has one duplicate to remove.
const Case& annotated_sphere() {
    static const Case c = [] {
        SynthParams p;
        p.level = 4;
        p.engraved_fraction = 0.5;
        const Mesh mesh = make_synthetic_sphere(p).mesh;
        PolygonSoup soup;
        soup.positions = mesh.positions;
        for (const auto& f : mesh.faces) {
            soup.face_indices.insert(soup.face_indices.end(), f.begin(), f.end());
            soup.face_offsets.push_back(static_cast<int>(soup.face_indices.size()));
        }
        soup.face_indices.insert(soup.face_indices.end(), mesh.faces[0].begin(),
                                 mesh.faces[0].end());
        soup.face_offsets.push_back(static_cast<int>(soup.face_indices.size()));
        Case out;
        out.repaired = repair_soup(soup);
        out.dictionary_text = test::read_source_file("dictionaries/default.yaml");
        const Dictionary dictionary = parse_dictionary(out.dictionary_text, "default.yaml");
        AnnotateOptions o;
        o.segmentation.radius_rel = 0.05;
        o.segmentation.orientation = OrientationMode::Both;
        o.description.num_resamples = 40;
        o.label_language = "fr";
        out.annotation = annotate(out.repaired.mesh,
                                  {"sphere.ply", "ply-ascii", std::string(64, 'a')}, dictionary, o);
        return out;
    }();
    return c;
}

ReportInput input_of(const Case& c) { return {"data/sphere.ply", "ply-ascii", c.repaired.report}; }

}  // namespace

TEST_CASE("number_or_null: finite numbers as they are, NaN and infinities as null",
          "[pipeline][report]") {
    CHECK(number_or_null(0.1).dump() == "0.1");
    CHECK(number_or_null(-3.0).get<double>() == -3.0);
    CHECK(number_or_null(std::numeric_limits<double>::quiet_NaN()).is_null());
    CHECK(number_or_null(std::numeric_limits<double>::infinity()).is_null());
    CHECK(number_or_null(-std::numeric_limits<double>::infinity()).is_null());
}

TEST_CASE("annotation_report: input, mesh and parameters of the run", "[pipeline][report]") {
    const Case& c = annotated_sphere();
    const Segmentation& seg = c.annotation.segmentation;
    const Json r = annotation_report(c.annotation, input_of(c));
    CHECK(r["geotex"] == Json{{"version", version()}, {"document", "segmentation"}, {"schema", 1}});
    const Json& in = r["input"];
    CHECK(in["file"] == "data/sphere.ply");
    CHECK(in["format"] == "ply-ascii");
    CHECK(in["input_polygons"] == c.annotation.num_faces + 1);  // the face given twice
    CHECK(in["input_vertices"] == c.annotation.num_vertices);
    CHECK(in["repair"]["duplicate_faces_removed"] == 1);
    CHECK(in["repair"]["polygons_triangulated"] == 0);
    CHECK(r["mesh"]["vertices"] == c.annotation.num_vertices);
    CHECK(r["mesh"]["faces"] == c.annotation.num_faces);
    CHECK(r["mesh"]["unit_scale"].get<double>() ==
          Approx(1.0 / r["mesh"]["largest_side"].get<double>()));
    CHECK(r["parameters"]["scale"] == 0.05);
    CHECK(r["parameters"]["radius"] == seg.radius);
    CHECK(r["parameters"]["orientation"] == "both");
    REQUIRE(r["depth"].size() == 2);
    CHECK(r["depth"][0]["orientation"] == "positive");
    CHECK(r["depth"][1]["orientation"] == "negative");
}

TEST_CASE("annotation_report: texels and textures are the segmentation's", "[pipeline][report]") {
    const Case& c = annotated_sphere();
    const Segmentation& seg = c.annotation.segmentation;
    const Json r = annotation_report(c.annotation, input_of(c));
    REQUIRE(!seg.texels.empty());
    REQUIRE(r["texels"].size() == seg.texels.size());
    // Every face of a texel in the report carries that texel and its texture in the per-face
    // labels, and the faces of all texels are exactly the labelled faces.
    std::set<int> reported;
    for (const auto& t : r["texels"]) {
        const int id = t["id"].get<int>();
        CHECK(t["face_count"] == t["faces"].size());
        for (const auto& f : t["faces"]) {
            const int face = f.get<int>();
            reported.insert(face);
            CHECK(seg.face_texel[static_cast<std::size_t>(face)] == id);
            CHECK(seg.face_texture[static_cast<std::size_t>(face)] == t["texture"].get<int>());
        }
        REQUIRE(t["features"].size() == static_cast<std::size_t>(kNumFeatures));
        for (int k = 0; k < kNumFeatures; ++k) {
            const double x = seg.features.values(id, k);
            const Json& v = t["features"][kFeatureIds[k]];
            if (std::isfinite(x))
                CHECK(v.get<double>() == x);
            else
                CHECK(v.is_null());
        }
    }
    std::set<int> labelled;
    for (std::size_t f = 0; f < seg.face_texel.size(); ++f)
        if (seg.face_texel[f] >= 0) labelled.insert(static_cast<int>(f));
    CHECK(reported == labelled);

    REQUIRE(r["textures"].size() == static_cast<std::size_t>(seg.num_textures));
    std::size_t members = 0;
    for (const auto& t : r["textures"]) {
        CHECK(t["texel_count"] == t["texels"].size());
        members += t["texels"].size();
        for (const auto& i : t["texels"])
            CHECK(r["texels"][i.get<std::size_t>()]["texture"] == t["id"]);
    }
    CHECK(members == seg.texels.size());
    CHECK(r["textures"][0]["colour"] == "#1f77b4");  // the first texture is blue (31, 119, 180)
}

TEST_CASE("annotation_report: the words, their dictionary and choice", "[pipeline][report]") {
    const Case& c = annotated_sphere();
    const Json r = annotation_report(c.annotation, input_of(c));
    const Json& a = r["annotation"];
    CHECK(a["dictionary"]["sha256"] == sha256_hex(c.dictionary_text));
    CHECK(a["dictionary"]["source"] == "default.yaml");
    CHECK(a["choice"]["resamples"] == 40);
    REQUIRE(a["textures"].size() == c.annotation.descriptions.size());
    for (std::size_t t = 0; t < c.annotation.descriptions.size(); ++t) {
        const TextureDescription& d = c.annotation.descriptions[t];
        const Json& e = a["textures"][t];
        CHECK(e["texture"] == d.texture);
        CHECK(e["texels"] == d.num_texels);
        REQUIRE(e["concepts"].size() == d.chosen.size());
        for (std::size_t i = 0; i < d.chosen.size(); ++i) {
            const FeatureScore& f = d.features[static_cast<std::size_t>(d.chosen[i])];
            CHECK(e["concepts"][i]["concept"] == f.concept_ptr->id);
            CHECK(e["concepts"][i]["feature"] == kFeatureIds[f.feature]);
        }
        CHECK(e["features"].size() == d.features.size());
    }
}

TEST_CASE("segmentation_report: the annotation report without its words", "[pipeline][report]") {
    const Case& c = annotated_sphere();
    Json whole = annotation_report(c.annotation, input_of(c));
    whole.erase("annotation");
    CHECK(segmentation_report(c.annotation.segmentation, c.annotation.options.segmentation,
                              input_of(c)) == whole);
}

TEST_CASE("report_text: two-space indentation, a final newline, read back unchanged",
          "[pipeline][report]") {
    const Case& c = annotated_sphere();
    const Json r = annotation_report(c.annotation, input_of(c));
    const std::string text = report_text(r);
    REQUIRE(text.size() > 2);
    CHECK(text.substr(0, 13) == "{\n  \"geotex\":");
    CHECK(text.back() == '\n');
    CHECK(text[text.size() - 2] == '}');
    CHECK(Json::parse(text) == r);
    CHECK(report_text(annotation_report(c.annotation, input_of(c))) == text);  // deterministic
}

TEST_CASE("annotation_report and segmentation_report refuse results that are not whole",
          "[pipeline][report]") {
    const Case& c = annotated_sphere();
    Annotation no_dictionary = c.annotation;
    no_dictionary.dictionary.reset();
    CHECK_THROWS_AS(annotation_report(no_dictionary, input_of(c)), InvalidInput);
    Segmentation cut = c.annotation.segmentation;
    cut.texel_texture.pop_back();
    CHECK_THROWS_WITH(segmentation_report(cut, c.annotation.options.segmentation, input_of(c)),
                      Catch::StartsWith("segmentation_report: "));
    Segmentation no_depth = c.annotation.segmentation;
    no_depth.negative_depth.reset();
    CHECK_THROWS_AS(segmentation_report(no_depth, c.annotation.options.segmentation, input_of(c)),
                    InvalidInput);
}
