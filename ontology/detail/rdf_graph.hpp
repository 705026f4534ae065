#pragma once
// The vocabularies, the typed triple helper (Graph) and the dictionary's SKOS graph, shared by
// the annotation writer (rdf_writer.cpp) and the dictionary writer (dictionary_rdf.cpp).
// Internal to ontology/.

#include <cctype>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/feature_table.hpp"
#include "ontology/detail/triple_sink.hpp"
#include "ontology/rdf_lexical.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::rdf_detail {

// ---- vocabularies ---------------------------------------------------------------------------

inline constexpr const char* kRdf = "http://www.w3.org/1999/02/22-rdf-syntax-ns#";
inline constexpr const char* kRdfs = "http://www.w3.org/2000/01/rdf-schema#";
inline constexpr const char* kOwl = "http://www.w3.org/2002/07/owl#";
inline constexpr const char* kXsd = "http://www.w3.org/2001/XMLSchema#";
inline constexpr const char* kOa = "http://www.w3.org/ns/oa#";
inline constexpr const char* kSkos = "http://www.w3.org/2004/02/skos/core#";
inline constexpr const char* kSh = "http://www.w3.org/ns/shacl#";
inline constexpr const char* kProv = "http://www.w3.org/ns/prov#";
inline constexpr const char* kSosa = "http://www.w3.org/ns/sosa/";
inline constexpr const char* kCrmdig = "http://www.ics.forth.gr/isl/CRMdig/";
inline constexpr const char* kDcterms = "http://purl.org/dc/terms/";
inline constexpr const char* kDc = "http://purl.org/dc/elements/1.1/";
inline constexpr const char* kCrm = "http://www.cidoc-crm.org/cidoc-crm/";
inline constexpr const char* kLa = "https://linked.art/ns/terms/";
inline constexpr const char* kAs = "http://www.w3.org/ns/activitystreams#";
inline constexpr const char* kQudt = "http://qudt.org/schema/qudt/";
inline constexpr const char* kUnit = "http://qudt.org/vocab/unit/";

inline std::string rdf(const char* local) { return std::string(kRdf) + local; }
inline std::string rdfs(const char* local) { return std::string(kRdfs) + local; }
inline std::string owl(const char* local) { return std::string(kOwl) + local; }
inline std::string xsd(const char* local) { return std::string(kXsd) + local; }
inline std::string oa(const char* local) { return std::string(kOa) + local; }
inline std::string skos(const char* local) { return std::string(kSkos) + local; }
inline std::string sh(const char* local) { return std::string(kSh) + local; }
inline std::string prov(const char* local) { return std::string(kProv) + local; }
inline std::string sosa(const char* local) { return std::string(kSosa) + local; }
inline std::string crmdig(const char* local) { return std::string(kCrmdig) + local; }
inline std::string dcterms(const char* local) { return std::string(kDcterms) + local; }
inline std::string dc(const char* local) { return std::string(kDc) + local; }
inline std::string crm(const char* local) { return std::string(kCrm) + local; }
inline std::string la(const char* local) { return std::string(kLa) + local; }
inline std::string as(const char* local) { return std::string(kAs) + local; }
inline std::string qudt(const char* local) { return std::string(kQudt) + local; }
inline std::string unit(const char* local) { return std::string(kUnit) + local; }
inline std::string gtx(const std::string& local) { return kGeotexNs + local; }

/// Typed helpers over a sink; every check that can fail on user data lives here, so the
/// counting pass raises it.
class Graph {
  public:
    explicit Graph(TripleSink& sink) : sink_(sink) {}

    void iri(const std::string& s, const std::string& p, const std::string& o) {
        sink_.add(s, p, Term{Term::Kind::Iri, o, {}, {}});
    }
    void type(const std::string& s, const std::string& cls) { iri(s, rdf("type"), cls); }
    void typed(const std::string& s, const std::string& p, const std::string& lexical,
               const std::string& datatype) {
        sink_.add(s, p, Term{Term::Kind::Literal, lexical, datatype, {}});
    }
    void dbl(const std::string& s, const std::string& p, double v, const std::string& what) {
        typed(s, p, double_lexical(v, what), xsd("double"));
    }
    void integer(const std::string& s, const std::string& p, long long v) {
        typed(s, p, std::to_string(v), xsd("integer"));
    }
    void boolean(const std::string& s, const std::string& p, bool v) {
        typed(s, p, v ? "true" : "false", xsd("boolean"));
    }
    void text(const std::string& s, const std::string& p, const std::string& v,
              const std::string& what) {
        check_text(v, what);
        sink_.add(s, p, Term{Term::Kind::Literal, v, {}, {}});
    }
    void lang_text(const std::string& s, const std::string& p, const std::string& v,
                   const std::string& lang, const std::string& what) {
        check_text(v, what);
        check_language(lang, what);
        sink_.add(s, p, Term{Term::Kind::Literal, v, {}, lang});
    }

  private:
    TripleSink& sink_;
};

/// gtx shortcut property of a feature id: snake_case to lowerCamelCase
/// ("pca_variance_1" -> "pcaVariance1").
inline std::string shortcut_name(const std::string& feature_id) {
    std::string out;
    bool upper = false;
    for (const char c : feature_id) {
        if (c == '_') {
            upper = true;
            continue;
        }
        out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
        upper = false;
    }
    return out;
}

inline std::string feature_iri(int feature) {
    return gtx(kFeatureIds[static_cast<std::size_t>(feature)]);
}
inline std::string shortcut_iri(int feature) {
    return gtx(shortcut_name(kFeatureIds[static_cast<std::size_t>(feature)]));
}

inline std::string orientation_iri(DetailOrientation o) {
    return gtx(o == DetailOrientation::Positive ? "PositiveDetails" : "NegativeDetails");
}

/// What a concept's relief says in RDF (gtx:appliesTo), or "" for Relief::Any.
inline std::string relief_iri(Relief r) {
    return r == Relief::Raised     ? orientation_iri(DetailOrientation::Positive)
           : r == Relief::Engraved ? orientation_iri(DetailOrientation::Negative)
                                   : std::string();
}

inline const std::vector<Prefix>& annotation_prefixes() {
    static const std::vector<Prefix> p = {
        {"rdfs", kRdfs}, {"owl", kOwl},   {"xsd", kXsd},     {"dcterms", kDcterms},
        {"prov", kProv}, {"oa", kOa},     {"sosa", kSosa},   {"crmdig", kCrmdig},
        {"crm", kCrm},   {"la", kLa},     {"as", kAs},       {"dc", kDc},
        {"qudt", kQudt}, {"unit", kUnit}, {"gtx", kGeotexNs}};
    return p;
}

inline const std::vector<Prefix>& dictionary_prefixes() {
    static const std::vector<Prefix> p = {{"owl", kOwl},     {"xsd", kXsd},   {"dcterms", kDcterms},
                                          {"prov", kProv},   {"skos", kSkos}, {"sh", kSh},
                                          {"gtx", kGeotexNs}};
    return p;
}

// ---- the dictionary (dictionary_rdf.cpp) ------------------------------------------------------

/// The dictionary's namespace as validate_base_iri returns it; InvalidInput naming the
/// dictionary otherwise.
std::string checked_namespace(const Dictionary& d);

/// Every concept's feature in range and its ids usable in IRIs; InvalidInput otherwise.
void check_concepts(const Dictionary& d);

/// The dictionary as a SKOS concept scheme, one version of it (ontology/README.md,
/// "dictionary" row and "Dictionary versions").
void emit_dictionary(Graph& g, const Dictionary& d);

/// The version node alone (N scheme/version/<v>: its types, scheme, version, digest, date),
/// for an annotation graph written without the dictionary: the run names what it used.
/// `ns` is checked_namespace(d).
void emit_dictionary_version(Graph& g, const Dictionary& d, const std::string& ns);

}  // namespace geotex::rdf_detail
