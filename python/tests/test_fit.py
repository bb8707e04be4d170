"""brdffit.fit(): round trips -- synthesise with evaluate(), build a dataset
from the arrays, fit, recover the parameters (STYLE §7) -- and the result's
consistency and errors."""

import numpy as np
import pytest

import brdffit
import synth

ANGLES = synth.directions(1999)
N = len(ANGLES)
TOL_FIT = 1e-6  # fitted parameters (STYLE §7), the refinement's tolerance


def synthetic(model, params, noise=0.0, seed=5):
    """A one-material dataset of model at params, multiplicative noise."""
    return synth.dataset(ANGLES, model, params, noise, seed)


@pytest.mark.parametrize("model, name, true", [
    ("LFTG", "n_d", 2.5),  # 0.1 + 0.04 * 60: a grid point (SPEC §7.4)
    ("VH-E", "m", 0.73),  # 0.1 + 0.01 * 63
])
def test_the_paper_grid_recovers_a_grid_point_exactly(model, name, true):
    r = brdffit.fit(synthetic(model, {name: true}), model, stats=False)
    assert r.parameters[name] == pytest.approx(true, abs=1e-12)
    assert r.objective == pytest.approx(0.0, abs=1e-20)
    assert r.k == N and r.free == (name,) and not r.bound[name]
    assert r.aic is None  # no analysis asked for


@pytest.mark.parametrize("model, params, name", [
    ("LFTG", {"n_d": 3.14159}, "n_d"),
    ("FC-E", {"m": 0.43217, "n": 1.7}, "m"),
    ("VH-G", {"m": 1.23456}, "m"),
])
def test_the_refinement_recovers_an_off_grid_value(model, params, name):
    r = brdffit.fit(synthetic(model, params), model)
    assert abs(r.refined[name] - params[name]) < TOL_FIT
    assert abs(r.grid[name] - params[name]) <= 0.04  # within a grid step
    assert r.refined_objective < 1e-12 < r.grid_objective


def test_with_noise_the_fit_is_near_the_truth_and_beats_it():
    true = 0.8765
    r = brdffit.fit(synthetic("FC-G", {"m": true}, noise=0.01), "FC-G",
                    bootstrap=50)
    assert abs(r.refined["m"] - true) < 0.02
    # The exact optimum's LSE is at most the LSE of the true value,
    # computed here from the data the fit used (SPEC §2, §7.3).
    curve = brdffit.evaluate("FC-G", {"m": true}, *r.angles.T)
    lse_true = np.sum((curve / curve.max() - r.measured)**2)
    assert 0.0 < r.refined_objective <= lse_true
    assert r.refined_objective <= r.grid_objective
    lo, hi = r.intervals["m"]
    assert lo < r.refined["m"] < hi and r.intervals_open["m"] == (False,
                                                                  False)
    blo, bhi = r.bootstrap["m"]  # about the maximum-likelihood estimate
    assert blo < r.ml_estimate["m"] < bhi
    assert np.isfinite([r.aic, r.bic, r.cv]).all() and r.n_params == 1
    assert r.bic - r.aic == pytest.approx(np.log(N) - 2.0)  # k = 1


def test_measured_and_predicted_give_the_objective(curet):
    r = brdffit.fit(curet, "FC-E", material=5)
    assert r.k == 198 and len(r.selected) == 198  # SPEC §1.4
    assert set(np.setdiff1d(np.arange(205), r.selected) + 1) == {
        54, 97, 131, 161, 183, 196, 202}
    assert r.measured.max() == 1.0 and r.predicted.max() == 1.0  # SPEC §2
    lse = np.sum(r.residuals**2)
    assert lse == pytest.approx(r.objective, rel=1e-12)
    np.testing.assert_array_equal(r.angles, curet.find(5).angles[r.selected])


def test_on_takes_its_parameters_from_a_file_or_a_mapping(curet,
                                                         reference_dir):
    path = reference_dir + "/oren_nayar_params.tsv"
    a = brdffit.fit(curet, "ON", material=1, on_params=path, stats=False)
    rho, sigma = a.parameters["rho"], a.parameters["sigma"]
    b = brdffit.fit(curet, "ON", material=1, on_params={1: (rho, sigma)},
                    stats=False)
    assert a.objective == b.objective and a.free == ()
    with pytest.raises(brdffit.NotFoundError, match="ON needs rho, sigma"):
        brdffit.fit(curet, "ON", material=1)


def test_exclusions_and_max_theta_leave_out_configurations(curet):
    r = brdffit.fit(curet, "LFTG", material=1, exclude=[1, 2, 3],
                    stats=False)
    assert r.k == 195 and not {0, 1, 2} & set(r.selected)
    r = brdffit.fit(curet, "LFTG", material=1, max_theta=np.radians(60),
                    stats=False)
    assert (r.angles[:, [0, 2]] <= np.radians(60)).all() and r.k < 198


def test_fit_rejects_bad_requests_clearly(curet):
    with pytest.raises(brdffit.InvalidArgumentError,
                       match="material is required"):
        brdffit.fit(curet, "LFTG")
    with pytest.raises(brdffit.NotFoundError, match="no material numbered"):
        brdffit.fit(curet, "LFTG", material=0)
    with pytest.raises(brdffit.InvalidArgumentError, match="'paper' or"):
        brdffit.fit(curet, "LFTG", material=1, fit="best")
    with pytest.raises(brdffit.InvalidArgumentError, match="needs fit='exact'"):
        brdffit.fit(curet, "LFTG", material=1, objective="log")
    with pytest.raises(brdffit.InvalidArgumentError, match="1-based"):
        brdffit.fit(curet, "LFTG", material=1, exclude=[0])
    with pytest.raises(brdffit.NotFoundError, match="no channel"):
        brdffit.fit(curet, "LFTG", material=1, channel="R")
    with pytest.raises(brdffit.LoadError, match="cannot open"):
        brdffit.fit(curet, "ON", material=1, on_params="/nonexistent.tsv")
