#include "pipeline/read_text_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/errors.hpp"

namespace geotex {

std::string read_text_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw IoError("cannot read: it is a directory", path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(std::string("cannot open (") + std::strerror(errno) + ")", path);
    // Read into a string of the file's size, not through a string stream, which grows its
    // buffer as it goes and copies it once more at the end: a tiled run's join reads texel
    // parts of tens of megabytes this way. A file that is not regular (a pipe) just grows it.
    std::string text;
    if (const auto size = std::filesystem::file_size(path, ec); !ec) text.reserve(size);
    char block[1 << 16];
    while (in.read(block, sizeof block) || in.gcount() > 0)
        text.append(block, static_cast<std::size_t>(in.gcount()));
    if (in.bad()) throw IoError("read failed", path);
    return text;
}

}  // namespace geotex
