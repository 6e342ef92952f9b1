/* tests/test_interval_gen.h — random interval inputs and __float128 helpers shared
   by the interval.h tests. Input classes (issue 3): ±0, denormals,
   magnitudes 1e-300..1e300, infinite endpoints, zero-width intervals and
   intervals straddling 0; points are sampled inside, endpoints included. */
#ifndef FILIGREE_INTERVAL_GEN_H
#define FILIGREE_INTERVAL_GEN_H

#include <quadmath.h>
#include <float.h>
#include "test.h"
#include "interval.h"

typedef __float128 q_t;

/* A random finite double from one of the magnitude classes. */
static double ig_value(t_rng_t *r)
{
    unsigned k = (unsigned)(t_rng_u64(r) % 10);
    double s = (t_rng_u64(r) & 1) ? -1.0 : 1.0;
    switch (k) {
    case 0: return s * 0.0;
    case 1: return s * ldexp((double)(t_rng_u64(r) >> 12), -1074); /* denormal */
    case 2: case 3: return s * pow(10.0, t_rng_range(r, -300, 300)); /* 1e-300..1e300 */
    case 4: return s * (double)(t_rng_u64(r) % 8);                   /* small integers */
    case 5: return s * pow(10.0, t_rng_range(r, -3, 3));
    case 6: return s * t_rng_range(r, 0, 20);                        /* trig range */
    case 7: return s * pow(10.0, t_rng_range(r, 14, 20));           /* huge trig args */
    default: return t_rng_range(r, -4, 4);
    }
}

/* A random interval from the input classes (never empty). */
static iv_t ig_interval(t_rng_t *r)
{
    unsigned k = (unsigned)(t_rng_u64(r) % 8);
    double a = ig_value(r), b = ig_value(r), t;
    switch (k) {
    case 0: return iv_make(a, a);                                  /* zero width */
    case 1: a = -fabs(a); b = fabs(b); break;                      /* straddles 0 */
    case 2: a = -HUGE_VAL; break;                                   /* infinite ends */
    case 3: b = HUGE_VAL; break;
    case 4: if (t_rng_u64(r) % 4 == 0) return iv_entire(); b = a + fabs(a) * 1e-12 * t_rng_unit(r); break;
    case 5: b = a + t_rng_range(r, 0, 3); break;                   /* narrow */
    default: break;
    }
    if (a > b) { t = a; a = b; b = t; }
    if (a == HUGE_VAL || b == -HUGE_VAL || a != a || b != b) return iv_make(0, 1);
    return iv_make(a, b);
}

/* A random real point in x (finite), endpoints included. x non-empty. */
static double ig_point(t_rng_t *r, iv_t x)
{
    unsigned k = (unsigned)(t_rng_u64(r) % 6);
    double lo = x.lo, hi = x.hi, p;
    if (k == 0 && lo > -HUGE_VAL) return lo;
    if (k == 1 && hi < HUGE_VAL) return hi;
    if (lo == -HUGE_VAL && hi == HUGE_VAL) return ig_value(r);
    if (lo == -HUGE_VAL) return hi - fabs(ig_value(r));
    if (hi == HUGE_VAL) return lo + fabs(ig_value(r));
    p = lo + (hi - lo) * t_rng_unit(r);
    if (!(p == p) || p - p != 0) p = 0.5 * lo + 0.5 * hi;
    if (p < lo) p = lo;
    if (p > hi) p = hi;
    return p;
}

/* An infinite or out-of-double-range quad result never breaks containment
   checks done in quad: compare there. */
static int ig_in(iv_t x, q_t v)
{
    if (v != v) return 1; /* the reference is undefined: nothing to check */
    return (q_t)x.lo <= v && v <= (q_t)x.hi;
}

/* Round a quad value down / up to a double (exact directed rounding). */
static double ig_rd(q_t v)
{
    double d = (double)v;
    if ((q_t)d > v) d = nextafter(d, -HUGE_VAL);
    return d;
}
static double ig_ru(q_t v)
{
    double d = (double)v;
    if ((q_t)d < v) d = nextafter(d, HUGE_VAL);
    return d;
}
/* Number of doubles strictly between a and b (a <= b), saturated. */
static long long ig_ulps(double a, double b)
{
    long long n = 0;
    while (a < b && n < 1000) { a = nextafter(a, HUGE_VAL); n++; }
    return n;
}

#endif
