"""synth: synthetic measurements for the round trips of the fit tests --
directions drawn with a fixed seed, radiance from brdffit.evaluate (the
model's values the library computes), noise of a fixed seed."""

import numpy as np

import brdffit

N = 150


def directions(seed, n=N):
    """(n, 4) upper-hemisphere configurations (measurement frame), never
    grazing: cos theta_i > 0, so BRDF = radiance / cos theta_i is defined
    (SPEC §2)."""
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(0.0, 1.45, n),
                            rng.uniform(-np.pi, np.pi, n),
                            rng.uniform(0.0, 1.45, n),
                            rng.uniform(-np.pi, np.pi, n)])


def glossy_directions(seed, n=200):
    """(n, 4) configurations (measurement frame) for specular models: half
    within a few degrees of the mirror direction, all with theta <= 80
    deg (SPEC §10 uses every one)."""
    rng = np.random.default_rng(seed)
    ti = rng.uniform(0.05, 1.3, n)
    near = np.arange(n) < n // 2
    to = np.where(near, ti + rng.uniform(-0.07, 0.07, n),
                  rng.uniform(0.05, 1.35, n))
    po = np.where(near, np.pi + rng.uniform(-0.1, 0.1, n),
                  rng.uniform(-np.pi, np.pi, n))
    return np.column_stack([ti, np.zeros(n), np.abs(to), po])


def dataset(angles, model, params, noise=0.0, seed=5, relative=True):
    """A one-material dataset whose radiance L is model at params with
    fixed-seed Gaussian noise e: L (1 + noise e) (relative) or
    L + noise max(L) e (absolute: homoscedastic, as the profile
    likelihood assumes)."""
    radiance = brdffit.evaluate(model, params, *angles.T)
    e = np.random.default_rng(seed).standard_normal(len(angles))
    scale = radiance if relative else radiance.max()
    brdf = (radiance + noise * scale * e) / np.cos(angles[:, 0])
    return brdffit.Dataset.from_arrays(angles, brdf, names="synthetic")
