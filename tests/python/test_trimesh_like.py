"""Scene.add_mesh given a trimesh-like object (trimesh.Trimesh's attributes: vertices,
faces, vertex_normals, visual.uv) instead of arrays. trimesh itself is not packaged in
Debian 12, so the objects here are plain classes with those attributes: what the module
reads of a mesh is exactly them."""
import numpy as np
import pytest

import tessera


class Visual:
    def __init__(self, uv):
        self.uv = uv


class TrimeshLike:
    def __init__(self, vertices, faces, vertex_normals=None, uv=None):
        self.vertices = vertices
        self.faces = faces
        if vertex_normals is not None:
            self.vertex_normals = vertex_normals
        self.visual = Visual(uv)


# A square facing the camera whose normals lean away from +Z (so smooth normals, the
# default without them, would differ), with uvs that put a 2×2 checker's cells on it.
POSITIONS = np.array([[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]], np.float64)
FACES = np.array([[0, 1, 2], [0, 2, 3]], np.int64)
LEANING = np.array([[0.3, 0, 1], [0.3, 0, 1], [-0.2, 0.4, 1], [-0.2, 0.4, 1]], np.float64)
LEANING /= np.linalg.norm(LEANING, axis=1, keepdims=True)
UVS = np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float64)
CHECKER = np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [255, 255, 255]]], np.uint8)


def render(add_mesh):
    scene = tessera.Scene(64, 48)
    texture = scene.add_texture(CHECKER)
    mesh = add_mesh(scene)
    scene.add_object(mesh, scene.add_material(albedo=(1, 1, 1), roughness=0.5, albedo_texture=texture))
    scene.add_light("point", position=(1, 2, 3), color=(20, 20, 20))
    scene.camera = tessera.Camera(position=(0, 0, 2), target=(0, 0, 0))
    return tessera.Renderer(threads=1, aovs="all").render(scene)


def test_a_trimesh_like_mesh_renders_as_its_arrays_do():
    from_arrays = render(lambda s: s.add_mesh(POSITIONS, FACES, normals=LEANING, uvs=UVS))
    from_object = render(lambda s: s.add_mesh(TrimeshLike(POSITIONS, FACES, LEANING, UVS)))
    inside = from_arrays.object_id == 1
    assert inside.sum() > 500
    np.testing.assert_array_equal(from_object.color, from_arrays.color)
    np.testing.assert_array_equal(from_object.normal, from_arrays.normal)
    # Its normals and uvs were read, not defaulted: the normal AOV leans, all four cells show.
    assert np.abs(from_object.normal[inside][:, 0]).max() > 0.1
    colours = {tuple(c) for c in (from_object.albedo[inside] > 0.5).astype(int)}
    assert {(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)} <= colours


def test_a_trimesh_like_mesh_without_normals_or_uvs_gets_the_defaults():
    from_arrays = render(lambda s: s.add_mesh(POSITIONS, FACES))
    from_object = render(lambda s: s.add_mesh(TrimeshLike(POSITIONS, FACES, uv=None)))
    np.testing.assert_array_equal(from_object.color, from_arrays.color)
    inside = from_object.object_id == 1
    np.testing.assert_allclose(from_object.normal[inside], [[0, 0, 1]] * int(inside.sum()), atol=1e-6)


def test_a_trimesh_like_mesh_with_bad_faces_is_refused():
    with pytest.raises(ValueError, match="indices"):
        render(lambda s: s.add_mesh(TrimeshLike(POSITIONS, np.array([[0, 1, 7]]))))
