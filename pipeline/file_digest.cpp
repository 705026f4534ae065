#include "pipeline/file_digest.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
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

std::optional<std::string> file_signature(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
    char line[160];
    std::snprintf(line, sizeof line, "size %lld inode %llu mtime %lld.%09ld ctime %lld.%09ld",
                  static_cast<long long>(st.st_size), static_cast<unsigned long long>(st.st_ino),
                  static_cast<long long>(st.st_mtim.tv_sec), st.st_mtim.tv_nsec,
                  static_cast<long long>(st.st_ctim.tv_sec), st.st_ctim.tv_nsec);
    return std::string(line);
}

}  // namespace geotex
