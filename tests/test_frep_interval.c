/* frep.h interval, affine and pruning: enclosures contain sampled values on
   10^6 random boxes over the whole operation set (zero violations), are
   tight for tiny boxes, and pruned tapes agree with the full tape. */
#include "interval.h"
#include "frep.h"
#include "test.h"
#include <float.h>

static double sq(double x) { return x * x; }

/* ------------------------------------------------------------ models */
typedef fr_node_t (*build_fn)(fr_builder_t *b, fr_p3_t X);

static fr_tape_t compile(build_fn f)
{
    fr_builder_t b;
    fr_tape_t t;
    fr_diag_t d;
    fr_builder_init(&b, NULL);
    fr_node_t n = f(&b, fr_coords(&b));
    if (fr_builder_finish(&b, n, NULL, 0, &t, &d) != FR_OK) T_FAIL("build failed: %s", d.message);
    fr_builder_free(&b);
    return t;
}

static const double C0[3] = {0.1, -0.2, 0.3}, C1[3] = {-0.4, 0.3, 0.0}, C2[3] = {0.5, 0.5, -0.5};

/* every elementary opcode */
static fr_node_t m_elementary(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t t1 = fr_unary(b, FR_OP_EXP, fr_unary(b, FR_OP_NEG, fr_unary(b, FR_OP_SQR, X.x)));
    fr_node_t t2 = fr_unary(b, FR_OP_LOG, fr_add(b, fr_const(b, 2), fr_unary(b, FR_OP_SIN, X.y)));
    fr_node_t t3 = fr_powi(b, fr_unary(b, FR_OP_COS, fr_mul(b, X.z, fr_const(b, 3))), 3);
    fr_node_t t4 = fr_unary(b, FR_OP_ATAN, fr_mul(b, X.x, X.y));
    fr_node_t t5 = fr_powc(b, fr_unary(b, FR_OP_ABS, X.z), 1.5);
    fr_node_t t6 = fr_div(b, X.x, fr_add(b, fr_const(b, 2), fr_unary(b, FR_OP_SQR, X.y)));
    fr_node_t t7 = fr_sub(b, fr_binary(b, FR_OP_MAX, X.x, X.y), fr_binary(b, FR_OP_MIN, X.y, X.z));
    fr_node_t t8 = fr_powi(b, fr_add(b, fr_const(b, 2.5), X.x), -2);
    fr_node_t t9 = fr_unary(b, FR_OP_SQRT, fr_add(b, fr_const(b, 3), X.z));
    return fr_add(b, fr_add(b, fr_add(b, t1, t2), fr_add(b, t3, t4)),
                  fr_add(b, fr_add(b, t5, t6), fr_add(b, t9, fr_add(b, t7, t8))));
}
/* primitives combined with every R-function, blend and smooth operation */
static fr_node_t m_csg(fr_builder_t *b, fr_p3_t X)
{
    double v[3] = {-0.5, -0.4, -0.3}, s[3] = {1, 0.8, 0.6}, abc[3] = {0.7, 0.5, 0.6}, n[3] = {0.2, 1, -0.3};
    double ax[3] = {1, 1, 0};
    fr_node_t a = fr_sphere(b, X, C0, 0.8), e = fr_ellipsoid(b, X, C1, 0.5, 0.9, 0.7);
    fr_node_t k = fr_block(b, X, v, s, 0.4), c = fr_cylinder(b, X, 0, C2, 0.3);
    fr_node_t co = fr_cone(b, X, 1, C1, 0.6), to = fr_torus(b, X, 2, C0, 0.6, 0.2);
    fr_node_t h = fr_halfspace(b, X, n, 0.3), se = fr_superellipsoid(b, X, C2, abc, 0.5, 0.8);
    fr_node_t ec = fr_ell_cylinder(b, X, 2, C0, 0.4, 0.3), ca = fr_cylinder_axis(b, X, C1, ax, 0.3);
    fr_node_t u = fr_union(b, a, e, 0.0), i = fr_intersect(b, k, c, 0.5), d = fr_subtract(b, co, to, 1.0);
    fr_node_t bu = fr_blend_union(b, u, i, 0.3, 0.5, 0.7), bi = fr_blend_intersect(b, d, h, 0.2, 1, 1);
    fr_node_t sm = fr_smooth_union(b, bu, se, 0.3), si = fr_smooth_intersect(b, bi, fr_negate(b, ec), 0.2);
    fr_node_t mo = fr_morph(b, sm, si, 0.35);
    return fr_union(b, fr_offset(b, mo, 0.05), fr_intersect(b, ca, fr_union(b, u, d, 1.0), 0.0), 0.7);
}
/* skeletal, convolution, noises and every space map */
static fr_node_t m_skeletal_maps(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t el[3] = {{{0, 0, 0}, {0, 0, 0}, 3, 1}, {{0.4, 0.1, 0}, {-0.3, 0.5, 0.2}, 2, 0.8},
                           {{0.2, -0.5, 0.3}, {0.2, -0.5, 0.3}, 4, 1.2}};
    fr_skeleton_t ms[2] = {{{0, 0, 0}, {0.5, 0, 0}, 0.7, 1}, {{-0.2, 0.3, 0.1}, {-0.2, 0.3, 0.1}, 0.9, 1}};
    fr_skeleton_t cv[1] = {{{-0.5, 0, 0.1}, {0.5, 0.2, -0.1}, 2, 0.8}};
    double off[3] = {0.3, 0.1, 0.7}, sh[3] = {0.1, -0.1, 0.2}, sc[3] = {1.2, 0.8, 1.1}, c[3] = {0, 0.1, 0};
    double M[9] = {0.9, 0.1, 0, -0.1, 1.0, 0.2, 0, -0.2, 1.1}, T[3] = {0.05, 0, -0.05};
    fr_p3_t P = fr_twist(b, fr_translate(b, X, sh), 2, -1, 1, 0.3, 1.7);
    P = fr_taper(b, fr_rotate(b, P, 0, 0.4), 1, -1, 1, 0.7, 1.3);
    P = fr_bend(b, fr_stretch(b, fr_scale(b, P, sc), c, sc), 2, 0.5);
    P = fr_affine(b, fr_rotate(b, fr_twist(b, P, 0, -1, 1, -0.5, 0.5), 1, -0.3), M, T);
    fr_node_t bl = fr_skeletal(b, P, FR_KERNEL_BLOBBY, el, 3, 0.4);
    fr_node_t mb = fr_skeletal(b, X, FR_KERNEL_METABALL, ms, 2, 0.3);
    fr_node_t so = fr_skeletal(b, fr_taper(b, X, 2, -0.5, 0.5, 1.2, 0.6), FR_KERNEL_SOFT, ms, 2, 0.2);
    fr_node_t co = fr_convolution(b, X, cv, 1, 0.3);
    fr_node_t no = fr_noise(b, X, 0.15, 2.0, off), ng = fr_noise_gardner(b, X, 0.5, 1.3, 1.4);
    fr_node_t s1 = fr_union(b, fr_union(b, bl, mb, 0.2), fr_union(b, so, co, 1.0), 0.0);
    return fr_add(b, fr_add(b, s1, no), fr_mul(b, ng, fr_const(b, 0.05)));
}
static iv_t cb_interval(const iv_t box[3], void *u)
{
    (void)u;
    return iv_sub(iv_point(0.5), iv_add(iv_add(iv_sqr(box[0]), iv_abs(box[1])), iv_sin(box[2])));
}
static double cb_point(const double p[3], void *u)
{
    (void)u;
    return 0.5 - (p[0] * p[0] + fabs(p[1]) + sin(p[2]));
}
static fr_node_t m_callback(fr_builder_t *b, fr_p3_t X)
{
    fr_callback_t cb = {cb_point, NULL, cb_interval, NULL};
    return fr_intersect(b, fr_callback(b, fr_rotate(b, X, 2, 0.3), &cb), fr_sphere(b, X, C0, 1.2), 0.0);
}

static const build_fn models[] = {m_elementary, m_csg, m_skeletal_maps, m_callback};
static const char *model_names[] = {"elementary", "csg", "skeletal+maps", "callback"};
#define N_MODELS 4

/* ------------------------------------------------------------ containment */

static double log_uniform(t_rng_t *r, double lo, double hi)
{
    return exp(t_rng_range(r, log(lo), log(hi)));
}
/* a value outside [lo, hi] is a violation; NaN values (outside the domain) are not checked */
static int outside(iv_t o, double v) { return !isnan(v) && !(o.lo <= v && v <= o.hi); }

static void interval_contains_samples_1e6_boxes(void)
{
    long per = t_count(1000000) / N_MODELS + 1, total = 0, viol = 0;
    for (int m = 0; m < N_MODELS; m++) {
        fr_tape_t t = compile(models[m]);
        iv_t *si = malloc(fr_scratch_size(&t, FR_EVAL_INTERVAL));
        double *sp = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
        t_rng_t r = {(unsigned long long)(100 + m)};
        for (long k = 0; k < per; k++) {
            iv_t box[3], o = iv_entire();
            for (int i = 0; i < 3; i++) {
                double c = t_rng_range(&r, -1.5, 1.5), h = log_uniform(&r, 1e-9, 1.0);
                box[i] = iv_make(c - h, c + h);
            }
            if (fr_eval_interval(&t, box, si, &o) != FR_OK) { viol++; continue; }
            for (int s = 0; s < 3; s++) {
                double p[3];
                for (int i = 0; i < 3; i++)
                    p[i] = s == 0 ? box[i].lo : s == 1 ? box[i].hi : t_rng_range(&r, box[i].lo, box[i].hi);
                double v = fr_eval(&t, p, sp);
                total++;
                if (outside(o, v) && viol++ < 5)
                    T_FAIL("%s: f(%.17g,%.17g,%.17g) = %.17g outside [%.17g, %.17g]", model_names[m], p[0], p[1], p[2],
                           v, o.lo, o.hi);
            }
        }
        free(si);
        free(sp);
        fr_tape_free(&t);
    }
    T_INT_EQ(viol, 0);
    T_GT(total, 0);
}

/* Issue 4: 10^6 random boxes (even k) and 10^6 ray segments (odd k), split
   over the models of the whole operation set; zero violations. */
static void affine_contains_samples_boxes_and_rays(void)
{
    long per = t_count(2000000) / N_MODELS + 1, viol = 0, ray_tighter = 0, rays = 0;
    for (int m = 0; m < N_MODELS; m++) {
        fr_tape_t t = compile(models[m]);
        iv_affine_t *sa = malloc(fr_scratch_size(&t, FR_EVAL_AFFINE));
        iv_t *si = malloc(fr_scratch_size(&t, FR_EVAL_INTERVAL));
        double *sp = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
        t_rng_t r = {(unsigned long long)(200 + m)};
        for (long k = 0; k < per; k++) {
            iv_affine_t in[3], o = iv_affine_const(0);
            double p[3], o3[3], d[3], t0 = 0, t1 = 0;
            int ray = k & 1;
            if (!ray) {
                for (int i = 0; i < 3; i++) {
                    double c = t_rng_range(&r, -1.5, 1.5), h = log_uniform(&r, 1e-9, 1.0);
                    in[i] = iv_affine_from_iv(iv_make(c - h, c + h));
                    o3[i] = c - h;
                    d[i] = 2 * h;
                }
            } else {
                /* x(t) = o + t d, t in [t0, t1]: every coordinate shares eps_t */
                t0 = t_rng_range(&r, 0, 2);
                t1 = t0 + log_uniform(&r, 1e-9, 1.0);
                iv_affine_t T = iv_affine_ray_param(t0, t1);
                for (int i = 0; i < 3; i++) {
                    o3[i] = t_rng_range(&r, -1.5, 1.5);
                    d[i] = t_rng_range(&r, -1, 1);
                    in[i] = iv_affine_add_d(iv_affine_mul_d(T, d[i]), o3[i]);
                }
            }
            if (fr_eval_affine(&t, in, sa, &o) != FR_OK) { viol++; continue; }
            iv_t oi = iv_from_affine(o);
            for (int s = 0; s < 3; s++) {
                double u = s == 0 ? 0 : s == 1 ? 1 : t_rng_unit(&r);
                for (int i = 0; i < 3; i++) {
                    if (ray) {
                        double tt = t0 + u * (t1 - t0);
                        p[i] = o3[i] + tt * d[i];
                    } else
                        p[i] = o3[i] + (s == 2 ? t_rng_unit(&r) : u) * d[i];
                }
                if (ray) {
                    /* the sampled point must lie in the affine inputs' ranges */
                    int in_range = 1;
                    for (int i = 0; i < 3; i++) in_range &= iv_contains(iv_from_affine(in[i]), p[i]);
                    if (!in_range) continue;
                }
                double v = fr_eval(&t, p, sp);
                if (outside(oi, v) && viol++ < 5)
                    T_FAIL("%s %s: f = %.17g outside [%.17g, %.17g]", model_names[m], ray ? "ray" : "box", v, oi.lo,
                           oi.hi);
            }
            if (ray) {
                iv_t box[3], ii;
                for (int i = 0; i < 3; i++) box[i] = iv_from_affine(in[i]);
                if (fr_eval_interval(&t, box, si, &ii) == FR_OK) {
                    rays++;
                    /* the interval shadow makes affine never wider, up to the
                       rounding of converting a range into a form */
                    ray_tighter += (iv_is_empty(oi) && iv_is_empty(ii)) ||
                                   iv_width(oi) <= iv_width(ii) + 1e-14 * (fabs(ii.lo) + fabs(ii.hi) + 1);
                }
            }
        }
        free(sa);
        free(si);
        free(sp);
        fr_tape_free(&t);
    }
    T_INT_EQ(viol, 0);
    T_INT_EQ(ray_tighter, rays);
}

/* a box of half-width 1e-9 must give an enclosure of width
   <= 1e-6 (|grad f| ~ 10, x 2e-9, plus rounding) */
static void interval_tight_on_tiny_boxes(void)
{
    for (int m = 0; m < N_MODELS; m++) {
        fr_tape_t t = compile(models[m]);
        iv_t *si = malloc(fr_scratch_size(&t, FR_EVAL_INTERVAL));
        t_rng_t r = {7};
        double worst = 0;
        for (long k = 0; k < t_count(2000); k++) {
            iv_t box[3], o = iv_entire();
            for (int i = 0; i < 3; i++) {
                double c = t_rng_range(&r, -1.5, 1.5);
                box[i] = iv_make(c - 1e-9, c + 1e-9);
            }
            fr_eval_interval(&t, box, si, &o);
            if (iv_width(o) > worst) worst = iv_width(o);
        }
        if (!(worst <= 1e-6)) T_FAIL("%s: width %.3g on a 2e-9 box", model_names[m], worst);
        T_LE(worst, 1e-6);
        free(si);
        fr_tape_free(&t);
    }
}

/* the noise enclosure: Lipschitz bound holds and stays within the amplitude bound */
static void noise_interval_is_rigorous_and_bounded(void)
{
    fr_builder_t b;
    fr_tape_t t;
    double off[3] = {0.1, 0.2, 0.3};
    fr_builder_init(&b, NULL);
    fr_node_t n = fr_noise(&b, fr_coords(&b), 1.5, 4.0, off);
    fr_builder_finish(&b, n, NULL, 0, &t, NULL);
    fr_builder_free(&b);
    iv_t si[8], o = iv_entire();
    double sp[8];
    t_rng_t r = {11};
    long viol = 0;
    for (long k = 0; k < t_count(200000); k++) {
        iv_t box[3];
        double h = log_uniform(&r, 1e-6, 3);
        for (int i = 0; i < 3; i++) {
            double c = t_rng_range(&r, -50, 50);
            box[i] = iv_make(c - h, c + h);
        }
        fr_eval_interval(&t, box, si, &o);
        if (o.lo < -3.0 || o.hi > 3.0) viol++; /* |n| <= 2 amp */
        for (int s = 0; s < 4; s++) {
            double p[3];
            for (int i = 0; i < 3; i++) p[i] = t_rng_range(&r, box[i].lo, box[i].hi);
            if (outside(o, fr_eval(&t, p, sp))) viol++;
        }
    }
    T_INT_EQ(viol, 0);
    fr_tape_free(&t);
}

/* ------------------------------------------------------------ pruning */

/* union (alpha = 1) of 8 x 8 x 2 = 128 spheres on a grid, minus a few
   alpha = 0 holes, blended with a block */
static fr_node_t m_big_csg(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t u = FR_NODE_NONE;
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++)
            for (int k = 0; k < 2; k++) {
                double c[3] = {-1.75 + 0.5 * i, -1.75 + 0.5 * j, -0.25 + 0.5 * k};
                fr_node_t s = fr_sphere(b, X, c, 0.3);
                u = u == FR_NODE_NONE ? s : fr_union(b, u, s, 1.0);
            }
    for (int i = 0; i < 4; i++) {
        double c[3] = {-1.5 + i, 0.2 * i, 0};
        u = fr_subtract(b, u, fr_cylinder(b, X, 2, c, 0.12), 0.0);
    }
    double v[3] = {-2, -2, -0.1}, s[3] = {4, 4, 0.2};
    return fr_union(b, u, fr_block(b, X, v, s, 1.0), 0.0);
}
/* alpha < 1 unions feeding a blend: not in sign context, must not be
   replaced by sign-only rules */
static fr_node_t m_blend_guard(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t a = fr_sphere(b, X, C0, 0.6), c = fr_sphere(b, X, C1, 0.5), d = fr_sphere(b, X, C2, 0.4);
    fr_node_t u = fr_union(b, a, c, 0.0);
    return fr_blend_union(b, u, d, 0.5, 0.4, 0.4);
}

static void check_pruning_mode(build_fn f, const char *name, double min_half, double max_half, int expect_shorter,
                               fr_prune_mode_t mode)
{
    fr_tape_t t = compile(f);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_PRUNE));
    fr_instr_t *buf = malloc(t.n_code * sizeof(fr_instr_t));
    double *sp = malloc(fr_scratch_size(&t, FR_EVAL_POINT)), *sq2 = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
    t_rng_t r = {21};
    long sign_bad = 0, value_bad = 0, shorter = 0, n = t_count(3000);
    for (long k = 0; k < n; k++) {
        iv_t box[3], range;
        fr_tape_t pr;
        double h = log_uniform(&r, min_half, max_half);
        for (int i = 0; i < 3; i++) {
            double c = t_rng_range(&r, -2, 2);
            box[i] = iv_make(c - h, c + h);
        }
        T_INT_EQ(fr_prune_ex(&t, box, mode, sc, buf, t.n_code, &pr, &range), FR_OK);
        shorter += pr.n_code < t.n_code;
        if (mode == FR_PRUNE_EXACT && (pr.flags & FR_TAPE_SIGN_ONLY)) value_bad++;
        for (int s = 0; s < 8; s++) {
            double p[3];
            for (int i = 0; i < 3; i++) p[i] = t_rng_range(&r, box[i].lo, box[i].hi);
            double full = fr_eval(&t, p, sp), part = fr_eval(&pr, p, sq2);
            int sf = (full > 0) - (full < 0), sp2 = (part > 0) - (part < 0);
            if (sf != sp2 && sign_bad++ < 3)
                T_FAIL("%s: sign differs at (%g,%g,%g): full %.17g pruned %.17g", name, p[0], p[1], p[2], full, part);
            if (!(pr.flags & FR_TAPE_SIGN_ONLY) && full != part && value_bad++ < 3)
                T_FAIL("%s: exact-pruned value differs: %.17g vs %.17g", name, full, part);
        }
    }
    T_INT_EQ(sign_bad, 0);
    T_INT_EQ(value_bad, 0);
    if (expect_shorter) T_GT((double)shorter, 0.5 * (double)n);
    free(sc);
    free(buf);
    free(sp);
    free(sq2);
    fr_tape_free(&t);
}
static void check_pruning(build_fn f, const char *name, double min_half, double max_half, int expect_shorter)
{
    check_pruning_mode(f, name, min_half, max_half, expect_shorter, FR_PRUNE_DEFAULT);
    check_pruning_mode(f, name, min_half, max_half, expect_shorter, FR_PRUNE_EXACT);
    check_pruning_mode(f, name, min_half, max_half, expect_shorter, FR_PRUNE_SIGN);
}
static void pruned_agrees_with_full_csg128(void) { check_pruning(m_big_csg, "csg128", 0.01, 0.3, 1); }
static void pruned_agrees_on_every_operation(void)
{
    check_pruning(m_csg, "csg", 1e-3, 1.0, 0);
    check_pruning(m_skeletal_maps, "skeletal", 1e-3, 1.0, 0);
    check_pruning(m_blend_guard, "blend-guard", 1e-3, 1.0, 0);
}
static void pruning_shrinks_small_boxes_of_csg128(void)
{
    /* a box around one sphere keeps about one sphere, the block and a hole */
    fr_tape_t t = compile(m_big_csg);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_PRUNE));
    fr_instr_t *buf = malloc(t.n_code * sizeof(fr_instr_t));
    iv_t box[3] = {{-1.80, -1.70}, {-1.80, -1.70}, {0.2, 0.3}}, range;
    fr_tape_t pr;
    T_INT_EQ(fr_prune(&t, box, sc, buf, t.n_code, &pr, &range), FR_OK);
    T_LT(pr.n_code * 10, t.n_code);
    /* sign mode drops the all-negative spheres too: even shorter, flagged */
    unsigned int exact_len = pr.n_code;
    T_INT_EQ(fr_prune_ex(&t, box, FR_PRUNE_SIGN, sc, buf, t.n_code, &pr, &range), FR_OK);
    T_LE(pr.n_code, exact_len);
    T_INT_EQ(fr_prune(&t, box, sc, buf, t.n_code - 1, &pr, &range), FR_ERR_BUFFER_TOO_SMALL);
    free(sc);
    free(buf);
    fr_tape_free(&t);
}

/* x^n, n = 2..8, in intervals and affine forms (frep.h's product fast path):
   encloses the exact range, computed in __float128 from the endpoints, and
   is no wider than it by more than 4n ulps of the magnitude; boxes straddle
   0, lie on either side, or are points. */
static void small_powers_enclose_tightly(void)
{
    t_rng_t g = {5};
    long n = t_count(20000), i;
    int e;
    for (e = 2; e <= 8; e++) {
        fr_builder_t b;
        fr_tape_t t;
        void *s;
        fr_builder_init(&b, NULL);
        if (fr_builder_finish(&b, fr_powi(&b, fr_coords(&b).x, e), NULL, 0, &t, NULL) != FR_OK) { T_FAIL("build"); return; }
        fr_builder_free(&b);
        s = malloc(fr_scratch_size(&t, FR_EVAL_AFFINE));
        for (i = 0; i < n; i++) {
            double lo = t_rng_range(&g, -3, 3), hi = i % 7 == 0 ? lo : lo + t_rng_range(&g, 0, 3);
            __float128 ql = 1, qh = 1, mig, mag, xl, xh;
            iv_t box[3], r;
            iv_affine_t P[3], ra;
            int k;
            double slack;
            if (e % 2 == 0) {
                mig = lo > 0 ? lo : hi < 0 ? -hi : 0;
                mag = -lo > hi ? -lo : hi;
                xl = mig; xh = mag;
            } else { xl = lo; xh = hi; }
            for (k = 0; k < e; k++) { ql *= xl; qh *= xh; }
            box[0] = iv_make(lo, hi); box[1] = box[2] = iv_point(0.0);
            T_INT_EQ(fr_eval_interval(&t, box, s, &r), FR_OK);
            slack = 4.0 * e * DBL_EPSILON * (fabs((double)ql) + fabs((double)qh)) + DBL_MIN;
            T_LE(r.lo, (double)ql); T_GE(r.hi, (double)qh);
            T_GE(r.lo, (double)ql - slack); T_LE(r.hi, (double)qh + slack);
            /* affine: must enclose the range too */
            for (k = 0; k < 3; k++) P[k] = iv_affine_from_iv(box[k]);
            T_INT_EQ(fr_eval_affine(&t, P, s, &ra), FR_OK);
            r = iv_from_affine(ra);
            T_LE(r.lo, (double)ql); T_GE(r.hi, (double)qh);
        }
        free(s);
        fr_tape_free(&t);
    }
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(interval_contains_samples_1e6_boxes), T_CASE(affine_contains_samples_boxes_and_rays),
        T_CASE(interval_tight_on_tiny_boxes),        T_CASE(noise_interval_is_rigorous_and_bounded),
        T_CASE(pruned_agrees_with_full_csg128),      T_CASE(pruned_agrees_on_every_operation),
        T_CASE(pruning_shrinks_small_boxes_of_csg128), T_CASE(small_powers_enclose_tightly),
    };
    (void)sq;
    return T_RUN(argc, argv, cases);
}
