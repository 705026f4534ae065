#include "pipeline/tile_parts.hpp"

#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <type_traits>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "common/release.hpp"
#include "pipeline/detail/little_endian.hpp"
#include "pipeline/geometry_cache.hpp"

namespace geotex {

namespace {

using Cbor = nlohmann::json;  // CBOR through the library's binary writer and reader
using Bytes = Cbor::binary_t;
constexpr int kPartSchema = 2;  // 2: texel parts carry their regions' depths
constexpr const char* kFormat = "geotex tile part";

// Numbers as a byte string, each little-endian (detail/little_endian.hpp). nlohmann_json has
// byte strings, not typed arrays (CBOR's typed arrays of RFC 8746 are not read by it), hence
// the packing by hand.
template <class T>
Bytes pack(const std::vector<T>& values) {
    static_assert(std::is_arithmetic_v<T>);
    std::vector<std::uint8_t> out(values.size() * sizeof(T));
    for (std::size_t i = 0; i < values.size(); ++i) {
        std::uint64_t bits = 0;
        if constexpr (std::is_floating_point_v<T>) {
            static_assert(sizeof(T) == 8);
            bits = detail::bits_of(values[i]);
        } else {
            bits = static_cast<std::uint64_t>(static_cast<std::make_unsigned_t<T>>(values[i]));
        }
        detail::put_le(&out[i * sizeof(T)], bits, sizeof(T));
    }
    return Bytes(std::move(out));
}

// The bytes of a byte string of values of type T.
template <class T>
const std::vector<std::uint8_t>& values_of(const Cbor& value) {
    if (!value.is_binary()) throw std::out_of_range("an array is not a byte string");
    const std::vector<std::uint8_t>& in = value.get_binary();
    if (in.size() % sizeof(T) != 0) throw std::out_of_range("an array has a partial value");
    return in;
}

// Values [first, last) of a byte string's values.
template <class T>
std::vector<T> unpack_range(const std::vector<std::uint8_t>& in, std::size_t first,
                            std::size_t last) {
    std::vector<T> out(last - first);
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::uint64_t bits = detail::get_le(&in[(first + i) * sizeof(T)], sizeof(T));
        if constexpr (std::is_floating_point_v<T>) {
            out[i] = detail::double_of(bits);
        } else {
            out[i] = static_cast<T>(static_cast<std::make_unsigned_t<T>>(bits));
        }
    }
    return out;
}

template <class T>
std::vector<T> unpack(const Cbor& value) {
    const std::vector<std::uint8_t>& in = values_of<T>(value);
    return unpack_range<T>(in, 0, in.size() / sizeof(T));
}

// Lists of lists as the concatenation and each list's end.
template <class T, class Fn>
void pack_lists(Cbor& c, const char* name, std::size_t count, Fn&& list_of) {
    std::vector<T> all;
    std::vector<std::int64_t> ends;
    for (std::size_t i = 0; i < count; ++i) {
        const std::vector<T>& list = list_of(i);
        all.insert(all.end(), list.begin(), list.end());
        ends.push_back(static_cast<std::int64_t>(all.size()));
    }
    c[name] = {{"values", pack(all)}, {"ends", pack(ends)}};
}

// Each list unpacked from the byte string itself, not from a copy of all the values: a texel
// part's region faces are tens of megabytes at level 11.
template <class T>
std::vector<std::vector<T>> unpack_lists(const Cbor& c) {
    const std::vector<std::uint8_t>& all = values_of<T>(c.at("values"));
    const auto count = static_cast<std::int64_t>(all.size() / sizeof(T));
    const std::vector<std::int64_t> ends = unpack<std::int64_t>(c.at("ends"));
    std::vector<std::vector<T>> out(ends.size());
    std::int64_t begin = 0;
    for (std::size_t i = 0; i < ends.size(); ++i) {
        if (ends[i] < begin || ends[i] > count)
            throw std::out_of_range("a list's end is out of order");
        out[i] = unpack_range<T>(all, static_cast<std::size_t>(begin),
                                 static_cast<std::size_t>(ends[i]));
        begin = ends[i];
    }
    if (begin != count) throw std::out_of_range("values past the last list");
    return out;
}

Cbor regions_cbor(const TexelRegions& r, const RegionDepths& depths) {
    const std::size_t n = r.regions.size();
    std::vector<int> seeds;
    std::vector<double> threshold, mean, spread;
    for (const TexelRegion& region : r.regions) {
        seeds.push_back(region.seed);
        threshold.push_back(region.threshold);
        mean.push_back(region.mean);
        spread.push_back(region.std);
    }
    Cbor c = {{"num_seeds", r.num_seeds},
              {"seeds", pack(seeds)},
              {"threshold", pack(threshold)},
              {"mean", pack(mean)},
              {"std", pack(spread)},
              {"seed_depth", pack(depths.seed)},
              {"face_depth", pack(depths.face)},
              {"face_peak", pack(depths.peak)}};
    pack_lists<int>(
        c, "faces", n, [&](std::size_t i) -> auto& { return r.regions[i].faces; });
    pack_lists<int>(
        c, "touch", n, [&](std::size_t i) -> auto& { return r.regions[i].touch; });
    return c;
}

// The value `name` of `c`, which is then dropped from it: a texel part's lists and depths
// are each freed once unpacked, so that the part is not held twice while it is read.
template <class T>
std::vector<T> take(Cbor& c, const char* name) {
    Cbor& value = c.at(name);
    std::vector<T> out = unpack<T>(value);
    value = nullptr;
    return out;
}
template <class T>
std::vector<std::vector<T>> take_lists(Cbor& c, const char* name) {
    Cbor& value = c.at(name);
    std::vector<std::vector<T>> out = unpack_lists<T>(value);
    value = nullptr;
    return out;
}

TexelRegions regions_from(Cbor& c, RegionDepths& depths) {
    TexelRegions r;
    depths.seed = take<double>(c, "seed_depth");
    depths.face = take<double>(c, "face_depth");
    depths.peak = take<double>(c, "face_peak");
    r.num_seeds = c.at("num_seeds").get<int>();
    const auto seeds = take<int>(c, "seeds");
    const auto threshold = take<double>(c, "threshold");
    const auto mean = take<double>(c, "mean");
    const auto spread = take<double>(c, "std");
    auto faces = take_lists<int>(c, "faces");
    auto touch = take_lists<int>(c, "touch");
    const std::size_t n = seeds.size();
    if (threshold.size() != n || mean.size() != n || spread.size() != n || faces.size() != n ||
        touch.size() != n)
        throw std::out_of_range("the regions' lists differ in length");
    r.regions.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        r.regions[i] = {seeds[i],  threshold[i],        mean[i],
                        spread[i], std::move(faces[i]), std::move(touch[i])};
    return r;
}

std::vector<char> flags_from(const Cbor& c) { return unpack<char>(c); }

}  // namespace

std::string tile_run_key(const std::string& mesh_sha256, const SegmentationParams& params,
                         int tiles) {
    return sha256_hex(geometry_cache_key(mesh_sha256, params) + "\ntiles " + std::to_string(tiles));
}

void write_tile_part(std::ostream& out, const std::string& key, const TilePart& part) {
    Cbor c;
    c["format"] = kFormat;
    c["schema"] = kPartSchema;
    c["key"] = key;
    c["pass"] = name_of(part.pass);
    c["tile"] = part.tile + 1;
    switch (part.pass) {
        case TilePass::Depth:
        case TilePass::DepthWithoutRims: {
            c["vertices"] = pack(part.vertices);
            Cbor depths = Cbor::array();
            for (const auto& d : part.depths) depths.push_back(pack(d));
            c["depths"] = depths;
            c["moved"] = part.moved;
            c["interpolated"] = part.interpolated;
            c["samples"] = part.samples;
            break;
        }
        case TilePass::Texels:
        case TilePass::TexelsWithoutRims: {
            if (part.region_depths.size() != part.regions.size())
                throw InvalidInput("tiles: a texel part without its regions' depths");
            Cbor regions = Cbor::array();
            for (std::size_t i = 0; i < part.regions.size(); ++i)
                regions.push_back(regions_cbor(part.regions[i], part.region_depths[i]));
            c["regions"] = regions;
            c["thresholds"] = pack(part.thresholds);
            break;
        }
        case TilePass::Rims:
            c["positive_rim"] = pack(part.rims.positive_rim);
            c["negative_rim"] = pack(part.rims.negative_rim);
            c["positive_makes_rim"] = pack(part.rims.positive_makes_rim);
            c["negative_makes_rim"] = pack(part.rims.negative_makes_rim);
            break;
        case TilePass::Features: {
            c["texels"] = pack(part.texels);
            const Eigen::MatrixXd& v = part.rows.values;
            std::vector<double> values;  // row-major: a texel's row after another
            for (Eigen::Index i = 0; i < v.rows(); ++i)
                for (Eigen::Index j = 0; j < v.cols(); ++j) values.push_back(v(i, j));
            c["columns"] = v.cols();
            c["values"] = pack(values);
            const auto& d = part.rows.diameters;
            std::vector<std::vector<double>> value(d.size()), weight(d.size());
            for (std::size_t t = 0; t < d.size(); ++t)
                for (const auto& x : d[t]) {
                    value[t].push_back(x.value);
                    weight[t].push_back(x.weight);
                }
            pack_lists<double>(
                c, "diameter_values", d.size(), [&](std::size_t t) -> auto& { return value[t]; });
            pack_lists<double>(
                c, "diameter_weights", d.size(), [&](std::size_t t) -> auto& { return weight[t]; });
            c["no_contour"] = pack(part.rows.no_contour);
            c["no_curvature"] = pack(part.rows.no_curvature);
            c["curvature_vertices"] = pack(part.curvature_vertices);
            c["gaussian"] = pack(part.curvature.gaussian);
            c["mean"] = pack(part.curvature.mean);
            c["shape_index"] = pack(part.curvature.shape_index);
            c["curvedness"] = pack(part.curvature.curvedness);
            break;
        }
        case TilePass::Done:
            throw InvalidInput("tiles: no part of the pass done");
    }
    const std::vector<std::uint8_t> bytes = Cbor::to_cbor(c);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

TilePart read_tile_part(std::string bytes, const std::string& key, TilePass pass, int tile) {
    const auto refuse = [](const std::string& what) { throw InvalidInput(what); };
    // Parsed as Cbor::from_cbor parses, with the same parser, but into `c` itself: from_cbor
    // returns its result through `ok ? result : discarded`, which copies the whole part (the
    // largest texel part of level 10 in 16 tiles: 23 MB) while the original and the bytes are
    // still held.
    Cbor c;
    bool parsed = false;  // the parser throws on an error, as from_cbor's does: kept as a guard
    try {
        nlohmann::detail::json_sax_dom_parser<Cbor> dom(c, true);
        parsed = Cbor::sax_parse(bytes.begin(), bytes.end(), &dom, Cbor::input_format_t::cbor);
    } catch (const std::exception& e) {
        refuse(std::string("not a geotex tile part (") + e.what() + ")");
    }
    if (!parsed) refuse("not a geotex tile part");
    release(bytes);  // parsed: not held beside what is unpacked from it
    TilePart part;
    try {
        if (!c.is_object() || c.value("format", "") != kFormat) refuse("not a geotex tile part");
        if (c.at("schema").get<int>() != kPartSchema)
            refuse("a tile part of schema " + c.at("schema").dump() + ", not " +
                   std::to_string(kPartSchema) + " (made by another geotex)");
        if (c.at("key").get<std::string>() != key)
            refuse(
                "a part of another run: another mesh, other options, another number of "
                "tiles or another geotex");
        const std::string name = c.at("pass").get<std::string>();
        if (name != name_of(pass)) refuse("a part of pass " + name + ", not " + name_of(pass));
        const int number = c.at("tile").get<int>();
        if (number != tile + 1)
            refuse("the part of tile " + std::to_string(number) + ", not " +
                   std::to_string(tile + 1));
        part.pass = pass;
        part.tile = tile;
        switch (pass) {
            case TilePass::Depth:
            case TilePass::DepthWithoutRims:
                part.vertices = take<int>(c, "vertices");
                for (auto& d : c.at("depths")) {
                    part.depths.push_back(unpack<double>(d));
                    d = nullptr;
                }
                part.moved = c.at("moved").get<std::vector<int>>();
                part.interpolated = c.at("interpolated").get<int>();
                part.samples = c.at("samples").get<int>();
                break;
            case TilePass::Texels:
            case TilePass::TexelsWithoutRims:
                for (auto& r : c.at("regions"))
                    part.regions.push_back(regions_from(r, part.region_depths.emplace_back()));
                part.thresholds = unpack<double>(c.at("thresholds"));
                break;
            case TilePass::Rims:
                part.rims.positive_rim = flags_from(c.at("positive_rim"));
                part.rims.negative_rim = flags_from(c.at("negative_rim"));
                part.rims.positive_makes_rim = flags_from(c.at("positive_makes_rim"));
                part.rims.negative_makes_rim = flags_from(c.at("negative_makes_rim"));
                break;
            case TilePass::Features: {
                part.texels = unpack<int>(c.at("texels"));
                const auto values = unpack<double>(c.at("values"));
                const auto columns = c.at("columns").get<Eigen::Index>();
                const auto rows = static_cast<Eigen::Index>(part.texels.size());
                if (columns < 0 || static_cast<Eigen::Index>(values.size()) != rows * columns)
                    refuse("damaged: the feature rows are not one per texel");
                part.rows.values.resize(rows, columns);
                for (Eigen::Index i = 0; i < rows; ++i)
                    for (Eigen::Index j = 0; j < columns; ++j)
                        part.rows.values(i, j) = values[static_cast<std::size_t>(i * columns + j)];
                const auto value = unpack_lists<double>(c.at("diameter_values"));
                const auto weight = unpack_lists<double>(c.at("diameter_weights"));
                if (value.size() != weight.size())
                    refuse("damaged: the diameters' values and weights differ in number");
                part.rows.diameters.resize(value.size());
                for (std::size_t t = 0; t < value.size(); ++t) {
                    if (value[t].size() != weight[t].size())
                        refuse("damaged: the diameters' values and weights differ in number");
                    for (std::size_t k = 0; k < value[t].size(); ++k)
                        part.rows.diameters[t].push_back({value[t][k], weight[t][k]});
                }
                part.rows.no_contour = flags_from(c.at("no_contour"));
                part.rows.no_curvature = flags_from(c.at("no_curvature"));
                part.curvature_vertices = unpack<int>(c.at("curvature_vertices"));
                part.curvature.gaussian = unpack<double>(c.at("gaussian"));
                part.curvature.mean = unpack<double>(c.at("mean"));
                part.curvature.shape_index = unpack<double>(c.at("shape_index"));
                part.curvature.curvedness = unpack<double>(c.at("curvedness"));
                break;
            }
            case TilePass::Done:
                refuse("no part of the pass done");
        }
    } catch (const InvalidInput&) {
        throw;
    } catch (const std::exception& e) {
        refuse(std::string("damaged (") + e.what() + ")");
    }
    return part;
}

}  // namespace geotex
