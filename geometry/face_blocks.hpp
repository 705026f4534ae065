#pragma once
/// The faces of a mesh that is not held whole, read a block at a time in face order: the mesh
/// job of a tiled run keeps a large scan's faces on disk (DIR/mesh.part) and passes over them
/// as it needs them, holding the positions and a block.

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace geotex {

/// Faces [first, first + count) of a mesh, into `out` (#count by 3). May throw (a file that
/// ends early, an index past the last vertex).
using FaceBlockReader =
    std::function<void(std::size_t first, std::size_t count, std::vector<std::array<int, 3>>& out)>;

/// A reader of faces held in memory (which must outlive it), for the code that takes faces a
/// block at a time to run on a mesh held whole. Throws std::out_of_range past the last face.
inline FaceBlockReader face_reader(const std::vector<std::array<int, 3>>& faces) {
    return [&faces](std::size_t first, std::size_t count, std::vector<std::array<int, 3>>& out) {
        if (first > faces.size() || count > faces.size() - first)
            throw std::out_of_range("face_reader: faces " + std::to_string(first) + " to " +
                                    std::to_string(first + count) + " of " +
                                    std::to_string(faces.size()));
        const auto begin = faces.begin() + static_cast<std::ptrdiff_t>(first);
        out.assign(begin, begin + static_cast<std::ptrdiff_t>(count));
    };
}

/// About 12 MB of faces: large enough that a file is read at disk speed.
constexpr std::size_t kFaceBlock = std::size_t{1} << 20;

/// Calls fn(first, block) for faces [0, num_faces) of `read`, in order, `block_size` at a time;
/// block[i] is face first + i.
template <class Fn>
void for_each_face_block(const FaceBlockReader& read, std::size_t num_faces, Fn&& fn,
                         std::size_t block_size = kFaceBlock) {
    std::vector<std::array<int, 3>> block;
    for (std::size_t first = 0; first < num_faces; first += block_size) {
        read(first, std::min(block_size, num_faces - first), block);
        fn(first, static_cast<const std::vector<std::array<int, 3>>&>(block));
    }
}

}  // namespace geotex
