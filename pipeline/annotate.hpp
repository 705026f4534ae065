#pragma once
/// annotate(): the whole method in one call, from a triangle mesh and a dictionary to the
/// annotation that the RDF writers take (paper §3 for the texels and textures, §4.3 for the
/// words). `geotex annotate` calls it, as the Python module and the workbench do; the steps
/// it runs (run_segmentation, describe_textures) stay public for a caller that needs only one.
///
///   MeshFile file = read_mesh_file("vase.ply");
///   const Mesh mesh = repair_soup(std::move(file.soup)).mesh;
///   AnnotateOptions options;
///   options.segmentation.radius_rel = 0.04;
///   const Annotation a = annotate(mesh, file_identity("vase.ply", file.format), dictionary,
///   options); write_annotation_rdf(std::cout, a.document(mesh), RdfFormat::Turtle);
///
/// No output and no printing here: the caller writes the document it gets
/// (write_annotation_rdf, write_annotation_jsonld) and reports the diagnostics it finds in
/// `Annotation::segmentation`.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "geometry/mesh.hpp"
#include "geometry/scale_levels.hpp"
#include "geometry/scale_series.hpp"
#include "geometry/segmentation.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex {

/// The version of geotex that these libraries are ("0.1.0"): recorded in the RDF as the
/// software of the run and part of the keys of geometry caches and batch stamps.
const char* version();

/// What names the mesh in the annotation: dcterms:identifier, gtx:fileFormat and gtx:sha256
/// of the mesh node, and, without a base IRI, the mesh's hash name ni:///sha-256;<sha256>.
struct MeshIdentity {
    std::string file_name;  ///< file name without its directories, e.g. "vase.ply"; not empty
    std::string format;     ///< format of the file, as MeshFile::format: "ply-ascii",
                            ///< "ply-binary-le", "ply-binary-be", "off", "obj" or "stl"
    std::string sha256;     ///< SHA-256 of the file's bytes, 64 lower-case hexadecimal digits
};

/// The identity of the mesh file at `path` (what `geotex annotate` records): its name without
/// directories, `format` (MeshFile::format of read_mesh_file) and the SHA-256 of its bytes,
/// read in chunks. Throws IoError naming the file when it cannot be read.
MeshIdentity file_identity(const std::string& path, const std::string& format);

/// The identity of a mesh that comes as arrays, not as a file (numpy's V and F): the SHA-256
/// of its canonical bytes, the binary little-endian PLY that `write_ply(out, mesh, {})`
/// writes, with `file_name` "mesh.ply" unless given and format "ply-binary-le". So the arrays
/// written with write_ply to a file of that name and annotated by `geotex annotate` get the
/// same mesh IRI and digest. Pass the arrays as given, before repair_soup repairs them.
/// Throws InvalidInput as write_ply does (a face index out of range, a coordinate not finite).
MeshIdentity array_identity(const Mesh& mesh, const std::string& file_name = "mesh.ply");

/// The options of annotate(): those of its two steps and the names of the run in the RDF.
struct AnnotateOptions {
    SegmentationParams segmentation;    ///< the geometric stages: scale (radius_rel or radius),
                                        ///< orientation, smoothing, ... (paper §3)
    DescriptionParams description;      ///< the choice of the words of every texture (§4.3)
    std::string label_language = "en";  ///< language tag of the texture labels; a language
                                        ///< the dictionary lacks falls back to its first
    /// Base IRI of the object, ending in '/' or '#': the mesh is `base_iri mesh`, the run's
    /// nodes hang under `base_iri run/<run key>/`. Empty: RFC 6920 hash names
    /// (ontology/README.md, "IRIs").
    std::string base_iri;
    std::string object_iri;                  ///< the physical object the mesh is a scan of
                                             ///< (crm:P138_represents); empty: none said
    std::string creator_iri;                 ///< dcterms:creator of the annotations; empty: none
    MeshUnit mesh_unit = MeshUnit::Unknown;  ///< unit of the coordinates; known, lengths and
                                             ///< areas are also given in it (QUDT)
    std::string timestamp;  ///< xsd:dateTime of the end of the run (prov:endedAtTime);
                            ///< empty (default): none, so the same input gives the same bytes
    bool include_dictionary = true;  ///< the document also carries the dictionary's concept
                                     ///< scheme, so that one file answers queries on labels
    /// How segmentation.radius_rel was chosen, when it was (`--scale auto`): the series and
    /// the choice, recorded in the report and the RDF. Absent: the user gave the scale.
    std::optional<ScaleChoice> scale_choice;
};

/// The result of annotate(): the segmentation, the description of every texture and what
/// they refer to. A value: it owns everything its document points to but the mesh, and can
/// be moved and returned freely (the dictionary it refers to is shared, never moved).
struct Annotation {
    MeshIdentity mesh;          ///< as given
    AnnotateOptions options;    ///< as given
    int num_vertices = 0;       ///< #V of the mesh annotated
    int num_faces = 0;          ///< #F of the mesh annotated
    Segmentation segmentation;  ///< texels and textures (face_texel, face_texture: #F;
                                ///< features: #texels by kNumFeatures) and the diagnostics
    /// One per texture (#textures), in texture order; their concept pointers point into
    /// `*dictionary`.
    std::vector<TextureDescription> descriptions;
    std::shared_ptr<const Dictionary> dictionary;  ///< the dictionary the words come from
    /// With --levels (annotate_levels): every level, fine to coarse, the main one being
    /// `segmentation`; and the words of each level's textures (empty for the main level,
    /// whose words are `descriptions`).
    std::vector<DetailLevel> levels;
    std::vector<std::vector<TextureDescription>> level_descriptions;
    /// What deserves a look beyond the segmentation's own diagnostics: a label language the
    /// dictionary lacks (the labels are then in its first language).
    Diagnostics diagnostics;

    /// The document that write_annotation_rdf and write_annotation_jsonld take, for the mesh
    /// that was annotated. A view: it points into this Annotation and `mesh`, which must
    /// outlive it, unmoved. Throws InvalidInput when `mesh` has not #V vertices and #F faces.
    AnnotationDocument document(const Mesh& mesh) const;
};

/// Annotates a mesh: texels and textures at the chosen scale (run_segmentation), then the
/// words of every texture from `dictionary` (describe_textures).
///   mesh        a clean triangle mesh (repair_soup of what was read), #V vertices, #F faces
///   identity    the mesh's name and digest (file_identity, array_identity)
///   dictionary  an interval dictionary (parse_dictionary); copied into the result
///   options     scale, orientation, word choice, the run's names
///   observer    told when each stage starts and ends, with its wall time: the stages of
///               run_segmentation, then "annotation"
/// Deterministic for any thread count. Throws InvalidInput on a bad option (an IRI, the
/// language tag, the timestamp), a bad identity or an empty mesh, before any work;
/// NumericalError when a stage fails.
Annotation annotate(const Mesh& mesh, const MeshIdentity& identity, const Dictionary& dictionary,
                    const AnnotateOptions& options = {}, const StageObserver& observer = {});

/// The second step of annotate() alone, for a segmentation computed before (a geometry
/// cache, or run_segmentation called apart): the words of its textures. `segmentation` must
/// be run_segmentation(mesh, options.segmentation)'s or read back from a cache made for the
/// same mesh and parameters. Throws as annotate() does, and InvalidInput when the
/// segmentation's sizes do not fit the mesh.
Annotation annotate_segmentation(Segmentation segmentation, const Mesh& mesh,
                                 const MeshIdentity& identity, const Dictionary& dictionary,
                                 const AnnotateOptions& options = {});

/// Adds the levels of detail (segment_levels of the annotation's scale choice, made with
/// `a.segmentation` as the main level) to `a`, and the words of every other level's textures,
/// from the same dictionary and options. Throws InvalidInput when `levels` holds no main
/// level, or one whose part_of does not fit its texels.
void annotate_levels(Annotation& a, std::vector<DetailLevel> levels);

}  // namespace geotex
