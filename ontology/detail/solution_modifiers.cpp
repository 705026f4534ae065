#include "ontology/detail/solution_modifiers.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <set>

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
/// uses): an unbound value first, whatever the direction; then rasqal_literal_compare with
/// the flags of a SPARQL query; a comparison error (values of kinds SPARQL does not order)
/// ends the comparison as a tie. `error` is set on such an error.
int compare_keys(const std::vector<rasqal_literal*>& a, const std::vector<rasqal_literal*>& b,
                 const std::vector<std::pair<std::size_t, bool>>& order, bool& error) {
    for (std::size_t i = 0; i < order.size(); ++i) {
        rasqal_literal* x = a[i];
        rasqal_literal* y = b[i];
        if (!x || !y) {
            if (!x && !y) continue;
            return x ? 1 : -1;
        }
        int failed = 0;
        int result = rasqal_literal_compare(x, y, RASQAL_COMPARE_XQUERY | RASQAL_COMPARE_URI,
                                            &failed);
        if (failed) {
            error = true;
            return 0;
        }
        if (result != 0) return order[i].second ? -result : result;
    }
    return 0;
}

struct ComparisonFailed {};

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
            if (l->type != first->type) return false;
            const bool same_language =
                (!l->language && !first->language) ||
                (l->language && first->language && std::strcmp(l->language, first->language) == 0);
            const bool same_datatype =
                (!l->datatype && !first->datatype) ||
                (l->datatype && first->datatype && raptor_uri_equals(l->datatype, first->datatype));
            if (!same_language || !same_datatype) return false;
        }
    }
    return true;
}

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
                static_cast<rasqal_expression*>(raptor_sequence_get_at(conditions, i)),
                descending);
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
        std::vector<std::size_t> order(rows.cells.size());
        std::iota(order.begin(), order.end(), std::size_t{0});
        try {
            std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
                bool error = false;
                const int c = compare_keys(rows.keys[a], rows.keys[b], m.order, error);
                if (error) throw ComparisonFailed{};
                return c < 0;
            });
        } catch (const ComparisonFailed&) {
            return false;
        }
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
