"""pytest plugin: `--tessera-update-golden` rewrites the goldens that
tessera.check.assert_matches_golden compares with (as TESSERA_UPDATE_GOLDEN=1
does). Enable it with `-p tessera.pytest_plugin` or, in a conftest.py,
`pytest_plugins = ["tessera.pytest_plugin"]`."""
import os

from .check import UPDATE_ENV


def pytest_addoption(parser):
    parser.addoption("--tessera-update-golden", action="store_true",
                     help="write golden images from the renders instead of comparing with them")


def pytest_configure(config):
    if config.getoption("--tessera-update-golden"):
        os.environ[UPDATE_ENV] = "1"
