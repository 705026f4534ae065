#include "cli/dictionary_input.hpp"

#include <cstdio>
#include <cstdlib>
#include <ctime>

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

DictionarySource load_dictionary_source(const std::string& path) {
    DictionarySource source;
    source.name = path.empty() ? std::string(kDefaultDictionaryName) : path;
    source.text = path.empty() ? std::string(kDefaultDictionaryText) : read_text_file(path);
    source.dictionary = in_phase(kExitInput, source.name,
                                 [&] { return parse_dictionary(source.text, source.name); });
    // Every command reads its dictionary here, once: a curator sees what deserves a look (an
    // older dictionary without facets) whichever command used it, even with --quiet, since it
    // changes what the annotations may say.
    for (const auto& w : source.dictionary.warnings)
        std::fprintf(stderr, "%s:%ld:%ld: warning: %s\n", detail::message_text(source.name).c_str(),
                     w.line, w.column, detail::message_text(w.message).c_str());
    return source;
}

Dictionary load_dictionary(const std::string& path) {
    return load_dictionary_source(path).dictionary;
}

std::string version_date() {
    std::time_t now = std::time(nullptr);
    if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"))
        now = static_cast<std::time_t>(std::strtoll(epoch, nullptr, 10));
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[16];
    std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
    return buf;
}

}  // namespace geotex::cli
