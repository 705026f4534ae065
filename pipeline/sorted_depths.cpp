#include "pipeline/sorted_depths.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <utility>

#include "common/errors.hpp"
#include "pipeline/detail/framed_file.hpp"

namespace geotex {

namespace {

using detail::bits_of;
using detail::Cbor;
using detail::double_of;
constexpr int kSortedDepthsSchema = 1;
const std::string kSortedDepthsMagic = "geotex sorted depths\n";
constexpr const char* kSortedDepthsKind = "sorted depths file";
constexpr int kThresholdsSchema = 1;
const std::string kThresholdsMagic = "geotex seed thresholds\n";
constexpr const char* kThresholdsKind = "seed thresholds file";

// Orientation i's depths read from the file `path` at byte `offset`, a block at a time.
class FileValues final : public SortedValues {
  public:
    FileValues(const std::string& path, std::uint64_t offset, std::uint64_t count)
        : path_(path), in_(path, std::ios::binary), offset_(offset), count_(count) {
        if (!in_) throw IoError("cannot open " + path, path);
        restart();
    }
    std::size_t size() const override { return static_cast<std::size_t>(count_); }
    void restart() override {
        in_.clear();
        in_.seekg(static_cast<std::streamoff>(offset_));
        given_ = 0;
    }
    std::size_t next(double* out, std::size_t max) override {
        const std::size_t n =
            static_cast<std::size_t>(std::min<std::uint64_t>(max, count_ - given_));
        bytes_.resize(8 * n);
        if (n > 0 && !in_.read(reinterpret_cast<char*>(bytes_.data()),
                               static_cast<std::streamsize>(bytes_.size())))
            throw InvalidInput("damaged: the file ends inside its depths", path_);
        for (std::size_t i = 0; i < n; ++i) out[i] = double_of(detail::get_le(&bytes_[8 * i], 8));
        given_ += n;
        return n;
    }
    std::string name() const override { return path_; }

  private:
    std::string path_;
    std::ifstream in_;
    std::uint64_t offset_, count_, given_ = 0;
    std::vector<std::uint8_t> bytes_;
};

}  // namespace

void write_sorted_depths(std::ostream& out, const std::string& key, const TilePart& part) {
    if (!is_depth_pass(part.pass))
        throw InvalidInput(std::string("sorted depths: pass ") + name_of(part.pass) +
                           " is not a depth pass");
    // One orientation sorted at a time: a copy of the tile's depths, not of the mesh's.
    std::vector<std::vector<double>> sorted;
    Cbor counts = Cbor::array(), greatest = Cbor::array();
    for (const std::vector<double>& depths : part.depths) {
        std::vector<double> s = depths;
        double most = 0;
        for (double& d : s) {
            if (!std::isfinite(d))
                throw InvalidInput("sorted depths: tile " + std::to_string(part.tile + 1) +
                                   " has a depth that is not finite");
            if (d == 0) d = 0.0;  // -0.0 as 0.0, as otsu_threshold takes it
            most = std::max(most, d);
        }
        std::sort(s.begin(), s.end());
        counts.push_back(s.size());
        greatest.push_back(bits_of(most));
        sorted.push_back(std::move(s));
    }
    // With the part's counts, so that the join of the outputs, which wants no more of a depth
    // part than these and the greatest depths, reads this header instead of the part.
    const Cbor header = {{"schema", kSortedDepthsSchema},
                         {"key", key},
                         {"pass", name_of(part.pass)},
                         {"tile", part.tile},
                         {"counts", counts},
                         {"greatest", greatest},
                         {"moved", part.moved},
                         {"interpolated", part.interpolated},
                         {"samples", part.samples}};
    detail::write_framed_header(out, kSortedDepthsMagic, header);
    for (const std::vector<double>& s : sorted)
        detail::write_values(out, s.size(), 8, [&](std::size_t i) { return bits_of(s[i]); });
}

SortedDepthsFile::SortedDepthsFile(std::string path, const std::string& key, TilePass pass,
                                   int tile)
    : path_(std::move(path)) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw IoError("cannot open " + path_, path_);
    try {
        const Cbor header = detail::read_framed_header(in, kSortedDepthsMagic, kSortedDepthsKind,
                                                       kSortedDepthsSchema, key);
        if (header.at("pass").get<std::string>() != name_of(pass) ||
            header.at("tile").get<int>() != tile)
            throw InvalidInput("the " + std::string(kSortedDepthsKind) + " of pass " +
                               header.at("pass").get<std::string>() + ", tile " +
                               std::to_string(header.at("tile").get<int>() + 1) + ", not of pass " +
                               name_of(pass) + ", tile " + std::to_string(tile + 1));
        const Cbor& counts = header.at("counts");
        const Cbor& greatest = header.at("greatest");
        if (!counts.is_array() || !greatest.is_array() || counts.size() != greatest.size() ||
            counts.size() > 2)
            throw InvalidInput("damaged: its counts and greatest depths do not match");
        std::uint64_t offset = static_cast<std::uint64_t>(in.tellg()), total = 0;
        for (std::size_t i = 0; i < counts.size(); ++i) {
            const std::uint64_t n = counts[i].get<std::uint64_t>();
            if (n > (std::uint64_t{1} << 40)) throw InvalidInput("damaged: a count is wrong");
            const double g = double_of(greatest[i].get<std::uint64_t>());
            if (!std::isfinite(g) || g < 0)
                throw InvalidInput("damaged: a greatest depth is not a depth");
            counts_.push_back(n);
            offsets_.push_back(offset);
            greatest_.push_back(g);
            offset += 8 * n;
            total += n;
        }
        // Files made before the counts were kept have none: the join then reads the parts.
        if (header.contains("moved")) {
            std::vector<int> moved = header.at("moved").get<std::vector<int>>();
            const int interpolated = header.at("interpolated").get<int>();
            const int samples = header.at("samples").get<int>();
            if (moved.size() != counts_.size() || interpolated < 0 || samples < 0 ||
                std::any_of(moved.begin(), moved.end(), [](int m) { return m < 0; }))
                throw InvalidInput("damaged: its part's counts are wrong");
            summary_ = DepthPartSummary{tile, greatest_, std::move(moved), interpolated, samples};
        }
        detail::expect_bytes_left(in, 8 * total);
    } catch (const InvalidInput& e) {
        throw InvalidInput(e.what(), path_);
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")", path_);
    }
}

std::unique_ptr<SortedValues> SortedDepthsFile::values(std::size_t i) const {
    if (i >= counts_.size())
        throw InvalidInput("the file has the depths of " + std::to_string(counts_.size()) +
                               " orientations, not " + std::to_string(i + 1),
                           path_);
    return std::make_unique<FileValues>(path_, offsets_[i], counts_[i]);
}

void write_seed_thresholds(std::ostream& out, const std::string& key, TilePass texel_pass,
                           const std::vector<double>& thresholds) {
    Cbor bits = Cbor::array();
    for (double t : thresholds) bits.push_back(bits_of(t));
    detail::write_framed_header(out, kThresholdsMagic,
                                {{"schema", kThresholdsSchema},
                                 {"key", key},
                                 {"pass", name_of(texel_pass)},
                                 {"thresholds", bits}});
}

std::vector<double> read_seed_thresholds(std::istream& in, const std::string& key,
                                         TilePass texel_pass, std::size_t orientations) {
    const Cbor header =
        detail::read_framed_header(in, kThresholdsMagic, kThresholdsKind, kThresholdsSchema, key);
    std::vector<double> thresholds;
    try {
        if (header.at("pass").get<std::string>() != name_of(texel_pass))
            throw InvalidInput("the " + std::string(kThresholdsKind) + " of pass " +
                               header.at("pass").get<std::string>() + ", not of pass " +
                               name_of(texel_pass));
        for (const Cbor& bits : header.at("thresholds"))
            thresholds.push_back(double_of(bits.get<std::uint64_t>()));
    } catch (const InvalidInput&) {
        throw;
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    if (thresholds.size() != orientations)
        throw InvalidInput("damaged: " + std::to_string(thresholds.size()) + " thresholds for " +
                           std::to_string(orientations) + " orientations");
    for (double t : thresholds)
        if (!(t >= 0)) throw InvalidInput("damaged: a threshold is not a depth");
    detail::expect_bytes_left(in, 0);
    return thresholds;
}

}  // namespace geotex
