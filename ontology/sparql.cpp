// SPARQL over geotex output, embedded: Raptor2 reads the data files into geotex's indexed
// store (ontology/detail/sparql_data.*, triple_store.*), Rasqal 0.9.33 runs the query over it
// (ontology/detail/rasqal_source.*). This file runs the query: it checks the text first
// (ontology/detail/sparql_checks.*), rewrites what Rasqal lacks or gets wrong
// (sparql_paths.*, sparql_aggregates.*), orders the triple patterns (sparql_join_order.*),
// applies the solution modifiers after (solution_modifiers.*), and turns Rasqal's values
// into the rows of a QueryResult; query_result_writer.cpp writes them.

#include "ontology/sparql.hpp"

#include <rasqal.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/detail/c_handle.hpp"
#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "ontology/detail/message_log.hpp"
#include "ontology/detail/query_deadline.hpp"
#include "ontology/detail/raptor_handles.hpp"
#include "ontology/detail/rasqal_source.hpp"
#include "ontology/detail/solution_modifiers.hpp"
#include "ontology/detail/sparql_aggregates.hpp"
#include "ontology/detail/sparql_checks.hpp"
#include "ontology/detail/sparql_clauses.hpp"
#include "ontology/detail/sparql_data.hpp"
#include "ontology/detail/sparql_grouping.hpp"
#include "ontology/detail/sparql_join_order.hpp"
#include "ontology/detail/sparql_paths.hpp"
#include "ontology/detail/sparql_run.hpp"
#include "ontology/detail/triple_store.hpp"
#include "ontology/rdf_lexical.hpp"

namespace geotex {

namespace {

using detail::LogEntry;
using detail::MessageLog;
using detail::on_log_message;

// ---------------------------------------------------------------------------------------
// Owning handles for the C objects of Raptor (ontology/detail/raptor_handles.hpp) and Rasqal.

template <auto Free>
using Deleter = detail::CDeleter<Free>;
using detail::RaptorWorld;

using RasqalWorld = std::unique_ptr<rasqal_world, Deleter<rasqal_free_world>>;
using RasqalQuery = std::unique_ptr<rasqal_query, Deleter<rasqal_free_query>>;
using RasqalResults = std::unique_ptr<rasqal_query_results, Deleter<rasqal_free_query_results>>;

// ---------------------------------------------------------------------------------------
// N-Triples terms (QueryResult::terms, read back by the result writers in
// query_result_writer.cpp).

/// Appends `text` with the bytes for which `escape` answers true written by `write`; the
/// bytes between them are appended as runs (a term seldom holds one to escape).
template <class NeedsEscape, class Write>
void append_escaped(std::string& out, std::string_view text, NeedsEscape escape, Write write) {
    std::size_t run = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (!escape(c)) continue;
        out.append(text.data() + run, i - run);
        write(out, c);
        run = i + 1;
    }
    out.append(text.data() + run, text.size() - run);
}

/// Escapes a literal's lexical form the canonical N-Triples way: \" \\ \n \r, and \u00XX
/// for the other control characters (UTF-8 passes through).
void append_escaped_literal(std::string& out, std::string_view text) {
    append_escaped(
        out, text, [](unsigned char c) { return c < 0x20 || c == 0x7F || c == '"' || c == '\\'; },
        [](std::string& o, unsigned char c) {
            switch (c) {
                case '"':
                    o += "\\\"";
                    break;
                case '\\':
                    o += "\\\\";
                    break;
                case '\n':
                    o += "\\n";
                    break;
                case '\r':
                    o += "\\r";
                    break;
                default:
                    detail::append_u_escape(o, c);
            }
        });
}

/// Escapes the characters that an N-Triples IRIREF cannot hold as \u00XX.
void append_escaped_iri(std::string& out, std::string_view iri) {
    append_escaped(
        out, iri,
        [](unsigned char c) {
            switch (c) {
                case '<':
                case '>':
                case '"':
                case '{':
                case '}':
                case '|':
                case '^':
                case '`':
                case '\\':
                    return true;
                default:
                    return c <= 0x20 || c == 0x7F;
            }
        },
        [](std::string& o, unsigned char c) { detail::append_u_escape(o, c); });
}

std::string nt_iri(std::string_view iri) {
    std::string out = "<";
    append_escaped_iri(out, iri);
    out += '>';
    return out;
}

std::string nt_literal(std::string_view lexical, std::string_view language,
                       std::string_view datatype) {
    std::string out = "\"";
    append_escaped_literal(out, lexical);
    out += '"';
    if (!language.empty()) {
        out += '@';
        out += language;
    } else if (!datatype.empty()) {
        out += "^^";
        out += nt_iri(datatype);
    }
    return out;
}

/// The expected number of triples that a pattern matches (detail::PatternCost) in `store`.
double pattern_cost(const detail::TripleStore& store, const std::string& predicate,
                    bool subject_fixed, bool object_fixed) {
    auto per = [](std::size_t n, std::size_t d) {
        return d == 0 ? 0.0 : static_cast<double>(n) / static_cast<double>(d);
    };
    std::size_t n = store.num_triples(), subjects = store.num_subjects(),
                objects = store.num_objects();
    if (!predicate.empty()) {
        std::string key;
        detail::append_iri_key(key, predicate);
        const detail::TripleStore::TermId id = store.find(key);
        if (id == detail::TripleStore::kAny) return 0;  // no such predicate: nothing matches
        const detail::TripleStore::PredicateStats st = store.predicate_stats(id);
        n = st.num_triples;
        subjects = st.num_subjects;
        objects = st.num_objects;
    }
    if (subject_fixed && object_fixed) return std::min(1.0, per(n, std::max(subjects, objects)));
    if (subject_fixed) return per(n, subjects);
    if (object_fixed) return per(n, objects);
    return static_cast<double>(n);
}

// ---------------------------------------------------------------------------------------
// Results

std::string uri_text(raptor_uri* uri) {
    std::size_t len = 0;
    const unsigned char* s = raptor_uri_as_counted_string(uri, &len);
    return s ? std::string(reinterpret_cast<const char*>(s), len) : std::string();
}

/// The (row, term) pair of one bound value.
std::pair<std::string, std::string> convert_value(rasqal_literal* value) {
    if (!value) return {std::string(), std::string()};
    if (value->type == RASQAL_LITERAL_URI) {
        const std::string iri = uri_text(value->value.uri);
        return {"<" + iri + ">", nt_iri(iri)};
    }
    if (value->type == RASQAL_LITERAL_BLANK) {
        const std::string label(reinterpret_cast<const char*>(value->string), value->string_len);
        return {"_:" + label, "_:" + label};
    }
    std::size_t len = 0;
    int error = 0;
    const unsigned char* s = rasqal_literal_as_counted_string(value, &len, 0, &error);
    const std::string lexical =
        s ? std::string(reinterpret_cast<const char*>(s), len) : std::string();
    const std::string language = value->language ? value->language : "";
    std::string datatype;
    if (language.empty()) {
        if (raptor_uri* dt = rasqal_literal_datatype(value)) datatype = uri_text(dt);
    }
    return {lexical, nt_literal(lexical, language, datatype)};
}

/// convert_value and native_literal, done once for each of the store's own literals: they
/// live as long as the triple source, so their address names their term. A literal that
/// Rasqal computed may be freed and its address reused: it is converted each time.
class ValueTexts {
  public:
    explicit ValueTexts(const detail::RasqalTripleSource& source) : source_(source) {}
    ~ValueTexts() {
        for (auto& [value, native] : natives_) rasqal_free_literal(native);
    }
    ValueTexts(const ValueTexts&) = delete;
    ValueTexts& operator=(const ValueTexts&) = delete;

    const std::pair<std::string, std::string>& operator()(rasqal_literal* value) {
        if (!value || !source_.owns(value)) return scratch_ = convert_value(value);
        auto [at, added] = cache_.try_emplace(value);
        if (added) at->second = convert_value(value);
        return at->second;
    }
    /// A new reference to native_literal(value): for a typed literal of the store, one
    /// conversion per query rather than one per row.
    rasqal_literal* native(rasqal_literal* value) {
        if (!value || !source_.owns(value)) return detail::native_literal(value);
        auto [at, added] = natives_.try_emplace(value, nullptr);
        if (added) at->second = detail::native_literal(value);
        return rasqal_new_literal_from_literal(at->second);
    }

  private:
    const detail::RasqalTripleSource& source_;
    std::unordered_map<const rasqal_literal*, std::pair<std::string, std::string>> cache_;
    std::unordered_map<const rasqal_literal*, rasqal_literal*> natives_;  // owned references
    std::pair<std::string, std::string> scratch_;
};

}  // namespace

namespace {

/// Rasqal's query, prepared from `text`; throws ParseError with Rasqal's message.
RasqalQuery prepare_query(rasqal_world* world, MessageLog& log, const std::string& text) {
    RasqalQuery q(rasqal_new_query(world, "sparql11-query", nullptr));
    if (!q) throw InvalidInput("run_sparql: Rasqal has no SPARQL 1.1 query language");
    const std::size_t mark = log.entries.size();
    if (rasqal_query_prepare(q.get(), reinterpret_cast<const unsigned char*>(text.c_str()),
                             nullptr) != 0) {
        const LogEntry* error = log.first_error(mark);
        throw ParseError("SPARQL: " + (error ? error->text : std::string("syntax error")), "",
                         error ? error->line : 0, error ? error->column : 0);
    }
    return q;
}

/// The names of the GROUP BY keys that are plain variables.
std::vector<std::string> group_variables(rasqal_query* q) {
    std::vector<std::string> names;
    raptor_sequence* conditions = rasqal_query_get_group_conditions_sequence(q);
    const int size = conditions ? raptor_sequence_size(conditions) : 0;
    for (int i = 0; i < size; ++i) {
        const auto* e =
            static_cast<const rasqal_expression*>(raptor_sequence_get_at(conditions, i));
        if (e && e->op == RASQAL_EXPR_LITERAL && e->literal)
            if (const rasqal_variable* v = rasqal_literal_as_variable(e->literal))
                if (v->name) names.emplace_back(reinterpret_cast<const char*>(v->name));
    }
    return names;
}

}  // namespace

QueryResult run_sparql(const std::string& query, const std::vector<std::string>& data_files,
                       const QueryParams& params) {
    return detail::run_sparql_with(
        query,
        [&](detail::TripleStore& store, const detail::Deadline& deadline) {
            detail::load_data(data_files, store, deadline);
        },
        params);
}

QueryResult detail::run_sparql_with(const std::string& query_text, const DataLoader& load,
                                    const QueryParams& params) {
    if (!(params.timeout >= 0) || !std::isfinite(params.timeout))
        throw InvalidInput("run_sparql: the timeout must be a finite number of seconds >= 0");
    const detail::Deadline deadline =
        params.timeout > 0 ? detail::Deadline(params.timeout) : detail::Deadline();
    // A byte order mark is no part of the query (editors on Windows write one); the columns
    // of line 1 are then counted after it, as an editor shows them.
    const std::string query =
        query_text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? query_text.substr(3) : query_text;
    detail::refuse_service(query);
    detail::refuse_updates(query);
    detail::check_values_form(query);
    // Rasqal has no property paths: those that are a fixed set of triple patterns become
    // them, with new variables, which no result shows.
    std::string fresh_prefix;
    std::vector<detail::ConcatColumn> concat_columns;
    std::string text = detail::rewrite_aggregates(
        detail::rewrite_property_paths(query, &fresh_prefix), &concat_columns);

    MessageLog log;
    RaptorWorld raptor(raptor_new_world());
    if (!raptor) throw InvalidInput("run_sparql: Raptor could not start (out of memory?)");
    raptor_world_set_log_handler(raptor.get(), &log, on_log_message);
    if (raptor_world_open(raptor.get()) != 0)
        throw InvalidInput("run_sparql: Raptor could not start");

    // Declared after `raptor`, so destroyed before it: Rasqal uses the Raptor world to the end.
    RasqalWorld world(rasqal_new_world());
    if (!world) throw InvalidInput("run_sparql: Rasqal could not start (out of memory?)");
    rasqal_world_set_raptor(world.get(), raptor.get());
    rasqal_world_set_log_handler(world.get(), &log, on_log_message);
    if (rasqal_world_open(world.get()) != 0)
        throw InvalidInput("run_sparql: Rasqal could not start");

    RasqalQuery q = prepare_query(world.get(), log, text);
    const rasqal_query_verb verb = rasqal_query_get_verb(q.get());
    if (verb != RASQAL_QUERY_VERB_SELECT && verb != RASQAL_QUERY_VERB_ASK) {
        const char* name = verb == RASQAL_QUERY_VERB_CONSTRUCT  ? "CONSTRUCT"
                           : verb == RASQAL_QUERY_VERB_DESCRIBE ? "DESCRIBE"
                                                                : "this kind of";
        throw InvalidInput(std::string("only SELECT and ASK queries can be run, not ") + name +
                           " queries");
    }
    if (detail::has_service(rasqal_query_get_query_graph_pattern(q.get())))
        throw InvalidInput(
            "SERVICE is refused: geotex query reads only the data files it is given, never a URI");
    if (rasqal_query_get_data_graph(q.get(), 0) != nullptr)
        throw InvalidInput(
            "FROM and FROM NAMED are not supported: give the data files to query "
            "instead (their union is the default graph)");

    QueryResult result;
    // The projection of the query, not of the results: Rasqal's results know their
    // variables only once a row has been read, so an empty result would have none.
    std::vector<std::string> all_variables;
    if (raptor_sequence* projection = rasqal_query_get_bound_variable_sequence(q.get())) {
        const int size = raptor_sequence_size(projection);
        for (int i = 0; i < size; ++i) {
            const auto* v =
                static_cast<const rasqal_variable*>(raptor_sequence_get_at(projection, i));
            if (v && v->name) all_variables.emplace_back(reinterpret_cast<const char*>(v->name));
        }
    }
    for (const std::string& name : all_variables)
        if (name.compare(0, fresh_prefix.size(), fresh_prefix) != 0)
            result.variables.push_back(name);
    detail::SolutionModifiers modifiers =
        detail::plan_solution_modifiers(q.get(), result.variables);

    detail::TripleStore store;
    load(store, deadline);

    // The join order, from the data's statistics (the query was prepared once before, so that
    // its errors come before reading the data).
    const std::string ordered = detail::order_triple_patterns(
        text, [&](const std::string& predicate, bool subject_fixed, bool object_fixed) {
            return pattern_cost(store, predicate, subject_fixed, object_fixed);
        });
    if (ordered != text) {
        text = ordered;
        q = prepare_query(world.get(), log, text);
    }

    // Declared after the worlds, so destroyed before them; before the results, so destroyed
    // after them (both hold references to its literals).
    detail::RasqalTripleSource source(world.get(), store);
    if (!source.attach()) throw InvalidInput("run_sparql: Rasqal refused the triple store");
    source.set_deadline(&deadline);
    detail::DeadlineCheck rows_deadline(&deadline);
    // After each run: rows cut short by the deadline are no answer.
    auto check_time = [&] {
        if (source.timed_out() || rows_deadline.seen()) deadline.throw_timeout();
    };

    std::size_t mark = 0;
    auto execution_error = [&](const char* what) {
        check_time();  // a pattern cut short may make Rasqal fail: the time is the reason
        const LogEntry* error = log.first_error(mark);
        std::string message = std::string("Rasqal could not ") + what + " the query: " +
                              (error ? error->text : std::string("no reason given"));
        if (detail::mentions_minus(query))
            message += " (MINUS fails in Rasqal 0.9.33: use OPTIONAL { ... } FILTER(!BOUND(?x)))";
        return InvalidInput(message);
    };
    // One row of values (nullptr: unbound) of the projected variables, converted, with the
    // values that ORDER BY compares kept as Rasqal's literals (new references).
    ValueTexts texts(source);
    auto add_row = [&](detail::ResultRows& rows, const std::vector<rasqal_literal*>& values,
                       const detail::SolutionModifiers& m) {
        std::vector<std::string> cells, terms;
        cells.reserve(values.size());
        terms.reserve(values.size());
        for (rasqal_literal* value : values) {
            const auto& [cell, term] = texts(value);
            cells.push_back(cell);
            terms.push_back(term);
        }
        std::vector<rasqal_literal*> keys;
        keys.reserve(m.order.size());
        for (const auto& key : m.order) {
            rasqal_literal* l = values[key.first];
            keys.push_back(l ? texts.native(l) : nullptr);
        }
        rows.cells.push_back(std::move(cells));
        rows.terms.push_back(std::move(terms));
        rows.keys.push_back(std::move(keys));
    };
    // Runs `rq` (prepared from `rq_text`) without the modifiers that geotex applies itself.
    auto select_rows = [&](RasqalQuery& rq, const std::string& rq_text,
                           const detail::SolutionModifiers& m, detail::ResultRows& rows) {
        if (!m.order.empty())
            rq = prepare_query(world.get(), log, detail::remove_order_by(rq_text));
        detail::remove_solution_modifiers(rq.get(), m);
        source.allow_correlation(rq.get());
        mark = log.entries.size();
        RasqalResults results(rasqal_query_execute(rq.get()));
        if (!results) throw execution_error("run");
        if (!rasqal_query_results_is_bindings(results.get()))
            throw InvalidInput("only SELECT and ASK queries can be run");
        const std::size_t num_variables = result.variables.size();
        std::vector<rasqal_literal*> values(num_variables, nullptr);
        while (!rasqal_query_results_finished(results.get())) {
            if (rows_deadline.passed_now()) break;
            for (std::size_t i = 0; i < num_variables; ++i)
                values[i] = rasqal_query_results_get_binding_value_by_name(
                    results.get(),
                    reinterpret_cast<const unsigned char*>(result.variables[i].c_str()));
            add_row(rows, values, m);
            if (rasqal_query_results_next(results.get()) != 0) break;
        }
        check_time();
        if (log.first_error(mark)) throw execution_error("finish");
    };

    if (verb == RASQAL_QUERY_VERB_ASK) {
        source.allow_correlation(q.get());
        mark = log.entries.size();
        RasqalResults results(rasqal_query_execute(q.get()));
        if (!results) throw execution_error("run");
        const int value = rasqal_query_results_get_boolean(results.get());
        check_time();
        if (value < 0) throw execution_error("answer");
        result.is_boolean = true;
        result.boolean_value = value > 0;
        return result;
    }

    // A GROUP BY that geotex does itself (sparql_grouping.hpp): the rows of the WHERE clause
    // from Rasqal, grouped by term id. False when it must be left to Rasqal.
    auto group_rows = [&](const detail::GroupingPlan& plan, detail::ResultRows& rows) {
        const std::string ungrouped = detail::ungrouped_select(text, plan.inputs);
        if (ungrouped.empty()) return false;
        RasqalQuery uq = prepare_query(world.get(), log, ungrouped);
        source.allow_correlation(uq.get());
        mark = log.entries.size();
        RasqalResults results(rasqal_query_execute(uq.get()));
        if (!results) throw execution_error("run");
        detail::Grouper grouper(plan);
        const std::size_t n = plan.inputs.size();
        std::vector<rasqal_literal*> values(n);
        std::vector<std::uint32_t> ids(n);
        // Values that are no term of the data (computed ones) are told apart by their term.
        std::unordered_map<std::string, std::uint32_t> other_terms;
        const auto first_other = static_cast<std::uint32_t>(store.num_terms());
        while (!rasqal_query_results_finished(results.get())) {
            if (rows_deadline.passed_now()) break;
            for (std::size_t i = 0; i < n; ++i) {
                values[i] = rasqal_query_results_get_binding_value_by_name(
                    results.get(), reinterpret_cast<const unsigned char*>(plan.inputs[i].c_str()));
                ids[i] = source.id_of(values[i]);
                if (values[i] && ids[i] == detail::TripleStore::kAny)
                    ids[i] = other_terms
                                 .try_emplace(
                                     convert_value(values[i]).second,
                                     first_other + static_cast<std::uint32_t>(other_terms.size()))
                                 .first->second;
            }
            if (!grouper.add(values, ids)) return false;
            if (rasqal_query_results_next(results.get()) != 0) break;
        }
        check_time();
        if (log.first_error(mark)) throw execution_error("finish");
        std::vector<std::vector<rasqal_literal*>> groups;
        if (!grouper.finish(groups)) return false;
        for (const auto& group : groups) add_row(rows, group, modifiers);
        return true;
    };

    const std::vector<std::string> group_keys = group_variables(q.get());
    auto rows = std::make_unique<detail::ResultRows>();
    const std::optional<detail::GroupingPlan> plan =
        detail::plan_grouping(q.get(), result.variables);
    const bool grouped = plan && group_rows(*plan, *rows);
    if (!grouped) {
        rows = std::make_unique<detail::ResultRows>();
        select_rows(q, text, modifiers, *rows);
    }

    // Rasqal 0.9.33 answers a GROUP BY over no solution with one group whose keys are unbound
    // (SPARQL: no group, no row). Such a row is kept only if the WHERE clause has a solution.
    if (!grouped && !group_keys.empty() && rows->cells.size() == 1) {
        bool keys_unbound = true;
        for (std::size_t i = 0; i < result.variables.size(); ++i)
            if (std::find(group_keys.begin(), group_keys.end(), result.variables[i]) !=
                    group_keys.end() &&
                !rows->terms[0][i].empty())
                keys_unbound = false;
        const std::string ask = keys_unbound ? detail::where_clause_as_ask(text) : std::string();
        if (!ask.empty()) {
            RasqalQuery check = prepare_query(world.get(), log, ask);
            source.allow_correlation(check.get());
            mark = log.entries.size();
            RasqalResults answer(rasqal_query_execute(check.get()));
            if (!answer) throw execution_error("run");
            const int value = rasqal_query_results_get_boolean(answer.get());
            check_time();
            if (value < 0) throw execution_error("answer");
            if (value == 0) rows = std::make_unique<detail::ResultRows>();
        }
    }

    if (!detail::apply_solution_modifiers(modifiers, *rows)) {
        // An ORDER BY column of values of several kinds: Rasqal's own ORDER BY orders them.
        modifiers.order.clear();
        rows = std::make_unique<detail::ResultRows>();
        RasqalQuery again = prepare_query(world.get(), log, text);
        select_rows(again, text, modifiers, *rows);
        detail::apply_solution_modifiers(modifiers, *rows);
    }
    result.rows = std::move(rows->cells);
    result.terms = std::move(rows->terms);
    // The GROUP_CONCAT columns whose separator Rasqal would have ignored (rewrite_aggregates).
    for (const detail::ConcatColumn& c : concat_columns) {
        const auto at = std::find(result.variables.begin(), result.variables.end(), c.variable);
        if (at == result.variables.end()) continue;
        const auto column = static_cast<std::size_t>(at - result.variables.begin());
        for (std::size_t i = 0; i < result.rows.size(); ++i) {
            // Unbound: an error in the group (SPARQL's GROUP_CONCAT passes errors on).
            if (result.terms[i][column].empty()) continue;
            std::string& cell = result.rows[i][column];
            cell = detail::join_concat_parts(cell, c.separator);
            result.terms[i][column] = nt_literal(cell, "", "");
        }
    }
    return result;
}

}  // namespace geotex

// Rasqal 0.9.33 writes a double that it computes (AVG, SUM, arithmetic) with 15 significant
// digits and then cuts the mantissa at the last zero that follows another digit, even when
// non-zero digits come after it: the mean 0.080676369739619 comes out as "8.0E-2", and that
// text is the value it hands out. Its calls to this formatter go through the dynamic symbol
// table, so this definition, linked into the program that embeds Rasqal, replaces it: the
// shortest form that reads back to the same double, as the RDF writer writes doubles. Rasqal
// frees the text with free(); no exception may cross into its C code.
// (tests/test_sparql.cpp, "computed doubles", fails if the replacement stops taking effect.)
extern "C" unsigned char* rasqal_xsd_format_double(double d, size_t* len_p) {
    try {
        const std::string text = std::isfinite(d)
                                     ? geotex::rdf_detail::double_lexical(d, "a double")
                                 : std::isnan(d) ? "NaN"
                                 : d > 0         ? "INF"
                                                 : "-INF";
        auto* out = static_cast<unsigned char*>(std::malloc(text.size() + 1));
        if (!out) return nullptr;
        std::memcpy(out, text.c_str(), text.size() + 1);
        if (len_p) *len_p = text.size();
        return out;
    } catch (...) {
        return nullptr;
    }
}
