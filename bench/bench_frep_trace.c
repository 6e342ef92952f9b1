/* bench/bench_frep_trace.c -- ray casting FRep models: error against run time.

   For each model (examples/models/ *.hf files, plus a distance-bound model for
   sphere tracing) and each method x parameter of fr_trace, a 96x96 pinhole
   image of primary rays is cast; we report rays per second on 1 and on 2
   threads, mean and max |t - t_ref| over rays both hit, and the percentage
   of missed and false hits. The reference is interval bisection (affine
   forms) to 1e-13 of the same ray, and for polynomial models (the cup and
   Barth's sextic as CSG of polynomials) its hits are confirmed in
   __float128. Rows marked "box" clip rays to the model's fr_bound_box box,
   "prepared" also use its fr_prepare model, as a renderer would (the
   other rows trace the bare segment [0, 12]). A row is Pareto-optimal when no other
   row of the model is at least as fast (1 thread), at least as accurate
   (max error) and misses no more rays.
   Usage: bench_frep_trace OUTDIR   (CSV: OUTDIR/frep_trace.csv) */
#define IV_IMPLEMENTATION
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include <pthread.h>
#include <quadmath.h>
#include "test_frep_ref_models.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define W 96
#define H 96
#define NR (W * H)
#define MAXROWS 24

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct job_t {
    const fr_tape_t *tape;
    fr_trace_desc_t desc;
    const double *o, *d; /* NR rays */
    double t0, t1;
    double *t;           /* out: t or NAN for a miss */
    int begin, end;
} job_t;

static void *run_job(void *arg)
{
    job_t *j = (job_t *)arg;
    void *s = malloc(fr_trace_scratch_size(j->tape, &j->desc));
    int i;
    for (i = j->begin; i < j->end; i++) {
        fr_hit_t h;
        if (fr_trace(j->tape, j->o + 3 * i, j->d + 3 * i, j->t0, j->t1, &j->desc, s, &h) != FR_OK || !h.hit)
            j->t[i] = NAN;
        else
            j->t[i] = h.t;
    }
    free(s);
    return NULL;
}

/* Cast all rays with `threads` threads; returns seconds. */
static double cast(const fr_tape_t *tape, fr_trace_desc_t desc, const double *o, const double *d, double t0,
                   double t1, double *t, int threads)
{
    pthread_t th[8];
    job_t jobs[8];
    double start = now_s();
    int k;
    for (k = 0; k < threads; k++) {
        jobs[k].tape = tape; jobs[k].desc = desc; jobs[k].o = o; jobs[k].d = d;
        jobs[k].t0 = t0; jobs[k].t1 = t1; jobs[k].t = t;
        jobs[k].begin = NR * k / threads; jobs[k].end = NR * (k + 1) / threads;
        if (threads == 1) run_job(&jobs[k]);
        else pthread_create(&th[k], NULL, run_job, &jobs[k]);
    }
    if (threads > 1)
        for (k = 0; k < threads; k++) pthread_join(th[k], NULL);
    return now_s() - start;
}

typedef struct row_t {
    char method[48];
    double rps1, rps2, mean_err, max_err, miss_pct, false_pct;
    int pareto;
} row_t;

static int load_model(const char *path, fr_tape_t *tape)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long n;
    fr_parse_desc_t pd;
    fr_diag_t dg;
    if (!f) return -1;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = (char *)malloc((size_t)n + 1);
    if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) { fclose(f); free(buf); return -1; }
    fclose(f);
    memset(&pd, 0, sizeof pd);
    if (fr_parse(buf, (size_t)n, &pd, tape, &dg) != FR_OK) {
        fprintf(stderr, "%s:%d:%d: %s\n", path, dg.line, dg.column, dg.message);
        free(buf);
        return -1;
    }
    free(buf);
    return 0;
}

/* Two spheres and a box-ish rounded slab as exact SDFs (Lipschitz 1), so
   sphere tracing has a model. */
static int sdf_model(fr_tape_t *tape)
{
    fr_builder_t b;
    fr_p3_t p;
    fr_node_t s1, s2, u;
    static const double c1[3] = {-0.5, 0, 0}, c2[3] = {0.6, 0.2, 0.1};
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    {
        int k;
        const double *cs[2] = {c1, c2};
        double rs[2] = {0.8, 0.6};
        fr_node_t sd[2];
        for (k = 0; k < 2; k++) {
            fr_node_t dx = fr_sub(&b, p.x, fr_const(&b, cs[k][0])), dy = fr_sub(&b, p.y, fr_const(&b, cs[k][1]));
            fr_node_t dz = fr_sub(&b, p.z, fr_const(&b, cs[k][2]));
            fr_node_t len = fr_unary(&b, FR_OP_SQRT, fr_add(&b, fr_add(&b, fr_unary(&b, FR_OP_SQR, dx),
                                                                        fr_unary(&b, FR_OP_SQR, dy)),
                                                              fr_unary(&b, FR_OP_SQR, dz)));
            sd[k] = fr_from_sdf(&b, fr_sub(&b, len, fr_const(&b, rs[k])), 1.0);
        }
        s1 = sd[0]; s2 = sd[1];
    }
    u = fr_binary(&b, FR_OP_MAX, s1, s2); /* union of distance bounds is a distance bound */
    if (fr_builder_finish(&b, u, NULL, 0, tape, NULL) != FR_OK) { fr_builder_free(&b); return -1; }
    fr_builder_free(&b);
    if (!(tape->lipschitz < HUGE_VAL)) tape->lipschitz = 1.0;
    return 0;
}

static void camera_rays(double *o, double *d, double dist)
{
    /* eye on a diagonal, looking at the origin, 40 degree field of view */
    double eye[3] = {dist * 0.55, -dist * 0.7, dist * 0.45}, f[3], r[3], u[3], n;
    int i, x, y;
    for (i = 0; i < 3; i++) f[i] = -eye[i];
    n = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (i = 0; i < 3; i++) f[i] /= n;
    r[0] = f[1]; r[1] = -f[0]; r[2] = 0; /* f x z */
    n = sqrt(r[0] * r[0] + r[1] * r[1]);
    r[0] /= n; r[1] /= n;
    u[0] = r[1] * f[2] - r[2] * f[1]; u[1] = r[2] * f[0] - r[0] * f[2]; u[2] = r[0] * f[1] - r[1] * f[0];
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            double px = (2.0 * (x + 0.5) / W - 1.0) * 0.364, py = (1.0 - 2.0 * (y + 0.5) / H) * 0.364;
            int k = y * W + x;
            for (i = 0; i < 3; i++) {
                o[3 * k + i] = eye[i];
                d[3 * k + i] = f[i] + px * r[i] + py * u[i];
            }
        }
}

static fr_trace_desc_t mk(fr_method_t m, double tol)
{
    fr_trace_desc_t d;
    memset(&d, 0, sizeof d);
    d.method = m;
    d.tol = tol;
    d.normal = FR_NORMAL_NONE; /* intersection cost only */
    return d;
}

/* Confirms reference hits of a polynomial model (the tangle cube) or a
   CSG of polynomials (cup, Barth) in quad: a sign change of g within
   +-eps of t_ref. Returns the number confirmed; *n gets the hits. */
static long quad_confirm(__float128 (*g)(const double *, const double *, __float128), const double *o, const double *d,
                         const double *tref, double eps, long *n)
{
    long ok = 0, i;
    *n = 0;
    for (i = 0; i < NR; i++) {
        __float128 a, b;
        if (!(tref[i] == tref[i])) continue;
        (*n)++;
        a = g(o + 3 * i, d + 3 * i, (__float128)tref[i] - eps);
        b = g(o + 3 * i, d + 3 * i, (__float128)tref[i] + eps);
        if ((a <= 0 && b >= 0) || (a >= 0 && b <= 0)) ok++;
    }
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    static const char *names[] = {"cup", "tangle_cube", "barth_sextic", "blended_cylinders", "sdf_spheres"};
    char path[1024];
    FILE *csv;
    double *o = (double *)malloc(sizeof(double) * 3 * NR), *d = (double *)malloc(sizeof(double) * 3 * NR);
    double *tref = (double *)malloc(sizeof(double) * NR), *t = (double *)malloc(sizeof(double) * NR);
    int mi;
    snprintf(path, sizeof path, "%s/frep_trace.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "model,method,rays_per_s_1,rays_per_s_2,mean_err,max_err,miss_pct,false_pct,pareto\n");
    for (mi = 0; mi < 5; mi++) {
        fr_tape_t tape;
        row_t rows[MAXROWS];
        int nrow = 0, r, i, poly;
        double t0 = 0, t1 = 12, tref_time;
        fr_trace_desc_t cand[MAXROWS];
        const char *label[MAXROWS];
        int nc = 0, has_prep = 0;
        fr_prepared_t prep;
        double box[6];
        if (mi < 4) {
            snprintf(path, sizeof path, "examples/models/%s.hf", names[mi]);
            if (load_model(path, &tape)) { fprintf(stderr, "skip %s\n", names[mi]); continue; }
        } else if (sdf_model(&tape)) continue;
        camera_rays(o, d, 6.0);
        fprintf(stderr, "%s: reference...\n", names[mi]);
        tref_time = cast(&tape, mk(FR_METHOD_INTERVAL, 1e-13), o, d, t0, t1, tref, 2);
        (void)tref_time;
        {
            void *s = malloc(fr_trace_scratch_size(&tape, NULL));
            fr_hit_t h;
            fr_trace_desc_t an = mk(FR_METHOD_ANALYTIC, 0);
            poly = fr_trace(&tape, o, d, t0, t1, &an, s, &h) == FR_OK;
            free(s);
        }
        /* the method x parameter grid */
        if (poly) { cand[nc] = mk(FR_METHOD_ANALYTIC, 0); label[nc++] = "analytic"; }
        {
            /* a renderer's setup: the model's box (fr_bound_box), and the
               prepared model (fr_prepare) of that box */
            static const double lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5};
            void *s = malloc(fr_scratch_size(&tape, FR_EVAL_INTERVAL));
            has_prep = s && !(tape.flags & FR_TAPE_NO_INTERVAL) && fr_bound_box(&tape, lo, hi, 7, s, box, box + 3) == FR_OK &&
                       fr_prepare(&tape, box, &prep) == FR_OK;
            free(s);
            if (has_prep && poly) {
                cand[nc] = mk(FR_METHOD_ANALYTIC, 0); cand[nc].bounds = box; label[nc++] = "analytic box";
                cand[nc] = mk(FR_METHOD_ANALYTIC, 0); cand[nc].bounds = box; cand[nc].prepared = &prep;
                label[nc++] = "analytic box prepared";
            }
            if (has_prep && prep.kind == FR_PREPARED_POLY) {
                cand[nc] = mk(FR_METHOD_INTERVAL, 1e-7); cand[nc].bounds = box; label[nc++] = "interval 1e-7 box";
                cand[nc] = mk(FR_METHOD_INTERVAL, 1e-7); cand[nc].bounds = box; cand[nc].prepared = &prep;
                label[nc++] = "interval 1e-7 box prepared";
                cand[nc] = mk(FR_METHOD_INTERVAL, 1e-10); cand[nc].bounds = box; cand[nc].prepared = &prep;
                label[nc++] = "interval 1e-10 box prepared";
            }
        }
        {
            static const double steps[3] = {12.0 / 64, 12.0 / 256, 12.0 / 1024};
            static const char *sl[3] = {"step L/64 illinois", "step L/256 illinois", "step L/1024 illinois"};
            int k;
            for (k = 0; k < 3; k++) { cand[nc] = mk(FR_METHOD_STEP, 1e-10); cand[nc].step = steps[k]; label[nc++] = sl[k]; }
            cand[nc] = mk(FR_METHOD_STEP, 1e-10); cand[nc].step = 12.0 / 256; cand[nc].refine = FR_REFINE_NEWTON;
            label[nc++] = "step L/256 newton";
            cand[nc] = mk(FR_METHOD_STEP, 1e-10); cand[nc].step = 12.0 / 256; cand[nc].refine = FR_REFINE_BRENT;
            label[nc++] = "step L/256 brent";
            cand[nc] = mk(FR_METHOD_STEP, 1e-10); cand[nc].step = 12.0 / 256; cand[nc].refine = FR_REFINE_BISECT;
            label[nc++] = "step L/256 bisect";
            cand[nc] = mk(FR_METHOD_INTERVAL, 1e-4); label[nc++] = "interval affine 1e-4";
            cand[nc] = mk(FR_METHOD_INTERVAL, 1e-7); label[nc++] = "interval affine 1e-7";
            cand[nc] = mk(FR_METHOD_INTERVAL, 1e-10); label[nc++] = "interval affine 1e-10";
            cand[nc] = mk(FR_METHOD_INTERVAL, 1e-7); cand[nc].plain_intervals = 1; label[nc++] = "interval plain 1e-7";
            cand[nc] = mk(FR_METHOD_INTERVAL, 1e-7); cand[nc].no_prune = 1; label[nc++] = "interval affine 1e-7 no prune";
            if (tape.lipschitz < HUGE_VAL) {
                cand[nc] = mk(FR_METHOD_SPHERE, 1e-7); cand[nc].over_relax = 1; label[nc++] = "sphere 1e-7";
                cand[nc] = mk(FR_METHOD_SPHERE, 1e-7); cand[nc].over_relax = 1.6; label[nc++] = "sphere 1e-7 omega 1.6";
                cand[nc] = mk(FR_METHOD_STEP, 1e-10); label[nc++] = "step lipschitz illinois";
            }
        }
        for (r = 0; r < nc; r++) {
            row_t *w = &rows[nrow++];
            double s1 = cast(&tape, cand[r], o, d, t0, t1, t, 1), s2, sum = 0, mx = 0;
            long both = 0, miss = 0, fals = 0, nref = 0;
            s2 = cast(&tape, cand[r], o, d, t0, t1, t, 2);
            for (i = 0; i < NR; i++) {
                int hr = tref[i] == tref[i], hm = t[i] == t[i];
                nref += hr;
                if (hr && hm) {
                    double e = fabs(t[i] - tref[i]);
                    both++; sum += e;
                    if (e > mx) mx = e;
                } else if (hr) miss++;
                else if (hm) fals++;
            }
            snprintf(w->method, sizeof w->method, "%s", label[r]);
            w->rps1 = NR / s1;
            w->rps2 = NR / s2;
            w->mean_err = both ? sum / (double)both : 0;
            w->max_err = mx;
            w->miss_pct = nref ? 100.0 * (double)miss / (double)nref : 0;
            w->false_pct = 100.0 * (double)fals / NR;
            fprintf(stderr, "  %s: %s\n", names[mi], label[r]);
        }
        for (r = 0; r < nrow; r++) {
            int k, dominated = 0;
            for (k = 0; k < nrow; k++)
                if (k != r && rows[k].rps1 >= rows[r].rps1 && rows[k].max_err <= rows[r].max_err &&
                    rows[k].miss_pct + rows[k].false_pct <= rows[r].miss_pct + rows[r].false_pct &&
                    (rows[k].rps1 > rows[r].rps1 || rows[k].max_err < rows[r].max_err ||
                     rows[k].miss_pct + rows[k].false_pct < rows[r].miss_pct + rows[r].false_pct))
                    dominated = 1;
            rows[r].pareto = !dominated;
        }
        printf("\n%s (%d x %d primary rays, reference interval bisection 1e-13%s)\n", names[mi], W, H,
               poly ? "; polynomial leaves: analytic available" : "");
        if (mi < 3) {
            __float128 (*g)(const double *, const double *, __float128) = mi == 0 ? cup_q : mi == 1 ? tangle_q : barth_q;
            long nh, ok = quad_confirm(g, o, d, tref, 1e-11, &nh);
            printf("reference checked in __float128: %ld of %ld hits have a sign change of f within +-1e-11\n", ok, nh);
        }
        printf("%-32s %11s %11s %10s %10s %7s %7s %s\n", "method", "rays/s 1c", "rays/s 2c", "mean|dt|", "max|dt|",
               "miss%", "false%", "pareto");
        for (r = 0; r < nrow; r++) {
            printf("%-32s %11.0f %11.0f %10.2e %10.2e %7.2f %7.2f %s\n", rows[r].method, rows[r].rps1, rows[r].rps2,
                   rows[r].mean_err, rows[r].max_err, rows[r].miss_pct, rows[r].false_pct, rows[r].pareto ? "*" : "");
            if (csv)
                fprintf(csv, "%s,%s,%.0f,%.0f,%.3e,%.3e,%.3f,%.3f,%d\n", names[mi], rows[r].method, rows[r].rps1,
                        rows[r].rps2, rows[r].mean_err, rows[r].max_err, rows[r].miss_pct, rows[r].false_pct,
                        rows[r].pareto);
        }
        fflush(stdout);
        if (has_prep) fr_prepared_free(&prep);
        fr_tape_free(&tape);
    }
    if (csv) fclose(csv);
    free(o); free(d); free(tref); free(t);
    return 0;
}
