// geotex dict: check a dictionary, publish it as SKOS, fit its bounds to a curator's marks.

#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "annotation/dictionary_fit.hpp"
#include "cli/commands.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/mesh_input.hpp"
#include "cli/output.hpp"
#include "common/detail/csv.hpp"
#include "common/detail/text.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/loaded_collection.hpp"

namespace geotex::cli {

namespace {

struct DictOptions {
    CommonOptions common;
    std::string file;
    std::string output;
    std::string format = "turtle";
    std::string from;        // fit: the batch output (or one object's outputs)
    std::string dictionary;  // fit: the dictionary the marks correct ("": the built-in one)
};

/// Exit status of `dict fit` when the new dictionary is written but some marks are not
/// reproduced (README.md, `geotex dict fit`).
constexpr int kExitMarksUnsatisfied = 5;

int run_check(const DictOptions& o) {
    set_current_input(o.file);
    const std::string text = read_text_file(o.file);
    const auto problems = check_dictionary(text);
    for (const auto& p : problems)
        std::fprintf(stderr, "%s:%ld:%ld: %s\n", detail::message_text(o.file).c_str(), p.line,
                     p.column, detail::message_text(p.message).c_str());
    if (!problems.empty()) {
        std::fprintf(stderr, "geotex: error: %s: %zu problem%s\n",
                     detail::message_text(o.file).c_str(), problems.size(),
                     problems.size() == 1 ? "" : "s");
        return kExitInput;
    }
    // load_dictionary prints the warnings (file:line:column: warning: ...); they do not make
    // the dictionary unusable, so the exit status stays 0.
    const Dictionary d = load_dictionary(o.file);
    std::printf("%s: clean: %zu concepts in %zu facet%s%s, languages", o.file.c_str(),
                d.concepts.size(), d.facets.size(), d.facets.size() == 1 ? "" : "s",
                d.declares_facets ? "" : " (one per feature: no 'facets')");
    for (const auto& l : d.languages) std::printf(" %s", l.c_str());
    std::printf(", version %s", d.version.c_str());
    if (!d.warnings.empty())
        std::printf(", %zu warning%s", d.warnings.size(), d.warnings.size() == 1 ? "" : "s");
    std::printf("\n");
    return 0;
}

int run_skos(const DictOptions& o) {
    set_current_input(o.file);
    check_output_paths({{"--output", o.output, true}}, {{"FILE", o.file}});
    static const std::map<std::string, RdfFormat> formats = {{"turtle", RdfFormat::Turtle},
                                                             {"ntriples", RdfFormat::NTriples},
                                                             {"rdfxml", RdfFormat::RdfXml}};
    const Dictionary d = load_dictionary(o.file);
    OutputSet outputs;
    outputs.add(o.output,
                [&](std::ostream& out) { write_dictionary_rdf(out, d, formats.at(o.format)); });
    outputs.commit();
    if (!o.common.quiet)
        std::fprintf(stderr, "geotex: wrote %s (%zu concepts)\n", o.output.c_str(),
                     d.concepts.size());
    return 0;
}

/// The marks of EXAMPLES.csv: object id, texture id, concept id, yes/no; a header row is
/// allowed (its texture field is not a number). A bad row is a one-line error at file:line.
std::vector<FitMark> read_marks(const std::string& file) {
    const std::string text = read_text_file(file);
    const auto rows = in_phase(kExitInput, file, [&] { return detail::parse_csv(text, file); });
    std::vector<FitMark> marks;
    const auto bad = [&](long line, const std::string& what) {
        return CliError(kExitInput, detail::message_text(file) + ":" + std::to_string(line) + ": " +
                                        detail::message_text(what));
    };
    for (size_t r = 0; r < rows.size(); ++r) {
        const auto& f = rows[r].fields;
        const long line = rows[r].line;
        if (f.size() != 4)
            throw bad(line, std::to_string(f.size()) +
                                " fields; expected 4: object,texture,concept,yes|no");
        const bool numeric =
            !f[1].empty() && f[1].find_first_not_of("0123456789") == std::string::npos;
        std::string answer = f[3];
        for (char& ch : answer)
            ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        const bool header = r == 0 && !numeric && answer != "yes" && answer != "no";
        if (header) continue;
        if (!numeric || f[1].size() > 9)
            throw bad(line, "texture '" + f[1] + "' is not a texture id (0, 1, 2, ...)");
        if (answer != "yes" && answer != "no")
            throw bad(line, "'" + f[3] + "' is neither yes nor no");
        if (f[0].empty()) throw bad(line, "empty object id");
        if (f[2].empty()) throw bad(line, "empty concept id");
        FitMark m;
        m.object = f[0];
        m.texture = std::atoi(f[1].c_str());
        m.concept_id = f[2];
        m.yes = answer == "yes";
        m.where = file + ":" + std::to_string(line);
        marks.push_back(std::move(m));
    }
    if (marks.empty()) throw CliError(kExitInput, detail::message_text(file) + ": no marks");
    return marks;
}

int run_fit(const DictOptions& o) {
    auto threads = limit_threads(o.common.threads);
    set_current_input(o.file);
    check_output_paths({{"--output", o.output, true}},
                       {{"EXAMPLES", o.file}, {"--dictionary", o.dictionary}});
    const std::vector<FitMark> marks = read_marks(o.file);
    const DictionarySource source = load_dictionary_source(o.dictionary);
    const std::string& dict_name = source.name;
    const std::string& yaml = source.text;
    const Dictionary& dictionary = source.dictionary;
    const LoadedCollection collection =
        in_phase(kExitInput, o.from, [&] { return load_collection(o.from); });
    size_t other_dictionary = 0;
    for (const auto& ob : collection.objects) {
        if (!ob.error.empty() && !o.common.quiet)
            std::fprintf(stderr, "geotex: note: %s\n", detail::message_text(ob.error).c_str());
        other_dictionary += ob.reannotate && ob.dictionary_sha256 != dictionary.sha256;
    }
    if (other_dictionary > 0 && !o.common.quiet)
        std::fprintf(stderr,
                     "geotex: note: %zu object%s of %s %s annotated with another dictionary "
                     "than %s; the fit uses %s\n",
                     other_dictionary, other_dictionary == 1 ? "" : "s",
                     detail::message_text(o.from).c_str(), other_dictionary == 1 ? "was" : "were",
                     detail::message_text(dict_name).c_str(),
                     detail::message_text(dict_name).c_str());

    const DictionaryFitResult fit = fit_dictionary(dictionary, fit_objects(collection), marks);
    std::string text = yaml;
    if (!fit.edits.empty()) {
        const DictionaryEditResult edited = edit_dictionary(yaml, fit.edits);
        if (!edited.problems.empty())
            throw CliError(kExitProcessing,
                           detail::message_text(dict_name) + ": the fitted bounds make a " +
                               "dictionary with problems (" +
                               detail::message_text(edited.problems.front().message) + ")");
        text = in_phase(kExitInput, dict_name,
                        [&] { return stamp_new_version(edited.text, version_date()); });
    }
    OutputSet outputs;
    outputs.add(o.output, [&](std::ostream& out) { out << text; });
    outputs.commit();

    for (const auto& e : fit.edits) {
        const DictionaryConcept* c = nullptr;
        for (const auto& k : dictionary.concepts)
            if (k.id == e.concept_id) c = &k;
        const std::string old = c ? (e.upper ? c->upper_text : c->lower_text) : "?";
        std::printf("moved: %s %s bound %s -> %s\n", detail::message_text(e.concept_id).c_str(),
                    e.upper ? "upper" : "lower", old.c_str(),
                    detail::message_text(e.value).c_str());
    }
    const auto print = [](const FitProblem& p, const char* kind) {
        std::printf("%s: %s: texture %d of '%s' %s '%s': %s\n",
                    detail::message_text(p.mark.where).c_str(), kind, p.mark.texture,
                    detail::message_text(p.mark.object).c_str(), p.mark.yes ? "is" : "is not",
                    detail::message_text(p.mark.concept_id).c_str(),
                    detail::message_text(p.reason).c_str());
    };
    for (const auto& p : fit.unsatisfied) print(p, "unsatisfied");
    for (const auto& p : fit.not_reproduced) print(p, "not reproduced");
    const size_t missed = fit.unsatisfied.size() + fit.not_reproduced.size();
    if (!o.common.quiet)
        std::fprintf(stderr, "geotex: wrote %s: %zu bound%s moved; %zu of %zu marks reproduced\n",
                     detail::message_text(o.output).c_str(), fit.edits.size(),
                     fit.edits.size() == 1 ? "" : "s", marks.size() - missed, marks.size());
    return missed == 0 ? 0 : kExitMarksUnsatisfied;
}

}  // namespace

Runner add_dict(CLI::App& sub) {
    auto o = std::make_shared<DictOptions>();
    sub.description("Work with YAML interval dictionaries (format: dictionaries/README.md).");
    sub.require_subcommand(1);
    CLI::App* check = sub.add_subcommand(
        "check",
        "Report every problem of a dictionary at once, each as file:line:column: what; exit 0 only "
        "when clean (warnings, as file:line:column: warning: what, allowed)");
    check->add_option("file", o->file, "Dictionary (YAML)")->required();
    CLI::App* skos =
        sub.add_subcommand("skos",
                           "Write one version of the dictionary as a SKOS concept scheme (facets "
                           "as top concepts; each concept with its feature, and its interval in "
                           "this version: bounds and a SHACL rule)");
    skos->add_option("file", o->file, "Dictionary (YAML)")->required();
    skos->add_option("-o,--output", o->output, "RDF file to write")->required();
    skos->add_option("--format", o->format, "turtle, ntriples or rdfxml")
        ->check(CLI::IsMember({"turtle", "ntriples", "rdfxml"}));
    add_output_options(*skos);
    add_common_options(*skos, o->common);
    CLI::App* fit = sub.add_subcommand(
        "fit",
        "Propose interval bounds that reproduce a curator's marks (EXAMPLES.csv: object id, "
        "texture id, concept id, yes or no: texture T of object O should or should not carry "
        "the concept), moving as few bounds as possible and as little as possible; write the "
        "dictionary with them and a new version. Prints each moved bound and each mark left "
        "unsatisfied (with the reason). Exit 0 when every mark is reproduced, 5 when the "
        "dictionary is written but some marks are not, 1-4 on errors");
    fit->add_option("examples", o->file, "Marks (CSV: object,texture,concept,yes|no)")->required();
    fit->add_option("--from", o->from,
                    "A geotex batch output directory, or one object's outputs directory, made "
                    "with this dictionary (its geometry.cbor files are read)")
        ->required();
    fit->add_option("--dictionary", o->dictionary,
                    "The dictionary (YAML) to correct; default: the built-in one");
    fit->add_option("-o,--output", o->output, "The new dictionary (YAML) to write")->required();
    add_output_options(*fit);
    add_common_options(*fit, o->common);
    return [o, check, fit] {
        if (fit->parsed()) return run_fit(*o);
        return check->parsed() ? run_check(*o) : run_skos(*o);
    };
}

}  // namespace geotex::cli
