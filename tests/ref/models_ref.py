#!/usr/bin/env python3
"""models_ref.py: independent reference values for tests/models/test_*.c and
tests/test_fresnel.c.

Plain Python (double precision, math module only). Every quantity is formed
by a route different from the C code:
  - v = k1 - ks from unit vectors (Beckmann's wave vectors), not the
    trigonometric vx, vy, vz of SPEC §3;
  - F_BK numerator as 1 + w_i . w_s (w_i towards the source, azimuth pi);
  - the E form in its printed (P2) shape, (1 + x)^(-3/2) / vz^2;
  - Fresnel from the textbook amplitude coefficients rs, rp (Born & Wolf
    §1.5), not from (P4);
  - Oren-Nayar's cos(dphi) from the tangential projections of w_i and w_s.
Run: python3 tests/ref/models_ref.py
"""
import math

TI, TS, PS = 0.7313, 1.0219, 2.2619   # high-entropy configuration
PS_FWD = 0.3512                       # a near-forward azimuth
M, N = 0.6173, 1.7


def unit(theta, phi):
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
            math.cos(theta))


def fresnel_textbook(a, r):
    st = math.sin(a) / r
    if st >= 1.0:
        return 1.0
    ci, ct = math.cos(a), math.sqrt(1.0 - st * st)
    rs = (ci - r * ct) / (ci + r * ct)
    rp = (ct - r * ci) / (ct + r * ci)
    return 0.5 * (rs * rs + rp * rp)


def bk_family(ti, ts, ps, m, n):
    wi = unit(ti, math.pi)           # towards the source, phi_i = pi
    ws = unit(ts, ps)
    k1 = tuple(-c for c in wi)       # incident wave vector, k = 1
    v = tuple(a - b for a, b in zip(k1, ws))
    vxy2 = v[0] ** 2 + v[1] ** 2
    vz2 = v[2] ** 2
    ci = wi[2]
    dot = sum(a * b for a, b in zip(wi, ws))
    f_bk = (1.0 + dot) / (ci * (ci + ws[2]))
    t_in = 1.0 - fresnel_textbook(ti, n)
    t_out = 1.0 - fresnel_textbook(math.asin(math.sin(ts) / n), 1.0 / n)
    fac = {"BK": f_bk ** 2, "VH": ci, "FC": t_in * t_out * ci}
    g = 1.0 / (m * m) / vz2 * math.exp(-vxy2 / (4 * m * m * vz2))
    e = 2.0 / (m * m) / vz2 * (1.0 + vxy2 / (m * m * vz2)) ** -1.5
    out = {}
    for key, f2 in fac.items():
        out[key + "-G"] = f2 * g
        out[key + "-E"] = f2 * e
    return out


def oren_nayar(ti, ts, ps, rho, sigma):
    wi, ws = unit(ti, math.pi), unit(ts, ps)
    cdp = (wi[0] * ws[0] + wi[1] * ws[1]) / (math.sin(ti) * math.sin(ts))
    a, b = max(ti, ts), min(ti, ts)
    s2 = sigma * sigma
    c1 = 1 - 0.5 * s2 / (s2 + 0.33)
    c2 = 0.45 * s2 / (s2 + 0.09) * (math.sin(a) if cdp >= 0
                                    else math.sin(a) - (2 * b / math.pi) ** 3)
    c3 = 0.125 * s2 / (s2 + 0.09) * (4 * a * b / math.pi ** 2) ** 2
    l1 = rho / math.pi * math.cos(ti) * (
        c1 + cdp * c2 * math.tan(b)
        + (1 - abs(cdp)) * c3 * math.tan((a + b) / 2))
    l2 = 0.17 * rho * rho / math.pi * math.cos(ti) * s2 / (s2 + 0.13) * (
        1 - cdp * (2 * b / math.pi) ** 2)
    return l1 + l2


for ps in (PS, PS_FWD):
    print("ti=%r ts=%r ps=%r m=%r n=%r" % (TI, TS, ps, M, N))
    for k, val in bk_family(TI, TS, ps, M, N).items():
        print("  %s %.17g" % (k, val))
print("ON rho=0.4127 sigma=0.5119:")
for ps in (PS, PS_FWD):
    print("  ps=%r %.17g" % (ps, oren_nayar(TI, TS, ps, 0.4127, 0.5119)))
print("  swapped ti<->ts ps=%r %.17g" % (PS, oren_nayar(TS, TI, PS, 0.4127, 0.5119)))
nd = 1.3917
print("LFTG n_d=%r %.17g" % (nd, (nd + 2) / (2 * math.pi)
                             * (math.cos(TI) * math.cos(TS)) ** nd))
for a in (0.7313, 0.1234, 1.3391, 1.5607):
    print("fresnel a=%r n=1.7 %.17g  r=1/1.7 %.17g" % (
        a, fresnel_textbook(a, 1.7), fresnel_textbook(a, 1 / 1.7)))


def precise_transmittance(a, r, digits=50):
    """1 - f(a, r) by the textbook form in 50-digit decimal arithmetic, at the
    exact binary value of the double a (for near-grazing references)."""
    from decimal import Decimal as D, getcontext
    getcontext().prec = digits
    x = D(a)

    def series(t, k):
        s, k0 = D(0), k
        while abs(t) > D(10) ** -(digits - 5):
            s += t
            t = -t * x * x / ((k0 + 1) * (k0 + 2))
            k0 += 2
        return s
    s, c, r = series(x, 1), series(D(1), 0), D(r)
    st = s / r
    ct = (1 - st * st).sqrt()
    rs = (c - r * ct) / (c + r * ct)
    rp = (ct - r * c) / (ct + r * c)
    return 1 - (rs * rs + rp * rp) / 2


if __name__ == "__main__":
    import sys
    if "--precise" in sys.argv:
        print("T(1.5607, 1.7) =", precise_transmittance(1.5607, 1.7))
