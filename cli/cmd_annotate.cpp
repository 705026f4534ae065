// geotex annotate: the whole pipeline, from a mesh to RDF (paper §3 and §4.3).

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "annotation/digest.hpp"
#include "annotation/significance.hpp"
#include "annotation/texture_label.hpp"
#include "cli/commands.hpp"
#include "cli/description_options.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/segment_run.hpp"
#include "geometry/detail/text.hpp"
#include "ontology/jsonld_writer.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/geometry_cache.hpp"
#include "pipeline/report_json.hpp"

namespace geotex::cli {

namespace {

struct AnnotateArgs {
    CommonOptions common;
    SegmentRunOptions run;
    std::string output;
    std::string format = "turtle";
    std::string dictionary;
    std::string base;
    std::string object;
    std::string creator;
    std::string mesh_unit;
    std::string lang = "en";
    std::string json;
    std::string jsonld;
    std::string segmentation;
    std::string geometry_cache;
    DescriptionParams description;
    std::string timestamp;
};

const std::map<std::string, RdfFormat> kFormats = {
    {"turtle", RdfFormat::Turtle}, {"ntriples", RdfFormat::NTriples}, {"rdfxml", RdfFormat::RdfXml}};

int run_annotate(AnnotateArgs& o) {
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    // Options that need no mesh are checked first, so a typo costs nothing.
    std::string base;
    if (!o.base.empty()) base = in_phase(kExitUsage, "--base", [&] { return validate_base_iri(o.base); });
    if (!o.object.empty()) in_phase(kExitUsage, "--object", [&] { return validate_iri(o.object, "object IRI"); });
    if (!o.creator.empty()) in_phase(kExitUsage, "--creator", [&] { return validate_iri(o.creator, "creator IRI"); });
    const MeshUnit mesh_unit = checked_mesh_unit(o.mesh_unit);
    if (!detail::is_language_tag(o.lang))
        throw CliError(kExitUsage,
                       "--lang: '" + o.lang + "' is not a language tag (e.g. en, fr, pt-BR)");
    check_segmentation_options(o.run);
    check_output_paths({{"--output", o.output, true},
                        {"--json", o.json},
                        {"--jsonld", o.jsonld},
                        {"--segmentation", o.segmentation},
                        {"--geometry-cache", o.geometry_cache}},
                       // The geometry cache is read and rewritten: an input of the others only.
                       {{"MESH", o.run.mesh}, {"--dictionary", o.dictionary}});
    const Dictionary dictionary = load_dictionary(o.dictionary);
    bool has_lang = false;
    for (const auto& l : dictionary.languages) has_lang = has_lang || l == o.lang;
    if (!has_lang)
        warn(dictionary.source_name + ": no labels in language '" + o.lang +
             "'; texture labels fall back to the first language of the dictionary");

    SegmentRun run{load_mesh(o.run.mesh, progress), {}};
    const std::string mesh_digest = sha256_of_file(o.run.mesh);
    // A valid geometry cache replaces the geometric stages; any other is rewritten.
    const std::string cache_key =
        o.geometry_cache.empty() ? std::string() : geometry_cache_key(mesh_digest, o.run.params);
    bool from_cache = false;
    if (!o.geometry_cache.empty()) {
        GeometryCacheRead cached =
            read_geometry_cache(o.geometry_cache, cache_key, run.input.repaired.mesh);
        if (cached.segmentation) {
            run.seg = std::move(*cached.segmentation);
            from_cache = true;
            progress.note(o.run.mesh + ": geometry read from " + o.geometry_cache);
            report_segmentation(o.run, run.seg, progress);
        } else if (!cached.refusal.empty()) {
            progress.note(o.geometry_cache + ": " + cached.refusal + "; recomputing the geometry");
        }
    }
    if (!from_cache) run.seg = segment_mesh(o.run, run.input, progress);

    const Mesh& mesh = run.input.repaired.mesh;
    const auto slash = o.run.mesh.find_last_of('/');
    const MeshIdentity identity{
        slash == std::string::npos ? o.run.mesh : o.run.mesh.substr(slash + 1), run.input.format,
        mesh_digest};
    AnnotateOptions options;
    options.segmentation = o.run.params;
    options.description = o.description;
    options.label_language = o.lang;
    options.base_iri = base;
    options.object_iri = o.object;
    options.creator_iri = o.creator;
    options.mesh_unit = mesh_unit;
    options.timestamp = o.timestamp;
    const Annotation annotation = timed_stage(progress, "annotation", [&] {
        return in_phase(kExitProcessing, o.run.mesh, [&] {
            return annotate_segmentation(std::move(run.seg), mesh, identity, dictionary, options);
        });
    });
    const Segmentation& seg = annotation.segmentation;
    const std::vector<TextureDescription>& descriptions = annotation.descriptions;
    const AnnotationDocument doc = annotation.document(mesh);

    OutputSet outputs;
    timed_stage(progress, "writing", [&] {
        outputs.add(o.output, [&](std::ostream& out) { write_annotation_rdf(out, doc, kFormats.at(o.format)); });
        if (!o.jsonld.empty()) outputs.add(o.jsonld, [&](std::ostream& out) { write_annotation_jsonld(out, doc); });
        if (!o.json.empty()) {
            const ReportInput input{o.run.mesh, run.input.format, run.input.repaired.report};
            outputs.add(o.json, [&](std::ostream& out) {
                out << report_text(annotation_report(annotation, input));
            });
        }
        if (!o.segmentation.empty()) {
            PlyWriteOptions w;
            w.comments = {"geotex segmentation of " + o.run.mesh};
            const auto attributes = segmentation_attributes(seg);
            outputs.add(o.segmentation, [&](std::ostream& out) { write_ply(out, run.input.repaired.mesh, attributes, w); });
        }
        if (!o.geometry_cache.empty() && !from_cache)
            outputs.add(o.geometry_cache, [&](std::ostream& out) { write_geometry_cache(out, cache_key, seg); });
        outputs.commit();
    });

    print_texture_summary(o.run.mesh, seg, o.run.params.orientation);
    for (const auto& d : descriptions) {
        const std::string labels = texture_label(d, d.chosen, *annotation.dictionary, o.lang).text;
        std::string withheld = texture_label(d, d.withheld, *annotation.dictionary, o.lang).text;
        if (!withheld.empty()) withheld = " (withheld, unstable: " + withheld + ")";
        std::printf("  texture %d: %s%s\n", d.texture,
                    labels.empty() ? "(no concept of the dictionary applies)" : labels.c_str(), withheld.c_str());
    }
    std::printf("wrote %s\n", o.output.c_str());
    return 0;
}

}  // namespace

Runner add_annotate(CLI::App& sub) {
    auto o = std::make_shared<AnnotateArgs>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "The whole pipeline: texels and textures of MESH (as 'geotex segment'), then the words of every texture\n"
        "(docs/words.md): per facet of the dictionary (outline, proportions, size, relief, surface shape, ...)\n"
        "at most one concept, from the first feature of the facet that sets the texture apart (paper section\n"
        "4.3: spread within the texture over spread over all texels at most --max-significance), whose\n"
        "concept holds for at least --min-agreement of its texels and comes out of at least --min-stability\n"
        "of --resamples bootstrap resamples of them (else withheld). Written as RDF: the mesh, the run and its\n"
        "parameters (PROV-O), texels with their faces, textures, feature measurements (SOSA), one Web\n"
        "Annotation per texture targeting the texture, and one per texel with the concepts its own values hold.\n"
        "The model is documented in ontology/README.md; ontology/queries/ holds SPARQL queries for it.");
    add_segmentation_options(sub, o->run);
    sub.add_option("-o,--output", o->output, "RDF file to write")->required();
    sub.add_option("--format", o->format, "RDF syntax: turtle, ntriples (streamable, for bulk loaders) or rdfxml")
        ->check(CLI::IsMember({"turtle", "ntriples", "rdfxml"}));
    sub.add_option("--dictionary", o->dictionary, "YAML interval dictionary (default: the built-in dictionaries/default.yaml)");
    sub.add_option("--base", o->base,
                   "Base IRI of the object, ending in / or #: the mesh is BASE mesh and the run's nodes BASE run/<run key>/...\n"
                   "(default: RFC 6920 hash names, ni:///sha-256;<mesh digest> for the mesh and ni:///sha-256;<run key>#... for\n"
                   "the run; the run key hashes the mesh, every option, the dictionary and the geotex version)")
        ->type_name("IRI");
    sub.add_option("--object", o->object,
                   "IRI of the physical object that the mesh is a scan of: written as crm:P138_represents (CIDOC-CRM,\n"
                   "Linked Art), so that the annotation joins the collection's own records")
        ->type_name("IRI");
    sub.add_option("--creator", o->creator, "IRI of the person or organisation responsible for the annotations (dcterms:creator)")
        ->type_name("IRI");
    sub.add_option("--mesh-unit", o->mesh_unit,
                   "Unit of the mesh coordinates (mm, cm, m or in): lengths and areas are then also given in it, with QUDT units")
        ->type_name("UNIT");
    sub.add_option("--lang", o->lang, "Language of the texture labels (a language of the dictionary)");
    add_description_options(sub, o->description);
    sub.add_option("--json", o->json, "Also write the JSON report, with the annotation of every texture");
    sub.add_option("--jsonld", o->jsonld,
                   "Also write the annotations as JSON-LD (a W3C Web Annotation page, with the IRIs of the RDF)");
    sub.add_option("--segmentation", o->segmentation, "Also write the segmentation PLY");
    sub.add_option("--geometry-cache", o->geometry_cache,
                   "Keep the geometric results in FILE and reuse them while the mesh, the geometric options and "
                   "geotex are unchanged: a run that changes only the dictionary or the annotation options then "
                   "skips segmentation")
        ->type_name("FILE");
    sub.add_option("--timestamp", o->timestamp,
                   "xsd:dateTime recorded as the end of the run, e.g. 2026-11-25T18:00:00Z (off by default: same input, "
                   "same bytes)")
        ->check(CLI::Validator(
            [](std::string& v) {
                return detail::is_date_time(v) ? std::string()
                                               : "not an xsd:dateTime (YYYY-MM-DDThh:mm:ss, a date that exists, "
                                                 "optionally Z or +hh:mm up to 14:00): " + v;
            },
            "DATETIME"));
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_annotate(*o); };
}

}  // namespace geotex::cli
