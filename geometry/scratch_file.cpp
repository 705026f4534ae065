#include "geometry/scratch_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "common/errors.hpp"

namespace geotex {

namespace {

// About 4 MB written at a time: large enough for disk speed, small beside a scan's arrays.
constexpr std::size_t kBufferValues = std::size_t{1} << 20;

[[noreturn]] void fail(const std::string& dir, const char* what) {
    throw IoError(std::string("cannot ") + what + " a scratch file (" + std::strerror(errno) + ")",
                  dir);
}

}  // namespace

ScratchFile::ScratchFile(const std::string& dir) : dir_(dir) {
    std::string name = (dir.empty() ? std::string(".") : dir) + "/.geotex-scratch-XXXXXX";
    fd_ = ::mkstemp(name.data());
    if (fd_ < 0) fail(dir_, "create");
    ::unlink(name.c_str());
    buffer_.reserve(kBufferValues);
}

ScratchFile::ScratchFile(ScratchFile&& other) noexcept
    : dir_(std::move(other.dir_)),
      fd_(std::exchange(other.fd_, -1)),
      written_(std::exchange(other.written_, 0)),
      buffer_(std::move(other.buffer_)) {}

ScratchFile& ScratchFile::operator=(ScratchFile&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        dir_ = std::move(other.dir_);
        fd_ = std::exchange(other.fd_, -1);
        written_ = std::exchange(other.written_, 0);
        buffer_ = std::move(other.buffer_);
    }
    return *this;
}

ScratchFile::~ScratchFile() {
    if (fd_ >= 0) ::close(fd_);
}

void ScratchFile::append(const int* values, std::size_t count) {
    while (count > 0) {
        const std::size_t n = std::min(count, kBufferValues - buffer_.size());
        buffer_.insert(buffer_.end(), values, values + n);
        values += n;
        count -= n;
        if (buffer_.size() == kBufferValues) flush();
    }
}

void ScratchFile::flush() {
    const char* bytes = reinterpret_cast<const char*>(buffer_.data());
    std::size_t left = buffer_.size() * sizeof(int);
    off_t at = static_cast<off_t>(written_ * sizeof(int));
    while (left > 0) {
        const ssize_t n = ::pwrite(fd_, bytes, left, at);
        if (n < 0 && errno == EINTR) continue;
        if (n == 0) errno = EIO;
        if (n <= 0) fail(dir_, "write");
        bytes += n;
        left -= static_cast<std::size_t>(n);
        at += n;
    }
    written_ += buffer_.size();
    buffer_.clear();
}

void ScratchFile::read(std::size_t first, std::size_t count, int* out) {
    if (first > size() || count > size() - first)
        throw std::out_of_range("ScratchFile::read: values " + std::to_string(first) + " to " +
                                std::to_string(first + count) + " of " + std::to_string(size()));
    if (!buffer_.empty() && first + count > written_) flush();
    char* bytes = reinterpret_cast<char*>(out);
    std::size_t left = count * sizeof(int);
    off_t at = static_cast<off_t>(first * sizeof(int));
    while (left > 0) {
        const ssize_t n = ::pread(fd_, bytes, left, at);
        if (n < 0 && errno == EINTR) continue;
        if (n == 0) errno = EIO;  // the file is shorter than what was written to it
        if (n <= 0) fail(dir_, "read");
        bytes += n;
        left -= static_cast<std::size_t>(n);
        at += n;
    }
}

FaceBlockReader face_reader(ScratchFile& file) {
    static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int), "faces are read as ints");
    return [&file](std::size_t first, std::size_t count, std::vector<std::array<int, 3>>& out) {
        out.resize(count);
        file.read(3 * first, 3 * count, out.empty() ? nullptr : out.front().data());
    };
}

}  // namespace geotex
