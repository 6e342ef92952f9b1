/* bench/bench_frep_solve.c -- quartic solvers, error against run time.

   Three solvers side by side, in one run:
     frep    fr_solve_quartic (derivative-sequence isolation + compensated polish)
     naive   textbook Ferrari with a Cardano resolvent (written here)
     gsl     gsl_poly_complex_solve (companion-matrix QR), real roots taken
   Accuracy is the relative forward error of every real root returned, against
   the roots of the polynomial whose coefficients are the doubles passed in,
   computed in __float128 (tests/test_frep_solve_ref.h). A reference real root
   with no returned root within 1e-6 relative is a miss; a returned root with
   no reference root (real, or complex with |Im|/|z| <= 1e-6) within 1e-6 is
   spurious.
   Sets: the 24 cases of Orellana & De Michele's published accuracy driver
   (ACM TOMS Algorithm 1010, Table 1: Flocke's and Strobach's quartics and
   theirs; tests/test_frep_solve_odm.h says why not 26),
   and 10^6 random quartics with roots uniform in [-1, 1] (real parts and
   imaginary parts), a third each with 4, 2 and 0 real roots, and 2.5e5
   draws of the family the authors searched their remark cases 25-26 in
   (x^4 -+ 1e-162 x^3 + A x^2 +- 1e-162 x + B, A, B uniform in [-50, 50]).
   Timing: ns per solve by class (random quartics by number of real roots,
   the ODM cases, random cubics, fr_solve_poly for degrees 5..10 on the whole
   line), all against GSL in the same process, thread CPU time, minimum of 5
   repetitions with the solvers interleaved.
   Per ODM case, ns per solve of the case repeated alone, next to GSL.
   Usage: bench_frep_solve OUTDIR  (CSV: OUTDIR/frep_solve_odm.csv, frep_solve_random.csv,
   frep_solve_odm_family.csv, frep_solve_time.csv, frep_solve_odm_time.csv) */
#define IV_IMPLEMENTATION
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include "test_frep_solve_ref.h"
#include "test_frep_solve_odm.h"
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MATCH_REL 1e-6
#define NEAR_REAL 1e-6

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts); /* CPU time: robust to a loaded machine */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---------------------------------------------------------------- naive Ferrari / Cardano */

/* One real root of y^3 + a y^2 + b y + c (Cardano, trigonometric when three real). */
static double naive_cubic_root(double a, double b, double c)
{
    double Q = (a * a - 3 * b) / 9, R = (2 * a * a * a - 9 * a * b + 27 * c) / 54;
    if (R * R < Q * Q * Q) {
        double th = acos(R / sqrt(Q * Q * Q));
        return -2 * sqrt(Q) * cos(th / 3) - a / 3;
    } else {
        double A = -copysign(cbrt(fabs(R) + sqrt(R * R - Q * Q * Q)), R), B = A != 0 ? Q / A : 0;
        return A + B - a / 3;
    }
}

static int naive_quadratic(double b, double c, double *r) /* y^2 + b y + c */
{
    double d = b * b - 4 * c;
    if (d < 0) return 0;
    r[0] = (-b - sqrt(d)) / 2;
    r[1] = (-b + sqrt(d)) / 2;
    return 2;
}

static int naive_quartic(const double *cf, double *r)
{
    double a = cf[3] / cf[4], b = cf[2] / cf[4], c = cf[1] / cf[4], d = cf[0] / cf[4];
    double p = b - 3 * a * a / 8, q = c - a * b / 2 + a * a * a / 8;
    double rr = d - a * c / 4 + a * a * b / 16 - 3 * a * a * a * a / 256, y[4];
    int n = 0, i;
    if (q == 0) { /* biquadratic */
        double z[2];
        int k, nz = naive_quadratic(p, rr, z);
        for (k = 0; k < nz; k++)
            if (z[k] >= 0) { y[n++] = sqrt(z[k]); y[n++] = -sqrt(z[k]); }
    } else {
        /* resolvent m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0, largest real root */
        double m = naive_cubic_root(p, p * p / 4 - rr, -q * q / 8), s;
        if (m <= 0) return 0;
        s = sqrt(2 * m);
        n = naive_quadratic(s, p / 2 + m - q / (2 * s), y);
        n += naive_quadratic(-s, p / 2 + m + q / (2 * s), y + n);
    }
    for (i = 0; i < n; i++) r[i] = y[i] - a / 4;
    return n;
}

/* ---------------------------------------------------------------- GSL */

static gsl_poly_complex_workspace *gsl_ws;
static int gsl_quartic(const double *c, double *r)
{
    double z[8];
    int i, n = 0;
    if (gsl_poly_complex_solve(c, 5, gsl_ws, z) != GSL_SUCCESS) return 0;
    for (i = 0; i < 4; i++)
        if (z[2 * i + 1] == 0) r[n++] = z[2 * i];
    return n;
}

static int frep_quartic(const double *c, double *r) { return fr_solve_quartic(c, r); }

/* cubics and degree 5..10 (fr_solve_poly on the whole line) against GSL */
static int g_deg;
static gsl_poly_complex_workspace *gsl_wsd[11];
static int frep_cubic(const double *c, double *r) { return fr_solve_cubic(c, r); }
static int frep_poly(const double *c, double *r) { return fr_solve_poly(c, g_deg, -HUGE_VAL, HUGE_VAL, r); }
static int gsl_poly(const double *c, double *r)
{
    double z[20];
    int i, n = 0;
    if (gsl_poly_complex_solve(c, (size_t)g_deg + 1, gsl_wsd[g_deg], z) != GSL_SUCCESS) return 0;
    for (i = 0; i < g_deg; i++)
        if (z[2 * i + 1] == 0) r[n++] = z[2 * i];
    return n;
}

typedef int (*solver_fn)(const double *, double *);
static double *g_family; /* the ODM remark family's draws, for the timing table */
static long g_family_n;
static const char *solver_names[3] = {"frep", "naive", "gsl"};
static solver_fn solvers[3] = {frep_quartic, naive_quartic, gsl_quartic};

/* ---------------------------------------------------------------- scoring */

typedef struct ref_t {
    int n;
    double re[4], im_rel[4];
    __float128 qre[4];
} ref_t;

typedef struct score_t {
    double max_rel;
    long misses, spurious, roots;
} score_t;

static void score(const ref_t *ref, const double *r, int n, score_t *s)
{
    int i, k;
    /* misses: each real reference root needs a returned root nearby */
    for (k = 0; k < ref->n; k++) {
        double best = HUGE_VAL;
        if (ref->im_rel[k] > 1e-20) continue;
        for (i = 0; i < n; i++) {
            double e = (double)(fabsq((__float128)r[i] - ref->qre[k]) / fabsq(ref->qre[k]));
            if (e < best) best = e;
        }
        if (!(best <= MATCH_REL)) s->misses++;
    }
    for (i = 0; i < n; i++) {
        double best = HUGE_VAL;
        for (k = 0; k < ref->n; k++) {
            double e;
            if (ref->im_rel[k] > NEAR_REAL) continue;
            e = (double)(fabsq((__float128)r[i] - ref->qre[k]) / fabsq(ref->qre[k]));
            if (e < best) best = e;
        }
        s->roots++;
        if (!(best <= MATCH_REL)) s->spurious++;
        else if (best > s->max_rel) s->max_rel = best;
    }
}

/* Reference: Aberth in quad on the double coefficients (no merging: a
   complex pair 1e-8 off the axis stays complex). */
static void reference_aberth(const double *c, ref_t *ref)
{
    ref_root_t all[4];
    int i;
    ref_roots_all(c, 4, all);
    ref->n = 4;
    for (i = 0; i < 4; i++) {
        ref->qre[i] = all[i].qre;
        ref->im_rel[i] = all[i].im_rel;
        ref->re[i] = (double)ref->qre[i];
    }
}

/* Fast reference for well-separated random roots: real quad Newton from
   each known real root on the double-coefficient polynomial. A complex
   pair at least 1e-6 (relative) off the axis cannot turn real under the
   rounding of the coefficients (which moves roots by ~1e-16 relative), so it
   is kept as the known pair; only real roots need quad values. Falls back to
   Aberth when two real iterates meet or one does not settle. */
static void reference_newton(const double *c, const __float128 *kre, const __float128 *kim, ref_t *ref)
{
    __float128 q[5];
    int i, k, j, ok = 1;
    for (i = 0; i < 5; i++) q[i] = c[i];
    for (k = 0; k < 4 && ok; k++) {
        __float128 z = kre[k], mag = sqrtq(kre[k] * kre[k] + kim[k] * kim[k]);
        ref->qre[k] = kre[k];
        ref->im_rel[k] = mag > 0 ? (double)(fabsq(kim[k]) / mag) : 0.0;
        if (kim[k] != 0) {
            if (ref->im_rel[k] < 1e-6) ok = 0;
            continue;
        }
        for (j = 0; j < 40; j++) {
            __float128 p = q[4], d = 0, step;
            for (i = 3; i >= 0; i--) { d = d * z + p; p = p * z + q[i]; }
            if (p == 0 || d == 0) break;
            step = p / d;
            z -= step;
            if (fabsq(step) <= 1e-30Q * fabsq(z)) break;
        }
        if (j == 40) ok = 0;
        ref->qre[k] = z;
        ref->im_rel[k] = 0;
        for (i = 0; i < k; i++)
            if (kim[i] == 0 && fabsq(ref->qre[i] - z) < 1e-20Q * fabsq(z)) ok = 0;
    }
    ref->n = 4;
    if (!ok) reference_aberth(c, ref);
}

/* ---------------------------------------------------------------- timing */

/* ns per solve of f over count polynomials (stride doubles apart, starting
   at first, every step-th), once. */
static double time_once(solver_fn f, const double *coef, int stride, long first, long step, long count)
{
    double t0 = now_s(), sink = 0, r[16];
    long i, m = 0;
    for (i = first; m < count; i += step, m++) {
        int n = f(coef + (size_t)stride * (size_t)i, r);
        if (n > 0) sink += r[0];
    }
    t0 = (now_s() - t0) * 1e9 / (double)count;
    return sink == 12345.678 ? t0 + 1 : t0;
}

/* Minimum over reps of ns per solve, the solvers interleaved within each
   repetition so that a change in machine load hits them alike. */
static void time_table(const char *label, solver_fn *fs, int nf, const double *coef, int stride, long first,
                       long step, long count, int reps, FILE *csv)
{
    double best[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    int rep, s;
    for (rep = 0; rep < reps; rep++)
        for (s = 0; s < nf; s++) {
            double t = time_once(fs[s], coef, stride, first, step, count);
            if (t < best[s]) best[s] = t;
        }
    printf("%-28s", label);
    for (s = 0; s < nf; s++) printf(" %9.1f", best[s]);
    printf("   gsl/frep %5.2f\n", best[nf - 1] / best[0]);
    if (csv) {
        fprintf(csv, "%s,%ld", label, count);
        for (s = 0; s < 3; s++) fprintf(csv, ",%.1f", s < nf ? best[s] : -1.0);
        fprintf(csv, ",%.2f\n", best[nf - 1] / best[0]);
    }
}

/* ns per solve of each ODM case alone (the case repeated reps times, so the
   branch predictor learns its path; the mixed-stream figure of the time
   table is the one the goal is judged by), solvers interleaved, min of 5;
   CSV OUTDIR/frep_solve_odm_time.csv. The sums show which cases carry the
   mixed figure. */
static void odm_case_times(long reps, const char *dir)
{
    char path[1024];
    double *buf = (double *)malloc(sizeof(double) * 5 * (size_t)reps), sum[3] = {0, 0, 0};
    FILE *csv;
    long m;
    int k, s, rep;
    if (!buf) return;
    snprintf(path, sizeof path, "%s/frep_solve_odm_time.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "case,frep_ns,naive_ns,gsl_ns,gsl_over_frep\n");
    printf("\nns per solve of each ODM case alone (repeated %ld times, min of 5, solvers interleaved)\n", reps);
    printf("%5s %9s %9s %9s %9s\n", "case", "frep", "naive", "gsl", "gsl/frep");
    for (k = 1; k <= ODM_NCASES; k++) {
        double best[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
        __float128 ex[4];
        for (m = 0; m < reps; m++) odm_case(k, buf + 5 * m, ex);
        for (rep = 0; rep < 5; rep++)
            for (s = 0; s < 3; s++) {
                double t = time_once(solvers[s], buf, 5, 0, 1, reps);
                if (t < best[s]) best[s] = t;
            }
        for (s = 0; s < 3; s++) sum[s] += best[s];
        printf("%5d %9.1f %9.1f %9.1f %9.2f\n", k, best[0], best[1], best[2], best[2] / best[0]);
        if (csv) fprintf(csv, "%d,%.1f,%.1f,%.1f,%.2f\n", k, best[0], best[1], best[2], best[2] / best[0]);
    }
    printf("%5s %9.1f %9.1f %9.1f %9.2f\n", "sum", sum[0], sum[1], sum[2], sum[2] / sum[0]);
    if (csv) fclose(csv);
    free(buf);
}

/* A random polynomial of degree deg with roots in [-1, 1] (real ones) and
   pairs with real and imaginary parts in [-1, 1] x (0, 1]: nreal real roots. */
static void random_poly(unsigned long long *st, int deg, int nreal, double *c)
{
    __float128 re[10], pr[5][2];
    int j, np = (deg - nreal) / 2;
    for (j = 0; j < nreal + 2 * np; j++) {
        unsigned long long z = (*st += 0x9E3779B97F4A7C15ull);
        double u;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        u = 2.0 * ((double)(z >> 11) * (1.0 / 9007199254740992.0)) - 1.0;
        if (j < nreal) re[j] = u;
        else if ((j - nreal) % 2 == 0) pr[(j - nreal) / 2][0] = u;
        else pr[(j - nreal) / 2][1] = fabs(u) + 1e-3;
    }
    ref_coeffs_from_roots(re, nreal, (const __float128(*)[2])pr, np, 1, c);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    char path[1024];
    FILE *csv;
    long N = 1000000, i;
    int k, s;
    double *coef;
    ref_t *refs;
    score_t tot[3];
    double ns[3];
    gsl_set_error_handler_off();
    gsl_ws = gsl_poly_complex_workspace_alloc(5);

    /* ---- ODM cases */
    snprintf(path, sizeof path, "%s/frep_solve_odm.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "case,real_roots,frep_rel,frep_miss,frep_spur,naive_rel,naive_miss,naive_spur,gsl_rel,gsl_miss,gsl_spur\n");
    printf("ODM 2020 accuracy cases: max relative forward error of real roots (misses/spurious)\n");
    printf("%5s %5s | %-20s | %-20s | %-20s\n", "case", "real", "frep", "naive Ferrari", "gsl complex_solve");
    memset(tot, 0, sizeof tot);
    for (k = 1; k <= ODM_NCASES; k++) {
        double c[5], r[4];
        ref_t ref;
        score_t sc[3];
        int nreal = 0, j;
        __float128 ex[4];
        if (odm_case(k, c, ex)) { /* exact coefficients: the known roots are exact */
            ref.n = 4;
            for (j = 0; j < 4; j++) { ref.qre[j] = ex[j]; ref.re[j] = (double)ex[j]; ref.im_rel[j] = 0; }
        } else
            reference_aberth(c, &ref);
        for (j = 0; j < 4; j++) nreal += ref.im_rel[j] <= 1e-20;
        memset(sc, 0, sizeof sc);
        for (s = 0; s < 3; s++) {
            int n = solvers[s](c, r);
            score(&ref, r, n, &sc[s]);
            if (sc[s].max_rel > tot[s].max_rel) tot[s].max_rel = sc[s].max_rel;
            tot[s].misses += sc[s].misses;
            tot[s].spurious += sc[s].spurious;
        }
        printf("%5d %5d |", k, nreal);
        for (s = 0; s < 3; s++) printf(" %9.2e (%ld/%ld)    |", sc[s].max_rel, sc[s].misses, sc[s].spurious);
        printf("\n");
        if (csv) {
            fprintf(csv, "%d,%d", k, nreal);
            for (s = 0; s < 3; s++) fprintf(csv, ",%.3e,%ld,%ld", sc[s].max_rel, sc[s].misses, sc[s].spurious);
            fprintf(csv, "\n");
        }
    }
    printf("  all       |");
    for (s = 0; s < 3; s++) printf(" %9.2e (%ld/%ld)    |", tot[s].max_rel, tot[s].misses, tot[s].spurious);
    printf("\n\n");
    if (csv) fclose(csv);

    /* ---- random quartics */
    if (getenv("FILIGREE_BENCH_N")) N = atol(getenv("FILIGREE_BENCH_N"));
    coef = (double *)malloc(sizeof(double) * 5 * (size_t)N);
    refs = (ref_t *)malloc(sizeof(ref_t) * (size_t)N);
    if (!coef || !refs) return 1;
    {
        unsigned long long st = 2024;
        for (i = 0; i < N; i++) {
            __float128 kre[4], kim[4], re[4], pr[2][2];
            double u[8];
            int kind = (int)(i % 3), j, nr = 0, np = 0;
            for (j = 0; j < 8; j++) {
                unsigned long long z = (st += 0x9E3779B97F4A7C15ull);
                z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
                z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
                z ^= z >> 31;
                u[j] = 2.0 * ((double)(z >> 11) * (1.0 / 9007199254740992.0)) - 1.0;
            }
            if (kind == 0) { for (j = 0; j < 4; j++) re[nr++] = u[j]; }
            else if (kind == 1) { re[nr++] = u[0]; re[nr++] = u[1]; pr[np][0] = u[2]; pr[np][1] = fabs(u[3]); np++; }
            else { pr[np][0] = u[0]; pr[np][1] = fabs(u[1]); np++; pr[np][0] = u[2]; pr[np][1] = fabs(u[3]); np++; }
            ref_coeffs_from_roots(re, nr, (const __float128(*)[2])pr, np, 1, coef + 5 * i);
            for (j = 0; j < nr; j++) { kre[j] = re[j]; kim[j] = 0; }
            for (j = 0; j < np; j++) {
                kre[nr + 2 * j] = pr[j][0]; kim[nr + 2 * j] = pr[j][1];
                kre[nr + 2 * j + 1] = pr[j][0]; kim[nr + 2 * j + 1] = -pr[j][1];
            }
            reference_newton(coef + 5 * i, kre, kim, &refs[i]);
            if (i % 100000 == 0) fprintf(stderr, "reference %ld/%ld\n", i, N);
        }
    }
    memset(tot, 0, sizeof tot);
    for (s = 0; s < 3; s++) {
        double t0, sink = 0, r[4];
        int rep;
        for (i = 0; i < N; i++) {
            int n = solvers[s](coef + 5 * i, r);
            score(&refs[i], r, n, &tot[s]);
        }
        ns[s] = HUGE_VAL;
        for (rep = 0; rep < 3; rep++) {
            t0 = now_s();
            for (i = 0; i < N; i++) {
                int n = solvers[s](coef + 5 * i, r);
                if (n > 0) sink += r[0];
            }
            t0 = (now_s() - t0) * 1e9 / (double)N;
            if (t0 < ns[s]) ns[s] = t0;
        }
        if (sink == 12345.678) printf(" ");
        fprintf(stderr, "timed %s\n", solver_names[s]);
    }
    printf("%ld random quartics (roots in [-1,1]^2): max rel error, misses, spurious, ns/solve, time vs frep\n", N);
    printf("%-8s %11s %9s %9s %9s %8s\n", "solver", "max_rel", "misses", "spurious", "ns", "ratio");
    snprintf(path, sizeof path, "%s/frep_solve_random.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "solver,n,max_rel,misses,spurious,ns_per_solve,time_ratio_vs_frep\n");
    for (s = 0; s < 3; s++) {
        printf("%-8s %11.2e %9ld %9ld %9.1f %8.2f\n", solver_names[s], tot[s].max_rel, tot[s].misses, tot[s].spurious,
               ns[s], ns[s] / ns[0]);
        if (csv)
            fprintf(csv, "%s,%ld,%.3e,%ld,%ld,%.1f,%.2f\n", solver_names[s], N, tot[s].max_rel, tot[s].misses,
                    tot[s].spurious, ns[s], ns[s] / ns[0]);
    }
    if (csv) fclose(csv);

    printf("\n");
    /* ---- the ODM remark family, drawn as the authors' search driver draws
       it (cridemichel/quartic_C, Drivers/accuracytest.c): x^4 - 1e-162 x^3
       + A x^2 + 1e-162 x + B, A and B uniform in [-50, 50]; the driver
       flags a solver whose summed relative error over the roots exceeds
       1e-3. Cases 25 and 26 are two such draws, listed nowhere we can
       reach. Reference: Aberth in quad on the very doubles. */
    {
        long M = N / 4 > 1000 ? N / 4 : 1000, m;
        double *fc = (double *)malloc(sizeof(double) * 5 * (size_t)M);
        ref_t *fr = (ref_t *)malloc(sizeof(ref_t) * (size_t)M);
        unsigned long long st = 1010;
        long flagged[3] = {0, 0, 0};
        if (!fc || !fr) return 1;
        for (m = 0; m < M; m++) {
            double u[2];
            int j;
            for (j = 0; j < 2; j++) {
                unsigned long long z = (st += 0x9E3779B97F4A7C15ull);
                z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
                z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
                z ^= z >> 31;
                u[j] = ((double)(z >> 11) * (1.0 / 9007199254740992.0) - 0.5) * 100.0;
            }
            fc[5 * m] = u[1]; fc[5 * m + 1] = 1e-162; fc[5 * m + 2] = u[0]; fc[5 * m + 3] = -1e-162; fc[5 * m + 4] = 1;
            reference_aberth(fc + 5 * m, &fr[m]);
            if (m % 50000 == 0) fprintf(stderr, "remark family reference %ld/%ld\n", m, M);
        }
        memset(tot, 0, sizeof tot);
        for (s = 0; s < 3; s++)
            for (m = 0; m < M; m++) {
                double r[4];
                score_t one;
                int n = solvers[s](fc + 5 * m, r);
                memset(&one, 0, sizeof one);
                score(&fr[m], r, n, &one);
                if (one.misses || one.spurious || one.max_rel * (double)(n > 0 ? n : 1) > 1e-3) flagged[s]++;
                tot[s].misses += one.misses; tot[s].spurious += one.spurious; tot[s].roots += one.roots;
                if (one.max_rel > tot[s].max_rel) tot[s].max_rel = one.max_rel;
            }
        printf("ODM remark family, %ld draws of x^4 - 1e-162 x^3 + A x^2 + 1e-162 x + B, A, B uniform in [-50, 50]\n", M);
        printf("(cases 25-26 of the issue are two such draws, published nowhere we can reach; flagged: the driver's test,\n");
        printf(" summed relative error > 1e-3, here any miss, spurious root or real-root error above it)\n");
        printf("%-8s %11s %9s %9s %9s\n", "solver", "max_rel", "misses", "spurious", "flagged");
        snprintf(path, sizeof path, "%s/frep_solve_odm_family.csv", dir);
        csv = fopen(path, "w");
        if (csv) fprintf(csv, "solver,draws,max_rel,misses,spurious,flagged\n");
        for (s = 0; s < 3; s++) {
            printf("%-8s %11.2e %9ld %9ld %9ld\n", solver_names[s], tot[s].max_rel, tot[s].misses, tot[s].spurious, flagged[s]);
            if (csv)
                fprintf(csv, "%s,%ld,%.3e,%ld,%ld,%ld\n", solver_names[s], M, tot[s].max_rel, tot[s].misses, tot[s].spurious,
                        flagged[s]);
        }
        if (csv) fclose(csv);
        free(fr);
        g_family = fc;
        g_family_n = M;
    }

    /* ---- ns per solve by class, solvers interleaved (min of 5) */
    snprintf(path, sizeof path, "%s/frep_solve_time.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "class,n,frep_ns,naive_ns,gsl_ns,gsl_over_frep\n");
    printf("\nns per solve by class (thread CPU time, min of 5, solvers interleaved)\n");
    printf("%-28s %9s %9s %9s\n", "class", "frep", "naive", "gsl");
    time_table("quartic random, all", solvers, 3, coef, 5, 0, 1, N, 5, csv);
    time_table("quartic random, 4 real", solvers, 3, coef, 5, 0, 3, N / 3, 5, csv);
    time_table("quartic random, 2 real", solvers, 3, coef, 5, 1, 3, N / 3, 5, csv);
    time_table("quartic random, 0 real", solvers, 3, coef, 5, 2, 3, N / 3, 5, csv);
    {
        /* the ODM cases, each repeated */
        long reps = N / 50 > 1 ? N / 50 : 1, m;
        double *odm = (double *)malloc(sizeof(double) * 5 * (size_t)(ODM_NCASES * reps));
        if (!odm) return 1;
        for (m = 0; m < ODM_NCASES * reps; m++) {
            __float128 ex[4];
            odm_case((int)(m % ODM_NCASES) + 1, odm + 5 * m, ex);
        }
        time_table("quartic ODM cases 1-24", solvers, 3, odm, 5, 0, 1, ODM_NCASES * reps, 5, csv);
        free(odm);
    }
    time_table("quartic ODM remark family", solvers, 3, g_family, 5, 0, 1, g_family_n, 5, csv);
    free(g_family);
    {
        long M = N / 5 > 1000 ? N / 5 : 1000, m;
        double *pc = (double *)malloc(sizeof(double) * 11 * (size_t)M);
        unsigned long long st = 77;
        solver_fn cub[2] = {frep_cubic, gsl_poly}, pol[2] = {frep_poly, gsl_poly};
        int deg;
        if (!pc) return 1;
        for (deg = 3; deg <= 10; deg++) gsl_wsd[deg] = gsl_poly_complex_workspace_alloc((size_t)deg + 1);
        g_deg = 3;
        for (m = 0; m < M; m++) random_poly(&st, 3, m % 2 ? 1 : 3, pc + 11 * m);
        printf("%-28s %9s %9s %9s\n", "", "frep", "gsl", "");
        time_table("cubic random, 3 real", cub, 2, pc, 11, 0, 2, M / 2, 5, csv);
        time_table("cubic random, 1 real", cub, 2, pc, 11, 1, 2, M / 2, 5, csv);
        for (deg = 5; deg <= 10; deg++) {
            char label[64];
            long M2 = M / 10 > 100 ? M / 10 : 100;
            g_deg = deg;
            for (m = 0; m < M2; m++) random_poly(&st, deg, (int)(m % (unsigned)(deg / 2 + 1)) * 2 + deg % 2, pc + 11 * m);
            snprintf(label, sizeof label, "poly degree %d (whole line)", deg);
            time_table(label, pol, 2, pc, 11, 0, 1, M2, 5, csv);
        }
        for (deg = 3; deg <= 10; deg++) gsl_poly_complex_workspace_free(gsl_wsd[deg]);
        free(pc);
    }
    if (csv) fclose(csv);
    odm_case_times(N / 50 > 100 ? N / 50 : 100, dir);
    gsl_poly_complex_workspace_free(gsl_ws);
    free(coef);
    free(refs);
    return 0;
}
