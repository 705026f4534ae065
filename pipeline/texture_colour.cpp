#include "pipeline/texture_colour.hpp"

#include <cmath>
#include <cstdio>

namespace geotex {

std::array<unsigned char, 3> texture_colour(int id) {
    if (id < 0) return {170, 170, 170};
    // Distinct, colour-blind-aware first choices (blue, orange, green, red, ...).
    static const std::array<std::array<unsigned char, 3>, 12> base = {{{31, 119, 180},
                                                                       {255, 127, 14},
                                                                       {44, 160, 44},
                                                                       {214, 39, 40},
                                                                       {148, 103, 189},
                                                                       {140, 86, 75},
                                                                       {227, 119, 194},
                                                                       {188, 189, 34},
                                                                       {23, 190, 207},
                                                                       {0, 0, 128},
                                                                       {128, 0, 0},
                                                                       {0, 128, 128}}};
    if (id < static_cast<int>(base.size())) return base[id];
    // Golden-angle hues, full saturation, for any further texture.
    const double h = std::fmod(id * 137.50776405, 360.0) / 60.0;
    const double x = 1 - std::abs(std::fmod(h, 2.0) - 1);
    double r = 0, g = 0, b = 0;
    switch (static_cast<int>(h)) {
        case 0:
            r = 1;
            g = x;
            break;
        case 1:
            r = x;
            g = 1;
            break;
        case 2:
            g = 1;
            b = x;
            break;
        case 3:
            g = x;
            b = 1;
            break;
        case 4:
            r = x;
            b = 1;
            break;
        default:
            r = 1;
            b = x;
            break;
    }
    auto c = [](double v) { return static_cast<unsigned char>(std::lround(40 + 200 * v)); };
    return {c(r), c(g), c(b)};
}

std::string hex_colour(const std::array<unsigned char, 3>& rgb) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
    return buf;
}

}  // namespace geotex
