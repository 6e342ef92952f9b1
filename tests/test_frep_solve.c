/* Polynomial solvers of frep.h (issue 5, item 1), against an independent
   __float128 oracle (tests/test_frep_solve_ref.h): the reference roots are
   those of the polynomial whose coefficients are the very doubles we pass,
   so every bound below is about the solver, not about coefficient rounding. */
#include "test.h"
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include "test_frep_solve_ref.h"
#include "test_frep_solve_odm.h"

/* A reference root counts as real when |Im|/|z| is at most this. */
#define REAL_TOL 1e-20

/* Compare fr_solve_poly on [t0, t1] with the oracle: same count (after
   merging reference roots closer than merge_rel, which a solver may return
   once), and every root within rel (relative to max(|root|, abs_floor)). */
static void check_roots(const char *what, const double *c, int degree, double t0, double t1, double rel,
                        double merge_rel)
{
    double r[REF_MAX_DEG + 1];
    __float128 ref[REF_MAX_DEG + 1], m[REF_MAX_DEG + 1];
    int n = fr_solve_poly(c, degree, t0, t1, r), nref, nm = 0, i;
    nref = ref_real_roots(c, degree, REAL_TOL, ref);
    for (i = 0; i < nref; i++) {
        if (ref[i] < (__float128)t0 || ref[i] > (__float128)t1) continue;
        if (nm > 0 && fabsq(ref[i] - m[nm - 1]) <= (__float128)merge_rel * fabsq(ref[i])) continue;
        m[nm++] = ref[i];
    }
    if (n != nm) {
        T_FAIL("%s: %d roots, reference has %d", what, n, nm);
        for (i = 0; i < n; i++) fprintf(stderr, "   got %.17g\n", r[i]);
        for (i = 0; i < nm; i++) fprintf(stderr, "   ref %.17g\n", (double)m[i]);
        return;
    }
    T_INT_EQ(n, nm);
    for (i = 0; i < n; i++) {
        __float128 err = fabsq((__float128)r[i] - m[i]) / (fabsq(m[i]) > 0 ? fabsq(m[i]) : 1);
        if (!(err <= (__float128)rel))
            T_FAIL("%s: root %d = %.17g, reference %.17g, rel error %.3g > %.3g", what, i, r[i], (double)m[i],
                   (double)err, rel);
        else
            T_CHECK(1);
    }
}

/* Coefficients from real roots and complex pairs (rounded once from quad). */
static void from_roots(double *c, const double *re, int nr, const double (*pairs)[2], int np, double lead)
{
    __float128 q[REF_MAX_DEG] = {0}, p[REF_MAX_DEG][2] = {{0}};
    int i;
    for (i = 0; i < nr; i++) q[i] = re[i];
    for (i = 0; i < np; i++) { p[i][0] = pairs[i][0]; p[i][1] = pairs[i][1]; }
    ref_coeffs_from_roots(q, nr, (const __float128(*)[2])p, np, lead, c);
}

/* ---------------------------------------------------------------- the oracle itself */

static void oracle_recovers_known_roots(void)
{
    static const double roots[4] = {-3, 0.5, 2, 7};
    double c[5];
    __float128 ref[5];
    int n, i;
    from_roots(c, roots, 4, NULL, 0, 1);
    n = ref_real_roots(c, 4, REAL_TOL, ref);
    T_INT_EQ(n, 4);
    for (i = 0; i < 4 && i < n; i++) T_REL((double)ref[i], roots[i], 1e-15);
}

/* ---------------------------------------------------------------- compensated Horner */

/* (x-1)^8 has exact integer coefficients; near x = 1 plain Horner loses every
   digit to cancellation, compensated Horner must keep about 16 of them. This
   fails if the compiler contracts the error-free transformations into fmas. */
static void compensated_horner_survives_contraction(void)
{
    static const double c[9] = {1, -8, 28, -56, 70, -56, 28, -8, 1};
    double x;
    for (x = 1.0009765625; x < 1.1; x += 0.0078125) { /* exact binary points */
        __float128 exact = powq((__float128)x - 1, 8);
        double a, v = fr_poly_eval_compensated(c, 8, x, &a);
        T_REL(v, (double)exact, 1e-12);
        T_LE(fabs(v - (double)exact), 1e-15 * fabs((double)exact) + 4 * 64 * 1.3e-32 * a);
    }
}

/* ---------------------------------------------------------------- quadratic */

static void quadratic_textbook(void)
{
    static const double c[3] = {6, -5, 1};
    double r[2];
    T_INT_EQ(fr_solve_quadratic(c, r), 2);
    T_EQ(r[0], 2);
    T_EQ(r[1], 3);
}

/* b^2 ~ 4ac: the discriminant cancels; near-double roots 1 +- 1e-8. */
static void quadratic_near_double_root(void)
{
    static const double roots[2] = {1 - 1e-8, 1 + 1e-8};
    double c[3];
    from_roots(c, roots, 2, NULL, 0, 1);
    check_roots("near double", c, 2, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* Complex pair with imaginary part 1e-9: no real root may appear. */
static void quadratic_complex_pair_near_axis(void)
{
    static const double pair[1][2] = {{1.5, 1e-7}};
    double c[3], r[2];
    from_roots(c, NULL, 0, pair, 1, 1);
    T_INT_EQ(fr_solve_quadratic(c, r), 0);
}

/* Cancellation-prone: roots 1e-9 and 1e9 (|b| >> |a c|). */
static void quadratic_roots_1e_minus9_and_1e9(void)
{
    static const double roots[2] = {1e-9, 1e9};
    double c[3];
    from_roots(c, roots, 2, NULL, 0, 1);
    check_roots("spread quadratic", c, 2, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* ---------------------------------------------------------------- stiff cases */

static void quartic_roots_spread_1e_minus9_to_1e9(void)
{
    static const double roots[4] = {1e-9, 1e-3, 1e3, 1e9};
    double c[5];
    from_roots(c, roots, 4, NULL, 0, 1);
    check_roots("spread quartic", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* Root magnitudes spread over more bits than one scaling holds (FR__BAND_BITS
   / degree: 150 bits at degree 6): the solver takes them in bands, negative
   side first; roots from 1e-25 to 1e25 on both sides, with a complex pair
   (gcov: no test had reached the banded path). */
static void roots_spread_over_several_bands(void)
{
    static const double roots[6] = {-1e25, -3e10, 1e-25, 2, 5e12, 1e24};
    static const double roots8[6] = {-4e-30, -1e-5, 7e-22, 3e18, 2e28, 1e30};
    static const double pair[1][2] = {{1e5, 3e4}};
    double c[9];
    from_roots(c, roots, 6, NULL, 0, 1);
    check_roots("degree 6, roots 1e-25 to 1e25", c, 6, -HUGE_VAL, HUGE_VAL, 1e-15, 0);
    from_roots(c, roots8, 6, pair, 1, 1);
    check_roots("degree 8, roots 4e-30 to 1e30 and a pair", c, 8, -HUGE_VAL, HUGE_VAL, 1e-15, 0);
    check_roots("degree 8 on [-1, 1e20]", c, 8, -1, 1e20, 1e-15, 0);
}

static void quartic_cluster_2_2001_2002_2003(void)
{
    static const double roots[4] = {2, 2.001, 2.002, 2.003};
    double c[5];
    from_roots(c, roots, 4, NULL, 0, 1);
    check_roots("cluster", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* Roots clustered within 1e-8 (relative 5e-9) plus a far one. */
static void quartic_cluster_within_1e_minus8(void)
{
    static const double roots[4] = {-4, 2, 2 + 1e-8, 2 + 2e-8};
    double c[5];
    from_roots(c, roots, 4, NULL, 0, 1);
    check_roots("cluster 1e-8", c, 4, -HUGE_VAL, HUGE_VAL, 1e-15, 1e-15);
}

/* Exact multiple roots (coefficients exact): each returned once, exactly. */
static void exact_multiple_roots(void)
{
    static const double d2[5] = {6, -17, 17, -7, 1};      /* (x-1)^2 (x-2)(x-3) */
    static const double t3[5] = {-2, 7, -9, 5, -1};       /* -(x-1)^3 (x-2) */
    static const double q4[5] = {1, -4, 6, -4, 1};        /* (x-1)^4 */
    static const double dd[5] = {4, 4, -3, -2, 1};        /* (x-2)^2 (x+1)^2 */
    static const double s5[6] = {32, -80, 80, -40, 10, -1}; /* -(x-2)^5 */
    double r[5];
    T_INT_EQ(fr_solve_quartic(d2, r), 3);
    T_EQ(r[0], 1); T_EQ(r[1], 2); T_EQ(r[2], 3);
    T_INT_EQ(fr_solve_quartic(t3, r), 2);
    T_EQ(r[0], 1); T_EQ(r[1], 2);
    T_INT_EQ(fr_solve_quartic(q4, r), 1);
    T_EQ(r[0], 1);
    T_INT_EQ(fr_solve_quartic(dd, r), 2);
    T_EQ(r[0], -1); T_EQ(r[1], 2);
    T_INT_EQ(fr_solve_poly(s5, 5, -HUGE_VAL, HUGE_VAL, r), 1);
    T_EQ(r[0], 2);
}

/* A tangent ray: two real roots 1e-7 apart relative, next to a double root
   perturbed into a complex pair. Counts and values against the oracle. */
static void near_double_roots_tangent(void)
{
    static const double roots[4] = {-1, 0.75, 0.75 + 1e-7, 3};
    static const double pair[1][2] = {{0.75, 1e-7}};
    static const double roots2[2] = {-1, 3};
    double c[5];
    from_roots(c, roots, 4, NULL, 0, 1);
    check_roots("near double (real pair)", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    from_roots(c, roots2, 2, pair, 1, 1);
    check_roots("near double (complex pair)", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

static void zero_leading_coefficient_drops_degree(void)
{
    static const double c[5] = {-6, 11, -6, 1, 0}; /* (x-1)(x-2)(x-3) */
    static const double lin[3] = {-3, 2, 0};
    double r[4];
    T_INT_EQ(fr_solve_quartic(c, r), 3);
    T_EQ(r[0], 1); T_EQ(r[1], 2); T_EQ(r[2], 3);
    T_INT_EQ(fr_solve_quadratic(lin, r), 1);
    T_EQ(r[0], 1.5);
}

/* 1e-20 t^4 + (t-1)(t-2)(t-3): three moderate roots and one near -1e20. */
static void tiny_leading_coefficient(void)
{
    double c[5] = {-6, 11, -6, 1, 1e-20};
    check_roots("tiny leading", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    c[4] = 1e-300;
    check_roots("tiny leading 1e-300", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

static void coefficient_scales_1e150_and_1e_minus150(void)
{
    static const double roots[4] = {-2.5, 0.1, 1.7, 40};
    double c[5], s[5];
    int i, k;
    from_roots(c, roots, 4, NULL, 0, 1);
    for (k = 0; k < 4; k++) {
        double scale = k == 0 ? 1e150 : k == 1 ? 1e-150 : k == 2 ? 1e300 : 1e-300;
        for (i = 0; i < 5; i++) s[i] = c[i] * scale;
        check_roots("scaled", s, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
}

/* ODM 2020 case 22: roots 1e154, 1e152, 10, 1 -- coefficients near 1e307. */
static void quartic_roots_1e154_1e152_10_1(void)
{
    static const double roots[4] = {1, 10, 1e152, 1e154};
    double c[5];
    from_roots(c, roots, 4, NULL, 0, 1);
    check_roots("1e154", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* ---------------------------------------------------------------- the certified shortcuts */

/* Exponents of c for the internal paths (INT_MIN for a zero coefficient). */
static void exponents(const double *c, int m, int *ex)
{
    int i;
    for (i = 0; i <= m; i++) ex[i] = c[i] != 0 ? fr__ilogb(c[i]) : INT_MIN;
}

/* fr__split_solve: roots spread so far that the Newton polygon cuts p into
   groups, each group's truncated closed form polished in its own scaling and
   certified by a sign change. Each case must take the path (it returns all m
   roots) and the public solver must agree with the oracle to 4e-16. */
static void split_path_spread_roots(void)
{
    static const double r4[4][4] = {{-2e60, -1e-40, 3, 7e25},  /* four groups, both signs */
                                    {-1e30, 1e-30, 1, 1e30},   /* ODM case 24's roots */
                                    {1, 10, 1e152, 1e154},     /* ODM case 22's: two groups of two */
                                    {1e-20, -5e-9, 4e9, -1e25}};
    static const double r3[2][3] = {{1e-30, 1, 1e30}, {-3e-100, 2e-50, 5e80}};
    double c[5], out[4];
    int ex[5], k;
    for (k = 0; k < 4; k++) {
        from_roots(c, r4[k], 4, NULL, 0, 1);
        exponents(c, 4, ex);
        T_INT_EQ(fr__split_solve(c, ex, 4, out), 4);
        check_roots("split quartic", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
    for (k = 0; k < 2; k++) {
        from_roots(c, r3[k], 3, NULL, 0, 1);
        exponents(c, 3, ex);
        T_INT_EQ(fr__split_solve(c, ex, 3, out), 3);
        check_roots("split cubic", c, 3, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
}

/* The split's fallback: a group it cannot certify (a complex pair, or a
   near-double pair whose truncated estimates are too close) returns -1, and
   the derivative sequence still finds every real root to 4e-16, none
   spurious. */
static void split_path_falls_back(void)
{
    static const double re1[2] = {1, 1e50}, pair1[1][2] = {{1e25, 1e24}};
    static const double re2[4] = {1, 1e20, 1e20 * (1 + 1e-12), 1e40};
    static const double re3[2] = {-1e-30, 1e30}, pair3[1][2] = {{1, 1e-3}};
    double c[5], out[4];
    int ex[5];
    from_roots(c, re1, 2, pair1, 1, 1);
    exponents(c, 4, ex);
    T_INT_EQ(fr__split_solve(c, ex, 4, out), -1);
    check_roots("split fallback, complex group", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    from_roots(c, re2, 4, NULL, 0, 1);
    exponents(c, 4, ex);
    T_INT_EQ(fr__split_solve(c, ex, 4, out), -1);
    check_roots("split fallback, near-double group", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 1e-10);
    from_roots(c, re3, 2, pair3, 1, 1);
    exponents(c, 4, ex);
    T_INT_EQ(fr__split_solve(c, ex, 4, out), -1);
    check_roots("split fallback, complex middle", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* fr__fast_retry: the closed forms miss roots of spread magnitudes (Ferrari
   gives 2 of 4, or a complex pair's real part twice), the discriminant's
   count stands, and the candidates of the reversed polynomial, the product
   of the roots and the middle pair's factor supply the rest. Each case's
   first estimates must fail (so the retry is what is tested), the fast
   path must then certify, and the roots match the oracle to 4e-16. */
static void fast_retry_spread_roots(void)
{
    static const double re[5][4] = {{1e14, 2, 1, -1}, /* ODM case 4 */
                                    {1e-6, 1, 2, 1e6}, {-1e-7, 3, 4, 1e7}, {1e-9, 1e-3, 1e3, 1e9}, {-3e7, 1e-2, 2, 5e6}};
    static const double re8[2] = {11, 1e8}, pair8[1][2] = {{1e3, 1}}; /* ODM case 8 */
    double c[5], est[4], out[4];
    int k;
    for (k = 0; k < 5; k++) {
        double x[4];
        int ne, first;
        from_roots(c, re[k], 4, NULL, 0, 1);
        ne = fr__estimate_roots(c, 4, est);
        for (first = 0; first < ne; first++) x[first] = est[first];
        first = ne == 4 ? fr__fast_finish(c, NULL, 4, x, 4) : -1;
        if (k < 4) T_INT_EQ(first, -1); /* the closed forms alone do not certify */
        T_INT_EQ(fr__fast_retry(c, NULL, 4, 4, est, ne, out), 4);
        check_roots("fast retry", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
    from_roots(c, re8, 2, pair8, 1, 1);
    /* 2 real roots; Ferrari gives 4 real estimates under -O2 (the retry
       picks 2 by residual), 2 under the sanitizer build's -O1 */
    T_INT_EQ(fr__solve_fast(c, NULL, 4, out, NULL), 2);
    check_roots("fast retry, complex pair between", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* Breakpoints from a derivative level's fast path (hi + lo: the rounded
   binomial products' exact parts): the critical points of a quintic with
   five real roots and of quartics with a (near-)double root amid spread
   ones (ODM's 19-21 kind) come from the quartic and cubic fast paths. The
   derivative level's certified roots must be those of the exact derivative
   (checked in __float128 by a sign change of it across each, +-4 ulps), and
   the polynomial's roots match the oracle. */
static void derivative_level_fast_breakpoints(void)
{
    static const double r5[5] = {-3, 0.5, 1, 2.5, 7};
    static const double r4[3][4] = {{1, 1e7, 1e7 * (1 + 3e-9), 1e15}, {-2, 1e-3, 5, 5 * (1 + 1e-10)},
                                    {1e-5, 0.3, 0.3 * (1 + 1e-9), 4e4}};
    double c[6], hi[6], lo[6], bp[5];
    int k, j, nb;
    from_roots(c, r5, 5, NULL, 0, 1);
    for (k = 1; k <= 2; k++) {
        fr__derivative_level(c, 5, k, hi, lo);
        nb = fr__solve_fast(hi, lo, 5 - k, bp, NULL);
        T_INT_EQ(nb, 5 - k);
        for (j = 0; j < nb; j++) { /* a sign change of the exact level across bp -+ 4 ulps */
            __float128 v[2];
            int s, i;
            for (s = 0; s < 2; s++) {
                __float128 x = (__float128)bp[j] * (1 + (s ? 8 : -8) * (__float128)1.1102230246251565e-16), acc = 0;
                for (i = 5 - k; i >= 0; i--) acc = acc * x + ((__float128)hi[i] + lo[i]);
                v[s] = acc;
            }
            T_CHECK(v[0] * v[1] < 0);
        }
    }
    check_roots("quintic", c, 5, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    for (k = 0; k < 3; k++) {
        from_roots(c, r4[k], 4, NULL, 0, 1);
        check_roots("near-double amid spread", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
}

/* fr__deflated_pair: Cardano's small pair of a cubic with spread roots is
   good only to ~1e-8 of the largest root (absolute), or missing when
   rounding puts R^2 >= Q^3; the largest root divided out from the low end
   gives the pair to ~1e-8 relative. Each case's estimates must be within
   1e-6 relative of the roots (one each), the fast path must certify, and
   the roots match the oracle to 4e-16. A complex pair beside a large root
   gets no real estimates. */
static void cubic_deflated_pair(void)
{
    static const double re[4][3] = {{3.3e6, 1e7, 7.5e14}, /* ODM case 21's p' */
                                    {-2e-3, 5, 1e11}, {1e-14, 1e-30, 1}, {-1, 7e-5, -4e20}};
    static const double re1[1] = {1e10}, pair1[1][2] = {{1, 1}};
    double c[5], est[3], out[3];
    int k, i, j;
    for (k = 0; k < 4; k++) {
        from_roots(c, re[k], 3, NULL, 0, 1);
        T_INT_EQ(fr__estimate_roots(c, 3, est), 3);
        for (i = 0; i < 3; i++) {
            double best = HUGE_VAL;
            for (j = 0; j < 3; j++)
                if (fabs(est[j] - re[k][i]) < best) best = fabs(est[j] - re[k][i]);
            T_LE(best, 1e-6 * fabs(re[k][i]));
        }
        T_INT_EQ(fr__solve_fast(c, NULL, 3, out, NULL), 3);
        check_roots("cubic, deflated pair", c, 3, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
    from_roots(c, re1, 1, pair1, 1, 1);
    T_INT_EQ(fr__estimate_roots(c, 3, est), 1);
    check_roots("cubic, complex pair beside a large root", c, 3, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
}

/* fr__sign_comp4 (the quartic brackets' four points at once) gives
   fr__sign_comp's sign at each point, and its value and derivative to a
   few ulps, with and without a lo part, on points near and away from the
   roots of ODM case 2's cluster and of a random quartic. */
static void sign_comp4_matches_scalar(void)
{
    static const double re[2][4] = {{2, 2.001, 2.002, 2.003}, {-3.5, 0.25, 1.75, 40}};
    double c[5], lo[5], x[4], v[4], d[4];
    int k, j, s[4], l;
    for (k = 0; k < 2; k++) {
        from_roots(c, re[k], 4, NULL, 0, 1);
        for (j = 0; j < 5; j++) lo[j] = ldexp(c[j], -60) * (j & 1 ? 1 : -1);
        for (l = 0; l < 2; l++) {
            int t;
            for (t = 0; t < 3; t++) {
                for (j = 0; j < 4; j++) x[j] = re[k][j] * (1.0 + (t == 0 ? 0.0 : t == 1 ? 4e-16 : -1e-3));
                fr__sign_comp4(c, l ? lo : NULL, 4, x, s, v, d);
                for (j = 0; j < 4; j++) {
                    double v1, d1;
                    int s1 = fr__sign_comp(c, l ? lo : NULL, 4, x[j], &v1, &d1);
                    T_INT_EQ(s[j], s1);
                    T_LE(fabs(v[j] - v1), 1e-15 * fabs(v1) + 1e-300);
                    T_LE(fabs(d[j] - d1), 1e-14 * fabs(d1) + 1e-300);
                }
            }
        }
    }
}

/* The cubic start at a critical end that is nearly a double root of p'
   (a triple root split by rounding: one real root ~u^(1/3) away, or three):
   (x - a)^3 (x - b) for a spread of a and b, every root to 4e-16 against
   the oracle (roots within 1e-4 relative may come back once). The a are
   not exact in binary, so rounding splits the triple root by ~u^(1/3),
   which the quad oracle resolves (an exact triple root it cannot: see
   exact_multiple_roots). */
static void near_triple_roots(void)
{
    static const double ab[6][2] = {{1000.1, 3.552713678800501e-15}, {1.1, -2}, {-7.3, 1e-9}, {3.3e5 + 0.1, 2.5},
                                    {1.1e-3, 1e3}, {0.1, 0.1000001}};
    double c[5];
    int k;
    for (k = 0; k < 6; k++) {
        double re[4];
        re[0] = re[1] = re[2] = ab[k][0];
        re[3] = ab[k][1];
        from_roots(c, re, 4, NULL, 0, 1);
        check_roots("near triple", c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 1e-4);
    }
}

/* Orellana & De Michele 2020, Table 1 (tests/test_frep_solve_odm.h): the
   Flocke and Strobach quartics on which Cardano/Ferrari solvers lose
   everything. Every real root to 4e-16 relative (the issue asks 1e-9), none
   missed, none spurious: exact-coefficient cases against their exact roots
   (a quadruple root is beyond the Aberth oracle), the others against the
   oracle on the very doubles. */
static void odm_2020_cases_1_to_24(void)
{
    int k;
    for (k = 1; k <= ODM_NCASES; k++) {
        double c[5], r[4];
        __float128 ex[4];
        char what[32];
        snprintf(what, sizeof what, "ODM case %d", k);
        if (odm_case(k, c, ex)) {
            __float128 u[4];
            int nu = 0, i, j, n = fr_solve_quartic(c, r);
            for (i = 0; i < 4; i++) { /* distinct exact roots, ascending */
                __float128 v = ex[i];
                for (j = 0; j < nu && u[j] != v; j++) {}
                if (j == nu) u[nu++] = v;
            }
            for (i = 1; i < nu; i++)
                for (j = i; j > 0 && u[j] < u[j - 1]; j--) { __float128 t = u[j]; u[j] = u[j - 1]; u[j - 1] = t; }
            if (n != nu) { T_FAIL("%s: %d roots, exactly %d", what, n, nu); continue; }
            for (i = 0; i < n; i++) T_LE((double)(fabsq((__float128)r[i] - u[i]) / fabsq(u[i])), 4e-16);
        } else
            check_roots(what, c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
}

/* The family behind the authors' two later remarks on Algorithm 1010 (the
   d2 = 0 branch of their LDL^T factorisation; their search driver draws
   x^4 + A x^2 + B with integer A, B in [-50, 50], and the same with odd
   coefficients -+1e-162): biquadratics, whose roots +-sqrt(z), z a root of
   z^2 + A z + B, are computed here in __float128 as an independent oracle.
   Exact double roots (A^2 = 4B) and, once perturbed, zero roots are left out
   (the perturbation splits them by ~1e-81, below any oracle's resolution). */
static void odm_remark_family_biquadratic(void)
{
    int A, B, pert;
    for (pert = 0; pert <= 1; pert++)
        for (A = -50; A <= 50; A += pert ? 10 : 5)
            for (B = -50; B <= 50; B += pert ? 10 : 5) {
                double c[5] = {0, 0, 0, 0, 1}, r[4];
                __float128 disc = (__float128)A * A - 4 * (__float128)B, z[2], ref[4];
                int nref = 0, n, i, j;
                if (A * A == 4 * B || (pert && B == 0)) continue;
                c[0] = B; c[2] = A;
                if (pert) { c[3] = -1e-162; c[1] = 1e-162; }
                if (disc > 0) {
                    z[0] = (-A - sqrtq(disc)) / 2;
                    z[1] = (-A + sqrtq(disc)) / 2;
                    for (i = 0; i < 2; i++) {
                        if (z[i] > 0) { ref[nref++] = -sqrtq(z[i]); ref[nref++] = sqrtq(z[i]); }
                        else if (z[i] == 0) ref[nref++] = 0;
                    }
                }
                for (i = 1; i < nref; i++)
                    for (j = i; j > 0 && ref[j] < ref[j - 1]; j--) { __float128 t = ref[j]; ref[j] = ref[j - 1]; ref[j - 1] = t; }
                n = fr_solve_quartic(c, r);
                if (n != nref) { T_FAIL("x^4 + %d x^2 + %d (perturbed %d): %d roots, %d expected", A, B, pert, n, nref); continue; }
                for (i = 0; i < n; i++) {
                    __float128 e = fabsq((__float128)r[i] - ref[i]) / (ref[i] != 0 ? fabsq(ref[i]) : 1);
                    if (!(e <= 4e-16Q)) T_FAIL("x^4 + %d x^2 + %d (perturbed %d): root %d rel error %.3g", A, B, pert, i, (double)e);
                    else T_CHECK(1);
                }
            }
}

/* The family itself as the authors' search driver draws it
   (cridemichel/quartic_C, Drivers/accuracytest.c): x^4 - 1e-162 x^3 +
   A x^2 + 1e-162 x + B with A, B uniform in [-50, 50] (real numbers, not
   integers), where the driver flags a solver whose summed relative root
   error exceeds 1e-3. Cases 25 and 26 are two such polynomials that no
   reachable source lists. Against the __float128 oracle on the very
   doubles: the same real roots, each within 4e-16 relative. */
static void odm_remark_family_random_draws(void)
{
    t_rng_t g = {1010};
    long n = t_count(10000), i;
    for (i = 0; i < n; i++) {
        double c[5], A = (t_rng_unit(&g) - 0.5) * 100.0, B = (t_rng_unit(&g) - 0.5) * 100.0;
        char what[96];
        c[0] = B; c[1] = 1e-162; c[2] = A; c[3] = -1e-162; c[4] = 1;
        snprintf(what, sizeof what, "x^4 - 1e-162 x^3 + %.17g x^2 + 1e-162 x + %.17g", A, B);
        check_roots(what, c, 4, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
}

/* Middle coefficients far below the others (down to subnormal) while the
   ends stay moderate: the fast paths take them unscaled (the roots stay
   within 2^+-122; the products that underflow lose less than the sign
   tests' absolute slack), and the biquadratic estimates seed quartics whose
   odd part underflows in Ferrari's resolvent. Against the oracle. */
static void tiny_middle_coefficients(void)
{
    static const double cases[][5] = {
        {4, 1e-310, -5, -1e-315, 1},        /* ~(x^2 - 1)(x^2 - 4), subnormal odd part */
        {-30, 1e-200, 7, 1e-250, 1},        /* two real roots */
        {1, -1e-162, -3, 1e-162, 1},        /* x^4 - 3x^2 + 1 perturbed */
        {2, 1e-300, 3, 0, 1},               /* no real root */
        {-1, 1e-200, 1, 0, 0},              /* quadratic x^2 + 1e-200 x - 1 */
        {1e-20, -1, 1e-280, 1, 0},          /* cubic x^3 + 1e-280 x^2 - x + 1e-20 */
    };
    int k;
    for (k = 0; k < (int)(sizeof cases / sizeof cases[0]); k++) {
        char what[48];
        int deg = cases[k][4] != 0 ? 4 : cases[k][3] != 0 ? 3 : 2;
        snprintf(what, sizeof what, "tiny middle coefficients, case %d", k);
        check_roots(what, cases[k], deg, -HUGE_VAL, HUGE_VAL, 4e-16, 0);
    }
}

static void zero_roots_split_off(void)
{
    static const double c[6] = {0, 0, -2, 1, 0, 0}; /* t^2 (t - 2) */
    double r[5];
    T_INT_EQ(fr_solve_poly(c, 5, -HUGE_VAL, HUGE_VAL, r), 2);
    T_EQ(r[0], 0); T_EQ(r[1], 2);
    T_INT_EQ(fr_solve_poly(c, 5, 0.5, 3, r), 1);
    T_EQ(r[0], 2);
}

static void invalid_input_returns_minus_one(void)
{
    double c[5] = {1, 2, 3, 4, 5}, r[4];
    T_INT_EQ(fr_solve_poly(c, FR_POLY_MAX_DEGREE + 1, 0, 1, r), -1);
    T_INT_EQ(fr_solve_poly(c, -1, 0, 1, r), -1);
    T_INT_EQ(fr_solve_poly(c, 4, 1, 0, r), -1);
    T_INT_EQ(fr_solve_poly(c, 4, NAN, 0, r), -1);
    T_INT_EQ(fr_solve_poly(NULL, 4, 0, 1, r), -1);
    c[2] = NAN;
    T_INT_EQ(fr_solve_quartic(c, r), -1);
    c[2] = HUGE_VAL;
    T_INT_EQ(fr_solve_quartic(c, r), -1);
    {
        static const double zero[3] = {0, 0, 0}, cst[3] = {2, 0, 0};
        T_INT_EQ(fr_solve_quadratic(zero, r), 0);
        T_INT_EQ(fr_solve_quadratic(cst, r), 0);
    }
}

/* ---------------------------------------------------------------- property tests */

static void random_quartics_against_oracle(void)
{
    t_rng_t g = {12345};
    long n = t_count(3000), i;
    for (i = 0; i < n; i++) {
        double re[4], pairs[2][2], c[5];
        int kind = (int)(t_rng_u64(&g) % 3), k;
        for (k = 0; k < 4; k++) re[k] = t_rng_range(&g, -1, 1) * pow(10, t_rng_range(&g, -3, 3));
        pairs[0][0] = re[2]; pairs[0][1] = fabs(re[3]);
        pairs[1][0] = re[0]; pairs[1][1] = fabs(re[1]);
        if (kind == 0) from_roots(c, re, 4, NULL, 0, t_rng_range(&g, 0.5, 2));
        else if (kind == 1) from_roots(c, re, 2, (const double(*)[2])pairs, 1, 1);
        else from_roots(c, NULL, 0, (const double(*)[2])pairs, 2, -3);
        check_roots("random quartic", c, 4, -HUGE_VAL, HUGE_VAL, 2e-15, 0);
    }
}

static void random_cubics_against_oracle(void)
{
    t_rng_t g = {777};
    long n = t_count(3000), i;
    for (i = 0; i < n; i++) {
        double re[3], pair[1][2], c[4];
        int k;
        for (k = 0; k < 3; k++) re[k] = t_rng_range(&g, -10, 10);
        pair[0][0] = re[1]; pair[0][1] = fabs(re[2]);
        if (t_rng_u64(&g) & 1) from_roots(c, re, 3, NULL, 0, 1);
        else from_roots(c, re, 1, (const double(*)[2])pair, 1, 1);
        check_roots("random cubic", c, 3, -HUGE_VAL, HUGE_VAL, 2e-15, 0);
    }
}

/* fr_solve_cubic, the named entry point: (t - 1)(t - 2)(t - 3) exactly,
   ascending; one real root of t^3 + t + 10 (t = -2); and on the random
   cubics above, fr_solve_poly's roots bit for bit. */
static void cubic_entry_point(void)
{
    const double c3[4] = {-6, 11, -6, 1}, c1[4] = {10, 1, 0, 1};
    double r[3], q[3], c[4];
    t_rng_t g = {777};
    int k, n;
    long i;
    T_INT_EQ(fr_solve_cubic(c3, r), 3);
    T_EQ(r[0], 1.0), T_EQ(r[1], 2.0), T_EQ(r[2], 3.0);
    T_INT_EQ(fr_solve_cubic(c1, r), 1);
    T_EQ(r[0], -2.0);
    for (i = 0; i < 200; i++) {
        for (k = 0; k < 4; k++) c[k] = t_rng_range(&g, -10, 10);
        n = fr_solve_cubic(c, r);
        if (!T_INT_EQ(n, fr_solve_poly(c, 3, -HUGE_VAL, HUGE_VAL, q))) continue;
        for (k = 0; k < n; k++) T_EQ(r[k], q[k]);
    }
}

/* Degree 5..10 with real roots and pairs, on a sub-interval [t0, t1]. */
static void random_degree_5_to_10_on_interval(void)
{
    t_rng_t g = {4242};
    long n = t_count(1000), i;
    for (i = 0; i < n; i++) {
        int deg = 5 + (int)(t_rng_u64(&g) % 6), np = (int)(t_rng_u64(&g) % (unsigned)(deg / 2 + 1)), nr = deg - 2 * np, k;
        double re[10], pairs[5][2], c[11], t0 = t_rng_range(&g, -3, 0), t1 = t_rng_range(&g, 0, 3);
        for (k = 0; k < nr; k++) re[k] = t_rng_range(&g, -4, 4);
        for (k = 0; k < np; k++) { pairs[k][0] = t_rng_range(&g, -4, 4); pairs[k][1] = t_rng_range(&g, 0.01, 2); }
        from_roots(c, re, nr, (const double(*)[2])pairs, np, 1);
        check_roots("degree 5..10", c, deg, t0, t1, 1e-14, 0);
    }
}

/* Barth-sextic-like degree 6 and a degree 10 Wilkinson-type (roots 1..10). */
static void wilkinson_degree_10(void)
{
    double re[10], c[11];
    int k;
    for (k = 0; k < 10; k++) re[k] = k + 1;
    from_roots(c, re, 10, NULL, 0, 1);
    check_roots("wilkinson 10", c, 10, -HUGE_VAL, HUGE_VAL, 1e-15, 0);
    check_roots("wilkinson 10 on [2.5, 7.5]", c, 10, 2.5, 7.5, 1e-15, 0);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(oracle_recovers_known_roots),
        T_CASE(compensated_horner_survives_contraction),
        T_CASE(quadratic_textbook),
        T_CASE(quadratic_near_double_root),
        T_CASE(quadratic_complex_pair_near_axis),
        T_CASE(quadratic_roots_1e_minus9_and_1e9),
        T_CASE(quartic_roots_spread_1e_minus9_to_1e9),
        T_CASE(quartic_cluster_2_2001_2002_2003),
        T_CASE(roots_spread_over_several_bands),
        T_CASE(quartic_cluster_within_1e_minus8),
        T_CASE(exact_multiple_roots),
        T_CASE(near_double_roots_tangent),
        T_CASE(zero_leading_coefficient_drops_degree),
        T_CASE(tiny_leading_coefficient),
        T_CASE(coefficient_scales_1e150_and_1e_minus150),
        T_CASE(quartic_roots_1e154_1e152_10_1),
        T_CASE(split_path_spread_roots),
        T_CASE(split_path_falls_back),
        T_CASE(fast_retry_spread_roots),
        T_CASE(derivative_level_fast_breakpoints),
        T_CASE(near_triple_roots),
        T_CASE(cubic_deflated_pair),
        T_CASE(sign_comp4_matches_scalar),
        T_CASE(odm_2020_cases_1_to_24),
        T_CASE(odm_remark_family_biquadratic),
        T_CASE(odm_remark_family_random_draws),
        T_CASE(tiny_middle_coefficients),
        T_CASE(zero_roots_split_off),
        T_CASE(invalid_input_returns_minus_one),
        T_CASE(random_quartics_against_oracle),
        T_CASE(random_cubics_against_oracle),
        T_CASE(cubic_entry_point),
        T_CASE(random_degree_5_to_10_on_interval),
        T_CASE(wilkinson_degree_10),
    };
    return T_RUN(argc, argv, cases);
}
