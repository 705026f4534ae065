#pragma once
// Rasqal's triple patterns answered from a TripleStore (ontology/detail/triple_store.hpp)
// instead of Rasqal's own store, a list that every triple pattern scans from the start.
// Include only from .cpp files: it brings in rasqal.h.

#include <rasqal.h>

#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "ontology/detail/query_deadline.hpp"
#include "ontology/detail/triple_store.hpp"

namespace geotex::detail {

struct PatternMatch;  // one triple pattern being matched (rasqal_source.cpp)

class RasqalTripleSource {
  public:
    /// `world` must be open and outlive this object; `store` must be finished and outlive it.
    RasqalTripleSource(rasqal_world* world, const TripleStore& store);
    ~RasqalTripleSource();
    RasqalTripleSource(const RasqalTripleSource&) = delete;
    RasqalTripleSource& operator=(const RasqalTripleSource&) = delete;

    /// Makes every query of the world match its triple patterns against the store. Returns
    /// false when Rasqal refuses the factory.
    bool attach();

    /// The term as a Rasqal literal (made once, owned here), or nullptr when out of memory.
    rasqal_literal* literal(TripleStore::TermId id);
    /// Whether `value` is one of the literals made by literal(), which live as long as this
    /// object (so that its address names its term).
    bool owns(const rasqal_literal* value) const { return ids_.count(value) > 0; }
    /// The store's id of a literal's term, or TripleStore::kAny when the data lacks it.
    TripleStore::TermId id_of(rasqal_literal* value) const;

    /// Prepares the execution of `query` (call before each): lets its triple patterns outside
    /// its subqueries use the values of the current row (see part_id in the .cpp; a
    /// subquery's patterns are left to Rasqal's own rules: its variables are those of the
    /// query, which Rasqal does not rename, and it runs once for all rows of a join), and
    /// moves each FILTER of a group that is one basic graph pattern and its FILTERs to the
    /// pattern after which all the filter's variables have values (see push_filters in the
    /// .cpp).
    void allow_correlation(rasqal_query* query);

    /// Bookkeeping of the values that the patterns of this store give to variables: a value
    /// is current while the pattern that gave it is still on that row (not finished, not
    /// moved on, not overwritten by another part of Rasqal).
    void note_binding(const rasqal_variable* v, const rasqal_literal* value, TripleStore::TermId id,
                      const void* pattern);
    void forget_binding(const rasqal_variable* v, const void* pattern);
    bool is_current(const rasqal_variable* v) const;
    /// The id of `value`, the value of `v`: from the bookkeeping when a pattern of this store
    /// gave it (no lookup in a map of all the terms), else id_of.
    TripleStore::TermId value_id(const rasqal_variable* v, rasqal_literal* value) const;
    /// id_of for a constant of a triple pattern, remembered for the query's execution.
    TripleStore::TermId constant_id(rasqal_literal* constant);
    /// The state of one triple pattern being matched, reused (one is made and freed for
    /// every pattern and row of a join).
    void* acquire_match();
    void release_match(void* match);
    /// What the execution knows of one triple pattern of the query (allow_correlation).
    struct PatternInfo {
        bool correlated = false;                  ///< outside a subquery
        std::vector<rasqal_expression*> filters;  ///< FILTERs to check once it has matched
    };
    /// nullptr for a pattern of a subquery without pushed filters.
    const PatternInfo* pattern_info(const rasqal_triple* t) const;
    /// Whether no filter of `filters` is false on the current values (an error or a value
    /// that is not a boolean counts as passing: Rasqal's own FILTER decides on those).
    bool passes(const std::vector<rasqal_expression*>& filters);

    /// Makes every pattern match nothing once `deadline` (which must outlive the queries) has
    /// passed; nullptr: no limit.
    void set_deadline(const Deadline* deadline) { deadline_ = DeadlineCheck(deadline); }
    /// Whether the deadline has passed (asked by the matching loop; reads the clock at times).
    bool out_of_time() { return deadline_.passed(); }
    /// Whether a pattern stopped because the deadline had passed: the rows are incomplete.
    bool timed_out() const { return deadline_.seen(); }

    const TripleStore& store() const { return store_; }
    rasqal_world* world() const { return world_; }

  private:
    rasqal_world* world_;
    const TripleStore& store_;
    std::vector<rasqal_literal*> literals_;  // #terms, nullptr until asked for
    std::unordered_map<const rasqal_literal*, TripleStore::TermId> ids_;  // of literals_
    mutable std::string key_;                                             // scratch of id_of
    struct Binding {
        const rasqal_variable* variable;
        const void* pattern;  // nullptr: the pattern is done
        const rasqal_literal* value;
        TripleStore::TermId id;  // of value
    };
    std::vector<Binding> live_;
    std::vector<std::pair<const rasqal_literal*, TripleStore::TermId>> constants_;
    std::vector<std::unique_ptr<PatternMatch>> matches_;
    std::vector<PatternMatch*> free_matches_;
    // A query has a few dozen patterns: a linear search beats a map (once per pattern start).
    std::vector<std::pair<const rasqal_triple*, PatternInfo>> patterns_;
    rasqal_evaluation_context* evaluation_ = nullptr;
    DeadlineCheck deadline_;
};

}  // namespace geotex::detail
