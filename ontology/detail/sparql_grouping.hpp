#pragma once
// GROUP BY with MIN, MAX and SAMPLE done by geotex on the rows of the WHERE clause, instead of
// by Rasqal 0.9.33, which copies every row into a tree of literal sequences and then steps
// its aggregates row by row (objects-sharing-concept.rq over 100 objects: 194k rows in 50,883
// groups, most of the query's time in malloc). Here a row is a few term ids in a hash map.
// The groups and their values are Rasqal's own: the same rows, folded in the same order with
// its comparison, groups ordered as its tree orders them; where that cannot be promised (an
// unbound key, keys of several kinds, two keys that Rasqal's comparison finds equal) Rasqal
// groups. Include only from .cpp files: it brings in rasqal.h.

#include <rasqal.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace geotex::detail {

/// What geotex does for a query it groups.
struct GroupingPlan {
    enum class Op { Key, Min, Max, Sample };
    struct Column {
        Op op = Op::Key;
        std::size_t input = 0;  ///< the input (the key, or the aggregated variable) it comes from
    };
    /// The variables read from each row of the WHERE clause: the GROUP BY keys first, then
    /// the aggregated variables (each once).
    std::vector<std::string> inputs;
    std::size_t num_keys = 0;
    std::vector<Column> columns;  ///< one per projected variable, in the projection's order
};

/// The plan for the prepared `query` whose projected variables are `variables`, when geotex
/// can group it: a GROUP BY of plain variables, no HAVING, and every projected variable a
/// key or (MIN(?v) AS ?x), (MAX(?v) AS ?x), (SAMPLE(?v) AS ?x). Nothing otherwise: Rasqal
/// groups.
std::optional<GroupingPlan> plan_grouping(rasqal_query* query,
                                          const std::vector<std::string>& variables);

/// The groups of the rows of the WHERE clause, given one by one.
class Grouper {
  public:
    explicit Grouper(const GroupingPlan& plan);
    ~Grouper();
    Grouper(const Grouper&) = delete;
    Grouper& operator=(const Grouper&) = delete;

    /// One row: the values of plan.inputs (nullptr: unbound) and, for each, an id that is the
    /// same for the same RDF term and different for different ones (the values are kept as new
    /// references). Returns false when geotex cannot
    /// group as Rasqal does (a key unbound, a key column holding values of several kinds):
    /// the caller lets Rasqal group the query instead.
    bool add(const std::vector<rasqal_literal*>& values, const std::vector<std::uint32_t>& ids);

    /// The groups in Rasqal's order, each the values of the projected columns (nullptr where
    /// an aggregate has no value: no bound value, or a comparison error), which live as long
    /// as this object. False when two different terms of a key column are equal to Rasqal's
    /// comparison (it would make their groups one) or do not compare.
    bool finish(std::vector<std::vector<rasqal_literal*>>& rows);

  private:
    struct KeyHash {
        std::size_t operator()(const std::vector<std::uint32_t>& key) const;
    };
    struct Group {
        std::vector<std::uint32_t> key_ids;
        std::vector<rasqal_literal*> keys;
        std::vector<rasqal_literal*> values;    ///< per column: the key or the aggregate so far
        std::vector<rasqal_literal*> compared;  ///< per column: values[c] as compared (native)
        std::vector<char> failed;               ///< per column: the fold met a comparison error
    };
    /// native_literal of the term `id`, made once.
    rasqal_literal* native(std::uint32_t id, rasqal_literal* value);
    void step(Group& group, const std::vector<rasqal_literal*>& values,
              const std::vector<std::uint32_t>& ids);

    const GroupingPlan& plan_;
    std::unordered_map<std::vector<std::uint32_t>, std::size_t, KeyHash> index_;
    std::vector<Group> groups_;
    std::unordered_map<std::uint32_t, rasqal_literal*> natives_;  ///< term id -> native_literal
    std::vector<const rasqal_literal*> first_of_kind_;  ///< per key: a native value, for kinds
    std::vector<std::uint32_t> scratch_;
};

}  // namespace geotex::detail
