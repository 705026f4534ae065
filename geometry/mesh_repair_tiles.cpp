// Steps (4) and (5) of repair_soup a spatial tile at a time (detail/repair_steps.hpp), so that
// the mesh job of a tiled run holds one tile's edge tables, not the whole mesh's (at sphere-1
// level 11 those are the repair's peak: docs/tiles.md).
//
// Each tile (make_mesh_tile) takes the faces whose centroid lies in its box, which it owns,
// and, as a halo as wide as the longest edge, every face with a vertex near the box. An edge
// with an end within the halo has all its faces in the tile, so the tile sees it as the whole
// mesh does: every edge of an owned face is such an edge, and so is every edge between an
// owned face and its neighbours. A face and its duplicates share their vertices, so the tile
// finds duplicates exactly. The tile spreads the orientation over those edges alone into local
// patches; a face that lies in two tiles joins their patches, with the parity of its two local
// orientations, and the joined patches are the whole mesh's. What decides a patch's orientation
// (its volume or its majority, about its first face) is summed per local patch over the faces
// the tile owns, and added up over the joined patches.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/detail/repair_steps.hpp"
#include "geometry/detail/union_find.hpp"
#include "geometry/tiles.hpp"
#include "geometry/work_progress.hpp"

namespace geotex::detail {
namespace {

// A face's state in orient_tiles: 2 * local patch + parity from the tile that owns it, or one of
// these marks: not seen yet, a duplicate to its owner, or kSeen - (2 * local patch + parity)
// from a tile that has it in its halo, until its owner's tile joins the two.
constexpr int kUnset = -1;
constexpr int kDuplicateFace = -2;
constexpr int kSeen = -3;

// Disjoint sets that also keep each element's parity (its orientation flipped or not)
// relative to its set's root: the tiles' local patches, joined through the faces they share.
// Written here because the library's union-find (union_find.hpp) has no parity.
class ParityUnionFind {
  public:
    // Elements 0 .. n - 1 after the ones it has, each a set of its own.
    void grow(std::size_t n) {
        for (std::size_t i = parent_.size(); i < n; ++i) parent_.push_back(static_cast<int>(i));
        parity_.resize(parent_.size(), 0);
    }

    // The root of x, and x's parity relative to it.
    std::pair<int, int> find(int x) {
        int root = x;
        int parity = 0;
        while (parent_[root] != root) {
            parity ^= parity_[root];
            root = parent_[root];
        }
        // Every element on the way now points at the root directly.
        for (int y = x, py = parity; parent_[y] != y;) {
            const int next = parent_[y];
            const int pnext = py ^ parity_[y];
            parent_[y] = root;
            parity_[y] = static_cast<char>(py);
            y = next;
            py = pnext;
        }
        return {root, parity};
    }

    // Joins the sets of a and b so that parity(a) ^ parity(b) == rel; false when they are one
    // set already with the other parity (a surface that cannot be oriented).
    bool unite(int a, int b, int rel) {
        const auto [ra, pa] = find(a);
        const auto [rb, pb] = find(b);
        if (ra == rb) return (pa ^ pb) == rel;
        const int high = std::max(ra, rb);
        parent_[high] = std::min(ra, rb);
        parity_[high] = static_cast<char>(pa ^ pb ^ rel);
        return true;
    }

  private:
    std::vector<int> parent_;
    std::vector<char> parity_;
};

// A local patch of a tile, summed over the faces the tile owns, each as oriented relative to
// the patch's first face in the tile.
struct LocalPatch {
    int tile = 0;
    int first_face = std::numeric_limits<int>::max();  // whole mesh's id
    int first_flip = 0;
    Eigen::Vector3d first_corner = Eigen::Vector3d::Zero();  // the first face's first vertex
    bool open = false;  // a face has a boundary or non-manifold edge
    std::int64_t size = 0;
    std::int64_t flips = 0;  // faces that must flip to agree with the local first face
    double volume6 = 0;      // six times the signed volume, about the tile's origin
    Eigen::Vector3d area2 = Eigen::Vector3d::Zero();  // sum of (b - a) x (c - a)
    // For the rounding bound of the volume: sums of |a| |b| |c|, |det| and |(b - a) x (c - a)|.
    double corner_norms = 0;
    double det_norms = 0;
    double area_norms = 0;
};

// A whole-mesh patch: its local patches joined.
struct Patch {
    int first_face = std::numeric_limits<int>::max();
    int first_flip = 0;  // the first face's parity relative to the root
    Eigen::Vector3d first_corner = Eigen::Vector3d::Zero();
    bool open = false;
    std::int64_t size = 0;
    std::int64_t flips = 0;  // relative to the root
    double volume6 = 0;      // relative to the root, about the first face's first vertex
    double rounding = 0;     // bound of the volume's rounding error
    bool invert = false;
};

double longest_edge(const Mesh& mesh) {
    double longest2 = 0;
    for (const auto& t : mesh.faces)
        longest2 = std::max(longest2, longest_edge2(t, mesh.positions));
    return std::sqrt(longest2);
}

}  // namespace

std::optional<OrientedFaces> orient_in_tiles(Mesh& mesh, std::vector<int>& source, bool orient,
                                             int tiles) {
    const TileBoxes boxes = make_tile_boxes(mesh.positions, tiles);
    // An owned face's corners lie within 2/3 of its longest edge of its centroid.
    const double halo = longest_edge(mesh);
    // Each tile cut from the faces near its box, not from a scan of the whole mesh.
    MeshTiler tiler(mesh, boxes);
    std::vector<char> duplicate;
    std::optional<OrientedFaces> out = orient_tiles(
        mesh.faces.size(), boxes.size(), [&](int b) { return tiler.tile(b, halo); }, orient,
        duplicate);
    if (out && out->num_duplicates > 0) remove_faces(mesh.faces, source, duplicate);
    return out;
}

std::optional<OrientedFaces> orient_tiles(std::size_t num_faces, int num_tiles,
                                          const std::function<MeshTile(int)>& tile_of, bool orient,
                                          std::vector<char>& duplicate) {
    OrientedFaces out;
    std::vector<int> state(num_faces, kUnset);  // per face (kUnset above)
    std::vector<LocalPatch> local;
    // The local patches joined through the faces that lie in several tiles, as the tiles come:
    // a face seen in a halo waits in `state` for its owner, so that nothing is kept per such
    // face (they were a tenth of the faces at sphere-1 level 10 in 81 tiles).
    ParityUnionFind patches;
    const auto join = [&](int a, int b) {
        return patches.unite(a >> 1, b >> 1, (a ^ b) & 1) || !orient;
    };
    std::vector<Eigen::Vector3d> tile_origin(static_cast<std::size_t>(num_tiles));
    std::vector<std::pair<int, int>> non_manifold;  // local patches joined by such an edge

    // How far the tiles are, by the faces they own (every face is owned once), for the line of
    // the repair on a terminal: of a scan of tens of millions of faces, this loop takes
    // minutes when memory is short.
    LoopMeter meter(static_cast<long long>(num_faces));
    for (int b = 0; b < num_tiles; ++b) {
        MeshTile tile = tile_of(b);
        const long long owned = std::count(tile.owned_face.begin(), tile.owned_face.end(), 1);
        if (tile.face.empty()) continue;
        std::vector<std::array<int, 3>>& faces = tile.mesh.faces;
        const std::vector<Eigen::Vector3d>& positions = tile.mesh.positions;
        EdgeMatch edges = match_edges(faces, tile.mesh.num_vertices());
        if (edges.num_duplicates > 0) {
            std::vector<char> owned;
            for (std::size_t i = 0; i < faces.size(); ++i) {
                if (!edges.duplicate[i]) {
                    owned.push_back(tile.owned_face[i]);
                } else if (tile.owned_face[i]) {
                    // Seen in a halo, it was no duplicate there.
                    if (state[tile.face[i]] != kUnset) return std::nullopt;
                    state[tile.face[i]] = kDuplicateFace;
                    ++out.num_duplicates;
                }
            }
            remove_faces(faces, tile.face, edges.duplicate);
            tile.owned_face = std::move(owned);
            edges = EdgeMatch();
            edges = match_edges(faces, tile.mesh.num_vertices());
        }
        // An edge with neither end within the halo may miss faces the whole mesh has there.
        for (std::size_t h = 0; h < edges.opposite.size(); ++h) {
            const auto& t = faces[h / 3];
            const int k = static_cast<int>(h % 3);
            if (edges.opposite[h] >= 0 && !tile.complete_vertex[t[k]] &&
                !tile.complete_vertex[t[k == 2 ? 0 : k + 1]])
                edges.opposite[h] = kUnknownEdge;
        }
        const OrientationSpread spread = spread_orientation(faces, edges.opposite);
        if (orient && spread.num_conflicts > 0) return std::nullopt;

        const Eigen::AlignedBox3d box = bounding_box(positions);
        const Eigen::Vector3d origin = 0.5 * (box.min() + box.max());
        tile_origin[b] = origin;
        const int base = static_cast<int>(local.size());
        local.resize(local.size() + spread.seed.size());
        patches.grow(local.size());
        for (std::size_t p = base; p < local.size(); ++p) local[p].tile = b;
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const int node = base + (spread.state[i] >> 1);
            const int bit = spread.state[i] & 1;
            const int here = 2 * node + bit;
            int& seen = state[tile.face[i]];
            if (seen == kDuplicateFace) return std::nullopt;  // to its owner, not here
            if (!tile.owned_face[i]) {
                if (seen == kUnset)
                    seen = kSeen - here;
                else if (!join(here, seen >= 0 ? seen : kSeen - seen))
                    return std::nullopt;
                continue;
            }
            if (seen <= kSeen && !join(here, kSeen - seen)) return std::nullopt;
            seen = here;
            const int f = tile.face[i];
            LocalPatch& patch = local[node];
            if (patch.first_face == std::numeric_limits<int>::max()) {
                patch.first_face = f;  // faces ascend in the tile
                patch.first_flip = bit;
                patch.first_corner = positions[faces[i][0]];
            }
            ++patch.size;
            patch.flips += bit;
            for (int k = 0; k < 3; ++k) {
                const int code = edges.opposite[3 * i + k];
                if (code == kUnknownEdge) return std::nullopt;  // the halo is too narrow
                if (code == kBoundaryEdge) ++out.num_boundary_edges;
                if (code < 0) patch.open = true;
            }
            const Eigen::Vector3d a = positions[faces[i][0]] - origin;
            const Eigen::Vector3d c1 = positions[faces[i][1]] - origin;
            const Eigen::Vector3d c2 = positions[faces[i][2]] - origin;
            const double det = a.dot(c1.cross(c2));
            const Eigen::Vector3d area2 = (c1 - a).cross(c2 - a);
            patch.volume6 += bit ? -det : det;
            patch.area2 += bit ? -area2 : area2;
            patch.corner_norms += a.norm() * c1.norm() * c2.norm();
            patch.det_norms += std::abs(det);
            patch.area_norms += area2.norm();
        }
        // A non-manifold edge is counted, and its patches joined, by the tile that owns the
        // first of its faces, where all of them are.
        for (std::size_t e = 0; e + 1 < edges.non_manifold_offsets.size(); ++e) {
            const auto first = edges.non_manifold_faces.begin() + edges.non_manifold_offsets[e];
            const auto last = edges.non_manifold_faces.begin() + edges.non_manifold_offsets[e + 1];
            const int lowest = *std::min_element(first, last);
            if (!tile.owned_face[lowest]) continue;
            ++out.num_non_manifold_edges;
            for (auto i = first; i != last; ++i)
                non_manifold.emplace_back(base + (spread.state[lowest] >> 1),
                                          base + (spread.state[*i] >> 1));
        }
        meter.add(owned);
    }

    // A face no tile owns, or one seen in a halo only.
    if (std::any_of(state.begin(), state.end(), [](int s) { return s == kUnset || s <= kSeen; }))
        return std::nullopt;

    // What decides each patch's orientation, as repair_soup decides it over the whole mesh.
    std::vector<Patch> patch(local.size());
    for (std::size_t n = 0; n < local.size(); ++n) {
        const LocalPatch& l = local[n];
        const auto [root, parity] = patches.find(static_cast<int>(n));
        Patch& p = patch[root];
        p.open = p.open || l.open;
        p.size += l.size;
        p.flips += parity ? l.size - l.flips : l.flips;
        if (l.first_face < p.first_face) {
            p.first_face = l.first_face;
            p.first_flip = l.first_flip ^ parity;
            p.first_corner = l.first_corner;
        }
    }
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    for (std::size_t n = 0; n < local.size(); ++n) {
        const LocalPatch& l = local[n];
        const auto [root, parity] = patches.find(static_cast<int>(n));
        Patch& p = patch[root];
        if (p.open) continue;
        // The volume about the first face's first vertex: moving the origin by d takes
        // d . (b - a) x (c - a) from each face's term.
        const Eigen::Vector3d d = p.first_corner - tile_origin[l.tile];
        const double volume6 = l.volume6 - d.dot(l.area2);
        p.volume6 += parity ? -volume6 : volume6;
        const double n_terms = static_cast<double>(p.size) + 8;
        p.rounding +=
            kEps * (8 * l.corner_norms + n_terms * l.det_norms + n_terms * d.norm() * l.area_norms);
    }
    for (std::size_t r = 0; r < patch.size(); ++r) {
        Patch& p = patch[r];
        if (p.size == 0) continue;
        if (p.open) {
            const std::int64_t disagree = p.first_flip ? p.size - p.flips : p.flips;
            p.invert = 2 * disagree > p.size;
        } else {
            // Near 0 the sign could differ from the whole mesh's sum in another order.
            if (orient && std::abs(p.volume6) <= 16 * p.rounding) return std::nullopt;
            p.invert = (p.first_flip ? -p.volume6 : p.volume6) < 0.0;
        }
    }

    // Components: patches joined through non-manifold edges.
    UnionFind components(static_cast<int>(local.size()));
    for (std::size_t n = 0; n < local.size(); ++n)
        components.unite(static_cast<int>(n), patches.find(static_cast<int>(n)).first);
    for (const auto& [a, b] : non_manifold) components.unite(a, b);
    std::vector<char> component_open(local.size(), 0);
    for (std::size_t n = 0; n < local.size(); ++n)
        if (local[n].open) component_open[components.find(static_cast<int>(n))] = 1;
    for (std::size_t n = 0; n < local.size(); ++n) {
        if (components.find(static_cast<int>(n)) != static_cast<int>(n)) continue;
        ++out.num_components;
        if (!component_open[n]) ++out.num_closed_components;
    }

    // Each face's flip: its parity relative to its patch's first face, then the patch's turn.
    duplicate.assign(out.num_duplicates > 0 ? num_faces : 0, 0);
    out.flip.assign(num_faces, 0);
    std::size_t kept = 0;
    for (std::size_t f = 0; f < num_faces; ++f) {
        if (state[f] == kDuplicateFace) {
            duplicate[f] = 1;
            continue;
        }
        const auto [root, parity] = patches.find(state[f] >> 1);
        const Patch& p = patch[root];
        out.flip[kept++] =
            orient ? static_cast<char>((state[f] & 1) ^ parity ^ p.first_flip ^ p.invert) : 0;
    }
    out.flip.resize(kept);
    return out;
}

}  // namespace geotex::detail
