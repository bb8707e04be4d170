"""The study on CURET from Python: the published Tables 2-3 subset of
Ragheb & Hancock (../shared/reference/ragheb_hancock_subset.tsv) within the
agreement stated in ../shared/reference/README.md, compared as printed (two
decimals) like tests/test_reproduction.c:
  VH-G, VH-E, LFTG parameters and LSE  exact to the printed digits
  ON LSE                               +-0.01, except Styrofoam (20)
  FC-G, FC-E at n = 1.7                parameters +-0.01, LSE +-0.02,
                                       except Leather (5)
The exceptions are properties of the published tables: they are reported
(printed), never tuned around, and their count is checked. Both fit() and
compare() (the rows of fits.csv) are checked.
"""

import csv
import os

import brdffit

TOL_ON_LSE = 0.01
TOL_FC_PARAM = 0.01
TOL_FC_LSE = 0.02
TOL_REPR = 1e-9  # two-decimal values as doubles
MODELS = ("VH-G", "VH-E", "FC-G", "FC-E", "ON", "LFTG")
EXCEPTIONS = {("FC-G", 5), ("FC-E", 5), ("ON", 20), ("ON", 41)}


def published(reference_dir):
    """{(model, sample): (parameter or None, LSE)} of the subset."""
    out = {}
    path = os.path.join(reference_dir, "ragheb_hancock_subset.tsv")
    with open(path) as f:
        for row in csv.DictReader(f, delimiter="\t"):
            s = int(row["sample"])
            for m in MODELS:
                key = m.replace("-", "_")
                par = row.get("slope_" + key) or (
                    row["LFTG_nd"] if m == "LFTG" else None)
                out[(m, s)] = (None if par is None else float(par),
                               float(row["LSE_" + key]))
    return out


def printed(x):
    """x as the tables print it (two decimals)."""
    return round(x * 100.0) / 100.0


def check_against_published(obtained, reference_dir):
    """obtained(model, sample) -> (parameter, LSE). Returns the failures
    (text) and the documented exceptions met."""
    failures = []
    exceptions = []
    for (m, s), (par, lse) in sorted(published(reference_dir).items()):
        got_par, got_lse = obtained(m, s)
        fc = m.startswith("FC")
        for what, pub, got, tol in (
                ("parameter", par, got_par, TOL_FC_PARAM if fc else 0.0),
                ("LSE", lse, got_lse, TOL_FC_LSE if fc else
                 TOL_ON_LSE if m == "ON" else 0.0)):
            if pub is None:
                continue
            ok = abs(printed(got) - pub) <= tol + TOL_REPR
            if (m, s) in EXCEPTIONS and not ok:
                exceptions.append("documented exception: sample %d %s %s: "
                                  "published %.2f, obtained %.4f"
                                  % (s, m, what, pub, got))
            elif not ok:
                failures.append("sample %d %s %s: published %.2f, obtained "
                                "%.6f, tolerance %.2f"
                                % (s, m, what, pub, got, tol))
    print("\n".join(exceptions))
    return failures, exceptions


def test_fit_reproduces_the_published_tables(curet, reference_dir):
    on = os.path.join(reference_dir, "oren_nayar_params.tsv")

    def obtained(m, s):
        r = brdffit.fit(curet, m, material=s, on_params=on, stats=False)
        par = None if m == "ON" else r.parameters[r.free[0]]
        return par, r.objective

    failures, exceptions = check_against_published(obtained, reference_dir)
    assert not failures, "\n".join(failures)
    # 2 FC slopes and 2 FC LSE of Leather, ON LSE of Styrofoam (Brick b,
    # 41, is not in the 12-sample subset).
    assert len(exceptions) == 5, "\n".join(exceptions)


def test_compare_reproduces_the_published_tables(curet, reference_dir):
    on = os.path.join(reference_dir, "oren_nayar_params.tsv")
    rows = brdffit.compare(curet, on_params=on)  # the paper's study
    got = {(r["model"], r["sample"]): (r["value"], r["lse"]) for r in rows}

    def obtained(m, s):
        par, lse = got[(m, s)]
        return (None if m == "ON" else par), lse

    failures, exceptions = check_against_published(obtained, reference_dir)
    assert not failures, "\n".join(failures)
    assert len(exceptions) == 5, "\n".join(exceptions)


def test_the_paper_samples_are_the_24_of_the_reference(reference_dir):
    from brdffit._study import PAPER_SAMPLES
    with open(os.path.join(reference_dir, "oren_nayar_params.tsv")) as f:
        samples = [int(r["sample"]) for r in csv.DictReader(f,
                                                             delimiter="\t")]
    assert list(PAPER_SAMPLES) == samples and len(samples) == 24
