// The bodies of the libFuzzer targets, shared by the fuzzers (fuzz_*.cpp, built
// with clang and -fsanitize=fuzzer) and by the doctest case that replays every
// file in tests/fuzz/regressions/<target>/ in the normal test suite.
// A target returns normally for any input; a crash, a sanitizer report or a
// failed invariant (std::abort) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::fuzz {

// Arbitrary bytes as a scene file. Bad input must end in SceneError; a scene
// that loads must pass validate_scene and render (at most 32×32) to finite pixels.
void scene_parser(const std::uint8_t* data, std::size_t size);

// Arbitrary bytes as a .glb or .gltf file (told apart by the "glTF" magic), with
// no external files read. Bad input must end in SceneError; a file that loads
// must make a scene that passes validate_scene and renders (at most 32×32).
void gltf_loader(const std::uint8_t* data, std::size_t size);

// Arbitrary bytes as a handful of triangles, with positions and normals that
// may be NaN, infinite, huge (1e30) or denormal, rendered at 64×64. The frame
// must survive with the right size.
void rasterizer(const std::uint8_t* data, std::size_t size);

}  // namespace tessera::fuzz
