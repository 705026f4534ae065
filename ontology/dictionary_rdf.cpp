// The dictionary as a SKOS concept scheme with SHACL rules, one version of it among others
// (ontology/README.md, "Dictionary versions").

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "ontology/detail/annotation_graph.hpp"
#include "ontology/detail/rdf_graph.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex {

namespace rdf_detail {

std::string checked_namespace(const Dictionary& d) {
    try {
        return validate_base_iri(d.namespace_iri);
    } catch (const InvalidInput& e) {
        throw InvalidInput("RDF writer: namespace of dictionary '" + d.id + "': " + e.what());
    }
}

void check_concepts(const Dictionary& d) {
    // The version names the version node and the interval nodes: without it, two versions
    // would share them.
    if (d.version.empty())
        throw InvalidInput("RDF writer: dictionary '" + d.id + "' has no version");
    for (std::size_t i = 0; i < d.concepts.size(); ++i) {
        const DictionaryConcept& c = d.concepts[i];
        const std::string where =
            "concept " + std::to_string(i + 1) + " of dictionary '" + d.id + "'";
        if (c.id.empty()) throw InvalidInput("RDF writer: " + where + " has an empty id");
        if (c.id == "scheme")
            throw InvalidInput("RDF writer: " + where +
                               ": the id 'scheme' names the concept scheme itself; rename it");
        if (c.feature < 0 || c.feature >= kNumFeatures)
            throw InvalidInput("RDF writer: " + where + " ('" + c.id + "') has feature column " +
                               std::to_string(c.feature) + ", not in [0, " +
                               std::to_string(kNumFeatures) + ")");
        for (std::size_t j = 0; j < i; ++j)
            if (d.concepts[j].id == c.id)
                throw InvalidInput("RDF writer: " + where + ": id '" + c.id +
                                   "' is also the id of concept " + std::to_string(j + 1));
    }
}

std::string version_iri(const std::string& ns, const Dictionary& d) {
    return scheme_iri(ns) + "/version/" + iri_segment(d.version);
}
std::string interval_iri(const std::string& ns, const Dictionary& d, const DictionaryConcept& c) {
    return version_iri(ns, d) + "/" + iri_segment(c.id);
}
std::string interval_rule_iri(const std::string& ns, const Dictionary& d,
                              const DictionaryConcept& c) {
    return interval_iri(ns, d, c) + "/rule";
}

void emit_dictionary_version(Graph& g, const Dictionary& d, const std::string& ns) {
    const std::string version = version_iri(ns, d), scheme = scheme_iri(ns);
    const std::string what = "dictionary '" + d.id + "'";
    g.type(version, gtx("DictionaryVersion"));
    g.type(version, prov("Entity"));
    g.iri(version, dcterms("isVersionOf"), scheme);
    // What a run used (prov:used) is this version of the scheme: PROV says so with
    // specializationOf, Dublin Core with isVersionOf; queries may follow either.
    g.iri(version, prov("specializationOf"), scheme);
    g.text(version, owl("versionInfo"), d.version, what + " version");
    check_sha256(d.sha256, what + " digest");
    g.text(version, gtx("sha256"), d.sha256, what + " digest");
    if (!d.modified.empty()) {
        if (!detail::is_calendar_date(d.modified))
            throw InvalidInput("RDF writer: " + what + ": modified '" + d.modified.substr(0, 40) +
                               "' is not a date YYYY-MM-DD");
        g.typed(version, dcterms("modified"), d.modified, xsd("date"));
    }
}

namespace {

/// The facets to write: the dictionary's, and for a feature whose concepts are in none of
/// them (a dictionary built by hand, without facets), the one-feature facet that
/// parse_dictionary would have made, so that every concept has its broader top concept.
/// The concepts' features must be in range (check_concepts).
std::vector<DictionaryFacet> facets_to_write(const Dictionary& d) {
    std::vector<DictionaryFacet> out = d.facets;
    std::vector<bool> covered(kNumFeatures, false);
    for (const DictionaryFacet& f : d.facets)
        for (int feature : f.features)
            if (feature >= 0 && feature < kNumFeatures)
                covered[static_cast<std::size_t>(feature)] = true;
    std::vector<std::string> languages = d.languages;
    if (languages.empty())
        for (const DictionaryConcept& c : d.concepts)
            for (const auto& [lang, label] : c.labels)
                if (std::find(languages.begin(), languages.end(), lang) == languages.end())
                    languages.push_back(lang);
    for (const DictionaryConcept& c : d.concepts) {
        if (covered[static_cast<std::size_t>(c.feature)]) continue;
        covered[static_cast<std::size_t>(c.feature)] = true;
        DictionaryFacet f;
        f.id = kFeatureIds[static_cast<std::size_t>(c.feature)];
        for (const std::string& lang : languages) f.labels.emplace(lang, f.id);
        f.features.push_back(c.feature);
        out.push_back(std::move(f));
    }
    return out;
}

/// A facet's checks: its id usable and unique, its features in range.
void check_facet(const Dictionary& d, const std::vector<DictionaryFacet>& facets, std::size_t i) {
    const DictionaryFacet& f = facets[i];
    const std::string where = "facet " + std::to_string(i + 1) + " of dictionary '" + d.id + "'";
    if (f.id.empty()) throw InvalidInput("RDF writer: " + where + " has an empty id");
    for (std::size_t j = 0; j < i; ++j)
        if (facets[j].id == f.id)
            throw InvalidInput("RDF writer: " + where + ": id '" + f.id +
                               "' is also the id of facet " + std::to_string(j + 1));
    for (int feature : f.features)
        if (feature < 0 || feature >= kNumFeatures)
            throw InvalidInput("RDF writer: " + where + " ('" + f.id + "') has feature column " +
                               std::to_string(feature) + ", not in [0, " +
                               std::to_string(kNumFeatures) + ")");
}

/// The facet whose features hold the concept's: its skos:broader. facets_to_write gives
/// every concept's feature one.
const DictionaryFacet& facet_of(const std::vector<DictionaryFacet>& facets,
                                const DictionaryConcept& c) {
    for (const DictionaryFacet& f : facets)
        for (int feature : f.features)
            if (feature == c.feature) return f;
    throw InvalidInput("RDF writer: concept '" + c.id + "' is in no facet");
}

}  // namespace

void emit_dictionary(Graph& g, const Dictionary& d) {
    const std::string ns = checked_namespace(d);
    check_concepts(d);
    const std::vector<DictionaryFacet> facets = facets_to_write(d);
    for (std::size_t i = 0; i < facets.size(); ++i) check_facet(d, facets, i);
    const std::string scheme = scheme_iri(ns);
    const std::string version = version_iri(ns, d);
    const std::string what = "dictionary '" + d.id + "'";

    // The scheme: what stays the same from one version to the next, so that two versions in
    // one store describe one scheme without contradiction.
    g.type(scheme, skos("ConceptScheme"));
    for (const auto& [lang, title] : d.titles)
        g.lang_text(scheme, skos("prefLabel"), title, lang, what + " title");
    for (const std::string& creator : d.creators)
        g.iri(scheme, dcterms("creator"),
              validate_iri(creator, "RDF writer: " + what + " creator"));
    if (!d.license.empty())
        g.iri(scheme, dcterms("license"),
              validate_iri(d.license, "RDF writer: " + what + " license"));
    g.iri(scheme, dcterms("hasVersion"), version);
    emit_dictionary_version(g, d, ns);

    // Facets are the top concepts: a SKOS browser shows the scheme as its facets, each with
    // the concepts that answer its question. A dictionary without `facets:` has one facet
    // per feature (parse_dictionary), written the same way.
    for (const DictionaryFacet& f : facets) {
        const std::string iri = facet_iri(ns, f);
        const std::string fwhat = "facet '" + f.id + "'";
        g.type(iri, skos("Concept"));
        g.type(iri, gtx("Facet"));
        for (const auto& [lang, label] : f.labels)
            g.lang_text(iri, skos("prefLabel"), label, lang, fwhat + " label");
        g.text(iri, skos("notation"), f.id, fwhat + " id");
        g.iri(iri, skos("inScheme"), scheme);
        g.iri(iri, skos("topConceptOf"), scheme);
        g.iri(scheme, skos("hasTopConcept"), iri);
        for (int feature : f.features) {
            g.iri(iri, gtx("coversFeature"), feature_iri(feature));
            for (const DictionaryConcept& c : d.concepts)
                if (c.feature == feature) g.iri(iri, skos("narrower"), concept_iri(ns, c));
        }
    }

    for (const DictionaryConcept& c : d.concepts) {
        const std::string iri = concept_iri(ns, c);
        const std::string cwhat = "concept '" + c.id + "'";
        // The concept: its identity, the same in every version (dictionaries/README.md,
        // "Versions").
        g.type(iri, skos("Concept"));
        for (const auto& [lang, label] : c.labels)
            g.lang_text(iri, skos("prefLabel"), label, lang, cwhat + " label");
        g.text(iri, skos("notation"), c.id, cwhat + " id");
        g.iri(iri, skos("inScheme"), scheme);
        g.iri(iri, skos("broader"), facet_iri(ns, facet_of(facets, c)));
        g.iri(iri, gtx("onFeature"), feature_iri(c.feature));
        for (const std::string& m : c.exact_matches)
            g.iri(iri, skos("exactMatch"), validate_iri(m, "RDF writer: " + cwhat + " exactMatch"));
        for (const std::string& m : c.close_matches)
            g.iri(iri, skos("closeMatch"), validate_iri(m, "RDF writer: " + cwhat + " closeMatch"));

        // Its interval in this version: what a version may change without changing the
        // concept (bounds, relief, the definition that names them, their source).
        const std::string interval = interval_iri(ns, d, c);
        g.iri(iri, gtx("hasInterval"), interval);
        g.type(interval, gtx("ConceptInterval"));
        g.iri(interval, gtx("ofConcept"), iri);
        g.iri(interval, gtx("inVersion"), version);
        if (c.relief != Relief::Any) g.iri(interval, gtx("appliesTo"), relief_iri(c.relief));
        for (const auto& [lang, definition] : c.definitions)
            g.lang_text(interval, skos("definition"), definition, lang, cwhat + " definition");
        if (!c.source.empty()) g.text(interval, dcterms("source"), c.source, cwhat + " source");

        // -inf / +inf bounds are simply absent; NaN is an error.
        const bool has_lower = !(std::isinf(c.lower) && c.lower < 0);
        const bool has_upper = !(std::isinf(c.upper) && c.upper > 0);
        const std::string rule = interval_rule_iri(ns, d, c);
        g.iri(interval, gtx("rule"), rule);
        g.type(rule, sh("PropertyShape"));
        g.iri(rule, sh("path"), shortcut_iri(c.feature));
        if (has_lower) {
            const std::string lower = bound_decimal(c.lower_text, c.lower, cwhat + " lower bound");
            g.typed(interval, gtx("lowerBound"), lower, xsd("decimal"));
            g.typed(rule, sh("minInclusive"), lower, xsd("decimal"));
        }
        if (has_upper) {
            const std::string upper = bound_decimal(c.upper_text, c.upper, cwhat + " upper bound");
            g.typed(interval, gtx("upperBound"), upper, xsd("decimal"));
            g.typed(rule, sh("maxExclusive"), upper, xsd("decimal"));
        }
    }
}

}  // namespace rdf_detail

using namespace rdf_detail;

void write_dictionary_rdf(std::ostream& out, const Dictionary& dictionary, RdfFormat format) {
    {
        DryRunSink dry_run;
        Graph g(dry_run);
        emit_dictionary(g, dictionary);
    }
    RaptorSink sink(out, format, dictionary_prefixes());
    Graph g(sink);
    emit_dictionary(g, dictionary);
    sink.finish();
}

}  // namespace geotex
