#pragma once
// A small annotation document built by hand, shared by the tests of the RDF and JSON-LD
// writers: a strip of 16 faces, 3 texels in 2 textures, a 5-concept dictionary in English and
// French with four facets, awkward doubles among the features.

#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "geometry/mesh.hpp"
#include "geometry/segmentation.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::test {

/// SHA-256 of the empty string, the mesh digest of the case.
inline const std::string kMeshDigest =
    "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";

/// Texels {0,1,2}, {5,6,7,9} and {12..15} of a strip of 8 unit squares (16 faces); textures
/// {texel 0, texel 2} (circular shape and small area chosen, flat withheld; texel 2's own
/// area is large) and {texel 1} (engraved, elongated chosen, a concept only for engravings);
/// base IRI https://example.org/objects/vase-42/, dictionary namespace
/// https://example.org/dict/, max_literal_faces 3 (texels 1 and 2 get a digest), no
/// dictionary in the graph. `doc` points into the other members: the case is not copied.
struct SmallAnnotationCase {
    Mesh mesh;
    Segmentation seg;
    Dictionary dictionary;
    std::vector<TextureDescription> descriptions;
    AnnotationDocument doc;

    SmallAnnotationCase();
    SmallAnnotationCase(const SmallAnnotationCase&) = delete;
    SmallAnnotationCase& operator=(const SmallAnnotationCase&) = delete;
};

/// A way to break the case, and its name: every annotation writer must refuse the broken
/// case with InvalidInput and write nothing (the preconditions that write_annotation_rdf
/// and write_annotation_jsonld share). Set doc.include_dictionary first: some break the
/// dictionary's labels.
struct BrokenCase {
    const char* name;
    void (*apply)(SmallAnnotationCase& c);
};
const std::vector<BrokenCase>& broken_cases();

}  // namespace geotex::test
