#pragma once
/// The whole geometric half of the method of A. Othmani, F. Torkhani and J.-M. Favreau,
/// "3D Geometric salient patterns analysis on 3D meshes", 2019 (a Springer journal
/// manuscript; "the paper", "§" below): its §3, the depth map (§3.1), texels (§3.2),
/// features (§3.3) and geometric textures (§3.4) of one mesh, with a callback that reports
/// each stage. Its §4.1 synthetic benchmark is synth.hpp.

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/clustering.hpp"
#include "geometry/curvature.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/diagnostics.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/mesh.hpp"
#include "geometry/texels.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// Which details to extract.
enum class OrientationMode { Positive, Negative, Both };

/// The names of the orientation modes in options and reports.
inline constexpr std::array<std::pair<const char*, OrientationMode>, 3> kOrientationModeNames = {
    {{"positive", OrientationMode::Positive},
     {"negative", OrientationMode::Negative},
     {"both", OrientationMode::Both}}};
inline const char* name_of(OrientationMode m) { return name_in(kOrientationModeNames, m); }
/// The mode named `name` ("positive", "negative", "both"); nullopt for another name.
inline std::optional<OrientationMode> parse_orientation_mode(std::string_view name) {
    return value_in(kOrientationModeNames, name);
}

struct SegmentationParams {
    double radius_rel = 0.04;  ///< scale r as a fraction of the largest bounding-box side
                               ///< (the paper's convention), used when `radius` is 0
    double radius = 0;         ///< r in mesh units; > 0 overrides radius_rel
    OrientationMode orientation = OrientationMode::Positive;
    SmoothingMethod smoothing = SmoothingMethod::Twicing;
    bool area_weighted = true;       ///< area-weighted disc means (false: eq. 1's vertex mean)
    DiscMode disc = DiscMode::Auto;  ///< see SmoothingParams::disc
    /// Curvature features from a quadric fitted over discs of radius curvature_scale * r
    /// (CurvatureParams::radius); 0: the one-ring operators, as the paper. The default keeps
    /// the texture features stable under sampling noise (bench/RESULTS.md, noise).
    double curvature_scale = 0.6;
    double merge_overlap = 0.5;   ///< see TexelParams
    double min_depth_rel = 0.01;  ///< see TexelParams
    int min_faces = 3;            ///< see TexelParams
    /// Rim removal (docs/rims.md, not in the paper): the details of the other orientation are
    /// left out of a second smoothing, so that an engraving does not raise a positive rim
    /// around it (nor a raised detail a negative one). No effect where there is none.
    bool remove_rims = true;
    ClusteringParams clustering;
};

/// What one run produces. Texel ids are indices into `texels`: positive texels first, then
/// negative ones; texture ids likewise (the two orientations are clustered separately, so
/// a texture never mixes raised and engraved details).
struct Segmentation {
    double radius = 0;                  ///< r used, mesh units
    int num_interpolated_vertices = 0;  ///< vertices whose disc means were interpolated
    int num_disc_samples = 0;           ///< exact discs walked as samples (fast mode)
    MeshMetrics metrics;
    MeshTopology topology;
    CurvatureField curvature;  ///< on the vertices of texels only (NaN elsewhere)
    std::optional<DepthMap> positive_depth;
    std::optional<DepthMap> negative_depth;
    std::vector<DetailOrientation> runs;   ///< orientations extracted, positive first
    std::vector<TexelSet> texel_sets;      ///< per run (statistics; texels moved out)
    std::vector<int> run_excluded_texels;  ///< per run: texels of the other orientation left out
                                           ///< of its second smoothing (0: none, one smoothing)
    std::vector<Texel> texels;
    std::vector<int> face_texel;     ///< #F, texel id or -1
    FeatureTable features;           ///< rows = texels
    std::vector<int> texel_texture;  ///< #texels
    std::vector<int> face_texture;   ///< #F, texture id or -1
    int num_textures = 0;
    std::vector<DetailOrientation> texture_orientation;  ///< per texture
    std::vector<ClusteringResult> clusterings;           ///< per run
    Diagnostics diagnostics;
};

/// The faces' texel and texture ids (face_texel, face_texture) taken from the texels, a block
/// of faces at a time in face order, for a segmentation that holds no face arrays (the join
/// of a tiled run, TiledResult::Outputs): 8 bytes a face of a texel, not a face of the mesh.
///
///     FaceLabelCursor labels(seg);
///     for (each block [first, first + count) of faces, in order)
///         labels.next(first, count, texel, texture);  // #count each
class FaceLabelCursor {
  public:
    /// `seg` must outlive the cursor. Throws InvalidInput when a face is in two texels.
    explicit FaceLabelCursor(const Segmentation& seg);
    /// The labels of faces [first, first + count), -1 where no texel is. `first` must not be
    /// below the end of the block before.
    void next(int first, int count, std::vector<int>& texel, std::vector<int>& texture);

  private:
    const Segmentation& seg_;
    std::vector<std::pair<int, int>> face_texel_;  // (face, texel), ascending
    std::size_t at_ = 0;
};

/// A stage starting (seconds < 0) or finished (seconds = its wall time).
struct StageEvent {
    std::string stage;
    double seconds = -1;
};
using StageObserver = std::function<void(const StageEvent&)>;

/// Checks every parameter against its range: `radius` positive and finite when not 0, else
/// `radius_rel` in (0, 1); `curvature_scale` and `merge_overlap` in [0, 1]; `min_depth_rel`
/// >= 0 and finite; `min_faces` >= 1; the clustering's as check_clustering_params. Throws
/// InvalidInput naming the first parameter out of range. run_segmentation calls it first, and
/// the RDF writer for the parameters it records (ontology/shapes.ttl states the same ranges).
void check_segmentation_params(const SegmentationParams& params);

/// Resolves the radius in mesh units from the params and the mesh size. Throws InvalidInput
/// when radius_rel is not in (0, 1) or radius is negative or not finite.
double resolve_radius(const SegmentationParams& params, double largest_side);

/// Runs the pipeline on a clean triangle mesh (repair_soup output). Deterministic for any
/// thread count. Throws InvalidInput on bad parameters or an empty mesh.
Segmentation run_segmentation(const Mesh& mesh, const SegmentationParams& params = {},
                              const StageObserver& observer = {});

/// What run_segmentation computes before the parameters matter (the unit frame, the topology,
/// the mesh metrics and the depth maps' triangle tree), computed once for several runs over one
/// mesh: the scales of a series (scale_series.hpp). Holds a pointer to `mesh`, which must outlive
/// it. run() may be called from several threads at once.
class SegmentationContext {
  public:
    /// Tells `observer` of the "topology" stage. Throws InvalidInput on an empty mesh or one
    /// whose size no double holds (make_unit_frame, make_mesh_metrics).
    explicit SegmentationContext(const Mesh& mesh, const StageObserver& observer = {});
    SegmentationContext(const SegmentationContext&) = delete;
    SegmentationContext& operator=(const SegmentationContext&) = delete;

    /// run_segmentation(mesh, params, observer), bit for bit; the result holds copies of the
    /// shared topology and metrics. Throws InvalidInput on bad parameters.
    Segmentation run(const SegmentationParams& params, const StageObserver& observer = {}) const&;
    /// The same, moving the topology and metrics into the result: for a context used once.
    Segmentation run(const SegmentationParams& params, const StageObserver& observer = {}) &&;
    /// The same with the result's topology and metrics left empty, for callers that read its
    /// texels and textures alone (the scales of a series), which would copy the two for every
    /// scale (22 MB at 327,680 faces) only to free them.
    Segmentation run_without_topology(const SegmentationParams& params,
                                      const StageObserver& observer = {}) const;

  private:
    // The result without its topology and metrics, in the unit frame.
    Segmentation run_without_shared(const SegmentationParams& params,
                                    const StageObserver& observer) const;

    const Mesh* mesh_;
    int exponent_ = 0;               // the unit frame's, when the mesh is brought to it; else 0
    std::optional<Mesh> unit_mesh_;  // the mesh scaled by 2^-exponent_, when exponent_ != 0
    MeshTopology topology_;          // of the mesh the pipeline runs on
    MeshMetrics metrics_;
    std::optional<DepthMapper> depth_mapper_;  // its components and triangle tree
};

}  // namespace geotex
