// libFuzzer target: the scene parser on arbitrary bytes (see fuzz_targets.hpp).
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    tessera::fuzz::scene_parser(data, size);
    return 0;
}
