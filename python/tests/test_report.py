"""brdffit.report() writes what `brdffit report` writes with the same
options: every file byte for byte (fits.csv, table2.md, table3.md, each
figure in every format) and report.html but for its provenance line (the
CLI's command line, or "Written by bf_report_write")."""

import os
import re
import subprocess

import pytest

import brdffit

PROVENANCE = re.compile(r"^<li>(Command: <code>brdffit .*</code>|Written by "
                        r"<code>bf_report_write</code>)</li>$", re.M)


def files(folder):
    """{relative path: bytes} of every file under folder."""
    out = {}
    for root, _, names in os.walk(folder):
        for n in names:
            p = os.path.join(root, n)
            with open(p, "rb") as f:
                out[os.path.relpath(p, folder)] = f.read()
    return out


def cli_report(cli, tmp_path, args):
    out = tmp_path / "cli"
    run = subprocess.run([cli, "report", "-q", "--threads", "1", "--out",
                          str(out)] + args, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return files(out)


def assert_same(cli_files, py_files):
    assert sorted(py_files) == sorted(cli_files)
    assert any(k.startswith("figures" + os.sep) and k.endswith(".png")
               for k in py_files)
    for name, data in cli_files.items():
        if name != "report.html":
            assert py_files[name] == data, name
    page_cli = cli_files["report.html"].decode()
    page_py = py_files["report.html"].decode()
    assert len(PROVENANCE.findall(page_cli)) == 1
    assert "Command: <code>brdffit report" in page_cli
    assert "Written by <code>bf_report_write</code>" in page_py
    assert PROVENANCE.sub("", page_py) == PROVENANCE.sub("", page_cli)


def test_curet_two_samples_with_the_analysis(cli, curet, curet_dir,
                                             reference_dir, tmp_path):
    on = os.path.join(reference_dir, "oren_nayar_params.tsv")
    want = cli_report(cli, tmp_path, ["--data", curet_dir, "--samples",
                                      "1,5", "--stats", "--on-params", on])
    n = brdffit.report(curet, out=tmp_path / "py", samples=[1, 5],
                       stats=True, on_params=on)
    got = files(tmp_path / "py")
    assert_same(want, got)
    assert n == sum(k.endswith(".png") for k in got)
    assert got["fits.csv"].startswith(b"sample,name,channel,model,")


def test_cornell_file_every_model_and_figure_options(cli, cornell_dir,
                                                     tmp_path):
    path = os.path.join(cornell_dir, "cayman.brdf")
    want = cli_report(cli, tmp_path, [
        "--input", path, "--models", "all", "--format", "png,svg",
        "--size", "single", "--exclude-specular", "10", "--per-sample",
        "--log", "--incidence", "30,60"])
    ds = brdffit.load(path)
    with pytest.warns(UserWarning, match="ON not evaluated"):
        brdffit.report(ds, out=tmp_path / "py", models="all",
                       format=("png", "svg"), size="single",
                       exclude_specular=10, per_sample=True, log=True,
                       incidence=(30, 60))
    got = files(tmp_path / "py")
    assert_same(want, got)
    assert "figures/scatter_sample1.svg" in got
    assert not any(k.endswith(".pdf") for k in got)


def test_a_bad_option_raises_and_writes_nothing(cornell_dir, tmp_path):
    ds = brdffit.load(os.path.join(cornell_dir, "cayman.brdf"))
    with pytest.raises(brdffit.InvalidArgumentError, match="NOPE"):
        brdffit.report(ds, out=tmp_path / "bad", models="VH-G,NOPE")
    with pytest.raises(brdffit.InvalidArgumentError, match="CURET"):
        brdffit.report(ds, out=tmp_path / "bad", samples="paper")
    assert not (tmp_path / "bad").exists()


def test_calibrate_writes_the_clis_calibration(cli, curet, curet_dir,
                                               tmp_path):
    # report(calibrate=N) is `brdffit report --calibrate N`: the same
    # calibrate.csv (and every other file), the table on the page and a
    # calibration figure; N < 10 is refused as the CLI refuses it
    want = cli_report(cli, tmp_path, ["--data", curet_dir, "--samples",
                                      "12", "--models", "VH-E,FC-E",
                                      "--calibrate", "10", "--format",
                                      "png"])
    brdffit.report(curet, out=tmp_path / "py", samples=[12],
                   models="VH-E,FC-E", calibrate=10, format="png")
    got = files(tmp_path / "py")
    assert_same(want, got)
    lines = got["calibrate.csv"].decode().splitlines()
    assert lines[0].startswith("sample,name,channel,model,parameter,")
    assert len(lines) == 3  # VH-E m, FC-E m (--fit paper: n given)
    assert "figures/calibration_sample12.png" in got
    assert '<table id="calibration">' in got["report.html"].decode()
    with pytest.raises(brdffit.InvalidArgumentError, match="at least 10"):
        brdffit.report(curet, out=tmp_path / "bad", samples=[12],
                       models="VH-E", calibrate=5)
    assert not (tmp_path / "bad").exists()


def test_glossy_cornell_file_under_ngan_by_model_family(cli, cornell_dir,
                                                        tmp_path):
    # diffuse and specular models: the plane, polar and profile figures per
    # family (README "Report"), the same files from Python as from the CLI
    path = os.path.join(cornell_dir, "krylon_blue.brdf")
    models = "LFTG,LAMBERT,WNO,VH-E,FC-E,ON,VH-G,LAMBERT+GGX,AS"
    want = cli_report(cli, tmp_path, [
        "--input", path, "--models", models, "--fit", "exact",
        "--objective", "ngan", "--exclude", "301-1439", "--format", "png"])
    ds = brdffit.load(path)
    brdffit.report(ds, out=tmp_path / "py", models=models, fit="exact",
                   objective="ngan", exclude="301-1439", format="png")
    got = files(tmp_path / "py")
    assert_same(want, got)
    figs = {k.split(os.sep)[-1] for k in got if k.endswith(".png")}
    for name in ("plane_sample1", "plane_sample1_diffuse2",
                 "plane_sample1_specular", "polar_sample1",
                 "polar_sample1_diffuse2", "polar_sample1_specular",
                 "profile_sample1", "profile_sample1_specular"):
        assert name + ".png" in figs, name
    assert "plane_sample1_specular2.png" not in figs  # two specular curves
