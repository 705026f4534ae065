#include "geometry/detail/text.hpp"

namespace geotex::detail {

std::vector<TextToken> split_tokens(std::string_view line, bool hash_comments) {
    std::vector<TextToken> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        if (i >= line.size() || (hash_comments && line[i] == '#')) break;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i]) && !(hash_comments && line[i] == '#')) ++i;
        tokens.push_back({line.substr(start, i - start), static_cast<long>(start) + 1});
    }
    return tokens;
}

std::string printable(std::string_view s) {
    std::string out;
    for (char c : s.substr(0, 40)) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 32 && u < 127) {
            out += c;
        } else {
            static const char hex[] = "0123456789abcdef";
            out += "\\x";
            out += hex[u >> 4];
            out += hex[u & 15];
        }
    }
    if (s.size() > 40) out += "...";
    return out;
}

}  // namespace geotex::detail
