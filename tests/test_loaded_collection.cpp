// A batch output written by the library functions `geotex batch` runs (annotate, the JSON
// report, the geometry cache, the stamp's digests), loaded back: the words chosen again from
// geometry.cbor must be the words the full run wrote, and broken objects get their error.

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/synth.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/geometry_cache.hpp"
#include "pipeline/loaded_collection.hpp"
#include "pipeline/report_json.hpp"
#include "tests/dictionary_fixtures.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
using test::default_dictionary;
namespace fs = std::filesystem;

namespace {

// One annotated object's files, as the batch writes them.
struct ObjectFiles {
    std::string report, cache;
};

ObjectFiles annotated(std::uint64_t layout_seed, const DescriptionParams& choice) {
    SynthParams p;
    p.level = 4;
    p.engraved_fraction = 0.4;
    p.layout_seed = layout_seed;
    const Mesh mesh = make_synthetic_sphere(p).mesh;
    AnnotateOptions options;
    options.segmentation.radius_rel = 0.08;
    options.segmentation.orientation = OrientationMode::Both;
    options.description = choice;
    const MeshIdentity identity{"s.ply", "ply-binary-le",
                                sha256_hex("mesh " + std::to_string(layout_seed))};
    const Annotation a = annotate(mesh, identity, default_dictionary(), options);
    ObjectFiles f;
    f.report = report_text(annotation_report(a, {"s.ply", "ply-binary-le", {}}));
    std::ostringstream cache;
    write_geometry_cache(cache, geometry_cache_key(identity.sha256, options.segmentation),
                         a.segmentation);
    f.cache = cache.str();
    return f;
}

std::string run_json(const ObjectFiles& f) {
    return "{\"outputs\": {\"report.json\": \"" + sha256_hex(f.report) +
           "\", \"geometry.cbor\": \"" + sha256_hex(f.cache) + "\"}}\n";
}

// OUTDIR with: a, b (complete; b with another word choice), c (failed), d (no geometry.cbor),
// e (a report that is not JSON), f (its directory a link to a's), g (geometry.cbor changed
// after the stamp), h (no run.json: not stamped).
struct Batch {
    fs::path dir;
    ObjectFiles a, b;
    Batch() {
        static int counter = 0;
        dir = fs::temp_directory_path() / ("geotex-test-loaded-" + std::to_string(::getpid()) +
                                           "-" + std::to_string(counter++));
        fs::create_directories(dir / "objects");
        a = annotated(1, {});
        DescriptionParams strict;
        strict.min_agreement = 0.9;
        strict.num_resamples = 50;
        b = annotated(2, strict);
        const auto object = [&](const std::string& id, const ObjectFiles& f, bool cache,
                                bool stamp) {
            test::write_file(dir / "objects" / id / "report.json", f.report);
            test::write_file(dir / "objects" / id / "segmentation.ply", "ply\n");
            if (cache) test::write_file(dir / "objects" / id / "geometry.cbor", f.cache);
            if (stamp) test::write_file(dir / "objects" / id / "run.json", run_json(f));
        };
        object("a", a, true, true);
        object("b", b, true, true);
        object("d", a, false, true);
        ObjectFiles broken{"{not json", a.cache};
        object("e", broken, true, true);
        fs::create_directory_symlink(dir / "objects" / "a", dir / "objects" / "f");
        object("g", a, true, true);
        test::write_file(dir / "objects" / "g" / "geometry.cbor", b.cache);
        object("h", a, true, false);
        // rows out of order, and the failed object in a shard's summary
        test::write_file(dir / "summary.csv",
                         "id,mesh,status,seconds,texels,textures,reason\n"
                         "h,h.ply,ok,1,1,1,\n"
                         "b,b.ply,skipped,1,7,3,\n"
                         "a,a.ply,ok,1,5,2,\n"
                         "d,d.ply,ok,1,1,1,\n"
                         "e,e.ply,ok,1,1,1,\n"
                         "f,f.ply,ok,1,1,1,\n"
                         "g,g.ply,ok,1,1,1,\n");
        test::write_file(dir / "summary-shard-2-of-2.csv",
                         "id,mesh,status,seconds,texels,textures,reason\n"
                         "c,c.ply,failed,1,,,\"mesh.ply: no faces\"\n");
    }
    ~Batch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

const Batch& batch() {
    static const Batch b;
    return b;
}

const LoadedObject& object_of(const LoadedCollection& c, const std::string& id) {
    for (const auto& o : c.objects)
        if (o.id == id) return o;
    FAIL("no object " << id);
    return c.objects.front();
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("load_collection: a batch's objects in id order, each failure its own",
          "[pipeline][loaded_collection]") {
    const LoadedCollection c = load_collection(batch().dir.string());
    CHECK(c.batch);
    std::vector<std::string> ids;
    for (const auto& o : c.objects) ids.push_back(o.id);
    CHECK(ids == std::vector<std::string>{"a", "b", "c", "d", "e", "f", "g", "h"});

    const LoadedObject& a = object_of(c, "a");
    CHECK(a.error.empty());
    CHECK(a.reannotate);
    CHECK(a.status == "ok");
    CHECK(a.texels == 5);  // the summary's numbers, as written
    CHECK(a.geometry.features.cols() == kNumFeatures);
    CHECK(static_cast<size_t>(a.geometry.features.rows()) == a.report.at("texels").size());
    CHECK(a.words.size() == a.report.at("textures").size());
    CHECK(a.params.min_agreement == 0.75);
    const LoadedObject& b = object_of(c, "b");
    CHECK(b.status == "skipped");
    CHECK(b.params.min_agreement == 0.9);
    CHECK(b.params.num_resamples == 50);

    CHECK(object_of(c, "c").error == "failed: mesh.ply: no faces");
    CHECK(object_of(c, "c").texels == -1);  // the failed row's empty cells: unknown
    CHECK(object_of(c, "c").textures == -1);
    CHECK(!object_of(c, "c").reannotate);
    const LoadedObject& d = object_of(c, "d");
    CHECK(d.error.empty());
    CHECK(!d.reannotate);
    CHECK(!d.words.empty());
    const LoadedObject& e = object_of(c, "e");
    CHECK(contains(e.error, "objects/e/report.json: not a geotex annotation report"));
    const LoadedObject& f = object_of(c, "f");
    CHECK(contains(f.error, "objects/f"));
    CHECK(contains(f.error, "symbolic link"));
    CHECK(contains(object_of(c, "g").error, "objects/g/geometry.cbor: changed since its run"));
    CHECK(contains(object_of(c, "h").error, "objects/h/run.json"));
    for (const auto& o : c.objects) CHECK(o.error.find('\n') == std::string::npos);
}

TEST_CASE("load_collection: one object's outputs directory, and what is neither",
          "[pipeline][loaded_collection]") {
    const fs::path one = batch().dir / "objects" / "d";
    const LoadedCollection c = load_collection(one.string());
    CHECK(!c.batch);
    REQUIRE(c.objects.size() == 1);
    CHECK(c.objects[0].id == "d");
    CHECK(c.objects[0].error.empty());
    CHECK(!c.objects[0].reannotate);  // no geometry.cbor
    // without run.json the files are taken as they are
    const LoadedCollection h = load_collection((batch().dir / "objects" / "h").string());
    CHECK(h.objects[0].error.empty());
    CHECK(h.objects[0].reannotate);

    try {
        load_collection((batch().dir / "objects").string());
        FAIL("no throw");
    } catch (const InvalidInput& e) {
        CHECK(contains(e.located(), "/objects: neither a geotex batch output (no summary.csv)"));
    }
    CHECK_THROWS_AS(load_collection((batch().dir / "nothing").string()), InvalidInput);
    // a link named on the command line is followed: the object is the directory it names
    const fs::path link = batch().dir / "object-link";
    fs::create_directory_symlink(batch().dir / "objects" / "a", link);
    const LoadedCollection linked = load_collection(link.string());
    REQUIRE(linked.objects.size() == 1);
    CHECK(linked.objects[0].id == "a");
    CHECK(linked.objects[0].error.empty());
    CHECK(linked.objects[0].reannotate);
    CHECK_THROWS_AS(load_collection((batch().dir / "summary.csv").string()), InvalidInput);
}

TEST_CASE("read_object_file: refuses ids, links and what is not a regular file",
          "[pipeline][loaded_collection]") {
    const std::string root = (batch().dir / "objects").string();
    CHECK(read_object_file(root, "a", "report.json") == batch().a.report);
    for (const char* id : {"", ".", "..", ".hidden", "a/../b", "x/y"})
        CHECK_THROWS_AS(read_object_file(root, id, "report.json"), InvalidInput);
    CHECK_THROWS_AS(read_object_file(root, "a", "../b/report.json"), InvalidInput);
    try {
        read_object_file(root, "f", "report.json");
        FAIL("no throw");
    } catch (const IoError& e) {
        CHECK(e.file() == root + "/f");
        CHECK(contains(e.what(), "symbolic link"));
    }
    fs::create_symlink(batch().dir / "objects" / "a" / "report.json",
                       batch().dir / "objects" / "d" / "linked.json");
    CHECK_THROWS_AS(read_object_file(root, "d", "linked.json"), IoError);
    REQUIRE(::mkfifo((batch().dir / "objects" / "d" / "fifo").c_str(), 0600) == 0);
    CHECK_THROWS_WITH(read_object_file(root, "d", "fifo"), Catch::Contains("not a regular file"));
    CHECK_THROWS_WITH(read_object_file(root, "d", "absent.json"), Catch::Contains("cannot open"));
}

TEST_CASE("load_collection: a link at OUTDIR/objects fails every object, naming it",
          "[pipeline][loaded_collection]") {
    const fs::path dir = batch().dir.string() + "-linked-objects";
    fs::create_directories(dir);
    fs::copy_file(batch().dir / "summary.csv", dir / "summary.csv");
    fs::create_directory_symlink(batch().dir / "objects", dir / "objects");
    const LoadedCollection c = load_collection(dir.string());
    REQUIRE(!c.objects.empty());
    for (const auto& o : c.objects) {
        INFO(o.id);
        CHECK(!o.reannotate);
        if (o.status == "ok" || o.status == "skipped")
            CHECK(contains(o.error, "/objects: is a symbolic link"));
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
}

TEST_CASE("reannotate: the same dictionary gives the words of the full run",
          "[pipeline][loaded_collection]") {
    const LoadedCollection c = load_collection(batch().dir.string());
    const auto descriptions = reannotate(c, default_dictionary());
    REQUIRE(descriptions.size() == c.objects.size());
    int compared = 0;
    for (size_t i = 0; i < c.objects.size(); ++i) {
        if (!c.objects[i].reannotate) {
            CHECK(descriptions[i].empty());
            continue;
        }
        INFO(c.objects[i].id);
        CHECK(chosen_words(descriptions[i]) == c.objects[i].words);
        ++compared;
    }
    CHECK(compared == 2);  // a and b
    // the words are not all empty: the comparison says something
    size_t words = 0;
    for (const auto& t : object_of(c, "a").words) words += t.size();
    CHECK(words > 0);
    CHECK(diff_words(c, report_words(c), chosen_words(descriptions)).empty());
    CHECK(report_label_language(object_of(c, "a").report, default_dictionary()) == "en");
}

TEST_CASE("reannotate: a moved bound changes the textures whose values cross it, no other",
          "[pipeline][loaded_collection]") {
    const LoadedCollection c = load_collection(batch().dir.string());
    const Dictionary& dict = default_dictionary();
    const LoadedObject& a = object_of(c, "a");
    // a concept chosen for a texture of a: move its lower bound above the texture's mean
    // value (or its upper bound below it), so that the interval no longer holds the value
    const nlohmann::json& t0 = a.report.at("annotation").at("textures");
    std::string concept_id, feature;
    double value = 0;
    int texture = -1;
    for (const auto& t : t0)
        for (const auto& w : t.at("concepts"))
            if (concept_id.empty()) {
                concept_id = w.at("concept").get<std::string>();
                feature = w.at("feature").get<std::string>();
                value = w.at("value").get<double>();
                texture = t.at("texture").get<int>();
            }
    REQUIRE(!concept_id.empty());
    const DictionaryConcept* chosen = nullptr;
    for (const auto& k : dict.concepts)
        if (k.id == concept_id) chosen = &k;
    REQUIRE(chosen);
    const int column = feature_index(feature);
    // the new bound: halfway between the value and the upper bound (finite) or the lower one
    const bool move_lower = std::isfinite(chosen->upper);
    const double old_bound = move_lower ? chosen->lower : chosen->upper;
    const double new_bound = move_lower ? (value + chosen->upper) / 2 : (value + chosen->lower) / 2;
    REQUIRE(std::isfinite(new_bound));
    char text[64];
    std::snprintf(text, sizeof text, "%.10g", new_bound);
    const std::string yaml = test::read_source_file("dictionaries/default.yaml");
    DictionaryEdit edit;
    edit.concept_id = concept_id;
    edit.upper = !move_lower;
    edit.value = text;
    const auto edited = edit_dictionary(yaml, {edit});
    REQUIRE(edited.problems.empty());
    const Dictionary moved = parse_dictionary(edited.text, "moved.yaml");
    const auto changes = diff_words(c, report_words(c), chosen_words(reannotate(c, moved)));
    const double lo = std::min(old_bound, std::atof(text)),
                 hi = std::max(old_bound, std::atof(text));
    // which textures have a texel value of the feature between the old and the new bound,
    // from the report's own per-texel table (not from geometry.cbor)
    const auto crossing = [&](const LoadedObject& o, int texture) {
        if (!std::isfinite(lo)) return true;  // an infinite bound: every value on that side
        for (const auto& x : o.report.at("texels")) {
            const auto& v = x.at("features").at(feature);
            if (x.at("texture").get<int>() != texture || v.is_null()) continue;
            const double d = v.get<double>();
            if (lo <= d && d <= hi) return true;
        }
        return false;
    };
    bool first_changed = false;
    for (const auto& ch : changes) {
        INFO(ch.object << " texture " << ch.texture);
        CHECK(crossing(object_of(c, ch.object), ch.texture));
        if (ch.object == "a" && ch.texture == texture) {
            first_changed = true;
            // the interval no longer holds the texture's mean: the word cannot be said
            CHECK(std::find(ch.after.begin(), ch.after.end(), concept_id) == ch.after.end());
        }
    }
    CHECK(first_changed);
    // a bound moved where no texel value lies changes nothing
    DictionaryEdit still = edit;
    std::snprintf(text, sizeof text, "%.10g", old_bound + (move_lower ? -1e-9 : 1e-9));
    bool empty_gap = true;
    for (const auto& o : c.objects)
        if (o.reannotate)
            for (Eigen::Index i = 0; i < o.geometry.features.rows(); ++i) {
                const double d = o.geometry.features(i, column);
                if (std::min(old_bound, std::atof(text)) <= d &&
                    d <= std::max(old_bound, std::atof(text)))
                    empty_gap = false;
            }
    REQUIRE(empty_gap);
    still.value = text;
    const auto nudged = edit_dictionary(yaml, {still});
    if (nudged.problems.empty()) {
        const auto none = diff_words(
            c, report_words(c), chosen_words(reannotate(c, parse_dictionary(nudged.text, "n"))));
        CHECK(none.empty());
    }
}

TEST_CASE("diff_words: set comparison, missing textures, sizes", "[pipeline][loaded_collection]") {
    LoadedCollection c;
    c.objects.resize(2);
    c.objects[0].id = "x";
    c.objects[0].reannotate = true;
    c.objects[1].id = "y";  // not re-annotated: never compared
    const std::vector<ObjectWords> before = {{{"p", "q"}, {"r"}}, {{"s"}}};
    const std::vector<ObjectWords> after = {{{"q", "p"}, {"t"}, {}}, {{"u"}}};
    const auto changes = diff_words(c, before, after);
    REQUIRE(changes.size() == 2);
    CHECK(changes[0].object == "x");
    CHECK(changes[0].texture == 1);
    CHECK(changes[0].before == TextureWords{"r"});
    CHECK(changes[0].after == TextureWords{"t"});
    CHECK(changes[1].texture == 2);
    CHECK(changes[1].before.empty());
    CHECK_THROWS_AS(diff_words(c, before, {}), InvalidInput);
}
