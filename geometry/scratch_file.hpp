#pragma once
/// Numbers kept on disk for a while by a step that cannot hold them: the repair of a tiled
/// run's mesh job keeps a large scan's polygons, triangles and positions there (docs/tiles.md),
/// and holds a block, or reads the positions through a mapping whose pages the system may drop
/// again when memory is short.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/face_blocks.hpp"
#include "geometry/mesh.hpp"

namespace geotex {

/// Values of type T (int or double) appended to a file and read back from any place. The file
/// has no name once created (it is unlinked at once), so that it goes with the object, or with
/// the process when that is killed, two of them never meet, and no other program can cut it
/// short under a mapping. Not for concurrent use.
template <class T>
class ScratchArray {
  public:
    /// An empty file in the directory `dir`. Throws IoError naming `dir` when it cannot be
    /// created there.
    explicit ScratchArray(const std::string& dir);
    ScratchArray(ScratchArray&& other) noexcept;
    ScratchArray& operator=(ScratchArray&& other) noexcept;
    ScratchArray(const ScratchArray&) = delete;
    ScratchArray& operator=(const ScratchArray&) = delete;
    ~ScratchArray();

    /// Appends `count` values. Throws IoError naming the directory when the disk is full, and
    /// std::logic_error once the file is mapped.
    void append(const T* values, std::size_t count);
    void append(const std::array<T, 3>& triple) { append(triple.data(), 3); }
    /// The values appended so far.
    std::size_t size() const { return written_ + buffer_.size(); }
    /// Values [first, first + count) into `out`. Throws std::out_of_range past the end, and
    /// IoError when the file cannot be read.
    void read(std::size_t first, std::size_t count, T* out);
    /// Every value, mapped read-only, for a step that reads them out of order: a page is read
    /// from the file when first touched, and the system may drop it again when memory is short,
    /// since the file holds it. Valid while the object lives; no value can be appended after.
    /// Throws IoError naming the directory when the last values cannot be written, and
    /// std::bad_alloc when the address space has no room for the mapping.
    const T* map();

  private:
    void flush();
    void release();

    std::string dir_;
    int fd_ = -1;
    std::size_t written_ = 0;  // values in the file
    std::vector<T> buffer_;    // values appended and not yet written
    const T* mapped_ = nullptr;
    std::size_t mapped_bytes_ = 0;
};

/// Integers: a scan's polygons and faces on disk.
using ScratchFile = ScratchArray<int>;

/// The faces of `file`, three values each, a block at a time; refers to `file`, which must
/// outlive it.
FaceBlockReader face_reader(ScratchFile& file);

/// The positions of a scan too large to hold (#V by 3 doubles), appended in order and then read
/// through a mapping: the steps of a tiled run's mesh job that look them up out of order take
/// the PositionSpan of positions(), and only the pages in use are in memory.
class PositionFile {
  public:
    /// No position yet; throws IoError naming `dir` when the file cannot be made there.
    explicit PositionFile(const std::string& dir) : file_(dir) {}

    /// Appends a position (IoError naming the directory on a full disk).
    void append(const Eigen::Vector3d& p) { file_.append(p.data(), 3); }
    void append(PositionSpan positions);
    /// The positions appended so far.
    std::size_t size() const { return file_.size() / 3; }
    /// The positions, mapped (ScratchArray::map, with its errors); none can be appended after.
    PositionSpan positions();

  private:
    ScratchArray<double> file_;
};

/// Positions (#V by 3 doubles, a PositionFile's) copied once more in the order of space, for the
/// steps that look them up face by face. The copy is sorted by the cell of a grid of 128 cells a
/// side over the positions' bounds, the cells in Morton order, so that the corners of faces near
/// each other lie near each other in it. A scan's vertex numbers need not follow space
/// (sphere-1's follow its subdivision levels): read in vertex order, a tile's faces have corners
/// on every page of the positions, which under a memory limit smaller than the positions are
/// read from disk again and again.
///
/// A vertex's *place* is its position's index in the copy. positions() reads the copy through
/// the places in operator[]; a step that can number the vertices by their places (the faces
/// renumbered by faces_in_places, StreamTiler) reads copy() and ids() without that look-up.
class SpaceOrderedPositions {
  public:
    /// Copies `positions` (read in vertex order, a pass for each `share_bytes` of the copy,
    /// which is what is held of it) into three scratch files in `dir`: the copy, each vertex's
    /// place and each place's vertex (IoError naming `dir`). `positions` must outlive the object.
    SpaceOrderedPositions(PositionSpan positions, const std::string& dir,
                          std::size_t share_bytes = std::size_t{128} << 20);

    /// The positions given, with operator[] reading the copy. Valid while the object lives.
    PositionSpan positions() const { return positions_; }
    /// The copy (#V): copy()[places()[v]] is vertex v's position.
    PositionSpan copy() const { return copy_span_; }
    /// Each vertex's place (#V).
    const int* places() const { return places_; }
    /// Each place's vertex (#V): the inverse of places().
    const int* ids() const { return ids_; }

  private:
    PositionFile copy_;
    ScratchFile place_file_, id_file_;
    PositionSpan positions_, copy_span_;
    const int* places_ = nullptr;
    const int* ids_ = nullptr;
};

/// The `num_faces` faces of `faces` with each corner replaced by its place (places[v]), in a
/// scratch file in `dir` (IoError naming it; what `faces` throws).
ScratchFile faces_in_places(const FaceBlockReader& faces, std::size_t num_faces, const int* places,
                            const std::string& dir);

}  // namespace geotex
