// geotex_recluster: the clustering stage alone on a feature table, for studying which
// features separate the textures (bench/experiments/run_experiments.py uses it to explain
// the noise results).
//
//   geotex_recluster [--max-points N] FEATURES.tsv [DROP ...]
//
// FEATURES.tsv: a header line of feature names (a last column "texture" is ignored), then
// one row per texel. Columns whose name starts with one of the DROP prefixes are left out.
// Prints the texture label of each row, one per line, from make_clustering with its
// default parameters (what `geotex segment` uses), but --max-points (--cluster-landmarks of
// `geotex segment`; 0: every row) when given.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/clustering.hpp"

int main(int argc, char** argv) {
    geotex::ClusteringParams params;
    int first = 1;  // the index of FEATURES.tsv
    if (argc > 2 && std::string(argv[1]) == "--max-points") {
        params.max_points = std::atoi(argv[2]);
        first = 3;
    }
    if (argc <= first) {
        std::fprintf(stderr,
                     "usage: geotex_recluster [--max-points N] FEATURES.tsv [DROP_PREFIX ...]\n");
        return 1;
    }
    std::ifstream in(argv[first]);
    std::string line;
    if (!in || !std::getline(in, line)) {
        std::fprintf(stderr, "geotex_recluster: error: cannot read %s\n", argv[first]);
        return 2;
    }
    std::vector<char> keep;
    {
        std::istringstream header(line);
        std::string name;
        while (std::getline(header, name, '\t')) {
            bool k = name != "texture";
            for (int a = first + 1; a < argc; ++a) k = k && name.rfind(argv[a], 0) != 0;
            keep.push_back(k ? 1 : 0);
        }
    }
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
        std::istringstream ss(line);
        std::string cell;
        std::vector<double> row;
        for (std::size_t j = 0; std::getline(ss, cell, '\t'); ++j)
            if (j < keep.size() && keep[j]) row.push_back(std::stod(cell));
        if (!row.empty()) rows.push_back(row);
    }
    if (rows.empty()) return 0;
    Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()),
                      static_cast<Eigen::Index>(rows[0].size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < rows[0].size(); ++j)
            m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i].at(j);
    try {
        const geotex::ClusteringResult r = geotex::make_clustering(m, params);
        for (int label : r.labels) std::printf("%d\n", label);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geotex_recluster: error: %s\n", e.what());
        return 3;
    }
    return 0;
}
