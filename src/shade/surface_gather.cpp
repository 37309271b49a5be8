#include "shade/surface_gather.hpp"

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

FragmentInputs FragmentBuffer::inputs(std::size_t count) const {
    return {count,
            channels_[world_x].data(),  channels_[world_y].data(),  channels_[world_z].data(),
            channels_[normal_x].data(), channels_[normal_y].data(), channels_[normal_z].data(),
            channels_[albedo_r].data(), channels_[albedo_g].data(), channels_[albedo_b].data(),
            channels_[metallic].data(), channels_[roughness].data(), channels_[ao].data()};
}

RadianceOutputs FragmentBuffer::outputs() { return {channels_[out_r].data(), channels_[out_g].data(), channels_[out_b].data()}; }

}  // namespace tessera::shade
