#pragma once
/// JSON-LD output of geotex: the Web Annotations of one mesh as a W3C AnnotationPage, for
/// the tools of IIIF and Europeana. The mapping is documented in ontology/README.md.

#include <iosfwd>

#include "ontology/rdf_writer.hpp"

namespace geotex {

/// The W3C Web Annotation JSON-LD context, the first entry of the output's "@context".
inline constexpr const char* kWebAnnotationContext = "http://www.w3.org/ns/anno.jsonld";

/// Writes the annotations of `doc` as one JSON-LD AnnotationPage `B annotations`: one
/// Annotation per texture (motivation classifying; body the chosen concepts, with their
/// skos:prefLabel when doc.include_dictionary; target the texels as SpecificResources on the
/// mesh, each with its face selector), named by the IRIs of write_annotation_rdf. Apart
/// from the page and its item list, every triple it denotes is one that write_annotation_rdf
/// writes for the same document. Deterministic: same document, same bytes (2-space
/// indentation, keys in a fixed order, UTF-8 unescaped, no floating-point number).
/// Throws InvalidInput, before writing anything, where write_annotation_rdf does, and when the
/// base IRI or the dictionary namespace starts with a term of the context followed by ':'
/// without '//' (e.g. "oa:x/": JSON-LD would read it as a compact IRI); IoError when the
/// stream fails.
void write_annotation_jsonld(std::ostream& out, const AnnotationDocument& doc);

}  // namespace geotex
