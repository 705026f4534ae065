#pragma once
/// Scores of a segmentation against a ground truth (paper §4.1.1): the surfacic Hausdorff
/// distance, the mean distance between adjacent faces, texel matching and the agreement of
/// textures with the true shape kinds.

#include <vector>

#include "geometry/mesh.hpp"

namespace geotex {

struct GroundTruth {
    std::vector<int> face_shape;    ///< #F, shape id or -1
    std::vector<int> shape_kind;    ///< per shape id: its kind (any int)
    std::vector<int> shape_family;  ///< per shape id: a coarser class (e.g. both disc sizes
                                    ///< in one); may be empty
};

struct SegmentationScore {
    double hausdorff = 0;          ///< surfacic Hausdorff distance between the foregrounds,
                                   ///< divided by the largest bounding-box side (+inf when
                                   ///< exactly one foreground is empty)
    double hausdorff_matched = 0;  ///< same, counting only texels matched to a shape
    double delta_t = 0;            ///< mean distance between barycentres of adjacent faces,
                                   ///< divided by the largest bounding-box side
    double largest_side = 0;       ///< mesh units
    int num_shapes = 0;            ///< shapes with at least one face
    int num_texels = 0;
    int num_matched = 0;    ///< shapes covered by exactly one texel
    int num_missed = 0;     ///< shapes that no texel covers
    int num_split = 0;      ///< shapes covered by more than one texel
    int num_spurious = 0;   ///< texels that cover no shape
    double ari_kind = 0;    ///< adjusted Rand index of texture vs kind over the texels
                            ///< that cover a shape
    double ari_family = 0;  ///< same against the families (0 when none given)
};

/// Scores `face_texel` (#F, texel or -1) and `face_texture` (#F, texture or -1) on `mesh`
/// against `truth`. A texel covers the shape with which it shares the most faces. Nearest
/// barycentres by a k-d tree (CGAL). Throws InvalidInput when sizes differ.
SegmentationScore evaluate_segmentation(const Mesh& mesh, const std::vector<int>& face_texel,
                                        const std::vector<int>& face_texture,
                                        const GroundTruth& truth);

/// Surfacic Hausdorff distance of paper §4.1.1 between face sets `a` and `b` (face
/// indices), in mesh units, by their barycentres. 0 when both are empty, +inf when one is.
double surfacic_hausdorff(const Mesh& mesh, const std::vector<int>& a, const std::vector<int>& b);

}  // namespace geotex
