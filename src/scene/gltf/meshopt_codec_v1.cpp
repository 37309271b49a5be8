#include "scene/gltf/meshopt_codec_v1.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <vector>

// The names below follow the KHR_meshopt_compression specification's Appendix A:
// a stream is a header byte, attribute blocks, tail padding and the tail block
// (baseline element, then in version 1 one channel mode byte per 4 bytes). A block
// holds up to 256 elements: in version 1 a control header (2 bits per byte
// position), then one data block per byte position, each delta bytes of 16-element
// groups behind 2 header bits per group.
namespace tessera::gltf {
namespace {

constexpr std::size_t kGroupSize = 16;
constexpr std::size_t kBlockBytes = 8192, kMaxBlockElements = 256;
constexpr std::size_t kTailMinV0 = 32, kTailMinV1 = 24;
constexpr char kHex[] = "0123456789abcdef";

// Bits per delta for a group's 2 header bits: version 0, then version 1 under control modes 0 and 1.
constexpr std::array<int, 4> kBitsV0 = {0, 2, 4, 8};
constexpr std::array<int, 4> kBitsV1Control0 = {0, 1, 2, 4};
constexpr std::array<int, 4> kBitsV1Control1 = {1, 2, 4, 8};

// The stream's bytes between the header byte and the tail padding, read front to back.
struct Reader {
    const std::uint8_t* at;
    const std::uint8_t* end;
    bool has(std::size_t n) const { return std::size_t(end - at) >= n; }
};

std::size_t max_block_elements(std::size_t stride) {
    return std::min((kBlockBytes / stride) & ~(kGroupSize - 1), kMaxBlockElements);
}

// One group's 16 deltas of `Bits` bits each (1, 2 or 4). A delta of all ones (the
// sentinel) is a full byte stored after the packed bits. 1-bit deltas are packed
// from the least significant bit, 2- and 4-bit ones from the most significant.
// False if the stream ends inside the group.
template <int Bits>
bool decode_packed_group(Reader& in, std::uint8_t* deltas) {
    constexpr std::size_t packed_bytes = kGroupSize * Bits / 8, per_byte = 8 / Bits;
    constexpr unsigned sentinel = (1u << Bits) - 1;
    if (!in.has(packed_bytes)) return false;
    const std::uint8_t* packed = in.at;
    in.at += packed_bytes;
    for (std::size_t i = 0; i < kGroupSize; ++i) {
        const unsigned shift = Bits == 1 ? unsigned(i % 8) : unsigned(8 - Bits * (1 + i % per_byte));
        unsigned delta = (packed[i / per_byte] >> shift) & sentinel;
        if (delta == sentinel) {
            if (!in.has(1)) return false;
            delta = *in.at++;
        }
        deltas[i] = std::uint8_t(delta);
    }
    return true;
}

// One group of 16 deltas of `bits` bits each: 0 (all zero, nothing stored), 1, 2, 4 or 8 (bytes as they are).
bool decode_group(Reader& in, int bits, std::uint8_t* deltas) {
    switch (bits) {
        case 0: std::fill_n(deltas, kGroupSize, std::uint8_t(0)); return true;
        case 1: return decode_packed_group<1>(in, deltas);
        case 2: return decode_packed_group<2>(in, deltas);
        case 4: return decode_packed_group<4>(in, deltas);
        default:
            if (!in.has(kGroupSize)) return false;
            std::copy_n(in.at, kGroupSize, deltas);
            in.at += kGroupSize;
            return true;
    }
}

template <typename T>
T unzigzag(T v) {
    return T(T(0 - (v & 1)) ^ T(v >> 1));
}

std::uint32_t rotate_left(std::uint32_t v, unsigned r) { return (v << r) | (v >> ((32 - r) & 31)); }

std::uint32_t load_le(const std::uint8_t* p, std::size_t bytes) {
    std::uint32_t v = 0;
    for (std::size_t b = 0; b < bytes; ++b) v |= std::uint32_t(p[b]) << (8 * b);
    return v;
}

void store_le(std::uint8_t* p, std::uint32_t v, std::size_t bytes) {
    for (std::size_t b = 0; b < bytes; ++b) p[b] = std::uint8_t(v >> (8 * b));
}

std::string block_name(std::size_t first, std::size_t n) {
    return "the block of elements " + std::to_string(first) + ".." + std::to_string(first + n - 1);
}

}  // namespace

std::string decode_meshopt_attributes(std::span<const std::uint8_t> stream, std::size_t count, std::size_t stride,
                                      std::span<std::uint8_t> out) {
    if (stride == 0 || stride % 4 != 0 || stride > 256)
        return "byteStride " + std::to_string(stride) + " is not a multiple of 4 from 4 to 256";
    std::size_t out_size = 0;
    if (__builtin_mul_overflow(count, stride, &out_size) || out_size != out.size())
        return "the output does not hold count × byteStride bytes";
    if (stream.empty()) return "the stream is empty";
    if ((stream[0] & 0xf0) != 0xa0)
        return "the stream's first byte is 0x" + std::string{kHex[stream[0] >> 4], kHex[stream[0] & 15]} +
               ", not an attribute codec header (0xa0 | version)";
    const int version = stream[0] & 0x0f;
    if (version > 1)
        return "the stream uses attribute codec version " + std::to_string(version) + "; versions 0 and 1 are defined";

    const std::size_t channel_bytes = version == 0 ? 0 : stride / 4;
    const std::size_t tail_size = stride + channel_bytes;
    const std::size_t tail_padded = std::max(tail_size, version == 0 ? kTailMinV0 : kTailMinV1);
    if (stream.size() - 1 < tail_padded)
        return "the stream (" + std::to_string(stream.size()) + " bytes) is shorter than its header and tail (" +
               std::to_string(1 + tail_padded) + " bytes)";
    const std::uint8_t* baseline = stream.data() + stream.size() - tail_size;
    const std::uint8_t* channels = baseline + stride;

    // Channel modes: 0 byte deltas, 1 16-bit deltas, 2 32-bit XOR deltas rotated by the high 4 bits.
    for (std::size_t c = 0; c < channel_bytes; ++c) {
        const unsigned mode = channels[c] & 0x0f, rotation = channels[c] >> 4;
        if (mode > 2 || (mode < 2 && rotation != 0))
            return "channel " + std::to_string(c) + " has mode byte " + std::to_string(channels[c]) +
                   " (modes are 0, 1 and 2; only mode 2 has a rotation)";
    }

    Reader in{stream.data() + 1, stream.data() + stream.size() - tail_padded};
    const std::size_t block_max = max_block_elements(stride);
    std::vector<std::uint8_t> deltas(block_max * stride);  // per byte position: block_max deltas
    for (std::size_t first = 0; first < count; first += block_max) {
        const std::size_t n = std::min(count - first, block_max);
        const std::size_t groups = (n + kGroupSize - 1) / kGroupSize, header_bytes = (groups + 3) / 4;
        const auto ends_inside = [&](const std::string& part, std::size_t k) {
            return "the stream ends inside " + part + " of byte " + std::to_string(k) + " in " + block_name(first, n);
        };
        const std::uint8_t* control = nullptr;
        if (version == 1) {
            if (!in.has(stride / 4)) return "the stream ends inside the control header of " + block_name(first, n);
            control = in.at;
            in.at += stride / 4;
        }
        for (std::size_t k = 0; k < stride; ++k) {
            std::uint8_t* column = deltas.data() + k * block_max;
            const unsigned control_mode = control ? (control[k / 4] >> (2 * (k % 4))) & 3 : 0;
            if (control_mode == 2) {  // every delta 0, nothing stored
                std::fill_n(column, n, std::uint8_t(0));
                continue;
            }
            if (control_mode == 3) {  // n delta bytes as they are, no groups
                if (!in.has(n)) return ends_inside("the literal deltas", k);
                std::copy_n(in.at, n, column);
                in.at += n;
                continue;
            }
            const std::array<int, 4>& bits =
                version == 0 ? kBitsV0 : control_mode == 0 ? kBitsV1Control0 : kBitsV1Control1;
            if (!in.has(header_bytes)) return ends_inside("the group headers", k);
            const std::uint8_t* header = in.at;
            in.at += header_bytes;
            // The last group may run past n (it always holds 16): the extra deltas land in
            // the column's spare room (block_max is a multiple of 16) and are not used.
            for (std::size_t g = 0; g < groups; ++g) {
                const int group_bits = bits[(header[g / 4] >> (2 * (g % 4))) & 3];
                if (!decode_group(in, group_bits, column + g * kGroupSize))
                    return ends_inside("group " + std::to_string(g), k);
            }
        }
        // Deltas to values, per 4-byte channel, each element from the one before
        // (the first element of all from the tail's baseline element).
        for (std::size_t c = 0; c < stride / 4; ++c) {
            const unsigned mode = version == 0 ? 0 : channels[c] & 0x0f;
            const unsigned rotation = version == 0 ? 0 : channels[c] >> 4;
            const std::size_t width = mode == 0 ? 1 : mode == 1 ? 2 : 4;  // bytes per delta
            for (std::size_t part = 0; part < 4; part += width) {
                const std::size_t byte = 4 * c + part;
                const std::uint8_t* previous = first == 0 ? baseline + byte : out.data() + (first - 1) * stride + byte;
                std::uint32_t value = load_le(previous, width);
                std::uint8_t* target = out.data() + first * stride + byte;
                for (std::size_t i = 0; i < n; ++i, target += stride) {
                    std::uint32_t delta = 0;
                    for (std::size_t b = 0; b < width; ++b)
                        delta |= std::uint32_t(deltas[(byte + b) * block_max + i]) << (8 * b);
                    if (mode == 0) value = std::uint8_t(value + unzigzag(std::uint8_t(delta)));
                    else if (mode == 1) value = std::uint16_t(value + unzigzag(std::uint16_t(delta)));
                    else value ^= rotate_left(delta, (32 - rotation) & 31);  // the encoder rotated left by `rotation`
                    store_le(target, value, width);
                }
            }
        }
    }
    if (in.at != in.end)
        return std::to_string(in.end - in.at) + (in.end - in.at == 1 ? " byte is" : " bytes are") +
               " left between the last block and the tail padding";
    return {};
}

namespace {

// One element of filter COLOR, components of N bits (8 or 16) in `c`.
template <int N>
bool color_element(std::uint32_t c[4]) {
    constexpr std::uint32_t max = (1u << N) - 1;
    constexpr std::uint32_t sign = 1u << (N - 1);
    const std::uint32_t alpha = c[3];
    if (alpha < 2) return false;  // the marker bit K - 1 must be bit 1 or higher (K >= 2)
    const int k = std::bit_width(alpha);                     // K
    const std::int32_t scale_bits = std::int32_t((1u << k) - 1);  // 2^K - 1, the K-bit maximum
    const auto as_signed = [&](std::uint32_t v) { return std::int32_t(v ^ sign) - std::int32_t(sign); };
    const std::int32_t y = std::int32_t(c[0]), co = as_signed(c[1]), cg = as_signed(c[2]);
    const std::int32_t r = y + co - cg, g = y + cg, b = y - co - cg;
    std::int32_t a = std::int32_t(alpha) & (scale_bits >> 1);  // the marker dropped,
    a = (a << 1) | (a & 1);                                     // then widened to K bits, the last bit repeated
    const float scale = float(max) / float(scale_bits);
    const auto to_unorm = [&](std::int32_t v) {
        // Rounded as meshoptimizer's scalar decoder rounds (+0.5, truncated); clamped, which only
        // changes components outside the K bits the encoder promises.
        const float f = float(v) * scale + 0.5f;
        return f <= 0.0f ? 0u : f >= float(max) ? max : std::uint32_t(f);
    };
    c[0] = to_unorm(r), c[1] = to_unorm(g), c[2] = to_unorm(b), c[3] = to_unorm(a);
    return true;
}

}  // namespace

std::string decode_meshopt_color_filter(std::span<std::uint8_t> data, std::size_t count, std::size_t stride) {
    if (stride != 4 && stride != 8) return "filter COLOR needs byteStride 4 or 8, not " + std::to_string(stride);
    std::size_t size = 0;
    if (__builtin_mul_overflow(count, stride, &size) || size != data.size())
        return "the data does not hold count × byteStride bytes";
    const std::size_t width = stride / 4;
    for (std::size_t i = 0; i < count; ++i) {
        std::uint8_t* element = data.data() + i * stride;
        std::uint32_t c[4];
        for (std::size_t j = 0; j < 4; ++j) c[j] = load_le(element + j * width, width);
        if (!(stride == 4 ? color_element<8>(c) : color_element<16>(c)))
            return "element " + std::to_string(i) + " of filter COLOR has alpha " + std::to_string(c[3]) +
                   ", which marks no bit count (its highest set bit must be bit 1 or above)";
        for (std::size_t j = 0; j < 4; ++j) store_le(element + j * width, c[j], width);
    }
    return {};
}

}  // namespace tessera::gltf
