#include "pipeline/scale_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace geotex {

namespace {

using Json = nlohmann::ordered_json;

Json step_json(const ScaleStep& s) {
    Json j{{"scale", s.radius_rel}, {"radius", s.radius}, {"skipped", s.skipped}};
    if (s.skipped) return j;
    j["texels"] = s.texels;
    j["textures"] = s.textures;
    j["persist_previous"] = s.persist_previous;
    j["persist_next"] = s.persist_next;
    j["persistent"] = s.persistent;
    j["stability"] = s.stability;
    j["stable"] = s.stable;
    return j;
}

// SVG is written by hand: no library of the toolchain draws plots, and the picture is a few
// lines, rectangles and labels.
std::string escape_xml(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default:
                // Control characters are not allowed in XML 1.0 text.
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n')
                    out += ' ';
                else
                    out += c;
        }
    }
    return out;
}

std::string fmt(const char* format, double v) {
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

}  // namespace

Json scale_series_json(const ScaleSeries& series, const ScaleSeriesParams& params) {
    Json steps = Json::array();
    for (const ScaleStep& s : series.steps) steps.push_back(step_json(s));
    Json plateaus = Json::array();
    for (const ScalePlateau& p : series.plateaus)
        plateaus.push_back(Json{{"from", series.steps[p.first].radius_rel},
                                {"to", series.steps[p.last].radius_rel},
                                {"recommended", series.steps[p.recommended].radius_rel}});
    return Json{
        {"parameters",
         {{"smallest", params.min_rel},
          {"largest", params.max_rel},
          {"steps", params.steps},
          {"match_iou", params.match_iou},
          {"stable_fraction", params.stable_fraction},
          {"min_radius_edges", params.min_radius_edges},
          {"near_most", params.near_most}}},
        {"scales", steps},
        {"plateaus", plateaus},
        {"best", series.best >= 0 ? Json(series.steps[series.best].radius_rel) : Json(nullptr)},
        {"notes", series.notes}};
}

std::string scale_series_svg(const ScaleSeries& series, const ScaleSeriesParams& params,
                             const std::string& title) {
    const double width = 640, height = 360, left = 56, right = 56, top = 40, bottom = 48;
    const double plot_w = width - left - right, plot_h = height - top - bottom;
    int most = 1;
    for (const ScaleStep& s : series.steps) most = std::max(most, s.texels);
    const double lmin = std::log(params.min_rel), lmax = std::log(params.max_rel);
    auto x = [&](double rel) { return left + plot_w * (std::log(rel) - lmin) / (lmax - lmin); };
    auto y_count = [&](double n) { return top + plot_h * (1 - n / most); };
    auto y_unit = [&](double v) { return top + plot_h * (1 - v); };
    // Half the distance to the neighbouring scale: the band a plateau's scale covers.
    const double half_step = series.steps.size() > 1 ? plot_w / (series.steps.size() - 1) / 2 : 0;

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\""
        << height << "\" viewBox=\"0 0 " << width << ' ' << height
        << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << width / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">"
        << escape_xml(title) << "</text>\n";
    for (const ScalePlateau& p : series.plateaus) {
        const double x0 = std::max(left, x(series.steps[p.first].radius_rel) - half_step);
        const double x1 = std::min(left + plot_w, x(series.steps[p.last].radius_rel) + half_step);
        svg << "<rect class=\"plateau\" x=\"" << fmt("%.1f", x0) << "\" y=\"" << top
            << "\" width=\"" << fmt("%.1f", x1 - x0) << "\" height=\"" << plot_h
            << "\" fill=\"#dff0d8\"/>\n";
    }
    // Axes and the scale of each step.
    svg << "<path d=\"M" << left << ' ' << top << "V" << top + plot_h << "H" << left + plot_w
        << "V" << top << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (const ScaleStep& s : series.steps) {
        const double sx = x(s.radius_rel);
        svg << "<text x=\"" << fmt("%.1f", sx) << "\" y=\"" << top + plot_h + 14
            << "\" text-anchor=\"middle\">" << fmt("%.3g", 100 * s.radius_rel) << "</text>\n";
        if (s.skipped)
            svg << "<text class=\"skipped\" x=\"" << fmt("%.1f", sx) << "\" y=\""
                << top + plot_h - 4 << "\" text-anchor=\"middle\" fill=\"#999\">×</text>\n";
    }
    svg << "<text x=\"" << left + plot_w / 2 << "\" y=\"" << height - 12
        << "\" text-anchor=\"middle\">scale r (% of the largest side, log axis)</text>\n";
    for (int k = 0; k <= 4; ++k) {
        const double v = k / 4.0;
        svg << "<text x=\"" << left - 6 << "\" y=\"" << fmt("%.1f", y_unit(v) + 4)
            << "\" text-anchor=\"end\">" << fmt("%.0f", v * most) << "</text>\n"
            << "<text x=\"" << left + plot_w + 6 << "\" y=\"" << fmt("%.1f", y_unit(v) + 4)
            << "\">" << fmt("%.2g", v) << "</text>\n";
    }
    svg << "<text transform=\"translate(14 " << top + plot_h / 2
        << ") rotate(-90)\" text-anchor=\"middle\">texels</text>\n"
        << "<text transform=\"translate(" << width - 10 << ' ' << top + plot_h / 2
        << ") rotate(90)\" text-anchor=\"middle\">stability</text>\n";

    // One polyline per quantity over the computed scales.
    auto line = [&](const char* cls, const char* colour, const char* dash, auto value) {
        svg << "<polyline class=\"" << cls << "\" fill=\"none\" stroke=\"" << colour
            << "\" stroke-width=\"2\"" << dash << " points=\"";
        bool first = true;
        for (const ScaleStep& s : series.steps) {
            if (s.skipped) continue;
            svg << (first ? "" : " ") << fmt("%.1f", x(s.radius_rel)) << ','
                << fmt("%.1f", value(s));
            first = false;
        }
        svg << "\"/>\n";
    };
    line("texels", "#1f4e9c", "", [&](const ScaleStep& s) { return y_count(s.texels); });
    line("persistent", "#e07b00", "", [&](const ScaleStep& s) { return y_count(s.persistent); });
    line("stability", "#555", " stroke-dasharray=\"4 3\"",
         [&](const ScaleStep& s) { return y_unit(s.stability); });
    if (series.best >= 0) {
        const double bx = x(series.steps[series.best].radius_rel);
        svg << "<line class=\"best\" x1=\"" << fmt("%.1f", bx) << "\" x2=\"" << fmt("%.1f", bx)
            << "\" y1=\"" << top << "\" y2=\"" << top + plot_h
            << "\" stroke=\"#c00\" stroke-width=\"1.5\"/>\n"
            << "<text x=\"" << fmt("%.1f", bx + 4) << "\" y=\"" << top + 12
            << "\" fill=\"#c00\">best " << fmt("%.3g", 100 * series.steps[series.best].radius_rel)
            << "%</text>\n";
    } else {
        svg << "<text x=\"" << left + plot_w / 2 << "\" y=\"" << top + plot_h / 2
            << "\" text-anchor=\"middle\" fill=\"#c00\">no stable scale</text>\n";
    }
    // Legend.
    const double ly = top - 8;
    svg << "<text x=\"" << left << "\" y=\"" << ly << "\" fill=\"#1f4e9c\">texels</text>"
        << "<text x=\"" << left + 50 << "\" y=\"" << ly
        << "\" fill=\"#e07b00\">persistent</text>"
        << "<text x=\"" << left + 120 << "\" y=\"" << ly << "\" fill=\"#555\">stability</text>"
        << "<text x=\"" << left + 180 << "\" y=\"" << ly
        << "\" fill=\"#5a9a4a\">plateaus shaded</text>\n";
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace geotex
