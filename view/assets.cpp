#include "view/assets.hpp"

#include <array>
#include <utility>

namespace geotex::view {

const EmbeddedAsset* find_asset(std::string_view name) {
    for (const EmbeddedAsset& a : embedded_assets())
        if (a.name == name) return &a;
    return nullptr;
}

std::string content_type_of(std::string_view name) {
    static const std::array<std::pair<std::string_view, std::string_view>, 9> kTypes = {{
        {".html", "text/html; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".json", "application/json"},
        {".png", "image/png"},
        {".svg", "image/svg+xml"},
        {".ico", "image/x-icon"},
        {".txt", "text/plain; charset=utf-8"},
        {".woff2", "font/woff2"},
    }};
    for (const auto& [ext, type] : kTypes)
        if (name.size() > ext.size() && name.substr(name.size() - ext.size()) == ext)
            return std::string(type);
    return "application/octet-stream";
}

std::string fill_token(std::string_view index_html, const std::string& token) {
    static constexpr std::string_view kMark = "__GEOTEX_TOKEN__";
    std::string out;
    std::size_t begin = 0;
    while (true) {
        const std::size_t at = index_html.find(kMark, begin);
        out.append(index_html.substr(
            begin, at == std::string_view::npos ? std::string_view::npos : at - begin));
        if (at == std::string_view::npos) return out;
        out += token;
        begin = at + kMark.size();
    }
}

}  // namespace geotex::view
