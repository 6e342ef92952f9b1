/* tests/test_frep_fp_env.c — frep.h's rigorous entry points under a host
   that turned flush-to-zero and denormals-are-zero on (as Embree
   recommends): fr_trace, fr_eval_interval, fr_eval_affine, fr_prune_ex,
   fr_bound_box, fr_prepare and fr_solve_poly give exactly the answers they
   give in the default environment, and hand the host its MXCSR back.
   Before 2026-12-05 they ran in the host's: tiny direction vectors then
   flushed the ray polynomial's coefficients to 0 and the roots were
   wrong. Callbacks run in the default environment too. */
#include "test.h"
#include "interval.h"
#include "frep.h"
#include "test_frep_trace_models.h"
#include <fenv.h>
#if defined(__SSE2__)
#  include <xmmintrin.h>
#  define FTZ_DAZ 0x8040u

static unsigned host_csr;
static void host_on(void) { _mm_setcsr(host_csr | FTZ_DAZ); }
static void host_off(void) { _mm_setcsr(host_csr & ~FTZ_DAZ); }
/* the environment was handed back: FTZ and DAZ as the host left them */
static int handed_back(void) { return _mm_getcsr() == (host_csr | FTZ_DAZ); }

static int cb_env_ok = 1;
static double cb_ball(const double p[3], void *u)
{
    (void)u;
    cb_env_ok &= iv_fp_env_ok();
    return 0.25 - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
}
static iv_t cb_ball_iv(const iv_t b[3], void *u)
{
    (void)u;
    cb_env_ok &= iv_fp_env_ok();
    return iv_sub(iv_point(0.25), iv_add(iv_add(iv_sqr(b[0]), iv_sqr(b[1])), iv_sqr(b[2])));
}


static int same_hit(const fr_hit_t *a, const fr_hit_t *b)
{
    return a->hit == b->hit && memcmp(&a->t, &b->t, sizeof a->t) == 0 && memcmp(&a->t_err, &b->t_err, sizeof a->t_err) == 0 &&
           memcmp(a->normal, b->normal, sizeof a->normal) == 0 && a->method == b->method;
}

/* Rays with directions 2^-266 long (the ray polynomial's t^4 term ~1e-320)
   and unit ones, every method, plain and prepared. */
static void trace_answers_as_in_the_default_environment(void)
{
    static const double box[6] = {-3, -3, -3, 3, 3, 3};
    static const fr_method_t meths[4] = {FR_METHOD_AUTO, FR_METHOD_ANALYTIC, FR_METHOD_INTERVAL, FR_METHOD_STEP};
    t_rng_t g = {4242};
    model_t m;
    fr_prepared_t pr;
    long n = t_count(300), i, differ = 0, lost = 0, hits = 0;
    make_torus_and_ball(&m);
    host_off();
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    for (i = 0; i < n; i++) {
        double o[3], d[3], f = (i & 1) ? ldexp(1.0, -266) : 1.0;
        int k, j, p;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -2.5, 2.5); d[k] = (t_rng_range(&g, -1, 1) - 0.5 * o[k]) * f; }
        for (j = 0; j < 4; j++)
            for (p = 0; p < 2; p++) {
                fr_trace_desc_t D = method(meths[j], 0);
                fr_hit_t a, b;
                fr_result_t ra, rb;
                if (p) D.prepared = &pr;
                host_off();
                ra = fr_trace(&m.tape, o, d, 0, 4 / f, &D, m.scratch, &a);
                host_on();
                rb = fr_trace(&m.tape, o, d, 0, 4 / f, &D, m.scratch, &b);
                lost += !handed_back();
                host_off();
                if (ra != rb || (ra == FR_OK && !same_hit(&a, &b))) {
                    if (differ++ < 5) T_FAIL("ray %ld method %d%s: %d hit %d t %.17g, with FTZ/DAZ %d hit %d t %.17g", i, j,
                                            p ? " prepared" : "", ra, a.hit, a.t, rb, b.hit, b.t);
                }
                hits += ra == FR_OK && a.hit;
            }
    }
    T_INT_EQ(differ, 0);
    T_INT_EQ(lost, 0);
    T_GT(hits, n);
    fr_prepared_free(&pr);
    model_free(&m);
}

/* Interval and affine evaluation, pruning and the bounding box on boxes
   with tiny widths (1e-320 to 1e-150 from a point on the surface). */
static void evaluations_as_in_the_default_environment(void)
{
    static const double lo3[3] = {-3, -3, -3}, hi3[3] = {3, 3, 3};
    t_rng_t g = {99};
    model_t m;
    long n = t_count(2000), i, differ = 0, lost = 0;
    iv_t *si;
    iv_affine_t *sa;
    fr_instr_t *buf;
    void *sp;
    make_torus_and_ball(&m);
    sp = malloc(fr_scratch_size(&m.tape, FR_EVAL_PRUNE));
    si = (iv_t *)malloc(fr_scratch_size(&m.tape, FR_EVAL_INTERVAL));
    sa = (iv_affine_t *)malloc(fr_scratch_size(&m.tape, FR_EVAL_AFFINE));
    buf = (fr_instr_t *)malloc(sizeof(fr_instr_t) * m.tape.n_code);
    for (i = 0; i < n; i++) {
        iv_t box[3], ra, rb, pa, pb;
        iv_affine_t P[3], aa, ab;
        fr_tape_t ta, tb;
        double w = pow(10.0, t_rng_range(&g, -320, -150)), c[3] = {0.5, 0, 0};
        int k;
        for (k = 0; k < 3; k++) box[k] = iv_make(c[k] + t_rng_range(&g, -1, 0) * w, c[k] + t_rng_range(&g, 0, 1) * w);
        for (k = 0; k < 3; k++) P[k] = iv_affine_from_iv(box[k]);
        host_off();
        fr_eval_interval(&m.tape, box, si, &ra);
        fr_eval_affine(&m.tape, P, sa, &aa);
        fr_prune_ex(&m.tape, box, FR_PRUNE_SIGN, sp, buf, m.tape.n_code, &ta, &pa);
        host_on();
        fr_eval_interval(&m.tape, box, si, &rb);
        fr_eval_affine(&m.tape, P, sa, &ab);
        fr_prune_ex(&m.tape, box, FR_PRUNE_SIGN, sp, buf, m.tape.n_code, &tb, &pb);
        lost += !handed_back();
        host_off();
        if (memcmp(&ra, &rb, sizeof ra) || memcmp(&aa, &ab, sizeof aa) || memcmp(&pa, &pb, sizeof pa) || ta.n_code != tb.n_code)
            differ++;
    }
    {
        double alo[3], ahi[3], blo[3], bhi[3];
        host_off();
        T_INT_EQ(fr_bound_box(&m.tape, lo3, hi3, 6, si, alo, ahi), FR_OK);
        host_on();
        T_INT_EQ(fr_bound_box(&m.tape, lo3, hi3, 6, si, blo, bhi), FR_OK);
        lost += !handed_back();
        host_off();
        T_CHECK(memcmp(alo, blo, sizeof alo) == 0 && memcmp(ahi, bhi, sizeof ahi) == 0);
    }
    T_INT_EQ(differ, 0);
    T_INT_EQ(lost, 0);
    free(si), free(sa), free(buf), free(sp);
    model_free(&m);
}

/* Polynomials with tiny coefficients (1e-320 to 1e-290, roots in [-2, 2]). */
static void solver_as_in_the_default_environment(void)
{
    t_rng_t g = {7};
    long n = t_count(5000), i, differ = 0, lost = 0;
    for (i = 0; i < n; i++) {
        double c[5], ra[4], rb[4], s = pow(10.0, t_rng_range(&g, -320, -290));
        double r1 = t_rng_range(&g, -2, 2), r2 = t_rng_range(&g, -2, 2);
        int na, nb;
        /* s (t - r1)(t - r2)(t^2 + 1) */
        c[4] = s; c[3] = -s * (r1 + r2); c[2] = s * (r1 * r2 + 1); c[1] = -s * (r1 + r2); c[0] = s * r1 * r2;
        host_off();
        na = fr_solve_poly(c, 4, -3, 3, ra);
        host_on();
        nb = fr_solve_poly(c, 4, -3, 3, rb);
        lost += !handed_back();
        host_off();
        if (na != nb || (na > 0 && memcmp(ra, rb, sizeof(double) * (size_t)na))) differ++;
    }
    T_INT_EQ(differ, 0);
    T_INT_EQ(lost, 0);
}

static void callbacks_run_in_the_default_environment(void)
{
    model_t m;
    fr_hit_t h;
    double o[3] = {-2, 0.01, 0.02}, d[3] = {1, 0, 0};
    fr_trace_desc_t D = method(FR_METHOD_INTERVAL, 1e-9);
    fr_builder_t b;
    fr_callback_t cb;
    memset(&cb, 0, sizeof cb);
    cb.point = cb_ball;
    cb.interval = cb_ball_iv;
    fr_builder_init(&b, NULL);
    model_finish(&m, &b, fr_callback(&b, fr_coords(&b), &cb));
    cb_env_ok = 1;
    host_on();
    T_INT_EQ(fr_trace(&m.tape, o, d, 0, 4, &D, m.scratch, &h), FR_OK);
    T_CHECK(handed_back());
    host_off();
    T_INT_EQ(h.hit, 1);
    T_INT_EQ(cb_env_ok, 1);
    model_free(&m);
}
#endif

/* A host rounding upward (or down, or toward zero): fr_trace answers as in
   round to nearest, and the host keeps its mode. */
static void rounding_modes_answer_as_to_nearest(void)
{
    static const int modes[3] = {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO};
    t_rng_t g = {31};
    model_t m;
    long n = t_count(200), i, differ = 0, kept = 0;
    int k;
    fr_builder_t b;
    static const double c0[3] = {0, 0, 0};
    fr_builder_init(&b, NULL);
    model_finish(&m, &b, fr_sphere(&b, fr_coords(&b), c0, 0.8));
    for (i = 0; i < n; i++) {
        double o[3], d[3];
        fr_trace_desc_t D = method(i % 2 ? FR_METHOD_INTERVAL : FR_METHOD_ANALYTIC, 0);
        fr_hit_t a, h;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -2, 2); d[k] = t_rng_range(&g, -1, 1) - 0.5 * o[k]; }
        T_INT_EQ(fr_trace(&m.tape, o, d, 0, 4, &D, m.scratch, &a), FR_OK);
        fesetround(modes[i % 3]);
        fr_trace(&m.tape, o, d, 0, 4, &D, m.scratch, &h);
        kept += fegetround() == modes[i % 3];
        fesetround(FE_TONEAREST);
        differ += a.hit != h.hit || memcmp(&a.t, &h.t, sizeof a.t) != 0;
    }
    T_INT_EQ(differ, 0);
    T_INT_EQ(kept, n);
    model_free(&m);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
#ifdef FTZ_DAZ
        T_CASE(trace_answers_as_in_the_default_environment), T_CASE(evaluations_as_in_the_default_environment),
        T_CASE(solver_as_in_the_default_environment), T_CASE(callbacks_run_in_the_default_environment),
#endif
        T_CASE(rounding_modes_answer_as_to_nearest),
    };
#ifdef FTZ_DAZ
    host_csr = _mm_getcsr();
#endif
    return T_RUN(argc, argv, cases);
}
