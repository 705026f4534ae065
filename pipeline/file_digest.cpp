#include "pipeline/file_digest.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "annotation/digest.hpp"
#include "common/errors.hpp"

namespace geotex {

std::string file_sha256(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw IoError("cannot read: it is a directory", path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(std::string("cannot open (") + std::strerror(errno) + ")", path);
    Sha256 hash;
    std::string chunk(1 << 20, '\0');
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        hash.update(std::string_view(chunk).substr(0, static_cast<std::size_t>(in.gcount())));
    }
    if (in.bad()) throw IoError("read failed", path);
    return hash.hex();
}

}  // namespace geotex
