// geotex as a library, the whole path from a mesh file to Turtle: read and repair the mesh,
// read a dictionary, annotate, write the RDF and, when asked, the JSON report. The same bytes as
//   geotex annotate MESH --scale SCALE --dictionary DICTIONARY -o OUT.ttl [--json REPORT.json]
//   example_library MESH SCALE DICTIONARY [REPORT.json] > OUT.ttl
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <utility>

#include "annotation/dictionary.hpp"
#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/read_text_file.hpp"
#include "pipeline/report_json.hpp"

int main(int argc, char** argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: %s MESH SCALE DICTIONARY [REPORT.json] > OUT.ttl\n", argv[0]);
        return 1;
    }
    const std::string mesh_path = argv[1], dictionary_path = argv[3];
    try {
        geotex::MeshFile file = geotex::read_mesh_file(mesh_path);
        // The soup is handed over: not needed after the repair, it is not held beside the mesh.
        const geotex::MeshRepairResult repaired = geotex::repair_soup(std::move(file.soup));
        const geotex::Mesh& mesh = repaired.mesh;

        const geotex::Dictionary dictionary =
            geotex::parse_dictionary(geotex::read_text_file(dictionary_path), dictionary_path);

        geotex::AnnotateOptions options;
        options.segmentation.radius_rel = std::atof(argv[2]);
        const geotex::Annotation annotation = geotex::annotate(
            mesh, geotex::file_identity(mesh_path, file.format), dictionary, options);
        for (const auto& d : annotation.segmentation.diagnostics)
            std::fprintf(stderr, "%s: %s: %s\n", mesh_path.c_str(), d.stage.c_str(),
                         d.message.c_str());

        geotex::write_annotation_rdf(std::cout, annotation.document(mesh),
                                     geotex::RdfFormat::Turtle);
        std::cout.flush();
        if (!std::cout) throw geotex::IoError("cannot write the Turtle", "stdout");

        if (argc == 5) {
            // The report's "input": the mesh as named here, its format and what repair did.
            const geotex::ReportInput input{mesh_path, file.format, repaired.report};
            std::ofstream report(argv[4], std::ios::binary);
            report << geotex::report_text(geotex::annotation_report(annotation, input));
            report.close();
            if (!report) throw geotex::IoError("cannot write the report", argv[4]);
        }
    } catch (const geotex::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.located(mesh_path).c_str());
        return 2;
    }
    return 0;
}
