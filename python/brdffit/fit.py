"""fit: one model fitted to one material of a dataset, by the library's
study (bf_study_run: the paper's grid protocol, SPEC §7) and its analysis
(bf_study_analyse: exact refinement, profile and bootstrap intervals, AIC,
BIC, cross-validation; doc/methods.md). fit="exact" fits the library's
exact-fit variant of the model (bf_model_variant_exact, the CLI's --fit
exact) and ranges= moves search ranges (bf_model_variant_range, --range).
"""

from . import _arrays
from ._errors import InvalidArgumentError, NotFoundError, check, new_error
from ._lib import CHANNEL_MEAN, ffi, lib, text
from ._study import Study


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
        model: the Model fitted (the registry's; with fit="exact" its
            inputs with an exact-fit range were fitted too: see free).
        material: the Material (of the dataset given to fit).
        channel: the channel fitted ("mean", a channel name, or "joint":
            one shape for every channel, the scales per channel, SPEC §9.4).
        fit: "paper" (the grid optimum, SPEC §7.4) or "exact" (refined).
        objective_name: "max" (the paper's LSE), "scale", "cosw", "log",
            "ngan", "cuberoot" or "log1p" (SPEC §10).
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
        interval_gaps: dict name -> (gap_low, gap_high) for the parameters
            whose interval is split in two regions (fits.csv's ci_gap_low,
            ci_gap_high): the set is [low, gap_low] and [gap_high, high];
            the values in between are outside. Empty where none is.
        bootstrap: dict name -> (low, high) with bootstrap=N (else empty):
            the residual bootstrap under the noise model (doc/methods.md
            §3; bootstrap_method "residual-bootstrap").
        n_params: the parameter count of AIC and BIC.
        aic, bic: of the refined optimum (NaN when the fit is exact: a zero
            residual).
        cv: the cross-validated error (NaN with folds=0).
        flags: what the analysis says about the fit, as fits.csv's flags
            column (bf_fit_flags_format: "reduces_to=LAMBERT
            not_identified=rho", "clamped=3", ...; "" for nothing), and
            each of its parts (bf_fit_stats):
        reduces_to: the model the fit is (ON at sigma = 0 is "LAMBERT"),
            or None.
        not_identified: names of the parameters along which the objective
            is flat at the optimum (ON's rho at sigma = 0), or whose
            profile stays below the interval's threshold to a bound of the
            search range (the interval ends there, open), or is below it
            in two separate regions (the interval spans both).
        clamped: on how many configurations the model's formula was
            clamped at 0 at the optimum (ON, doc/methods.md §8), else 0.
        not_converged: True when the refinement stopped at its iteration
            limit (the optimum is the best point found).
        interval_failed, bootstrap_failed: True when a profile interval
            could not be found (its ends are NaN) / the bootstrap failed.
        bootstrap_split: names of the parameters whose bootstrap
            replicates fall into separate basins.
        rho_d: under the objectives that keep the scale (ngan, cuberoot,
            log1p; SPEC §10) the fitted free scale rho_d (SPEC §9.4:
            the model is rho_d d with d = 1/pi at normal incidence and
            view; LAMBERT's albedo), else None. objective is then the
            value SPEC §10 reports (ngan: E); measured and predicted stay
            the normalised radiances of SPEC §2.
        ci_method: how intervals were computed, fits.csv's ci_method
            ("profile-lik": the noise model's likelihood; "profile": the
            objective's own S, noise="objective"; "neyman": the
            likelihood's with each end's threshold simulated, neyman=N).
        ci_methods: {parameter: method}, each parameter's own: "neyman"
            where its interval is the construction's (neyman="auto": the
            parameters in competing), else ci_method.
        competing: names of the parameters whose profile has a second
            minimum that competes with the estimate's (flag competing).
        noise_power: p of the noise model var ~ mu^p (0 absolute, 2
            relative; NaN for noise="objective").
        bootstrap_method: how bootstrap was computed ("residual-bootstrap";
            "" without bootstrap or when it failed).
        ml_estimate: {name: value}, the maximum-likelihood estimate the
            intervals are about (the scale free; under the max objective
            it differs from refined, doc/methods.md §3).
        ci_robust: {name: factor}, fits.csv's ci_robust: the factor >= 1
            a specular model's interval threshold was widened by where
            the residuals show more variance than the noise model
            (doc/methods.md §3); NaN for the diffuse models.
      Without the analysis these are None.
      With channel="joint" (SPEC §9.4; fit="exact", objective="ngan", a
      model with scales): parameters, free, bound, grid, refined,
      intervals hold the shared shape only; scales: {channel: {scale:
      value}} (rho_d, rho_s, A, Rd); per_channel: a FitResult per channel
      (its full parameters, measured, predicted); objective, n_params,
      aic, bic those of the whole fit (E over the K C values); measured
      and predicted every channel's, channel-major. Otherwise scales and
      per_channel are None.
    """

    def __init__(self, study, t=0, whole=True):
        spec, rows, stats = study.spec, study.rows, study.stats
        row = rows[t]
        self.model = m = spec.models[0]
        self._type = spec.types[0]
        self.material = spec.dataset[int(row.material)]
        ch = int(row.channel)
        self.channel = "mean" if ch == CHANNEL_MEAN else \
            self.material.channels[ch]
        self.fit = study.fit
        self.objective_name = study.objective
        p = [float(row.fit.param[j]) for j in range(len(m.parameters))]
        self.parameters = {q.name: p[j] for j, q in enumerate(m.parameters)}
        mask = int(stats[0].free_mask) if stats is not None else sum(
            1 << j for j, q in enumerate(m.parameters) if q.fitted)
        self.free = _names(m, mask)
        self.objective = float(row.fit.lse)
        self.bound = {q.name: bool(row.fit.bound_hit & (1 << j))
                      for j, q in enumerate(m.parameters)
                      if mask & (1 << j)}
        self.n_eval = int(row.fit.n_eval)
        self.k = int(row.k)
        self.selected, self.measured = spec.target_data(t)
        self.angles = self.material.angles[self.selected]
        self.predicted = spec.model_curve(t, self._type, p, self.selected)
        for a in (self.selected, self.measured, self.angles, self.predicted):
            a.flags.writeable = False
        self.grid = self.refined = self.grid_objective = None
        self.refined_objective = self.intervals = self.intervals_open = None
        self.interval_gaps = None
        self.bootstrap = self.n_params = self.aic = self.bic = None
        self.rho_d = None
        self.cv = self.flags = self.reduces_to = self.not_identified = None
        self.clamped = self.not_converged = self.interval_failed = None
        self.ci_method = self.noise_power = self.ml_estimate = None
        self.ci_robust = self.ci_methods = self.competing = None
        self.bootstrap_failed = self.bootstrap_split = None
        self.bootstrap_method = None
        self.scales = self.per_channel = None
        self._study = study  # what profiles() asks the library about
        if stats is not None:
            self._stats(m, stats[t], mask, int(study.opts.n_boot) > 0,
                        not int(study.opts.no_intervals))
        if whole and spec.spec.targets[t].joint:
            self._joint(study)

    def _joint(self, study):
        """channel="joint" (SPEC §9.4): one result for the whole fit --
        the shared shape in parameters (and grid, refined, intervals,
        bound), each channel's scales in scales, each channel's own
        result in per_channel; measured and predicted every channel's,
        channel-major (what E sums over)."""
        import numpy as np
        per = tuple(FitResult(study, t, whole=False)
                    for t in range(int(study.spec.spec.n_targets)))
        linear = {q.name for q in self.model.parameters if q.linear}
        self.per_channel = per
        self.channel = "joint"
        self.scales = {r.channel: {k: v for k, v in r.parameters.items()
                                   if k in linear} for r in per}
        for name in ("parameters", "bound", "grid", "refined", "intervals",
                     "intervals_open", "interval_gaps", "bootstrap",
                     "ml_estimate", "ci_methods"):
            d = getattr(self, name)
            if d is not None:
                setattr(self, name, {k: v for k, v in d.items()
                                     if k not in linear})
        self.free = tuple(k for k in self.free if k not in linear)
        self.measured = np.concatenate([r.measured for r in per])
        self.predicted = np.concatenate([r.predicted for r in per])
        for a in (self.measured, self.predicted):
            a.flags.writeable = False

    def _stats(self, m, st, mask, boot, shown):
        self.grid = _by_name(m, st.grid.param, mask)
        self.grid_objective = float(st.grid.lse)
        self.refined = _by_name(m, st.refined.param, mask)
        self.refined_objective = float(st.refined.lse)
        self.intervals = {}
        self.intervals_open = {}
        self.interval_gaps = {}
        self.bootstrap = {}
        for j, q in enumerate(m.parameters):
            if not mask & (1 << j):
                continue
            if boot:
                self.bootstrap[q.name] = (float(st.boot_low[j]),
                                          float(st.boot_high[j]))
            if not shown:
                continue
            self.intervals[q.name] = (float(st.ci_low[j]),
                                      float(st.ci_high[j]))
            bits = (int(st.ci_open) >> (2 * j)) & 3
            self.intervals_open[q.name] = (bool(bits & 1), bool(bits & 2))
            gap = (float(st.ci_gap_low[j]), float(st.ci_gap_high[j]))
            if gap[0] == gap[0] and gap[1] == gap[1]:  # not NaN: split
                self.interval_gaps[q.name] = gap
        if lib.bf_objective_keeps_scale(st.objective):
            self.rho_d = float(st.scale)  # SPEC §9.4: the free scale
        self.ci_method = ffi.string(lib.bf_ci_method_name(
            int(st.ci_method))).decode()
        self.bootstrap_method = ffi.string(lib.bf_ci_method_name(
            int(st.boot_method))).decode()
        self.noise_power = float(st.noise_power)
        self.ml_estimate = _by_name(m, st.ml_param, mask) if shown else {}
        self.ci_robust = _by_name(m, st.ci_robust, mask) if shown else {}
        self.n_params = int(st.k)
        self.aic = float(st.aic)
        self.bic = float(st.bic)
        self.cv = float(st.cv)
        size = lib.bf_fit_flags_format(self._type, ffi.addressof(st),
                                       ffi.NULL, 0) + 1
        buf = ffi.new("char[]", size)
        lib.bf_fit_flags_format(self._type, ffi.addressof(st), buf, size)
        self.flags = ffi.string(buf).decode()
        f = int(st.flags)
        self.reduces_to = text(st.reduces_to) if (
            f & lib.BF_STAT_REDUCED and st.reduces_to != ffi.NULL) else None
        self.not_identified = _names(m, int(st.refined.flat) |
                                     int(st.not_identified))
        self.competing = _names(m, int(st.ci_competing))
        self.ci_methods = {q.name: ffi.string(lib.bf_ci_method_name(
            lib.bf_fit_stats_ci_method(ffi.addressof(st), j))).decode()
            for j, q in enumerate(m.parameters)
            if shown and (mask >> j) & 1}
        self.clamped = int(st.n_clamped) if f & lib.BF_STAT_CLAMPED else 0
        self.not_converged = bool(f & lib.BF_STAT_NOCONV)
        self.interval_failed = bool(f & lib.BF_STAT_CI_FAIL)
        self.bootstrap_failed = bool(f & lib.BF_STAT_BOOT_FAIL)
        self.bootstrap_split = _names(m, int(st.boot_split)) if (
            f & lib.BF_STAT_BOOT_SPLIT) else ()

    def profiles(self, n=41):
        """The profiles behind the intervals, as the report's profile
        figure draws them (bf_study_profiles, doc/methods.md §3): {name:
        (theta, dev, threshold)} for every free parameter -- n values
        theta (numpy) over a window around the estimate the interval is
        about (ml_estimate; the interval widened 2.5 times each side,
        within the search range), dev = n ln(S_p/S_min) of the criterion
        the interval thresholds there (the noise model's likelihood, or
        the objective's with noise="objective"), and its threshold: the
        interval is where dev <= threshold. Needs the analysis (stats);
        a joint fit has no profile interval (InvalidArgumentError)."""
        import numpy as np
        if self.intervals is None:
            raise InvalidArgumentError("profiles: the fit has no analysis "
                                       "(stats=False)", 1)
        if int(self._study.opts.no_intervals):
            raise InvalidArgumentError("profiles: the fit has no interval "
                                       "(intervals=False)", 1)
        if self.per_channel is not None:
            raise InvalidArgumentError("profiles: a joint fit (SPEC 9.4) "
                                       "has no profile interval", 1)
        n = int(n)
        st = self._study
        names = [q.name for q in self.model.parameters
                 if q.name in self.intervals]
        theta = np.zeros(n * len(names))
        dev = np.zeros(n * len(names))
        thr = np.zeros(max(len(names), 1))
        err = new_error()
        check(lib.bf_study_profiles(st.spec.spec, st.opts, st.rows, st.stats,
                                    0, n, _arrays.doubles(theta),
                                    _arrays.doubles(dev),
                                    _arrays.doubles(thr), err),
              err, "profiles")
        return {name: (theta[q * n:(q + 1) * n].copy(),
                       dev[q * n:(q + 1) * n].copy(), float(thr[q]))
                for q, name in enumerate(names)}

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
        objective="max", stats=True, bootstrap=0, folds=None, seed=None,
        level=None, n=None, n_file=None, on_params=None, exclude=(),
        max_theta=None, cone=None, ranges=None, threads=1, progress=None,
        noise="auto", fresnel=None, smith=None, intervals=True,
        neyman="auto"):
    """Fits one model to one material (the library's study on one target).

    Args:
        dataset: a Dataset (brdffit.load or built from arrays).
        model: a model name ("FC-E") or Model.
        material: the material -- its number (CURET's sample number), name
            or Material; may be left out when the dataset holds one.
        channel: "mean" (default: the mean over the channels, SPEC §2),
            a channel name ("R", "550") or "joint" (one shape for every
            channel, the scales per channel, SPEC §9.4: needs fit="exact",
            objective="ngan" and a model with scales, e.g. "LAMBERT+GGX").
        fit: "paper" (the paper's grid, SPEC §7.4) or "exact" (the grid,
            then GSL refinement, with the library's exact-fit policy
            bf_model_variant_exact: FC's n over [1.2, 2.5] unless n or
            n_file is given, ON's rho and sigma fitted; doc/methods.md §6).
        objective: "max" (the paper's LSE), "scale", "cosw", "log"
            (doc/methods.md §1), "ngan", "cuberoot", "log1p" (SPEC §10:
            BRDF values at their scale, a free rho_d); other than "max"
            needs fit="exact".
        stats: run the analysis (refinement, intervals, AIC, BIC, CV);
            always on with fit="exact" and with bootstrap.
        bootstrap: N residual-bootstrap replicates (0: none; refits of
            the fitted curve plus resampled standardised residuals under
            the noise model, doc/methods.md §3).
        folds: K-fold cross-validation (0: none); seed: its and the
            bootstrap's seed; level: the interval level. None: the
            library's defaults (bf_analysis_opts_init: 10 folds, seed 1,
            level 0.95).
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
        ranges: {name: (lo, hi)}: fit parameter name over [lo, hi] with
            its grid step (bf_model_variant_range, the CLI's --range);
            optima on a bound are flagged in bound.
        threads: OpenMP threads (0: one per core; results do not depend
            on it).
        progress: None, or a callable progress(done, total) the analysis
            calls as it goes (from the library's threads; an exception it
            raises is re-raised when the fit ends).
        noise: the intervals' noise model (doc/methods.md §3): "auto"
            (var ~ mu^p, p estimated; default), "absolute", "relative", or
            "objective" (the objective's own profile, the intervals before
            issue 18).
        intervals: True (default) for the profile intervals under the
            noise model; False for none (the CLI's --intervals none):
            intervals, intervals_open and ml_estimate empty, noise_power
            NaN -- the fit, AIC, BIC and CV in a fraction of the time (not
            with bootstrap).
        neyman: the Neyman construction (the CLI's --neyman; ci_method
            "neyman"; doc/methods.md §3): each end's threshold the 95%
            quantile of the profile criterion over N measurements
            simulated there and refitted, about 4 N fits per parameter.
            "auto" (default): N = 100 (BF_NEYMAN_AUTO_SIM) for a diffuse
            model's parameters whose profile has a second minimum that
            competes with the estimate's (competing), where the F
            threshold covers less than it says; N >= 100
            (BF_NEYMAN_MIN_SIM): every parameter's; "off": the F
            threshold alone.
        fresnel, smith: the specular models' options (SPEC §9.2, the CLI's
            --fresnel, --smith; None: each model's own, Schlick's F0 and
            height-correlated Smith): fresnel "schlick", "dielectric" (a
            refractive index n in [1.01, 4] in F0's place) or "none" (no
            F0), for GGX, BECKMANN, CT and their composites D+S; smith
            "height" or "separable", for GGX, BECKMANN and theirs. A
            diffuse model is unaffected; a specular model that cannot take
            the option, or options that no model takes, raise
            InvalidArgumentError. result.model is the variant fitted
            (its parameters, ndf, masking, fresnel).
    Returns a FitResult.
    Raises InvalidArgumentError (bad option), NotFoundError (material,
    channel or model unknown; ON without on_params), DomainError (data
    that cannot be normalised), and the loaders' errors for on_params and
    n_file.
    """
    return FitResult(fit_study(
        dataset, model, material, channel=channel, fit=fit,
        objective=objective, stats=stats, bootstrap=bootstrap, folds=folds,
        seed=seed, level=level, n=n, n_file=n_file, on_params=on_params,
        exclude=exclude, max_theta=max_theta, cone=cone, ranges=ranges,
        threads=threads, progress=progress, noise=noise, fresnel=fresnel,
        smith=smith, intervals=intervals, neyman=neyman))


def fit_study(dataset, model, material, **kw):
    """The Study of fit(dataset, model, material, **kw) (its arguments),
    the material's missing inputs checked."""
    if material is None:
        if len(dataset) != 1:
            raise InvalidArgumentError(
                "fit: material is required (the dataset holds %d)"
                % len(dataset), 1)
        material = dataset[0]
    context = "fit %s" % getattr(model, "name", model)
    study = Study(dataset, [material], [model], context=context, **kw)
    row = study.rows[0]
    if study.missing:
        m = study.spec.models[0]
        inputs = ", ".join(q.name for q in m.parameters if not q.fitted)
        raise NotFoundError(
            "%s: %s needs %s for material %d (%s): pass on_params= (a file "
            "or {number: (rho, sigma)})" % (context, m.name, inputs,
                                            int(row.sample),
                                            dataset[int(row.material)].name),
            int(row.status))
    return study
