// The order blended objects are drawn in (AlphaMode::blend): back to front, so
// that each is composited over what lies behind it.
//
// Sorted per object (a glTF primitive is one object), by the view-space depth
// of the centre of its mesh's object-space bounding box placed by its model
// matrix: the farthest first. Ties keep scene order (a stable sort), so the
// order — and the image — depends on the scene and camera only, never on
// threads or tiles. Within an object, triangles keep their mesh order, as a GL
// draw call does: an object that overlaps itself on screen (both sides of a
// double-sided glass) is not sorted per triangle. Objects whose bounds
// interpenetrate can be ordered wrongly where they overlap: the usual limit of
// per-object sorting, which per-triangle or order-independent schemes lift.
#pragma once

#include <cstdint>
#include <vector>

#include "tessera/scene.hpp"

namespace tessera::geometry {

// Indices of the scene's objects whose material is AlphaMode::blend, farthest first.
std::vector<std::uint32_t> blended_objects_back_to_front(const Scene& scene);

// The view-space depth (distance in front of the camera along its axis) of
// the object's bounds centre; a mesh without finite positions sorts at 0.
float object_view_depth(const Scene& scene, const Object& object);

}  // namespace tessera::geometry
