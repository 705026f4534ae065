// libFuzzer target: the CSV manifest of `geotex batch` (cli/collection.cpp) on arbitrary
// text. A manifest is either refused as a whole with one input error naming the file, or
// gives objects that hold what the batch relies on: an object without an error has an id
// that cannot leave OUTDIR/objects/ (no '/', no leading '.'), unique among the good ones, a
// mesh path, and a shard in range; every message is one line; objects are sorted by id.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>

#include "cli/collection.hpp"
#include "cli/output.hpp"

namespace {

void require(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_manifest: invariant broken: %s\n", what);
    std::abort();
}

bool one_line(const std::string& s) { return s.find_first_of("\r\n") == std::string::npos; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string file = "dir/manifest.csv";
    geotex::cli::Collection c;
    try {
        c = geotex::cli::parse_manifest(text, file);
    } catch (const geotex::cli::CliError& e) {
        const std::string message = e.what();
        require(e.code() == geotex::cli::kExitInput, "a refused manifest is an input error");
        require(message.rfind(file + ":", 0) == 0, "the error names the manifest");
        require(one_line(message), "the error is one line");
        return 0;
    }
    for (const std::string& note : c.notes) require(one_line(note), "a note is one line");
    std::set<std::string> good_ids;
    for (std::size_t i = 0; i < c.objects.size(); ++i) {
        const geotex::cli::CollectionObject& o = c.objects[i];
        require(o.where.rfind(file + ":", 0) == 0, "an object's place is in the manifest");
        require(one_line(o.error), "an object's error is one line");
        if (i > 0) {
            const auto& p = c.objects[i - 1];
            require(p.id < o.id || (p.id == o.id && p.where <= o.where), "objects sorted by id");
        }
        if (!o.error.empty()) continue;
        require(geotex::cli::check_object_id(o.id).empty(), "a good object has a valid id");
        require(!o.id.empty() && o.id[0] != '.' && o.id.find('/') == std::string::npos &&
                    o.id.find('\\') == std::string::npos,
                "a good object's id stays inside OUTDIR/objects/");
        require(good_ids.insert(o.id).second, "good objects have distinct ids");
        require(!o.mesh.empty() && !o.path.empty(), "a good object has a mesh");
        require(o.path == o.mesh || o.path == "dir/" + o.mesh,
                "the path is the cell, or relative to the manifest");
        for (int n = 1; n <= 7; ++n) {
            const int s = geotex::cli::shard_of(o.id, n);
            require(s >= 1 && s <= n, "shard in range");
        }
    }
    return 0;
}
