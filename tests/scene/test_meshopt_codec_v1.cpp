// meshoptimizer's attribute codec version 1 and filter COLOR (issue #31), decoded by
// src/scene/gltf/meshopt_codec_v1.cpp: hand-made streams for each feature (written
// by a small encoder below that follows the specification's text, not the
// decoder), streams from meshoptimizer's own encoder (meshopt_v1_vectors.hpp),
// version 0 against Debian's libmeshoptimizer, and broken streams refused.
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <meshoptimizer.h>

#include "meshopt_v1_vectors.hpp"
#include "scene/gltf/meshopt_codec_v1.hpp"

using namespace tessera;

namespace {

using Bytes = std::vector<std::uint8_t>;

std::string decode(const Bytes& stream, std::size_t count, std::size_t stride, Bytes& out) {
    out.assign(count * stride, 0xcd);
    return gltf::decode_meshopt_attributes(stream, count, stride, out);
}

std::uint32_t next_random(std::uint32_t& state) {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
}

// ---- An encoder for codec version 1, from the specification's description ----------------------

struct V1Choices {
    std::vector<std::uint8_t> channels;  // one mode byte per 4 bytes: mode | rotation << 4
    // Control mode of byte k in block b (2 = all zero and 3 = literal are used only where they fit).
    std::function<unsigned(std::size_t b, std::size_t k)> control = [](std::size_t, std::size_t) { return 1u; };
    // Header bits of group g of byte k in block b (a 0-bit choice for a group that is not all zero takes the next).
    std::function<unsigned(std::size_t b, std::size_t k, std::size_t g)> header = [](std::size_t, std::size_t, std::size_t) {
        return 2u;
    };
    const std::uint8_t* baseline = nullptr;  // the tail's element; default: the first element
};

void encode_group(Bytes& out, const std::uint8_t* deltas, int bits) {
    if (bits == 0) return;
    if (bits == 8) {
        out.insert(out.end(), deltas, deltas + 16);
        return;
    }
    const unsigned sentinel = (1u << bits) - 1;
    const std::size_t per_byte = 8 / std::size_t(bits);
    for (std::size_t i = 0; i < 16; i += per_byte) {
        std::uint8_t byte = 0;
        for (std::size_t j = 0; j < per_byte; ++j) {
            const unsigned code = std::min<unsigned>(deltas[i + j], sentinel);
            // "1-bit: from least significant to most significant bit"; 2- and 4-bit: delta 0 in the top bits.
            byte |= std::uint8_t(code << (bits == 1 ? j : 8 - std::size_t(bits) * (j + 1)));
        }
        out.push_back(byte);
    }
    for (std::size_t i = 0; i < 16; ++i)
        if (deltas[i] >= sentinel) out.push_back(deltas[i]);
}

Bytes encode_v1(const Bytes& data, std::size_t count, std::size_t stride, const V1Choices& choices) {
    REQUIRE(choices.channels.size() == stride / 4);
    const std::uint8_t* baseline = choices.baseline ? choices.baseline : data.data();
    // Deltas per element and byte, from the channel modes.
    Bytes deltas(count * stride);
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* previous = i == 0 ? baseline : &data[(i - 1) * stride];
        for (std::size_t c = 0; c < stride / 4; ++c) {
            std::uint32_t v = 0, p = 0;
            std::memcpy(&v, &data[i * stride + 4 * c], 4);
            std::memcpy(&p, previous + 4 * c, 4);
            const unsigned mode = choices.channels[c] & 15, rotation = choices.channels[c] >> 4;
            std::uint32_t d = 0;
            if (mode == 0) {
                for (int b = 0; b < 4; ++b) {
                    const std::uint8_t x = std::uint8_t(std::uint8_t(v >> (8 * b)) - std::uint8_t(p >> (8 * b)));
                    const std::uint8_t z = (x & 0x80) ? std::uint8_t(~(x << 1)) : std::uint8_t(x << 1);  // the spec's encode()
                    d |= std::uint32_t(z) << (8 * b);
                }
            } else if (mode == 1) {
                for (int h = 0; h < 2; ++h) {
                    const std::uint16_t x = std::uint16_t(std::uint16_t(v >> (16 * h)) - std::uint16_t(p >> (16 * h)));
                    const std::uint16_t z = (x & 0x8000) ? std::uint16_t(~(x << 1)) : std::uint16_t(x << 1);
                    d |= std::uint32_t(z) << (16 * h);
                }
            } else {
                const std::uint32_t x = v ^ p;
                d = (x << rotation) | (x >> ((32 - rotation) & 31));  // the spec's rotate()
            }
            std::memcpy(&deltas[i * stride + 4 * c], &d, 4);
        }
    }
    Bytes out = {0xa1};
    const std::size_t block_max = std::min<std::size_t>((8192 / stride) & ~std::size_t(15), 256);
    for (std::size_t first = 0, b = 0; first < count; first += block_max, ++b) {
        const std::size_t n = std::min(count - first, block_max), groups = (n + 15) / 16;
        const std::size_t control_at = out.size();
        out.resize(out.size() + stride / 4, 0);
        for (std::size_t k = 0; k < stride; ++k) {
            Bytes column(groups * 16, 0);  // the last group padded with zero deltas
            for (std::size_t i = 0; i < n; ++i) column[i] = deltas[(first + i) * stride + k];
            unsigned control = choices.control(b, k);
            const bool zero = std::all_of(column.begin(), column.end(), [](std::uint8_t d) { return d == 0; });
            if (control == 2 && !zero) control = 1;
            out[control_at + k / 4] |= std::uint8_t(control << (2 * (k % 4)));
            if (control == 2) continue;
            if (control == 3) {
                out.insert(out.end(), column.begin(), column.begin() + std::ptrdiff_t(n));
                continue;
            }
            static constexpr int kBits[2][4] = {{0, 1, 2, 4}, {1, 2, 4, 8}};
            const std::size_t header_at = out.size();
            out.resize(out.size() + (groups + 3) / 4, 0);
            for (std::size_t g = 0; g < groups; ++g) {
                unsigned header = choices.header(b, k, g) & 3;
                const bool zero_group = std::all_of(&column[g * 16], &column[g * 16] + 16, [](std::uint8_t d) { return d == 0; });
                if (kBits[control][header] == 0 && !zero_group) header = 1;
                out[header_at + g / 4] |= std::uint8_t(header << (2 * (g % 4)));
                encode_group(out, &column[g * 16], kBits[control][header]);
            }
        }
    }
    const std::size_t tail = stride + stride / 4;
    out.resize(out.size() + (tail < 24 ? 24 - tail : 0), 0);
    out.insert(out.end(), baseline, baseline + stride);
    out.insert(out.end(), choices.channels.begin(), choices.channels.end());
    return out;
}

// Elements whose byte deltas are a mix of 0, small and large (so that every bit width meets its sentinel).
Bytes mixed_data(std::size_t count, std::size_t stride, std::uint32_t seed) {
    Bytes data(count * stride);
    for (std::size_t i = 0; i < data.size(); ++i) {
        const std::uint32_t r = next_random(seed);
        const std::uint8_t previous = i >= stride ? data[i - stride] : 0x80;
        const unsigned kind = r % 8;
        data[i] = kind < 3 ? previous : kind < 6 ? std::uint8_t(previous + (r >> 3) % 5 - 2) : std::uint8_t(r >> 5);
    }
    return data;
}

// The test's copy of make_meshopt_v1_vectors.mjs's vector_data().
Bytes vector_data(const std::string& kind, std::size_t count, std::size_t stride) {
    Bytes out(count * stride);
    std::uint32_t s = 12345;
    const auto rand = [&] {
        s = s * 1664525u + 1013904223u;
        return s >> 24;
    };
    for (std::size_t i = 0; i < count; ++i) {
        for (std::size_t b = 0; b < stride; b += 4) {
            const std::uint32_t c = std::uint32_t(b / 4), e = std::uint32_t(i);
            std::uint32_t v = 0;
            if (kind == "smooth16") {
                const std::uint32_t lo = (1000 * c + 3 * e + (rand() & 3)) & 0xffff;
                const std::uint32_t hi = (60000 - 7 * e * (c + 1) + (rand() & 1)) & 0xffff;
                v = lo | hi << 16;
            } else if (kind == "floatbits") {
                v = 0x3f800000u + ((e * 40503 + c * 9973) & 0x7fffff);
                if ((e + c) % 5 == 0) v ^= 0x80000000u;
            } else if (kind == "random") {
                const std::uint32_t b0 = rand(), b1 = rand(), b2 = rand(), b3 = rand();
                v = b0 | b1 << 8 | b2 << 16 | b3 << 24;
            } else if (kind == "steady") {
                v = 0x11223300u | (c == 0 ? e & 0xff : 0x44);
            } else if (kind == "sparse") {
                v = 0x01000000u * (c + 1) + (e / 29 * 3 + c) % 7;
            } else if (kind == "tiny") {
                v = (((e >> 1) + (rand() & 1)) & 0xff) * 0x01010101u;
            }
            for (std::size_t k = 0; k < 4; ++k) out[i * stride + b + k] = std::uint8_t(v >> (8 * k));
        }
    }
    return out;
}

}  // namespace

TEST_CASE("meshopt codec v1: the specification's 4-bit sentinel example decodes to its deltas") {
    // Stride 4, 16 elements: byte 0 under control mode 0 with one 4-bit group (header 3), bytes 1-3 all zero (control 2).
    Bytes stream = {0xa1, 0x00 | 2 << 2 | 2 << 4 | 2 << 6, 0x03, 0x17, 0x5f, 0xf0, 0xbc, 0x77, 0xa9, 0x21, 0x00, 0x34, 0xb5};
    stream.resize(stream.size() + 19, 0);                 // tail padding: the 5-byte tail padded to 24
    stream.insert(stream.end(), {100, 7, 8, 9, 0x00});  // baseline element, channel 0 in byte deltas
    Bytes out;
    REQUIRE(decode(stream, 16, 4, out) == "");
    const int deltas[16] = {-1, -4, -3, 26, -91, 0, -6, 6, -4, -4, 5, -5, 1, -1, 0, 0};
    int value = 100;
    for (std::size_t i = 0; i < 16; ++i) {
        CAPTURE(i);
        value = (value + deltas[i]) & 0xff;
        CHECK(out[i * 4] == value);
        CHECK(out[i * 4 + 1] == 7);
        CHECK(out[i * 4 + 2] == 8);
        CHECK(out[i * 4 + 3] == 9);
    }
}

TEST_CASE("meshopt codec v1: every control mode, group bit width and channel mode round-trips") {
    for (const std::size_t stride : {4u, 8u, 12u, 256u}) {
        // 300 elements: two blocks (256 + 44, the last group partly used); 70 at stride 256 (blocks of 32).
        const std::size_t count = stride == 256 ? 70 : 300;
        const Bytes data = mixed_data(count, stride, std::uint32_t(stride));
        for (unsigned channel_mode = 0; channel_mode < 3; ++channel_mode) {
            for (unsigned rotation = 0; rotation < (channel_mode == 2 ? 16u : 1u); rotation += (channel_mode == 2 ? 3u : 1u)) {
                for (unsigned control = 0; control < 4; ++control) {
                    CAPTURE(stride);
                    CAPTURE(channel_mode);
                    CAPTURE(rotation);
                    CAPTURE(control);
                    V1Choices choices;
                    // Channel 0 is the mode under test; the others cycle through the modes.
                    for (std::size_t c = 0; c < stride / 4; ++c) {
                        const unsigned mode = c == 0 ? channel_mode : unsigned(c % 3);
                        choices.channels.push_back(std::uint8_t(mode | (mode == 2 ? rotation : 0u) << 4));
                    }
                    choices.control = [control](std::size_t b, std::size_t k) { return (control + unsigned(k + b)) % 4; };
                    choices.header = [](std::size_t b, std::size_t k, std::size_t g) { return unsigned(g + k + b) % 4; };
                    const Bytes baseline(stride, 0x33);
                    choices.baseline = baseline.data();
                    Bytes out;
                    REQUIRE(decode(encode_v1(data, count, stride, choices), count, stride, out) == "");
                    CHECK(out == data);
                }
            }
        }
    }
    SUBCASE("all-zero columns (control mode 2) and 0-bit groups") {
        Bytes data(100 * 8, 0x42);
        for (std::size_t i = 0; i < 100; ++i) data[i * 8 + 5] = std::uint8_t(i / 40);  // changes twice: one nonzero group each
        V1Choices choices;
        choices.channels = {0, 0};
        choices.control = [](std::size_t, std::size_t k) { return k == 5 ? 0u : 2u; };
        choices.header = [](std::size_t, std::size_t, std::size_t) { return 0u; };
        const Bytes stream = encode_v1(data, 100, 8, choices);
        // Header byte, control header, byte 5's group headers and its two 1-bit groups with one sentinel byte each, tail.
        CHECK(stream.size() == 1 + 2 + (2 + 3 + 3) + 24);
        Bytes out;
        REQUIRE(decode(stream, 100, 8, out) == "");
        CHECK(out == data);
    }
}

TEST_CASE("meshopt codec v1: meshoptimizer's own encoder's streams decode to their elements") {
    for (const test::meshopt_v1::AttributeVector& v : test::meshopt_v1::kAttributeVectors) {
        CAPTURE(v.kind);
        CAPTURE(v.stride);
        CAPTURE(v.level);
        CAPTURE(v.uses);
        const Bytes stream(v.stream, v.stream + v.stream_size);
        Bytes out;
        REQUIRE(decode(stream, v.count, v.stride, out) == "");
        CHECK(out == vector_data(v.kind, v.count, v.stride));
        // Cut anywhere, the stream is refused.
        for (std::size_t size = 0; size < stream.size(); ++size) {
            CAPTURE(size);
            CHECK(decode(Bytes(stream.begin(), stream.begin() + std::ptrdiff_t(size)), v.count, v.stride, out) != "");
        }
    }
}

TEST_CASE("meshopt codec v0: the same output and the same refusals as Debian's libmeshoptimizer") {
    std::uint32_t seed = 99;
    for (const std::size_t stride : {4u, 12u, 64u, 256u}) {
        for (const std::size_t count : {1u, 17u, 300u}) {
            CAPTURE(stride);
            CAPTURE(count);
            const Bytes data = mixed_data(count, stride, seed++);
            Bytes stream(meshopt_encodeVertexBufferBound(count, stride));
            stream.resize(meshopt_encodeVertexBuffer(stream.data(), stream.size(), data.data(), count, stride));
            REQUIRE(stream[0] == 0xa0);
            Bytes ours, theirs(data.size());
            REQUIRE(decode(stream, count, stride, ours) == "");
            CHECK(ours == data);
            // Damaged copies: a bit flipped, a byte replaced, the stream cut.
            int disagreements = 0, accepted = 0;
            for (int t = 0; t < 300; ++t) {
                Bytes damaged = stream;
                const std::uint32_t r = next_random(seed);
                if (r % 3 == 0) damaged[(r >> 2) % damaged.size()] ^= std::uint8_t(1u << (r >> 20) % 8);
                else if (r % 3 == 1) damaged[(r >> 2) % damaged.size()] = std::uint8_t(r >> 16);
                else damaged.resize((r >> 2) % damaged.size());
                const bool ours_ok = decode(damaged, count, stride, ours).empty();
                std::fill(theirs.begin(), theirs.end(), 0xcd);
                const bool theirs_ok = meshopt_decodeVertexBuffer(theirs.data(), count, stride, damaged.data(), damaged.size()) == 0;
                accepted += ours_ok;
                disagreements += ours_ok != theirs_ok || (ours_ok && ours != theirs);
            }
            CHECK(disagreements == 0);
            CHECK(accepted < 300);  // some damage is seen (most flips in delta bytes only change values)
        }
    }
}

TEST_CASE("meshopt codec v1: broken streams are refused with what is wrong") {
    const Bytes data = mixed_data(40, 8, 5);
    V1Choices choices;
    choices.channels = {0x22, 0x01};  // XOR rotated by 2, 16-bit deltas
    const Bytes stream = encode_v1(data, 40, 8, choices);
    Bytes out;
    REQUIRE(decode(stream, 40, 8, out) == "");
    const auto with = [&](std::size_t at, std::uint8_t byte) {
        Bytes changed = stream;
        changed[at] = byte;
        return decode(changed, 40, 8, out);
    };
    CHECK(with(0, 0xa2) == "the stream uses attribute codec version 2; versions 0 and 1 are defined");
    CHECK(with(0, 0xb1) == "the stream's first byte is 0xb1, not an attribute codec header (0xa0 | version)");
    CHECK(with(stream.size() - 2, 0x03) == "channel 0 has mode byte 3 (modes are 0, 1 and 2; only mode 2 has a rotation)");
    CHECK(with(stream.size() - 1, 0x11) == "channel 1 has mode byte 17 (modes are 0, 1 and 2; only mode 2 has a rotation)");
    CHECK(decode(Bytes(stream.begin(), stream.begin() + 20), 40, 8, out) ==
          "the stream (20 bytes) is shorter than its header and tail (25 bytes)");
    // One more byte before the tail: left over. One fewer (the tail moved): the blocks run into it.
    Bytes longer = stream;
    longer.insert(longer.end() - 24, 0x00);
    CHECK(decode(longer, 40, 8, out) == "1 byte is left between the last block and the tail padding");
    Bytes shorter = stream;
    shorter.erase(shorter.end() - 25);
    CHECK(decode(shorter, 40, 8, out).find("the stream ends inside ") == 0);
    // Asking for more groups than it holds; a stride the codec does not have.
    CHECK(decode(stream, 49, 8, out).find("the stream ends inside ") == 0);
    CHECK(decode(stream, 40, 6, out) == "byteStride 6 is not a multiple of 4 from 4 to 256");
    // Every cut of it is refused, and every single-byte change either decodes or is refused (never read past).
    for (std::size_t size = 0; size < stream.size(); ++size)
        CHECK(decode(Bytes(stream.begin(), stream.begin() + std::ptrdiff_t(size)), 40, 8, out) != "");
    for (std::size_t at = 0; at < stream.size(); ++at)
        for (const std::uint8_t byte : {0x00, 0x55, 0xff}) (void)with(at, byte);
}

TEST_CASE("meshopt filter COLOR: YCoCg with a K-bit alpha marker to RGBA unorm") {
    SUBCASE("by hand: K = 8 and K = 5 in 8-bit components") {
        // y 100, co 20, cg -10 at K = 8: r = y + co - cg = 130, g = y + cg = 90, b = y - co - cg = 90; alpha 0x7f (7 bits) + marker.
        // y 16, co 4, cg -2 at K = 5: r 22, g 14, b 14, × 255/31 rounded: 181, 115, 115; alpha 0x0f + marker → 31 → 255.
        Bytes data = {100, 20, std::uint8_t(-10), 0xff, 16, 4, std::uint8_t(-2), 0x1f, 16, 4, std::uint8_t(-2), 0x10};
        REQUIRE(gltf::decode_meshopt_color_filter(data, 3, 4) == "");
        CHECK(data == Bytes{130, 90, 90, 255, 181, 115, 115, 255, 181, 115, 115, 0});
    }
    SUBCASE("by hand: K = 12 in 16-bit components") {
        // y 2000, co -100, cg 50: r 1850, g 2050, b 2050 × 65535/4095; alpha 0x400 (11 bits: 1024) → 2048 + 0 → 32775.
        std::uint16_t c[4] = {2000, std::uint16_t(-100), 50, 0x800 | 0x400};
        Bytes data(8);
        std::memcpy(data.data(), c, 8);
        REQUIRE(gltf::decode_meshopt_color_filter(data, 1, 8) == "");
        std::memcpy(c, data.data(), 8);
        const float scale = 65535.0f / 4095.0f;
        CHECK(c[0] == std::uint16_t(1850 * scale + 0.5f));
        CHECK(c[1] == std::uint16_t(2050 * scale + 0.5f));
        CHECK(c[2] == std::uint16_t(2050 * scale + 0.5f));
        CHECK(c[3] == std::uint16_t(2048 * scale + 0.5f));
    }
    SUBCASE("meshoptimizer's encoder and decoder agree with it byte for byte") {
        for (const test::meshopt_v1::ColorVector& v : test::meshopt_v1::kColorVectors) {
            CAPTURE(v.stride);
            CAPTURE(v.bits);
            Bytes out;
            REQUIRE(decode(Bytes(v.stream, v.stream + v.stream_size), v.count, v.stride, out) == "");
            REQUIRE(gltf::decode_meshopt_color_filter(out, v.count, v.stride) == "");
            CHECK(out == Bytes(v.rgba, v.rgba + v.count * v.stride));
        }
    }
    SUBCASE("an alpha without its marker, a bad stride, components past K bits") {
        Bytes zero = {1, 2, 3, 0};
        CHECK(gltf::decode_meshopt_color_filter(zero, 1, 4) ==
              "element 0 of filter COLOR has alpha 0, which marks no bit count (its highest set bit must be bit 1 or above)");
        Bytes one = {1, 2, 3, 4, 1, 2, 3, 1};
        CHECK(gltf::decode_meshopt_color_filter(one, 2, 4).find("element 1 of filter COLOR has alpha 1,") == 0);
        Bytes twelve(12);
        CHECK(gltf::decode_meshopt_color_filter(twelve, 1, 12) == "filter COLOR needs byteStride 4 or 8, not 12");
        // K = 2 (alpha 0b11): co 127 is far past 2 bits; r = 127 and b = -127 are clamped, not wrapped.
        Bytes past = {0, 127, 0, 0x03};
        REQUIRE(gltf::decode_meshopt_color_filter(past, 1, 4) == "");
        CHECK(past == Bytes{255, 0, 0, 255});
    }
}
