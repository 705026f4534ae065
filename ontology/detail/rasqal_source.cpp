#include "ontology/detail/rasqal_source.hpp"

#include <algorithm>
#include <cstring>
#include <new>
#include <string>
#include <string_view>

namespace geotex::detail {

namespace {

using TermId = TripleStore::TermId;

std::string_view uri_view(raptor_uri* uri) {
    std::size_t len = 0;
    const unsigned char* s = raptor_uri_as_counted_string(uri, &len);
    return s ? std::string_view(reinterpret_cast<const char*>(s), len) : std::string_view();
}

/// A NUL-terminated copy in memory that Rasqal frees (it takes the strings of the literals
/// it is given).
unsigned char* rasqal_copy(std::string_view text) {
    auto* out = static_cast<unsigned char*>(rasqal_alloc_memory(text.size() + 1));
    if (!out) return nullptr;
    if (!text.empty()) std::memcpy(out, text.data(), text.size());
    out[text.size()] = '\0';
    return out;
}

/// The key of a literal's RDF term; false for what is no RDF term (a variable, a pattern).
bool term_key(rasqal_literal* value, std::string& key) {
    key.clear();
    switch (value->type) {
        case RASQAL_LITERAL_URI:
            append_iri_key(key, uri_view(value->value.uri));
            return true;
        case RASQAL_LITERAL_BLANK:
            append_blank_key(key, std::string_view(reinterpret_cast<const char*>(value->string),
                                                   value->string_len));
            return true;
        case RASQAL_LITERAL_VARIABLE:
        case RASQAL_LITERAL_PATTERN:
        case RASQAL_LITERAL_QNAME:
        case RASQAL_LITERAL_UNKNOWN:
            return false;
        default: {
            raptor_uri* datatype = rasqal_literal_datatype(value);
            append_literal_key(
                key,
                std::string_view(reinterpret_cast<const char*>(value->string), value->string_len),
                value->language ? std::string_view(value->language) : std::string_view(),
                datatype ? uri_view(datatype) : std::string_view());
            return true;
        }
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// One triple pattern being matched: a range of one index of the store.

struct PatternMatch {
    RasqalTripleSource* source = nullptr;
    bool correlated = false;  // a pattern of the query itself, not of a subquery
    const std::vector<rasqal_expression*>* filters = nullptr;  // pushed FILTERs, or nullptr
    TripleStore::Matches matches;
    const TripleStore::Triple* at = nullptr;
    std::array<const rasqal_variable*, 3> bound{};  // the variables it has given values
    int num_bound = 0;
};

namespace {

rasqal_triple_parts bind_match(rasqal_triples_match* rtm, void*, rasqal_variable* bindings[4],
                               rasqal_triple_parts parts) {
    auto* m = static_cast<PatternMatch*>(rtm->user_data);
    const TripleStore::Triple& t = *m->at;
    const TermId spo[3] = {t[m->matches.position[0]], t[m->matches.position[1]],
                           t[m->matches.position[2]]};
    static const rasqal_triple_parts flags[3] = {RASQAL_TRIPLE_SUBJECT, RASQAL_TRIPLE_PREDICATE,
                                                 RASQAL_TRIPLE_OBJECT};
    // A variable repeated in the pattern (?x ?p ?x) binds once and must take equal terms.
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < i; ++j)
            if (bindings[i] && bindings[i] == bindings[j] && (parts & flags[i]) && spo[i] != spo[j])
                return static_cast<rasqal_triple_parts>(0);
    for (int i = 0; i < 3; ++i) {
        if (!bindings[i] || !(parts & flags[i])) continue;
        bool repeated = false;
        for (int j = 0; j < i; ++j) repeated = repeated || bindings[j] == bindings[i];
        if (repeated) continue;
        rasqal_literal* value = m->source->literal(spo[i]);
        if (!value) return static_cast<rasqal_triple_parts>(0);
        rasqal_variable_set_value(bindings[i], rasqal_new_literal_from_literal(value));
        if (m->correlated) {
            m->source->note_binding(bindings[i], value, spo[i], m);
            const auto end = m->bound.begin() + m->num_bound;
            if (std::find(m->bound.begin(), end, bindings[i]) == end)
                m->bound[static_cast<std::size_t>(m->num_bound++)] = bindings[i];
        }
    }
    // A row that a pushed FILTER rejects goes no further (Rasqal asks for the next triple).
    if (m->filters && !m->source->passes(*m->filters)) return static_cast<rasqal_triple_parts>(0);
    // Rasqal reads 0 as "this triple does not match": a pattern whose variables all had
    // values before (see part_id) binds nothing and still matches.
    return parts;
}

void next_match(rasqal_triples_match* rtm, void*) {
    auto* m = static_cast<PatternMatch*>(rtm->user_data);
    if (m->at != m->matches.end) ++m->at;
    // Out of time: the pattern ends here, and so do the joins around it (each of their
    // patterns ends at its next step), so that Rasqal returns soon.
    if (m->source->out_of_time()) m->at = m->matches.end;
}

int is_end(rasqal_triples_match* rtm, void*) {
    const auto* m = static_cast<PatternMatch*>(rtm->user_data);
    return m->at == m->matches.end;
}

void finish_match(rasqal_triples_match* rtm, void*) {
    auto* m = static_cast<PatternMatch*>(rtm->user_data);
    if (m) {
        for (int i = 0; i < m->num_bound; ++i)
            m->source->forget_binding(m->bound[static_cast<std::size_t>(i)], m);
        m->source->release_match(m);
    }
    rtm->user_data = nullptr;
}

/// The store's id of a part of a pattern (kAny: any term), and the variable that the
/// pattern binds there (nullptr: none). `missing` is set when the part is a term that the
/// data does not hold (nothing can match).
///
/// Rasqal marks in `binds` the variables that this pattern is to bind. Its own store then
/// clears their values and matches all the data, also on the right side of a join (an
/// OPTIONAL), which it runs again for each row of the left side: every pair of rows is
/// compared (measured: features-by-significance.rq over 100 objects, minutes). Where the
/// variable's value was given by a pattern of this store that is still on its row, it is
/// the value of the current left row, and the pattern matches that value alone, binding
/// nothing. Any other value (a subquery's, an aggregate's, one left over from a finished
/// pattern) is not trusted: cleared as Rasqal does, so that the rows are the same.
TermId part_id(RasqalTripleSource& source, rasqal_literal* part, bool binds, bool correlated,
               rasqal_variable** variable, bool& missing) {
    rasqal_variable* v = rasqal_literal_as_variable(part);
    *variable = v;
    rasqal_literal* value = v ? v->value : part;
    if (v && binds && value) {
        if (correlated && source.is_current(v)) {
            *variable = nullptr;
        } else {
            rasqal_variable_set_value(v, nullptr);
            value = nullptr;
        }
    }
    if (!value) return TripleStore::kAny;
    const TermId id = v ? source.value_id(v, value) : source.constant_id(part);
    if (id == TripleStore::kAny) missing = true;
    return id;
}

int init_triples_match(rasqal_triples_match* rtm, rasqal_triples_source*, void* user_data,
                       rasqal_triple_meta* meta, rasqal_triple* t) {
    auto* source = *static_cast<RasqalTripleSource**>(user_data);
    rtm->bind_match = bind_match;
    rtm->next_match = next_match;
    rtm->is_end = is_end;
    rtm->finish = finish_match;
    auto* m = static_cast<PatternMatch*>(source->acquire_match());
    if (!m) return 1;
    m->source = source;
    if (const RasqalTripleSource::PatternInfo* info = source->pattern_info(t)) {
        m->correlated = info->correlated;
        if (!info->filters.empty()) m->filters = &info->filters;
    }
    rtm->user_data = m;

    bool missing = false;
    const TermId s = part_id(*source, t->subject, meta->parts & RASQAL_TRIPLE_SUBJECT,
                             m->correlated, &meta->bindings[0], missing);
    const TermId p = part_id(*source, t->predicate, meta->parts & RASQAL_TRIPLE_PREDICATE,
                             m->correlated, &meta->bindings[1], missing);
    const TermId o = part_id(*source, t->object, meta->parts & RASQAL_TRIPLE_OBJECT, m->correlated,
                             &meta->bindings[2], missing);
    // The data is the default graph alone: a GRAPH pattern matches nothing.
    meta->bindings[3] = nullptr;
    if (!missing && !t->origin && !source->out_of_time())
        m->matches = source->store().match(s, p, o);
    m->at = m->matches.begin;
    return 0;
}

int triple_present(rasqal_triples_source*, void* user_data, rasqal_triple* t) {
    const auto* source = *static_cast<RasqalTripleSource**>(user_data);
    if (t->origin) return 0;
    const TermId s = source->id_of(t->subject);
    const TermId p = source->id_of(t->predicate);
    const TermId o = source->id_of(t->object);
    if (s == TripleStore::kAny || p == TripleStore::kAny || o == TripleStore::kAny) return 0;
    return source->store().contains(s, p, o) ? 1 : 0;
}

void free_triples_source(void*) {}  // the source belongs to run_sparql

int support_feature(void*, rasqal_triples_source_feature) { return 0; }

int new_triples_source(rasqal_query*, void* factory_user_data, void* user_data,
                       rasqal_triples_source* rts) {
    // Rasqal allocates user_data (factory.user_data_size bytes) for each query's source.
    *static_cast<RasqalTripleSource**>(user_data) =
        static_cast<RasqalTripleSource*>(factory_user_data);
    rts->version = 2;
    rts->init_triples_match = init_triples_match;
    rts->triple_present = triple_present;
    rts->free_triples_source = free_triples_source;
    rts->support_feature = support_feature;
    return 0;
}

int register_factory(rasqal_triples_source_factory* factory) {
    factory->version = 1;
    factory->user_data_size = sizeof(RasqalTripleSource*);
    factory->new_triples_source = new_triples_source;
    return 0;
}

}  // namespace

RasqalTripleSource::RasqalTripleSource(rasqal_world* world, const TripleStore& store)
    : world_(world), store_(store), literals_(store.num_terms(), nullptr) {}

RasqalTripleSource::~RasqalTripleSource() {
    for (rasqal_literal* l : literals_)
        if (l) rasqal_free_literal(l);
    if (evaluation_) rasqal_free_evaluation_context(evaluation_);
}

bool RasqalTripleSource::attach() {
    return rasqal_set_triples_source_factory(world_, register_factory, this) == 0;
}

rasqal_literal* RasqalTripleSource::literal(TermId id) {
    if (rasqal_literal* made = literals_[id]) return made;
    const TermParts term = split_term_key(store_.key(id));
    rasqal_literal* made = nullptr;
    switch (term.kind) {
        case TermKind::Iri: {
            raptor_uri* uri = raptor_new_uri_from_counted_string(
                rasqal_world_get_raptor(world_),
                reinterpret_cast<const unsigned char*>(term.text.data()), term.text.size());
            if (uri) made = rasqal_new_uri_literal(world_, uri);  // takes the URI
            break;
        }
        case TermKind::Blank:
            if (unsigned char* label = rasqal_copy(term.text))
                made = rasqal_new_simple_literal(world_, RASQAL_LITERAL_BLANK, label);
            break;
        case TermKind::Literal: {
            unsigned char* lexical = rasqal_copy(term.text);
            char* language = nullptr;
            if (!term.language.empty())
                language = reinterpret_cast<char*>(rasqal_copy(term.language));
            raptor_uri* datatype = nullptr;
            if (!term.datatype.empty())
                datatype = raptor_new_uri_from_counted_string(
                    rasqal_world_get_raptor(world_),
                    reinterpret_cast<const unsigned char*>(term.datatype.data()),
                    term.datatype.size());
            if (lexical && (term.language.empty() || language) &&
                (term.datatype.empty() || datatype)) {
                // Takes the three (and frees them on failure).
                made = rasqal_new_string_literal(world_, lexical, language, datatype, nullptr);
                // Rasqal measures the string with strlen(), which stops at a U+0000 of the
                // lexical form: the length is the key's (the results read it with
                // rasqal_literal_as_counted_string). Only while the literal holds our copy
                // (Rasqal may replace a typed literal's text with its canonical form).
                if (made && made->string == lexical &&
                    term.text.find('\0') != std::string_view::npos)
                    made->string_len = static_cast<unsigned int>(term.text.size());
            } else {
                rasqal_free_memory(lexical);
                rasqal_free_memory(language);
                if (datatype) raptor_free_uri(datatype);
            }
            break;
        }
    }
    if (!made) return nullptr;
    try {
        ids_.emplace(made, id);
    } catch (...) {
        rasqal_free_literal(made);
        return nullptr;
    }
    literals_[id] = made;
    return made;
}

namespace {

using PatternList = std::vector<std::pair<const rasqal_triple*, RasqalTripleSource::PatternInfo>>;

RasqalTripleSource::PatternInfo& info_of(PatternList& patterns, const rasqal_triple* t) {
    for (auto& [triple, info] : patterns)
        if (triple == t) return info;
    patterns.emplace_back(t, RasqalTripleSource::PatternInfo());
    return patterns.back().second;
}

/// The triples of a graph pattern and its sub-patterns, subqueries (SELECT) left out, marked
/// correlated.
void collect_triples(rasqal_graph_pattern* gp, PatternList& out) {
    if (!gp || rasqal_graph_pattern_get_operator(gp) == RASQAL_GRAPH_PATTERN_OPERATOR_SELECT)
        return;
    for (int i = 0;; ++i) {
        const rasqal_triple* t = rasqal_graph_pattern_get_triple(gp, i);
        if (!t) break;
        info_of(out, t).correlated = true;
    }
    for (int i = 0;; ++i) {
        rasqal_graph_pattern* sub = rasqal_graph_pattern_get_sub_graph_pattern(gp, i);
        if (!sub) break;
        collect_triples(sub, out);
    }
}

/// The variables of a FILTER expression; false when it cannot be evaluated early and again
/// with the same answer: an aggregate, RAND(), BNODE(), UUID(), NOW(), an IRI() resolved
/// against the query's base, an extension function.
bool filter_variables(rasqal_expression* e, std::vector<const rasqal_variable*>& variables) {
    struct Visit {
        std::vector<const rasqal_variable*>* variables;
        bool pushable = true;
    } visit{&variables};
    rasqal_expression_visit(
        e,
        [](void* user_data, rasqal_expression* x) -> int {
            auto* v = static_cast<Visit*>(user_data);
            switch (x->op) {
                case RASQAL_EXPR_COUNT:
                case RASQAL_EXPR_SUM:
                case RASQAL_EXPR_AVG:
                case RASQAL_EXPR_MIN:
                case RASQAL_EXPR_MAX:
                case RASQAL_EXPR_SAMPLE:
                case RASQAL_EXPR_GROUP_CONCAT:
                case RASQAL_EXPR_VARSTAR:
                case RASQAL_EXPR_RAND:
                case RASQAL_EXPR_BNODE:
                case RASQAL_EXPR_UUID:
                case RASQAL_EXPR_STRUUID:
                case RASQAL_EXPR_NOW:
                case RASQAL_EXPR_CURRENT_DATETIME:
                case RASQAL_EXPR_IRI:
                case RASQAL_EXPR_URI:
                case RASQAL_EXPR_FUNCTION:
                    v->pushable = false;
                    return 1;
                case RASQAL_EXPR_LITERAL:
                    if (x->literal)
                        if (const rasqal_variable* var = rasqal_literal_as_variable(x->literal))
                            v->variables->push_back(var);
                    return 0;
                default:
                    return 0;
            }
        },
        &visit);
    return visit.pushable;
}

/// Filter pushing: in a group that is one basic graph pattern (triples matched in order)
/// and FILTERs, a FILTER whose variables all occur in the triples is checked as soon as the
/// last of them has matched, rather than on whole rows: the rows it rejects are not
/// extended by the triples that follow (objects-sharing-concept.rq: half of 393k rows,
/// before three more triples each). The group's answer is the same: its FILTERs apply to
/// every row of the basic pattern, and Rasqal still applies them to the rows that pass.
void push_filters(rasqal_graph_pattern* gp, PatternList& out) {
    if (!gp || rasqal_graph_pattern_get_operator(gp) == RASQAL_GRAPH_PATTERN_OPERATOR_SELECT)
        return;
    std::vector<rasqal_graph_pattern*> subs;
    for (int i = 0;; ++i) {
        rasqal_graph_pattern* sub = rasqal_graph_pattern_get_sub_graph_pattern(gp, i);
        if (!sub) break;
        subs.push_back(sub);
        push_filters(sub, out);
    }
    if (rasqal_graph_pattern_get_operator(gp) != RASQAL_GRAPH_PATTERN_OPERATOR_GROUP) return;
    rasqal_graph_pattern* basic = nullptr;
    std::vector<rasqal_expression*> filters;
    for (rasqal_graph_pattern* sub : subs) {
        const rasqal_graph_pattern_operator op = rasqal_graph_pattern_get_operator(sub);
        if (op == RASQAL_GRAPH_PATTERN_OPERATOR_BASIC && !basic) {
            basic = sub;
        } else if (op == RASQAL_GRAPH_PATTERN_OPERATOR_FILTER) {
            if (rasqal_expression* e = rasqal_graph_pattern_get_filter_expression(sub))
                filters.push_back(e);
        } else {
            return;  // two basic patterns, an OPTIONAL, a UNION...: left to Rasqal
        }
    }
    if (!basic || filters.empty()) return;
    std::vector<rasqal_triple*> triples;
    for (int i = 0;; ++i) {
        rasqal_triple* t = rasqal_graph_pattern_get_triple(basic, i);
        if (!t) break;
        triples.push_back(t);
    }
    auto occurs_in = [](const rasqal_variable* v, const rasqal_triple* t) {
        for (rasqal_literal* part : {t->subject, t->predicate, t->object})
            if (part && rasqal_literal_as_variable(part) == v) return true;
        return false;
    };
    for (rasqal_expression* e : filters) {
        std::vector<const rasqal_variable*> variables;
        if (!filter_variables(e, variables)) continue;
        // The first triple after which every variable has occurred.
        std::size_t last = 0;
        bool all = true;
        for (const rasqal_variable* v : variables) {
            std::size_t k = 0;
            while (k < triples.size() && !occurs_in(v, triples[k])) ++k;
            if (k == triples.size()) all = false;
            last = std::max(last, k);
        }
        if (all && last < triples.size()) info_of(out, triples[last]).filters.push_back(e);
    }
}

}  // namespace

void RasqalTripleSource::allow_correlation(rasqal_query* query) {
    // The patterns and constants of the query that ran before may be freed, their addresses
    // reused.
    patterns_.clear();
    constants_.clear();
    collect_triples(rasqal_query_get_query_graph_pattern(query), patterns_);
    push_filters(rasqal_query_get_query_graph_pattern(query), patterns_);
}

const RasqalTripleSource::PatternInfo* RasqalTripleSource::pattern_info(
    const rasqal_triple* t) const {
    for (const auto& [triple, info] : patterns_)
        if (triple == t) return &info;
    return nullptr;
}

bool RasqalTripleSource::passes(const std::vector<rasqal_expression*>& filters) {
    if (!evaluation_) {
        // SPARQL's comparison rules, as Rasqal's own FILTER evaluates them.
        evaluation_ = rasqal_new_evaluation_context(world_, nullptr, RASQAL_COMPARE_XQUERY);
        if (!evaluation_) return true;
    }
    for (rasqal_expression* e : filters) {
        int error = 0;
        rasqal_literal* value = rasqal_expression_evaluate2(e, evaluation_, &error);
        const bool is_false =
            value && !error && value->type == RASQAL_LITERAL_BOOLEAN && value->value.integer == 0;
        if (value) rasqal_free_literal(value);
        if (is_false) return false;
    }
    return true;
}

TermId RasqalTripleSource::value_id(const rasqal_variable* v, rasqal_literal* value) const {
    // Our literals live as long as this source, so a value that is one of them has its id
    // whether or not the pattern that gave it is still on its row.
    for (const Binding& b : live_)
        if (b.variable == v && b.value == value) return b.id;
    return id_of(value);
}

// A query has a few dozen variables and constants at most: linear searches in small
// vectors beat any map here (they run for every triple pattern matched).

void RasqalTripleSource::note_binding(const rasqal_variable* v, const rasqal_literal* value,
                                      TermId id, const void* pattern) {
    for (Binding& b : live_)
        if (b.variable == v) {
            b.pattern = pattern;
            b.value = value;
            b.id = id;
            return;
        }
    live_.push_back({v, pattern, value, id});
}

void RasqalTripleSource::forget_binding(const rasqal_variable* v, const void* pattern) {
    for (Binding& b : live_)
        if (b.variable == v && b.pattern == pattern) b.pattern = nullptr;
}

bool RasqalTripleSource::is_current(const rasqal_variable* v) const {
    for (const Binding& b : live_)
        if (b.variable == v) return b.pattern && v->value && b.value == v->value;
    return false;
}

TermId RasqalTripleSource::constant_id(rasqal_literal* constant) {
    for (const auto& [l, id] : constants_)
        if (l == constant) return id;
    const TermId id = id_of(constant);
    constants_.emplace_back(constant, id);
    return id;
}

void* RasqalTripleSource::acquire_match() {
    if (free_matches_.empty()) {
        matches_.push_back(std::make_unique<PatternMatch>());
        return matches_.back().get();
    }
    PatternMatch* m = free_matches_.back();
    free_matches_.pop_back();
    *m = PatternMatch();
    return m;
}

void RasqalTripleSource::release_match(void* m) {
    free_matches_.push_back(static_cast<PatternMatch*>(m));
}

TermId RasqalTripleSource::id_of(rasqal_literal* value) const {
    if (!value) return TripleStore::kAny;
    // The values that Rasqal copies from the store are the same objects (it counts
    // references): no key to build for them.
    if (const auto found = ids_.find(value); found != ids_.end()) return found->second;
    if (!term_key(value, key_)) return TripleStore::kAny;
    return store_.find(key_);
}

}  // namespace geotex::detail
