// read_text_file: the one reader of whole text files (dictionaries, manifests, queries,
// reports), bytes unchanged, and IoError naming the file where the command says why.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "common/errors.hpp"
#include "pipeline/read_text_file.hpp"
#include "tests/sparql_test_support.hpp"

using namespace geotex;
using sparql_test::TempFile;

TEST_CASE("read_text_file: the bytes as written, line ends and NUL included", "[pipeline][io]") {
    const std::string bytes = std::string("a\r\nb\n\0c", 7) + "\xc3\xa9";
    const TempFile file("t.txt", bytes);
    CHECK(read_text_file(file.path()) == bytes);
    const TempFile empty("empty.txt", "");
    CHECK(read_text_file(empty.path()).empty());
}

TEST_CASE("read_text_file: a missing file or a directory is an IoError naming it",
          "[pipeline][io]") {
    const TempFile file("t.txt", "x");
    const std::string dir = std::filesystem::path(file.path()).parent_path().string();
    const std::string missing = dir + "/missing.yaml";
    try {
        read_text_file(missing);
        FAIL("no IoError");
    } catch (const IoError& e) {
        CHECK(e.file() == missing);
        CHECK(e.located() == missing + ": cannot open (No such file or directory)");
    }
    try {
        read_text_file(dir);
        FAIL("no IoError");
    } catch (const IoError& e) {
        CHECK(e.located() == dir + ": cannot read: it is a directory");
    }
}
