#include "ontology/rdf_writer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "annotation/digest.hpp"
#include "annotation/texture_label.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/scale_levels.hpp"
#include "ontology/detail/annotation_document.hpp"
#include "ontology/detail/annotation_graph.hpp"
#include "ontology/detail/rdf_graph.hpp"
#include "ontology/detail/triple_sink.hpp"
#include "ontology/rdf_lexical.hpp"

namespace geotex {

namespace {

using namespace rdf_detail;

// ---- the annotation -------------------------------------------------------------------------

/// The power of length in the dimension of a feature on the unit-side mesh (docs/features.md):
/// 1 for a length, 2 for an area, -1 and -2 for curvatures, 0 when dimensionless.
int length_power(int feature) {
    const std::string id = kFeatureIds[static_cast<std::size_t>(feature)];
    if (id == "contour_perimeter" || id == "bounding_sphere_radius_rel") return 1;
    if (id == "area_rel") return 2;
    if (id == "curvedness_mean" || id == "curvedness_std") return -1;
    if (id == "gaussian_curvature_mean" || id == "gaussian_curvature_std") return -2;
    return 0;
}

/// The IANA media type of a mesh format, "" when none is registered (PLY and OFF have none;
/// gtx:fileFormat names them).
std::string media_type(const std::string& format) {
    if (format == "obj") return "model/obj";
    if (format == "stl") return "model/stl";
    return "";
}

/// The visual item that the mesh shows (Linked Art): a fragment of a hash name, a path
/// segment under a base.
std::string visual_item_iri(const std::string& mesh) {
    return mesh + (mesh.rfind("ni:", 0) == 0 ? "#visual-item" : "/visual-item");
}

/// Area-weighted centroid of the texel's surface, in unit-side coordinates (mesh coordinates
/// times unit_scale, no translation), as "x y z" of xsd:double lexical forms.
std::string centroid_lexical(const Mesh& mesh, const std::vector<int>& faces, double unit_scale,
                             const std::string& what) {
    // Areas are squared lengths: a mesh 1e100 wide would overflow them. The positions are
    // brought near unit size by a power of two (exact: the same bits of result as without it
    // for any mesh that did not overflow) and unit_scale is corrected by the same power.
    const int exponent = -std::ilogb(unit_scale);
    unit_scale = std::ldexp(unit_scale, exponent);
    const auto position = [&](int v) -> Eigen::Vector3d {
        const Eigen::Vector3d& p = mesh.positions[static_cast<std::size_t>(v)];
        return {std::ldexp(p.x(), -exponent), std::ldexp(p.y(), -exponent),
                std::ldexp(p.z(), -exponent)};
    };
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero(), plain = Eigen::Vector3d::Zero();
    double area = 0;
    for (int f : faces) {
        const auto& fv = mesh.faces[static_cast<std::size_t>(f)];
        const Eigen::Vector3d a = position(fv[0]);
        const Eigen::Vector3d b = position(fv[1]);
        const Eigen::Vector3d c = position(fv[2]);
        const double fa = 0.5 * (b - a).cross(c - a).norm();
        const Eigen::Vector3d centre = (a + b + c) / 3.0;
        first_moment += fa * centre;
        plain += centre;
        area += fa;
    }
    // A texel of zero area (degenerate faces only) falls back to the mean of face centres.
    const Eigen::Vector3d c =
        unit_scale * (area > 0 ? Eigen::Vector3d(first_moment / area)
                               : Eigen::Vector3d(plain / static_cast<double>(faces.size())));
    return double_lexical(c.x(), what) + " " + double_lexical(c.y(), what) + " " +
           double_lexical(c.z(), what);
}

/// With a known mesh unit, a feature of length or area dimension is also given in that unit:
/// `node property Q`, Q a qudt:QuantityValue of the value times L^power (L the mesh's largest
/// side in the unit, 1 / unit_scale).
void emit_quantity(Graph& g, const Document& d, const std::string& node,
                   const std::string& property, const std::string& quantity, int feature,
                   double value, const std::string& what) {
    const int power = length_power(feature);
    if (d.doc.mesh_unit == MeshUnit::Unknown || (power != 1 && power != 2)) return;
    const double side = 1.0 / d.doc.unit_scale;
    g.iri(node, property, quantity);
    g.type(quantity, qudt("QuantityValue"));
    g.iri(quantity, gtx("ofFeature"), feature_iri(feature));
    g.dbl(quantity, qudt("numericValue"), value * (power == 2 ? side * side : side),
          what + " in the mesh unit");
    g.iri(quantity, qudt("unit"), unit_iri(d.doc.mesh_unit, power));
}

/// Who made an annotation (Web Annotation): the software as generator, the user's creator,
/// the time only when asked (same input, same bytes).
void emit_authorship(Graph& g, const AnnotationDocument& doc, const std::string& annotation,
                     const std::string& software) {
    g.iri(annotation, as("generator"), software);
    if (!doc.creator_iri.empty()) g.iri(annotation, dcterms("creator"), doc.creator_iri);
    if (!doc.timestamp.empty())
        g.typed(annotation, dcterms("created"), doc.timestamp, xsd("dateTime"));
}

void emit_level(Graph& g, const Document& d, const Segmentation& seg,
                const std::vector<TextureDescription>& descriptions, const std::string& B,
                const std::string& run, const std::string& software);
void emit_levels(Graph& g, const Document& d, const std::string& run, const std::string& software);

void emit_annotation(Graph& g, const Document& d) {
    const AnnotationDocument& doc = d.doc;
    const Segmentation& seg = d.seg;
    const std::string& B = d.names.base;
    const std::string& mesh = d.names.mesh;
    const std::string run = B + "run", software = software_iri(doc.software_version),
                      parameters = B + "run/parameters",
                      dictionary_used = version_iri(d.dictionary_ns, d.dictionary);

    // Mesh: a CRMdig digital object, the same node for every run of it.
    g.type(mesh, gtx("Mesh"));
    g.type(mesh, crmdig("D1_Digital_Object"));
    g.type(mesh, prov("Entity"));
    g.text(mesh, dcterms("identifier"), doc.mesh_file, "the mesh file name");
    g.text(mesh, gtx("fileFormat"), doc.mesh_format, "the mesh format");
    if (const std::string type = media_type(doc.mesh_format); !type.empty())
        g.text(mesh, dc("format"), type, "the media type");
    g.text(mesh, gtx("sha256"), doc.mesh_sha256, "the mesh digest");
    g.integer(mesh, gtx("vertexCount"), d.mesh.num_vertices());
    g.integer(mesh, gtx("faceCount"), d.mesh.num_faces());
    g.dbl(mesh, gtx("unitScale"), doc.unit_scale, "unit_scale");
    if (!doc.object_iri.empty()) {
        // CIDOC-CRM's short path, and Linked Art's pattern: the digital object shows a visual
        // item that represents the object (the object's record may say the inverse).
        const std::string visual = visual_item_iri(mesh);
        g.iri(mesh, crm("P138_represents"), doc.object_iri);
        g.iri(mesh, la("digitally_shows"), visual);
        g.type(visual, crm("E36_Visual_Item"));
        g.iri(visual, crm("P138_represents"), doc.object_iri);
        g.iri(doc.object_iri, crm("P138i_has_representation"), visual);
    }

    // Software (one node per geotex version) and run.
    g.type(software, prov("SoftwareAgent"));
    g.type(software, as("Application"));
    g.text(software, rdfs("label"), "geotex", "software name");
    g.text(software, owl("versionInfo"), doc.software_version, "the software version");
    g.type(run, gtx("TextureAnalysis"));
    g.type(run, prov("Activity"));
    g.text(run, gtx("runKey"), d.names.key, "the run key");
    g.iri(run, prov("used"), mesh);
    g.iri(run, prov("used"), scheme_iri(d.dictionary_ns));
    g.iri(run, prov("used"), parameters);
    g.iri(run, prov("used"), dictionary_used);
    g.iri(run, prov("wasAssociatedWith"), software);
    if (!doc.creator_iri.empty()) g.iri(run, prov("wasAssociatedWith"), doc.creator_iri);
    if (!doc.timestamp.empty()) g.typed(run, prov("endedAtTime"), doc.timestamp, xsd("dateTime"));

    // The version of the dictionary this run used (its scheme's IRI is the same for every
    // version). With the dictionary in the graph, emit_dictionary writes this node.
    if (!doc.include_dictionary) emit_dictionary_version(g, d.dictionary, d.dictionary_ns);

    emit_parameters(g, parameters, doc, seg);

    emit_level(g, d, seg, d.descriptions, B, run, software);
    if (doc.levels != nullptr) emit_levels(g, d, run, software);
}

/// The textures of one segmentation, their measurements and annotations, then its texels and
/// their face selectors, as nodes under `B` (the run's base; `B level/K/` for a level of
/// detail other than the main one).
void emit_level(Graph& g, const Document& d, const Segmentation& seg,
                const std::vector<TextureDescription>& descriptions, const std::string& B,
                const std::string& run, const std::string& software) {
    const AnnotationDocument& doc = d.doc;
    const std::string& mesh = d.names.mesh;
    // Textures, their measurements and annotations.
    std::vector<std::vector<std::size_t>> texels_of(descriptions.size());
    for (std::size_t i = 0; i < seg.texels.size(); ++i)
        texels_of[static_cast<std::size_t>(seg.texel_texture[i])].push_back(i);
    for (std::size_t k = 0; k < descriptions.size(); ++k) {
        const TextureDescription& t = descriptions[k];
        const std::string texture = texture_iri(B, k);
        const std::string what = "texture " + std::to_string(k);
        g.type(texture, gtx("GeometricTexture"));
        g.type(texture, prov("Entity"));
        // The texture is the target of its annotation: its texels as a whole, part of the mesh.
        g.type(texture, oa("SpecificResource"));
        g.iri(texture, oa("hasSource"), mesh);
        for (std::size_t i : texels_of[k]) g.iri(texture, gtx("hasTexel"), texel_iri(B, i));
        g.integer(texture, gtx("texelCount"), t.num_texels);
        g.iri(texture, gtx("orientation"), orientation_iri(seg.texture_orientation[k]));
        const auto [label, label_lang] =
            texture_label(t, t.chosen, d.dictionary, doc.label_language);
        if (!label.empty()) {
            if (label_lang.empty())
                g.text(texture, rdfs("label"), label, what + " label");
            else
                g.lang_text(texture, rdfs("label"), label, label_lang, what + " label");
        }
        g.iri(texture, prov("wasGeneratedBy"), run);

        // Measurements in feature column order.
        std::vector<const FeatureScore*> by_column(kNumFeatures, nullptr);
        for (const FeatureScore& f : t.features)
            by_column[static_cast<std::size_t>(f.feature)] = &f;
        for (const FeatureScore* f : by_column) {
            const std::string id = kFeatureIds[static_cast<std::size_t>(f->feature)];
            const std::string m = measurement_iri(B, k, f->feature);
            const std::string mwhat = what + " " + id;
            g.type(m, gtx("FeatureMeasurement"));
            g.type(m, sosa("Observation"));
            g.iri(m, sosa("hasFeatureOfInterest"), texture);
            g.iri(m, sosa("observedProperty"), feature_iri(f->feature));
            g.dbl(m, sosa("hasSimpleResult"), f->value, mwhat + " value");
            emit_quantity(g, d, m, sosa("hasResult"), m + "/quantity", f->feature, f->value, mwhat);
            if (!std::isnan(f->significance))
                g.dbl(m, gtx("significance"), f->significance, mwhat + " significance");
            if (f->rank > 0) g.integer(m, gtx("rank"), f->rank);
            if (f->concept_ptr) {
                g.iri(m, gtx("concept"), concept_iri(d.dictionary_ns, *f->concept_ptr));
                // The interval that held the value: the concept's in the version the run used.
                g.iri(m, gtx("interval"),
                      interval_iri(d.dictionary_ns, d.dictionary, *f->concept_ptr));
                g.dbl(m, gtx("agreement"), f->agreement, mwhat + " agreement");
            }
            // Stability is measured only for the concept the rule picks for its facet.
            if (f->chosen || f->withheld)
                g.dbl(m, gtx("stability"), f->stability, mwhat + " stability");
            g.boolean(m, gtx("chosen"), f->chosen);
            if (f->withheld) g.boolean(m, gtx("withheld"), true);
        }

        const std::string annotation = annotation_iri(B, k);
        g.type(annotation, oa("Annotation"));
        g.iri(annotation, oa("motivatedBy"), oa("classifying"));
        // Its score is that of its weakest body: each body is at least this stable and holds
        // for at least this share of the texels (ontology/README.md).
        double stability = 1, agreement = 1;
        for (int i : t.chosen) {
            const FeatureScore& f = t.features[static_cast<std::size_t>(i)];
            g.iri(annotation, oa("hasBody"), concept_iri(d.dictionary_ns, *f.concept_ptr));
            g.iri(annotation, gtx("justifiedBy"), measurement_iri(B, k, f.feature));
            stability = std::min(stability, f.stability);
            agreement = std::min(agreement, f.agreement);
        }
        if (!t.chosen.empty()) {
            g.dbl(annotation, gtx("stability"), stability, what + " stability");
            g.dbl(annotation, gtx("agreement"), agreement, what + " agreement");
        }
        g.iri(annotation, oa("hasTarget"), texture);
        g.iri(annotation, gtx("describes"), texture);
        g.iri(annotation, prov("wasGeneratedBy"), run);
        emit_authorship(g, doc, annotation, software);
    }

    // Texels and their face selectors.
    for (std::size_t i = 0; i < seg.texels.size(); ++i) {
        const Texel& texel = seg.texels[i];
        const std::string iri = texel_iri(B, i), selector = selector_iri(B, i);
        const std::string what = "texel " + std::to_string(i);
        const long long num_faces = static_cast<long long>(texel.faces.size());
        g.type(iri, gtx("Texel"));
        g.type(iri, oa("SpecificResource"));
        g.type(iri, crmdig("D35_Area"));
        g.iri(iri, oa("hasSource"), mesh);
        g.iri(iri, oa("hasSelector"), selector);
        g.iri(iri, gtx("inTexture"),
              texture_iri(B, static_cast<std::size_t>(seg.texel_texture[i])));
        g.iri(iri, gtx("orientation"), orientation_iri(texel.orientation));
        g.integer(iri, gtx("faceCount"), num_faces);
        g.typed(iri, gtx("centroid"),
                centroid_lexical(d.mesh, texel.faces, doc.unit_scale, what + " centroid"),
                gtx("point3"));
        g.iri(iri, prov("wasGeneratedBy"), run);
        for (int j = 0; j < kNumFeatures; ++j)
            g.dbl(iri, shortcut_iri(j), seg.features.values(static_cast<Eigen::Index>(i), j),
                  what + " " + kFeatureIds[static_cast<std::size_t>(j)]);
        for (int j = 0; j < kNumFeatures; ++j)
            emit_quantity(g, d, iri, gtx("quantity"),
                          iri + "/" + iri_segment(kFeatureIds[static_cast<std::size_t>(j)]), j,
                          seg.features.values(static_cast<Eigen::Index>(i), j),
                          what + " " + kFeatureIds[static_cast<std::size_t>(j)]);

        g.type(selector, gtx("FaceSetSelector"));
        const std::string ranges = face_ranges(texel.faces);
        if (num_faces <= doc.max_literal_faces)
            g.typed(selector, rdf("value"), ranges, gtx("faceRanges"));
        else
            g.text(selector, gtx("facesSha256"), sha256_hex(ranges), "face digest");
        g.integer(selector, gtx("faceCount"), num_faces);
        g.text(selector, gtx("boundToMesh"), doc.mesh_sha256, "the mesh digest");
        g.iri(selector, dcterms("conformsTo"), gtx("FaceSetSelectorSpec"));

        // What is true of this texel itself, not of its texture's mean.
        const std::vector<const DictionaryConcept*> bodies =
            texel_concepts(doc, seg, descriptions, i);
        if (!bodies.empty()) {
            const std::string a = texel_annotation_iri(B, i);
            g.type(a, oa("Annotation"));
            g.type(a, gtx("TexelAnnotation"));
            g.iri(a, oa("motivatedBy"), oa("classifying"));
            for (const DictionaryConcept* c : bodies)
                g.iri(a, oa("hasBody"), concept_iri(d.dictionary_ns, *c));
            g.iri(a, oa("hasTarget"), iri);
            g.iri(a, prov("wasGeneratedBy"), run);
            emit_authorship(g, doc, a, software);
        }
    }
}

/// The base of the nodes of level `k`: the run's own for the main level, `B level/K/` else.
std::string level_base(const Document& d, std::size_t k) {
    return (*d.doc.levels)[k].main ? d.names.base
                                   : d.names.base + "level/" + std::to_string(k) + "/";
}

/// --levels (docs/scales.md): one gtx:DetailLevel per level, the textures and texels of the
/// levels but the main one (emitted by emit_annotation), and for every texel its level and
/// the texel of the next coarser level it lies on.
void emit_levels(Graph& g, const Document& d, const std::string& run, const std::string& software) {
    const std::vector<DetailLevel>& levels = *d.doc.levels;
    const std::string& B = d.names.base;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const DetailLevel& level = levels[k];
        const Segmentation& seg = level_segmentation(levels, k, d.seg);
        const std::string node = B + "level/" + std::to_string(k);
        const std::string base = level_base(d, k);
        g.type(node, gtx("DetailLevel"));
        g.type(node, prov("Entity"));
        g.integer(node, gtx("levelIndex"), static_cast<long long>(k));
        g.dbl(node, gtx("levelScale"), level.radius_rel, "level scale");
        g.dbl(node, gtx("levelRadius"), seg.radius, "level radius");
        g.boolean(node, gtx("mainLevel"), level.main);
        g.integer(node, gtx("levelTexelCount"), static_cast<long long>(seg.texels.size()));
        g.iri(node, gtx("levelCandidate"),
              scale_candidate_iri(B + "run/parameters", static_cast<std::size_t>(level.step)));
        g.iri(node, oa("hasSource"), d.names.mesh);
        g.iri(node, prov("wasGeneratedBy"), run);
        if (!level.main) emit_level(g, d, seg, (*d.doc.level_descriptions)[k], base, run, software);
        // The coarsest level lies on nothing: its part_of is all -1.
        const std::string coarser_base = k + 1 < levels.size() ? level_base(d, k + 1) : "";
        for (std::size_t i = 0; i < seg.texels.size(); ++i) {
            const std::string texel = texel_iri(base, i);
            g.iri(texel, gtx("atLevel"), node);
            const int coarse = level.part_of[i];
            if (coarse >= 0)
                g.iri(texel, gtx("partOf"),
                      texel_iri(coarser_base, static_cast<std::size_t>(coarse)));
        }
    }
}

}  // namespace

std::vector<const DictionaryConcept*> rdf_detail::texel_concepts(const AnnotationDocument& doc,
                                                                 std::size_t texel) {
    return texel_concepts(doc, *doc.segmentation, *doc.descriptions, texel);
}

std::vector<const DictionaryConcept*> rdf_detail::texel_concepts(
    const AnnotationDocument& doc, const Segmentation& seg,
    const std::vector<TextureDescription>& descriptions, std::size_t texel) {
    const TextureDescription& t = descriptions[static_cast<std::size_t>(seg.texel_texture[texel])];
    const DetailOrientation orientation = seg.texels[texel].orientation;
    std::vector<const DictionaryConcept*> out;
    for (int i : t.chosen) {
        const int feature = t.features[static_cast<std::size_t>(i)].feature;
        const double value = seg.features.values(static_cast<Eigen::Index>(texel), feature);
        // A scan rather than Dictionary::find, which needs the concepts sorted: a document
        // built by hand may not be, and the intervals of one feature are disjoint anyway.
        for (const DictionaryConcept& c : doc.dictionary->concepts)
            if (c.feature == feature && c.lower <= value && value < c.upper) {
                if (relief_allows(c.relief, orientation)) out.push_back(&c);
                break;
            }
    }
    return out;
}

namespace {

/// The checks, then a dry run: nothing is written, so that every InvalidInput is raised
/// before the first byte goes out.
Document checked_and_dry_run(const AnnotationDocument& doc, const std::string& stage) {
    Document d = checked_document(doc, stage);
    DryRunSink dry_run;
    Graph g(dry_run);
    emit_annotation(g, d);
    if (doc.include_dictionary) emit_dictionary(g, *doc.dictionary);
    return d;
}

}  // namespace

rdf_detail::CheckedAnnotation rdf_detail::check_annotation_document(const AnnotationDocument& doc,
                                                                    const std::string& stage) {
    const Document d = checked_and_dry_run(doc, stage);
    return {d.names, d.dictionary_ns};
}

// Determinism: triples are emitted in a fixed order (mesh, software, run, parameters, each
// texture with its measurements in feature column order and its annotation, then each texel
// and its selector) and every lexical form is computed from the data alone. N-Triples and
// RDF/XML keep that order; Raptor's Turtle writer sorts subjects, then predicates, then
// objects by their text, which depends on nothing else. Two passes: the first only checks,
// so that an InvalidInput leaves the stream untouched.
void write_annotation_rdf(std::ostream& out, const AnnotationDocument& doc, RdfFormat format) {
    const Document d = checked_and_dry_run(doc, "write_annotation_rdf");
    auto emit = [&](Graph& g) {
        emit_annotation(g, d);
        if (doc.include_dictionary) emit_dictionary(g, *doc.dictionary);
    };
    std::vector<Prefix> prefixes = annotation_prefixes();
    if (doc.include_dictionary)
        for (const Prefix& p : dictionary_prefixes()) {
            bool known = false;
            for (const Prefix& q : prefixes) known = known || std::string(q.prefix) == p.prefix;
            if (!known) prefixes.push_back(p);
        }
    RaptorSink sink(out, format, prefixes);
    Graph g(sink);
    emit(g);
    sink.finish();
}

}  // namespace geotex
