#include "cli/description_options.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/output.hpp"
#include "common/detail/text.hpp"

namespace geotex::cli {

void add_description_options(CLI::App& sub, DescriptionParams& p) {
    sub.add_option("--concepts", p.max_concepts,
                   "At most N concepts per texture, the most significant first (0: one per facet "
                   "of the dictionary, "
                   "no other limit)")
        ->check(CLI::Range(0, 20));
    // CLI::Range accepts NaN (every comparison with it is false): these checks refuse it.
    const auto in_range = [](double lo, bool lo_open, double hi) {
        return CLI::Validator(
            [=](std::string& text) {
                double v = 0;
                try {
                    v = std::stod(text);
                } catch (...) {
                    return std::string("not a number: ") + text;
                }
                const bool ok = (lo_open ? v > lo : v >= lo) && v <= hi;
                char buf[96];
                std::snprintf(buf, sizeof buf, "%s not in %s%g, %g]", text.c_str(),
                              lo_open ? "(" : "[", lo, hi);
                return ok ? std::string() : std::string(buf);
            },
            "FLOAT");
    };
    sub.add_option("--max-significance", p.max_significance,
                   "A feature names a texture only when its significance S (spread over the "
                   "texture / spread over "
                   "all texels, paper section 4.3) is at most this (0: no such test)")
        ->check(in_range(0, false, 1e9));
    sub.add_option("--min-agreement", p.min_agreement,
                   "A concept names a texture only when it holds for at least this share of its "
                   "texels' own values")
        ->check(in_range(0, true, 1));
    sub.add_option("--min-stability", p.min_stability,
                   "A concept is asserted only when at least this share of the bootstrap resamples "
                   "of the texels "
                   "choose it too; the others are reported as withheld")
        ->check(in_range(0, false, 1));
    sub.add_option("--resamples", p.num_resamples,
                   "Bootstrap resamples of the texels (0: no stability test)")
        ->check(CLI::Range(0, 100000));
}

std::string description_params_text(const DescriptionParams& p) {
    char buf[192];
    std::snprintf(
        buf, sizeof buf,
        "concepts=%d max-significance=%.17g min-agreement=%.17g min-stability=%.17g resamples=%d",
        p.max_concepts, p.max_significance, p.min_agreement, p.min_stability, p.num_resamples);
    return buf;
}

MeshUnit checked_mesh_unit(const std::string& text) {
    if (text.empty()) return MeshUnit::Unknown;
    if (const auto unit = parse_mesh_unit(text)) return *unit;
    throw CliError(kExitUsage, "--mesh-unit: '" + detail::printable(text.substr(0, 40)) +
                                   "' is not a unit: mm, cm, m or in");
}

}  // namespace geotex::cli
