/* Ray-surface intersection of frep.h (issue 5, items 2-7): ray to polynomial,
   analytic CSG, stepping, interval bisection, sphere tracing, the entry
   point, and the stability cases of the issue, one named test each with an
   asserted bound. References are closed forms evaluated in __float128. */
#include "test.h"
#include "interval.h"
#include "frep.h"
#include <quadmath.h>
#include "test_frep_trace_models.h"

/* ---------------------------------------------------------------- models */

/* exact distance bound: r - |p - c| (an SDF wrapped, Lipschitz 1) */
static void make_sdf_sphere(model_t *m, const double c[3], double r)
{
    fr_builder_t b;
    fr_p3_t p;
    fr_node_t dx, dy, dz, len;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    dx = fr_sub(&b, p.x, fr_const(&b, c[0]));
    dy = fr_sub(&b, p.y, fr_const(&b, c[1]));
    dz = fr_sub(&b, p.z, fr_const(&b, c[2]));
    len = fr_unary(&b, FR_OP_SQRT, fr_add(&b, fr_add(&b, fr_unary(&b, FR_OP_SQR, dx), fr_unary(&b, FR_OP_SQR, dy)),
                                          fr_unary(&b, FR_OP_SQR, dz)));
    model_finish(m, &b, fr_from_sdf(&b, fr_sub(&b, len, fr_const(&b, r)), 1.0));
}

/* first entry of a ray x = ox + t along +x at height rho into a sphere of
   radius r at the origin, in quad */
static double sphere_entry(double ox, double rho, double r)
{
    __float128 h = (__float128)r * r - (__float128)rho * rho;
    return (double)(-(__float128)ox - sqrtq(h));
}

/* ---------------------------------------------------------------- ray to polynomial */

static void ray_poly_matches_point_evaluation(void)
{
    model_t m;
    double o[3] = {0.3, -1.7, 2.2}, d[3] = {0.5, 0.25, -0.8}, coef[FR_POLY_MAX_DEGREE + 1], t;
    void *s;
    int deg;
    make_torus_poly(&m, 2, 0.5);
    s = malloc(fr_ray_poly_scratch_size(&m.tape));
    T_INT_EQ(fr_ray_poly(&m.tape, o, d, s, coef, &deg), FR_OK);
    T_INT_EQ(deg, 4);
    for (t = -3; t <= 3; t += 0.37) {
        double p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
        double a, v = fr_poly_eval_compensated(coef, deg, t, &a);
        T_LE(fabs(v - fr_eval(&m.tape, p, m.scratch)), 1e-13 * a);
    }
    free(s);
    model_free(&m);
}

static void ray_poly_reports_non_polynomial_tape(void)
{
    model_t m;
    double o[3] = {0.5, 0.1, -3}, d[3] = {0.1, 0.2, 1}, coef[FR_POLY_MAX_DEGREE + 1];
    void *s;
    int deg;
    make_torus_hf(&m, 2, 0.5);
    s = malloc(fr_ray_poly_scratch_size(&m.tape));
    T_INT_EQ(fr_ray_poly(&m.tape, o, d, s, coef, &deg), FR_ERR_NOT_POLYNOMIAL);
    free(s);
    model_free(&m);
}

/* fr_ray_poly through each opcode it accepts, in a tape of its own: the
   polynomial ones on a = x + 0.7y - 0.2z and c = yz - 0.3x (POWI at 0, 3
   and the squaring path's 4; DIV by a constant), and every operation it
   takes on a slot that is constant along the ray (y and z for a ray along
   x: sqrt, abs, exp, log, sin, cos, atan, powc, min, max, never run by a
   test before). The polynomial at t must give fr_eval at o + t d; with a
   direction that moves y and z those tapes are FR_ERR_NOT_POLYNOMIAL. */
static int g_poly_case;
static fr_node_t b_poly_case(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t a = fr_sub(b, fr_add(b, X.x, fr_mul(b, fr_const(b, 0.7), X.y)), fr_mul(b, fr_const(b, 0.2), X.z));
    fr_node_t c = fr_sub(b, fr_mul(b, X.y, X.z), fr_mul(b, fr_const(b, 0.3), X.x));
    fr_node_t yz = fr_add(b, fr_add(b, fr_unary(b, FR_OP_SQR, X.y), fr_unary(b, FR_OP_SQR, X.z)), fr_const(b, 0.5));
    static const fr_op_t const_ops[7] = {FR_OP_SQRT, FR_OP_ABS, FR_OP_EXP, FR_OP_LOG, FR_OP_SIN, FR_OP_COS, FR_OP_ATAN};
    switch (g_poly_case) {
    case 0: return fr_unary(b, FR_OP_NEG, a);
    case 1: return fr_unary(b, FR_OP_SQR, c);
    case 2: return fr_add(b, a, c);
    case 3: return fr_sub(b, a, c);
    case 4: return fr_mul(b, a, c);
    case 5: return fr_add(b, fr_add(b, fr_powi(b, a, 3), fr_powi(b, c, 4)), fr_powi(b, a, 0));
    case 6: return fr_div(b, c, fr_const(b, 2.5));
    case 7: return fr_add(b, a, fr_powc(b, yz, 1.7));
    case 8: return fr_add(b, a, fr_binary(b, FR_OP_MIN, X.y, X.z));
    case 9: return fr_add(b, a, fr_binary(b, FR_OP_MAX, X.y, X.z));
    default: return fr_add(b, a, fr_unary(b, const_ops[g_poly_case - 10], yz));
    }
}
static void ray_poly_every_accepted_opcode(void)
{
    double o[3] = {0.3, -1.7, 2.2}, along_x[3] = {0.9, 0, 0}, d[3] = {0.5, 0.25, -0.8}, coef[FR_POLY_MAX_DEGREE + 1], t;
    int deg;
    for (g_poly_case = 0; g_poly_case < 17; g_poly_case++) {
        fr_builder_t b;
        fr_tape_t tape;
        fr_diag_t dg;
        void *s, *sp;
        int k, constant_op = g_poly_case >= 7; /* constant along x only */
        fr_builder_init(&b, NULL);
        if (!T_INT_EQ(fr_builder_finish(&b, b_poly_case(&b, fr_coords(&b)), NULL, 0, &tape, &dg), FR_OK)) {
            fr_builder_free(&b);
            continue;
        }
        fr_builder_free(&b);
        s = malloc(fr_ray_poly_scratch_size(&tape)), sp = malloc(fr_scratch_size(&tape, FR_EVAL_POINT));
        for (k = 0; k < 2; k++) {
            const double *dir = k ? d : along_x;
            fr_result_t rc = fr_ray_poly(&tape, o, dir, s, coef, &deg);
            if (k && constant_op) { T_INT_EQ(rc, FR_ERR_NOT_POLYNOMIAL); continue; }
            if (!T_INT_EQ(rc, FR_OK)) continue;
            for (t = -3; t <= 3; t += 0.37) {
                double p[3] = {o[0] + t * dir[0], o[1] + t * dir[1], o[2] + t * dir[2]};
                double a, v = fr_poly_eval_compensated(coef, deg, t, &a);
                T_LE(fabs(v - fr_eval(&tape, p, sp)), 1e-13 * a + 1e-15);
            }
        }
        free(s), free(sp);
        fr_tape_free(&tape);
    }
}

/* ---------------------------------------------------------------- stability cases */

/* A ray 1e-10 inside the silhouette of a unit sphere (two roots 2.8e-5
   apart), one exactly tangent, one 1e-10 outside. */
static void grazing_ray_sphere(void)
{
    static const double c[3] = {0, 0, 0};
    model_t m;
    double d[3] = {1, 0, 0};
    int k;
    make_sphere(&m, c, 1);
    for (k = 0; k < 3; k++) {
        double rho = k == 0 ? 1 - 1e-10 : k == 1 ? 1.0 : 1 + 1e-10, o[3] = {-5, rho, 0};
        fr_hit_t a = trace(&m, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0));
        fr_hit_t iv = trace(&m, o, d, 0, 10, method(FR_METHOD_INTERVAL, 1e-10));
        if (k < 2) {
            double tr = sphere_entry(-5, rho, 1);
            T_INT_EQ(a.hit, 1);
            T_NEAR(a.t, tr, 1e-9);
            T_INT_EQ(iv.hit, 1);
            T_NEAR(iv.t, tr, 2e-5); /* the enclosure cannot tell the two roots apart closer than this */
        } else {
            T_INT_EQ(a.hit, 0);
            /* a reported touch must be within the enclosure's reach of the surface */
            if (iv.hit) T_LE(fabs(sqrt(iv.point[0] * iv.point[0] + iv.point[1] * iv.point[1]) - 1), 1e-6);
        }
    }
    model_free(&m);
}

/* Tangent to the torus' outer equator (R + r = 2.5) from 1e-9 inside. */
static void grazing_ray_torus(void)
{
    model_t m, h;
    double d[3] = {1, 0, 0}, y = 2.5 - 1e-9, o[3] = {-5, 2.5 - 1e-9, 0};
    double tr = (double)(5 - sqrtq((__float128)2.5 * 2.5 - (__float128)y * y));
    fr_hit_t a, iv;
    make_torus_poly(&m, 2, 0.5);
    make_torus_hf(&h, 2, 0.5);
    a = trace(&m, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(a.hit, 1);
    T_NEAR(a.t, tr, 1e-8);
    iv = trace(&h, o, d, 0, 10, method(FR_METHOD_INTERVAL, 1e-9));
    T_INT_EQ(iv.hit, 1);
    T_NEAR(iv.t, tr, 1e-4);
    model_free(&m);
    model_free(&h);
}

/* Along the axis the ray passes through the hole: every method misses. */
static void ray_along_torus_axis_misses(void)
{
    model_t m, h;
    double o[3] = {0, 0, -5}, d[3] = {0, 0, 1};
    fr_trace_desc_t st = method(FR_METHOD_STEP, 1e-9);
    make_torus_poly(&m, 2, 0.5);
    make_torus_hf(&h, 2, 0.5);
    st.step = 0.01;
    T_INT_EQ(trace(&m, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0)).hit, 0);
    T_INT_EQ(trace(&h, o, d, 0, 10, method(FR_METHOD_INTERVAL, 1e-9)).hit, 0);
    T_INT_EQ(trace(&h, o, d, 0, 10, st).hit, 0);
    model_free(&m);
    model_free(&h);
}

/* Edge-on, in the torus plane through the centre: first hit at x = -2.5. */
static void ray_edge_on_torus(void)
{
    model_t m, h;
    double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0};
    fr_trace_desc_t st = method(FR_METHOD_STEP, 1e-11);
    fr_hit_t a, iv, s;
    make_torus_poly(&m, 2, 0.5);
    make_torus_hf(&h, 2, 0.5);
    st.step = 0.01;
    a = trace(&m, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0));
    iv = trace(&h, o, d, 0, 10, method(FR_METHOD_INTERVAL, 1e-11));
    s = trace(&h, o, d, 0, 10, st);
    T_INT_EQ(a.hit, 1); T_NEAR(a.t, 2.5, 1e-14);
    T_INT_EQ(iv.hit, 1); T_NEAR(iv.t, 2.5, 1e-11);
    T_INT_EQ(s.hit, 1); T_NEAR(s.t, 2.5, 1e-11);
    model_free(&m);
    model_free(&h);
}

/* A slab 2e-5 thick between the sample points of a 0.01 step: stepping
   misses it (the documented trade), interval bisection must not. */
static void thin_feature_stepping_misses_interval_finds(void)
{
    fr_builder_t b;
    model_t m;
    fr_p3_t p;
    double o[3] = {-1, 0.1, 0.2}, d[3] = {1, 0, 0}, w = 1e-5, xc = 0.3037;
    fr_trace_desc_t st = method(FR_METHOD_STEP, 1e-12);
    fr_hit_t s, iv;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&m, &b, fr_sub(&b, fr_const(&b, w * w), fr_unary(&b, FR_OP_SQR, fr_sub(&b, p.x, fr_const(&b, xc)))));
    st.step = 0.01;
    s = trace(&m, o, d, 0, 2, st);
    T_INT_EQ(s.hit, 0);
    iv = trace(&m, o, d, 0, 2, method(FR_METHOD_INTERVAL, 1e-12));
    T_INT_EQ(iv.hit, 1);
    T_NEAR(iv.t, 1 + xc - w, 1e-12);
    /* the same through affine forms (the tape is polynomial, so the default
       above bounds segments by the ray polynomial's centred form), and with
       a pixel footprint 1000 times the slab: coarser leaves, same root */
    {
        fr_trace_desc_t af = method(FR_METHOD_INTERVAL, 1e-12), fp = method(FR_METHOD_INTERVAL, 1e-12);
        af.no_poly_range = 1;
        fp.footprint = 0.01;
        iv = trace(&m, o, d, 0, 2, af);
        T_INT_EQ(iv.hit, 1);
        T_NEAR(iv.t, 1 + xc - w, 1e-12);
        iv = trace(&m, o, d, 0, 2, fp);
        T_INT_EQ(iv.hit, 1);
        T_NEAR(iv.t, 1 + xc - w, 1e-12);
    }
    model_free(&m);
}

/* fr_bound_box: the box holds every sampled solid point (and the closed-form
   extent), and is no larger than that plus three octree cells (interval
   evaluation of x^4 - 5x^2 over a cell overestimates by O(cell), which
   keeps a few empty cells beside the solid at depth 6; 2.66 is measured). */
static void bound_box_holds_the_solid(void)
{
    model_t m;
    static const double lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5}, far_lo[3] = {6, 6, 6}, far_hi[3] = {7, 7, 7};
    double blo[3], bhi[3], cell = 10.0 / 64.0;
    void *s;
    t_rng_t g = {7};
    long n = t_count(20000), i, inside = 0;
    int k;
    make_tangle(&m);
    s = malloc(fr_scratch_size(&m.tape, FR_EVAL_INTERVAL));
    T_INT_EQ(fr_bound_box(&m.tape, lo, hi, 6, s, blo, bhi), FR_OK);
    for (k = 0; k < 3; k++) {
        T_LE(blo[k], -TANGLE_EXTENT); T_GE(blo[k], -TANGLE_EXTENT - 3 * cell);
        T_GE(bhi[k], TANGLE_EXTENT); T_LE(bhi[k], TANGLE_EXTENT + 3 * cell);
    }
    for (i = 0; i < n; i++) {
        double p[3];
        for (k = 0; k < 3; k++) p[k] = t_rng_range(&g, -2.4, 2.4);
        if (fr_eval(&m.tape, p, s) < 0) continue;
        inside++;
        for (k = 0; k < 3; k++) { T_GE(p[k], blo[k]); T_LE(p[k], bhi[k]); }
    }
    T_GT(inside, n / 20); /* the samples do reach the solid */
    T_INT_EQ(fr_bound_box(&m.tape, far_lo, far_hi, 0, s, blo, bhi), FR_OK);
    T_GT(blo[0], bhi[0]); /* no solid there: an empty box */
    T_INT_EQ(fr_bound_box(&m.tape, hi, lo, 0, s, blo, bhi), FR_ERR_INVALID_ARG);
    free(s);
    model_free(&m);
}

/* Random rays at the tangle cube: interval bisection through the centred
   form (default), through affine forms, clipped to fr_bound_box's box, with
   a pixel footprint, and any-hit, against the analytic roots. */
static void tangle_interval_variants_agree(void)
{
    model_t m;
    static const double lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5};
    double box[6];
    t_rng_t g = {11};
    long n = t_count(300), i, hits = 0;
    int k;
    make_tangle(&m);
    T_INT_EQ(fr_bound_box(&m.tape, lo, hi, 0, m.scratch, box, box + 3), FR_OK);
    for (i = 0; i < n; i++) {
        double o[3], d[3];
        fr_trace_desc_t af = method(FR_METHOD_INTERVAL, 1e-10), cl = method(FR_METHOD_INTERVAL, 1e-10);
        fr_trace_desc_t fp = method(FR_METHOD_INTERVAL, 1e-10), any = method(FR_METHOD_INTERVAL, 1e-10);
        fr_hit_t a, iv, h;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -8, 8); d[k] = t_rng_range(&g, -2, 2) - o[k]; }
        af.no_poly_range = 1;
        cl.bounds = box;
        fp.footprint = 1e-2;
        any.any_hit = 1;
        a = trace(&m, o, d, 0, 2, method(FR_METHOD_ANALYTIC, 0));
        iv = trace(&m, o, d, 0, 2, method(FR_METHOD_INTERVAL, 1e-10));
        hits += a.hit;
        T_INT_EQ(iv.hit, a.hit);
        if (a.hit) T_NEAR(iv.t, a.t, 2e-10);
        h = trace(&m, o, d, 0, 2, af);
        T_INT_EQ(h.hit, a.hit);
        if (a.hit) T_NEAR(h.t, a.t, 2e-10);
        h = trace(&m, o, d, 0, 2, cl);
        T_INT_EQ(h.hit, a.hit);
        if (a.hit) T_NEAR(h.t, a.t, 2e-10);
        /* a footprint leaf may hold several roots: within the footprint */
        h = trace(&m, o, d, 0, 2, fp);
        T_INT_EQ(h.hit, a.hit);
        if (a.hit) T_NEAR(h.t, a.t, 1e-2 * fabs(a.t) + 2e-10);
        h = trace(&m, o, d, 0, 2, any);
        T_INT_EQ(h.hit, a.hit);
        if (h.hit) T_LE(h.t_err, 1.0);
    }
    T_GT(hits, n / 10);
    model_free(&m);
}

/* Interval Newton never loses a root the plain bisection finds: random rays
   at the tangle cube and the quartic torus, grazing ones included, and the
   thin slab; same hits, same t to the tolerance. */
static void interval_newton_never_misses(void)
{
    model_t tc, to, slab;
    fr_builder_t b;
    fr_p3_t p;
    t_rng_t g = {23};
    long n = t_count(400), i, hits = 0;
    unsigned long long ev_plain = 0, ev_newton = 0;
    double os[3] = {-1, 0.1, 0.2}, ds[3] = {1, 0, 0}, w = 1e-5, xc = 0.3037;
    fr_trace_desc_t pl = method(FR_METHOD_INTERVAL, 1e-10), nw = method(FR_METHOD_INTERVAL, 1e-10);
    fr_hit_t a, h;
    int k;
    nw.interval_newton = 1;
    make_tangle(&tc);
    make_torus_poly(&to, 2, 0.5);
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&slab, &b, fr_sub(&b, fr_const(&b, w * w), fr_unary(&b, FR_OP_SQR, fr_sub(&b, p.x, fr_const(&b, xc)))));
    for (i = 0; i < n; i++) {
        model_t *m = i % 2 ? &to : &tc;
        double o[3], d[3];
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -8, 8); d[k] = t_rng_range(&g, -2.5, 2.5) - o[k]; }
        a = trace(m, o, d, 0, 2, pl);
        h = trace(m, o, d, 0, 2, nw);
        hits += a.hit;
        ev_plain += a.evals;
        ev_newton += h.evals;
        T_INT_EQ(h.hit, a.hit);
        if (a.hit && h.hit) T_NEAR(h.t, a.t, 2e-10);
    }
    T_GT(hits, n / 10);
    /* Newton acts where G' excludes 0; there the default monotone hand-over
       already takes the segment to regula falsi (or drops it), so Newton
       may only narrow what is left: never more evaluations */
    T_LE((double)ev_newton, (double)ev_plain);
    h = trace(&slab, os, ds, 0, 2, nw);
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, 1 + xc - w, 1e-10);
    model_free(&tc);
    model_free(&to);
    model_free(&slab);
}

/* bounds: a ray that misses the box costs no evaluation and reports a miss */
static void bounds_reject_without_evaluation(void)
{
    model_t m;
    static const double c[3] = {0, 0, 0}, box[6] = {-1, -1, -1, 1, 1, 1};
    double o[3] = {-5, 3, 0}, d[3] = {1, 0, 0}, o2[3] = {-5, 0.5, 0};
    fr_trace_desc_t desc = method(FR_METHOD_INTERVAL, 1e-10);
    fr_hit_t h;
    make_sphere(&m, c, 1.0);
    desc.bounds = box;
    h = trace(&m, o, d, 0, 100, desc);
    T_INT_EQ(h.hit, 0);
    T_INT_EQ(h.evals, 0);
    h = trace(&m, o2, d, 0, HUGE_VAL, desc); /* clipped: an infinite ray becomes finite */
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, 5 - sqrt(0.75), 1e-10);
    model_free(&m);
}

/* Ray origin at 1e6 towards a unit sphere at the origin. */
static void ray_origin_at_1e6(void)
{
    static const double c[3] = {0, 0, 0};
    model_t m, sd;
    double o[3] = {1e6, 0.3, 0.2}, d[3] = {-1, 0, 0};
    double tr = (double)(1e6Q - sqrtq(1 - 0.3Q * 0.3Q - 0.2Q * 0.2Q));
    fr_trace_desc_t st = method(FR_METHOD_STEP, 1e-9), sp = method(FR_METHOD_SPHERE, 1e-9);
    fr_hit_t h;
    st.step = 0.01;
    make_sphere(&m, c, 1);
    make_sdf_sphere(&sd, c, 1);
    h = trace(&m, o, d, 1e6 - 3, 1e6, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, tr, 1e-8);
    h = trace(&m, o, d, 1e6 - 3, 1e6, method(FR_METHOD_INTERVAL, 1e-8));
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, tr, 2e-8);
    h = trace(&m, o, d, 1e6 - 3, 1e6, st);
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, tr, 2e-8);
    h = trace(&sd, o, d, 0, 2e6, sp);
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, tr, 1e-7);
    model_free(&m);
    model_free(&sd);
}

/* A shell 1e-8 thick (A minus a concentric B of radius 1 - 1e-8): the
   ray's roots 4 and 4 + 1e-8 are clustered within 1e-8. */
static void roots_clustered_within_1e_minus8(void)
{
    static const double c[3] = {0, 0, 0};
    fr_builder_t b;
    model_t m;
    fr_p3_t p;
    double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0};
    fr_hit_t h;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&m, &b, fr_subtract(&b, fr_sphere(&b, p, c, 1), fr_sphere(&b, p, c, 1 - 1e-8), 1.0));
    h = trace(&m, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, 4, 1e-14);
    h = trace(&m, o, d, 0, 10, method(FR_METHOD_INTERVAL, 1e-10));
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, 4, 1e-10);
    /* the exit of the shell, from inside it */
    o[0] = -1 + 5e-9;
    h = trace(&m, o, d, 0, 1, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(h.hit, 1); T_NEAR(h.t, 5e-9, 1e-15);
    model_free(&m);
}

/* Concentric spheres 1e-12 apart: their union is hit at the outer one; A
   minus the larger B is empty, so the analytic CSG method reports no hit. */
static void near_coincident_csg_surfaces(void)
{
    static const double c[3] = {0, 0, 0};
    fr_builder_t b;
    model_t u, e;
    fr_p3_t p;
    double o[3] = {-5, 0.25, 0}, d[3] = {1, 0, 0};
    fr_hit_t h;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&u, &b, fr_union(&b, fr_sphere(&b, p, c, 1), fr_sphere(&b, p, c, 1 + 1e-12), 1.0));
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&e, &b, fr_subtract(&b, fr_sphere(&b, p, c, 1), fr_sphere(&b, p, c, 1 + 1e-12), 1.0));
    h = trace(&u, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, sphere_entry(-5, 0.25, 1 + 1e-12), 1e-14);
    T_INT_EQ(trace(&e, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0)).hit, 0);
    /* R-functions with alpha = 0 (HyperFun's default) behave alike */
    model_free(&u);
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&u, &b, fr_union(&b, fr_sphere(&b, p, c, 1), fr_sphere(&b, p, c, 1 + 1e-12), 0.0));
    h = trace(&u, o, d, 0, 10, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, sphere_entry(-5, 0.25, 1 + 1e-12), 1e-14);
    model_free(&u);
    model_free(&e);
}

/* f = 1 - x + 0 sqrt(x): NaN for x < 0, the plane x = 1 beyond. No method
   may report a hit in the NaN half-space. */
static void nan_region_never_hit(void)
{
    fr_builder_t b;
    model_t m;
    fr_p3_t p;
    double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0};
    fr_method_t ms[4] = {FR_METHOD_STEP, FR_METHOD_INTERVAL, FR_METHOD_SPHERE, FR_METHOD_AUTO};
    int k;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&m, &b, fr_add(&b, fr_sub(&b, fr_const(&b, 1), p.x),
                                fr_mul(&b, fr_const(&b, 0), fr_unary(&b, FR_OP_SQRT, p.x))));
    for (k = 0; k < 4; k++) {
        fr_trace_desc_t ds = method(ms[k], 1e-10);
        fr_hit_t h;
        ds.step = 0.1;
        ds.lipschitz = 1;
        h = trace(&m, o, d, 0, 10, ds);
        if (h.hit) T_NEAR(h.t, 6, 1e-9); /* only the plane */
        else T_CHECK(ms[k] == FR_METHOD_SPHERE); /* sphere tracing stops at NaN: a miss */
    }
    model_free(&m);
}

/* ---------------------------------------------------------------- methods against closed forms */

static void all_methods_on_random_sphere_rays(void)
{
    static const double c[3] = {0.1, -0.2, 0.3};
    model_t m, sd;
    t_rng_t g = {99};
    long n = t_count(400), i;
    fr_refine_t refs[4] = {FR_REFINE_ILLINOIS, FR_REFINE_NEWTON, FR_REFINE_BRENT, FR_REFINE_BISECT};
    make_sphere(&m, c, 1.5);
    make_sdf_sphere(&sd, c, 1.5);
    for (i = 0; i < n; i++) {
        double o[3], d[3], oc[3], b2, cc, disc, tr;
        __float128 qb, qc, qd;
        int k;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -6, 6); d[k] = t_rng_range(&g, -1, 1); }
        for (k = 0; k < 3; k++) d[k] = (c[k] + t_rng_range(&g, -1, 1)) - o[k]; /* roughly at the sphere */
        for (k = 0; k < 3; k++) oc[k] = o[k] - c[k];
        qb = 0; qc = 0; qd = 0;
        for (k = 0; k < 3; k++) {
            qb += (__float128)oc[k] * d[k];
            qc += (__float128)oc[k] * oc[k];
            qd += (__float128)d[k] * d[k];
        }
        qc -= 2.25Q;
        b2 = (double)qb; cc = (double)qc;
        disc = (double)(qb * qb - qd * qc);
        if (disc <= 1e-6 || cc <= 0) { (void)b2; continue; } /* grazing or origin inside: other tests */
        tr = (double)((-qb - sqrtq(qb * qb - qd * qc)) / qd);
        {
            fr_hit_t a = trace(&m, o, d, 0, 4, method(FR_METHOD_ANALYTIC, 0));
            fr_hit_t iv = trace(&m, o, d, 0, 4, method(FR_METHOD_INTERVAL, 1e-10));
            fr_hit_t ip, sp;
            fr_trace_desc_t pd = method(FR_METHOD_INTERVAL, 1e-10);
            pd.plain_intervals = 1;
            ip = trace(&m, o, d, 0, 4, pd);
            T_INT_EQ(a.hit, 1); T_NEAR(a.t, tr, 1e-13);
            T_INT_EQ(iv.hit, 1); T_NEAR(iv.t, tr, 1e-10);
            T_INT_EQ(ip.hit, 1); T_NEAR(ip.t, tr, 1e-10);
            for (k = 0; k < 4; k++) {
                fr_trace_desc_t sd2 = method(FR_METHOD_STEP, 1e-11);
                fr_hit_t s;
                sd2.step = 0.01;
                sd2.refine = refs[k];
                s = trace(&m, o, d, 0, 4, sd2);
                T_INT_EQ(s.hit, 1); T_NEAR(s.t, tr, 2e-11);
            }
            sp = trace(&sd, o, d, 0, 4, method(FR_METHOD_SPHERE, 1e-10));
            T_INT_EQ(sp.hit, 1); T_NEAR(sp.t, tr, 1e-9);
            /* AD normal against the closed form (p - c) / r */
            for (k = 0; k < 3; k++) T_NEAR(a.normal[k], (a.point[k] - c[k]) / 1.5, 1e-12);
        }
    }
    model_free(&m);
    model_free(&sd);
}

static void finite_difference_normals_match_ad(void)
{
    static const double c[3] = {0, 0, 0};
    model_t m;
    double o[3] = {-4, 0.7, -0.4}, d[3] = {1, 0, 0.05};
    fr_trace_desc_t ad = method(FR_METHOD_ANALYTIC, 0), fd = ad;
    fr_hit_t a, f;
    int k;
    make_torus_poly(&m, 2, 0.5);
    fd.normal = FR_NORMAL_FD;
    a = trace(&m, o, d, 0, 10, ad);
    f = trace(&m, o, d, 0, 10, fd);
    T_INT_EQ(a.hit, 1);
    for (k = 0; k < 3; k++) T_NEAR(f.normal[k], a.normal[k], 1e-8);
    T_NEAR(a.normal[0] * a.normal[0] + a.normal[1] * a.normal[1] + a.normal[2] * a.normal[2], 1, 1e-15);
    (void)c;
    model_free(&m);
}

/* Keinert's over-relaxation must not skip a surface and must not cost more
   evaluations than plain sphere tracing on a grazing-ish ray. */
static void sphere_tracing_over_relaxation(void)
{
    static const double c[3] = {0, 0, 0};
    model_t m;
    double o[3] = {-20, 0.9, 0}, d[3] = {1, 0, 0};
    fr_trace_desc_t plain = method(FR_METHOD_SPHERE, 1e-10), relax = plain;
    fr_hit_t a, b;
    make_sdf_sphere(&m, c, 1);
    plain.over_relax = 1;
    relax.over_relax = 1.9;
    a = trace(&m, o, d, 0, 40, plain);
    b = trace(&m, o, d, 0, 40, relax);
    T_INT_EQ(a.hit, 1); T_INT_EQ(b.hit, 1);
    T_NEAR(a.t, sphere_entry(-20, 0.9, 1), 1e-9);
    T_NEAR(b.t, sphere_entry(-20, 0.9, 1), 1e-9);
    T_LE(b.evals, a.evals + 4); /* at worst a couple of fallback steps */
    model_free(&m);
}

/* Over-relaxed sphere tracing (the default omega 1.6) of exact SDFs where
   the overshoot lands inside at a depth equal to its own radius: a plane
   hit head-on (x >= 1), also tilted by 1e-8, and a ball traced from its
   centre. The spheres still overlapped, so the step stood and the march
   went on through the inside (every such ray missed); the sign change now
   sends it back to the safe step. Hits within 2 t_err + 1e-12 of exact. */
static void sphere_tracing_relaxed_step_into_the_solid(void)
{
    static const double c[3] = {0, 0, 0};
    model_t plane, ball;
    fr_builder_t b;
    t_rng_t g = {1600};
    long n = t_count(2000), i;
    fr_trace_desc_t D = method(FR_METHOD_SPHERE, 0);
    fr_hit_t h;
    fr_builder_init(&b, NULL);
    model_finish(&plane, &b, fr_from_sdf(&b, fr_sub(&b, fr_const(&b, 1.0), fr_coords(&b).x), 1.0));
    for (i = 0; i < n; i++) {
        double o[3], d[3] = {1, i % 2 ? 1e-8 : 0, 0}, want;
        o[0] = 1 - t_rng_range(&g, 0.01, 10), o[1] = t_rng_range(&g, -1, 1), o[2] = t_rng_range(&g, -1, 1);
        want = 1 - o[0];
        h = trace(&plane, o, d, 0, 100, D);
        if (!T_INT_EQ(h.hit, 1)) break;
        T_LE(fabs(h.t - want), 2 * h.t_err + 1e-12);
    }
    make_sdf_sphere(&ball, c, 1);
    {
        double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
        h = trace(&ball, o, d, 0, 10, D);
        T_INT_EQ(h.hit, 1);
        T_LE(fabs(h.t - 1), 2 * h.t_err + 1e-12);
    }
    model_free(&plane);
    model_free(&ball);
}

/* A root exactly at t1 on the plain (unprepared) analytic CSG path: two
   concentric spheres' union entered at t = 4 = t1. The leaf's last gap
   [4, 4] has its midpoint on the root, where the sign is 0, so the root
   was never a crossing (the prepared path and a single sphere found it). */
static void analytic_csg_root_at_t1(void)
{
    static const double c[3] = {0, 0, 0}, box[6] = {-2, -2, -2, 2, 2, 2};
    model_t m;
    fr_builder_t b;
    fr_prepared_t pr;
    fr_p3_t p;
    double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0}, t1s[3] = {4, 4.0000000000000009, 4.5};
    int k, pp;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&m, &b, fr_union(&b, fr_sphere(&b, p, c, 1), fr_sphere(&b, p, c, 0.5), 0));
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    for (k = 0; k < 3; k++)
        for (pp = 0; pp < 2; pp++) {
            fr_trace_desc_t D = method(FR_METHOD_ANALYTIC, 0);
            fr_hit_t h;
            if (pp) D.prepared = &pr;
            h = trace(&m, o, d, 0, t1s[k], D);
            T_INT_EQ(h.hit, 1);
            T_NEAR(h.t, 4, 1e-12);
        }
    fr_prepared_free(&pr);
    model_free(&m);
}

/* The interval method's centred form over a constant op whose argument
   was rounded: 1e16 sin(13 y) - x^2 on a ray with d_y = 0, where 13 Y is
   2 pi + 2e-16 exactly but 2 pi rounded in double, so the plain
   polynomial is negative everywhere while the surface is crossed at t =
   3.59 and 6.41. The magnitude run took |sin(13 Y)| = 2.4e-16 as the
   coefficient's error scale, and INTERVAL proved a miss, plain and
   prepared (found by review, 2026-12-06). The method must not miss nor
   answer past the first root (a touch before it, from the wide interval
   enclosures, is allowed). */
static void centred_form_over_a_rounded_constant_op(void)
{
    static const double box[6] = {-10, -1, -1, 10, 1, 1};
    const double Y = 0x1.eeebf2ca2ada8p-2;
    double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0}, first;
    model_t m;
    fr_builder_t b;
    fr_prepared_t pr;
    fr_p3_t p;
    fr_node_t s;
    int pp;
    o[1] = Y;
    first = (double)(5 - sqrtq((__float128)1e16 * sinq(13 * (__float128)Y)));
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    s = fr_unary(&b, FR_OP_SIN, fr_mul(&b, fr_const(&b, 13.0), p.y));
    model_finish(&m, &b, fr_sub(&b, fr_mul(&b, fr_const(&b, 1e16), s), fr_mul(&b, p.x, p.x)));
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    for (pp = 0; pp < 2; pp++) {
        fr_trace_desc_t D = method(FR_METHOD_INTERVAL, 0);
        fr_hit_t h;
        if (pp) D.prepared = &pr;
        h = trace(&m, o, d, 0, 10, D);
        if (!T_INT_EQ(h.hit, 1)) continue;
        T_LE(h.t - h.t_err, first);
    }
    fr_prepared_free(&pr);
    model_free(&m);
}

/* A Taylor term that underflows to exactly 0: an ellipsoid with half-axes
   1e162 (f = 1 - |p|^2 / a^2, between -3 and 1 along the ray) has the t^2
   coefficient -1/a^2, about -1e-324, which rounded to 0; the polynomial
   read as the constant 1 and ANALYTIC, AUTO and INTERVAL answered no hit,
   plain and prepared (found by review, 2026-12-06). Now the degree drop
   is seen: ANALYTIC says FR_ERR_NOT_POLYNOMIAL, the others find the
   entry. At 1e150 nothing underflows and every method answers as before. */
static void taylor_term_underflow_is_not_a_miss(void)
{
    static const double c[3] = {0, 0, 0}, as[2] = {1e162, 1e150};
    static const fr_method_t ms[3] = {FR_METHOD_AUTO, FR_METHOD_INTERVAL, FR_METHOD_ANALYTIC};
    int i, k, pp;
    for (i = 0; i < 2; i++) {
        double a = as[i], o[3] = {0, 0, 0}, d[3] = {1, 0, 0}, box[6], want = a * sqrt(0.91);
        model_t m;
        fr_builder_t b;
        fr_prepared_t pr;
        o[1] = 0.3 * a;
        for (k = 0; k < 3; k++) box[k] = -2 * a, box[k + 3] = 2 * a;
        fr_builder_init(&b, NULL);
        model_finish(&m, &b, fr_ellipsoid(&b, fr_coords(&b), c, a, a, a));
        T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
        for (k = 0; k < 3; k++)
            for (pp = 0; pp < 2; pp++) {
                fr_trace_desc_t D = method(ms[k], 0);
                void *scratch;
                fr_hit_t h;
                fr_result_t r;
                if (pp) D.prepared = &pr;
                scratch = malloc(fr_trace_scratch_size(&m.tape, &D));
                r = fr_trace(&m.tape, o, d, 0, 3 * a, &D, scratch, &h);
                free(scratch);
                if (ms[k] == FR_METHOD_ANALYTIC && i == 0 && r == FR_ERR_NOT_POLYNOMIAL) continue;
                if (!T_INT_EQ(r, FR_OK) || !T_INT_EQ(h.hit, 1)) {
                    fprintf(stderr, "    a %g method %d prepared %d: %s hit %d\n", a, (int)ms[k], pp, fr_result_string(r), h.hit);
                    continue;
                }
                T_LE(fabs(h.t - want), h.t_err + 1e-9 * want);
            }
        fr_prepared_free(&pr);
        model_free(&m);
    }
}

/* Directions 1e-170 and 1e-300 long at the unit ball: |d|^2 underflows to
   exactly 0, so the ray polynomial lost its t^2 term unseen (degree 1:
   ANALYTIC answered x = 2.6, INTERVAL x = 1.67, both outside the ball);
   and 1e+150 long, where it overflows. Every method traces the same line
   with d scaled by a power of 2 (exact), so each finds t = 4 / |d| to its
   tolerance, SPHERE too (its steps need |d|). */
static void extreme_direction_lengths_every_method(void)
{
    static const double c[3] = {0, 0, 0};
    static const double lens[4] = {1e-170, 1e-300, 1e150, 1e-5};
    static const fr_method_t ms[4] = {FR_METHOD_ANALYTIC, FR_METHOD_INTERVAL, FR_METHOD_STEP, FR_METHOD_AUTO};
    model_t poly, sdf;
    int i, k;
    make_sphere(&poly, c, 1);
    make_sdf_sphere(&sdf, c, 1);
    for (i = 0; i < 4; i++) {
        double o[3] = {-5, 0, 0}, d[3] = {lens[i], 0, 0}, want = 4 / lens[i];
        for (k = 0; k < 5; k++) {
            fr_trace_desc_t D = method(k < 4 ? ms[k] : FR_METHOD_SPHERE, 0);
            fr_hit_t h = trace(k < 4 ? &poly : &sdf, o, d, 0, 8 / lens[i], D);
            if (!T_INT_EQ(h.hit, 1)) continue;
            T_LE(fabs(h.t - want), 2 * h.t_err + 1e-12 * want);
            T_LE(fabs(o[0] + h.t * d[0] + 1), 1e-8); /* the point is the ball's entry x = -1 */
        }
    }
    model_free(&poly);
    model_free(&sdf);
}

/* t in [-inf, inf] with bounds (which make the segment finite): the
   default tolerance 1e-9 (1 + |t0|) was infinite there, and INTERVAL
   reported t = 10 with t_err 4.2 where the first root is 8.7 (STEP was off
   by 0.01). The torus-and-ball from x = -10 along +x meets the torus's
   outer wall at x = -1.3. */
static void infinite_segment_with_bounds(void)
{
    static const double box[6] = {-1.5, -1.5, -0.5, 1.5, 1.5, 0.5};
    static const fr_method_t ms[2] = {FR_METHOD_INTERVAL, FR_METHOD_STEP};
    model_t m;
    double o[3] = {-10, 0, 0}, d[3] = {1, 0, 0};
    int k, e;
    make_torus_and_ball(&m);
    for (k = 0; k < 2; k++)
        for (e = 0; e < 2; e++) {
            fr_trace_desc_t D = method(ms[k], 0);
            fr_hit_t h;
            D.bounds = box;
            h = trace(&m, o, d, e ? -HUGE_VAL : 0, HUGE_VAL, D);
            if (!T_INT_EQ(h.hit, 1)) continue;
            T_LE(h.t_err, 1e-8);
            T_NEAR(h.t, 8.7, 1e-8);
        }
    model_free(&m);
}

static void auto_method_choices_and_stats(void)
{
    static const double c[3] = {0, 0, 0};
    model_t p, h;
    double o[3] = {-5, 0.1, 0.05}, d[3] = {1, 0, 0};
    fr_hit_t a, b;
    make_sphere(&p, c, 1);
    make_torus_hf(&h, 2, 0.5);
    a = trace(&p, o, d, 0, 10, method(FR_METHOD_AUTO, 0));
    b = trace(&h, o, d, 0, 10, method(FR_METHOD_AUTO, 0));
    T_INT_EQ(a.method, FR_METHOD_ANALYTIC);
    T_INT_EQ(b.method, FR_METHOD_INTERVAL);
    T_GT(a.evals, 0); T_GT(b.evals, 0); T_GT(b.iterations, 0);
    T_LE(b.t_err, 1e-8);
    model_free(&p);
    model_free(&h);
}

static double unit_sphere_sdf(const double p[3], void *user)
{
    (void)user;
    return sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0;
}

/* A black box with only a point function: AUTO falls back to Lipschitz
   stepping, sphere tracing works, normals fall back to differences. */
static void black_box_callback_model(void)
{
    fr_builder_t b;
    fr_callback_t cb;
    model_t m;
    double o[3] = {-4, 0.3, -0.2}, d[3] = {1, 0, 0};
    double tr = sphere_entry(-4, sqrt(0.13), 1);
    fr_hit_t a, s;
    int k;
    memset(&cb, 0, sizeof cb);
    cb.point = unit_sphere_sdf;
    fr_builder_init(&b, NULL);
    model_finish(&m, &b, fr_from_sdf(&b, fr_callback(&b, fr_coords(&b), &cb), 1.0));
    a = trace(&m, o, d, 0, 10, method(FR_METHOD_AUTO, 1e-10));
    s = trace(&m, o, d, 0, 10, method(FR_METHOD_SPHERE, 1e-10));
    T_INT_EQ(a.method, FR_METHOD_STEP);
    T_INT_EQ(a.hit, 1); T_NEAR(a.t, tr, 1e-10);
    T_INT_EQ(s.hit, 1); T_NEAR(s.t, tr, 1e-9);
    for (k = 0; k < 3; k++) T_NEAR(a.normal[k], a.point[k], 1e-6); /* unit sphere: n = p */
    model_free(&m);
}

/* A method stopped by desc.max_iters with part of the segment undecided
   does not report a miss (found by review, 2026-12-06): a ray grazing the
   quartic torus (R 1, r 0.3) 1e-15 below the top of its tube, where g is
   as flat as (t - 3)^4 over 1e-3, kept INTERVAL's 10^5 bisections busy,
   and it answered FR_OK with no hit, plain and prepared: a false proof.
   Now such a ray gets the hit or FR_ERR_ITERATIONS, whose hit->t +-
   t_err holds ANALYTIC's root; with a cap of 2000 it is the error, and
   STEP and SPHERE with a cap of 5 give it too (their range holds the
   root at t = 4.2 of the unit ball, and starts where they stopped). */
static void iteration_cap_is_not_a_miss(void)
{
    static const double box[6] = {-2, -2, -2, 2, 2, 2};
    double o[3] = {-3, 1, 0x1.3333333333321p-2}, d[3] = {1, 0, 0}, ob[3] = {-5, 0.6, 0};
    model_t m, ball;
    fr_builder_t b;
    fr_callback_t cb;
    fr_prepared_t pr;
    fr_hit_t ref, h;
    int k, pp;
    make_torus_poly(&m, 1, 0.3);
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    ref = trace(&m, o, d, 0, 6, method(FR_METHOD_ANALYTIC, 0));
    T_INT_EQ(ref.hit, 1);
    for (k = 0; k < 2; k++)
        for (pp = 0; pp < 2; pp++) {
            fr_trace_desc_t D = method(FR_METHOD_INTERVAL, 7e-12);
            fr_result_t r;
            if (pp) D.prepared = &pr;
            D.max_iters = k ? 2000 : 0;
            r = fr_trace(&m.tape, o, d, 0, 6, &D, m.scratch, &h);
            if (r == FR_OK && !k) { /* the default cap may be enough on another machine's code */
                T_INT_EQ(h.hit, 1);
                T_NEAR(h.t, ref.t, 1e-3);
                continue;
            }
            T_INT_EQ(r, FR_ERR_ITERATIONS);
            T_INT_EQ(h.hit, 0);
            T_LE(h.t - h.t_err, ref.t);
            T_GE(h.t + h.t_err, ref.t);
            T_LE(h.t + h.t_err, 6);
            T_GE(h.iterations, k ? 2000 : 100000);
        }
    fr_prepared_free(&pr);
    model_free(&m);
    memset(&cb, 0, sizeof cb);
    cb.point = unit_sphere_sdf;
    fr_builder_init(&b, NULL);
    model_finish(&ball, &b, fr_from_sdf(&b, fr_callback(&b, fr_coords(&b), &cb), 1.0));
    for (k = 0; k < 2; k++) {
        fr_trace_desc_t D = method(k ? FR_METHOD_SPHERE : FR_METHOD_STEP, 1e-10);
        fr_result_t r;
        D.step = k ? 0 : 0.01;
        D.over_relax = 1;
        D.max_iters = 5;
        r = fr_trace(&ball.tape, ob, d, 0, 10, &D, ball.scratch, &h);
        T_INT_EQ(r, FR_ERR_ITERATIONS);
        T_INT_EQ(h.hit, 0);
        T_LE(h.t - h.t_err, 4.2);
        T_GE(h.t + h.t_err, 4.2);
        T_GE(h.t - h.t_err, k ? 4.0 : 0.04); /* STEP checked 5 steps of 0.01; SPHERE's first step is 4.04 */
        D.max_iters = 0;
        h = trace(&ball, ob, d, 0, 10, D);
        T_INT_EQ(h.hit, 1);
        T_NEAR(h.t, 4.2, 1e-9);
    }
    model_free(&ball);
    T_CHECK(strcmp(fr_result_string(FR_ERR_ITERATIONS), "unknown result") != 0);
}

/* Sphere tracing with over-relaxation near t1 (found by review,
   2026-12-06): the relaxed step from t = 0 toward the plane z = 0 at t = 1
   lands at 1.6; for t1 in [1, 1.6) it left the loop unchecked and the
   ray missed. A relaxed step past t1 now falls back to the safe step. */
static void sphere_tracing_relaxed_step_past_t1(void)
{
    static const double t1s[5] = {1.0, 1.2, 1.5, 1.599, 3};
    double o[3] = {0, 0, 1}, d[3] = {0, 0, -1};
    fr_builder_t b;
    model_t m;
    int k;
    fr_builder_init(&b, NULL);
    model_finish(&m, &b, fr_from_sdf(&b, fr_coords(&b).z, 1.0));
    for (k = 0; k < 5; k++) {
        fr_hit_t h = trace(&m, o, d, 0, t1s[k], method(FR_METHOD_SPHERE, 1e-9));
        if (!T_INT_EQ(h.hit, 1)) continue;
        T_NEAR(h.t, 1, 1e-9);
    }
    model_free(&m);
}

/* Sphere tracing's stop within tol of the surface is a distance; on an
   oblique ray the root lay up to tol / sin(angle) farther than the
   reported t +- t_err (9.5 tol at 5.7 degrees; found by review,
   2026-12-06). The stop now looks ahead for the sign change and refines
   it. A plane z = 0 from (0, 0, 1) at 90 .. 0.5 degrees and a unit ball
   (exact SDFs) from x = -20 at impact parameters up to 0.999 (2.6
   degrees): the exact root (__float128 for the ball) within
   t_err + 4 ulp of t, t_err <= tol. A ray passing the ball 0.4 tol
   outside its surface crosses nowhere: a hit at its stop, t_err = tol, the
   point within tol of the surface (the documented grazing case). */
static void sphere_tracing_oblique_rays_bracket_the_root(void)
{
    static const double deg[6] = {90, 30, 5.7, 2, 1, 0.5}, c[3] = {0, 0, 0};
    const double tol = 1e-6;
    fr_builder_t b;
    model_t plane, ball;
    t_rng_t g = {5150};
    int k;
    long i, n = t_count(400);
    fr_trace_desc_t D = method(FR_METHOD_SPHERE, tol);
    fr_builder_init(&b, NULL);
    model_finish(&plane, &b, fr_from_sdf(&b, fr_coords(&b).z, 1.0));
    for (k = 0; k < 6; k++) {
        double a = deg[k] * 3.14159265358979323846 / 180, o[3] = {0, 0, 1}, d[3], want = 1 / sin(a);
        fr_hit_t h;
        d[0] = cos(a), d[1] = 0, d[2] = -sin(a);
        h = trace(&plane, o, d, 0, 1000, D);
        if (!T_INT_EQ(h.hit, 1)) continue;
        T_LE(fabs(h.t - want), h.t_err + 4 * 2.220446049250313e-16 * want);
        T_LE(h.t_err, tol);
    }
    make_sdf_sphere(&ball, c, 1);
    for (i = 0; i < n; i++) {
        double rho = t_rng_range(&g, 0, 0.999), o[3] = {-20, rho, 0}, d[3] = {1, 0, 0}, want = sphere_entry(-20, rho, 1);
        fr_hit_t h = trace(&ball, o, d, 0, 40, D);
        if (!T_INT_EQ(h.hit, 1)) break;
        T_LE(fabs(h.t - want), h.t_err + 4 * 2.220446049250313e-16 * 20);
        T_LE(h.t_err, tol);
    }
    {
        double o[3] = {-20, 1 + 0.4 * tol, 0}, d[3] = {1, 0, 0};
        fr_hit_t h = trace(&ball, o, d, 0, 40, D);
        if (T_INT_EQ(h.hit, 1)) {
            T_NEAR(h.t_err, tol, 0);
            T_LE(fabs(sqrt(h.point[0] * h.point[0] + h.point[1] * h.point[1] + h.point[2] * h.point[2]) - 1), tol);
        }
    }
    model_free(&plane);
    model_free(&ball);
}

static void invalid_arguments(void)
{
    static const double c[3] = {0, 0, 0};
    model_t m;
    double o[3] = {-5, 0, 0}, d[3] = {1, 0, 0}, z[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 0};
    fr_hit_t h;
    fr_trace_desc_t sp = method(FR_METHOD_SPHERE, 0), an = method(FR_METHOD_ANALYTIC, 0);
    make_sphere(&m, c, 1);
    T_INT_EQ(fr_trace(&m.tape, o, d, 1, 0, NULL, m.scratch, &h), FR_ERR_INVALID_ARG);
    T_INT_EQ(fr_trace(&m.tape, o, z, 0, 1, NULL, m.scratch, &h), FR_ERR_INVALID_ARG);
    T_INT_EQ(fr_trace(&m.tape, nan3, d, 0, 1, NULL, m.scratch, &h), FR_ERR_INVALID_ARG);
    T_INT_EQ(fr_trace(&m.tape, o, d, 0, 1, &sp, m.scratch, &h), FR_ERR_NO_LIPSCHITZ);
    {
        /* also for a ray that misses the bounds (it was a miss, FR_OK) */
        static const double far_box[6] = {10, 10, 10, 11, 11, 11};
        fr_trace_desc_t spb = sp;
        spb.bounds = far_box;
        T_INT_EQ(fr_trace(&m.tape, o, d, 0, 1, &spb, m.scratch, &h), FR_ERR_NO_LIPSCHITZ);
    }
    {
        /* an infinite segment: stepping needs a step length or a
           Lipschitz bound (the sphere's tape has none), intervals a finite
           segment; a finite one is traced */
        fr_trace_desc_t st = method(FR_METHOD_STEP, 0), iv = method(FR_METHOD_INTERVAL, 1e-10);
        T_INT_EQ(fr_trace(&m.tape, o, d, 0, HUGE_VAL, &st, m.scratch, &h), FR_ERR_INVALID_ARG);
        T_INT_EQ(fr_trace(&m.tape, o, d, 0, HUGE_VAL, &iv, m.scratch, &h), FR_ERR_INVALID_ARG);
        T_INT_EQ(fr_trace(&m.tape, o, d, 0, 10, &st, m.scratch, &h), FR_OK);
        T_CHECK(h.hit && fabs(h.t - 4) < 1e-6);
        st.step = 0.01;
        T_INT_EQ(fr_trace(&m.tape, o, d, 0, HUGE_VAL, &st, m.scratch, &h), FR_OK);
        T_CHECK(h.hit && fabs(h.t - 4) < 1e-6);
    }
    model_free(&m);
    make_torus_hf(&m, 2, 0.5);
    T_INT_EQ(fr_trace(&m.tape, o, d, 0, 10, &an, m.scratch, &h), FR_ERR_NOT_POLYNOMIAL);
    T_CHECK(strcmp(fr_result_string(FR_ERR_NOT_POLYNOMIAL), "unknown result") != 0);
    model_free(&m);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(ray_poly_matches_point_evaluation),
        T_CASE(ray_poly_reports_non_polynomial_tape),
        T_CASE(ray_poly_every_accepted_opcode),
        T_CASE(grazing_ray_sphere),
        T_CASE(grazing_ray_torus),
        T_CASE(ray_along_torus_axis_misses),
        T_CASE(ray_edge_on_torus),
        T_CASE(thin_feature_stepping_misses_interval_finds),
        T_CASE(ray_origin_at_1e6),
        T_CASE(roots_clustered_within_1e_minus8),
        T_CASE(near_coincident_csg_surfaces),
        T_CASE(nan_region_never_hit),
        T_CASE(all_methods_on_random_sphere_rays),
        T_CASE(finite_difference_normals_match_ad),
        T_CASE(sphere_tracing_over_relaxation),
        T_CASE(sphere_tracing_relaxed_step_into_the_solid),
        T_CASE(analytic_csg_root_at_t1),
        T_CASE(centred_form_over_a_rounded_constant_op),
        T_CASE(taylor_term_underflow_is_not_a_miss),
        T_CASE(extreme_direction_lengths_every_method),
        T_CASE(infinite_segment_with_bounds),
        T_CASE(auto_method_choices_and_stats),
        T_CASE(black_box_callback_model),
        T_CASE(iteration_cap_is_not_a_miss),
        T_CASE(sphere_tracing_relaxed_step_past_t1),
        T_CASE(sphere_tracing_oblique_rays_bracket_the_root),
        T_CASE(invalid_arguments),
        T_CASE(bound_box_holds_the_solid),
        T_CASE(tangle_interval_variants_agree),
        T_CASE(bounds_reject_without_evaluation),
        T_CASE(interval_newton_never_misses),
    };
    return T_RUN(argc, argv, cases);
}
