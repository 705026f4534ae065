#include "annotation/yaml_tree.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <map>
#include <sstream>

namespace geotex::yaml_detail {

namespace {

using detail::code_point_name;

// yaml-cpp's Node API keeps the last of duplicate keys and forgets where scalars were quoted;
// the event stream keeps both, with the place of every node.

/// Thrown by TreeBuilder when yaml-cpp keeps sending events without reading on: a stray
/// ',' at the top level makes yaml-cpp 0.7 start empty documents at the same place forever.
struct NoProgress {
    size_t offset;
};

class TreeBuilder : public YAML::EventHandler {
  public:
    /// `bom`: length of the byte order mark yaml-cpp skipped; `text_size`: bytes of the text.
    TreeBuilder(size_t bom, size_t text_size) : bom_(bom), max_events_(4 * text_size + 64) {}

    std::vector<YNode> nodes;
    std::vector<int> roots;  ///< one per document
    std::vector<size_t> document_starts;

    void OnDocumentStart(const YAML::Mark& mark) override {
        const size_t at = offset(mark);
        count(at);
        if (!document_starts.empty() && at <= document_starts.back()) throw NoProgress{at};
        document_starts.push_back(at);
        roots.push_back(-1);
        stack_.clear();
    }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        add(YNode::Kind::Null, mark, "", "", anchor);
    }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        count(offset(mark));
        const auto it = anchors_.find(anchor);
        if (it != anchors_.end()) attach(it->second);
    }
    void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  const std::string& value) override {
        add(YNode::Kind::Scalar, mark, tag, value, anchor);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        stack_.push_back(add(YNode::Kind::Sequence, mark, tag, "", anchor));
    }
    void OnSequenceEnd() override {
        if (!stack_.empty()) stack_.pop_back();
    }
    void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value) override {
        stack_.push_back(add(YNode::Kind::Map, mark, tag, "", anchor));
    }
    void OnMapEnd() override {
        if (!stack_.empty()) stack_.pop_back();
    }

    size_t offset(const YAML::Mark& mark) const {
        // yaml-cpp counts bytes from after the byte order mark
        return mark.is_null() || mark.pos < 0 ? 0 : static_cast<size_t>(mark.pos) + bom_;
    }

  private:
    // A node takes at least half a character ("? " is two empty nodes), so more events than
    // a few per byte means that yaml-cpp is not reading on.
    void count(size_t at) {
        if (++num_events_ > max_events_) throw NoProgress{at};
    }
    int add(YNode::Kind kind, const YAML::Mark& mark, const std::string& tag,
            const std::string& value, YAML::anchor_t anchor) {
        count(offset(mark));
        YNode n;
        n.kind = kind;
        n.offset = offset(mark);
        n.tag = tag;
        n.value = value;
        nodes.push_back(std::move(n));
        const int id = static_cast<int>(nodes.size()) - 1;
        if (anchor != YAML::NullAnchor) anchors_[anchor] = id;
        attach(id);
        return id;
    }
    // Children are attached when they start, so a document cut short by a syntax error still
    // has every node read so far (for the duplicate-key check).
    void attach(int id) {
        if (!stack_.empty())
            nodes[stack_.back()].items.push_back(id);
        else if (!roots.empty() && roots.back() < 0)
            roots.back() = id;
    }

    size_t bom_;
    size_t max_events_;
    size_t num_events_ = 0;
    std::vector<int> stack_;
    std::map<YAML::anchor_t, int> anchors_;
};

/// Where an unterminated quoted scalar starts, or npos. yaml-cpp lets a quote that is never
/// closed run to the end of the input without complaint; re-scan each quoted scalar here.
size_t unterminated_quote(std::string_view text, const YNode& n) {
    if (n.kind != YNode::Kind::Scalar || n.tag != "!" || n.offset >= text.size())
        return std::string::npos;
    const char q = text[n.offset];
    if (q != '"' && q != '\'') return std::string::npos;  // a block scalar (| or >)
    for (size_t i = n.offset + 1; i < text.size(); ++i) {
        if (q == '"' && text[i] == '\\') {
            ++i;
        } else if (text[i] == q) {
            if (q == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
                ++i;  // '' is an escaped quote
            } else {
                return std::string::npos;
            }
        }
    }
    return n.offset;
}

/// Where the quoted scalar that yaml-cpp found unterminated ("illegal EOF in scalar") opens,
/// or npos. The parser's exception only gives the end of the file, so the text is scanned
/// with the few YAML rules that decide where a quote opens a scalar: at the start of a line
/// (after the indentation), after "- ", "? ", ": ", '[', '{' or ','; not inside a comment,
/// a plain scalar (l'objet) or a block scalar (| or >); quoted scalars that close are skipped.
size_t unclosed_quote_by_scan(std::string_view text) {
    size_t i = text.substr(0, kUtf8Bom.size()) == kUtf8Bom ? kUtf8Bom.size() : 0;
    const auto blank = [&](size_t k) {
        return k >= text.size() || text[k] == ' ' || text[k] == '\t' || text[k] == '\n' ||
               text[k] == '\r';
    };
    const auto line_indent = [&](size_t k) {
        const size_t newline = k == 0 ? std::string_view::npos : text.rfind('\n', k - 1);
        size_t at = newline == std::string_view::npos ? 0 : newline + 1;
        size_t n = 0;
        while (at < text.size() && text[at++] == ' ') ++n;
        return n;
    };
    bool scalar_may_start = true;
    while (i < text.size()) {
        const char c = text[i];
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
            continue;
        }
        if (c == '\n') {
            scalar_may_start = true;
            ++i;
            continue;
        }
        if (c == '#' && (i == 0 || blank(i - 1))) {
            while (i < text.size() && text[i] != '\n') ++i;
            continue;
        }
        if (scalar_may_start && (c == '"' || c == '\'')) {
            size_t j = i + 1;
            bool closed = false;
            for (; j < text.size(); ++j) {
                if (c == '"' && text[j] == '\\') {
                    ++j;
                } else if (text[j] == c) {
                    if (c == '\'' && j + 1 < text.size() && text[j + 1] == '\'') {
                        ++j;
                    } else {
                        closed = true;
                        break;
                    }
                }
            }
            if (!closed) return i;
            i = j + 1;
            scalar_may_start = false;
            continue;
        }
        if (scalar_may_start && (c == '|' || c == '>')) {
            // skip the block: the lines indented deeper than the line that opens it
            const size_t indent = line_indent(i);
            while (i < text.size() && text[i] != '\n') ++i;
            while (i < text.size()) {
                const size_t next = i + 1;
                size_t n = 0;
                while (next + n < text.size() && text[next + n] == ' ') ++n;
                const bool empty_line = next + n >= text.size() || text[next + n] == '\n';
                if (!empty_line && n <= indent) break;
                i = text.find('\n', next);
                if (i == std::string_view::npos) return std::string_view::npos;
            }
            continue;
        }
        if (c == '[' || c == '{' || c == ',') {
            scalar_may_start = true;
        } else if ((c == '-' || c == '?' || c == ':') && blank(i + 1)) {
            scalar_may_start = true;
        } else {
            scalar_may_start = false;
        }
        ++i;
    }
    return std::string_view::npos;
}

/// Encoding: ill-formed UTF-8, and characters YAML does not allow in a stream.
void check_encoding(std::string_view text, Problems& problems) {
    size_t i = text.substr(0, kUtf8Bom.size()) == kUtf8Bom ? kUtf8Bom.size() : 0;
    while (i < text.size()) {
        char32_t cp = 0;
        const size_t n = detail::utf8_decode(text, i, cp);
        if (n == 0) {
            // one problem per run of bad bytes
            size_t j = i + 1;
            while (j < text.size() && detail::utf8_decode(text, j, cp) == 0) ++j;
            char byte[8];
            std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[i]));
            problems.add(i, "invalid UTF-8 (" + std::to_string(j - i) + " byte" +
                                (j - i == 1 ? "" : "s") + " from " + byte +
                                "); save the file as UTF-8");
            i = j;
            continue;
        }
        const bool allowed = cp == '\t' || cp == '\n' || cp == '\r' || (cp >= 0x20 && cp < 0x7F) ||
                             cp == 0x85 ||
                             (cp >= 0xA0 && cp != 0xFEFF && cp != 0xFFFE && cp != 0xFFFF);
        if (!allowed)
            problems.add(i, "the character " + code_point_name(cp) +
                                " is not allowed in YAML (write it as an escape in a double-quoted "
                                "string, or remove it)");
        i += n;
    }
}

constexpr const char* kUnclosedQuote =
    "quoted text is never closed (the quote runs to the end of the file)";

}  // namespace

const char* kind_name(YNode::Kind k) {
    switch (k) {
        case YNode::Kind::Null:
            return "nothing";
        case YNode::Kind::Scalar:
            return "a single value";
        case YNode::Kind::Sequence:
            return "a list";
        case YNode::Kind::Map:
            return "a map";
    }
    return "?";
}

YamlTree read_yaml_tree(std::string_view text, Problems& problems) {
    check_encoding(text, problems);
    const size_t bom = text.substr(0, kUtf8Bom.size()) == kUtf8Bom ? kUtf8Bom.size() : 0;
    TreeBuilder builder(bom, text.size());
    YamlTree tree;
    try {
        std::istringstream in{std::string(text)};
        YAML::Parser parser(in);
        while (parser.HandleNextDocument(builder)) {
        }
    } catch (const YAML::Exception& e) {
        const size_t quote = e.msg == YAML::ErrorMsg::EOF_IN_SCALAR ? unclosed_quote_by_scan(text)
                                                                    : std::string::npos;
        if (quote != std::string::npos)
            problems.add(quote, kUnclosedQuote);
        else
            problems.add(builder.offset(e.mark), "YAML syntax error: " + e.msg);
        tree.readable = false;
    } catch (const NoProgress& stuck) {
        problems.add(stuck.offset,
                     "YAML syntax error: the YAML reader cannot get past this point (a stray ',', "
                     "']' or '}'?)");
        tree.readable = false;
    }
    for (const YNode& n : builder.nodes) {
        const size_t at = unterminated_quote(text, n);
        if (at != std::string::npos) {
            problems.add(at, kUnclosedQuote);
            tree.readable = false;
        }
    }
    for (size_t d = 1; d < builder.roots.size(); ++d) {
        const int r = builder.roots[d];
        if (r >= 0 && builder.nodes[static_cast<size_t>(r)].kind != YNode::Kind::Null)
            problems.add(builder.document_starts[d],
                         "a second YAML document: a dictionary is one document (remove '---' and "
                         "what follows, or make it a separate file)");
    }
    tree.nodes = std::move(builder.nodes);
    tree.roots = std::move(builder.roots);
    return tree;
}

}  // namespace geotex::yaml_detail
