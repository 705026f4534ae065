#pragma once
// Owning handles for the C objects of Raptor, shared by the ontology sources that parse or
// serialize with it (sparql.cpp, rdf_transcode.cpp). Include only from .cpp files: it brings
// in raptor2.h.

#include <raptor2.h>

#include <memory>

#include "common/detail/c_handle.hpp"

namespace geotex::detail {

using RaptorWorld = std::unique_ptr<raptor_world, CDeleter<raptor_free_world>>;
using RaptorParser = std::unique_ptr<raptor_parser, CDeleter<raptor_free_parser>>;
using RaptorSerializer = std::unique_ptr<raptor_serializer, CDeleter<raptor_free_serializer>>;
using RaptorUri = std::unique_ptr<raptor_uri, CDeleter<raptor_free_uri>>;
using RaptorIostream = std::unique_ptr<raptor_iostream, CDeleter<raptor_free_iostream>>;
using RaptorTerm = std::unique_ptr<raptor_term, CDeleter<raptor_free_term>>;

}  // namespace geotex::detail
