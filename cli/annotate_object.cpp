#include "cli/annotate_object.hpp"

#include <cstdio>
#include <map>
#include <string>

#include "annotation/digest.hpp"
#include "annotation/texture_label.hpp"
#include "cli/description_options.hpp"
#include "cli/dictionary_input.hpp"
#include "common/detail/text.hpp"
#include "ontology/jsonld_writer.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/geometry_cache.hpp"
#include "pipeline/report_json.hpp"

namespace geotex::cli {

namespace {

const std::map<std::string, RdfFormat> kFormats = {{"turtle", RdfFormat::Turtle},
                                                   {"ntriples", RdfFormat::NTriples},
                                                   {"rdfxml", RdfFormat::RdfXml}};

}  // namespace

int annotate_object(AnnotateJob& o) {
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    // Options that need no mesh are checked first, so a typo costs nothing.
    std::string base;
    if (!o.base.empty())
        base = in_phase(kExitUsage, "--base", [&] { return validate_base_iri(o.base); });
    if (!o.object.empty())
        in_phase(kExitUsage, "--object", [&] { return validate_iri(o.object, "object IRI"); });
    if (!o.creator.empty())
        in_phase(kExitUsage, "--creator", [&] { return validate_iri(o.creator, "creator IRI"); });
    const MeshUnit mesh_unit = checked_mesh_unit(o.mesh_unit);
    if (!detail::is_language_tag(o.lang))
        throw CliError(kExitUsage,
                       "--lang: '" + o.lang + "' is not a language tag (e.g. en, fr, pt-BR)");
    check_segmentation_options(o.run);
    const bool refuse = o.refuse_output_links;
    check_output_paths({{"--output", o.output, true, refuse},
                        {"--json", o.json, false, refuse},
                        {"--jsonld", o.jsonld, false, refuse},
                        {"--segmentation", o.segmentation, false, refuse},
                        {"--geometry-cache", o.geometry_cache, false, refuse}},
                       // The geometry cache is read and rewritten: an input of the others only.
                       {{"MESH", o.run.mesh}, {"--dictionary", o.dictionary}});
    const Dictionary read_dictionary =
        o.loaded_dictionary != nullptr ? Dictionary() : load_dictionary(o.dictionary);
    const Dictionary& dictionary =
        o.loaded_dictionary != nullptr ? *o.loaded_dictionary : read_dictionary;
    bool has_lang = false;
    for (const auto& l : dictionary.languages) has_lang = has_lang || l == o.lang;
    if (!has_lang)
        warn(dictionary.source_name + ": no labels in language '" + o.lang +
             "'; texture labels fall back to the first language of the dictionary");

    SegmentRun run{load_mesh(o.run.mesh, progress), {}, {}, {}, {}, {}};
    const std::string mesh_digest = sha256_of_file(o.run.mesh);
    // --scale auto looks at the whole series before anything else: the cache below holds the
    // segmentation at the scale chosen, under that scale's key.
    if (o.run.auto_scale) run.scale_choice = choose_auto_scale(o.run, run.input, progress);
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
    // The other levels are not cached: the cache holds the main segmentation only.
    if (o.run.levels)
        run.levels = segment_other_levels(o.run, run.input, *run.scale_choice, run.seg, progress);

    const Mesh& mesh = run.input.repaired.mesh;
    const auto slash = o.run.mesh.find_last_of('/');
    const MeshIdentity identity{
        slash == std::string::npos ? o.run.mesh : o.run.mesh.substr(slash + 1), run.input.format,
        mesh_digest};
    AnnotateOptions options;
    options.segmentation = o.run.params;
    options.scale_choice = std::move(run.scale_choice);
    options.description = o.description;
    options.label_language = o.lang;
    options.base_iri = base;
    options.object_iri = o.object;
    options.creator_iri = o.creator;
    options.mesh_unit = mesh_unit;
    options.timestamp = o.timestamp;
    const Annotation annotation = timed_stage(progress, "annotation", [&] {
        return in_phase(kExitProcessing, o.run.mesh, [&] {
            Annotation a =
                annotate_segmentation(std::move(run.seg), mesh, identity, dictionary, options);
            if (o.run.levels) annotate_levels(a, std::move(run.levels));
            return a;
        });
    });
    const Segmentation& seg = annotation.segmentation;
    const std::vector<TextureDescription>& descriptions = annotation.descriptions;
    const AnnotationDocument doc = annotation.document(mesh);

    OutputSet outputs(refuse ? OutputLinks::Refuse : OutputLinks::Follow);
    timed_stage(progress, "writing", [&] {
        outputs.add(o.output, [&](std::ostream& out) {
            write_annotation_rdf(out, doc, kFormats.at(o.format));
        });
        if (!o.jsonld.empty())
            outputs.add(o.jsonld, [&](std::ostream& out) { write_annotation_jsonld(out, doc); });
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
            outputs.add(o.segmentation, [&](std::ostream& out) {
                write_ply(out, run.input.repaired.mesh, attributes, w);
            });
        }
        if (!o.geometry_cache.empty() && !from_cache)
            outputs.add(o.geometry_cache,
                        [&](std::ostream& out) { write_geometry_cache(out, cache_key, seg); });
        outputs.commit();
    });

    const auto print_words = [&](const std::vector<TextureDescription>& words) {
        for (const auto& d : words) {
            const std::string labels =
                texture_label(d, d.chosen, *annotation.dictionary, o.lang).text;
            std::string withheld =
                texture_label(d, d.withheld, *annotation.dictionary, o.lang).text;
            if (!withheld.empty()) withheld = " (withheld, unstable: " + withheld + ")";
            std::printf("  texture %d: %s%s\n", d.texture,
                        labels.empty() ? "(no concept of the dictionary applies)" : labels.c_str(),
                        withheld.c_str());
        }
    };
    for (std::size_t k = 0; k < annotation.levels.size(); ++k)
        if (annotation.levels[k].main)
            std::printf("level %zu, scale %s (main):\n", k,
                        scale_percent(annotation.levels[k].radius_rel).c_str());
    print_texture_summary(o.run.mesh, seg, o.run.params.orientation);
    print_words(descriptions);
    // --levels: the other levels after the main one, each as the main one is shown.
    for (std::size_t k = 0; k < annotation.levels.size(); ++k) {
        if (annotation.levels[k].main) continue;
        const Segmentation& level = annotation.levels[k].segmentation;
        std::printf("level %zu, scale %s:\n", k,
                    scale_percent(annotation.levels[k].radius_rel).c_str());
        print_texture_summary(o.run.mesh, level, o.run.params.orientation);
        print_words(annotation.level_descriptions[k]);
    }
    std::printf("wrote %s\n", o.output.c_str());
    return 0;
}

}  // namespace geotex::cli
