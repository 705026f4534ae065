#pragma once
// OUTDIR/published.json: what `geotex publish` sent where, so that a rerun sends only what
// changed. Rewritten whole (temporary file, then rename) after every object, so a publish
// killed at any moment leaves the record of a consistent state.

#include <cstddef>
#include <map>
#include <string>

namespace geotex::cli {

/// One object's triples in one graph of one store.
struct PublishedObject {
    std::string annotation_sha256;  ///< of the annotation.ttl whose triples were sent
    std::size_t triples = 0;
    std::size_t bytes = 0;  ///< request bodies
    bool complete = false;  ///< false: being sent, or a send failed; the graph's content is
                            ///< then unknown and the next publish rewrites the graph
};

/// Object id -> what of it a graph holds.
using PublishedGraph = std::map<std::string, PublishedObject>;

/// Endpoint URL -> graph IRI -> objects.
struct PublishRecord {
    std::map<std::string, std::map<std::string, PublishedGraph>> endpoints;
};

/// The record in `path`; empty when the file does not exist. Throws CliError (input) when it
/// exists but cannot be read or is not a publish record.
PublishRecord read_publish_record(const std::string& path);

/// Replaces `path` with the record, atomically. Throws CliError (output).
void write_publish_record(const std::string& path, const PublishRecord& record);

}  // namespace geotex::cli
