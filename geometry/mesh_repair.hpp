#pragma once
/// Turning a polygon soup into a clean, consistently oriented triangle mesh.

#include <string>
#include <vector>

#include "geometry/diagnostics.hpp"
#include "geometry/mesh.hpp"
#include "geometry/scratch_file.hpp"

namespace geotex {

struct MeshRepairParams {
    bool merge_duplicate_vertices = true;  ///< merge vertices with identical coordinates
    bool orient = true;                    ///< make face orientation consistent per component
    /// Above 1: the edges are matched and the faces oriented a spatial tile at a time
    /// (tiles.hpp's boxes, this many), holding one tile's edge tables instead of the whole
    /// mesh's, as the mesh job of a tiled run does (docs/tiles.md). The same result; a mesh that
    /// the tiles cannot orient alone (a non-orientable or flat closed surface) is done whole.
    int tiles = 1;
    /// With the faces on disk (repair_soup_on_disk) and `tiles` above 1: the faces an
    /// orientation tile should hold at most, on average. A larger mesh is oriented in more tiles
    /// than `tiles` (orientation_tiles, detail/repair_steps.hpp), since a tile's tables grow with
    /// it and the tiles of a tiled run are cut for the jobs after, not for the repair.
    std::size_t tile_faces = std::size_t{1} << 18;
    /// Fill MeshRepairResult::source_polygon. The command line reads it nowhere and leaves it
    /// out: at 4 bytes a face it is a tenth of a tiled run's mesh job.
    bool keep_sources = true;
};

/// What repair did and what it found, as counts.
struct MeshRepairReport {
    int num_input_vertices = 0;
    int num_input_polygons = 0;
    int num_polygons_triangulated = 0;  ///< polygons with more than 3 vertices
    int num_duplicate_vertices_merged = 0;
    int num_degenerate_faces_removed = 0;  ///< repeated vertex or zero area
    int num_duplicate_faces_removed = 0;   ///< same vertex set as an earlier face
    int num_faces_flipped = 0;
    int num_isolated_vertices = 0;  ///< kept (indices stay stable), used by no face
    int num_boundary_edges = 0;
    int num_non_manifold_edges = 0;  ///< edges with more than two faces
    int num_components = 0;          ///< face-connected components
    int num_closed_components = 0;
};

struct MeshRepairResult {
    Mesh mesh;
    /// #F: index of the input polygon each face comes from; empty without keep_sources
    std::vector<int> source_polygon;
    MeshRepairReport report;
    Diagnostics diagnostics;
};

/// Triangulates polygons, merges duplicate vertices, removes degenerate and duplicate
/// faces and orients faces consistently (outward on closed components; on open components
/// the orientation held by most input faces). Faces keep the input polygon order; vertices
/// keep their first-occurrence order, so a clean input comes out unchanged.
/// Throws InvalidInput on an index out of range, a non-finite coordinate, a polygon with
/// fewer than 3 vertices, or when no face is left.
MeshRepairResult repair_soup(const PolygonSoup& soup, const MeshRepairParams& params = {});

/// As above, giving up the soup (left empty) for a lower peak: its positions become the
/// mesh's, merged in place, and its polygons are released once triangulated, so that a large
/// scan's soup is not held beside the mesh and the repair's edge tables (the mesh job of a
/// tiled run at sphere-1 level 11: bench/RESULTS.md). The same result.
MeshRepairResult repair_soup(PolygonSoup&& soup, const MeshRepairParams& params = {});

/// repair_soup's result with the positions and faces on disk.
struct RepairedOnDisk {
    PositionFile positions;     ///< #V, read through positions.positions()
    ScratchFile faces;          ///< #F by 3, read back with face_reader(faces)
    std::size_t num_faces = 0;  ///< #F
    MeshRepairReport report;
    Diagnostics diagnostics;
};

/// A polygon soup whose positions and polygons wait in scratch files (each polygon's number of
/// corners, then its corners): a scan read with its polygons given to a PolygonSink
/// (mesh_io.hpp) that appends them here, so that they are never all held.
///
///     SoupOnDisk soup(dir);
///     MeshFile file = read_mesh_file(path, [&](const PolygonSoup& b) { soup.append(b); });
///     soup.positions.append(file.soup.positions);
///     RepairedOnDisk repaired = repair_soup_on_disk(std::move(soup), params, dir);
struct SoupOnDisk {
    /// No positions or polygons yet; they will go to scratch files in the directory
    /// `scratch_dir` (throws IoError naming it when a file cannot be made there).
    explicit SoupOnDisk(const std::string& scratch_dir)
        : positions(scratch_dir), polygons(scratch_dir) {}

    /// Appends the positions and polygons of `block` (a PolygonSink's). Throws IoError naming
    /// the directory when the disk is full, InvalidInput when the offsets do not fit the
    /// indices or the polygons outgrow an int.
    void append(const PolygonSoup& block);

    PositionFile positions;  ///< #P
    ScratchFile polygons;    ///< the polygons, in order
    int num_polygons = 0;
};

/// repair_soup(std::move(soup), params) for a scan too large to hold its faces beside their
/// repair (the mesh job of a tiled run, docs/tiles.md): the soup's polygons, then its
/// triangles, wait in scratch files in the directory `scratch_dir`, and the positions are read
/// through a mapping of theirs, while each step holds a block, the merge's numbers (4 bytes a
/// vertex), or with params.tiles above 1 one tile's edges; the positions and faces come back
/// in scratch files. The same positions, faces, report and notes. Where the tiles cannot tell
/// the orientation (repair_soup falls back to the whole mesh there), and with one tile, the
/// faces are held for steps (4) and (5) as repair_soup holds them. Throws as repair_soup,
/// IoError naming `scratch_dir` when a scratch file cannot be made or written (a full disk),
/// and std::invalid_argument when params.keep_sources asks for the sources, which it does not
/// keep.
RepairedOnDisk repair_soup_on_disk(PolygonSoup&& soup, const MeshRepairParams& params,
                                   const std::string& scratch_dir);

/// The same from a soup already on disk, nothing of which is held. Its checks are
/// repair_soup's, each error with the same words.
RepairedOnDisk repair_soup_on_disk(SoupOnDisk&& soup, const MeshRepairParams& params,
                                   const std::string& scratch_dir);

}  // namespace geotex
