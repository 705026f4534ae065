#pragma once
/// Interval dictionaries (paper §4.3, Table 3): for each feature, half-open intervals of its
/// value, each a concept with a stable id and labels in several languages. Written by hand
/// in YAML by curators; the format is documented in dictionaries/README.md.

#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace geotex {

/// Which details a concept may describe. A word for a convex property (dome, ridge) is false
/// of an engraving, one for a concave property (cup, groove) false of a raised detail: such a
/// concept says so (YAML key `relief`), and the choice never gives it to the other kind.
enum class Relief { Any, Raised, Engraved };

/// One labelled interval [lower, upper) of a feature: a concept of the dictionary.
struct DictionaryConcept {
    std::string id;    ///< stable concept id, unique in the dictionary (e.g. "circular-shape")
    int feature = -1;  ///< column in kFeatureIds
    double lower = -std::numeric_limits<double>::infinity();  ///< inclusive; -inf allowed
    double upper = std::numeric_limits<double>::infinity();   ///< exclusive; +inf allowed
    std::string lower_text;  ///< the bound as written in the YAML (for xsd:decimal output)
    std::string upper_text;  ///< idem; "" for an infinite bound
    std::map<std::string, std::string> labels;       ///< language tag -> label (sorted)
    std::map<std::string, std::string> definitions;  ///< language tag -> definition, optional
    std::string source;           ///< where the interval comes from (free text), optional
    Relief relief = Relief::Any;  ///< the details it may describe (YAML `relief`, optional)
    /// Absolute IRIs of concepts of other vocabularies (Getty AAT) with the same meaning
    /// (skos:exactMatch) or nearly (skos:closeMatch); YAML `exactMatch`, `closeMatch`,
    /// optional. Only reviewed matches: dictionaries/aat-mappings.md.
    std::vector<std::string> exact_matches;
    std::vector<std::string> close_matches;
    long line = 0;  ///< 1-based place of the concept in the YAML
    long column = 0;
};

/// A facet: features whose concepts answer one question about a texture (its outline, its
/// size, ...), so that they exclude each other: a texture gets at most one concept per facet.
struct DictionaryFacet {
    std::string id;                             ///< stable facet id (e.g. "outline")
    std::map<std::string, std::string> labels;  ///< language tag -> label (sorted)
    std::vector<int> features;  ///< columns in kFeatureIds, in the YAML's order (the order of
                                ///< preference when several could describe a texture)
    long line = 0;              ///< 1-based place of the facet in the YAML
    long column = 0;
};

/// One problem found in a dictionary, with its place (1-based line and column).
struct DictionaryProblem {
    long line = 0;
    long column = 0;
    std::string message;
};

/// A whole dictionary.
struct Dictionary {
    std::string id;                             ///< scheme id (e.g. "default"), used in IRIs
    std::string version;                        ///< curator's version string
    std::string namespace_iri;                  ///< concept IRIs are namespace_iri + concept id
    std::map<std::string, std::string> titles;  ///< language tag -> title
    std::vector<std::string> creators;          ///< absolute IRIs (dcterms:creator), optional
    std::string license;   ///< absolute IRI (dcterms:license), "" when not given
    std::string modified;  ///< YYYY-MM-DD of this version (dcterms:modified), "" when not given
    std::vector<std::string> languages;       ///< languages every concept must label
    std::vector<DictionaryConcept> concepts;  ///< grouped by feature (column order), then
                                              ///< by lower bound
    std::vector<DictionaryFacet> facets;      ///< in the YAML's order; every feature that has a
                                              ///< concept is in exactly one facet
    std::vector<int> feature_facet;  ///< #features (kNumFeatures): index into `facets`, or -1
                                     ///< for a feature without concepts
    bool declares_facets = false;    ///< false: an older dictionary without `facets`, each
                                     ///< feature its own facet (id = the feature id)
    std::vector<DictionaryProblem> warnings;  ///< what loads but deserves a look (no facets)
    std::string sha256;                       ///< hex digest of the YAML bytes
    std::string source_name;                  ///< file name, for messages

    /// The concept of `feature` whose interval holds `value`, or nullptr.
    const DictionaryConcept* find(int feature, double value) const;
};

/// Every problem of a dictionary text at once: YAML syntax (including duplicate keys and an
/// unterminated quote, which yaml-cpp lets through), unknown keys, unknown feature ids,
/// non-numeric bounds (.inf and -.inf allowed), lower >= upper, overlapping intervals of a
/// feature, a missing label in a required language, duplicate concept ids; and of the facets:
/// two concepts (or facets) with one label in one language, a feature with concepts in no
/// facet, a feature in two facets, an unknown feature or key in a facet, a facet without
/// features or without a label in a required language, an unknown relief, a facet with the
/// label of a concept in one language (a facet is a SKOS top concept); of the metadata: a
/// creator, licence or match that is not an absolute IRI, a `modified` that is no date
/// (YYYY-MM-DD). Empty when the dictionary is clean (warnings are not problems:
/// Dictionary::warnings). Sorted by place.
std::vector<DictionaryProblem> check_dictionary(std::string_view yaml_text);

/// Parses a dictionary. `name` goes into messages and `source_name`. Throws ParseError
/// (file, line, column of the first problem, and the count of the others) when
/// check_dictionary finds anything.
Dictionary parse_dictionary(std::string_view yaml_text, const std::string& name);

}  // namespace geotex
