/* degrees.c: angles in degrees as decimal text <-> radians, bit for bit
 * (the tidy CSV reader and writer, README "Tidy CSV"; SPEC §1.5).
 *
 * [1] T. J. Dekker, "A floating-point technique for extending the
 *     available precision", Numer. Math. 18, 1971 (double-double sums and
 *     products; the product's error term by fma, C11 7.12.13.1).
 *
 * Why not rad = deg * (pi/180) on a double deg: the doubles deg of one
 * binade are 32 or 64 times coarser than the radians they map to, so on
 * the coarse side consecutive degrees land 64 * pi/180 = 1.12 units in the
 * last place apart and about one radian value in nine is the image of no
 * double at all -- a file could not hold it in degrees. Here the decimal
 * text is read into a double-double (its first 30 significant digits,
 * about 1e-30 relative), multiplied by pi/180 in double-double and
 * rounded once. That is within 1e-30 of the exact product, so every
 * radian value r has decimals that read back into it: those within the
 * middle of r's rounding interval, whose relative width is at least 2^-53
 * (17 significant digits always reach one). The writer tries 1, 2, ...
 * significant digits of r * 180/pi and keeps the first decimal that this
 * reader maps back onto r. Zero, and magnitudes below 1e-200 or above
 * 1e200 (far outside any angle range; the double-double powers of ten
 * would underflow or overflow there), are multiplied in plain double. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* pi/180 and 180/pi as double-doubles: the doubles nearest them and the
 * double nearest the remainder (60-digit decimal arithmetic). */
static const double rad_per_deg[2] = {0.017453292519943295,
                                      2.9486522708701687e-19};
static const double deg_per_rad[2] = {57.29577951308232,
                                      -1.9878495670576283e-15};

/* Magnitudes handled in plain double arithmetic (see above). */
#define PLAIN_MIN 1e-200
#define PLAIN_MAX 1e200

/* Significant digits read from the text, in two 15-digit chunks (each an
 * integer below 2^53, so exact in a double). */
#define CHUNK 15
#define DIGITS (2 * CHUNK)

/* Most significant digits the writer tries (17 always suffice). */
#define MAX_DIGITS 18

typedef struct {
    double hi;
    double lo;
} dd;

/* ==== double-double arithmetic [1] ==== */

static dd quick_two_sum(double a, double b) /* |a| >= |b| */
{
    dd r;
    r.hi = a + b;
    r.lo = b - (r.hi - a);
    return r;
}

static dd two_sum(double a, double b)
{
    dd r;
    double bb;
    r.hi = a + b;
    bb = r.hi - a;
    r.lo = (a - (r.hi - bb)) + (b - bb);
    return r;
}

static dd dd_mul(dd x, dd y)
{
    double p = x.hi * y.hi;
    double e = fma(x.hi, y.hi, -p); /* exact error of p */
    e += (x.hi * y.lo) + (x.lo * y.hi);
    return quick_two_sum(p, e);
}

static dd dd_mul_d(dd x, double d)
{
    double p = x.hi * d;
    double e = fma(x.hi, d, -p);
    e += x.lo * d;
    return quick_two_sum(p, e);
}

static dd dd_sub(dd x, dd y)
{
    dd s = two_sum(x.hi, -y.hi);
    s.lo += x.lo - y.lo;
    return quick_two_sum(s.hi, s.lo);
}

static dd dd_div(dd x, dd y)
{
    double q1 = x.hi / y.hi;
    dd r = dd_sub(x, dd_mul_d(y, q1));
    double q2 = r.hi / y.hi;
    dd q;
    r = dd_sub(r, dd_mul_d(y, q2));
    q = quick_two_sum(q1, q2);
    return two_sum(q.hi, q.lo + (r.hi / y.hi));
}

/* The powers of ten that are exact doubles. */
static const double p10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,
                               1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17,
                               1e18, 1e19, 1e20, 1e21, 1e22};

/* x * 10^e: by one exact power of ten when |e| <= 22, else by a power
 * built from multiplications by 10 (each exact to double-double
 * precision; |e| stays below 260 for the magnitudes handled here). */
static dd dd_scale10(dd x, int e)
{
    dd p = {1.0, 0.0};
    int k;
    int a = e < 0 ? -e : e;
    if (a <= 22) {
        p.hi = p10[a];
    } else {
        for (k = 0; k < a; k++) {
            p = dd_mul_d(p, 10.0);
        }
    }
    return e < 0 ? dd_div(x, p) : dd_mul(x, p);
}

/* ==== reading ==== */

/* The value of a decimal text already checked by bf__parse_double, from
 * its first DIGITS significant digits (later ones are dropped). */
static dd decimal_value(const char *s)
{
    double chunk[2] = {0.0, 0.0};
    int nsig = 0;
    int exp10 = 0;
    int after_point = 0;
    int neg = 0;
    dd v;
    if (*s == '+' || *s == '-') {
        neg = *s == '-';
        s++;
    }
    for (; *s != '\0' && *s != 'e' && *s != 'E'; s++) {
        if (*s == '.') {
            after_point = 1;
            continue;
        }
        if (nsig == 0 && *s == '0') {
            exp10 -= after_point; /* a leading zero */
            continue;
        }
        if (nsig < DIGITS) {
            chunk[nsig / CHUNK] = 10.0 * chunk[nsig / CHUNK] + (*s - '0');
            nsig++;
            exp10 -= after_point;
        } else {
            exp10 += !after_point; /* a dropped digit before the point */
        }
    }
    if (*s == 'e' || *s == 'E') {
        exp10 += (int)strtol(s + 1, NULL, 10); /* bounded: |v| <= 1e200 */
    }
    if (nsig > CHUNK) {
        /* chunk[0] * 10^(nsig - CHUNK) + chunk[1], exactly */
        dd a = dd_mul_d((dd){chunk[0], 0.0}, p10[nsig - CHUNK]);
        dd b = two_sum(a.hi, chunk[1]);
        v = quick_two_sum(b.hi, b.lo + a.lo);
    } else {
        v.hi = chunk[0];
        v.lo = 0.0;
    }
    v = dd_scale10(v, exp10);
    if (neg) {
        v.hi = -v.hi;
        v.lo = -v.lo;
    }
    return v;
}

int bf__parse_degrees(const char *text, double *rad)
{
    double v;
    int st = bf__parse_double(text, &v);
    dd r;
    if (st != BF__NUM_OK) {
        return st;
    }
    if (v == 0.0 || fabs(v) < PLAIN_MIN || fabs(v) > PLAIN_MAX) {
        *rad = v * rad_per_deg[0];
        return BF__NUM_OK;
    }
    r = dd_mul(decimal_value(text),
               (dd){rad_per_deg[0], rad_per_deg[1]});
    *rad = r.hi + r.lo; /* rounded once */
    return BF__NUM_OK;
}

/* ==== writing ==== */

/* Writes sign, the digits of m and exponent e (value m * 10^e, m without
 * trailing zeros) as %.17g would: plain from 1e-4 up to 1e17, else
 * d.ddde[+-]XX. */
static void write_decimal(int neg, uint64_t m, int e, char *buf)
{
    char dig[24];
    int nd = snprintf(dig, sizeof dig, "%llu", (unsigned long long)m);
    int lead = nd - 1 + e; /* exponent of the leading digit */
    char *p = buf;
    if (neg) {
        *p++ = '-';
    }
    if (lead >= -4 && lead < 17) {
        if (e >= 0) {
            memcpy(p, dig, (size_t)nd);
            p += nd;
            memset(p, '0', (size_t)e);
            p += e;
        } else if (lead >= 0) {
            memcpy(p, dig, (size_t)(lead + 1));
            p += lead + 1;
            *p++ = '.';
            memcpy(p, dig + lead + 1, (size_t)(nd - lead - 1));
            p += nd - lead - 1;
        } else {
            *p++ = '0';
            *p++ = '.';
            memset(p, '0', (size_t)(-lead - 1));
            p += -lead - 1;
            memcpy(p, dig, (size_t)nd);
            p += nd;
        }
        *p = '\0';
        return;
    }
    *p++ = dig[0];
    if (nd > 1) {
        *p++ = '.';
        memcpy(p, dig + 1, (size_t)(nd - 1));
        p += nd - 1;
    }
    *p++ = 'e';
    *p++ = lead < 0 ? '-' : '+';
    lead = lead < 0 ? -lead : lead; /* below 310 */
    if (lead >= 100) {
        *p++ = (char)('0' + lead / 100);
    }
    *p++ = (char)('0' + (lead / 10) % 10);
    *p++ = (char)('0' + lead % 10);
    *p = '\0';
}

/* 1 when the decimal m * 10^e (sign neg) reads back into rad; it is then
 * in buf. */
static int try_decimal(int neg, uint64_t m, int e, double rad, char *buf)
{
    double back;
    if (m == 0) {
        return 0;
    }
    while (m % 10 == 0) {
        m /= 10;
        e++;
    }
    write_decimal(neg, m, e, buf);
    return bf__parse_degrees(buf, &back) == BF__NUM_OK &&
           memcmp(&back, &rad, sizeof back) == 0;
}

/* 1 when the decimal of p significant digits nearest deg (|rad| in
 * degrees, leading digit at 10^lead) reads back into rad; it is then in
 * buf. */
static int try_digits(int neg, dd deg, int lead, int p, double rad, char *buf)
{
    int e = lead - (p - 1);
    dd s = dd_scale10(deg, -e);
    double fh = floor(s.hi);
    double frac = (s.hi - fh) + s.lo;
    int64_t m = (int64_t)fh + (int64_t)floor(frac + 0.5);
    return m > 0 && try_decimal(neg, (uint64_t)m, e, rad, buf);
}

int bf__format_degrees(double rad, char *buf)
{
    dd deg;
    int neg;
    int lead;
    int lo;
    int hi;
    int p;
    if (!isfinite(rad)) {
        buf[0] = '\0';
        return BF_EINVAL;
    }
    deg = dd_mul((dd){rad, 0.0}, (dd){deg_per_rad[0], deg_per_rad[1]});
    if (rad == 0.0 || fabs(deg.hi) < PLAIN_MIN || fabs(deg.hi) > PLAIN_MAX) {
        /* plain double arithmetic, as the reader does there */
        for (p = 1; p <= 17; p++) {
            double back;
            snprintf(buf, BF__DEGREES_MAX, "%.*g", p, rad / rad_per_deg[0]);
            if (bf__parse_degrees(buf, &back) == BF__NUM_OK &&
                memcmp(&back, &rad, sizeof back) == 0) {
                return BF_OK;
            }
        }
        return BF_EINVAL; /* no decimal is read into rad there */
    }
    neg = deg.hi < 0.0;
    if (neg) {
        deg.hi = -deg.hi;
        deg.lo = -deg.lo;
    }
    lead = (int)floor(log10(deg.hi));
    /* 17 digits reach rad: its decimals form an interval centred on deg
     * of relative half-width at least 2^-54, and 17-digit decimals lie
     * less than 5e-17 relative apart from their nearest. Only at a power
     * of two, whose lower half-interval is half as wide, may it take 18. */
    for (hi = 17; hi <= MAX_DIGITS; hi++) {
        if (try_digits(neg, deg, lead, hi, rad, buf)) {
            break;
        }
    }
    if (hi > MAX_DIGITS) {
        return BF_EINVAL; /* not reached (see the tests) */
    }
    /* If p digits reach rad, so do p + 1 (the nearest (p+1)-digit decimal
     * is no farther from the interval's centre deg than the p-digit one),
     * so the fewest is found by search: most angles need 16 or 17 digits,
     * so step down twice, then bisect. */
    for (p = hi - 1, lo = 0; p >= 1 && lo < 2; p--, lo++) {
        if (!try_digits(neg, deg, lead, p, rad, buf)) {
            break;
        }
        hi = p;
    }
    if (p >= 1 && lo == 2) { /* hi works; bisect [1, hi] */
        lo = 1;
        while (lo < hi) {
            int mid = (lo + hi) / 2;
            if (try_digits(neg, deg, lead, mid, rad, buf)) {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
    }
    if (!try_digits(neg, deg, lead, hi, rad, buf)) {
        return BF_EINVAL; /* not reached: hi digits were found */
    }
    return BF_OK;
}
