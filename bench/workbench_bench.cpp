// The workbench's preview: how long re-choosing the words of a whole collection takes after a
// curator moves one bound (view/README.md, POST /api/preview; target: 100 objects in 1 s).
//
//   geotex_workbench_bench PATH [--dictionary FILE] [--objects N] [--repeat R]
//
// PATH is a `geotex batch` output (or one object's outputs) annotated with FILE (default:
// dictionaries/default.yaml of the source tree). Its loadable objects are repeated until there
// are N (default 100): re-choosing the words of an object depends on its tables only, so a
// copy costs what the original does. It first checks that FILE reproduces the words of every
// report (exit 1 otherwise), then moves the shared bound 0.625 of shape_index_mean (ridge |
// dome) to 0.6 through edit_dictionary and times load of the edit + reannotate + diff_words,
// R times (default 5), printing the median and the slowest.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "common/errors.hpp"
#include "pipeline/loaded_collection.hpp"
#include "pipeline/read_text_file.hpp"

using namespace geotex;

int main(int argc, char** argv) {
    std::string path, dictionary_file = GEOTEX_SOURCE_DIR "/dictionaries/default.yaml";
    size_t num_objects = 100;
    int repeat = 5;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--dictionary" && i + 1 < argc)
            dictionary_file = argv[++i];
        else if (a == "--objects" && i + 1 < argc)
            num_objects = static_cast<size_t>(std::atol(argv[++i]));
        else if (a == "--repeat" && i + 1 < argc)
            repeat = std::max(1, std::atoi(argv[++i]));
        else if (path.empty() && a[0] != '-')
            path = a;
        else {
            std::fprintf(stderr,
                         "usage: geotex_workbench_bench PATH [--dictionary FILE] [--objects N] "
                         "[--repeat R]\n");
            return 1;
        }
    }
    if (path.empty()) {
        std::fprintf(stderr, "geotex_workbench_bench: PATH missing\n");
        return 1;
    }
    try {
        using Clock = std::chrono::steady_clock;
        const auto t_load = Clock::now();
        LoadedCollection loaded = load_collection(path);
        const double load_s = std::chrono::duration<double>(Clock::now() - t_load).count();
        const std::string yaml = read_text_file(dictionary_file);
        const Dictionary dictionary = parse_dictionary(yaml, dictionary_file);

        // the collection's own words first: the bench times the right computation
        size_t mismatches = 0, compared = 0;
        const auto same = chosen_words(reannotate(loaded, dictionary));
        for (size_t i = 0; i < loaded.objects.size(); ++i)
            if (loaded.objects[i].reannotate) {
                ++compared;
                if (same[i] != loaded.objects[i].words) {
                    ++mismatches;
                    std::fprintf(stderr, "%s: words differ from its report.json\n",
                                 loaded.objects[i].id.c_str());
                }
            }
        if (compared == 0 || mismatches > 0) {
            std::fprintf(stderr, "geotex_workbench_bench: %zu of %zu objects reproduced\n",
                         compared - mismatches, compared);
            return 1;
        }

        LoadedCollection c;
        c.path = loaded.path;
        size_t texels = 0;
        for (size_t k = 0; c.objects.size() < num_objects; ++k) {
            const LoadedObject& o = loaded.objects[k % loaded.objects.size()];
            if (!o.reannotate) continue;
            c.objects.push_back(o);
            c.objects.back().id += "#" + std::to_string(c.objects.size());
            texels += static_cast<size_t>(o.geometry.features.rows());
        }
        const auto before = report_words(c);

        DictionaryEdit edit;
        edit.concept_id = "ridge";
        edit.upper = true;
        edit.value = "0.6";
        std::vector<double> seconds, reannotate_seconds;
        size_t changed = 0;
        for (int r = 0; r < repeat; ++r) {
            const auto t0 = Clock::now();
            const DictionaryEditResult edited = edit_dictionary(yaml, {edit});
            if (!edited.problems.empty()) {
                std::fprintf(stderr, "edit: %s\n", edited.problems[0].message.c_str());
                return 1;
            }
            const Dictionary moved = parse_dictionary(edited.text, dictionary_file);
            const auto t1 = Clock::now();
            const auto descriptions = reannotate(c, moved);
            reannotate_seconds.push_back(std::chrono::duration<double>(Clock::now() - t1).count());
            changed = diff_words(c, before, chosen_words(descriptions)).size();
            seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
        }
        std::sort(seconds.begin(), seconds.end());
        std::sort(reannotate_seconds.begin(), reannotate_seconds.end());
        std::printf(
            "load %s: %zu objects in %.3f s; reproduced the words of %zu reports\n"
            "preview of one bound move (edit + parse + reannotate + diff) on %zu objects, %zu "
            "texels: median %.3f s (reannotate alone %.3f s), slowest %.3f s over %d runs; %zu "
            "textures changed words\n",
            path.c_str(), loaded.objects.size(), load_s, compared, c.objects.size(), texels,
            seconds[seconds.size() / 2], reannotate_seconds[reannotate_seconds.size() / 2],
            seconds.back(), repeat, changed);
        return 0;
    } catch (const Error& e) {
        std::fprintf(stderr, "geotex_workbench_bench: %s\n", e.located().c_str());
        return 2;
    }
}
