"""Renderer and Frame: array shapes and types, the background values, and the
memory: arrays view the frame's images without a copy and stay valid."""
import gc

import numpy as np
import pytest

import tessera
from conftest import quad_scene


def data_address(array):
    return array.__array_interface__["data"][0]


def test_arrays_have_the_documented_shapes_types_and_backgrounds():
    scene = quad_scene()
    frame = tessera.Renderer(threads=2, aovs="all", radiance=True).render(scene)
    h, w = 48, 64
    assert (frame.width, frame.height) == (w, h)
    for name, shape, dtype in [("color", (h, w, 3), np.uint8), ("radiance", (h, w, 3), np.float32),
                               ("depth", (h, w), np.float32), ("normal", (h, w, 3), np.float32),
                               ("albedo", (h, w, 3), np.float32), ("roughness", (h, w), np.float32),
                               ("metallic", (h, w), np.float32), ("position", (h, w, 3), np.float32),
                               ("object_id", (h, w), np.uint32), ("material_id", (h, w), np.uint32)]:
        array = getattr(frame, name)
        assert array.shape == shape, name
        assert array.dtype == dtype, name
    inside = frame.object_id == 1
    assert 100 < inside.sum() < h * w - 100  # the square covers part of the view
    assert np.all(frame.material_id[inside] == 1)
    assert np.all(frame.material_id[~inside] == 0)
    assert np.all(np.isinf(frame.depth[~inside]))
    # The square is at z = 0, 3 units in front of the camera, facing it.
    np.testing.assert_allclose(frame.depth[inside], 3.0, rtol=1e-5)
    np.testing.assert_allclose(frame.normal[inside], [[0, 0, 1]] * int(inside.sum()), atol=1e-6)
    np.testing.assert_allclose(frame.albedo[inside][0], [0.8, 0.3, 0.1], rtol=1e-6)
    assert np.all(frame.normal[~inside] == 0)
    # The colour image's background is the clear colour, as glClear writes it.
    assert len(np.unique(frame.color[~inside], axis=0)) == 1


def test_aovs_not_asked_for_are_none():
    frame = tessera.Renderer(aovs=("depth",)).render(quad_scene())
    assert frame.depth is not None
    for name in ("radiance", "normal", "albedo", "position", "object_id", "material_id"):
        assert getattr(frame, name) is None, name


def test_arrays_view_the_frames_memory_without_a_copy():
    renderer = tessera.Renderer(threads=1, aovs=("depth", "object_id"))
    frame = renderer.render(quad_scene())
    color, again = frame.color, frame.color
    assert np.shares_memory(color, again)  # two views of one buffer, not two copies
    assert not color.flags.owndata
    assert color.base is not None  # the owner that keeps the frame's images alive
    assert np.shares_memory(frame.depth, frame.depth)
    assert np.shares_memory(frame.object_id, frame.object_id)


def test_arrays_stay_valid_after_their_frame_is_dropped_and_other_frames_render():
    renderer = tessera.Renderer(threads=1, aovs=("object_id",))
    scene = quad_scene()
    color = renderer.render(scene).color  # the Frame itself is gone at once
    kept = color.copy()
    scene.clear_color = (1.0, 1.0, 1.0)
    for _ in range(3):
        other = renderer.render(scene).color
        assert not np.shares_memory(other, color)
    assert np.array_equal(color, kept)


def test_a_loop_that_drops_its_frames_reuses_their_memory():
    renderer = tessera.Renderer(threads=1)
    scene = quad_scene()
    addresses = set()
    for _ in range(6):
        frame = renderer.render(scene)
        addresses.add(data_address(frame.color))
        del frame
        gc.collect()
    # Two buffers at most take turns (the frame in hand and the one being rendered).
    assert len(addresses) <= 2


def test_renderer_size_and_msaa_override_the_scenes_and_leave_it_unchanged():
    scene = quad_scene()
    frame = tessera.Renderer(32, 24, msaa=4).render(scene)
    assert frame.color.shape == (24, 32, 3)
    assert (scene.width, scene.height, scene.msaa) == (64, 48, 1)


def test_frames_save_png_and_exr(tmp_path):
    frame = tessera.Renderer(aovs=("depth", "object_id"), radiance=True).render(quad_scene())
    frame.save(tmp_path / "quad.png")
    assert np.array_equal(tessera.read_image(tmp_path / "quad.png"), frame.color)
    frame.save(tmp_path / "quad.exr")
    assert tessera.read_image(tmp_path / "quad.exr").shape == (48, 64, 5)  # R G B Z object_id
    with pytest.raises(tessera.ImageError, match="no HDR radiance"):
        tessera.Renderer().render(quad_scene()).save(tmp_path / "no_radiance.exr")


def test_loaded_scenes_render(scenes_dir):
    scene = tessera.load(scenes_dir / "shapes.toml")
    assert scene.object_count == 4
    frame = tessera.Renderer(160, 90, aovs=("object_id",)).render(scene)
    assert set(np.unique(frame.object_id)) == {0, 1, 2, 3, 4}
