// Points and lines (Topology::points, ::lines) as GL draws them at point size
// and line width 1, made of triangles so that the one rasterizer draws them:
// each frame, every point becomes a 1×1-pixel square around its window
// position and every line a parallelogram one pixel across its minor axis,
// both placed back in world space so the rest of the pipeline (WorldPos,
// shading, depth) treats them as any surface.
//
// - A point covers the pixel whose centre lies in the square around it (the
//   nearest one; ties go by the rasterizer's top-left rule), GL's point of size
//   1. A point outside the clip volume is dropped, as GL clips points.
// - A line is GL's wide-line parallelogram at width 1: an x-major line spans
//   window y ± 0.5 at every x (a y-major one x ± 0.5), from one endpoint to the
//   other. Along the line this gives GL's diamond-exit pixels; at the ends it
//   may differ by one pixel (diamond-exit drops the last pixel when the line
//   ends inside its diamond, and starts where the line leaves the first one;
//   the parallelogram takes the pixels whose centres fall between the ends).
//   Lines are clipped at the near and far planes first; a zero-length line draws
//   nothing, as in GL.
// - Normals: the mesh's, where it has them. Without (glTF's points and lines
//   SHOULD then be drawn unlit), the material is drawn unlit (Material::unlit:
//   the base colour as the image shows it); the normal faces the camera.
// - Materials are drawn double-sided (a line has no back).
#pragma once

#include "tessera/scene.hpp"

namespace tessera::geometry {

// Whether any object of the scene draws a points or lines mesh.
bool has_points_or_lines(const Scene& scene);

// `drawn` becomes `scene` with each object drawing points or lines replaced by
// one drawing a new world-space triangle mesh (model = identity, a double-sided
// copy of its material), for the scene's camera and image size.
void expand_points_and_lines(const Scene& scene, Scene& drawn);

// The triangles standing for one points or lines mesh placed by `model`, in world space.
Mesh expand_to_triangles(const Mesh& mesh, const glm::mat4& model, const Camera& camera, int width, int height);

}  // namespace tessera::geometry
