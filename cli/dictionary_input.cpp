#include "cli/dictionary_input.hpp"

#include <cstdio>

#include "annotation/digest.hpp"
#include "cli/output.hpp"
#include "common/detail/text.hpp"
#include "default_dictionary.hpp"
#include "pipeline/file_digest.hpp"
#include "pipeline/read_text_file.hpp"

namespace geotex::cli {

std::string read_text_file(const std::string& path) {
    return in_phase(kExitInput, path, [&] { return geotex::read_text_file(path); });
}

std::string sha256_of_file(const std::string& path) {
    return in_phase(kExitInput, path, [&] { return file_sha256(path); });
}

Dictionary load_dictionary(const std::string& path) {
    const std::string name = path.empty() ? std::string(kDefaultDictionaryName) : path;
    const std::string text =
        path.empty() ? std::string(kDefaultDictionaryText) : read_text_file(path);
    Dictionary d = in_phase(kExitInput, name, [&] { return parse_dictionary(text, name); });
    // Every command reads its dictionary here, once: a curator sees what deserves a look (an
    // older dictionary without facets) whichever command used it, even with --quiet, since it
    // changes what the annotations may say.
    for (const auto& w : d.warnings)
        std::fprintf(stderr, "%s:%ld:%ld: warning: %s\n", detail::message_text(name).c_str(),
                     w.line, w.column, detail::message_text(w.message).c_str());
    return d;
}

}  // namespace geotex::cli
