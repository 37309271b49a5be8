"""The module renders what the command line renders, bit for bit: the same
scene files, settings and libraries give the same PNG, and the EXR's AOVs
hold the arrays' values."""
import numpy as np
import pytest

import tessera


@pytest.mark.parametrize("scene_name, size", [("shapes.toml", (192, 108)), ("spheres_msaa.toml", (160, 90)),
                                              ("textured.toml", (160, 90))])
def test_png_equals_the_clis_bit_for_bit(tmp_path, scenes_dir, tessera_cli, scene_name, size):
    width, height = size
    out = tmp_path / "cli.png"
    tessera_cli("render", scenes_dir / scene_name, "-o", out, "--width", width, "--height", height, "--threads", 2)
    frame = tessera.Renderer(width, height, threads=2).render(tessera.load(scenes_dir / scene_name))
    assert np.array_equal(tessera.read_image(out), frame.color)


def test_exr_aovs_equal_the_arrays(tmp_path, scenes_dir, tessera_cli):
    out = tmp_path / "cli.exr"
    tessera_cli("render", scenes_dir / "shapes.toml", "-o", out, "--width", 128, "--height", 72,
                "--aov", "depth,object_id,material_id")
    frame = tessera.Renderer(128, 72, aovs=("depth", "object_id", "material_id"), radiance=True).render(
        tessera.load(scenes_dir / "shapes.toml"))
    channel = tessera.read_image(out, channels=True)
    assert sorted(channel) == ["B", "G", "R", "Z", "material_id", "object_id"]
    assert channel["object_id"].dtype == np.uint32
    assert np.array_equal(channel["Z"], frame.depth)
    assert np.array_equal(channel["material_id"], frame.material_id)
    assert np.array_equal(channel["object_id"], frame.object_id)
    assert set(np.unique(frame.object_id)) == {0, 1, 2, 3, 4}
    frame.save(tmp_path / "python.exr")
    assert np.array_equal(tessera.read_image(tmp_path / "python.exr"), tessera.read_image(out))
