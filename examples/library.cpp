// geotex as a library: segment a mesh file and print its textures.
//   build/example_library MESH [SCALE]
#include <cstdio>
#include <cstdlib>

#include "geometry/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s MESH [SCALE]\n", argv[0]);
        return 1;
    }
    try {
        const geotex::MeshFile file = geotex::read_mesh_file(argv[1]);
        const geotex::MeshRepairResult repaired = geotex::repair_soup(file.soup);
        geotex::SegmentationParams params;
        if (argc > 2) params.radius_rel = std::atof(argv[2]);
        const geotex::Segmentation seg = geotex::run_segmentation(repaired.mesh, params);
        std::printf("%zu texels, %d textures\n", seg.texels.size(), seg.num_textures);
        for (std::size_t i = 0; i < seg.texels.size(); ++i)
            std::printf("texel %zu: %zu faces, texture %d, contour sphericity %.4f\n", i, seg.texels[i].faces.size(),
                        seg.texel_texture[i],
                        seg.features.values(static_cast<int>(i), static_cast<int>(geotex::Feature::ContourSphericity)));
    } catch (const geotex::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.located(argv[1]).c_str());
        return 2;
    }
    return 0;
}
