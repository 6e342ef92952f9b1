/* tests/test_frep_solve_ref.h -- an independent __float128 oracle for the
   polynomial solvers (shared by tests/test_frep_solve.c and
   bench/bench_frep_solve.c).

   The reference roots are those of the polynomial whose coefficients are the
   given doubles (exactly representable in __float128), found by the
   Aberth-Ehrlich simultaneous iteration in complex quad precision and then
   polished by quad Newton steps. It shares no code or method with frep.h's
   derivative-sequence solver. */
#ifndef FILIGREE_TEST_FREP_SOLVE_REF_H
#define FILIGREE_TEST_FREP_SOLVE_REF_H

#include <quadmath.h>
#include <math.h>

#define REF_MAX_DEG 16

typedef struct ref_root_t {
    double re, im;   /* root, rounded to double */
    __float128 qre;  /* real part in quad */
    double im_rel;   /* |Im| / |z|: 0 for a polished real root */
} ref_root_t;

static __complex128 ref_cpoly_(const __float128 *c, int n, __complex128 z, __complex128 *dp)
{
    __complex128 p = c[n], d = 0;
    int i;
    for (i = n - 1; i >= 0; i--) {
        d = d * z + p;
        p = p * z + c[i];
    }
    *dp = d;
    return p;
}

/* p and p' in real quad at x. */
static __float128 ref_rpoly_(const __float128 *c, int n, __float128 x, __float128 *dp)
{
    __float128 p = c[n], d = 0;
    int i;
    for (i = n - 1; i >= 0; i--) {
        d = d * x + p;
        p = p * x + c[i];
    }
    *dp = d;
    return p;
}

/* All n complex roots of the double-coefficient polynomial (c[n] != 0 after
   dropping leading zeros, which the caller must have done). Returns n. */
static int ref_roots_all(const double *cd, int n, ref_root_t *out)
{
    __float128 c[REF_MAX_DEG + 1], rmax = 0;
    __complex128 z[REF_MAX_DEG];
    int i, k, it;
    for (i = 0; i <= n; i++) c[i] = (__float128)cd[i] / (__float128)cd[n];
    /* start on a circle of the Fujiwara radius, rotated off the real axis */
    for (i = 0; i < n; i++) {
        __float128 r = powq(fabsq(c[i]), (__float128)1 / (__float128)(n - i));
        if (r > rmax) rmax = r;
    }
    if (rmax == 0) rmax = 1;
    for (k = 0; k < n; k++) {
        __float128 ang = 2 * M_PIq * (__float128)k / (__float128)n + 0.4Q;
        __complex128 e;
        __real__ e = cosq(ang);
        __imag__ e = sinq(ang);
        z[k] = rmax * (0.5Q + 0.5Q * (__float128)(k + 1) / (__float128)n) * e;
    }
    for (it = 0; it < 4000; it++) {
        __float128 maxstep = 0;
        for (k = 0; k < n; k++) {
            __complex128 dp, p = ref_cpoly_(c, n, z[k], &dp), ratio, sum = 0, w;
            if (p == 0) continue;
            ratio = p / dp;
            for (i = 0; i < n; i++)
                if (i != k) sum += 1 / (z[k] - z[i]);
            w = ratio / (1 - ratio * sum);
            z[k] -= w;
            if (cabsq(w) > maxstep * cabsq(z[k])) maxstep = cabsq(w) / (cabsq(z[k]) + 1e-300Q);
        }
        if (maxstep < 1e-30Q) break;
    }
    for (k = 0; k < n; k++) {
        __float128 re = crealq(z[k]), im = cimagq(z[k]), mag = cabsq(z[k]);
        out[k].qre = re;
        out[k].im_rel = mag > 0 ? (double)(fabsq(im) / mag) : 0.0;
        /* a nearly real root is polished on the real line */
        if (out[k].im_rel < 1e-12) {
            int j;
            for (j = 0; j < 8; j++) {
                __float128 d, p = ref_rpoly_(c, n, re, &d);
                if (d == 0 || p == 0) break;
                re -= p / d;
            }
            if (fabsq(re - crealq(z[k])) < 1e-10Q * (fabsq(re) + 1e-300Q)) {
                out[k].qre = re;
                out[k].im_rel = (double)(fabsq(im) / mag);
            }
        }
        out[k].re = (double)out[k].qre;
        out[k].im = (double)im;
    }
    return n;
}

/* Real reference roots in ascending order: those with |Im|/|z| <= real_tol.
   Returns their count. */
static int ref_real_roots(const double *cd, int degree, double real_tol, __float128 *rr)
{
    ref_root_t all[REF_MAX_DEG];
    int n = degree, i, j, cnt = 0, z = 0;
    while (n > 0 && cd[n] == 0) n--;
    while (z < n && cd[z] == 0) z++;
    if (z > 0) rr[cnt++] = 0;
    if (n - z > 0) {
        ref_roots_all(cd + z, n - z, all);
        for (i = 0; i < n - z; i++)
            if (all[i].im_rel <= real_tol) rr[cnt++] = all[i].qre;
    }
    for (i = 1; i < cnt; i++)
        for (j = i; j > 0 && rr[j] < rr[j - 1]; j--) {
            __float128 t = rr[j]; rr[j] = rr[j - 1]; rr[j - 1] = t;
        }
    return cnt;
}

/* Polynomial coefficients (increasing degree) from roots, computed in quad
   and rounded to double once: c = lead * prod (x - roots[i]) * prod over
   complex pairs (x^2 - 2 re x + re^2 + im^2). */
static void ref_coeffs_from_roots(const __float128 *roots, int nr, const __float128 (*pairs)[2], int np,
                                  __float128 lead, double *c)
{
    __float128 q[REF_MAX_DEG + 1];
    int n = 0, i, k;
    q[0] = lead;
    for (k = 0; k < nr; k++) {
        q[n + 1] = 0;
        for (i = n + 1; i > 0; i--) q[i] = q[i - 1] - roots[k] * q[i];
        q[0] = -roots[k] * q[0];
        n++;
    }
    for (k = 0; k < np; k++) {
        __float128 b = -2 * pairs[k][0], cc = pairs[k][0] * pairs[k][0] + pairs[k][1] * pairs[k][1];
        q[n + 1] = 0;
        q[n + 2] = 0;
        for (i = n + 2; i >= 0; i--) {
            __float128 v = (i >= 2 ? q[i - 2] : 0) + (i >= 1 ? b * q[i - 1] : 0) + cc * q[i];
            q[i] = v;
        }
        n += 2;
    }
    for (i = 0; i <= n; i++) c[i] = (double)q[i];
}

#endif
