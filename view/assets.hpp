#pragma once
/// The files of the workbench's page (view/web/) and the three.js it draws with (Debian's
/// libjs-three), built into the binary by cmake/embed_assets.cmake: no CDN, it works offline.

#include <string>
#include <string_view>
#include <vector>

namespace geotex::view {

struct EmbeddedAsset {
    std::string_view name;   ///< file name, e.g. "app.js"
    std::string_view bytes;  ///< the file's content
};

/// Every embedded asset, in the order of the build (view/web/ sorted, then three.js).
const std::vector<EmbeddedAsset>& embedded_assets();

/// The asset called `name`, or nullptr.
const EmbeddedAsset* find_asset(std::string_view name);

/// The Content-Type of a file name by its extension (html, js, css, png, svg, json, ...);
/// application/octet-stream for any other.
std::string content_type_of(std::string_view name);

/// index.html with every "__GEOTEX_TOKEN__" replaced by `token`.
std::string fill_token(std::string_view index_html, const std::string& token);

}  // namespace geotex::view
