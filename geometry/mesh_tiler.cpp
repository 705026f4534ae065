#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/key_index_sort.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/tiles.hpp"

namespace geotex {

namespace {

// make_mesh_tile's codes for a vertex: in the box, within the halo of it, neither; and one for
// a vertex whose code the tile has not needed yet.
constexpr char kOutside = 0, kInBox = 1, kInHalo = 2, kUnknown = 3;

// StreamTiler's flags for a vertex: in the box (box_of), within the halo, and near enough to
// the box to be the corner of a face whose centroid is in it.
constexpr char kBoxFlag = 1, kHaloFlag = 2, kNearFlag = 4;

// The fine grid's cells along an axis cut into `boxes` parts: `per_box` to a box, on an axis
// that the boxes cut (the others are one box deep, and no halo is narrower along them).
int cells_along(int boxes, int per_box) { return boxes > 1 ? boxes * per_box : 1; }

void set_bit(std::vector<std::uint64_t>& bits, int i) {
    bits[static_cast<std::size_t>(i) >> 6] |= std::uint64_t{1} << (i & 63);
}

bool bit(const std::vector<std::uint64_t>& bits, int i) {
    return (bits[static_cast<std::size_t>(i) >> 6] >> (i & 63)) & 1;
}

// Calls fn(i) for each set bit i, ascending, and clears the set.
template <class Fn>
void drain_bits(std::vector<std::uint64_t>& bits, Fn&& fn) {
    for (std::size_t w = 0; w < bits.size(); ++w) {
        for (std::uint64_t word = bits[w]; word != 0; word &= word - 1)
            fn(static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(word))));
        bits[w] = 0;
    }
}

}  // namespace

MeshTiler::MeshTiler(const Mesh& mesh, const TileBoxes& boxes) : mesh_(mesh), boxes_(boxes) {
    if (boxes.size() < 1) throw InvalidInput("tiles: there is no box to cut the mesh into");
    // About 65,536 cells in all: a tile then looks at its halo to within a cell's width (at
    // 16 tiles, 64 cells to a box's side), and the cells' offsets stay small.
    int cut_axes = 0;
    for (int n : boxes.count) cut_axes += n > 1 ? 1 : 0;
    int per_box = 1;
    if (cut_axes > 0) {
        const double room = 65536.0 / boxes.size();
        per_box = std::max(1, static_cast<int>(std::floor(std::pow(room, 1.0 / cut_axes))));
    }
    for (int a = 0; a < 3; ++a) cells_[a] = cells_along(boxes.count[a], per_box);
    const int nf = mesh.num_faces(), nv = mesh.num_vertices();
    const int num_cells = cells_[0] * cells_[1] * cells_[2];
    // Each face's cell, then a counting sort of the faces by cell, stable so that each cell's
    // faces ascend.
    std::vector<int> cell(static_cast<std::size_t>(nf));
    // The greatest reach by chunks of faces, whose maxima are then compared: the same for any
    // thread count, without a number for each face.
    constexpr int kChunk = 1 << 16;
    std::vector<double> reach2((static_cast<std::size_t>(nf) + kChunk - 1) / kChunk, 0.0);
    detail::parallel_for(
        static_cast<int>(reach2.size()),
        [&](int chunk) {
            const int end = std::min(nf, (chunk + 1) * kChunk);
            for (int f = chunk * kChunk; f < end; ++f) {
                const auto& fv = mesh.faces[f];
                const Eigen::Vector3d centroid =
                    (mesh.positions[fv[0]] + mesh.positions[fv[1]] + mesh.positions[fv[2]]) / 3.0;
                int c = 0;
                for (int a = 2; a >= 0; --a)
                    c = c * cells_[a] +
                        detail::cell_of(centroid[a], boxes.lo[a], boxes.hi[a], cells_[a]);
                cell[f] = c;
                for (int v : fv)
                    reach2[chunk] =
                        std::max(reach2[chunk], (mesh.positions[v] - centroid).squaredNorm());
            }
        },
        1);
    for (double r2 : reach2) reach_ = std::max(reach_, std::sqrt(r2));
    cell_offsets_.assign(static_cast<std::size_t>(num_cells) + 1, 0);
    for (int c : cell) ++cell_offsets_[c + 1];
    for (int c = 0; c < num_cells; ++c) cell_offsets_[c + 1] += cell_offsets_[c];
    faces_.resize(static_cast<std::size_t>(nf));
    {
        std::vector<int> next(cell_offsets_.begin(), cell_offsets_.end() - 1);
        for (int f = 0; f < nf; ++f) faces_[next[cell[f]]++] = f;
    }
    // The cells' bounds and the boxes' are computed from lo, hi and the counts by different
    // roundings: a margin far above either keeps a cell that may hold a face of the tile.
    const double scale = std::max(boxes.lo.cwiseAbs().maxCoeff(), boxes.hi.cwiseAbs().maxCoeff());
    slack_ = 1e-9 * (scale + (boxes.hi - boxes.lo).maxCoeff() + reach_);
    where_.assign(static_cast<std::size_t>(nv), kUnknown);
    local_.assign(static_cast<std::size_t>(nv), -1);
    taken_.assign((static_cast<std::size_t>(nf) + 63) / 64, 0);
    owned_.assign(taken_.size(), 0);
    used_.assign((static_cast<std::size_t>(nv) + 63) / 64, 0);
}

MeshTile MeshTiler::tile(int index, double halo) {
    detail::check_tile_request(boxes_, index, halo);
    const Mesh& mesh = mesh_;
    std::vector<int> touched;  // the vertices whose code is found, to forget after the tile
    const auto code_of = [&](int v) {
        const Eigen::Vector3d& p = mesh.positions[v];
        return boxes_.box_of(p) == index           ? kInBox
               : boxes_.distance(index, p) <= halo ? kInHalo
                                                   : kOutside;
    };
    const auto where = [&](int v) {
        char& code = where_[v];
        if (code == kUnknown) {
            code = code_of(v);
            touched.push_back(v);
        }
        return code;
    };
    // The cells within the halo and a face's reach of the box, along each axis and then in
    // space: a face of the tile has its centroid in one of them.
    const double within = halo + reach_ + slack_;
    const int box_cell[3] = {index % boxes_.count[0], (index / boxes_.count[0]) % boxes_.count[1],
                             index / (boxes_.count[0] * boxes_.count[1])};
    const auto [box_from, box_to] = boxes_.corners(index);
    std::array<double, 3> cell_width{};
    std::array<int, 3> first{}, last{};
    for (int a = 0; a < 3; ++a) {
        cell_width[a] = (boxes_.hi[a] - boxes_.lo[a]) / cells_[a];
        first[a] = detail::cell_of(box_from[a] - within, boxes_.lo[a], boxes_.hi[a], cells_[a]);
        last[a] = detail::cell_of(box_to[a] + within, boxes_.lo[a], boxes_.hi[a], cells_[a]);
    }
    // Most cells need no test of their faces: a cell inside the box, farther than the rounding
    // from its sides, holds faces the tile owns; one outside it holds none; and one whose every
    // point is within the halo, less a face's reach, holds faces with every corner in the halo.
    for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
            for (int x = first[0]; x <= last[0]; ++x) {
                const int at[3] = {x, y, z};
                double near2 = 0, far2 = 0;
                bool inside = true, outside = false;
                for (int a = 0; a < 3; ++a) {
                    const double from = boxes_.lo[a] + at[a] * cell_width[a];
                    const double to = from + cell_width[a];
                    const double gap = std::max({from - box_to[a], box_from[a] - to, 0.0});
                    const double far = std::max({to - box_to[a], box_from[a] - from, 0.0});
                    near2 += gap * gap;
                    far2 += far * far;
                    // box_of puts what lies beyond the first or last box along an axis in it.
                    inside = inside && (box_cell[a] == 0 || from >= box_from[a] + slack_) &&
                             (box_cell[a] == boxes_.count[a] - 1 || to <= box_to[a] - slack_);
                    outside = outside || gap > slack_;
                }
                if (std::sqrt(near2) > within) continue;
                const bool all_near = std::sqrt(far2) + reach_ + slack_ <= halo;
                const int c = (z * cells_[1] + y) * cells_[0] + x;
                for (int k = cell_offsets_[c]; k < cell_offsets_[c + 1]; ++k) {
                    const int f = faces_[k];
                    const auto& fv = mesh.faces[f];
                    if (inside || (!outside && detail::face_box(mesh, boxes_, f) == index)) {
                        set_bit(taken_, f);
                        set_bit(owned_, f);
                    } else if (all_near || where(fv[0]) != kOutside || where(fv[1]) != kOutside ||
                               where(fv[2]) != kOutside) {
                        set_bit(taken_, f);
                    }
                }
            }
    // The faces ascending, as make_mesh_tile gathers them; then their vertices.
    MeshTile tile;
    drain_bits(taken_, [&](int f) {
        tile.face.push_back(f);
        tile.owned_face.push_back(bit(owned_, f) ? 1 : 0);
        for (int v : mesh.faces[f]) set_bit(used_, v);
    });
    for (int f : tile.face) owned_[static_cast<std::size_t>(f) >> 6] = 0;
    drain_bits(used_, [&](int v) {
        local_[v] = static_cast<int>(tile.vertex.size());
        tile.vertex.push_back(v);
    });
    tile.mesh.positions = detail::restricted(mesh.positions, tile.vertex);
    tile.owned_vertex.resize(tile.vertex.size());
    tile.complete_vertex.resize(tile.vertex.size());
    // In parallel: the tile's vertices are distinct, and each one's code is forgotten below.
    detail::parallel_for(static_cast<int>(tile.vertex.size()), [&](int i) {
        const int v = tile.vertex[i];
        const char code = where_[v] != kUnknown ? where_[v] : code_of(v);
        tile.owned_vertex[i] = code == kInBox ? 1 : 0;
        tile.complete_vertex[i] = code != kOutside ? 1 : 0;
    });
    tile.mesh.faces.reserve(tile.face.size());
    for (int f : tile.face) {
        const auto& fv = mesh.faces[f];
        tile.mesh.faces.push_back({local_[fv[0]], local_[fv[1]], local_[fv[2]]});
    }
    for (int v : touched) where_[v] = kUnknown;
    for (int v : tile.vertex) where_[v] = kUnknown;
    return tile;
}

namespace {

// The lowest and highest corners of the bounds of point(i) for i in [begin, end).
template <class Point>
std::pair<Eigen::Vector3d, Eigen::Vector3d> bounds_of(int begin, int end, Point&& point) {
    std::pair<Eigen::Vector3d, Eigen::Vector3d> box{point(begin), point(begin)};
    for (int i = begin + 1; i < end; ++i) {
        box.first = box.first.cwiseMin(point(i));
        box.second = box.second.cwiseMax(point(i));
    }
    return box;
}

}  // namespace

StreamTiler::StreamTiler(PositionSpan positions, FaceBlockReader faces, std::size_t num_faces,
                         const TileBoxes& boxes, std::size_t chunk_size, const int* vertex_ids)
    : positions_(positions),
      faces_(std::move(faces)),
      vertex_ids_(vertex_ids),
      num_faces_(num_faces),
      chunk_(static_cast<int>(std::clamp<std::size_t>(chunk_size, 1, kFaceBlock))),
      boxes_(boxes) {
    if (boxes.size() < 1) throw InvalidInput("tiles: there is no box to cut the mesh into");
    const std::size_t nv = positions.size();
    const auto chunks = [&](std::size_t n) { return (n + chunk_ - 1) / chunk_; };
    // The bounds of each chunk of vertices, and of the corners of each chunk of faces with the
    // farthest a corner lies from its face's centroid (compared as maxima: the same for any
    // thread count). The vertices are read in their order (PositionSpan::in_order), the faces'
    // corners as looked up (through a copy in the order of space, when the span has one).
    const PositionSpan in_order = positions.in_order();
    vertex_chunks_.resize(chunks(nv));
    detail::parallel_for(
        static_cast<int>(vertex_chunks_.size()),
        [&](int c) {
            const int end = static_cast<int>(std::min(nv, (c + std::size_t{1}) * chunk_));
            vertex_chunks_[c] = bounds_of(c * chunk_, end, [&](int v) { return in_order[v]; });
        },
        1);
    face_chunks_.resize(chunks(num_faces));
    std::vector<double> reach2(face_chunks_.size(), 0.0);
    for_each_face_block(
        faces_, num_faces_,
        [&](std::size_t first, const std::vector<std::array<int, 3>>& block) {
            const int n = static_cast<int>(block.size());
            const int first_chunk = static_cast<int>(first / chunk_);
            detail::parallel_for(
                static_cast<int>(chunks(block.size())),
                [&](int k) {
                    const int begin = k * chunk_, end = std::min(n, begin + chunk_);
                    double& r2 = reach2[first_chunk + k];
                    for (int f = begin; f < end; ++f) {
                        const auto& fv = block[f];
                        const Eigen::Vector3d centroid =
                            (positions[fv[0]] + positions[fv[1]] + positions[fv[2]]) / 3.0;
                        for (int v : fv) r2 = std::max(r2, (positions[v] - centroid).squaredNorm());
                    }
                    face_chunks_[first_chunk + k] = bounds_of(
                        3 * begin, 3 * end, [&](int i) { return positions[block[i / 3][i % 3]]; });
                },
                1);
        },
        block_faces());
    for (double r2 : reach2) reach_ = std::max(reach_, std::sqrt(r2));
    const double scale = std::max(boxes.lo.cwiseAbs().maxCoeff(), boxes.hi.cwiseAbs().maxCoeff());
    slack_ = 1e-9 * (scale + (boxes.hi - boxes.lo).maxCoeff() + reach_);
    where_.assign(nv, 0);
    used_.assign((nv + 63) / 64, 0);
    rank_.assign(used_.size(), 0);
}

std::size_t StreamTiler::block_faces() const {
    return chunk_ * std::max<std::size_t>(1, kFaceBlock / chunk_);
}

// Whether no point within `bounds` can be of the tile: each is farther than `reach` from the
// box (from, to), and inside the boxes, so that box_of does not pull it in from beyond. The
// distance of the bounds is computed as each point's is, and rounding is monotone: it is no
// more than any point's.
bool StreamTiler::far(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& bounds,
                      const Eigen::Vector3d& from, const Eigen::Vector3d& to, double reach) const {
    const auto& [lo, hi] = bounds;
    const bool inside =
        (lo.array() >= boxes_.lo.array()).all() && (hi.array() <= boxes_.hi.array()).all();
    if (!inside) return false;
    double squared = 0;
    for (int a = 0; a < 3; ++a) {
        const double gap = std::max({from[a] - hi[a], lo[a] - to[a], 0.0});
        squared += gap * gap;
    }
    return std::sqrt(squared) > reach;
}

std::vector<char> StreamTiler::mark(int index, double halo, std::size_t& bound) {
    detail::check_tile_request(boxes_, index, halo);
    const PositionSpan in_order = positions_.in_order();
    const int nv = static_cast<int>(positions_.size());
    const std::pair<Eigen::Vector3d, Eigen::Vector3d> box = boxes_.corners(index);
    // Each vertex's flags. A face whose centroid is in the box has every corner within a
    // face's reach of it (plus the rounding), so a face without that flag on each corner is
    // not owned, found without its centroid. box_of is asked only of the vertices within the
    // rounding of the box, or outside all the boxes, which it puts in the nearest. A chunk
    // farther than the halo and the reach is passed over whole.
    const double near = reach_ + slack_;
    const double reach = std::max(halo, near);
    detail::parallel_for(
        static_cast<int>(vertex_chunks_.size()),
        [&](int c) {
            const int begin = c * chunk_, end = std::min(nv, begin + chunk_);
            if (far(vertex_chunks_[c], box.first, box.second, reach)) {
                std::fill(where_.begin() + begin, where_.begin() + end, 0);
                return;
            }
            for (int v = begin; v < end; ++v) {
                const Eigen::Vector3d& x = in_order[v];
                const double d = TileBoxes::distance(box.first, box.second, x);
                char flags = 0;
                if (d <= near) flags |= kNearFlag;
                if (d <= halo) flags |= kHaloFlag;
                const bool beyond =
                    (x.array() < boxes_.lo.array()).any() || (x.array() > boxes_.hi.array()).any();
                if ((d <= slack_ || beyond) && boxes_.box_of(x) == index)
                    flags |= kBoxFlag | kHaloFlag | kNearFlag;
                where_[v] = flags;
            }
        },
        1);
    const std::size_t num_chunks = face_chunks_.size();
    std::vector<char> read(num_chunks);
    bound = 0;
    for (std::size_t c = 0; c < num_chunks; ++c) {
        read[c] = far(face_chunks_[c], box.first, box.second, reach) ? 0 : 1;
        if (read[c]) bound += std::min(num_faces_, (c + 1) * chunk_) - c * chunk_;
    }
    return read;
}

// The faces in order, decided in parallel a read at a time (2: owned, 1: in the halo); the
// runs of chunks that may hold a face of the tile are read, up to a block at a time.
template <class Take>
void StreamTiler::take_faces(int index, const std::vector<char>& read, Take&& take) {
    const PositionSpan p = positions_;
    const std::size_t num_chunks = read.size(), most = block_faces() / chunk_;
    for (std::size_t c = 0; c < num_chunks;) {
        if (!read[c]) {
            ++c;
            continue;
        }
        std::size_t end = c + 1;
        while (end < num_chunks && end - c < most && read[end]) ++end;
        const std::size_t first = c * chunk_;
        faces_(first, std::min(num_faces_, end * chunk_) - first, block_);
        c = end;
        const std::vector<std::array<int, 3>>& block = block_;
        const int n = static_cast<int>(block.size());
        std::vector<char>& taken = taken_;
        taken.assign(static_cast<std::size_t>(n), 0);
        detail::parallel_for(n, [&](int k) {
            const auto& fv = block[k];
            const char any = where_[fv[0]] | where_[fv[1]] | where_[fv[2]];
            const char all = where_[fv[0]] & where_[fv[1]] & where_[fv[2]];
            if ((all & kNearFlag) && detail::face_box(p, boxes_, fv) == index)
                taken[k] = 2;
            else if (any & kHaloFlag)
                taken[k] = 1;
        });
        for (int k = 0; k < n; ++k) {
            if (!taken[k]) continue;
            take(static_cast<int>(first) + k, block[k], taken[k] == 2);
            for (int v : block[k]) set_bit(used_, v);
        }
    }
}

std::vector<int> StreamTiler::number_vertices(std::vector<int>& ids) {
    std::vector<int> cut;
    for (std::size_t w = 0; w < used_.size(); ++w) {
        rank_[w] = static_cast<int>(cut.size());
        for (std::uint64_t word = used_[w]; word != 0; word &= word - 1)
            cut.push_back(
                static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(word))));
    }
    number_by_id(cut, ids);
    return cut;
}

int StreamTiler::local(int v) const {
    const auto w = static_cast<std::size_t>(v) >> 6;
    const std::uint64_t before = used_[w] & ((std::uint64_t{1} << (v & 63)) - 1);
    const auto rank = static_cast<std::size_t>(rank_[w] + __builtin_popcountll(before));
    return order_.empty() ? static_cast<int>(rank) : order_[rank];
}

void StreamTiler::forget_tile() {
    std::fill(used_.begin(), used_.end(), 0);
    order_.clear();
}

template <class Cut>
void StreamTiler::with_tile(Cut&& cut) {
    try {
        cut();
    } catch (...) {
        forget_tile();
        throw;
    }
    forget_tile();
}

MeshTile StreamTiler::tile(int index, double halo) {
    std::size_t bound = 0;
    const std::vector<char> read = mark(index, halo, bound);
    // Reserved, not grown face by face: growing had the kernel clear each new array's pages
    // (a tenth of the cutting's profile), and the pages past the tile's faces are not touched.
    MeshTile tile;
    tile.face.reserve(bound);
    tile.owned_face.reserve(bound);
    tile.mesh.faces.reserve(bound);
    with_tile([&] {
        take_faces(index, read, [&](int id, const std::array<int, 3>& face, bool owned) {
            tile.face.push_back(id);
            tile.owned_face.push_back(owned ? 1 : 0);
            tile.mesh.faces.push_back(face);
        });
        // The tile's vertices ascending by id, as make_mesh_tile numbers them, each read in the
        // order cut (ascending: the positions a page after another); then its faces renumbered.
        const std::vector<int> cut = number_vertices(tile.vertex);
        const std::size_t n = cut.size();
        tile.mesh.positions.resize(n);
        tile.owned_vertex.resize(n);
        tile.complete_vertex.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const int v = cut[i];
            const auto k = order_.empty() ? i : static_cast<std::size_t>(order_[i]);
            tile.mesh.positions[k] = positions_[v];
            tile.owned_vertex[k] = (where_[v] & kBoxFlag) ? 1 : 0;
            tile.complete_vertex[k] = (where_[v] & kHaloFlag) ? 1 : 0;
        }
        for (auto& fv : tile.mesh.faces)
            for (int& v : fv) v = local(v);
    });
    return tile;
}

SpooledTile::SpooledTile(const StreamTiler& tiler, const std::string& scratch_dir)
    : tiler_(tiler), faces_(scratch_dir) {}

Eigen::Vector3d SpooledTile::position(std::size_t k) const { return tiler_.positions_[at_[k]]; }

bool SpooledTile::owned_vertex(std::size_t k) const {
    return (tiler_.where_[static_cast<std::size_t>(at_[k])] & kBoxFlag) != 0;
}

bool SpooledTile::complete_vertex(std::size_t k) const {
    return (tiler_.where_[static_cast<std::size_t>(at_[k])] & kHaloFlag) != 0;
}

void SpooledTile::for_each_face_block(const std::function<void(const TileFaceBlock&)>& fn) const {
    TileFaceBlock block;
    std::vector<int> values;
    for (std::size_t first = 0; first < num_faces_; first += block_) {
        const std::size_t n = std::min(block_, num_faces_ - first);
        values.resize(4 * n);
        faces_.read(4 * first, 4 * n, values.data());
        block.faces.resize(n);
        block.ids.resize(n);
        block.owned.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) block.faces[i][c] = tiler_.local(values[4 * i + c]);
            const int id = values[4 * i + 3];
            block.ids[i] = id >= 0 ? id : ~id;
            block.owned[i] = id >= 0 ? 1 : 0;
        }
        fn(block);
    }
}

void StreamTiler::spool(int index, double halo, const std::string& scratch_dir,
                        const std::function<void(const SpooledTile&)>& use, std::size_t block) {
    std::size_t bound = 0;
    const std::vector<char> read = mark(index, halo, bound);
    SpooledTile tile(*this, scratch_dir);
    tile.block_ = std::max<std::size_t>(1, block);
    with_tile([&] {
        take_faces(index, read, [&](int id, const std::array<int, 3>& face, bool owned) {
            const std::array<int, 4> values{face[0], face[1], face[2], owned ? id : ~id};
            tile.faces_.append(values.data(), values.size());
        });
        tile.num_faces_ = tile.faces_.size() / 4;
        std::vector<int> cut = number_vertices(tile.vertex_);
        if (order_.empty()) {
            tile.at_ = std::move(cut);
        } else {
            tile.at_.resize(cut.size());
            for (std::size_t i = 0; i < cut.size(); ++i)
                tile.at_[static_cast<std::size_t>(order_[i])] = cut[i];
        }
        use(tile);
    });
}

// The tile's vertices `cut` (ascending, in the numbers cut in) numbered in the tile in the
// order of their ids, which go to `ids`: cut in other numbers (vertex_ids_), they are sorted by
// id, and order_[i] is cut[i]'s number; else their ranks are their numbers, and order_ stays
// empty. Which faces a tile takes, in what order, and each vertex's flags depend on the
// positions alone, not on the numbers, so the tile is make_mesh_tile's either way.
void StreamTiler::number_by_id(const std::vector<int>& cut, std::vector<int>& ids) {
    order_.clear();
    if (vertex_ids_ == nullptr) {
        ids = cut;
        return;
    }
    ids.resize(cut.size());
    std::vector<detail::KeyIndex> by_id(cut.size());  // (id, rank)
    for (std::size_t i = 0; i < cut.size(); ++i)
        by_id[i] = detail::key_index(static_cast<std::uint32_t>(vertex_ids_[cut[i]]),
                                     static_cast<std::uint32_t>(i));
    detail::sort_by_key(by_id);
    order_.resize(cut.size());
    for (std::size_t k = 0; k < by_id.size(); ++k) {
        ids[k] = static_cast<int>(detail::key_of(by_id[k]));
        order_[detail::index_of(by_id[k])] = static_cast<int>(k);
    }
}

}  // namespace geotex
