"""_study: one bf_study_spec built from Python arguments, shared by fit(),
compare() and rank(), and the runs of the library's study on it
(bf_study_run, bf_study_analyse). Everything the spec points to is kept
alive by the Spec object.
"""

import os
from collections.abc import Mapping

import numpy as np

from . import _arrays
from ._errors import InvalidArgumentError, check, error, new_error
from ._lib import DEFAULT_N, ffi, lib, libc
from .models import _find

#: The 24 CURET samples of Ragheb & Hancock's study (bf_study_samples).
PAPER_SAMPLES = tuple(int(s) for s in lib.bf_study_samples)

OBJECTIVES = ("max", "scale", "cosw", "log")


def _objective(name):
    """The bf_objective called name; InvalidArgumentError otherwise."""
    obj = ffi.new("bf_objective *")
    if not isinstance(name, str) or lib.bf_objective_find(name.encode(),
                                                          obj) != 0:
        raise InvalidArgumentError("objective must be one of %s, got %r"
                                   % (", ".join(OBJECTIVES), name), 1)
    return obj[0]


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
        buf = ffi.new("char[]", ("\n".join(rows) + "\n").encode())
        name = b"on_params" if kind == "on" else b"n_file"
        fp = libc.fmemopen(buf, len(buf) - 1, b"r")
        if fp == ffi.NULL:
            raise MemoryError("cannot open an in-memory stream")
        try:
            read = lib.bf_on_params_read if kind == "on" else lib.bf_n_file_read
            rc = read(fp, name, out, err)
        finally:
            libc.fclose(fp)
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


class Spec:
    """A bf_study_spec: targets (materials x channel) x models, the
    configuration selection and the models' inputs.

    Args (all as in brdffit.compare):
        dataset, materials, channel, models, n, n_file, on_params, exclude,
        max_theta, cone, threads.
    """

    def __init__(self, dataset, materials, channel, models, n=None,
                 n_file=None, on_params=None, exclude=(), max_theta=None,
                 cone=None, threads=1):
        self.dataset = dataset
        self.models = [_find(m) for m in models]
        if not self.models:
            raise InvalidArgumentError("no model to fit", 1)
        index = _material_indices(dataset, materials)
        if not index:
            raise InvalidArgumentError("no material to fit", 1)
        self._keep = []
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
        lib.bf_select_init(sel)
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

        types = ffi.new("const bf_model_type *[]",
                        [m._type for m in self.models])
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
        spec.n_threads = int(threads)

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

    def analyse(self, rows, objective, exact, level, bootstrap, folds, seed,
                context):
        """The analysis (bf_study_analyse) of rows: n_rows bf_fit_stats."""
        opts = ffi.new("bf_analysis_opts *")
        opts.objective = _objective(objective)
        opts.exact = 1 if exact else 0
        opts.level = float(level)
        opts.n_boot = int(bootstrap)
        opts.folds = int(folds)
        opts.seed = int(seed)
        stats = ffi.new("bf_fit_stats[]", self.n_rows)
        err = new_error()
        check(lib.bf_study_analyse(self.spec, opts, rows, stats, err), err,
              context)
        return stats

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
