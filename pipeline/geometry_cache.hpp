#pragma once
// The geometric results of a run kept on disk, so that a run that changes only the
// dictionary or the annotation options (a curator's edit, re-run over a whole collection)
// skips the geometric stages. The file is CBOR (via nlohmann_json, which keeps doubles and
// NaN exactly); it holds what the outputs need (texels, features, textures, statistics and
// diagnostics), not the per-vertex fields (depth, curvature), and is valid only for the
// same mesh bytes, parameters and geotex version (its key).

#include <Eigen/Core>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/mesh.hpp"
#include "geometry/segmentation.hpp"

namespace geotex {

/// The key of a cache: SHA-256 of the geotex version, the mesh file's digest and every
/// parameter as given (the relative scale, or the absolute radius of --radius; the radius
/// that a scale resolves to is not needed; the clustering's thresholds that no option sets
/// too), so a cache never outlives a change of any of them.
std::string geometry_cache_key(const std::string& mesh_sha256, const SegmentationParams& params);

/// Writes what the outputs need of `seg` with `key`.
void write_geometry_cache(std::ostream& out, const std::string& key, const Segmentation& seg);

/// What read_geometry_cache found.
struct GeometryCacheRead {
    std::optional<Segmentation> segmentation;  ///< the cached results, when the file is valid
    std::string refusal;  ///< why an existing file was not used ("made from another mesh,
                          ///< ...", "unreadable (...)"); empty when absent or used
};

/// Reads the cache at `path` when it exists and holds `key`; rebuilds the topology and
/// metrics from `mesh` (cheap) and checks every index against it. No segmentation when the
/// file is absent, for another key, truncated or otherwise unreadable (the refusal says which).
GeometryCacheRead read_geometry_cache(const std::string& path, const std::string& key,
                                      const Mesh& mesh);

/// What describe_textures needs of a cache, read without the mesh (the workbench and
/// `geotex dict fit` re-choose words over a whole collection without reading a mesh).
struct GeometryTables {
    std::string key;                 ///< the cache's key (geometry_cache_key)
    Eigen::MatrixXd features;        ///< #texels by kNumFeatures, columns in kFeatureIds order
    std::vector<int> texel_texture;  ///< #texels, in [0, num_textures)
    int num_textures = 0;
    std::vector<DetailOrientation> texture_orientation;  ///< #textures
};

/// Reads the tables of a cache's bytes. Nothing ties them to a mesh here: the caller checks
/// the file against the run that made it (the digest recorded in the batch's run.json).
/// Throws InvalidInput saying what is wrong when the bytes are no cache of this schema, its
/// feature columns are not this geotex's, or its sizes or texture ids disagree.
GeometryTables read_geometry_tables(std::string_view bytes);

}  // namespace geotex
