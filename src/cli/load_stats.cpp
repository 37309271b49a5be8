#include "cli/load_stats.hpp"

#include <cstdio>

#include <sys/resource.h>

#include "scene/gltf/gltf_import.hpp"
#include "texture/texture.hpp"

namespace tessera::cli {

LoadCounters read_load_counters() {
    const GltfImportTimes& gltf = gltf_import_times();
    const texture::TextureBuildTimes& textures = texture::build_times();
    return {gltf.file_read_ns.load(), gltf.parse_ns.load(),   gltf.convert_ns.load(), gltf.images_ns.load(),
            textures.decode_ns.load(), textures.upload_ns.load(), textures.mips_ns.load(), textures.textures.load(),
            textures.bytes.load()};
}

void print_load_stats(const LoadCounters& before, const LoadCounters& after, double load_ms) {
    const auto ms = [&](std::int64_t LoadCounters::*field) { return double(after.*field - before.*field) * 1e-6; };
    std::printf("load %.1f ms (glTF file read %.1f, parse %.1f, convert %.1f, images %.1f)\n", load_ms,
                ms(&LoadCounters::file_read_ns), ms(&LoadCounters::parse_ns), ms(&LoadCounters::convert_ns),
                ms(&LoadCounters::images_ns));
    std::printf("images: %lld textures, %.1f MB; thread time: decode %.1f ms, upload %.1f ms, mips %.1f ms\n",
                (long long)(after.textures - before.textures), double(after.texture_bytes - before.texture_bytes) / 1e6,
                ms(&LoadCounters::decode_ns), ms(&LoadCounters::upload_ns), ms(&LoadCounters::mips_ns));
}

void print_write_stats(double encode_ms) {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("encode %.1f ms; peak RSS %.1f MB\n", encode_ms, double(usage.ru_maxrss) / 1024.0);
}

}  // namespace tessera::cli
