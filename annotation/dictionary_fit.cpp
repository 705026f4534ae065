#include "annotation/dictionary_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "annotation/detail/dictionary_text.hpp"
#include "geometry/feature_table.hpp"

namespace geotex {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string number_text(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string interval_text(double lower, double upper) {
    return "[" + (std::isinf(lower) ? std::string("-.inf") : number_text(lower)) + ", " +
           (std::isinf(upper) ? std::string(".inf") : number_text(upper)) + ")";
}

std::string mark_name(const FitMark& m) {
    return (m.where.empty() ? std::string() : m.where + ": ") + "texture " +
           std::to_string(m.texture) + " of '" + m.object + "' " + (m.yes ? "is" : "is not") +
           " '" + m.concept_id + "'";
}

/// Significant digits of a decimal text.
size_t significant_digits(const std::string& text) {
    const auto first = text.find_first_of("123456789");
    if (first == std::string::npos) return 0;
    size_t n = 0;
    for (size_t k = first; k <= text.find_last_of("123456789"); ++k) n += text[k] != '.';
    return n;
}

/// n * 10^k as a decimal text without exponent.
std::string scaled_integer_text(long long n, int k) {
    const bool negative = n < 0;
    std::string digits = std::to_string(negative ? -n : n);
    if (n == 0) return "0";
    if (k >= 0) {
        digits += std::string(static_cast<size_t>(k), '0');
    } else {
        const size_t decimals = static_cast<size_t>(-k);
        if (digits.size() <= decimals) digits.insert(0, decimals - digits.size() + 1, '0');
        digits.insert(digits.size() - decimals, ".");
        while (digits.back() == '0') digits.pop_back();
        if (digits.back() == '.') digits.pop_back();
    }
    return negative ? "-" + digits : digits;
}

// ---- the fit of one feature ----------------------------------------------------------------

/// A bound of the feature's intervals; two intervals that share it share the slot.
struct Slot {
    double value = 0;
    std::vector<std::pair<size_t, bool>> members;  // (concept index, upper?)
};

struct Candidate {
    double position = 0;
    std::string text;  // "" for the current position
    bool moved = false;
    double distance = 0;
};

struct Cost {
    int violated = 0;
    int moved = 0;
    double distance = 0;
    bool operator<(const Cost& o) const {
        if (violated != o.violated) return violated < o.violated;
        if (moved != o.moved) return moved < o.moved;
        return distance < o.distance;
    }
    Cost operator+(const Cost& o) const {
        return {violated + o.violated, moved + o.moved, distance + o.distance};
    }
};

struct FeatureMark {
    size_t mark = 0;      // index into the marks
    size_t concept_ = 0;  // position among the feature's concepts
    double value = 0;
    bool yes = true;
};

bool holds(double lower, double upper, double v) { return lower <= v && v < upper; }

/// The texture values are plain means, the marked ones describe_textures' (summed from
/// another origin): the same texture's mean may differ in its last bits between the two.
bool same_value(double x, double y) {
    return std::fabs(x - y) <= 1e-12 * std::max(1.0, std::max(std::fabs(x), std::fabs(y)));
}

/// The candidate positions of a slot: where it is, and one point per stretch between the
/// marked values it is not in (the stretches are what the marks can tell apart), placed in
/// the gap of texture values next to that stretch's end nearest the slot.
std::vector<Candidate> candidates(double current, const std::vector<double>& marked,
                                  const std::vector<double>& values) {
    std::vector<Candidate> out{{current, "", false, 0}};
    if (std::isinf(current)) return out;
    // stretch r: positions b with marked[r-1] < b <= marked[r]
    const auto stretch_of = [&](double b) {
        return static_cast<size_t>(std::lower_bound(marked.begin(), marked.end(), b) -
                                   marked.begin());
    };
    const size_t here = stretch_of(current);
    for (size_t r = 0; r <= marked.size(); ++r) {
        if (r == here) continue;
        double a = 0, b = 0;
        if (r > here) {
            // above the slot: just above the stretch's lower end, below the next texture value
            a = marked[r - 1];
            auto next = std::upper_bound(values.begin(), values.end(), a);
            while (next != values.end() && same_value(*next, a)) ++next;
            b = next == values.end() ? a + std::max(1.0, std::fabs(a)) * 0.1 : *next;
            if (r < marked.size()) b = std::min(b, marked[r]);
        } else {
            // below the slot: at most the stretch's upper end, above the texture value before
            b = marked[r];
            auto before = std::lower_bound(values.begin(), values.end(), b);
            while (before != values.begin() && same_value(*(before - 1), b)) --before;
            a = before == values.begin() ? b - std::max(1.0, std::fabs(b)) * 0.1 : *(before - 1);
            if (r > 0) a = std::max(a, marked[r - 1]);
        }
        Candidate c;
        if (!(a < b) || !shortest_decimal_between(a, b, current, c.position, c.text)) continue;
        c.moved = true;
        c.distance = std::fabs(c.position - current);
        out.push_back(std::move(c));
    }
    return out;
}

struct FeatureFit {
    std::vector<Slot> slots;
    std::vector<Candidate> chosen;  // per slot
    std::vector<size_t> violated;   // marks (indices into the marks) left unsatisfied
};

FeatureFit fit_feature(const Dictionary& d, const std::vector<size_t>& concepts,
                       const std::vector<FeatureMark>& marks, const std::vector<double>& values) {
    FeatureFit fit;
    // slots in order: lower and upper of each concept, a shared bound once
    std::vector<size_t> lower_slot(concepts.size()), upper_slot(concepts.size());
    for (size_t i = 0; i < concepts.size(); ++i) {
        const DictionaryConcept& c = d.concepts[concepts[i]];
        if (i > 0 && fit.slots.back().value == c.lower && !std::isinf(c.lower)) {
            fit.slots.back().members.emplace_back(concepts[i], false);
        } else {
            fit.slots.push_back({c.lower, {{concepts[i], false}}});
        }
        lower_slot[i] = fit.slots.size() - 1;
        fit.slots.push_back({c.upper, {{concepts[i], true}}});
        upper_slot[i] = fit.slots.size() - 1;
    }
    std::vector<double> marked;
    for (const auto& m : marks) marked.push_back(m.value);
    std::sort(marked.begin(), marked.end());
    marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
    std::vector<std::vector<Candidate>> cands;
    for (const Slot& s : fit.slots) cands.push_back(candidates(s.value, marked, values));
    // the marks of the concept whose upper bound is slot j, by j
    std::vector<std::vector<const FeatureMark*>> marks_at(fit.slots.size());
    std::vector<bool> own_interval(fit.slots.size(), false);  // slot j-1, j bound one concept
    for (size_t i = 0; i < concepts.size(); ++i) own_interval[upper_slot[i]] = true;
    for (const auto& m : marks) marks_at[upper_slot[m.concept_]].push_back(&m);

    // Every constraint binds two neighbouring slots (a concept's own bounds, or the upper of
    // one and the lower of the next), so the best placement is a shortest path along them.
    const size_t n = fit.slots.size();
    std::vector<std::vector<Cost>> best(n);
    std::vector<std::vector<int>> from(n);
    const auto own_cost = [](const Candidate& c) { return Cost{0, c.moved ? 1 : 0, c.distance}; };
    best[0].resize(cands[0].size());
    from[0].assign(cands[0].size(), -1);
    for (size_t c = 0; c < cands[0].size(); ++c) best[0][c] = own_cost(cands[0][c]);
    const Cost impossible{std::numeric_limits<int>::max() / 4, 0, 0};
    for (size_t j = 1; j < n; ++j) {
        best[j].assign(cands[j].size(), impossible);
        from[j].assign(cands[j].size(), -1);
        for (size_t c = 0; c < cands[j].size(); ++c) {
            const double upper = cands[j][c].position;
            for (size_t p = 0; p < cands[j - 1].size(); ++p) {
                if (!(best[j - 1][p] < impossible)) continue;
                const double lower = cands[j - 1][p].position;
                if (own_interval[j] ? !(lower < upper) : !(lower <= upper)) continue;
                Cost cost = best[j - 1][p] + own_cost(cands[j][c]);
                if (own_interval[j])
                    for (const FeatureMark* m : marks_at[j])
                        cost.violated += holds(lower, upper, m->value) != m->yes;
                if (cost < best[j][c]) {
                    best[j][c] = cost;
                    from[j][c] = static_cast<int>(p);
                }
            }
        }
    }
    size_t end = 0;
    for (size_t c = 1; c < best[n - 1].size(); ++c)
        if (best[n - 1][c] < best[n - 1][end]) end = c;
    fit.chosen.resize(n);
    for (size_t j = n; j-- > 0;) {
        fit.chosen[j] = cands[j][end];
        if (j > 0) end = static_cast<size_t>(from[j][end]);
    }
    for (const auto& m : marks) {
        const double lower = fit.chosen[lower_slot[m.concept_]].position;
        const double upper = fit.chosen[upper_slot[m.concept_]].position;
        if (holds(lower, upper, m.value) != m.yes) fit.violated.push_back(m.mark);
    }
    return fit;
}

/// Means of each feature over each texture's texels: the values between which bounds go.
std::vector<std::vector<double>> texture_values(const std::vector<FitObject>& objects) {
    std::vector<std::vector<double>> values(kNumFeatures);
    for (const auto& o : objects) {
        std::vector<int> count(static_cast<size_t>(std::max(0, o.num_textures)), 0);
        Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(o.num_textures, kNumFeatures);
        for (size_t i = 0; i < o.texel_texture.size(); ++i) {
            const int t = o.texel_texture[i];
            if (t < 0 || t >= o.num_textures || static_cast<Eigen::Index>(i) >= o.features.rows())
                continue;
            ++count[static_cast<size_t>(t)];
            sum.row(t) += o.features.row(static_cast<Eigen::Index>(i));
        }
        for (int t = 0; t < o.num_textures; ++t)
            for (int f = 0; f < kNumFeatures && count[static_cast<size_t>(t)] > 0; ++f) {
                const double v = sum(t, f) / count[static_cast<size_t>(t)];
                if (std::isfinite(v)) values[static_cast<size_t>(f)].push_back(v);
            }
    }
    for (auto& v : values) {
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
    }
    return values;
}

const FeatureScore* score_of(const TextureDescription& t, int feature) {
    for (const auto& s : t.features)
        if (s.feature == feature) return &s;
    return nullptr;
}

std::string percent(double x) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.0f%%", 100 * x);
    return buf;
}

/// Why describe_textures does not give a texture the concept that its value's interval holds.
std::string why_not_chosen(const TextureDescription& t, const FeatureScore& s,
                           const DictionaryConcept& c, const Dictionary& d,
                           const DescriptionParams& p) {
    const std::string feature = kFeatureIds[c.feature];
    if (!relief_allows(c.relief, t.orientation))
        return "'" + c.id + "' is only for " +
               (c.relief == Relief::Raised ? "raised details" : "engravings") +
               "; the texture is " +
               (t.orientation == DetailOrientation::Positive ? "raised" : "engraved");
    if (std::isnan(s.significance))
        return feature + " is the same over all the object's texels: it names no texture";
    if (!(s.agreement >= p.min_agreement))
        return "only " + percent(s.agreement) + " of the texture's texels have their own " +
               feature + " in " + interval_text(c.lower, c.upper) + " (min_agreement " +
               percent(p.min_agreement) + ")";
    if (p.max_significance > 0 && !(s.significance <= p.max_significance))
        return "its significance " + number_text(s.significance) + " is above max_significance " +
               number_text(p.max_significance);
    if (s.withheld)
        return "withheld: chosen in only " + percent(s.stability) +
               " of the resamples of the texels (min_stability " + percent(p.min_stability) +
               "), or beyond max_concepts";
    const int facet = s.facet;
    for (int i : t.chosen) {
        const FeatureScore& o = t.features[static_cast<size_t>(i)];
        if (o.facet == facet && o.concept_ptr)
            return "facet '" +
                   (facet >= 0 && facet < static_cast<int>(d.facets.size())
                        ? d.facets[static_cast<size_t>(facet)].id
                        : std::string("?")) +
                   "' says '" + o.concept_ptr->id + "' (" + kFeatureIds[o.feature] +
                   " comes first in the facet's order)";
    }
    return "not chosen by the word-choice rule (docs/words.md)";
}

}  // namespace

bool shortest_decimal_between(double a, double b, double target, double& value, std::string& text) {
    if (std::isinf(a) && std::isinf(b)) return false;
    if (std::isinf(a)) a = b - std::max(1.0, std::fabs(b));
    if (std::isinf(b)) b = a + std::max(1.0, std::fabs(a));
    if (!(a < b)) return false;
    const int top = static_cast<int>(std::floor(std::log10(b - a))) + 1;
    for (int k = top; k >= top - 20; --k) {
        const double step = std::pow(10.0, k);
        if (std::max(std::fabs(a), std::fabs(b)) / step > 1e15) break;
        const long long lo = static_cast<long long>(std::floor(a / step)) + 1;
        const long long hi = static_cast<long long>(std::ceil(b / step)) - 1;
        if (lo > hi) continue;
        long long n = std::isfinite(target) ? std::llround(target / step) : (target > 0 ? hi : lo);
        n = std::clamp(n, lo, hi);
        // the rounding of a / step may admit an end: try the neighbours inwards too
        for (long long m : {n, n + 1, n - 1}) {
            if (m < lo || m > hi) continue;
            const std::string t = scaled_integer_text(m, k);
            const double v = std::strtod(t.c_str(), nullptr);
            if (a < v && v < b && significant_digits(t) <= 15) {
                value = v;
                text = t;
                return true;
            }
        }
    }
    return false;
}

DictionaryFitResult fit_dictionary(const Dictionary& dictionary,
                                   const std::vector<FitObject>& objects,
                                   const std::vector<FitMark>& marks) {
    DictionaryFitResult result;
    result.fitted = dictionary;
    std::map<std::string, size_t> object_index, concept_index;
    for (size_t i = 0; i < objects.size(); ++i) object_index.emplace(objects[i].id, i);
    for (size_t i = 0; i < dictionary.concepts.size(); ++i)
        concept_index.emplace(dictionary.concepts[i].id, i);

    // the words of the marked objects now: their exact texture values
    std::map<size_t, std::vector<TextureDescription>> now;
    std::vector<bool> left_out(marks.size(), false);
    std::vector<std::pair<size_t, FitProblem>> unsat;  // by mark index
    const auto unsatisfied = [&](size_t k, const std::string& reason) {
        left_out[k] = true;
        unsat.push_back({k, {marks[k], reason}});
    };
    std::vector<double> mark_value(marks.size(), 0);
    for (size_t k = 0; k < marks.size(); ++k) {
        const FitMark& m = marks[k];
        const auto o = object_index.find(m.object);
        const auto c = concept_index.find(m.concept_id);
        if (o == object_index.end()) {
            unsatisfied(k, "object '" + m.object +
                               "' is not loaded, or has no geometry.cbor to choose words from");
            continue;
        }
        if (c == concept_index.end()) {
            unsatisfied(k, "unknown concept '" + m.concept_id + "'");
            continue;
        }
        const FitObject& obj = objects[o->second];
        if (m.texture < 0 || m.texture >= obj.num_textures) {
            unsatisfied(k, "object '" + m.object + "' has no texture " + std::to_string(m.texture) +
                               " (it has " + std::to_string(obj.num_textures) + ")");
            continue;
        }
        if (!now.count(o->second))
            now[o->second] = describe_textures(obj.features, obj.texel_texture, obj.num_textures,
                                               obj.texture_orientation, dictionary, obj.params);
        const FeatureScore* s = score_of(now[o->second][static_cast<size_t>(m.texture)],
                                         dictionary.concepts[c->second].feature);
        if (!s || !std::isfinite(s->value)) {
            unsatisfied(k, std::string("the texture has no value of ") +
                               kFeatureIds[dictionary.concepts[c->second].feature]);
            continue;
        }
        mark_value[k] = s->value;
    }
    // Marks that contradict each other outright: one value yes and no for one concept, or yes
    // for two concepts of one feature (its intervals are disjoint). Both are left out.
    for (size_t k = 0; k < marks.size(); ++k)
        for (size_t l = k + 1; l < marks.size(); ++l) {
            if (mark_value[k] != mark_value[l]) continue;
            const FitMark& a = marks[k];
            const FitMark& b = marks[l];
            const auto ca = concept_index.find(a.concept_id);
            const auto cb = concept_index.find(b.concept_id);
            if (ca == concept_index.end() || cb == concept_index.end()) continue;
            const DictionaryConcept& x = dictionary.concepts[ca->second];
            const DictionaryConcept& y = dictionary.concepts[cb->second];
            if (x.feature != y.feature || (left_out[k] && left_out[l])) continue;
            const bool same = x.id == y.id && a.yes != b.yes;
            const bool both_yes = x.id != y.id && a.yes && b.yes;
            if (!same && !both_yes) continue;
            const std::string value = number_text(mark_value[k]);
            const std::string why =
                same ? "the same value of " + std::string(kFeatureIds[x.feature]) + " (" + value +
                           ") is marked yes and no for '" + x.id + "'"
                     : "the same value of " + std::string(kFeatureIds[x.feature]) + " (" + value +
                           ") is marked yes for '" + x.id + "' and '" + y.id +
                           "', whose intervals are disjoint";
            if (!left_out[k]) unsatisfied(k, why + " (see " + mark_name(b) + ")");
            if (!left_out[l]) unsatisfied(l, why + " (see " + mark_name(a) + ")");
        }

    // per feature, the fit of its bounds
    const auto values = texture_values(objects);
    std::map<int, std::vector<FeatureMark>> by_feature;
    for (size_t k = 0; k < marks.size(); ++k) {
        if (left_out[k]) continue;
        const size_t c = concept_index.at(marks[k].concept_id);
        by_feature[dictionary.concepts[c].feature].push_back({k, c, mark_value[k], marks[k].yes});
    }
    struct Move {
        size_t slot_concept;  // the member that the edit names
        bool upper;
        std::string text;
        double value;
        std::vector<std::pair<size_t, bool>> members;
    };
    std::vector<Move> moves;
    for (auto& [feature, fmarks] : by_feature) {
        std::vector<size_t> concepts;
        for (size_t i = 0; i < dictionary.concepts.size(); ++i)
            if (dictionary.concepts[i].feature == feature) concepts.push_back(i);
        std::map<size_t, size_t> position;
        for (size_t i = 0; i < concepts.size(); ++i) position[concepts[i]] = i;
        for (auto& m : fmarks) m.concept_ = position.at(m.concept_);
        const FeatureFit fit =
            fit_feature(dictionary, concepts, fmarks, values[static_cast<size_t>(feature)]);
        for (size_t k : fit.violated) {
            const FitMark& m = marks[k];
            const DictionaryConcept& c = dictionary.concepts[concept_index.at(m.concept_id)];
            unsat.push_back(
                {k,
                 {m, "no placement of the bounds of " + std::string(kFeatureIds[feature]) +
                         " puts its value " + number_text(mark_value[k]) +
                         (m.yes ? " inside " : " outside ") + "the interval of '" + c.id +
                         "' without breaking more of the other marks"}});
        }
        for (size_t j = 0; j < fit.slots.size(); ++j) {
            if (!fit.chosen[j].moved) continue;
            // name the slot by an upper bound when it has one: edit_dictionary moves the
            // lower bound of the next interval with it
            auto member = fit.slots[j].members.front();
            for (const auto& mm : fit.slots[j].members)
                if (mm.second) member = mm;
            moves.push_back({member.first, member.second, fit.chosen[j].text,
                             fit.chosen[j].position, fit.slots[j].members});
        }
    }

    // The order of the edits: edit_dictionary also moves a neighbour whose bound equals the
    // old value; an edit is safe when every such neighbour moves with it.
    std::vector<DictionaryConcept>& cs = result.fitted.concepts;
    std::vector<bool> done(moves.size(), false);
    for (size_t applied = 0; applied < moves.size(); ++applied) {
        size_t pick = moves.size();
        for (size_t i = 0; i < moves.size() && pick == moves.size(); ++i) {
            if (done[i]) continue;
            const Move& mv = moves[i];
            const DictionaryConcept& c = cs[mv.slot_concept];
            const double old = mv.upper ? c.upper : c.lower;
            bool safe = true;
            for (size_t o = 0; o < cs.size(); ++o) {
                if (o == mv.slot_concept || cs[o].feature != c.feature) continue;
                const double other = mv.upper ? cs[o].lower : cs[o].upper;
                const bool member = std::find(mv.members.begin(), mv.members.end(),
                                              std::make_pair(o, !mv.upper)) != mv.members.end();
                if (other == old && !member) safe = false;
            }
            if (safe) pick = i;
        }
        if (pick == moves.size())  // no order avoids it (not met in practice): keep going
            for (size_t i = 0; i < moves.size(); ++i)
                if (!done[i]) {
                    pick = i;
                    break;
                }
        done[pick] = true;
        const Move& mv = moves[pick];
        DictionaryEdit e;
        e.kind = DictionaryEdit::Kind::Bound;
        e.concept_id = cs[mv.slot_concept].id;
        e.upper = mv.upper;
        e.value = mv.text;
        result.edits.push_back(e);
        std::string normal;
        dictionary_detail::decimal_text(mv.text, normal);
        for (const auto& [ci, upper] : mv.members) {
            (upper ? cs[ci].upper : cs[ci].lower) = mv.value;
            (upper ? cs[ci].upper_text : cs[ci].lower_text) = normal;
        }
    }
    // bounds keep their order within a feature, so the concepts stay sorted; stable anyway
    std::stable_sort(cs.begin(), cs.end(),
                     [](const DictionaryConcept& a, const DictionaryConcept& b) {
                         return a.feature != b.feature ? a.feature < b.feature : a.lower < b.lower;
                     });

    // what the word-choice rule says with the fitted bounds
    std::map<std::string, size_t> fitted_index;
    for (size_t i = 0; i < cs.size(); ++i) fitted_index.emplace(cs[i].id, i);
    std::set<size_t> unsatisfied_marks;
    for (const auto& p : unsat) unsatisfied_marks.insert(p.first);
    std::map<size_t, std::vector<TextureDescription>> after;
    for (size_t k = 0; k < marks.size(); ++k) {
        if (unsatisfied_marks.count(k)) continue;
        const FitMark& m = marks[k];
        const size_t o = object_index.at(m.object);
        if (!after.count(o)) {
            const FitObject& obj = objects[o];
            after[o] = describe_textures(obj.features, obj.texel_texture, obj.num_textures,
                                         obj.texture_orientation, result.fitted, obj.params);
        }
        const TextureDescription& t = after[o][static_cast<size_t>(m.texture)];
        const DictionaryConcept& c = cs[fitted_index.at(m.concept_id)];
        bool chosen = false;
        for (int i : t.chosen)
            chosen = chosen || t.features[static_cast<size_t>(i)].concept_ptr->id == c.id;
        if (chosen == m.yes) continue;
        const FeatureScore* s = score_of(t, c.feature);
        result.not_reproduced.push_back(
            {m, m.yes ? why_not_chosen(t, *s, c, result.fitted, objects[o].params)
                      : "still chosen by the word-choice rule"});
    }
    std::stable_sort(unsat.begin(), unsat.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& p : unsat) result.unsatisfied.push_back(std::move(p.second));
    return result;
}

}  // namespace geotex
