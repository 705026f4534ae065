#pragma once
/// The colour of a texture id, as the segmentation PLY, the renderer and the JSON report show
/// it, so that every output of a run paints the same texture alike.

#include <array>
#include <string>

namespace geotex {

/// Red, green and blue of texture `id` (0..255 each): grey {170, 170, 170} for the
/// background (id < 0), twelve colour-blind-aware first choices, then golden-angle hues.
std::array<unsigned char, 3> texture_colour(int id);

/// "#rrggbb", lower-case hexadecimal, of `rgb`.
std::string hex_colour(const std::array<unsigned char, 3>& rgb);

}  // namespace geotex
