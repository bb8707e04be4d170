"""fit: one model fitted to one material of a dataset, by the library's
study (bf_study_run: the paper's grid protocol, SPEC §7) and its analysis
(bf_study_analyse: exact refinement, profile and bootstrap intervals, AIC,
BIC, cross-validation; doc/methods.md).
"""

import math

from ._errors import InvalidArgumentError, NotFoundError
from ._lib import CHANNEL_MEAN, ffi, lib
from ._study import Spec
from .models import _find

FITS = ("paper", "exact")


def _names(model, mask):
    """The names of model's parameters whose bit is set in mask."""
    return tuple(p.name for j, p in enumerate(model.parameters)
                 if mask & (1 << j))


def _by_name(model, values, mask):
    """A dict name -> float of values[j] for the parameters in mask."""
    return {p.name: float(values[j]) for j, p in enumerate(model.parameters)
            if mask & (1 << j)}


class FitResult:
    """The outcome of brdffit.fit: one model on one material and channel.

    Attributes:
        model: the Model fitted.
        material: the Material (of the dataset given to fit).
        channel: the channel fitted ("mean", or a channel name).
        fit: "paper" (the grid optimum, SPEC §7.4) or "exact" (refined).
        objective_name: "max" (the paper's LSE), "scale", "cosw" or "log".
        parameters: dict name -> value of every parameter (fitted ones at
            the optimum, the others at their fixed inputs).
        free: names of the fitted parameters.
        objective: the objective at parameters (the LSE, SPEC §7.3, for
            objective "max": a sum over the K configurations).
        bound: dict name -> bool for the fitted parameters: True when the
            optimum is on a bound of the grid or search range.
        k: the number of configurations used (K).
        selected: their indices (0-based) in the material's configurations.
        angles: (K, 4) their angles (radians, SPEC §1.5).
        measured: (K,) the normalised measured radiance (SPEC §2).
        predicted: (K,) the normalised model curve at parameters.
        n_eval: model evaluations the fit used.
      With the analysis (stats=True, the default; always with fit="exact"):
        grid, refined: dicts name -> value of the grid and exact optima of
            the fitted parameters; grid_objective, refined_objective.
        intervals: dict name -> (low, high), the profile interval at level.
        intervals_open: dict name -> (low_open, high_open): True where the
            interval reaches the search range.
        bootstrap: dict name -> (low, high) with bootstrap=N (else empty).
        n_params: the parameter count of AIC and BIC.
        aic, bic: of the refined optimum (NaN when the fit is exact: a zero
            residual).
        cv: the cross-validated error (NaN with folds=0).
        flags: what the analysis says about the fit, as fits.csv's flags
            column (bf_fit_flags_format: "reduces_to=LAMBERT
            not_identified=rho", "clamped=3", ...; "" for nothing).
      Without the analysis these are None.
    """

    def __init__(self, spec, rows, stats, fit, objective):
        row = rows[0]
        self.model = m = spec.models[0]
        self.material = spec.dataset[int(row.material)]
        ch = int(row.channel)
        self.channel = "mean" if ch == CHANNEL_MEAN else \
            self.material.channels[ch]
        self.fit = fit
        self.objective_name = objective
        p = [float(row.fit.param[j]) for j in range(len(m.parameters))]
        self.parameters = {q.name: p[j] for j, q in enumerate(m.parameters)}
        mask = int(stats[0].free_mask) if stats is not None else sum(
            1 << j for j, q in enumerate(m.parameters) if q.fitted)
        self.free = _names(m, mask)
        self.objective = float(row.fit.lse)
        self.bound = {name: bool(row.fit.bound_hit & (1 << j))
                      for j, name in enumerate(q.name for q in m.parameters)
                      if name in self.free}
        self.n_eval = int(row.fit.n_eval)
        self.k = int(row.k)
        self.selected, self.measured = spec.target_data(0)
        self.angles = self.material.angles[self.selected]
        self.predicted = spec.model_curve(0, m._type, p, self.selected)
        for a in (self.selected, self.measured, self.angles, self.predicted):
            a.flags.writeable = False
        self.grid = self.refined = self.grid_objective = None
        self.refined_objective = self.intervals = self.intervals_open = None
        self.bootstrap = self.n_params = self.aic = self.bic = None
        self.cv = self.flags = None
        if stats is not None:
            self._stats(m, stats[0], mask)

    def _stats(self, m, st, mask):
        self.grid = _by_name(m, st.grid.param, mask)
        self.grid_objective = float(st.grid.lse)
        self.refined = _by_name(m, st.refined.param, mask)
        self.refined_objective = float(st.refined.lse)
        self.intervals = {}
        self.intervals_open = {}
        self.bootstrap = {}
        for j, q in enumerate(m.parameters):
            if not mask & (1 << j):
                continue
            self.intervals[q.name] = (float(st.ci_low[j]),
                                      float(st.ci_high[j]))
            bits = (int(st.ci_open) >> (2 * j)) & 3
            self.intervals_open[q.name] = (bool(bits & 1), bool(bits & 2))
            lo, hi = float(st.boot_low[j]), float(st.boot_high[j])
            if not (math.isnan(lo) and math.isnan(hi)):
                self.bootstrap[q.name] = (lo, hi)
        self.n_params = int(st.k)
        self.aic = float(st.aic)
        self.bic = float(st.bic)
        self.cv = float(st.cv)
        buf = ffi.new("char[]", 512)
        lib.bf_fit_flags_format(m._type, ffi.addressof(st), buf, 512)
        self.flags = ffi.string(buf).decode()

    @property
    def residuals(self):
        """predicted - measured, per used configuration."""
        return self.predicted - self.measured

    def __repr__(self):
        par = ", ".join("%s=%.6g%s" % (k, v, "*" if self.bound.get(k) else "")
                        for k, v in self.parameters.items())
        out = "FitResult(%s on %d %r [%s], %s: %s; %s = %.6g, K = %d" % (
            self.model.name, self.material.number, self.material.name,
            self.channel, self.fit, par or "no parameters",
            self.objective_name, self.objective, self.k)
        if self.aic is not None:
            out += ", AIC %.6g, BIC %.6g, CV %.6g" % (self.aic, self.bic,
                                                      self.cv)
        return out + ")"


def fit(dataset, model, material=None, channel="mean", fit="paper",
        objective="max", stats=True, bootstrap=0, folds=10, seed=1,
        level=0.95, n=None, n_file=None, on_params=None, exclude=(),
        max_theta=None, cone=None, threads=1):
    """Fits one model to one material (the library's study on one target).

    Args:
        dataset: a Dataset (brdffit.load or built from arrays).
        model: a model name ("FC-E") or Model.
        material: the material -- its number (CURET's sample number), name
            or Material; may be left out when the dataset holds one.
        channel: "mean" (default: the mean over the channels, SPEC §2) or
            a channel name ("R", "550").
        fit: "paper" (the paper's grid, SPEC §7.4) or "exact" (the grid,
            then GSL refinement; FC's n and ON's rho, sigma fitted too).
        objective: "max" (the paper's LSE), "scale", "cosw", "log"
            (doc/methods.md §1; other than "max" needs fit="exact").
        stats: run the analysis (refinement, intervals, AIC, BIC, CV);
            always on with fit="exact".
        bootstrap: N percentile-bootstrap resamples (0: none).
        folds: K-fold cross-validation (0: none); seed: its and the
            bootstrap's seed. level: the interval level.
        n: refractive index of the FC models (default 1.7, SPEC §4.2);
            n_file: a per-material table, a path ("sample n" rows) or a
            mapping number -> n.
        on_params: Oren-Nayar (rho, sigma) per material: a path ("sample
            rho sigma" rows, CURET's op.dat accepted) or a mapping
            number -> (rho, sigma). ON needs it unless fit="exact".
        exclude: configuration numbers (1-based) to leave out besides the
            specular ones; max_theta: leave out configurations with
            theta_i or theta_o above it (radians); cone: half-angle
            (radians) of the specular cone left out (SPEC §1.6; default:
            the format's own rule, CURET's 7 specular configurations).
        threads: OpenMP threads (results do not depend on it).
    Returns a FitResult.
    Raises InvalidArgumentError (bad option), NotFoundError (material,
    channel or model unknown; ON without on_params), DomainError (data
    that cannot be normalised), and the loaders' errors for on_params and
    n_file.
    """
    if fit not in FITS:
        raise InvalidArgumentError("fit must be 'paper' or 'exact', got %r"
                                   % (fit,), 1)
    if material is None:
        if len(dataset) != 1:
            raise InvalidArgumentError(
                "fit: material is required (the dataset holds %d)"
                % len(dataset), 1)
        material = dataset[0]
    if fit == "exact":
        raise NotImplementedError(
            "fit='exact' waits for the library's --fit exact variant policy"
            " (issue 11)")
    if objective != "max" and fit != "exact":
        raise InvalidArgumentError("objective %r needs fit='exact' (the "
                                   "paper's grid minimises 'max')"
                                   % (objective,), 1)
    m = _find(model)
    spec = Spec(dataset, [material], channel, [m], n=n, n_file=n_file,
                on_params=on_params, exclude=exclude, max_theta=max_theta,
                cone=cone, threads=threads)
    context = "fit %s" % m.name
    rows = spec.run(context)
    stats_rows = None
    if stats or bootstrap:
        stats_rows = spec.analyse(rows, objective, fit == "exact", level,
                                  bootstrap, folds, seed, context)
    if rows[0].status != 0:
        inputs = ", ".join(q.name for q in m.parameters if not q.fitted)
        raise NotFoundError(
            "%s: %s needs %s for material %d (%s): pass on_params= (a file "
            "or {number: (rho, sigma)})" % (context, m.name, inputs,
                                            int(rows[0].sample),
                                            spec.dataset[int(
                                                rows[0].material)].name),
            int(rows[0].status))
    return FitResult(spec, rows, stats_rows, fit, objective)
