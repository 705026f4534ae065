// geotex.annotate and geotex.annotate_file: the words of every texture from an interval
// dictionary (paper §4.3), over the library's annotate_segmentation, and the RDF and
// JSON-LD of `geotex annotate` as strings.

#include "pipeline/annotate.hpp"

#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "annotation/texture_label.hpp"
#include "arrays.hpp"
#include "bindings.hpp"
#include "common/detail/text.hpp"
#include "default_dictionary.hpp"
#include "errors.hpp"
#include "geometry/feature_table.hpp"
#include "ontology/jsonld_writer.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/read_text_file.hpp"
#include "segment.hpp"

namespace py = pybind11;

namespace geotex::python {

namespace {

/// What geotex.annotate returns (Python class geotex.Annotation): the segmentation it
/// annotated, which owns the mesh, and the library's Annotation, which points into it.
struct AnnotationResult {
    py::object segmentation;  ///< a geotex.Segmentation
    Annotation annotation;
    ReportInput input;  ///< the "input" of the JSON report

    const Mesh& mesh() const { return segmentation.cast<const SegmentationResult&>().input.mesh; }
};

/// The keywords of the words and of the run's names, as the command's options.
struct AnnotateKeywords {
    std::optional<std::string> dictionary;
    std::string label_language = "en";
    std::optional<std::string> base, object, creator, mesh_unit, timestamp, name;
    int concepts = 0;
    double max_significance = 0, min_agreement = 0, min_stability = 0;
    int resamples = 0;
};

/// The dictionary: the built-in one (None), a YAML text (a string holding a line break) or
/// a file, parsed as the command parses --dictionary; its warnings become Python warnings.
Dictionary load_dictionary(const std::optional<std::string>& given) {
    std::string name = cli::kDefaultDictionaryName, text = cli::kDefaultDictionaryText;
    if (given && given->find('\n') != std::string::npos) {
        name = "<dictionary text>";
        text = *given;
    } else if (given) {
        name = *given;
        text = in_phase(Phase::Input, name, [&] { return read_text_file(name); });
    }
    Dictionary d = in_phase(Phase::Input, name, [&] { return parse_dictionary(text, name); });
    for (const auto& w : d.warnings) {
        const std::string message =
            name + ":" + std::to_string(w.line) + ":" + std::to_string(w.column) + ": " + w.message;
        if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();
    }
    return d;
}

AnnotateOptions checked_options(const AnnotateKeywords& k, const SegmentationParams& params) {
    AnnotateOptions o;
    o.segmentation = params;
    o.label_language = k.label_language;
    if (!detail::is_language_tag(o.label_language))
        raise_error(Phase::Usage, "label_language: '" + o.label_language +
                                      "' is not a language tag (e.g. en, fr, pt-BR)");
    if (k.base) o.base_iri = in_phase(Phase::Usage, {}, [&] { return validate_base_iri(*k.base); });
    if (k.object) {
        in_phase(Phase::Usage, {}, [&] { return validate_iri(*k.object, "object IRI"); });
        o.object_iri = *k.object;
    }
    if (k.creator) {
        in_phase(Phase::Usage, {}, [&] { return validate_iri(*k.creator, "creator IRI"); });
        o.creator_iri = *k.creator;
    }
    if (k.mesh_unit) {
        const auto unit = parse_mesh_unit(*k.mesh_unit);
        if (!unit)
            raise_error(Phase::Usage,
                        "mesh_unit: '" + *k.mesh_unit + "' is not a unit: mm, cm, m or in");
        o.mesh_unit = *unit;
    }
    if (k.timestamp) {
        if (!detail::is_date_time(*k.timestamp))
            raise_error(Phase::Usage,
                        "timestamp: not an xsd:dateTime (YYYY-MM-DDThh:mm:ss, "
                        "optionally Z or +hh:mm): " +
                            *k.timestamp);
        o.timestamp = *k.timestamp;
    }
    // The ranges of the command's options (cli/description_options.cpp).
    auto range = [](const char* keyword, double v, double lo, bool lo_open, double hi) {
        if (!((lo_open ? v > lo : v >= lo) && v <= hi))
            raise_error(Phase::Usage, std::string(keyword) + " must be in " +
                                          (lo_open ? "(" : "[") +
                                          py::repr(py::float_(lo)).cast<std::string>() + ", " +
                                          py::repr(py::float_(hi)).cast<std::string>() + "] (got " +
                                          py::repr(py::float_(v)).cast<std::string>() + ")");
    };
    range("concepts", k.concepts, 0, false, 20);
    range("max_significance", k.max_significance, 0, false, 1e9);
    range("min_agreement", k.min_agreement, 0, true, 1);
    range("min_stability", k.min_stability, 0, false, 1);
    range("resamples", k.resamples, 0, false, 100000);
    o.description.max_concepts = k.concepts;
    o.description.max_significance = k.max_significance;
    o.description.min_agreement = k.min_agreement;
    o.description.min_stability = k.min_stability;
    o.description.num_resamples = k.resamples;
    return o;
}

/// Annotates the geotex.Segmentation `segmentation` (no new segmentation), its mesh named by
/// `identity`.
py::object annotate_segmented(py::object segmentation, const MeshIdentity& identity,
                              const AnnotateKeywords& k) {
    const auto& s = segmentation.cast<const SegmentationResult&>();
    AnnotateOptions options = checked_options(k, s.params);
    options.scale_choice = s.scale_choice;  // scale="auto": recorded in the RDF and the report
    const Dictionary dictionary = load_dictionary(k.dictionary);
    auto result = std::make_unique<AnnotationResult>();
    result->annotation = in_phase(Phase::Processing, {}, [&] {
        py::gil_scoped_release release;
        // The copy of the segmentation keeps geotex.Segmentation's arrays unchanged.
        Annotation a = annotate_segmentation(s.seg, s.input.mesh, identity, dictionary, options);
        if (!s.levels.empty()) annotate_levels(a, s.levels);  // levels=True: their words too
        return a;
    });
    result->input = s.report_input(identity.file_name);
    result->segmentation = std::move(segmentation);
    for (const Diagnostic& d : result->annotation.diagnostics)
        if (PyErr_WarnEx(PyExc_UserWarning, d.message.c_str(), 1) != 0)
            throw py::error_already_set();
    return py::cast(result.release(), py::return_value_policy::take_ownership);
}

/// geotex.annotate: arrays (segmented here with the keywords of geotex.segment) or a
/// geotex.Segmentation (annotated as it is). The mesh's identity is that of the repaired
/// mesh as binary PLY (array_identity).
py::object annotate(py::module_ m, py::object mesh, py::object F, const AnnotateKeywords& k,
                    const py::kwargs& segment_keywords) {
    py::object segmentation;
    if (py::isinstance<SegmentationResult>(mesh)) {
        if (!F.is_none() || py::len(segment_keywords) > 0)
            raise_error(Phase::Usage,
                        "annotate(segmentation, ...) takes no F and no keyword of geotex.segment: "
                        "the segmentation is annotated as it is");
        segmentation = std::move(mesh);
    } else {
        if (F.is_none())
            raise_error(Phase::Usage,
                        "annotate needs V and F, or a geotex.Segmentation (for a file: "
                        "geotex.annotate_file)");
        segmentation = m.attr("segment")(mesh, F, **segment_keywords);
    }
    const auto& s = segmentation.cast<const SegmentationResult&>();
    const MeshIdentity identity = in_phase(Phase::Input, {}, [&] {
        return array_identity(s.input.mesh, k.name.value_or("mesh.ply"));
    });
    return annotate_segmented(std::move(segmentation), identity, k);
}

/// geotex.annotate_file: as `geotex annotate FILE`: the file read once and repaired as the
/// command does, named by its digest, so that to_turtle() and to_json() give the command's
/// bytes.
py::object annotate_file(py::module_ m, const std::string& path, const AnnotateKeywords& k,
                         const py::kwargs& segment_keywords) {
    py::object segmentation = m.attr("_segment_file")(path, **segment_keywords);
    const auto& s = segmentation.cast<const SegmentationResult&>();
    const MeshIdentity identity =
        in_phase(Phase::Input, path, [&] { return file_identity(path, s.format); });
    return annotate_segmented(std::move(segmentation), identity, k);
}

std::string rdf_text(const AnnotationResult& r, RdfFormat format) {
    std::ostringstream out;
    in_phase(Phase::Processing, {},
             [&] { write_annotation_rdf(out, r.annotation.document(r.mesh()), format); });
    return out.str();
}

/// One texture's words as a dict (the JSON report's "annotation" of a texture).
py::dict texture_dict(const TextureDescription& d, const Dictionary& dictionary,
                      const std::string& language) {
    auto concept_ids = [&](const std::vector<int>& indices) {
        std::vector<std::string> ids;
        for (int i : indices)
            ids.push_back(d.features[static_cast<std::size_t>(i)].concept_ptr->id);
        return ids;
    };
    const Label label = texture_label(d, d.chosen, dictionary, language);
    py::dict out;
    out["texture"] = d.texture;
    out["num_texels"] = d.num_texels;
    out["orientation"] = name_of(d.orientation);
    out["concepts"] = concept_ids(d.chosen);
    out["label"] = label.text;
    out["label_language"] = label.language;
    out["withheld"] = concept_ids(d.withheld);
    out["note"] = d.note;
    py::dict features;
    for (const FeatureScore& f : d.features) {
        py::dict one;
        one["value"] = f.value;
        one["significance"] = f.significance;
        one["rank"] = f.rank;
        one["concept"] = f.concept_ptr ? py::object(py::str(f.concept_ptr->id)) : py::none();
        one["agreement"] = f.agreement;
        one["stability"] = f.stability;
        features[py::str(kFeatureIds[static_cast<std::size_t>(f.feature)])] = one;
    }
    out["features"] = features;
    return out;
}

void bind_annotation_result(py::module_& m) {
    using R = AnnotationResult;
    py::class_<R>(m, "Annotation",
                  "The result of geotex.annotate: the segmentation annotated and the words of "
                  "every texture; to_turtle() and the other writers give the command's bytes.")
        .def_property_readonly(
            "segmentation", [](const R& r) { return r.segmentation; },
            "the geotex.Segmentation annotated (its arrays, its repaired mesh V and F)")
        .def_property_readonly(
            "textures",
            [](const R& r) {
                py::list out;
                for (const TextureDescription& d : r.annotation.descriptions)
                    out.append(texture_dict(d, *r.annotation.dictionary,
                                            r.annotation.options.label_language));
                return out;
            },
            "[dict] per texture: texture, num_texels, orientation, concepts (concept ids "
            "asserted, most significant first), label and label_language (their labels, the "
            "rule of the RDF's rdfs:label), withheld (unstable concept ids), note, features "
            "({feature id: value, significance, rank, concept, agreement, stability})")
        .def_property_readonly(
            "mesh_sha256", [](const R& r) { return r.annotation.mesh.sha256; },
            "SHA-256 naming the mesh (of the file, or of the repaired mesh as binary PLY)")
        .def(
            "to_turtle", [](const R& r) { return rdf_text(r, RdfFormat::Turtle); },
            "The RDF as Turtle: the bytes of `geotex annotate` for the same mesh and options")
        .def("to_ntriples", [](const R& r) { return rdf_text(r, RdfFormat::NTriples); })
        .def("to_rdfxml", [](const R& r) { return rdf_text(r, RdfFormat::RdfXml); })
        .def(
            "to_jsonld",
            [](const R& r) {
                std::ostringstream out;
                in_phase(Phase::Processing, {},
                         [&] { write_annotation_jsonld(out, r.annotation.document(r.mesh())); });
                return out.str();
            },
            "The annotations as JSON-LD (a W3C Web Annotation page): the bytes of `geotex "
            "annotate --jsonld`")
        .def(
            "to_json",
            [](const R& r) {
                return in_phase(Phase::Processing, {}, [&] {
                    return report_text(annotation_report(r.annotation, r.input));
                });
            },
            "The JSON report as text: for annotate_file(path), the bytes of `geotex annotate path "
            "--json` with the same options. For arrays its \"input\" names the file `name` "
            "(default \"mesh.ply\") in format \"ply-binary-le\", with the counts of the arrays "
            "and of their repair")
        .def("__repr__", [](const R& r) {
            return "<geotex.Annotation: " + std::to_string(r.annotation.descriptions.size()) +
                   " textures, dictionary " + r.annotation.dictionary->id + " " +
                   r.annotation.dictionary->version + ">";
        });
}

}  // namespace

void bind_annotate(py::module_& m) {
    bind_annotation_result(m);
    const DescriptionParams d;  // the command's defaults are the library's
    m.def(
        "annotate",
        [m](py::object mesh, py::object F, std::optional<std::string> dictionary,
            std::string label_language, std::optional<std::string> base,
            std::optional<std::string> object, std::optional<std::string> creator,
            std::optional<std::string> mesh_unit, std::optional<std::string> timestamp,
            int concepts, double max_significance, double min_agreement, double min_stability,
            int resamples, std::optional<std::string> name, const py::kwargs& segment_keywords) {
            return annotate(m, std::move(mesh), std::move(F),
                            {std::move(dictionary), std::move(label_language), std::move(base),
                             std::move(object), std::move(creator), std::move(mesh_unit),
                             std::move(timestamp), std::move(name), concepts, max_significance,
                             min_agreement, min_stability, resamples},
                            segment_keywords);
        },
        py::arg("mesh"), py::arg("F") = py::none(), py::kw_only(),
        py::arg("dictionary") = py::none(), py::arg("label_language") = "en",
        py::arg("base") = py::none(), py::arg("object") = py::none(),
        py::arg("creator") = py::none(), py::arg("mesh_unit") = py::none(),
        py::arg("timestamp") = py::none(), py::arg("concepts") = d.max_concepts,
        py::arg("max_significance") = d.max_significance,
        py::arg("min_agreement") = d.min_agreement, py::arg("min_stability") = d.min_stability,
        py::arg("resamples") = d.num_resamples, py::arg("name") = py::none(),
        R"(Names every texture with concepts of an interval dictionary, as `geotex annotate`
does (paper §4.3, docs/words.md).

annotate(V, F, scale=0.04, ...): segments the arrays first, with the keywords of
geotex.segment; annotate(segmentation, ...): annotates a geotex.Segmentation as it is. For a
file, geotex.annotate_file gives the command's bytes exactly.

dictionary: None (the built-in dictionaries/default.yaml), a path, or the YAML text itself
(a string holding a line break). label_language, base, object, creator, mesh_unit,
timestamp, concepts, max_significance, min_agreement, min_stability, resamples: the
command's options of the same names (--lang for label_language). name: the file name
recorded for arrays (default "mesh.ply"); their mesh is named by the SHA-256 of the repaired
mesh written as binary PLY, so the same arrays give the same IRIs.

Returns a geotex.Annotation: .textures (the words), .segmentation, and to_turtle(),
to_ntriples(), to_rdfxml(), to_jsonld(), to_json() (the JSON report). Raises geotex.UsageError, geotex.InputError (a bad
dictionary, with its line) or geotex.ProcessingError.)");
    m.def(
        "annotate_file",
        [m](const std::string& path, std::optional<std::string> dictionary,
            std::string label_language, std::optional<std::string> base,
            std::optional<std::string> object, std::optional<std::string> creator,
            std::optional<std::string> mesh_unit, std::optional<std::string> timestamp,
            int concepts, double max_significance, double min_agreement, double min_stability,
            int resamples, const py::kwargs& segment_keywords) {
            return annotate_file(
                m, path,
                {std::move(dictionary), std::move(label_language), std::move(base),
                 std::move(object), std::move(creator), std::move(mesh_unit), std::move(timestamp),
                 std::nullopt, concepts, max_significance, min_agreement, min_stability, resamples},
                segment_keywords);
        },
        py::arg("path"), py::kw_only(), py::arg("dictionary") = py::none(),
        py::arg("label_language") = "en", py::arg("base") = py::none(),
        py::arg("object") = py::none(), py::arg("creator") = py::none(),
        py::arg("mesh_unit") = py::none(), py::arg("timestamp") = py::none(),
        py::arg("concepts") = d.max_concepts, py::arg("max_significance") = d.max_significance,
        py::arg("min_agreement") = d.min_agreement, py::arg("min_stability") = d.min_stability,
        py::arg("resamples") = d.num_resamples,
        R"(geotex.annotate of a mesh file, named as `geotex annotate PATH` names it (its file
name and the SHA-256 of its bytes), the file read once as the command reads it: to_turtle(),
to_jsonld() and to_json() give the command's bytes (-o, --jsonld, --json) for the same path and
options. The keywords are geotex.annotate's and geotex.segment's.)");
}

}  // namespace geotex::python
