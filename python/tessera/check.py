"""Golden-image assertions for pytest, by the rules of `tessera check`: the
comparison is the C++ one (src/check/compare.cpp), not a second implementation.

    from tessera.check import assert_matches_golden
    assert_matches_golden(frame, "golden/cube.png", fail=2/255, fail_pixels=10)

Thresholds are tessera check's (docs on `tessera check`): fail, fail_relative,
fail_pixels, fail_ratio, warn, warn_relative, warn_pixels, warn_ratio,
max_error, max_warn_pixels, max_warn_ratio, perceptual. PNG goldens compare
the colour image (differences in [0, 1], one 8-bit step = 1/255); EXR goldens
the radiance (render with radiance=True).

Regeneration: with TESSERA_UPDATE_GOLDEN=1 in the environment (or pytest's
--tessera-update-golden, from the plugin tessera.pytest_plugin), the golden is
written from the image instead of compared, and a missing golden is written
rather than failing.
"""
import os
import warnings

from . import _tessera

UPDATE_ENV = "TESSERA_UPDATE_GOLDEN"


def updating():
    """Whether goldens are being regenerated (TESSERA_UPDATE_GOLDEN set to anything but '', '0')."""
    return os.environ.get(UPDATE_ENV, "") not in ("", "0")


def compare_with_golden(image, golden, **thresholds):
    """The comparison's status ('pass', 'warn', 'fail') and metrics, as a dict."""
    return _tessera.compare_with_golden(image, os.fspath(golden), thresholds)


def assert_matches_golden(image, golden, **thresholds):
    """Fails (AssertionError) unless `image` (a Frame, or an (H, W, 3) uint8 or
    float array) matches the golden file; a 'warn' passes with a warning."""
    golden = os.fspath(golden)
    if updating():
        _tessera.write_golden(image, golden)
        return {"status": "updated"}
    if not os.path.exists(golden):
        raise AssertionError(f"{golden}: no golden image; run with {UPDATE_ENV}=1 to write it")
    result = compare_with_golden(image, golden, **thresholds)
    status = result["status"]
    summary = (f"max error {result['max_error']:.4g} at ({result['max_x']}, {result['max_y']}), "
               f"{result['pixels_over_fail']} pixels over the fail threshold, "
               f"{result['pixels_over_warn']} over warn, PSNR {result['psnr']:.1f} dB")
    if status == "fail":
        reason = result["reason"] or summary
        raise AssertionError(f"{golden}: does not match: {reason}" + (f" ({summary})" if result["compared"] else "")
                             + f"; {UPDATE_ENV}=1 rewrites it")
    if status == "warn":
        warnings.warn(f"{golden}: matches with differences: {result['reason'] or summary}", stacklevel=2)
    return result
