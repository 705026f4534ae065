// geotex.segment: texels and textures of a mesh given as arrays, as `geotex segment` finds
// them (paper §3), and the result object whose arrays are views of the library's result.

#include "segment.hpp"

#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "geometry/unit_frame.hpp"

namespace py = pybind11;

namespace geotex::python {

namespace {

/// The value of an enum keyword from its name beside the enum (`parse`: parse_orientation_mode,
/// ...), accepted in any case as the command's options are; UsageError listing `table`'s
/// names otherwise.
template <class Table, class Parse>
auto value_of(const Table& table, Parse parse, const char* keyword, const std::string& given) {
    std::string lower = given;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (const auto value = parse(lower)) return *value;
    std::string choices;
    for (const auto& entry : table)
        choices += (choices.empty() ? "" : ", ") + std::string(entry.first);
    raise_error(Phase::Usage,
                std::string(keyword) + " must be one of " + choices + " (got '" + given + "')");
}

std::string repr(double x) { return py::repr(py::float_(x)).cast<std::string>(); }

void check_range(const char* keyword, double value, double lo, double hi) {
    if (!(value >= lo && value <= hi))
        raise_error(Phase::Usage, std::string(keyword) + " must be in [" + repr(lo) + ", " +
                                      repr(hi) + "] (got " + repr(value) + ")");
}

/// The keyword arguments of geotex.segment, as the command's options.
struct Keywords {
    std::optional<double> scale;
    bool auto_scale = false;  ///< scale="auto"
    bool levels = false;
    std::optional<double> radius;
    std::string orientation, smoothing, disc;
    double curvature_scale = 0, merge_overlap = 0, min_depth = 0;
    bool vertex_mean = false, keep_rims = false;
    int min_faces = 0, max_textures = 0, cluster_landmarks = 0;
    int threads = 0;
    int tiles = 0;  ///< as the command's --tiles: 0 the whole mesh at once
};

/// The parameters the command would run with, or geotex.UsageError where it would refuse an
/// option (check_segmentation_options and the options' ranges in cli/segment_run.cpp).
SegmentationParams checked_params(const Keywords& k) {
    if ((k.scale.has_value() || k.auto_scale) == k.radius.has_value())
        raise_error(Phase::Usage,
                    "give exactly one of scale (fraction of the largest bounding-box side, or "
                    "'auto') or radius (mesh units)");
    if (k.levels && !k.auto_scale)
        raise_error(Phase::Usage,
                    "levels=True needs scale='auto': the levels are the stable scales of the "
                    "series");
    if (k.scale && !(*k.scale > 0 && *k.scale < 1))
        raise_error(Phase::Usage,
                    "scale must be in (0, 1), a fraction of the largest bounding-box side (got " +
                        repr(*k.scale) + ")");
    if (k.radius && !(*k.radius > 0 && std::isfinite(*k.radius)))
        raise_error(Phase::Usage,
                    "radius must be positive and finite (got " + repr(*k.radius) + ")");
    SegmentationParams p;
    if (k.scale) p.radius_rel = *k.scale;
    p.radius = k.radius.value_or(0);
    p.orientation =
        value_of(kOrientationModeNames, parse_orientation_mode, "orientation", k.orientation);
    p.smoothing = value_of(kSmoothingMethodNames, parse_smoothing_method, "smoothing", k.smoothing);
    p.disc = value_of(kDiscModeNames, parse_disc_mode, "disc", k.disc);
    check_range("curvature_scale", k.curvature_scale, 0, 1);
    check_range("merge_overlap", k.merge_overlap, 0, 1);
    check_range("min_depth", k.min_depth, 0, 1);
    check_range("min_faces", k.min_faces, 1, 1000000);
    check_range("max_textures", k.max_textures, 1, 100);
    check_range("cluster_landmarks", k.cluster_landmarks, 0, 100000000);
    if (k.cluster_landmarks == 1)
        raise_error(Phase::Usage, "cluster_landmarks must be 0 (every texel) or at least 2");
    check_range("tiles", k.tiles, 0, 10000);
    if (k.tiles > 0 && k.auto_scale)
        raise_error(Phase::Usage,
                    "tiles with scale='auto': the scale series segments the whole mesh at every "
                    "scale; give a scale (geotex.scales finds one) to segment in tiles");
    if (k.threads < 0)
        raise_error(Phase::Usage, "threads must be 0 (all cores) or positive (got " +
                                      std::to_string(k.threads) + ")");
    p.curvature_scale = k.curvature_scale;
    p.merge_overlap = k.merge_overlap;
    p.min_depth_rel = k.min_depth;
    p.min_faces = k.min_faces;
    p.clustering.max_clusters = k.max_textures;
    p.clustering.max_points = k.cluster_landmarks;
    p.area_weighted = !k.vertex_mean;
    p.remove_rims = !k.keep_rims;
    return p;
}

const SegmentationResult& result_of(const py::object& self) {
    return self.cast<const SegmentationResult&>();
}

/// The repair and the pipeline on `soup`, as the command runs them on what it read; `file`
/// names the file it was read from (errors then name it), empty for arrays.
py::object segment_soup(PolygonSoup soup, const Keywords& keywords,
                        const SegmentationParams& params, const std::string& file,
                        const std::string& format) {
    auto result = std::make_unique<SegmentationResult>();
    result->mode = params.orientation;
    result->params = params;
    result->file = file;
    result->format = format;
    std::unique_ptr<tbb::global_control> threads;
    if (keywords.threads > 0)
        threads =
            std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(keywords.threads));
    // As the command's load_mesh and segment_mesh (cli/mesh_input.cpp, cli/segment_run.cpp):
    // the size check before the repair, then the pipeline; errors of the first are the
    // input's, of the second the processing's.
    in_phase(Phase::Input, file, [&] {
        py::gil_scoped_release release;
        make_unit_frame(soup.positions);
        result->input = repair_soup(std::move(soup));  // leaves the soup empty
    });
    if (keywords.auto_scale) {
        // As the command's choose_auto_scale: the series, then its best scale; a mesh too
        // coarse for every scale is the input's fault.
        ScaleSeries series = in_phase(Phase::Processing, {}, [&] {
            py::gil_scoped_release release;
            return run_scale_series(result->input.mesh, params, ScaleSeriesParams{});
        });
        result->scale_choice = in_phase(Phase::Input, file, [&] {
            return choose_scale(std::move(series), ScaleSeriesParams{});
        });
        result->params.radius_rel =
            result->scale_choice->series.steps[result->scale_choice->chosen].radius_rel;
        result->params.radius = 0;
    }
    in_phase(Phase::Processing, {}, [&] {
        py::gil_scoped_release release;
        result->seg = keywords.tiles > 0 ? run_tiled_segmentation(result->input.mesh,
                                                                  result->params, keywords.tiles)
                                         : run_segmentation(result->input.mesh, result->params);
        if (keywords.levels)
            result->levels = segment_levels(result->input.mesh, result->params,
                                            *result->scale_choice, result->seg);
    });
    if (result->seg.texels.empty()) {
        char radius[32];
        std::snprintf(radius, sizeof radius, "%.6g", result->seg.radius);
        const std::string message = std::string("no salient detail at radius ") + radius +
                                    " (mesh units); the result has zero texels. Try another "
                                    "scale or orientation.";
        if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();
    }
    return py::cast(result.release(), py::return_value_policy::take_ownership);
}

py::object segment(const Keywords& keywords, const py::object& V, const py::object& F) {
    const SegmentationParams params = checked_params(keywords);
    return segment_soup(soup_from_arrays(V, F), keywords, params, {}, {});  // the one copy
}

/// As `geotex segment PATH`: the file read once, as the command reads it.
py::object segment_file(const Keywords& keywords, const std::string& path) {
    const SegmentationParams params = checked_params(keywords);
    MeshFile mesh_file = in_phase(Phase::Input, path, [&] {
        py::gil_scoped_release release;
        return read_mesh_file(path);
    });
    return segment_soup(std::move(mesh_file.soup), keywords, params, path, mesh_file.format);
}

/// Defines `name` as a function of `leading` (its positional arguments) and of the keywords
/// of geotex.segment, with the command's defaults, that calls `run`.
template <class... Leading, class... LeadingArgs>
void def_segment(py::module_& m, const char* name, py::object (*run)(const Keywords&, Leading...),
                 const char* doc, LeadingArgs... leading) {
    const SegmentationParams d;  // the command's defaults are the library's
    m.def(
        name,
        [run](Leading... lead, const py::object& scale, std::optional<double> radius, bool levels,
              std::string orientation, std::string smoothing, std::string disc,
              double curvature_scale, bool vertex_mean, bool keep_rims, double merge_overlap,
              double min_depth, int min_faces, int max_textures, int cluster_landmarks, int threads,
              int tiles) {
            Keywords k;
            k.radius = radius;
            k.levels = levels;
            k.orientation = std::move(orientation);
            k.smoothing = std::move(smoothing);
            k.disc = std::move(disc);
            k.curvature_scale = curvature_scale;
            k.merge_overlap = merge_overlap;
            k.min_depth = min_depth;
            k.vertex_mean = vertex_mean;
            k.keep_rims = keep_rims;
            k.min_faces = min_faces;
            k.max_textures = max_textures;
            k.cluster_landmarks = cluster_landmarks;
            k.threads = threads;
            k.tiles = tiles;
            // scale: a number, or the text "auto" (as the command's --scale auto).
            if (py::isinstance<py::str>(scale)) {
                const std::string text = scale.cast<std::string>();
                if (text != "auto")
                    raise_error(Phase::Usage,
                                "scale must be a number in (0, 1) or 'auto' (got '" + text + "')");
                k.auto_scale = true;
            } else if (!scale.is_none()) {
                try {
                    k.scale = scale.cast<double>();
                } catch (const py::cast_error&) {
                    raise_error(Phase::Usage, "scale must be a number in (0, 1) or 'auto'");
                }
            }
            return run(k, lead...);
        },
        leading..., py::kw_only(), py::arg("scale") = py::none(), py::arg("radius") = py::none(),
        py::arg("levels") = false, py::arg("orientation") = name_of(d.orientation),
        py::arg("smoothing") = name_of(d.smoothing), py::arg("disc") = name_of(d.disc),
        py::arg("curvature_scale") = d.curvature_scale, py::arg("vertex_mean") = !d.area_weighted,
        py::arg("keep_rims") = !d.remove_rims, py::arg("merge_overlap") = d.merge_overlap,
        py::arg("min_depth") = d.min_depth_rel, py::arg("min_faces") = d.min_faces,
        py::arg("max_textures") = d.clustering.max_clusters,
        py::arg("cluster_landmarks") = d.clustering.max_points, py::arg("threads") = 0,
        py::arg("tiles") = 0, doc);
}

py::dict depth_of(const py::object& self, bool per_vertex) {
    const Segmentation& s = result_of(self).seg;
    py::dict out;
    for (const DetailOrientation o : s.runs) {
        const DepthMap& d =
            o == DetailOrientation::Positive ? *s.positive_depth : *s.negative_depth;
        out[name_of(o)] = view(per_vertex ? d.vertex_depth : d.face_depth, self);
    }
    return out;
}

void bind_segmentation_result(py::module_& m) {
    using R = SegmentationResult;
    py::class_<R>(m, "Segmentation",
                  "The result of geotex.segment. Arrays are read-only views of the result (no "
                  "copy); face indices refer to F, the repaired mesh (README, \"Python\").")
        .def_property_readonly(
            "V", [](py::object self) { return vertices_view(result_of(self).input.mesh, self); },
            "float64 #V by 3: vertex positions of the repaired mesh the labels refer to")
        .def_property_readonly(
            "F", [](py::object self) { return faces_view(result_of(self).input.mesh, self); },
            "int32 #F by 3: faces of the repaired mesh (the input's F when it needed no repair)")
        .def_property_readonly(
            "source_face",
            [](py::object self) { return view(result_of(self).input.source_polygon, self); },
            "int32 #F: the row of the input F each face comes from")
        .def_property_readonly(
            "radius", [](const R& r) { return r.seg.radius; }, "scale r used, mesh units")
        .def_property_readonly(
            "scale",
            [](const R& r) -> py::object {
                if (r.params.radius > 0) return py::none();
                return py::float_(r.params.radius_rel);
            },
            "scale r used, a fraction of the largest bounding-box side (the one chosen with "
            "scale='auto'); None when radius was given")
        .def_property_readonly(
            "scale_choice",
            [](const R& r) -> py::object {
                if (!r.scale_choice) return py::none();
                // The JSON report's "scale_choice", as Python values.
                return py::module_::import("json").attr("loads")(
                    scale_choice_json(*r.scale_choice).dump());
            },
            "with scale='auto': how the scale was chosen, as the JSON report's scale_choice "
            "(every scale of the series with its counts, the plateaus, chosen, stable); else None")
        .def_property_readonly(
            "levels",
            [](py::object self) {
                const R& r = result_of(self);
                py::list out;
                for (std::size_t k = 0; k < r.levels.size(); ++k) {
                    const DetailLevel& level = r.levels[k];
                    const Segmentation& s = level_segmentation(r.levels, k, r.seg);
                    py::dict d;
                    d["scale"] = level.radius_rel;
                    d["radius"] = s.radius;
                    d["main"] = level.main;
                    d["num_texels"] = s.texels.size();
                    d["num_textures"] = s.num_textures;
                    d["texel_of_face"] = view(s.face_texel, self);
                    d["texture_of_face"] = view(s.face_texture, self);
                    d["part_of"] = view(level.part_of, self);
                    out.append(d);
                }
                return out;
            },
            "with levels=True: per level of detail, fine to coarse, a dict: scale, radius, main "
            "(the level of this result's own texels), num_texels, num_textures, texel_of_face "
            "and texture_of_face (int32 #F), part_of (int32 #texels: the texel of the next "
            "coarser level each texel lies on, -1 none); else []")
        .def_property_readonly(
            "orientation", [](const R& r) { return name_of(r.mode); },
            "'positive', 'negative' or 'both'")
        .def_property_readonly(
            "texel_of_face",
            [](py::object self) { return view(result_of(self).seg.face_texel, self); },
            "int32 #F: texel id of each face, -1 = background")
        .def_property_readonly(
            "texture_of_face",
            [](py::object self) { return view(result_of(self).seg.face_texture, self); },
            "int32 #F: texture id of each face, -1 = background")
        .def_property_readonly(
            "vertex_depth", [](py::object self) { return depth_of(self, true); },
            "{'positive' and/or 'negative': float64 #V}: oriented depth of each vertex, mesh units "
            "(paper §3.1), per orientation extracted")
        .def_property_readonly(
            "face_depth", [](py::object self) { return depth_of(self, false); },
            "{'positive' and/or 'negative': float64 #F}: mean depth of each face's vertices")
        .def_property_readonly("num_texels", [](const R& r) { return r.seg.texels.size(); })
        .def_property_readonly("num_textures", [](const R& r) { return r.seg.num_textures; })
        .def_property_readonly(
            "feature_names", [](const R& r) { return r.seg.features.names; },
            "the feature ids, in column order (docs/features.md)")
        .def_property_readonly(
            "feature_values",
            [](py::object self) {
                const Eigen::MatrixXd& x = result_of(self).seg.features.values;
                const auto d = static_cast<py::ssize_t>(sizeof(double));
                // Eigen stores it column by column: a Fortran-order view.
                py::array_t<double> a(
                    {static_cast<py::ssize_t>(x.rows()), static_cast<py::ssize_t>(x.cols())},
                    {d, d * x.rows()}, x.data(), self);
                py::detail::array_proxy(a.ptr())->flags &=
                    ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
                return a;
            },
            "float64 #texels by #features (feature_names), NaN where a feature is undefined")
        .def_property_readonly(
            "features",
            [](py::object self) {
                const Segmentation& s = result_of(self).seg;
                const Eigen::MatrixXd& x = s.features.values;
                py::dict out;
                for (std::size_t k = 0; k < s.features.names.size(); ++k)
                    out[py::str(s.features.names[k])] =
                        view(x.data() + k * static_cast<std::size_t>(x.rows()), {x.rows()}, self);
                return out;
            },
            "{feature id: float64 #texels}, the 20 texel features (docs/features.md)")
        .def_property_readonly(
            "texel_texture",
            [](py::object self) { return view(result_of(self).seg.texel_texture, self); },
            "int32 #texels: texture id of each texel")
        .def_property_readonly(
            "texel_faces",
            [](py::object self) {
                py::list out;
                for (const Texel& t : result_of(self).seg.texels) out.append(view(t.faces, self));
                return out;
            },
            "[int32 array of sorted face ids] per texel")
        .def_property_readonly(
            "texel_orientation",
            [](const R& r) {
                std::vector<std::string> out;
                for (const Texel& t : r.seg.texels) out.emplace_back(name_of(t.orientation));
                return out;
            },
            "['positive' or 'negative'] per texel")
        .def_property_readonly(
            "texel_seed",
            [](const R& r) {
                py::array_t<int> out(static_cast<py::ssize_t>(r.seg.texels.size()));
                for (std::size_t i = 0; i < r.seg.texels.size(); ++i)
                    out.mutable_at(i) = r.seg.texels[i].seed;
                return out;
            },
            "int32 #texels: the deepest seed vertex of each texel")
        .def_property_readonly(
            "texel_depth_threshold",
            [](const R& r) {
                py::array_t<double> out(static_cast<py::ssize_t>(r.seg.texels.size()));
                for (std::size_t i = 0; i < r.seg.texels.size(); ++i)
                    out.mutable_at(i) = r.seg.texels[i].threshold;
                return out;
            },
            "float64 #texels: the local Otsu threshold of each texel's seed, mesh units")
        .def_property_readonly(
            "texture_texels",
            [](const R& r) {
                std::vector<std::vector<int>> members(static_cast<std::size_t>(r.seg.num_textures));
                for (std::size_t i = 0; i < r.seg.texel_texture.size(); ++i)
                    members[static_cast<std::size_t>(r.seg.texel_texture[i])].push_back(
                        static_cast<int>(i));
                py::list out;
                for (const auto& t : members)
                    out.append(py::array_t<int>(static_cast<py::ssize_t>(t.size()), t.data()));
                return out;
            },
            "[int32 array of texel ids] per texture")
        .def_property_readonly(
            "texture_orientation",
            [](const R& r) {
                std::vector<std::string> out;
                for (const DetailOrientation o : r.seg.texture_orientation)
                    out.emplace_back(name_of(o));
                return out;
            },
            "['positive' or 'negative'] per texture")
        .def_property_readonly(
            "diagnostics",
            [](const R& r) {
                std::vector<std::pair<std::string, std::string>> out;
                for (const Diagnostics* list : {&r.input.diagnostics, &r.seg.diagnostics})
                    for (const Diagnostic& d : *list) out.emplace_back(d.stage, d.message);
                return out;
            },
            "[(stage, message)]: what the repair and the pipeline noticed (the command's notes)")
        .def_property_readonly(
            "repair",
            [](const R& r) {
                const MeshRepairReport& p = r.input.report;
                py::dict out;
                out["input_vertices"] = p.num_input_vertices;
                out["input_polygons"] = p.num_input_polygons;
                out["polygons_triangulated"] = p.num_polygons_triangulated;
                out["duplicate_vertices_merged"] = p.num_duplicate_vertices_merged;
                out["degenerate_faces_removed"] = p.num_degenerate_faces_removed;
                out["duplicate_faces_removed"] = p.num_duplicate_faces_removed;
                out["faces_flipped"] = p.num_faces_flipped;
                out["isolated_vertices"] = p.num_isolated_vertices;
                out["boundary_edges"] = p.num_boundary_edges;
                out["non_manifold_edges"] = p.num_non_manifold_edges;
                out["components"] = p.num_components;
                out["closed_components"] = p.num_closed_components;
                return out;
            },
            "what the repair of V and F did, as counts (the JSON report's input.repair)")
        .def(
            "to_json",
            [](const R& r) {
                return in_phase(Phase::Processing, {}, [&] {
                    return report_text(segmentation_report(
                        r.seg, r.params, r.report_input(),
                        r.scale_choice ? &*r.scale_choice : nullptr, &r.levels));
                });
            },
            "The JSON report as text: the bytes of `geotex segment --json` for the same mesh and "
            "options. Its \"input\" names the file read, or for arrays \"mesh.ply\" in format "
            "\"ply-binary-le\", with the counts of the arrays and of their repair")
        .def("__repr__", [](const R& r) {
            char radius[32];
            std::snprintf(radius, sizeof radius, "%.6g", r.seg.radius);
            return "<geotex.Segmentation: " + std::to_string(r.seg.texels.size()) + " texels in " +
                   std::to_string(r.seg.num_textures) + " textures, radius " + radius + ", " +
                   name_of(r.mode) + " details>";
        });
}

}  // namespace

void bind_segment(py::module_& m) {
    bind_segmentation_result(m);
    def_segment(
        m, "segment", &segment,
        R"(Finds the texels of a mesh and groups them into textures, as `geotex segment` does
(paper §3), with the same result for the same mesh and options.

V: #V by 3 vertex positions (any real dtype); F: #F by 3 vertex indices (any integer dtype).
They are read once into the library's input and repaired as the command repairs a file
(duplicates merged, degenerate faces removed, faces oriented): the result's V, F and
source_face say what came out. Give exactly one of scale (a fraction of the largest
bounding-box side, in (0, 1); the paper uses 0.04; or "auto", the best stable scale of the
series of `geotex scales`, see scale_choice) or radius (mesh units). levels=True (with
scale="auto"): every stable scale as a level of detail (see levels). The other
keywords are the command's options of the same names (geotex segment --help), with its
defaults. threads: 0 uses every core; the result is the same for any count. tiles=N (not
with scale="auto"): the same segmentation made in N spatial tiles one at a time, in less
memory where r is small beside the object (docs/tiles.md). The work runs without the GIL.

Raises geotex.UsageError (a keyword the command would refuse), geotex.InputError (bad
arrays: shape, dtype, a non-finite coordinate, an index out of range, no face left) or
geotex.ProcessingError.)",
        py::arg("V"), py::arg("F"));
    // annotate_file's segmentation of a file read once, as the command reads it (annotate.cpp).
    def_segment(m, "_segment_file", &segment_file,
                "geotex.segment of the mesh file at path, read as `geotex segment path` reads it: "
                "internal, for geotex.annotate_file.",
                py::arg("path"));
}

}  // namespace geotex::python
