"""Cameras from intrinsics K and an extrinsic, in OpenCV's and OpenGL's
conventions, checked against a point projected by hand and against every
pixel's seen world position."""
import numpy as np
import pytest

import tessera

WIDTH, HEIGHT = 160, 100
FX, FY, CX, CY = 300.0, 280.0, 70.3, 40.6  # off-centre principal point, non-square pixels
K = np.array([[FX, 0, CX], [0, FY, CY], [0, 0, 1]])


def rotation(y_degrees, x_degrees):
    a, b = np.radians(y_degrees), np.radians(x_degrees)
    ry = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
    return ry @ rx


# World to OpenCV camera (x right, y down, z forward).
R = rotation(15, -10)
T = np.array([0.2, -0.1, 4.0])
EXTRINSIC_CV = np.eye(4)
EXTRINSIC_CV[:3, :3], EXTRINSIC_CV[:3, 3] = R, T
# The same camera in OpenGL's frame (x right, y up, looking along -z).
EXTRINSIC_GL = np.diag([1.0, -1.0, -1.0, 1.0]) @ EXTRINSIC_CV

# A point at camera coordinates (0.3, -0.2, 4.5), projected by hand:
#   u = fx·X/Z + cx = 300·0.3/4.5 + 70.3 = 90.3
#   v = fy·Y/Z + cy = 280·(-0.2)/4.5 + 40.6 = 28.1556
POINT_CAMERA = np.array([0.3, -0.2, 4.5])
POINT_WORLD = R.T @ (POINT_CAMERA - T)
POINT_PIXEL = (90.3, 28.1556)


def plane_scene(camera):
    """A large quad through the point, turned a little away from the image plane."""
    scene = tessera.Scene(WIDTH, HEIGHT)
    right, down, forward = R.T[:, 0], R.T[:, 1], R.T[:, 2]
    corners = [POINT_WORLD + 3 * (s * right + t * down) + 0.4 * s * forward for s, t in
               [(-1, -1), (1, -1), (1, 1), (-1, 1)]]
    mesh = scene.add_mesh(np.array(corners), np.array([[0, 1, 2], [0, 2, 3]]))
    scene.add_object(mesh, scene.add_material())
    scene.add_light("directional", direction=-forward, color=(2, 2, 2))
    scene.camera = camera
    return scene


def seen_pixels(frame):
    """Each pixel's seen world point projected by hand through K and the extrinsic."""
    camera_points = frame.position.reshape(-1, 3) @ R.T + T
    u = FX * camera_points[:, 0] / camera_points[:, 2] + CX
    v = FY * camera_points[:, 1] / camera_points[:, 2] + CY
    return u.reshape(HEIGHT, WIDTH), v.reshape(HEIGHT, WIDTH), camera_points[:, 2].reshape(HEIGHT, WIDTH)


@pytest.mark.parametrize("convention, extrinsic", [("opencv", EXTRINSIC_CV), ("opengl", EXTRINSIC_GL)])
def test_intrinsics_project_as_k_says(convention, extrinsic):
    camera = tessera.Camera.from_intrinsics(K, extrinsic, WIDTH, HEIGHT, convention=convention, near=0.5, far=50)
    np.testing.assert_allclose(camera.position, -R.T @ T, atol=1e-5)  # the camera centre, -Rᵀt
    frame = tessera.Renderer(threads=2, aovs=("position", "depth", "object_id")).render(plane_scene(camera))
    assert np.all(frame.object_id == 1)  # the quad fills the view

    # The hand-computed point lands on its pixel: integer coordinates are pixel centres (OpenCV's rule).
    i, j = round(POINT_PIXEL[0]), round(POINT_PIXEL[1])
    seen = frame.position[j, i]
    footprint = POINT_CAMERA[2] / FX  # world units per pixel at that depth
    expected = R.T @ (np.array([(i - CX) / FX, (j - CY) / FY, 1.0]) * POINT_CAMERA[2] - T)
    assert np.linalg.norm(seen - POINT_WORLD) < 0.75 * footprint
    assert np.linalg.norm(seen - expected) < 0.05 * footprint

    # Every pixel centre sees the point that K and the extrinsic put there, and its depth is Z.
    u, v, z = seen_pixels(frame)
    columns, rows = np.meshgrid(np.arange(WIDTH), np.arange(HEIGHT))
    assert np.abs(u - columns).max() < 0.01
    assert np.abs(v - rows).max() < 0.01
    np.testing.assert_allclose(frame.depth, z, rtol=1e-4)


def test_both_conventions_give_the_same_picture():
    frames = [tessera.Renderer(threads=1, aovs=("depth",)).render(plane_scene(
        tessera.Camera.from_intrinsics(K, e, WIDTH, HEIGHT, convention=c)))
        for c, e in [("opencv", EXTRINSIC_CV), ("opengl", EXTRINSIC_GL)]]
    np.testing.assert_allclose(frames[0].depth, frames[1].depth, rtol=1e-5)
    assert np.abs(frames[0].color.astype(int) - frames[1].color).max() <= 1


def test_bad_intrinsics_are_refused():
    with pytest.raises(ValueError, match="K"):
        tessera.Camera.from_intrinsics(np.eye(4), EXTRINSIC_CV, WIDTH, HEIGHT)
    with pytest.raises(ValueError, match="fx, fy > 0"):
        tessera.Camera.from_intrinsics(np.diag([-1.0, 1.0, 1.0]), EXTRINSIC_CV, WIDTH, HEIGHT)
    with pytest.raises(ValueError, match="rotation"):
        tessera.Camera.from_intrinsics(K, np.diag([2.0, 1.0, 1.0, 1.0]), WIDTH, HEIGHT)
    with pytest.raises(ValueError, match="convention"):
        tessera.Camera.from_intrinsics(K, EXTRINSIC_CV, WIDTH, HEIGHT, convention="blender")
    with pytest.raises(ValueError, match="finite"):
        tessera.Camera.from_intrinsics(np.full((3, 3), np.nan), EXTRINSIC_CV, WIDTH, HEIGHT)
