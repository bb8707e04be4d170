"""python/examples/fit_curet.py prints, for each model, the numbers fit()
gives (the table a user sees is the library's result, not a copy)."""

import os
import subprocess
import sys

import brdffit

EXAMPLE = os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "examples", "fit_curet.py")


def test_the_example_table_shows_each_fit(curet, curet_dir, tmp_path):
    env = dict(os.environ,  # this package and library, from any folder
               PYTHONPATH=os.path.dirname(os.path.dirname(brdffit.__file__)),
               BRDFFIT_LIB=os.path.abspath(brdffit.library_path))
    out = subprocess.run([sys.executable, EXAMPLE, curet_dir, "--material",
                          "9", "--models", "VH-E,LFTG", "--plot",
                          str(tmp_path / "fig.png")],
                         capture_output=True, text=True, cwd=str(tmp_path),
                         env=env)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].endswith("material 9 (Frosted Glass), K = 198 "
                             "configurations")
    for name in ("VH-E", "LFTG"):
        r = brdffit.fit(curet, name, material=9)
        (row,) = [ln.split() for ln in lines if ln.startswith(name + " ")]
        assert row[-4:] == ["%.6g" % v for v in (r.objective, r.aic, r.bic,
                                                 r.cv)]
    try:
        import matplotlib  # noqa: F401 -- optional
    except ImportError:
        assert "matplotlib is not installed" in out.stderr
    else:
        assert (tmp_path / "fig.png").stat().st_size > 0
