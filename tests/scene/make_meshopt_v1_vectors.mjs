// Writes tests/scene/meshopt_v1_vectors.hpp: attribute streams of codec version 1
// and filter COLOR made by meshoptimizer's own encoder (npm `meshoptimizer`, the
// WebAssembly build of the C++ library), for test_meshopt_codec_v1.cpp. Not needed
// to run the tests. Run it in a folder where `npm install meshoptimizer@1.3.0` was done:
//   node $TESSERA/tests/scene/make_meshopt_v1_vectors.mjs > $TESSERA/tests/scene/meshopt_v1_vectors.hpp
// The element data comes from vector_data() below, which the test repeats in C++
// (integer arithmetic only), so only the encoded streams are stored.
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';
const dir = path.join(process.cwd(), 'node_modules', 'meshoptimizer');
const { MeshoptEncoder, MeshoptDecoder } = await import(pathToFileURL(path.join(dir, 'index.js')));
const pkg = JSON.parse(fs.readFileSync(path.join(dir, 'package.json')));

// The test's `vector_data`: element i, byte b of vector kind `kind`.
function vector_data(kind, count, stride) {
	const out = new Uint8Array(count * stride);
	let s = 12345;
	const rand = () => {
		s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
		return s >>> 24;
	};
	for (let i = 0; i < count; ++i) {
		for (let b = 0; b < stride; b += 4) {
			let v = 0; // one little-endian 32-bit word per 4 bytes
			const c = b / 4;
			if (kind === 'smooth16') {
				// two 16-bit components drifting slowly: 16-bit deltas
				const lo = (1000 * c + 3 * i + (rand() & 3)) & 0xffff;
				const hi = (60000 - 7 * i * (c + 1) + (rand() & 1)) & 0xffff;
				v = (lo | (hi << 16)) >>> 0;
			} else if (kind === 'floatbits') {
				// float bit patterns: sign and exponent steady, mantissa bits changing
				v = (0x3f800000 + ((i * 40503 + c * 9973) & 0x7fffff)) >>> 0;
				if ((i + c) % 5 === 0) v = (v ^ 0x80000000) >>> 0;
			} else if (kind === 'random') {
				v = (rand() | (rand() << 8) | (rand() << 16) | (rand() << 24)) >>> 0;
			} else if (kind === 'steady') {
				// constant bytes but one: zero columns
				v = (0x11223300 | (c === 0 ? i & 0xff : 0x44)) >>> 0;
			} else if (kind === 'sparse') {
				// a byte that changes every 29 elements, by a little: zero groups under control mode 0
				v = (0x01000000 * (c + 1) + (Math.floor(i / 29) * 3 + c) % 7) >>> 0;
			} else if (kind === 'tiny') {
				// deltas of 0 and 1: 1-bit groups
				v = (((i >> 1) + (rand() & 1)) & 0xff) * 0x01010101;
			}
			out[i * stride + b] = v & 0xff;
			out[i * stride + b + 1] = (v >>> 8) & 0xff;
			out[i * stride + b + 2] = (v >>> 16) & 0xff;
			out[i * stride + b + 3] = v >>> 24;
		}
	}
	return out;
}

// What a stream uses, read from its structure (control modes, group bit widths, channel modes).
function features(stream, count, stride) {
	const version = stream[0] & 15;
	const blockMax = Math.min((8192 / stride) & ~15, 256);
	const tail = stride + stride / 4;
	const channels = [...stream.slice(stream.length - stride / 4)];
	const used = { control: new Set(), bits: new Set(), channel: new Set(channels.map((c) => (c & 3) + (c >> 4 ? `r${c >> 4}` : ''))) };
	let at = 1;
	for (let first = 0; first < count; first += blockMax) {
		const n = Math.min(count - first, blockMax), groups = Math.ceil(n / 16), hb = Math.ceil(groups / 4);
		const control = at;
		at += stride / 4;
		for (let k = 0; k < stride; ++k) {
			const cm = (stream[control + (k >> 2)] >> (2 * (k & 3))) & 3;
			used.control.add(cm);
			if (cm === 2) continue;
			if (cm === 3) { at += n; continue; }
			const header = at;
			at += hb;
			for (let g = 0; g < groups; ++g) {
				const bits = [[0, 1, 2, 4], [1, 2, 4, 8]][cm][(stream[header + (g >> 2)] >> (2 * (g & 3))) & 3];
				used.bits.add(bits);
				if (bits === 0) continue;
				if (bits === 8) { at += 16; continue; }
				const packed = 2 * bits, per = 8 / bits, sentinel = (1 << bits) - 1;
				let extra = 0;
				for (let i = 0; i < 16; ++i) {
					const byte = stream[at + Math.floor(i / per)];
					const d = bits === 1 ? (byte >> (i % 8)) & 1 : (byte >> (8 - bits * (1 + (i % per)))) & sentinel;
					if (d === sentinel) extra++;
				}
				at += packed + extra;
			}
		}
	}
	if (version !== 1 || at !== stream.length - Math.max(tail, 24)) throw new Error('structure walk disagrees with the stream');
	return `control modes {${[...used.control].sort()}}, group bits {${[...used.bits].sort((a, b) => a - b)}}, channels {${[...used.channel]}}`;
}

function hex(bytes) {
	const lines = [];
	for (let i = 0; i < bytes.length; i += 24)
		lines.push('    ' + [...bytes.slice(i, i + 24)].map((b) => '0x' + b.toString(16).padStart(2, '0')).join(', ') + ',');
	return lines.join('\n');
}

await MeshoptEncoder.ready;
await MeshoptDecoder.ready;

const attribute_vectors = [
	['smooth16', 300, 8, 2],
	['smooth16', 300, 8, 0],
	['floatbits', 70, 12, 3],
	['random', 40, 16, 2],
	['steady', 70, 4, 2],
	['tiny', 100, 4, 2],
	['floatbits', 20, 32, 3],
	['sparse', 200, 8, 2],
	['random', 1, 4, 1],
];

let text = `// Made by make_meshopt_v1_vectors.mjs with npm meshoptimizer ${pkg.version}; do not edit.
// Attribute streams of codec version 1 by meshoptimizer's encoder, each of the
// elements vector_data(kind, count, stride) makes, and filter COLOR streams with
// the decoder's RGBA output.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::test::meshopt_v1 {

struct AttributeVector {
    const char* kind;
    std::size_t count, stride;
    int level;
    const char* uses;
    const std::uint8_t* stream;
    std::size_t stream_size;
};

struct ColorVector {
    std::size_t count, stride;
    int bits;
    const std::uint8_t* stream;  // codec version 1, filter COLOR
    std::size_t stream_size;
    const std::uint8_t* rgba;    // meshoptimizer's decoded output, count × stride bytes
};

`;
const names = [];
attribute_vectors.forEach(([kind, count, stride, level], v) => {
	const data = vector_data(kind, count, stride);
	const stream = MeshoptEncoder.encodeVertexBufferLevel(data, count, stride, level, 1);
	const check = new Uint8Array(count * stride);
	MeshoptDecoder.decodeVertexBuffer(check, count, stride, stream);
	if (!check.every((b, i) => b === data[i])) throw new Error('meshoptimizer does not round-trip ' + kind);
	const uses = features(stream, count, stride);
	text += `inline constexpr std::uint8_t kAttributes${v}[] = {\n${hex(stream)}\n};\n`;
	names.push(`    {"${kind}", ${count}, ${stride}, ${level}, "${uses}", kAttributes${v}, sizeof(kAttributes${v})},`);
});
text += `\ninline constexpr AttributeVector kAttributeVectors[] = {\n${names.join('\n')}\n};\n\n`;

const color_vectors = [
	[4, 8],
	[4, 5],
	[8, 16],
	[8, 10],
];
const cnames = [];
color_vectors.forEach(([stride, bits], v) => {
	const count = 37;
	const rgba = new Float32Array(count * 4);
	for (let i = 0; i < count; ++i) {
		rgba[i * 4 + 0] = ((i * 37) % 64) / 63;
		rgba[i * 4 + 1] = ((i * 11 + 5) % 32) / 31;
		rgba[i * 4 + 2] = i % 3 === 0 ? 1 : ((i * 23) % 17) / 16;
		rgba[i * 4 + 3] = i % 4 === 0 ? 1 : ((i * 7) % 10) / 9;
	}
	const filtered = MeshoptEncoder.encodeFilterColor(rgba, count, stride, bits);
	const stream = MeshoptEncoder.encodeVertexBufferLevel(filtered, count, stride, 2, 1);
	const out = new Uint8Array(count * stride);
	MeshoptDecoder.decodeGltfBuffer(out, count, stride, stream, 'ATTRIBUTES', 'COLOR');
	text += `inline constexpr std::uint8_t kColorStream${v}[] = {\n${hex(stream)}\n};\n`;
	text += `inline constexpr std::uint8_t kColorRgba${v}[] = {\n${hex(out)}\n};\n`;
	cnames.push(`    {${count}, ${stride}, ${bits}, kColorStream${v}, sizeof(kColorStream${v}), kColorRgba${v}},`);
});
text += `\ninline constexpr ColorVector kColorVectors[] = {\n${cnames.join('\n')}\n};\n\n}  // namespace tessera::test::meshopt_v1\n`;
process.stdout.write(text);
