"""brdffit.compare and `brdffit compare` run the same study set up by the
same library functions (bf_study_models, bf_study_variants,
bf_study_rows_check): for two CURET samples, under the paper's protocol
with the analysis and under the exact fit with a model list, a given n and
a search range (the variants), Python's records hold exactly the CLI's
fits.csv -- the same rows in the same order, every value (a double read
from the library's bf_fits_line, not from the text) printing as the CLI
printed it."""

import csv
import io
import math
import os
import subprocess

import pytest

import brdffit

SAMPLES = (5, 12)
CASES = {
    "paper-stats": (["--stats"], dict(stats=True)),
    "exact-variants": (["--fit", "exact", "--models", "VH-E,FC-G,ON",
                        "--n", "1.5", "--range", "m=0.01:1"],
                       dict(fit="exact", models="VH-E,FC-G,ON", n=1.5,
                            ranges={"m": (0.01, 1)})),
}


def cli_fits(cli, curet_dir, on, out, args):
    run = subprocess.run([cli, "compare", "--data", curet_dir, "--samples",
                          ",".join(map(str, SAMPLES)), "--on-params", on,
                          "--out", str(out), "-q"] + args,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    with open(out / "fits.csv", newline="") as f:
        return f.read()


@pytest.mark.parametrize("case", sorted(CASES))
def test_compare_equals_cli_fits_csv(case, cli, curet, curet_dir,
                                     reference_dir, tmp_path):
    args, kw = CASES[case]
    on = os.path.join(reference_dir, "oren_nayar_params.tsv")
    text = cli_fits(cli, curet_dir, on, tmp_path, args)
    recs = brdffit.compare(curet, samples=list(SAMPLES), on_params=on,
                           **kw)
    rows = list(csv.DictReader(io.StringIO(text, newline="")))
    assert len(rows) > 0
    assert recs.text == text
    assert list(recs.columns) == list(rows[0].keys())
    assert len(recs) == len(rows)
    assert {r["sample"] for r in recs} == set(SAMPLES)
    bad = []
    for got, want in zip(recs, rows):
        for col, w in want.items():
            v = got[col]
            if w == "":
                ok = v is None
            elif isinstance(v, str):
                ok = v == w
            elif isinstance(v, int):
                ok = str(v) == w
            else:  # the library's double, printed as the CLI prints it
                ok = "%.10g" % v == w and not math.isnan(v)
            if not ok:
                bad.append("%s %s %s: CLI %r, Python %r" % (
                    want["sample"], want["model"], col, w, v))
    assert not bad, "\n".join(bad[:20])
