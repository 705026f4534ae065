// Tests of the indexed set of triples under `geotex query` (ontology/detail/triple_store.*).

#include <algorithm>
#include <catch2/catch.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "ontology/detail/triple_store.hpp"

using geotex::detail::TripleStore;
using Id = TripleStore::TermId;

namespace {

std::string iri(const std::string& x) {
    std::string key;
    geotex::detail::append_iri_key(key, x);
    return key;
}

/// The (s, p, o) of every match, sorted.
std::set<std::vector<Id>> matched(const TripleStore& store, Id s, Id p, Id o) {
    std::set<std::vector<Id>> out;
    const TripleStore::Matches m = store.match(s, p, o);
    for (const TripleStore::Triple* t = m.begin; t != m.end; ++t)
        out.insert({(*t)[m.position[0]], (*t)[m.position[1]], (*t)[m.position[2]]});
    return out;
}

}  // namespace

TEST_CASE("TripleStore: every pattern finds exactly the triples that a scan finds",
          "[ontology][sparql]") {
    TripleStore store;
    std::vector<Id> t;
    for (int i = 0; i < 7; ++i)
        t.push_back(store.intern(iri("http://ex.org/" + std::to_string(i))));
    // A small graph with repeated subjects, predicates and objects, and a triple twice.
    std::vector<std::vector<Id>> triples;
    for (int a = 0; a < 7; ++a)
        for (int b = 0; b < 3; ++b)
            for (int c = 0; c < 7; ++c)
                if ((a * 5 + b * 3 + c) % 4 == 0) triples.push_back({t[a], t[b], t[c]});
    // Added out of order (the indexes are sorted by finish()), one twice.
    std::vector<std::vector<Id>> shuffled = triples;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
    for (const auto& x : shuffled) store.add(x[0], x[1], x[2]);
    store.add(triples[0][0], triples[0][1], triples[0][2]);
    store.finish();
    CHECK(store.num_triples() == triples.size());

    const Id any = TripleStore::kAny;
    std::vector<Id> choices = t;
    choices.push_back(any);
    for (Id s : choices)
        for (Id p : choices)
            for (Id o : choices) {
                std::set<std::vector<Id>> expected;
                for (const auto& x : triples)
                    if ((s == any || x[0] == s) && (p == any || x[1] == p) &&
                        (o == any || x[2] == o))
                        expected.insert(x);
                INFO(s << " " << p << " " << o);
                CHECK(matched(store, s, p, o) == expected);
                if (s != any && p != any && o != any)
                    CHECK(store.contains(s, p, o) == !expected.empty());
            }
}

TEST_CASE("TripleStore: terms by key; a literal typed xsd:string is the simple literal",
          "[ontology][sparql]") {
    TripleStore store;
    std::string plain, typed, lang, lang_upper, number;
    geotex::detail::append_literal_key(plain, "x", "", "");
    geotex::detail::append_literal_key(typed, "x", "", "http://www.w3.org/2001/XMLSchema#string");
    geotex::detail::append_literal_key(lang, "x", "en-GB", "");
    geotex::detail::append_literal_key(lang_upper, "x", "EN-gb", "");
    geotex::detail::append_literal_key(number, "x", "", "http://www.w3.org/2001/XMLSchema#integer");
    CHECK(plain == typed);
    CHECK(lang == lang_upper);
    const Id a = store.intern(plain);
    CHECK(store.intern(typed) == a);
    CHECK(store.intern(number) != a);
    CHECK(store.find(lang) == TripleStore::kAny);
    CHECK(store.find(plain) == a);

    // The parts come back, the lexical form with any byte in it.
    std::string odd;
    geotex::detail::append_literal_key(odd, std::string("a\0b@^", 5), "",
                                       "https://w3id.org/geotex/ns#faceRanges");
    const auto parts = geotex::detail::split_term_key(store.key(store.intern(odd)));
    CHECK(parts.kind == geotex::detail::TermKind::Literal);
    CHECK(parts.text == std::string_view("a\0b@^", 5));
    CHECK(parts.datatype == "https://w3id.org/geotex/ns#faceRanges");
    CHECK(parts.language.empty());
    CHECK(geotex::detail::split_term_key(lang).language == "en-gb");
}

TEST_CASE("TripleStore: merging parts keeps one id per term and the set of triples",
          "[ontology][sparql]") {
    TripleStore one, two, merged;
    const Id a1 = one.intern(iri("a")), p1 = one.intern(iri("p")), b1 = one.intern(iri("b"));
    one.add(a1, p1, b1);
    const Id b2 = two.intern(iri("b")), p2 = two.intern(iri("p")), c2 = two.intern(iri("c"));
    two.add(b2, p2, c2);
    const Id a2 = two.intern(iri("a"));
    two.add(a2, p2, b2);  // the triple of `one` again
    merged.merge(one);
    merged.merge(two);
    merged.finish();
    CHECK(merged.num_terms() == 4);
    CHECK(merged.num_triples() == 2);
    CHECK(merged.key(0) == iri("a"));  // ids in reading order
    CHECK(merged.contains(merged.find(iri("b")), merged.find(iri("p")), merged.find(iri("c"))));
}

TEST_CASE("TripleStore: many terms (the table grows) keep their ids", "[ontology][sparql]") {
    TripleStore store;
    for (int i = 0; i < 50000; ++i) CHECK(store.intern(iri("x" + std::to_string(i))) == Id(i));
    for (int i = 0; i < 50000; i += 997) CHECK(store.find(iri("x" + std::to_string(i))) == Id(i));
    CHECK(store.find(iri("x50000")) == TripleStore::kAny);
}

TEST_CASE("TripleStore: predicate statistics count triples, distinct subjects and objects",
          "[ontology][sparql]") {
    TripleStore store;
    const Id a = store.intern(iri("a")), b = store.intern(iri("b")), c = store.intern(iri("c"));
    const Id p = store.intern(iri("p")), q = store.intern(iri("q"));
    // p: a->b, a->c, b->c (3 triples, subjects a b, objects b c); q: c->a twice (a repeat).
    store.add(a, p, b);
    store.add(a, p, c);
    store.add(b, p, c);
    store.add(c, q, a);
    store.add(c, q, a);
    store.finish();
    const TripleStore::PredicateStats sp = store.predicate_stats(p);
    CHECK(sp.num_triples == 3);
    CHECK(sp.num_subjects == 2);
    CHECK(sp.num_objects == 2);
    const TripleStore::PredicateStats sq = store.predicate_stats(q);
    CHECK(sq.num_triples == 1);
    CHECK(sq.num_subjects == 1);
    CHECK(sq.num_objects == 1);
    CHECK(store.predicate_stats(a).num_triples == 0);
    CHECK(store.num_subjects() == 3);  // a, b, c
    CHECK(store.num_objects() == 3);   // b, c, a
}
