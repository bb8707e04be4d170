"""`pip install ./python` offline (Debian's pip, setuptools and wheel; no
index, no build isolation): the installed package finds the library it was
installed against with no environment variable. A copy of python/ is
installed with --target into a temporary folder, so the source tree is not
written to. And the README's other way, PYTHONPATH=python in a built
checkout, finds the checkout's build/ with no environment variable."""

import importlib.util
import os
import shutil
import subprocess
import sys

import pytest

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
    lib = os.path.abspath(brdffit.library_path)
    run = _pip_install(src, tmp_path / "site", _env(BRDFFIT_LIB=lib))
    assert run.returncode == 0, run.stdout + run.stderr
    assert _installed_library(tmp_path / "site", tmp_path) == [lib, "True"]


def _find_library(monkeypatch, here, **env):
    """setup.py's find_library() under env (and no pkg-config brdffit),
    as if setup.py were in the folder here (whose parent has no build
    folder)."""
    for k in list(os.environ):
        if k.startswith("BRDFFIT_"):
            monkeypatch.delenv(k)
    for k, v in _env(**env).items():
        monkeypatch.setenv(k, v)
    spec = importlib.util.spec_from_file_location(
        "brdffit_setup", os.path.join(PYTHON_DIR, "setup.py"))
    setup = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(setup)
    monkeypatch.setattr(setup, "HERE", str(here))
    return setup.find_library


def test_setup_finds_the_library_under_brdffit_prefix(tmp_path, monkeypatch):
    libdir = tmp_path / "prefix" / "lib"
    libdir.mkdir(parents=True)
    os.symlink(os.path.abspath(brdffit.library_path),
               libdir / "libbrdffit.so.0")
    find = _find_library(monkeypatch, tmp_path / "src",
                         BRDFFIT_PREFIX=str(tmp_path / "prefix"))
    assert find() == str(libdir / "libbrdffit.so.0")


def test_setup_without_a_library_fails_saying_what_it_tried(tmp_path,
                                                            monkeypatch):
    find = _find_library(monkeypatch, tmp_path / "src")
    with pytest.raises(SystemExit) as e:
        find()
    text = str(e.value)
    assert "libbrdffit not found" in text and "pkg-config" in text
    assert str(tmp_path / "build") in text and "BRDFFIT_PREFIX" in text


def test_the_pythonpath_way_finds_the_checkouts_build_folder(tmp_path):
    # README: PYTHONPATH=python in a checkout built with make (build/ beside
    # python/), no environment variable: a checkout's layout is made here,
    # with this build's library in its build/.
    checkout = tmp_path / "checkout"
    shutil.copytree(os.path.join(PYTHON_DIR, "brdffit"),
                    checkout / "python" / "brdffit",
                    ignore=shutil.ignore_patterns("__pycache__",
                                                  "_location.py"))
    (checkout / "build").mkdir()
    lib = checkout / "build" / "libbrdffit.so"
    os.symlink(os.path.abspath(brdffit.library_path), lib)
    env = _env(PYTHONPATH=str(checkout / "python"))
    env.pop("LD_LIBRARY_PATH", None)
    out = subprocess.run(
        [sys.executable, "-c", "import brdffit; print(brdffit.library_path);"
         " print(brdffit.fit(brdffit.Dataset.from_arrays([[0.1, 0, 0.2, 3],"
         " [0.5, 0, 0.3, 1]], [0.4, 0.3]), 'LAMBERT').k)"],
        env=env, cwd=str(tmp_path), capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == [str(lib), "2"]
