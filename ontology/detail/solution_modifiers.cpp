#include "ontology/detail/solution_modifiers.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <set>
#include <unordered_map>

namespace geotex::detail {

namespace {

/// The variable an ORDER BY condition sorts by, or nullptr for an expression.
const rasqal_variable* order_variable(const rasqal_expression* e, bool& descending) {
    descending = false;
    if (e && (e->op == RASQAL_EXPR_ORDER_COND_ASC || e->op == RASQAL_EXPR_ORDER_COND_DESC)) {
        descending = e->op == RASQAL_EXPR_ORDER_COND_DESC;
        e = e->arg1;
    }
    if (!e || e->op != RASQAL_EXPR_LITERAL || !e->literal) return nullptr;
    return rasqal_literal_as_variable(e->literal);
}

/// Rasqal 0.9.33's comparison of two rows by their ORDER BY values (the one its ORDER BY
/// uses), on the ranks of the values (rank_literals with kOrderCompareFlags; -1 unbound): an
/// unbound value first, whatever the direction; then the ranks, reversed when descending.
int compare_ranks(const int* a, const int* b,
                  const std::vector<std::pair<std::size_t, bool>>& order) {
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (a[i] == b[i]) continue;
        if (a[i] < 0 || b[i] < 0) return a[i] < 0 ? -1 : 1;
        const int c = a[i] < b[i] ? -1 : 1;
        return order[i].second ? -c : c;
    }
    return 0;
}

/// The flags of a SPARQL query's comparison in Rasqal 0.9.33's ORDER BY.
constexpr int kOrderCompareFlags = RASQAL_COMPARE_XQUERY | RASQAL_COMPARE_URI;

/// Whether each ORDER BY column holds values of one kind (one Rasqal type, one datatype and
/// one language, unbound values aside): Rasqal's comparison is then a strict weak order, and
/// a stable sort gives the order of its own ORDER BY. Between kinds it is not (a string, a
/// number and an IRI do not compare transitively), and the order its tree then gives is
/// left to Rasqal.
bool all_of_one_kind(const ResultRows& rows, std::size_t num_keys) {
    for (std::size_t k = 0; k < num_keys; ++k) {
        const rasqal_literal* first = nullptr;
        for (const auto& row : rows.keys) {
            const rasqal_literal* l = row[k];
            if (!l) continue;
            if (!first) {
                first = l;
                continue;
            }
            if (!same_kind(l, first)) return false;
        }
    }
    return true;
}

}  // namespace

rasqal_literal* native_literal(rasqal_literal* value) {
    if (!value || value->type != RASQAL_LITERAL_STRING || !value->datatype || !value->string)
        return rasqal_new_literal_from_literal(value);
    const std::size_t n = value->string_len;
    auto* text = static_cast<unsigned char*>(rasqal_alloc_memory(n + 1));
    if (!text) return rasqal_new_literal_from_literal(value);
    std::memcpy(text, value->string, n);
    text[n] = 0;
    // Takes the text and the datatype (and frees them on failure).
    rasqal_literal* native = rasqal_new_string_literal(value->world, text, nullptr,
                                                       raptor_uri_copy(value->datatype), nullptr);
    if (native && native->type != RASQAL_LITERAL_STRING) return native;
    if (native) rasqal_free_literal(native);
    return rasqal_new_literal_from_literal(value);
}

bool rank_literals(const std::vector<rasqal_literal*>& values, int flags, std::vector<int>& ranks,
                   bool& tie) {
    tie = false;
    bool error = false;
    auto compare = [&](rasqal_literal* a, rasqal_literal* b) {
        int failed = 0;
        const int c = rasqal_literal_compare(a, b, flags, &failed);
        if (failed) error = true;
        return c;
    };
    std::vector<std::size_t> order(values.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // A stable sort (a merge) stays in bounds even if a comparison fails.
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return compare(values[a], values[b]) < 0;
    });
    ranks.assign(values.size(), 0);
    int rank = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (i > 0) {
            if (compare(values[order[i - 1]], values[order[i]]) == 0)
                tie = true;
            else
                ++rank;
        }
        ranks[order[i]] = rank;
    }
    return !error;
}

bool same_kind(const rasqal_literal* a, const rasqal_literal* b) {
    if (a->type != b->type) return false;
    const bool same_language =
        (!a->language && !b->language) ||
        (a->language && b->language && std::strcmp(a->language, b->language) == 0);
    const bool same_datatype =
        (!a->datatype && !b->datatype) ||
        (a->datatype && b->datatype && raptor_uri_equals(a->datatype, b->datatype));
    return same_language && same_datatype;
}

namespace {

template <class T>
void permute(std::vector<T>& v, const std::vector<std::size_t>& order) {
    std::vector<T> out;
    out.reserve(order.size());
    for (std::size_t i : order) out.push_back(std::move(v[i]));
    v.swap(out);
}

}  // namespace

SolutionModifiers plan_solution_modifiers(rasqal_query* query,
                                          const std::vector<std::string>& variables) {
    SolutionModifiers m;
    if (raptor_sequence* conditions = rasqal_query_get_order_conditions_sequence(query)) {
        const int size = raptor_sequence_size(conditions);
        std::vector<std::pair<std::size_t, bool>> order;
        for (int i = 0; i < size; ++i) {
            bool descending = false;
            const rasqal_variable* v = order_variable(
                static_cast<rasqal_expression*>(raptor_sequence_get_at(conditions, i)), descending);
            if (!v || !v->name) break;
            const auto at = std::find(variables.begin(), variables.end(),
                                      reinterpret_cast<const char*>(v->name));
            if (at == variables.end()) break;
            order.emplace_back(static_cast<std::size_t>(at - variables.begin()), descending);
        }
        if (size > 0 && static_cast<int>(order.size()) == size) m.order = std::move(order);
    }
    m.distinct = rasqal_query_get_distinct(query) != 0;
    if (m.any()) {
        m.limit = rasqal_query_get_limit(query);
        m.offset = std::max(0, rasqal_query_get_offset(query));
    }
    return m;
}

void remove_solution_modifiers(rasqal_query* query, const SolutionModifiers& m) {
    if (!m.any()) return;
    rasqal_query_set_distinct(query, 0);
    rasqal_query_set_limit(query, -1);
    rasqal_query_set_offset(query, -1);
}

ResultRows::~ResultRows() {
    for (auto& row : keys)
        for (rasqal_literal* l : row)
            if (l) rasqal_free_literal(l);
}

bool apply_solution_modifiers(const SolutionModifiers& m, ResultRows& rows) {
    if (!m.order.empty() && !all_of_one_kind(rows, m.order.size())) return false;
    if (m.distinct) {
        std::set<std::vector<std::string>> seen;
        std::vector<std::size_t> kept;
        for (std::size_t i = 0; i < rows.terms.size(); ++i)
            if (seen.insert(rows.terms[i]).second) kept.push_back(i);
        if (kept.size() < rows.terms.size()) {
            for (std::size_t i = 0, k = 0; i < rows.keys.size(); ++i) {
                if (k < kept.size() && kept[k] == i) {
                    ++k;
                    continue;
                }
                for (rasqal_literal* l : rows.keys[i])
                    if (l) rasqal_free_literal(l);
                rows.keys[i].clear();
            }
            permute(rows.cells, kept);
            permute(rows.terms, kept);
            permute(rows.keys, kept);
        }
    }
    if (!m.order.empty() && rows.cells.size() > 1) {
        // Each column's distinct values ranked once, then the rows sorted by their ranks: a
        // column holds few distinct values (objects, concepts), and comparing integers is
        // what makes a sort of 50,000 rows cheap.
        const std::size_t num_keys = m.order.size(), n = rows.keys.size();
        std::vector<int> ranks(n * num_keys, -1);
        for (std::size_t k = 0; k < num_keys; ++k) {
            std::unordered_map<const rasqal_literal*, std::size_t> index;
            std::vector<rasqal_literal*> distinct;
            std::vector<std::size_t> of_row(n, SIZE_MAX);
            for (std::size_t r = 0; r < n; ++r) {
                rasqal_literal* l = rows.keys[r][k];
                if (!l) continue;
                const auto [at, added] = index.try_emplace(l, distinct.size());
                if (added) distinct.push_back(l);
                of_row[r] = at->second;
            }
            std::vector<int> distinct_ranks;
            bool tie = false;
            if (!rank_literals(distinct, kOrderCompareFlags, distinct_ranks, tie)) return false;
            for (std::size_t r = 0; r < n; ++r)
                if (of_row[r] != SIZE_MAX) ranks[r * num_keys + k] = distinct_ranks[of_row[r]];
        }
        std::vector<std::size_t> order(n);
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return compare_ranks(&ranks[a * num_keys], &ranks[b * num_keys], m.order) < 0;
        });
        permute(rows.cells, order);
        permute(rows.terms, order);
        permute(rows.keys, order);
    }
    const std::size_t n = rows.cells.size();
    const std::size_t first = std::min(n, static_cast<std::size_t>(m.offset));
    const std::size_t last =
        m.limit < 0 ? n : std::min(n, first + static_cast<std::size_t>(m.limit));
    if (first == 0 && last == n) return true;
    for (std::size_t i = 0; i < n; ++i) {
        if (i >= first && i < last) continue;
        for (rasqal_literal* l : rows.keys[i])
            if (l) rasqal_free_literal(l);
        rows.keys[i].clear();
    }
    auto cut = [&](auto& v) {
        v.erase(v.begin() + static_cast<long>(last), v.end());
        v.erase(v.begin(), v.begin() + static_cast<long>(first));
    };
    cut(rows.cells);
    cut(rows.terms);
    cut(rows.keys);
    return true;
}

}  // namespace geotex::detail
