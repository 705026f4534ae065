// geotex annotate: the whole pipeline, from a mesh to RDF (paper §3 and §4.3).

#include <CLI/CLI.hpp>
#include <memory>

#include "cli/annotate_object.hpp"
#include "cli/description_options.hpp"
#include "cli/output.hpp"
#include "common/detail/text.hpp"

namespace geotex::cli {

Runner add_annotate(CLI::App& sub) {
    auto o = std::make_shared<AnnotateJob>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "The whole pipeline: texels and textures of MESH (as 'geotex segment'), then the words of "
        "every texture\n"
        "(docs/words.md): per facet of the dictionary (outline, proportions, size, relief, surface "
        "shape, ...)\n"
        "at most one concept, from the first feature of the facet that sets the texture apart "
        "(paper section\n"
        "4.3: spread within the texture over spread over all texels at most --max-significance), "
        "whose\n"
        "concept holds for at least --min-agreement of its texels and comes out of at least "
        "--min-stability\n"
        "of --resamples bootstrap resamples of them (else withheld). Written as RDF: the mesh, the "
        "run and its\n"
        "parameters (PROV-O), texels with their faces, textures, feature measurements (SOSA), one "
        "Web\n"
        "Annotation per texture targeting the texture, and one per texel with the concepts its own "
        "values hold.\n"
        "The model is documented in ontology/README.md; ontology/queries/ holds SPARQL queries for "
        "it.");
    add_segmentation_options(sub, o->run);
    sub.add_option("-o,--output", o->output, "RDF file to write")->required();
    sub.add_option("--format", o->format,
                   "RDF syntax: turtle, ntriples (streamable, for bulk loaders) or rdfxml")
        ->check(CLI::IsMember({"turtle", "ntriples", "rdfxml"}));
    sub.add_option("--dictionary", o->dictionary,
                   "YAML interval dictionary (default: the built-in dictionaries/default.yaml)");
    sub.add_option("--base", o->base,
                   "Base IRI of the object, ending in / or #: the mesh is BASE mesh and the run's "
                   "nodes BASE run/<run key>/...\n"
                   "(default: RFC 6920 hash names, ni:///sha-256;<mesh digest> for the mesh and "
                   "ni:///sha-256;<run key>#... for\n"
                   "the run; the run key hashes the mesh, every option, the dictionary and the "
                   "geotex version)")
        ->type_name("IRI");
    sub.add_option("--object", o->object,
                   "IRI of the physical object that the mesh is a scan of: written as "
                   "crm:P138_represents (CIDOC-CRM,\n"
                   "Linked Art), so that the annotation joins the collection's own records")
        ->type_name("IRI");
    sub.add_option(
           "--creator", o->creator,
           "IRI of the person or organisation responsible for the annotations (dcterms:creator)")
        ->type_name("IRI");
    sub.add_option("--mesh-unit", o->mesh_unit,
                   "Unit of the mesh coordinates (mm, cm, m or in): lengths and areas are then "
                   "also given in it, with QUDT units")
        ->type_name("UNIT");
    sub.add_option("--lang", o->lang,
                   "Language of the texture labels (a language of the dictionary)");
    add_description_options(sub, o->description);
    sub.add_option("--json", o->json,
                   "Also write the JSON report, with the annotation of every texture");
    sub.add_option("--jsonld", o->jsonld,
                   "Also write the annotations as JSON-LD (a W3C Web Annotation page, with the "
                   "IRIs of the RDF)");
    sub.add_option("--segmentation", o->segmentation, "Also write the segmentation PLY");
    sub.add_option("--geometry-cache", o->geometry_cache,
                   "Keep the geometric results in FILE and reuse them while the mesh, the "
                   "geometric options and "
                   "geotex are unchanged: a run that changes only the dictionary or the annotation "
                   "options then "
                   "skips segmentation")
        ->type_name("FILE");
    sub.add_option("--timestamp", o->timestamp,
                   "xsd:dateTime recorded as the end of the run, e.g. 2026-11-25T18:00:00Z (off by "
                   "default: same input, "
                   "same bytes)")
        ->check(CLI::Validator(
            [](std::string& v) {
                return detail::is_date_time(v)
                           ? std::string()
                           : "not an xsd:dateTime (YYYY-MM-DDThh:mm:ss, a date that exists, "
                             "optionally Z or +hh:mm up to 14:00): " +
                                 v;
            },
            "DATETIME"));
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return annotate_object(*o); };
}

}  // namespace geotex::cli
