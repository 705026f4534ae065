// repair_soup with the faces on disk (mesh_repair.hpp): the steps of mesh_repair.cpp, shared
// through detail/repair_steps.hpp, each a pass over a scratch file, the positions read through
// a mapping of theirs. What is held is, one step at a time, the merge's numbers (4 bytes a
// vertex) and a share of its sort, a block of polygons or triangles, or a tile and the
// orientation's 6 bytes a face: at sphere-1 level 11 the whole repair held the soup, the
// triangles and the positions at once (44 bytes a face).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/repair_steps.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/tiles.hpp"

namespace geotex {
namespace {

// The polygons of a SoupOnDisk in order, read a block at a time.
class PolygonStream {
  public:
    explicit PolygonStream(ScratchFile& file) : file_(file) {}

    // The next polygon's corners into `corners`; false after the last.
    bool next(std::vector<int>& corners) {
        if (done_ == file_.size() && at_ == block_.size()) return false;
        const int n = value();
        corners.resize(static_cast<std::size_t>(n));
        for (int& c : corners) c = value();
        return true;
    }

  private:
    int value() {
        if (at_ == block_.size()) {
            block_.resize(std::min(kBlock, file_.size() - done_));
            file_.read(done_, block_.size(), block_.data());
            done_ += block_.size();
            at_ = 0;
        }
        return block_[at_++];
    }

    static constexpr std::size_t kBlock = std::size_t{1} << 20;
    ScratchFile& file_;
    std::vector<int> block_;
    std::size_t at_ = 0, done_ = 0;
};

[[noreturn]] void refuse_sources() {
    throw std::invalid_argument("repair_soup_on_disk: the faces' sources are not kept");
}

// The matching's sort for step (1) holds 16 bytes a vertex: at most about this much at once,
// below what the orientation's tiles hold at sphere-1 level 11 (6 bytes a face, 500 MB).
constexpr std::size_t kMergeBytes = std::size_t{128} << 20;

// Step (1) for positions on disk: old vertex index -> new index into `remap`, as vertex_remap,
// with the positions kept (all of them without `merge`) in a file of their own, in order.
PositionFile merged_positions(PositionFile& input, bool merge, const std::string& scratch_dir,
                              std::vector<int>& remap) {
    const PositionSpan in = input.positions();
    if (!merge) {
        remap.resize(in.size());
        std::iota(remap.begin(), remap.end(), 0);
        return std::move(input);
    }
    PositionFile merged(scratch_dir);
    const int passes = 1 + static_cast<int>(16 * in.size() / kMergeBytes);
    remap = detail::first_occurrences(in, passes);
    detail::number_first_occurrences(remap, [&](int v) { merged.append(in[v]); });
    return merged;
}

}  // namespace

int detail::orientation_tiles(std::size_t num_faces, int asked, std::size_t most) {
    most = std::max<std::size_t>(most, 1);
    if (asked <= 1 || num_faces <= static_cast<std::size_t>(asked) * most) return asked;
    const std::size_t needed = (num_faces + most - 1) / most;
    std::size_t k = 1;
    while (k * k < needed) ++k;
    const std::size_t count = (k - 1) * k >= needed ? (k - 1) * k : k * k;
    return static_cast<int>(std::min<std::size_t>(count, std::numeric_limits<int>::max()));
}

void SoupOnDisk::append(const PolygonSoup& block) {
    detail::validate_offsets(block);
    if (static_cast<std::int64_t>(num_polygons) + block.num_polygons() >
        std::numeric_limits<int>::max()) {
        throw InvalidInput("more than " + std::to_string(std::numeric_limits<int>::max()) +
                           " polygons");
    }
    for (int p = 0; p < block.num_polygons(); ++p) {
        const int begin = block.face_offsets[p];
        const int n = block.face_offsets[p + 1] - begin;
        polygons.append(&n, 1);
        polygons.append(block.face_indices.data() + begin, static_cast<std::size_t>(n));
    }
    num_polygons += block.num_polygons();
    positions.append(block.positions);
}

RepairedOnDisk repair_soup_on_disk(PolygonSoup&& soup, const MeshRepairParams& params,
                                   const std::string& scratch_dir) {
    if (params.keep_sources) refuse_sources();
    // append checks the offsets, and the repair the rest in validate_soup's order: the soup is
    // checked once, with repair_soup's words.
    SoupOnDisk on_disk(scratch_dir);
    on_disk.append(soup);
    soup = PolygonSoup();
    return repair_soup_on_disk(std::move(on_disk), params, scratch_dir);
}

RepairedOnDisk repair_soup_on_disk(SoupOnDisk&& soup, const MeshRepairParams& params,
                                   const std::string& scratch_dir) {
    if (params.keep_sources) refuse_sources();
    detail::validate_positions(soup.positions.positions(), soup.num_polygons);
    MeshRepairReport report;
    report.num_input_vertices = static_cast<int>(soup.positions.size());
    report.num_input_polygons = soup.num_polygons;

    // The positions are read through a mapping of their file from here on: its pages are in
    // memory while a step reads them, and leave again when memory is short.
    std::optional<PositionFile> merged;
    std::optional<SpaceOrderedPositions> near;
    std::optional<ScratchFile> placed;  // the triangles in near's places
    PositionSpan positions;
    ScratchFile triangles(scratch_dir);
    std::size_t num_triangles = 0;
    double longest2 = 0;  // the longest edge, squared: the tiles' halo
    {
        // (1) merge bit-identical vertices, with the polygons on disk. The new numbers go with
        // this scope, before the orientation's tiles.
        std::vector<int> remap;
        merged =
            merged_positions(soup.positions, params.merge_duplicate_vertices, scratch_dir, remap);
        {
            const PositionFile done = std::move(soup.positions);  // its mapping and disk go now
        }
        positions = merged->positions();
        // For the orientation's tiles, the faces' corners are looked up through a copy in the
        // order of space from here on, and the tiles are cut from the faces in its places.
        if (params.tiles > 1) {
            near.emplace(positions, scratch_dir);
            positions = near->positions();
            placed.emplace(scratch_dir);
        }
        report.num_duplicate_vertices_merged =
            report.num_input_vertices - static_cast<int>(positions.size());

        // (2) triangulate, keeping the polygon order, and (3) drop the degenerate faces; each
        // polygon checked first (step 0, with repair_soup's words once the pass is over).
        detail::PolygonCheck check(report.num_input_vertices);
        PolygonStream stream(soup.polygons);
        std::vector<int> corners;
        std::vector<Eigen::Vector3d> ring;
        std::vector<std::array<int, 3>> made;
        for (int p = 0; stream.next(corners); ++p) {
            const int n = static_cast<int>(corners.size());
            if (!check.add(p, corners.data(), n)) continue;  // counted; thrown after the pass
            if (n > 3) ++report.num_polygons_triangulated;
            made.clear();
            detail::triangulate(
                n, [&](int i) { return remap[corners[i]]; }, positions, ring, made);
            num_triangles += made.size();
            for (const std::array<int, 3>& t : made) {
                if (detail::degenerate(t, positions)) {
                    ++report.num_degenerate_faces_removed;
                    continue;
                }
                longest2 = std::max(longest2, detail::longest_edge2(t, positions));
                triangles.append(t);
                if (placed) {
                    const int* place = near->places();
                    placed->append({place[t[0]], place[t[1]], place[t[2]]});
                }
            }
        }
        check.throw_if_bad();
        const ScratchFile done = std::move(soup.polygons);  // its disk space goes now
    }
    const std::size_t nf = triangles.size() / 3;
    if (nf == 0) detail::no_face_left(num_triangles, report.num_input_polygons);

    // (4) duplicate faces and edges, (5) orientation: in tiles cut from the file when asked
    // and they can tell it, else over the whole mesh, held.
    std::optional<detail::OrientedFaces> oriented;
    std::vector<char> duplicate;  // #F when there are duplicates
    if (params.tiles > 1) {
        const TileBoxes boxes = make_tile_boxes(
            positions, detail::orientation_tiles(nf, params.tiles, params.tile_faces));
        StreamTiler tiler(near->copy(), face_reader(*placed), nf, boxes, StreamTiler::kChunkSize,
                          near->ids());
        const double halo = std::sqrt(longest2);
        oriented = detail::orient_tiles(
            nf, boxes.size(), [&](int b) { return tiler.tile(b, halo); }, params.orient, duplicate);
    }
    if (!oriented) {
        std::vector<std::array<int, 3>> faces;
        face_reader(triangles)(0, nf, faces);
        std::vector<int> no_sources;
        oriented = detail::orient_whole(positions, faces, no_sources, params.orient);
        // The duplicates are gone from the faces held: they take the file's place.
        triangles = ScratchFile(scratch_dir);
        for (const std::array<int, 3>& t : faces) triangles.append(t);
        release(faces);
        duplicate.clear();
    }
    detail::count_orientation(*oriented, report);
    placed.reset();  // their disk space goes now
    near.reset();
    positions = merged->positions();

    // The faces left, oriented, into the file returned.
    ScratchFile faces(scratch_dir);
    std::vector<char> used(positions.size(), 0);
    std::size_t kept = 0;
    for_each_face_block(face_reader(triangles), triangles.size() / 3,
                        [&](std::size_t first, const auto& block) {
                            for (std::size_t i = 0; i < block.size(); ++i) {
                                if (!duplicate.empty() && duplicate[first + i]) continue;
                                std::array<int, 3> t = block[i];
                                if (oriented->flip[kept++]) {
                                    std::swap(t[1], t[2]);
                                    ++report.num_faces_flipped;
                                }
                                used[t[0]] = used[t[1]] = used[t[2]] = 1;
                                faces.append(t);
                            }
                        });
    report.num_isolated_vertices = static_cast<int>(std::count(used.begin(), used.end(), 0));
    Diagnostics notes = detail::repair_notes(report, oriented->num_conflicts);
    return RepairedOnDisk{std::move(*merged), std::move(faces), kept, report, std::move(notes)};
}

}  // namespace geotex
