#include "pipeline/geometry_cache.hpp"

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/topology.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/parameters_json.hpp"

namespace geotex {

namespace {

using Cbor = nlohmann::json;  // CBOR through the library's binary writer and reader
constexpr int kSchema = 2;    // 2: 20 feature columns (area_rel, bounding_sphere_radius_rel)

Cbor diagnostics_cbor(const Diagnostics& diagnostics) {
    Cbor a = Cbor::array();
    for (const auto& d : diagnostics) a.push_back({d.stage, d.message});
    return a;
}

Diagnostics diagnostics_from(const Cbor& a) {
    Diagnostics out;
    for (const auto& d : a.at("d"))
        out.push_back({d.at(0).get<std::string>(), d.at(1).get<std::string>()});
    return out;
}

DetailOrientation orientation_from(const Cbor& v) {
    const int o = v.get<int>();
    if (o != 0 && o != 1) throw std::out_of_range("orientation " + std::to_string(o));
    return o == 0 ? DetailOrientation::Positive : DetailOrientation::Negative;
}

int orientation_code(DetailOrientation o) { return o == DetailOrientation::Positive ? 0 : 1; }

/// The cache's content checked against the mesh: every index in range, faces of texels
/// disjoint, sizes consistent. Throws std::out_of_range with what is wrong.
Segmentation segmentation_from(const Cbor& c, const Mesh& mesh) {
    const int nf = mesh.num_faces();
    if (c.at("faces").get<int>() != nf || c.at("vertices").get<int>() != mesh.num_vertices())
        throw std::out_of_range("made for a mesh of another size");
    Segmentation seg;
    seg.radius = c.at("radius").get<double>();
    seg.num_interpolated_vertices = c.at("interpolated").get<int>();
    seg.num_disc_samples = c.at("disc_samples").get<int>();
    seg.topology = make_topology(mesh);
    seg.metrics = make_mesh_metrics(mesh, seg.topology);
    for (const auto& r : c.at("runs")) {
        DepthMap depth;
        depth.orientation = orientation_from(r.at("orientation"));
        depth.max_depth = r.at("max_depth").get<double>();
        depth.num_moved_vertices = r.at("moved").get<int>();
        seg.runs.push_back(depth.orientation);
        seg.run_excluded_texels.push_back(r.at("excluded").get<int>());
        (depth.orientation == DetailOrientation::Positive ? seg.positive_depth
                                                          : seg.negative_depth) = depth;
        TexelSet set;
        set.global_threshold = r.at("threshold").get<double>();
        set.num_local_maxima = r.at("seeds").get<int>();
        set.num_regions = r.at("regions").get<int>();
        set.num_merges = r.at("merges").get<int>();
        set.diagnostics = diagnostics_from(r);
        seg.texel_sets.push_back(std::move(set));
        const Cbor& k = r.at("clustering");
        ClusteringResult clustering;
        clustering.labels = k.at("labels").get<std::vector<int>>();
        clustering.num_clusters = k.at("k").get<int>();
        clustering.quality = k.at("quality").get<std::vector<double>>();
        clustering.conductance = k.at("conductance").get<std::vector<double>>();
        clustering.diagnostics = diagnostics_from(k);
        seg.clusterings.push_back(std::move(clustering));
    }
    if (seg.runs.size() > 2 || (seg.runs.size() == 2 && seg.runs[0] == seg.runs[1]))
        throw std::out_of_range("orientations of the runs");

    seg.face_texel.assign(static_cast<std::size_t>(nf), -1);
    for (const auto& t : c.at("texels")) {
        Texel texel;
        texel.faces = t.at("faces").get<std::vector<int>>();
        texel.seed = t.at("seed").get<int>();
        texel.orientation = orientation_from(t.at("orientation"));
        texel.threshold = t.at("threshold").get<double>();
        texel.depth_mean = t.at("mean").get<double>();
        texel.depth_std = t.at("std").get<double>();
        const int id = static_cast<int>(seg.texels.size());
        for (int f : texel.faces) {
            if (f < 0 || f >= nf || seg.face_texel[static_cast<std::size_t>(f)] != -1)
                throw std::out_of_range("texel " + std::to_string(id) + " face " +
                                        std::to_string(f));
            seg.face_texel[static_cast<std::size_t>(f)] = id;
        }
        if (texel.seed < -1 || texel.seed >= mesh.num_vertices())
            throw std::out_of_range("texel " + std::to_string(id) + " seed");
        seg.texels.push_back(std::move(texel));
    }
    const std::size_t num_texels = seg.texels.size();

    const Cbor& features = c.at("features");
    seg.features.names = features.at("names").get<std::vector<std::string>>();
    const auto values = features.at("values").get<std::vector<double>>();
    const std::size_t cols = seg.features.names.size();
    if (values.size() != num_texels * cols) throw std::out_of_range("feature table size");
    seg.features.values.resize(static_cast<Eigen::Index>(num_texels),
                               static_cast<Eigen::Index>(cols));
    for (std::size_t i = 0; i < num_texels; ++i)
        for (std::size_t j = 0; j < cols; ++j)
            seg.features.values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                values[i * cols + j];
    seg.features.diagnostics = diagnostics_from(features);

    seg.num_textures = c.at("num_textures").get<int>();
    for (const auto& o : c.at("texture_orientation"))
        seg.texture_orientation.push_back(orientation_from(o));
    seg.texel_texture = c.at("texel_texture").get<std::vector<int>>();
    if (seg.num_textures < 0 ||
        seg.texture_orientation.size() != static_cast<std::size_t>(seg.num_textures) ||
        seg.texel_texture.size() != num_texels)
        throw std::out_of_range("texture table size");
    seg.face_texture.assign(static_cast<std::size_t>(nf), -1);
    for (std::size_t i = 0; i < num_texels; ++i) {
        const int k = seg.texel_texture[i];
        if (k < 0 || k >= seg.num_textures)
            throw std::out_of_range("texture of texel " + std::to_string(i));
        for (int f : seg.texels[i].faces) seg.face_texture[static_cast<std::size_t>(f)] = k;
    }
    seg.diagnostics = diagnostics_from(c);
    return seg;
}

}  // namespace

std::string geometry_cache_key(const std::string& mesh_sha256, const SegmentationParams& params) {
    // The report's parameters, and the clustering's thresholds that no option sets but a
    // library caller may: they change the textures, so they are in the key too.
    nlohmann::ordered_json all = parameters_json(params, params.radius);
    all["quality_tolerance"] = params.clustering.quality_tolerance;
    all["min_quality"] = params.clustering.min_quality;
    all["max_conductance"] = params.clustering.max_conductance;
    return sha256_hex(std::string("geotex ") + version() + "\n" + mesh_sha256 + "\n" + all.dump());
}

void write_geometry_cache(std::ostream& out, const std::string& key, const Segmentation& seg) {
    Cbor c;
    c["format"] = "geotex geometry cache";
    c["schema"] = kSchema;
    c["key"] = key;
    c["faces"] = seg.face_texel.size();
    c["vertices"] = seg.metrics.num_vertices;
    c["radius"] = seg.radius;
    c["interpolated"] = seg.num_interpolated_vertices;
    c["disc_samples"] = seg.num_disc_samples;
    Cbor runs = Cbor::array();
    for (std::size_t r = 0; r < seg.runs.size(); ++r) {
        const DepthMap& d =
            seg.runs[r] == DetailOrientation::Positive ? *seg.positive_depth : *seg.negative_depth;
        const TexelSet& set = seg.texel_sets[r];
        const ClusteringResult& k = seg.clusterings[r];
        runs.push_back(
            {{"orientation", orientation_code(seg.runs[r])},
             {"max_depth", d.max_depth},
             {"moved", d.num_moved_vertices},
             {"threshold", set.global_threshold},
             {"seeds", set.num_local_maxima},
             {"regions", set.num_regions},
             {"merges", set.num_merges},
             {"excluded", seg.run_excluded_texels.empty() ? 0 : seg.run_excluded_texels[r]},
             {"d", diagnostics_cbor(set.diagnostics)},
             {"clustering",
              {{"labels", k.labels},
               {"k", k.num_clusters},
               {"quality", k.quality},
               {"conductance", k.conductance},
               {"d", diagnostics_cbor(k.diagnostics)}}}});
    }
    c["runs"] = runs;
    Cbor texels = Cbor::array();
    for (const Texel& t : seg.texels)
        texels.push_back({{"faces", t.faces},
                          {"seed", t.seed},
                          {"orientation", orientation_code(t.orientation)},
                          {"threshold", t.threshold},
                          {"mean", t.depth_mean},
                          {"std", t.depth_std}});
    c["texels"] = texels;
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(seg.features.values.size()));
    for (Eigen::Index i = 0; i < seg.features.values.rows(); ++i)
        for (Eigen::Index j = 0; j < seg.features.values.cols(); ++j)
            values.push_back(seg.features.values(i, j));
    c["features"] = {{"names", seg.features.names},
                     {"values", values},
                     {"d", diagnostics_cbor(seg.features.diagnostics)}};
    c["num_textures"] = seg.num_textures;
    Cbor orientations = Cbor::array();
    for (auto o : seg.texture_orientation) orientations.push_back(orientation_code(o));
    c["texture_orientation"] = orientations;
    c["texel_texture"] = seg.texel_texture;
    c["d"] = diagnostics_cbor(seg.diagnostics);
    const std::vector<std::uint8_t> bytes = Cbor::to_cbor(c);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

GeometryCacheRead read_geometry_cache(const std::string& path, const std::string& key,
                                      const Mesh& mesh) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                          std::istreambuf_iterator<char>()};
    try {
        const Cbor c = Cbor::from_cbor(bytes);
        if (c.at("format").get<std::string>() != "geotex geometry cache" ||
            c.at("schema").get<int>() != kSchema)
            return {std::nullopt,
                    "not a geotex geometry cache of schema " + std::to_string(kSchema)};
        if (c.at("key").get<std::string>() != key)
            return {std::nullopt,
                    "made from another mesh, other parameters or another geotex version"};
        return {segmentation_from(c, mesh), {}};
    } catch (const std::exception& e) {
        return {std::nullopt, std::string("unreadable (") + e.what() + ")"};
    }
}

GeometryTables read_geometry_tables(std::string_view bytes) {
    const auto refuse = [](const std::string& what) {
        throw InvalidInput("geometry cache: " + what);
    };
    GeometryTables t;
    try {
        const Cbor c = Cbor::from_cbor(bytes.begin(), bytes.end());
        if (c.at("format").get<std::string>() != "geotex geometry cache" ||
            c.at("schema").get<int>() != kSchema)
            refuse("not a geotex geometry cache of schema " + std::to_string(kSchema));
        t.key = c.at("key").get<std::string>();
        const Cbor& features = c.at("features");
        const auto names = features.at("names").get<std::vector<std::string>>();
        if (names.size() != static_cast<std::size_t>(kNumFeatures))
            refuse("its " + std::to_string(names.size()) +
                   " feature columns are not this geotex's " + std::to_string(kNumFeatures));
        for (int j = 0; j < kNumFeatures; ++j)
            if (names[static_cast<std::size_t>(j)] != kFeatureIds[j])
                refuse("feature column " + std::to_string(j + 1) + " is '" +
                       names[static_cast<std::size_t>(j)] + "', not '" + kFeatureIds[j] + "'");
        t.texel_texture = c.at("texel_texture").get<std::vector<int>>();
        const std::size_t num_texels = t.texel_texture.size();
        if (c.at("texels").size() != num_texels) refuse("texel_texture is not one entry per texel");
        const auto values = features.at("values").get<std::vector<double>>();
        if (values.size() != num_texels * names.size()) refuse("feature table size");
        t.features.resize(static_cast<Eigen::Index>(num_texels), kNumFeatures);
        for (std::size_t i = 0; i < num_texels; ++i)
            for (std::size_t j = 0; j < names.size(); ++j)
                t.features(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                    values[i * names.size() + j];
        t.num_textures = c.at("num_textures").get<int>();
        for (const auto& o : c.at("texture_orientation"))
            t.texture_orientation.push_back(orientation_from(o));
        if (t.num_textures < 0 ||
            t.texture_orientation.size() != static_cast<std::size_t>(t.num_textures))
            refuse("texture_orientation is not one entry per texture");
        for (std::size_t i = 0; i < num_texels; ++i)
            if (t.texel_texture[i] < 0 || t.texel_texture[i] >= t.num_textures)
                refuse("texture of texel " + std::to_string(i) + " out of range");
    } catch (const InvalidInput&) {
        throw;
    } catch (const std::exception& e) {
        refuse(std::string("unreadable (") + e.what() + ")");
    }
    return t;
}

}  // namespace geotex
