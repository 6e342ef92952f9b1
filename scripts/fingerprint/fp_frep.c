/* scripts/fingerprint/fp_frep.c — frep.h's ray answers, hashed: fr_trace
   with 16 method and option sets (every method; Newton, Brent and
   bisection refinement; plain intervals; tol -1; interval Newton; bounds;
   footprint; any-hit; no pruning with FD normals; prepared models) on rays
   at the example's models (examples/models, run from the repository root)
   and eight written here (CSG of quadrics, a torus, the tangle polynomial,
   a blend, a superellipsoid, noise); and fr_solve_poly's roots for random
   polynomials of every degree (from roots: clustered, spread over 1e-30 to
   1e30, zero roots; or random coefficients), over random intervals; and
   fr_parse's answers on those texts and 20 000 random mutations of them. */
#define IV_IMPLEMENTATION
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "test.h"
#include "fp.h"

static const char *const fp_files[] = {"barth_sextic.hf", "blended_cylinders.hf", "cup.hf",
                                       "metamorphosis.hf", "noise_hole.hf", "tangle_cube.hf"};
static const char *const fp_models[] = {
    "m(x[3], a[1]) { array c[3]; c = [0, 0, 0]; m = hfSphere(x, c, 0.8) | hfCylinderZ(x, c, 0.3) & ~hfBlock(x, c, 1, 0.8, 0.6) \\ hfCylinderZ(x, c, 0.3); }",
    "m(x[3], a[1]) { array c[3], d[3]; c = [0, 0, 0]; d = [0.5, 0.2, 0.1]; m = hfSphere(x, c, 0.8) | hfSphere(x, d, 0.6) & hfEllipsoid(x, c, 0.9, 0.6, 0.4); }",
    "m(x[3], a[1]) { array c[3]; c = [0, 0, 0]; m = hfTorusZ(x, c, 0.7, 0.2); }",
    "m(x[3], a[1]) { m = x[1]^4 - 5*x[1]^2 + x[2]^4 - 5*x[2]^2 + x[3]^4 - 5*x[3]^2 + 11.8; }",
    "m(x[3], a[1]) { array c[3]; c = [0, 0, 0]; m = hfBlendUni(hfSphere(x, c, 0.8), hfCylinderZ(x, c, 0.3), 0.3, 0.5, 0.7); }",
    "m(x[3], a[1]) { m = 1 - x[1]*x[1] - 2*x[2]*x[2] - 0.5*x[3]*x[3] + 0.3*x[1]*x[2]; }",
    "m(x[3], a[1]) { array c[3]; c = [0.1, -0.2, 0]; m = hfSuperEll(x, c, 0.8, 0.6, 0.5, 0.5, 0.8); }",
    "m(x[3], a[1]) { array c[3]; c = [0, 0, 0]; m = hfNoiseG(x, 2.5, 0.7, 1.4) + hfSphere(x, c, 0.9); }",
};

static char *fp_read(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    char *b;
    long m;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    m = ftell(f);
    fseek(f, 0, SEEK_SET);
    b = (char *)malloc((size_t)m + 1);
    *n = b ? fread(b, 1, (size_t)m, f) : 0;
    fclose(f);
    return b;
}

/* Option set v of 16 (see the top). */
static fr_trace_desc_t fp_desc(int v, const double *bounds, const fr_prepared_t *prep)
{
    fr_trace_desc_t D;
    memset(&D, 0, sizeof D);
    D.method = v < 5 ? (fr_method_t)v : v % 2 ? FR_METHOD_INTERVAL : FR_METHOD_STEP;
    if (v == 5) D.refine = FR_REFINE_NEWTON;
    if (v == 6) D.plain_intervals = 1;
    if (v == 7) D.refine = FR_REFINE_BRENT;
    if (v == 8) D.tol = -1;
    if (v == 9) D.interval_newton = 1;
    if (v == 10) D.bounds = bounds, D.refine = FR_REFINE_BISECT;
    if (v == 11) D.no_poly_range = 1, D.footprint = 1e-3;
    if (v == 12) D.any_hit = 1, D.method = FR_METHOD_AUTO;
    if (v == 13) D.no_prune = 1, D.normal = FR_NORMAL_FD;
    if (v == 14) D.method = FR_METHOD_AUTO, D.prepared = prep;
    if (v == 15) D.method = FR_METHOD_ANALYTIC, D.prepared = prep, D.normal = FR_NORMAL_NONE;
    return D;
}

static unsigned long long fp_tape(const fr_tape_t *tape, int nrays, unsigned long long seed, long *hits)
{
    static const double bounds[6] = {-3, -3, -3, 3, 3, 3};
    unsigned long long h = FP_START;
    fr_prepared_t prep;
    int have_prep = fr_prepare(tape, bounds, &prep) == FR_OK, q, v, k;
    t_rng_t rng;
    rng.s = seed;
    for (q = 0; q < nrays; q++) {
        double o[3], d[3], len = 0;
        for (k = 0; k < 3; k++) o[k] = 4 * (2 * t_rng_unit(&rng) - 1), d[k] = 1.2 * (2 * t_rng_unit(&rng) - 1) - o[k];
        for (k = 0; k < 3; k++) len += d[k] * d[k];
        for (k = 0; k < 3; k++) d[k] /= sqrt(len);
        for (v = 0; v < 16; v++) {
            fr_trace_desc_t D = fp_desc(v, bounds, have_prep ? &prep : NULL);
            fr_hit_t hit;
            fr_result_t r;
            void *scratch = malloc(fr_trace_scratch_size(tape, &D));
            memset(&hit, 0, sizeof hit);
            r = fr_trace(tape, o, d, 0.0, 10.0, &D, scratch, &hit);
            free(scratch);
            h = fp_hash(h, &r, sizeof r);
            if (r == FR_OK) h = fp_hash(h, &hit, sizeof hit), *hits += hit.hit;
        }
    }
    if (have_prep) fr_prepared_free(&prep);
    return h;
}

static void fp_solve(int cases)
{
    unsigned long long h = FP_START;
    t_rng_t rng;
    int q;
    rng.s = 4515;
    for (q = 0; q < cases; q++) {
        double c[FR_POLY_MAX_DEGREE + 1], r[FR_POLY_MAX_DEGREE + 1], t0 = -HUGE_VAL, t1 = HUGE_VAL;
        int deg = 1 + (int)(t_rng_u64(&rng) % FR_POLY_MAX_DEGREE), k, i, n, kind = (int)(t_rng_u64(&rng) % 4);
        memset(c, 0, sizeof c);
        if (kind == 3) {
            for (k = 0; k <= deg; k++) c[k] = (2 * t_rng_unit(&rng) - 1) * pow(10, 6 * (t_rng_unit(&rng) - 0.5));
        } else {
            c[0] = 1;
            for (k = 0; k < deg; k++) { /* times (x - root) */
                double x = kind == 0 ? 1 + 1e-6 * t_rng_unit(&rng)                       /* clustered */
                         : kind == 1 ? pow(10, 60 * (t_rng_unit(&rng) - 0.5))            /* spread */
                                     : (t_rng_u64(&rng) % 3 == 0 ? 0.0 : 4 * t_rng_unit(&rng) - 2); /* zero roots */
                if (t_rng_u64(&rng) & 1) x = -x;
                for (i = k + 1; i > 0; i--) c[i] = c[i - 1] - x * c[i];
                c[0] = -x * c[0];
            }
        }
        if (q % 3 == 0) t0 = -2 * t_rng_unit(&rng), t1 = t0 + 4 * t_rng_unit(&rng);
        n = fr_solve_poly(c, deg, t0, t1, r);
        h = fp_hash(h, &n, sizeof n);
        if (n > 0) h = fp_hash(h, r, sizeof(double) * (size_t)n);
    }
    printf("frep      fr_solve_poly          %016llx  (%d polynomials)\n", h, cases);
}

/* The parser's answers: each model text and `cases` random mutations of
   them (a byte deleted, inserted or replaced, one to four times), parsed;
   the result, line, column and message, and on success the tape (its
   instructions field by field, parameters, outputs, flags, Lipschitz
   bound). Two parses of each text: default alpha and alpha 1. */
static unsigned long long fp_tape_bytes(unsigned long long h, const fr_tape_t *t)
{
    unsigned i;
    for (i = 0; i < t->n_code; i++) {
        const fr_instr_t *in = &t->code[i];
        h = fp_hash(h, &in->op, sizeof in->op);
        h = fp_hash(h, &in->a, sizeof in->a * 4); /* a, b, c, aux */
        h = fp_hash(h, &in->k, sizeof in->k);
    }
    if (t->n_params) h = fp_hash(h, t->params, sizeof(double) * t->n_params);
    h = fp_hash(h, t->outputs, sizeof(unsigned) * t->n_outputs);
    h = fp_hash(h, &t->flags, sizeof t->flags);
    return fp_hash(h, &t->lipschitz, sizeof t->lipschitz);
}
static void fp_parse(const char *const *texts, unsigned n_texts, int cases)
{
    static const char alphabet[] = "x[]();,.=+-*/^|&\\~ 0123456789eahfSpr\n";
    t_rng_t rng = {4242};
    unsigned long long h = FP_START;
    long ok = 0;
    int q;
    char buf[4096];
    for (q = 0; q < cases + (int)n_texts; q++) {
        const char *src = texts[(unsigned)q % n_texts];
        size_t n = strlen(src);
        int a;
        if (n >= sizeof buf - 8) continue;
        memcpy(buf, src, n);
        for (a = 0; q >= (int)n_texts && a < 1 + (int)(t_rng_unit(&rng) * 4); a++) {
            size_t at = (size_t)(t_rng_unit(&rng) * (double)n);
            int what = (int)(t_rng_unit(&rng) * 3);
            char c = alphabet[(int)(t_rng_unit(&rng) * (sizeof alphabet - 1))];
            if (what == 0 && n > 0) memmove(buf + at, buf + at + 1, n - at - 1), n--;
            else if (what == 1) memmove(buf + at + 1, buf + at, n - at), buf[at] = c, n++;
            else if (at < n) buf[at] = c;
        }
        for (a = 0; a < 2; a++) {
            fr_parse_desc_t d;
            fr_tape_t t;
            fr_diag_t dg;
            fr_result_t r;
            memset(&d, 0, sizeof d);
            memset(&dg, 0, sizeof dg);
            d.alpha = a;
            r = fr_parse(buf, n, &d, &t, &dg);
            h = fp_hash(h, &r, sizeof r);
            if (r == FR_OK) {
                h = fp_tape_bytes(h, &t);
                fr_tape_free(&t);
                ok++;
            } else {
                h = fp_hash(h, &dg.line, sizeof dg.line);
                h = fp_hash(h, &dg.column, sizeof dg.column);
                h = fp_hash(h, dg.message, strlen(dg.message));
            }
        }
    }
    printf("frep      fr_parse               %016llx  (%d texts, %ld parsed)\n", h, cases + (int)n_texts, ok);
}

int main(int argc, char **argv)
{
    int nrays = argc > 1 ? atoi(argv[1]) : 300;
    unsigned i, nf = sizeof fp_files / sizeof *fp_files, nm = sizeof fp_models / sizeof *fp_models;
    for (i = 0; i < nf + nm; i++) {
        fr_tape_t tape;
        fr_diag_t dg;
        size_t n = 0;
        char path[256], name[64], *text;
        long hits = 0;
        unsigned long long h;
        if (i < nf) {
            snprintf(path, sizeof path, "examples/models/%s", fp_files[i]);
            snprintf(name, sizeof name, "%s", fp_files[i]);
            text = fp_read(path, &n);
        } else {
            n = strlen(fp_models[i - nf]);
            snprintf(name, sizeof name, "model %u", i - nf);
            text = (char *)malloc(n + 1);
            if (text) memcpy(text, fp_models[i - nf], n + 1);
        }
        if (!text || fr_parse(text, n, NULL, &tape, &dg) != FR_OK) {
            printf("frep      %-22s cannot read or parse\n", name);
            free(text);
            continue;
        }
        h = fp_tape(&tape, nrays, 77 + i, &hits);
        printf("frep      %-22s %016llx  (%ld hits)\n", name, h, hits);
        fr_tape_free(&tape);
        free(text);
    }
    {
        /* the example files' texts and the models written here */
        const char *texts[sizeof fp_files / sizeof *fp_files + sizeof fp_models / sizeof *fp_models];
        char *owned[sizeof fp_files / sizeof *fp_files];
        unsigned k, nt = 0;
        for (k = 0; k < nf; k++) {
            char path[256];
            size_t n = 0;
            snprintf(path, sizeof path, "examples/models/%s", fp_files[k]);
            owned[k] = fp_read(path, &n);
            if (owned[k]) owned[k][n] = 0, texts[nt++] = owned[k];
        }
        for (k = 0; k < nm; k++) texts[nt++] = fp_models[k];
        fp_parse(texts, nt, 20000);
        for (k = 0; k < nf; k++) free(owned[k]);
    }
    fp_solve(200000);
    return 0;
}
