// Checks a Scene built in code (not read from a file) before it reaches the
// pipeline, whose stages trust their input: a mesh index past the end of its
// vertex arrays would read out of bounds there. Scene files are validated as
// they are read; this covers scenes assembled by programs and tests, and the
// CLI's size overrides.
#pragma once

#include <filesystem>

#include "tessera/scene.hpp"

namespace tessera {

// Throws SceneError reading "source: message" (source is Scene::source, or
// "scene" when empty) for the first problem found, naming the mesh, object or
// field at fault:
// - image size: each side in 1..kMaxImageDimension, width·height <= kMaxImagePixels;
// - camera: finite, fov_y in (0, 180), 0 < near < far, target != position,
//   up non-zero and not parallel to the view direction;
// - clear colour, lights and materials finite and in their documented ranges;
// - objects: mesh and material indices in range, a finite model matrix;
// - meshes: normals (and uvs, when present) as many as positions, a whole
//   number of triangles, every index < positions.size().
// Non-finite vertex positions or normals are not errors: the renderer drops
// such triangles, as a GPU would, rather than refusing the frame.
void validate_scene(const Scene& scene);

// A scene file's kind comes from its extension (any case): .toml is a scene
// file, .gltf and .glb a model rendered on its own. Anything else (.obj, .ply,
// .png, none) throws SceneError "PATH: not a scene file (expected .toml, .gltf
// or .glb)" before the file is read: load_scene_file calls it, and the CLI
// calls it for every scene before starting work.
void check_scene_file_extension(const std::filesystem::path& path);

}  // namespace tessera
