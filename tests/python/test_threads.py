"""Several renderers from several Python threads, the GIL released while they draw."""
import threading
import time

import numpy as np

import tessera
from conftest import quad_scene


def test_renderers_in_threads_give_the_images_they_give_alone(scenes_dir):
    scenes = [tessera.load(scenes_dir / "shapes.toml"), tessera.load(scenes_dir / "spheres.toml"), quad_scene()]
    alone = [tessera.Renderer(96, 64, threads=1, aovs=("object_id",)).render(s) for s in scenes]
    results, errors = {}, []

    def work(k):
        try:
            renderer = tessera.Renderer(96, 64, threads=2, aovs=("object_id",))
            for frame_number in range(4):
                scene = scenes[(k + frame_number) % len(scenes)]  # threads share scenes too
                results[k, frame_number] = (scenes.index(scene), renderer.render(scene))
        except Exception as error:  # pragma: no cover - reported below
            errors.append(error)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert len(results) == 16
    for which, frame in results.values():
        assert np.array_equal(frame.color, alone[which].color)
        assert np.array_equal(frame.object_id, alone[which].object_id)


def test_one_renderer_shared_by_threads_draws_one_frame_at_a_time():
    renderer = tessera.Renderer(threads=1)
    scene = quad_scene()
    expected = renderer.render(scene).color.copy()
    frames = []
    threads = [threading.Thread(target=lambda: frames.append(renderer.render(scene))) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(f.color, expected) for f in frames)


def test_python_runs_while_a_frame_renders(scenes_dir):
    scene = tessera.load(scenes_dir / "spheres.toml")  # 1280x720: tens of milliseconds on one thread
    renderer = tessera.Renderer(threads=1)
    renderer.render(scene)  # warm up
    done = threading.Event()
    frame, span = [], []

    def render():
        span.append(time.perf_counter())
        frame.append(renderer.render(scene))
        span.append(time.perf_counter())
        done.set()

    thread = threading.Thread(target=render)
    stamps = []
    thread.start()
    while not done.is_set():
        stamps.append(time.perf_counter())
    thread.join()
    assert frame[0].stats["total_ms"] > 5
    # Holding the GIL would stop this loop for the whole call: no stamp in its
    # middle half. (Not a bound on the loop's gaps: on a loaded machine the
    # scheduler alone leaves gaps of several milliseconds.)
    start, end = span
    quarter = (end - start) / 4
    inside = sum(1 for t in stamps if start + quarter < t < end - quarter)
    assert inside > 0, (len(stamps), 1000 * (end - start))
