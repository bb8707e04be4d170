"""models: the library's model registry and model evaluation.

Angles are in radians, zenith from the surface normal (SPEC §1.1). By
default they are given in the measurement frame of SPEC §1.5 -- incident
(theta_i, phi_i) and outgoing (theta_o, phi_o) directions both pointing
away from the surface, the mirror direction of (theta_i, phi_i) at
(theta_i, phi_i + pi) -- and the library converts them to Beckmann's frame
(bf_geom_from_measurement) before evaluating. frame="beckmann" passes
(theta_i, phi_i, theta_s, phi_s) in Beckmann's frame (SPEC §1.2: phi_i = pi,
the specular direction at theta_s = theta_i, phi_s = 0) unchanged.
"""

import warnings
from collections.abc import Mapping

import numpy as np

from . import _arrays
from ._errors import DomainWarning, InvalidArgumentError, NotFoundError
from ._errors import check
from ._lib import ffi, lib, text

FRAMES = ("measurement", "beckmann")


class Parameter:
    """One parameter of a model (bf_param).

    Attributes:
        name: short name ("m", "n", "n_d", "rho", "sigma").
        label: label for tables and plots, e.g. "sigma/T (G)".
        unit: "1" for dimensionless, "rad" for radians.
        min, max: the valid domain, inclusive.
        default: the value used when the parameter is held fixed.
        fitted: True when the paper's protocol fits it.
        grid: (lo, step, n) of the paper's grid lo + step*i, i < n
            (SPEC §7.4), or None when it has none.
        exact_range: (lo, hi, step) over which fit="exact" fits this input
            (FC's n, ON's rho and sigma; doc/methods.md §6), or None when
            the exact fit never frees it.
        linear: True for a scale the value is proportional to (SPEC §9.3's
            rho_s, A, AS's Rd), which a separable fit solves exactly.
        homog: its part in a lobe homogeneous in some parameters
            (bf_param.homog: LAFORTUNE's value at (t Cxy, t Cz, n) is t^n
            times that at (Cxy, Cz, n)): "unit" (Cz, held at 1 while the
            separable fit's grid solves the lobe's size), "scaled" (Cxy),
            "degree" (n), or None.
    """

    __slots__ = ("name", "label", "unit", "min", "max", "default", "fitted",
                 "grid", "exact_range", "linear", "homog")

    def __init__(self, p):
        self.name = text(p.name)
        self.label = text(p.label)
        self.unit = text(p.unit)
        self.min = float(p.min)
        self.max = float(p.max)
        self.default = float(p.value)
        self.fitted = bool(p.fitted)
        self.grid = ((float(p.grid_lo), float(p.grid_step), int(p.grid_n))
                     if p.grid_n > 0 else None)
        self.exact_range = ((float(p.free_lo), float(p.free_hi),
                             float(p.free_step))
                            if p.free_lo < p.free_hi else None)
        self.linear = bool(p.linear)
        self.homog = {1: "unit", 2: "scaled", 3: "degree"}.get(int(p.homog))

    def __repr__(self):
        return ("Parameter(%r, unit=%r, range=[%g, %g], default=%g%s)"
                % (self.name, self.unit, self.min, self.max, self.default,
                   ", fitted" if self.fitted else ""))


class Model:
    """A reflectance model of the registry (bf_model_type).

    Attributes:
        name: registry name, e.g. "FC-E".
        title: one-line description.
        reference: the equations it implements, e.g. "paper (P2),(P6)".
        parameters: tuple of Parameter.
        kind: "diffuse" (SPEC §3-6: radiance up to scale, compared after
            max-normalisation) or "specular" (SPEC §9: BRDF in sr^-1).
        ndf, masking, fresnel: a specular model's normal distribution,
            masking form and Fresnel term (SPEC §9.2), None for diffuse.
    Use brdffit.model(name) or brdffit.models() to get one.
    """

    def __init__(self, ctype):
        self._type = ctype
        self.name = text(ctype.name)
        self.title = text(ctype.title)
        self.reference = text(ctype.reference)
        self.parameters = tuple(Parameter(ctype.param[j])
                                for j in range(ctype.p))
        specular = ctype.kind == lib.BF_MODEL_SPECULAR
        self.kind = "specular" if specular else "diffuse"
        self.ndf = text(ctype.ndf) if specular else None
        self.masking = text(ctype.masking) if specular else None
        self.fresnel = text(ctype.fresnel_term) if specular else None

    @property
    def defaults(self):
        """The default parameter values, as a dict name -> value."""
        return {p.name: p.default for p in self.parameters}

    def values(self, params):
        """The full parameter vector (a float64 array, one value per
        parameter) from a sequence of values, a mapping name -> value
        (parameters left out keep their defaults) or None (the defaults).
        Raises InvalidArgumentError for an unknown name, a wrong count or a
        value outside the parameter's domain."""
        names = [p.name for p in self.parameters]
        if params is None:
            params = {}
        if isinstance(params, Mapping):
            unknown = sorted(set(params) - set(names))
            if unknown:
                raise InvalidArgumentError(
                    "%s has no parameter %s (it has: %s)"
                    % (self.name, ", ".join(map(repr, unknown)),
                       ", ".join(names) or "none"), 1)
            vals = [params.get(p.name, p.default) for p in self.parameters]
        else:
            vals = list(np.atleast_1d(_arrays.real("params", params)).ravel())
            if len(vals) != len(names):
                raise InvalidArgumentError(
                    "%s takes %d parameter(s) (%s), got %d"
                    % (self.name, len(names), ", ".join(names), len(vals)),
                    1)
        out = _arrays.real("params", np.asarray(vals, dtype=float))
        for p, v in zip(self.parameters, out):
            if not (p.min <= v <= p.max):  # also rejects NaN
                raise InvalidArgumentError(
                    "%s: parameter %s = %r is outside its domain [%g, %g]"
                    % (self.name, p.name, float(v), p.min, p.max), 1)
        return out

    def evaluate(self, params, theta_i, phi_i, theta_o, phi_o,
                 frame="measurement"):
        """The model's radiance (up to scale; a specular model's BRDF in
        sr^-1) at the given directions; see brdffit.evaluate."""
        return evaluate(self, params, theta_i, phi_i, theta_o, phi_o, frame)

    def __repr__(self):
        return "Model(%r: %s; %s)" % (
            self.name, self.title,
            ", ".join(p.name for p in self.parameters) or "no parameters")

    def __eq__(self, other):
        return isinstance(other, Model) and other.name == self.name

    def __hash__(self):
        return hash(self.name)


_REGISTRY = None


def models():
    """Every model of the library's registry, in registry order, as a list
    of Model (name, title, reference, parameters with units, ranges,
    defaults and grids)."""
    global _REGISTRY
    if _REGISTRY is None:
        _REGISTRY = [Model(lib.bf_model_get(i))
                     for i in range(lib.bf_model_count())]
    return list(_REGISTRY)


def model(name, fresnel=None, smith=None):
    """The model called name (case-insensitive, bf_model_find; "D+S" is the
    composite of SPEC §9.4, e.g. "LAMBERT+GGX"); a Model is returned as it
    is. fresnel ("schlick", "dielectric", "none") and smith ("height",
    "separable"), SPEC §9.2, give a specular model's variant
    (bf_model_specular_variant; the CLI's --fresnel, --smith): GGX with
    fresnel="dielectric" has the parameters rho_s, alpha, n. Raises
    NotFoundError naming the known models (for a composite, why the name
    is refused); InvalidArgumentError when the model cannot take the
    option (the library's sentence says why)."""
    m = _find(name)
    if fresnel is None and smith is None:
        return m
    from ._study import _fresnel, _smith
    why = ffi.new("const char **")
    ctype = lib.bf_model_specular_variant(m._type, _fresnel(fresnel),
                                          _smith(smith), why)
    if ctype == ffi.NULL:
        raise InvalidArgumentError("%s %s" % (m.name, text(why[0])), 1)
    return m if ctype == m._type else Model(ctype)


def _find(name):
    """model(name), callable where a parameter is called model."""
    if isinstance(name, Model):
        return name
    if not isinstance(name, str):
        raise TypeError("model: expected a model name, got %r" % (name,))
    why = ffi.new("const char **")
    ctype = lib.bf_model_find_why(name.encode(), why)
    if ctype == ffi.NULL and "+" in name:  # a composite D+S (SPEC §9.4)
        raise NotFoundError("model %r: %s" % (name, text(why[0])), 7)
    if ctype == ffi.NULL:
        raise NotFoundError("unknown model %r (known: %s)" % (
            name, ", ".join(m.name for m in models())), 7)
    # a composite D+S is not listed by the registry: its own Model
    return next((m for m in models() if m.name == text(ctype.name)),
                None) or Model(ctype)


def _beckmann_geometry(angles, frame, keep):
    """A `bf_geom *` for the (n, 4) float64 array angles given in frame.
    Objects that must outlive the call are appended to keep."""
    if frame == "beckmann":
        keep.append(angles)
        # bf_geom is four doubles (test_layout.py checks it).
        return ffi.cast("bf_geom *", _arrays.doubles(angles))
    # The library converts SPEC §1.5 to Beckmann's frame for a dataset's
    # configurations; a one-material dataset lends them.
    ds = ffi.gc(lib.bf_dataset_alloc(), lib.bf_dataset_free)
    if ds == ffi.NULL:
        raise MemoryError("evaluate: out of memory")
    keep.append(ds)
    set_id = ffi.new("size_t *")
    bad = ffi.new("size_t *")
    rc = lib.bf_dataset_add_configs(ds, len(angles), _arrays.doubles(angles),
                                    set_id, bad)
    if rc == 1:
        raise InvalidArgumentError(
            "evaluate: configuration %d (theta_i, phi_i, theta_o, phi_o) = "
            "%s: zenith angles must lie in [0, pi/2] and azimuths be finite"
            % (bad[0], tuple(float(v) for v in angles[bad[0]])), 1)
    check(rc, context="evaluate")
    values = np.zeros(len(angles))
    desc = ffi.new("bf_material_desc *")
    name = ffi.new("char[]", b"evaluate")
    desc.name = name
    desc.format = lib.BF_FORMAT_MEMORY
    desc.set = set_id[0]
    desc.n_channels = 1
    desc.values = _arrays.doubles(values)
    check(lib.bf_dataset_add_material(ds, desc, ffi.NULL),
          context="evaluate")
    return lib.bf_dataset_geom(ds, 0)


def evaluate(model, params, theta_i, phi_i, theta_o, phi_o,
             frame="measurement"):
    """Evaluates a model at many configurations (bf_model_eval).

    Args:
        model: a model name ("FC-E") or a Model.
        params: the parameter values -- a sequence in the model's order, a
            mapping name -> value (the others keep their defaults), or None
            for the defaults. Each must lie in its domain.
        theta_i, phi_i, theta_o, phi_o: angles in radians, any shapes that
            broadcast together (numpy rules). In the measurement frame of
            SPEC §1.5 by default; with frame="beckmann" the last two are
            theta_s, phi_s of Beckmann's frame (SPEC §1.2).
        frame: "measurement" (default) or "beckmann".

    Returns:
        A float64 array of the broadcast shape (a numpy scalar for scalar
        angles): the model's radiance up to a constant factor, as the study
        uses it before normalising (SPEC §2).

    Raises:
        InvalidArgumentError: a parameter outside its domain, a zenith
            angle outside [0, pi/2] or a non-finite angle.
        TypeError, ValueError: arrays that are not real numbers or do not
            broadcast.
    Where the model itself is undefined (BK-G, BK-E at theta_i = pi/2) the
    value is NaN and a DomainWarning is issued.
    """
    m = _find(model)
    if frame not in FRAMES:
        raise ValueError("evaluate: frame must be one of %s, got %r"
                         % (", ".join(FRAMES), frame))
    p = m.values(params)
    arrays = [_arrays.real(n, a) for n, a in
              zip(("theta_i", "phi_i", "theta_o", "phi_o"),
                  (theta_i, phi_i, theta_o, phi_o))]
    try:
        b = np.broadcast_arrays(*arrays)
    except ValueError as exc:
        raise ValueError("evaluate: the angle arrays do not broadcast "
                         "together: %s" % exc) from None
    shape = b[0].shape
    angles = np.ascontiguousarray(np.stack([a.ravel() for a in b], axis=1))
    out = np.empty(len(angles))
    if len(angles) > 0:
        keep = []
        geom = _beckmann_geometry(angles, frame, keep)
        rc = lib.bf_model_eval(m._type, _arrays.doubles(p), len(angles),
                               geom, _arrays.doubles(out))
        if rc == 2:
            warnings.warn("%s is undefined at %d of %d configurations "
                          "(NaN there)" % (m.name, np.isnan(out).sum(),
                                           len(out)),
                          DomainWarning, stacklevel=2)
        elif rc == 1:
            bad = np.flatnonzero(~((angles[:, 0] >= 0) &
                                   (angles[:, 0] <= np.pi / 2) &
                                   (angles[:, 2] >= 0) &
                                   (angles[:, 2] <= np.pi / 2) &
                                   np.isfinite(angles).all(axis=1)))
            where = (" (first at flat index %d: %s)"
                     % (bad[0], tuple(float(v) for v in angles[bad[0]]))
                     if len(bad) else "")
            raise InvalidArgumentError(
                "evaluate: %s: a zenith angle is outside [0, pi/2] or an "
                "angle is not finite%s" % (m.name, where), 1)
        else:
            check(rc, context="evaluate: " + m.name)
    out = out.reshape(shape)
    return out[()] if out.ndim == 0 else out
