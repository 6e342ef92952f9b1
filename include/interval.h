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
     IV_NO_SIMD          keep + - * / sqrt sqr mul_d on the portable scalar
                         path where the SSE4.1 + FMA pair path would be used
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
     It assumes the environment C gives a program at start: round to
     nearest and gradual underflow. A host that turns on flush-to-zero and
     denormals-are-zero (x86 MXCSR FTZ and DAZ; Embree recommends them for
     speed) or another rounding mode loses it: a product below 2^-1022
     becomes 0 and the error terms the method relies on vanish (with FTZ
     and DAZ on, 0.5% of the property test's points fall outside their
     enclosures). Floating-point exceptions must stay masked, as C starts
     them: the method makes inf and NaN on purpose in rare cases, which
     trap where a host unmasks them (x86 MXCSR). iv_fp_env_ok() tells;
     iv_fp_env_enter() and iv_fp_env_leave() set that environment around
     interval work and restore the host's (frep.h's rigorous entry points
     do so themselves).

   THE METHOD
     Every endpoint is first computed in round-to-nearest, so it lies within
     half an ulp of the exact value (IEEE 754: + - * / sqrt are correctly
     rounded). It is then stepped exactly one double outward (the next
     double below for a lower endpoint, above for an upper one), by one
     fused multiply-add where the target has one, else by integer
     arithmetic on the bit pattern (iv__next_down). The step needs no
     rounding mode and no compiler contraction can change it. Hence each
     endpoint of + - * / sqrt sqr pow_n is either the correctly rounded
     outward endpoint or one ulp outside it (pow_n uses an error-bounded
     double-double evaluation, see iv_pow_n). One exception makes + and -
     tighter: a sum that rounds below 2^-1022 (or to 0) is exact, since both
     terms are multiples of 2^-1074 and so is their sum, and every such
     multiple below 2^-1022 is a double; it is not stepped. The libm
     functions are trusted to IV_LIBM_ULPS ulps and stepped 2*IV_LIBM_ULPS
     doubles outward, which is enough whatever side the libm error falls on
     (docs/interval.md); an end is then at most 4*IV_LIBM_ULPS doubles
     beyond the correctly rounded one. sin, cos and tan of |x| >= 2^20 are
     reduced by this header (Payne-Hanek; glibc's own reduction is off by
     thousands of ulps near multiples of pi/2 there), libm sees |r| <= pi/4
     only, and the values are stepped two doubles more (at most
     4*(IV_LIBM_ULPS + 1) beyond).

   THE PAIR PATH AND ITS STEP
     On x86 with FMA (SSE4.1 and __FMA__, e.g. -march=haswell or
     -march=native) + - * / sqrt sqr mul_d hold an interval as one SSE
     register [lo, hi] and step both ends with one instruction,
         fma([-phi, +phi], X, v),   phi = 2^-53 + 2^-105,
     where X is |v| for + - sqrt and |v| raised to at least 2^-1022 for
     * / sqr (one integer max on the high words). Proof that this is the
     next double outward, for the upper end (the lower is its mirror
     image): let v > 0 lie in [2^e, 2^(e+1)) with spacing u = 2^(e-52) and
     X in [2^e, 2^(e+1)) (X = |v| or the floor). Then phi X lies in
     (u/2, u (1 + 2^-52)), strictly between half and one and a half
     spacings, so the single rounding of v + phi X is v + u. For v < 0 the
     spacing toward zero is u as well, except at v = -2^e (e > -1022),
     where it is u/2 and phi X = (u/2)(1 + 2^-52) lies in (u/4, 3u/4): the
     result is v + u/2. For subnormal v (and zero) the spacing is 2^-1074
     on both sides; with the floor X in [2^-1022, 2^-1021), phi X lies in
     (2^-1075, 1.5 * 2^-1074), so the result is v + 2^-1074; with X = |v|,
     phi X is below 2^-1075 and v stays (exact sums and square roots,
     which are never subnormal: sqrt(2^-1074) = 2^-537). v = +inf stays;
     v = -inf (the upper end of an overflowed negative result) gives
     inf - inf = NaN. Products pick their two candidates per end by sign
     (blendv) in the negated form [-lo, hi] (Lambov 2008), take one max,
     and fmaddsub steps both ends and negates lane 0 back in the same
     instruction. Any NaN lane (empty input, 0 * inf, an overflowed end)
     sends the operation to the scalar code: a branch that is predicted,
     so not on the dependency chain (add, abs, fma: 8 cycles on Zen 4, the
     latency bound is derived in docs/interval.md). On valid intervals
     (what iv_make and the operations return) the pair path gives the
     scalar code's values exactly (tested); the sign of a zero end may
     differ ([0, 0] - [0, 0] is [0, +0] there and [0, -0] in the scalar
     code; no operation's value depends on it). IV_NO_SIMD selects the
     scalar code.

   ARRAY FORMS
     iv_add_n / iv_sub_n / iv_mul_n (iv_t arrays) and iv_add_soa /
     iv_sub_soa / iv_mul_soa (separate lo and hi arrays) do the pair
     path's steps for four to eight intervals per AVX-512 instruction (two
     to four with AVX2; the portable code in vectorisable blocks) and give
     the per-call results bit for bit; they are what reaches the
     throughput figures of docs/interval.md.

   CONVENTIONS
     See docs/conventions.md: results are iv_result_t codes with IV_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe. Intervals are closed sets of reals;
     an infinite endpoint means "unbounded". The empty set is represented by
     NaN endpoints (iv_empty()); every operation returns the empty interval
     when an input is empty. Bad input (a NaN endpoint, lo > hi, lo = +inf or
     hi = -inf) is turned into the empty interval by iv_make, never into a
     silently wrong enclosure. Operations assume valid intervals: + - * /
     sqrt sqr mul_d do not re-check a struct literal with lo > hi or one
     NaN end, and their answer to one is unspecified (it may differ
     between the pair and the scalar path: iv_add of {2, 1} and {0, 1}
     gives [2, 2]; iv_sqrt of {NaN, 4} gives [0, 2] on the pair path and
     the empty set on the scalar one). Make intervals with iv_make.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_IV_H
#define FILIGREE_IV_H

#include <limits.h>
#include <stddef.h>
#include <string.h>
#include <stdint.h>
#include <math.h>
#include <float.h>
/* The floating-point environment (iv_fp_env_ok): MXCSR on x86, the C
   rounding mode elsewhere. */
#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#  define IV__MXCSR 1
#  include <xmmintrin.h>
#else
#  include <fenv.h>
#endif
/* The pair path: both endpoints in one SSE register (x86 with FMA, e.g.
   -march=haswell or later / -march=native); else portable scalar code. */
#if !defined(IV_NO_SIMD) && defined(__FMA__) && defined(__SSE4_1__) && defined(__GNUC__)
#  define IV__PAIR 1
#  include <immintrin.h>
#endif
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

/* The floating-point environment the guarantee assumes (THE GUARANTEE
   above): round to nearest, gradual underflow. The calling thread's is
   checked and set; on x86 its MXCSR (flush-to-zero, denormals-are-zero
   and rounding bits), elsewhere its C rounding mode (fenv.h; an ARM
   flush-to-zero bit is not seen). */
typedef struct iv_fp_env_t {
    unsigned int saved; /* what iv_fp_env_leave() restores */
    int changed;        /* iv_fp_env_enter() changed the environment */
} iv_fp_env_t;
#ifdef IV__MXCSR
#  define IV__MXCSR_MODES 0xE040u /* FTZ (bit 15), rounding (13-14), DAZ (6) */
/* every exception masked (bits 7-12): the outward step makes NaN and inf
   on purpose in its rare cases (an overflowed end, 0 * inf), which trap
   where a host unmasks them (found by review, 2026-12-06: SIGFPE in
   iv_mul([1e300], [1e300]) with FE_INVALID unmasked, iv_fp_env_ok() 1) */
#  define IV__MXCSR_MASKS 0x1F80u
#endif

/* 1 when the calling thread's environment is the one the guarantee assumes. */
static inline int iv_fp_env_ok(void)
{
#ifdef IV__MXCSR
    return (_mm_getcsr() & (IV__MXCSR_MODES | IV__MXCSR_MASKS)) == IV__MXCSR_MASKS;
#elif defined(FE_TONEAREST)
    return fegetround() == FE_TONEAREST;
#else
    return 1;
#endif
}

/* Sets that environment on the calling thread (only when it differs: one
   register read otherwise) and returns what to restore. Compilers do not
   order arithmetic against these register writes (C's FENV_ACCESS, which
   gcc does not implement): put the interval work in a function of its own
   that is not inlined, as frep.h does. */
static inline iv_fp_env_t iv_fp_env_enter(void)
{
    iv_fp_env_t e;
#ifdef IV__MXCSR
    e.saved = _mm_getcsr();
    e.changed = (e.saved & (IV__MXCSR_MODES | IV__MXCSR_MASKS)) != IV__MXCSR_MASKS;
    if (e.changed) _mm_setcsr((e.saved & ~IV__MXCSR_MODES) | IV__MXCSR_MASKS);
#elif defined(FE_TONEAREST)
    int r = fegetround();
    e.saved = (unsigned int)r;
    e.changed = r != FE_TONEAREST;
    if (e.changed) fesetround(FE_TONEAREST);
#else
    e.saved = 0;
    e.changed = 0;
#endif
    return e;
}

/* Restores the environment iv_fp_env_enter() found. */
static inline void iv_fp_env_leave(iv_fp_env_t e)
{
    if (!e.changed) return;
#ifdef IV__MXCSR
    _mm_setcsr(e.saved);
#elif defined(FE_TONEAREST)
    fesetround((int)e.saved);
#endif
}

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

/* The double just below x, two proven ways; both give exactly the next
   double below for every x (+0 and -0 both go to the negative denormal,
   +inf to DBL_MAX; -inf and NaN stay), in any rounding mode, and no
   compiler contraction can change them.

   Bits: the bit pattern is mapped to an integer of the same order (a
   negative double's magnitude bits are flipped; the map is its own inverse),
   decremented, and mapped back. A logical shift keeps it vectorisable. */
static inline uint64_t iv__ordered(uint64_t u) { return u ^ ((0u - (u >> 63)) >> 1); }
static inline double iv__next_down_bits(double x)
{
    uint64_t u;
    double y, z = x == 0 ? -0.0 : x; /* -0 steps to the negative denormal */
    memcpy(&u, &z, sizeof u);
    u = iv__ordered(iv__ordered(u) - 1u);
    memcpy(&y, &u, sizeof u);
    return x > -HUGE_VAL ? y : x; /* -inf and NaN stay */
}
/* FMA (Rump, Zimmermann, Boldo, Melquiond 2009, "Computing predecessor and
   successor in rounding to nearest", with the fused form): for normal x,
   phi|x| with phi = 2^-53 + 2^-105 lies strictly between half an ulp of x
   and an ulp (times 1 + 2^-52), so fma(-phi, |x|, x) rounds to exactly the
   next double below, also when |x| is a power of two (the spacing below is
   then half as large and phi|x| is just over half of it). For subnormal x
   that term is below half the spacing 2^-1074 and x - 2^-1074 is the exact
   answer; the min picks whichever applies. Lower latency than the bit path
   and no moves between float and integer registers. */
#define IV__PHI 1.1102230246251568e-16   /* 2^-53 + 2^-105 */
#define IV__ETA 4.9406564584124654e-324  /* 2^-1074 */
static inline double iv__next_down_fma(double x)
{
    double a = x - IV__ETA;               /* the answer for subnormal x */
    double b = fma(-IV__PHI, fabs(x), x); /* for normal x; NaN for +-inf */
    double y = b < a ? b : a;              /* a when b is NaN */
    /* +inf -> DBL_MAX; NaN passes (the comparison is false): one minsd */
    return DBL_MAX < y ? DBL_MAX : y;
}
/* The fused form is used when the target has a hardware fma (with no fma
   instruction, fma() is a slow software routine). */
#if defined(FP_FAST_FMA) || defined(__FMA__)
static inline double iv__next_down(double x) { return iv__next_down_fma(x); }
#else
static inline double iv__next_down(double x) { return iv__next_down_bits(x); }
#endif
static inline double iv__next_up(double x) { return -iv__next_down(-x); }

/* Outward rounding of a round-to-nearest endpoint. Under IV_FAST none,
   but an end that overflowed inward (a lower end of +inf, an upper end of
   -inf) becomes the largest double, as in the rigorous build: a result is
   never [inf, inf], which iv_make rejects (iv_pow_n of [1e300, 1e300]
   returned the empty set; found by review, 2026-12-06). NaN stays NaN. */
#ifdef IV_FAST
static inline double iv__down(double x) { return x == HUGE_VAL ? DBL_MAX : x; }
static inline double iv__up(double x) { return x == -HUGE_VAL ? -DBL_MAX : x; }
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

/* For + and -: a sum (or difference) of two doubles that rounds into the
   subnormal range, or to 0, is exact: both terms are integer multiples of
   2^-1074, so the exact sum is one too, and below 2^-1022 every such
   multiple is a double (gradual underflow; RN is monotone and 2^-1022 is a
   double, so a rounded sum below it had an exact sum below it). Such an
   endpoint needs no step; every other one takes the usual one. */
static inline double iv__down_sum(double s) { return fabs(s) < 2.2250738585072014e-308 ? s : iv__down(s); }

#ifdef IV__PAIR
/* The pair path: an interval is one SSE register [lo, hi] (lane 0 = lo).
   Both ends are stepped outward by one fused multiply-add with the factor
   [-phi, +phi]: fma(Q, X, v) = [v0 - phi X0, v1 + phi X1], where X is
   |v| (for + - and sqrt, whose subnormal results are exact) or |v| raised
   to at least 2^-1022 (for * / sqr, whose subnormal results may be
   rounded): see iv__floor_normal. Products pick their candidates in the
   form [-lo, hi] (Lambov 2008, "Interval arithmetic using SSE-2"), where
   one max serves both ends, and fmaddsub steps and un-negates lane 0 in
   the same instruction. A result lane that is NaN (empty input, 0 * inf,
   an end that overflowed to the wrong infinity) sends the operation to
   the scalar code, kept out of line; that test is not on the dependency
   chain (a predicted branch). Values are identical to the scalar code's,
   zero ends up to their sign (tests: pair_path_matches_scalar). */
/* [lo, hi] to a vector with _mm_set_pd and back through a union (iv_t is
   two doubles without padding on every x86 ABI, checked by the array size
   below; reading the other member of a union is defined in C99 and, as a
   documented extension, by gcc and clang in C++, and the pair path needs a
   gcc-compatible compiler). Measured with gcc 12 (clang does well with
   any form): the union both ways keeps a tape's values in vector loads
   and stores, but where gcc splits a loop-carried iv_t into two scalars
   (a field is read after the loop) it writes them as two 8-byte stores and
   reloads 16 bytes, a failed store-to-load forwarding that made a
   dependent chain of adds 4.5x slower; _mm_set_pd joins such scalars in a
   register (one unpcklpd) and still compiles to one 16-byte load from
   memory. */
typedef char iv__pair_layout_check[sizeof(iv_t) == sizeof(__m128d) ? 1 : -1];
typedef union iv__pun_t { __m128d v; iv_t x; } iv__pun_t;
static inline __m128d iv__vec(iv_t x) { return _mm_set_pd(x.hi, x.lo); }
static inline iv_t iv__unvec(__m128d v)
{
    iv__pun_t u;
    u.v = v;
    return u.x;
}
static inline __m128d iv__swap(__m128d v) { return _mm_shuffle_pd(v, v, 1); }
/* xor with this negates lane 0: [lo, hi] <-> [-lo, hi] */
static inline __m128d iv__sign_lo(void) { return _mm_set_pd(0.0, -0.0); }
static inline __m128d iv__abs2(__m128d v) { return _mm_andnot_pd(_mm_set1_pd(-0.0), v); }
/* any NaN lane in a or b; with AVX-512VL a compare into a mask register
   (no move to an integer register: measured 0.4 cycles less per product
   in a dependent chain on Zen 4, where the test competes for ports) */
#if defined(__AVX512VL__)
static inline int iv__any_nan(__m128d a, __m128d b) { return _mm_cmp_pd_mask(a, b, _CMP_UNORD_Q) != 0; }
#else
static inline int iv__any_nan(__m128d a, __m128d b) { return _mm_movemask_pd(_mm_cmpunord_pd(a, b)); }
#endif
/* blendv on the sign bits of m. gcc with AVX-512VL rewrites it as a
   compare into a mask register plus a masked permute, 3 cycles longer on
   the dependency chain (measured on Zen 4); the asm keeps the blend. */
#if defined(__AVX512VL__) && !defined(__clang__)
static inline __m128d iv__blendv(__m128d a, __m128d b, __m128d m)
{
    __m128d r;
    __asm__("vblendvpd %3, %2, %1, %0" : "=x"(r) : "x"(a), "x"(b), "x"(m));
    return r;
}
#else
static inline __m128d iv__blendv(__m128d a, __m128d b, __m128d m) { return _mm_blendv_pd(a, b, m); }
#endif
/* m = |v| (sign bits clear) raised to at least 2^-1022 by a signed max on
   the high 32 bits of each lane (the low 32 bits are kept: the constant
   there is INT32_MIN). Normal |v| and NaN stay as they are; a subnormal or
   zero |v| becomes a value in [2^-1022, 2^-1021). */
static inline __m128d iv__floor_normal(__m128d m)
{
    return _mm_castsi128_pd(_mm_max_epi32(_mm_castpd_si128(m), _mm_set_epi32(0x00100000, INT32_MIN, 0x00100000, INT32_MIN)));
}
/* The step, exact for every double v (proof in the top comment):
   lane 0 goes to the next double below, lane 1 to the next above. With X
   in the binade of |v| (the floor for subnormal v), phi X lies strictly
   between half and one and a half spacings of the doubles at v on the
   outward side (a quarter and three quarters at a power of two stepped
   toward zero), so the single rounding of the fma lands on the neighbour.
   v = +-inf on the outward side stays; on the inward side it gives NaN
   (overflow: the caller's scalar path clamps it to +-DBL_MAX). */
#ifdef IV_FAST
/* [lo, hi] with an inward overflow clamped (iv__down); min and max return
   their second operand for NaN, so NaN lanes stay */
static inline __m128d iv__fast_clamp(__m128d v)
{
    return _mm_max_pd(_mm_set_pd(-DBL_MAX, -HUGE_VAL), _mm_min_pd(_mm_set_pd(HUGE_VAL, DBL_MAX), v));
}
static inline __m128d iv__out_exact(__m128d v) { return iv__fast_clamp(v); }
static inline __m128d iv__out(__m128d v) { return iv__fast_clamp(v); }
static inline __m128d iv__out_pair(__m128d v, __m128d m) { (void)m; return iv__fast_clamp(_mm_xor_pd(v, iv__sign_lo())); }
#else
static inline __m128d iv__q(void) { return _mm_set_pd(IV__PHI, -IV__PHI); }
/* for results whose subnormals are exact (+ - sqrt): X = |v| */
static inline __m128d iv__out_exact(__m128d v) { return _mm_fmadd_pd(iv__q(), iv__abs2(v), v); }
/* for any correctly rounded result (* / sqr) */
static inline __m128d iv__out(__m128d v) { return _mm_fmadd_pd(iv__q(), iv__floor_normal(iv__abs2(v)), v); }
/* from the pair v = [-lo, hi] (m = |v|) to [lo, hi], both stepped outward:
   fmaddsub gives [-phi X0 - v0, phi X1 + v1] = [-(v0 + phi X0), v1 + phi X1] */
static inline __m128d iv__out_pair(__m128d v, __m128d m) { return _mm_fmaddsub_pd(iv__q(), iv__floor_normal(m), v); }
#endif
/* The rare cases, out of line with vector arguments, so that the call does
   not force the fast path's operands out of registers. */
enum { IV__SLOW_ADD, IV__SLOW_SUB, IV__SLOW_MUL, IV__SLOW_MUL_D, IV__SLOW_SQR, IV__SLOW_DIV_POS, IV__SLOW_SQRT };
static __attribute__((noinline, unused)) __m128d iv__slow2(int op, __m128d a, __m128d b);
#endif

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
    if (x.lo == -HUGE_VAL) return x.hi == HUGE_VAL ? 0.0 : -DBL_MAX;
    if (x.hi == HUGE_VAL) return DBL_MAX;
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
/* Bisection at m = iv_mid(x): *left = [lo, m], *right = [m, hi], whose
   union is x. Returns 1 when both halves are proper subsets of x, which
   holds exactly when a double lies strictly between lo and hi (m is then
   one of them; a half-line splits at +-DBL_MAX, the entire line at 0).
   Returns 0 when no double does, so no two intervals with double ends can
   split x: a point (both halves are x), two adjacent doubles, [DBL_MAX,
   inf] ([DBL_MAX, DBL_MAX] and x) and [-inf, -DBL_MAX] (x and [-DBL_MAX,
   -DBL_MAX]); one half is x, the other the point at its finite end (for
   two adjacent doubles the end m rounds to). A bisection stops there.
   Returns 0 with both halves empty when x is empty. */
static inline int iv_split(iv_t x, iv_t *left, iv_t *right)
{
    double m = iv_mid(x);
    if (iv_is_empty(x)) { *left = *right = iv_empty(); return 0; }
    *left = iv__raw(x.lo, m);
    *right = iv__raw(m, x.hi);
    return m > x.lo && m < x.hi;
}

/* ------------------------------------------------------------------------ */
/* Arithmetic. Endpoints: correctly rounded outward or one ulp beyond.      */
/* ------------------------------------------------------------------------ */

static inline iv_t iv_neg(iv_t x) { return iv__raw(-x.hi, -x.lo); }
/* Each operation has a portable scalar form (iv__add1, ...) and, where
   IV__PAIR is on, a pair form (iv__add2, ...) giving identical values (a
   zero end's sign may differ); the tests compare the two on every class
   of input. */
/* + and -: an empty input (NaN endpoints) propagates through the
   arithmetic, and valid endpoints never give inf - inf, so no test is
   needed. The upper end is computed negated, -(a.hi + b.hi) = (-a.hi) -
   b.hi exactly (round-to-nearest is symmetric), so both ends take the same
   downward step. Sums in the subnormal range are exact (iv__down_sum). */
static inline iv_t iv__add1(iv_t a, iv_t b)
{
    return iv__raw(iv__down_sum(a.lo + b.lo), -iv__down_sum(-a.hi - b.hi));
}
static inline iv_t iv__sub1(iv_t a, iv_t b)
{
    return iv__raw(iv__down_sum(a.lo - b.hi), -iv__down_sum(b.lo - a.hi));
}
#ifdef IV__PAIR
/* [lo, hi] + [lo', hi'] in one vector add, a - b subtracts b's lanes
   swapped; then one fma steps both ends (iv__out_exact: add, abs, fma is
   the whole dependency chain). */
static inline iv_t iv__add2(iv_t a, iv_t b)
{
    __m128d av = iv__vec(a), bv = iv__vec(b), r = iv__out_exact(_mm_add_pd(av, bv));
    if (iv__any_nan(r, r)) r = iv__slow2(IV__SLOW_ADD, av, bv);
    return iv__unvec(r);
}
static inline iv_t iv__sub2(iv_t a, iv_t b)
{
    __m128d av = iv__vec(a), bv = iv__vec(b), r = iv__out_exact(_mm_sub_pd(av, iv__swap(bv)));
    if (iv__any_nan(r, r)) r = iv__slow2(IV__SLOW_SUB, av, bv);
    return iv__unvec(r);
}
static inline iv_t iv_add(iv_t a, iv_t b) { return iv__add2(a, b); }
static inline iv_t iv_sub(iv_t a, iv_t b) { return iv__sub2(a, b); }
#else
static inline iv_t iv_add(iv_t a, iv_t b) { return iv__add1(a, b); }
static inline iv_t iv_sub(iv_t a, iv_t b) { return iv__sub1(a, b); }
#endif
/* x + d for a scalar d; empty for NaN or infinite d. */
static inline iv_t iv_add_d(iv_t x, double d) { return iv_add(x, iv_point(d)); }
static inline iv_t iv_sub_d(iv_t x, double d) { return iv_add(x, iv_point(-d)); }
/* Unbounded or empty inputs (out of line, so iv_mul stays small enough to
   be inlined everywhere). */
IV_DEF iv_t iv__mul_slow(iv_t a, iv_t b);
/* Bounded inputs (the common case, one predictable branch) need no 0*inf
   repair and no empty test: NaN endpoints fail the comparisons. The test
   is written twice: with && here (gcc 12 makes it two compare-and-branch
   pairs per factor; with & it built four setae and two tests, 3 more
   instructions per call) and with & in iv__mul_bounded, for the array
   forms' blocks (with && gcc did not vectorise them). */
static inline iv_t iv__mul1_bounded(iv_t a, iv_t b)
{
    double p1 = a.lo * b.lo, p2 = a.lo * b.hi, p3 = a.hi * b.lo, p4 = a.hi * b.hi;
    return iv__raw(iv__down(iv__min(iv__min(p1, p2), iv__min(p3, p4))),
                   iv__up(iv__max(iv__max(p1, p2), iv__max(p3, p4))));
}
static inline iv_t iv__mul1(iv_t a, iv_t b)
{
    if (!(a.lo > -HUGE_VAL && a.hi < HUGE_VAL && b.lo > -HUGE_VAL && b.hi < HUGE_VAL)) return iv__mul_slow(a, b);
    return iv__mul1_bounded(a, b);
}
static inline int iv__mul_bounded(iv_t a, iv_t b)
{
    return (a.lo > -HUGE_VAL) & (a.hi < HUGE_VAL) & (b.lo > -HUGE_VAL) & (b.hi < HUGE_VAL);
}
#ifdef IV__PAIR
/* |max(p, q)|: one instruction with AVX-512DQ/VL (vrangepd, max with the
   sign cleared), else abs of the max (the compiler shares the max). */
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
static inline __m128d iv__abs_max(__m128d p, __m128d q) { return _mm_range_pd(p, q, 9); }
#else
static inline __m128d iv__abs_max(__m128d p, __m128d q) { return iv__abs2(_mm_max_pd(p, q)); }
#endif
/* a * b without min/max chains: for a fixed factor x, x*y over
   [b.lo, b.hi] is smallest at b.lo when x >= 0 and at b.hi otherwise (the
   reverse for the largest), so each end of a picks its partners from b by
   its own sign bit (blendv; -0 may pick either, its products are zeros).
   That leaves two candidates per end, p = [-a.lo*f, a.lo*g] and q the same
   for a.hi, and one max gives [-lo, hi], which iv__out_pair steps and
   turns into [lo, hi]. Infinite endpoints are fine (each chosen product is
   still the extreme over its segment) unless a chosen product is
   0 * inf = NaN, which also marks empty inputs. maxpd returns its second
   operand when either is NaN, so a NaN in q reaches the result, and the
   test of p and the result catches every NaN (and the overflows that
   iv__out_pair turns into NaN); those go to the scalar code. */
/* The product as a vector, *p one set of candidates (for the NaN test). */
static inline __m128d iv__mul_v(__m128d av, __m128d bv, __m128d *p)
{
    __m128d bs = iv__swap(bv), sg = iv__sign_lo();
    __m128d al = _mm_unpacklo_pd(av, av), ah = _mm_unpackhi_pd(av, av);
    __m128d q = _mm_mul_pd(_mm_xor_pd(ah, sg), iv__blendv(bv, bs, ah));
    *p = _mm_mul_pd(_mm_xor_pd(al, sg), iv__blendv(bv, bs, al));
    return iv__out_pair(_mm_max_pd(*p, q), iv__abs_max(*p, q));
}
static inline iv_t iv__mul2(iv_t a, iv_t b)
{
    __m128d av = iv__vec(a), bv = iv__vec(b), p, r = iv__mul_v(av, bv, &p);
    if (iv__any_nan(p, r)) r = iv__slow2(IV__SLOW_MUL, av, bv);
    return iv__unvec(r);
}
static inline iv_t iv_mul(iv_t a, iv_t b) { return iv__mul2(a, b); }
#else
static inline iv_t iv_mul(iv_t a, iv_t b) { return iv__mul1(a, b); }
#endif
/* x * d for a scalar d (two products instead of four); empty for NaN or
   infinite d. */
static inline iv_t iv__mul_d1(iv_t x, double d)
{
    double p, q;
    if (iv_is_empty(x) || !(d - d == 0)) return iv_empty();
    p = iv__mul0(x.lo, d);
    q = iv__mul0(x.hi, d);
    return d >= 0 ? iv__raw(iv__down(p), iv__up(q)) : iv__raw(iv__down(q), iv__up(p));
}
#ifdef IV__PAIR
/* [x.lo, x.hi] * d, the lanes of x swapped when d's sign bit is set; a
   0 * inf lane (NaN) or an overflow goes to the scalar code. */
static inline iv_t iv__mul_d2(iv_t x, double d)
{
    __m128d xv, dv, r;
    if (iv_is_empty(x) || !(d - d == 0)) return iv_empty();
    xv = iv__vec(x);
    dv = _mm_set1_pd(d);
    r = iv__out(_mm_mul_pd(iv__blendv(xv, iv__swap(xv), dv), dv));
    if (iv__any_nan(r, r)) r = iv__slow2(IV__SLOW_MUL_D, xv, dv);
    return iv__unvec(r);
}
static inline iv_t iv_mul_d(iv_t x, double d) { return iv__mul_d2(x, d); }
#else
static inline iv_t iv_mul_d(iv_t x, double d) { return iv__mul_d1(x, d); }
#endif
/* x^2 >= 0 (tighter than x*x when x straddles 0: no dependency): the
   squares of the smallest and largest |x|, branch-free. */
static inline iv_t iv__sqr1(iv_t x)
{
    /* NaN (empty) endpoints propagate: every max keeps its first argument
       when the comparison fails */
    double mig = iv__max(iv__max(x.lo, -x.hi), 0.0), mag = iv__max(-x.lo, x.hi);
    return iv__raw(iv__max(iv__down(mig * mig), 0.0), iv__up(mag * mag));
}
#ifdef IV__PAIR
/* The same as the product x * x with its lower end raised to 0: its
   candidates for the lower end are lo^2, hi^2 and lo*hi, and lo*hi is
   either between the squares (x on one side of 0) or negative (x straddles
   0, where the lower end is 0); its upper end is the larger square. Each
   rounded candidate is stepped as in the scalar code, so the results are
   the same, and the chain is the product's plus one max (14 cycles on
   Zen 4, against 19 for the squares of mig and mag). */
static inline iv_t iv__sqr2(iv_t x)
{
    __m128d xv = iv__vec(x), p, r = iv__mul_v(xv, xv, &p);
    if (iv__any_nan(p, r)) return iv__unvec(iv__slow2(IV__SLOW_SQR, xv, xv));
    return iv__unvec(_mm_max_pd(_mm_set_pd(-HUGE_VAL, 0.0), r));
}
static inline iv_t iv_sqr(iv_t x) { return iv__sqr2(x); }
#else
static inline iv_t iv_sqr(iv_t x) { return iv__sqr1(x); }
#endif
/* a / b for b > 0 strictly (b.hi may be +inf): no 0/0 or inf/inf occurs. */
static inline iv_t iv__div_pos1(iv_t a, iv_t b)
{
    /* A nonnegative numerator endpoint gives a nonnegative quotient, so a
       lower bound below 0 (from stepping an underflowed or exact 0) is
       pointless: clamp it, and symmetrically for the upper endpoint. */
    double lo = a.lo >= 0 ? iv__max(0.0, iv__down(a.lo / b.hi)) : iv__down(a.lo / b.lo);
    double hi = a.hi <= 0 ? iv__min(0.0, iv__up(a.hi / b.hi)) : iv__up(a.hi / b.lo);
    return iv__raw(lo, hi);
}
#ifdef IV__PAIR
/* The same with one vector division: each numerator end picks its divisor
   by its sign bit (-0 may pick either: its quotients are zeros), lane 0
   divides by the negated divisor so the quotient comes out as the pair
   [-lo, hi], which steps upward in both lanes; the clamps above are then
   min(., 0) in both lanes of the pair (masks from a, off the chain). */
static inline iv_t iv__div_pos2(iv_t a, iv_t b)
{
    __m128d av = iv__vec(a), bv = iv__vec(b), sg = iv__sign_lo();
    __m128d d = iv__blendv(_mm_xor_pd(iv__swap(bv), sg), _mm_xor_pd(bv, sg), av);
    __m128d w = _mm_div_pd(av, d), r;
    /* [a.lo >= 0, a.hi <= 0] as all-ones lanes: those ends are clamped */
    __m128d keep = _mm_cmpge_pd(_mm_xor_pd(av, _mm_set_pd(-0.0, 0.0)), _mm_setzero_pd());
#ifdef IV_FAST
    r = _mm_max_pd(_mm_set1_pd(-DBL_MAX), w); /* -lo and hi: an inward overflow clamped */
#else
    r = _mm_fmadd_pd(_mm_set1_pd(IV__PHI), iv__floor_normal(iv__abs2(w)), w);
#endif
    if (iv__any_nan(r, r)) return iv__unvec(iv__slow2(IV__SLOW_DIV_POS, av, bv));
    r = _mm_min_pd(r, _mm_andnot_pd(keep, _mm_set1_pd(HUGE_VAL)));
    return iv__unvec(_mm_xor_pd(r, sg));
}
static inline iv_t iv__div_pos(iv_t a, iv_t b) { return iv__div_pos2(a, b); }
#else
static inline iv_t iv__div_pos(iv_t a, iv_t b) { return iv__div_pos1(a, b); }
#endif
/* Tightest enclosure of a / b over b's nonzero points. Returns the number of
   pieces written to out[0..1] (sorted, disjoint): 0 when the quotient is
   empty (a empty, b empty or b = [0,0]), 1 normally, 2 when 0 is interior to
   b and not in a, e.g. [1,2]/[-1,1] = [-inf,-1] and [1,inf]; 1 there too
   when the two pieces touch or overlap after outward rounding (the whole
   line: [1,2]/[-inf,inf], or [-inf,-2^-1074]/[-1,DBL_MAX], whose pieces'
   inner ends both round to 0). */
IV_DEF int iv_div_ext(iv_t a, iv_t b, iv_t out[2]);
/* Divisors holding 0, and empty inputs (out of line). */
IV_DEF iv_t iv__div_slow(iv_t a, iv_t b);
/* a / b: the hull of iv_div_ext (entire when 0 is interior to b and a is
   not [0,0]); empty when b = [0,0]. A NaN divisor fails both tests; an
   empty numerator gives NaN quotients, which stay NaN. */
static inline iv_t iv_div(iv_t a, iv_t b)
{
    if (b.lo > 0) return iv__div_pos(a, b);
    if (b.hi < 0) return iv__div_pos(iv_neg(a), iv_neg(b));
    return iv__div_slow(a, b);
}
static inline iv_t iv_div_d(iv_t x, double d) { return iv_div(x, iv_point(d)); }
/* 1 / x (see iv_div for x containing 0). */
static inline iv_t iv_recip(iv_t x) { return iv_div(iv__raw(1.0, 1.0), x); }
/* sqrt over x ∩ [0, inf]: iv_sqrt([-1,4]) = [0,2]; empty when x < 0. */
static inline iv_t iv__sqrt1(iv_t x)
{
    double lo;
    if (iv_is_empty(x) || x.hi < 0) return iv_empty();
    lo = x.lo > 0 ? iv__down(sqrt(x.lo)) : 0.0;
    return iv__raw(iv__max(lo, 0.0), x.hi == 0 ? 0.0 : iv__up(sqrt(x.hi)));
}
#ifdef IV__PAIR
/* One vector sqrt of [max(lo, 0), hi]: a square root is never subnormal
   (sqrt(2^-1074) = 2^-537) and sqrt(0) = 0 is exact, so the step needs no
   floor; hi < 0 or NaN gives a NaN lane and the scalar code (empty). */
static inline iv_t iv__sqrt2(iv_t x)
{
    __m128d xv = iv__vec(x), r = iv__out_exact(_mm_sqrt_pd(_mm_max_pd(xv, _mm_set_pd(-HUGE_VAL, 0.0))));
    if (iv__any_nan(r, r)) r = iv__slow2(IV__SLOW_SQRT, xv, xv);
    return iv__unvec(r);
}
static inline iv_t iv_sqrt(iv_t x) { return iv__sqrt2(x); }
#else
static inline iv_t iv_sqrt(iv_t x) { return iv__sqrt1(x); }
#endif
#ifdef IV__PAIR
static __attribute__((noinline, unused)) __m128d iv__slow2(int op, __m128d a, __m128d b)
{
    iv_t x = iv__unvec(a), y = iv__unvec(b), r;
    switch (op) {
    case IV__SLOW_ADD: r = iv__add1(x, y); break;
    case IV__SLOW_SUB: r = iv__sub1(x, y); break;
    case IV__SLOW_MUL: r = iv__mul1(x, y); break;
    case IV__SLOW_MUL_D: r = iv__mul_d1(x, y.lo); break;
    case IV__SLOW_SQR: r = iv__sqr1(x); break;
    case IV__SLOW_DIV_POS: r = iv__div_pos1(x, y); break;
    default: r = iv__sqrt1(x); break;
    }
    return iv__vec(r);
}
#endif
/* Array forms: out[i] = a[i] op b[i] for i < n, exactly the intervals of
   iv_add, iv_sub and iv_mul (tested), several intervals per instruction
   where the target has AVX2 (two per register) or AVX-512 F/DQ/VL (four);
   without the pair path, blocks of 8 of the scalar code that compilers
   vectorise where there is a hardware fma, one at a time otherwise. They
   are how the throughput figures of docs/interval.md for arrays are
   reached: a call to iv_mul has a fixed cost in instructions per interval
   that a loop over calls cannot spread.
   out may be a or b (element i is read before it is written); otherwise
   the arrays must not overlap. n = 0 does nothing. */
IV_DEF void iv_add_n(iv_t *out, const iv_t *a, const iv_t *b, size_t n);
IV_DEF void iv_sub_n(iv_t *out, const iv_t *a, const iv_t *b, size_t n);
IV_DEF void iv_mul_n(iv_t *out, const iv_t *a, const iv_t *b, size_t n);
/* The same with the intervals as structure of arrays, interval i being
   [lo[i], hi[i]]: out_lo[i], out_hi[i] = [a_lo[i], a_hi[i]] op
   [b_lo[i], b_hi[i]], the per-call intervals again (tested). A register
   then holds eight lower ends (AVX-512) or four (AVX2), and a product
   needs about half the instructions of the iv_t form, which has to pair
   up and separate the ends of each interval inside a register. The same
   aliasing rule: an output array may be the matching input array. */
IV_DEF void iv_add_soa(double *out_lo, double *out_hi, const double *a_lo, const double *a_hi, const double *b_lo,
                       const double *b_hi, size_t n);
IV_DEF void iv_sub_soa(double *out_lo, double *out_hi, const double *a_lo, const double *a_hi, const double *b_lo,
                       const double *b_hi, size_t n);
IV_DEF void iv_mul_soa(double *out_lo, double *out_hi, const double *a_lo, const double *a_hi, const double *b_lo,
                       const double *b_hi, size_t n);
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


/* ------------------------------------------------------------------------ */
/* Elementary functions. Each result contains f over x ∩ dom(f); empty when */
/* nothing is left. libm values are stepped 2*IV_LIBM_ULPS doubles outward; */
/* exact cases (exp 0, log 1, sin/tan/atan 0, cos 0) are kept exact.        */
/* ------------------------------------------------------------------------ */

/* x^n for an integer n, via an error-bounded double-double power so each
   endpoint is at most one ulp outside the correctly rounded one (for results
   in the normal range). Even n never goes below 0; odd n is monotone.
   n = 0 gives [1,1]; n < 0 follows iv_div for x containing 0 (empty for
   x = [0,0]). */
IV_DEF iv_t iv_pow_n(iv_t x, int n);
/* x^y = exp(y log x) over x ∩ [0, inf] with C's pow conventions at 0 and
   inf (0^0 = 1, 0^-y = inf); negative bases are outside the domain (use
   iv_pow_n for integer powers of negative numbers). */
IV_DEF iv_t iv_pow(iv_t x, iv_t y);
IV_DEF iv_t iv_exp(iv_t x);
/* Natural log over x ∩ (0, inf]: iv_log([0,1]) = [-inf, 0]. */
IV_DEF iv_t iv_log(iv_t x);
/* sin, cos: exact extremum detection for widths below pi, tested at 1e15
   and beyond; intervals wider than 2pi (and every non-point interval at
   |x| >= 2^55, where doubles are 8 apart, and those wider than pi in
   [2^54, 2^55), where they are 4 apart) give [-1, 1] in constant time. */
IV_DEF iv_t iv_sin(iv_t x);
IV_DEF iv_t iv_cos(iv_t x);
/* tan: entire when x may contain a pole (width >= 3.14 or a sign change of
   cos), else the monotone image. */
IV_DEF iv_t iv_tan(iv_t x);
IV_DEF iv_t iv_atan(iv_t x);
/* sqrt(x^2 + y^2) without intermediate overflow or underflow: computed on
   arguments scaled by a power of two, with this header's rigorous + sqr
   sqrt, so it does not depend on libm's hypot. */
IV_DEF iv_t iv_hypot(iv_t x, iv_t y);

#ifndef IV_NO_AFFINE
/* ------------------------------------------------------------------------ */
/* Reduced affine arithmetic (Knoll et al. 2009, "Fast ray tracing of        */
/* arbitrary implicit surfaces with interval and affine arithmetic").       */
/* ------------------------------------------------------------------------ */

/* The affine form  c + t*eps_t + e*eps_x, with eps_t, eps_x in [-1, 1].
   eps_t is one noise symbol shared by every form of a computation: the ray
   parameter (iv_affine_ray_param), so forms of x(t), y(t), z(t) stay
   correlated through the whole expression. e >= 0 collects everything else
   (non-affine approximation errors, floating-point rounding errors, and
   independent input ranges); each form's eps_x is a fresh symbol,
   independent of all others, which is always sound.
   Empty form: c = t = e = NaN. Unbounded form: c = t = 0, e = +inf
   (iv_from_affine gives the entire line); any overflow yields it. A form
   with any infinite part (no operation makes one; a struct literal, or
   parts copied from an overflowed computation) is unbounded too: it
   stands for any real, as an overflow does, so iv_from_affine gives the
   entire line and every operation answers as for (0, 0, inf) (neg
   negates the parts: the same set). */
typedef struct iv_affine_t {
    double c; /* centre */
    double t; /* coefficient of the shared ray symbol eps_t */
    double e; /* accumulated error radius, >= 0 */
} iv_affine_t;

/* Defined inline after these declarations (small and hot):
     iv_affine_const(d)          the point d; empty for NaN or infinite d
     iv_affine_from_iv(x)        a new independent range: centre mid(x), the
                                 radius in e (never in eps_t), so it is
                                 uncorrelated with every other form; the
                                 unbounded form for an unbounded x
     iv_affine_ray_param(t0, t1) the ray parameter t over [t0, t1]: centre
                                 (t0+t1)/2, eps_t coefficient the half-length
                                 rounded up, e = 0; empty when t0 > t1 or
                                 either is NaN or infinite
     iv_from_affine(x)           an interval holding every value of the form
     iv_affine_is_empty(x)
     iv_affine_add, _sub, _neg, _add_d, _sub_d, _mul_d (_div_d below)
     iv_affine_mul, iv_affine_sqr  products keep the mean of the squared
                                 shared symbol (t*t'/2 into the centre), the
                                 standard affine treatment of eps_t^2 */
IV_DEF iv_affine_t iv_affine_div(iv_affine_t x, iv_affine_t y);
/* x / d for a double d: iv_affine_div by the constant form (the domain
   rules of iv_div_d: d = 0 or NaN gives the empty form). */
IV_DEF iv_affine_t iv_affine_div_d(iv_affine_t x, double d);
/* Non-affine operations. exp log sqrt recip atan pow_n (and div through
   recip), on a range where f is convex or concave: a linear approximation
   alpha x + g with g = f - alpha x enclosed rigorously (end values and a
   tangent bound); the slope is the one nearest the Chebyshev (minimax)
   slope, among Chebyshev, halfway and min-range (Stolfi & de Figueiredo),
   whose range stays within 1.1x f's image (see the implementation and
   docs/interval.md); sin, cos and tan too, on ranges where they have no
   inflection (since 2026-12-06). Elsewhere (sin, cos and tan across an
   inflection, atan across 0, odd pow_n across 0, log and sqrt of ranges
   touching 0): a first-order Taylor form
   with an interval Lagrange remainder, f(c) + f'(c)(x - c) + [0, r^2]
   f''(X)/2. When the error term would exceed the plain interval image, the
   result is iv_affine_from_iv(interval image) instead. */
IV_DEF iv_affine_t iv_affine_recip(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_sqrt(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_pow_n(iv_affine_t x, int n);
IV_DEF iv_affine_t iv_affine_pow(iv_affine_t x, iv_affine_t y);
IV_DEF iv_affine_t iv_affine_exp(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_log(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_sin(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_cos(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_tan(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_atan(iv_affine_t x);
/* abs, sqr, sqrt, even pow_n and hypot: a result whose range would read
   below 0 while its t is 0 (hypot: whatever its t) is c + c eps_x, which
   iv_from_affine gives as [0, 2c]; one with t != 0 keeps the dip of its
   approximation, and its correlation (docs/interval.md). */
IV_DEF iv_affine_t iv_affine_abs(iv_affine_t x);
IV_DEF iv_affine_t iv_affine_min(iv_affine_t x, iv_affine_t y);
IV_DEF iv_affine_t iv_affine_max(iv_affine_t x, iv_affine_t y);
IV_DEF iv_affine_t iv_affine_hypot(iv_affine_t x, iv_affine_t y);

/* The linear operations and products are small and hot: inline. */
/* Rounding-error accounting. A coefficient computed in round-to-nearest
   from at most three operations on terms whose magnitudes sum to S is off
   by at most gamma_3 S + 3*2^-1075 (standard model; an fma from
   contraction only removes roundings). We charge IV__AFF_REL*S + IV__AFF_ABS.
   The error radius itself is summed in round-to-nearest from at most 16
   operations and then inflated by IV__AFF_UP, which exceeds the relative
   error gamma_16 of that sum. Under IV_FAST rounding errors are ignored. */
#define IV__AFF_REL 8.881784197001252e-16  /* 2^-50 > gamma_3 */
#define IV__AFF_ABS 8.289046e-317          /* > 16 * 2^-1075, subnormal */
#define IV__AFF_UP  1.0000000000000142     /* 1 + 2^-46 > 1 + 2 gamma_16 */

#ifdef IV_FAST
static inline double iv__aff_rnd(double s) { (void)s; return 0.0; }
static inline double iv__aff_radius(double r) { return r; }
#else
static inline double iv__aff_rnd(double s) { return IV__AFF_REL * s + IV__AFF_ABS; }
static inline double iv__aff_radius(double r) { return r * IV__AFF_UP + IV__AFF_ABS; }
#endif

static inline iv_affine_t iv__aff(double c, double t, double e)
{
    iv_affine_t r;
    r.c = c;
    r.t = t;
    r.e = e;
    return r;
}
static inline iv_affine_t iv__aff_empty(void) { return iv__aff(NAN, NAN, NAN); }
static inline iv_affine_t iv__aff_entire(void) { return iv__aff(0.0, 0.0, HUGE_VAL); }
static inline int iv_affine_is_empty(iv_affine_t x) { return x.e != x.e; }
/* any infinite part: the unbounded form, whatever the other parts hold */
static inline int iv__aff_unbounded(iv_affine_t x)
{
    return x.e == HUGE_VAL || fabs(x.c) == HUGE_VAL || fabs(x.t) == HUGE_VAL;
}
/* Inputs were non-empty; anything non-finite now is overflow (or an
   unbounded input): the sound answer is the unbounded form. */
static inline iv_affine_t iv__aff_finish(double c, double t, double e)
{
    if (c - c == 0 && t - t == 0 && e - e == 0) return iv__aff(c, t, e);
    return iv__aff_entire();
}

static inline iv_affine_t iv_affine_const(double d)
{
    if (!(d - d == 0)) return iv__aff_empty();
    return iv__aff(d, 0.0, 0.0);
}

static inline iv_affine_t iv_affine_from_iv(iv_t x)
{
    double m;
    if (iv_is_empty(x)) return iv__aff_empty();
    if (x.lo == -HUGE_VAL || x.hi == HUGE_VAL) return iv__aff_entire();
    m = iv_mid(x);
    return iv__aff_finish(m, 0.0, iv__up(iv__max(x.hi - m, m - x.lo)));
}

static inline iv_affine_t iv_affine_ray_param(double t0, double t1)
{
    double m;
    if (!(t0 <= t1) || !(t0 - t0 == 0) || !(t1 - t1 == 0)) return iv__aff_empty();
    m = iv_mid(iv__raw(t0, t1));
    /* c - t <= t0 and c + t >= t1 exactly, so every t in [t0, t1] is
       c + t*eps_t for some eps_t in [-1, 1] */
    return iv__aff_finish(m, t0 == t1 ? 0.0 : iv__up(iv__max(t1 - m, m - t0)), 0.0);
}

static inline iv_t iv_from_affine(iv_affine_t x)
{
    double r;
    if (iv_affine_is_empty(x)) return iv_empty();
    /* an infinite centre or coefficient gave [DBL_MAX, inf] or NaN ends */
    if (iv__aff_unbounded(x)) return iv_entire();
    r = fabs(x.t) + x.e;
    r = r == 0 ? 0.0 : iv__up(r);
    if (r == 0) return iv__raw(x.c, x.c);
    /* c + c eps_x is [0, 2c] exactly: the outward steps below would put
       its lower end under 0, which a function >= 0 (iv__aff_nonneg)
       must not show */
    if (x.t == 0 && x.e == x.c) return iv__raw(0.0, x.c + x.c); /* doubling is exact */
    return iv_make(iv__down(x.c - r), iv__up(x.c + r));
}

/* A form of a function >= 0 (abs, sqr, sqrt, even pow_n, hypot) whose
   range reads below 0 (the outward steps at a range that ends at 0, the
   rounding terms in e) becomes c + c eps_x, c = hi/2 rounded up, whose
   range is [0, 2c] (iv_from_affine above; 2c = hi unless hi is subnormal
   and odd): where t = 0 the form had no
   correlation to lose. A form with t != 0 keeps its dip (see
   docs/interval.md): a lower line c - e + t eps_t below 0 somewhere in
   [-1, 1] allows no t != 0 once both its ends must be >= 0, and the
   correlation is what later cancellations need (x^2 of t in [-0.5, 1.5]
   reads [-0.75, 2.25]; with it x^2 - x is [-0.25, 0.75], without it
   [-1.5, 2.75]). hypot passes any = 1: any dip goes. */
static inline iv_affine_t iv__aff_nonneg(iv_affine_t x, int any)
{
    iv_t r;
    double h;
    if (x.t != 0 && !any) return x;
    r = iv_from_affine(x);
    if (!(r.lo < 0 && r.hi < HUGE_VAL)) return x;
    h = 0.5 * r.hi; /* exact but in the subnormal range */
    if (h + h < r.hi) h = iv__up(h);
    return iv__aff(h, 0.0, h);
}

static inline iv_affine_t iv_affine_add(iv_affine_t x, iv_affine_t y)
{
    double c, t;
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv__aff_empty();
    c = x.c + y.c;
    t = x.t + y.t;
    return iv__aff_finish(c, t, iv__aff_radius(x.e + y.e + iv__aff_rnd(fabs(c) + fabs(t))));
}
static inline iv_affine_t iv_affine_neg(iv_affine_t x) { return iv__aff(-x.c, -x.t, x.e); }
static inline iv_affine_t iv_affine_sub(iv_affine_t x, iv_affine_t y) { return iv_affine_add(x, iv_affine_neg(y)); }

static inline iv_affine_t iv_affine_add_d(iv_affine_t x, double d)
{
    double c;
    if (iv_affine_is_empty(x) || !(d - d == 0)) return iv__aff_empty();
    c = x.c + d;
    return iv__aff_finish(c, x.t, iv__aff_radius(x.e + iv__aff_rnd(fabs(c))));
}
static inline iv_affine_t iv_affine_sub_d(iv_affine_t x, double d) { return iv_affine_add_d(x, -d); }

static inline iv_affine_t iv_affine_mul_d(iv_affine_t x, double d)
{
    double c, t;
    if (iv_affine_is_empty(x) || !(d - d == 0)) return iv__aff_empty();
    /* returning x kept its infinite parts (1e300 * a form with c = inf) */
    if (iv__aff_unbounded(x)) return d == 0 ? iv__aff(0.0, 0.0, 0.0) : iv__aff_entire();
    c = x.c * d;
    t = x.t * d;
    return iv__aff_finish(c, t, iv__aff_radius(x.e * fabs(d) + iv__aff_rnd(fabs(c) + fabs(t))));
}

/* (xc + xt E + xe X)(yc + yt E + ye Y), E = eps_t shared, X, Y independent:
   E^2 in [0, 1] is split as 1/2 + [-1/2, 1/2]. */
static inline iv_affine_t iv_affine_mul(iv_affine_t x, iv_affine_t y)
{
    double cc, tt, c, t, e;
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv__aff_empty();
    if (x.e == HUGE_VAL || y.e == HUGE_VAL) return iv__aff_entire();
    cc = x.c * y.c;
    tt = 0.5 * (x.t * y.t);
    c = cc + tt;
    t = x.c * y.t + x.t * y.c;
    e = fabs(x.c) * y.e + fabs(y.c) * x.e + fabs(tt) + fabs(x.t) * y.e + x.e * fabs(y.t) + x.e * y.e;
    e += iv__aff_rnd(fabs(cc) + fabs(tt) + fabs(x.c * y.t) + fabs(x.t * y.c));
    return iv__aff_finish(c, t, iv__aff_radius(e));
}

/* (c + t E + e X)^2 with one X for both factors: E^2 and X^2 in [0, 1]
   give centre terms t^2/2 + e^2/2 of radius t^2/2 + e^2/2. */
static inline iv_affine_t iv_affine_sqr(iv_affine_t x)
{
    double cc, tt, ee, c, t, e;
    if (iv_affine_is_empty(x)) return iv__aff_empty();
    if (x.e == HUGE_VAL) return iv__aff_entire();
    cc = x.c * x.c;
    tt = 0.5 * (x.t * x.t);
    ee = 0.5 * (x.e * x.e);
    c = cc + tt + ee;
    t = 2.0 * x.c * x.t;
    e = 2.0 * fabs(x.c) * x.e + tt + ee + 2.0 * fabs(x.t) * x.e;
    e += iv__aff_rnd(cc + tt + ee + fabs(t));
    return iv__aff_nonneg(iv__aff_finish(c, t, iv__aff_radius(e)), 0);
}

#endif /* IV_NO_AFFINE */

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

/* Unbounded or empty inputs: 0 * inf is an exact zero times an unbounded
   real, i.e. 0 (iv__mul0), and emptiness is restored by a select. */
IV_DEF iv_t iv__mul_slow(iv_t a, iv_t b)
{
    double p1 = iv__mul0(a.lo, b.lo), p2 = iv__mul0(a.lo, b.hi);
    double p3 = iv__mul0(a.hi, b.lo), p4 = iv__mul0(a.hi, b.hi);
    double lo = iv__down(iv__min(iv__min(p1, p2), iv__min(p3, p4)));
    double hi = iv__up(iv__max(iv__max(p1, p2), iv__max(p3, p4)));
    int empty = iv_is_empty(a) | iv_is_empty(b);
    return iv__raw(empty ? NAN : lo, empty ? NAN : hi);
}
enum { IV__N_ADD, IV__N_SUB, IV__N_MUL };
/* The array forms, written once below over the iv__w_ operations of the
   widest register the target has. iv_add_n and iv_sub_n keep one
   interval [lo, hi] per 128-bit half of a register and take the pair
   path's own step (iv__out_exact). iv_mul_n splits two registers of
   intervals into one of lower and one of upper ends (two in-lane unpacks
   per operand), runs the structure-of-arrays product (iv__w_op_soa) and
   joins the ends again (two more): 6 shuffles per 2 IV__W intervals
   instead of the pair form's dup, dup, swap, two sign flips and two
   blends per register, measured 3.2x -> 2.4x the double loop (docs/
   interval.md). A block with a NaN lane is redone one interval at a time
   by iv_add / iv_sub / iv_mul, so the results are theirs bit for bit. */
/* gcc 12's AVX-512 intrinsics start from _mm512_undefined_pd(), which its
   C++ front end reports as maybe-uninitialized once inlined here */
#if defined(__GNUC__) && !defined(__clang__)
#  pragma GCC diagnostic push
#  pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#if defined(IV__PAIR) && defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512VL__)
#  define IV__W 4 /* intervals per register */
typedef __m512d iv__wv;
static inline iv__wv iv__w_load(const iv_t *x) { return _mm512_loadu_pd(&x->lo); }
static inline void iv__w_store(iv_t *x, iv__wv v) { _mm512_storeu_pd(&x->lo, v); }
static inline iv__wv iv__w_pairs(__m128d v) { return _mm512_broadcast_f64x2(v); }
static inline iv__wv iv__w_loadd(const double *x) { return _mm512_loadu_pd(x); }
static inline void iv__w_stored(double *x, iv__wv v) { _mm512_storeu_pd(x, v); }
/* max(|v|, 2^-1022), the step's X for any rounded result (see iv__out) */
static inline iv__wv iv__w_mag_floor(iv__wv v) { return _mm512_range_pd(v, _mm512_set1_pd(2.2250738585072014e-308), 11); }
static inline iv__wv iv__w_swap(iv__wv v) { return _mm512_shuffle_pd(v, v, 0x55); }
static inline iv__wv iv__w_blendv(iv__wv a, iv__wv b, iv__wv m) { return _mm512_mask_blend_pd(_mm512_movepi64_mask(_mm512_castpd_si512(m)), a, b); }
static inline int iv__w_any_nan(iv__wv a, iv__wv b) { return _mm512_cmp_pd_mask(a, b, _CMP_UNORD_Q) != 0; }
#  define IV__W_OP(op) _mm512_##op##_pd
#elif defined(IV__PAIR) && defined(__AVX2__)
#  define IV__W 2
typedef __m256d iv__wv;
static inline iv__wv iv__w_load(const iv_t *x) { return _mm256_loadu_pd(&x->lo); }
static inline void iv__w_store(iv_t *x, iv__wv v) { _mm256_storeu_pd(&x->lo, v); }
static inline iv__wv iv__w_pairs(__m128d v) { return _mm256_broadcast_pd(&v); }
static inline iv__wv iv__w_loadd(const double *x) { return _mm256_loadu_pd(x); }
static inline void iv__w_stored(double *x, iv__wv v) { _mm256_storeu_pd(x, v); }
static inline iv__wv iv__w_swap(iv__wv v) { return _mm256_permute_pd(v, 5); }
/* gcc 12 computes the 256-bit blendv's mask again with a compare against
   0 (vpcmpgtq, one more instruction per blend); the asm keeps the sign
   bits as the mask (the AVX2 product 2.8x the double loop, not 3.05x) */
#  if defined(__clang__)
static inline iv__wv iv__w_blendv(iv__wv a, iv__wv b, iv__wv m) { return _mm256_blendv_pd(a, b, m); }
#  else
static inline iv__wv iv__w_blendv(iv__wv a, iv__wv b, iv__wv m)
{
    iv__wv r;
    __asm__("vblendvpd %3, %2, %1, %0" : "=x"(r) : "x"(a), "x"(b), "x"(m));
    return r;
}
#  endif
static inline iv__wv iv__w_floor_normal(iv__wv m) { return _mm256_castsi256_pd(_mm256_max_epi32(_mm256_castpd_si256(m), _mm256_set1_epi64x(0x0010000080000000LL))); }
#  if defined(__AVX512DQ__) && defined(__AVX512VL__)
static inline iv__wv iv__w_mag_floor(iv__wv v) { return _mm256_range_pd(v, _mm256_set1_pd(2.2250738585072014e-308), 11); }
#  else
static inline iv__wv iv__w_mag_floor(iv__wv v) { return iv__w_floor_normal(_mm256_andnot_pd(_mm256_set1_pd(-0.0), v)); }
#  endif
#  ifdef __AVX512VL__
static inline int iv__w_any_nan(iv__wv a, iv__wv b) { return _mm256_cmp_pd_mask(a, b, _CMP_UNORD_Q) != 0; }
#  else
static inline int iv__w_any_nan(iv__wv a, iv__wv b) { return _mm256_movemask_pd(_mm256_cmp_pd(a, b, _CMP_UNORD_Q)); }
#  endif
#  define IV__W_OP(op) _mm256_##op##_pd
#endif
#ifdef IV__W
/* the pair path's step for + and -, lane pair by lane pair (see
   iv__out_exact) */
#  ifdef IV_FAST
static inline iv__wv iv__w_out_exact(iv__wv v)
{
    return IV__W_OP(max)(iv__w_pairs(_mm_set_pd(-DBL_MAX, -HUGE_VAL)),
                         IV__W_OP(min)(iv__w_pairs(_mm_set_pd(HUGE_VAL, DBL_MAX)), v));
}
#  else
static inline iv__wv iv__w_out_exact(iv__wv v)
{
    return IV__W_OP(fmadd)(iv__w_pairs(iv__q()), IV__W_OP(andnot)(iv__w_pairs(_mm_set1_pd(-0.0)), v), v);
}
#  endif
/* one register of intervals through + or -; *bad: a NaN lane */
static inline iv__wv iv__w_op(int op, iv__wv av, iv__wv bv, int *bad)
{
    iv__wv r = iv__w_out_exact(op == IV__N_ADD ? IV__W_OP(add)(av, bv) : IV__W_OP(sub)(av, iv__w_swap(bv)));
    *bad = iv__w_any_nan(r, r);
    return r;
}
/* 2 IV__W intervals as structure of arrays through op: the pair path's
   candidates and steps end by end (per-call p holds c1 and c3 negated in
   its lower lane, q c2 and c4; a max there is a min here on the same
   operands in the same order, so equal values and signed zeros come out
   the same), X = max(|v|, 2^-1022) in one vrangepd (the step's proof
   allows any X in the binade or, for subnormal v, in [2^-1022, 2^-1021),
   so the result is the same double). *bad: a NaN candidate or end. */
static inline void iv__w_op_soa(int op, iv__wv al, iv__wv ah, iv__wv bl, iv__wv bh, iv__wv *lo, iv__wv *hi, int *bad)
{
    iv__wv l, h, c1 = al, c3 = ah, phi = IV__W_OP(set1)(IV__PHI);
    if (op == IV__N_MUL) {
        /* keeps the four loads in registers: gcc 12 otherwise folds bl and
           bh into each blend as memory operands, ten loads instead of four
           (measured 2.7x -> 2.2x the double loop) */
        __asm__("" : "+v"(al), "+v"(ah), "+v"(bl), "+v"(bh));
        c1 = IV__W_OP(mul)(al, iv__w_blendv(bl, bh, al));
        c3 = IV__W_OP(mul)(al, iv__w_blendv(bh, bl, al));
        l = IV__W_OP(min)(c1, IV__W_OP(mul)(ah, iv__w_blendv(bl, bh, ah)));
        h = IV__W_OP(max)(c3, IV__W_OP(mul)(ah, iv__w_blendv(bh, bl, ah)));
    } else {
        l = op == IV__N_ADD ? IV__W_OP(add)(al, bl) : IV__W_OP(sub)(al, bh);
        h = op == IV__N_ADD ? IV__W_OP(add)(ah, bh) : IV__W_OP(sub)(ah, bl);
    }
#  ifdef IV_FAST
    (void)phi;
    l = IV__W_OP(min)(IV__W_OP(set1)(DBL_MAX), l); /* an inward overflow clamped */
    h = IV__W_OP(max)(IV__W_OP(set1)(-DBL_MAX), h);
#  else
    if (op == IV__N_MUL) {
        l = IV__W_OP(fnmadd)(phi, iv__w_mag_floor(l), l);
        h = IV__W_OP(fmadd)(phi, iv__w_mag_floor(h), h);
    } else { /* exact subnormal sums: X = |v| (iv__out_exact) */
        iv__wv sign = IV__W_OP(set1)(-0.0);
        l = IV__W_OP(fnmadd)(phi, IV__W_OP(andnot)(sign, l), l);
        h = IV__W_OP(fmadd)(phi, IV__W_OP(andnot)(sign, h), h);
    }
#  endif
    *lo = l;
    *hi = h;
    *bad = iv__w_any_nan(c1, c3) | iv__w_any_nan(l, h);
}
/* 2 IV__W intervals of iv_t arrays (a0 the first IV__W, a1 the next)
   through the product above. unpacklo/unpackhi work inside each 128-bit
   lane: with a0 = [l0 h0 l1 h1 ..] and a1 = [l4 h4 l5 h5 ..] (AVX-512)
   they give [l0 l4 l1 l5 ..] and [h0 h4 h1 h5 ..], b in the same order, so
   lane k of the ends belongs to one interval; the same two unpacks of the
   results give back [l0 h0 l1 h1 ..] and [l4 h4 ..] (for AVX2 likewise
   with two intervals per register). */
static inline void iv__w_mul_pairs(iv__wv a0, iv__wv a1, iv__wv b0, iv__wv b1, iv__wv *r0, iv__wv *r1, int *bad)
{
    iv__wv lo, hi;
    /* one load per operand: gcc 12 otherwise folds each load into both of
       its unpacks as a memory operand */
    __asm__("" : "+v"(a0), "+v"(a1), "+v"(b0), "+v"(b1));
    iv__w_op_soa(IV__N_MUL, IV__W_OP(unpacklo)(a0, a1), IV__W_OP(unpackhi)(a0, a1), IV__W_OP(unpacklo)(b0, b1),
                 IV__W_OP(unpackhi)(b0, b1), &lo, &hi, bad);
    *r0 = IV__W_OP(unpacklo)(lo, hi);
    *r1 = IV__W_OP(unpackhi)(lo, hi);
}
#endif
static inline iv_t iv__op_one(int op, iv_t a, iv_t b)
{
    return op == IV__N_MUL ? iv_mul(a, b) : op == IV__N_ADD ? iv_add(a, b) : iv_sub(a, b);
}
#if !defined(IV__PAIR) && (defined(FP_FAST_FMA) || defined(__FMA__))
/* The portable array forms: blocks of IV__B intervals through the scalar
   code without its branch (iv__mul1_bounded; + and - have none) into a
   local array, which the compiler may vectorise (gcc 12 -O2 does, with
   the fused step: IV_NO_SIMD -march=native mul_n 13.9x -> 5.7x the double
   loop, mul_soa 12x -> 3.8x); a block with an unbounded or empty factor
   is redone by iv_mul, so the results are the per-call ones. *ok: cleared
   by such a factor. Without a hardware fma the step is the bit path,
   which gcc did not vectorise (8 more instructions per interval): those
   targets keep the loop of calls. */
#  define IV__B 8
static inline iv_t iv__op_lane1(int op, iv_t a, iv_t b, int *ok)
{
    if (op != IV__N_MUL) return op == IV__N_ADD ? iv__add1(a, b) : iv__sub1(a, b);
    *ok &= iv__mul_bounded(a, b);
    return iv__mul1_bounded(a, b);
}
#endif
/* op is a constant at every call; forced inline (where the compiler has
   the attribute), each array form compiles to its own loop. A block with
   a NaN lane is redone interval by interval. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void iv__op_n(int op, iv_t *out, const iv_t *a, const iv_t *b, size_t n)
{
    size_t i = 0, k;
#ifdef IV__W
    size_t blocks = n - n % (2 * IV__W);
    for (; i < blocks; i += 2 * IV__W) {
        int bad0, bad1 = 0;
        iv__wv r0, r1;
        if (op == IV__N_MUL) {
            iv__w_mul_pairs(iv__w_load(a + i), iv__w_load(a + i + IV__W), iv__w_load(b + i), iv__w_load(b + i + IV__W), &r0,
                            &r1, &bad0);
        } else {
            r0 = iv__w_op(op, iv__w_load(a + i), iv__w_load(b + i), &bad0);
            r1 = iv__w_op(op, iv__w_load(a + i + IV__W), iv__w_load(b + i + IV__W), &bad1);
        }
        if (bad0 | bad1) {
            for (k = i; k < i + 2 * IV__W; k++) out[k] = iv__op_one(op, a[k], b[k]);
            continue;
        }
        iv__w_store(out + i, r0);
        iv__w_store(out + i + IV__W, r1);
    }
#elif defined(IV__B)
    for (; i + IV__B <= n; i += IV__B) {
        iv_t r[IV__B];
        int ok = 1;
        for (k = 0; k < IV__B; k++) r[k] = iv__op_lane1(op, a[i + k], b[i + k], &ok);
        if (!ok) {
            for (k = i; k < i + IV__B; k++) out[k] = iv__op_one(op, a[k], b[k]);
            continue;
        }
        memcpy(out + i, r, sizeof r);
    }
#endif
    for (k = i; k < n; k++) out[k] = iv__op_one(op, a[k], b[k]);
}
IV_DEF void iv_add_n(iv_t *out, const iv_t *a, const iv_t *b, size_t n) { iv__op_n(IV__N_ADD, out, a, b, n); }
IV_DEF void iv_sub_n(iv_t *out, const iv_t *a, const iv_t *b, size_t n) { iv__op_n(IV__N_SUB, out, a, b, n); }
IV_DEF void iv_mul_n(iv_t *out, const iv_t *a, const iv_t *b, size_t n) { iv__op_n(IV__N_MUL, out, a, b, n); }
/* intervals [from, to) of the structure-of-arrays forms one call at a time:
   the tail, and a block with a NaN lane */
static inline void iv__op_soa_each(int op, double *out_lo, double *out_hi, const double *a_lo, const double *a_hi,
                                   const double *b_lo, const double *b_hi, size_t from, size_t to)
{
    size_t k;
    for (k = from; k < to; k++) {
        iv_t r = iv__op_one(op, iv__raw(a_lo[k], a_hi[k]), iv__raw(b_lo[k], b_hi[k]));
        out_lo[k] = r.lo;
        out_hi[k] = r.hi;
    }
}
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void iv__op_soa(int op, double *out_lo, double *out_hi, const double *a_lo, const double *a_hi,
                              const double *b_lo, const double *b_hi, size_t n)
{
    size_t i = 0;
#ifdef IV__W
    size_t blocks = n - n % (2 * IV__W);
    for (; i < blocks; i += 2 * IV__W) {
        int bad;
        iv__wv lo, hi;
        iv__w_op_soa(op, iv__w_loadd(a_lo + i), iv__w_loadd(a_hi + i), iv__w_loadd(b_lo + i), iv__w_loadd(b_hi + i), &lo,
                     &hi, &bad);
        if (bad) {
            iv__op_soa_each(op, out_lo, out_hi, a_lo, a_hi, b_lo, b_hi, i, i + 2 * IV__W);
            continue;
        }
        iv__w_stored(out_lo + i, lo);
        iv__w_stored(out_hi + i, hi);
    }
#elif defined(IV__B)
    for (; i + IV__B <= n; i += IV__B) {
        double lo[IV__B], hi[IV__B];
        int ok = 1;
        size_t k;
        for (k = 0; k < IV__B; k++) {
            iv_t r = iv__op_lane1(op, iv__raw(a_lo[i + k], a_hi[i + k]), iv__raw(b_lo[i + k], b_hi[i + k]), &ok);
            lo[k] = r.lo;
            hi[k] = r.hi;
        }
        if (!ok) {
            iv__op_soa_each(op, out_lo, out_hi, a_lo, a_hi, b_lo, b_hi, i, i + IV__B);
            continue;
        }
        memcpy(out_lo + i, lo, sizeof lo);
        memcpy(out_hi + i, hi, sizeof hi);
    }
#endif
    iv__op_soa_each(op, out_lo, out_hi, a_lo, a_hi, b_lo, b_hi, i, n);
}
IV_DEF void iv_add_soa(double *out_lo, double *out_hi, const double *a_lo, const double *a_hi, const double *b_lo,
                       const double *b_hi, size_t n)
{
    iv__op_soa(IV__N_ADD, out_lo, out_hi, a_lo, a_hi, b_lo, b_hi, n);
}
IV_DEF void iv_sub_soa(double *out_lo, double *out_hi, const double *a_lo, const double *a_hi, const double *b_lo,
                       const double *b_hi, size_t n)
{
    iv__op_soa(IV__N_SUB, out_lo, out_hi, a_lo, a_hi, b_lo, b_hi, n);
}
IV_DEF void iv_mul_soa(double *out_lo, double *out_hi, const double *a_lo, const double *a_hi, const double *b_lo,
                       const double *b_hi, size_t n)
{
    iv__op_soa(IV__N_MUL, out_lo, out_hi, a_lo, a_hi, b_lo, b_hi, n);
}
#if defined(__GNUC__) && !defined(__clang__)
#  pragma GCC diagnostic pop
#endif

/* a / (0, h] for h > 0: as the divisor tends to 0+ the quotient of a
   positive (negative) numerator runs to +inf (-inf); a zero numerator
   stays 0. */
static iv_t iv__div_zero_pos(iv_t a, double h)
{
    double lo = a.lo >= 0 ? iv__max(0.0, iv__down(a.lo / h)) : -HUGE_VAL;
    double hi = a.hi <= 0 ? iv__min(0.0, iv__up(a.hi / h)) : HUGE_VAL;
    return iv__raw(lo, hi);
}

IV_DEF iv_t iv__div_slow(iv_t a, iv_t b)
{
    iv_t piece[2];
    int n;
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    n = iv_div_ext(a, b, piece);
    if (n == 0) return iv_empty();
    return n == 1 ? piece[0] : iv_hull(piece[0], piece[1]);
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

/* ------------------------------------------------------------------------ */
/* libm-based functions                                                     */
/* ------------------------------------------------------------------------ */

/* If libm's result y is within N ulps of f (N = IV_LIBM_ULPS, measured in
   ulps of f as glibc does), at most N doubles lie between y and f on the
   side above f, but up to 2N below it (the spacing halves below a power of
   two). Stepping 2N doubles outward therefore always reaches past f. */
#define IV__LIBM_STEPS (2 * (IV_LIBM_ULPS))

/* y stepped n doubles down (up). */
static double iv__steps_down(double y, int n)
{
    int i;
    for (i = 0; i < n; i++) y = iv__down(y);
    return y;
}
static double iv__steps_up(double y, int n)
{
    int i;
    for (i = 0; i < n; i++) y = iv__up(y);
    return y;
}
static double iv__libm_down(double y) { return iv__steps_down(y, IV__LIBM_STEPS); }
static double iv__libm_up(double y) { return iv__steps_up(y, IV__LIBM_STEPS); }

IV_DEF iv_t iv_exp(iv_t x)
{
    double lo, hi;
    if (iv_is_empty(x)) return iv_empty();
    lo = x.lo == 0 ? 1.0 : iv__max(0.0, iv__libm_down(exp(x.lo)));
    hi = x.hi == 0 ? 1.0 : iv__libm_up(exp(x.hi));
    return iv__raw(lo, hi);
}

IV_DEF iv_t iv_log(iv_t x)
{
    double lo, hi;
    if (iv_is_empty(x) || x.hi <= 0) return iv_empty();
    lo = x.lo <= 0 ? -HUGE_VAL : x.lo == 1 ? 0.0 : iv__libm_down(log(x.lo));
    hi = x.hi == 1 ? 0.0 : iv__libm_up(log(x.hi));
    return iv__raw(lo, hi);
}

IV_DEF iv_t iv_atan(iv_t x)
{
    if (iv_is_empty(x)) return iv_empty();
    return iv__raw(x.lo == 0 ? 0.0 : iv__libm_down(atan(x.lo)), x.hi == 0 ? 0.0 : iv__libm_up(atan(x.hi)));
}

/* A real width below pi: then [a, b] holds at most one zero of a function
   whose zeros are pi apart (sin, cos), so comparing signs at the ends finds
   it. b - a is rounded to nearest; 3.14 + half an ulp is still below pi. */
#define IV__NARROW 3.14
/* A real width above 2pi holds a full period of sin and cos. */
#define IV__FULL_PERIOD 6.2832

/* Our own argument reduction for |x| >= IV__REDUCE_MIN. libm is trusted
   to IV_LIBM_ULPS only where it reduces well: glibc 2.36's sin, cos and
   tan are off by up to 39 141 ulps at doubles near multiples of pi/2 from
   2^39 up (its reduced argument loses bits there; found by review,
   2026-12-06), so large arguments are reduced here, exactly enough, and
   libm sees only |r| <= pi/4 (plus rounding). Payne-Hanek: x = M 2^E
   (M < 2^53 an integer), x (2/pi) mod 4 needs only the bits of 2/pi from
   2^-(E-1) on (the earlier ones give multiples of 4); 192 of them times M
   give the quadrant and 128 bits of the fraction. The nearest double to a
   multiple of pi/2 is at least 2^-62 from it (in units of pi/2, for every
   double), so the fraction keeps 60 significant bits or more, and the
   bits past the window change it by less than 2^-137. */
#define IV__REDUCE_MIN 1048576.0 /* 2^20 */
/* 2/pi, 1344 bits, 32 per word, most significant first (0.A2F9836E...) */
static const uint32_t iv__two_over_pi[42] = {
    0xa2f9836eu, 0x4e441529u, 0xfc2757d1u, 0xf534ddc0u, 0xdb629599u, 0x3c439041u,
    0xfe5163abu, 0xdebbc561u, 0xb7246e3au, 0x424dd2e0u, 0x06492eeau, 0x09d1921cu,
    0xfe1deb1cu, 0xb129a73eu, 0xe88235f5u, 0x2ebb4484u, 0xe99c7026u, 0xb45f7e41u,
    0x3991d639u, 0x835339f4u, 0x9c845f8bu, 0xbdf9283bu, 0x1ff897ffu, 0xde05980fu,
    0xef2f118bu, 0x5a0a6d1fu, 0x6d367ecfu, 0x27cb09b7u, 0x4f463f66u, 0x9e5fea2du,
    0x7527bac7u, 0xebe5f17bu, 0x3d0739f7u, 0x8a5292eau, 0x6bfb5fb1u, 0x1f8d5d08u,
    0x56033046u, 0xfc7b6babu, 0xf0cfbc20u, 0x9af4361du, 0xa9e39161u, 0x5ee61b08u,
};
/* pi/2 = IV__PIO2_HI + IV__PIO2_LO to 2^-107 */
#define IV__PIO2_HI 1.5707963267948966     /* 0x1.921fb54442d18p+0 */
#define IV__PIO2_LO 6.123233995736766e-17  /* 0x1.1a62633145c07p-54 */

/* 32 bits of 2/pi from bit i on (bit 1 is the first after the point). */
static uint32_t iv__tpi_bits(int i)
{
    int a = (i - 1) / 32, b = (i - 1) % 32;
    return b ? (uint32_t)(iv__two_over_pi[a] << b | iv__two_over_pi[a + 1] >> (32 - b)) : iv__two_over_pi[a];
}
/* 64 bits of the 256-bit little-endian number p (8 words) from bit l up. */
static uint64_t iv__bits64(const uint32_t *p, int l)
{
    int k = l / 32, sh = l % 32;
    uint64_t w0 = k < 8 ? p[k] : 0, w1 = k + 1 < 8 ? p[k + 1] : 0, w2 = k + 2 < 8 ? p[k + 2] : 0;
    return sh ? w0 >> sh | w1 << (32 - sh) | w2 << (64 - sh) : w0 | w1 << 32;
}
/* |x| = q pi/2 + r (q mod 4), r = *rh + *rl as a double-double with
   |r| <= pi/4 (to rounding), for finite |x| >= 2^20. */
static int iv__reduce(double x, double *rh, double *rl)
{
    uint32_t w[6], p[8] = {0, 0, 0, 0, 0, 0, 0, 0}, m[2];
    uint64_t M, hi, lo;
    int e, E, st, pb, q, i, j, neg = 0, lz = 0;
    double fh, fl;
    M = (uint64_t)ldexp(frexp(fabs(x), &e), 53);
    E = e - 53;
    st = E - 1 > 1 ? E - 1 : 1;
    for (j = 0; j < 6; j++) w[5 - j] = iv__tpi_bits(st + 32 * j);
    m[0] = (uint32_t)M, m[1] = (uint32_t)(M >> 32);
    for (i = 0; i < 2; i++) { /* p = M W, schoolbook on 32-bit words */
        uint64_t c = 0;
        for (j = 0; j < 6; j++) {
            uint64_t t = (uint64_t)m[i] * w[j] + p[i + j] + c;
            p[i + j] = (uint32_t)t;
            c = t >> 32;
        }
        p[i + 6] = (uint32_t)c;
    }
    /* x (2/pi) = p 2^-pb plus a multiple of 4 */
    pb = st + 191 - E;
    q = (int)(iv__bits64(p, pb) & 3);
    hi = iv__bits64(p, pb - 64);
    lo = iv__bits64(p, pb - 128);
    if (hi >> 63) { /* fraction >= 1/2: the next quadrant, r < 0 */
        q = (q + 1) & 3;
        neg = 1;
        lo = ~lo + 1;
        hi = ~hi + (lo == 0);
    }
    if (hi == 0) hi = lo, lo = 0, lz = 64;
    if (hi == 0) { *rh = *rl = 0; return q; }
    for (; !(hi >> 63); lz++) hi = hi << 1 | lo >> 63, lo <<= 1;
    /* the fraction f = (hi + lo 2^-64) 2^-(64 + lz) as fh + fl: hi's top
       53 bits are exact in a double, the other 75 in fl to 2^-128 of f */
    fh = ldexp((double)(hi & ~(uint64_t)0x7ff), -64 - lz);
    fl = ldexp((double)(hi & 0x7ff) + ldexp((double)lo, -64), -64 - lz);
    {
        double ph = fh * IV__PIO2_HI, pe = fma(fh, IV__PIO2_HI, -ph) + (fh * IV__PIO2_LO + fl * IV__PIO2_HI), sh = ph + pe;
        *rl = pe - (sh - ph);
        *rh = sh;
    }
    if (neg) *rh = -*rh, *rl = -*rl;
    return q;
}
/* sin (k = 0), cos (1) or tan (2) of a finite x with |x| >= 2^20, from
   the reduced argument: within IV_LIBM_ULPS + 1/2 ulp for sin and cos (the
   correction's rounding; r's own error is below 2^-60 of r) and
   IV_LIBM_ULPS + 1 for tan (one more rounding in -1/tan). */
static double iv__trig_reduced(double x, int k)
{
    double rh, rl, s, c, t;
    int q = iv__reduce(x, &rh, &rl), odd = x < 0;
    s = sin(rh) + cos(rh) * rl;
    c = cos(rh) - sin(rh) * rl;
    if (k == 2) {
        t = q & 1 ? -c / s : s / c;
        return odd ? -t : t;
    }
    if (k == 1) q = (q + 1) & 3, odd = 0; /* cos x = sin(|x| + pi/2) */
    t = q & 1 ? c : s;
    if (q & 2) t = -t;
    return odd ? -t : t;
}
/* Outward steps for a libm-based value at a: one pair more where it came
   from iv__trig_reduced (its extra half ulp or ulp). */
static int iv__trig_steps(double a) { return fabs(a) < IV__REDUCE_MIN ? IV__LIBM_STEPS : IV__LIBM_STEPS + 2; }
static double iv__sin_any(double a) { return fabs(a) < IV__REDUCE_MIN ? sin(a) : iv__trig_reduced(a, 0); }
static double iv__cos_any(double a) { return fabs(a) < IV__REDUCE_MIN ? cos(a) : iv__trig_reduced(a, 1); }
static double iv__tan_any(double a) { return fabs(a) < IV__REDUCE_MIN ? tan(a) : iv__trig_reduced(a, 2); }

/* sin or cos at a double a, from its libm-based value v, stepped outward;
   exact at a = 0 (value_at_0: sin 0 = 0, cos 0 = 1). */
static iv_t iv__trig_point(double a, double v, double value_at_0)
{
    int n = iv__trig_steps(a);
    return a == 0 ? iv__raw(value_at_0, value_at_0) : iv__raw(iv__steps_down(v, n), iv__steps_up(v, n));
}
static iv_t iv__clamp_unit(iv_t y) { return iv__raw(iv__max(y.lo, -1.0), iv__min(y.hi, 1.0)); }

/* sin over [a, b] with b - a < pi: the image of the ends, plus +1 (-1)
   when cos = sin' changes sign from + to - (- to +) inside. cos is never 0
   at a double, so the signs are strict. */
static iv_t iv__sin_narrow(double a, double b)
{
    iv_t y = iv_hull(iv__trig_point(a, iv__sin_any(a), 0.0), iv__trig_point(b, iv__sin_any(b), 0.0));
    double ca = iv__cos_any(a), cb = iv__cos_any(b);
    if (ca > 0 && cb < 0) y.hi = 1.0;
    if (ca < 0 && cb > 0) y.lo = -1.0;
    return iv__clamp_unit(y);
}
/* cos over [a, b] with b - a < pi; cos' = -sin, and sin(a) = 0 only at
   a = 0, where the extremum is the end value itself. */
static iv_t iv__cos_narrow(double a, double b)
{
    iv_t y = iv_hull(iv__trig_point(a, iv__cos_any(a), 1.0), iv__trig_point(b, iv__cos_any(b), 1.0));
    double sa = iv__sin_any(a), sb = iv__sin_any(b);
    if (sa > 0 && sb < 0) y.lo = -1.0;
    if (sa < 0 && sb > 0) y.hi = 1.0;
    return iv__clamp_unit(y);
}

/* Shared by sin and cos: narrow intervals directly; widths in [3.14, 2pi)
   as three narrow pieces (no loop); wider ones (and infinite) give [-1,1]. */
static iv_t iv__periodic(iv_t x, iv_t (*narrow)(double, double))
{
    double w, m1, m2;
    if (iv_is_empty(x)) return iv_empty();
    w = x.hi - x.lo;
    if (w < IV__NARROW) return narrow(x.lo, x.hi);
    if (!(w < IV__FULL_PERIOD)) return iv__raw(-1.0, 1.0);
    /* each piece is about w/3 < 2.1 wide, below pi after the rounding of
       m1, m2 wherever doubles are at most 2 apart (|x| < 2^54). In
       [2^54, 2^55) they are 4 apart and w = 4: the cut points round back
       onto the ends, leaving a piece wider than pi, which may hold a
       maximum and a minimum that narrow() cannot see (the differences
       below are exact there) */
    m1 = iv__min(iv__max(x.lo + w / 3, x.lo), x.hi);
    m2 = iv__min(iv__max(x.hi - w / 3, m1), x.hi);
    if (!(m1 - x.lo < IV__NARROW && m2 - m1 < IV__NARROW && x.hi - m2 < IV__NARROW)) return iv__raw(-1.0, 1.0);
    return iv_hull(iv_hull(narrow(x.lo, m1), narrow(m1, m2)), narrow(m2, x.hi));
}

IV_DEF iv_t iv_sin(iv_t x) { return iv__periodic(x, iv__sin_narrow); }
IV_DEF iv_t iv_cos(iv_t x) { return iv__periodic(x, iv__cos_narrow); }

IV_DEF iv_t iv_tan(iv_t x)
{
    double ca, cb;
    if (iv_is_empty(x)) return iv_empty();
    if (!(x.hi - x.lo < IV__NARROW)) return iv_entire();
    /* poles are the zeros of cos, pi apart: at most one inside */
    ca = iv__cos_any(x.lo);
    cb = iv__cos_any(x.hi);
    if ((ca > 0) != (cb > 0)) return iv_entire();
    return iv__raw(x.lo == 0 ? 0.0 : iv__steps_down(iv__tan_any(x.lo), iv__trig_steps(x.lo)),
                   x.hi == 0 ? 0.0 : iv__steps_up(iv__tan_any(x.hi), iv__trig_steps(x.hi)));
}

/* pow at one corner (x >= 0), stepped outward; exact C conventions for the
   exact cases 1^y, x^0. */
static iv_t iv__pow_point(double x, double y)
{
    double p = pow(x, y);
    if (x == 1 || y == 0) return iv__raw(1.0, 1.0);
    if (x == 0 || x == HUGE_VAL || y == HUGE_VAL || y == -HUGE_VAL)
        return iv__raw(p, p); /* exact limits (0, 1 or inf) */
    return iv__raw(iv__max(0.0, iv__libm_down(p)), iv__libm_up(p));
}

/* x^y is monotone in x for fixed y and in y for fixed x (on x >= 0), so
   its range over a box is the hull of the four corners. */
IV_DEF iv_t iv_pow(iv_t x, iv_t y)
{
    iv_t r;
    if (iv_is_empty(x) || iv_is_empty(y) || x.hi < 0) return iv_empty();
    if (x.lo <= 0) x.lo = 0.0; /* also turns -0 into +0: pow(-0, -3) = -inf */
    if (x.hi == 0) x.hi = 0.0;
    r = iv_hull(iv_hull(iv__pow_point(x.lo, y.lo), iv__pow_point(x.lo, y.hi)),
                iv_hull(iv__pow_point(x.hi, y.lo), iv__pow_point(x.hi, y.hi)));
    /* pow(0, y) = 0 exactly only for y > 0: a corner 0^0 or 0^-y is handled
       by C's pow, and 0 * inf-type limits do not arise for x >= 0 */
    if (r.lo == HUGE_VAL) return iv_empty(); /* only 0^-y: no real value */
    return r;
}

/* ------------------------------------------------------------------------ */
/* pow_n: double-double power with a proven relative error bound            */
/* ------------------------------------------------------------------------ */

/* (ah + al)(bh + bl) as a normalised double-double. The product residual
   comes from fma, exact in any compilation; cross terms and the Fast2Sum
   renormalisation may be contracted by the compiler, which only changes
   errors of order u^2 |ab| that the bound below already covers. */
static void iv__dd_mul(double ah, double al, double bh, double bl, double *rh, double *rl)
{
    double p = ah * bh;
    double e = fma(ah, bh, -p);
    double s;
    e += ah * bl + al * bh;
    s = p + e;
    *rl = e - (s - p);
    *rh = s;
}
/* Keep the high part in [0.5, 1): exponents are tracked apart, so no
   intermediate overflows or underflows whatever n is. */
static void iv__dd_renorm(double *h, double *l, long long *ex)
{
    int k;
    *h = frexp(*h, &k);
    *l = ldexp(*l, -k);
    *ex += k;
}
/* Per double-double product the relative error is below 7u^2 = 2^-103.2
   (Joldes, Muller, Popescu 2017, DWTimesDW); we charge 2^-100 per
   operation, an 8x margin that also absorbs contraction effects. */
#define IV__DD_REL 7.888609052210118e-31 /* 2^-100 */
/* Relative error bound of a product whose factors carry relative errors
   ea and eb, formed with one more operation: (1+ea)(1+eb)(1+2^-100) - 1.
   Errors compound through the squarings (a square doubles its base's
   error), so after the square-and-multiply of x^n the bound grows like
   |n| 2^-100, not like the number of operations. The bound is itself
   computed in double, rounded to nearest: its own relative error (a few
   2^-53) is covered by the factor IV__DD_SLACK where it is used. */
static double iv__dd_err(double ea, double eb) { return ea + eb + ea * eb + IV__DD_REL * (1 + ea) * (1 + eb); }
#define IV__DD_SLACK 1.0000001

/* Bounds lo <= x^n <= hi for x > 0 finite, n != 0. Each is the correctly
   rounded bound or one double beyond it when the result is normal. */
static void iv__pown_bounds(double x, int n, double *lo, double *hi)
{
    double rh = 1.0, rl = 0.0, bh, bl = 0.0, s, l, err, dn, up;
    double er = 0.0, eb = 0.0; /* relative error bounds of r and of the base */
    long long re = 0, be;
    unsigned long k = n < 0 ? 0ul - (unsigned long)n : (unsigned long)n;
    int exact = 1, e0;
    bh = frexp(x, &e0);
    be = e0;
    while (k) {
        if (k & 1ul) {
            iv__dd_mul(rh, rl, bh, bl, &rh, &rl);
            re += be;
            iv__dd_renorm(&rh, &rl, &re);
            exact &= rl == 0;
            er = iv__dd_err(er, eb);
        }
        k >>= 1;
        if (k) {
            iv__dd_mul(bh, bl, bh, bl, &bh, &bl);
            be *= 2;
            iv__dd_renorm(&bh, &bl, &be);
            exact &= bl == 0;
            eb = iv__dd_err(eb, eb);
        }
    }
    if (n < 0) {
        /* 1/(rh + rl): Newton correction from the exact residual 1 - q rh;
           1/(v(1+e)) = (1/v)(1 - e/(1+e)), then two operations */
        double q = 1.0 / rh;
        double res = fma(-q, rh, 1.0) - q * rl;
        double corr = res * q;
        exact &= res == 0;
        rh = q + corr;
        rl = corr - (rh - q);
        re = -re;
        er = iv__dd_err(iv__dd_err(er / (1 - er), 0.0), 0.0);
    }
    s = rh + rl;
    l = rl - (s - rh);
    err = iv__dd_err(er, 0.0) * IV__DD_SLACK * s;
    /* s is within half an ulp of the value; l (and the error bound) say on
       which side the value lies when that is certain */
    dn = exact && l == 0 ? s : l > err ? s : iv__down(s);
    up = exact && l == 0 ? s : -l > err ? s : iv__up(s);
    if (re > 2200) re = 2200;
    if (re < -2200) re = -2200;
    /* scaling is exact unless it overflowed or went subnormal, and then it
       rounded to nearest, even up to DBL_MIN itself (a tie just below it).
       Scaling back is exact, so it shows which way each end moved. */
    {
        double ds = ldexp(dn, (int)re), us = ldexp(up, (int)re);
        if (ds == HUGE_VAL || ldexp(ds, -(int)re) > dn) ds = iv__down(ds);
        if (us != HUGE_VAL && ldexp(us, -(int)re) < up) us = iv__up(us);
        dn = ds;
        up = us;
    }
    *lo = iv__max(dn, 0.0);
    *hi = up;
}

/* Bounds of t^n for one endpoint t >= 0 (t may be 0 or inf). */
static iv_t iv__pown_mag(double t, int n)
{
    double lo, hi;
    if (t == 0) return n > 0 ? iv__raw(0.0, 0.0) : iv__raw(HUGE_VAL, HUGE_VAL);
    if (t == HUGE_VAL) return n > 0 ? iv__raw(HUGE_VAL, HUGE_VAL) : iv__raw(0.0, 0.0);
    if (t == 1) return iv__raw(1.0, 1.0);
    iv__pown_bounds(t, n, &lo, &hi);
    return iv__raw(lo, hi);
}

IV_DEF iv_t iv_pow_n(iv_t x, int n)
{
    iv_t a, b;
    if (iv_is_empty(x)) return iv_empty();
    if (n == 0) return iv__raw(1.0, 1.0);
    if (n == 1) return x;
    if (n % 2 == 0) {
        iv_t m = iv_abs(x); /* |x|^n, monotone in |x| */
        a = iv__pown_mag(m.lo, n);
        b = iv__pown_mag(m.hi, n);
        return n > 0 ? iv_make(a.lo, b.hi) : iv_make(b.lo, a.hi);
    }
    if (n > 0) { /* odd: increasing on the whole line */
        double lo = x.lo >= 0 ? iv__pown_mag(x.lo, n).lo : -iv__pown_mag(-x.lo, n).hi;
        double hi = x.hi >= 0 ? iv__pown_mag(x.hi, n).hi : -iv__pown_mag(-x.hi, n).lo;
        return iv__raw(lo, hi);
    }
    /* odd negative: decreasing on each side of the pole at 0 */
    if (x.lo > 0) return iv__raw(iv__pown_mag(x.hi, n).lo, iv__pown_mag(x.lo, n).hi);
    if (x.hi < 0) return iv__raw(-iv__pown_mag(-x.hi, n).hi, -iv__pown_mag(-x.lo, n).lo);
    if (x.lo == 0 && x.hi > 0) return iv__raw(iv__pown_mag(x.hi, n).lo, HUGE_VAL);
    if (x.hi == 0 && x.lo < 0) return iv__raw(-HUGE_VAL, -iv__pown_mag(-x.lo, n).lo);
    if (x.lo == 0 && x.hi == 0) return iv_empty();
    return iv_entire();
}

/* ------------------------------------------------------------------------ */
/* hypot                                                                    */
/* ------------------------------------------------------------------------ */

/* Scale a bound by 2^k: exact unless the result overflows or is subnormal,
   in which case it is stepped outward once more. */
static double iv__scale_down(double v, int k)
{
    double r = ldexp(v, k);
    return (r == HUGE_VAL || (r != 0 && fabs(r) < 2.2250738585072014e-308) || (r == 0 && v != 0)) ? iv__down(r) : r;
}
static double iv__scale_up(double v, int k)
{
    double r = ldexp(v, k);
    return ((r != 0 && fabs(r) < 2.2250738585072014e-308) || (r == 0 && v != 0)) ? iv__up(r) : r;
}

/* Is sqrt(a^2 + b^2) surely at most 1 - 2^-53 (DBL_MAX 2^-1024), for
   a, b in [0, 1]? a^2 + b^2 - (1 - 2^-53)^2 from exact squares (fma) and
   an exact sum (TwoSum; s - 1 is exact for s in [0.5, 2]), its six small
   terms added with an error below 2^-100: their sum must lie below
   -2^-99. */
static int iv__hypot_below_one(double a, double b)
{
    double p1 = a * a, e1 = fma(a, a, -p1), p2 = b * b, e2 = fma(b, b, -p2);
    double s = p1 + p2, v = s - p1, ts = (p1 - (s - v)) + (p2 - v);
    return s >= 0.5 && (s - 1.0) + ts + e1 + e2 + 0x1p-52 - 0x1p-106 < -0x1p-99;
}

/* Enclosure of hypot(a, b) for a, b >= 0. */
static iv_t iv__hypot_point(double a, double b)
{
    double m = iv__max(a, b), as, bs, hi;
    iv_t ai, bi, s;
    int k;
    if (m == HUGE_VAL) return iv__raw(HUGE_VAL, HUGE_VAL);
    if (a == 0 || b == 0) return iv__raw(m, m); /* exact, 0 included */
    (void)frexp(m, &k);
    as = ldexp(a, -k);
    bs = ldexp(b, -k);
    /* the larger one scales exactly into [0.5, 1); the smaller may lose bits
       if it falls into the subnormal range */
    ai = fabs(as) < 2.2250738585072014e-308 ? iv__raw(iv__max(0.0, iv__down(as)), iv__up(as)) : iv__raw(as, as);
    bi = fabs(bs) < 2.2250738585072014e-308 ? iv__raw(iv__max(0.0, iv__down(bs)), iv__up(bs)) : iv__raw(bs, bs);
    if (as == 0 && a == 0) ai = iv__raw(0.0, 0.0);
    if (bs == 0 && b == 0) bi = iv__raw(0.0, 0.0);
    s = iv_sqrt(iv_add(iv_sqr(ai), iv_sqr(bi)));
    /* the three stepped operations can take s.hi to 1 when the value lies
       within a few ulps below DBL_MAX: scaled, that would be inf */
    hi = iv__scale_up(s.hi, k);
    if (hi == HUGE_VAL && iv__hypot_below_one(ai.hi, bi.hi)) hi = DBL_MAX;
    return iv__raw(iv__max(0.0, iv__scale_down(s.lo, k)), hi);
}

IV_DEF iv_t iv_hypot(iv_t x, iv_t y)
{
    iv_t ax, ay;
    if (iv_is_empty(x) || iv_is_empty(y)) return iv_empty();
    ax = iv_abs(x);
    ay = iv_abs(y);
    return iv__raw(iv__hypot_point(ax.lo, ay.lo).lo, iv__hypot_point(ax.hi, ay.hi).hi);
}

#ifndef IV_NO_AFFINE
/* ------------------------------------------------------------------------ */
/* Reduced affine arithmetic                                                */
/* ------------------------------------------------------------------------ */

/* x + K for an interval constant K (its radius goes into e). */
static iv_affine_t iv__aff_add_iv(iv_affine_t x, iv_t k)
{
    double m, r, c;
    if (iv_affine_is_empty(x) || iv_is_empty(k)) return iv__aff_empty();
    if (k.lo == -HUGE_VAL || k.hi == HUGE_VAL) return iv__aff_entire();
    m = iv_mid(k);
    r = iv__max(k.hi - m, m - k.lo);
    c = x.c + m;
    return iv__aff_finish(c, x.t, iv__aff_radius(x.e + r + iv__aff_rnd(fabs(c))));
}

/* The first-order Taylor form of f on the form x whose values of interest
   lie in dom = range(x) ∩ dom(f):
     f(x) = f(c) + a (x - c) + (f'(c) - a)(x - c) + f''(xi)/2 (x - c)^2,
   with c in dom, a a double near f'(c), |x - c| <= r. Everything but
   a (x - c) is enclosed by interval arithmetic into K and added as a
   constant range. fc, d1 enclose f(c), f'(c); d2 encloses f'' on dom; img
   encloses f(dom) and is used when the form would be wider. */
static iv_affine_t iv__aff_taylor(iv_affine_t x, iv_t dom, double c, iv_t fc, iv_t d1, iv_t d2, iv_t img)
{
    double r, a, w;
    iv_t k, rem;
    iv_affine_t z;
    if (iv_is_empty(img)) return iv__aff_empty();
    r = iv__up(iv__max(dom.hi - c, c - dom.lo));
    a = iv_mid(d1);
    w = iv__up(iv__max(d1.hi - a, a - d1.lo));
    rem = iv_mul(iv__raw(0.0, iv__up(r * r)), iv_mul_d(d2, 0.5));
    k = iv_add(iv_add(fc, rem), iv_mul_d(iv__raw(-r, r), w));
    if (iv_is_empty(k) || !(iv_width(k) < iv_width(img)) || !(a - a == 0))
        return iv_affine_from_iv(img);
    z = iv__aff_add_iv(iv_affine_mul_d(iv_affine_sub_d(x, c), a), k);
    return z;
}

/* The range of x clipped to [lo, hi] and an expansion point inside it. */
static int iv__aff_domain(iv_affine_t x, double lo, double hi, iv_t *dom, double *c)
{
    *dom = iv_intersect(iv_from_affine(x), iv__raw(lo, hi));
    if (iv_is_empty(*dom)) return 0;
    *c = iv__min(iv__max(x.c, dom->lo), dom->hi);
    if (!(*c - *c == 0)) *c = iv_mid(*dom);
    return 1;
}

/* Linearisations of convex or concave f (Stolfi & de Figueiredo 1997,
   "Self-validated numerical methods and applications", section 3.4 on
   non-affine operations; Chebyshev and min-range approximations).
   f(x) = alpha x + g(x) with g = f - alpha x; g's range over dom = [a, b]
   goes into the error term. For every double alpha this is sound when g
   is enclosed rigorously, so alpha and the tangent point u need no
   rigour. With s g convex (s = +1 for convex f, -1 for concave):
     the far side of g is at an end of dom:  s g <= max(s g(a), s g(b));
     the near side is bounded by the tangent at any u in dom:
                      s g(x) >= s (g(u) + g'(u)(x - u)),
   each evaluated in interval arithmetic. Chebyshev: alpha the secant slope
   (f(b) - f(a))/(b - a) and u where f'(u) = alpha, which minimises the new
   error term (the best linear approximation in the max norm). Min-range:
   alpha = f' at the end of dom where |f'| is smaller, u that end, which
   makes the result's range that of f itself. */
enum { IV__F_EXP, IV__F_LOG, IV__F_SQRT, IV__F_RECIP, IV__F_POWN, IV__F_ATAN, IV__F_SIN, IV__F_COS, IV__F_TAN };
enum { IV__LIN_TAYLOR, IV__LIN_CHEBYSHEV, IV__LIN_MINRANGE, IV__LIN_AUTO };
/* IV__LIN_AUTO (the default): the slope closest to Chebyshev's, among
   Chebyshev, halfway to min-range and min-range, whose result's range is
   at most IV__LIN_RANGE_RATIO times the width of f's image. Chebyshev
   keeps the most correlation for later cancellation (f(t) - k t), min-range
   the narrowest range (an operation whose own range matters, as in a
   distance sqrt(x^2+y^2+z^2) - r). Measured on both kinds
   (bench_interval_surfaces, docs/interval.md), 1.1 is tighter than the
   Taylor form almost everywhere and never far behind the better of the two
   pure methods; 1.5 and above lost up to 30% on the blob surface. A ratio
   of widths: independent of scale. */
#define IV__LIN_RANGE_RATIO 1.1

/* x^(n - k) for k = 1, 2 (the derivatives of x^n), also where n - k is
   below INT_MIN: then as x^(n + 2) x^(-2 - k), whose enclosures' product
   encloses it. */
static iv_t iv__pown_less(iv_t x, int n, int k)
{
    return n >= INT_MIN + k ? iv_pow_n(x, n - k) : iv_mul(iv_pow_n(x, n + 2), iv_pow_n(x, -2 - k));
}

/* f (deriv = 0) or f' (deriv = 1) over x, rigorously. */
static iv_t iv__aff_fn(int f, int n, iv_t x, int deriv)
{
    switch (f) {
    case IV__F_EXP: return iv_exp(x);
    case IV__F_LOG: return deriv ? iv_recip(x) : iv_log(x);
    case IV__F_SQRT: return deriv ? iv_recip(iv_mul_d(iv_sqrt(x), 2.0)) : iv_sqrt(x);
    case IV__F_RECIP: return deriv ? iv_neg(iv_recip(iv_sqr(x))) : iv_recip(x);
    case IV__F_POWN: return deriv ? iv_mul_d(iv__pown_less(x, n, 1), (double)n) : iv_pow_n(x, n);
    case IV__F_SIN: return deriv ? iv_cos(x) : iv_sin(x);
    case IV__F_COS: return deriv ? iv_neg(iv_sin(x)) : iv_cos(x);
    case IV__F_TAN: return deriv ? iv_add_d(iv_sqr(iv_tan(x)), 1.0) : iv_tan(x);
    default: return deriv ? iv_recip(iv_add_d(iv_sqr(x), 1.0)) : iv_atan(x);
    }
}

/* +1 when f is convex on dom, -1 when concave, 0 when neither is known. */
static int iv__aff_curvature(int f, int n, iv_t dom)
{
    int side = dom.lo >= 0 ? 1 : dom.hi <= 0 ? -1 : 0;
    switch (f) {
    case IV__F_EXP: return 1;
    case IV__F_LOG: case IV__F_SQRT: return -1;
    case IV__F_RECIP: return side;
    /* f'' = n (n - 1) x^(n-2) with n (n - 1) > 0 for n other than 0, 1 */
    case IV__F_POWN: return n % 2 == 0 ? 1 : side;
    case IV__F_SIN: case IV__F_COS: case IV__F_TAN: {
        /* f'' = -f (sin, cos), 2 f (1 + f^2) (tan): the sign of f over dom,
           proved by the enclosure (a range around a pole of tan: none) */
        iv_t v = iv__aff_fn(f, n, dom, 0);
        int sg = v.lo >= 0 ? 1 : v.hi <= 0 ? -1 : 0;
        return f == IV__F_TAN ? sg : -sg;
    }
    default: return -side; /* atan'' = -2x / (1 + x^2)^2 */
    }
}

/* sin' = cos and cos' = -sin take alpha at +-a0 (+ pi) plus whole turns,
   tan' = 1 + tan^2 at +-atan(sqrt(alpha - 1)) plus multiples of pi: the
   solution nearest dom's middle, clamped into dom (any u in dom is sound,
   iv__aff_linearise; a good one is tighter). */
static double iv__aff_trig_tangent(int f, double alpha, iv_t dom)
{
    const double pi = 3.141592653589793;
    double a = iv__min(iv__max(alpha, -1.0), 1.0), m = iv_mid(dom), best = m, bd = HUGE_VAL, cand[2], period = 2 * pi;
    int i;
    if (f == IV__F_SIN) cand[0] = acos(a), cand[1] = -acos(a);
    else if (f == IV__F_COS) cand[0] = asin(-a), cand[1] = pi - asin(-a);
    else cand[0] = atan(sqrt(iv__max(alpha - 1.0, 0.0))), cand[1] = -cand[0], period = pi;
    for (i = 0; i < 2; i++) {
        double u = cand[i] + period * floor((m - cand[i]) / period + 0.5);
        if (fabs(u - m) < bd) bd = fabs(u - m), best = u;
    }
    return iv__min(iv__max(best, dom.lo), dom.hi);
}

/* A double u in dom with f'(u) close to alpha (the Chebyshev tangent). */
static double iv__aff_tangent_point(int f, int n, double alpha, iv_t dom)
{
    double side = dom.lo >= 0 ? 1.0 : -1.0, u;
    switch (f) {
    case IV__F_EXP: u = log(alpha); break;
    case IV__F_LOG: u = 1.0 / alpha; break;
    case IV__F_SQRT: u = 0.25 / (alpha * alpha); break;
    case IV__F_RECIP: u = side * sqrt(-1.0 / alpha); break;
    case IV__F_POWN: u = side * pow(fabs(alpha / (double)n), 1.0 / ((double)n - 1.0)); break;
    case IV__F_SIN: case IV__F_COS: case IV__F_TAN: return iv__aff_trig_tangent(f, alpha, dom);
    default: u = side * sqrt(1.0 / alpha - 1.0); break;
    }
    if (!(u == u)) u = iv_mid(dom);
    return iv__min(iv__max(u, dom.lo), dom.hi);
}

/* The linearisation above with the slope w of the way from min-range's
   (w = 0) to Chebyshev's (w = 1); the empty form when it does not apply
   (unknown curvature, unbounded dom or values), so that the caller falls
   back to the Taylor form. */
static iv_affine_t iv__aff_linearise(iv_affine_t x, iv_t dom, int f, int n, double w)
{
    int s = iv__aff_curvature(f, n, dom);
    iv_t fa, fb, pa, pb, pu, ga, gb, t, g;
    double alpha, u, da, db;
    if (s == 0 || !(dom.lo > -HUGE_VAL && dom.hi < HUGE_VAL)) return iv__aff_empty();
    pa = iv__raw(dom.lo, dom.lo);
    pb = iv__raw(dom.hi, dom.hi);
    fa = iv__aff_fn(f, n, pa, 0);
    fb = iv__aff_fn(f, n, pb, 0);
    da = iv_mid(iv__aff_fn(f, n, pa, 1));
    db = iv_mid(iv__aff_fn(f, n, pb, 1));
    /* min-range slope and end */
    alpha = fabs(da) <= fabs(db) ? da : db;
    u = fabs(da) <= fabs(db) ? dom.lo : dom.hi;
    if (w > 0 && dom.hi > dom.lo) {
        /* toward the Chebyshev (secant) slope by the weight w */
        alpha += w * ((iv_mid(fb) - iv_mid(fa)) / (dom.hi - dom.lo) - alpha);
        u = iv__aff_tangent_point(f, n, alpha, dom);
    }
    if (!(alpha - alpha == 0)) return iv__aff_empty();
    pu = iv__raw(u, u);
    /* g = f - alpha x at both ends, and its tangent at u over dom */
    ga = iv_sub(fa, iv_mul_d(pa, alpha));
    gb = iv_sub(fb, iv_mul_d(pb, alpha));
    t = iv_add(iv_sub(iv__aff_fn(f, n, pu, 0), iv_mul_d(pu, alpha)),
               iv_mul(iv_sub_d(iv__aff_fn(f, n, pu, 1), alpha), iv_sub_d(dom, u)));
    g = s > 0 ? iv__raw(t.lo, iv__max(ga.hi, gb.hi)) : iv__raw(iv__min(ga.lo, gb.lo), t.hi);
    /* an error term as wide as f's image makes the linear part useless */
    if (!(g.lo <= g.hi) || !(g.lo > -HUGE_VAL && g.hi < HUGE_VAL) || !(iv_width(g) < iv_width(iv_hull(fa, fb))))
        return iv__aff_empty();
    return iv__aff_add_iv(iv_affine_mul_d(x, alpha), g);
}

/* The Taylor form for each f (f'' enclosed over dom). */
static iv_affine_t iv__aff_taylor_fn(iv_affine_t x, iv_t dom, double c, int f, int n)
{
    iv_t cc = iv__raw(c, c), d2;
    switch (f) {
    case IV__F_EXP: d2 = iv_exp(dom); break;
    case IV__F_LOG: d2 = iv_neg(iv_recip(iv_sqr(dom))); break;
    /* -1/(4 x sqrt x) */
    case IV__F_SQRT: d2 = iv_neg(iv_recip(iv_mul_d(iv_mul(dom, iv_sqrt(dom)), 4.0))); break;
    case IV__F_RECIP: d2 = iv_mul_d(iv_pow_n(dom, -3), 2.0); break;
    /* n (n - 1) is not a double beyond |n| ~ 2^26.5: two exact factors */
    case IV__F_POWN: d2 = iv_mul_d(iv_mul_d(iv__pown_less(dom, n, 2), (double)n), (double)n - 1.0); break;
    case IV__F_SIN: case IV__F_COS: d2 = iv_neg(iv__aff_fn(f, n, dom, 0)); break; /* f'' = -f */
    case IV__F_TAN: { /* 2 tan (1 + tan^2) */
        iv_t td = iv_tan(dom);
        d2 = iv_mul_d(iv_mul(td, iv_add_d(iv_sqr(td), 1.0)), 2.0);
        break;
    }
    /* -2x / (1 + x^2)^2 */
    default: d2 = iv_div(iv_mul_d(dom, -2.0), iv_sqr(iv_add_d(iv_sqr(dom), 1.0))); break;
    }
    return iv__aff_taylor(x, dom, c, iv__aff_fn(f, n, cc, 0), iv__aff_fn(f, n, cc, 1), d2, iv__aff_fn(f, n, dom, 0));
}

/* The non-affine operation f on x by a given method (the tests and the
   bench compare methods through this; the public functions use
   IV__LIN_DEFAULT). dom = range(x) ∩ dom(f). A range that holds a pole
   gives the interval image; a range touching 0 for log and sqrt (f'
   unbounded there: no tangent) takes the Taylor form, and so does any case
   the linearisation leaves out; that form falls back to the interval image
   when its error term would be wider. */
#define IV__LIN_DEFAULT IV__LIN_AUTO
static iv_affine_t iv__aff_unary(iv_affine_t x, int f, int n, int method)
{
    iv_t dom;
    double c;
    iv_affine_t z;
    int root = f == IV__F_LOG || f == IV__F_SQRT;
    if (iv_affine_is_empty(x) || !iv__aff_domain(x, root ? 0.0 : -HUGE_VAL, HUGE_VAL, &dom, &c)) return iv__aff_empty();
    if (root && c == 0) return iv_affine_from_iv(iv__aff_fn(f, n, dom, 0));
    if ((f == IV__F_RECIP || (f == IV__F_POWN && n < 0)) && dom.lo <= 0 && dom.hi >= 0)
        return iv_affine_from_iv(iv__aff_fn(f, n, dom, 0));
    if (root && dom.lo == 0) method = IV__LIN_TAYLOR;
    if (method == IV__LIN_TAYLOR) z = iv__aff_empty();
    else if (method != IV__LIN_AUTO) z = iv__aff_linearise(x, dom, f, n, method == IV__LIN_CHEBYSHEV ? 1.0 : 0.0);
    else {
        /* the slope closest to Chebyshev's whose range stays within
           IV__LIN_RANGE_RATIO of f's image: Chebyshev, halfway, min-range */
        double lim = IV__LIN_RANGE_RATIO * iv_width(iv__aff_fn(f, n, dom, 0)), w;
        for (w = 1.0, z = iv__aff_empty(); w >= 0; w -= 0.5) {
            z = iv__aff_linearise(x, dom, f, n, w);
            if (iv_affine_is_empty(z) || iv_width(iv_from_affine(z)) <= lim) break;
        }
    }
    return iv_affine_is_empty(z) ? iv__aff_taylor_fn(x, dom, c, f, n) : z;
}

IV_DEF iv_affine_t iv_affine_exp(iv_affine_t x) { return iv__aff_unary(x, IV__F_EXP, 0, IV__LIN_DEFAULT); }
IV_DEF iv_affine_t iv_affine_log(iv_affine_t x) { return iv__aff_unary(x, IV__F_LOG, 0, IV__LIN_DEFAULT); }
IV_DEF iv_affine_t iv_affine_sqrt(iv_affine_t x) { return iv__aff_nonneg(iv__aff_unary(x, IV__F_SQRT, 0, IV__LIN_DEFAULT), 0); }
IV_DEF iv_affine_t iv_affine_recip(iv_affine_t x) { return iv__aff_unary(x, IV__F_RECIP, -1, IV__LIN_DEFAULT); }
IV_DEF iv_affine_t iv_affine_atan(iv_affine_t x) { return iv__aff_unary(x, IV__F_ATAN, 0, IV__LIN_DEFAULT); }

IV_DEF iv_affine_t iv_affine_div(iv_affine_t x, iv_affine_t y) { return iv_affine_mul(x, iv_affine_recip(y)); }
IV_DEF iv_affine_t iv_affine_div_d(iv_affine_t x, double d) { return iv_affine_div(x, iv_affine_const(d)); }

IV_DEF iv_affine_t iv_affine_pow_n(iv_affine_t x, int n)
{
    if (iv_affine_is_empty(x)) return iv__aff_empty();
    if (n == 0) return iv_affine_const(1.0);
    if (n == 1) return x;
    if (n == 2) return iv_affine_sqr(x); /* already the Chebyshev form of x^2 */
    if (n == -1) return iv_affine_recip(x);
    if (n % 2 == 0) return iv__aff_nonneg(iv__aff_unary(x, IV__F_POWN, n, IV__LIN_DEFAULT), 0);
    return iv__aff_unary(x, IV__F_POWN, n, IV__LIN_DEFAULT);
}

/* sin and cos: the linearisation where f has no inflection over the range
   (f'' = -f keeps its sign), the Taylor form elsewhere. */
IV_DEF iv_affine_t iv_affine_sin(iv_affine_t x) { return iv__aff_unary(x, IV__F_SIN, 0, IV__LIN_DEFAULT); }
IV_DEF iv_affine_t iv_affine_cos(iv_affine_t x) { return iv__aff_unary(x, IV__F_COS, 0, IV__LIN_DEFAULT); }

/* tan likewise on a pole-free range where tan keeps its sign; across a
   pole the Taylor form gives the interval image (entire). */
IV_DEF iv_affine_t iv_affine_tan(iv_affine_t x) { return iv__aff_unary(x, IV__F_TAN, 0, IV__LIN_DEFAULT); }

/* |x| across 0: convex, so the Chebyshev form alpha x + g with alpha the
   secant slope (b + a)/(b - a) of [a, b] (clamped to [-1, 1], where
   |x| - alpha x >= 0 exactly) and g in [0, max(g(a), g(b))], kept when
   its range stays within IV__LIN_RANGE_RATIO of the image [0, max(-a,
   b)] (ranges nearly one-sided: the correlation survives, for min, max
   and cancellations later); else the image (until 2026-12-06 always the
   image, found by the issue audit). */
IV_DEF iv_affine_t iv_affine_abs(iv_affine_t x)
{
    iv_t r = iv_from_affine(x), ga, gb, img;
    iv_affine_t z;
    double alpha;
    if (iv_affine_is_empty(x)) return iv__aff_empty();
    if (r.lo >= 0) return x;
    if (r.hi <= 0) return iv_affine_neg(x);
    img = iv_abs(r);
    if (!(r.lo > -HUGE_VAL && r.hi < HUGE_VAL)) return iv_affine_from_iv(img);
    alpha = iv__min(iv__max((r.hi + r.lo) / (r.hi - r.lo), -1.0), 1.0);
    ga = iv_sub(iv__raw(-r.lo, -r.lo), iv_mul_d(iv__raw(r.lo, r.lo), alpha));
    gb = iv_sub(iv__raw(r.hi, r.hi), iv_mul_d(iv__raw(r.hi, r.hi), alpha));
    z = iv__aff_add_iv(iv_affine_mul_d(x, alpha), iv__raw(0.0, iv__max(ga.hi, gb.hi)));
    if (iv_affine_is_empty(z) || !(iv_width(iv_from_affine(z)) <= IV__LIN_RANGE_RATIO * iv_width(img)))
        z = iv_affine_from_iv(img);
    return iv__aff_nonneg(z, 0);
}

/* min(x, y) = (x + y - |x - y|) / 2, max with + |x - y|; when the ranges
   do not overlap the answer is one of the inputs. */
IV_DEF iv_affine_t iv_affine_min(iv_affine_t x, iv_affine_t y)
{
    iv_t rx = iv_from_affine(x), ry = iv_from_affine(y);
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv__aff_empty();
    if (rx.hi <= ry.lo) return x;
    if (ry.hi <= rx.lo) return y;
    return iv_affine_mul_d(iv_affine_sub(iv_affine_add(x, y), iv_affine_abs(iv_affine_sub(x, y))), 0.5);
}
IV_DEF iv_affine_t iv_affine_max(iv_affine_t x, iv_affine_t y)
{
    iv_t rx = iv_from_affine(x), ry = iv_from_affine(y);
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv__aff_empty();
    if (rx.hi <= ry.lo) return y;
    if (ry.hi <= rx.lo) return x;
    return iv_affine_mul_d(iv_affine_add(iv_affine_add(x, y), iv_affine_abs(iv_affine_sub(x, y))), 0.5);
}

/* x^y = exp(y log x) over x > 0; a range reaching 0 or below takes the
   interval iv_pow (its domain rule, x^y at x = 0 included). */
IV_DEF iv_affine_t iv_affine_pow(iv_affine_t x, iv_affine_t y)
{
    iv_t rx = iv_from_affine(x);
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv__aff_empty();
    if (rx.lo <= 0) return iv_affine_from_iv(iv_pow(rx, iv_from_affine(y)));
    return iv_affine_exp(iv_affine_mul(y, iv_affine_log(x)));
}

/* hypot >= 0, but where its range reaches 0 the form's would not stop
   there: the squares' rounding terms (IV__AFF_ABS) and sqrt's
   linearisation reach below 0, and so do the outward steps of any range
   that ends at 0. Such a form becomes c + c eps_x, c = hi/2 rounded up,
   whose range is [0, 2c] (iv_from_affine); it had no correlation worth
   keeping, being that wide. */
IV_DEF iv_affine_t iv_affine_hypot(iv_affine_t x, iv_affine_t y)
{
    iv_affine_t s;
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv__aff_empty();
    /* hypot(0, 0) is 0 exactly; through the squares it was a range of 1e-158 */
    if (x.c == 0 && x.t == 0 && x.e == 0 && y.c == 0 && y.t == 0 && y.e == 0) return iv_affine_const(0.0);
    s = iv_affine_sqrt(iv_affine_add(iv_affine_sqr(x), iv_affine_sqr(y)));
    /* squares overflow long before hypot does: fall back to the interval */
    if (s.e == HUGE_VAL) s = iv_affine_from_iv(iv_hypot(iv_from_affine(x), iv_from_affine(y)));
    return iv__aff_nonneg(s, 1);
}
#endif /* IV_NO_AFFINE */

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
