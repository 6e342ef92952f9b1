/* Prepared models of frep.h (fr_prepare, fr_trace_desc_t.prepared): the
   prepared CSG path (quadric leaves in monomial form, the boolean sign tree,
   leaf and node boxes) and the prepared Taylor programs (ANALYTIC and the
   INTERVAL centred form, with the monotone hand-over) against the
   unprepared fr_trace and against __float128 references: random rays,
   grazing and tangent rays, huge origins, thin features. */
#include "test.h"
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include <quadmath.h>
#include "test_frep_trace_models.h"
#include "test_frep_ref_models.h"

/* ---------------------------------------------------------------- the cup */

/* The example's cup (examples/models/cup.hf), through the C API with the
   parser's alpha = 0 R-functions: a spherical shell cut by a plane, on a
   cone stand cut by two planes. */
#define CUP_R1 1.0
#define CUP_R2 0.92
#define CUP_CONE 0.8
static const double cup_c[3] = {0, 0, 0.6}, cup_foot[3] = {0, 0, -0.2};

static void make_cup(model_t *m)
{
    fr_builder_t b;
    fr_p3_t p;
    fr_node_t shell, cut, stand;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    shell = fr_subtract(&b, fr_sphere(&b, p, cup_c, CUP_R1), fr_sphere(&b, p, cup_c, CUP_R2), 0.0);
    cut = fr_intersect(&b, shell, fr_sub(&b, fr_const(&b, 0.75), p.z), 0.0);
    stand = fr_intersect(&b, fr_cone(&b, p, 2, cup_foot, CUP_CONE), fr_add(&b, p.z, fr_const(&b, 0.55)), 0.0);
    stand = fr_intersect(&b, stand, fr_sub(&b, fr_const(&b, -0.25), p.z), 0.0);
    model_finish(m, &b, fr_union(&b, cut, stand, 0.0));
}

/* The cup's six leaves on o + t d in __float128: each a quadratic
   c0 + c1 t + c2 t^2 in t, from the closed forms (not from the tape). */
typedef struct qleaf_t { __float128 c[3]; } qleaf_t;
static void cup_leaves(const double o[3], const double d[3], qleaf_t L[6])
{
    __float128 oq[3], dq[3], r2[2] = {(__float128)CUP_R1 * CUP_R1, (__float128)CUP_R2 * CUP_R2}, k = 1 / ((__float128)CUP_CONE * CUP_CONE);
    int i, s;
    for (i = 0; i < 3; i++) { oq[i] = o[i]; dq[i] = d[i]; }
    for (s = 0; s < 2; s++) { /* r^2 - |p - c|^2 */
        __float128 a = 0, b = 0, c = 0;
        for (i = 0; i < 3; i++) {
            __float128 e = oq[i] - cup_c[i];
            a += dq[i] * dq[i]; b += 2 * e * dq[i]; c += e * e;
        }
        L[s].c[0] = r2[s] - c; L[s].c[1] = -b; L[s].c[2] = -a;
    }
    /* 0.75 - z, z + 0.55, -0.25 - z */
    L[2].c[0] = 0.75Q - oq[2]; L[2].c[1] = -dq[2]; L[2].c[2] = 0;
    L[4].c[0] = oq[2] + 0.55Q; L[4].c[1] = dq[2]; L[4].c[2] = 0;
    L[5].c[0] = -0.25Q - oq[2]; L[5].c[1] = -dq[2]; L[5].c[2] = 0;
    { /* the cone (z - fz)^2 - (x^2 + y^2) / r^2 */
        __float128 ez = oq[2] - cup_foot[2];
        L[3].c[0] = ez * ez - k * (oq[0] * oq[0] + oq[1] * oq[1]);
        L[3].c[1] = 2 * ez * dq[2] - 2 * k * (oq[0] * dq[0] + oq[1] * dq[1]);
        L[3].c[2] = dq[2] * dq[2] - k * (dq[0] * dq[0] + dq[1] * dq[1]);
    }
}

/* the cup's sign at t (test_frep_ref_models.h) */
static int cup_sign(const double o[3], const double d[3], __float128 t)
{
    __float128 a = cup_q(o, d, t);
    return a > 0 ? 1 : a < 0 ? -1 : 0;
}

/* The reference hit: the first leaf root in (t0, t1] where the cup's sign
   changes. *ambiguous is set when that is not decided far above rounding:
   two leaf roots within `sep` of each other near the hit or before it (a
   tangency, an edge), or a root within sep of t0 or t1. */
static int cup_reference(const double o[3], const double d[3], double t0, double t1, double sep, double *t_ref,
                         int *ambiguous)
{
    qleaf_t L[6];
    __float128 r[12];
    int n = 0, i, j;
    cup_leaves(o, d, L);
    for (i = 0; i < 6; i++) {
        __float128 a = L[i].c[2], b = L[i].c[1], c = L[i].c[0];
        if (a == 0) {
            if (b != 0) r[n++] = -c / b;
            continue;
        }
        {
            __float128 D = b * b - 4 * a * c, h;
            if (D < 0) continue;
            h = -(b + (b < 0 ? -sqrtq(D) : sqrtq(D))) / 2;
            r[n++] = h / a;
            if (h != 0) r[n++] = c / h;
        }
    }
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && r[j] < r[j - 1]; j--) { __float128 x = r[j]; r[j] = r[j - 1]; r[j - 1] = x; }
    *ambiguous = 0;
    for (i = 0; i < n; i++) {
        __float128 tc = r[i], dl = (__float128)sep * (1 + fabsq(tc));
        int near = (i > 0 && r[i] - r[i - 1] < dl) || (i + 1 < n && r[i + 1] - r[i] < dl);
        if (tc <= (__float128)t0 - dl || tc > (__float128)t1 + dl) continue;
        if (near || fabsq(tc - t0) < dl || fabsq(tc - t1) < dl) { *ambiguous = 1; return 0; }
        if (tc <= (__float128)t0) continue;
        if (cup_sign(o, d, tc - dl / 4) * cup_sign(o, d, tc + dl / 4) < 0) { *t_ref = (double)tc; return 1; }
    }
    return 0;
}

typedef struct cup_rig_t {
    model_t m;
    fr_prepared_t prep;
    double box[6];
    fr_trace_desc_t plain, fast;
} cup_rig_t;

static void cup_rig(cup_rig_t *c)
{
    static const double lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5};
    make_cup(&c->m);
    T_INT_EQ(fr_bound_box(&c->m.tape, lo, hi, 7, c->m.scratch, c->box, c->box + 3), FR_OK);
    T_INT_EQ(fr_prepare(&c->m.tape, c->box, &c->prep), FR_OK);
    c->plain = method(FR_METHOD_AUTO, 0);
    c->plain.bounds = c->box;
    c->fast = c->plain;
    c->fast.prepared = &c->prep;
}

static void cup_rig_free(cup_rig_t *c)
{
    fr_prepared_free(&c->prep);
    model_free(&c->m);
}

/* fr_prepare recognises the cup as CSG over six quadric leaves and five
   nodes, the tangle cube as a polynomial, HyperFun's torus (a square root)
   as neither; a prepared model of another tape is ignored. */
static void prepared_kinds_and_foreign_tapes(void)
{
    cup_rig_t c;
    model_t tc, to;
    fr_prepared_t pt, po;
    double o[3] = {3, -4, 2}, d[3] = {-3, 4, -1.9};
    fr_hit_t a, b;
    fr_trace_desc_t wrong;
    cup_rig(&c);
    T_INT_EQ(c.prep.kind, FR_PREPARED_CSG);
    T_INT_EQ(c.prep.n_leaves, 6);
    T_INT_EQ(c.prep.n_quadrics, 6);
    T_INT_EQ(c.prep.n_nodes, 5);
    make_tangle(&tc);
    T_INT_EQ(fr_prepare(&tc.tape, NULL, &pt), FR_OK);
    T_INT_EQ(pt.kind, FR_PREPARED_POLY);
    T_INT_EQ(pt.n_prog, tc.tape.n_code);
    make_torus_hf(&to, 2, 0.5);
    T_INT_EQ(fr_prepare(&to.tape, NULL, &po), FR_OK);
    T_INT_EQ(po.kind, FR_PREPARED_NONE);
    /* the tangle cube's prepared model handed to the cup: ignored */
    wrong = c.plain;
    wrong.prepared = &pt;
    a = trace(&c.m, o, d, 0, 10, c.plain);
    b = trace(&c.m, o, d, 0, 10, wrong);
    T_INT_EQ(a.hit, 1);
    T_INT_EQ(b.hit, a.hit);
    T_EQ(b.t, a.t);
    T_INT_EQ(fr_prepare(NULL, NULL, &pt), FR_ERR_INVALID_ARG);
    {
        double bad[6] = {1, 0, 0, 0, 1, 1};
        fr_prepared_t x;
        T_INT_EQ(fr_prepare(&c.m.tape, bad, &x), FR_ERR_INVALID_ARG);
    }
    fr_prepared_free(&pt);
    fr_prepared_free(&po);
    model_free(&tc);
    model_free(&to);
    cup_rig_free(&c);
}

/* Random rays at the cup (origins around it, aimed into its box): the
   prepared path agrees with the unprepared one and with the __float128
   reference -- same hits, t within 1e-12 relative, the same unit normal to
   1e-12 -- wherever the reference is not within 1e-9 of an edge or a
   tangency (those have their own tests below). */
static void prepared_csg_agrees_on_random_rays(void)
{
    cup_rig_t c;
    t_rng_t g = {31};
    long n = t_count(20000), i, hits = 0, amb = 0;
    int k;
    cup_rig(&c);
    for (i = 0; i < n; i++) {
        double o[3], d[3], tr = 0, lo = i % 3 == 0 ? 0.5 : 0.0;
        int am, ref;
        fr_hit_t a, b;
        for (k = 0; k < 3; k++) {
            double target = t_rng_range(&g, c.box[k], c.box[k + 3]);
            o[k] = t_rng_range(&g, -4, 4);
            d[k] = target - o[k];
        }
        a = trace(&c.m, o, d, lo, 2, c.plain);
        b = trace(&c.m, o, d, lo, 2, c.fast);
        ref = cup_reference(o, d, lo, 2, 1e-9, &tr, &am);
        if (am) { amb++; continue; }
        T_INT_EQ(b.hit, ref);
        T_INT_EQ(a.hit, ref);
        if (!(b.hit && a.hit && ref)) continue;
        hits++;
        T_NEAR(b.t, tr, 1e-12 * (1 + fabs(tr)));
        T_NEAR(b.t, a.t, 1e-12 * (1 + fabs(tr)));
        T_GE(b.normal[0] * a.normal[0] + b.normal[1] * a.normal[1] + b.normal[2] * a.normal[2], 1 - 1e-12);
        T_INT_EQ(b.method, FR_METHOD_ANALYTIC);
    }
    T_GT(hits, n / 4);
    T_LT(amb, n / 100);
    cup_rig_free(&c);
}

/* Grazing and tangent rays at the outer sphere, below the cut plane: at
   distance r (1 - 1e-9) from its centre the ray enters (its exit 9e-5
   later) and both paths give the __float128 entry to 3e-11 (the sign walk
   flips leaf signs at crossings instead of evaluating g 64 ulps either
   side of the root, where rounding hid this entry before); at r (1 + 1e-9)
   it misses the sphere. An exactly tangent ray (distance r up to the
   rounding of o) may be a touch or an entry at the tangent point. */
static void prepared_csg_grazing_and_tangent_rays(void)
{
    cup_rig_t c;
    t_rng_t g = {5};
    long n = t_count(2000), i, hits = 0;
    int k, s;
    cup_rig(&c);
    for (i = 0; i < n; i++) {
        /* a unit normal u in the lower half (below the cut), a tangent v */
        double u[3], v[3], o[3], d[3], len = 0, dot = 0;
        for (k = 0; k < 3; k++) { u[k] = t_rng_range(&g, -1, 1); v[k] = t_rng_range(&g, -1, 1); }
        u[2] = -fabs(u[2]) - 0.2;
        for (k = 0; k < 3; k++) len += u[k] * u[k];
        for (k = 0; k < 3; k++) u[k] /= sqrt(len);
        for (k = 0; k < 3; k++) dot += u[k] * v[k];
        len = 0;
        for (k = 0; k < 3; k++) { v[k] -= dot * u[k]; len += v[k] * v[k]; }
        for (k = 0; k < 3; k++) v[k] /= sqrt(len);
        for (s = -1; s <= 1; s++) {
            double rho = CUP_R1 * (1 + s * 1e-9), tr = 0;
            int am, ref;
            fr_hit_t a, b;
            for (k = 0; k < 3; k++) { o[k] = cup_c[k] + rho * u[k] - 3 * v[k]; d[k] = v[k]; }
            a = trace(&c.m, o, d, 0, 6, c.plain);
            b = trace(&c.m, o, d, 0, 6, c.fast);
            ref = cup_reference(o, d, 0, 6, 1e-12, &tr, &am);
            if (s == -1 && (am || !ref || fabs(tr - 3) > 0.01)) break; /* the stand or the cut plane in the way */
            if (s == 0) {
                /* a touch or an entry at the tangent point: nothing else
                   comes before it (the s = -1 ray entered there first) */
                if (b.hit) T_GE(b.t, 3 - 1e-7);
                if (a.hit) T_GE(a.t, 3 - 1e-7);
                if (a.hit && b.hit && a.t < 3.01 && b.t < 3.01) T_NEAR(b.t, a.t, 1e-7);
                continue;
            }
            T_INT_EQ(b.hit, a.hit);
            if (am) continue;
            T_INT_EQ(b.hit, ref);
            if (b.hit && ref) {
                /* a grazing entry is ill-conditioned: coefficient rounding of
                   ~1e-15 over g' = 9e-5 moves it by ~1e-11 */
                T_NEAR(b.t, tr, 3e-11);
                T_NEAR(a.t, tr, 3e-11);
                if (s < 0) { hits++; T_NEAR(tr, 3, 1e-4); }
                else T_GT(tr, 3.01); /* outside the silhouette: only a later part */
            }
        }
    }
    T_GT(hits, n / 4);
    cup_rig_free(&c);
}

/* Rays parallel to a generator of the double cone z^2 - x^2 - y^2 >= 0
   (fr_cone, r = 1) cut by the ball of radius 10: along (3, 4, 5), (5, 0,
   5), ... the ray's quadratic loses its t^2 term exactly and the leaf is
   linear, a case no other test reaches (fr__quadric_leaf's c2 = 0 branch);
   tilted by 1e-9 it is a quadratic whose leading term is nine orders
   below the others, its far root at ~1e9. Origins inside the ball and
   outside the cone, entering it inside the ball: the first hit is the
   cone's entry, from __float128. Prepared, unprepared ANALYTIC and
   INTERVAL agree with it. */
static __float128 cone_entry_q(const double o[3], const double d[3])
{
    __float128 a = (__float128)d[2] * d[2] - (__float128)d[0] * d[0] - (__float128)d[1] * d[1];
    __float128 b = 2 * ((__float128)o[2] * d[2] - (__float128)o[0] * d[0] - (__float128)o[1] * d[1]);
    __float128 c = (__float128)o[2] * o[2] - (__float128)o[0] * o[0] - (__float128)o[1] * o[1];
    __float128 disc, q;
    if (a == 0) return -c / b;
    disc = b * b - 4 * a * c;
    if (disc < 0) return -1;
    q = -(b + (b >= 0 ? sqrtq(disc) : -sqrtq(disc))) / 2; /* both roots without cancellation */
    {
        __float128 r1 = q / a, r2 = c / q, lo = r1 < r2 ? r1 : r2, hi = r1 < r2 ? r2 : r1;
        return lo >= 0 ? lo : hi;
    }
}
static void ray_parallel_to_cone_generator(void)
{
    static const double gen[8][3] = {{3, 4, 5}, {-3, 4, 5}, {4, -3, -5}, {5, 0, 5}, {0, -5, 5}, {-5, 0, -5}, {0.75, 1, 1.25}, {-4, -3, 5}};
    static const double c0[3] = {0, 0, 0}, box[6] = {-10, -10, -10, 10, 10, 10};
    t_rng_t g = {2026};
    fr_builder_t b;
    model_t m;
    fr_prepared_t pr;
    fr_trace_desc_t an = method(FR_METHOD_ANALYTIC, 0), pp, iv = method(FR_METHOD_INTERVAL, 1e-13);
    long n = t_count(4000), i, linear = 0, tilted = 0;
    fr_p3_t X;
    fr_builder_init(&b, NULL);
    X = fr_coords(&b);
    model_finish(&m, &b, fr_intersect(&b, fr_cone(&b, X, 2, c0, 1), fr_sphere(&b, X, c0, 10), 0));
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    T_INT_EQ((int)pr.kind, (int)FR_PREPARED_CSG);
    pp = an;
    pp.prepared = &pr;
    for (i = 0; i < n; i++) {
        double o[3], d[3], tilt = (i & 1) ? 1e-9 * t_rng_range(&g, -1, 1) : 0, tr, t1, p2 = 0;
        __float128 tq;
        fr_hit_t h[3];
        int k, j;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -5, 5); d[k] = gen[i % 8][k]; }
        d[0] += tilt * d[2];
        if (o[2] * o[2] - o[0] * o[0] - o[1] * o[1] >= 0 || o[0] * o[0] + o[1] * o[1] + o[2] * o[2] >= 25) continue;
        tq = cone_entry_q(o, d);
        tr = (double)tq;
        for (k = 0; k < 3; k++) p2 += (o[k] + tr * d[k]) * (o[k] + tr * d[k]);
        if (!(tr > 0) || p2 >= 99) continue; /* no entry, or not inside the ball */
        t1 = 2 * tr + 1;
        h[0] = trace(&m, o, d, 0, t1, pp);
        h[1] = trace(&m, o, d, 0, t1, an);
        h[2] = trace(&m, o, d, 0, t1, iv);
        for (j = 0; j < 3; j++) {
            if (!h[j].hit) { T_FAIL("ray %ld, method %d: no hit, want t = %.17g", i, j, tr); continue; }
            /* the root's condition: |f| rounding over the slope |b| */
            if (fabs(h[j].t - tr) > 1e-12 * (1 + tr)) T_FAIL("ray %ld, method %d: t = %.17g, want %.17g", i, j, h[j].t, tr);
            T_CHECK(1);
        }
        if (tilt == 0) linear++;
        else tilted++;
    }
    T_GT(linear, n / 20);
    T_GT(tilted, n / 20);
    fr_prepared_free(&pr);
    model_free(&m);
}

/* Direction vectors 1e-80 and 1e80 long (2^-266, 2^266: exact scalings,
   so the ray is the same line and t scales exactly) at a quartic torus
   united with a sphere, plain and prepared: the t^4 coefficient of the
   ray polynomial would be ~1e-320 or ~1e320. Overflow took the ray to the
   interval method; underflow kept the analytic path, whose roots from
   subnormal coefficients were off by 1e-5 relative while t_err claimed
   3e-14 (then, until 2026-12-05, ANALYTIC reported FR_ERR_NOT_POLYNOMIAL).
   fr_trace now traces such directions rescaled by a power of 2 (exact),
   so every answer (AUTO and ANALYTIC, plain and prepared) lies within its
   own t_err (plus 1e-12) of the unit-direction analytic root, scaled. */
static void tiny_and_huge_direction_vectors(void)
{
    static const double box[6] = {-3, -3, -3, 3, 3, 3};
    t_rng_t g = {266};
    model_t m;
    fr_prepared_t pr;
    long n = t_count(300), i, checked = 0;
    make_torus_and_ball(&m);
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    for (i = 0; i < n; i++) {
        double o[3], d[3], ds[3], ref;
        fr_trace_desc_t an = method(FR_METHOD_ANALYTIC, 0), au = method(FR_METHOD_AUTO, 0);
        fr_hit_t h0;
        int k, sc, pp;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -2.5, 2.5); d[k] = t_rng_range(&g, -1, 1) - 0.5 * o[k]; }
        h0 = trace(&m, o, d, 0, 4, an);
        if (!h0.hit) continue;
        ref = h0.t;
        for (sc = 0; sc < 2; sc++) {
            double f = ldexp(1.0, sc ? 266 : -266);
            for (k = 0; k < 3; k++) ds[k] = d[k] * f;
            for (pp = 0; pp < 4; pp++) {
                fr_trace_desc_t D = pp < 2 ? au : an;
                fr_hit_t h;
                if (pp % 2) D.prepared = &pr;
                h = trace(&m, o, ds, 0, 4 / f, D);
                if (!h.hit) { T_FAIL("ray %ld scale 2^%d%s: no hit, want t = %.17g", i, sc ? 266 : -266, pp % 2 ? " prepared" : "", ref); continue; }
                if (!(fabs(h.t * f - ref) <= h.t_err * f + 1e-12 * (1 + ref)))
                    T_FAIL("ray %ld scale 2^%d%s: t = %.17g, want %.17g, t_err %.3g", i, sc ? 266 : -266, pp % 2 ? " prepared" : "", h.t * f, ref, h.t_err * f);
                checked++;
            }
        }
    }
    T_GT(checked, n);
    fr_prepared_free(&pr);
    model_free(&m);
}

/* Rays through the cup's rim edge (the cut plane z = 0.75 meets the shell),
   and rays inside the cut plane: both paths report the same hit, within
   1e-12 of each other. */
static void prepared_csg_edges_and_planes(void)
{
    cup_rig_t c;
    t_rng_t g = {77};
    long n = t_count(2000), i;
    int k;
    cup_rig(&c);
    for (i = 0; i < n; i++) {
        double ang = t_rng_range(&g, 0, 6.283185307179586), rr = i % 2 ? CUP_R1 : CUP_R2, zc = 0.75 - cup_c[2];
        double p[3], o[3], d[3], rad = sqrt(rr * rr - zc * zc);
        fr_hit_t a, b;
        p[0] = rad * cos(ang); p[1] = rad * sin(ang); p[2] = 0.75; /* a rim point */
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -4, 4); d[k] = p[k] - o[k]; }
        if (i % 4 == 3) { o[2] = 0.75; d[2] = 0; } /* in the plane itself */
        a = trace(&c.m, o, d, 0, 3, c.plain);
        b = trace(&c.m, o, d, 0, 3, c.fast);
        T_INT_EQ(b.hit, a.hit);
        if (a.hit && b.hit) T_NEAR(b.t, a.t, 1e-12 * (1 + fabs(a.t)));
    }
    cup_rig_free(&c);
}

/* Origins at 1e6 (the leaves' forms are about their own centres, rays
   expanded about their point nearest each centre): within 1e-10 of the
   reference entry as the unprepared path; at 1e200 the leaf polynomials
   overflow and fr_trace falls back to the unprepared path. */
static void prepared_csg_huge_origins(void)
{
    cup_rig_t c;
    double o[3] = {1e6, -2e5, 3e5}, d[3], tr = 0;
    fr_hit_t a, b;
    int k, am;
    cup_rig(&c);
    for (k = 0; k < 3; k++) d[k] = (k == 2 ? 0.1 : 0.0) - o[k];
    a = trace(&c.m, o, d, 0, 2, c.plain);
    b = trace(&c.m, o, d, 0, 2, c.fast);
    T_INT_EQ(cup_reference(o, d, 0, 2, 1e-12, &tr, &am), 1);
    T_INT_EQ(am, 0);
    T_INT_EQ(a.hit, 1);
    T_INT_EQ(b.hit, 1);
    T_NEAR(b.t, tr, 1e-10);
    T_NEAR(a.t, tr, 1e-10);
    for (k = 0; k < 3; k++) { o[k] = k == 0 ? 1e200 : 0.1; d[k] = k == 0 ? -1 : 0; }
    a = trace(&c.m, o, d, 0, 2e200, c.plain);
    b = trace(&c.m, o, d, 0, 2e200, c.fast);
    T_INT_EQ(b.hit, a.hit);
    if (a.hit) T_EQ(b.t, a.t);
    cup_rig_free(&c);
}

/* Shadow rays (any hit, no normal) agree on whether the segment meets the
   cup; FD normals through a prepared model are the tape's. */
static void prepared_csg_shadow_rays_and_fd_normals(void)
{
    cup_rig_t c;
    t_rng_t g = {13};
    long n = t_count(4000), i;
    int k;
    fr_trace_desc_t sp, sf, fd;
    cup_rig(&c);
    sp = c.plain; sp.any_hit = 1; sp.normal = FR_NORMAL_NONE;
    sf = sp; sf.prepared = &c.prep;
    fd = c.fast; fd.normal = FR_NORMAL_FD;
    for (i = 0; i < n; i++) {
        double o[3], d[3], tr = 0;
        int am, ref;
        fr_hit_t a, b;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -2, 2); d[k] = t_rng_range(&g, -2, 2) - o[k]; }
        ref = cup_reference(o, d, 0, 1, 1e-9, &tr, &am);
        if (am) continue;
        a = trace(&c.m, o, d, 0, 1, sp);
        b = trace(&c.m, o, d, 0, 1, sf);
        T_INT_EQ(b.hit, ref);
        T_INT_EQ(a.hit, ref);
        if (i % 8 == 0 && ref) {
            fr_hit_t e = trace(&c.m, o, d, 0, 1, fd), f = trace(&c.m, o, d, 0, 1, c.fast);
            T_GE(e.normal[0] * f.normal[0] + e.normal[1] * f.normal[1] + e.normal[2] * f.normal[2], 1 - 1e-8);
        }
    }
    cup_rig_free(&c);
}

/* A CSG of 25 leaves of every kind the prepared path knows: spheres,
   rotated ellipsoids (quadrics with off-diagonal terms), finite cylinders
   on oblique axes (each cut by two planes), a quartic torus (a Taylor
   program leaf), minus a sphere: small leaf and node boxes, so rays meet
   the culling of both. Random rays: the prepared path gives the plain
   path's hits, t within 1e-10 (1 + |t|) and normals within 1e-9, but for
   at most 0.1% of rays (grazing an edge where the two paths' roundings
   may decide differently). */
/* One ray through the plain tape (pl) and the prepared model (fa): 0 when
   they disagree on the hit or on t beyond 1e-10 relative, else 1 (and
   *hits counts a shared hit, whose normals must agree to 1e-9). */
static int prepared_ray_agrees(model_t *m, fr_trace_desc_t pl, fr_trace_desc_t fa, const double o[3], const double d[3],
                               long *hits)
{
    fr_hit_t a = trace(m, o, d, 0, 2, pl), h = trace(m, o, d, 0, 2, fa);
    if (a.hit != h.hit || (a.hit && fabs(a.t - h.t) > 1e-10 * (1 + fabs(a.t)))) return 0;
    if (!a.hit) return 1;
    ++*hits;
    T_GE(a.normal[0] * h.normal[0] + a.normal[1] * h.normal[1] + a.normal[2] * h.normal[2], 1 - 1e-9);
    return 1;
}

static void prepared_csg_many_leaves_agree(void)
{
    fr_builder_t b;
    fr_p3_t p;
    fr_node_t u = FR_NODE_NONE;
    model_t m;
    fr_prepared_t pr;
    t_rng_t g = {4242};
    static const double lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5};
    double box[6];
    long n = t_count(6000), i, hits = 0, off = 0;
    int k, j;
    fr_trace_desc_t pl = method(FR_METHOD_AUTO, 0), fa;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    for (j = 0; j < 24; j++) {
        double c[3];
        fr_node_t f;
        for (k = 0; k < 3; k++) c[k] = t_rng_range(&g, -1.5, 1.5);
        if (j % 3 == 0) f = fr_sphere(&b, p, c, t_rng_range(&g, 0.1, 0.35));
        else if (j % 3 == 1) {
            double a = t_rng_range(&g, 0, 3.14159), m9[9], t3[3];
            /* p' = R (p - c): a rotation about z then about x */
            double ca = cos(a), sa = sin(a), cb = cos(0.7 * a), sb = sin(0.7 * a);
            static const double zero[3] = {0, 0, 0};
            m9[0] = ca; m9[1] = sa; m9[2] = 0;
            m9[3] = -sa * cb; m9[4] = ca * cb; m9[5] = sb;
            m9[6] = sa * sb; m9[7] = -ca * sb; m9[8] = cb;
            for (k = 0; k < 3; k++) t3[k] = -(m9[3 * k] * c[0] + m9[3 * k + 1] * c[1] + m9[3 * k + 2] * c[2]);
            f = fr_ellipsoid(&b, fr_affine(&b, p, m9, t3), zero, 0.35, 0.2, 0.1);
        } else {
            double dir[3], nn = 0, d0;
            for (k = 0; k < 3; k++) { dir[k] = t_rng_range(&g, -1, 1); nn += dir[k] * dir[k]; }
            for (k = 0; k < 3; k++) dir[k] /= sqrt(nn);
            d0 = dir[0] * c[0] + dir[1] * c[1] + dir[2] * c[2];
            f = fr_cylinder_axis(&b, p, c, dir, 0.12);
            /* between the planes dir.p = d0 - 0.3 and d0 + 0.3 */
            f = fr_intersect(&b, f, fr_halfspace(&b, p, dir, d0 + 0.3), 1.0);
            {
                double nd[3] = {-dir[0], -dir[1], -dir[2]};
                f = fr_intersect(&b, f, fr_halfspace(&b, p, nd, -(d0 - 0.3)), 1.0);
            }
        }
        u = j == 0 ? f : fr_union(&b, u, f, j % 2 ? 1.0 : 0.0);
    }
    /* a quartic torus about (0, 0, 1.8) */
    u = fr_union(&b, u, torus_poly_node(&b, p.x, p.y, fr_sub(&b, p.z, fr_const(&b, 1.8)), 0.5, 0.15), 1.0);
    {
        static const double hc[3] = {0.3, -0.2, 0.1};
        u = fr_subtract(&b, u, fr_sphere(&b, p, hc, 0.5), 0.0);
    }
    model_finish(&m, &b, u);
    T_INT_EQ(fr_bound_box(&m.tape, lo, hi, 7, m.scratch, box, box + 3), FR_OK);
    T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK);
    T_INT_EQ(pr.kind, FR_PREPARED_CSG);
    T_INT_EQ(pr.n_leaves, 8 + 8 + 8 * 3 + 1 + 1);
    T_INT_EQ(pr.n_quadrics, pr.n_leaves - 1); /* all but the torus */
    { /* small boxes: culling does happen (the header's private layout) */
        fr__leaf_t *L;
        fr__csg_node_t *N;
        unsigned int q, bl = 0, bn = 0, full = 0;
        fr__prep_layout(pr.n_leaves, pr.n_nodes, pr.n_prog, &L, &N, NULL, pr.mem);
        for (q = 0; q < pr.n_leaves; q++) { bl += (unsigned int)L[q].boxed; full += L[q].quadric && L[q].shape == FR__LEAF_FULL; }
        for (q = 0; q < pr.n_nodes; q++) bn += (unsigned int)N[q].boxed;
        T_GE(bl, 16);
        T_GE(bn, 8);
        T_GE(full, 8);
    }
    pl.bounds = box;
    fa = pl;
    fa.prepared = &pr;
    for (i = 0; i < n; i++) {
        double o[3], d[3];
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -4, 4); d[k] = t_rng_range(&g, box[k], box[k + 3]) - o[k]; }
        off += !prepared_ray_agrees(&m, pl, fa, o, d, &hits);
    }
    T_GT(hits, n / 5);
    T_LE(off, n / 1000);
    fr_prepared_free(&pr);
    model_free(&m);
}

/* CSG leaves written with the operations the quadric form takes that no
   other test uses (gcov): a sphere divided by a constant, a plane from a
   zeroth power, a first power and the power of a constant; rays at random
   and along y and z, parallel to the plane leaf, which is then constant
   along the ray. Prepared against plain. */
static void prepared_csg_leaf_forms(void)
{
    fr_builder_t b;
    fr_p3_t p;
    model_t m;
    fr_prepared_t pr;
    t_rng_t g = {99};
    static const double c0[3] = {0.1, 0.2, -0.1}, lo[3] = {-3, -3, -3}, hi[3] = {3, 3, 3};
    double box[6];
    long n = t_count(3000), i, hits = 0, off = 0;
    int k;
    fr_node_t sph, plane, slab, f;
    fr_trace_desc_t pl = method(FR_METHOD_AUTO, 0), fa;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    sph = fr_div(&b, fr_sphere(&b, p, c0, 1.0), fr_const(&b, 2.5));
    plane = fr_sub(&b, fr_powi(&b, p.y, 0), fr_add(&b, p.x, fr_const(&b, 0.5))); /* x < 0.5 */
    slab = fr_sub(&b, fr_powi(&b, fr_const(&b, 0.9), 3), fr_unary(&b, FR_OP_SQR, fr_powi(&b, p.z, 1))); /* |z| < 0.854 */
    f = fr_union(&b, fr_intersect(&b, sph, plane, 1.0), fr_intersect(&b, slab, fr_sphere(&b, p, c0, 1.4), 0.0), 1.0);
    model_finish(&m, &b, f);
    T_INT_EQ(fr_bound_box(&m.tape, lo, hi, 7, m.scratch, box, box + 3), FR_OK);
    if (!T_INT_EQ(fr_prepare(&m.tape, box, &pr), FR_OK)) { model_free(&m); return; }
    T_INT_EQ(pr.kind, FR_PREPARED_CSG);
    T_INT_EQ(pr.n_quadrics, pr.n_leaves);
    pl.bounds = box;
    fa = pl;
    fa.prepared = &pr;
    for (i = 0; i < n; i++) {
        double o[3], d[3];
        for (k = 0; k < 3; k++) o[k] = t_rng_range(&g, -2.5, 2.5), d[k] = t_rng_range(&g, -1, 1) - o[k];
        if (i % 3) { /* along y or z: parallel to the plane leaf */
            int ax = i % 3;
            for (k = 0; k < 3; k++) d[k] = k == ax ? -o[k] : 0;
        }
        off += !prepared_ray_agrees(&m, pl, fa, o, d, &hits);
    }
    T_GT(hits, n / 5);
    T_INT_EQ(off, 0);
    fr_prepared_free(&pr);
    model_free(&m);
}

/* ---------------------------------------------------------------- polynomial tapes */

/* g(t) of the quartic torus in __float128 (the tangle cube's: test_frep_ref_models.h) */
static __float128 torus_q(const double o[3], const double d[3], __float128 t, double R, double r)
{
    __float128 x = (__float128)o[0] + t * d[0], y = (__float128)o[1] + t * d[1], z = (__float128)o[2] + t * d[2];
    __float128 rho2 = x * x + y * y, s = rho2 + z * z + (__float128)R * R - (__float128)r * r;
    return 4 * (__float128)R * R * rho2 - s * s;
}

/* Random rays at the tangle cube and the quartic torus: the prepared
   Taylor program gives the unprepared hits, ANALYTIC within 1e-12 (and
   the program's AD normals within 1e-12 of the tape's) and
   INTERVAL (monotone hand-over, footprint and any-hit too) within its
   tolerance; every INTERVAL hit brackets a sign change of g in
   __float128 within tol + 1e-12, and no miss leaves a sign change that
   ANALYTIC finds. */
static void prepared_poly_agrees_on_random_rays(void)
{
    model_t tc, to;
    fr_prepared_t ptc, pto;
    t_rng_t g = {17};
    long n = t_count(3000), i, hits = 0;
    int k;
    double tol = 1e-10;
    make_tangle(&tc);
    make_torus_poly(&to, 2, 0.5);
    T_INT_EQ(fr_prepare(&tc.tape, NULL, &ptc), FR_OK);
    T_INT_EQ(fr_prepare(&to.tape, NULL, &pto), FR_OK);
    for (i = 0; i < n; i++) {
        model_t *m = i % 2 ? &to : &tc;
        fr_prepared_t *pp = i % 2 ? &pto : &ptc;
        fr_trace_desc_t an = method(FR_METHOD_ANALYTIC, 0), iv = method(FR_METHOD_INTERVAL, tol), anp, ivp;
        double o[3], d[3];
        fr_hit_t a, ap, b, bp;
        for (k = 0; k < 3; k++) { o[k] = t_rng_range(&g, -8, 8); d[k] = t_rng_range(&g, -2.5, 2.5) - o[k]; }
        if (i % 5 == 1) iv.footprint = 1e-3;
        if (i % 5 == 2) iv.any_hit = 1;
        anp = an; anp.prepared = pp;
        ivp = iv; ivp.prepared = pp;
        a = trace(m, o, d, 0, 2, an);
        ap = trace(m, o, d, 0, 2, anp);
        b = trace(m, o, d, 0, 2, iv);
        bp = trace(m, o, d, 0, 2, ivp);
        T_INT_EQ(ap.hit, a.hit);
        if (a.hit && ap.hit) {
            T_NEAR(ap.t, a.t, 1e-12 * (1 + fabs(a.t)));
            /* the program's AD normal against the tape's */
            T_GE(ap.normal[0] * a.normal[0] + ap.normal[1] * a.normal[1] + ap.normal[2] * a.normal[2], 1 - 1e-12);
        }
        T_INT_EQ(bp.hit, b.hit);
        T_INT_EQ(bp.hit, a.hit);
        if (bp.hit) {
            double w = bp.t_err + 1e-12;
            __float128 lo = i % 2 ? torus_q(o, d, bp.t - w, 2, 0.5) : tangle_q(o, d, bp.t - w);
            __float128 hi = i % 2 ? torus_q(o, d, bp.t + w, 2, 0.5) : tangle_q(o, d, bp.t + w);
            hits++;
            T_CHECK(lo * hi <= 0);
            if (!iv.any_hit) T_NEAR(bp.t, a.t, iv.footprint > 0 ? 1e-3 * (1 + fabs(a.t)) : 2 * tol);
        }
    }
    T_GT(hits, n / 10);
    fr_prepared_free(&ptc);
    fr_prepared_free(&pto);
    model_free(&tc);
    model_free(&to);
}

/* The prepared program's own kernels and AD rules (fr__prog_normal), one
   model each: a product by a constant on either side, a general product,
   odd, even and fourth powers, a division by a constant, and operations
   on constants (sqrt, exp, atan, min), all on a closed degree-4 solid.
   Prepared and unprepared analytic traces agree on hit, t and normal
   (gcov: no test had taken MULK, the general product, POWI, DIV or the
   constant operations through the program). */
static fr_node_t prep_case(fr_builder_t *b, int which)
{
    fr_p3_t X = fr_coords(b);
    fr_node_t r2 = fr_add(b, fr_add(b, fr_unary(b, FR_OP_SQR, X.x), fr_unary(b, FR_OP_SQR, X.y)), fr_unary(b, FR_OP_SQR, X.z));
    fr_node_t q = fr_unary(b, FR_OP_SQR, r2); /* |p|^4: closes the solid */
    fr_node_t k = fr_const(b, 0.3), term;
    switch (which) {
    case 0: term = fr_mul(b, X.x, k); break;                                     /* by a constant, right */
    case 1: term = fr_mul(b, k, fr_sub(b, X.y, X.z)); break;                     /* by a constant, left */
    case 2: term = fr_mul(b, fr_add(b, X.x, k), fr_sub(b, X.y, k)); break;       /* two slots */
    case 3: term = fr_add(b, fr_powi(b, X.x, 3), fr_powi(b, X.y, 2)); break;
    case 4: term = fr_mul(b, k, fr_powi(b, fr_add(b, X.z, k), 4)); break;
    case 5: term = fr_div(b, fr_add(b, X.x, X.y), fr_const(b, 2.5)); break;
    default: { /* operations on constants, as a factor and as a term */
        fr_node_t c = fr_add(b, fr_add(b, fr_unary(b, FR_OP_SQRT, k), fr_unary(b, FR_OP_EXP, k)),
                             fr_add(b, fr_unary(b, FR_OP_ATAN, k), fr_binary(b, FR_OP_MIN, k, fr_const(b, 0.1))));
        term = fr_add(b, fr_mul(b, c, X.x), fr_sub(b, c, fr_const(b, 1.9)));
        break;
    }
    }
    return fr_sub(b, fr_sub(b, fr_const(b, 1.0), q), term);
}
static void prepared_poly_program_kernels(void)
{
    int which, k;
    long i, n = t_count(400);
    for (which = 0; which < 7; which++) {
        model_t m;
        fr_builder_t b;
        fr_prepared_t pp;
        t_rng_t g = {(unsigned long long)(31 + which)};
        long hits = 0;
        fr_builder_init(&b, NULL);
        model_finish(&m, &b, prep_case(&b, which));
        if (!T_INT_EQ(fr_prepare(&m.tape, NULL, &pp), FR_OK)) { model_free(&m); continue; }
        T_INT_EQ(pp.kind, FR_PREPARED_POLY);
        for (i = 0; i < n; i++) {
            fr_trace_desc_t an = method(FR_METHOD_ANALYTIC, 0), anp;
            double o[3], d[3];
            fr_hit_t a, ap;
            for (k = 0; k < 3; k++) o[k] = t_rng_range(&g, -4, 4), d[k] = t_rng_range(&g, -0.8, 0.8) - o[k];
            anp = an;
            anp.prepared = &pp;
            a = trace(&m, o, d, 0, 2, an);
            ap = trace(&m, o, d, 0, 2, anp);
            T_INT_EQ(ap.hit, a.hit);
            if (!(a.hit && ap.hit)) continue;
            hits++;
            T_NEAR(ap.t, a.t, 1e-12 * (1 + fabs(a.t)));
            T_GE(ap.normal[0] * a.normal[0] + ap.normal[1] * a.normal[1] + ap.normal[2] * a.normal[2], 1 - 1e-12);
        }
        T_GT(hits, n / 4);
        fr_prepared_free(&pp);
        model_free(&m);
    }
}

/* A slab 2e-5 thick, far thinner than any step: interval bisection through
   the prepared program still finds it (the monotone hand-over never drops
   a segment that holds a root), at the closed-form entry within tol. */
static void prepared_interval_thin_feature(void)
{
    fr_builder_t b;
    fr_p3_t p;
    model_t slab;
    fr_prepared_t pr;
    double o[3] = {-1, 0.1, 0.2}, d[3] = {1, 0, 0}, w = 1e-5, xc = 0.3037;
    fr_trace_desc_t iv = method(FR_METHOD_INTERVAL, 1e-12);
    fr_hit_t h;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(&slab, &b, fr_sub(&b, fr_const(&b, w * w), fr_unary(&b, FR_OP_SQR, fr_sub(&b, p.x, fr_const(&b, xc)))));
    T_INT_EQ(fr_prepare(&slab.tape, NULL, &pr), FR_OK);
    T_INT_EQ(pr.kind, FR_PREPARED_POLY);
    iv.prepared = &pr;
    h = trace(&slab, o, d, 0, 2, iv);
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, 1 + xc - w, 1e-11);
    iv.footprint = 1e-2; /* a footprint far wider than the slab */
    h = trace(&slab, o, d, 0, 2, iv);
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, 1 + xc - w, 1e-11);
    fr_prepared_free(&pr);
    model_free(&slab);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(prepared_kinds_and_foreign_tapes),
        T_CASE(prepared_csg_agrees_on_random_rays),
        T_CASE(prepared_csg_grazing_and_tangent_rays),
        T_CASE(prepared_csg_edges_and_planes),
        T_CASE(prepared_csg_huge_origins), T_CASE(ray_parallel_to_cone_generator),
        T_CASE(tiny_and_huge_direction_vectors),
        T_CASE(prepared_csg_shadow_rays_and_fd_normals),
        T_CASE(prepared_csg_many_leaves_agree),
        T_CASE(prepared_poly_agrees_on_random_rays),
        T_CASE(prepared_poly_program_kernels),
        T_CASE(prepared_csg_leaf_forms),
        T_CASE(prepared_interval_thin_feature),
    };
    return T_RUN(argc, argv, cases);
}
