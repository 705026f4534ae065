#pragma once
/// Integers kept on disk for a while by a step that cannot hold them: the repair of a tiled
/// run's mesh job keeps a large scan's polygons and triangles there (docs/tiles.md), and holds
/// the positions and a block.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/face_blocks.hpp"

namespace geotex {

/// 32-bit integers appended to a file and read back from any place. The file has no name once
/// created (it is unlinked at once), so that it goes with the object, or with the process when
/// that is killed, and two of them never meet. Not for concurrent use.
class ScratchFile {
  public:
    /// An empty file in the directory `dir`. Throws IoError naming `dir` when it cannot be
    /// created there.
    explicit ScratchFile(const std::string& dir);
    ScratchFile(ScratchFile&& other) noexcept;
    ScratchFile& operator=(ScratchFile&& other) noexcept;
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;
    ~ScratchFile();

    /// Appends `count` values. Throws IoError naming the directory when the disk is full.
    void append(const int* values, std::size_t count);
    void append(const std::array<int, 3>& face) { append(face.data(), 3); }
    /// The values appended so far.
    std::size_t size() const { return written_ + buffer_.size(); }
    /// Values [first, first + count) into `out`. Throws std::out_of_range past the end, and
    /// IoError when the file cannot be read.
    void read(std::size_t first, std::size_t count, int* out);

  private:
    void flush();

    std::string dir_;
    int fd_ = -1;
    std::size_t written_ = 0;  // values in the file
    std::vector<int> buffer_;  // values appended and not yet written
};

/// The faces of `file`, three values each, a block at a time; refers to `file`, which must
/// outlive it.
FaceBlockReader face_reader(ScratchFile& file);

}  // namespace geotex
