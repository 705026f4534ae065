#include "ontology/detail/sparql_grouping.hpp"

#include <algorithm>
#include <numeric>

#include "ontology/detail/solution_modifiers.hpp"

namespace geotex::detail {

namespace {

/// The variable that a plain-variable expression is, or nullptr.
const rasqal_variable* variable_of(const rasqal_expression* e) {
    if (!e || e->op != RASQAL_EXPR_LITERAL || !e->literal) return nullptr;
    return rasqal_literal_as_variable(e->literal);
}

std::string name_of(const rasqal_variable* v) {
    return v && v->name ? std::string(reinterpret_cast<const char*>(v->name)) : std::string();
}

std::size_t input_index(std::vector<std::string>& inputs, const std::string& name) {
    const auto at = std::find(inputs.begin(), inputs.end(), name);
    if (at != inputs.end()) return static_cast<std::size_t>(at - inputs.begin());
    inputs.push_back(name);
    return inputs.size() - 1;
}

/// The flags of Rasqal 0.9.33's GROUP BY tree: its groups are ordered, and told apart, by
/// rasqal_literal_compare with these, key by key.
constexpr int kGroupCompareFlags = RASQAL_COMPARE_URI;

}  // namespace

std::optional<GroupingPlan> plan_grouping(rasqal_query* query,
                                          const std::vector<std::string>& variables) {
    if (rasqal_query_get_verb(query) != RASQAL_QUERY_VERB_SELECT) return std::nullopt;
    raptor_sequence* conditions = rasqal_query_get_group_conditions_sequence(query);
    const int num_conditions = conditions ? raptor_sequence_size(conditions) : 0;
    if (num_conditions == 0) return std::nullopt;
    if (raptor_sequence* having = rasqal_query_get_having_conditions_sequence(query))
        if (raptor_sequence_size(having) > 0) return std::nullopt;

    GroupingPlan plan;
    for (int i = 0; i < num_conditions; ++i) {
        const std::string key = name_of(variable_of(
            static_cast<const rasqal_expression*>(raptor_sequence_get_at(conditions, i))));
        if (key.empty()) return std::nullopt;  // an expression, or (?e AS ?v)
        if (std::find(plan.inputs.begin(), plan.inputs.end(), key) != plan.inputs.end())
            return std::nullopt;  // a key given twice
        plan.inputs.push_back(key);
    }
    plan.num_keys = plan.inputs.size();

    raptor_sequence* projection = rasqal_query_get_bound_variable_sequence(query);
    const int size = projection ? raptor_sequence_size(projection) : 0;
    if (static_cast<std::size_t>(size) != variables.size()) return std::nullopt;
    for (int i = 0; i < size; ++i) {
        const auto* v = static_cast<const rasqal_variable*>(raptor_sequence_get_at(projection, i));
        if (!v || name_of(v) != variables[static_cast<std::size_t>(i)]) return std::nullopt;
        GroupingPlan::Column column;
        const rasqal_expression* e = v->expression;
        if (!e) {
            const auto at =
                std::find(plan.inputs.begin(),
                          plan.inputs.begin() + static_cast<long>(plan.num_keys), name_of(v));
            if (at == plan.inputs.begin() + static_cast<long>(plan.num_keys))
                return std::nullopt;  // neither a key nor an aggregate: Rasqal's to judge
            column.input = static_cast<std::size_t>(at - plan.inputs.begin());
        } else {
            if (e->op == RASQAL_EXPR_MIN)
                column.op = GroupingPlan::Op::Min;
            else if (e->op == RASQAL_EXPR_MAX)
                column.op = GroupingPlan::Op::Max;
            else if (e->op == RASQAL_EXPR_SAMPLE)
                column.op = GroupingPlan::Op::Sample;
            else
                return std::nullopt;
            // DISTINCT changes nothing for these three; an expression argument is Rasqal's.
            const std::string argument = name_of(variable_of(e->arg1));
            if (argument.empty() || e->args) return std::nullopt;
            column.input = input_index(plan.inputs, argument);
        }
        plan.columns.push_back(column);
    }
    return plan;
}

std::size_t Grouper::KeyHash::operator()(const std::vector<std::uint32_t>& key) const {
    std::size_t h = key.size();
    for (std::uint32_t id : key) h = (h ^ id) * 0x100000001b3ULL + (h >> 29);
    return h;
}

Grouper::Grouper(const GroupingPlan& plan)
    : plan_(plan), first_of_kind_(plan.num_keys, nullptr), scratch_(plan.num_keys) {}

Grouper::~Grouper() {
    for (Group& g : groups_) {
        for (rasqal_literal* l : g.keys) rasqal_free_literal(l);
        for (std::size_t c = 0; c < g.values.size(); ++c)
            if (g.values[c] && plan_.columns[c].op != GroupingPlan::Op::Key)
                rasqal_free_literal(g.values[c]);
    }
    for (auto& [id, l] : natives_) rasqal_free_literal(l);
}

rasqal_literal* Grouper::native(std::uint32_t id, rasqal_literal* value) {
    auto [at, added] = natives_.try_emplace(id, nullptr);
    if (added) at->second = native_literal(value);
    return at->second;
}

bool Grouper::add(const std::vector<rasqal_literal*>& values,
                  const std::vector<std::uint32_t>& ids) {
    for (std::size_t k = 0; k < plan_.num_keys; ++k) {
        if (!values[k]) return false;
        scratch_[k] = ids[k];
    }
    auto [at, added] = index_.try_emplace(scratch_, groups_.size());
    if (added) {
        for (std::size_t k = 0; k < plan_.num_keys; ++k) {
            rasqal_literal* key = native(ids[k], values[k]);
            if (!first_of_kind_[k])
                first_of_kind_[k] = key;
            else if (!same_kind(key, first_of_kind_[k]))
                return false;
        }
        Group g;
        g.key_ids = scratch_;
        for (std::size_t k = 0; k < plan_.num_keys; ++k)
            g.keys.push_back(rasqal_new_literal_from_literal(values[k]));
        g.values.assign(plan_.columns.size(), nullptr);
        g.compared.assign(plan_.columns.size(), nullptr);
        g.failed.assign(plan_.columns.size(), 0);
        for (std::size_t c = 0; c < plan_.columns.size(); ++c)
            if (plan_.columns[c].op == GroupingPlan::Op::Key)
                g.values[c] = g.keys[plan_.columns[c].input];
        groups_.push_back(std::move(g));
    }
    step(groups_[at->second], values, ids);
    return true;
}

// The fold of Rasqal 0.9.33's MIN, MAX and SAMPLE: an unbound value is skipped (SPARQL's
// ListEvalE); SAMPLE keeps the first value; MIN and MAX compare the values as Rasqal holds
// them while it runs (native_literal) with flags 0, keep the current value on a tie, and a
// comparison error leaves the aggregate without a value.
void Grouper::step(Group& group, const std::vector<rasqal_literal*>& values,
                   const std::vector<std::uint32_t>& ids) {
    for (std::size_t c = 0; c < plan_.columns.size(); ++c) {
        const GroupingPlan::Column& column = plan_.columns[c];
        rasqal_literal* l = values[column.input];
        if (column.op == GroupingPlan::Op::Key || !l || group.failed[c]) continue;
        rasqal_literal*& current = group.values[c];
        if (current && column.op == GroupingPlan::Op::Sample) continue;
        rasqal_literal* compared = native(ids[column.input], l);
        bool replace = !current;
        if (current) {
            int error = 0;
            const int order = rasqal_literal_compare(group.compared[c], compared, 0, &error);
            if (error) {
                group.failed[c] = 1;
                rasqal_free_literal(current);
                current = nullptr;
                continue;
            }
            replace = column.op == GroupingPlan::Op::Min ? order > 0 : order < 0;
        }
        if (replace) {
            if (current) rasqal_free_literal(current);
            current = rasqal_new_literal_from_literal(l);
            group.compared[c] = compared;
        }
    }
}

bool Grouper::finish(std::vector<std::vector<rasqal_literal*>>& rows) {
    rows.clear();
    // Rasqal's tree orders the groups by their keys, compared one after the other. Each key
    // column's distinct terms are ranked once (values of one kind, checked in add, make the
    // comparison a strict weak order), and the groups sorted by their ranks. Two terms that
    // compare equal would be one group in Rasqal's tree: then Rasqal groups.
    const std::size_t num_keys = plan_.num_keys, n = groups_.size();
    std::vector<int> ranks(n * num_keys);
    for (std::size_t k = 0; k < num_keys; ++k) {
        std::unordered_map<std::uint32_t, std::size_t> index;  // term id -> distinct value
        std::vector<rasqal_literal*> distinct;
        std::vector<std::size_t> of_group(n);
        for (std::size_t g = 0; g < n; ++g) {
            const auto [at, added] = index.try_emplace(groups_[g].key_ids[k], distinct.size());
            if (added) distinct.push_back(native(groups_[g].key_ids[k], groups_[g].keys[k]));
            of_group[g] = at->second;
        }
        std::vector<int> distinct_ranks;
        bool tie = false;
        if (!rank_literals(distinct, kGroupCompareFlags, distinct_ranks, tie) || tie) return false;
        for (std::size_t g = 0; g < n; ++g) ranks[g * num_keys + k] = distinct_ranks[of_group[g]];
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::lexicographical_compare(&ranks[a * num_keys], &ranks[a * num_keys] + num_keys,
                                            &ranks[b * num_keys], &ranks[b * num_keys] + num_keys);
    });
    rows.reserve(n);
    for (std::size_t g : order) rows.push_back(groups_[g].values);
    return true;
}

}  // namespace geotex::detail
