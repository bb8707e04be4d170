"""python/examples/fit_curet.py prints, for each model, the numbers fit()
gives (the table a user sees is the library's result, not a copy), on
CURET with the paper's fit and on a Cornell file with the exact fit, and
draws its figure when matplotlib is installed."""

import os
import subprocess
import sys

import pytest

import brdffit

EXAMPLE = os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "examples", "fit_curet.py")


def run_example(args, cwd):
    env = dict(os.environ,  # this package and library, from any folder
               PYTHONPATH=os.path.dirname(os.path.dirname(brdffit.__file__)),
               BRDFFIT_LIB=os.path.abspath(brdffit.library_path))
    out = subprocess.run([sys.executable, EXAMPLE] + args,
                         capture_output=True, text=True, cwd=str(cwd),
                         env=env)
    assert out.returncode == 0, out.stderr
    return out


def check_rows(lines, results):
    for r in results:
        (row,) = [ln for ln in lines if ln.startswith(r.model.name + " ")]
        assert ("%10.6g %10.6g %10.6g %10.6g  %s"
                % (r.objective, r.aic, r.bic, r.cv, r.flags or "-")) in row
        for name, value in r.parameters.items():
            assert "%s=%.4g" % (name, value) in row


def test_the_example_table_shows_each_fit(curet, curet_dir, tmp_path):
    out = run_example([curet_dir, "--material", "9", "--models",
                       "VH-E,LFTG", "--plot", str(tmp_path / "fig.png")],
                      tmp_path)
    lines = out.stdout.splitlines()
    assert lines[0].endswith("material 9 (Frosted Glass), channel mean, "
                             "K = 198 configurations, fit paper")
    check_rows(lines, [brdffit.fit(curet, m, material=9)
                       for m in ("VH-E", "LFTG")])
    try:
        import matplotlib  # noqa: F401 -- optional
    except ImportError:
        assert "matplotlib is not installed" in out.stderr
    else:
        assert (tmp_path / "fig.png").stat().st_size > 0


@pytest.mark.parametrize("stem", ["acryl_blue"])
def test_the_example_fits_a_cornell_file_exactly(cornell_dir, stem,
                                                 tmp_path):
    path = os.path.join(cornell_dir, stem + ".brdf")
    out = run_example([path, "--channel", "550", "--fit", "exact",
                       "--models", "ON,LFTG", "--no-plot"], tmp_path)
    ds = brdffit.load(path)
    results = [brdffit.fit(ds, m, channel="550", fit="exact")
               for m in ("ON", "LFTG")]
    lines = out.stdout.splitlines()
    assert lines[0].endswith("channel 550, K = %d configurations, fit exact"
                             % results[0].k)
    check_rows(lines, results)
    for r in results:  # with their profile intervals
        for name in r.free:
            assert "[%.3g,%.3g]" % r.intervals[name] in out.stdout
