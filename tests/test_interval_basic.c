/* Unit tests of interval.h: construction, bad input, division cases, and
   the tightness of + - * / sqrt sqr against the __float128 exact result. */
#define IV_IMPLEMENTATION
#include "test_interval_oracle.h"

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
    T_CHECK(iv_is_empty(iv_sub_d(iv_make(0, 1), NAN)));
    T_CHECK(iv_is_empty(iv_sub_d(iv_make(0, 1), -HUGE_VAL)));
    T_CHECK(iv_is_empty(iv_add_d(iv_make(0, 1), HUGE_VAL)));
    T_CHECK(iv_is_empty(iv_div_d(iv_make(0, 1), NAN)));
    T_CHECK(iv_is_empty(iv_div_d(iv_make(0, 1), HUGE_VAL)));
    T_CHECK(iv_is_empty(iv_mul_d(iv_empty(), 2.0)));
    T_CHECK(iv_is_empty(iv_sub(iv_make(0, 1), iv_empty())));
    T_CHECK(iv_is_empty(iv_mul(iv_empty(), iv_make(-1, 1))));
    T_CHECK(iv_is_empty(iv_div(iv_make(1, 2), iv_empty())));
    T_CHECK(iv_is_empty(iv_div(iv_make(1, 2), iv_make(NAN, 1))));
    T_CHECK(iv_is_empty(iv_sqr(iv_empty())));
    T_CHECK(iv_is_empty(iv_sqrt(iv_empty())));
    T_CHECK(iv_is_empty(iv_recip(iv_empty())));
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

/* iv_result_string (T_RESULT_NAMES) */
static void result_strings(void) { T_RESULT_NAMES(iv_result_string, iv_result_t, IV_RESULT_COUNT_); }

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

/* iv_split with infinite ends and unsplittable inputs (issue 3; found by
   review: [DBL_MAX, inf] came back as one of its own halves, unannounced).
   The union is x; the return value is 1 exactly when a double lies
   strictly inside x, and then both halves are proper subsets; else one
   half is x and the other a point at a finite end. */
static void split_infinite_and_unsplittable(void)
{
    static const double ends[][2] = {{DBL_MAX, HUGE_VAL}, {-HUGE_VAL, -DBL_MAX}, {-HUGE_VAL, HUGE_VAL}, {DBL_MAX, DBL_MAX},
        {-DBL_MAX, -DBL_MAX}, {0, HUGE_VAL}, {-HUGE_VAL, 0}, {-DBL_MAX, HUGE_VAL}, {0x1.fffffffffffffp+1022, HUGE_VAL},
        {-HUGE_VAL, -0x1.fffffffffffffp+1022}, {1, 0x1.0000000000001p+0}, {0x1.0000000000001p+0, 0x1.0000000000002p+0},
        {0, 0x1p-1074}, {-0x1p-1074, 0x1p-1074}, {0x1p-1074, 0x1.8p-1073}, {-0.0, 0.0}, {1, 3}, {-DBL_MAX, DBL_MAX}};
    static const int splits[] = {0, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0, 0, 0, 1, 1, 0, 1, 1};
    int i;
    iv_t l, r;
    for (i = 0; i < (int)(sizeof splits / sizeof splits[0]); i++) {
        iv_t x = iv_make(ends[i][0], ends[i][1]);
        int got = iv_split(x, &l, &r), lx = l.lo == x.lo && l.hi == x.hi, rx = r.lo == x.lo && r.hi == x.hi;
        T_CHECK(!iv_is_empty(l) && !iv_is_empty(r) && l.hi < HUGE_VAL && r.lo > -HUGE_VAL);
        T_CHECK(l.lo == x.lo && r.hi == x.hi && l.hi == r.lo && l.hi >= x.lo && l.hi <= x.hi);
        if (!T_INT_EQ(got, splits[i])) fprintf(stderr, "    split [%a, %a] -> %d\n", x.lo, x.hi, got);
        if (got) T_CHECK(!lx && !rx);
        else T_CHECK((lx && r.lo == r.hi) || (rx && l.lo == l.hi));
    }
    T_EQ(l.hi, 0); /* [-DBL_MAX, DBL_MAX] at 0 */
    iv_split(iv_make(DBL_MAX, HUGE_VAL), &l, &r);
    T_EQ(l.lo, DBL_MAX); T_EQ(l.hi, DBL_MAX); T_EQ(r.lo, DBL_MAX); T_EQ(r.hi, HUGE_VAL);
    iv_split(iv_make(-HUGE_VAL, -DBL_MAX), &l, &r);
    T_EQ(l.lo, -HUGE_VAL); T_EQ(l.hi, -DBL_MAX); T_EQ(r.lo, -DBL_MAX); T_EQ(r.hi, -DBL_MAX);
    T_INT_EQ(iv_split(iv_empty(), &l, &r), 0);
    T_CHECK(iv_is_empty(l) && iv_is_empty(r));
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

/* equal, or both NaN */
static int same_double(double a, double b) { return a == b || (a != a && b != b); }

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
#ifdef IV__PAIR
    /* the vector steps against nextafter on the same values: iv__out
       (lane 0 down, lane 1 up), iv__out_exact (the same for normal values;
       subnormals and zeros stay, as sums there are exact) and iv__out_pair
       (from [-lo, hi]: both ends outward, lane 0 negated back) */
    for (i = 0, bad = 0; i < (long)(sizeof special / sizeof special[0]) + n; i++) {
        double x, y, got[2], gex[2], gpr[2], wx, wy, ex, ey;
        if (i < (long)(sizeof special / sizeof special[0])) {
            x = special[i];
            y = -special[(i + 5) % (sizeof special / sizeof special[0])];
        } else {
            x = ig_value(&r);
            y = ig_value(&r);
        }
        wx = x == -HUGE_VAL ? x : x == 0 ? -4.9406564584124654e-324 : nextafter(x, -HUGE_VAL);
        wy = y == HUGE_VAL ? y : y == 0 ? 4.9406564584124654e-324 : nextafter(y, HUGE_VAL);
        ex = fabs(x) < DBL_MIN ? x : wx;
        ey = fabs(y) < DBL_MIN ? y : wy;
        _mm_storeu_pd(got, iv__out(_mm_set_pd(y, x)));
        _mm_storeu_pd(gex, iv__out_exact(_mm_set_pd(y, x)));
        _mm_storeu_pd(gpr, iv__out_pair(_mm_set_pd(y, -x), iv__abs2(_mm_set_pd(y, -x))));
        /* an inward infinity (overflow) gives NaN, which sends the
           operation to the scalar code */
        if (x == HUGE_VAL) wx = ex = NAN;
        if (y == -HUGE_VAL) wy = ey = NAN;
        if (!same_double(got[0], wx) || !same_double(got[1], wy) || !same_double(gex[0], ex) ||
            !same_double(gex[1], ey) || !same_double(gpr[0], wx) || !same_double(gpr[1], wy)) {
            if (bad++ < 5)
                T_FAIL("vector step at (%a, %a): out (%a, %a) exact (%a, %a) pair (%a, %a); want (%a, %a) / (%a, %a)", x, y,
                       got[0], got[1], gex[0], gex[1], gpr[0], gpr[1], wx, wy, ex, ey);
        }
    }
    T_INT_EQ(bad, 0);
#endif
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

/* Each finite endpoint lies on the right side of the exact value and at
   most one double beyond the correctly rounded outward endpoint. */
static void tightness_basic_ops(void)
{
    static const int ops[] = {OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_SQRT, OP_SQR};
    t_rng_t r = {42};
    long n = t_count(2000000), i, bad = 0;
    long long worst = 0;
    for (i = 0; i < n; i++) {
        int op = ops[i % 6];
        iv_t a, b, z;
        long long g;
        do a = ig_interval(&r); while (a.lo == -HUGE_VAL || a.hi == HUGE_VAL);
        do b = ig_interval(&r); while (b.lo == -HUGE_VAL || b.hi == HUGE_VAL ||
                                      (op == OP_DIV && !(b.lo > 0 || b.hi < 0)));
        if (op == OP_SQRT && a.hi < 0) a = iv_neg(a);
        z = eval_iv(op, a, b, 0);
        g = tight_gap(op, a, b, z);
        if (g < 0) {
            if (bad++ < 5) T_FAIL("%s: [%a,%a] op [%a,%a] = [%a,%a] misses exact", op_name[op], a.lo, a.hi, b.lo, b.hi, z.lo, z.hi);
            continue;
        }
        if (g > worst) worst = g;
        if (g > 1 && bad++ < 5)
            T_FAIL("%s: [%a,%a] op [%a,%a] = [%a,%a] more than 1 ulp outside the correctly rounded ends", op_name[op], a.lo,
                   a.hi, b.lo, b.hi, z.lo, z.hi);
    }
    T_INT_EQ(bad, 0);
    T_LE(worst, 1);
    fprintf(stderr, "    tightness: %ld cases, worst endpoint %lld ulp outside the correctly rounded one\n", n, worst);
}

/* The pair path and the scalar path give the same intervals
   (test_interval_gen.h; IV_FAST builds run it too). */
static void pair_path_matches_scalar(void) { ig_pair_matches_scalar(); }
static void arrays_match_per_call(void) { ig_arrays_match_per_call(); }

/* Named edge cases of the outward step in + - * (both paths): each end
   is on the right side of the exact result and at most one double beyond
   its correctly rounded value; exact results stay within one step. */
static void check_exact(const char *what, iv_t z, q_t lo, q_t hi)
{
    double rd = ig_rd(lo), ru = ig_ru(hi);
    if (!((q_t)z.lo <= lo && hi <= (q_t)z.hi) || ig_ulps(z.lo, rd) > 1 || ig_ulps(ru, z.hi) > 1)
        T_FAIL("%s: [%a,%a] for exact [%a,%a]", what, z.lo, z.hi, (double)lo, (double)hi);
}
static void step_edge_cases(void)
{
    const double tiny = 4.9406564584124654e-324, minn = 2.2250738585072014e-308, big = 1.7976931348623157e308;
    iv_t z;
    /* denormals: sums that round below 2^-1022 are exact and not stepped
       (iv__down_sum); products there are rounded and are stepped */
    z = iv_add(iv_point(tiny), iv_point(tiny));
    check_exact("denormal sum", z, 2 * (q_t)tiny, 2 * (q_t)tiny);
    T_EQ(z.lo, 2 * tiny); T_EQ(z.hi, 2 * tiny);
    z = iv_sub(iv_point(minn), iv_point(tiny)); /* the largest denormal */
    check_exact("smallest normal - denormal", z, (q_t)minn - tiny, (q_t)minn - tiny);
    T_EQ(z.lo, minn - tiny); T_EQ(z.hi, minn - tiny);
    z = iv_add(iv_point(minn - tiny), iv_point(tiny)); /* reaches 2^-1022: normal, stepped */
    T_EQ(z.lo, minn - tiny); T_EQ(z.hi, minn + tiny);
    z = iv_add(iv_make(-1e-310, 3e-310), iv_make(1e-310, 2e-310));
    T_EQ(z.lo, 0); T_EQ(z.hi, 5e-310);
    z = iv_mul(iv_point(0.5), iv_point(3 * tiny)); /* 1.5 tiny rounds to 2 tiny */
    check_exact("denormal product", z, 1.5 * (q_t)tiny, 1.5 * (q_t)tiny);
    T_EQ(z.lo, tiny); T_EQ(z.hi, 3 * tiny);
    z = iv_div(iv_point(3 * tiny), iv_point(2.0));
    check_exact("denormal quotient", z, 1.5 * (q_t)tiny, 1.5 * (q_t)tiny);
    T_EQ(z.lo, tiny); T_EQ(z.hi, 3 * tiny);
    z = iv_sqrt(iv_point(tiny)); /* never subnormal: a normal step */
    T_EQ(z.lo, nextafter(sqrt(tiny), 0)); T_EQ(z.hi, nextafter(sqrt(tiny), 1));
    z = iv_div(iv_make(0, 1), iv_make(1, 2)); /* a nonnegative numerator keeps lo >= 0 */
    T_EQ(z.lo, 0); T_EQ(z.hi, nextafter(1.0, 2));
    z = iv_div(iv_make(-1, -0.0), iv_make(1, 2));
    T_EQ(z.hi, 0); T_EQ(z.lo, nextafter(-1.0, -2));
    z = iv_div(iv_point(1e-300), iv_point(1e300)); /* underflow to 0: [0, tiny] */
    T_EQ(z.lo, 0); T_EQ(z.hi, tiny);
    /* the smallest normal: the spacing is 2^-1074 on both sides */
    z = iv_mul(iv_point(minn), iv_point(1.0));
    T_EQ(z.lo, minn - tiny); T_EQ(z.hi, minn + tiny);
    z = iv_mul(iv_point(-minn), iv_make(1.0, 1.0));
    T_EQ(z.lo, -minn - tiny); T_EQ(z.hi, -minn + tiny);
    /* powers of two: the spacing below is half the spacing above */
    z = iv_add(iv_point(1.0), iv_point(1.0));
    T_EQ(z.lo, nextafter(2.0, 0)); T_EQ(z.hi, nextafter(2.0, 4));
    z = iv_mul(iv_point(-0.5), iv_point(4.0));
    T_EQ(z.lo, nextafter(-2.0, -4)); T_EQ(z.hi, nextafter(-2.0, 0));
    /* underflow to zero: the enclosure keeps the sign of the product */
    z = iv_mul(iv_point(1e-200), iv_point(-1e-200));
    T_EQ(z.lo, -tiny); T_EQ(z.hi, 0.0 + tiny);
    /* +-huge: overflow gives DBL_MAX on the inner side and inf outside */
    z = iv_add(iv_point(big), iv_point(big));
    T_EQ(z.lo, big); T_EQ(z.hi, HUGE_VAL);
    z = iv_mul(iv_point(-big), iv_point(2.0));
    T_EQ(z.lo, -HUGE_VAL); T_EQ(z.hi, -big);
    z = iv_mul_d(iv_point(big), -2.0);
    T_EQ(z.lo, -HUGE_VAL); T_EQ(z.hi, -big);
    z = iv_sub(iv_point(big), iv_point(-big));
    T_EQ(z.lo, big); T_EQ(z.hi, HUGE_VAL);
    /* infinities */
    z = iv_add(iv_make(-HUGE_VAL, 1), iv_make(2, HUGE_VAL));
    T_EQ(z.lo, -HUGE_VAL); T_EQ(z.hi, HUGE_VAL);
    z = iv_mul(iv_make(-HUGE_VAL, -1), iv_make(2, 3));
    T_EQ(z.lo, -HUGE_VAL); T_GE(z.hi, -2.0); T_LE(z.hi, nextafter(-2.0, 0));
    z = iv_mul(iv_make(0, HUGE_VAL), iv_make(0, 1)); /* 0 * inf is 0 */
    T_LE(z.lo, 0); T_GE(z.lo, -tiny); T_EQ(z.hi, HUGE_VAL);
    z = iv_mul(iv_make(-1, 2), iv_make(-3, 5));
    check_exact("straddling product", z, -6, 10);
    z = iv_mul_d(iv_make(0, HUGE_VAL), 0.0);
    T_LE(z.lo, 0); T_GE(z.hi, 0); T_LE(z.hi, tiny);
    /* exact results are enclosed within one step on each side */
    z = iv_add(iv_point(0.25), iv_point(0.5));
    check_exact("exact sum", z, 0.75, 0.75);
    z = iv_mul(iv_make(3, 5), iv_make(-7, -2));
    check_exact("exact product", z, -35, -6);
    z = iv_sub(iv_point(1e300), iv_point(1e300)); /* exact 0: not stepped */
    T_EQ(z.lo, 0); T_EQ(z.hi, 0);
    /* overflow in the other operations: the inner end is DBL_MAX */
    z = iv_sqr(iv_make(1e200, 1e300));
    T_EQ(z.lo, big); T_EQ(z.hi, HUGE_VAL);
    z = iv_div(iv_point(1e300), iv_point(1e-300));
    T_EQ(z.lo, big); T_EQ(z.hi, HUGE_VAL);
    z = iv_div(iv_point(-1e300), iv_point(1e-300));
    T_EQ(z.lo, -HUGE_VAL); T_EQ(z.hi, -big);
    z = iv_div(iv_point(1e300), iv_point(-1e-300));
    T_EQ(z.lo, -HUGE_VAL); T_EQ(z.hi, -big);
    z = iv_sqrt(iv_make(4, HUGE_VAL));
    T_EQ(z.lo, nextafter(2.0, 0)); T_EQ(z.hi, HUGE_VAL);
    z = iv_mul_d(iv_make(1e300, 2e300), 1e10);
    T_EQ(z.lo, big); T_EQ(z.hi, HUGE_VAL);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(bad_input_is_empty),
        T_CASE(queries),
        T_CASE(split_infinite_and_unsplittable),
        T_CASE(result_strings),
        T_CASE(div_one_two_by_minus_one_one),
        T_CASE(div_zero_cases),
        T_CASE(x_times_x_against_sqr),
        T_CASE(sqrt_clips_domain),
        T_CASE(mul_zero_times_unbounded),
        T_CASE(tightness_basic_ops),
        T_CASE(outward_step_both_paths),
        T_CASE(pair_path_matches_scalar),
        T_CASE(arrays_match_per_call),
        T_CASE(step_edge_cases),
    };
    return T_RUN(argc, argv, cases);
}
