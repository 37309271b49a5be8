#include "shade/surface_gather.hpp"

#include <algorithm>

namespace tessera::shade {

void FragmentBuffer::reserve(std::size_t max_fragments) {
    capacity_ = max_fragments;
    triangles_.reserve(max_fragments);
    // A kernel over a run starting anywhere may read whole vectors past the
    // run's end: one vector of slack past the padded size.
    for (auto& c : channels_) c.resize(padded_count(max_fragments) + kLanePadding);
}

void FragmentBuffer::pad(std::size_t count) {
    for (auto& c : channels_)
        for (std::size_t i = count; i < padded_count(count); ++i) c[i] = count > 0 ? c[0] : 0.5f;
}

void FragmentBuffer::fill_plain_runs(std::span<const MaterialRun> runs, std::size_t count) {
    bool any = false;
    for (const MaterialRun& run : runs)
        if (run.plain) set_material(run.begin, run.end, *run.material), any = true;
    if (!any || count == 0) return;
    for (int c = albedo_r; c <= ao; ++c)  // as pad() fills them
        std::fill(channels_[c].begin() + count, channels_[c].begin() + padded_count(count), channels_[c][0]);
}

void FragmentBuffer::fill_plain_run_edges(std::span<const MaterialRun> runs, std::size_t count) {
    // A batch of any ISA's width (a divisor of kLanePadding, starting at a
    // multiple of it) lies wholly inside a run or reaches at most this far into it.
    const auto down = [](std::size_t i) { return i / kLanePadding * kLanePadding; };
    for (const MaterialRun& run : runs) {
        if (!run.plain) continue;
        const std::size_t head_end = std::min<std::size_t>(run.end, down(run.begin + kLanePadding - 1));
        set_material(run.begin, head_end, *run.material);
        // The last run's batches run on into the padding, which counts as its own.
        if (run.end < count) set_material(std::max<std::size_t>(head_end, down(run.end)), run.end, *run.material);
    }
}

FragmentInputs FragmentBuffer::inputs(std::size_t count) const {
    return {count,
            channels_[world_x].data(),  channels_[world_y].data(),  channels_[world_z].data(),
            channels_[normal_x].data(), channels_[normal_y].data(), channels_[normal_z].data(),
            channels_[albedo_r].data(), channels_[albedo_g].data(), channels_[albedo_b].data(),
            channels_[metallic].data(), channels_[roughness].data(), channels_[ao].data()};
}

RadianceOutputs FragmentBuffer::outputs() { return {channels_[out_r].data(), channels_[out_g].data(), channels_[out_b].data()}; }

}  // namespace tessera::shade
