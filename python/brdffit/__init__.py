"""brdffit: fit rough-surface reflectance models to measured BRDF data.

A thin numpy layer over the C library libbrdffit (through cffi, ABI mode):
every number comes from the library. See python/README.md section
"Python" of the repository's README.md.

    import brdffit
    brdffit.models()                       # the registry
    brdffit.evaluate("FC-E", {"m": 0.3}, theta_i, phi_i, theta_o, phi_o)
    ds = brdffit.load("../shared/data/curet")
    r = brdffit.fit(ds, "FC-E", material=5, fit="exact")
    c = brdffit.calibrate(ds, "FC-E", material=5)   # do its intervals cover?
    fits = brdffit.compare(ds, stats=True)   # the rows of fits.csv
    ranking = brdffit.rank(ds)               # the rows of ranking.csv
    brdffit.report(ds, out="out", stats=True)  # `brdffit report`'s files
"""

from ._version import VERSION as __version__
from ._errors import (BrdffitError, ConvergenceError, DomainError,
                      DomainWarning, InvalidArgumentError, LoadError,
                      NotFoundError, OutOfMemoryError, ParseError)
from ._lib import library_candidates
from ._lib import path as library_path
from .studies import compare, rank
from .dataset import Dataset, Material, load
from .fit import FitResult, fit
from .calibrate import Calibration, calibrate
from .models import Model, Parameter, evaluate, model, models
from .records import Records
from ._report import report

__all__ = [
    "BrdffitError", "ConvergenceError", "DomainError", "DomainWarning",
    "InvalidArgumentError", "LoadError", "NotFoundError", "OutOfMemoryError",
    "ParseError", "Dataset", "Material", "load", "FitResult", "fit",
    "Calibration", "calibrate",
    "compare", "rank", "report", "Records", "Model", "Parameter", "evaluate",
    "model", "models", "objectives", "library_candidates", "library_path",
    "library_version",
]


def objectives():
    """The names of the objectives fit(), compare() and rank() accept
    (the library's bf_objective_name: "max", the paper's LSE, first)."""
    from ._study import OBJECTIVES
    return list(OBJECTIVES)


def library_version():
    """The version string of the loaded libbrdffit (bf_version)."""
    from ._lib import lib, text
    return text(lib.bf_version())
