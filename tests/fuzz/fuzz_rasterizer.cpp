// libFuzzer target: random triangles with extreme coordinates through the
// whole renderer (see fuzz_targets.hpp).
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    tessera::fuzz::rasterizer(data, size);
    return 0;
}
