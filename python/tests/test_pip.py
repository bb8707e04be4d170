"""`pip install ./python` offline (Debian's pip, setuptools and wheel; no
index, no build isolation): the installed package finds the library it was
installed against with no environment variable. A copy of python/ is
installed with --target into a temporary folder, so the source tree is not
written to."""

import os
import shutil
import subprocess
import sys

import brdffit

PYTHON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _copy_package(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in ("setup.py", "pyproject.toml", "README.md"):
        shutil.copy(os.path.join(PYTHON_DIR, name), src)
    shutil.copytree(os.path.join(PYTHON_DIR, "brdffit"), src / "brdffit",
                    ignore=shutil.ignore_patterns("__pycache__",
                                                  "_location.py"))
    return src


def _env(**kw):
    """The environment without BRDFFIT_* and without any pkg-config
    brdffit (so only what the test passes is found), plus kw."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("BRDFFIT_") and k != "PYTHONPATH"}
    env["PKG_CONFIG_LIBDIR"] = env["PKG_CONFIG_PATH"] = "/nonexistent"
    env.update(kw)
    return env


def _pip_install(src, target, env):
    return subprocess.run(
        [sys.executable, "-m", "pip", "install", "--no-build-isolation",
         "--no-index", "--no-deps", "--no-cache-dir", "--target",
         str(target), str(src)], env=env, capture_output=True, text=True)


def _installed_library(target, cwd):
    out = subprocess.run(
        [sys.executable, "-c", "import brdffit; print(brdffit.library_path);"
         " print(brdffit.evaluate('LAMBERT', [], 0.5, 0, 0.1, 0) > 0)"],
        env=_env(PYTHONPATH=str(target)), cwd=str(cwd), capture_output=True,
        text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout.split()


def test_pip_records_brdffit_lib_and_the_install_finds_it(tmp_path):
    src = _copy_package(tmp_path)
    lib = brdffit.library_path
    run = _pip_install(src, tmp_path / "site", _env(BRDFFIT_LIB=lib))
    assert run.returncode == 0, run.stdout + run.stderr
    assert _installed_library(tmp_path / "site", tmp_path) == [
        os.path.abspath(lib), "True"]


def test_pip_finds_the_library_under_brdffit_prefix(tmp_path):
    src = _copy_package(tmp_path)
    libdir = tmp_path / "prefix" / "lib"
    libdir.mkdir(parents=True)
    os.symlink(brdffit.library_path, libdir / "libbrdffit.so.0")
    run = _pip_install(src, tmp_path / "site",
                       _env(BRDFFIT_PREFIX=str(tmp_path / "prefix")))
    assert run.returncode == 0, run.stdout + run.stderr
    assert _installed_library(tmp_path / "site", tmp_path)[0] == str(
        libdir / "libbrdffit.so.0")


def test_pip_without_a_library_fails_saying_what_it_tried(tmp_path):
    src = _copy_package(tmp_path)
    run = _pip_install(src, tmp_path / "site", _env())
    assert run.returncode != 0
    out = run.stdout + run.stderr
    assert "libbrdffit not found" in out and "BRDFFIT_PREFIX" in out
