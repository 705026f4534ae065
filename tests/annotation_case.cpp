#include "tests/annotation_case.hpp"

#include <initializer_list>
#include <limits>

#include "geometry/feature_table.hpp"

namespace geotex::test {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Two rows of unit squares in the z = 0 plane, split into triangles: 8 squares, 16 faces.
Mesh strip_mesh() {
    Mesh m;
    for (int y = 0; y <= 1; ++y)
        for (int x = 0; x <= 8; ++x) m.positions.emplace_back(x, y, 0);
    for (int x = 0; x < 8; ++x) {
        const int a = x, b = x + 1, c = 9 + x + 1, d = 9 + x;
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
    }
    return m;
}

/// Column values of one feature row, with awkward doubles among them.
std::vector<double> row(std::initializer_list<double> firsts) {
    std::vector<double> r(kNumFeatures, 0.5);
    std::size_t i = 0;
    for (double v : firsts) r[i++] = v;
    return r;
}

}  // namespace

SmallAnnotationCase::SmallAnnotationCase() : mesh(strip_mesh()) {
    // Texels: faces {0,1,2}, {5,6,7,9} and {12..15}; textures {0, 2} and {1}.
    const std::vector<std::vector<int>> faces = {{0, 1, 2}, {5, 6, 7, 9}, {12, 13, 14, 15}};
    seg.radius = 0.25;
    seg.face_texel.assign(16, -1);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        Texel t;
        t.faces = faces[i];
        t.orientation = i == 1 ? DetailOrientation::Negative : DetailOrientation::Positive;
        seg.texels.push_back(t);
        for (int f : faces[i]) seg.face_texel[static_cast<std::size_t>(f)] = static_cast<int>(i);
    }
    seg.texel_texture = {0, 1, 0};
    seg.num_textures = 2;
    seg.texture_orientation = {DetailOrientation::Positive, DetailOrientation::Negative};
    seg.features.names.assign(kFeatureIds.begin(), kFeatureIds.end());
    seg.features.values.resize(3, kNumFeatures);
    const std::vector<std::vector<double>> rows = {
        row({12.5, 0.01, 1e-300, -0.0, 0.1, 1.0 / 3.0, 0.0, 0.5, 0.3, 0.0}),
        row({4.0, 0.3, 5e-324, 1e21, 1.0, 0.25, 16.0, 0.9, 0.1, 0.0}),
        row({123456789.125, 0.02, -2.5e-8, 0.75, 0.3, 1.0, 12.566370614359172, 0.6, 0.3, 0.001})};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < kNumFeatures; ++j)
            seg.features.values(i, j) =
                rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];

    dictionary.id = "demo";
    dictionary.version = "1.0";
    dictionary.namespace_iri = "https://example.org/dict/";
    dictionary.titles = {{"en", "Demo dictionary"}, {"fr", "Dictionnaire de démonstration"}};
    dictionary.languages = {"en", "fr"};
    dictionary.sha256 = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08";
    dictionary.source_name = "demo.yaml";
    dictionary.concepts.resize(5);
    auto& circular = dictionary.concepts[0];
    circular.id = "circular-shape";
    circular.feature = static_cast<int>(Feature::ContourSphericity);
    circular.upper = 0.05;
    circular.upper_text = "0.05";
    circular.labels = {{"en", "circular shape"}, {"fr", "forme circulaire"}};
    circular.definitions = {{"en", "The contour stays close to a circle."}};
    circular.source = "paper, Table 3";
    auto& small = dictionary.concepts[1];
    small.id = "small-area";
    small.feature = static_cast<int>(Feature::Area);
    small.lower = 0;
    small.lower_text = "0";
    small.upper = 0.25;
    small.upper_text = ".25";
    small.labels = {{"en", "small area"}, {"fr", "petite aire"}};
    auto& elongated = dictionary.concepts[2];
    elongated.id = "elongated";
    elongated.feature = static_cast<int>(Feature::PcaVariance1);
    elongated.lower = 0.8;
    elongated.lower_text = "8e-1";
    elongated.labels = {{"en", "elongated"}, {"fr", "allongé"}};
    elongated.relief = Relief::Engraved;
    auto& flat = dictionary.concepts[3];
    flat.id = "flat";
    flat.feature = static_cast<int>(Feature::PcaVariance3);
    flat.lower = 0;
    flat.upper = 1e-3;
    flat.labels = {{"en", "flat"}, {"fr", "plat"}};
    // Last, out of the parser's order (by feature, then lower bound): the writers must not
    // rely on it.
    auto& large = dictionary.concepts[4];
    large.id = "large-area";
    large.feature = static_cast<int>(Feature::Area);
    large.lower = 0.25;
    large.lower_text = "0.25";
    large.labels = {{"en", "large area"}, {"fr", "grande aire"}};

    dictionary.declares_facets = true;
    const auto facet = [](const char* id, const char* en, const char* fr, Feature f) {
        DictionaryFacet out;
        out.id = id;
        out.labels = {{"en", en}, {"fr", fr}};
        out.features = {static_cast<int>(f)};
        return out;
    };
    dictionary.facets = {facet("outline", "outline", "contour", Feature::ContourSphericity),
                         facet("size", "size", "taille", Feature::Area),
                         facet("elongation", "elongation", "allongement", Feature::PcaVariance1),
                         facet("flatness", "flatness", "planéité", Feature::PcaVariance3)};
    dictionary.feature_facet.assign(kNumFeatures, -1);
    for (std::size_t i = 0; i < dictionary.facets.size(); ++i)
        dictionary.feature_facet[static_cast<std::size_t>(dictionary.facets[i].features[0])] =
            static_cast<int>(i);

    // Texture 0 (texels 0 and 2): circular shape and small area chosen, flat withheld; texture
    // 1 (one texel): every S is 0, elongated chosen.
    for (int k = 0; k < 2; ++k) {
        TextureDescription t;
        t.texture = k;
        t.num_texels = k == 0 ? 2 : 1;
        for (int j = 0; j < kNumFeatures; ++j) {
            FeatureScore f;
            f.feature = j;
            f.value = k == 0 ? (seg.features.values(0, j) + seg.features.values(2, j)) / 2
                             : seg.features.values(1, j);
            f.significance = k == 0 ? 0.1 * (j + 1) : 0.0;
            f.rank = j + 1;
            f.facet = dictionary.feature_facet[static_cast<std::size_t>(j)];
            t.features.push_back(f);
        }
        t.features[5].significance = kNaN;  // constant over all texels
        t.features[5].rank = 0;
        descriptions.push_back(t);
    }
    auto& t0 = descriptions[0];
    t0.features[1].concept_ptr = &dictionary.concepts[0];
    t0.features[1].chosen = true;
    t0.features[1].agreement = 1;  // both texels are circular
    t0.features[1].stability = 0.985;
    t0.features[4].concept_ptr = &dictionary.concepts[1];  // the mean 0.2 is a small area,
    t0.features[4].chosen = true;                          // but not texel 2's own 0.3
    t0.features[4].agreement = 0.5;
    t0.features[4].stability = 0.9;
    t0.features[9].concept_ptr = &dictionary.concepts[3];  // holds the mean, withheld
    t0.features[9].withheld = true;
    t0.features[9].agreement = 0.5;
    t0.features[9].stability = 0.625;
    t0.chosen = {1, 4};
    t0.withheld = {9};
    auto& t1 = descriptions[1];
    t1.features[7].concept_ptr = &dictionary.concepts[2];
    t1.features[7].chosen = true;
    t1.features[7].agreement = 1;
    t1.features[7].stability = 1;
    t1.chosen = {7};
    t1.note = "one texel";

    doc.base_iri = "https://example.org/objects/vase-42/";
    doc.mesh_file = "vase.ply";
    doc.mesh_format = "ply-binary-le";
    doc.mesh_sha256 = kMeshDigest;
    doc.unit_scale = 0.125;
    doc.params.clustering.max_clusters = 4;
    doc.description.max_concepts = 2;
    doc.description.max_significance = 0.5;  // set, so that the golden files show the parameter
    doc.software_version = "0.9.0";
    doc.max_literal_faces = 3;  // texels 1 and 2 get a digest instead of their ranges
    doc.mesh = &mesh;
    doc.segmentation = &seg;
    doc.descriptions = &descriptions;
    doc.dictionary = &dictionary;
}

const std::vector<BrokenCase>& broken_cases() {
    static const std::vector<BrokenCase> cases = {
        {"missing segmentation", [](SmallAnnotationCase& c) { c.doc.segmentation = nullptr; }},
        {"missing mesh", [](SmallAnnotationCase& c) { c.doc.mesh = nullptr; }},
        {"missing descriptions", [](SmallAnnotationCase& c) { c.doc.descriptions = nullptr; }},
        {"missing dictionary", [](SmallAnnotationCase& c) { c.doc.dictionary = nullptr; }},
        {"base IRI with a space",
         [](SmallAnnotationCase& c) { c.doc.base_iri = "https://example.org/my vase/"; }},
        {"base IRI with '>'",
         [](SmallAnnotationCase& c) { c.doc.base_iri = "https://example.org/a>b/"; }},
        {"relative base IRI", [](SmallAnnotationCase& c) { c.doc.base_iri = "vase/"; }},
        {"bad mesh digest", [](SmallAnnotationCase& c) { c.doc.mesh_sha256 = "abc"; }},
        {"empty file name", [](SmallAnnotationCase& c) { c.doc.mesh_file.clear(); }},
        {"unit scale 0", [](SmallAnnotationCase& c) { c.doc.unit_scale = 0; }},
        {"non-finite feature", [](SmallAnnotationCase& c) { c.seg.features.values(2, 7) = kInf; }},
        {"NaN measurement",
         [](SmallAnnotationCase& c) { c.descriptions[1].features[3].value = kNaN; }},
        {"bad timestamp", [](SmallAnnotationCase& c) { c.doc.timestamp = "yesterday"; }},
        {"unsorted faces",
         [](SmallAnnotationCase& c) {
             c.seg.texels[1].faces = {6, 5, 7, 9};
         }},
        {"face out of range",
         [](SmallAnnotationCase& c) {
             c.seg.texels[1].faces = {5, 6, 7, 16};
         }},
        {"texture label out of range", [](SmallAnnotationCase& c) { c.seg.texel_texture[1] = 2; }},
        {"description count", [](SmallAnnotationCase& c) { c.descriptions.pop_back(); }},
        {"texel count", [](SmallAnnotationCase& c) { c.descriptions[0].num_texels = 3; }},
        {"missing feature", [](SmallAnnotationCase& c) { c.descriptions[0].features.pop_back(); }},
        {"chosen without concept",
         [](SmallAnnotationCase& c) {
             c.descriptions[0].features[2].chosen = true;
             c.descriptions[0].chosen.push_back(2);
         }},
        {"foreign concept",
         [](SmallAnnotationCase& c) {
             static DictionaryConcept other;
             c.descriptions[0].features[3].concept_ptr = &other;
         }},
        {"mesh of another size", [](SmallAnnotationCase& c) { c.mesh.faces.pop_back(); }},
        {"bad dictionary namespace",
         [](SmallAnnotationCase& c) { c.dictionary.namespace_iri = "https://example.org/dict"; }},
        {"concept id 'scheme'",
         [](SmallAnnotationCase& c) { c.dictionary.concepts[2].id = "scheme"; }},
        {"bad dictionary digest", [](SmallAnnotationCase& c) { c.dictionary.sha256 = "abc"; }},
        {"negative cap", [](SmallAnnotationCase& c) { c.doc.max_literal_faces = -1; }},
        {"rank without significance",
         [](SmallAnnotationCase& c) { c.descriptions[0].features[5].rank = 18; }},
        {"significance without rank",
         [](SmallAnnotationCase& c) { c.descriptions[1].features[0].rank = 0; }},
        {"rank beyond the feature count",
         [](SmallAnnotationCase& c) { c.descriptions[1].features[0].rank = kNumFeatures + 1; }},
        {"negative significance",
         [](SmallAnnotationCase& c) { c.descriptions[1].features[0].significance = -1; }},
        {"radius_rel out of range", [](SmallAnnotationCase& c) { c.doc.params.radius_rel = 1.5; }},
        {"no radius", [](SmallAnnotationCase& c) { c.seg.radius = 0; }},
        {"min_quality out of range",
         [](SmallAnnotationCase& c) { c.doc.params.clustering.min_quality = 2; }},
        {"quality_tolerance above 1",
         [](SmallAnnotationCase& c) { c.doc.params.clustering.quality_tolerance = 1.5; }},
        {"curvature_scale out of range",
         [](SmallAnnotationCase& c) { c.doc.params.curvature_scale = 2; }},
        {"max_concepts negative",
         [](SmallAnnotationCase& c) { c.doc.description.max_concepts = -1; }},
        {"max_significance negative",
         [](SmallAnnotationCase& c) { c.doc.description.max_significance = -1; }},
        {"min_agreement out of range",
         [](SmallAnnotationCase& c) { c.doc.description.min_agreement = 1.5; }},
        {"min_stability NaN",
         [](SmallAnnotationCase& c) { c.doc.description.min_stability = kNaN; }},
        {"negative resamples",
         [](SmallAnnotationCase& c) { c.doc.description.num_resamples = -1; }},
        {"chosen and withheld",
         [](SmallAnnotationCase& c) { c.descriptions[0].features[1].withheld = true; }},
        {"withheld without concept",
         [](SmallAnnotationCase& c) {
             c.descriptions[0].features[2].withheld = true;
             c.descriptions[0].withheld.push_back(2);
         }},
        {"withheld index of a feature not withheld",
         [](SmallAnnotationCase& c) { c.descriptions[0].withheld = {4}; }},
        {"stability above 1",
         [](SmallAnnotationCase& c) { c.descriptions[0].features[4].stability = 1.5; }},
        {"NaN agreement",
         [](SmallAnnotationCase& c) { c.descriptions[1].features[7].agreement = kNaN; }},
        {"an engraving called by a raised word",
         [](SmallAnnotationCase& c) { c.dictionary.concepts[2].relief = Relief::Raised; }},
        {"file name with a control character",
         [](SmallAnnotationCase& c) { c.doc.mesh_file = "a\x01.ply"; }},
        {"label not UTF-8",
         [](SmallAnnotationCase& c) { c.dictionary.concepts[0].labels["en"] = "caf\xE9"; }},
        {"label with a non-character",
         [](SmallAnnotationCase& c) { c.dictionary.concepts[0].labels["en"] = "\xEF\xBF\xBE"; }},
        {"bad language tag of a label",
         [](SmallAnnotationCase& c) { c.dictionary.concepts[0].labels["en fr"] = "x"; }},
        {"bad label language", [](SmallAnnotationCase& c) { c.doc.label_language = "en fr"; }},
    };
    return cases;
}

}  // namespace geotex::test
