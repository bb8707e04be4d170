"""_report: `brdffit report` from Python -- the library's bf_report_write
(libbrdffit_report, beside libbrdffit) with the CLI's options as keywords.
It runs the same study and writes the same files: fits.csv, table2.md,
table3.md, report.html and figures/.

libbrdffit_report is looked for in BRDFFIT_REPORT_LIB (a file or folder),
then beside the loaded libbrdffit, then by the dynamic loader.
"""

import math
import os
import warnings
from collections.abc import Mapping

from cffi import FFI

from ._errors import InvalidArgumentError, error, new_error
from ._lib import DEFAULT_N, ffi, lib
from ._lib import path as _core_path
from ._study import (_fresnel, _neyman, _noise, _objective, _sample_table,
                     _smith)

REPORT_CDEF = r"""
int bf_report_write(bf_report_inputs *in, const bf_report_options *o,
                    const char *out_dir, size_t *n_figures, bf_error *err);
"""
NAMES = ("libbrdffit_report.so", "libbrdffit_report.so.0")

_rffi = FFI()
_rffi.include(ffi)
_rffi.cdef(REPORT_CDEF)
_handle = None


def library_candidates():
    """Where libbrdffit_report is looked for, in order, as paths (the last
    a name for the dynamic loader)."""
    out = []
    env = os.environ.get("BRDFFIT_REPORT_LIB", "")
    folders = [env] if env and os.path.isdir(env) else []
    if env and not folders:
        out.append(env)
    folders.append(os.path.dirname(os.path.realpath(_core_path)))
    folders.append(os.path.dirname(os.path.abspath(_core_path)))
    for folder in folders:
        out += [os.path.join(folder, n) for n in NAMES]
    out.append(NAMES[1])
    return out


def _report_lib():
    global _handle
    if _handle is None:
        tried = []
        for p in library_candidates():
            if os.sep in p and not os.path.exists(p):
                continue
            try:
                _handle = _rffi.dlopen(p)
                break
            except OSError as exc:
                tried.append("%s (%s)" % (p, exc))
        if _handle is None:
            raise ImportError("brdffit.report: cannot load libbrdffit_report"
                              " (built with libbrdffit: make build); tried "
                              + ", ".join(tried or library_candidates()))
    return _handle


def _list(name, value, fmt=str):
    """A comma-separated option (the CLI's syntax) from a str or a
    sequence; None stays None."""
    if value is None or isinstance(value, str):
        return value
    items = [fmt(v) for v in value]
    if not items:
        raise InvalidArgumentError("%s: empty list" % name, 1)
    return ",".join(items)


def _model_name(m):
    return m if isinstance(m, str) else m.name


def _inputs(dataset, keep):
    """The bf_report_inputs of dataset: its files for the provenance, as
    the CLI names them (CURET: the folder's table.txt, abrdf.dat and
    samples.tsv; otherwise each material's source file, in order)."""
    inp = ffi.new("bf_report_inputs *")
    inp.ds = dataset._ds
    mats = list(dataset)
    sources = []
    for m in mats:
        if m.source and m.source not in sources:
            sources.append(m.source)
    if mats and all(m.format == "curet" for m in mats):
        inp.curet = 1
        folder = os.path.dirname(sources[0]) if sources else "."
        names = os.path.join(folder, "samples.tsv")
        paths = [os.path.join(folder, "table.txt"), sources[0],
                 names if os.path.exists(names) else ""]
        c = [ffi.new("char[]", os.fsencode(p)) for p in paths]
        keep += c
        inp.table_path, inp.brdf_path, inp.names_path = c
    else:
        if len(sources) > lib.BF_REPORT_MAX_FILES:
            raise InvalidArgumentError("report: more than %d source files"
                                       % lib.BF_REPORT_MAX_FILES, 1)
        for i, p in enumerate(sources):
            c = ffi.new("char[]", os.fsencode(p))
            keep.append(c)
            inp.files[i] = c
        inp.n_files = len(sources)
    return inp


def _formats(value):
    bits = {"png": lib.BF_REPORT_PNG, "svg": lib.BF_REPORT_SVG,
            "pdf": lib.BF_REPORT_PDF}
    names = value.split(",") if isinstance(value, str) else list(value)
    if not names or any(n not in bits for n in names):
        raise InvalidArgumentError("format: %r is not a list of png, svg, "
                                   "pdf" % (value,), 1)
    out = 0
    for n in names:
        out |= 1 << bits[n]
    return out


def report(dataset, out="out", models=None, samples=None, channel=None,
           fit="paper", objective="max", noise="auto", stats=False,
           bootstrap=0, folds=10, seed=1, n=None, n_file=None,
           on_params=None, exclude=None, max_theta=90.0,
           exclude_specular=None, ranges=None, threads=1, format="png,pdf",
           size="double", log=False, per_sample=False, incidence=None,
           fresnel=None, smith=None, calibrate=0, neyman="auto"):
    """Runs the study of `brdffit report` on dataset and writes its report
    into folder out (created, one level, if missing): fits.csv, table2.md,
    table3.md, dispersion.csv (a fitted refractive index -- n with
    fresnel="dielectric", ABC's ior -- on spectral channels), report.html and figures/ -- the same files as the CLI with
    the same options (the page's provenance names bf_report_write instead
    of a command line).

    Keywords are the CLI's options (README, brdffit(1)), in its units:
        models: "all", a comma-separated string or a sequence of names or
            Models; default the paper's six (--models).
        samples: "paper", "all", a string "1,5-9" or numbers; default
            paper on CURET data, all otherwise (--samples).
        channel: a channel name, "mean", "each" or "joint" (--channel).
        fit: "paper" or "exact" (--fit); objective, noise: names
            (--objective, --noise); stats (--stats); bootstrap (--bootstrap
            N); neyman (--neyman: "auto", the default, the Neyman
            construction where a second minimum of a diffuse model's
            profile competes; N >= 100: every parameter's, N simulations
            per threshold; "off": none); folds, seed (--folds, --seed); calibrate: N simulated
            measurements of every fit checking its intervals, 0 none,
            else at least 10; runs the analysis (--calibrate N: the
            report's calibrate.csv, table and calibration_sampleN
            figures; brdffit.calibrate is the same for one fit).
        n: refractive index (--n); n_file, on_params: file paths (--n-file,
            --on-params).
        exclude: configuration numbers (--exclude); max_theta and
            exclude_specular: degrees (--max-theta, --exclude-specular);
            ranges: {parameter: (lo, hi)} (--range).
        fresnel: "schlick", "dielectric" or "none"; smith: "height" or
            "separable"; None each model's own (--fresnel, --smith; SPEC
            §9.2; the page's run description names each specular model's
            NDF, masking and Fresnel term).
        threads: fitting threads and drawing processes, 0 one per core
            (--threads); format: "png,pdf" or a sequence of png, svg, pdf
            (--format); size: "double" or "single" (--size); log (--log);
            per_sample (--per-sample); incidence: degrees, at most 4
            (--incidence).
    Returns the number of figures written; the CLI's notes (a model left
    out for want of its inputs) are UserWarnings. Raises InvalidArgumentError for
    a bad option, DomainError for data the models cannot be fitted to,
    LoadError when an input or output file fails, OutOfMemoryError.
    """
    if fit not in ("paper", "exact"):
        raise InvalidArgumentError("fit must be paper or exact, got %r"
                                   % (fit,), 1)
    if size not in ("double", "single"):
        raise InvalidArgumentError("size must be double or single, got %r"
                                   % (size,), 1)
    for name, v in (("n_file", n_file), ("on_params", on_params)):
        if v is not None and isinstance(v, Mapping):
            raise TypeError("report: %s must be a file path (the page "
                            "names and checksums it)" % name)
    keep = []

    def c(s):
        if s is None:
            return ffi.NULL
        b = ffi.new("char[]", str(s).encode())
        keep.append(b)
        return b

    o = ffi.new("bf_report_options *")
    o.models = c(_list("models", None if models is None else
                       ([_model_name(m) for m in models]
                        if not isinstance(models, str) else models)))
    o.default_models = lib.BF_MODELS_PAPER
    o.samples = c(_list("samples", samples))
    o.channel = c(channel)
    o.exclude = c(_list("exclude", exclude))
    o.cone = -1.0 if exclude_specular is None else float(exclude_specular)
    o.max_theta = float(max_theta)
    o.n = DEFAULT_N if n is None else float(n)
    o.n_given = n is not None
    o.exact = fit == "exact"
    o.objective = _objective(objective)
    o.fresnel = _fresnel(fresnel)
    o.smith = _smith(smith)
    o.noise = _noise(noise)
    rng = list((ranges or {}).items())
    if len(rng) > lib.BF_REPORT_MAX_RANGES:
        raise InvalidArgumentError("ranges: at most %d"
                                   % lib.BF_REPORT_MAX_RANGES, 1)
    for i, (name, (lo, hi)) in enumerate(rng):
        o.range[i] = c("%s=%r:%r" % (name, float(lo), float(hi)))
    o.n_range = len(rng)
    o.n_boot = int(bootstrap)
    o.n_neyman, o.neyman_every = _neyman(neyman)
    o.folds = int(folds)
    o.seed = int(seed)
    o.stats = bool(stats)
    if int(calibrate) < 0:
        raise InvalidArgumentError("calibrate: %r is not a number of "
                                   "simulations (0: none)" % (calibrate,), 1)
    o.calibrate = int(calibrate)
    o.threads = int(threads)
    o.formats = _formats(format)
    o.single_column = size == "single"
    o.log_lse = bool(log)
    o.per_sample = bool(per_sample)
    inc = [] if incidence is None else list(incidence)
    if len(inc) > lib.BF_REPORT_MAX_INCIDENCE or \
            any(not 0.0 <= float(a) <= 89.0 for a in inc):
        raise InvalidArgumentError("incidence: 1 to %d angles in [0, 89] "
                                   "degrees" % lib.BF_REPORT_MAX_INCIDENCE, 1)
    for i, a in enumerate(inc):
        o.incidence[i] = float(a) * (math.pi / 180.0)
    o.n_incidence = len(inc)
    inp = _inputs(dataset, keep)
    tables = []
    if n_file is not None:
        o.n_file = c(os.fspath(n_file))
        tables.append(_sample_table("n", os.fspath(n_file)))
        inp.n_file = tables[-1]
    if on_params is not None:
        o.on_file = c(os.fspath(on_params))
        tables.append(_sample_table("on", os.fspath(on_params)))
        inp.on_params = tables[-1]
    notes = []

    @ffi.callback("bf_report_message_fn")
    def message(_ctx, kind, text):
        if kind == lib.BF_REPORT_MSG_NOTE:
            notes.append(ffi.string(text).decode("utf-8", "replace"))

    o.message = message
    err = new_error()
    nfig = ffi.new("size_t *")
    status = _report_lib().bf_report_write(inp, o, os.fsencode(
        os.fspath(out)), nfig, err)
    for note in notes:  # as the CLI prints them
        warnings.warn(note, UserWarning, stacklevel=2)
    if status != lib.BF_REPORT_OK:
        raise error(err.code, err)
    return int(nfig[0])
