"""tessera.check: golden images compared by tessera check's library, and regenerated on request."""
import numpy as np
import pytest

import tessera
from tessera.check import assert_matches_golden, compare_with_golden
from conftest import quad_scene


def test_the_repositorys_golden_matches(source_dir, scenes_dir):
    frame = tessera.Renderer(threads=2).render(tessera.load(scenes_dir / "shapes.toml"))
    # The thresholds of tests/golden/check.toml.
    result = assert_matches_golden(frame, source_dir / "golden" / "shapes.png", fail=2.5 / 255, warn=1.5 / 255,
                                   max_warn_ratio=0.001, fail_ratio=0.00001, max_error=8.5 / 255)
    assert result["status"] in ("pass", "warn")


def test_a_golden_is_written_on_request_then_matched_and_a_change_fails(tmp_path, monkeypatch):
    golden = tmp_path / "goldens" / "quad.png"
    frame = tessera.Renderer().render(quad_scene())
    with pytest.raises(AssertionError, match="no golden image; run with TESSERA_UPDATE_GOLDEN=1"):
        assert_matches_golden(frame, golden)
    monkeypatch.setenv("TESSERA_UPDATE_GOLDEN", "1")
    assert assert_matches_golden(frame, golden)["status"] == "updated"
    assert np.array_equal(tessera.read_image(golden), frame.color)
    monkeypatch.delenv("TESSERA_UPDATE_GOLDEN")
    assert assert_matches_golden(frame, golden)["status"] == "pass"
    assert assert_matches_golden(frame.color, golden)["status"] == "pass"  # a plain array too

    changed = frame.color.copy()
    changed[10:14, 20:24] = 255 - changed[10:14, 20:24]
    with pytest.raises(AssertionError, match="does not match"):
        assert_matches_golden(changed, golden)
    result = compare_with_golden(changed, golden)
    assert result["status"] == "fail"
    assert result["pixels_over_fail"] == 16
    # Thresholds loosen it, as in a check.toml.
    with pytest.warns(UserWarning, match="matches with differences: 16 pixels"):
        assert assert_matches_golden(changed, golden, fail=1.0)["status"] == "warn"
    assert assert_matches_golden(changed, golden, fail_pixels=16, warn=1.0)["status"] == "pass"


def test_exr_goldens_compare_radiance(tmp_path, monkeypatch):
    golden = tmp_path / "quad.exr"
    frame = tessera.Renderer(radiance=True).render(quad_scene())
    monkeypatch.setenv("TESSERA_UPDATE_GOLDEN", "1")
    assert_matches_golden(frame, golden)
    monkeypatch.delenv("TESSERA_UPDATE_GOLDEN")
    assert assert_matches_golden(frame, golden, fail=0)["status"] == "pass"
    with pytest.raises(ValueError, match="radiance=True"):
        assert_matches_golden(tessera.Renderer().render(quad_scene()), golden)


def test_size_mismatch_and_unknown_thresholds(tmp_path, monkeypatch):
    golden = tmp_path / "quad.png"
    monkeypatch.setenv("TESSERA_UPDATE_GOLDEN", "1")
    assert_matches_golden(tessera.Renderer().render(quad_scene()), golden)
    monkeypatch.delenv("TESSERA_UPDATE_GOLDEN")
    with pytest.raises(AssertionError, match="does not match"):
        assert_matches_golden(tessera.Renderer(32, 24).render(quad_scene()), golden)
    with pytest.raises(ValueError, match="unknown threshold 'tolerance'"):
        assert_matches_golden(tessera.Renderer().render(quad_scene()), golden, tolerance=1)
