"""brdffit.models() and brdffit.evaluate(): the registry, closed forms of
SPEC §3 and §6 computed here independently, the measurement frame of
SPEC §1.5, numpy broadcasting, and clear errors for bad input."""

import warnings

import numpy as np
import pytest

import brdffit

RNG = np.random.default_rng(20240613)
# High-entropy directions (STYLE §7), zeniths below grazing.
TI = RNG.uniform(0.0, 1.5, 64)
PI_ = RNG.uniform(-np.pi, np.pi, 64)
TO = RNG.uniform(0.0, 1.5, 64)
PO = RNG.uniform(-np.pi, np.pi, 64)
REL = 1e-13  # a few hundred ulps: different operation orders


def vh_g(m, ti, ts, ps):
    """SPEC §3.1 with F_BK^2 replaced by cos ti (§3.3), k = 1."""
    vx = np.sin(ti) - np.sin(ts) * np.cos(ps)
    vy = -np.sin(ts) * np.sin(ps)
    vz = -(np.cos(ti) + np.cos(ts))
    return (1 / m**2) * np.cos(ti) / vz**2 * np.exp(
        -(vx**2 + vy**2) / (4 * m**2 * vz**2))


def test_the_version_of_the_package_is_the_librarys():
    assert brdffit.__version__ == brdffit.library_version()


def test_the_library_is_the_one_brdffit_lib_names():
    import os
    env = os.environ.get("BRDFFIT_LIB")
    assert env, "CTest sets BRDFFIT_LIB to the build's libbrdffit.so"
    assert brdffit.library_path == env


def test_the_registry_lists_every_model_with_sane_parameters():
    models = brdffit.models()
    names = [m.name for m in models]
    for name in ("BK-G", "BK-E", "VH-G", "VH-E", "FC-G", "FC-E", "ON",
                 "LFTG", "LAMBERT", "WNO", "WNO-R"):
        assert name in names
    assert len(set(names)) == len(names)
    for m in models:
        assert m.title and m.reference
        for p in m.parameters:
            assert p.unit in ("1", "rad")
            assert p.min <= p.default <= p.max
            if p.grid is not None:
                lo, step, n = p.grid
                assert p.min <= lo and lo + step * (n - 1) <= p.max + 1e-12


def test_the_paper_grids_are_those_of_spec_7_4():
    # m = 0.1 + 0.01 i and n_d = 0.1 + 0.04 i, i = 0..500 (SPEC §7.4)
    for name in ("VH-G", "VH-E", "FC-G", "FC-E"):
        (m,) = [p for p in brdffit.model(name).parameters if p.name == "m"]
        assert m.fitted and m.grid == (0.1, 0.01, 501)
    (nd,) = brdffit.model("LFTG").parameters
    assert nd.fitted and nd.grid == (0.1, 0.04, 501)
    on = brdffit.model("on")
    assert [p.name for p in on.parameters] == ["rho", "sigma"]
    assert [p.unit for p in on.parameters] == ["1", "rad"]
    assert not any(p.fitted for p in on.parameters)


def test_lftg_equals_p7_in_the_measurement_frame():
    n_d = 3.4567
    got = brdffit.evaluate("LFTG", [n_d], TI, PI_, TO, PO)
    expected = (n_d + 2) / (2 * np.pi) * (np.cos(TI) * np.cos(TO))**n_d
    np.testing.assert_allclose(got, expected, rtol=REL)


def test_vh_g_equals_spec_3_with_phi_s_from_spec_1_5():
    m = 0.4321
    got = brdffit.evaluate("VH-G", {"m": m}, TI, PI_, TO, PO)
    ps = np.angle(np.exp(1j * (PO - PI_ - np.pi)))  # wrap(po - pi - pi)
    np.testing.assert_allclose(got, vh_g(m, TI, TO, ps), rtol=REL)


def test_the_beckmann_frame_is_passed_through():
    m = 0.2718
    ps = RNG.uniform(-np.pi, np.pi, TI.shape)
    got = brdffit.evaluate("VH-G", [m], TI, np.pi, TO, ps, frame="beckmann")
    np.testing.assert_allclose(got, vh_g(m, TI, TO, ps), rtol=REL)


def test_the_mirror_direction_is_specular_in_either_frame():
    # SPEC §1.5: the mirror of (ti, pi) is (ti, pi + pi); Beckmann's
    # specular direction is ts = ti, ps = 0 (SPEC §1.2).
    a = brdffit.evaluate("FC-E", {"m": 0.3}, 0.6, 1.234, 0.6, 1.234 + np.pi)
    b = brdffit.evaluate("FC-E", {"m": 0.3}, 0.6, np.pi, 0.6, 0.0,
                         frame="beckmann")
    assert a == pytest.approx(b, rel=REL)


def test_lambert_is_cos_theta_i_up_to_a_constant():
    got = brdffit.evaluate("LAMBERT", [], TI, PI_, TO, PO)
    ratio = got / np.cos(TI)
    np.testing.assert_allclose(ratio, ratio[0], rtol=REL)


def test_angles_broadcast_like_numpy():
    ti = np.linspace(0.0, 1.4, 5)[:, None]
    to = np.linspace(0.1, 1.3, 3)[None, :]
    got = brdffit.evaluate("LFTG", [2.0], ti, 0.0, to, np.pi)
    assert got.shape == (5, 3)
    for i in range(5):
        for j in range(3):
            assert got[i, j] == brdffit.evaluate("LFTG", [2.0], ti[i, 0],
                                                 0.0, to[0, j], np.pi)
    scalar = brdffit.evaluate("LFTG", [2.0], 0.3, 0.0, 0.5, np.pi)
    assert np.ndim(scalar) == 0
    assert brdffit.evaluate("LFTG", [2.0], np.zeros((0, 3)), 0, 0, 0).shape \
        == (0, 3)


def test_strided_and_integer_arrays_give_the_same_values():
    big = np.zeros((64, 3))
    big[:, 1] = TI
    ref = brdffit.evaluate("LFTG", [1.5], TI, PI_, TO, PO)
    strided = brdffit.evaluate("LFTG", [1.5], big[:, 1], PI_, TO, PO)
    np.testing.assert_array_equal(strided, ref)
    ints = brdffit.evaluate("LFTG", [2], 0, 0, 1, 3)
    assert ints == brdffit.evaluate("LFTG", [2.0], 0.0, 0.0, 1.0, 3.0)


def test_parameters_by_name_keep_the_other_defaults():
    fc = brdffit.model("FC-E")
    assert fc.defaults["n"] == 1.7
    a = brdffit.evaluate(fc, {"m": 0.5}, TI, PI_, TO, PO)
    b = brdffit.evaluate(fc, [0.5, 1.7], TI, PI_, TO, PO)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, fc.evaluate({"m": 0.5, "n": 1.4}, TI, PI_,
                                             TO, PO))


def test_bk_g_is_nan_with_a_warning_only_where_it_is_undefined():
    ti = np.array([0.3, np.pi / 2, 0.7])
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        got = brdffit.evaluate("BK-G", [0.5], ti, 0.0, 0.4, np.pi)
    assert [type(x.message) for x in w] == [brdffit.DomainWarning]
    assert "1 of 3" in str(w[0].message)
    assert np.isnan(got[1]) and np.isfinite(got[[0, 2]]).all()


@pytest.mark.parametrize("params, text", [
    ([200.0], "n_d = 200.0 is outside its domain [0, 100]"),
    ([np.nan], "n_d = nan is outside its domain"),
    ([1.0, 2.0], "takes 1 parameter(s) (n_d), got 2"),
    ({"m": 1.0}, "LFTG has no parameter 'm' (it has: n_d)"),
])
def test_bad_parameters_are_clear_errors(params, text):
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        brdffit.evaluate("LFTG", params, 0.1, 0.0, 0.2, 0.0)
    assert text in str(e.value)
    assert e.value.code_name == "BF_EINVAL"


def test_bad_angles_and_arrays_are_clear_errors():
    with pytest.raises(brdffit.InvalidArgumentError, match=r"\[0, pi/2\]"):
        brdffit.evaluate("LFTG", [1], [0.1, 1.6], 0.0, 0.2, 0.0)
    with pytest.raises(brdffit.InvalidArgumentError, match="flat index 1"):
        brdffit.evaluate("LFTG", [1], [0.1, -0.1], 0.0, 0.2, 0.0,
                         frame="beckmann")
    with pytest.raises(ValueError, match="do not broadcast"):
        brdffit.evaluate("LFTG", [1], [0.1, 0.2], 0.0, [0.1, 0.2, 0.3], 0)
    with pytest.raises(TypeError, match="theta_o: expected real numbers"):
        brdffit.evaluate("LFTG", [1], 0.1, 0.0, "0.2", 0.0)
    with pytest.raises(TypeError, match="phi_i: expected real numbers"):
        brdffit.evaluate("LFTG", [1], 0.1, 1j, 0.2, 0.0)
    with pytest.raises(TypeError, match="theta_i: expected real numbers"):
        brdffit.evaluate("LFTG", [1], [True], 0.0, 0.2, 0.0)
    with pytest.raises(ValueError, match="frame must be one of"):
        brdffit.evaluate("LFTG", [1], 0.1, 0.0, 0.2, 0.0, frame="sample")
    with pytest.raises(brdffit.NotFoundError, match="unknown model 'XYZ'"):
        brdffit.evaluate("XYZ", [], 0.1, 0.0, 0.2, 0.0)
    with pytest.raises(LookupError):  # NotFoundError is a LookupError
        brdffit.model("nope")


def test_the_specular_family_is_listed_with_its_kind_and_scales():
    # SPEC §9.3: names, parameters in order, the linear scales
    want = {"GGX": ("rho_s", "alpha", "F0"), "BECKMANN": ("rho_s", "alpha",
                                                         "F0"),
            "CT": ("rho_s", "alpha", "F0"), "BLINN-PHONG": ("rho_s", "e"),
            "WARD": ("rho_s", "alpha"), "WARD-DUER": ("rho_s", "alpha"),
            "WARD-GMD": ("rho_s", "alpha"), "AS": ("Rd", "Rs", "n"),
            "LAFORTUNE": ("Cxy", "Cz", "n"),
            "ABC": ("A", "B", "C", "ior")}
    models = {m.name: m for m in brdffit.models()}
    for name, params in want.items():
        m = models[name]
        assert m.kind == "specular"
        assert tuple(p.name for p in m.parameters) == params
        assert [p.name for p in m.parameters if p.linear] == (
            [] if name == "LAFORTUNE" else [params[0]])
        assert [p.homog for p in m.parameters] == (
            ["scaled", "unit", "degree"] if name == "LAFORTUNE"
            else [None] * len(params))
        assert m.ndf and m.masking and m.fresnel
    assert models["GGX"].masking.startswith("Smith height-correlated")
    # a composite carries its lobe's parameters as they are
    assert [p.homog for p in brdffit.model("LAMBERT+LAFORTUNE").parameters
            ] == [None, "scaled", "unit", "degree"]
    for name in ("VH-G", "ON", "LAMBERT", "WNO-R"):
        m = models[name]
        assert m.kind == "diffuse" and m.ndf is None
        assert not any(p.linear for p in m.parameters)


def test_a_specular_model_evaluates_in_sr_per_steradian():
    # GGX at normal incidence and view, F0 = 1: D(0) G2 / 4 = 1/(4 pi a^2)
    v = brdffit.evaluate("GGX", {"alpha": 0.1, "F0": 1.0}, 0.0, 0.0, 0.0,
                         0.0)
    assert abs(float(v) - 1.0 / (4 * np.pi * 0.01)) < 1e-12 * float(v)


def test_a_composite_is_a_model_by_name():
    # SPEC §9.4: rho_d, then D's, then S's; LAMBERT's d is 1/pi
    m = brdffit.model("lambert+ggx")
    assert m.name == "LAMBERT+GGX" and m.kind == "specular"
    assert [p.name for p in m.parameters] == ["rho_d", "rho_s", "alpha",
                                              "F0"]
    assert m.ndf == brdffit.model("GGX").ndf
    v = brdffit.evaluate(m, [0.3, 0.5, 0.2, 0.04], 0.5, 0.0, 0.4, 2.0)
    s = brdffit.evaluate("GGX", [0.5, 0.2, 0.04], 0.5, 0.0, 0.4, 2.0)
    assert abs(v - (0.3 / np.pi + s)) <= 1e-14 * abs(v)
    assert m not in brdffit.models()  # found by name, not listed
    with pytest.raises(brdffit.NotFoundError, match="diffuse model first"):
        brdffit.model("GGX+LAMBERT")
    with pytest.raises(brdffit.NotFoundError, match="one specular part"):
        brdffit.model("GGX+CT")
