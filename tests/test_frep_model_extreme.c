/* frep.h model: stiff and extreme cases, one named test each with a bound,
   and concurrent evaluation of one tape from several threads. */
#include "interval.h"
#include "frep.h"
#include "test.h"
#include <float.h>
#include <pthread.h>
#include <quadmath.h>

/* the fixed scratch arrays below hold 1024 doubles: every tape here fits */
static fr_tape_t finish(fr_builder_t *b, fr_node_t n)
{
    fr_tape_t t;
    fr_diag_t d;
    if (fr_builder_finish(b, n, NULL, 0, &t, &d) != FR_OK) T_FAIL("build: %s", d.message);
    fr_builder_free(b);
    if (t.n_code <= 256) T_LE(fr_scratch_size(&t, FR_EVAL_GRAD), 1024 * sizeof(double));
    return t;
}

/* sphere of radius 1 far from the origin: p - c is exact, so the value
   keeps full relative accuracy: |f - 0.75| <= 4 ulp(1) */
static void extreme_sphere_far_from_origin_1e8(void)
{
    fr_builder_t b;
    double c[3] = {1e8, -1e8, 3e8}, p[3] = {1e8 + 0.5, -1e8, 3e8}, sc[1024], v = 0, g[3] = {0, 0, 0};
    fr_builder_init(&b, NULL);
    fr_tape_t t = finish(&b, fr_sphere(&b, fr_coords(&b), c, 1.0));
    T_NEAR(fr_eval(&t, p, sc), 0.75, 4 * DBL_EPSILON);
    T_INT_EQ(fr_eval_grad(&t, p, sc, &v, g), FR_OK);
    T_NEAR(g[0], -1.0, 4 * DBL_EPSILON);
    fr_tape_free(&t);
}

/* boxes at 1e150 (squares near 1e300) and 1e200 (squares overflow): the
   enclosure still contains the point values and is never NaN */
static void extreme_interval_at_overflowing_coordinates(void)
{
    fr_builder_t b;
    double c[3] = {0, 0, 0};
    iv_t sc[1024], o = {0, 0};
    double sp[1024];
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    fr_node_t f = fr_blend_union(&b, fr_sphere(&b, X, c, 1), fr_cylinder(&b, X, 2, c, 0.5), 0.5, 1, 1);
    fr_tape_t t = finish(&b, f);
    for (int e = 100; e <= 200; e += 50) {
        double s = pow(10.0, e);
        iv_t box[3] = {{s, 2 * s}, {-s, s}, {0, s}};
        double p[3] = {1.5 * s, 0.5 * s, 0.25 * s};
        T_INT_EQ(fr_eval_interval(&t, box, sc, &o), FR_OK);
        T_CHECK(!isnan(o.lo) && !isnan(o.hi));
        double v = fr_eval(&t, p, sp);
        if (!isnan(v)) T_CHECK(o.lo <= v && v <= o.hi);
    }
    fr_tape_free(&t);
}

/* R-union (alpha 0) exactly at f1 = f2 = 0: the radicand is 0, the
   gradient rule takes the sqrt term's derivative as 0: finite, and equal
   to g1 + g2 */
static void extreme_r_union_gradient_at_double_zero(void)
{
    fr_builder_t b;
    double n1[3] = {1, 0, 0}, n2[3] = {0, 1, 0}, p[3] = {0, 0, 0.3}, sc[1024], v = 0, g[3] = {0, 0, 0};
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    fr_tape_t t = finish(&b, fr_union(&b, fr_halfspace(&b, X, n1, 0), fr_halfspace(&b, X, n2, 0), 0.0));
    T_INT_EQ(fr_eval_grad(&t, p, sc, &v, g), FR_OK);
    T_EQ(v, 0.0);
    T_EQ(g[0], -1.0);
    T_EQ(g[1], -1.0);
    T_EQ(g[2], 0.0);
    fr_tape_free(&t);
}

/* x^0 + y - 1.5 at x = 0 and at a subnormal x: x^0 is the constant 1, so
   the gradient is (0, 1, 0); its derivative 0 * x^-1 was 0 * inf = NaN,
   and fr_trace's hits there had a zero normal. The parsed form too. */
static void extreme_zeroth_power_gradient_at_zero(void)
{
    static const double xs[3] = {0.0, 1e-310, -0.0};
    static const char text[] = "m(x[3], a[1]) { m = x[1]^0 + x[2] - 1.5; }";
    double sc[1024], v = 0, g[3];
    fr_tape_t t[2];
    fr_builder_t b;
    fr_diag_t dg;
    int i, k;
    fr_builder_init(&b, NULL);
    {
        fr_p3_t X = fr_coords(&b);
        t[0] = finish(&b, fr_sub(&b, fr_add(&b, fr_powi(&b, X.x, 0), X.y), fr_const(&b, 1.5)));
    }
    if (!T_INT_EQ(fr_parse(text, sizeof text - 1, NULL, &t[1], &dg), FR_OK)) { fr_tape_free(&t[0]); return; }
    for (k = 0; k < 2; k++)
        for (i = 0; i < 3; i++) {
            double p[3] = {xs[i], 1, 0};
            T_INT_EQ(fr_eval_grad(&t[k], p, sc, &v, g), FR_OK);
            T_EQ(v, 0.5);
            T_EQ(g[0], 0.0);
            T_EQ(g[1], 1.0);
            T_EQ(g[2], 0.0);
        }
    fr_tape_free(&t[0]);
    fr_tape_free(&t[1]);
}

/* gradient noise at |x| ~ 1e15 (the lattice index wraps through fmod):
   values stay within 2 amp and the enclosure contains samples */
static void extreme_noise_at_huge_coordinates(void)
{
    fr_builder_t b;
    double off[3] = {0, 0, 0}, sp[1024];
    iv_t sc[1024], o = {0, 0};
    fr_builder_init(&b, NULL);
    fr_tape_t t = finish(&b, fr_noise(&b, fr_coords(&b), 0.5, 1.0, off));
    t_rng_t r = {4};
    long bad = 0;
    for (int k = 0; k < 2000; k++) {
        double c = t_rng_range(&r, -1e15, 1e15);
        iv_t box[3] = {{c, c + 0.5}, {-c, -c + 0.5}, {0.25, 0.75}};
        double p[3] = {c + 0.25, -c + 0.125, 0.5};
        double v = fr_eval(&t, p, sp);
        fr_eval_interval(&t, box, sc, &o);
        if (!(fabs(v) <= 1.0) || !(o.lo <= v && v <= o.hi) || o.lo < -1.0 || o.hi > 1.0) bad++;
    }
    T_INT_EQ(bad, 0);
    fr_tape_free(&t);
}

/* blend with arguments near 1e200: (f/a)^2 overflows to inf, the
   displacement a0/(1+inf) is 0, and the value is the R-union's, not NaN */
static void extreme_blend_with_overflowing_arguments(void)
{
    fr_builder_t b;
    double sc[1024];
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    fr_tape_t t = finish(&b, fr_blend_union(&b, X.x, X.y, 0.5, 1e-3, 1e-3));
    double p[3] = {1e200, -1e200, 0};
    double v = fr_eval(&t, p, sc);
    T_CHECK(isfinite(v));
    T_REL(v, 1e200 - 1e200 + sqrt(2.0) * 1e200, 1e-15);
    fr_tape_free(&t);
}

/* a model at micrometre scale: the value, AD gradient and a 1e-12 box
   all scale with the model (no absolute tolerance hidden inside) */
static void extreme_micrometre_sphere(void)
{
    fr_builder_t b;
    double c[3] = {1e-6, 0, 0}, sc[1024], v = 0, g[3] = {0, 0, 0};
    iv_t si[1024], o = {0, 0};
    fr_builder_init(&b, NULL);
    fr_tape_t t = finish(&b, fr_sphere(&b, fr_coords(&b), c, 1e-6));
    double p[3] = {1.5e-6, 0, 0};
    T_REL(fr_eval(&t, p, sc), 0.75e-12, 1e-15);
    fr_eval_grad(&t, p, sc, &v, g);
    T_REL(g[0], -1e-6, 1e-15);
    iv_t box[3] = {{1.5e-6 - 1e-12, 1.5e-6 + 1e-12}, {-1e-12, 1e-12}, {-1e-12, 1e-12}};
    fr_eval_interval(&t, box, si, &o);
    T_CHECK(o.lo <= 0.75e-12 && 0.75e-12 <= o.hi);
    T_LE(iv_width(o), 1e-17); /* |grad| 1e-6 x 2e-12 x 3 axes, plus rounding */
    fr_tape_free(&t);
}

/* HyperFun's alpha rule is discontinuous at 1: alpha = 1 is max, alpha
   just below 1 is a + b + |a - b| ~ 2 max (documented) */
static void extreme_alpha_just_below_one(void)
{
    fr_builder_t b;
    double sc[1024], p[3] = {0.3, 0.7, 0};
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    fr_node_t u1 = fr_union(&b, X.x, X.y, 1.0), u2 = fr_union(&b, X.x, X.y, 1.0 - 1e-12);
    fr_tape_t t1, t2;
    T_INT_EQ(fr_builder_finish(&b, u1, NULL, 0, &t1, NULL), FR_OK);
    T_INT_EQ(fr_builder_finish(&b, u2, NULL, 0, &t2, NULL), FR_OK);
    T_EQ(fr_eval(&t1, p, sc), 0.7);
    T_NEAR(fr_eval(&t2, p, sc), 1.4, 1e-6);
    fr_tape_free(&t1);
    fr_tape_free(&t2);
    fr_builder_free(&b);
}

/* R-union and R-intersection far from one operand's surface: a + b -+ s
   cancels there (alpha 0, a = 1e17, b = -1: the intersection was 0, on
   the surface, for a point 1 outside b). The reference is __float128,
   where it cancels too past |a / b| ~ 2^56: it takes the identity
   a + b -+ s = 2 (1 + alpha) a b / (a + b +- s) there (when a + b and -+s
   differ in sign; checked against the plain sum where |a / b| is within
   2^±40). Point values and the gradient
   path's value within 4 ulp of the __float128 value, over operands of
   random signs and magnitudes 1e-150..1e150 and four alphas; interval
   evaluation of the point box contains it. */
static void extreme_r_functions_far_from_the_surface(void)
{
    static const double alphas[4] = {0, 0.25, 0.5, 0.9};
    t_rng_t rng = {0x5eed0f12ULL};
    double worst = 0, sc[1024], g[3];
    iv_t si[1024];
    int ia, op, k, n = (int)(20000 * t_scale()) + 10;
    for (ia = 0; ia < 4; ia++)
        for (op = 0; op < 2; op++) {
            fr_builder_t b;
            fr_builder_init(&b, NULL);
            fr_p3_t X = fr_coords(&b);
            double al = alphas[ia];
            fr_tape_t t = finish(&b, op ? fr_intersect(&b, X.x, X.y, al) : fr_union(&b, X.x, X.y, al));
            for (k = 0; k < n; k++) {
                double a = (t_rng_unit(&rng) < 0.5 ? -1 : 1) * pow(10.0, t_rng_range(&rng, -150, 150));
                double c = (t_rng_unit(&rng) < 0.5 ? -1 : 1) * pow(10.0, t_rng_range(&rng, -150, 150));
                double p[3], v, vg = 0, err;
                __float128 A, C, ref;
                iv_t box[3], o;
                if (k == 0) a = 1e17, c = -1; /* the case above, both ways */
                if (k == 1) a = -1e17, c = 1;
                p[0] = a, p[1] = c, p[2] = 0;
                A = a, C = c;
                { /* in __float128 the sum itself cancels past |a/b| ~ 2^56: its
                     cancellation-free form there (the docs' identity) */
                    __float128 S = sqrtq(A * A + C * C - 2 * (__float128)al * A * C), sg = op ? -1 : 1;
                    ref = sg * (A + C) < 0 ? 2 * (1 + (__float128)al) * A * C / (A + C - sg * S) : A + C + sg * S;
                    if (fabs(a / c) > 0x1p-40 && fabs(a / c) < 0x1p40 && !T_LE(fabsq((A + C + sg * S - ref) / ref), 1e-20)) break;
                }
                v = fr_eval(&t, p, sc);
                T_INT_EQ(fr_eval_grad(&t, p, sc, &vg, g), FR_OK);
                err = fabs((double)(((__float128)v - ref) / ref));
                if (err > worst) worst = err;
                if (!(err <= 4 * DBL_EPSILON) || vg != v) {
                    T_FAIL("%s alpha %g at (%.17g, %.17g): %.17g (gradient path %.17g), exact %.17g", op ? "intersect" : "union",
                           al, a, c, v, vg, (double)ref);
                    break;
                }
                box[0] = iv_point(a), box[1] = iv_point(c), box[2] = iv_point(0);
                T_INT_EQ(fr_eval_interval(&t, box, si, &o), FR_OK);
                if (!T_CHECK(o.lo <= (double)ref && (double)ref <= o.hi)) break;
            }
            fr_tape_free(&t);
        }
    printf("    R-functions far from the surface: worst relative error %.2g ulp\n", worst / DBL_EPSILON);
}

/* The interval image of an alpha < 1 R-function was padded by alpha
   itself, as if it were a field value (found by review, 2026-12-06): the
   alpha = 0.5 lens of two spheres of radius 0.5 s, evaluated on the point
   (0, s, 0), came out [-1.8e-15, 1.8e-15] for s = 1e-100 (the value is
   -2.52 s^2), and INTERVAL tracing reported hits at the ray origin on rays
   that miss. Now the point box's enclosure holds the point value and is
   within 1e-12 of it, relatively, at every scale (plus the widening's
   absolute floor, 4.5e-308, which matters at 1e-150 only). */
static void extreme_tiny_r_function_enclosure(void)
{
    static const double scales[4] = {1, 1e-8, 1e-100, 1e-150};
    int k;
    for (k = 0; k < 4; k++) {
        double s = scales[k], c1[3] = {-0.3 * s, 0, 0}, c2[3] = {0.3 * s, 0, 0}, p[3] = {0, s, 0}, sp[1024], v;
        iv_t box[3], o, si[1024];
        fr_builder_t b;
        fr_builder_init(&b, NULL);
        fr_p3_t X = fr_coords(&b);
        fr_tape_t t = finish(&b, fr_intersect(&b, fr_sphere(&b, X, c1, 0.5 * s), fr_sphere(&b, X, c2, 0.5 * s), 0.5));
        v = fr_eval(&t, p, sp);
        box[0] = iv_point(0), box[1] = iv_point(s), box[2] = iv_point(0);
        T_INT_EQ(fr_eval_interval(&t, box, si, &o), FR_OK);
        T_CHECK(o.lo <= v && v <= o.hi);
        T_LE(iv_width(o), 1e-12 * fabs(v) + 1e-306); /* + the widening's floor near underflow */
        T_LE(v, 0); /* outside both balls */
        fr_tape_free(&t);
    }
}

/* a tape of 10^6 instructions: building, finishing and pruning are
   iterative (no recursion), scratch is sized by the query */
static void extreme_million_instruction_tape(void)
{
    fr_builder_t b;
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    long n = t_count(1000000) / 4 + 1;
    fr_node_t acc = X.x;
    for (long i = 0; i < n; i++) acc = fr_binary(&b, FR_OP_MAX, acc, fr_sub(&b, X.y, fr_const(&b, (double)i)));
    fr_tape_t t = finish(&b, acc);
    T_GE(t.n_code, (unsigned int)(3 * n));
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_PRUNE));
    double p[3] = {-5, 2, 0};
    T_EQ(fr_eval(&t, p, sc), 2.0); /* max(x, y - 0, y - 1, ...) */
    fr_instr_t *buf = malloc(t.n_code * sizeof(fr_instr_t));
    iv_t box[3] = {{-6, -4}, {1.5, 2.5}, {0, 1}};
    fr_tape_t pr;
    T_INT_EQ(fr_prune_ex(&t, box, FR_PRUNE_EXACT, sc, buf, t.n_code, &pr, NULL), FR_OK);
    T_LT(pr.n_code, 16u); /* only y - 0 survives (plus its inputs) */
    T_EQ(fr_eval(&pr, p, sc), 2.0);
    free(buf);
    free(sc);
    fr_tape_free(&t);
}

/* ---------------------------------------------------------- threads */
typedef struct job_t {
    const fr_tape_t *t;
    const double *pts;
    double *out;
    int n;
} job_t;
static void *worker(void *arg)
{
    job_t *j = (job_t *)arg;
    void *sc = malloc(fr_scratch_size(j->t, FR_EVAL_AFFINE) + fr_scratch_size(j->t, FR_EVAL_GRAD));
    for (int rep = 0; rep < 4; rep++)
        for (int i = 0; i < j->n; i++) {
            double v = 0, g[3] = {0, 0, 0};
            iv_t box[3] = {{j->pts[3 * i], j->pts[3 * i] + 0.01}, {j->pts[3 * i + 1], j->pts[3 * i + 1] + 0.01},
                           {j->pts[3 * i + 2], j->pts[3 * i + 2] + 0.01}}, o = {0, 0};
            fr_eval_grad(j->t, j->pts + 3 * i, sc, &v, g);
            fr_eval_interval(j->t, box, sc, &o);
            j->out[i] = fr_eval(j->t, j->pts + 3 * i, sc) + 0 * v + 0 * o.lo;
        }
    free(sc);
    return NULL;
}
static void concurrent_evaluation_matches_serial(void)
{
    fr_builder_t b;
    double c[3] = {0, 0, 0}, off[3] = {0.1, 0.2, 0.3};
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_twist(&b, fr_coords(&b), 2, -1, 1, 0, 1);
    fr_node_t f = fr_smooth_union(&b, fr_torus(&b, X, 2, c, 0.6, 0.2), fr_noise(&b, X, 0.2, 2, off), 0.1);
    fr_tape_t t = finish(&b, f);
    enum { N = 2000, T = 4 };
    double *pts = malloc(sizeof(double) * 3 * N), *serial = malloc(sizeof(double) * N);
    double *outs[T];
    t_rng_t r = {77};
    for (int i = 0; i < 3 * N; i++) pts[i] = t_rng_range(&r, -1, 1);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
    for (int i = 0; i < N; i++) serial[i] = fr_eval(&t, pts + 3 * i, sc);
    pthread_t th[T];
    job_t jobs[T];
    for (int k = 0; k < T; k++) {
        outs[k] = malloc(sizeof(double) * N);
        jobs[k].t = &t;
        jobs[k].pts = pts;
        jobs[k].out = outs[k];
        jobs[k].n = N;
        pthread_create(&th[k], NULL, worker, &jobs[k]);
    }
    long diff = 0;
    for (int k = 0; k < T; k++) {
        pthread_join(th[k], NULL);
        for (int i = 0; i < N; i++) diff += outs[k][i] != serial[i];
        free(outs[k]);
    }
    T_INT_EQ(diff, 0);
    free(pts);
    free(serial);
    free(sc);
    fr_tape_free(&t);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(extreme_sphere_far_from_origin_1e8),  T_CASE(extreme_interval_at_overflowing_coordinates),
        T_CASE(extreme_r_union_gradient_at_double_zero), T_CASE(extreme_zeroth_power_gradient_at_zero),
        T_CASE(extreme_noise_at_huge_coordinates),
        T_CASE(extreme_blend_with_overflowing_arguments), T_CASE(extreme_micrometre_sphere),
        T_CASE(extreme_alpha_just_below_one),        T_CASE(extreme_million_instruction_tape),
        T_CASE(extreme_r_functions_far_from_the_surface),
        T_CASE(extreme_tiny_r_function_enclosure),
        T_CASE(concurrent_evaluation_matches_serial),
    };
    return T_RUN(argc, argv, cases);
}
