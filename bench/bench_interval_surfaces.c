/* bench/bench_interval_surfaces.c — enclosure error against run time
   (issue 3): for the tangle cube, the Barth sextic, the Steiner (Roman)
   surface and a torus quartic, evaluate f over ray segments of several
   lengths with interval arithmetic and with reduced affine arithmetic,
   and report the width of each enclosure divided by the true range of f on
   the segment (dense sampling, 1024 points: an independent reference that
   can only underestimate the true range, so ratios err high), next to the
   time per evaluation and the plain double evaluation's time.
   Output: table on stdout, out/bench/interval_surfaces.csv. */
#define IV_IMPLEMENTATION
#include "interval.h"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define PHI 1.6180339887498949
#define TORUS_R 1.0
#define TORUS_r 0.4

typedef struct seg_t { double o[3], d[3], t0, t1; } seg_t;

/* ------------------------------------------------------------ surfaces */
static double tangle_d(double x, double y, double z)
{
    double x2 = x * x, y2 = y * y, z2 = z * z;
    return x2 * x2 - 5 * x2 + y2 * y2 - 5 * y2 + z2 * z2 - 5 * z2 + 11.8;
}
static iv_t tangle_i(iv_t x, iv_t y, iv_t z)
{
    iv_t x2 = iv_sqr(x), y2 = iv_sqr(y), z2 = iv_sqr(z);
    iv_t s = iv_add(iv_sub(iv_sqr(x2), iv_mul_d(x2, 5)), iv_sub(iv_sqr(y2), iv_mul_d(y2, 5)));
    return iv_add_d(iv_add(s, iv_sub(iv_sqr(z2), iv_mul_d(z2, 5))), 11.8);
}
static iv_affine_t tangle_a(iv_affine_t x, iv_affine_t y, iv_affine_t z)
{
    iv_affine_t x2 = iv_affine_sqr(x), y2 = iv_affine_sqr(y), z2 = iv_affine_sqr(z);
    iv_affine_t s = iv_affine_add(iv_affine_sub(iv_affine_sqr(x2), iv_affine_mul_d(x2, 5)),
                                  iv_affine_sub(iv_affine_sqr(y2), iv_affine_mul_d(y2, 5)));
    return iv_affine_add_d(iv_affine_add(s, iv_affine_sub(iv_affine_sqr(z2), iv_affine_mul_d(z2, 5))), 11.8);
}

/* Barth sextic: 4(p x^2 - y^2)(p y^2 - z^2)(p z^2 - x^2) - (1 + 2 phi)(x^2 + y^2 + z^2 - 1)^2, p = phi^2 */
static double barth_d(double x, double y, double z)
{
    double p = PHI * PHI, x2 = x * x, y2 = y * y, z2 = z * z, s = x2 + y2 + z2 - 1;
    return 4 * (p * x2 - y2) * (p * y2 - z2) * (p * z2 - x2) - (1 + 2 * PHI) * s * s;
}
static iv_t barth_i(iv_t x, iv_t y, iv_t z)
{
    double p = PHI * PHI;
    iv_t x2 = iv_sqr(x), y2 = iv_sqr(y), z2 = iv_sqr(z);
    iv_t a = iv_sub(iv_mul_d(x2, p), y2), b = iv_sub(iv_mul_d(y2, p), z2), c = iv_sub(iv_mul_d(z2, p), x2);
    iv_t s = iv_add_d(iv_add(iv_add(x2, y2), z2), -1);
    return iv_sub(iv_mul_d(iv_mul(iv_mul(a, b), c), 4), iv_mul_d(iv_sqr(s), 1 + 2 * PHI));
}
static iv_affine_t barth_a(iv_affine_t x, iv_affine_t y, iv_affine_t z)
{
    double p = PHI * PHI;
    iv_affine_t x2 = iv_affine_sqr(x), y2 = iv_affine_sqr(y), z2 = iv_affine_sqr(z);
    iv_affine_t a = iv_affine_sub(iv_affine_mul_d(x2, p), y2), b = iv_affine_sub(iv_affine_mul_d(y2, p), z2);
    iv_affine_t c = iv_affine_sub(iv_affine_mul_d(z2, p), x2);
    iv_affine_t s = iv_affine_add_d(iv_affine_add(iv_affine_add(x2, y2), z2), -1);
    return iv_affine_sub(iv_affine_mul_d(iv_affine_mul(iv_affine_mul(a, b), c), 4),
                         iv_affine_mul_d(iv_affine_sqr(s), 1 + 2 * PHI));
}

/* Steiner's Roman surface: x^2 y^2 + y^2 z^2 + z^2 x^2 - x y z */
static double steiner_d(double x, double y, double z)
{
    return x * x * y * y + y * y * z * z + z * z * x * x - x * y * z;
}
static iv_t steiner_i(iv_t x, iv_t y, iv_t z)
{
    iv_t x2 = iv_sqr(x), y2 = iv_sqr(y), z2 = iv_sqr(z);
    return iv_sub(iv_add(iv_add(iv_mul(x2, y2), iv_mul(y2, z2)), iv_mul(z2, x2)), iv_mul(iv_mul(x, y), z));
}
static iv_affine_t steiner_a(iv_affine_t x, iv_affine_t y, iv_affine_t z)
{
    iv_affine_t x2 = iv_affine_sqr(x), y2 = iv_affine_sqr(y), z2 = iv_affine_sqr(z);
    return iv_affine_sub(iv_affine_add(iv_affine_add(iv_affine_mul(x2, y2), iv_affine_mul(y2, z2)), iv_affine_mul(z2, x2)),
                         iv_affine_mul(iv_affine_mul(x, y), z));
}

/* torus quartic: (x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) */
static double torus_d(double x, double y, double z)
{
    double q = x * x + y * y, s = q + z * z + TORUS_R * TORUS_R - TORUS_r * TORUS_r;
    return s * s - 4 * TORUS_R * TORUS_R * q;
}
static iv_t torus_i(iv_t x, iv_t y, iv_t z)
{
    iv_t q = iv_add(iv_sqr(x), iv_sqr(y)), s = iv_add_d(iv_add(q, iv_sqr(z)), TORUS_R * TORUS_R - TORUS_r * TORUS_r);
    return iv_sub(iv_sqr(s), iv_mul_d(q, 4 * TORUS_R * TORUS_R));
}
static iv_affine_t torus_a(iv_affine_t x, iv_affine_t y, iv_affine_t z)
{
    iv_affine_t q = iv_affine_add(iv_affine_sqr(x), iv_affine_sqr(y));
    iv_affine_t s = iv_affine_add_d(iv_affine_add(q, iv_affine_sqr(z)), TORUS_R * TORUS_R - TORUS_r * TORUS_r);
    return iv_affine_sub(iv_affine_sqr(s), iv_affine_mul_d(q, 4 * TORUS_R * TORUS_R));
}

typedef struct surface_t {
    const char *name;
    double half; /* half the edge of the box holding the surface: size = 2*half */
    double (*fd)(double, double, double);
    iv_t (*fi)(iv_t, iv_t, iv_t);
    iv_affine_t (*fa)(iv_affine_t, iv_affine_t, iv_affine_t);
} surface_t;

static const surface_t surfaces[] = {
    {"tangle", 2.6, tangle_d, tangle_i, tangle_a},
    {"barth", 1.8, barth_d, barth_i, barth_a},
    {"steiner", 0.6, steiner_d, steiner_i, steiner_a},
    {"torus", 1.5, torus_d, torus_i, torus_a},
};

/* ------------------------------------------------------------ helpers */
static unsigned long long rng = 0x2545F4914F6CDD1Dull;
static double urand(void)
{
    rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}
/* the thread's CPU time: time spent descheduled on a shared machine does
   not count */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static iv_t seg_iv(const seg_t *s, int k)
{
    return iv_add_d(iv_mul_d(iv_make(s->t0, s->t1), s->d[k]), s->o[k]);
}
static iv_affine_t seg_aff(const seg_t *s, iv_affine_t t, int k)
{
    return iv_affine_add_d(iv_affine_mul_d(t, s->d[k]), s->o[k]);
}
static iv_t eval_iv(const surface_t *f, const seg_t *s)
{
    return f->fi(seg_iv(s, 0), seg_iv(s, 1), seg_iv(s, 2));
}
static iv_t eval_aff(const surface_t *f, const seg_t *s)
{
    iv_affine_t t = iv_affine_ray_param(s->t0, s->t1);
    return iv_from_affine(f->fa(seg_aff(s, t, 0), seg_aff(s, t, 1), seg_aff(s, t, 2)));
}
static double true_range(const surface_t *f, const seg_t *s)
{
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    int i;
    for (i = 0; i <= 1024; i++) {
        double t = s->t0 + (s->t1 - s->t0) * (double)i / 1024.0;
        double v = f->fd(s->o[0] + t * s->d[0], s->o[1] + t * s->d[1], s->o[2] + t * s->d[2]);
        if (v < lo) lo = v;
        if (v > hi) hi = v;
    }
    return hi - lo;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

enum { RAYS = 2000, REPS = 8 };

/* ------------------------------------------- non-affine linearisations */
/* The affine forms of exp log sqrt recip atan pow_n by each method of
   interval.h (iv__aff_unary: Taylor, Chebyshev, min-range, and the
   default per-range choice): (1) overestimation (width of the enclosure
   minus the true range, from 4097 samples) of f(t) - k t over a segment of
   the ray parameter t, k = 0 (the single operation) and k != 0 (what a
   later operation can cancel); (2) two implicit surfaces that use such
   operations, over random ray segments: a sphere distance
   sqrt(x^2+y^2+z^2) - 1 and a two-centre blob exp(-4|p-c1|^2) +
   exp(-4|p-c2|^2) - 0.5. */
typedef struct lin_case_t { const char *name; int f, n; double a, b, k; } lin_case_t;
static double lin_f(int f, int n, double x)
{
    switch (f) {
    case IV__F_EXP: return exp(x);
    case IV__F_LOG: return log(x);
    case IV__F_SQRT: return sqrt(x);
    case IV__F_RECIP: return 1 / x;
    case IV__F_POWN: return pow(x, n);
    default: return atan(x);
    }
}
static const char *const lin_names[4] = {"taylor", "chebyshev", "min-range", "default"};

static iv_affine_t sq3(iv_affine_t x, iv_affine_t y, iv_affine_t z)
{
    return iv_affine_add(iv_affine_add(iv_affine_sqr(x), iv_affine_sqr(y)), iv_affine_sqr(z));
}
static double sphere_d(double x, double y, double z) { return sqrt(x * x + y * y + z * z) - 1; }
static iv_affine_t sphere_m(iv_affine_t x, iv_affine_t y, iv_affine_t z, int m)
{
    return iv_affine_sub_d(iv__aff_unary(sq3(x, y, z), IV__F_SQRT, 0, m), 1);
}
static double blob_d(double x, double y, double z)
{
    return exp(-4 * ((x + 0.4) * (x + 0.4) + y * y + z * z)) + exp(-4 * ((x - 0.4) * (x - 0.4) + y * y + z * z)) - 0.5;
}
static iv_affine_t blob_m(iv_affine_t x, iv_affine_t y, iv_affine_t z, int m)
{
    iv_affine_t a = iv_affine_mul_d(sq3(iv_affine_add_d(x, 0.4), y, z), -4);
    iv_affine_t b = iv_affine_mul_d(sq3(iv_affine_sub_d(x, 0.4), y, z), -4);
    return iv_affine_sub_d(iv_affine_add(iv__aff_unary(a, IV__F_EXP, 0, m), iv__aff_unary(b, IV__F_EXP, 0, m)), 0.5);
}

static int cmp_double(const void *a, const void *b);
static void linearisations(const char *dir)
{
    static const lin_case_t cs[] = {
        {"exp", IV__F_EXP, 0, 0, 1, 0}, {"exp", IV__F_EXP, 0, -3, 3, 0}, {"exp", IV__F_EXP, 0, -1, 1, 1},
        {"exp", IV__F_EXP, 0, 0, 2, 1}, {"log", IV__F_LOG, 0, 1, 2, 0}, {"log", IV__F_LOG, 0, 0.1, 10, 0},
        {"log", IV__F_LOG, 0, 1, 3, 0.5}, {"log", IV__F_LOG, 0, 0.1, 10, 0.5}, {"sqrt", IV__F_SQRT, 0, 0.5, 1, 0},
        {"sqrt", IV__F_SQRT, 0, 0.01, 4, 0}, {"sqrt", IV__F_SQRT, 0, 0.5, 2, 0.5}, {"sqrt", IV__F_SQRT, 0, 0.01, 4, 0.5},
        {"recip", IV__F_RECIP, -1, 1, 2, 0}, {"recip", IV__F_RECIP, -1, 0.1, 1, 0}, {"recip", IV__F_RECIP, -1, 1, 3, -0.25},
        {"recip", IV__F_RECIP, -1, 0.1, 1, -0.25}, {"pow_n 3", IV__F_POWN, 3, 0.4, 0.5, 0}, {"pow_n 3", IV__F_POWN, 3, 0.5, 1, 1},
        {"pow_n 4", IV__F_POWN, 4, 1, 2, 0}, {"pow_n -2", IV__F_POWN, -2, 1, 3, 0}, {"atan", IV__F_ATAN, 0, 0.5, 2, 0},
        {"atan", IV__F_ATAN, 0, 0.5, 2, 0.5},
    };
    static const double rel_len[] = {0.03, 0.1, 0.3};
    static seg_t segs[RAYS];
    static double w[4][RAYS];
    char path[512];
    FILE *csv;
    size_t c;
    int m, i, k, li, si;
    snprintf(path, sizeof path, "%s/interval_affine_linearisation.csv", dir);
    csv = fopen(path, "w");
    if (!csv) { fprintf(stderr, "cannot write %s\n", path); return; }
    fprintf(csv, "case,lo,hi,k,true_range,taylor,chebyshev,min_range,default\n");
    printf("\nnon-affine operations in affine arithmetic: overestimation (enclosure width - true range) of f(t) - k t,\n"
           "t the ray parameter over [a, b], by linearisation method (k = 0: the operation alone)\n");
    printf("%-9s %13s %6s %10s %11s %11s %11s %11s\n", "f", "[a, b]", "k", "range", lin_names[0], lin_names[1], lin_names[2],
           lin_names[3]);
    for (c = 0; c < sizeof cs / sizeof cs[0]; c++) {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        char ab[32];
        for (i = 0; i <= 4096; i++) {
            double x = cs[c].a + (cs[c].b - cs[c].a) * i / 4096.0, v = lin_f(cs[c].f, cs[c].n, x) - cs[c].k * x;
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        snprintf(ab, sizeof ab, "[%g, %g]", cs[c].a, cs[c].b);
        printf("%-9s %13s %6g %10.4g", cs[c].name, ab, cs[c].k, hi - lo);
        fprintf(csv, "%s,%g,%g,%g,%.6g", cs[c].name, cs[c].a, cs[c].b, cs[c].k, hi - lo);
        for (m = 0; m < 4; m++) {
            iv_affine_t t = iv_affine_ray_param(cs[c].a, cs[c].b);
            iv_t z = iv_from_affine(iv_affine_sub(iv__aff_unary(t, cs[c].f, cs[c].n, m), iv_affine_mul_d(t, cs[c].k)));
            printf(" %11.3g", iv_width(z) - (hi - lo));
            fprintf(csv, ",%.6g", iv_width(z) - (hi - lo));
        }
        printf("\n");
        fprintf(csv, "\n");
    }
    printf("\nsurfaces with non-affine operations: enclosure width / true range, median over %d random segments\n", RAYS);
    printf("%-8s %8s %11s %11s %11s %11s\n", "surface", "L/size", lin_names[0], lin_names[1], lin_names[2], lin_names[3]);
    fprintf(csv, "surface,segment_over_size,taylor,chebyshev,min_range,default\n");
    for (si = 0; si < 2; si++) {
        double half = si == 0 ? 1.5 : 1.2;
        double (*fd)(double, double, double) = si == 0 ? sphere_d : blob_d;
        for (li = 0; li < 3; li++) {
            int n = 0;
            for (i = 0; i < RAYS; i++) {
                seg_t *s = &segs[i];
                double nrm = 0, tlo = HUGE_VAL, thi = -HUGE_VAL;
                for (k = 0; k < 3; k++) { s->o[k] = (2 * urand() - 1) * half; s->d[k] = 2 * urand() - 1; nrm += s->d[k] * s->d[k]; }
                nrm = sqrt(nrm);
                for (k = 0; k < 3; k++) s->d[k] /= nrm;
                s->t0 = 0;
                s->t1 = rel_len[li] * 2 * half;
                for (k = 0; k <= 1024; k++) {
                    double t = s->t1 * (double)k / 1024.0;
                    double v = fd(s->o[0] + t * s->d[0], s->o[1] + t * s->d[1], s->o[2] + t * s->d[2]);
                    tlo = v < tlo ? v : tlo;
                    thi = v > thi ? v : thi;
                }
                if (!(thi > tlo)) continue;
                for (m = 0; m < 4; m++) {
                    iv_affine_t t = iv_affine_ray_param(s->t0, s->t1);
                    iv_affine_t x = seg_aff(s, t, 0), y = seg_aff(s, t, 1), z = seg_aff(s, t, 2);
                    iv_t r = iv_from_affine(si == 0 ? sphere_m(x, y, z, m) : blob_m(x, y, z, m));
                    w[m][n] = iv_width(r) / (thi - tlo);
                }
                n++;
            }
            printf("%-8s %8.2f", si == 0 ? "sphere" : "blob", rel_len[li]);
            fprintf(csv, "%s,%g", si == 0 ? "sphere" : "blob", rel_len[li]);
            for (m = 0; m < 4; m++) {
                qsort(w[m], (size_t)n, sizeof w[m][0], cmp_double);
                printf(" %11.3f", w[m][n / 2]);
                fprintf(csv, ",%.5g", w[m][n / 2]);
            }
            printf("\n");
            fprintf(csv, "\n");
        }
    }
    fclose(csv);
}

int main(int argc, char **argv)
{
    static const double rel_len[] = {0.01, 0.03, 0.1, 0.3, 1.0};
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    char path[512];
    FILE *csv;
    static seg_t segs[RAYS];
    static double ri[RAYS], ra[RAYS];
    volatile double sink = 0;
    size_t si;
    int li;
    snprintf(path, sizeof path, "%s/interval_surfaces.csv", dir);
    csv = fopen(path, "w");
    if (!csv) { fprintf(stderr, "cannot write %s\n", path); return 1; }
    fprintf(csv, "surface,segment_over_size,iv_width_over_range_median,aff_width_over_range_median,"
                 "iv_excess_over_aff_excess,double_ns,iv_ns,aff_ns\n");
    printf("enclosure width / true range (median over %d random segments) and ns per evaluation (best of 5)\n", RAYS);
    printf("%-8s %8s %10s %10s %9s %9s %8s %8s %8s\n", "surface", "L/size", "interval", "affine", "iv/aff", "excess", "dbl ns",
           "iv ns", "aff ns");
    for (si = 0; si < sizeof surfaces / sizeof surfaces[0]; si++) {
        const surface_t *f = &surfaces[si];
        for (li = 0; li < 5; li++) {
            double len = rel_len[li] * 2 * f->half, t0, td, ti, ta, mi, ma;
            int i, r, k, n = 0;
            fprintf(stderr, "%s L/size=%g\n", f->name, rel_len[li]);
            for (i = 0; i < RAYS; i++) {
                seg_t *s = &segs[i];
                double nrm = 0;
                for (k = 0; k < 3; k++) { s->o[k] = (2 * urand() - 1) * f->half; s->d[k] = 2 * urand() - 1; nrm += s->d[k] * s->d[k]; }
                nrm = sqrt(nrm);
                for (k = 0; k < 3; k++) s->d[k] /= nrm;
                s->t0 = 0;
                s->t1 = len;
            }
            /* accuracy */
            for (i = 0; i < RAYS; i++) {
                double tr = true_range(f, &segs[i]);
                iv_t a = eval_iv(f, &segs[i]), b = eval_aff(f, &segs[i]);
                if (!(tr > 0)) continue;
                ri[n] = (a.hi - a.lo) / tr;
                ra[n] = (b.hi - b.lo) / tr;
                n++;
            }
            qsort(ri, (size_t)n, sizeof ri[0], cmp_double);
            qsort(ra, (size_t)n, sizeof ra[0], cmp_double);
            mi = ri[n / 2];
            ma = ra[n / 2];
            /* time: best of 5 short runs (the machine may be shared) */
            td = ti = ta = HUGE_VAL;
            for (k = 0; k < 5; k++) {
                double t;
                t0 = now();
                for (r = 0; r < REPS; r++)
                    for (i = 0; i < RAYS; i++) {
                        const seg_t *s = &segs[i];
                        double t = s->t0 + 0.5 * (s->t1 - s->t0) + 1e-9 * r;
                        sink += f->fd(s->o[0] + t * s->d[0], s->o[1] + t * s->d[1], s->o[2] + t * s->d[2]);
                    }
                t = (now() - t0) / (REPS * RAYS) * 1e9;
                td = t < td ? t : td;
                t0 = now();
                for (r = 0; r < REPS; r++)
                    for (i = 0; i < RAYS; i++) sink += eval_iv(f, &segs[i]).hi;
                t = (now() - t0) / (REPS * RAYS) * 1e9;
                ti = t < ti ? t : ti;
                t0 = now();
                for (r = 0; r < REPS; r++)
                    for (i = 0; i < RAYS; i++) sink += eval_aff(f, &segs[i]).hi;
                t = (now() - t0) / (REPS * RAYS) * 1e9;
                ta = t < ta ? t : ta;
            }
            printf("%-8s %8.2f %10.3f %10.3f %9.2f %9.2f %8.1f %8.1f %8.1f\n", f->name, rel_len[li], mi, ma, mi / ma,
                   (mi - 1) / (ma - 1), td, ti, ta);
            fprintf(csv, "%s,%g,%.5g,%.5g,%.4g,%.2f,%.2f,%.2f\n", f->name, rel_len[li], mi, ma, (mi - 1) / (ma - 1), td, ti, ta);
        }
    }
    (void)sink;
    fclose(csv);
    linearisations(dir);
    return 0;
}
