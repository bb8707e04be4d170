"""brdffit.compare() and brdffit.rank() give exactly the tables of
`brdffit compare` and `brdffit rank`: each case runs the CLI and the
Python call with the same options and compares fits.csv / ranking.csv
byte for byte, then every value of the records with the CLI file read here
with the csv module (empty field = None, numbers printed as the table
prints them, %.10g, text as is).
The wins of rank() are those of the CLI's summary in ranking.md."""

import csv
import io
import math
import os
import re
import subprocess
import sys

import pytest

import brdffit


def cli_table(cli, command, args, tmp_path, name):
    out = tmp_path / "out"
    run = subprocess.run([cli, command, "--out", str(out), "-q"] + args,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    with open(out / name, newline="") as f:
        return f.read()


def assert_records_are_the_table(records, text):
    assert records.text == text  # byte for byte
    rows = list(csv.DictReader(io.StringIO(text, newline="")))
    assert len(records) == len(rows) > 0
    assert list(records.columns) == list(rows[0].keys())
    bad = []
    for i, (got, want) in enumerate(zip(records, rows)):
        for col, field in want.items():
            value = got[col]
            if field == "":
                ok = value is None
            elif isinstance(value, int):
                ok = str(value) == field
            elif isinstance(value, float):  # the table prints %.10g
                ok = "%.10g" % value == field
            else:
                ok = value == field
            if not ok:
                bad.append("row %d %s: CLI %r, Python %r" % (i, col, field,
                                                             value))
    assert not bad, "\n".join(bad[:20])


def on_file(reference_dir):
    return os.path.join(reference_dir, "oren_nayar_params.tsv")


def test_compare_defaults_are_the_clis(cli, curet, curet_dir, tmp_path):
    # The paper's 24 samples and six models; ON without its inputs is left
    # out with the CLI's note.
    with pytest.warns(UserWarning, match="ON not evaluated for 24 of 24"):
        got = brdffit.compare(curet)
    assert_records_are_the_table(
        got, cli_table(cli, "compare", ["--data", curet_dir], tmp_path,
                       "fits.csv"))
    assert {r["sample"] for r in got} == set(brdffit._study.PAPER_SAMPLES)


def test_the_paper_protocol_on_every_sample_and_model(cli, curet, curet_dir,
                                                      reference_dir,
                                                      tmp_path):
    on = on_file(reference_dir)
    with pytest.warns(UserWarning, match="ON not evaluated for 37 of 61"):
        got = brdffit.compare(curet, models="all", samples="all",
                              on_params=on)
    assert_records_are_the_table(got, cli_table(
        cli, "compare", ["--data", curet_dir, "--samples", "all", "--models",
                         "all", "--on-params", on], tmp_path, "fits.csv"))
    # "all": every diffuse model (the specular ones need SPEC §10)
    assert len({r["model"] for r in got}) == len(
        [m for m in brdffit.models() if m.kind == "diffuse"])


def test_the_exact_fit_with_the_analysis_and_a_bootstrap(cli, curet,
                                                         curet_dir,
                                                         reference_dir,
                                                         tmp_path):
    on = on_file(reference_dir)
    got = brdffit.compare(curet, models="all", samples=[1, 5, 20],
                          fit="exact", stats=True, bootstrap=8,
                          on_params=on)
    assert_records_are_the_table(got, cli_table(
        cli, "compare", ["--data", curet_dir, "--samples", "1,5,20",
                         "--models", "all", "--fit", "exact", "--stats",
                         "--bootstrap", "8", "--on-params", on], tmp_path,
        "fits.csv"))
    assert {r["fit"] for r in got} == {"exact"}
    assert all(r["boot_low"] is not None for r in got if r["parameter"])
    # FC's n and ON's rho, sigma are fitted by the exact fit.
    assert {r["parameter"] for r in got if r["model"] == "FC-E"} == {"m",
                                                                     "n"}
    assert {r["parameter"] for r in got if r["model"] == "ON"} == {"rho",
                                                                   "sigma"}


def test_objective_range_n_and_exclusions_as_the_cli(cli, curet, curet_dir,
                                                     tmp_path):
    got = brdffit.compare(curet, models="FC-E,VH-G,LFTG", samples=[5, 9, 44],
                          fit="exact", objective="cosw",
                          ranges={"m": (0.05, 3.0)}, n=1.5,
                          exclude=[1, 2, 3], max_theta=math.radians(70),
                          folds=4, seed=7)
    assert_records_are_the_table(got, cli_table(
        cli, "compare", ["--data", curet_dir, "--samples", "5,9,44",
                         "--models", "FC-E,VH-G,LFTG", "--fit", "exact",
                         "--objective", "cosw", "--range", "m=0.05:3",
                         "--n", "1.5", "--exclude", "1,2,3", "--max-theta",
                         "70", "--folds", "4", "--seed", "7"], tmp_path,
        "fits.csv"))
    # n given: the exact fit keeps it as the input (only m is fitted).
    assert {r["parameter"] for r in got if r["model"] == "FC-E"} == {"m"}
    assert {r["objective"] for r in got} == {"cosw"}


def test_every_channel_of_a_cornell_file(cli, cornell_dir, tmp_path):
    path = os.path.join(cornell_dir, "garnet_red.brdf")
    got = brdffit.compare(brdffit.load(path), models=["VH-E", "LAMBERT"],
                          channel="each")
    assert_records_are_the_table(got, cli_table(
        cli, "compare", ["--input", path, "--channel", "each", "--models",
                         "VH-E,LAMBERT"], tmp_path, "fits.csv"))
    assert len(got) == 31 * 2  # 31 wavelengths, one row per model


def cli_wins(md):
    """{criterion: [(model, wins)]} of ranking.md's summary lines
    '- AIC: FC-E best for 3 of 6 samples, LAMBERT 2, VH-G 1'."""
    out = {}
    for crit, rest in re.findall(r"^- (\w+): (.*)$", md, flags=re.M):
        parts = rest.split(", ")
        first = re.match(r"(\S+) best for (\d+) of \d+ samples$", parts[0])
        out[crit] = [(first.group(1), int(first.group(2)))] + [
            (p.rsplit(" ", 1)[0], int(p.rsplit(" ", 1)[1]))
            for p in parts[1:]]
    return out


def test_rank_is_the_clis_ranking(cli, curet, curet_dir, tmp_path):
    got = brdffit.rank(curet, samples=[1, 2, 3, 4, 7, 20])
    args = ["--data", curet_dir, "--samples", "1,2,3,4,7,20"]
    assert_records_are_the_table(got, cli_table(cli, "rank", args, tmp_path,
                                                "ranking.csv"))
    with open(tmp_path / "out" / "ranking.md") as f:
        assert got.wins == cli_wins(f.read())
    assert len(got) == 6 * 9  # rank's nine models
    # the records are the library's doubles (bf_ranking_lines), not the
    # text read back: some carry more digits than the table's %.10g
    assert any(repr(r["aic"]) != "%.10g" % r["aic"] for r in got)
    for crit in ("aic", "bic", "cv"):  # one best model per sample
        best = [r["sample"] for r in got if r["best_" + crit] == 1]
        assert sorted(best) == [1, 2, 3, 4, 7, 20]


def test_progress_counts_every_pair_once(curet):
    calls = []
    brdffit.compare(curet, models=["VH-E", "LFTG"], samples=[1, 5, 9],
                    fit="exact", threads=2,
                    progress=lambda done, total: calls.append((done, total)))
    assert calls == [(i, 6) for i in range(1, 7)]


def test_records_as_a_dataframe(curet, monkeypatch):
    got = brdffit.compare(curet, models=["VH-E", "LFTG"], samples=[5, 9],
                          stats=True)
    df = got.to_dataframe()  # pandas is installed here
    assert list(df.columns) == list(got.columns) and len(df) == 4
    assert df["lse"].tolist() == got.column("lse")
    assert df["boot_low"].isna().all()  # no bootstrap: empty, NaN
    # Without pandas: an ImportError saying what to install.
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match="to_dataframe needs pandas"):
        got.to_dataframe()


def test_bad_requests_fail_clearly(curet):
    with pytest.raises(brdffit.NotFoundError, match="unknown model 'XX'"):
        brdffit.compare(curet, models="VH-E,XX")
    with pytest.raises(brdffit.InvalidArgumentError, match="listed twice"):
        brdffit.compare(curet, models=["VH-E", "vh-e"])
    with pytest.raises(brdffit.NotFoundError, match="no material numbered"):
        brdffit.compare(curet, samples=[1, 99])
    with pytest.raises(brdffit.InvalidArgumentError,
                       match="no model fitted has a parameter 'q'"):
        brdffit.compare(curet, samples=[1], ranges={"q": (0, 1)})
    with pytest.raises(brdffit.InvalidArgumentError,
                       match=r"VH-E's m must stay in \[0.001, 100\]"):
        brdffit.compare(curet, samples=[1], models=["VH-E"],
                        ranges={"m": (-1, 2)})
    with pytest.raises(brdffit.NotFoundError,
                       match="an excluded configuration number"):
        brdffit.compare(curet, samples=[1], exclude=[206])
    with pytest.raises(brdffit.InvalidArgumentError, match="one of max"):
        brdffit.rank(curet, samples=[1], objective="abs")
