"""fresnel= and smith= (SPEC §9.2, the CLI's --fresnel and --smith) on
brdffit.model, fit, compare, rank, calibrate and report: the variant's
parameters, exact recovery of noise-free synthetic composites under ngan,
the variant named in every result, and clear errors."""

import numpy as np
import pytest

import brdffit

from synth import directions


def glossy(model, params, seed=3, n=400):
    """A one-material dataset of model's BRDF (sr^-1) at params on n
    directions, theta <= 75 degrees (SPEC §10 uses every one)."""
    a = directions(seed, n)
    a[:, 0] *= 75.0 / 83.1
    a[:, 2] *= 75.0 / 83.1
    brdf = brdffit.evaluate(model, params, *a.T)
    return brdffit.Dataset.from_arrays(a, brdf, names="synthetic")


def test_model_variants_have_their_parameters():
    m = brdffit.model("LAMBERT+GGX", fresnel="dielectric")
    assert [p.name for p in m.parameters] == ["rho_d", "rho_s", "alpha", "n"]
    assert m.fresnel != brdffit.model("LAMBERT+GGX").fresnel
    b = brdffit.model("BECKMANN", fresnel="none", smith="separable")
    assert [p.name for p in b.parameters] == ["rho_s", "alpha"]
    assert b.masking != brdffit.model("BECKMANN").masking
    assert brdffit.model("GGX", fresnel="schlick") is brdffit.model("GGX")


@pytest.mark.parametrize("name, fresnel, smith, truth", [
    ("LAMBERT+GGX", "dielectric", None,
     {"rho_d": 0.3, "rho_s": 0.8, "alpha": 0.3, "n": 1.5}),
    ("LAMBERT+BECKMANN", None, "separable",
     {"rho_d": 0.2, "rho_s": 0.5, "alpha": 0.4, "F0": 0.08}),
])
def test_fit_recovers_the_variant(name, fresnel, smith, truth):
    variant = brdffit.model(name, fresnel=fresnel, smith=smith)
    ds = glossy(variant, truth)
    r = brdffit.fit(ds, name, fit="exact", objective="ngan",
                    fresnel=fresnel, smith=smith)
    assert r.model.parameters == variant.parameters or \
        [p.name for p in r.model.parameters] == list(truth)
    assert (r.model.ndf, r.model.masking, r.model.fresnel) == \
        (variant.ndf, variant.masking, variant.fresnel)
    assert r.objective < 1e-9  # E, noise-free
    for k, v in truth.items():
        assert r.parameters[k] == pytest.approx(v, rel=1e-5), k


def test_compare_records_name_the_variant():
    variant = brdffit.model("LAMBERT+GGX", fresnel="dielectric",
                            smith="separable")
    ds = glossy(variant, {"rho_d": 0.3, "rho_s": 0.8, "alpha": 0.3,
                          "n": 1.5})
    recs = brdffit.compare(ds, models=["LAMBERT+GGX", "LAMBERT"],
                           fit="exact", objective="ngan",
                           fresnel="dielectric", smith="separable")
    ggx = [r for r in recs if r["model"] == "LAMBERT+GGX"]
    assert [r["parameter"] for r in ggx] == ["rho_d", "rho_s", "alpha", "n"]
    for r in ggx:
        assert (r["ndf"], r["masking"], r["fresnel"]) == \
            (variant.ndf, variant.masking, variant.fresnel)
    n = [r for r in ggx if r["parameter"] == "n"][0]
    assert n["value"] == pytest.approx(1.5, rel=1e-5)
    lam = [r for r in recs if r["model"] == "LAMBERT"]
    assert lam and lam[0]["fresnel"] is None  # diffuse: unaffected
    ranked = brdffit.rank(ds, models="LAMBERT+GGX,LAMBERT",
                          objective="ngan", fresnel="dielectric",
                          smith="separable", folds=0)
    assert {r["model"] for r in ranked} == {"LAMBERT+GGX", "LAMBERT"}
    assert "n" in [v for r in ranked for k, v in r.items()
                   if k.startswith("p") and k[1:].isdigit()]


def test_separable_and_height_fits_differ():
    truth = {"rho_d": 0.2, "rho_s": 0.5, "alpha": 0.5, "F0": 0.08}
    ds = glossy(brdffit.model("LAMBERT+BECKMANN", smith="separable"), truth)
    sep = brdffit.fit(ds, "LAMBERT+BECKMANN", fit="exact", objective="ngan",
                      smith="separable")
    hei = brdffit.fit(ds, "LAMBERT+BECKMANN", fit="exact", objective="ngan",
                      smith="height")
    assert sep.objective < 1e-9
    assert hei.objective > 1e3 * sep.objective and hei.objective > 1e-6
    # far beyond the 1e-5 of the exact recovery
    assert max(abs(hei.parameters[k] / sep.parameters[k] - 1.0)
               for k in truth) > 1e-3


def test_calibrate_and_report_take_the_options(tmp_path):
    # calibrate and report resolve their models with the options as fit
    # does: a model that cannot take them is refused before anything runs
    ds = glossy(brdffit.model("LAMBERT+GGX"),
                {"rho_d": 0.3, "rho_s": 0.8, "alpha": 0.3, "F0": 0.05})
    with pytest.raises(brdffit.InvalidArgumentError,
                       match="LAMBERT\\+WARD has no Fresnel term"):
        brdffit.calibrate(ds, "LAMBERT+WARD", n_sim=10, objective="ngan",
                          fresnel="dielectric")
    with pytest.raises(brdffit.InvalidArgumentError,
                       match="CT has no Smith masking"):
        brdffit.report(ds, out=str(tmp_path / "bad"), models="GGX,CT",
                       fit="exact", objective="ngan", smith="separable")
    assert not (tmp_path / "bad").exists()


@pytest.mark.parametrize("kw, words", [
    ({"models": "LAMBERT+WARD", "fresnel": "dielectric"},
     ["LAMBERT+WARD has no Fresnel term", "--fresnel applies to"]),
    ({"models": "CT", "smith": "separable"}, ["CT has no Smith masking"]),
    ({"models": "LAMBERT", "fresnel": "none"},
     ["no selected model takes"]),
    ({"models": "LAMBERT+GGX", "fresnel": "glass"},
     ["fresnel must be one of schlick, dielectric, none"]),
    ({"models": "LAMBERT+GGX", "smith": 1}, ["smith must be one of"]),
])
def test_bad_options_say_why(kw, words):
    ds = glossy(brdffit.model("LAMBERT+GGX"),
                {"rho_d": 0.3, "rho_s": 0.8, "alpha": 0.3, "F0": 0.05})
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        brdffit.compare(ds, fit="exact", objective="ngan", **kw)
    for w in words:
        assert w in str(e.value)
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.model("WARD", fresnel="dielectric")
