#pragma once
// What the SPARQL tests share (test_sparql.cpp: the documented queries and the engine;
// test_query_results.cpp: the result writers; test_sparql_refusals.cpp: errors, refusals and
// limits): the fixtures tests/data/annotation-sample*.ttl and small helpers.

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "ontology/sparql.hpp"

#ifndef GEOTEX_SOURCE_DIR
#error "GEOTEX_SOURCE_DIR (the repository root) must be defined"
#endif

namespace geotex::sparql_test {

using geotex::QueryResult;
using geotex::ResultFormat;
using geotex::run_sparql;
using Rows = std::vector<std::vector<std::string>>;

inline const std::string kRoot = GEOTEX_SOURCE_DIR;
inline const std::string kSample1 = kRoot + "/tests/data/annotation-sample.ttl";
inline const std::string kSample2 = kRoot + "/tests/data/annotation-sample2.ttl";
inline const std::string kB1 = "https://collection.example.org/object/42/model/";
inline const std::string kB2 =
    "urn:sha256:31a8e0614cf6ac52dbe268ebcebf6c5c33e1742d5c6038b8e90b282f1851de92/";
inline const std::string kAmphora = "amphora \"B\", fragment 3.ply";
inline const std::string kXsd = "http://www.w3.org/2001/XMLSchema#";

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline std::string query_file(const std::string& name) {
    return read_text(kRoot + "/ontology/queries/" + name);
}

/// `text` with its one occurrence of `from` replaced by `to` (the way a user edits a
/// query's parameter).
inline std::string edited(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(text.find(from, at + 1) == std::string::npos);
    return text.replace(at, from.size(), to);
}

inline std::string written(const QueryResult& r, ResultFormat format) {
    std::ostringstream out;
    geotex::write_query_result(out, r, format);
    return out.str();
}

/// A file in a fresh temporary directory, removed with the object.
class TempFile {
  public:
    TempFile(const std::string& name, const std::string& content) {
        // The process id keeps apart the test processes that ctest runs in parallel.
        dir_ = std::filesystem::temp_directory_path() /
               ("geotex-test-sparql-" + std::to_string(::getpid()) + "-" +
                std::to_string(counter()++));
        std::filesystem::create_directories(dir_);
        path_ = (dir_ / name).string();
        std::ofstream(path_, std::ios::binary) << content;
    }
    ~TempFile() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }

  private:
    static int& counter() {
        static int n = 0;
        return n;
    }
    std::filesystem::path dir_;
    std::string path_;
};

/// The first fixture without its dictionary section: what `geotex annotate` writes alone.
inline std::string sample1_without_dictionary() {
    const std::string text = read_text(kSample1);
    const auto at = text.find("# ---- the dictionary");
    REQUIRE(at != std::string::npos);
    return text.substr(0, at);
}

inline const std::vector<std::string> kQueryFiles = {
    "textures-with-concept.rq", "texels-per-texture.rq", "features-by-significance.rq",
    "objects-with-concept.rq", "texture-labels.rq"};

}  // namespace geotex::sparql_test
