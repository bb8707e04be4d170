#!/usr/bin/python3
"""numpy_baseline.py: the paper's protocol (SPEC §7) as a vectorised numpy
program -- the comparison baseline of the speed benchmark (issue 6).

Never part of the tests or CI: bench_study runs it when /usr/bin/python3 has
numpy (Debian: python3-numpy) and reports both implementations from one run.

For the 24 samples of Ragheb & Hancock and the models VH-G, VH-E, FC-G,
FC-E (n = 1.7), ON (tabulated rho, sigma) and LFTG: the K = 198 non-specular
CURET configurations (SPEC §1.4), radiance = BRDF x cos(theta_i) normalised
by its maximum (SPEC §2), every model curve on the 501-point grid (SPEC
§7.4) normalised the same way, LSE = sum of squared differences (SPEC §7.3),
best grid point (first on ties).

    numpy_baseline.py --data DIR --on-params FILE [--reps N] [--print]

Prints `compute_ms_median <ms>` (fit compute: loading excluded, median of N
runs) and, with --print, the best value and LSE per sample and model.
"""
import argparse
import os
import time

import numpy as np

SPECULAR_TOL = 1e-3  # SPEC §1.4
PAPER_SAMPLES = [1, 2, 5, 7, 9, 12, 16, 17, 20, 22, 23, 25,
                 29, 31, 33, 34, 36, 37, 39, 41, 44, 54, 55, 56]
GRID_M = 0.1 + 0.01 * np.arange(501)     # slope sigma/T, SPEC §7.4
GRID_ND = 0.1 + 0.04 * np.arange(501)    # LFTG n_d, SPEC §7.4
N_FC = 1.7                               # SPEC §4.2


def wrap(a):
    """Wraps angles to (-pi, pi]."""
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi)


def load(data_dir, on_file):
    table = np.loadtxt(os.path.join(data_dir, "table.txt"))
    brdf = np.loadtxt(os.path.join(data_dir, "abrdf.dat"))
    on = {}
    with open(on_file) as fp:
        for line in fp:
            f = line.split()
            if len(f) >= 3 and f[0].isdigit():
                on[int(f[0])] = (float(f[1]), float(f[2]))
    return table, brdf, on


def fresnel(s, c, r):
    """Unpolarised Fresnel reflectance from sin, cos of the angle of arrival
    (SPEC §4.1, with the factor 1/2; no total internal reflection here)."""
    ct = np.sqrt(1.0 - (s / r) ** 2)
    a = (r * ct - c) / (r * ct + c)
    b = (r * c * ct - s * s) / (r * c * ct + s * s)
    return 0.5 * a * a * (1.0 + b * b)


def protocol(table, brdf, on):
    # SPEC §1.3: table.txt columns: index, theta_v, phi_v, theta_i, phi_i
    tv, pv, ti, pi_ = table[:, 1], table[:, 2], table[:, 3], table[:, 4]
    ps = wrap(pv - pi_ - np.pi)
    used = ~((np.abs(tv - ti) < SPECULAR_TOL) & (np.abs(ps) < SPECULAR_TOL))
    tv, ti, ps = tv[used], ti[used], ps[used]
    si, ci, ss, cs = np.sin(ti), np.cos(ti), np.sin(tv), np.cos(tv)
    cp, sp = np.cos(ps), np.sin(ps)

    # SPEC §2: measured radiance, normalised
    rows = {int(r[0]): r[1:] for r in brdf}
    data = np.array([rows[s][used] for s in PAPER_SAMPLES]) * ci
    data /= data.max(axis=1, keepdims=True)

    # SPEC §3: Beckmann-Kirchhoff geometry (k = 1)
    vxy2 = (si - ss * cp) ** 2 + (ss * sp) ** 2
    vz2 = (ci + cs) ** 2
    f_vh = ci                                            # SPEC §3.3
    f_fc = (1 - fresnel(si, ci, N_FC)) * (1 - fresnel(ss / N_FC, np.sqrt(
        1 - (ss / N_FC) ** 2), 1 / N_FC)) * ci           # SPEC §4.2
    m2 = (GRID_M ** 2)[:, None]

    def gauss(f2):   # (P1), SPEC §3.1
        return f2 / (m2 * vz2) * np.exp(-vxy2 / (4 * m2 * vz2))

    def expo(f2):    # (P2), SPEC §3.2
        return 2 / m2 * f2 / vz2 * (1 + vxy2 / (m2 * vz2)) ** -1.5

    curves = {
        "VH-G": gauss(f_vh), "VH-E": expo(f_vh),
        "FC-G": gauss(f_fc), "FC-E": expo(f_fc),
        "LFTG": (GRID_ND[:, None] + 2) / (2 * np.pi)
        * (ci * cs)[None, :] ** GRID_ND[:, None],       # (P7), SPEC §6
    }
    out = {}
    for name, c in curves.items():
        c = c / c.max(axis=1, keepdims=True)             # SPEC §2
        # LSE of every sample against every grid point: |c|^2 - 2 c.d + |d|^2
        lse = ((c * c).sum(axis=1)[None, :] - 2.0 * data @ c.T
               + (data * data).sum(axis=1)[:, None])
        best = lse.argmin(axis=1)
        grid = GRID_ND if name == "LFTG" else GRID_M
        out[name] = (grid[best], lse[np.arange(len(best)), best])

    # SPEC §5: Oren-Nayar at the tabulated rho, sigma, per sample
    alpha, beta = np.maximum(ti, tv), np.minimum(ti, tv)
    cdp = -cp
    lse_on = []
    for j, s in enumerate(PAPER_SAMPLES):
        rho, sig = on[s]
        s2 = sig * sig
        c1 = 1 - 0.5 * s2 / (s2 + 0.33)
        c2 = 0.45 * s2 / (s2 + 0.09) * np.where(
            cdp >= 0, np.sin(alpha), np.sin(alpha) - (2 * beta / np.pi) ** 3)
        c3 = 0.125 * s2 / (s2 + 0.09) * (4 * alpha * beta / np.pi ** 2) ** 2
        l1 = rho / np.pi * ci * (c1 + cdp * c2 * np.tan(beta)
                                 + (1 - np.abs(cdp)) * c3
                                 * np.tan((alpha + beta) / 2))
        l2 = 0.17 * rho ** 2 / np.pi * ci * s2 / (s2 + 0.13) * (
            1 - cdp * (2 * beta / np.pi) ** 2)
        l = l1 + l2
        l /= l.max()
        lse_on.append(((l - data[j]) ** 2).sum())
    out["ON"] = (np.full(len(PAPER_SAMPLES), np.nan), np.array(lse_on))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True)
    ap.add_argument("--on-params", required=True)
    ap.add_argument("--reps", type=int, default=11)
    ap.add_argument("--print", action="store_true")
    a = ap.parse_args()
    table, brdf, on = load(a.data, a.on_params)
    times = []
    for _ in range(max(1, a.reps)):
        t0 = time.perf_counter()
        out = protocol(table, brdf, on)
        times.append(time.perf_counter() - t0)
    print("compute_ms_median %.3f" % (1e3 * float(np.median(times))))
    if a.print:
        for name, (best, lse) in out.items():
            for s, b, l in zip(PAPER_SAMPLES, best, lse):
                print("%d %s %.4f %.6f" % (s, name, b, l))


if __name__ == "__main__":
    main()
