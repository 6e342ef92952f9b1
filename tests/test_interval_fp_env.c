/* tests/test_interval_fp_env.c — interval.h and the host's floating-point
   environment (THE GUARANTEE in the header): iv_fp_env_ok() sees
   flush-to-zero, denormals-are-zero and other rounding modes;
   iv_fp_env_enter() sets the environment the guarantee assumes and
   iv_fp_env_leave() gives the host its own back, bit for bit; inside,
   operations on tiny operands under a host that had FTZ and DAZ on
   contain the __float128 truth, which without it they miss. */
#define IV_IMPLEMENTATION
#include "test_interval_gen.h"
#include <fenv.h>
#if defined(__SSE2__)
#  include <xmmintrin.h>
#  define FTZ_DAZ 0x8040u
#endif

static void default_environment_is_ok(void)
{
    iv_fp_env_t e;
    T_INT_EQ(iv_fp_env_ok(), 1);
    e = iv_fp_env_enter();
    T_INT_EQ(e.changed, 0);
    T_INT_EQ(iv_fp_env_ok(), 1);
    iv_fp_env_leave(e);
    T_INT_EQ(iv_fp_env_ok(), 1);
}

static void rounding_mode_seen_set_and_restored(void)
{
    static const int modes[3] = {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO};
    int i;
    for (i = 0; i < 3; i++) {
        iv_fp_env_t e;
        iv_t z;
        T_INT_EQ(fesetround(modes[i]), 0);
        T_INT_EQ(iv_fp_env_ok(), 0);
        e = iv_fp_env_enter();
        T_INT_EQ(e.changed, 1);
        T_INT_EQ(iv_fp_env_ok(), 1);
#ifdef FTZ_DAZ
        T_INT_EQ(_mm_getcsr() & 0x6000u, 0); /* SSE's rounding (fegetround reads the x87 unit's) */
#else
        T_INT_EQ(fegetround(), FE_TONEAREST);
#endif
        /* inside: 1/3 enclosed with its round-to-nearest ends one step out */
        z = iv_div(iv_point(1), iv_point(3));
        T_CHECK(ig_in(z, (q_t)1 / 3) && z.lo < z.hi);
        iv_fp_env_leave(e);
        T_INT_EQ(fegetround(), modes[i]);
    }
    fesetround(FE_TONEAREST);
}

#ifdef FTZ_DAZ
/* One operation, out of line: compilers may move arithmetic across an
   MXCSR write, not across a call. */
__attribute__((noinline)) static iv_t one_op(int op, iv_t x, iv_t y)
{
    return op == 0 ? iv_mul(x, y) : op == 1 ? iv_div(x, y) : op == 2 ? iv_sqr(x) : iv_add(x, y);
}

/* Random products, quotients, squares and sums of operands between 1e-320
   and 1e-150 (and their negatives), under a host with FTZ and DAZ on:
   inside enter/leave every enclosure holds the __float128 value; outside
   the same operations miss it (the hazard the header states). */
static void tiny_operands_under_ftz_daz(void)
{
    t_rng_t g = {2026};
    unsigned host = _mm_getcsr() | FTZ_DAZ;
    long n = t_count(200000), i, miss_inside = 0, miss_outside = 0;
    for (i = 0; i < n; i++) {
        double a = (t_rng_unit(&g) < 0.5 ? -1 : 1) * pow(10.0, t_rng_range(&g, -320, -150));
        double b = (t_rng_unit(&g) < 0.5 ? -1 : 1) * pow(10.0, t_rng_range(&g, -320, 0));
        int op = (int)(i % 4), pass;
        q_t want = op == 0 ? (q_t)a * b : op == 1 ? (q_t)a / b : op == 2 ? (q_t)a * a : (q_t)a + b;
        for (pass = 0; pass < 2; pass++) {
            iv_fp_env_t e;
            iv_t x = iv_point(a), y = iv_point(b), z;
            _mm_setcsr(host);
            if (pass == 0) e = iv_fp_env_enter();
            z = one_op(op, x, y);
            if (pass == 0) {
                iv_fp_env_leave(e);
                if (_mm_getcsr() != host) { T_FAIL("the host's MXCSR %#x not restored (%#x)", host, _mm_getcsr()); break; }
            }
            _mm_setcsr(host & ~FTZ_DAZ);
            if (!ig_in(z, want)) {
                if (pass == 0 && miss_inside++ < 5)
                    T_FAIL("op %d of %.17g and %.17g: [%.17g, %.17g] misses the exact value", op, a, b, z.lo, z.hi);
                if (pass == 1) miss_outside++;
            }
        }
    }
    _mm_setcsr(host & ~FTZ_DAZ);
    T_INT_EQ(miss_inside, 0);
    T_GT(miss_outside, n / 100); /* the test sees the hazard it guards against */
}

static void ftz_daz_seen_and_restored(void)
{
    unsigned base = _mm_getcsr(), bits[3] = {0x8000u, 0x0040u, FTZ_DAZ};
    int i;
    for (i = 0; i < 3; i++) {
        iv_fp_env_t e;
        _mm_setcsr(base | bits[i]);
        T_INT_EQ(iv_fp_env_ok(), 0);
        e = iv_fp_env_enter();
        T_INT_EQ(iv_fp_env_ok(), 1);
        T_INT_EQ(_mm_getcsr() & FTZ_DAZ, 0);
        iv_fp_env_leave(e);
        T_INT_EQ(_mm_getcsr(), base | bits[i]);
    }
    _mm_setcsr(base);
}

/* A host that unmasks floating-point exceptions (a debug build's
   feenableexcept(FE_INVALID)): the method makes NaN and inf on purpose in
   rare cases (iv_mul([1e300], [1e300]) overflows, the step turns its
   lower end into NaN to reach the clamp), which then trapped with SIGFPE
   while iv_fp_env_ok() said 1 (found by review, 2026-12-06). Now it says
   0, enter masks them, the product is [DBL_MAX, inf] without a trap, and
   leave restores the host's bits. */
static __attribute__((noinline)) iv_t square_of(volatile double *x) { return iv_mul(iv_point(*x), iv_point(*x)); }
static void unmasked_exceptions_seen_and_masked(void)
{
    volatile double big = 1e300;
    unsigned base = _mm_getcsr(), bits[3] = {0x0080u, 0x0200u, 0x1F80u};
    int i;
    for (i = 0; i < 3; i++) {
        iv_fp_env_t e;
        unsigned host = base & ~bits[i];
        iv_t z;
        _mm_setcsr(host);
        T_INT_EQ(iv_fp_env_ok(), 0);
        e = iv_fp_env_enter();
        T_INT_EQ(iv_fp_env_ok(), 1);
        z = square_of(&big); /* not inlined: its arithmetic stays between enter and leave */
        iv_fp_env_leave(e);
        T_INT_EQ(_mm_getcsr(), host);
        _mm_setcsr(base);
        T_EQ(z.lo, 1.7976931348623157e308);
        T_EQ(z.hi, HUGE_VAL);
    }
}
#endif

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(default_environment_is_ok), T_CASE(rounding_mode_seen_set_and_restored),
#ifdef FTZ_DAZ
        T_CASE(ftz_daz_seen_and_restored), T_CASE(tiny_operands_under_ftz_daz), T_CASE(unmasked_exceptions_seen_and_masked),
#endif
    };
    return T_RUN(argc, argv, cases);
}
