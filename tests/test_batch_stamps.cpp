// The stamps of geotex batch objects: an object is up to date only while its mesh,
// dictionary, options, geotex version and every output are those its stamp records.

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/batch_stamps.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
namespace fs = std::filesystem;

namespace {

/// A fresh object directory with its five outputs; report.json lists 3 texels in 2 textures.
fs::path object_dir(const std::string& name) {
    const fs::path dir = fs::current_path() / ("stamp_test_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& out : kObjectOutputs)
        test::write_file(dir / out.file, std::string("content of ") + out.file);
    test::write_file(dir / "report.json", R"({"texels": [{}, {}, {}], "textures": [{}, {}]})");
    return dir;
}

const std::string kOptions = "{\"scale\":0.04}\nlang=en";

StampKey key_of(const std::string& options = kOptions, const std::string& ver = version()) {
    return {sha256_hex("mesh bytes"), sha256_hex("dictionary bytes"),
            stamp_options_sha256(options, ver)};
}

/// The object stamped with `key`, as geotex batch leaves it.
Stamp stamped(const fs::path& dir, const StampKey& key, const std::string& base = "") {
    const Stamp stamp = make_stamp(dir, key, "vase-42", "meshes/vase.ply", base);
    test::write_file(dir / kStampFile, stamp.text);
    return stamp;
}

}  // namespace

TEST_CASE("up_to_date_stamp: a stamped object is up to date with its counts",
          "[pipeline][stamps]") {
    const fs::path dir = object_dir("fresh");
    const StampKey key = key_of();
    CHECK_FALSE(up_to_date_stamp(dir, key));  // no stamp yet: it must run
    const Stamp stamp = stamped(dir, key);
    CHECK(stamp.counts.texels == 3);
    CHECK(stamp.counts.textures == 2);
    const auto counts = up_to_date_stamp(dir, key);
    REQUIRE(counts);
    CHECK(counts->texels == 3);
    CHECK(counts->textures == 2);

    const auto j = nlohmann::json::parse(stamp.text);
    CHECK(j.at("geotex").at("version") == version());
    CHECK(j.at("geotex").at("document") == "batch-object");
    CHECK(j.at("id") == "vase-42");
    CHECK(j.at("mesh") == "meshes/vase.ply");
    CHECK(j.at("graph") == ni_name(key.mesh_sha256));  // no base: the mesh's hash name
    CHECK(j.at("outputs").at("annotation.ttl") == sha256_hex("content of annotation.ttl"));
    CHECK(stamp.text.back() == '\n');
    CHECK(nlohmann::json::parse(stamped(dir, key, "https://example.org/o/1/").text).at("graph") ==
          "https://example.org/o/1/");
    fs::remove_all(dir);
}

TEST_CASE("up_to_date_stamp: stale when the mesh, dictionary, options or version change",
          "[pipeline][stamps]") {
    const fs::path dir = object_dir("keys");
    const StampKey key = key_of();
    stamped(dir, key);
    REQUIRE(up_to_date_stamp(dir, key));
    StampKey other = key;
    other.mesh_sha256 = sha256_hex("other mesh bytes");
    CHECK_FALSE(up_to_date_stamp(dir, other));
    other = key;
    other.dictionary_sha256 = sha256_hex("edited dictionary");
    CHECK_FALSE(up_to_date_stamp(dir, other));
    CHECK_FALSE(up_to_date_stamp(dir, key_of(kOptions + "\nlang=fr")));
    CHECK_FALSE(up_to_date_stamp(dir, key_of(kOptions, "0.0.1")));
    // The options key itself: the same text and version, the same digest; any change, another.
    CHECK(stamp_options_sha256(kOptions, "1.0") == stamp_options_sha256(kOptions, "1.0"));
    CHECK(stamp_options_sha256(kOptions, "1.0") != stamp_options_sha256(kOptions, "1.1"));
    CHECK(stamp_options_sha256(kOptions, "1.0") != stamp_options_sha256(kOptions + " ", "1.0"));
    fs::remove_all(dir);
}

TEST_CASE("up_to_date_stamp: stale when an output changed, is missing or is a link",
          "[pipeline][stamps]") {
    const StampKey key = key_of();
    for (const auto& out : kObjectOutputs) {
        INFO(out.file);
        fs::path dir = object_dir("changed");
        stamped(dir, key);
        test::write_file(dir / out.file, "edited by hand");
        CHECK_FALSE(up_to_date_stamp(dir, key));

        dir = object_dir("missing");
        stamped(dir, key);
        fs::remove(dir / out.file);
        CHECK_FALSE(up_to_date_stamp(dir, key));

        // A link to a file with the very bytes recorded is still not geotex's output.
        dir = object_dir("link");
        stamped(dir, key);
        fs::rename(dir / out.file, dir / "elsewhere");
        fs::create_symlink(dir / "elsewhere", dir / out.file);
        CHECK_FALSE(up_to_date_stamp(dir, key));
        fs::remove_all(dir);
    }
    fs::remove_all(fs::current_path() / "stamp_test_changed");
    fs::remove_all(fs::current_path() / "stamp_test_missing");
}

TEST_CASE("up_to_date_stamp: a foreign, truncated or linked stamp means the object runs",
          "[pipeline][stamps]") {
    const fs::path dir = object_dir("foreign");
    const StampKey key = key_of();
    const Stamp stamp = stamped(dir, key);
    test::write_file(dir / kStampFile, stamp.text.substr(0, stamp.text.size() / 2));
    CHECK_FALSE(up_to_date_stamp(dir, key));
    test::write_file(dir / kStampFile, "[1, 2, 3]\n");
    CHECK_FALSE(up_to_date_stamp(dir, key));
    test::write_file(dir / "real.json", stamp.text);
    fs::remove(dir / kStampFile);
    fs::create_symlink(dir / "real.json", dir / kStampFile);
    CHECK_FALSE(up_to_date_stamp(dir, key));
    fs::remove_all(dir);
}

TEST_CASE("make_stamp: a missing output or report is an error naming the file",
          "[pipeline][stamps]") {
    const fs::path dir = object_dir("incomplete");
    fs::remove(dir / "segmentation.ply");
    try {
        make_stamp(dir, key_of(), "a", "a.ply", "");
        FAIL("stamped without its segmentation");
    } catch (const IoError& e) {
        CHECK(e.file() == (dir / "segmentation.ply").string());
    }
    fs::remove_all(dir);
    CHECK(is_plain_file(fs::path(GEOTEX_SOURCE_DIR) / "CMakeLists.txt"));
    CHECK_FALSE(is_plain_file(fs::path(GEOTEX_SOURCE_DIR)));
}
