// annotate(): the one call from a mesh to the annotation document, against its own steps
// called one by one, and the value it returns (moved, outliving its inputs).

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "ontology/jsonld_writer.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/file_digest.hpp"
#include "tests/dictionary_fixtures.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
using test::default_dictionary;

namespace {

PolygonSoup soup_of(const Mesh& m) {
    PolygonSoup s;
    s.positions = m.positions;
    for (const auto& f : m.faces) {
        s.face_indices.insert(s.face_indices.end(), f.begin(), f.end());
        s.face_offsets.push_back(static_cast<int>(s.face_indices.size()));
    }
    return s;
}

AnnotateOptions small_options() {
    AnnotateOptions o;
    o.segmentation.radius_rel = 0.05;
    o.segmentation.orientation = OrientationMode::Both;
    o.description.num_resamples = 40;  // the stability test, cheaply
    o.label_language = "fr";
    o.base_iri = "https://example.org/objects/7/";
    return o;
}

std::string turtle(const AnnotationDocument& doc) {
    std::ostringstream out;
    write_annotation_rdf(out, doc, RdfFormat::Turtle);
    return out.str();
}

}  // namespace

TEST_CASE("annotate: the same document as its steps called one by one", "[pipeline][annotate]") {
    const Mesh mesh =
        repair_soup(soup_of(test::half_engraved_sphere(4))).mesh;  // as geotex annotate reads it
    const Dictionary dictionary = default_dictionary();
    const AnnotateOptions options = small_options();
    const MeshIdentity identity = array_identity(mesh, "sphere.ply");
    const Annotation a = annotate(mesh, identity, dictionary, options);

    // The steps by hand.
    const Segmentation seg = run_segmentation(mesh, options.segmentation);
    const std::vector<TextureDescription> descriptions =
        describe_textures(seg.features.values, seg.texel_texture, seg.num_textures,
                          seg.texture_orientation, dictionary, options.description);
    AnnotationDocument doc;
    doc.base_iri = options.base_iri;
    doc.mesh = &mesh;
    doc.mesh_file = "sphere.ply";
    doc.mesh_format = "ply-binary-le";
    doc.mesh_sha256 = identity.sha256;
    doc.unit_scale = 1.0 / seg.metrics.largest_side;
    doc.params = options.segmentation;
    doc.description = options.description;
    doc.software_version = version();
    doc.label_language = "fr";
    doc.segmentation = &seg;
    doc.descriptions = &descriptions;
    doc.dictionary = &dictionary;
    doc.include_dictionary = true;

    REQUIRE(a.segmentation.texels.size() > 0);
    CHECK(a.segmentation.face_texel == seg.face_texel);
    CHECK(a.segmentation.texel_texture == seg.texel_texture);
    REQUIRE(a.descriptions.size() == static_cast<std::size_t>(seg.num_textures));
    CHECK(a.num_vertices == mesh.num_vertices());
    CHECK(a.num_faces == mesh.num_faces());
    const std::string expected = turtle(doc);
    CHECK(turtle(a.document(mesh)) == expected);
    CHECK(expected.find("\"" + std::string(version()) + "\"") != std::string::npos);

    CHECK(a.diagnostics.empty());  // French is a language of the dictionary

    // The second step alone, on the same segmentation, says the same.
    const Annotation b = annotate_segmentation(seg, mesh, identity, dictionary, options);
    CHECK(turtle(b.document(mesh)) == expected);

    // A language the dictionary lacks: said in the diagnostics, labels in its first language.
    AnnotateOptions german = options;
    german.label_language = "de";
    const Annotation c = annotate_segmentation(seg, mesh, identity, dictionary, german);
    REQUIRE(c.diagnostics.size() == 1);
    CHECK(
        c.diagnostics[0].message ==
        "the dictionary 'default' has no labels in language 'de': the texture labels are in 'en', "
        "its first language");
    const std::string de = turtle(c.document(mesh));
    int texture_labels = 0;
    for (auto at = de.find("rdfs:label \""); at != std::string::npos;
         at = de.find("rdfs:label \"", at + 1)) {
        const auto end = de.find('"', at + 12);
        if (de[end + 1] != '@') continue;  // the software's name, no language
        CHECK(de.compare(end, 4, "\"@en") == 0);
        ++texture_labels;
    }
    CHECK(texture_labels >= 1);
}

TEST_CASE("annotate: the result outlives its dictionary and survives moves",
          "[pipeline][annotate]") {
    const Mesh mesh = test::half_engraved_sphere(3);
    AnnotateOptions options = small_options();
    options.segmentation.radius_rel = 0.15;
    const MeshIdentity identity = array_identity(mesh);
    std::string before;
    std::vector<Annotation> kept;
    {
        auto dictionary = std::make_unique<Dictionary>(default_dictionary());
        Annotation a = annotate(mesh, identity, *dictionary, options);
        before = turtle(a.document(mesh));
        kept.push_back(std::move(a));
        dictionary.reset();  // the caller's dictionary is gone
    }
    for (int i = 0; i < 8; ++i) kept.push_back(kept.front());  // reallocations move the first
    const Annotation moved = std::move(kept.front());
    CHECK(turtle(moved.document(mesh)) == before);
    CHECK(turtle(kept.back().document(mesh)) == before);
    std::ostringstream jsonld;
    write_annotation_jsonld(jsonld, moved.document(mesh));
    CHECK(jsonld.str().find("\"@context\"") != std::string::npos);
}

TEST_CASE("annotate: the observer hears every stage and then the annotation",
          "[pipeline][annotate]") {
    const Mesh mesh = test::half_engraved_sphere(3);
    AnnotateOptions options = small_options();
    options.segmentation.radius_rel = 0.15;
    std::vector<StageEvent> events;
    annotate(mesh, array_identity(mesh), default_dictionary(), options,
             [&](const StageEvent& e) { events.push_back(e); });
    REQUIRE(events.size() >= 4);
    CHECK(events.front().seconds < 0);
    CHECK(events[events.size() - 2].stage == "annotation");
    CHECK(events[events.size() - 2].seconds < 0);
    CHECK(events.back().stage == "annotation");
    CHECK(events.back().seconds >= 0);
}

TEST_CASE("array_identity: the digest of the PLY that write_ply writes of the arrays",
          "[pipeline][annotate]") {
    // Level 4 writes about 130 KB: more than the hashing buffer holds at once.
    const int level = GENERATE(2, 4);
    const Mesh mesh = test::half_engraved_sphere(level);
    const MeshIdentity id = array_identity(mesh, "arrays.ply");
    CHECK(id.file_name == "arrays.ply");
    CHECK(id.format == "ply-binary-le");
    const std::string path = "array_identity_test.ply";
    {
        std::ofstream out(path, std::ios::binary);
        write_ply(out, mesh, {});
    }
    // The file written from the arrays, read back, is what geotex annotate would record.
    const MeshFile file = read_mesh_file(path);
    const MeshIdentity from_file = file_identity(path, file.format);
    CHECK(from_file.sha256 == id.sha256);
    CHECK(from_file.format == id.format);
    CHECK(from_file.file_name == path);
    CHECK(file_identity("./" + path, file.format).file_name == path);
    CHECK(file_sha256(path) == id.sha256);
    std::remove(path.c_str());
    // Another mesh, another digest.
    Mesh other = mesh;
    other.positions[0].x() += 0.5;
    CHECK(array_identity(other).sha256 != id.sha256);
    CHECK(sha256_hex("") != id.sha256);
}

TEST_CASE("file_sha256: a missing file and a directory are refused with their name",
          "[pipeline][annotate]") {
    REQUIRE_THROWS_AS(file_sha256("no/such/file.ply"), IoError);
    try {
        file_sha256(".");
        FAIL("a directory was read");
    } catch (const IoError& e) {
        CHECK(e.located() == ".: cannot read: it is a directory");
    }
}

TEST_CASE("annotate: bad options, identity and mesh are refused before any work",
          "[pipeline][annotate]") {
    const Mesh mesh = test::half_engraved_sphere(2);
    const Dictionary dictionary = default_dictionary();
    const MeshIdentity identity = array_identity(mesh);
    const AnnotateOptions good = small_options();
    const auto refused = [&](AnnotateOptions o, MeshIdentity id) {
        CHECK_THROWS_AS(annotate(mesh, id, dictionary, o), InvalidInput);
    };
    AnnotateOptions o = good;
    o.base_iri = "https://example.org/no-slash";
    refused(o, identity);
    o = good;
    o.object_iri = "not an iri";
    refused(o, identity);
    o = good;
    o.creator_iri = "https://example.org/a b";
    refused(o, identity);
    o = good;
    o.label_language = "english!";
    refused(o, identity);
    o = good;
    o.timestamp = "2026-02-30T00:00:00Z";
    refused(o, identity);
    MeshIdentity id = identity;
    id.sha256 = "ABC";
    refused(good, id);
    id = identity;
    id.file_name.clear();
    refused(good, id);
    id = identity;
    id.format.clear();
    refused(good, id);
    CHECK_THROWS_AS(annotate(Mesh{}, identity, dictionary, good), InvalidInput);

    // The segmentation of another mesh, and the document of another mesh.
    const Mesh other = test::half_engraved_sphere(3);
    AnnotateOptions coarse = good;
    coarse.segmentation.radius_rel = 0.15;
    const Segmentation seg = run_segmentation(other, coarse.segmentation);
    CHECK_THROWS_AS(annotate_segmentation(seg, mesh, identity, dictionary, coarse), InvalidInput);
    const Annotation a = annotate_segmentation(seg, other, identity, dictionary, coarse);
    CHECK_THROWS_AS(a.document(mesh), InvalidInput);
    CHECK_NOTHROW(a.document(other));
}
