"""The study from Python gives exactly the numbers of `brdffit compare`:
every value of the CLI's fits.csv (the paper's 24 samples and six models,
with --stats: grid and refined optima, profile intervals, AIC, BIC, CV)
equals the corresponding fit() result printed as fits.csv prints it
(%.10g)."""

import csv
import math
import os
import subprocess

import pytest

import brdffit

ARGS = ["--samples", "paper", "--stats", "-q"]


@pytest.fixture(scope="module")
def cli_fits(cli, curet_dir, reference_dir, tmp_path_factory):
    """The CLI's fits.csv rows (dicts of strings) and the ON file."""
    out = tmp_path_factory.mktemp("compare")
    on = os.path.join(reference_dir, "oren_nayar_params.tsv")
    run = subprocess.run([cli, "compare", "--data", curet_dir,
                          "--on-params", on, "--out", str(out)] + ARGS,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    with open(out / "fits.csv", newline="") as f:
        return list(csv.DictReader(f)), on


def g(x):
    """A number as fits.csv prints it."""
    return "%.10g" % x


def g_or_empty(x):
    """A number as fits.csv prints it, empty where it is not finite."""
    return g(x) if math.isfinite(x) else ""


def expected_row(r, param):
    """The fits.csv row of FitResult r for parameter param (None for a
    model without a fitted parameter), from r alone."""
    m = r.material
    row = {"sample": str(m.number), "name": m.name, "channel": r.channel,
           "model": r.model.name, "k": str(r.k), "lse": g(r.objective),
           "objective": r.objective_name, "fit": r.fit,
           "grid_lse": g(r.grid_objective),
           "refined_lse": g(r.refined_objective),
           "boot_low": "", "boot_high": "", "n_params": str(r.n_params),
           "aic": g(r.aic), "bic": g(r.bic), "cv": g(r.cv),
           "flags": r.flags}
    # the specular part's columns: empty for the diffuse models fitted here
    row.update({c: "" for c in ("ndf", "masking", "fresnel", "albedo_0",
                                "albedo_30", "albedo_60", "albedo_80",
                                "albedo_over_1")})
    if param is None:
        row.update(parameter="", unit="", value="", bound_hit="0",
                   grid_value="", refined_value="", ci_low="", ci_high="",
                   ml_value="",
                   ci_method="", ci_open="", ci_robust="", ci_gap_low="",
                   ci_gap_high="")
        return row
    (p,) = [q for q in r.model.parameters if q.name == param]
    lo, hi = r.intervals[param]
    lo_open, hi_open = r.intervals_open[param]
    gap = r.interval_gaps.get(param)
    row.update(parameter=param, unit=p.unit, value=g(r.parameters[param]),
               bound_hit=str(int(r.bound[param])),
               grid_value=g(r.grid[param]),
               refined_value=g(r.refined[param]), ci_low=g(lo),
               ci_high=g(hi), ml_value=g(r.ml_estimate[param]),
               ci_method=r.ci_method,
               ci_open=str(int(lo_open) + 2 * int(hi_open)),
               ci_robust=g_or_empty(r.ci_robust[param]),
               ci_gap_low=g(gap[0]) if gap else "",
               ci_gap_high=g(gap[1]) if gap else "")
    return row


def test_every_value_of_fits_csv_equals_fit(curet, cli_fits):
    rows, on = cli_fits
    assert len(rows) == 24 * 6  # one fitted parameter per model; ON: one
    results = {}
    mismatches = []
    for row in rows:
        key = (int(row["sample"]), row["model"])
        if key not in results:
            results[key] = brdffit.fit(curet, row["model"], material=key[0],
                                       on_params=on)
        want = expected_row(results[key], row["parameter"] or None)
        for col, value in row.items():
            if want[col] != value:
                mismatches.append("%s %s %s: CLI %s, Python %s" % (
                    key[0], key[1], col, value, want[col]))
    assert not mismatches, "\n".join(mismatches[:40])
