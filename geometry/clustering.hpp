#pragma once
/// Self-tuning spectral clustering (Zelnik-Manor & Perona, NIPS 2004: ZP04), paper §3.4: groups
/// texels with similar features into geometric textures without being told how many.

#include <Eigen/Core>
#include <vector>

#include "geometry/diagnostics.hpp"

namespace geotex {

struct ClusteringParams {
    int neighbour_rank = 7;            ///< local scale sigma_i = distance to this nearest
                                       ///< neighbour (ZP04: 7); groups need more points
                                       ///< than this to separate from similar ones
    int max_clusters = 10;             ///< largest number of groups tried (capped by #points)
    double quality_tolerance = 0.002;  ///< pick the largest group count whose alignment
                                       ///< quality is within this of the best (ZP04's rule;
                                       ///< why 0.002 in clustering.cpp), in [0, 1]: qualities
                                       ///< lie in [1/C, 1], so 1 already admits every count
    double min_quality = 0.95;         ///< single-group rule: a group count needs at least
                                       ///< this alignment quality, in [0, 1]; quality =
                                       ///< 1 / (1 + mean spill of a point onto other groups)
    double max_conductance = 0.1;      ///< single-group rule: at most this fraction of any
                                       ///< group's total affinity may link it to other
                                       ///< groups, in [0, 1]
    /// Most points the spectral step sees; 0: all. Its time grows as the cube of the points
    /// and its memory as the square (one core: 1.6 s at 2,000 points, 44 s and
    /// 0.9 GB at 5,280; bench/RESULTS.md). Above it, that many landmarks evenly spaced
    /// in the points' order are clustered and every other point joins the group of its
    /// nearest landmark (clustering.cpp, "Landmarks"). At least 2 when not 0.
    int max_points = 2000;
};

struct ClusteringResult {
    std::vector<int> labels;          ///< #points, in [0, num_clusters); groups numbered by
                                      ///< their smallest member index
    int num_clusters = 0;             ///< 0 only for no points
    std::vector<double> quality;      ///< alignment quality per tried group count
                                      ///< (index 0 = 2 groups), in [0, 1]
    std::vector<double> conductance;  ///< largest group conductance per tried group count
                                      ///< (index 0 = 2 groups), in [0, 1]
    Diagnostics diagnostics;          ///< duplicates and isolated points, if any
    /// 0 when every point took part in the spectral step; else the number of landmarks that
    /// did (params.max_points), quality and conductance being theirs
    int num_landmarks = 0;
};

/// Checks every field against the range its comment states (neighbour_rank and max_clusters
/// at least 1, the others in [0, 1]). Throws InvalidInput naming the first field out of range.
/// make_clustering calls it; so does the RDF writer, for the parameters it records.
void check_clustering_params(const ClusteringParams& params);

/// Clusters the rows of `features` (#points by #features, raw values; columns are
/// standardised inside, so units do not matter). One group when no tried group count gives
/// a partition that is both crisp (quality >= min_quality) and separated (conductance <=
/// max_conductance); so one group for 1 point, and for 2 unless max_conductance is 1 (their
/// split has conductance 1); no group for 0. Deterministic: the same input gives
/// bit-identical labels. Details and formulas in clustering.cpp.
/// Throws InvalidInput on a non-finite feature value (naming row and column) or a parameter
/// out of range; NumericalError if the eigen solver fails.
ClusteringResult make_clustering(const Eigen::MatrixXd& features,
                                 const ClusteringParams& params = {});

}  // namespace geotex
