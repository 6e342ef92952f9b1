/* Unit tests of interval.h: construction, bad input, division cases, and
   the tightness of + - * / sqrt sqr against the __float128 exact result. */
#define IV_IMPLEMENTATION
#include "test_interval_gen.h"

static void bad_input_is_empty(void)
{
    T_CHECK(iv_is_empty(iv_make(NAN, 1)));
    T_CHECK(iv_is_empty(iv_make(0, NAN)));
    T_CHECK(iv_is_empty(iv_make(2, 1)));
    T_CHECK(iv_is_empty(iv_make(HUGE_VAL, HUGE_VAL)));
    T_CHECK(iv_is_empty(iv_make(-HUGE_VAL, -HUGE_VAL)));
    T_CHECK(iv_is_empty(iv_point(NAN)));
    T_CHECK(iv_is_empty(iv_add_d(iv_make(0, 1), NAN)));
    T_CHECK(iv_is_empty(iv_mul_d(iv_make(0, 1), NAN)));
    T_CHECK(iv_is_empty(iv_mul_d(iv_make(0, 1), HUGE_VAL)));
    T_CHECK(iv_is_empty(iv_add(iv_empty(), iv_make(0, 1))));
    T_CHECK(iv_is_empty(iv_mul(iv_make(0, 0), iv_empty())));
    T_CHECK(iv_is_empty(iv_div(iv_empty(), iv_make(1, 2))));
    T_CHECK(iv_is_empty(iv_sqrt(iv_make(-2, -1))));
    T_CHECK(!iv_contains(iv_make(0, 1), NAN));
    T_CHECK(!iv_contains(iv_empty(), 0.5));
    T_CHECK(iv_width(iv_empty()) != iv_width(iv_empty())); /* NaN */
    T_CHECK(iv_mid(iv_empty()) != iv_mid(iv_empty()));
    T_CHECK(iv_is_empty(iv_intersect(iv_make(0, 1), iv_make(2, 3))));
    T_EQ(iv_hull(iv_empty(), iv_make(1, 2)).lo, 1);
}

static void queries(void)
{
    iv_t l, r, x = iv_make(1, 3);
    T_EQ(iv_mid(x), 2);
    T_EQ(iv_width(iv_point(5)), 0);
    T_GE(iv_width(iv_make(0.1, 0.3)), 0.3 - 0.1);
    T_EQ(iv_mid(iv_entire()), 0);
    T_EQ(iv_mid(iv_make(1, HUGE_VAL)), DBL_MAX);
    T_EQ(iv_mid(iv_make(-DBL_MAX, DBL_MAX)), 0);
    iv_split(x, &l, &r);
    T_EQ(l.lo, 1); T_EQ(l.hi, 2); T_EQ(r.lo, 2); T_EQ(r.hi, 3);
    T_CHECK(iv_contains(x, 1) && iv_contains(x, 3) && !iv_contains(x, 3.0000001));
}

static void div_one_two_by_minus_one_one(void)
{
    iv_t p[2];
    iv_t d = iv_div(iv_make(1, 2), iv_make(-1, 1));
    T_EQ(d.lo, -HUGE_VAL); T_EQ(d.hi, HUGE_VAL);
    T_INT_EQ(iv_div_ext(iv_make(1, 2), iv_make(-1, 1), p), 2);
    T_EQ(p[0].lo, -HUGE_VAL); T_GE(p[0].hi, -1); T_LE(p[0].hi, nextafter(-1, 0));
    T_GE(p[1].lo, nextafter(1, 0)); T_LE(p[1].lo, 1); T_EQ(p[1].hi, HUGE_VAL);
}

static void div_zero_cases(void)
{
    iv_t p[2], d;
    T_INT_EQ(iv_div_ext(iv_make(1, 2), iv_make(0, 0), p), 0);
    T_CHECK(iv_is_empty(iv_div(iv_make(1, 2), iv_make(0, 0))));
    d = iv_div(iv_make(0, 0), iv_make(-1, 1));
    T_EQ(d.lo, 0); T_EQ(d.hi, 0);
    d = iv_div(iv_make(0, 5), iv_make(0, 2));
    T_EQ(d.lo, 0); T_EQ(d.hi, HUGE_VAL);
    d = iv_div(iv_make(2, 5), iv_make(0, 2));
    T_EQ(d.lo, nextafter(1, 0)); T_EQ(d.hi, HUGE_VAL);
    d = iv_div(iv_make(2, 5), iv_make(-2, 0));
    T_EQ(d.lo, -HUGE_VAL); T_EQ(d.hi, nextafter(-1, 0));
    d = iv_div(iv_make(-1, 5), iv_make(-2, 0));
    T_EQ(d.lo, -HUGE_VAL); T_EQ(d.hi, HUGE_VAL);
    T_INT_EQ(iv_div_ext(iv_make(-1, 5), iv_make(-2, 3), p), 1);
    d = iv_recip(iv_make(2, HUGE_VAL));
    T_EQ(d.lo, 0); T_GE(d.hi, 0.5);
    d = iv_div(iv_make(1, HUGE_VAL), iv_make(1, HUGE_VAL));
    T_EQ(d.lo, 0); T_EQ(d.hi, HUGE_VAL);
}

static void x_times_x_against_sqr(void)
{
    iv_t m = iv_mul(iv_make(-1, 2), iv_make(-1, 2));
    iv_t s = iv_sqr(iv_make(-1, 2));
    T_LE(m.lo, -2); T_GE(m.lo, nextafter(-2, -3));
    T_EQ(s.lo, 0); T_LE(s.hi, nextafter(4, 5)); T_GE(s.hi, 4);
    s = iv_sqr(iv_make(-3, -2));
    T_GE(s.lo, nextafter(4, 0)); T_LE(s.lo, 4); T_GE(s.hi, 9);
    s = iv_sqr(iv_make(-1e-200, 1e-300));
    T_EQ(s.lo, 0); T_GT(s.hi, 0);
}

static void sqrt_clips_domain(void)
{
    iv_t s = iv_sqrt(iv_make(-1, 4));
    T_EQ(s.lo, 0); T_GE(s.hi, 2); T_LE(s.hi, nextafter(2, 3));
    s = iv_sqrt(iv_make(-1, 0));
    T_EQ(s.lo, 0); T_EQ(s.hi, 0);
}

static void mul_zero_times_unbounded(void)
{
    iv_t p = iv_mul(iv_make(0, 0), iv_entire());
    T_LE(p.lo, 0); T_GE(p.lo, -4.9406564584124654e-324); /* at most one step */
    T_LE(p.hi, 4.9406564584124654e-324); T_GE(p.hi, 0);
    p = iv_mul(iv_make(0, 1), iv_make(1, HUGE_VAL));
    T_LE(p.lo, 0); T_GE(p.lo, -4.9406564584124654e-324); T_EQ(p.hi, HUGE_VAL);

}

/* Both implementations of the outward step (bit pattern and fused
   multiply-add; the header picks one per target) are exactly nextafter
   toward -inf, on special values and on random doubles and bit patterns. */
static void outward_step_both_paths(void)
{
    static const double special[] = {0.0, -0.0, 4.9406564584124654e-324, -4.9406564584124654e-324,
        2.2250738585072014e-308, -2.2250738585072014e-308, 2.2250738585072009e-308, 4.4501477170144028e-308,
        4.4501477170144033e-308, 1.0, -1.0, 2.0, -2.0, 0.5, 3.0, 1.7976931348623157e308, -1.7976931348623157e308,
        HUGE_VAL, -HUGE_VAL, 1e-310, -1e-310, 9007199254740992.0, 1.0000000000000002};
    t_rng_t r = {3};
    long i, n = t_count(2000000), bad = 0;
    for (i = 0; i < (long)(sizeof special / sizeof special[0]) + n; i++) {
        double x, want;
        if (i < (long)(sizeof special / sizeof special[0])) x = special[i];
        else if (i % 2) x = ig_value(&r);
        else { unsigned long long u = t_rng_u64(&r); memcpy(&x, &u, sizeof x); if (x != x) continue; }
        want = x == 0 ? -4.9406564584124654e-324 : x == -HUGE_VAL ? x : nextafter(x, -HUGE_VAL);
        if (iv__next_down_bits(x) != want || iv__next_down_fma(x) != want ||
            iv__next_up(x) != (x == 0 ? 4.9406564584124654e-324 : x == HUGE_VAL ? x : nextafter(x, HUGE_VAL))) {
            if (bad++ < 5) T_FAIL("step at %a: bits %a fma %a want %a", x, iv__next_down_bits(x), iv__next_down_fma(x), want);
        }
    }
    T_INT_EQ(bad, 0);
    T_CHECK(iv__next_down_bits(NAN) != iv__next_down_bits(NAN));
    T_CHECK(iv__next_down_fma(NAN) != iv__next_down_fma(NAN));
    /* a product that underflows must still be enclosed */
    {
        iv_t p = iv_mul(iv_point(-1e-200), iv_point(1e-200));
        T_LT(p.lo, 0); T_GE(p.hi, 0);
        p = iv_mul(iv_point(1e-200), iv_point(1e-200));
        T_LE(p.lo, 0); T_GT(p.hi, 0);
    }
}

/* Exact endpoint references in quad for the tightness test. */
typedef struct tight_op_t {
    const char *name;
    iv_t (*f)(iv_t, iv_t);
    int unary;
} tight_op_t;

static iv_t sqrt2(iv_t a, iv_t b) { (void)b; return iv_sqrt(a); }
static iv_t sqr2(iv_t a, iv_t b) { (void)b; return iv_sqr(a); }

/* The exact hull of f over the corners (monotone pieces), as quad. */
static void exact_bounds(int op, iv_t a, iv_t b, q_t *lo, q_t *hi)
{
    q_t al = a.lo, ah = a.hi, bl = b.lo, bh = b.hi, c[4];
    int i;
    switch (op) {
    case 0: *lo = al + bl; *hi = ah + bh; return;
    case 1: *lo = al - bh; *hi = ah - bl; return;
    case 2: c[0] = al * bl; c[1] = al * bh; c[2] = ah * bl; c[3] = ah * bh; break;
    case 3: c[0] = al / bl; c[1] = al / bh; c[2] = ah / bl; c[3] = ah / bh; break;
    case 4: *lo = sqrtq(al < 0 ? 0 : al); *hi = sqrtq(ah); return;
    default:
        c[0] = c[1] = al * al; c[2] = c[3] = ah * ah;
        if (al < 0 && ah > 0) c[0] = 0;
        break;
    }
    *lo = *hi = c[0];
    for (i = 1; i < 4; i++) { if (c[i] < *lo) *lo = c[i]; if (c[i] > *hi) *hi = c[i]; }
}

/* Each finite endpoint lies on the right side of the exact value and at
   most one double beyond the correctly rounded outward endpoint. */
static void tightness_basic_ops(void)
{
    static const tight_op_t ops[] = {
        {"add", iv_add, 0}, {"sub", iv_sub, 0}, {"mul", iv_mul, 0},
        {"div", iv_div, 0}, {"sqrt", sqrt2, 1}, {"sqr", sqr2, 1},
    };
    t_rng_t r = {42};
    long n = t_count(2000000), i, bad = 0;
    long long worst = 0;
    for (i = 0; i < n; i++) {
        int op = (int)(i % 6);
        iv_t a, b, z;
        q_t lo, hi;
        double rd, ru;
        do a = ig_interval(&r); while (a.lo == -HUGE_VAL || a.hi == HUGE_VAL);
        do b = ig_interval(&r); while (b.lo == -HUGE_VAL || b.hi == HUGE_VAL ||
                                      (op == 3 && !(b.lo > 0 || b.hi < 0)));
        if (op == 4 && a.hi < 0) a = iv_neg(a);
        z = ops[op].f(a, b);
        exact_bounds(op, a, b, &lo, &hi);
        rd = ig_rd(lo);
        ru = ig_ru(hi);
        if (!((q_t)z.lo <= lo && (q_t)z.hi >= hi)) {
            if (bad++ < 5) T_FAIL("%s: [%a,%a] op [%a,%a] = [%a,%a] misses exact", ops[op].name, a.lo, a.hi, b.lo, b.hi, z.lo, z.hi);
            continue;
        }
        /* outward distance in doubles from the correctly rounded endpoint */
        if (rd > -HUGE_VAL && ig_ulps(z.lo, rd) > worst) worst = ig_ulps(z.lo, rd);
        if (ru < HUGE_VAL && ig_ulps(ru, z.hi) > worst) worst = ig_ulps(ru, z.hi);
        if ((rd > -HUGE_VAL && ig_ulps(z.lo, rd) > 1) || (ru < HUGE_VAL && ig_ulps(ru, z.hi) > 1)) {
            if (bad++ < 5) T_FAIL("%s: [%a,%a] op [%a,%a] = [%a,%a] more than 1 ulp wide of [%a,%a]",
                                  ops[op].name, a.lo, a.hi, b.lo, b.hi, z.lo, z.hi, rd, ru);
        }
    }
    T_INT_EQ(bad, 0);
    T_LE(worst, 1);
    fprintf(stderr, "    tightness: %ld cases, worst endpoint %lld ulp outside the correctly rounded one\n", n, worst);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(bad_input_is_empty),
        T_CASE(queries),
        T_CASE(div_one_two_by_minus_one_one),
        T_CASE(div_zero_cases),
        T_CASE(x_times_x_against_sqr),
        T_CASE(sqrt_clips_domain),
        T_CASE(mul_zero_times_unbounded),
        T_CASE(tightness_basic_ops),
        T_CASE(outward_step_both_paths),
    };
    return T_RUN(argc, argv, cases);
}
