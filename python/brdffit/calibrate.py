"""calibrate: whether to trust a fit's intervals on one's own data -- the
library's bf_study_calibrate (doc/methods.md §3, the CLI's `brdffit
calibrate`): at the material's configurations, the fitted parameters as
the truth and the fitted noise model, n_sim simulated measurements are
fitted again and each parameter's interval checked against the truth.
"""

import numpy as np

from ._errors import check, new_error
from ._lib import ffi, lib

# The per-parameter fields of bf_calibration, in Calibration's order.
FIELDS = ("truth", "coverage", "bias", "sd", "ml_bias", "ml_sd", "width",
          "not_identified", "boot_coverage", "boot_width", "f_coverage",
          "f_width", "competing")


class Calibration:
    """The outcome of brdffit.calibrate: one model on one material.

    Attributes:
        fit: the FitResult calibrated (its ml_estimate, noise_power).
        parameters: names of the fitted parameters, the order of the
            arrays below.
        truth: (P,) the values simulated (the fit's refined optimum).
        coverage: (P,) share of the simulations whose interval at level
            holds the truth (0.95 within binomial error when the
            intervals mean what they say).
        bias, sd: (P,) mean minus truth, and spread, of the objective's
            estimates; ml_bias, ml_sd: the same for the
            maximum-likelihood estimates the intervals are about.
        width: (P,) the median interval width.
        not_identified: (P,) share of the simulations whose interval was
            flagged not identified.
        boot_coverage, boot_width: (P,) the same coverage and median width
            for the residual bootstrap's intervals with bootstrap=N (NaN
            without).
        f_coverage, f_width: (P,) the same for the profile threshold's
            intervals before any Neyman construction (coverage and width
            when none is made: neyman="off", a specular model).
        competing: (P,) share of the simulations whose profile has a
            second minimum that competes with the estimate's (their
            intervals are the construction's with neyman="auto").
        n_sim, n_failed: simulations fitted, and that could not be.
        level, seed: as given (level: the analysis's).
    """

    def __init__(self, result, cal, level, seed):
        self.fit = result
        self.parameters = tuple(result.free)
        idx = [j for j, q in enumerate(result.model.parameters)
               if q.name in self.parameters]
        for f in FIELDS:
            a = np.array([float(getattr(cal, f)[j]) for j in idx])
            a.flags.writeable = False
            setattr(self, f, a)
        self.n_sim = int(cal.n_sim)
        self.n_failed = int(cal.n_failed)
        self.level = level
        self.seed = seed

    def records(self):
        """A numpy structured array, one record per fitted parameter:
        parameter, and every field of FIELDS."""
        dt = [("parameter", "U32")] + [(f, "f8") for f in FIELDS]
        out = np.zeros(len(self.parameters), dtype=dt)
        out["parameter"] = self.parameters
        for f in FIELDS:
            out[f] = getattr(self, f)
        return out

    def __repr__(self):
        parts = ", ".join("%s coverage %.3f bias %.3g" % (
            p, self.coverage[i], self.bias[i])
            for i, p in enumerate(self.parameters))
        return "Calibration(%s on %d, %d simulations: %s)" % (
            self.fit.model.name, self.fit.material.number, self.n_sim,
            parts)


def calibrate(dataset, model, material=None, n_sim=200, seed=1,
              bootstrap=0, channel="mean", fit="exact", objective="max",
              level=None,
              noise="auto", n=None, n_file=None, on_params=None, exclude=(),
              max_theta=None, cone=None, ranges=None, threads=1,
              fresnel=None, smith=None, neyman="auto"):
    """Fits model to material as brdffit.fit does (the analysis on), then
    simulates n_sim measurements of the fitted model under the fitted
    noise model at the material's configurations, refits each and checks
    its intervals (bf_study_calibrate; GSL mt19937 seeded with seed: the
    same seed gives the same numbers).

    Args as brdffit.fit's (fit="exact" by default); n_sim: simulations,
    at least 10 (BF_CALIBRATE_MIN_SIM); seed: of the simulations;
    bootstrap: N replicates to check the bootstrap's intervals too (each
    simulation's; the fit's own bootstrap is run as well); neyman: as in
    brdffit.fit -- each simulation's intervals are made as the fit's are
    ("auto": the Neyman construction where a second minimum competes;
    N: every parameter's, about 4 N fits per parameter and simulation;
    "off": the profile threshold alone), and f_coverage, f_width are the
    profile threshold's before it.
    Returns a Calibration.
    Raises InvalidArgumentError (n_sim < 10, bad options; the library's
    message), DomainError (the noise cannot be estimated: K not above
    the parameters, the scale and the noise power), and fit's errors.
    """
    from .fit import FitResult, fit_study
    study = fit_study(dataset, model, material, channel=channel, fit=fit,
                      objective=objective, stats=True, folds=0, level=level,
                      bootstrap=bootstrap, neyman=neyman,
                      n=n, n_file=n_file, on_params=on_params,
                      exclude=exclude, max_theta=max_theta, cone=cone,
                      ranges=ranges, threads=threads, noise=noise,
                      fresnel=fresnel, smith=smith)
    cal = ffi.new("bf_calibration *")
    err = new_error()
    rc = lib.bf_study_calibrate(study.spec.spec, study.opts, study.rows,
                                study.stats, 0, max(int(n_sim), 0),
                                int(seed), cal, err)
    check(rc, err, "calibrate")
    return Calibration(FitResult(study), cal, float(study.opts.level),
                       int(seed))
