/* frep.h evaluation benchmark: ns per tape instruction for the point, batch,
   gradient, interval and affine evaluators, each beside its error; and the
   tape length and speed-up that pruning gives on a 128-primitive CSG model.
   Usage: build/bench/bench_frep_eval OUT_DIR   (table on stdout, CSV in OUT_DIR) */
#define _POSIX_C_SOURCE 199309L
#define IV_IMPLEMENTATION
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    /* this thread's CPU time: other processes on a shared machine do not count */
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static unsigned long long rng_s = 0x1234567ull;
static double urand(double a, double b)
{
    rng_s = rng_s * 6364136223846793005ull + 1442695040888963407ull;
    return a + (b - a) * (double)(rng_s >> 11) * (1.0 / 9007199254740992.0);
}
static volatile double sink;

/* 8 x 8 x 2 spheres joined by min/max unions, four alpha-0 holes and a plate */
static fr_node_t csg128(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t u = FR_NODE_NONE;
    int i, j, k;
    for (i = 0; i < 8; i++)
        for (j = 0; j < 8; j++)
            for (k = 0; k < 2; k++) {
                double c[3];
                fr_node_t s;
                c[0] = -1.75 + 0.5 * i;
                c[1] = -1.75 + 0.5 * j;
                c[2] = -0.25 + 0.5 * k;
                s = fr_sphere(b, X, c, 0.3);
                u = u == FR_NODE_NONE ? s : fr_union(b, u, s, 1.0);
            }
    for (i = 0; i < 4; i++) {
        double c[3];
        c[0] = -1.5 + i;
        c[1] = 0.2 * i;
        c[2] = 0;
        u = fr_subtract(b, u, fr_cylinder(b, X, 2, c, 0.12), 1.0);
    }
    {
        double v[3] = {-2, -2, -0.1}, s[3] = {4, 4, 0.2};
        return fr_union(b, u, fr_block(b, X, v, s, 1.0), 1.0);
    }
}
/* skeletal + space maps + noise: transcendental-heavy */
static fr_node_t mixed(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t el[3] = {{{0, 0, 0}, {0, 0, 0}, 3, 1}, {{0.4, 0.1, 0}, {-0.3, 0.5, 0.2}, 2, 0.8},
                           {{0.2, -0.5, 0.3}, {0.2, -0.5, 0.3}, 4, 1.2}};
    double off[3] = {0.3, 0.1, 0.7}, c[3] = {0, 0, 0};
    fr_p3_t P = fr_twist(b, X, 2, -1, 1, 0.3, 1.7);
    fr_node_t bl = fr_skeletal(b, P, FR_KERNEL_BLOBBY, el, 3, 0.4);
    fr_node_t to = fr_torus(b, fr_taper(b, X, 2, -1, 1, 0.7, 1.3), 2, c, 0.8, 0.25);
    fr_node_t f = fr_blend_union(b, bl, to, 0.3, 0.5, 0.5);
    return fr_add(b, f, fr_noise(b, X, 0.05, 3.0, off));
}

/* the tangle cube quartic: polynomial, where affine forms keep the ray symbol */
static fr_node_t tangle(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t c[3], acc = FR_NODE_NONE;
    int i;
    c[0] = X.x;
    c[1] = X.y;
    c[2] = X.z;
    for (i = 0; i < 3; i++) {
        fr_node_t t = fr_sub(b, fr_powi(b, c[i], 4), fr_mul(b, fr_const(b, 5), fr_unary(b, FR_OP_SQR, c[i])));
        acc = i ? fr_add(b, acc, t) : t;
    }
    return fr_negate(b, fr_add(b, acc, fr_const(b, 11.8)));
}

static fr_tape_t compile(fr_node_t (*f)(fr_builder_t *, fr_p3_t))
{
    fr_builder_t b;
    fr_tape_t t;
    fr_builder_init(&b, NULL);
    if (fr_builder_finish(&b, f(&b, fr_coords(&b)), NULL, 0, &t, NULL) != FR_OK) {
        fprintf(stderr, "build failed\n");
        exit(1);
    }
    fr_builder_free(&b);
    return t;
}

#define NPTS 4096
static double px[NPTS], py[NPTS], pz[NPTS], outv[NPTS];

typedef struct row_t {
    const char *model, *method;
    unsigned int n_code;
    double ns_per_eval, ns_per_instr, error;
    const char *error_kind;
} row_t;

static void print_row(FILE *csv, const row_t *r)
{
    printf("| %-8s | %-9s | %5u | %10.1f | %6.2f | %-38s | %10.3g |\n", r->model, r->method, r->n_code, r->ns_per_eval,
           r->ns_per_instr, r->error_kind, r->error);
    fprintf(csv, "%s,%s,%u,%.3f,%.4f,%s,%.6g\n", r->model, r->method, r->n_code, r->ns_per_eval, r->ns_per_instr,
            r->error_kind, r->error);
}

static void bench_evaluators(FILE *csv, const char *name, const fr_tape_t *t)
{
    size_t need = fr_scratch_size(t, FR_EVAL_BATCH);
    void *sc = malloc(need > fr_scratch_size(t, FR_EVAL_AFFINE) ? need : fr_scratch_size(t, FR_EVAL_AFFINE));
    double ref[NPTS], t0, dt, err;
    int rep, i, reps = 40;
    row_t r;
    for (i = 0; i < NPTS; i++) {
        px[i] = urand(-2, 2);
        py[i] = urand(-2, 2);
        pz[i] = urand(-1, 1);
    }
    r.model = name;
    r.n_code = t->n_code;
    /* point */
    t0 = now();
    for (rep = 0; rep < reps; rep++)
        for (i = 0; i < NPTS; i++) {
            double p[3] = {px[i], py[i], pz[i]};
            ref[i] = fr_eval(t, p, sc);
        }
    dt = (now() - t0) / (reps * NPTS);
    r.method = "point";
    r.ns_per_eval = dt * 1e9;
    r.ns_per_instr = r.ns_per_eval / t->n_code;
    r.error_kind = "reference";
    r.error = 0;
    print_row(csv, &r);
    /* batch */
    t0 = now();
    for (rep = 0; rep < reps; rep++) fr_eval_batch(t, NPTS, px, py, pz, outv, sc);
    dt = (now() - t0) / (reps * NPTS);
    err = 0;
    for (i = 0; i < NPTS; i++) {
        double e = fabs(outv[i] - ref[i]) / (fabs(ref[i]) + 1);
        if (e > err) err = e;
    }
    r.method = "batch";
    r.ns_per_eval = dt * 1e9;
    r.ns_per_instr = r.ns_per_eval / t->n_code;
    r.error_kind = "max |batch-point|/(|f|+1)";
    r.error = err;
    print_row(csv, &r);
    /* gradient, against central differences */
    t0 = now();
    for (rep = 0; rep < reps / 4; rep++)
        for (i = 0; i < NPTS; i++) {
            double p[3] = {px[i], py[i], pz[i]}, v, g[3];
            fr_eval_grad(t, p, sc, &v, g);
            sink = g[0];
        }
    dt = (now() - t0) / ((reps / 4) * NPTS);
    err = 0;
    for (i = 0; i < 256; i++) {
        double p[3] = {px[i], py[i], pz[i]}, v, g[3], h = 1e-5;
        int k;
        fr_eval_grad(t, p, sc, &v, g);
        for (k = 0; k < 3; k++) {
            double q[3] = {p[0], p[1], p[2]}, fp, fm, e;
            q[k] += h;
            fp = fr_eval(t, q, sc);
            q[k] -= 2 * h;
            fm = fr_eval(t, q, sc);
            e = fabs((fp - fm) / (2 * h) - g[k]) / (fabs(g[k]) + 1);
            if (e > err) err = e;
        }
    }
    r.method = "gradient";
    r.ns_per_eval = dt * 1e9;
    r.ns_per_instr = r.ns_per_eval / t->n_code;
    r.error_kind = "max |AD-CD|/(|g|+1), CD h=1e-5";
    r.error = err;
    print_row(csv, &r);
    /* interval and affine along ray segments of length 0.1 (the renderer's
       use): the interval gets the segment's bounding box, the affine form the
       shared ray symbol. error = enclosure width / range sampled on the segment */
    {
        int nb = 2000, s;
        double (*seg)[6] = malloc(sizeof(double[6]) * (size_t)nb);
        double wi = 0, wa = 0, wt = 0, ti, ta;
        for (i = 0; i < nb; i++) {
            double d[3], l;
            int k;
            for (k = 0; k < 3; k++) d[k] = urand(-1, 1);
            l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-300;
            for (k = 0; k < 3; k++) {
                seg[i][k] = urand(-1.8, 1.8);
                seg[i][3 + k] = d[k] / l; /* unit direction, t in [0, 0.1] */
            }
        }
#define SEG_BOX(i, box)                                                                                                \
    for (s = 0; s < 3; s++) {                                                                                          \
        double e0 = seg[i][s], e1 = seg[i][s] + 0.1 * seg[i][3 + s];                                                    \
        box[s] = iv_make(e0 < e1 ? e0 : e1, e0 < e1 ? e1 : e0);                                                         \
    }
#define SEG_AFF(i, in)                                                                                                 \
    {                                                                                                                  \
        iv_affine_t T = iv_affine_ray_param(0, 0.1);                                                                   \
        for (s = 0; s < 3; s++) in[s] = iv_affine_add_d(iv_affine_mul_d(T, seg[i][3 + s]), seg[i][s]);                 \
    }
        t0 = now();
        for (rep = 0; rep < 10; rep++)
            for (i = 0; i < nb; i++) {
                iv_t box[3], o;
                SEG_BOX(i, box)
                fr_eval_interval(t, box, sc, &o);
                sink = o.lo;
            }
        ti = (now() - t0) / (10.0 * nb);
        t0 = now();
        for (rep = 0; rep < 10; rep++)
            for (i = 0; i < nb; i++) {
                iv_affine_t in[3], o;
                SEG_AFF(i, in)
                fr_eval_affine(t, in, sc, &o);
                sink = o.c;
            }
        ta = (now() - t0) / (10.0 * nb);
        for (i = 0; i < 300; i++) {
            iv_t box[3], o;
            iv_affine_t in[3], oa;
            double lo = INFINITY, hi = -INFINITY;
            int q;
            SEG_BOX(i, box)
            SEG_AFF(i, in)
            fr_eval_interval(t, box, sc, &o);
            fr_eval_affine(t, in, sc, &oa);
            for (q = 0; q <= 400; q++) {
                double tt = 0.1 * q / 400.0, p[3], v;
                for (s = 0; s < 3; s++) p[s] = seg[i][s] + tt * seg[i][3 + s];
                v = fr_eval(t, p, sc);
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
            }
            wi += iv_width(o);
            wa += iv_width(iv_from_affine(oa));
            wt += hi - lo;
        }
#undef SEG_BOX
#undef SEG_AFF
        r.method = "interval";
        r.ns_per_eval = ti * 1e9;
        r.ns_per_instr = r.ns_per_eval / t->n_code;
        r.error_kind = "width / sampled range, ray segment 0.1";
        r.error = wi / wt;
        print_row(csv, &r);
        r.method = "affine";
        r.ns_per_eval = ta * 1e9;
        r.ns_per_instr = r.ns_per_eval / t->n_code;
        r.error = wa / wt;
        print_row(csv, &r);
        free(seg);
    }
    free(sc);
}

/* pruning: split [-2,2]x[-2,2]x[-0.5,0.5] into n^3 boxes; prune per box and
   evaluate K points in each with the full and the pruned tape */
static void bench_pruning(FILE *csv, const fr_tape_t *t, fr_prune_mode_t mode, const char *mode_name)
{
    static const int grid[3] = {2, 4, 8};
    int g;
    void *sp = malloc(fr_scratch_size(t, FR_EVAL_PRUNE) + fr_scratch_size(t, FR_EVAL_POINT));
    fr_instr_t *buf = malloc(t->n_code * sizeof(fr_instr_t));
    printf("\n%s\n\n| boxes | mean pruned length | full length | eval speed-up | incl. pruning (K=256) | max |pruned-full| |\n",
           mode_name);
    printf("|---|---|---|---|---|---|\n");
    for (g = 0; g < 3; g++) {
        int n = grid[g], i, j, k, s, K = 256;
        double len = 0, tf = 0, tp = 0, tprune = 0, maxdiff = 0;
        for (i = 0; i < n; i++)
            for (j = 0; j < n; j++)
                for (k = 0; k < n; k++) {
                    iv_t box[3];
                    fr_tape_t pr;
                    double pts[256][3], t0, acc = 0;
                    box[0] = iv_make(-2 + 4.0 * i / n, -2 + 4.0 * (i + 1) / n);
                    box[1] = iv_make(-2 + 4.0 * j / n, -2 + 4.0 * (j + 1) / n);
                    box[2] = iv_make(-0.5 + 1.0 * k / n, -0.5 + 1.0 * (k + 1) / n);
                    for (s = 0; s < K; s++) {
                        pts[s][0] = urand(box[0].lo, box[0].hi);
                        pts[s][1] = urand(box[1].lo, box[1].hi);
                        pts[s][2] = urand(box[2].lo, box[2].hi);
                    }
                    t0 = now();
                    fr_prune_ex(t, box, mode, sp, buf, t->n_code, &pr, NULL);
                    tprune += now() - t0;
                    len += pr.n_code;
                    t0 = now();
                    for (s = 0; s < K; s++) acc += fr_eval(t, pts[s], sp);
                    tf += now() - t0;
                    t0 = now();
                    for (s = 0; s < K; s++) acc -= fr_eval(&pr, pts[s], sp);
                    tp += now() - t0;
                    for (s = 0; s < 16; s++) {
                        double d = fabs(fr_eval(t, pts[s], sp) - fr_eval(&pr, pts[s], sp));
                        if (d > maxdiff) maxdiff = d;
                    }
                    sink = acc;
                }
        len /= (double)(n * n * n);
        printf("| %d^3 | %.1f | %u | %.1fx | %.1fx | %.3g |\n", n, len, t->n_code, tf / tp, tf / (tp + tprune), maxdiff);
        fprintf(csv, "csg128,prune_%s_%d^3,%u,%.2f,%.4f,speedup_eval;speedup_with_prune;max_diff,%.3f;%.3f;%.3g\n",
                mode_name, n, t->n_code, len, tf / tp, tf / tp, tf / (tp + tprune), maxdiff);
        fprintf(stderr, "pruning %d^3 done\n", n);
    }
    free(sp);
    free(buf);
}

int main(int argc, char **argv)
{
    char path[512];
    FILE *csv;
    fr_tape_t a = compile(csg128), b = compile(mixed), c = compile(tangle);
    snprintf(path, sizeof path, "%s/bench_frep_eval.csv", argc > 1 ? argv[1] : ".");
    csv = fopen(path, "w");
    if (!csv) {
        fprintf(stderr, "cannot write %s\n", path);
        return 1;
    }
    fprintf(csv, "model,method,n_code,ns_per_eval,ns_per_instr,error_kind,error\n");
    printf("| model    | method    | instr | ns / eval  | ns/ins | error measure                          | error      |\n");
    printf("|---|---|---|---|---|---|---|\n");
    fprintf(stderr, "evaluators on csg128...\n");
    bench_evaluators(csv, "csg128", &a);
    fprintf(stderr, "evaluators on mixed...\n");
    bench_evaluators(csv, "mixed", &b);
    fprintf(stderr, "evaluators on tangle...\n");
    bench_evaluators(csv, "tangle", &c);
    bench_pruning(csv, &a, FR_PRUNE_EXACT, "exact");
    bench_pruning(csv, &a, FR_PRUNE_DEFAULT, "default");
    bench_pruning(csv, &a, FR_PRUNE_SIGN, "sign");
    fclose(csv);
    fr_tape_free(&a);
    fr_tape_free(&b);
    fr_tape_free(&c);
    return 0;
}
