#!/usr/bin/python3
"""numpy_cells.py: the paper's grid fit over every valid cell of a MERL
table, as a user would write it in numpy -- the comparison baseline of
bench/bench_merl.c (issue 10). Never part of the tests or CI.

Reads FILE, written by bench_merl: K, then K values each of theta_i,
theta_s, phi_s (Beckmann's frame, SPEC §1.2) and the normalised measured
radiance (SPEC §2), all float64. For VH-E, LFTG and VH-G it loops over the
501 grid values (SPEC §7.4), evaluates the model on all K configurations
(up to the factors that cancel in the normalisation), normalises it,
takes LSE = sum of squared differences (SPEC §7.3) and keeps the best;
501 x K arrays (4.4 GB each at K = 1.1 million) would not fit, so one
grid value at a time, each a vector operation over the configurations.

    numpy_cells.py FILE

Prints one line per model: `<model> <seconds> <best value> <lse>`.
"""
import sys
import time

import numpy as np


def main():
    np.seterr(all="ignore")  # log(0) at grazing: exp(-inf) = 0, as (P7)
    raw = np.fromfile(sys.argv[1], dtype=np.float64)
    k = int(raw[0])
    ti, ts, ps, data = (raw[1 + i * k:1 + (i + 1) * k] for i in range(4))
    si, ci, ss, cs = np.sin(ti), np.cos(ti), np.sin(ts), np.cos(ts)
    cp, sp = np.cos(ps), np.sin(ps)
    vxy2 = (si - ss * cp) ** 2 + (ss * sp) ** 2        # SPEC §3
    vz2 = (ci + cs) ** 2
    ln_base = np.log(ci * cs)                         # (P7)
    grid_m = 0.1 + 0.01 * np.arange(501)
    grid_nd = 0.1 + 0.04 * np.arange(501)
    models = {
        "VH-E": (grid_m, lambda m: ci / vz2 * (1 + vxy2 / (m * m * vz2))
                 ** -1.5),                            # (P2), SPEC §3.3
        "LFTG": (grid_nd, lambda n: np.exp(n * ln_base)),
        "VH-G": (grid_m, lambda m: ci / vz2 * np.exp(-vxy2 / (4 * m * m
                                                             * vz2))),
    }
    for name, (grid, curve) in models.items():
        t0 = time.perf_counter()
        best, value = np.inf, np.nan
        for x in grid:
            c = curve(x)
            c /= c.max()                              # SPEC §2
            r = c - data
            lse = np.dot(r, r)                        # SPEC §7.3
            if lse < best:
                best, value = lse, x
        print("%s %.4f %.4f %.6g" % (name, time.perf_counter() - t0, value,
                                     best))


if __name__ == "__main__":
    main()
