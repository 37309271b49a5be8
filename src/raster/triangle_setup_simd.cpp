// triangle setup's integer part over vectors of triangles (raster_kernels.hpp),
// compiled once per ISA. Each lane does what setup_triangle() does for one
// triangle, in int32: exact for triangles spanning less than 64 pixels, whose
// coordinate deltas stay below 2^14 so that every product stays below 2^30.
// Larger triangles are handed back to the scalar int64 code.
#include <cstdint>

#include "simd/kernel_prelude.hpp"

#include "simd/hardware_gather.hpp"

#include "raster/raster_kernels.hpp"
#include "raster/raster_limits.hpp"

namespace tessera::raster {
namespace {

using Arch = TESSERA_SIMD_ARCH;
using Int = xsimd::batch<std::int32_t, Arch>;
using Mask = xsimd::batch_bool<std::int32_t, Arch>;
static_assert(kSetupBatch % Int::size == 0);

constexpr std::int32_t kMaxExtent = 1 << 14;  // fixed-point units: 64 pixels

// Edge a→b at centre p, biased by the top-left rule (as EdgeStepper).
Int biased_edge(const Int& ax, const Int& ay, const Int& bx, const Int& by, const Int& px, const Int& py) {
    const Int dx = bx - ax, dy = by - ay;
    const Mask top_left = (dy < Int(0)) | ((dy == Int(0)) & (dx > Int(0)));
    const Int bias = xsimd::select(top_left, Int(0), Int(-1));
    return dx * (py - ay) - dy * (px - ax) + bias;
}

void setup_batch(const SetupBatchInput& in, SetupBatchOutput& out) {
    constexpr int kLanes = int(Int::size);
    const Int half(kSubpixelScale / 2), round_up(kSubpixelScale - 1), zero(0), one(1);
    const Int last_x(in.width - 1), last_y(in.height - 1);
    for (int i = 0; i < in.count; i += kLanes) {
        // Corner positions: x at int32 index 4·ref, y at 4·ref + 1.
        Int x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            const Int at = Int::load_unaligned(in.ref[k] + i) * Int(4);
            x[k] = simd::hardware_gather(in.screen, at);
            y[k] = simd::hardware_gather(in.screen, at + one);
        }
        const Int min_x = xsimd::min(x[0], xsimd::min(x[1], x[2])), max_x = xsimd::max(x[0], xsimd::max(x[1], x[2]));
        const Int min_y = xsimd::min(y[0], xsimd::min(y[1], y[2])), max_y = xsimd::max(y[0], xsimd::max(y[1], y[2]));
        // Pixel box of the centres inside the extent (>> is floor division), clamped to the image.
        const Int px_min = xsimd::max((min_x - half + round_up) >> kSubpixelBits, zero);
        const Int px_max = xsimd::min((max_x - half) >> kSubpixelBits, last_x);
        const Int py_min = xsimd::max((min_y - half + round_up) >> kSubpixelBits, zero);
        const Int py_max = xsimd::min((max_y - half) >> kSubpixelBits, last_y);
        const Mask empty = (px_min > px_max) | (py_min > py_max);
        const Mask small_enough = ((max_x - min_x) < Int(kMaxExtent)) & ((max_y - min_y) < Int(kMaxExtent));

        const Int area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        const Mask swapped = area < zero;
        const Int double_area = xsimd::abs(area);
        // Corners 1 and 2 as setup orders them.
        const Int x1 = xsimd::select(swapped, x[2], x[1]), y1 = xsimd::select(swapped, y[2], y[1]);
        const Int x2 = xsimd::select(swapped, x[1], x[2]), y2 = xsimd::select(swapped, y[1], y[2]);

        // Boxes of at most 2×2 centres: is any of them covered?
        Mask covered(false);
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const Int cx = px_min + Int(dx), cy = py_min + Int(dy);
                const Int px = cx * Int(kSubpixelScale) + half, py = cy * Int(kSubpixelScale) + half;
                const Int w0 = biased_edge(x1, y1, x2, y2, px, py);
                const Int w1 = biased_edge(x2, y2, x[0], y[0], px, py);
                const Int w2 = biased_edge(x[0], y[0], x1, y1, px, py);
                covered = covered | ((((w0 | w1) | w2) >= zero) & (cx <= px_max) & (cy <= py_max));
            }
        const Mask small_box = ((px_max - px_min) <= one) & ((py_max - py_min) <= one);

        // The scalar order of decisions: no area, then an empty box, then an uncovered small box.
        const Mask dropped = small_enough & ((area == zero) | empty | (small_box & !covered));
        const Int verdict = xsimd::select(
            empty, Int(kSetupDropped),
            xsimd::select(!small_enough, Int(kSetupScalar), xsimd::select(dropped, Int(kSetupDropped), Int(kSetupKept))));
        verdict.store_unaligned(out.verdict + i);
        xsimd::select(swapped, one, zero).store_unaligned(out.swapped + i);
        double_area.store_unaligned(out.double_area + i);
        px_min.store_unaligned(out.px_min + i);
        px_max.store_unaligned(out.px_max + i);
        py_min.store_unaligned(out.py_min + i);
        py_max.store_unaligned(out.py_max + i);
    }
}

}  // namespace

void TESSERA_SIMD_ENTRY(setup_batch)(const SetupBatchInput& in, SetupBatchOutput& out) {
    setup_batch(in, out);
}

}  // namespace tessera::raster
