// libFuzzer target: the glTF importer on arbitrary bytes (see fuzz_targets.hpp).
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    tessera::fuzz::gltf_loader(data, size);
    return 0;
}
