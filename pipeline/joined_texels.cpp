#include "pipeline/joined_texels.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "pipeline/detail/framed_file.hpp"

namespace geotex {

namespace {

using detail::bits_of;
using detail::Cbor;
using detail::double_of;
constexpr int kJoinedSchema = 1;
const std::string kJoinedMagic = "geotex joined texels\n";
constexpr const char* kJoinedKind = "joined texels file";

// Bytes a texel (its list's end, seed, orientation, threshold, mean, spread and greatest
// depth) and a face of one, after the header.
constexpr std::uint64_t kJoinedTexelBytes = 8 + 4 + 1 + 8 + 8 + 8 + 8, kJoinedFaceBytes = 4;

std::uint64_t u32(int x) { return static_cast<std::uint32_t>(x); }

// One orientation's texels as one array after another, each value given by value(texel).
template <class Fn>
void write_per_texel(std::ostream& out, const std::vector<Texel>& texels, std::size_t size,
                     Fn&& value) {
    detail::write_values(out, texels.size(), size,
                         [&](std::size_t t) -> std::uint64_t { return value(texels[t]); });
}

// Each orientation's counts and numbers from the header, checked to fit the file's length.
struct SetHeader {
    std::size_t texels = 0, faces = 0;
    TexelSet numbers;  // all but the texels and face_texel
};

std::vector<SetHeader> read_sets(std::istream& in, const Cbor& header) {
    std::vector<SetHeader> sets;
    try {
        for (const Cbor& c : header.at("sets")) {
            SetHeader s;
            s.texels = c.at("texels").get<std::size_t>();
            s.faces = c.at("faces").get<std::size_t>();
            s.numbers.global_threshold = double_of(c.at("global_threshold").get<std::uint64_t>());
            s.numbers.num_local_maxima = c.at("num_local_maxima").get<int>();
            s.numbers.num_regions = c.at("num_regions").get<int>();
            s.numbers.num_merges = c.at("num_merges").get<int>();
            for (const Cbor& d : c.at("diagnostics"))
                s.numbers.diagnostics.push_back(
                    {d.at(0).get<std::string>(), d.at(1).get<std::string>()});
            sets.push_back(std::move(s));
        }
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    if (sets.size() != 2)
        throw InvalidInput("damaged: the texels of two orientations, not " +
                           std::to_string(sets.size()));
    std::uint64_t bytes = 0;
    for (const SetHeader& s : sets) {
        // Ids are 32-bit; a count past that is a damaged header, not an allocation.
        if (s.texels > static_cast<std::size_t>(INT32_MAX) ||
            s.faces > static_cast<std::size_t>(INT32_MAX) * 64)
            throw InvalidInput("damaged: the counts are out of range");
        bytes += kJoinedTexelBytes * s.texels + kJoinedFaceBytes * s.faces;
    }
    detail::expect_bytes_left(in, bytes);
    return sets;
}

// Reads per-texel values, handing texel t its bits.
template <class Fn>
void read_per_texel(std::istream& in, std::vector<Texel>& texels, std::size_t size, Fn&& take) {
    detail::read_values(in, texels.size(), size,
                        [&](std::size_t t, std::uint64_t bits) { take(texels[t], bits); });
}

TexelSet read_set(std::istream& in, SetHeader s, std::vector<double>& depth) {
    TexelSet out = std::move(s.numbers);
    std::vector<Texel>& texels = out.texels;
    texels.resize(s.texels);
    std::uint64_t begin = 0;
    read_per_texel(in, texels, 8, [&](Texel& t, std::uint64_t end) {
        if (end <= begin || end > s.faces)
            throw InvalidInput("damaged: a texel's list of faces is empty or out of order");
        t.faces.resize(end - begin);
        begin = end;
    });
    if (begin != s.faces) throw InvalidInput("damaged: faces past the last texel's");
    // The faces, one array over every texel: a cursor walks the texels as they are read.
    std::size_t t = 0, k = 0;
    detail::read_values(in, s.faces, kJoinedFaceBytes, [&](std::size_t, std::uint64_t bits) {
        while (k == texels[t].faces.size()) ++t, k = 0;
        std::vector<int>& faces = texels[t].faces;
        if (bits > static_cast<std::uint64_t>(INT32_MAX) ||
            (k > 0 && static_cast<int>(bits) <= faces[k - 1]))
            throw InvalidInput("damaged: the faces of texel " + std::to_string(t) +
                               " do not ascend");
        faces[k++] = static_cast<int>(bits);
    });
    read_per_texel(in, texels, 4, [](Texel& x, std::uint64_t bits) {
        x.seed = static_cast<int>(static_cast<std::uint32_t>(bits));
    });
    read_per_texel(in, texels, 1, [](Texel& x, std::uint64_t bits) {
        if (bits > 1) throw InvalidInput("damaged: a texel's orientation is not one");
        x.orientation = bits == 0 ? DetailOrientation::Positive : DetailOrientation::Negative;
    });
    read_per_texel(in, texels, 8,
                   [](Texel& x, std::uint64_t bits) { x.threshold = double_of(bits); });
    read_per_texel(in, texels, 8,
                   [](Texel& x, std::uint64_t bits) { x.depth_mean = double_of(bits); });
    read_per_texel(in, texels, 8,
                   [](Texel& x, std::uint64_t bits) { x.depth_std = double_of(bits); });
    depth.resize(s.texels);
    detail::read_values(in, s.texels, 8,
                        [&](std::size_t i, std::uint64_t bits) { depth[i] = double_of(bits); });
    return out;
}

}  // namespace

void write_joined_texels(std::ostream& out, const std::string& key, TilePass texel_pass,
                         const JoinedTexels& joined) {
    if (!is_texel_pass(texel_pass))
        throw InvalidInput(std::string("tiles: joined texels of pass ") + name_of(texel_pass) +
                           ", not of a texel pass");
    Cbor sets = Cbor::array();
    for (std::size_t o = 0; o < 2; ++o) {
        const TexelSet& set = joined.texels[o];
        if (joined.depth[o].size() != set.texels.size())
            throw InvalidInput("tiles: the joined texels' depths are not one a texel");
        std::size_t faces = 0;
        for (const Texel& t : set.texels) faces += t.faces.size();
        Cbor diagnostics = Cbor::array();
        for (const Diagnostic& d : set.diagnostics) diagnostics.push_back({d.stage, d.message});
        sets.push_back({{"texels", set.texels.size()},
                        {"faces", faces},
                        {"global_threshold", bits_of(set.global_threshold)},
                        {"num_local_maxima", set.num_local_maxima},
                        {"num_regions", set.num_regions},
                        {"num_merges", set.num_merges},
                        {"diagnostics", diagnostics}});
    }
    detail::write_framed_header(
        out, kJoinedMagic,
        {{"schema", kJoinedSchema}, {"key", key}, {"pass", name_of(texel_pass)}, {"sets", sets}});
    for (std::size_t o = 0; o < 2; ++o) {
        const std::vector<Texel>& texels = joined.texels[o].texels;
        std::uint64_t end = 0;
        write_per_texel(out, texels, 8, [&](const Texel& t) { return end += t.faces.size(); });
        std::size_t t = 0, k = 0;
        detail::write_values(out, static_cast<std::size_t>(end), kJoinedFaceBytes,
                             [&](std::size_t) {
                                 while (k == texels[t].faces.size()) ++t, k = 0;
                                 return u32(texels[t].faces[k++]);
                             });
        write_per_texel(out, texels, 4, [](const Texel& x) { return u32(x.seed); });
        write_per_texel(out, texels, 1, [](const Texel& x) -> std::uint64_t {
            return x.orientation == DetailOrientation::Positive ? 0 : 1;
        });
        write_per_texel(out, texels, 8, [](const Texel& x) { return bits_of(x.threshold); });
        write_per_texel(out, texels, 8, [](const Texel& x) { return bits_of(x.depth_mean); });
        write_per_texel(out, texels, 8, [](const Texel& x) { return bits_of(x.depth_std); });
        const std::vector<double>& depth = joined.depth[o];
        detail::write_values(out, depth.size(), 8,
                             [&](std::size_t i) { return bits_of(depth[i]); });
    }
}

JoinedTexels read_joined_texels(std::istream& in, const std::string& key, TilePass texel_pass) {
    const Cbor header =
        detail::read_framed_header(in, kJoinedMagic, kJoinedKind, kJoinedSchema, key);
    std::string pass;
    try {
        pass = header.at("pass").get<std::string>();
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    if (pass != name_of(texel_pass))
        throw InvalidInput("the joined texels of pass " + pass + ", not of pass " +
                           name_of(texel_pass));
    std::vector<SetHeader> sets = read_sets(in, header);
    JoinedTexels out;
    for (std::size_t o = 0; o < 2; ++o)
        out.texels[o] = read_set(in, std::move(sets[o]), out.depth[o]);
    return out;
}

}  // namespace geotex
