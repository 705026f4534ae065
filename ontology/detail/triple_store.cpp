#include "ontology/detail/triple_store.hpp"

#include <algorithm>
#include <cstring>
#include <functional>

namespace geotex::detail {

namespace {

const std::string_view kXsdString = "http://www.w3.org/2001/XMLSchema#string";

/// Component orders of the three indexes: index[k] holds the triple's part order[k].
constexpr std::array<int, 3> kSpo{0, 1, 2};
constexpr std::array<int, 3> kPos{1, 2, 0};
constexpr std::array<int, 3> kOsp{2, 0, 1};

TripleStore::Triple permuted(const TripleStore::Triple& spo, const std::array<int, 3>& order) {
    return {spo[order[0]], spo[order[1]], spo[order[2]]};
}

/// For a triple in `order`, where subject, predicate and object sit.
std::array<int, 3> positions(const std::array<int, 3>& order) {
    std::array<int, 3> at{};
    for (int k = 0; k < 3; ++k) at[order[k]] = k;
    return at;
}

}  // namespace

void append_iri_key(std::string& out, std::string_view iri) {
    out += static_cast<char>(TermKind::Iri);
    out += iri;
}

void append_blank_key(std::string& out, std::string_view label) {
    out += static_cast<char>(TermKind::Blank);
    out += label;
}

void append_literal_key(std::string& out, std::string_view lexical, std::string_view language,
                        std::string_view datatype) {
    out += static_cast<char>(TermKind::Literal);
    if (!language.empty()) {
        out += '@';
        for (char c : language) out += (c >= 'A' && c <= 'Z') ? static_cast<char>(c + 32) : c;
    } else if (!datatype.empty() && datatype != kXsdString) {
        out += '^';
        out += datatype;
    } else {
        out += '-';
    }
    out += '\0';
    out += lexical;
}

TermParts split_term_key(std::string_view key) {
    TermParts parts;
    parts.kind = static_cast<TermKind>(key.empty() ? 'I' : key[0]);
    if (parts.kind != TermKind::Literal) {
        parts.text = key.substr(1);
        return parts;
    }
    const std::size_t nul = key.find('\0');
    const std::string_view tag = key.substr(1, nul - 1);
    parts.text = key.substr(nul + 1);
    if (!tag.empty() && tag[0] == '@') parts.language = tag.substr(1);
    if (!tag.empty() && tag[0] == '^') parts.datatype = tag.substr(1);
    return parts;
}

std::size_t TripleStore::hash_key(std::string_view key) {
    return std::hash<std::string_view>{}(key);
}

void TripleStore::grow() {
    const std::size_t size = std::max<std::size_t>(1024, slots_.size() * 2);
    slots_.assign(size, 0);
    const std::size_t mask = size - 1;
    for (std::size_t id = 0; id < keys_.size(); ++id) {
        std::size_t at = hashes_[id] & mask;
        while (slots_[at] != 0) at = (at + 1) & mask;
        slots_[at] = static_cast<TermId>(id + 1);
    }
}

TripleStore::TermId TripleStore::intern(std::string_view key, std::size_t hash) {
    if (2 * (keys_.size() + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    std::size_t at = hash & mask;
    while (const TermId slot = slots_[at]) {
        if (hashes_[slot - 1] == hash && keys_[slot - 1] == key) return slot - 1;
        at = (at + 1) & mask;
    }
    if (block_used_ + key.size() > block_size_) {
        // Blocks double from 64 kB: a file's part stays small, the merged store makes few.
        block_size_ = std::max<std::size_t>(block_size_ == 0
                                                ? std::size_t{1} << 16
                                                : std::min(2 * block_size_, std::size_t{1} << 24),
                                            key.size());
        blocks_.push_back(std::make_unique<char[]>(block_size_));
        block_used_ = 0;
    }
    char* stored = blocks_.back().get() + block_used_;
    if (!key.empty()) std::memcpy(stored, key.data(), key.size());
    block_used_ += key.size();
    const auto id = static_cast<TermId>(keys_.size());
    keys_.emplace_back(stored, key.size());
    hashes_.push_back(hash);
    slots_[at] = id + 1;
    return id;
}

TripleStore::TermId TripleStore::find(std::string_view key) const {
    if (slots_.empty()) return kAny;
    const std::size_t hash = hash_key(key);
    const std::size_t mask = slots_.size() - 1;
    std::size_t at = hash & mask;
    while (const TermId slot = slots_[at]) {
        if (hashes_[slot - 1] == hash && keys_[slot - 1] == key) return slot - 1;
        at = (at + 1) & mask;
    }
    return kAny;
}

void TripleStore::merge(const TripleStore& part) {
    std::vector<TermId> id(part.keys_.size());
    for (std::size_t i = 0; i < part.keys_.size(); ++i)
        id[i] = intern(part.keys_[i], part.hashes_[i]);
    for (const Triple& t : part.spo_) spo_.push_back({id[t[0]], id[t[1]], id[t[2]]});
}

namespace {

/// `in` stably sorted by component `c` into `out` (a counting sort: the ids are dense, below
/// `num_terms`), each triple written in the component order `order` of `in`'s components;
/// `start` gets where each id's triples begin (#terms + 1).
void counting_sort(const std::vector<TripleStore::Triple>& in, int c,
                   const std::array<int, 3>& order, std::size_t num_terms,
                   std::vector<TripleStore::Triple>& out, std::vector<std::uint32_t>& start) {
    start.assign(num_terms + 1, 0);
    for (const TripleStore::Triple& t : in) ++start[t[static_cast<std::size_t>(c)] + 1];
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    out.resize(in.size());
    for (const TripleStore::Triple& t : in)
        out[next[t[static_cast<std::size_t>(c)]]++] = permuted(t, order);
}

}  // namespace

void TripleStore::finish() {
    // Sorted by radix over the dense ids, not by comparison (three times faster on a
    // collection: most of a load's time after parsing went to std::sort). A stable sort by
    // one component keeps the order of the others, so SPO takes three passes (by o, by p,
    // by s); OSP is SPO stably sorted by o, and POS is OSP stably sorted by p.
    const std::size_t n = keys_.size();
    std::vector<Triple> scratch;
    counting_sort(spo_, 2, kSpo, n, scratch, spo_start_);
    counting_sort(scratch, 1, kSpo, n, spo_, spo_start_);
    counting_sort(spo_, 0, kSpo, n, scratch, spo_start_);
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    spo_.assign(scratch.begin(), scratch.end());
    scratch.clear();
    scratch.shrink_to_fit();
    counting_sort(spo_, 2, kOsp, n, osp_, osp_start_);  // (s, p, o) by o: (o, s, p)
    // osp_'s component 2 is the predicate: (o, s, p) by p, written (p, o, s).
    counting_sort(osp_, 2, {2, 0, 1}, n, pos_, pos_start_);
    // The starts of SPO, after removing the repeats.
    spo_start_.assign(n + 1, 0);
    for (const Triple& t : spo_) ++spo_start_[t[0] + 1];
    for (std::size_t i = 1; i < spo_start_.size(); ++i) spo_start_[i] += spo_start_[i - 1];

    // Distinct (predicate, object) pairs follow each other in POS; distinct (subject,
    // predicate) pairs in SPO, counted per predicate through a table over the ids.
    predicates_.clear();
    for (std::size_t i = 0; i < pos_.size(); ++i) {
        const Triple& t = pos_[i];
        if (predicates_.empty() || predicates_.back().first != t[0])
            predicates_.emplace_back(t[0], PredicateStats());
        PredicateStats& st = predicates_.back().second;
        ++st.num_triples;
        if (i == 0 || pos_[i - 1][0] != t[0] || pos_[i - 1][1] != t[1]) ++st.num_objects;
    }
    for (std::size_t i = 0; i < spo_.size(); ++i) {
        const Triple& t = spo_[i];
        if (i > 0 && spo_[i - 1][0] == t[0] && spo_[i - 1][1] == t[1]) continue;
        const auto at = std::lower_bound(
            predicates_.begin(), predicates_.end(), t[1],
            [](const std::pair<TermId, PredicateStats>& e, TermId id) { return e.first < id; });
        ++at->second.num_subjects;
    }
    num_subjects_ = num_objects_ = 0;
    for (std::size_t id = 0; id + 1 < spo_start_.size(); ++id) {
        num_subjects_ += spo_start_[id + 1] != spo_start_[id];
        num_objects_ += osp_start_[id + 1] != osp_start_[id];
    }
}

TripleStore::PredicateStats TripleStore::predicate_stats(TermId p) const {
    const auto at = std::lower_bound(
        predicates_.begin(), predicates_.end(), p,
        [](const std::pair<TermId, PredicateStats>& e, TermId id) { return e.first < id; });
    return at != predicates_.end() && at->first == p ? at->second : PredicateStats();
}

TripleStore::Matches TripleStore::match(TermId s, TermId p, TermId o) const {
    const bool has_s = s != kAny, has_p = p != kAny, has_o = o != kAny;
    // The index whose leading components are the fixed parts: every pattern is a prefix of
    // one of SPO, POS and OSP.
    const std::vector<Triple>* index = &spo_;
    const std::vector<std::uint32_t>* start = &spo_start_;
    std::array<int, 3> order = kSpo;
    if (has_p && !has_s) {
        index = &pos_;
        start = &pos_start_;
        order = kPos;
    } else if (has_o && !has_p) {
        index = &osp_;
        start = &osp_start_;
        order = kOsp;
    }
    const Triple pattern{s, p, o};
    const Triple key = permuted(pattern, order);
    int fixed = 0;
    while (fixed < 3 && key[fixed] != kAny) ++fixed;

    Matches m;
    m.position = positions(order);
    const Triple* first = index->data();
    const Triple* last = first + index->size();
    if (fixed == 0 || key[0] >= keys_.size()) {
        m.begin = first;
        m.end = fixed == 0 ? last : first;
        return m;
    }
    last = first + (*start)[key[0] + 1];
    first += (*start)[key[0]];
    if (fixed == 1) {
        m.begin = first;
        m.end = last;
        return m;
    }
    auto before = [fixed](const Triple& a, const Triple& b) {
        for (int k = 1; k < fixed; ++k)
            if (a[k] != b[k]) return a[k] < b[k];
        return false;
    };
    const auto range = std::equal_range(first, last, key, before);
    m.begin = range.first;
    m.end = range.second;
    return m;
}

bool TripleStore::contains(TermId s, TermId p, TermId o) const {
    return std::binary_search(spo_.begin(), spo_.end(), Triple{s, p, o});
}

}  // namespace geotex::detail
