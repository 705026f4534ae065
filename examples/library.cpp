// geotex as a library, the whole path from a mesh file to Turtle: read and repair the mesh,
// read a dictionary, annotate, write the RDF. The same bytes as
//   geotex annotate MESH --scale SCALE --dictionary DICTIONARY -o OUT.ttl
//   example_library MESH SCALE DICTIONARY > OUT.ttl
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "annotation/dictionary.hpp"
#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/annotate.hpp"

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s MESH SCALE DICTIONARY > OUT.ttl\n", argv[0]);
        return 1;
    }
    const std::string mesh_path = argv[1], dictionary_path = argv[3];
    try {
        const geotex::MeshFile file = geotex::read_mesh_file(mesh_path);
        const geotex::Mesh mesh = geotex::repair_soup(file.soup).mesh;

        std::ifstream in(dictionary_path, std::ios::binary);
        if (!in) throw geotex::IoError("cannot open", dictionary_path);
        std::ostringstream text;
        text << in.rdbuf();
        const geotex::Dictionary dictionary = geotex::parse_dictionary(text.str(), dictionary_path);

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
    } catch (const geotex::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.located(mesh_path).c_str());
        return 2;
    }
    return 0;
}
