"""brdffit.fit(fit="exact"): the library's exact-fit policy (inputs with an
exact-fit range fitted too, bf_model_variant_exact), every objective,
ranges=, profile and bootstrap intervals, and the flags of FitResult.
Round trips: synthesise with evaluate(), build a dataset from the arrays,
fit, recover the parameters (STYLE §7)."""

import numpy as np
import pytest

import brdffit
from brdffit import _lib
import synth

ANGLES = synth.directions(2024)
N = len(ANGLES)
TOL_FIT = 1e-6  # fitted parameters (STYLE §7), the refinement's tolerance


def synthetic(model, params, noise=0.0, seed=3):
    """A one-material dataset of model at params, with absolute noise
    (homoscedastic, as the profile likelihood assumes)."""
    return synth.dataset(ANGLES, model, params, noise, seed, relative=False)


def test_the_exact_fit_frees_the_inputs_with_an_exact_range():
    fc = brdffit.model("FC-E")
    assert fc.parameters[1].name == "n"
    lo, hi, step = fc.parameters[1].exact_range
    assert (lo, hi) == (_lib.FREE_N_LO, _lib.FREE_N_HI) and step > 0
    assert fc.parameters[0].exact_range is None  # m: fitted anyway
    ds = synthetic("FC-E", {"m": 0.5, "n": 1.7})
    assert brdffit.fit(ds, "FC-E", fit="exact").free == ("m", "n")
    # n given: it stays the input, as with the CLI's --n.
    r = brdffit.fit(ds, "FC-E", fit="exact", n=1.7)
    assert r.free == ("m",) and r.parameters["n"] == 1.7
    on = brdffit.fit(synthetic("ON", {"rho": 0.4, "sigma": 0.3}), "ON",
                     fit="exact")  # no on_params needed
    assert on.free == ("rho", "sigma")


@pytest.mark.parametrize("objective", [
    o for o in brdffit.objectives() if o not in ("ngan", "cuberoot", "log1p")])
def test_every_objective_recovers_off_grid_parameters(objective):
    # Every objective on normalised data (doc/methods.md §1) is zero at the
    # truth on noiseless data; those that keep the scale below.
    true = {"m": 0.43217, "n": 1.83}
    r = brdffit.fit(synthetic("FC-E", true), "FC-E", fit="exact",
                    objective=objective, folds=0)
    assert r.objective_name == objective and r.fit == "exact"
    for name, value in true.items():
        assert abs(r.parameters[name] - value) < TOL_FIT, name
        assert r.refined[name] == r.parameters[name]
    assert r.objective == r.refined_objective < 1e-12 < r.grid_objective
    assert np.isnan(r.cv)  # folds=0
    assert r.n_params == (3 if objective == "scale" else 2)  # + the scale


@pytest.mark.parametrize("objective, model, true", [
    ("ngan", "FC-E", {"m": 0.43217, "n": 1.83}),
    ("cuberoot", "FC-E", {"m": 0.43217, "n": 1.83}),
    # log1p flattens the valley along which FC-E's m and n trade off under
    # a free scale: the simplex stops 1.6e-6 from n (a single-parameter
    # model instead)
    ("log1p", "VH-E", {"m": 0.43217}),
])
def test_scale_keeping_objectives_recover_parameters_and_rho_d(
        objective, model, true):
    # SPEC §10: rho = BRDF cos theta_i as measured, theta <= 80 deg; the
    # model's free scale rho_d (SPEC §9.4) with d = 1/pi at normal
    # incidence and view. synth's BRDF is radiance v / cos theta_i, so
    # rho_d = pi v(normal).
    r = brdffit.fit(synthetic(model, true), model, fit="exact",
                    objective=objective, folds=0)
    assert r.objective_name == objective
    for name, value in true.items():
        assert abs(r.parameters[name] - value) < TOL_FIT, name
    inside = np.sum((ANGLES[:, 0] <= np.radians(80) + 1e-9)
                    & (ANGLES[:, 2] <= np.radians(80) + 1e-9))
    assert r.k == inside < N
    # the sum S below 1e-12 (ngan reports E = sqrt(S / K), SPEC §10)
    s = r.objective ** 2 * r.k if objective == "ngan" else r.objective
    assert s < 1e-12
    v0 = brdffit.evaluate(model, true, *np.zeros((4, 1)))[0]
    assert r.rho_d == pytest.approx(np.pi * v0, rel=1e-5)
    assert r.n_params == len(true) + 1  # rho_d counts


@pytest.mark.parametrize("model, true", [
    ("FC-E", {"m": 0.43217, "n": 1.83}),
    ("ON", {"rho": 0.4, "sigma": 0.3}),
])
def test_with_noise_the_intervals_contain_the_truth(model, true):
    # objective "scale": a noisy maximum would otherwise scale the whole
    # normalised curve (doc/methods.md §1).
    r = brdffit.fit(synthetic(model, true, noise=0.01), model, fit="exact",
                    objective="scale", bootstrap=40)
    for name, value in true.items():
        lo, hi = r.intervals[name]
        assert lo < value < hi, (name, lo, hi)
        assert lo <= r.parameters[name] <= hi
        # the bootstrap's replicates are refits of the maximum-likelihood
        # estimate, the one the intervals are about (doc/methods.md §3)
        blo, bhi = r.bootstrap[name]
        assert blo <= r.ml_estimate[name] <= bhi, (name, blo, bhi)
    k = r.n_params
    assert r.bic - r.aic == pytest.approx(k * np.log(N) - 2 * k)
    assert np.isfinite(r.cv) and not r.not_converged
    assert not r.interval_failed and not r.bootstrap_failed
    assert r.bootstrap_method == "residual-bootstrap"


def test_neyman_intervals_are_named_and_hold_the_estimate():
    # the Neyman construction (doc/methods.md §3): each end's threshold
    # simulated at that end; the same seed, the same interval
    data = synthetic("FC-E", {"m": 0.43217, "n": 1.83}, noise=0.01)
    r = brdffit.fit(data, "FC-E", fit="exact", neyman=100, folds=0)
    assert r.ci_method == "neyman"
    for name, (lo, hi) in r.intervals.items():
        assert lo <= r.ml_estimate[name] <= hi, (name, lo, hi)
    again = brdffit.fit(data, "FC-E", fit="exact", neyman=100, folds=0)
    assert again.intervals == r.intervals
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.fit(data, "FC-E", fit="exact", neyman=99)
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.fit(data, "FC-E", fit="exact", neyman=-1)
    with pytest.raises(brdffit.InvalidArgumentError, match="'auto', 'off'"):
        brdffit.fit(data, "FC-E", fit="exact", neyman="sometimes")


def test_the_default_constructs_where_a_second_minimum_competes(curet):
    # Felt (1): VH-G's m is split by a rise inside its interval, two
    # minima; by default (neyman="auto") its interval is the
    # construction's, as the CLI's; neyman="off" keeps the F threshold's
    r = brdffit.fit(curet, "VH-G", material=1, fit="exact", folds=0)
    assert r.competing == ("m",) and "competing=m" in r.flags
    assert r.ci_methods == {"m": "neyman"} and r.ci_method == "neyman"
    off = brdffit.fit(curet, "VH-G", material=1, fit="exact", folds=0,
                      neyman="off")
    assert off.competing == ("m",) and off.ci_methods == {"m": "profile-lik"}
    assert off.intervals["m"] != r.intervals["m"]
    # WNO-R: n's two branches compete, sigma's profile does not
    w = brdffit.fit(curet, "WNO-R", material=1, fit="exact", folds=0)
    assert w.competing == ("n",)
    assert w.ci_methods == {"sigma": "profile-lik", "n": "neyman"}
    assert w.ci_method == "profile-lik"  # not every parameter's


def test_a_range_moves_the_search_and_flags_the_bound():
    r = brdffit.fit(synthetic("VH-G", {"m": 0.8}), "VH-G", fit="exact",
                    ranges={"m": (0.2, 0.5)})
    assert r.parameters["m"] == 0.5 and r.bound == {"m": True}
    assert r.intervals["m"][1] == 0.5 and r.intervals_open["m"] == (False,
                                                                    True)
    with pytest.raises(brdffit.InvalidArgumentError, match="no model"):
        brdffit.fit(synthetic("VH-G", {"m": 0.8}), "VH-G",
                    ranges={"n": (1.2, 2.0)})


def test_lambertian_data_reduce_on_to_lambert():
    r = brdffit.fit(synthetic("LAMBERT", {}), "ON", fit="exact")
    assert r.reduces_to == "LAMBERT" and "reduces_to=LAMBERT" in r.flags
    assert r.parameters["sigma"] < 1e-6 and r.bound["sigma"]


def test_the_flags_of_curet_fits_are_the_librarys_words(curet):
    # Felt (1): ON's optimum is sigma = 0, where rho is not identified.
    r = brdffit.fit(curet, "ON", material=1, fit="exact")
    assert r.flags == ("reduces_to=LAMBERT not_identified=rho "
                       "noise=power:%.3g" % r.noise_power
                       if 0 < r.noise_power < 2 or r.noise_power > 2 else
                       "reduces_to=LAMBERT not_identified=rho noise=%s"
                       % ("absolute" if r.noise_power == 0 else "relative"))
    assert r.reduces_to == "LAMBERT" and r.not_identified == ("rho",)
    assert r.ci_method == "profile-lik"
    assert r.clamped == 0 and r.parameters["sigma"] == 0.0
    # Velvet (7): both ON parameters on their exact-fit range's ends, the
    # formula clamped at 0 on some configurations.
    r = brdffit.fit(curet, "ON", material=7, fit="exact")
    (rho, sigma) = brdffit.model("ON").parameters
    assert r.parameters == {"rho": rho.exact_range[0],
                            "sigma": sigma.exact_range[1]}
    assert r.bound == {"rho": True, "sigma": True}
    # Both profiles stay below the threshold to the other ends of their
    # ranges: the likelihood's intervals are the whole ranges, flagged.
    assert r.clamped > 0 and r.flags == (
        "not_identified=rho not_identified=sigma clamped=%d noise=absolute"
        % r.clamped)
    assert r.reduces_to is None and r.not_identified == ("rho", "sigma")
    assert r.intervals["rho"] == rho.exact_range[:2]


def test_progress_reports_the_pair(curet):
    calls = []
    brdffit.fit(curet, "VH-E", material=5, fit="exact",
                progress=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 1)]


def test_an_exception_in_progress_is_raised_after_the_call(curet):
    def fail(done, total):
        raise KeyError("stop at %d" % done)
    with pytest.raises(KeyError, match="stop at 1"):
        brdffit.fit(curet, "VH-E", material=1, progress=fail)
    with pytest.raises(TypeError, match="expected a callable"):
        brdffit.fit(curet, "VH-E", material=1, progress=3)


def test_a_composite_has_intervals_bootstrap_and_cv():
    # LAMBERT+GGX (SPEC §9.4) under ngan: its scales are parameters, solved
    # exactly at every profile point (doc/methods.md §3); 2 % relative
    # noise, a lobe broad enough for random directions (alpha 0.3)
    true = {"rho_d": 0.3, "rho_s": 0.6, "alpha": 0.3, "F0": 0.2}
    brdf = brdffit.evaluate("LAMBERT+GGX", true, *ANGLES.T)  # sr^-1
    e = np.random.default_rng(9).standard_normal(N)
    ds = brdffit.Dataset.from_arrays(ANGLES, brdf * (1.0 + 0.02 * e),
                                     names="synthetic")
    r = brdffit.fit(ds, "LAMBERT+GGX", fit="exact", objective="ngan",
                    noise="relative", bootstrap=40)
    for name, value in true.items():
        lo, hi = r.intervals[name]
        assert lo < value < hi, (name, lo, hi)
        assert lo <= r.ml_estimate[name] <= hi
        blo, bhi = r.bootstrap[name]
        assert blo <= r.ml_estimate[name] <= bhi, (name, blo, bhi)
    assert r.n_params == 4  # no scale beside rho_d and rho_s
    assert np.isfinite(r.cv) and r.cv > 0 and r.not_identified == ()
    assert not r.interval_failed and not r.bootstrap_failed
    # each interval's threshold widened by its robust factor (>= 1,
    # doc/methods.md §3): the profile figure's curve crosses that threshold
    # at the interval's ends
    assert set(r.ci_robust) == set(true)
    prof = r.profiles(n=81)
    for name, (theta, dev, thr) in prof.items():
        assert r.ci_robust[name] >= 1.0
        # K ln(1 + F(1, K - 5)/(K - 5)) is at least chi2_1's 3.84
        assert thr >= 3.84 * r.ci_robust[name]
        for end, is_open in zip(r.intervals[name], r.intervals_open[name]):
            if not is_open:
                assert abs(np.interp(end, theta, dev) - thr) < 0.05 * thr, (
                    name, end, np.interp(end, theta, dev), thr)


def test_profiles_cross_their_threshold_at_the_interval_ends(curet):
    # Linen (44), FC-E with n free: what the report's profile figure draws
    # (bf_study_profiles) -- for each free parameter a window that holds
    # the interval and the estimate it is about, a curve near 0 there, and
    # the F-form threshold crossed at each end of the reported interval
    # (linear interpolation between the window's points).
    import numpy as np
    r = brdffit.fit(curet, "FC-E", material=44, fit="exact", folds=0)
    prof = r.profiles(n=81)
    assert set(prof) == set(r.intervals) == {"m", "n"}
    for name, (theta, dev, thr) in prof.items():
        lo, hi = r.intervals[name]
        assert len(theta) == len(dev) == 81 and np.all(np.diff(theta) > 0)
        assert theta[0] <= lo < r.ml_estimate[name] < hi <= theta[-1]
        # K ln(1 + F(1, K - 4)/(K - 4)) = 3.93 at K = 198 (chi2_1: 3.84)
        assert 3.9 < thr < 3.96 and np.all(np.isfinite(dev))
        assert -1e-9 <= dev.min() < 0.5
        for end, is_open in zip((lo, hi), r.intervals_open[name]):
            if not is_open:
                assert abs(np.interp(end, theta, dev) - thr) < 0.05, (
                    name, end, np.interp(end, theta, dev), thr)
    # the objective's own profile under noise="objective": chi2_1
    o = brdffit.fit(curet, "FC-E", material=44, fit="exact", folds=0,
                    noise="objective")
    assert all(abs(t - 3.841458820694124) < 1e-9
               for _, _, t in o.profiles().values())
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.fit(curet, "FC-E", material=44, stats=False).profiles()


def test_a_split_interval_has_its_gap_where_the_profile_is_above(curet):
    # Felt (1), VH-G: its m's profile rises above the threshold inside the
    # interval and comes back below (the normalising maximum moves); the
    # set is two segments, interval_gaps names the gap, and the profile the
    # report draws is above the threshold across it and below either side
    # (the F threshold's segments: by default this interval, whose minima
    # compete, is the Neyman construction's, each end at its own threshold).
    import numpy as np
    r = brdffit.fit(curet, "VH-G", material=1, fit="exact", folds=0,
                    neyman="off")
    assert set(r.interval_gaps) == {"m"} and "m" in r.not_identified
    lo, hi = r.intervals["m"]
    g_lo, g_hi = r.interval_gaps["m"]
    assert lo < g_lo < g_hi < hi
    theta, dev, thr = r.profiles(n=401)["m"]
    inside_gap = (theta > g_lo + 1e-3) & (theta < g_hi - 1e-3)
    segments = ((theta > lo + 1e-3) & (theta < g_lo - 1e-3)) | (
        (theta > g_hi + 1e-3) & (theta < hi - 1e-3))
    assert inside_gap.any() and np.all(dev[inside_gap] > thr)
    assert np.all(dev[segments] <= thr)
    # a one-region interval has no gap
    e = brdffit.fit(curet, "VH-E", material=1, fit="exact", folds=0)
    assert e.interval_gaps == {}


def test_without_intervals_the_fit_is_the_same_and_has_none():
    """intervals=False (the CLI's --intervals none): the same fit, AIC,
    BIC and CV as the default run, no interval, noise model or ML
    estimate; with bootstrap, and asking for profiles, clear errors."""
    ds = synthetic("FC-E", {"m": 0.5, "n": 1.7}, noise=0.01)
    a = brdffit.fit(ds, "FC-E", fit="exact", folds=4)
    b = brdffit.fit(ds, "FC-E", fit="exact", folds=4, intervals=False)
    assert a.parameters == b.parameters and a.objective == b.objective
    assert (a.aic, a.bic, a.cv) == (b.aic, b.bic, b.cv)
    assert set(a.intervals) == {"m", "n"} and a.ci_method == "profile-lik"
    assert b.intervals == {} and b.ml_estimate == {} and b.ci_method == ""
    assert np.isnan(b.noise_power)
    with pytest.raises(brdffit.InvalidArgumentError, match="bootstrap"):
        brdffit.fit(ds, "FC-E", fit="exact", intervals=False, bootstrap=10)
    with pytest.raises(brdffit.InvalidArgumentError, match="no interval"):
        b.profiles()
    with pytest.raises(brdffit.InvalidArgumentError, match="True or False"):
        brdffit.fit(ds, "FC-E", fit="exact", intervals="none")
    rec = brdffit.compare(ds, models="FC-E", fit="exact", intervals=False)
    assert all(r["ci_low"] is None and r["ml_value"] is None for r in rec)
