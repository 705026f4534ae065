#include "tests/dictionary_fixtures.hpp"

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "geometry/feature_table.hpp"

namespace geotex::test {

// A small clean dictionary. Places used below (1-based line:column): the concept maps start
// at their `id` key (column 7), id values at column 11, interval lists '[' at column 17,
// label maps '{' at column 15. `area` comes first and the sphericity concepts are out of
// order on purpose: parse_dictionary sorts by feature column, then lower bound.
const std::string kClean =
    "scheme:\n"                                                            //  1
    "  id: test\n"                                                         //  2
    "  version: \"1\"\n"                                                   //  3
    "  namespace: \"https://example.org/dict/\"\n"                         //  4
    "  languages: [en, fr]\n"                                              //  5
    "  title: {en: Test, fr: Essai}\n"                                     //  6
    "features:\n"                                                          //  7
    "  area:\n"                                                            //  8
    "    - id: small-area\n"                                               //  9
    "      interval: [-.inf, 0.1]\n"                                       // 10
    "      labels: {en: small area, fr: petite aire}\n"                    // 11
    "  contour_sphericity:\n"                                              // 12
    "    - id: non-circular-shape\n"                                       // 13
    "      interval: [0.15, .inf]\n"                                       // 14
    "      labels: {en: non circular shape, fr: forme non circulaire}\n"   // 15
    "      definition: {en: \"The contour moves away from a circle.\"}\n"  // 16
    "      source: Table 3\n"                                              // 17
    "    - id: circular-shape\n"                                           // 18
    "      interval: [0, 0.05]\n"                                          // 19
    "      labels: {en: circular shape, fr: forme circulaire}\n";          // 20

// A small clean dictionary with facets. The facets list their features out of column order on
// purpose (their order is the curator's preference), `surface` holds concepts of each relief.
// Places used below: facet keys at column 3, facet label maps '{' at column 13 (label texts at
// 18), feature lists '[' at column 15; concept label texts at column 20.
const std::string kFaceted =
    "scheme:\n"                                                        //  1
    "  id: test\n"                                                     //  2
    "  version: \"1\"\n"                                               //  3
    "  namespace: \"https://example.org/dict/\"\n"                     //  4
    "  languages: [en, fr]\n"                                          //  5
    "  title: {en: Test, fr: Essai}\n"                                 //  6
    "facets:\n"                                                        //  7
    "  outline:\n"                                                     //  8
    "    labels: {en: outline, fr: contour}\n"                         //  9
    "    features: [perimeter2_area_ratio, contour_sphericity]\n"      // 10
    "  size:\n"                                                        // 11
    "    labels: {en: size, fr: taille}\n"                             // 12
    "    features: [area_rel, area]\n"                                 // 13
    "  surface:\n"                                                     // 14
    "    labels: {en: surface shape, fr: forme de la surface}\n"       // 15
    "    features: [shape_index_mean]\n"                               // 16
    "features:\n"                                                      // 17
    "  area:\n"                                                        // 18
    "    - id: small-area\n"                                           // 19
    "      interval: [-.inf, 0.1]\n"                                   // 20
    "      labels: {en: small area, fr: petite aire}\n"                // 21
    "  contour_sphericity:\n"                                          // 22
    "    - id: circular-shape\n"                                       // 23
    "      interval: [0, 0.05]\n"                                      // 24
    "      labels: {en: circular shape, fr: forme circulaire}\n"       // 25
    "  perimeter2_area_ratio:\n"                                       // 26
    "    - id: non-compact-shape\n"                                    // 27
    "      interval: [16, .inf]\n"                                     // 28
    "      labels: {en: non compact shape, fr: forme non compacte}\n"  // 29
    "  area_rel:\n"                                                    // 30
    "    - id: tiny-detail\n"                                          // 31
    "      interval: [0, 0.0002]\n"                                    // 32
    "      labels: {en: tiny detail, fr: détail minuscule}\n"          // 33
    "  shape_index_mean:\n"                                            // 34
    "    - id: spherical-cup\n"                                        // 35
    "      interval: [-1, -0.75]\n"                                    // 36
    "      labels: {en: spherical cup, fr: cuvette sphérique}\n"       // 37
    "      relief: engraved\n"                                         // 38
    "    - id: dome\n"                                                 // 39
    "      interval: [0.5, 0.75]\n"                                    // 40
    "      labels: {en: dome, fr: dôme}\n"                             // 41
    "      relief: raised\n"                                           // 42
    "    - id: saddle\n"                                               // 43
    "      interval: [-0.125, 0.125]\n"                                // 44
    "      labels: {en: saddle, fr: selle}\n";                         // 45

/// `text` with the one occurrence of `from` replaced by `to`.
std::string edit(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(text.find(from, at + 1) == std::string::npos);
    return text.replace(at, from.size(), to);
}

std::string listing(const std::vector<DictionaryProblem>& problems) {
    std::string out;
    for (const auto& p : problems)
        out += std::to_string(p.line) + ":" + std::to_string(p.column) + ": " + p.message + "\n";
    return out;
}

/// The text has exactly one problem, at line:column, whose message contains `fragment`.
void require_one(const std::string& text, long line, long column, const std::string& fragment) {
    const auto problems = check_dictionary(text);
    INFO(listing(problems));
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].line == line);
    CHECK(problems[0].column == column);
    CHECK_THAT(problems[0].message, Catch::Contains(fragment));
}

void require_each(const std::string& text, const std::vector<ExpectedProblem>& cases) {
    for (const auto& c : cases) {
        INFO("edit: '" << c.from << "' -> '" << c.to << "'");
        require_one(edit(text, c.from, c.to), c.line, c.column, c.fragment);
    }
}

std::string read_source_file(const std::string& relative) {
    const std::string path = std::string(GEOTEX_SOURCE_DIR) + "/" + relative;
    std::ifstream in(path, std::ios::binary);
    INFO(path);
    REQUIRE(in);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

const Dictionary& default_dictionary() {
    static const Dictionary d =
        parse_dictionary(read_source_file("dictionaries/default.yaml"), "default.yaml");
    return d;
}

/// Lower-case letters and digits in words joined by single hyphens ("flat-region-pca3").
bool is_kebab_case(const std::string& id) {
    if (id.empty() || id.front() == '-' || id.back() == '-') return false;
    for (size_t i = 0; i < id.size(); ++i) {
        const char c = id[i];
        const bool word = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (!word && !(c == '-' && id[i - 1] != '-')) return false;
    }
    return true;
}

int column_of(const char* id) {
    const int i = feature_index(id);
    REQUIRE(i >= 0);
    return i;
}

}  // namespace geotex::test
