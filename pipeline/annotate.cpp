#include "pipeline/annotate.hpp"

#include <algorithm>
#include <chrono>
#include <ostream>
#include <streambuf>
#include <string_view>
#include <utility>

#include "annotation/digest.hpp"
#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "pipeline/file_digest.hpp"

namespace geotex {

namespace {

bool is_sha256(const std::string& hex) {
    if (hex.size() != 64) return false;
    for (char c : hex)
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
    return true;
}

/// What the RDF writer would refuse at the end, checked before the work.
void check_inputs(const MeshIdentity& identity, const AnnotateOptions& o) {
    const std::string stage = "annotate";
    if (identity.file_name.empty()) throw InvalidInput(stage + ": the mesh's file name is empty");
    if (identity.format.empty()) throw InvalidInput(stage + ": the mesh's format is empty");
    if (!is_sha256(identity.sha256))
        throw InvalidInput(stage + ": the mesh digest is not 64 lower-case hexadecimal digits");
    if (!o.base_iri.empty()) validate_base_iri(o.base_iri);
    if (!o.object_iri.empty()) validate_iri(o.object_iri, "object IRI");
    if (!o.creator_iri.empty()) validate_iri(o.creator_iri, "creator IRI");
    if (!detail::is_language_tag(o.label_language))
        throw InvalidInput(stage + ": label_language '" + o.label_language +
                           "' is not a language tag (e.g. en, fr, pt-BR)");
    if (!o.timestamp.empty() && !detail::is_date_time(o.timestamp))
        throw InvalidInput(stage + ": timestamp '" + o.timestamp.substr(0, 60) +
                           "' is not an xsd:dateTime (e.g. 2026-11-25T18:00:00Z)");
}

/// An output stream buffer that hashes what is written through it: array_identity digests
/// the canonical PLY without holding its bytes (a copy the size of the mesh file).
class HashingBuffer : public std::streambuf {
  public:
    HashingBuffer() { setp(buffer_, buffer_ + sizeof buffer_); }
    std::string hex() {
        sync();
        return hash_.hex();
    }

  protected:
    int_type overflow(int_type c) override {
        sync();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    int sync() override {
        hash_.update(std::string_view(pbase(), static_cast<std::size_t>(pptr() - pbase())));
        setp(buffer_, buffer_ + sizeof buffer_);
        return 0;
    }

  private:
    char buffer_[1 << 16];
    Sha256 hash_;
};

}  // namespace

const char* version() { return GEOTEX_VERSION; }

MeshIdentity file_identity(const std::string& path, const std::string& format) {
    const auto slash = path.find_last_of('/');
    return {slash == std::string::npos ? path : path.substr(slash + 1), format, file_sha256(path)};
}

MeshIdentity array_identity(const Mesh& mesh, const std::string& file_name) {
    HashingBuffer hashing;
    std::ostream bytes(&hashing);
    write_ply(bytes, mesh, {});
    return {file_name, "ply-binary-le", hashing.hex()};
}

AnnotationDocument Annotation::document(const Mesh& m) const {
    if (m.num_vertices() != num_vertices || m.num_faces() != num_faces)
        throw InvalidInput("Annotation::document: the mesh has " +
                           std::to_string(m.num_vertices()) + " vertices and " +
                           std::to_string(m.num_faces()) + " faces, the annotated one " +
                           std::to_string(num_vertices) + " and " + std::to_string(num_faces) +
                           ": pass the mesh given to annotate()");
    AnnotationDocument doc;
    doc.base_iri = options.base_iri;
    doc.object_iri = options.object_iri;
    doc.creator_iri = options.creator_iri;
    doc.mesh_unit = options.mesh_unit;
    doc.mesh = &m;
    doc.mesh_file = mesh.file_name;
    doc.mesh_format = mesh.format;
    doc.mesh_sha256 = mesh.sha256;
    doc.unit_scale = 1.0 / segmentation.metrics.largest_side;
    doc.params = options.segmentation;
    doc.description = options.description;
    doc.software_version = version();
    doc.timestamp = options.timestamp;
    doc.label_language = options.label_language;
    doc.segmentation = &segmentation;
    doc.descriptions = &descriptions;
    doc.dictionary = dictionary.get();
    doc.include_dictionary = options.include_dictionary;
    doc.scale_choice = options.scale_choice ? &*options.scale_choice : nullptr;
    if (!levels.empty()) {
        doc.levels = &levels;
        doc.level_descriptions = &level_descriptions;
    }
    return doc;
}

Annotation annotate_segmentation(Segmentation segmentation, const Mesh& mesh,
                                 const MeshIdentity& identity, const Dictionary& dictionary,
                                 const AnnotateOptions& options) {
    check_inputs(identity, options);
    if (segmentation.face_texel.size() != mesh.faces.size() ||
        segmentation.face_texture.size() != mesh.faces.size())
        throw InvalidInput("annotate: the segmentation has " +
                           std::to_string(segmentation.face_texel.size()) + " faces, the mesh " +
                           std::to_string(mesh.num_faces()) + ": it was made for another mesh");
    Annotation a;
    a.mesh = identity;
    a.options = options;
    a.num_vertices = mesh.num_vertices();
    a.num_faces = mesh.num_faces();
    a.segmentation = std::move(segmentation);
    // On the heap and shared, so that the descriptions' concept pointers survive every move.
    a.dictionary = std::make_shared<const Dictionary>(dictionary);
    const auto& languages = dictionary.languages;
    if (!languages.empty() &&
        std::find(languages.begin(), languages.end(), options.label_language) == languages.end())
        a.diagnostics.push_back(
            {"annotation", "the dictionary '" + dictionary.id + "' has no labels in language '" +
                               options.label_language + "': the texture labels are in '" +
                               languages.front() + "', its first language"});
    const Segmentation& seg = a.segmentation;
    a.descriptions = describe_textures(seg.features.values, seg.texel_texture, seg.num_textures,
                                       seg.texture_orientation, *a.dictionary, options.description);
    return a;
}

Annotation annotate(const Mesh& mesh, const MeshIdentity& identity, const Dictionary& dictionary,
                    const AnnotateOptions& options, const StageObserver& observer) {
    check_inputs(identity, options);
    Segmentation seg = run_segmentation(mesh, options.segmentation, observer);
    if (observer) observer({"annotation", -1});
    const auto start = std::chrono::steady_clock::now();
    Annotation a = annotate_segmentation(std::move(seg), mesh, identity, dictionary, options);
    if (observer)
        observer({"annotation",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    return a;
}

void annotate_levels(Annotation& a, std::vector<DetailLevel> levels) {
    int mains = 0;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        mains += levels[k].main;
        if (levels[k].part_of.size() != level_segmentation(levels, k, a.segmentation).texels.size())
            throw InvalidInput("annotate_levels: level " + std::to_string(k) +
                               " has not one part_of entry per texel");
    }
    if (mains != 1) throw InvalidInput("annotate_levels: the levels must hold one main level");
    a.level_descriptions.assign(levels.size(), {});
    for (std::size_t k = 0; k < levels.size(); ++k) {
        if (levels[k].main) continue;
        const Segmentation& seg = levels[k].segmentation;
        a.level_descriptions[k] =
            describe_textures(seg.features.values, seg.texel_texture, seg.num_textures,
                              seg.texture_orientation, *a.dictionary, a.options.description);
    }
    a.levels = std::move(levels);
}

}  // namespace geotex
