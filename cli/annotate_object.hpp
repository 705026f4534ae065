#pragma once
// One object annotated into its files: what `geotex annotate` runs once its options are
// parsed, and what each child of `geotex batch` runs. A batch child is forked and calls
// annotate_object() with the job filled in, so the options travel as this struct, never as a
// rebuilt command line.

#include <string>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "cli/commands.hpp"
#include "cli/segment_run.hpp"

namespace geotex::cli {

struct AnnotateJob {
    CommonOptions common;
    SegmentRunOptions run;          ///< the mesh and the geometric options
    std::string output;             ///< the RDF file
    std::string format = "turtle";  ///< turtle, ntriples or rdfxml
    std::string dictionary;         ///< YAML dictionary file; "" the built-in one
    /// The dictionary already read from `dictionary` (batch reads it once for all its
    /// objects); nullptr: annotate_object reads it.
    const Dictionary* loaded_dictionary = nullptr;
    std::string base;       ///< base IRI, "" hash names
    std::string object;     ///< IRI of the physical object, "" none
    std::string creator;    ///< IRI of the creator, "" none
    std::string mesh_unit;  ///< mm, cm, m, in or ""
    std::string lang = "en";
    std::string json;            ///< JSON report, "" none
    std::string jsonld;          ///< JSON-LD, "" none
    std::string segmentation;    ///< segmentation PLY, "" none
    std::string geometry_cache;  ///< geometry cache, read and rewritten; "" none
    DescriptionParams description;
    std::string timestamp;  ///< xsd:dateTime of the end of the run, "" none
    /// Every output must be a file of its own, never a link: batch's outputs are inside its
    /// output directory, where a planted link could send them anywhere.
    bool refuse_output_links = false;
};

/// Checks the job's options (before any mesh is read), segments the mesh (or reads its
/// geometry cache), annotates it and writes every output atomically; the textures and their
/// words on stdout, progress on stderr. Returns the exit code; throws CliError or
/// geotex::Error as the commands do (run_command turns them into the one-line error).
int annotate_object(AnnotateJob& job);

}  // namespace geotex::cli
