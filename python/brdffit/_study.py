"""_study: one run of the library's study built from Python arguments,
shared by fit(), compare() and rank(): the bf_study_spec (targets x
models, with the exact fit's and the ranges' model variants,
bf_model_variant_exact / bf_model_variant_range), the paper's protocol
(bf_study_run), the analysis (bf_study_analyse) and the library's writers
of fits.csv and ranking.csv. Everything the spec points to is kept alive
by the Spec object.
"""

import os
import re
from collections.abc import Mapping

import numpy as np

from . import _arrays
from ._errors import (DomainError, InvalidArgumentError, check, error,
                      new_error)
from ._lib import DEFAULT_N, ffi, lib, libc, text
from ._streams import read_from, written_by
from .models import Model, _find
from .records import Records

#: The 24 CURET samples of Ragheb & Hancock's study (bf_study_samples).
PAPER_SAMPLES = tuple(int(s) for s in lib.bf_study_samples)


def _library_names(name_of):
    """The names name_of(0), name_of(1), ... up to the first NULL (the
    library's bf_objective_name and the like)."""
    out = []
    while name_of(len(out)) != ffi.NULL:
        out.append(text(name_of(len(out))))
    return tuple(out)


#: The objectives the library minimises (bf_objective_name).
OBJECTIVES = _library_names(lib.bf_objective_name)
#: The model-selection criteria of ranking.csv (bf_criterion_name).
CRITERIA = _library_names(lib.bf_criterion_name)
FITS = ("paper", "exact")


def _objective(name):
    """The bf_objective called name; InvalidArgumentError otherwise."""
    obj = ffi.new("bf_objective *")
    if not isinstance(name, str) or lib.bf_objective_find(name.encode(),
                                                          obj) != 0:
        raise InvalidArgumentError("objective must be one of %s, got %r"
                                   % (", ".join(OBJECTIVES), name), 1)
    return obj[0]


NOISES = ("auto", "absolute", "relative", "objective")


def _noise(name):
    """The bf_noise called name; InvalidArgumentError otherwise."""
    nz = ffi.new("bf_noise *")
    if not isinstance(name, str) or lib.bf_noise_find(name.encode(),
                                                      nz) != 0:
        raise InvalidArgumentError("noise must be one of %s, got %r"
                                   % (", ".join(NOISES), name), 1)
    return nz[0]


FRESNELS = ("schlick", "dielectric", "none")
SMITHS = ("height", "separable")


def _neyman(value):
    """(n_neyman, neyman_every) of a neyman argument: "auto" (the
    default: the construction where a second minimum of a diffuse
    model's profile competes, BF_NEYMAN_AUTO_SIM simulations), "off" or 0
    (the profile threshold alone), or N >= 100 (every parameter's, N
    simulations per threshold; bf_analysis_opts)."""
    if isinstance(value, str):
        if value == "auto":
            return lib.BF_NEYMAN_AUTO_SIM, 0
        if value == "off":
            return 0, 0
    elif not isinstance(value, bool) and isinstance(value, int) and \
            value >= 0:
        return value, 1 if value > 0 else 0
    raise InvalidArgumentError("neyman must be 'auto', 'off' or a number "
                               "of simulations, got %r" % (value,), 1)


def _option(what, names, find, ctype, value):
    """The bf_fresnel_kind or bf_smith_kind of value, a name of names
    (find: bf_fresnel_find, bf_smith_find), or 0 (each model's own) for
    None; InvalidArgumentError otherwise."""
    if value is None:
        return 0
    out = ffi.new(ctype)
    if not isinstance(value, str) or find(value.encode(), out) != 0:
        raise InvalidArgumentError("%s must be one of %s or None, got %r"
                                   % (what, ", ".join(names), value), 1)
    return out[0]


def _fresnel(value):
    """The bf_fresnel_kind of fresnel= (SPEC §9.2, the CLI's --fresnel)."""
    return _option("fresnel", FRESNELS, lib.bf_fresnel_find,
                   "bf_fresnel_kind *", value)


def _smith(value):
    """The bf_smith_kind of smith= (SPEC §9.2, the CLI's --smith)."""
    return _option("smith", SMITHS, lib.bf_smith_find, "bf_smith_kind *",
                   value)


def _sample_table(kind, value):
    """A bf_sample_table (owned, freed with the returned cdata) from a file
    path, or from a mapping number -> value(s) written as the file's rows
    and read by the same reader. kind is "on" (rho, sigma; SPEC §5) or "n"
    (refractive index). None gives NULL."""
    if value is None:
        return ffi.NULL
    out = ffi.new("bf_sample_table **")
    err = new_error()
    if isinstance(value, Mapping):
        rows = []
        for number, v in value.items():
            vals = np.atleast_1d(_arrays.real("%s[%r]" % (kind, number), v))
            # repr() round-trips every double exactly through strtod.
            rows.append("%d %s" % (int(number),
                                   " ".join(repr(float(x)) for x in vals)))
        name = b"on_params" if kind == "on" else b"n_file"
        read = lib.bf_on_params_read if kind == "on" else lib.bf_n_file_read
        rc = read_from("\n".join(rows) + "\n",
                       lambda fp: read(fp, name, out, err))
    else:
        load = lib.bf_on_params_load if kind == "on" else lib.bf_n_file_load
        rc = load(os.fsencode(os.fspath(value)), out, err)
    check(rc, err)
    return ffi.gc(out[0], lib.bf_sample_table_free)


def _material_indices(dataset, materials):
    """Dataset indices of materials: None (every material), "all", "paper"
    (the study's 24 CURET samples, by number), one key or a list of keys
    (numbers, names or Material objects; see Dataset.material)."""
    if materials is None or (isinstance(materials, str) and
                             materials == "all"):
        return list(range(len(dataset)))
    if isinstance(materials, str) and materials == "paper":
        materials = PAPER_SAMPLES
    elif isinstance(materials, (str, int, np.integer)) or \
            hasattr(materials, "dataset"):
        materials = [materials]
    return [dataset.material(m).index for m in materials]


def _ranges(ranges):
    """[(name, lo, hi)] of a mapping name -> (lo, hi) (None: none)."""
    if ranges is None:
        return []
    if not isinstance(ranges, Mapping):
        raise TypeError("ranges: expected a mapping parameter name -> (lo, "
                        "hi), got %r" % (ranges,))
    out = []
    for name, bounds in ranges.items():
        b = _arrays.real("ranges[%r]" % (name,), bounds)
        if b.shape != (2,):
            raise ValueError("ranges[%r]: expected (lo, hi), got %r"
                             % (name, bounds))
        out.append((str(name), float(b[0]), float(b[1])))
    return out


def _models(models, defaults, objective, fresnel=None, smith=None):
    """([Model], [bf_model_type *]) of models (bf_study_models): None (the
    library's model set called defaults, e.g. "BF_MODELS_PAPER"), "all"
    (every diffuse registry model; under ngan, cuberoot, log1p also
    LAMBERT+S for every specular model S, AS alone: the complete glossy
    comparison), a comma-separated string or a sequence
    of names or Models; under fresnel, smith (SPEC §9.2: None each model's
    own) the specular models and the S of composites are their variants,
    whose Models have the variants' parameters (n in F0's place)."""
    if models is not None and not isinstance(models, str):
        if not models:
            raise InvalidArgumentError("no model to fit", 1)
        models = ",".join(m if isinstance(m, str) else m.name
                          for m in models)
    cap = lib.bf_model_count() + 1
    out = ffi.new("const bf_model_type *[]", cap)
    n = ffi.new("size_t *")
    err = new_error()
    obj = _objective(objective)
    rc = lib.bf_study_models(ffi.NULL if models is None else
                             models.encode(), getattr(lib, defaults), obj,
                             _fresnel(fresnel), _smith(smith), out, cap, n,
                             err)
    if rc == lib.BF_EDOM and lib.bf_objective_keeps_scale(obj):
        # fresnel=, smith=: a model that cannot take them (SPEC §9.2)
        raise InvalidArgumentError("models: %s" % text(err.msg), rc)
    if rc == lib.BF_EDOM:  # SPEC §9, §10: the others max-normalise
        raise InvalidArgumentError(
            "models: %s; fit it with fit='exact' and objective 'ngan', "
            "'cuberoot' or 'log1p'" % text(err.msg), rc)
    if rc != 0:
        raise type(error(rc))("models: %s" % text(err.msg), rc)
    base = [out[i] for i in range(n[0])]
    if not base:
        raise InvalidArgumentError("no model to fit", 1)
    return [_model_of(t) for t in base], base


def _model_of(ctype):
    """The Model of a type bf_study_models gave: the registry's (or the
    composite's) when it is that type, else its variant's own."""
    m = _find(text(ctype.name))
    return m if m._type == ctype else Model(ctype)


def _field(v):
    """A value of a bf_fits_line as a record's field: NaN, NULL, "" and
    -1 (the library's empty fields) None, text str, numbers int or
    float."""
    if isinstance(v, float):
        return None if v != v else v
    if isinstance(v, int):
        return None if v < 0 else v
    if isinstance(v, ffi.CData):
        if ffi.typeof(v).kind == "pointer" and v == ffi.NULL:
            return None
        v = ffi.string(v)
    v = v.decode("utf-8", "replace") if isinstance(v, bytes) else v
    return v or None


class _Progress:
    """The analysis's progress callback (bf_progress_fn) calling fn(done,
    total). An exception fn raises is kept (the library cannot be
    interrupted), fn is not called again, and raise_kept() raises it once
    the call into the library has returned."""

    def __init__(self, fn):
        if not callable(fn):
            raise TypeError("progress: expected a callable (done, total), "
                            "got %r" % (fn,))
        self.fn = fn
        self.exc = None
        self.c = ffi.callback("bf_progress_fn", self._call,
                              onerror=self._keep)

    def _call(self, ctx, done, total):
        if self.exc is None:
            self.fn(int(done), int(total))

    def _keep(self, exc_type, exc, tb):
        if self.exc is None:
            self.exc = exc if exc is not None else exc_type()

    def raise_kept(self):
        if self.exc is not None:
            raise self.exc


class Spec:
    """A bf_study_spec: targets (materials x channel) x models, the
    configuration selection and the models' inputs.

    Args (all as in brdffit.compare):
        dataset, materials, channel, models, n, n_file, on_params, exclude,
        max_theta, cone, threads; exact: the models are the library's
        exact-fit variants (bf_model_variant_exact, n kept as the input
        when n or n_file is given); ranges: name -> (lo, hi), applied to
        every model with that parameter (bf_model_variant_range).
    """

    def __init__(self, dataset, materials, channel, models, n=None,
                 n_file=None, on_params=None, exclude=(), max_theta=None,
                 cone=None, threads=1, exact=False, ranges=None,
                 defaults="BF_MODELS_PAPER", objective="max", fresnel=None,
                 smith=None):
        self.dataset = dataset
        self._keep = []
        self.models, base = _models(models, defaults, objective, fresnel,
                                    smith)
        index = _material_indices(dataset, materials)
        if not index:
            raise InvalidArgumentError("no material to fit", 1)
        spec = self.spec = ffi.new("bf_study_spec *")
        spec.data = dataset._ds

        idx = ffi.new("size_t[]", index)
        out = ffi.new("bf_target **")
        n_out = ffi.new("size_t *")
        err = new_error()
        rc = lib.bf_study_targets(dataset._ds, idx, len(index),
                                  ffi.NULL if channel is None
                                  else str(channel).encode(),
                                  out, n_out, err)
        check(rc, err)
        self._keep.append(ffi.gc(out[0], libc.free))
        spec.targets = out[0]
        spec.n_targets = n_out[0]

        sel = ffi.addressof(spec[0], "select")
        lib.bf_selection_init(sel)
        if cone is not None:
            sel.cone = float(cone)
        if max_theta is not None:
            sel.max_theta = float(max_theta)
        exclude = [int(x) for x in exclude]
        if any(x < 1 for x in exclude):
            raise InvalidArgumentError("exclude: configuration numbers are "
                                       "1-based, got %r" % (exclude,), 1)
        if exclude:
            arr = ffi.new("size_t[]", exclude)
            self._keep.append(arr)
            sel.exclude = arr
            sel.n_exclude = len(exclude)

        self.types = self._variants(base, exact, n is not None or
                                    n_file is not None, _ranges(ranges))
        types = ffi.new("const bf_model_type *[]", self.types)
        self._keep.append(types)
        spec.models = types
        spec.n_models = len(self.models)
        spec.n_default = DEFAULT_N if n is None else float(n)
        self._keep.append(_sample_table("n", n_file))
        spec.n_file = self._keep[-1]
        self._keep.append(_sample_table("on", on_params))
        spec.on_params = self._keep[-1]
        if threads is None or int(threads) < 0:
            raise InvalidArgumentError("threads must be an integer >= 0", 1)
        spec.n_threads = int(threads) or os.cpu_count() or 1

    def _variants(self, base, exact, n_given, ranges):
        """The model types fitted (bf_study_variants): base, or -- with
        exact or ranges -- the library's variants of them (kept alive and
        never moved: the types point into them), as the CLI's --fit exact
        and --range make them."""
        n = len(base)
        v = ffi.new("bf_model_variant[]", n)
        out = ffi.new("const bf_model_type *[]", n)
        r = ffi.new("bf_param_range[]", max(len(ranges), 1))
        names = [ffi.new("char[]", name.encode()) for name, _, _ in ranges]
        self._keep += [v, names]
        for i, (name, lo, hi) in enumerate(ranges):
            r[i].name, r[i].lo, r[i].hi = names[i], lo, hi
        bad_range = ffi.new("size_t *")
        bad_model = ffi.new("size_t *")
        keep = (1 << lib.BF_INPUT_INDEX) if n_given else 0
        rc = lib.bf_study_variants(base, n, 1 if exact else 0, keep, r,
                                   len(ranges), v, out, bad_range, bad_model)
        if rc == lib.BF_ENOTFOUND:
            raise InvalidArgumentError("ranges: no model fitted has a "
                                       "parameter %r"
                                       % ranges[bad_range[0]][0], 1)
        if rc != 0:
            name, lo, hi = ranges[bad_range[0]]
            m = self.models[bad_model[0]]
            (p,) = [q for q in m.parameters if q.name == name]
            raise InvalidArgumentError(
                "ranges[%r] = (%r, %r): %s's %s must stay in [%g, %g], lo < "
                "hi, with at most %d grid points"
                % (name, lo, hi, m.name, name, p.min, p.max,
                   lib.BF_VARIANT_MAX_GRID), rc)
        return [out[i] for i in range(n)]

    @property
    def n_rows(self):
        """targets x models."""
        return int(self.spec.n_targets) * len(self.models)

    def run(self, context):
        """The paper's protocol (bf_study_run): n_rows bf_study_row."""
        rows = ffi.new("bf_study_row[]", self.n_rows)
        err = new_error()
        check(lib.bf_study_run(self.spec, rows, err), err, context)
        return rows

    def analysis_opts(self, objective, exact, level, bootstrap, folds,
                      seed, noise="auto", intervals=True, neyman="auto"):
        """A bf_analysis_opts: the library's defaults
        (bf_analysis_opts_init), with the arguments that are not None;
        intervals=False: none (no_intervals, the CLI's --intervals none);
        neyman: "auto", "off" or N (_neyman)."""
        opts = ffi.new("bf_analysis_opts *")
        lib.bf_analysis_opts_init(opts)
        opts.objective = _objective(objective)
        opts.noise = _noise(noise)
        opts.exact = 1 if exact else 0
        if intervals not in (True, False):
            raise InvalidArgumentError("intervals must be True or False, "
                                       "got %r" % (intervals,), 1)
        opts.no_intervals = 0 if intervals else 1
        if level is not None:
            opts.level = float(level)
        if bootstrap is not None:
            if int(bootstrap) < 0:
                raise InvalidArgumentError("bootstrap must be >= 0", 1)
            opts.n_boot = int(bootstrap)
        if neyman is not None:
            opts.n_neyman, opts.neyman_every = _neyman(neyman)
        if folds is not None:
            if int(folds) < 0:
                raise InvalidArgumentError("folds must be >= 0", 1)
            opts.folds = int(folds)
        if seed is not None:
            opts.seed = int(seed)
        err = new_error()  # the library's check, before any fit
        check(lib.bf_analysis_opts_check(opts, err), err, "analysis")
        return opts

    def analyse(self, rows, opts, progress, context):
        """The analysis (bf_study_analyse) of rows under opts, calling
        progress(done, total) when it is not None: n_rows bf_fit_stats."""
        stats = ffi.new("bf_fit_stats[]", self.n_rows)
        err = new_error()
        cb = None if progress is None else _Progress(progress)
        if cb is not None:
            opts.progress = cb.c
        try:
            rc = lib.bf_study_analyse(self.spec, opts, rows, stats, err)
        finally:
            opts.progress = ffi.NULL
        if cb is not None:
            cb.raise_kept()
        check(rc, err, context)
        return stats

    def check_rows(self, rows, context):
        """The rows whose model lacks an input (ON without rho, sigma:
        BF_ENOTFOUND), as indices; a failed row (bf_study_rows_check)
        raises (a model that cannot be normalised on the used
        configurations)."""
        bad = ffi.new("size_t *")
        rc = lib.bf_study_rows_check(rows, self.n_rows, bad)
        if rc == lib.BF_EDOM:
            r = rows[bad[0]]
            raise DomainError(
                "%s: %s cannot be fitted to sample %d: the model is "
                "undefined at some of the K = %d used configurations or "
                "zero at all of them, so it cannot be normalised (SPEC §2);"
                " leave configurations out with exclude=, cone= or "
                "max_theta=" % (context, text(r.type.name), int(r.sample),
                                int(r.k)), rc)
        if rc != 0:
            raise error(rc, context=context)
        return [i for i in range(self.n_rows)
                if rows[i].status == lib.BF_ENOTFOUND]

    def write(self, writer, rows, stats, opts):
        """The text the library's writer (bf_fits_csv_write,
        bf_ranking_csv_write) writes for this study."""
        rc, out = written_by(lambda fp: writer(
            fp, self.spec, rows, ffi.NULL if stats is None else stats,
            ffi.NULL if opts is None else opts))
        check(rc, context="writing the table")
        return out

    def wins(self, stats, criterion):
        """[(model name, wins)] over the targets by criterion
        (bf_study_wins), most wins first."""
        c = ffi.new("bf_criterion *")
        check(lib.bf_criterion_find(criterion.encode(), c))
        cap = 2 * len(self.models)
        names = ffi.new("const char *[]", cap)
        wins = ffi.new("size_t[]", cap)
        n = ffi.new("size_t *")
        check(lib.bf_study_wins(self.spec, stats, c[0], names, wins, n))
        return [(text(names[i]), int(wins[i])) for i in range(n[0])]

    def target_data(self, t):
        """(sel, data): the used configurations (0-based) of target t and
        its normalised measured radiance, as the study fits them
        (bf_study_target_data)."""
        m = int(self.spec.targets[t].material)
        cap = int(lib.bf_dataset_nconf(self.dataset._ds, m))
        sel = np.zeros(cap, dtype=np.uintp)
        data = np.zeros(cap)
        k = ffi.new("size_t *")
        err = new_error()
        check(lib.bf_study_target_data(
            self.spec, t, ffi.from_buffer("size_t[]", sel), k,
            _arrays.doubles(data), err), err)
        return sel[:k[0]].astype(np.intp), data[:k[0]].copy()

    def model_curve(self, t, ctype, param, sel):
        """The normalised model curve (SPEC §2) of type ctype at param on
        target t's configurations sel: bf_model_eval on the dataset's
        Beckmann geometry, then bf_normalise."""
        m = int(self.spec.targets[t].material)
        n = int(lib.bf_dataset_nconf(self.dataset._ds, m))
        geom = _arrays.copy_doubles(
            ffi.cast("double *", lib.bf_dataset_geom(self.dataset._ds, m)),
            (n, 4))
        g = np.ascontiguousarray(geom[sel])
        p = np.ascontiguousarray(param, dtype=np.float64)
        out = np.empty(len(sel))
        rc = lib.bf_model_eval(ctype, _arrays.doubles(p), len(sel),
                               ffi.cast("bf_geom *", _arrays.doubles(g)),
                               _arrays.doubles(out))
        if rc == 0:
            rc = lib.bf_normalise(len(sel), _arrays.doubles(out),
                                  _arrays.doubles(out))
        if rc != 0:
            raise error(rc, context="model curve")
        return out


class Study:
    """One run: the Spec, its rows (bf_study_row), the analysis (stats:
    bf_fit_stats, and its opts; None without the analysis) and the rows
    left out for lack of inputs (missing). Arguments as brdffit.compare's;
    the analysis runs with fit="exact", stats, bootstrap or neyman=N, as
    in the CLI."""

    def __init__(self, dataset, materials, models, channel="mean",
                 defaults="BF_MODELS_PAPER", fit="paper", objective="max", stats=False, bootstrap=0,
                 folds=None, seed=None, level=None, n=None, n_file=None,
                 on_params=None, exclude=(), max_theta=None, cone=None,
                 ranges=None, threads=1, progress=None, context="study",
                 noise="auto", fresnel=None, smith=None, intervals=True,
                 neyman="auto"):
        if fit not in FITS:
            raise InvalidArgumentError("fit must be 'paper' or 'exact', got "
                                       "%r" % (fit,), 1)
        exact = fit == "exact"
        _objective(objective)
        _noise(noise)
        if objective != "max" and not exact:
            raise InvalidArgumentError("objective %r needs fit='exact' (the "
                                       "paper's grid minimises 'max')"
                                       % (objective,), 1)
        self.fit = fit
        self.objective = objective
        self.spec = Spec(dataset, materials, channel, models, n=n,
                         n_file=n_file, on_params=on_params,
                         exclude=exclude, max_theta=max_theta, cone=cone,
                         threads=threads, exact=exact, ranges=ranges,
                         defaults=defaults, objective=objective,
                         fresnel=fresnel, smith=smith)
        self.stats = self.opts = None
        if exact:  # the analysis is the study (it fills the rows)
            self.rows = ffi.new("bf_study_row[]", self.spec.n_rows)
        else:
            self.rows = self.spec.run(context)
        if exact or stats or bootstrap or _neyman(neyman)[1]:
            self.opts = self.spec.analysis_opts(objective, exact, level,
                                                bootstrap, folds, seed,
                                                noise, intervals, neyman)
            self.stats = self.spec.analyse(self.rows, self.opts, progress,
                                           context)
        self.missing = self.spec.check_rows(self.rows, context)

    def fits_csv(self):
        """fits.csv of the run (bf_fits_csv_write), as text."""
        return self.spec.write(lib.bf_fits_csv_write, self.rows, self.stats,
                               self.opts)

    def fits_records(self):
        """fits.csv's lines as Records from the library's structs
        (bf_fits_lines): numbers at full precision, empty fields None;
        .text the table (fits_csv)."""
        text_ = self.fits_csv()
        columns = text_.split("\n", 1)[0].split(",")
        spec = self.spec.spec
        stats = ffi.NULL if self.stats is None else self.stats
        opts = ffi.NULL if self.opts is None else self.opts
        n = lib.bf_fits_lines(spec, self.rows, stats, opts, ffi.NULL)
        lines = ffi.new("bf_fits_line[]", max(n, 1))
        lib.bf_fits_lines(spec, self.rows, stats, opts, lines)
        albedo = [c for c in columns if c.startswith("albedo_")
                  and c[7:].isdigit()]

        def value(ln, c):
            if c in albedo:
                return float(ln.albedo[albedo.index(c)])
            return getattr(ln, c)
        return self._records(text_, columns, lines, n, value)

    def dispersion_records(self):
        """dispersion.csv's lines (the refractive index against wavelength:
        n under fresnel="dielectric", ABC's ior, on spectral channels) as
        Records from the library's structs (bf_dispersion_points): numbers
        at full precision, empty fields None; .text the table (bf_dispersion_csv_write, as the CLI
        writes it; its header alone when there is no point)."""
        spec = self.spec.spec
        stats = ffi.NULL if self.stats is None else self.stats
        rc, text_ = written_by(lambda fp: lib.bf_dispersion_csv_write(
            fp, spec, self.rows, stats))
        check(rc, context="writing dispersion.csv")
        columns = text_.split("\n", 1)[0].split(",")
        n = lib.bf_dispersion_points(spec, self.rows, stats, ffi.NULL)
        points = ffi.new("bf_dispersion_point[]", max(n, 1))
        lib.bf_dispersion_points(spec, self.rows, stats, points)

        def value(pt, c):
            return pt.wavelength if c == "wavelength_nm" else getattr(pt, c)
        return self._records(text_, columns, points, n, value)

    def ranking_csv(self):
        """ranking.csv of the run (bf_ranking_csv_write), as text; needs
        the analysis."""
        return self.spec.write(lib.bf_ranking_csv_write, self.rows,
                               self.stats, self.opts)

    def ranking_records(self):
        """ranking.csv's lines as Records from the library's structs
        (bf_ranking_lines): numbers at full precision, empty fields None;
        .text the table (ranking_csv); needs the analysis."""
        text_ = self.ranking_csv()
        columns = text_.split("\n", 1)[0].split(",")
        spec = self.spec.spec
        opts = ffi.NULL if self.opts is None else self.opts
        n = ffi.new("size_t *")
        check(lib.bf_ranking_lines(spec, self.rows, self.stats, opts,
                                   ffi.NULL, n))
        lines = ffi.new("bf_ranking_line[]", max(n[0], 1))
        check(lib.bf_ranking_lines(spec, self.rows, self.stats, opts, lines,
                                   n))
        crit = [c.lower() for c in CRITERIA]
        slot = {"": "param", "_value": "value", "_ci_low": "ci_low",
                "_ci_high": "ci_high", "_ci_gap_low": "ci_gap_low",
                "_ci_gap_high": "ci_gap_high", "_boot_low": "boot_low",
                "_boot_high": "boot_high", "_ml": "ml"}

        def value(ln, c):
            kind, _, which = c.partition("_")
            if kind in ("rank", "best") and which in crit:
                return int(getattr(ln, kind)[crit.index(which)])
            m = re.match(r"p(\d+)(\w*)$", c)
            if m and m.group(2) in slot:
                q = int(m.group(1)) - 1
                if q >= ln.n_params:
                    return None
                v = getattr(ln, slot[m.group(2)])[q]
                return v if m.group(2) == "" else float(v)
            return getattr(ln, c)
        return self._records(text_, columns, lines, n[0], value)

    def _records(self, text_, columns, lines, n, value):
        """Records of the n library lines (bf_fits_line, bf_ranking_line)
        with the table's columns: sample, name and channel of the line's
        target (its row's), the others value(line, column)."""
        spec = self.spec.spec
        ds = self.spec.dataset._ds
        out = []
        for i in range(n):
            ln = lines[i]
            t = spec.targets[self.rows[ln.row].target]
            rec = {}
            for c in columns:
                if c == "sample":
                    v = int(lib.bf_dataset_number(ds, t.material))
                elif c == "name":
                    v = lib.bf_dataset_name(ds, t.material)
                elif c == "channel":  # a joint fit's shape: "joint"
                    joint = getattr(ln, "joint", 0)  # ranking: per channel
                    v = "joint" if joint else lib.bf_dataset_channel(
                        ds, t.material, t.channel)
                else:
                    v = value(ln, c)
                rec[c] = _field(v)
            out.append(rec)
        return Records(out, columns, text_)

    def missing_note(self):
        """The CLI's note on models left out for lack of inputs, or ""."""
        per_model = {}
        for i in self.missing:
            m = self.spec.models[i % len(self.spec.models)]
            per_model[m] = per_model.get(m, 0) + 1
        return "; ".join(
            "%s not evaluated for %d of %d samples (no %s given: pass "
            "on_params=)" % (m.name, count, int(self.spec.spec.n_targets),
                             ", ".join(p.name for p in m.parameters
                                       if not p.fitted))
            for m, count in per_model.items())
