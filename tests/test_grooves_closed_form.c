/* grooves.h against hand-derived closed forms (Bosch et al. 2006, §4).
   Every expected value here is derived in the comment above it from the
   geometry of a V-groove, not from the code under test. */
#include "grooves.h"
#include "test.h"
#include "grooves_test_util.h"

/* One straight groove along +v at u = 0.5: T = (0,1), so B = (-T_v, T_u)
   = (-1, 0): section b > 0 lies toward -u. */
static gr_grid_t *one_groove(const double *sec, int nsec)
{
    static const double path[4] = {0.5, 0.0, 0.5, 1.0};
    gr_groove_desc_t g;
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_diag_t diag;
    memset(&g, 0, sizeof g);
    memset(&d, 0, sizeof d);
    g.points = path;
    g.point_count = 2;
    g.section = sec;
    g.section_count = nsec;
    g.reflectance = 7;
    d.grooves = &g;
    d.groove_count = 1;
    d.base_reflectance = 1;
    if (gr_grid_build(&d, &grid, &diag) != GR_OK) T_FAIL("build: %s", diag.message);
    return grid;
}


/* Symmetric V (half-width a, depth D) from straight above with a square
   footprint of half-size r > a centred on the path: each slope projects to
   width a, the ground to 2r - 2a, out of S = [-r, r]: ratios a/2r, a/2r,
   1 - a/r. Normals: facet 0 from (-a,0) to (0,-D) has (b,w)-normal
   (D, a)/sqrt(a²+D²), i.e. texture (-D, 0, a)/len since B = (-1, 0). */
static void v_groove_from_above(void)
{
    const double a = 0.01, D = 0.02, r = 0.05;
    const double sec[6] = {-a, 0, 0, -D, a, 0};
    gr_grid_t *grid = one_groove(sec, 3);
    gr_query_t q = gt_query(0.5, 0.5, r, 0, 0, 1);
    gr_facet_list_t l;
    const gr_facet_t *f0;
    double len = sqrt(a * a + D * D);
    if (!grid || !gt_run(grid, &q, &l)) return;
    T_INT_EQ(l.count, 3);
    T_NEAR(gt_ratio_of(&l, 0), a / (2 * r), 1e-14);
    T_NEAR(gt_ratio_of(&l, 1), a / (2 * r), 1e-14);
    T_NEAR(gt_ratio_of(&l, -1), 1 - a / r, 1e-14);
    f0 = gt_entry(&l, 0);
    if (T_CHECK(f0 != NULL)) {
        T_NEAR(f0->normal[0], -D / len, 1e-14);
        T_NEAR(f0->normal[1], 0, 1e-14);
        T_NEAR(f0->normal[2], a / len, 1e-14);
        T_INT_EQ(f0->reflectance, 7);
    }
    T_INT_EQ(gt_entry(&l, -1) ? gt_entry(&l, -1)->reflectance : -99, 1);
    T_INT_EQ(l.flags, 0);
    gr_grid_free(grid);
}

/* Viewer tilted by θ toward +u (E = (sin θ, 0, cos θ)), so toward -b.
   A ray at angle θ through the rim (-a, 0)... rather: the profile point
   (b, w) is seen at b + w tan θ on the base line (E_b = -sin θ, tan θ' =
   tan θ). The bottom (0, -D) lands at -D tan θ: while D tan θ < a, facet 0
   covers [-a, -D tan θ] (width a - D tan θ) and facet 1 [-D tan θ, a]
   (width a + D tan θ); once D tan θ >= a, facet 0 is hidden and facet 1 is
   seen from its masked start at the rim: [-a, a]. */
static void v_groove_masking_at_known_angles(void)
{
    const double a = 0.01, D = 0.02, r = 0.05;
    const double sec[6] = {-a, 0, 0, -D, a, 0};
    const double deg[] = {5, 10, 20, 26.5, 30, 45, 60, 80};
    gr_grid_t *grid = one_groove(sec, 3);
    unsigned i;
    if (!grid) return;
    for (i = 0; i < sizeof deg / sizeof deg[0]; i++) {
        double th = deg[i] * M_PI / 180, t = tan(th);
        gr_query_t q = gt_query(0.5, 0.5, r, sin(th), 0, cos(th));
        gr_facet_list_t l;
        double w0 = D * t < a ? a - D * t : 0, w1 = D * t < a ? a + D * t : 2 * a;
        if (!gt_run(grid, &q, &l)) continue;
        T_NEAR(gt_ratio_of(&l, 0), w0 / (2 * r), 1e-13);
        T_NEAR(gt_ratio_of(&l, 1), w1 / (2 * r), 1e-13);
        T_NEAR(gt_ratio_of(&l, -1), 1 - a / r, 1e-13);
    }
    gr_grid_free(grid);
}

/* Light at angle φ toward +u, viewer straight above. Facet 0 (near wall,
   (b,w)-normal (D, a)) faces the light while tan φ < a/D and nothing can
   block it, so it is lit wholly, else not at all. Facet 1 is shadowed by the
   rim (-a, 0): the light ray through the rim, (-a + s sin φ, -s cos φ),
   meets facet 1's point (ua, -D + uD) at u* = (D tan φ - a)/(a + D tan φ);
   the lit part is u in [max(u*, 0), 1]. */
static void v_groove_shadowing_at_known_angles(void)
{
    const double a = 0.01, D = 0.02, r = 0.05;
    const double sec[6] = {-a, 0, 0, -D, a, 0};
    const double deg[] = {0, 10, 20, 26, 27, 40, 60, 85};
    gr_grid_t *grid = one_groove(sec, 3);
    unsigned i;
    if (!grid) return;
    for (i = 0; i < sizeof deg / sizeof deg[0]; i++) {
        double ph = deg[i] * M_PI / 180, t = tan(ph);
        double light[3] = {sin(ph), 0, cos(ph)};
        gr_query_t q = gt_query(0.5, 0.5, r, 0, 0, 1);
        gr_facet_list_t l;
        double us = (D * t - a) / (a + D * t);
        const gr_facet_t *f0, *f1, *g;
        q.lights = light;
        q.light_count = 1;
        if (!gt_run(grid, &q, &l)) continue;
        f0 = gt_entry(&l, 0);
        f1 = gt_entry(&l, 1);
        g = gt_entry(&l, -1);
        if (!T_CHECK(f0 && f1 && g)) continue;
        T_NEAR(f0->lit[0], t < a / D ? 1.0 : 0.0, 1e-13);
        T_NEAR(f1->lit[0], 1 - (us > 0 ? us : 0), 1e-13);
        T_NEAR(g->lit[0], 1.0, 1e-13);
        /* the mirror image: light toward -u swaps the roles of the slopes */
        light[0] = -sin(ph);
        if (!gt_run(grid, &q, &l)) continue;
        f0 = gt_entry(&l, 0);
        f1 = gt_entry(&l, 1);
        if (!T_CHECK(f0 && f1)) continue;
        T_NEAR(f1->lit[0], t < a / D ? 1.0 : 0.0, 1e-13);
        T_NEAR(f0->lit[0], 1 - (us > 0 ? us : 0), 1e-13);
    }
    gr_grid_free(grid);
}

/* Oblique footprints over the same V (half-width a = 0.01) from above:
   each slope covers a strip of width a beside the path, so its ratio is the
   share of the footprint's area in that strip, from the parallelogram's
   chord length L(x) across the groove (x = |u - 0.5|, the footprint's
   projection onto B is |A1_u| + |A2_u|).
   - A diamond, A1 = (c/2, c/2), A2 = (-c/2, c/2), c = 0.02: L(x) falls
     linearly from its peak at x = 0 to 0 at x = c, so the strip [0, a]
     holds (a c - a^2/2) / c^2 = 0.375 of it; the ground 1 - 2 (0.375).
   - A1 = (0.012, 0.01), A2 = (-0.006, 0.03): L is constant L0 up to
     x = 0.012 - 0.006 and falls to 0 at 0.018, total area L0 0.024; the
     strip holds L0 (0.006 + ∫_0.006^0.01 (0.018 - x)/0.012 dx) = L0 0.00933..,
     a share of 7/18. §4.2's uniform segment [-0.012, 0.012] would say 5/12. */
static void check_slopes(const gr_grid_t *grid, const double *ax, int ellipse, double want)
{
    gr_query_t q = gt_query(0.5, 0.5, 0, 0, 0, 1);
    gr_facet_list_t l;
    q.footprint.axis1[0] = ax[0]; q.footprint.axis1[1] = ax[1];
    q.footprint.axis2[0] = ax[2]; q.footprint.axis2[1] = ax[3];
    q.ellipse = ellipse;
    if (!gt_run(grid, &q, &l)) return;
    T_NEAR(gt_ratio_of(&l, 0), want, 1e-14);
    T_NEAR(gt_ratio_of(&l, 1), want, 1e-14);
    T_NEAR(gt_ratio_of(&l, -1), 1 - 2 * want, 1e-14);
}

static void v_groove_oblique_footprints(void)
{
    const double a = 0.01, D = 0.02;
    const double sec[6] = {-a, 0, 0, -D, a, 0};
    const double ax[2][4] = {{0.01, 0.01, -0.01, 0.01}, {0.012, 0.01, -0.006, 0.03}};
    const double want[2] = {0.375, 7.0 / 18};
    gr_grid_t *grid = one_groove(sec, 3);
    int i;
    if (!grid) return;
    for (i = 0; i < 2; i++) check_slopes(grid, ax[i], 0, want[i]);
    gr_grid_free(grid);
}

/* The same V under elliptical footprints (query.ellipse = 1): the strip
   0 <= x <= a of the disc of radius c holds the circular segment
   ∫_0^a 2 sqrt(c^2 - x^2) dx = a sqrt(c^2 - a^2) + c^2 asin(a/c), a share
   (u sqrt(1 - u^2) + asin u) / pi of its area, u = a/c. An ellipse
   F + a A1 + b A2 (a^2 + b^2 <= 1) has the same chord profile across x
   with c = |(A1_u, A2_u)|, its largest x. */
static void v_groove_elliptical_footprints(void)
{
    const double a = 0.01, D = 0.02;
    const double sec[6] = {-a, 0, 0, -D, a, 0};
    const double ax[2][4] = {{0.02, 0, 0, 0.02}, {0.02, 0.01, -0.005, 0.03}};
    gr_grid_t *grid = one_groove(sec, 3);
    int i;
    if (!grid) return;
    for (i = 0; i < 2; i++) {
        double u = a / hypot(ax[i][0], ax[i][2]);
        check_slopes(grid, ax[i], 1, (u * sqrt(1 - u * u) + asin(u)) / M_PI);
    }
    gr_grid_free(grid);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(v_groove_from_above),
        T_CASE(v_groove_masking_at_known_angles),
        T_CASE(v_groove_shadowing_at_known_angles),
        T_CASE(v_groove_oblique_footprints),
        T_CASE(v_groove_elliptical_footprints),
    };
    return T_RUN(argc, argv, cases);
}
