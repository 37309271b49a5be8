"""object_id and material_id: one id per object as the scene defines it, the
same on every run and with any thread count."""
import numpy as np
import pytest

import tessera


def sphere_row_scene():
    """Five spheres in a row, two materials, ids given and defaulted."""
    scene = tessera.Scene(96, 32)
    u, v = np.meshgrid(np.linspace(0, np.pi, 12), np.linspace(0, 2 * np.pi, 16), indexing="ij")
    positions = np.stack([np.sin(u) * np.cos(v), np.cos(u), np.sin(u) * np.sin(v)], -1).reshape(-1, 3)
    rows, cols = u.shape
    quads = [(r * cols + c, (r + 1) * cols + c, (r + 1) * cols + c + 1, r * cols + c + 1)
             for r in range(rows - 1) for c in range(cols - 1)]
    indices = np.array([[a, b, c] for a, b, c, d in quads] + [[a, c, d] for a, b, c, d in quads])
    mesh = scene.add_mesh(positions, indices, normals=positions)
    red = scene.add_material(albedo=(0.8, 0.1, 0.1))
    blue = scene.add_material(albedo=(0.1, 0.1, 0.8))
    ids = []
    for k in range(5):
        transform = np.eye(4)
        transform[:3, 3] = (2.2 * (k - 2), 0, 0)
        transform[:3, :3] *= 0.9
        ids.append(scene.add_object(mesh, red if k % 2 else blue, transform, id=100 if k == 3 else None))
    scene.add_light("directional", direction=(0, -1, -1), color=(3, 3, 3))
    scene.camera = tessera.Camera(position=(0, 0, 12), target=(0, 0, 0), fov_y=25)
    return scene, ids


def test_each_object_and_material_has_its_id():
    scene, ids = sphere_row_scene()
    assert ids == [1, 2, 3, 100, 101]
    assert list(scene.object_ids()) == ids
    frame = tessera.Renderer(aovs=("object_id", "material_id")).render(scene)
    row = frame.object_id[16]
    seen = [int(i) for i in row[np.r_[True, row[1:] != row[:-1]]]]  # the ids along the middle row, in runs
    assert seen == [0, 1, 0, 2, 0, 3, 0, 100, 0, 101, 0]
    for k, object_id in enumerate(ids):
        materials = np.unique(frame.material_id[frame.object_id == object_id])
        assert list(materials) == [1 if k % 2 else 2]  # red (index 0) or blue (index 1), + 1
    assert np.all(frame.material_id[frame.object_id == 0] == 0)


def test_ids_are_the_same_on_every_run_and_with_any_thread_count():
    scene, _ = sphere_row_scene()
    reference = tessera.Renderer(threads=1, aovs=("object_id", "material_id")).render(scene)
    for threads, tile_size, msaa in [(1, 64, None), (2, 16, None), (3, 32, None), (2, 64, 4)]:
        renderer = tessera.Renderer(threads=threads, tile_size=tile_size, msaa=msaa,
                                    aovs=("object_id", "material_id"))
        for _ in range(2):
            frame = renderer.render(scene)
            if msaa is None:
                assert np.array_equal(frame.object_id, reference.object_id)
                assert np.array_equal(frame.material_id, reference.material_id)
            else:  # a pixel holds its sample 0's id: the same objects, edges may move
                assert set(np.unique(frame.object_id)) == set(np.unique(reference.object_id))
    msaa_frames = [tessera.Renderer(threads=t, msaa=4, aovs=("object_id",)).render(scene) for t in (1, 2, 3)]
    assert all(np.array_equal(f.object_id, msaa_frames[0].object_id) for f in msaa_frames)


def test_toml_entries_are_objects(scenes_dir):
    scene = tessera.load(scenes_dir / "shapes.toml")
    assert list(scene.object_ids()) == [1, 2, 3, 4]  # one per [[objects]] entry, in file order
    first = tessera.Renderer(160, 90, threads=1, aovs=("object_id",)).render(scene).object_id.copy()
    again = tessera.Renderer(160, 90, threads=2, aovs=("object_id",)).render(tessera.load(scenes_dir / "shapes.toml"))
    assert np.array_equal(first, again.object_id)


def test_gltf_node_instances_are_objects(assets_dir):
    # NegativeScaleTest: 11 nodes place its 8 meshes (some meshes twice); each node is an object.
    scene = tessera.load(assets_dir / "gltf" / "NegativeScaleTest" / "glTF" / "NegativeScaleTest.gltf")
    ids = scene.object_ids()
    assert list(np.unique(ids)) == list(range(1, 12))
    assert list(ids) == sorted(ids)  # in node order; a node's primitives share its id
    frames = [tessera.Renderer(160, 120, threads=t, aovs=("object_id",)).render(scene).object_id for t in (1, 2)]
    assert np.array_equal(frames[0], frames[1])
    assert len(np.unique(frames[0])) > 2


def test_ids_may_not_be_zero():
    scene, _ = sphere_row_scene()
    with pytest.raises(ValueError, match="background"):
        scene.add_object(0, 0, id=0)
