"""Shared fixtures of the Python module's tests. ctest runs each file with
PYTHONPATH at the build tree's python/ (tests/python/CMakeLists.txt)."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import tessera

SOURCE_DIR = pathlib.Path(os.environ.get("TESSERA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
ASSETS_DIR = SOURCE_DIR / ".." / "shared" / "assets"


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def scenes_dir():
    return SOURCE_DIR / "scenes"


@pytest.fixture
def assets_dir():
    if not ASSETS_DIR.is_dir():
        pytest.skip(f"the shared sample models are not at {ASSETS_DIR}")
    return ASSETS_DIR


@pytest.fixture
def tessera_cli():
    """Runs the tessera command line; fails the test with its stderr if it fails."""
    binary = os.environ.get("TESSERA_BIN")
    if not binary:
        pytest.skip("TESSERA_BIN names no tessera binary (ctest sets it)")

    def run(*args):
        done = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        return done
    return run


def quad_scene(width=64, height=48):
    """A unit square facing +Z at the origin, seen from z = 3: a small scene for many tests."""
    scene = tessera.Scene(width, height)
    positions = np.array([[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]], np.float32)
    mesh = scene.add_mesh(positions, np.array([[0, 1, 2], [0, 2, 3]], np.uint32))
    material = scene.add_material(albedo=(0.8, 0.3, 0.1), roughness=0.4)
    scene.add_object(mesh, material)
    scene.add_light("point", position=(1, 2, 3), color=(20, 20, 20))
    scene.camera = tessera.Camera(position=(0, 0, 3), target=(0, 0, 0))
    return scene


def pytest_sessionfinish(session, exitstatus):
    # Every test skipped (e.g. no sample models): exit 77, which ctest reports as Skipped, not Passed.
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    if reporter.stats.get("skipped") and not reporter.stats.get("passed"):
        session.exitstatus = 77
