#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/tiles.hpp"

namespace geotex {

namespace {

// make_mesh_tile's codes for a vertex: in the box, within the halo of it, neither; and one for
// a vertex whose code the tile has not needed yet.
constexpr char kOutside = 0, kInBox = 1, kInHalo = 2, kUnknown = 3;

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
    std::array<double, 3> box_from{}, box_to{}, cell_width{};
    std::array<int, 3> first{}, last{};
    for (int a = 0; a < 3; ++a) {
        const double extent = boxes_.hi[a] - boxes_.lo[a];
        const double width = extent / boxes_.count[a];
        box_from[a] = boxes_.lo[a] + box_cell[a] * width;
        box_to[a] = box_from[a] + width;
        cell_width[a] = extent / cells_[a];
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

}  // namespace geotex
