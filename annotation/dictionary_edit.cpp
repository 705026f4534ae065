#include "annotation/dictionary_edit.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include "annotation/detail/dictionary_text.hpp"
#include "annotation/yaml_tree.hpp"
#include "common/detail/text.hpp"
#include "common/errors.hpp"

namespace geotex {

namespace {

using namespace yaml_detail;
using dictionary_detail::quoted;

// Every edit is a replacement of a byte span of the original text (an insertion is an empty
// span); they are collected first and spliced at the end, so the tree's offsets stay valid
// and several edits of one bound see each other's result.
struct Splice {
    size_t begin = 0;
    size_t end = 0;
    std::string text;
    int order = 0;  // insertions at one place keep the order of the edits
};

const YNode& at(const YamlTree& t, int i) { return t.nodes[static_cast<size_t>(i)]; }

/// The value node of `key` in the map `map`, or -1.
int entry(const YamlTree& t, int map, std::string_view key) {
    if (map < 0 || at(t, map).kind != YNode::Kind::Map) return -1;
    const auto& items = at(t, map).items;
    for (size_t k = 0; k + 1 < items.size(); k += 2) {
        const YNode& n = at(t, items[k]);
        if (n.kind == YNode::Kind::Scalar && n.value == key) return items[k + 1];
    }
    return -1;
}

bool is_flow(std::string_view text, const YNode& collection) {
    return collection.offset < text.size() &&
           (text[collection.offset] == '[' || text[collection.offset] == '{');
}

/// The bytes of the scalar `n` in the text, or false when it cannot be replaced in place: a
/// block scalar, or a plain or quoted scalar written over several lines. `flow`: inside
/// [...] or {...}, where ',', ']' and '}' end a plain scalar.
bool scalar_span(std::string_view text, const YNode& n, bool flow, size_t& begin, size_t& end) {
    if (n.kind != YNode::Kind::Scalar || n.offset >= text.size()) return false;
    begin = n.offset;
    const char c = text[begin];
    if (c == '|' || c == '>') return false;
    if (c == '"' || c == '\'') {
        for (size_t i = begin + 1; i < text.size(); ++i) {
            if (text[i] == '\n') return false;
            if (c == '"' && text[i] == '\\') {
                ++i;
            } else if (text[i] == c) {
                if (c == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
                    ++i;
                } else {
                    end = i + 1;
                    return true;
                }
            }
        }
        return false;
    }
    size_t i = begin;
    while (i < text.size() && text[i] != '\n' && text[i] != '\r') {
        if (text[i] == '#' && i > begin && (text[i - 1] == ' ' || text[i - 1] == '\t')) break;
        if (flow && (text[i] == ',' || text[i] == ']' || text[i] == '}')) break;
        ++i;
    }
    while (i > begin && (text[i - 1] == ' ' || text[i - 1] == '\t')) --i;
    end = i;
    // a plain scalar continued on the next lines reads as more than its first line
    return text.substr(begin, end - begin) == n.value;
}

bool is_special_plain(const std::string& s) {
    std::string lower = s;
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    static const char* const words[] = {"null", "~",   "true", "false", "yes", "no",
                                        "on",   "off", "y",    "n",     "=",   "<<"};
    for (const char* w : words)
        if (lower == w) return true;
    std::string decimal;
    if (dictionary_detail::decimal_text(s, decimal)) return true;
    const std::string body = lower[0] == '+' || lower[0] == '-' ? lower.substr(1) : lower;
    return body == ".inf" || body == ".nan" || lower.rfind("0x", 0) == 0 ||
           lower.rfind("0o", 0) == 0;
}

/// Whether `s` reads back as the same text when written bare, in a block or a flow collection.
bool plain_safe(const std::string& s, bool flow) {
    if (s.empty() || s.front() == ' ' || s.back() == ' ' || s.back() == ':') return false;
    if (std::string_view("-?:,[]{}#&*!|>'\"%@`").find(s.front()) != std::string_view::npos)
        return false;
    if (s.find(": ") != std::string::npos || s.find(" #") != std::string::npos) return false;
    for (unsigned char ch : s)
        if (ch < 0x20 || ch == 0x7F) return false;
    if (flow && s.find_first_of(",[]{}") != std::string::npos) return false;
    return !is_special_plain(s);
}

std::string double_quoted(const std::string& s) {
    std::string out = "\"";
    for (unsigned char ch : s) {
        if (ch == '"' || ch == '\\') {
            out += '\\';
            out += static_cast<char>(ch);
        } else if (ch == '\n') {
            out += "\\n";
        } else if (ch == '\t') {
            out += "\\t";
        } else if (ch < 0x20 || ch == 0x7F) {
            char esc[8];
            std::snprintf(esc, sizeof esc, "\\x%02X", ch);
            out += esc;
        } else {
            out += static_cast<char>(ch);
        }
    }
    return out + "\"";
}

std::string single_quoted(const std::string& s) {
    std::string out = "'";
    for (char ch : s) {
        out += ch;
        if (ch == '\'') out += '\'';
    }
    return out + "'";
}

/// `value` written as a scalar in the style of `original` (its first byte: a quote or not).
std::string scalar_text(const std::string& value, char original, bool flow) {
    bool control = false;
    for (unsigned char ch : value) control = control || ch < 0x20 || ch == 0x7F;
    if (original == '\'' && !control) return single_quoted(value);
    if (original == '"' || control || !plain_safe(value, flow)) return double_quoted(value);
    return value;
}

/// The line end used at `offset` ("\r\n" or "\n").
std::string line_end_at(std::string_view text, size_t offset) {
    const size_t nl = text.find('\n', offset);
    if (nl != std::string_view::npos && nl > 0 && text[nl - 1] == '\r') return "\r\n";
    if (nl == std::string_view::npos && text.find("\r\n") != std::string_view::npos) return "\r\n";
    return "\n";
}

/// An entry `key: value` added to the map `map`, after the entry whose value is `after`
/// (a scalar on one line): in a flow map after that value, in a block map on a new line
/// under the key of that entry.
bool insert_entry(std::string_view text, const YamlTree& t, int map, int after,
                  const std::string& key, const std::string& value, Splice& out) {
    const YNode& m = at(t, map);
    const bool flow = is_flow(text, m);
    size_t begin = 0, end = 0;
    if (after < 0 || !scalar_span(text, at(t, after), flow, begin, end)) return false;
    if (flow) {
        out = {end, end, ", " + key + ": " + scalar_text(value, 0, true), 0};
        return true;
    }
    // the key of `after` sets the indentation of the new line
    int key_id = -1;
    for (size_t k = 1; k < m.items.size(); k += 2)
        if (m.items[k] == after) key_id = m.items[k - 1];
    if (key_id < 0) return false;
    const size_t key_offset = at(t, key_id).offset;
    const size_t line_start = text.rfind('\n', key_offset == 0 ? 0 : key_offset - 1);
    const size_t from =
        line_start == std::string_view::npos || key_offset == 0 ? 0 : line_start + 1;
    // characters before the key ("- " of a sequence item included) become spaces
    std::string indent;
    for (size_t i = from; i < key_offset;) {
        char32_t cp = 0;
        const size_t n = detail::utf8_decode(text, i, cp);
        i += n == 0 ? 1 : n;
        indent += ' ';
    }
    size_t eol = text.find('\n', end);
    const std::string nl = line_end_at(text, end);
    if (eol == std::string_view::npos) {
        // the last line of a file without a final newline
        out = {text.size(), text.size(), nl + indent + key + ": " + scalar_text(value, 0, false),
               0};
        return true;
    }
    if (eol > 0 && text[eol - 1] == '\r') --eol;
    out = {eol, eol, nl + indent + key + ": " + scalar_text(value, 0, false), 0};
    return true;
}

std::string splice(std::string_view text, std::vector<Splice> splices) {
    std::stable_sort(splices.begin(), splices.end(), [](const Splice& a, const Splice& b) {
        return a.begin != b.begin ? a.begin < b.begin : a.order < b.order;
    });
    std::string out;
    size_t pos = 0;
    for (const Splice& s : splices) {
        out.append(text.substr(pos, s.begin - pos));
        out += s.text;
        pos = std::max(pos, s.end);
    }
    out.append(text.substr(pos));
    return out;
}

bool infinite_text(const std::string& s, int& sign) {
    if (s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf" || s == "+.Inf" || s == "+.INF") {
        sign = 1;
        return true;
    }
    if (s == "-.inf" || s == "-.Inf" || s == "-.INF") {
        sign = -1;
        return true;
    }
    return false;
}

/// A bound as the checker compares it: the decimal form, or "+inf"/"-inf"; "" when neither.
std::string bound_key(const std::string& s) {
    int sign = 0;
    if (infinite_text(s, sign)) return sign > 0 ? "+inf" : "-inf";
    std::string decimal;
    return dictionary_detail::decimal_text(s, decimal) ? decimal : "";
}

// One concept of the text, as far as edits need it.
struct ConceptSlots {
    std::string id;
    std::string feature;
    int bound[2] = {-1, -1};  // lower, upper scalar nodes
    bool bound_flow = true;
    std::string bound_key[2];  // current value, as bound_key() compares it
    int splice_of_bound[2] = {-1, -1};
    int labels = -1;  // the labels map node
    std::map<std::string, int> splice_of_label;
};

std::vector<ConceptSlots> concept_slots(std::string_view text, const YamlTree& t) {
    std::vector<ConceptSlots> out;
    if (t.roots.empty() || t.roots[0] < 0) return out;
    const int features = entry(t, t.roots[0], "features");
    if (features < 0 || at(t, features).kind != YNode::Kind::Map) return out;
    const auto& fitems = at(t, features).items;
    for (size_t k = 0; k + 1 < fitems.size(); k += 2) {
        const YNode& list = at(t, fitems[k + 1]);
        if (list.kind != YNode::Kind::Sequence) continue;
        for (int item : list.items) {
            const int id = entry(t, item, "id");
            if (id < 0 || at(t, id).kind != YNode::Kind::Scalar) continue;
            ConceptSlots c;
            c.id = at(t, id).value;
            c.feature = at(t, fitems[k]).value;
            const int interval = entry(t, item, "interval");
            if (interval >= 0 && at(t, interval).kind == YNode::Kind::Sequence &&
                at(t, interval).items.size() == 2) {
                c.bound_flow = is_flow(text, at(t, interval));
                for (int side = 0; side < 2; ++side) {
                    c.bound[side] = at(t, interval).items[static_cast<size_t>(side)];
                    if (at(t, c.bound[side]).kind == YNode::Kind::Scalar)
                        c.bound_key[side] = bound_key(at(t, c.bound[side]).value);
                }
            }
            c.labels = entry(t, item, "labels");
            out.push_back(std::move(c));
        }
    }
    return out;
}

}  // namespace

DictionaryEditResult edit_dictionary(std::string_view yaml_text,
                                     const std::vector<DictionaryEdit>& edits) {
    DictionaryEditResult result;
    const Places places(yaml_text);
    Problems problems{&places, {}};
    const YamlTree tree = read_yaml_tree(yaml_text, problems);
    if (!tree.readable) {
        result.text = std::string(yaml_text);
        result.problems = check_dictionary(yaml_text);
        return result;
    }
    std::vector<ConceptSlots> concepts = concept_slots(yaml_text, tree);
    std::map<std::string, size_t> by_id;
    for (size_t i = 0; i < concepts.size(); ++i) by_id.emplace(concepts[i].id, i);

    std::vector<Splice> splices;
    std::vector<DictionaryProblem> edit_problems;
    const auto problem = [&](size_t n, int node, const std::string& message) {
        long line = 0, column = 0;
        if (node >= 0) std::tie(line, column) = places.at(at(tree, node).offset);
        edit_problems.push_back({line, column, "edit " + std::to_string(n + 1) + ": " + message});
    };
    // Replaces the scalar `node` by `text`, or the earlier replacement of it.
    const auto replace = [&](int& slot, int node, bool flow, const std::string& text) {
        if (slot >= 0) {
            splices[static_cast<size_t>(slot)].text = text;
            return true;
        }
        size_t begin = 0, end = 0;
        if (!scalar_span(yaml_text, at(tree, node), flow, begin, end)) return false;
        slot = static_cast<int>(splices.size());
        splices.push_back({begin, end, text, static_cast<int>(splices.size())});
        return true;
    };

    for (size_t n = 0; n < edits.size(); ++n) {
        const DictionaryEdit& e = edits[n];
        const auto found = by_id.find(e.concept_id);
        if (found == by_id.end()) {
            problem(n, -1, "unknown concept " + quoted(e.concept_id));
            continue;
        }
        ConceptSlots& c = concepts[found->second];
        if (e.kind == DictionaryEdit::Kind::Bound) {
            const int side = e.upper ? 1 : 0;
            const char* which = e.upper ? "upper" : "lower";
            if (c.bound[side] < 0 || at(tree, c.bound[side]).kind != YNode::Kind::Scalar) {
                problem(n, -1, "concept " + quoted(e.concept_id) + " has no interval to edit");
                continue;
            }
            const std::string key = bound_key(e.value);
            if (key.empty()) {
                problem(n, c.bound[side],
                        std::string(which) + " bound " + quoted(e.value) + " of " +
                            quoted(e.concept_id) +
                            " is not a number (write a decimal such as 0.05, or .inf / -.inf)");
                continue;
            }
            // the neighbour that shares this bound: its other side written as the same number
            ConceptSlots* neighbour = nullptr;
            const std::string& old_key = c.bound_key[side];
            if (!old_key.empty() && old_key != "+inf" && old_key != "-inf")
                for (ConceptSlots& o : concepts)
                    if (&o != &c && o.feature == c.feature && o.bound_key[1 - side] == old_key) {
                        neighbour = &o;
                        break;
                    }
            if (!replace(c.splice_of_bound[side], c.bound[side], c.bound_flow, e.value)) {
                problem(n, c.bound[side],
                        "the " + std::string(which) + " bound of " + quoted(e.concept_id) +
                            " is not written as one value on one line; edit it by hand");
                continue;
            }
            c.bound_key[side] = key;
            if (neighbour && replace(neighbour->splice_of_bound[1 - side],
                                     neighbour->bound[1 - side], neighbour->bound_flow, e.value))
                neighbour->bound_key[1 - side] = key;
        } else {
            if (!detail::is_language_tag(e.language)) {
                problem(n, -1,
                        "label language " + quoted(e.language) + " of " + quoted(e.concept_id) +
                            " is not a language tag (en, fr, pt-BR)");
                continue;
            }
            if (c.labels < 0 || at(tree, c.labels).kind != YNode::Kind::Map) {
                problem(n, -1, "concept " + quoted(e.concept_id) + " has no 'labels' map to edit");
                continue;
            }
            const YNode& labels = at(tree, c.labels);
            const bool flow = is_flow(yaml_text, labels);
            const int value = entry(tree, c.labels, e.language);
            auto slot = c.splice_of_label.find(e.language);
            if (value >= 0 || slot != c.splice_of_label.end()) {
                if (slot != c.splice_of_label.end() && value < 0) {
                    // a label added by an earlier edit: rewrite the added entry
                    Splice& s = splices[static_cast<size_t>(slot->second)];
                    const std::string head = s.text.substr(0, s.text.find(e.language + ": "));
                    s.text = head + e.language + ": " + scalar_text(e.value, 0, flow);
                    continue;
                }
                const char style = yaml_text[at(tree, value).offset];
                int& index = c.splice_of_label[e.language];
                if (slot == c.splice_of_label.end()) index = -1;
                if (!replace(index, value, flow, scalar_text(e.value, style, flow))) {
                    c.splice_of_label.erase(e.language);
                    problem(n, value,
                            "the " + e.language + " label of " + quoted(e.concept_id) +
                                " is not written on one line; edit it by hand");
                }
                continue;
            }
            // a new language: after the last label
            const int last = labels.items.empty() ? -1 : labels.items.back();
            Splice s;
            if (!insert_entry(yaml_text, tree, c.labels, last, e.language, e.value, s)) {
                problem(n, c.labels,
                        "cannot add a " + e.language + " label to " + quoted(e.concept_id) +
                            " (its labels are not one value per line); edit it by hand");
                continue;
            }
            s.order = static_cast<int>(splices.size());
            c.splice_of_label[e.language] = static_cast<int>(splices.size());
            splices.push_back(std::move(s));
        }
    }
    result.text = splice(yaml_text, std::move(splices));
    result.problems = std::move(edit_problems);
    for (auto& p : check_dictionary(result.text)) result.problems.push_back(std::move(p));
    return result;
}

std::string next_version(std::string_view version) {
    std::string v(version);
    size_t end = v.size();
    while (end > 0 && !std::isdigit(static_cast<unsigned char>(v[end - 1]))) --end;
    if (end == 0) return v + ".1";
    // add one to the digits ending at `end`, carrying to the left
    size_t i = end;
    while (i > 0 && std::isdigit(static_cast<unsigned char>(v[i - 1]))) {
        --i;
        if (v[i] != '9') {
            ++v[i];
            return v;
        }
        v[i] = '0';
    }
    v.insert(i, "1");
    return v;
}

std::string stamp_new_version(std::string_view yaml_text, std::string_view today) {
    if (!detail::is_calendar_date(today))
        throw InvalidInput("stamp_new_version: " + quoted(std::string(today)) +
                           " is not a date YYYY-MM-DD");
    const Places places(yaml_text);
    Problems problems{&places, {}};
    const YamlTree tree = read_yaml_tree(yaml_text, problems);
    const int scheme = tree.readable && !tree.roots.empty() && tree.roots[0] >= 0
                           ? entry(tree, tree.roots[0], "scheme")
                           : -1;
    const int version = entry(tree, scheme, "version");
    if (version < 0 || at(tree, version).kind != YNode::Kind::Scalar)
        throw InvalidInput("stamp_new_version: the dictionary has no scheme.version to bump");
    const bool flow = is_flow(yaml_text, at(tree, scheme));
    std::vector<Splice> splices;
    size_t begin = 0, end = 0;
    if (!scalar_span(yaml_text, at(tree, version), flow, begin, end))
        throw InvalidInput("stamp_new_version: scheme.version is not one value on one line");
    const YNode& v = at(tree, version);
    splices.push_back(
        {begin, end, scalar_text(next_version(v.value), yaml_text[v.offset], flow), 0});
    const int modified = entry(tree, scheme, "modified");
    if (modified >= 0) {
        const YNode& m = at(tree, modified);
        if (m.kind != YNode::Kind::Scalar || !scalar_span(yaml_text, m, flow, begin, end))
            throw InvalidInput("stamp_new_version: scheme.modified is not one value on one line");
        // a date written bare reads back as the same text (yaml-cpp keeps it)
        const char style = yaml_text[m.offset];
        splices.push_back({begin, end,
                           style == '"' || style == '\''
                               ? scalar_text(std::string(today), style, flow)
                               : std::string(today),
                           1});
    } else {
        Splice s;
        if (!insert_entry(yaml_text, tree, scheme, version, "modified", std::string(today), s))
            throw InvalidInput("stamp_new_version: cannot add scheme.modified after version");
        // insert_entry quotes a date (it reads as a timestamp in YAML 1.1); bare is the format
        const std::string quoted_date = scalar_text(std::string(today), 0, flow);
        s.text.replace(s.text.size() - quoted_date.size(), quoted_date.size(), today);
        s.order = 1;
        splices.push_back(std::move(s));
    }
    return splice(yaml_text, std::move(splices));
}

}  // namespace geotex
