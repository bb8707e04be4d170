"""n(lambda) in Python (issue 17 item 7): compare()'s .dispersion records
come from the library's structs (bf_dispersion_points) and recover a
Cauchy-law index per channel within its intervals; brdffit.report() writes
the CLI's dispersion.csv byte for byte; a model without n gives none."""

import numpy as np
import pytest

import brdffit
import synth

NM = (450.0, 550.0, 650.0)


def cauchy(nm):
    """Cauchy's law n = A + B / lambda^2 (lambda in micrometres)."""
    return 1.50 + 0.03 / (nm / 1000.0) ** 2


def _dataset():
    """LAMBERT+GGX under the dielectric Fresnel factor with n = cauchy on
    three wavelengths, 1% relative noise; half the directions near the
    mirror direction."""
    rng = np.random.default_rng(11)
    angles = synth.glossy_directions(11, 300)
    n = len(angles)
    model = brdffit.model("LAMBERT+GGX", fresnel="dielectric")
    values = np.column_stack([
        model.evaluate({"rho_d": 0.2, "rho_s": 0.5, "alpha": 0.12,
                        "n": cauchy(nm)}, *angles.T)
        * (1.0 + 0.01 * rng.standard_normal(n))
        for nm in NM])
    return brdffit.Dataset.from_arrays(
        angles, values, names="paint",
        channels=[str(int(nm)) for nm in NM], wavelengths=NM)


def test_compare_dispersion_records_within_intervals():
    recs = brdffit.compare(_dataset(), models="LAMBERT+GGX", channel="each",
                           fit="exact", objective="ngan", fresnel="dielectric",
                           folds=0)
    d = recs.dispersion
    assert d.columns == ("sample", "name", "channel", "model",
                         "wavelength_nm", "n", "ci_low", "ci_high", "n_ml")
    assert [r["wavelength_nm"] for r in d] == list(NM)
    for r in d:
        truth = cauchy(r["wavelength_nm"])
        assert r["ci_low"] <= truth <= r["ci_high"], r
        assert r["model"] == "LAMBERT+GGX"
    # the records are fits.csv's n rows (value and interval)
    n_rows = [r for r in recs if r["parameter"] == "n"]
    assert [r["value"] for r in n_rows] == [r["n"] for r in d]
    assert [r["ci_low"] for r in n_rows] == [r["ci_low"] for r in d]
    assert d.text.count("\n") == 1 + len(NM)


def test_no_n_no_dispersion():
    recs = brdffit.compare(_dataset(), models="LAMBERT+GGX", channel="each",
                           fit="exact", objective="ngan")
    assert len(recs.dispersion) == 0
    assert recs.dispersion.text.startswith("sample,name,channel,model,")


def test_report_writes_the_clis_dispersion_csv(tmp_path, cli):
    import subprocess
    ds = _dataset()
    csv = tmp_path / "paint.csv"
    ds.to_csv(str(csv))
    args = ["--input", str(csv), "--models", "LAMBERT+GGX", "--channel",
            "each", "--fit", "exact", "--objective", "ngan", "--fresnel",
            "dielectric", "--folds", "0", "--format", "png"]
    run = subprocess.run([cli, "report", "-q", "--threads", "1", "--out",
                          str(tmp_path / "cli")] + args,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    brdffit.report(brdffit.load(str(csv)), out=str(tmp_path / "py"),
                   models="LAMBERT+GGX", channel="each", fit="exact",
                   objective="ngan", fresnel="dielectric", folds=0,
                   format="png")
    cli_csv = (tmp_path / "cli" / "dispersion.csv").read_bytes()
    assert (tmp_path / "py" / "dispersion.csv").read_bytes() == cli_csv
    assert cli_csv.count(b"\n") == 1 + len(NM)
    assert (tmp_path / "py" / "figures" / "dispersion_sample1.png").exists()
