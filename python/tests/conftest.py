"""conftest: where the tests find their inputs, and the rule that tests
never skip.

The package under test is the one on sys.path (PYTHONPATH=python in CTest);
it finds libbrdffit as documented in brdffit/_lib.py (CTest sets
BRDFFIT_LIB to the build's libbrdffit.so). Inputs come from environment
variables that CTest sets (tests/CMakeLists.txt), with the repository's
defaults otherwise:
  BRDFFIT_CURET_DIR      CURET folder (../shared/data/curet)
  BRDFFIT_CORNELL_DIR    the five Cornell .brdf files
                         (../shared/data/cornell-pbrt-v2)
  BRDFFIT_REFERENCE_DIR  published values (../shared/reference)
  BRDFFIT_CLI            the brdffit program (build/brdffit)
  BRDFFIT_INCLUDE        the folder of brdffit.h (include/)
  CC                     a C compiler (cc)
A missing input fails the test that needs it, loudly: tests never skip.
"""

import os

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))


def _path(var, default, what):
    path = os.environ.get(var) or default
    if not os.path.exists(path):
        pytest.fail("%s not found: %s (set %s)" % (what, path, var))
    return path


@pytest.fixture(scope="session")
def curet_dir():
    """The CURET folder (table.txt, abrdf.dat, samples.tsv)."""
    path = _path("BRDFFIT_CURET_DIR",
                 os.path.join(REPO, "..", "shared", "data", "curet"),
                 "CURET data")
    for f in ("table.txt", "abrdf.dat"):
        _path("BRDFFIT_CURET_DIR", os.path.join(path, f), "CURET " + f)
    return path


#: The Cornell files of ../shared/data/cornell-pbrt-v2 (SOURCES.md there).
CORNELL_FILES = ("acryl_blue", "cayman", "garnet_red", "krylon_blue",
                 "mystique")


@pytest.fixture(scope="session")
def cornell_dir():
    """The folder of the five Cornell .brdf files (pbrt-v2's)."""
    path = _path("BRDFFIT_CORNELL_DIR",
                 os.path.join(REPO, "..", "shared", "data",
                              "cornell-pbrt-v2"), "Cornell data")
    for f in CORNELL_FILES:
        _path("BRDFFIT_CORNELL_DIR", os.path.join(path, f + ".brdf"),
              "Cornell " + f + ".brdf")
    return path


@pytest.fixture(scope="session")
def reference_dir():
    """The folder of the published values (../shared/reference)."""
    return _path("BRDFFIT_REFERENCE_DIR",
                 os.path.join(REPO, "..", "shared", "reference"),
                 "reference values")


@pytest.fixture(scope="session")
def cli():
    """The brdffit program of the same build."""
    return _path("BRDFFIT_CLI", os.path.join(REPO, "build", "brdffit"),
                 "the brdffit program")


@pytest.fixture(scope="session")
def include_dir():
    """The folder holding brdffit.h."""
    return _path("BRDFFIT_INCLUDE", os.path.join(REPO, "include"),
                 "include/brdffit.h")


@pytest.fixture(scope="session")
def curet(curet_dir):
    """The CURET dataset, loaded once."""
    import brdffit
    return brdffit.load(curet_dir)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A skipped test fails: tests never skip (TEAM.md)."""
    outcome = yield
    rep = outcome.get_result()
    if rep.skipped and not hasattr(rep, "wasxfail"):
        rep.outcome = "failed"
        rep.longrepr = "tests never skip; this one did: %s" % (rep.longrepr,)
