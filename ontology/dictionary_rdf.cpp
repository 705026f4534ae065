// The dictionary as a SKOS concept scheme with SHACL rules (ontology/README.md).

#include <string>
#include <vector>

#include "geometry/errors.hpp"
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

void emit_dictionary(Graph& g, const Dictionary& d) {
    const std::string ns = checked_namespace(d);
    check_concepts(d);
    const std::string scheme = scheme_iri(ns);
    const std::string what = "dictionary '" + d.id + "'";
    g.type(scheme, skos("ConceptScheme"));
    for (const auto& [lang, title] : d.titles)
        g.lang_text(scheme, skos("prefLabel"), title, lang, what + " title");
    g.text(scheme, owl("versionInfo"), d.version, what + " version");
    check_sha256(d.sha256, what + " digest");
    g.text(scheme, gtx("sha256"), d.sha256, what + " digest");

    for (const DictionaryConcept& c : d.concepts) {
        const std::string iri = concept_iri(ns, c);
        const std::string cwhat = "concept '" + c.id + "'";
        g.type(iri, skos("Concept"));
        for (const auto& [lang, label] : c.labels)
            g.lang_text(iri, skos("prefLabel"), label, lang, cwhat + " label");
        g.text(iri, skos("notation"), c.id, cwhat + " id");
        g.iri(iri, skos("inScheme"), scheme);
        g.iri(iri, gtx("onFeature"), feature_iri(c.feature));
        if (c.relief != Relief::Any) g.iri(iri, gtx("appliesTo"), relief_iri(c.relief));
        for (const auto& [lang, definition] : c.definitions)
            g.lang_text(iri, skos("definition"), definition, lang, cwhat + " definition");
        if (!c.source.empty()) g.text(iri, dcterms("source"), c.source, cwhat + " source");

        // -inf / +inf bounds are simply absent; NaN is an error.
        const bool has_lower = !(std::isinf(c.lower) && c.lower < 0);
        const bool has_upper = !(std::isinf(c.upper) && c.upper > 0);
        const std::string rule = iri + "/rule";
        g.iri(iri, gtx("rule"), rule);
        g.type(rule, sh("PropertyShape"));
        g.iri(rule, sh("path"), shortcut_iri(c.feature));
        if (has_lower) {
            const std::string lower = bound_decimal(c.lower_text, c.lower, cwhat + " lower bound");
            g.typed(iri, gtx("lowerBound"), lower, xsd("decimal"));
            g.typed(rule, sh("minInclusive"), lower, xsd("decimal"));
        }
        if (has_upper) {
            const std::string upper = bound_decimal(c.upper_text, c.upper, cwhat + " upper bound");
            g.typed(iri, gtx("upperBound"), upper, xsd("decimal"));
            g.typed(rule, sh("maxExclusive"), upper, xsd("decimal"));
        }
    }

    // Facets: only those the curator declared. Without `facets:` each feature is its own
    // facet, which says nothing that gtx:onFeature does not say already.
    if (!d.declares_facets) return;
    for (std::size_t i = 0; i < d.facets.size(); ++i) {
        const DictionaryFacet& f = d.facets[i];
        const std::string fwhat = "facet " + std::to_string(i + 1) + " of dictionary '" + d.id + "'";
        if (f.id.empty()) throw InvalidInput("RDF writer: " + fwhat + " has an empty id");
        for (std::size_t j = 0; j < i; ++j)
            if (d.facets[j].id == f.id)
                throw InvalidInput("RDF writer: " + fwhat + ": id '" + f.id +
                                   "' is also the id of facet " + std::to_string(j + 1));
        const std::string iri = facet_iri(ns, f);
        g.type(iri, skos("Collection"));
        g.type(iri, gtx("Facet"));
        for (const auto& [lang, label] : f.labels)
            g.lang_text(iri, skos("prefLabel"), label, lang, "facet '" + f.id + "' label");
        g.text(iri, skos("notation"), f.id, "facet '" + f.id + "' id");
        for (int feature : f.features) {
            if (feature < 0 || feature >= kNumFeatures)
                throw InvalidInput("RDF writer: " + fwhat + " ('" + f.id +
                                   "') has feature column " + std::to_string(feature) +
                                   ", not in [0, " + std::to_string(kNumFeatures) + ")");
            g.iri(iri, gtx("coversFeature"), feature_iri(feature));
            for (const DictionaryConcept& c : d.concepts)
                if (c.feature == feature) g.iri(iri, skos("member"), concept_iri(ns, c));
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
