// The pieces of animation evaluation that the [animation] reader also needs
// (to check every frame's camera at load) and that tests check one by one.
#pragma once

#include "tessera/animation.hpp"

namespace tessera {

// A track's value at `frame` (fractional frames allowed); the track is not empty.
template <typename Value>
Value sample_track(const Track<Value>& track, Interpolation interpolation, double frame);

// Where an orbiting camera is at `frame`.
glm::vec3 orbit_position(const CameraOrbit& orbit, int frame_count, double frame);

// translate · Rz · Ry · Rx · scale, as [[objects]] places an object.
glm::mat4 placement_matrix(const glm::vec3& translate, const glm::vec3& rotate_degrees, const glm::vec3& scale);

// Writes the animated camera values at `frame` into `camera` (the others stay).
void evaluate_camera(const Animation& animation, double frame, Camera& camera);

// Poses the scene's glTF models that play an animation at `frame` (posed_models.cpp).
void pose_models_at_frame(Scene& scene, int frame, double fps);

}  // namespace tessera
