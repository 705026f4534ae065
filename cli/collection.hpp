#pragma once
// The objects of a collection for `geotex batch`: read from a directory of meshes or a CSV
// manifest, with their ids checked, duplicates refused and the shard of each (see
// docs/collections.md). No processing here, only the listing.

#include <string>
#include <vector>

namespace geotex::cli {

struct CollectionObject {
    std::string id;    ///< object id (as found, even when invalid)
    std::string mesh;  ///< the mesh as listed: file name in the directory, or the manifest's cell
    std::string path;  ///< the file to open (the manifest's directory prepended to a relative cell)
    std::string where;       ///< "manifest.csv:12" or the mesh path, for messages
    std::string error;       ///< non-empty: the object fails with this one-line reason
    std::string object_iri;  ///< the manifest's `object` cell: the physical object's IRI ("" none)
    std::string mesh_unit;   ///< the manifest's `mesh_unit` cell: mm, cm, m or in ("" none)
};

struct Collection {
    std::vector<CollectionObject> objects;  ///< sorted by id, then by where
    std::vector<std::string> notes;         ///< e.g. manifest columns that are ignored
};

/// Extensions of the mesh files a directory contributes (lower case, with the dot).
bool is_mesh_file_name(const std::string& name);

/// Empty when `id` can be an object id, else why not.
std::string check_object_id(const std::string& id);

/// The objects of `input`, a directory or a CSV manifest. Throws CliError (kExitInput) when
/// `input` cannot be read or the manifest as a whole is unusable (no `mesh` column, a quote
/// never closed); a bad row, an invalid or duplicate id only fail their objects.
Collection read_collection(const std::string& input);

/// The objects of a CSV manifest's `text` (`file` names it in messages and is the base of
/// relative mesh cells), as read_collection gives them. Throws CliError (kExitInput) when
/// the manifest as a whole is unusable.
Collection parse_manifest(const std::string& text, const std::string& file);

/// Shard of `id` among `num_shards`, in [1, num_shards]: SHA-256(id)'s first 8 bytes,
/// big-endian, modulo num_shards, plus one. Depends on the id alone.
int shard_of(const std::string& id, int num_shards);

/// An object's IRI from a template (`option` names it in messages: --base-template,
/// --object-template): "{id}" becomes the id as one percent-encoded IRI segment, "{sha256}"
/// the mesh file's digest. Throws CliError (kExitUsage) for another "{...}" or a template
/// that names neither (every object would share its IRIs).
std::string expand_iri_template(const std::string& option, const std::string& templ,
                                const std::string& id, const std::string& sha256);

}  // namespace geotex::cli
