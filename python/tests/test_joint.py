"""--channel joint in Python (SPEC §9.4): brdffit.fit(channel="joint")
recovers one shape and each channel's scales of a synthetic three-channel
LAMBERT+GGX material; compare's records carry the shape on channel
"joint"; a model without scales is refused."""

import numpy as np
import pytest

import brdffit
import synth

CHANNELS = ("R", "G", "B")
SHAPE = {"alpha": 0.15, "F0": 0.05}
SCALES = {"R": (0.3, 0.8), "G": (0.2, 0.6), "B": (0.1, 0.4)}


def _dataset():
    """Half the directions within a few degrees of the mirror direction,
    all with theta <= 80 deg (SPEC §10 uses every one)."""
    angles = synth.glossy_directions(3)
    values = np.column_stack([
        brdffit.evaluate("LAMBERT+GGX",
                         {"rho_d": SCALES[c][0], "rho_s": SCALES[c][1],
                          **SHAPE}, *angles.T)
        for c in CHANNELS])
    return brdffit.Dataset.from_arrays(angles, values, names="paint",
                                       channels=CHANNELS)


def test_fit_joint_recovers_shape_and_scales():
    r = brdffit.fit(_dataset(), "LAMBERT+GGX", channel="joint", fit="exact",
                    objective="ngan")
    assert r.channel == "joint"
    assert set(r.parameters) == {"alpha", "F0"}
    for name, v in SHAPE.items():
        assert r.parameters[name] == pytest.approx(v, rel=1e-5)
    assert set(r.scales) == set(CHANNELS)
    for c in CHANNELS:
        assert r.scales[c]["rho_d"] == pytest.approx(SCALES[c][0], rel=1e-5)
        assert r.scales[c]["rho_s"] == pytest.approx(SCALES[c][1], rel=1e-5)
    assert r.objective < 1e-9
    assert r.n_params == 2 + 2 * len(CHANNELS)
    assert [p.channel for p in r.per_channel] == list(CHANNELS)
    for p in r.per_channel:  # each channel: the shape and its own scales
        assert p.parameters["alpha"] == r.parameters["alpha"]
        assert p.parameters["rho_s"] == r.scales[p.channel]["rho_s"]
    assert len(r.measured) == len(CHANNELS) * r.k


def test_compare_records_joint_layout():
    recs = brdffit.compare(_dataset(), models="LAMBERT+GGX", channel="joint",
                           fit="exact", objective="ngan")
    rows = [(x["channel"], x["parameter"]) for x in recs]
    assert rows == [("R", "rho_d"), ("R", "rho_s"), ("joint", "alpha"),
                    ("joint", "F0"), ("G", "rho_d"), ("G", "rho_s"),
                    ("B", "rho_d"), ("B", "rho_s")]


def test_joint_refuses_a_model_without_scales():
    with pytest.raises(brdffit.InvalidArgumentError,
                       match="no scale parameter"):
        brdffit.fit(_dataset(), "LAFORTUNE", channel="joint", fit="exact",
                    objective="ngan")
