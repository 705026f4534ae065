// geotex dict: check a dictionary, publish it as SKOS.

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "annotation/dictionary.hpp"
#include "cli/commands.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/mesh_input.hpp"
#include "cli/output.hpp"
#include "common/detail/text.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::cli {

namespace {

struct DictOptions {
    CommonOptions common;
    std::string file;
    std::string output;
    std::string format = "turtle";
};

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
    return [o, check] { return check->parsed() ? run_check(*o) : run_skos(*o); };
}

}  // namespace geotex::cli
