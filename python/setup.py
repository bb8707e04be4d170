"""setup.py: records, when the package is built (pip install ./python),
where libbrdffit is, so that the installed package finds it with no
environment variable. Looked for, in order:
  1. BRDFFIT_LIB: the library file, or a folder holding it;
  2. BRDFFIT_PREFIX: an install prefix (PREFIX/lib*/libbrdffit.so*);
  3. pkg-config --variable=libdir brdffit (an installed brdffit);
  4. the build folder of this checkout (python/../build).
The first found is written to brdffit/_location.py in the built package;
when none is found the build fails with what was tried. At run time
BRDFFIT_LIB still overrides the recorded path (brdffit/_lib.py).
"""

import glob
import os
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
NAMES = ("libbrdffit.so.0", "libbrdffit.so")  # the soname first


def _in(folder):
    for name in NAMES:
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            return os.path.abspath(path)
    return None


def _pkg_config_libdir():
    try:
        out = subprocess.run(["pkg-config", "--variable=libdir", "brdffit"],
                             capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    return out.stdout.strip() or None


def find_library():
    """The path of libbrdffit to record, or SystemExit listing the tries."""
    tried = []
    env = os.environ.get("BRDFFIT_LIB")
    if env:
        path = _in(env) if os.path.isdir(env) else (
            os.path.abspath(env) if os.path.isfile(env) else None)
        if path:
            return path
        raise SystemExit("brdffit: BRDFFIT_LIB=%s is not libbrdffit.so or a "
                         "folder holding it" % env)
    prefix = os.environ.get("BRDFFIT_PREFIX")
    if prefix:
        for folder in sorted(glob.glob(os.path.join(prefix, "lib*"))) + \
                sorted(glob.glob(os.path.join(prefix, "lib", "*-linux-*"))):
            path = _in(folder)
            if path:
                return path
        tried.append("BRDFFIT_PREFIX=%s (no lib*/libbrdffit.so)" % prefix)
    libdir = _pkg_config_libdir()
    if libdir:
        path = _in(libdir)
        if path:
            return path
        tried.append("pkg-config libdir %s (no libbrdffit.so)" % libdir)
    else:
        tried.append("pkg-config brdffit (not found)")
    build = os.path.join(os.path.dirname(HERE), "build")
    path = _in(build)
    if path:
        return path
    tried.append("%s (no libbrdffit.so: run make)" % build)
    raise SystemExit("brdffit: libbrdffit not found; tried:\n  " +
                     "\n  ".join(tried) + "\nSet BRDFFIT_LIB to the library "
                     "or BRDFFIT_PREFIX to its install prefix.")


class BuildPy(build_py):
    """build_py that also writes brdffit/_location.py."""

    def run(self):
        super().run()
        library = find_library()
        target = os.path.join(self.build_lib, "brdffit", "_location.py")
        with open(target, "w") as f:
            f.write('"""Written by setup.py at install time."""\n'
                    "LIBRARY = %r\n" % library)
        print("brdffit: recorded libbrdffit at %s" % library)


if __name__ == "__main__":  # also when pip builds; importable for tests
    setup(cmdclass={"build_py": BuildPy})
