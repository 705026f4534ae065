// libFuzzer target: the OBJ reader (read_mesh_memory) and the stages that see its geometry.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return geotex::fuzz::run_mesh_input(data, size, "fuzz.obj");
}
