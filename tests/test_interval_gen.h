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

/* Guaranteed bound for the libm-based functions: libm's value y is within
   N = IV_LIBM_ULPS ulps of f (ulps of f's binade), so up to 2N doubles
   below f where the spacing halves below a power of two; the header steps
   it 2N doubles outward, so an end lies at most 4N doubles beyond the
   correctly rounded one (at N = 1 the same 4 as the 3N + 1 this gave
   until 2026-12-06, which was short for N >= 2: found by review). */
#define LIBM_BOUND (4 * IV_LIBM_ULPS)
/* sin, cos, tan at |x| >= 2^20, reduced by the header itself: one more
   ulp of error (the reduced argument's correction, tan's division) and
   two more steps: 4 (N + 1) */
#define LIBM_REDUCED_BOUND (4 * (IV_LIBM_ULPS + 1))

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

/* The pair path (SSE + FMA, the default where available) and the scalar
   path give the same intervals (equal endpoints, or both NaN), on random
   inputs of every class and on all combinations of special endpoints; the
   scalar path is what IV_NO_SIMD and other targets use. Without the pair
   path this checks nothing and says so. */
static int ig_same(iv_t a, iv_t b)
{
    return (a.lo == b.lo || (a.lo != a.lo && b.lo != b.lo)) && (a.hi == b.hi || (a.hi != a.hi && b.hi != b.hi));
}
/* the same, and equal values also in the sign of a zero (both NaN is a
   match: NaN payloads are not specified) */
static int ig_same_bits(iv_t a, iv_t b)
{
    return ig_same(a, b) && (a.lo != a.lo || !signbit(a.lo) == !signbit(b.lo)) && (a.hi != a.hi || !signbit(a.hi) == !signbit(b.hi));
}
static void ig_pair_matches_scalar(void)
{
#ifdef IV__PAIR
    static const double sp[] = {0.0, -0.0, 4.9406564584124654e-324, -1e-310, 2.2250738585072014e-308,
        -2.2250738585072014e-308, 1.0, -2.0, 0.5, 1.7976931348623157e308, -1.7976931348623157e308, HUGE_VAL, -HUGE_VAL};
    enum { NS = sizeof sp / sizeof sp[0] };
    t_rng_t r = {99};
    long n = t_count(1000000), i, bad = 0;
    for (i = 0; i < n + NS * NS * NS * NS; i++) {
        iv_t a, b;
        double d;
        if (i < NS * NS * NS * NS) {
            a = iv_make(sp[i % NS], sp[i / NS % NS]);
            b = iv_make(sp[i / (NS * NS) % NS], sp[i / (NS * NS * NS)]);
            if (iv_is_empty(a)) a = iv_empty();
            if (iv_is_empty(b)) b = iv_empty();
            d = sp[i % NS];
        } else {
            a = ig_interval(&r);
            b = ig_interval(&r);
            d = ig_value(&r);
        }
        if (!ig_same(iv__add2(a, b), iv__add1(a, b)) || !ig_same(iv__sub2(a, b), iv__sub1(a, b)) ||
            !ig_same(iv__mul2(a, b), iv__mul1(a, b)) || !ig_same(iv__mul_d2(a, d), iv__mul_d1(a, d)) ||
            !ig_same(iv__sqr2(a), iv__sqr1(a)) || !ig_same(iv__sqrt2(a), iv__sqrt1(a)) ||
            (b.lo > 0 && !ig_same(iv__div_pos2(a, b), iv__div_pos1(a, b))) ||
            (b.hi < 0 && !ig_same(iv__div_pos2(iv_neg(a), iv_neg(b)), iv__div_pos1(iv_neg(a), iv_neg(b))))) {
            if (bad++ < 5) T_FAIL("[%a,%a] [%a,%a] d=%a: pair %a %a %a %a %a %a / scalar %a %a %a %a %a %a", a.lo, a.hi, b.lo,
                                  b.hi, d, iv__mul2(a, b).lo, iv__mul2(a, b).hi, iv__mul_d2(a, d).lo, iv__mul_d2(a, d).hi,
                                  iv__sqr2(a).lo, iv__sqr2(a).hi, iv__mul1(a, b).lo, iv__mul1(a, b).hi,
                                  iv__mul_d1(a, d).lo, iv__mul_d1(a, d).hi, iv__sqr1(a).lo, iv__sqr1(a).hi);
        }
    }
    T_INT_EQ(bad, 0);
    fprintf(stderr, "    pair path: %ld cases identical to the scalar path\n", n + NS * NS * NS * NS);
#else
    fprintf(stderr, "    SKIPPED: no pair path in this build (no SSE4.1 + FMA, or IV_NO_SIMD)\n");
#endif
}


/* iv_add_n, iv_sub_n and iv_mul_n, and the _soa forms, give exactly the
   per-call intervals (equal endpoints, or both NaN), element by element, for every length
   0..40 (whole blocks of wide registers and every remainder), start
   offsets 0..3 (alignment), in place (out = a and out = b), and arrays
   whose blocks hold NaN lanes (empty inputs, 0 * inf, overflow), which
   send a block to the per-call code. Inputs: the random classes, and
   blocks of special endpoints. */
static void ig_arrays_match_per_call(void)
{
    static const double sp[] = {0.0, -0.0, 4.9406564584124654e-324, -1e-310, 2.2250738585072014e-308, 1.0, -2.0,
        1.7976931348623157e308, -1.7976931348623157e308, HUGE_VAL, -HUGE_VAL};
    enum { NS = sizeof sp / sizeof sp[0], M = 1024 };
    static iv_t a[M + 8], b[M + 8], got[M + 8], want[M + 8], inplace[M + 8];
    static double alo[M + 8], ahi[M + 8], blo[M + 8], bhi[M + 8], olo[M + 8], ohi[M + 8];
    t_rng_t r = {123};
    long trials = t_count(400), t, bad = 0, checked = 0;
    for (t = 0; t < trials; t++) {
        size_t n = t < 164 ? (size_t)(t % 41) : (size_t)(t_rng_u64(&r) % M), off = (size_t)(t % 4), i;
        int op = (int)(t % 3), special = t % 5 == 4;
        for (i = 0; i < n; i++) {
            iv_t *x = &a[off + i], *y = &b[off + i];
            if (special) {
                *x = iv_make(sp[t_rng_u64(&r) % NS], sp[t_rng_u64(&r) % NS]);
                *y = iv_make(sp[t_rng_u64(&r) % NS], sp[t_rng_u64(&r) % NS]);
            } else {
                *x = ig_interval(&r);
                *y = ig_interval(&r);
                if (t_rng_u64(&r) % 64 == 0) *y = iv_empty();
            }
            if (iv_is_empty(*x)) *x = iv_empty();
            if (iv_is_empty(*y)) *y = iv_empty();
            want[off + i] = op == 0 ? iv_add(*x, *y) : op == 1 ? iv_sub(*x, *y) : iv_mul(*x, *y);
        }
        if (op == 0) iv_add_n(got + off, a + off, b + off, n);
        else if (op == 1) iv_sub_n(got + off, a + off, b + off, n);
        else iv_mul_n(got + off, a + off, b + off, n);
        for (i = 0; i < n; i++, checked++)
            if (!ig_same_bits(got[off + i], want[off + i]) && bad++ < 5)
                T_FAIL("op %d n %zu element %zu: [%a,%a] [%a,%a] gives [%a,%a], per call [%a,%a]", op, n, i, a[off + i].lo,
                       a[off + i].hi, b[off + i].lo, b[off + i].hi, got[off + i].lo, got[off + i].hi, want[off + i].lo,
                       want[off + i].hi);
        /* in place: out = a (odd trials) or out = b (even) */
        memcpy(inplace + off, (t & 1) ? a + off : b + off, n * sizeof(iv_t));
        if (t & 1) {
            if (op == 0) iv_add_n(inplace + off, inplace + off, b + off, n);
            else if (op == 1) iv_sub_n(inplace + off, inplace + off, b + off, n);
            else iv_mul_n(inplace + off, inplace + off, b + off, n);
        } else {
            if (op == 0) iv_add_n(inplace + off, a + off, inplace + off, n);
            else if (op == 1) iv_sub_n(inplace + off, a + off, inplace + off, n);
            else iv_mul_n(inplace + off, a + off, inplace + off, n);
        }
        for (i = 0; i < n; i++)
            if (!ig_same_bits(inplace[off + i], want[off + i]) && bad++ < 5)
                T_FAIL("in place, op %d n %zu element %zu: [%a,%a], per call [%a,%a]", op, n, i, inplace[off + i].lo,
                       inplace[off + i].hi, want[off + i].lo, want[off + i].hi);
        /* structure of arrays, out of place (even trials) or in place in a */
        for (i = 0; i < n; i++) {
            alo[off + i] = a[off + i].lo, ahi[off + i] = a[off + i].hi;
            blo[off + i] = b[off + i].lo, bhi[off + i] = b[off + i].hi;
        }
        {
            double *ol = (t & 1) ? alo : olo, *oh = (t & 1) ? ahi : ohi;
            if (op == 0) iv_add_soa(ol + off, oh + off, alo + off, ahi + off, blo + off, bhi + off, n);
            else if (op == 1) iv_sub_soa(ol + off, oh + off, alo + off, ahi + off, blo + off, bhi + off, n);
            else iv_mul_soa(ol + off, oh + off, alo + off, ahi + off, blo + off, bhi + off, n);
            for (i = 0; i < n; i++)
                if (!ig_same_bits(iv__raw(ol[off + i], oh[off + i]), want[off + i]) && bad++ < 5)
                    T_FAIL("soa%s, op %d n %zu element %zu: [%a,%a], per call [%a,%a]", (t & 1) ? " in place" : "", op, n, i,
                           ol[off + i], oh[off + i], want[off + i].lo, want[off + i].hi);
        }
    }
    T_INT_EQ(bad, 0);
    fprintf(stderr, "    array forms (iv_t and structure of arrays): %ld elements identical to the per-call forms\n", checked);
}

#endif
