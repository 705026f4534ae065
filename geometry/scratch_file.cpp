#include "geometry/scratch_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/mapped_file.hpp"

namespace geotex {

namespace {

// About 4 MB written at a time: large enough for disk speed, small beside a scan's arrays.
constexpr std::size_t kBufferBytes = std::size_t{4} << 20;

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

template <class T>
ScratchArray<T>::ScratchArray(const std::string& dir) : dir_(dir) {
    std::string name = (dir.empty() ? std::string(".") : dir) + "/.geotex-scratch-XXXXXX";
    fd_ = ::mkstemp(name.data());
    if (fd_ < 0) fail(dir_, "create");
    ::unlink(name.c_str());
    buffer_.reserve(kBufferBytes / sizeof(T));
}

template <class T>
ScratchArray<T>::ScratchArray(ScratchArray&& other) noexcept
    : dir_(std::move(other.dir_)),
      fd_(std::exchange(other.fd_, -1)),
      written_(std::exchange(other.written_, 0)),
      buffer_(std::move(other.buffer_)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      mapped_bytes_(std::exchange(other.mapped_bytes_, 0)) {}

template <class T>
ScratchArray<T>& ScratchArray<T>::operator=(ScratchArray&& other) noexcept {
    if (this != &other) {
        release();
        dir_ = std::move(other.dir_);
        fd_ = std::exchange(other.fd_, -1);
        written_ = std::exchange(other.written_, 0);
        buffer_ = std::move(other.buffer_);
        mapped_ = std::exchange(other.mapped_, nullptr);
        mapped_bytes_ = std::exchange(other.mapped_bytes_, 0);
    }
    return *this;
}

template <class T>
ScratchArray<T>::~ScratchArray() {
    release();
}

template <class T>
void ScratchArray<T>::release() {
    if (mapped_ != nullptr) ::munmap(const_cast<T*>(mapped_), mapped_bytes_);
    mapped_ = nullptr;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

template <class T>
void ScratchArray<T>::append(const T* values, std::size_t count) {
    if (mapped_ != nullptr) throw std::logic_error("ScratchArray::append: the file is mapped");
    const std::size_t capacity = kBufferBytes / sizeof(T);
    while (count > 0) {
        const std::size_t n = std::min(count, capacity - buffer_.size());
        buffer_.insert(buffer_.end(), values, values + n);
        values += n;
        count -= n;
        if (buffer_.size() == capacity) flush();
    }
}

template <class T>
void ScratchArray<T>::flush() {
    transfer(::pwrite, fd_, reinterpret_cast<const char*>(buffer_.data()),
             buffer_.size() * sizeof(T), written_ * sizeof(T), dir_, "write");
    written_ += buffer_.size();
    buffer_.clear();
}

template <class T>
void ScratchArray<T>::read(std::size_t first, std::size_t count, T* out) {
    if (first > size() || count > size() - first)
        throw std::out_of_range("ScratchArray::read: values " + std::to_string(first) + " to " +
                                std::to_string(first + count) + " of " + std::to_string(size()));
    if (!buffer_.empty() && first + count > written_) flush();
    transfer(::pread, fd_, reinterpret_cast<char*>(out), count * sizeof(T), first * sizeof(T), dir_,
             "read");
}

template <class T>
const T* ScratchArray<T>::map() {
    if (mapped_ != nullptr || size() == 0) return mapped_;
    if (!buffer_.empty()) flush();
    buffer_ = std::vector<T>();  // nothing more is appended
    // Written with pwrite, not through a writable mapping, so that a full disk is an IoError
    // here rather than a SIGBUS at a page; the file has no name, so no other program can cut it
    // short under the mapping.
    const std::size_t bytes = written_ * sizeof(T);
    const char* p = detail::map_read_only(fd_, bytes);
    if (p == nullptr) fail(dir_, "map");
    mapped_ = reinterpret_cast<const T*>(p);
    mapped_bytes_ = bytes;
    return mapped_;
}

template class ScratchArray<int>;
template class ScratchArray<double>;

FaceBlockReader face_reader(ScratchFile& file) {
    static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int), "faces are read as ints");
    return [&file](std::size_t first, std::size_t count, std::vector<std::array<int, 3>>& out) {
        out.resize(count);
        file.read(3 * first, 3 * count, out.empty() ? nullptr : out.front().data());
    };
}

void PositionFile::append(PositionSpan positions) {
    if (!positions.empty()) file_.append(positions.begin()->data(), 3 * positions.size());
}

PositionSpan PositionFile::positions() {
    // A Vector3d is its three doubles, as std::vector<Eigen::Vector3d> lays them out too.
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double) &&
                      alignof(Eigen::Vector3d) <= alignof(double),
                  "positions are mapped as doubles");
    return {reinterpret_cast<const Eigen::Vector3d*>(file_.map()), size()};
}

namespace {

// The grid of SpaceOrderedPositions: 2^7 cells a side, 2^21 in all (8 MB of counts). At sphere-1
// level 11 a cell the surface crosses holds about 800 vertices, 20 KB of the copy.
constexpr int kCellBits = 7;
constexpr int kCellsPerSide = 1 << kCellBits;

// The Morton order of the grid's cells: a position's cell number interleaves the bits of its
// three cell coordinates, so that cells near each other mostly have numbers near each other.
class MortonCells {
  public:
    explicit MortonCells(PositionSpan positions) {
        const Eigen::AlignedBox3d box = bounding_box(positions);
        lo_ = box.min();
        for (int a = 0; a < 3; ++a) {
            const double side = box.max()[a] - box.min()[a];
            scale_[a] = side > 0 ? kCellsPerSide / side : 0.0;
        }
        for (std::uint32_t x = 0; x < kCellsPerSide; ++x)
            for (int b = 0; b < kCellBits; ++b) spread_[x] |= ((x >> b) & 1U) << (3 * b);
    }

    static constexpr std::size_t count() { return std::size_t{1} << (3 * kCellBits); }

    std::uint32_t operator()(const Eigen::Vector3d& p) const {
        std::uint32_t cell = 0;
        for (int a = 0; a < 3; ++a) {
            const double t = (p[a] - lo_[a]) * scale_[a];  // the highest side's end is 128
            const double c = t >= 0 ? std::min(t, kCellsPerSide - 1.0) : 0.0;
            cell |= spread_[static_cast<std::uint32_t>(c)] << a;
        }
        return cell;
    }

  private:
    Eigen::Vector3d lo_, scale_;
    std::array<std::uint32_t, kCellsPerSide> spread_{};
};

}  // namespace

SpaceOrderedPositions::SpaceOrderedPositions(PositionSpan positions, const std::string& dir,
                                             std::size_t share_bytes)
    : copy_(dir), place_file_(dir), id_file_(dir) {
    const PositionSpan in_order = positions.in_order();
    const std::size_t nv = in_order.size();
    if (nv == 0) return;
    {
        // Each vertex's place: a counting sort by cell, the vertices of a cell in vertex order.
        const MortonCells cell_of(in_order);
        std::vector<std::uint32_t> next(MortonCells::count(), 0);
        for (const Eigen::Vector3d& p : in_order) ++next[cell_of(p)];
        std::uint32_t first = 0;
        for (std::uint32_t& n : next) first += std::exchange(n, first);
        for (const Eigen::Vector3d& p : in_order) {
            const int place = static_cast<int>(next[cell_of(p)]++);
            place_file_.append(&place, 1);
        }
    }
    places_ = place_file_.map();
    // The copy and the places' vertices, a share of the places at a time: the positions are
    // read in order, never from here and there.
    const std::size_t share = std::max<std::size_t>(1, share_bytes / sizeof(Eigen::Vector3d));
    std::vector<Eigen::Vector3d> buffer;
    std::vector<int> ids;
    for (std::size_t first = 0; first < nv; first += share) {
        buffer.resize(std::min(share, nv - first));
        ids.resize(buffer.size());
        for (std::size_t v = 0; v < nv; ++v) {
            const std::size_t k = static_cast<std::size_t>(places_[v]) - first;  // wraps below
            if (k < buffer.size()) {
                buffer[k] = in_order[v];
                ids[k] = static_cast<int>(v);
            }
        }
        copy_.append(buffer);
        id_file_.append(ids.data(), ids.size());
    }
    release(buffer);
    release(ids);
    copy_span_ = copy_.positions();
    ids_ = id_file_.map();
    positions_ = PositionSpan(in_order.begin(), nv, copy_span_.begin(), places_);
}

ScratchFile faces_in_places(const FaceBlockReader& faces, std::size_t num_faces, const int* places,
                            const std::string& dir) {
    ScratchFile out(dir);
    std::vector<std::array<int, 3>> placed;
    for_each_face_block(faces, num_faces, [&](std::size_t, const auto& block) {
        placed = block;
        for (std::array<int, 3>& t : placed)
            for (int& v : t) v = places[v];
        if (!placed.empty()) out.append(placed.front().data(), 3 * placed.size());
    });
    return out;
}

}  // namespace geotex
