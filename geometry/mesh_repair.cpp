#include "geometry/mesh_repair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <optional>
#include <string>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/cgal_polygon.hpp"
#include "geometry/detail/key_index_sort.hpp"
#include "geometry/detail/repair_steps.hpp"
#include "geometry/detail/union_find.hpp"

namespace geotex {
namespace {

const char* const kStage = "mesh repair";

[[noreturn]] void invalid(const std::string& message) {
    throw InvalidInput("repair_soup: " + message);
}

std::string count_of(long n, const char* singular, const char* plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

}  // namespace

namespace detail {

void validate_offsets(const PolygonSoup& soup) {
    const std::vector<int>& offsets = soup.face_offsets;
    if (offsets.empty() || offsets[0] != 0) {
        invalid("face_offsets must start with 0 (it has " + std::to_string(offsets.size()) +
                " entries)");
    }
    if (static_cast<std::size_t>(offsets.back()) != soup.face_indices.size()) {
        invalid("face_offsets ends at " + std::to_string(offsets.back()) +
                ", but face_indices has " + std::to_string(soup.face_indices.size()) + " entries");
    }
    for (int p = 0; p < soup.num_polygons(); ++p) {
        if (offsets[p + 1] < offsets[p]) {
            invalid("face_offsets is not increasing within [0, " +
                    std::to_string(soup.face_indices.size()) + "] at polygon " + std::to_string(p) +
                    " (" + std::to_string(offsets[p]) + " then " + std::to_string(offsets[p + 1]) +
                    ")");
        }
    }
}

void validate_positions(PositionSpan positions, int num_polygons) {
    if (num_polygons == 0) invalid("the soup has no polygons");
    int non_finite = 0;
    int first_non_finite = -1;
    for (int v = 0; v < static_cast<int>(positions.size()); ++v) {
        if (!positions[v].allFinite()) {
            if (non_finite++ == 0) first_non_finite = v;
        }
    }
    if (non_finite > 0) {
        invalid(count_of(non_finite, "vertex has", "vertices have") +
                " a non-finite coordinate (first: vertex " + std::to_string(first_non_finite) +
                "); fix or drop them before building the mesh");
    }
}

bool PolygonCheck::add(int p, const int* corners, int n) {
    bool good = true;
    if (n < 3) {
        good = false;
        if (small_++ == 0) {
            first_small_ = p;
            first_small_size_ = n;
        }
    }
    for (int i = 0; i < n; ++i) {
        if (corners[i] < 0 || corners[i] >= num_vertices_) {
            if (out_of_range_++ == 0) {
                first_out_ = p;
                first_out_index_ = corners[i];
            }
            return false;
        }
    }
    return good;
}

void PolygonCheck::throw_if_bad() const {
    if (out_of_range_ > 0) {
        invalid(count_of(out_of_range_, "polygon references", "polygons reference") +
                " a vertex out of range (first: polygon " + std::to_string(first_out_) +
                " uses index " + std::to_string(first_out_index_) + ", but the soup has " +
                std::to_string(num_vertices_) + " vertices)");
    }
    if (small_ > 0) {
        invalid(count_of(small_, "polygon has", "polygons have") +
                " fewer than 3 vertices (first: polygon " + std::to_string(first_small_) +
                " with " + std::to_string(first_small_size_) + ")");
    }
}

void validate_soup(const PolygonSoup& soup) {
    validate_offsets(soup);
    validate_positions(soup.positions, soup.num_polygons());
    PolygonCheck check(static_cast<int>(soup.positions.size()));
    for (int p = 0; p < soup.num_polygons(); ++p) {
        const int begin = soup.face_offsets[p];
        check.add(p, soup.face_indices.data() + begin, soup.face_offsets[p + 1] - begin);
    }
    check.throw_if_bad();
}

}  // namespace detail

namespace {

std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

}  // namespace

namespace detail {

std::vector<int> first_occurrences(PositionSpan positions, int passes) {
    const auto bits = [](const Eigen::Vector3d& p, int k) {
        std::uint64_t b = 0;
        std::memcpy(&b, &p[k], 8);
        return b;
    };
    const auto same = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
        return bits(p, 0) == bits(q, 0) && bits(p, 1) == bits(q, 1) && bits(p, 2) == bits(q, 2);
    };
    const int nv = static_cast<int>(positions.size());
    std::vector<int> first(positions.size());
    const std::size_t share = positions.size() / static_cast<std::size_t>(passes);
    // Each pass takes the vertices whose hash's low half is `pass` modulo `passes`, so that
    // equal positions, whose hashes are equal, are taken together, and the keys, its high
    // half, keep all their 32 bits to tell the pass's vertices apart.
    for (int pass = 0; pass < passes; ++pass) {
        // A pass's share, and an eighth more for the hashes' spread: grown by push_back, the
        // keys' capacity could reach twice what they need (one pass: all of them).
        std::vector<KeyIndex> keys;
        keys.reserve(passes == 1 ? share : share + share / 8 + 64);
        for (int v = 0; v < nv; ++v) {
            const Eigen::Vector3d& p = positions[v];
            const std::uint64_t hash = mix64(mix64(mix64(bits(p, 0)) ^ bits(p, 1)) ^ bits(p, 2));
            if (static_cast<std::uint32_t>(hash) % static_cast<unsigned>(passes) ==
                static_cast<unsigned>(pass))
                keys.push_back(key_index(static_cast<std::uint32_t>(hash >> 32),
                                         static_cast<std::uint32_t>(v)));
        }
        sort_by_key(keys);
        // A vertex alone with its key (nearly all of them) is its own first occurrence, found
        // without its position. The vertices of a run of one key (equal positions, or a
        // collision of 32 bits: about 11,000 vertices in each of sphere-1 level 11's 6 passes) go,
        // with their run's number, to `members`, and are told apart in the order of the vertices,
        // their positions read in one forward pass: read in the keys' order, they came from all
        // over a scan's file on disk, a page each, which was most of the repair under a memory
        // limit.
        // A soup whose vertices all repeat puts every one of them in a run: the members are
        // counted first, so as not to grow by doubling beside the keys, and the keys go before
        // the members' sort, which would otherwise hold both (bench/RESULTS.md).
        const auto for_each_run = [&](auto&& fn) {
            for (std::size_t i = 0; i < keys.size();) {
                std::size_t j = i + 1;
                while (j < keys.size() && key_of(keys[j]) == key_of(keys[i])) ++j;
                fn(i, j);
                i = j;
            }
        };
        std::size_t in_runs = 0;
        for_each_run([&](std::size_t i, std::size_t j) {
            if (j - i == 1)
                first[index_of(keys[i])] = static_cast<int>(index_of(keys[i]));
            else
                in_runs += j - i;
        });
        std::vector<KeyIndex> members;  // (vertex, run)
        members.reserve(in_runs);
        std::uint32_t runs = 0;
        for_each_run([&](std::size_t i, std::size_t j) {
            if (j - i == 1) return;
            for (std::size_t g = i; g < j; ++g)
                members.push_back(key_index(index_of(keys[g]), runs));
            ++runs;
        });
        release(keys);
        sort_by_key(members);
        // Each run's groups of equal positions met so far, a list from run_group: a group's
        // position and its first vertex, which the later ones of the group take.
        struct Group {
            Eigen::Vector3d position;
            int vertex;
            int next;  // the run's next group, or -1
        };
        std::vector<int> run_group(runs, -1);
        std::vector<Group> groups;
        for (const KeyIndex m : members) {
            const int v = static_cast<int>(key_of(m));
            const Eigen::Vector3d& p = positions[v];
            int* link = &run_group[index_of(m)];
            while (*link >= 0 && !same(groups[*link].position, p)) link = &groups[*link].next;
            if (*link >= 0) {
                first[v] = groups[*link].vertex;
            } else {
                *link = static_cast<int>(groups.size());
                groups.push_back({p, v, -1});
                first[v] = v;
            }
        }
    }
    return first;
}

std::vector<int> vertex_remap(std::vector<Eigen::Vector3d>& positions, bool merge) {
    std::vector<int> remap(positions.size());
    if (!merge) {
        std::iota(remap.begin(), remap.end(), 0);
        return remap;
    }
    remap = first_occurrences(positions, 1);
    // Compacted in place (each one's new index is at most its old), so that a large scan's
    // positions are not held twice.
    std::size_t kept = 0;
    number_first_occurrences(remap, [&](int v) { positions[kept++] = positions[v]; });
    if (kept < positions.size()) {
        positions.resize(kept);
        positions.shrink_to_fit();
    }
    return remap;
}

bool degenerate(const std::array<int, 3>& t, PositionSpan positions) {
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
           collinear(positions[t[0]], positions[t[1]], positions[t[2]]);
}

void no_face_left(std::size_t num_triangles, int num_polygons) {
    invalid("no non-degenerate face: all " + std::to_string(num_triangles) + " triangles of the " +
            std::to_string(num_polygons) + " polygons are degenerate or duplicates");
}

void count_orientation(const OrientedFaces& oriented, MeshRepairReport& report) {
    report.num_duplicate_faces_removed = oriented.num_duplicates;
    report.num_boundary_edges = oriented.num_boundary_edges;
    report.num_non_manifold_edges = oriented.num_non_manifold_edges;
    report.num_components = oriented.num_components;
    report.num_closed_components = oriented.num_closed_components;
}

Diagnostics repair_notes(const MeshRepairReport& report, int num_conflicts) {
    // Each count's note, when it is not 0: "<verb> <count> <thing><after>".
    struct Kind {
        int MeshRepairReport::*count;
        const char* verb;
        const char* singular;
        const char* plural;
        const char* after;
    };
    using R = MeshRepairReport;
    static constexpr Kind kinds[] = {
        {&R::num_duplicate_vertices_merged, "merged", "duplicate vertex", "duplicate vertices", ""},
        {&R::num_polygons_triangulated, "triangulated", "polygon", "polygons",
         " with more than 3 vertices"},
        {&R::num_degenerate_faces_removed, "removed", "degenerate face", "degenerate faces",
         " (repeated vertex or zero area)"},
        {&R::num_duplicate_faces_removed, "removed", "duplicate face", "duplicate faces", ""},
        {&R::num_faces_flipped, "flipped", "face", "faces", " to orient them consistently"},
        {&R::num_isolated_vertices, "kept", "isolated vertex", "isolated vertices",
         " that no face uses"},
        {&R::num_non_manifold_edges, "found", "non-manifold edge", "non-manifold edges",
         " (more than two faces); orientation is not propagated across them"},
    };
    Diagnostics notes;
    for (const Kind& k : kinds) {
        const int n = report.*k.count;
        if (n > 0)
            notes.push_back(
                {kStage, std::string(k.verb) + " " + count_of(n, k.singular, k.plural) + k.after});
    }
    if (num_conflicts > 0) {
        notes.push_back({kStage, "could not orient " + count_of(num_conflicts, "edge", "edges") +
                                     " consistently (non-orientable surface)"});
    }
    return notes;
}

}  // namespace detail

namespace {

// Sorts a small range; buckets hold a handful of entries except at high-valence vertices.
template <typename It, typename Less>
void sort_small(It first, It last, Less less) {
    // An empty bucket has no `first + 1`.
    if (last - first < 2) return;
    if (last - first <= 16) {
        for (It i = first + 1; i < last; ++i) {
            auto value = *i;
            It j = i;
            for (; j > first && less(value, *(j - 1)); --j) *j = *(j - 1);
            *j = value;
        }
    } else {
        std::sort(first, last, less);
    }
}

}  // namespace

namespace detail {

// Half-edge 3f+k runs from faces[f][k] to faces[f][(k+1)%3]. Edges are matched by a
// counting sort of the half-edges on their smaller vertex, then a small sort on the larger
// one (no map or set per face). Faces with the same vertex set share all three edges, so
// duplicates are found here too.
EdgeMatch match_edges(const std::vector<std::array<int, 3>>& faces, int nv) {
    struct HalfEdge {
        int other;  // the larger vertex of the edge
        int code;   // 2 * (3f+k) + 1 if it runs from the smaller to the larger vertex
    };
    const int nf = static_cast<int>(faces.size());
    // Straight from the faces into buckets. The buckets hold only the codes: theirs is the
    // largest allocation of repair_soup, 12 bytes a face (a level-11 sphere: 1 GB), and each
    // bucket gets its larger vertices back from the faces when it is sorted.
    std::vector<int> start(static_cast<std::size_t>(nv) + 1, 0);
    for (const auto& t : faces) {
        ++start[std::min(t[0], t[1]) + 1];
        ++start[std::min(t[1], t[2]) + 1];
        ++start[std::min(t[2], t[0]) + 1];
    }
    for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<int> codes(static_cast<std::size_t>(nf) * 3);
    {
        std::vector<int> cursor(start.begin(), start.end() - 1);
        for (int f = 0; f < nf; ++f) {
            for (int k = 0; k < 3; ++k) {
                const int u = faces[f][k];
                const int v = faces[f][k == 2 ? 0 : k + 1];
                codes[cursor[std::min(u, v)]++] = 2 * (3 * f + k) + (u < v ? 1 : 0);
            }
        }
    }
    const auto larger = [&](int code) {
        const int h = code >> 1;
        const std::array<int, 3>& t = faces[h / 3];
        const int k = h % 3;
        return std::max(t[k], t[k == 2 ? 0 : k + 1]);
    };

    EdgeMatch m;
    m.opposite.assign(codes.size(), kBoundaryEdge);
    m.duplicate.assign(faces.size(), 0);
    auto mark_duplicate = [&](int f) {
        if (!m.duplicate[f]) {
            m.duplicate[f] = 1;
            ++m.num_duplicates;
        }
    };
    std::vector<std::pair<int, int>> run_thirds;
    std::vector<HalfEdge> bucket;
    for (int b = 0; b < nv; ++b) {
        bucket.clear();
        for (int i = start[b]; i < start[b + 1]; ++i)
            bucket.push_back({larger(codes[i]), codes[i]});
        const auto first = bucket.begin();
        const auto last = bucket.end();
        sort_small(first, last, [](const HalfEdge& x, const HalfEdge& y) {
            return x.other < y.other || (x.other == y.other && x.code < y.code);
        });
        for (auto i = first; i != last;) {
            auto j = i;
            while (j != last && j->other == i->other) ++j;
            const long run = j - i;
            if (run == 1) {
                ++m.num_boundary_edges;
            } else if (run == 2) {
                const int same = ((i->code ^ (i + 1)->code) & 1) == 0 ? 1 : 0;
                m.opposite[i->code >> 1] = 2 * ((i + 1)->code >> 1) + same;
                m.opposite[(i + 1)->code >> 1] = 2 * (i->code >> 1) + same;
            } else {
                ++m.num_non_manifold_edges;
                run_thirds.clear();
                for (auto h = i; h != j; ++h) {
                    const int id = h->code >> 1;
                    m.opposite[id] = kNonManifoldEdge;
                    m.non_manifold_faces.push_back(id / 3);
                    run_thirds.emplace_back(faces[id / 3][(id % 3 + 2) % 3], id / 3);
                }
                m.non_manifold_offsets.push_back(static_cast<int>(m.non_manifold_faces.size()));
                // Same third corner on one edge: same vertex set; the first face stays.
                std::sort(run_thirds.begin(), run_thirds.end());
                for (std::size_t r = 1; r < run_thirds.size(); ++r) {
                    if (run_thirds[r].first == run_thirds[r - 1].first) {
                        mark_duplicate(run_thirds[r].second);
                    }
                }
            }
            i = j;
        }
    }
    // On manifold edges a duplicate is the one neighbour across all three edges of a face.
    for (int f = 0; f < nf; ++f) {
        const int a = m.opposite[3 * f];
        const int b = m.opposite[3 * f + 1];
        const int c = m.opposite[3 * f + 2];
        if (a >= 0 && b >= 0 && c >= 0) {
            const int g = (a >> 1) / 3;
            if ((b >> 1) / 3 == g && (c >> 1) / 3 == g && g < f) mark_duplicate(f);
        }
    }
    return m;
}

// Breadth-first over the manifold edges. Hand-written rather than
// CGAL::Polygon_mesh_processing::orient_polygon_soup, which duplicates the vertices at
// non-manifold places (that would change our vertex indices) and takes over a second on
// 327k faces.
OrientationSpread spread_orientation(const std::vector<std::array<int, 3>>& faces,
                                     const std::vector<int>& opposite) {
    const int nf = static_cast<int>(faces.size());
    OrientationSpread result;
    // -1 before the face is reached: one array read per neighbour, since the search reaches
    // faces in scattered order.
    std::vector<int>& state = result.state;
    state.assign(faces.size(), -1);
    std::vector<int> queue;
    queue.reserve(faces.size());
    for (int seed = 0; seed < nf; ++seed) {
        if (state[seed] >= 0) continue;
        const int id = static_cast<int>(result.seed.size());
        queue.clear();
        queue.push_back(seed);
        state[seed] = 2 * id;
        bool closed = true;
        for (std::size_t q = 0; q < queue.size(); ++q) {
            const int f = queue[q];
            const int flip = state[f] & 1;
            for (int k = 0; k < 3; ++k) {
                const int code = opposite[3 * f + k];
                if (code < 0) {
                    closed = false;
                    continue;
                }
                const int g = (code >> 1) / 3;
                // Neighbours are consistent when they run along their edge in opposite ways.
                const int wanted = flip ^ (code & 1);
                if (state[g] < 0) {
                    state[g] = 2 * id + wanted;
                    queue.push_back(g);
                } else if ((state[g] & 1) != wanted && f < g) {
                    ++result.num_conflicts;
                }
            }
        }
        result.seed.push_back(seed);
        result.patch_open.push_back(closed ? 0 : 1);
    }
    return result;
}

void remove_faces(std::vector<std::array<int, 3>>& faces, std::vector<int>& source,
                  const std::vector<char>& removed) {
    std::size_t kept = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (removed[f]) continue;
        faces[kept] = faces[f];
        if (!source.empty()) source[kept] = source[f];
        ++kept;
    }
    faces.resize(kept);
    if (!source.empty()) source.resize(kept);
}

// Each patch (faces reachable over manifold edges) is made outward when closed (positive
// signed volume), else keeps the orientation most of its faces had; components are patches
// joined through non-manifold edges.
OrientedFaces orient_whole(PositionSpan positions, std::vector<std::array<int, 3>>& faces,
                           std::vector<int>& source, bool orient) {
    const int nv = static_cast<int>(positions.size());
    OrientedFaces out;
    // Duplicate faces show up among the edges, which are matched again without them.
    EdgeMatch edges = match_edges(faces, nv);
    if (edges.num_duplicates > 0) {
        out.num_duplicates = edges.num_duplicates;
        remove_faces(faces, source, edges.duplicate);
        edges = EdgeMatch();  // not held beside the new match
        edges = match_edges(faces, nv);
    }
    out.num_boundary_edges = edges.num_boundary_edges;
    out.num_non_manifold_edges = edges.num_non_manifold_edges;
    const OrientationSpread spread = spread_orientation(faces, edges.opposite);
    release(edges.opposite);

    // Per patch, in one pass in face order: six times the signed volume of a closed patch
    // (about its first face's first vertex, to keep the terms small), or how many faces of an
    // open patch disagree with its first face.
    const int nf = static_cast<int>(faces.size());
    const std::size_t num_patches = spread.seed.size();
    std::vector<double> volume6(num_patches, 0.0);
    std::vector<std::int64_t> disagree(num_patches, 0);
    std::vector<std::int64_t> size(num_patches, 0);
    for (int f = 0; f < nf; ++f) {
        const int p = spread.state[f] >> 1;
        const bool flip = (spread.state[f] & 1) != 0;
        if (spread.patch_open[p]) {
            disagree[p] += flip ? 1 : 0;
            ++size[p];
        } else {
            const Eigen::Vector3d& o = positions[faces[spread.seed[p]][0]];
            const Eigen::Vector3d a = positions[faces[f][0]] - o;
            const Eigen::Vector3d b = positions[faces[f][1]] - o;
            const Eigen::Vector3d c = positions[faces[f][2]] - o;
            const double det = a.dot(b.cross(c));
            volume6[p] += flip ? -det : det;
        }
    }
    std::vector<char> invert(num_patches, 0);
    for (std::size_t p = 0; p < num_patches; ++p) {
        invert[p] = spread.patch_open[p] ? 2 * disagree[p] > size[p] : volume6[p] < 0.0;
    }
    out.flip.resize(faces.size());
    for (int f = 0; f < nf; ++f) {
        const int p = spread.state[f] >> 1;
        out.flip[f] = orient ? static_cast<char>((spread.state[f] & 1) ^ invert[p]) : 0;
    }
    if (orient) out.num_conflicts = spread.num_conflicts;

    detail::UnionFind components(static_cast<int>(num_patches));
    for (std::size_t e = 0; e + 1 < edges.non_manifold_offsets.size(); ++e) {
        const int first = edges.non_manifold_faces[edges.non_manifold_offsets[e]];
        for (int i = edges.non_manifold_offsets[e] + 1; i < edges.non_manifold_offsets[e + 1];
             ++i) {
            components.unite(spread.state[first] >> 1,
                             spread.state[edges.non_manifold_faces[i]] >> 1);
        }
    }
    std::vector<char> component_open(num_patches, 0);
    for (std::size_t p = 0; p < num_patches; ++p) {
        if (spread.patch_open[p]) component_open[components.find(static_cast<int>(p))] = 1;
    }
    for (std::size_t p = 0; p < num_patches; ++p) {
        if (components.find(static_cast<int>(p)) == static_cast<int>(p)) {
            ++out.num_components;
            if (!component_open[p]) ++out.num_closed_components;
        }
    }
    return out;
}

}  // namespace detail

MeshRepairResult repair_soup(const PolygonSoup& soup, const MeshRepairParams& params) {
    PolygonSoup copy = soup;
    return repair_soup(std::move(copy), params);
}

MeshRepairResult repair_soup(PolygonSoup&& soup, const MeshRepairParams& params) {
    detail::validate_soup(soup);
    MeshRepairResult result;
    MeshRepairReport& report = result.report;
    report.num_input_vertices = static_cast<int>(soup.positions.size());
    report.num_input_polygons = soup.num_polygons();

    // (1) merge bit-identical vertices
    std::vector<Eigen::Vector3d>& positions = result.mesh.positions;
    positions = std::move(soup.positions);
    std::vector<int> remap = detail::vertex_remap(positions, params.merge_duplicate_vertices);
    report.num_duplicate_vertices_merged =
        report.num_input_vertices - static_cast<int>(positions.size());

    // (2) triangulate, keeping the polygon order
    std::vector<std::array<int, 3>>& faces = result.mesh.faces;
    std::vector<int> source;  // empty unless params.keep_sources
    faces.reserve(soup.face_indices.size() - 2 * static_cast<std::size_t>(soup.num_polygons()));
    if (params.keep_sources) source.reserve(faces.capacity());
    std::vector<Eigen::Vector3d> ring;
    for (int p = 0; p < soup.num_polygons(); ++p) {
        const int begin = soup.face_offsets[p];
        const int n = soup.face_offsets[p + 1] - begin;
        if (n > 3) ++report.num_polygons_triangulated;
        detail::triangulate(
            n, [&](int i) { return remap[soup.face_indices[begin + i]]; }, positions, ring, faces);
        if (params.keep_sources) source.resize(faces.size(), p);  // its faces came from p
    }

    // The soup's polygons are all in `faces` now: released before the edges, the repair's
    // largest step.
    soup = PolygonSoup();
    release(remap);

    // (3) degenerate faces (repeated vertex, or exactly collinear corners)
    const std::size_t num_triangles = faces.size();
    {
        std::vector<char> degenerate(faces.size(), 0);
        for (std::size_t f = 0; f < faces.size(); ++f) {
            if (detail::degenerate(faces[f], positions)) {
                degenerate[f] = 1;
                ++report.num_degenerate_faces_removed;
            }
        }
        if (report.num_degenerate_faces_removed > 0)
            detail::remove_faces(faces, source, degenerate);
    }
    if (faces.empty()) detail::no_face_left(num_triangles, report.num_input_polygons);

    // (4) duplicate faces and edges, (5) orientation per patch of faces joined by manifold
    // edges: in tiles when asked and they can tell it, else over the whole mesh.
    std::optional<detail::OrientedFaces> oriented;
    if (params.tiles > 1)
        oriented = detail::orient_in_tiles(result.mesh, source, params.orient, params.tiles);
    if (!oriented)
        oriented =
            detail::orient_whole(result.mesh.positions, result.mesh.faces, source, params.orient);
    detail::count_orientation(*oriented, report);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (oriented->flip[f]) {
            std::swap(faces[f][1], faces[f][2]);
            ++report.num_faces_flipped;
        }
    }
    std::vector<char> used(positions.size(), 0);
    for (const auto& t : faces) used[t[0]] = used[t[1]] = used[t[2]] = 1;
    report.num_isolated_vertices = static_cast<int>(std::count(used.begin(), used.end(), 0));

    // (6) diagnostics for what was changed or found
    result.diagnostics = detail::repair_notes(report, oriented->num_conflicts);
    result.source_polygon = std::move(source);
    return result;
}

}  // namespace geotex
