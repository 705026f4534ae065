// The API's JSON (view/README.md, HTTP API) from a hand-made report: the textures' colours,
// orientation and words with their bounds, each texel's interval, the feature lists.

#include <catch2/catch.hpp>

#include "annotation/dictionary.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "view/api_json.hpp"
#include "view/assets.hpp"

using namespace geotex;
using Json = nlohmann::json;

namespace {

// Two concepts of depth_mean that share the bound 0.02.
const char* kDictionary = R"(scheme:
  id: test
  version: "1.0"
  namespace: "https://example.org/test/"
  languages: [en]
  title: {en: test}
facets:
  relief:
    labels: {en: relief}
    features: [depth_mean]
features:
  depth_mean:
    - id: shallow
      interval: [0, 0.02]
      labels: {en: shallow}
    - id: deep
      interval: [0.02, .inf]
      labels: {en: deep}
)";

LoadedObject object() {
    LoadedObject o;
    o.id = "obj-1";
    o.status = "ok";
    o.texels = 2;
    o.textures = 2;
    o.reannotate = true;
    o.report = Json::parse(R"({
      "mesh": {"vertices": 10, "faces": 16},
      "texels": [
        {"id": 0, "texture": 0, "features": {"depth_mean": 0.01, "area": null}},
        {"id": 1, "texture": 1, "features": {"depth_mean": 0.05, "area": 2.5}}],
      "textures": [
        {"id": 0, "orientation": "positive", "colour": "#112233", "texel_count": 1},
        {"id": 1, "orientation": "negative", "colour": "#445566", "texel_count": 1}],
      "annotation": {"textures": [
        {"texture": 0, "concepts": [{"feature": "depth_mean", "concept": "shallow", "label": "x"}],
         "withheld": [], "features": [{"feature": "depth_mean", "value": 0.01, "significance": 0.5}]},
        {"texture": 1, "concepts": [], "withheld": [{"feature": "depth_mean", "concept": "deep"}],
         "features": [{"feature": "depth_mean", "value": 0.05, "significance": null}]}]}
    })");
    return o;
}

}  // namespace

TEST_CASE("object_json: textures with words and bounds, texels with intervals",
          "[view][api_json]") {
    const Dictionary d = parse_dictionary(kDictionary, "test.yaml");
    const Json j = view::object_json(object(), d);
    CHECK(j["faces"] == 16);
    CHECK(j["vertices"] == 10);
    REQUIRE(j["textures"].size() == 2);
    CHECK(j["textures"][0]["colour"] == "#112233");
    CHECK(j["textures"][0]["orientation"] == "raised");
    CHECK(j["textures"][1]["orientation"] == "engraved");
    REQUIRE(j["textures"][0]["concepts"].size() == 1);
    const Json& word = j["textures"][0]["concepts"][0];
    CHECK(word["id"] == "shallow");
    CHECK(word["label"] == "shallow");  // the dictionary's label, not the report's
    CHECK(word["lower"] == 0.0);
    CHECK(word["upper"] == 0.02);
    REQUIRE(j["textures"][1]["withheld"].size() == 1);
    CHECK(j["textures"][1]["withheld"][0]["upper"].is_null());  // .inf
    REQUIRE(j["texels"].size() == 2);
    CHECK(j["texels"][0]["interval"]["depth_mean"] == "shallow");
    CHECK(j["texels"][1]["interval"]["depth_mean"] == "deep");
    CHECK(j["texels"][0]["interval"]["area"].is_null());
    CHECK(j["texels"][0]["features"]["area"].is_null());
    CHECK(j["texels"][1]["features"]["area"] == 2.5);
    CHECK(j["texels"][0]["significance"]["depth_mean"] == 0.5);
    CHECK(j["texels"][1]["significance"]["depth_mean"].is_null());
    CHECK(j["texels"][0]["features"].size() == static_cast<std::size_t>(kNumFeatures));
}

TEST_CASE("objects_json and features_json: over the objects without error", "[view][api_json]") {
    LoadedCollection c;
    c.path = "work/out/";
    CHECK(view::collection_name(c) == "out");
    c.objects.push_back(object());
    LoadedObject broken;
    broken.id = "obj-2";
    broken.status = "ok";
    broken.error = "objects/obj-2/report.json: not JSON";
    c.objects.push_back(broken);
    const Json list = view::objects_json(c);
    REQUIRE(list.size() == 2);
    CHECK(list[0]["concepts"] == Json::array({"shallow"}));
    CHECK(list[0]["reannotate"] == true);
    CHECK(list[0]["error"].is_null());
    CHECK(list[1]["error"] == "objects/obj-2/report.json: not JSON");
    CHECK(list[1]["reannotate"] == false);
    CHECK(list[1]["texels"].is_null());  // no summary row: unknown
    c.objects[1].texels = 7;             // summary.csv's count of a damaged object
    c.objects[1].textures = 2;
    const Json with_counts = view::objects_json(c);
    CHECK(with_counts[1]["texels"] == 7);
    CHECK(with_counts[1]["textures"] == 2);
    const Json f = view::features_json(c);
    CHECK(f["depth_mean"]["texels"] == Json::array({0.01, 0.05}));
    CHECK(f["depth_mean"]["textures"] == Json::array({0.01, 0.05}));
    CHECK(f["area"]["texels"] == Json::parse("[null, 2.5]"));
    CHECK(f.size() == static_cast<std::size_t>(kNumFeatures));
    CHECK(view::find_object(c, "obj-2") == &c.objects[1]);
    CHECK(view::find_object(c, "obj-9") == nullptr);
    CHECK(view::find_object(c, "..") == nullptr);
    const std::vector<double> depth = view::texel_depths(c.objects[0].report);
    CHECK(depth == std::vector<double>{0.01, 0.05});
}

TEST_CASE("concept_json: infinite bounds are null", "[view][api_json]") {
    const Dictionary d = parse_dictionary(kDictionary, "test.yaml");
    const Json all = view::concepts_json(d);
    REQUIRE(all.size() == 2);
    CHECK(all[1]["id"] == "deep");
    CHECK(all[1]["lower"] == 0.02);
    CHECK(all[1]["upper"].is_null());
    CHECK(all[1]["lower_text"] == "0.02");
    CHECK(all[1]["labels"]["en"] == "deep");
    CHECK(all[1]["line"].get<long>() > 0);
}

TEST_CASE("fill_token and content_type_of", "[view][assets]") {
    CHECK(view::fill_token("<meta content=\"__GEOTEX_TOKEN__\">", "ab12") ==
          "<meta content=\"ab12\">");
    CHECK(view::fill_token("no mark", "ab12") == "no mark");
    CHECK(view::fill_token("__GEOTEX_TOKEN____GEOTEX_TOKEN__", "x") == "xx");
    CHECK(view::content_type_of("app.js") == "text/javascript; charset=utf-8");
    CHECK(view::content_type_of("index.html") == "text/html; charset=utf-8");
    CHECK(view::content_type_of("style.css") == "text/css; charset=utf-8");
    CHECK(view::content_type_of("x.png") == "image/png");
    CHECK(view::content_type_of("js") == "application/octet-stream");
    // three.js is built in whatever the page holds.
    CHECK(view::find_asset("three.min.js") != nullptr);
    CHECK(view::find_asset("OrbitControls.js") != nullptr);
    CHECK(view::find_asset("nothing.js") == nullptr);
}

TEST_CASE("edits_from_json: the two kinds of E, and refusals naming the edit", "[view][api_json]") {
    const Json e = Json::parse(R"([
      {"op": "bound", "concept": "deep", "side": "lower", "value": "0.03"},
      {"op": "label", "concept": "deep", "lang": "fr", "value": "profond"}])");
    const std::vector<DictionaryEdit> edits = view::edits_from_json(e);
    REQUIRE(edits.size() == 2);
    CHECK(edits[0].kind == DictionaryEdit::Kind::Bound);
    CHECK(edits[0].concept_id == "deep");
    CHECK_FALSE(edits[0].upper);
    CHECK(edits[0].value == "0.03");
    CHECK(edits[1].kind == DictionaryEdit::Kind::Label);
    CHECK(edits[1].language == "fr");
    CHECK(view::edit_json(edits[0]) == e[0]);
    CHECK(view::edit_json(edits[1]) == e[1]);
    CHECK_THROWS_WITH(view::edits_from_json(Json::parse(R"([{"op": "bound", "concept": "a",
        "side": "middle", "value": "1"}])")),
                      Catch::Contains("edit 1"));
    CHECK_THROWS_AS(view::edits_from_json(Json::parse(R"([{"op": "move"}])")), InvalidInput);
    CHECK_THROWS_AS(view::edits_from_json(Json::parse(R"({"op": "bound"})")), InvalidInput);
    CHECK_THROWS_AS(view::edits_from_json(Json::parse(R"([{"op": "bound", "concept": "a",
        "side": "lower", "value": 1}])")),
                    InvalidInput);
}

TEST_CASE("marks_from_json and fit_json: the marks of POST /api/fit and its answer",
          "[view][api_json]") {
    const std::vector<FitMark> marks = view::marks_from_json(Json::parse(R"({"marks": [
      {"object": "obj-1", "texture": 2, "concept": "deep", "yes": true},
      {"object": "obj-2", "texture": 0, "concept": "shallow", "yes": false}]})"));
    REQUIRE(marks.size() == 2);
    CHECK(marks[0].object == "obj-1");
    CHECK(marks[0].texture == 2);
    CHECK(marks[0].concept_id == "deep");
    CHECK(marks[0].yes);
    CHECK_FALSE(marks[1].yes);
    CHECK(marks[1].where == "mark 2");
    CHECK_THROWS_WITH(view::marks_from_json(Json::parse(R"({"marks": [
      {"object": "obj-1", "texture": 2, "concept": "deep", "yes": true},
      {"object": "obj-1", "texture": "2", "concept": "deep", "yes": true}]})")),
                      Catch::Contains("mark 2"));
    CHECK_THROWS_AS(view::marks_from_json(Json::parse(R"({"marks": {}})")), InvalidInput);
    CHECK_THROWS_AS(view::marks_from_json(Json::parse(R"({})")), InvalidInput);

    DictionaryFitResult fit;
    DictionaryEdit edit;
    edit.concept_id = "deep";
    edit.upper = true;
    edit.value = "0.5";
    fit.edits.push_back(edit);
    fit.unsatisfied.push_back({marks[0], "marked yes and no"});
    fit.not_reproduced.push_back({marks[1], "too few texels agree"});
    const Json answer = view::fit_json(fit);
    CHECK(answer["edits"] == Json::parse(
                                 R"([{"op": "bound", "concept": "deep", "side": "upper",
                                      "value": "0.5"}])"));
    REQUIRE(answer["unsatisfied"].size() == 2);
    CHECK(answer["unsatisfied"][0] == Json::parse(R"({"object": "obj-1", "texture": 2,
        "concept": "deep", "yes": true, "reason": "marked yes and no"})"));
    CHECK(answer["unsatisfied"][1]["reason"] == "too few texels agree");
}
