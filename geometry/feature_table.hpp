#pragma once
/// The texel features: the 18 of paper §3.3, then two sizes relative to the object's largest
/// side. Their exact formulas are documented in one place, docs/features.md; the ids below are
/// the stable names used by dictionaries, JSON and RDF.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "geometry/curvature.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/diagnostics.hpp"
#include "geometry/mesh.hpp"
#include "geometry/texels.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// Column of each feature in FeatureTable::values.
enum class Feature : int {
    ContourPerimeter,
    ContourSphericity,
    LocalDiameterMean,
    LocalDiameterStd,
    Area,
    BoundingSphereRadius,
    Perimeter2AreaRatio,
    PcaVariance1,
    PcaVariance2,
    PcaVariance3,
    DepthMean,
    DepthStd,
    GaussianCurvatureMean,
    GaussianCurvatureStd,
    ShapeIndexMean,
    ShapeIndexStd,
    CurvednessMean,
    CurvednessStd,
    // Not in the paper: the paper's Area and BoundingSphereRadius are min-max normalised over
    // the texels of one object ("large" = larger than the other details of this object); these
    // two are fractions of the object's largest side (squared for the area), so they mean the
    // same across a collection.
    AreaRel,
    BoundingSphereRadiusRel,
};

inline constexpr int kNumFeatures = 20;
/// The clustering uses the paper's 18 features (the first columns): AreaRel and
/// BoundingSphereRadiusRel are affine in Area and BoundingSphereRadius within one object, so
/// after standardisation they would only count those two twice.
inline constexpr int kNumClusteringFeatures = 18;

/// Stable feature ids, in column order.
inline constexpr std::array<const char*, kNumFeatures> kFeatureIds = {
    "contour_perimeter",
    "contour_sphericity",
    "local_diameter_mean",
    "local_diameter_std",
    "area",
    "bounding_sphere_radius",
    "perimeter2_area_ratio",
    "pca_variance_1",
    "pca_variance_2",
    "pca_variance_3",
    "depth_mean",
    "depth_std",
    "gaussian_curvature_mean",
    "gaussian_curvature_std",
    "shape_index_mean",
    "shape_index_std",
    "curvedness_mean",
    "curvedness_std",
    "area_rel",
    "bounding_sphere_radius_rel",
};

/// Column of a feature id, or -1 when unknown.
int feature_index(const std::string& id);

struct FeatureTable {
    std::vector<std::string> names;  ///< kFeatureIds
    Eigen::MatrixXd values;          ///< #texels by kNumFeatures, as documented in docs/features.md
    Diagnostics diagnostics;
};

/// Inputs of make_feature_table that describe the whole mesh.
struct FeatureInputs {
    const Mesh* mesh = nullptr;
    const MeshTopology* topology = nullptr;
    const CurvatureField* curvature = nullptr;  ///< of `mesh`, in mesh units
    /// Depth maps by orientation; a texel uses the one of its orientation (may be null when
    /// no texel has that orientation).
    const DepthMap* positive_depth = nullptr;
    const DepthMap* negative_depth = nullptr;
    double largest_side = 0;  ///< largest bounding-box side, mesh units (features are
                              ///< computed on the mesh scaled to a unit side)
};

/// The features of texels before their normalisations across all the texels of the mesh: what
/// a part of the mesh (a tile, tiles.hpp) computes for the texels it holds whole; the rows of
/// every part, joined in texel order, are normalised once.
struct FeatureRows {
    /// #texels by kNumFeatures: Area and BoundingSphereRadius not yet min-max normalised, the
    /// local diameter columns not yet set
    Eigen::MatrixXd values;
    struct Diameter {
        double value, weight;
    };
    std::vector<std::vector<Diameter>> diameters;  ///< #texels: the local diameters along the
                                                   ///< contour, each with its edge's length
    std::vector<char> no_contour;                  ///< #texels: no boundary loop
    std::vector<char> no_curvature;                ///< #texels: only border vertices
};

/// The first step of make_feature_table: every texel's row on its own. Throws as
/// make_feature_table.
FeatureRows make_feature_rows(const FeatureInputs& inputs, const std::vector<Texel>& texels);

/// The second step: the local diameters over the largest of all contours, Area and
/// BoundingSphereRadius min-max over all texels, and the diagnostics. Throws InvalidInput
/// when the parts of `rows` differ in length.
FeatureTable normalise_feature_rows(FeatureRows rows);

/// Features of every texel (rows in texel order). Faces of distinct texels must be
/// disjoint. Parallel over texels, deterministic. Throws InvalidInput on missing inputs.
FeatureTable make_feature_table(const FeatureInputs& inputs, const std::vector<Texel>& texels);

}  // namespace geotex
