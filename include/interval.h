/* interval.h — rigorous interval and affine arithmetic (part of filigree)

   Interval enclosures that are guaranteed in the default rounding mode, and
   affine forms for tighter ranges along rays.

   USAGE
     In exactly one C or C++ file:
         #define IV_IMPLEMENTATION
         #include "interval.h"
     Everywhere else just #include "interval.h".
   OPTIONS (define before including)
     IV_IMPLEMENTATION  emit the implementation in this translation unit
     IV_STATIC          make every function static (private to this file)
     IV_DEF             linkage of public functions (default extern)
     IV_ASSERT(c)       internal-invariant check (default assert)
     IV_MALLOC(sz,ctx) / IV_FREE(p,ctx)   allocator hooks (default malloc/free)
     IV_NO_AFFINE        leave out affine arithmetic
     IV_FAST             round-to-nearest endpoints: faster, NOT rigorous
     IV_LIBM_ULPS        the error bound (in ulps) trusted for the libm
                         functions exp log sin cos tan atan pow; default 1
   Define IV_FAST and IV_LIBM_ULPS the same way in every translation unit.

   THE GUARANTEE
     For every operation f and all inputs, the returned interval contains
     f(x) for every real x in the input that lies in f's domain. This holds
     in the default rounding mode (round to nearest), with any optimisation
     flags except -ffast-math (in particular with -ffp-contract=fast and
     -march=native), without fesetround and without -frounding-math.

   THE METHOD
     Every endpoint is first computed in round-to-nearest, so it lies within
     half an ulp of the exact value (IEEE 754: + - * / sqrt are correctly
     rounded). It is then stepped one floating-point number outward (the
     next double below for a lower endpoint, above for an upper one) by
     integer arithmetic on its bit pattern. The step is exact, needs no
     rounding mode, and no compiler contraction can change it. Hence each
     endpoint of + - * / sqrt sqr pow_n is either the correctly rounded
     outward endpoint or one ulp outside it (pow_n uses an error-bounded
     double-double evaluation, see iv_pow_n). The libm functions are trusted
     to IV_LIBM_ULPS ulps and stepped 2*IV_LIBM_ULPS doubles outward, which
     is enough whatever side the libm error falls on (docs/interval.md).

   CONVENTIONS
     See docs/conventions.md: results are iv_result_t codes with IV_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe. Intervals are closed sets of reals;
     an infinite endpoint means "unbounded". The empty set is represented by
     NaN endpoints (iv_empty()); every operation returns the empty interval
     when an input is empty. Bad input (a NaN endpoint, lo > hi, lo = +inf or
     hi = -inf) is turned into the empty interval by iv_make, never into a
     silently wrong enclosure.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_IV_H
#define FILIGREE_IV_H

#include <stddef.h>
#include <string.h>
#include <stdint.h>
#include <math.h>
#ifndef IV_DEF
#  ifdef IV_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define IV_DEF static __attribute__((unused))
#    else
#      define IV_DEF static
#    endif
#  else
#    define IV_DEF extern
#  endif
#endif
#ifndef IV_LIBM_ULPS
#  define IV_LIBM_ULPS 1
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. IV_OK is 0; iv_result_string() names each. */
typedef enum iv_result_t {
    IV_OK = 0,
    IV_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    IV_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    IV_RESULT_COUNT_
} iv_result_t;

/* A human-readable name for a result code; never NULL. */
IV_DEF const char *iv_result_string(iv_result_t r);

/* A closed interval [lo, hi] of reals. Empty: lo and hi are NaN. */
typedef struct iv_t {
    double lo, hi;
} iv_t;

/* ------------------------------------------------------------------------ */
/* Private helpers (double underscore: not part of the API).                */
/* ------------------------------------------------------------------------ */

static inline iv_t iv__raw(double lo, double hi)
{
    iv_t r;
    r.lo = lo;
    r.hi = hi;
    return r;
}

/* The next double below x (x may be +inf: gives DBL_MAX; -inf and NaN stay).
   Bit arithmetic, so it is exact in any rounding mode and immune to
   contraction. Magnitude grows by one step for negative x. */
static inline double iv__next_down(double x)
{
    uint64_t u;
    if (x == 0) return -4.9406564584124654e-324; /* -denormal min */
    if (!(x > -HUGE_VAL)) return x;             /* -inf or NaN */
    memcpy(&u, &x, sizeof u);
    if (x > 0) u -= 1; else u += 1;
    memcpy(&x, &u, sizeof u);
    return x;
}
static inline double iv__next_up(double x) { return -iv__next_down(-x); }

/* Outward rounding of a round-to-nearest endpoint (identity under IV_FAST). */
#ifdef IV_FAST
static inline double iv__down(double x) { return x; }
static inline double iv__up(double x) { return x; }
#else
static inline double iv__down(double x) { return iv__next_down(x); }
static inline double iv__up(double x) { return iv__next_up(x); }
#endif
static inline double iv__min(double a, double b) { return b < a ? b : a; }
static inline double iv__max(double a, double b) { return b > a ? b : a; }
/* 0 * inf inside an interval product means "exact zero times an unbounded
   real", whose value is 0: map that NaN to 0. */
static inline double iv__mul0(double a, double b)
{
    double p = a * b;
    return p == p ? p : 0.0;
}

/* ------------------------------------------------------------------------ */
/* Construction and queries                                                 */
/* ------------------------------------------------------------------------ */

/* The empty set (both endpoints NaN). */
static inline iv_t iv_empty(void) { return iv__raw(NAN, NAN); }
/* All reals, [-inf, +inf]. */
static inline iv_t iv_entire(void) { return iv__raw(-HUGE_VAL, HUGE_VAL); }
/* 1 when x is empty (any NaN endpoint or lo > hi), else 0. */
static inline int iv_is_empty(iv_t x) { return !(x.lo <= x.hi); }
/* [lo, hi]. Returns the empty interval for bad input: a NaN endpoint,
   lo > hi, lo = +inf or hi = -inf (no real lies in such a set). */
static inline iv_t iv_make(double lo, double hi)
{
    if (!(lo <= hi) || lo == HUGE_VAL || hi == -HUGE_VAL) return iv_empty();
    return iv__raw(lo, hi);
}
/* [x, x]; empty for NaN or infinite x (not a real number). */
static inline iv_t iv_point(double x) { return iv_make(x, x); }
/* 1 when v lies in x (0 for NaN v or empty x). */
static inline int iv_contains(iv_t x, double v) { return x.lo <= v && v <= x.hi; }
/* hi - lo rounded upward (an upper bound of the width); NaN when empty. */
static inline double iv_width(iv_t x)
{
    double d = x.hi - x.lo; /* 0 exactly when hi == lo (gradual underflow) */
    if (iv_is_empty(x)) return NAN;
    return d == 0 ? 0.0 : iv__up(d);
}
/* A point inside x near its centre: 0 for the entire line, -DBL_MAX or
   +DBL_MAX for a half-line; NaN when empty. */
static inline double iv_mid(iv_t x)
{
    double m;
    if (iv_is_empty(x)) return NAN;
    if (x.lo == -HUGE_VAL) return x.hi == HUGE_VAL ? 0.0 : -1.7976931348623157e308;
    if (x.hi == HUGE_VAL) return 1.7976931348623157e308;
    m = 0.5 * x.lo + 0.5 * x.hi; /* no overflow; rounding may leave [lo,hi] */
    return iv__min(iv__max(m, x.lo), x.hi);
}
/* The smallest interval containing both (empty inputs are ignored). */
static inline iv_t iv_hull(iv_t a, iv_t b)
{
    if (iv_is_empty(a)) return b;
    if (iv_is_empty(b)) return a;
    return iv__raw(iv__min(a.lo, b.lo), iv__max(a.hi, b.hi));
}
/* a ∩ b; empty when they do not meet. */
static inline iv_t iv_intersect(iv_t a, iv_t b)
{
    double lo = iv__max(a.lo, b.lo), hi = iv__min(a.hi, b.hi);
    if (iv_is_empty(a) || iv_is_empty(b) || lo > hi) return iv_empty();
    return iv__raw(lo, hi);
}
/* Bisection at iv_mid(x): *left = [lo, m], *right = [m, hi]. Both empty
   when x is empty. */
static inline void iv_split(iv_t x, iv_t *left, iv_t *right)
{
    double m = iv_mid(x);
    if (iv_is_empty(x)) { *left = *right = iv_empty(); return; }
    *left = iv__raw(x.lo, m);
    *right = iv__raw(m, x.hi);
}

/* ------------------------------------------------------------------------ */
/* Arithmetic. Endpoints: correctly rounded outward or one ulp beyond.      */
/* ------------------------------------------------------------------------ */

static inline iv_t iv_neg(iv_t x) { return iv__raw(-x.hi, -x.lo); }
static inline iv_t iv_add(iv_t a, iv_t b)
{
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    return iv__raw(iv__down(a.lo + b.lo), iv__up(a.hi + b.hi));
}
static inline iv_t iv_sub(iv_t a, iv_t b)
{
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    return iv__raw(iv__down(a.lo - b.hi), iv__up(a.hi - b.lo));
}
/* x + d for a scalar d; empty for NaN or infinite d. */
static inline iv_t iv_add_d(iv_t x, double d) { return iv_add(x, iv_point(d)); }
static inline iv_t iv_sub_d(iv_t x, double d) { return iv_add(x, iv_point(-d)); }
static inline iv_t iv_mul(iv_t a, iv_t b)
{
    double p1, p2, p3, p4;
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    p1 = iv__mul0(a.lo, b.lo);
    p2 = iv__mul0(a.lo, b.hi);
    p3 = iv__mul0(a.hi, b.lo);
    p4 = iv__mul0(a.hi, b.hi);
    return iv__raw(iv__down(iv__min(iv__min(p1, p2), iv__min(p3, p4))),
                   iv__up(iv__max(iv__max(p1, p2), iv__max(p3, p4))));
}
/* x * d for a scalar d (two products instead of four); empty for NaN or
   infinite d. */
static inline iv_t iv_mul_d(iv_t x, double d)
{
    double p, q;
    if (iv_is_empty(x) || !(d - d == 0)) return iv_empty();
    p = iv__mul0(x.lo, d);
    q = iv__mul0(x.hi, d);
    return d >= 0 ? iv__raw(iv__down(p), iv__up(q)) : iv__raw(iv__down(q), iv__up(p));
}
/* x^2 >= 0 (tighter than x*x when x straddles 0: no dependency). */
static inline iv_t iv_sqr(iv_t x)
{
    double a, b;
    if (iv_is_empty(x)) return iv_empty();
    a = x.lo * x.lo;
    b = x.hi * x.hi;
    if (x.lo >= 0) return iv__raw(iv__max(0.0, iv__down(a)), iv__up(b));
    if (x.hi <= 0) return iv__raw(iv__max(0.0, iv__down(b)), iv__up(a));
    return iv__raw(0.0, iv__up(iv__max(a, b)));
}
/* a / b for b > 0 strictly (b.hi may be +inf): no 0/0 or inf/inf occurs. */
static inline iv_t iv__div_pos(iv_t a, iv_t b)
{
    /* A nonnegative numerator endpoint gives a nonnegative quotient, so a
       lower bound below 0 (from stepping an underflowed or exact 0) is
       pointless: clamp it, and symmetrically for the upper endpoint. */
    double lo = a.lo >= 0 ? iv__max(0.0, iv__down(a.lo / b.hi)) : iv__down(a.lo / b.lo);
    double hi = a.hi <= 0 ? iv__min(0.0, iv__up(a.hi / b.hi)) : iv__up(a.hi / b.lo);
    return iv__raw(lo, hi);
}
/* Tightest enclosure of a / b over b's nonzero points. Returns the number of
   pieces written to out[0..1] (sorted, disjoint): 0 when the quotient is
   empty (a empty, b empty or b = [0,0]), 1 normally, 2 when 0 is interior to
   b and not in a, e.g. [1,2]/[-1,1] = [-inf,-1] and [1,inf]. */
IV_DEF int iv_div_ext(iv_t a, iv_t b, iv_t out[2]);
/* a / b: the hull of iv_div_ext (entire when 0 is interior to b and a is
   not [0,0]); empty when b = [0,0]. */
static inline iv_t iv_div(iv_t a, iv_t b)
{
    iv_t piece[2];
    int n;
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    if (b.lo > 0) return iv__div_pos(a, b);
    if (b.hi < 0) return iv__div_pos(iv_neg(a), iv_neg(b));
    n = iv_div_ext(a, b, piece);
    if (n == 0) return iv_empty();
    return n == 1 ? piece[0] : iv_hull(piece[0], piece[1]);
}
static inline iv_t iv_div_d(iv_t x, double d) { return iv_div(x, iv_point(d)); }
/* 1 / x (see iv_div for x containing 0). */
static inline iv_t iv_recip(iv_t x) { return iv_div(iv__raw(1.0, 1.0), x); }
/* sqrt over x ∩ [0, inf]: iv_sqrt([-1,4]) = [0,2]; empty when x < 0. */
static inline iv_t iv_sqrt(iv_t x)
{
    double lo;
    if (iv_is_empty(x) || x.hi < 0) return iv_empty();
    lo = x.lo > 0 ? iv__down(sqrt(x.lo)) : 0.0;
    return iv__raw(iv__max(lo, 0.0), x.hi == 0 ? 0.0 : iv__up(sqrt(x.hi)));
}
/* |x| (exact). */
static inline iv_t iv_abs(iv_t x)
{
    if (x.lo >= 0) return x;
    if (x.hi <= 0) return iv_neg(x);
    if (iv_is_empty(x)) return iv_empty();
    return iv__raw(0.0, iv__max(-x.lo, x.hi));
}
/* Elementwise min and max (exact). */
static inline iv_t iv_min(iv_t a, iv_t b)
{
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    return iv__raw(iv__min(a.lo, b.lo), iv__min(a.hi, b.hi));
}
static inline iv_t iv_max(iv_t a, iv_t b)
{
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    return iv__raw(iv__max(a.lo, b.lo), iv__max(a.hi, b.hi));
}

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_IV_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef IV_IMPLEMENTATION
#ifndef FILIGREE_IV_IMPLEMENTATION_DONE
#define FILIGREE_IV_IMPLEMENTATION_DONE

#ifndef IV_ASSERT
#  include <assert.h>
#  define IV_ASSERT(c) assert(c)
#endif
#if defined(IV_MALLOC) != defined(IV_FREE)
#  error "define both IV_MALLOC and IV_FREE, or neither"
#endif
#ifndef IV_MALLOC
#  include <stdlib.h>
#  define IV_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define IV_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

IV_DEF const char *iv_result_string(iv_result_t r)
{
    switch (r) {
    case IV_OK: return "ok";
    case IV_ERR_INVALID_ARG: return "invalid argument";
    case IV_ERR_OUT_OF_MEMORY: return "out of memory";
    case IV_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* a / (0, h] for h > 0: as the divisor tends to 0+ the quotient of a
   positive (negative) numerator runs to +inf (-inf); a zero numerator
   stays 0. */
static iv_t iv__div_zero_pos(iv_t a, double h)
{
    double lo = a.lo >= 0 ? iv__max(0.0, iv__down(a.lo / h)) : -HUGE_VAL;
    double hi = a.hi <= 0 ? iv__min(0.0, iv__up(a.hi / h)) : HUGE_VAL;
    return iv__raw(lo, hi);
}

IV_DEF int iv_div_ext(iv_t a, iv_t b, iv_t out[2])
{
    iv_t pos, neg;
    int has_pos, has_neg;
    if (!out || iv_is_empty(a) || iv_is_empty(b)) return 0;
    if (b.lo > 0) { out[0] = iv__div_pos(a, b); return 1; }
    if (b.hi < 0) { out[0] = iv__div_pos(iv_neg(a), iv_neg(b)); return 1; }
    has_pos = b.hi > 0;
    has_neg = b.lo < 0;
    if (!has_pos && !has_neg) return 0; /* b = [0, 0]: no quotient exists */
    pos = has_pos ? iv__div_zero_pos(a, b.hi) : iv_empty();
    neg = has_neg ? iv__div_zero_pos(iv_neg(a), -b.lo) : iv_empty();
    if (!has_neg) { out[0] = pos; return 1; }
    if (!has_pos) { out[0] = neg; return 1; }
    if (neg.lo > pos.lo) { iv_t t = neg; neg = pos; pos = t; }
    if (neg.hi >= pos.lo) { out[0] = iv_hull(neg, pos); return 1; }
    out[0] = neg;
    out[1] = pos;
    return 2;
}

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_IV_IMPLEMENTATION_DONE */
#endif /* IV_IMPLEMENTATION */

/*
MIT License

Copyright (c) 2026 the filigree authors

Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
*/
