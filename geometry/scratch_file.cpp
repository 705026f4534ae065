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

// All `size` bytes at offset `at` through `io` (::pread or ::pwrite), which may move fewer at a
// time; `what` names the failure ("read", "write").
template <class Io, class Byte>
void transfer(Io io, int fd, Byte* bytes, std::size_t size, std::size_t at, const std::string& dir,
              const char* what) {
    while (size > 0) {
        const ssize_t n = io(fd, bytes, size, static_cast<off_t>(at));
        if (n < 0 && errno == EINTR) continue;
        if (n == 0) errno = EIO;  // a read past what the file holds, or a write that stalls
        if (n <= 0) fail(dir, what);
        bytes += n;
        size -= static_cast<std::size_t>(n);
        at += static_cast<std::size_t>(n);
    }
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
    transfer(::pwrite, fd_, reinterpret_cast<const char*>(buffer_.data()),
             buffer_.size() * sizeof(int), written_ * sizeof(int), dir_, "write");
    written_ += buffer_.size();
    buffer_.clear();
}

void ScratchFile::read(std::size_t first, std::size_t count, int* out) {
    if (first > size() || count > size() - first)
        throw std::out_of_range("ScratchFile::read: values " + std::to_string(first) + " to " +
                                std::to_string(first + count) + " of " + std::to_string(size()));
    if (!buffer_.empty() && first + count > written_) flush();
    transfer(::pread, fd_, reinterpret_cast<char*>(out), count * sizeof(int), first * sizeof(int),
             dir_, "read");
}

FaceBlockReader face_reader(ScratchFile& file) {
    static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int), "faces are read as ints");
    return [&file](std::size_t first, std::size_t count, std::vector<std::array<int, 3>>& out) {
        out.resize(count);
        file.read(3 * first, 3 * count, out.empty() ? nullptr : out.front().data());
    };
}

}  // namespace geotex
