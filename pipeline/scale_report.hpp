#pragma once
// What `geotex scales` writes of a scale series (geometry/scale_series.hpp): its JSON, and a
// plot of the texel counts and the stability against r as SVG.

#include <nlohmann/json.hpp>
#include <string>

#include "geometry/scale_series.hpp"

namespace geotex {

/// The series as JSON: the parameters, one entry per scale, the plateaus, the best scale (or
/// null) and the notes. Scales are given relative (fraction of the largest side) and in mesh
/// units.
nlohmann::ordered_json scale_series_json(const ScaleSeries& series,
                                         const ScaleSeriesParams& params);

/// A self-contained SVG picture (640 by 360): texels and persistent texels against r (log
/// axis), the stability on a second axis from 0 to 1, the plateaus shaded and the best scale
/// marked. `title` is shown at the top (escaped here).
std::string scale_series_svg(const ScaleSeries& series, const ScaleSeriesParams& params,
                             const std::string& title);

}  // namespace geotex
