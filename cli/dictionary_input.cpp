#include "cli/dictionary_input.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "annotation/digest.hpp"
#include "cli/output.hpp"
#include "default_dictionary.hpp"

namespace geotex::cli {

std::string read_text_file(const std::string& path) {
    // A directory opens as a stream that reads nothing: it would pass for an empty file.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw CliError(kExitInput, path + ": cannot read: it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CliError(kExitInput, path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw CliError(kExitInput, path + ": read failed");
    return text.str();
}

std::string sha256_of_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw CliError(kExitInput, path + ": cannot read: it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CliError(kExitInput, path + ": cannot open (" + std::strerror(errno) + ")");
    Sha256 hash;
    std::string chunk(1 << 20, '\0');
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        hash.update(std::string_view(chunk).substr(0, static_cast<std::size_t>(in.gcount())));
    }
    if (in.bad()) throw CliError(kExitInput, path + ": read failed");
    return hash.hex();
}

Dictionary load_dictionary(const std::string& path) {
    if (path.empty())
        return in_phase(kExitInput, kDefaultDictionaryName,
                        [&] { return parse_dictionary(kDefaultDictionaryText, kDefaultDictionaryName); });
    const std::string text = read_text_file(path);
    return in_phase(kExitInput, path, [&] { return parse_dictionary(text, path); });
}

}  // namespace geotex::cli
