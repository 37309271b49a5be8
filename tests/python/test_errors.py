"""Bad input becomes a Python exception carrying the C++ message: ValueError
for arrays the scene cannot take, SceneError (a ValueError) with
file:line:column for scene files."""
import numpy as np
import pytest

import tessera

SQUARE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], np.float32)
TRIANGLES = np.array([[0, 1, 2], [0, 2, 3]], np.int32)


@pytest.mark.parametrize("positions, indices, message", [
    (SQUARE.astype(np.int32), TRIANGLES, "positions: expected a float32 or float64 array, got dtype int32"),
    (SQUARE.astype(np.complex64), TRIANGLES, "positions: expected a float32 or float64 array"),
    (SQUARE[:, :2], TRIANGLES, r"positions: expected shape \(N, 3\), got \(4, 2\)"),
    (SQUARE.reshape(-1), TRIANGLES, r"positions: expected shape \(N, 3\), got \(12,\)"),
    (np.where(SQUARE == 1, np.nan, SQUARE), TRIANGLES, "positions: row 1 holds nan"),
    (np.where(SQUARE == 1, np.inf, SQUARE), TRIANGLES, "every value must be finite"),
    (SQUARE, TRIANGLES.astype(np.float32), "indices: expected an integer array, got dtype float32"),
    (SQUARE, TRIANGLES[:, :2], r"indices: expected shape \(M, 3\) or \(3M,\), got \(2, 2\)"),
    (SQUARE, np.array([[0, 1, 4]]), r"triangle 0 refers to vertex 4; expected 0..3"),
    (SQUARE, np.array([[0, 1, 2], [0, -1, 2]]), "triangle 1 refers to vertex -1"),
    (SQUARE, None, "indices: expected"),
    ("not an array", TRIANGLES, "positions: expected a float32 or float64 array"),
])
def test_bad_mesh_arrays_are_refused_with_a_value_error(positions, indices, message):
    scene = tessera.Scene()
    with pytest.raises(ValueError, match=message):
        scene.add_mesh(positions, indices)
    assert scene.mesh_count == 0  # nothing half-added


def test_bad_optional_arrays_are_refused():
    scene = tessera.Scene()
    with pytest.raises(ValueError, match="normals: expected 4 rows"):
        scene.add_mesh(SQUARE, TRIANGLES, normals=SQUARE[:3])
    with pytest.raises(ValueError, match=r"uvs: expected shape \(N, 2\)"):
        scene.add_mesh(SQUARE, TRIANGLES, uvs=SQUARE)
    with pytest.raises(ValueError, match="transform: expected shape"):
        scene.add_object(scene.add_mesh(SQUARE, TRIANGLES), scene.add_material(), transform=np.eye(3))
    with pytest.raises(ValueError, match="transform: every value must be finite"):
        scene.add_object(0, 0, transform=np.full((4, 4), np.nan))
    with pytest.raises(ValueError, match="no material 5"):
        scene.add_object(0, 5)
    with pytest.raises(ValueError, match="pixels: expected a uint8 or float array"):
        scene.add_texture(np.zeros((4, 4, 3), np.int16))
    with pytest.raises(ValueError, match="albedo: expected"):
        scene.add_material(albedo=(2, 0, 0))
    with pytest.raises(ValueError, match="albedo_texture: no texture 0"):
        scene.add_material(albedo_texture=0)
    with pytest.raises(ValueError, match="type: expected 'point'"):
        scene.add_light("area")


def test_good_arrays_of_other_layouts_are_taken():
    scene = tessera.Scene()
    scene.add_mesh(SQUARE.astype(np.float64)[::1], TRIANGLES.reshape(-1).astype(np.uint64))
    scene.add_mesh(np.asfortranarray(SQUARE), TRIANGLES.T.copy().T)  # not C-ordered: converted once
    assert scene.mesh_count == 2


def test_a_scene_file_error_keeps_file_line_and_column(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[camera]\nposition = [0, 0, 3]\ntarget = [0, 0, 0]\nfov_y = 270.0\n')
    with pytest.raises(tessera.SceneError) as error:
        tessera.load(path)
    assert str(error.value).startswith(f"{path}:4:")
    assert "fov_y" in str(error.value)
    assert isinstance(error.value, ValueError)
    with pytest.raises(tessera.SceneError, match="cannot"):
        tessera.load(tmp_path / "missing.toml")


def test_renderer_settings_are_checked():
    with pytest.raises(ValueError, match="unknown AOV 'colour'"):
        tessera.Renderer(aovs=("depth", "colour"))
    with pytest.raises(ValueError, match="tile size"):
        tessera.Renderer(tile_size=48)
    with pytest.raises(ValueError, match="msaa"):
        tessera.Renderer(msaa=2)
    with pytest.raises(ValueError, match="image size"):
        tessera.Renderer(0, 10)
    with pytest.raises(ValueError, match="unknown ISA"):
        tessera.Renderer(isa="neon")
