// meshoptimizer's attribute codec version 1 and filter COLOR, which
// KHR_meshopt_compression adds to EXT_meshopt_compression's (gltfpack -ce khr
// writes both), decoded in plain C++: Debian 12's libmeshoptimizer (0.18)
// decodes codec version 0 only and has no COLOR filter. The index codecs and the
// other filters stay meshoptimizer's (gltf_compression.cpp).
//
// Follows the bitstream of the KHR_meshopt_compression specification (Appendix
// A, "Mode 0: attributes"; Appendix B, "Filter 4: color") and the scalar
// decoder of meshoptimizer 1.x (src/vertexcodec.cpp decodeVertexBlock,
// src/vertexfilter.cpp decodeFilterColor; MIT licence, © Arseny Kapoulkine),
// without its SIMD paths. Every read is checked against the stream's end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace tessera::gltf {

// Decodes an ATTRIBUTES stream of codec version 1 (header byte 0xa1) or 0
// (0xa0; the loader gives those to libmeshoptimizer, tests compare the two)
// into `out`, which holds `count` elements of `stride` bytes (a multiple of 4,
// 4 to 256). Returns "" on success, else why the stream is invalid (one line,
// naming no file: the caller adds it). The stream must end exactly at its
// tail, as the specification requires.
std::string decode_meshopt_attributes(std::span<const std::uint8_t> stream, std::size_t count, std::size_t stride,
                                      std::span<std::uint8_t> out);

// Filter COLOR in place on `count` elements of `stride` 4 (four 8-bit
// components) or 8 (four 16-bit, little-endian): YCoCg with K-bit luma and
// chroma and a (K-1)-bit alpha marked by bit K-1, to RGBA unorm. Returns "" or
// why not (an alpha without its marker bit: K < 2). Components outside the K
// bits the encoder promises are clamped to [0, 2^N - 1] (the reference wraps).
std::string decode_meshopt_color_filter(std::span<std::uint8_t> data, std::size_t count, std::size_t stride);

}  // namespace tessera::gltf
