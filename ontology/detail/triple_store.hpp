#pragma once
// The data of `geotex query`: a set of RDF triples over interned terms, indexed three ways so
// that a triple pattern with any of its parts fixed is a binary search, not a scan.
//
// Hand-written rather than Redland's librdf (the indexed store Debian packages under Rasqal),
// because of load time, measured on 100 annotated level-6 objects (626k parsed triples, 497k
// distinct; bench/RESULTS.md, "Queries"): librdf's "hashes" storage takes 5.5 s and its
// "trees" storage 3.6 s to take the triples, against 0.95 s for Raptor's parse alone, while
// the target is 2 s for the whole query. Sorted arrays of integer triples are the
// smallest structure that answers every pattern: they are built once and never change.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace geotex::detail {

/// The kind of an RDF term, the first byte of its key.
enum class TermKind : char { Iri = 'I', Blank = 'B', Literal = 'L' };

/// Keys: one string per RDF term, equal exactly when the terms are equal (RDF 1.1: a literal
/// typed xsd:string is the simple literal; language tags compare in lower case).
///   IRI       'I' iri
///   blank     'B' label
///   literal   'L' ('@' language | '^' datatype IRI | '-') '\0' lexical form
/// The lexical form comes last, so it may hold any byte; a language tag or an IRI holds no NUL.
void append_iri_key(std::string& out, std::string_view iri);
void append_blank_key(std::string& out, std::string_view label);
void append_literal_key(std::string& out, std::string_view lexical, std::string_view language,
                        std::string_view datatype);

/// The parts of a term key (views into the key).
struct TermParts {
    TermKind kind = TermKind::Iri;
    std::string_view text;      ///< IRI, blank node label or lexical form
    std::string_view language;  ///< lower case; empty unless a literal with a language tag
    std::string_view datatype;  ///< empty for IRIs, blank nodes and simple literals
};
TermParts split_term_key(std::string_view key);

class TripleStore {
  public:
    using TermId = std::uint32_t;
    using Triple = std::array<TermId, 3>;  ///< in the component order of its index
    static constexpr TermId kAny = UINT32_MAX;

    /// The id of the term with this key, added when new. Only before finish().
    TermId intern(std::string_view key) { return intern(key, hash_key(key)); }
    /// The id of the term with this key, or kAny when the data has no such term.
    TermId find(std::string_view key) const;
    std::string_view key(TermId id) const { return keys_[id]; }
    std::size_t num_terms() const { return keys_.size(); }

    /// Adds a triple (a repeat counts once). Only before finish().
    void add(TermId s, TermId p, TermId o) { spo_.push_back({s, p, o}); }
    /// Adds the terms and triples of `part` (read apart, e.g. from another file on another
    /// thread), after those already here. Only before finish() of either.
    void merge(const TripleStore& part);
    /// Room for `n` triples in all, before adding or merging them.
    void reserve(std::size_t n) { spo_.reserve(n); }
    /// Removes the repeated triples and builds the indexes.
    void finish();
    std::size_t num_triples() const { return spo_.size(); }

    /// The triples that match a pattern (kAny: any term), as a range of one index.
    struct Matches {
        const Triple* begin = nullptr;
        const Triple* end = nullptr;
        /// Where subject, predicate and object sit in each Triple of the range.
        std::array<int, 3> position{0, 1, 2};
    };
    Matches match(TermId s, TermId p, TermId o) const;
    bool contains(TermId s, TermId p, TermId o) const;

    /// How a predicate is used, for ordering the patterns of a query (after finish()).
    struct PredicateStats {
        std::size_t num_triples = 0;
        std::size_t num_subjects = 0;  ///< distinct
        std::size_t num_objects = 0;   ///< distinct
    };
    /// Zero counts for a term that is no predicate of the data.
    PredicateStats predicate_stats(TermId p) const;
    std::size_t num_subjects() const { return num_subjects_; }  ///< distinct, over all triples
    std::size_t num_objects() const { return num_objects_; }    ///< distinct, over all triples

  private:
    static std::size_t hash_key(std::string_view key);
    TermId intern(std::string_view key, std::size_t hash);
    void grow();

    // Keys live in blocks that never move. The table is open addressing over the ids
    // (slot = id + 1, 0 empty), with each key's hash kept: most lookups of a load find their
    // term (one probe, one comparison), and a node-based map missed the cache on each.
    std::vector<std::unique_ptr<char[]>> blocks_;
    std::size_t block_used_ = 0;
    std::size_t block_size_ = 0;
    std::vector<std::string_view> keys_;
    std::vector<std::size_t> hashes_;
    std::vector<TermId> slots_;
    std::vector<Triple> spo_;  // (s, p, o) sorted
    std::vector<Triple> pos_;  // (p, o, s) sorted
    std::vector<Triple> osp_;  // (o, s, p) sorted
    // For each index, where the triples of each leading term start (#terms + 1): the range
    // of a term is two loads, not a binary search over the whole index.
    std::vector<std::uint32_t> spo_start_, pos_start_, osp_start_;
    // For each term used as a predicate: its distinct subjects and objects (finish()).
    std::vector<std::pair<TermId, PredicateStats>> predicates_;  // sorted by id
    std::size_t num_subjects_ = 0, num_objects_ = 0;
};

}  // namespace geotex::detail
