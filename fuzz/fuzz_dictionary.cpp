// libFuzzer target: the YAML interval dictionary loader on arbitrary text. check_dictionary
// must list no problem exactly when parse_dictionary accepts the text; an accepted dictionary
// must hold the invariants that Dictionary::find relies on, and publish as SKOS (what
// `geotex dict check` calls clean, `geotex dict skos` must write).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "annotation/dictionary.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "ontology/rdf_writer.hpp"

namespace {

void require(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_dictionary: invariant broken: %s\n", what);
    std::abort();
}

void check_parsed(const geotex::Dictionary& d) {
    require(!d.id.empty(), "the dictionary has an id");
    require(d.sha256.size() == 64, "the digest is set");
    require(d.source_name == "fuzz.yaml", "the source name is kept");
    for (std::size_t i = 0; i < d.concepts.size(); ++i) {
        const geotex::DictionaryConcept& c = d.concepts[i];
        require(c.feature >= 0 && c.feature < geotex::kNumFeatures, "feature in range");
        require(!std::isnan(c.lower) && !std::isnan(c.upper), "bounds are numbers");
        require(c.lower < c.upper, "lower bound below the upper");
        require(c.line > 0 && c.column > 0, "the concept has a place");
        for (const std::string& lang : d.languages)
            require(c.labels.count(lang) == 1, "every required language is labelled");
        if (i > 0) {
            const geotex::DictionaryConcept& b = d.concepts[i - 1];
            require(b.feature < c.feature || (b.feature == c.feature && b.upper <= c.lower),
                    "concepts sorted by feature and disjoint");
        }
        if (std::isfinite(c.lower)) require(d.find(c.feature, c.lower) == &c, "find(lower)");
        require(c.relief == geotex::Relief::Any || c.relief == geotex::Relief::Raised ||
                    c.relief == geotex::Relief::Engraved,
                "relief is one of the three");
    }
    // Facets: what the choice of concepts relies on (at most one concept per facet needs each
    // feature with concepts in exactly one facet, and feature_facet to say which).
    require(d.feature_facet.size() == static_cast<std::size_t>(geotex::kNumFeatures),
            "feature_facet has one entry per feature");
    std::vector<int> listed(geotex::kNumFeatures, 0);
    for (std::size_t f = 0; f < d.facets.size(); ++f) {
        const geotex::DictionaryFacet& facet = d.facets[f];
        require(!facet.id.empty() && !facet.features.empty(), "a facet has an id and features");
        require(facet.line > 0 && facet.column > 0, "the facet has a place");
        for (const std::string& lang : d.languages)
            require(facet.labels.count(lang) == 1, "every required language labels the facet");
        for (int feature : facet.features) {
            require(feature >= 0 && feature < geotex::kNumFeatures, "facet feature in range");
            ++listed[static_cast<std::size_t>(feature)];
            const int index = d.feature_facet[static_cast<std::size_t>(feature)];
            require(index == -1 || index == static_cast<int>(f), "feature_facet names its facet");
        }
    }
    for (int feature = 0; feature < geotex::kNumFeatures; ++feature) {
        bool has_concepts = false;
        for (const auto& c : d.concepts) has_concepts = has_concepts || c.feature == feature;
        const int index = d.feature_facet[static_cast<std::size_t>(feature)];
        require(listed[static_cast<std::size_t>(feature)] <= 1,
                "a feature is in one facet at most");
        require(has_concepts == (index >= 0), "a feature has a facet exactly when it has concepts");
    }
    require(d.declares_facets || d.warnings.size() == 1, "no facets: one warning");
    for (const auto& w : d.warnings)
        require(!w.message.empty() && w.line >= 1 && w.column >= 1, "a warning has a place");
    std::ostringstream skos;
    try {
        geotex::write_dictionary_rdf(skos, d, geotex::RdfFormat::Turtle);
    } catch (const geotex::InvalidInput& e) {
        std::fprintf(stderr, "write_dictionary_rdf: %s\n", e.what());
        require(false, "a clean dictionary publishes as SKOS");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::vector<geotex::DictionaryProblem> problems = geotex::check_dictionary(text);
    for (std::size_t i = 0; i < problems.size(); ++i) {
        require(!problems[i].message.empty(), "a problem says what is wrong");
        require(problems[i].line >= 1 && problems[i].column >= 1, "a problem has a place");
        if (i > 0)
            require(problems[i - 1].line < problems[i].line ||
                        (problems[i - 1].line == problems[i].line &&
                         problems[i - 1].column <= problems[i].column),
                    "problems sorted by place");
    }
    bool parsed = false;
    try {
        check_parsed(geotex::parse_dictionary(text, "fuzz.yaml"));
        parsed = true;
    } catch (const geotex::ParseError& e) {
        require(!problems.empty(), "parse_dictionary throws only when check_dictionary complains");
        require(e.file() == "fuzz.yaml" && e.line() == problems.front().line &&
                    e.column() == problems.front().column,
                "the ParseError is placed at the first problem");
    }
    require(parsed == problems.empty(), "check_dictionary is empty iff parse_dictionary accepts");
    return 0;
}
