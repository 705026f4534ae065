#pragma once
// The polygons and positions a mesh reader parses (ply.cpp, obj_reader.cpp, off_reader.cpp,
// stl_reader.cpp): into the file's soup, or, when the caller gave a PolygonSink, to the sink a
// block at a time, so that the mesh job of a tiled run does not hold a scan's polygons (16
// bytes a triangle) or positions (24 bytes a vertex) as it reads them. The STL reader keeps its
// positions in the soup: it matches each corner to the positions read before.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "geometry/mesh_io.hpp"

namespace geotex::detail {

class PolygonCollector {
  public:
    /// Into `soup`, or to `sink` when it is set (the soup's polygons then stay empty). Both
    /// must outlive the collector.
    PolygonCollector(PolygonSoup& soup, const PolygonSink& sink)
        : sink_(sink), target_(sink ? &block_ : &soup) {}

    /// Room for `polygons` with `corners` in all; with a sink, for a block of them.
    void reserve(std::size_t polygons, std::size_t corners) {
        if (sink_) {
            corners = std::min(corners, kBlockCorners + kBlockCorners / 8);
            polygons = std::min(polygons, corners / 3 + 1);
        }
        target_->face_offsets.reserve(polygons + 1);
        target_->face_indices.reserve(corners);
    }

    /// Room for `vertices` positions; with a sink, for a block of them.
    void reserve_vertices(std::size_t vertices) {
        target_->positions.reserve(sink_ ? std::min(vertices, kBlockVertices) : vertices);
    }

    /// The next vertex's position.
    void vertex(const Eigen::Vector3d& p) { new_vertex() = p; }

    /// The next vertex, at the origin, for a reader that sets its coordinates one at a time
    /// (a PLY's properties) through vertex_being_read() before the next vertex or polygon.
    Eigen::Vector3d& new_vertex() {
        // A full block goes before the next vertex, so that it holds whole vertices only.
        if (sink_ && target_->positions.size() >= kBlockVertices && open_corners() == 0) flush();
        return target_->positions.emplace_back(0.0, 0.0, 0.0);
    }
    Eigen::Vector3d& vertex_being_read() { return target_->positions.back(); }

    /// The vertices read so far, in the soup or given to the sink.
    std::uint64_t num_vertices() const { return done_vertices_ + target_->positions.size(); }

    /// The next corner of the polygon being read.
    void corner(int v) { target_->face_indices.push_back(v); }

    /// The corners of the polygon being read, so far.
    std::size_t open_corners() const {
        return target_->face_indices.size() -
               static_cast<std::size_t>(target_->face_offsets.back());
    }

    /// Ends the polygon being read. The reader keeps num_corners() within an int.
    void end_polygon() {
        target_->face_offsets.push_back(static_cast<int>(target_->face_indices.size()));
        if (sink_ && block_.face_indices.size() >= kBlockCorners) flush();
    }

    /// The polygons ended so far, in the soup or given to the sink.
    std::int64_t num_polygons() const { return done_polygons_ + target_->num_polygons(); }
    /// Their corners, with those of the polygon being read.
    std::uint64_t num_corners() const { return done_corners_ + target_->face_indices.size(); }

    /// Gives the sink the polygons and positions it has not had yet; nothing without a sink.
    void finish() {
        if (sink_ && (block_.num_polygons() > 0 || !block_.positions.empty())) flush();
    }

  private:
    void flush() {
        sink_(block_);
        done_polygons_ += block_.num_polygons();
        done_corners_ += block_.face_indices.size();
        done_vertices_ += block_.positions.size();
        block_.face_offsets.resize(1);
        block_.face_indices.clear();
        block_.positions.clear();
    }

    // A block's corners, 4 MB, and positions, 6 MB: enough that the sink's call costs nothing
    // per polygon or vertex.
    static constexpr std::size_t kBlockCorners = std::size_t{1} << 20;
    static constexpr std::size_t kBlockVertices = std::size_t{1} << 18;

    const PolygonSink& sink_;
    PolygonSoup block_;
    PolygonSoup* target_;
    std::int64_t done_polygons_ = 0;
    std::uint64_t done_corners_ = 0;
    std::uint64_t done_vertices_ = 0;
};

}  // namespace geotex::detail
