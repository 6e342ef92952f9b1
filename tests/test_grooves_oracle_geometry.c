/* The grooves oracle (tests/grooves_oracle.h) against closed forms: before it
   judges grooves.h, its Embree geometry, ground holes, masking and shadow rays
   are checked on shapes whose visible and lit fractions follow from plane
   geometry by hand (V-grooves, vertical walls, a protruding ridge, wide
   footprints, the texture seam, perturbation, curves).

   Statistical bound: a footprint whose facets are straight strips has, with
   n×n stratified rays, a standard deviation of at most sqrt(B/(2 n^3)) per
   fraction (B region boundaries); n = 256, B <= 4 gives 4.9e-4, so the 3e-3
   tolerance below is over 6 sigma. Shadow boundaries are strips too. */
#include "test.h"
#include "grooves_oracle.h"

#define TOL 3e-3
static gro_device_t dev;

/* A straight groove along v through u = 0.5; B = (-1, 0), so section b maps
   to u = 0.5 - b. The viewer and the light lie in the u-w plane. */
static gro_groove_t straight(const double *sec, int nsec)
{
    static const double path[4] = {0.5, -0.5, 0.5, 1.5};
    gro_groove_t g;
    memset(&g, 0, sizeof g);
    g.kind = GRO_LINE; g.nctrl = 2; g.ctrl = path;
    g.nsec = nsec; g.sec = sec;
    return g;
}

/* direction in the u-w plane with horizontal drift per unit height tau (u/w) */
static void dir_uw(double tau, double *d)
{
    double l = sqrt(1 + tau * tau);
    d[0] = tau / l; d[1] = 0; d[2] = 1 / l;
}

static gro_result_t run(const gro_groove_t *g, int ng, double Fu, double Fv, double halfu, double tau,
                        const double *lights, int nl, int wrap, uint64_t seed)
{
    gro_query_t q;
    gro_result_t r;
    memset(&q, 0, sizeof q);
    q.grooves = g; q.ngrooves = ng; q.wrap = wrap;
    q.F[0] = Fu; q.F[1] = Fv;
    q.A1[0] = halfu; q.A2[1] = 0.25 * halfu; /* A2 along the groove: strips stay strips */
    dir_uw(tau, q.E);
    q.lights = lights; q.nlights = nl;
    q.n = 256; q.seed = seed;
    if (gro_query(&q, dev.dev, &r)) T_FAIL("gro_query failed");
    return r;
}

static double clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

/* V-groove mouth [-a, a] (u relative to the path), depth D. Facet 0 is the
   +u wall, facet 1 the -u wall. A ray through mouth point x drifts by -tau
   per unit depth; the shadow ray from a wall point drifts +lam per unit
   height. Returns the four fractions of a footprint [-a, a]. */
static void vgroove_left_wall(double a, double D, double tau, double lam, double *vis, double *lit)
{
    /* -u wall: u = -a + a s / D at depth s. Ray hits it for x in [-a, min(a, tau D)],
       at depth s = (x + a) / (tau + a/D). Its shadow ray leaves through the
       mouth while -a + s (a/D + lam) <= a. */
    double hi = fmin(a, tau * D), sstar;
    *vis = clamp(hi + a, 0, 2 * a) / (2 * a);
    if (*vis <= 0 || lam <= -a / D) { *lit = 0; return; }
    sstar = fmin(D, 2 * a / (a / D + lam));
    *lit = clamp(fmin(hi, sstar * (tau + a / D) - a) + a, 0, 2 * a) / (2 * a);
}

static void vgroove_fractions(double a, double D, double tau, double lam, double *v0, double *v1, double *l0,
                              double *l1)
{
    vgroove_left_wall(a, D, tau, lam, v1, l1);
    vgroove_left_wall(a, D, -tau, -lam, v0, l0); /* mirror u -> -u */
}

static void v_groove_all_view_angles(void)
{
    static const double sec[6] = {-0.01, 0, 0, -0.015, 0.01, 0};
    gro_groove_t g = straight(sec, 3);
    static const double degs[] = {0, 10, 25, 40, 55, 70, 80, 85};
    static const double light_deg[] = {-60, -20, 0, 30, 50, 75};
    int i, j, every = t_scale() < 1 ? 4 : 1;
    for (i = 0; i < 8; i += every)
        for (j = 0; j < 6; j += every > 1 ? 3 : 1) {
            double tau = tan(degs[i] * M_PI / 180) * (i % 2 ? -1 : 1), lam = tan(light_deg[j] * M_PI / 180);
            double L[3], v0, v1, l0, l1;
            gro_result_t r;
            dir_uw(lam, L);
            r = run(&g, 1, 0.5, 0.5, 0.01, tau, L, 1, 0, (uint64_t)(i * 10 + j));
            vgroove_fractions(0.01, 0.015, tau, lam, &v0, &v1, &l0, &l1);
            T_NEAR(gro_vis(&r, 0, 0), v0, TOL);
            T_NEAR(gro_vis(&r, 0, 1), v1, TOL);
            T_NEAR(gro_lit(&r, 0, 0, 0), l0, TOL);
            T_NEAR(gro_lit(&r, 0, 0, 1), l1, TOL);
            T_NEAR(r.ground_vis, 0, TOL); /* the footprint is exactly the mouth */
            T_EQ(r.miss, 0);
            gro_result_free(&r);
        }
}

/* Vertical walls (a stiff case for the core): rectangle 2a wide, D deep.
   Facets: 0 = wall at u = +a, 1 = floor, 2 = wall at u = -a. */
static void vertical_walls_masking_and_shadowing(void)
{
    const double a = 0.01, D = 0.012;
    static const double sec[8] = {-0.01, 0, -0.01, -0.012, 0.01, -0.012, 0.01, 0};
    gro_groove_t g = straight(sec, 4);
    static const double taus[] = {0.0, 0.4, 1.0, 1.9};
    static const double lams[] = {0.3, 1.2, 2.5};
    int i, j;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 3; j++) {
            double tau = taus[i], lam = lams[j], L[3];
            double floor_vis = clamp(2 * a - tau * D, 0, 2 * a) / (2 * a), wall_vis = 1 - floor_vis;
            /* floor hit u_f = x - tau D lit when -a <= u_f + lam D <= a */
            double xlo = fmax(tau * D - a, -a - lam * D + tau * D), xhi = fmin(a, a - lam * D + tau * D);
            double floor_lit = clamp(xhi - xlo, 0, 2 * a) / (2 * a);
            /* wall u = -a hit at depth s = (x + a)/tau, lit while s <= 2a/lam, x in [-a, tau D - a] */
            double wall_lit = tau > 0 ? clamp(fmin(tau * D - a, 2 * a / lam * tau - a) + a, 0, 2 * a) / (2 * a) : 0;
            gro_result_t r;
            dir_uw(lam, L);
            r = run(&g, 1, 0.5, 0.5, a, tau, L, 1, 0, 7 + (uint64_t)i);
            T_NEAR(gro_vis(&r, 0, 1), floor_vis, TOL);
            T_NEAR(gro_vis(&r, 0, 2), wall_vis, TOL);
            T_NEAR(gro_vis(&r, 0, 0), 0, TOL);
            T_NEAR(gro_lit(&r, 0, 0, 1), floor_lit, TOL);
            T_NEAR(gro_lit(&r, 0, 0, 2), wall_lit, TOL);
            gro_result_free(&r);
        }
}

/* A ridge (w > 0) of half-width a and height H inside a footprint [-4a, 4a]:
   seen from +u it hides ground behind it and casts a shadow toward +u when
   lit from -u. Facet 0 faces +u, facet 1 faces -u. */
static void protruding_ridge_masks_and_shadows_ground(void)
{
    const double a = 0.01, H = 0.008;
    static const double sec[6] = {-0.01, 0, 0, 0.008, 0.01, 0};
    gro_groove_t g = straight(sec, 3);
    static const double taus[] = {0.3, 1.0, 2.5};
    static const double lams[] = {-0.5, -2.0, 0.7};
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double tau = taus[i], lam = lams[j], L[3], span = 8 * a;
            double r0 = (a + tau * H) / span, r1 = fmax(0, a - tau * H) / span, rg = 1 - r0 - r1;
            /* ground lit: the only shadow falls on [a, |lam| H] for lam < 0 (light from -u),
               on [-lam H, -a] for lam > 0 where facet 0 may hide part of it */
            double shadow_lo, shadow_hi, gl;
            gro_result_t r;
            if (lam < 0) { shadow_lo = a; shadow_hi = fmax(a, -lam * H); }
            else { shadow_lo = fmin(-a, -lam * H); shadow_hi = -a; }
            /* visible ground is [-4a, -tau H] ∪ [a, 4a] when tau H > a, else [-4a,-a] ∪ [a,4a] */
            {
                double vis_lo = fmax(a, tau * H) > a ? -tau * H : -a; /* left end of the ridge's hidden zone */
                double shadow_on_visible = fmax(0, fmin(shadow_hi, 4 * a) - fmax(shadow_lo, a)) +
                                           fmax(0, fmin(shadow_hi, vis_lo) - fmax(shadow_lo, -4 * a));
                gl = rg - shadow_on_visible / span;
            }
            dir_uw(lam, L);
            r = run(&g, 1, 0.5, 0.5, 4 * a, tau, L, 1, 0, 100 + (uint64_t)(3 * i + j));
            T_NEAR(gro_vis(&r, 0, 0), r0, TOL);
            T_NEAR(gro_vis(&r, 0, 1), r1, TOL);
            T_NEAR(r.ground_vis, rg, TOL);
            T_NEAR(r.ground_lit[0], gl, TOL);
            /* facet 0 faces +u: lit unless the light is behind it */
            T_NEAR(gro_lit(&r, 0, 0, 0), lam > -a / H ? r0 : 0, TOL);
            T_NEAR(gro_lit(&r, 0, 0, 1), lam < a / H ? r1 : 0, TOL);
            gro_result_free(&r);
        }
}

/* Footprints much wider than the groove see the ground around it; a light
   at or below the horizon lights nothing. */
static void wide_footprint_and_horizon_light(void)
{
    static const double sec[6] = {-0.01, 0, 0, -0.015, 0.01, 0};
    gro_groove_t g = straight(sec, 3);
    double L[6] = {1, 0, 0, 0.6, 0, -0.8}; /* at the horizon, below it */
    gro_result_t r = run(&g, 1, 0.5, 0.5, 0.08, 0.0, L, 2, 0, 3);
    T_NEAR(r.ground_vis, 1 - 0.02 / 0.16, TOL);
    T_NEAR(gro_vis(&r, 0, 0) + gro_vis(&r, 0, 1), 0.02 / 0.16, TOL);
    T_EQ(r.ground_lit[0], 0);
    T_EQ(r.ground_lit[1], 0);
    T_EQ(gro_lit(&r, 0, 0, 0) + gro_lit(&r, 0, 0, 1) + gro_lit(&r, 1, 0, 0) + gro_lit(&r, 1, 0, 1), 0);
    gro_result_free(&r);
}

/* Repeating texture: a groove at u = 0.993 (mouth [0.983, 1.003]) seen
   through the footprint [-0.017, 0.023] around u = 0.003, across the seam:
   its copy at u = -0.007 fills the left half exactly, ground the right half. */
static void footprint_across_the_seam(void)
{
    static const double sec[6] = {-0.01, 0, 0, -0.015, 0.01, 0};
    static const double path[4] = {0.993, -0.5, 0.993, 1.5};
    gro_groove_t g = straight(sec, 3);
    double L[3], v0, v1, l0, l1, tau = 0.5, lam = 0.8;
    gro_result_t r;
    g.ctrl = path;
    dir_uw(lam, L);
    r = run(&g, 1, 0.003, 0.3, 0.02, tau, L, 1, 1, 11);
    vgroove_fractions(0.01, 0.015, tau, lam, &v0, &v1, &l0, &l1);
    T_NEAR(gro_vis(&r, 0, 0), 0.5 * v0, TOL);
    T_NEAR(gro_vis(&r, 0, 1), 0.5 * v1, TOL);
    T_NEAR(gro_lit(&r, 0, 0, 1), 0.5 * l1, TOL);
    T_NEAR(r.ground_vis, 0.5, TOL);
    T_NEAR(r.ground_lit[0], 0.5, TOL);
    T_EQ(r.miss, 0);
    gro_result_free(&r);
    /* without wrapping the footprint sees only ground */
    r = run(&g, 1, 0.003, 0.3, 0.02, tau, L, 1, 0, 11);
    T_NEAR(r.ground_vis, 1, 0);
    gro_result_free(&r);
}

/* A constant perturbation s = 0.5 halves the section: the closed form for
   (a/2, D/2) holds; two parallel grooves add up. */
static double half(double t, void *ctx) { (void)t; (void)ctx; return 0.5; }
static void perturbation_and_parallel_grooves(void)
{
    static const double sec[6] = {-0.02, 0, 0, -0.03, 0.02, 0};
    static const double p0[4] = {0.49, 0, 0.49, 1}, p1[4] = {0.51, 0, 0.51, 1};
    gro_groove_t g[2];
    double L[3], v0, v1, l0, l1, tau = -0.4, lam = 0.5;
    gro_result_t r;
    g[0] = straight(sec, 3); g[0].ctrl = p0; g[0].scale = half;
    g[1] = g[0]; g[1].ctrl = p1;
    dir_uw(lam, L);
    r = run(g, 2, 0.5, 0.5, 0.02, tau, L, 1, 0, 5); /* footprint = both mouths exactly */
    vgroove_fractions(0.01, 0.015, tau, lam, &v0, &v1, &l0, &l1);
    T_NEAR(gro_vis_all(&r, 0), v0, TOL);
    T_NEAR(gro_vis_all(&r, 1), v1, TOL);
    T_NEAR(gro_lit_all(&r, 0, 0), l0, TOL);
    T_NEAR(gro_lit_all(&r, 0, 1), l1, TOL);
    T_NEAR(gro_vis(&r, 0, 0), gro_vis(&r, 1, 0), 2 * TOL);
    T_NEAR(r.ground_vis, 0, TOL);
    gro_result_free(&r);
}

/* A quarter-circle-like cubic Bézier: at normal incidence a footprint much
   smaller than the radius of curvature, centred on the path, sees each wall
   of a V-groove over half the mouth (curvature error ~ (a/R)^2 << TOL). */
static void bezier_groove_at_normal_incidence(void)
{
    static const double sec[6] = {-0.004, 0, 0, -0.006, 0.004, 0};
    static const double ctrl[8] = {0.2, 0.2, 0.2, 0.6, 0.4, 0.8, 0.8, 0.8};
    gro_groove_t g = straight(sec, 3);
    gro_query_t q;
    gro_result_t r;
    double P[2], T[2], Pa[2], Pb[2], l;
    g.kind = GRO_CUBIC; g.nctrl = 4; g.ctrl = ctrl;
    gro__path_point(&g, 0.5, P);
    gro__path_point(&g, 0.5 - 1e-6, Pa);
    gro__path_point(&g, 0.5 + 1e-6, Pb);
    T[0] = Pb[0] - Pa[0]; T[1] = Pb[1] - Pa[1]; l = hypot(T[0], T[1]); T[0] /= l; T[1] /= l;
    memset(&q, 0, sizeof q);
    q.grooves = &g; q.ngrooves = 1;
    q.F[0] = P[0]; q.F[1] = P[1];
    q.A1[0] = -T[1] * 0.004; q.A1[1] = T[0] * 0.004; /* across: exactly the mouth */
    q.A2[0] = T[0] * 0.001; q.A2[1] = T[1] * 0.001;
    q.E[2] = 1; q.n = 256;
    if (gro_query(&q, dev.dev, &r)) T_FAIL("gro_query failed");
    T_NEAR(gro_vis(&r, 0, 0), 0.5, TOL);
    T_NEAR(gro_vis(&r, 0, 1), 0.5, TOL);
    T_NEAR(r.ground_vis, 0, TOL);
    T_EQ(r.miss, 0);
    gro_result_free(&r);
}

/* The stated bound: over 8 seeds the spread of a strip fraction stays within
   3 sigma of sqrt(B/(2 n^3)) with B = 2. */
static void sample_error_within_stated_bound(void)
{
    static const double sec[6] = {-0.01, 0, 0, -0.015, 0.01, 0};
    gro_groove_t g = straight(sec, 3);
    double sum2 = 0, bound = sqrt(2.0 / (2.0 * 256 * 256 * 256)), v0, v1, l0, l1;
    int s, ns = t_scale() < 1 ? 3 : 8;
    vgroove_fractions(0.01, 0.015, 0.37, 0, &v0, &v1, &l0, &l1);
    for (s = 0; s < ns; s++) {
        gro_result_t r = run(&g, 1, 0.5, 0.5, 0.01, 0.37, NULL, 0, 0, 1000 + (uint64_t)s);
        double e = gro_vis(&r, 0, 0) - v0;
        sum2 += e * e;
        T_LE(fabs(e), 5 * bound);
        gro_result_free(&r);
    }
    T_LE(sqrt(sum2 / ns), 3 * bound);
}

/* Crossings (CSG): rectangular grooves of half width a, seen straight down,
   one light drifting +u by lam per unit height. Groove A runs along u
   (b -> v), B along v (b -> -u); facet 1 is each floor. The true surface is
   the ground minus both volumes, so where they overlap the deeper floor is
   seen; a ray must not stop on the shallower floor, nor a shadow ray on a
   wall the other groove has cut away. */
static gro_groove_t rect_groove(const double *path, const double *sec)
{
    gro_groove_t g;
    memset(&g, 0, sizeof g);
    g.kind = GRO_LINE; g.nctrl = 2; g.ctrl = path;
    g.nsec = 4; g.sec = sec;
    return g;
}

#define CR_A 0.01   /* half width of both grooves */
#define CR_R 0.05   /* footprint half size, centred on the crossing (0.5, 0.5) */
#define CR_LAM 0.25 /* the light's drift per unit height, toward +u */

/* Groove A (path pa, depth dA) and B (along v through u = 0.5, depth dB),
   seen straight down over the square footprint, lit by one light. */
static gro_result_t crossing(const double *pa, double dA, double dB)
{
    const double a = CR_A, secA[8] = {-a, 0, -a, -dA, a, -dA, a, 0}, secB[8] = {-a, 0, -a, -dB, a, -dB, a, 0};
    static const double pb[4] = {0.5, 0.2, 0.5, 0.8};
    double L[3];
    gro_groove_t g[2];
    gro_query_t q;
    gro_result_t r;
    dir_uw(CR_LAM, L);
    g[0] = rect_groove(pa, secA);
    g[1] = rect_groove(pb, secB);
    memset(&q, 0, sizeof q);
    q.grooves = g; q.ngrooves = 2;
    q.F[0] = 0.5; q.F[1] = 0.5; q.A1[0] = CR_R; q.A2[1] = CR_R;
    q.E[2] = 1;
    q.lights = L; q.nlights = 1;
    q.n = 256; q.seed = 77;
    if (gro_query(&q, dev.dev, &r)) T_FAIL("gro_query failed");
    T_LE(r.miss, 0);
    return r;
}

static void x_crossing_deeper_floor_wins(void)
{
    const double a = CR_A, dA = 0.01, dB = 0.02, R = CR_R, lam = CR_LAM, F = 4 * R * R;
    static const double pa[4] = {0.2, 0.5, 0.8, 0.5};
    gro_result_t r = crossing(pa, dA, dB);
    T_NEAR(r.ground_vis, (F - 8 * a * R + 4 * a * a) / F, TOL);
    T_NEAR(gro_vis(&r, 0, 1), (4 * a * R - 4 * a * a) / F, TOL); /* the old oracle: + 4a²/F */
    T_NEAR(gro_vis(&r, 1, 1), 4 * a * R / F, TOL);
    T_NEAR(r.ground_lit[0], r.ground_vis, TOL);
    T_NEAR(gro_lit(&r, 0, 0, 1), gro_vis(&r, 0, 1), TOL);
    /* B's floor: its +u wall stands up to w = 0, except inside A, where it is cut down to -dA */
    T_NEAR(gro_lit(&r, 0, 1, 1), ((2 * R - 2 * a) * clamp(2 * a - lam * dB, 0, 2 * a) +
                                  2 * a * clamp(2 * a - lam * (dB - dA), 0, 2 * a)) / F, TOL);
    gro_result_free(&r);
}

static void t_crossing_end_cap_and_floor(void)
{
    const double a = CR_A, dA = 0.03, dB = 0.02, R = CR_R, lam = CR_LAM, F = 4 * R * R;
    static const double pa[4] = {0.2, 0.5, 0.5, 0.5}; /* A is deeper and ends on B's centre line */
    gro_result_t r = crossing(pa, dA, dB);
    T_NEAR(r.ground_vis, (F - 4 * a * R - 2 * a * (R - a)) / F, TOL);
    T_NEAR(gro_vis(&r, 0, 1), 2 * a * R / F, TOL);
    T_NEAR(gro_vis(&r, 1, 1), (4 * a * R - 2 * a * a) / F, TOL);
    T_NEAR(gro_vis(&r, 0, GRO_CAP1), 0, TOL);
    /* A's floor: lit where the shadow ray clears A's cap above -dB and B's +u wall */
    T_NEAR(gro_lit(&r, 0, 0, 1), 2 * a * clamp(fmin(-lam * (dA - dB), a - lam * dA) + R, 0, R) / F, TOL);
    T_NEAR(gro_lit(&r, 0, 1, 1), ((2 * R - 2 * a) * clamp(2 * a - lam * dB, 0, 2 * a) +
                                  2 * a * clamp(a - lam * dB, 0, a)) / F, TOL);
    gro_result_free(&r);
}

/* An isolated end seen from the groove's side: its cap faces the viewer. A
   rectangular groove along u ends at u = 0.5; the viewer leans toward -u
   (rays drift +u by tau per unit depth), so the cap (depth d, width 2a) covers tau·d of the footprint's u
   extent over the groove's width. */
static void isolated_end_cap_is_seen(void)
{
    const double a = 0.01, d = 0.02, R = 0.05, tau = 0.5, F = 4 * R * R;
    const double sec[8] = {-a, 0, -a, -d, a, -d, a, 0};
    static const double pa[4] = {0.2, 0.5, 0.5, 0.5};
    gro_groove_t g = rect_groove(pa, sec);
    gro_query_t q;
    gro_result_t r;
    memset(&q, 0, sizeof q);
    q.grooves = &g; q.ngrooves = 1;
    q.F[0] = 0.5; q.F[1] = 0.5; q.A1[0] = R; q.A2[1] = R;
    dir_uw(-tau, q.E);
    q.n = 256; q.seed = 5;
    if (gro_query(&q, dev.dev, &r)) T_FAIL("gro_query failed");
    T_NEAR(gro_vis(&r, 0, GRO_CAP1), 2 * a * tau * d / F, TOL);
    T_NEAR(gro_vis(&r, 0, 1), 2 * a * (R - tau * d) / F, TOL);
    T_LE(r.miss, 0);
    gro_result_free(&r);
}

/* A protruding bar across a cut is a bridge: the solid is the ground
   minus the cuts plus the protrusions, so over the cut's hole the plane
   w = 0 is the bar's underside (a surface facing down), and over solid
   ground it is no surface (the bar and the ground are one solid). Rays
   from inside the cut up under the bar, and from inside the bar down
   over the cut, meet w = 0; beside the bar, and inside the bar over the
   ground, they do not; the cut's floor under the bar is in its shadow. */
static void bridge_has_an_underside(void)
{
    const double a = 0.01, d = 0.02, h = 0.01;
    const double cut[8] = {-a, 0, -a, -d, a, -d, a, 0}, bar[8] = {-a, 0, -a, h, a, h, a, 0};
    static const double pa[4] = {0.2, 0.5, 0.8, 0.5}, pb[4] = {0.5, 0.2, 0.5, 0.8};
    static const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1}, slant[3] = {0.6, 0, 0.8};
    gro_groove_t g[2];
    gro_scene_t sc;
    gro_hit_t hit;
    double o[3];
    g[0] = rect_groove(pa, cut);
    g[1] = rect_groove(pb, bar);
    if (!T_CHECK(gro_scene_build(&sc, dev.dev, g, 2, NULL) == 0)) return;
    T_INT_EQ(sc.bridges, 1);
    o[0] = 0.5; o[1] = 0.5; o[2] = -0.015; /* in the cut, under the bar */
    hit = gro_scene_intersect(&sc, o, up, 0, INFINITY);
    T_INT_EQ(hit.kind, GRO_HIT_GROUND);
    T_NEAR(hit.t, 0.015, 1e-9);
    T_NEAR(hit.n[2], -1, 1e-12);
    o[0] = 0.495 - 0.75 * 0.015; /* slanting up, entering under the bar's -u side */
    hit = gro_scene_intersect(&sc, o, slant, 0, INFINITY);
    T_INT_EQ(hit.kind, GRO_HIT_GROUND);
    T_NEAR(hit.p[0], 0.495, 1e-6);
    o[0] = 0.53; /* in the cut, beside the bar: the sky */
    hit = gro_scene_intersect(&sc, o, up, 0, INFINITY);
    T_INT_EQ(hit.kind, GRO_HIT_NONE);
    o[0] = 0.5; o[2] = 0.005; /* inside the bar over the cut: out through the underside */
    hit = gro_scene_intersect(&sc, o, down, 0, INFINITY);
    T_INT_EQ(hit.kind, GRO_HIT_GROUND);
    T_NEAR(hit.t, 0.005, 1e-9);
    T_NEAR(hit.n[2], 1, 1e-12);
    o[1] = 0.6; /* inside the bar over the ground: one solid, no surface at w = 0 */
    hit = gro_scene_intersect(&sc, o, down, 0, INFINITY);
    T_INT_EQ(hit.kind, GRO_HIT_NONE);
    o[1] = 0.5; o[2] = 0.1; /* the cut's floor: shadowed under the bar, lit beside it */
    o[0] = 0.5 + 0.3 * a;
    hit = gro_scene_intersect(&sc, o, down, 0, INFINITY);
    T_INT_EQ(hit.kind, GRO_HIT_FACET);
    T_INT_EQ(hit.groove, 1); /* the bar's top */
    hit.kind = GRO_HIT_FACET; hit.p[0] = 0.5 + 0.3 * a; hit.p[1] = 0.5; hit.p[2] = -d;
    hit.n[0] = hit.n[1] = 0; hit.n[2] = 1;
    T_INT_EQ(gro_scene_lit(&sc, &hit, up), 0);
    hit.p[0] = 0.5 + 2 * a;
    T_INT_EQ(gro_scene_lit(&sc, &hit, up), 1);
    gro_scene_free(&sc);
    { /* one groove alone cannot bridge itself: no test */
        if (!T_CHECK(gro_scene_build(&sc, dev.dev, g + 1, 1, NULL) == 0)) return;
        T_INT_EQ(sc.bridges, 0);
        gro_scene_free(&sc);
    }
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(v_groove_all_view_angles),
        T_CASE(vertical_walls_masking_and_shadowing),
        T_CASE(protruding_ridge_masks_and_shadows_ground),
        T_CASE(wide_footprint_and_horizon_light),
        T_CASE(footprint_across_the_seam),
        T_CASE(perturbation_and_parallel_grooves),
        T_CASE(bezier_groove_at_normal_incidence),
        T_CASE(sample_error_within_stated_bound),
        T_CASE(x_crossing_deeper_floor_wins),
        T_CASE(t_crossing_end_cap_and_floor),
        T_CASE(isolated_end_cap_is_seen),
        T_CASE(bridge_has_an_underside),
    };
    int rc;
    if (gro_device_init(&dev)) { printf("0 passed, 1 failed\n"); return 1; }
    rc = T_RUN(argc, argv, cases);
    gro_device_free(&dev);
    return rc;
}
