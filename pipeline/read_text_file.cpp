#include "pipeline/read_text_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"

namespace geotex {

std::string read_text_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw IoError("cannot read: it is a directory", path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(std::string("cannot open (") + std::strerror(errno) + ")", path);
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw IoError("read failed", path);
    return text.str();
}

}  // namespace geotex
