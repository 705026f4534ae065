// The geometry cache: what run_segmentation gave comes back from the file unchanged, and a
// file for another key, a truncated or a foreign file is refused with the reason.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "annotation/digest.hpp"
#include "geometry/synth.hpp"
#include "pipeline/geometry_cache.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
using test::same_bits;

namespace {

const std::string kDigest = sha256_hex("a mesh file");

struct SegmentedCase {
    Mesh mesh;
    SegmentationParams params;
    Segmentation seg;
};

// Raised and engraved shapes, both orientations: two runs, textures of each.
const SegmentedCase& both_orientations() {
    static const SegmentedCase c = [] {
        SegmentedCase k;
        SynthParams p;
        p.level = 4;
        p.engraved_fraction = 0.5;
        k.mesh = make_synthetic_sphere(p).mesh;
        k.params.radius_rel = 0.08;
        k.params.orientation = OrientationMode::Both;
        k.seg = run_segmentation(k.mesh, k.params);
        return k;
    }();
    return c;
}

std::string cache_bytes(const Segmentation& seg, const std::string& key) {
    std::ostringstream out;
    write_geometry_cache(out, key, seg);
    return out.str();
}

bool same_diagnostics(const Diagnostics& a, const Diagnostics& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].stage != b[i].stage || a[i].message != b[i].message) return false;
    return true;
}

}  // namespace

TEST_CASE("geometry cache: a round trip gives back what the outputs use", "[pipeline][cache]") {
    const SegmentedCase& c = both_orientations();
    const Segmentation& seg = c.seg;
    REQUIRE(seg.runs.size() == 2);
    REQUIRE(seg.texels.size() > 2);
    const std::string key = geometry_cache_key(kDigest, c.params);
    const std::string path = "cache_round_trip.cbor";
    test::write_file(path, cache_bytes(seg, key));
    const GeometryCacheRead read = read_geometry_cache(path, key, c.mesh);
    std::remove(path.c_str());
    INFO(read.refusal);
    REQUIRE(read.segmentation);
    CHECK(read.refusal.empty());
    const Segmentation& back = *read.segmentation;

    CHECK(same_bits(back.radius, seg.radius));
    CHECK(back.num_interpolated_vertices == seg.num_interpolated_vertices);
    CHECK(back.num_disc_samples == seg.num_disc_samples);
    CHECK(back.runs == seg.runs);
    CHECK(back.run_excluded_texels == seg.run_excluded_texels);
    CHECK(back.face_texel == seg.face_texel);
    CHECK(back.face_texture == seg.face_texture);
    CHECK(back.texel_texture == seg.texel_texture);
    CHECK(back.num_textures == seg.num_textures);
    CHECK(back.texture_orientation == seg.texture_orientation);
    REQUIRE(back.texels.size() == seg.texels.size());
    for (std::size_t i = 0; i < seg.texels.size(); ++i) {
        CHECK(back.texels[i].faces == seg.texels[i].faces);
        CHECK(back.texels[i].seed == seg.texels[i].seed);
        CHECK(back.texels[i].orientation == seg.texels[i].orientation);
        CHECK(same_bits(back.texels[i].threshold, seg.texels[i].threshold));
        CHECK(same_bits(back.texels[i].depth_mean, seg.texels[i].depth_mean));
        CHECK(same_bits(back.texels[i].depth_std, seg.texels[i].depth_std));
    }
    CHECK(back.features.names == seg.features.names);
    REQUIRE(back.features.values.rows() == seg.features.values.rows());
    REQUIRE(back.features.values.cols() == seg.features.values.cols());
    for (Eigen::Index i = 0; i < seg.features.values.rows(); ++i)
        for (Eigen::Index j = 0; j < seg.features.values.cols(); ++j)
            CHECK(same_bits(back.features.values(i, j), seg.features.values(i, j)));
    REQUIRE(back.clusterings.size() == seg.clusterings.size());
    for (std::size_t r = 0; r < seg.clusterings.size(); ++r) {
        CHECK(back.clusterings[r].labels == seg.clusterings[r].labels);
        CHECK(back.clusterings[r].num_clusters == seg.clusterings[r].num_clusters);
        CHECK(back.texel_sets[r].num_regions == seg.texel_sets[r].num_regions);
        CHECK(same_bits(back.texel_sets[r].global_threshold, seg.texel_sets[r].global_threshold));
    }
    CHECK(same_bits(back.positive_depth->max_depth, seg.positive_depth->max_depth));
    CHECK(same_bits(back.negative_depth->max_depth, seg.negative_depth->max_depth));
    CHECK(same_diagnostics(back.diagnostics, seg.diagnostics));
    CHECK(same_bits(back.metrics.largest_side, seg.metrics.largest_side));
    // Writing what was read gives the same bytes: nothing lost, nothing added.
    CHECK(cache_bytes(back, key) == cache_bytes(seg, key));
}

TEST_CASE("geometry cache: the key changes with the mesh and every parameter",
          "[pipeline][cache]") {
    const SegmentationParams p;
    const std::string key = geometry_cache_key(kDigest, p);
    CHECK(key.size() == 64);
    CHECK(geometry_cache_key(kDigest, p) == key);
    CHECK(geometry_cache_key(sha256_hex("another mesh file"), p) != key);
    // One change of every field of SegmentationParams and ClusteringParams: each gives a key
    // of its own.
    const std::vector<std::pair<const char*, std::function<void(SegmentationParams&)>>> changes = {
        {"radius_rel", [](SegmentationParams& q) { q.radius_rel = 0.05; }},
        {"radius", [](SegmentationParams& q) { q.radius = 0.1; }},
        {"orientation", [](SegmentationParams& q) { q.orientation = OrientationMode::Negative; }},
        {"smoothing", [](SegmentationParams& q) { q.smoothing = SmoothingMethod::Mean; }},
        {"area_weighted", [](SegmentationParams& q) { q.area_weighted = false; }},
        {"disc", [](SegmentationParams& q) { q.disc = DiscMode::Exact; }},
        {"curvature_scale", [](SegmentationParams& q) { q.curvature_scale = 0.5; }},
        {"merge_overlap", [](SegmentationParams& q) { q.merge_overlap = 0.4; }},
        {"min_depth_rel", [](SegmentationParams& q) { q.min_depth_rel = 0.02; }},
        {"min_faces", [](SegmentationParams& q) { q.min_faces = 4; }},
        {"remove_rims", [](SegmentationParams& q) { q.remove_rims = false; }},
        {"neighbour_rank", [](SegmentationParams& q) { q.clustering.neighbour_rank += 1; }},
        {"max_clusters", [](SegmentationParams& q) { q.clustering.max_clusters += 1; }},
        {"quality_tolerance", [](SegmentationParams& q) { q.clustering.quality_tolerance = 0.01; }},
        {"min_quality", [](SegmentationParams& q) { q.clustering.min_quality = 0.9; }},
        {"max_conductance", [](SegmentationParams& q) { q.clustering.max_conductance = 0.2; }},
        {"max_points", [](SegmentationParams& q) { q.clustering.max_points = 0; }},
    };
    std::set<std::string> keys{key};
    for (const auto& [name, change] : changes) {
        CAPTURE(name);
        SegmentationParams q = p;
        change(q);
        CHECK(keys.insert(geometry_cache_key(kDigest, q)).second);
    }
    // An absolute radius (--radius) replaces the relative one: two radii, two keys.
    SegmentationParams r = p;
    r.radius = 0.1;
    const std::string key_01 = geometry_cache_key(kDigest, r);
    r.radius = 0.3;
    CHECK(geometry_cache_key(kDigest, r) != key_01);
}

TEST_CASE("geometry cache: another key, a truncated or foreign file is refused with the reason",
          "[pipeline][cache]") {
    const SegmentedCase& c = both_orientations();
    const std::string key = geometry_cache_key(kDigest, c.params);
    const std::string bytes = cache_bytes(c.seg, key);

    SECTION("absent: nothing, and no refusal") {
        const GeometryCacheRead read = read_geometry_cache("no/such/cache.cbor", key, c.mesh);
        CHECK_FALSE(read.segmentation);
        CHECK(read.refusal.empty());
    }
    SECTION("another key") {
        const std::string path = "cache_other_key.cbor";
        test::write_file(path, bytes);
        SegmentationParams other = c.params;
        other.radius_rel = 0.1;
        const GeometryCacheRead read =
            read_geometry_cache(path, geometry_cache_key(kDigest, other), c.mesh);
        std::remove(path.c_str());
        CHECK_FALSE(read.segmentation);
        CHECK(read.refusal == "made from another mesh, other parameters or another geotex version");
    }
    SECTION("truncated anywhere") {
        for (std::size_t n : {std::size_t{0}, std::size_t{1}, bytes.size() / 3, bytes.size() - 1}) {
            const std::string path = "cache_truncated.cbor";
            test::write_file(path, bytes.substr(0, n));
            const GeometryCacheRead read = read_geometry_cache(path, key, c.mesh);
            std::remove(path.c_str());
            INFO("first " << n << " bytes of " << bytes.size());
            CHECK_FALSE(read.segmentation);
            CHECK(read.refusal.rfind("unreadable (", 0) == 0);
        }
    }
    SECTION("not a cache") {
        const std::string path = "cache_foreign.cbor";
        test::write_file(path, "{\"format\": \"json\"}");
        const GeometryCacheRead read = read_geometry_cache(path, key, c.mesh);
        std::remove(path.c_str());
        CHECK_FALSE(read.segmentation);
        CHECK(read.refusal.rfind("unreadable (", 0) == 0);
    }
    SECTION("made for a mesh of another size") {
        SynthParams p;
        p.level = 3;
        const Mesh other = make_synthetic_sphere(p).mesh;
        const std::string path = "cache_other_mesh.cbor";
        test::write_file(path, bytes);
        const GeometryCacheRead read = read_geometry_cache(path, key, other);
        std::remove(path.c_str());
        CHECK_FALSE(read.segmentation);
        CHECK(read.refusal == "unreadable (made for a mesh of another size)");
    }
}
