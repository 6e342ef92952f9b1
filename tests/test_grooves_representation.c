/* grooves.h representation and API (§3, §4.1-4.2): bounds, blockers,
   merged parallel cross-sections, mirrored paths, protruding shadows,
   Bézier paths, perturbation and oversampling, the footprint from ray
   differentials, the grid's interior anchors, gr_shade, threads.
   Expected values are derived by hand in the comment above each case. */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "test.h"
#include "grooves_test_util.h"
#include <pthread.h>

static gr_grid_t *build(const gr_groove_desc_t *g, int n, int cells)
{
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_diag_t diag;
    memset(&d, 0, sizeof d);
    d.grooves = g;
    d.groove_count = n;
    d.cells_u = d.cells_v = cells;
    if (gr_grid_build(&d, &grid, &diag) != GR_OK) T_FAIL("build: %s", diag.message);
    return grid;
}
static gr_groove_desc_t groove(const double *pts, int np, const double *sec, int ns)
{
    gr_groove_desc_t g;
    memset(&g, 0, sizeof g);
    g.points = pts;
    g.point_count = np;
    g.section = sec;
    g.section_count = ns;
    return g;
}
static const gr_facet_t *entry(const gr_facet_list_t *l, int groove, int facet)
{
    int i;
    for (i = 0; i < l->count; i++)
        if (l->facets[i].facet == facet && (facet < 0 || l->facets[i].groove == groove)) return &l->facets[i];
    return NULL;
}
static double ratio_of(const gr_facet_list_t *l, int groove, int facet)
{
    const gr_facet_t *f = entry(l, groove, facet);
    return f ? f->ratio : 0.0;
}

static const double VPATH[4] = {0.5, 0.0, 0.5, 1.0};   /* along +v: B = (-1, 0) */
static const double VPATH_BACK[4] = {0.5, 1.0, 0.5, 0.0}; /* along -v: B = (+1, 0) */

/* §3 bounds: section W = (-2,0) (-1,-3) (0,1) (1,-2) (2,0) (x0.01), scaled
   by perturb_max 1.5: w = 2*0.01*1.5, h = 1*0.01*1.5, d = 3*0.01*1.5.
   Blockers of facet i: facets j != i with a point above facet i's lowest
   point. Heights per facet (lowest): R0 [0,-3] -3, R1 [-3,1] -3,
   R2 [1,-2] -2, R3 [-2,0] -2. R0: R1,R2,R3 (all reach above -3);
   R1: R0,R2,R3; R2: R0 (0 > -2), R1 (1), R3 (0); R3: R0, R1, R2. */
static double one(double t, void *u) { (void)t; (void)u; return 1; }
static void bounds_and_blockers(void)
{
    const double s = 0.01, sec[10] = {-2 * s, 0, -1 * s, -3 * s, 0, 1 * s, 1 * s, -2 * s, 2 * s, 0};
    gr_groove_desc_t g = groove(VPATH, 2, sec, 5);
    gr_grid_t *grid;
    const int *list;
    int f, n;
    g.perturb = one;
    g.perturb_max = 1.5;
    grid = build(&g, 1, 0);
    if (!grid) return;
    T_NEAR(grid->w, 2 * s * 1.5, 1e-17);
    T_NEAR(grid->h, 1 * s * 1.5, 1e-17);
    T_NEAR(grid->d, 3 * s * 1.5, 1e-17);
    for (f = 0; f < 4; f++) {
        n = gr_facet_blockers(grid, 0, f, &list);
        T_INT_EQ(n, 3);
        if (n == 3) {
            int k, seen = 0;
            for (k = 0; k < 3; k++) { T_CHECK(list[k] != f); seen |= 1 << list[k]; }
            T_INT_EQ(seen, 15 & ~(1 << f));
        }
    }
    T_INT_EQ(gr_facet_blockers(grid, 0, 4, &list), 0);
    T_INT_EQ(gr_facet_blockers(grid, 1, 0, &list), 0);
    gr_grid_free(grid);
}

/* Two parallel V-grooves (a = 0.01, D = 0.02) at u = 0.47 and 0.53, one
   running backward (mirrored, §4.2), footprint r = 0.05 at u = 0.5, viewer
   tilted θ toward +u. Each groove alone shows its slopes a -+ Dt wide on
   the base line; the groove at 0.53 lies toward +u, x in [-0.04, -0.02],
   inside S = [-0.05, 0.05]; the one at 0.47 at x in [0.02, 0.04]. So every
   facet facing +u (toward the viewer) gets (a + Dt)/2r, the others
   (a - Dt)/2r, and the ground the rest: 1 - 2a/r. Merged entries: the
   slopes with equal normals of both grooves add up. */
static void parallel_grooves_and_mirrored_path(void)
{
    const double a = 0.01, D = 0.02, sec[6] = {-a, 0, 0, -D, a, 0};
    double p1[4] = {0.47, 0, 0.47, 1}, p2[4] = {0.53, 1, 0.53, 0};
    gr_groove_desc_t g[2];
    gr_grid_t *grid;
    double th = 15 * M_PI / 180, t = tan(th);
    gr_query_t q = gt_query(0.5, 0.5, 0.05, sin(th), 0, cos(th));
    gr_facet_list_t l;
    int i;
    double toward = 0, away = 0;
    g[0] = groove(p1, 2, sec, 3);
    g[1] = groove(p2, 2, sec, 3);
    grid = build(g, 2, 0);
    if (!grid || !gt_run(grid, &q, &l)) return;
    T_INT_EQ(l.grooves, 2);
    T_INT_EQ(l.count, 3);
    for (i = 0; i < l.count; i++) {
        const gr_facet_t *f = &l.facets[i];
        if (f->groove < 0) T_NEAR(f->ratio, 1 - 2 * a / 0.05, 1e-13);
        else if (f->normal[0] > 0) toward += f->ratio;
        else away += f->ratio;
        if (f->groove >= 0) T_INT_EQ(f->merged, 2);
    }
    T_NEAR(toward, 2 * (a + D * t) / 0.1, 1e-13);
    T_NEAR(away, 2 * (a - D * t) / 0.1, 1e-13);
    gr_grid_free(grid);
}

/* More distinct facets than the list holds: 20 parallel grooves along v,
   each with its own reflectance id, so their 40 walls and the ground are 41
   entries for GR_MAX_FACETS = 32 places. The extra ones fold into the
   closest orientation (GR_LIST_APPROX_MERGE), which here is always the
   same wall normal of another groove: no normal is averaged, and each
   orientation keeps its closed-form share from above, 20 a / 2r (gcov: no
   test had filled the list; this found the fold preferring the same
   reflectance id over any normal, which averaged groove 4's two walls
   into the flat normal: 1 entry off, each wall share 0.01 short). */
static void facet_list_overflow_folds_into_equal_normals(void)
{
    const double a = 0.005, D = 0.01, sec[6] = {-a, 0, 0, -D, a, 0};
    static double pts[20][4];
    gr_groove_desc_t g[20];
    gr_grid_t *grid;
    gr_query_t q = gt_query(0.5, 0.5, 0.25, 0, 0, 1);
    gr_facet_list_t l;
    double wall[2] = {0, 0}, ground = 0, sum = 0;
    int i, other = 0;
    for (i = 0; i < 20; i++) {
        pts[i][0] = pts[i][2] = 0.31 + 0.02 * i, pts[i][1] = 0, pts[i][3] = 1;
        g[i] = groove(pts[i], 2, sec, 3);
        g[i].reflectance = 10 + i;
    }
    grid = build(g, 20, 0);
    if (!grid || !gt_run(grid, &q, &l)) return;
    T_CHECK(l.flags & GR_LIST_APPROX_MERGE);
    T_INT_EQ(l.count, GR_MAX_FACETS);
    for (i = 0; i < l.count; i++) {
        const gr_facet_t *f = &l.facets[i];
        double h = hypot(a, D);
        sum += f->ratio;
        if (f->normal[0] == 0 && f->normal[1] == 0 && f->normal[2] == 1) ground += f->ratio;
        else if (fabs(fabs(f->normal[0]) - D / h) <= 1e-15 && f->normal[1] == 0 && fabs(f->normal[2] - a / h) <= 1e-15)
            wall[f->normal[0] > 0] += f->ratio;
        else other++;
    }
    T_INT_EQ(other, 0); /* every entry one of the three orientations: nothing averaged */
    T_NEAR(sum, 1, 1e-12);
    T_NEAR(wall[0], 20 * a / 0.5, 1e-12);
    T_NEAR(wall[1], 20 * a / 0.5, 1e-12);
    T_NEAR(ground, 1 - 40 * a / 0.5, 1e-12);
    gr_grid_free(grid);
}

/* An asymmetric section (-a,0) (0,-D) (2a,0) on a path running -v: there
   B = (+1, 0), so b lies toward +u: the steep facet 0 spans u in
   [0.5 - a, 0.5], the shallow facet 1 [0.5, 0.5 + 2a]. From above:
   ratios a/2r and 2a/2r. Texture normal of facet 0: (b,w)-normal (D, a)/len
   times B = (1, 0): (D, 0, a)/len, facing +u. */
static void asymmetric_section_backward_path(void)
{
    const double a = 0.01, D = 0.02, sec[6] = {-a, 0, 0, -D, 2 * a, 0};
    gr_groove_desc_t g = groove(VPATH_BACK, 2, sec, 3);
    gr_grid_t *grid = build(&g, 1, 0);
    gr_query_t q = gt_query(0.5, 0.5, 0.05, 0, 0, 1);
    gr_facet_list_t l;
    double len = hypot(a, D);
    if (!grid || !gt_run(grid, &q, &l)) return;
    T_NEAR(ratio_of(&l, 0, 0), a / 0.1, 1e-14);
    T_NEAR(ratio_of(&l, 0, 1), 2 * a / 0.1, 1e-14);
    if (T_CHECK(entry(&l, 0, 0) != NULL)) {
        T_NEAR(entry(&l, 0, 0)->normal[0], D / len, 1e-14);
        T_NEAR(entry(&l, 0, 0)->normal[2], a / len, 1e-14);
    }
    /* a footprint at u = 0.5 - a/2 is on facet 0 (point sample) */
    q = gt_query(0.5 - a / 2, 0.5, 0, 0, 0, 1);
    if (gt_run(grid, &q, &l)) T_NEAR(ratio_of(&l, 0, 0), 1, 0);
    gr_grid_free(grid);
}

/* A ridge (-a,0) (0,H) (a,0) at u = 0.5 on the path along +v (x = b - d,
   B = (-1,0), so +x is -u), light at φ toward +u (toward -x). The peak
   throws its shadow to x = H tan φ. The far slope (b-normal (H, a)/len,
   with L = (L_b, L_w) = (-sin φ, cos φ)) faces the light while
   tan φ < a/H, and then nothing stands between: lit wholly, else unlit. From above (r = 0.05): ground seen
   on [-r, -a] and [a, r]; lit on [-r, -a] and [max(a, H tan φ), r]:
   lit fraction ((r - a) + (r - max(a, H t))) / (2(r - a)). The near slope
   is lit wholly. */
static void protruding_ridge_shadows_ground(void)
{
    const double a = 0.01, H = 0.02, r = 0.05, sec[6] = {-a, 0, 0, H, a, 0};
    const double deg[] = {10, 30, 50, 60};
    gr_groove_desc_t g = groove(VPATH, 2, sec, 3);
    gr_grid_t *grid = build(&g, 1, 0);
    unsigned i;
    if (!grid) return;
    for (i = 0; i < sizeof deg / sizeof deg[0]; i++) {
        double ph = deg[i] * M_PI / 180, t = tan(ph), light[3] = {sin(ph), 0, cos(ph)};
        double sh = H * t > a ? H * t : a;
        gr_query_t q = gt_query(0.5, 0.5, r, 0, 0, 1);
        gr_facet_list_t l;
        q.lights = light;
        q.light_count = 1;
        if (sh > r) sh = r;
        if (!gt_run(grid, &q, &l)) continue;
        if (!T_CHECK(entry(&l, 0, -1) && entry(&l, 0, 0) && entry(&l, 0, 1))) continue;
        T_NEAR(entry(&l, 0, -1)->lit[0], ((r - a) + (r - sh)) / (2 * (r - a)), 1e-13);
        T_NEAR(entry(&l, 0, 0)->lit[0], 1, 1e-13);
        T_NEAR(entry(&l, 0, 1)->lit[0], t < a / H ? 1 : 0, 1e-13);
    }
    gr_grid_free(grid);
}

/* A straight line written as a quadratic and as a cubic Bézier (evenly
   spaced collinear control points) is the polyline's groove: the same
   ratios as from the closed form, a/2r each from above and (a -+ Dt)/2r
   tilted. */
static void straight_beziers_match_segment(void)
{
#ifndef GR_NO_CURVES
    const double a = 0.01, D = 0.02, sec[6] = {-a, 0, 0, -D, a, 0};
    const double quad[6] = {0.5, 0, 0.5, 0.5, 0.5, 1};
    const double cub[8] = {0.5, 0, 0.5, 1.0 / 3, 0.5, 2.0 / 3, 0.5, 1};
    gr_groove_desc_t g[2];
    int k;
    double th = 0.3, t = tan(th);
    g[0] = groove(quad, 3, sec, 3);
    g[0].kind = GR_PATH_QUADRATIC;
    g[1] = groove(cub, 4, sec, 3);
    g[1].kind = GR_PATH_CUBIC;
    for (k = 0; k < 2; k++) {
        gr_grid_t *grid = build(&g[k], 1, 0);
        gr_query_t q = gt_query(0.5, 0.37, 0.05, sin(th), 0, cos(th));
        gr_facet_list_t l;
        if (!grid) continue;
        if (gt_run(grid, &q, &l)) {
            T_NEAR(ratio_of(&l, 0, 0), (a - D * t) / 0.1, 1e-12);
            T_NEAR(ratio_of(&l, 0, 1), (a + D * t) / 0.1, 1e-12);
            T_INT_EQ(l.subfootprints, 1);
        }
        gr_grid_free(grid);
    }
#endif
}

/* A quadratic Bézier parabola (0.3,0.2) (0.5,0.8) (0.7,0.2): B(τ) has its
   vertex at τ = 1/2, point (0.5, 0.5), tangent (1, 0) there, so
   B = (0, 1): b lies toward +v. A footprint at (0.5, 0.5 - a/2) is at
   b = -a/2, on facet 0 (point sample). Curvature at the vertex:
   |B' x B''|/|B'|^3 = |(0.4,0) x (0,-2.4)| / 0.4^3 = 0.96/0.064 = 15; a
   footprint spanning 0.1 along it has sagitta 15*0.05²/2 = 0.019 against a
   width 0.02: oversampling (tol 0.05) splits it in ceil(sqrt(0.019/0.001))
   = 5. */
static void curved_path_local_frame_and_oversampling(void)
{
#ifndef GR_NO_CURVES
    const double a = 0.01, sec[6] = {-a, 0, 0, -a, a, 0}, quad[6] = {0.3, 0.2, 0.5, 0.8, 0.7, 0.2};
    gr_groove_desc_t g = groove(quad, 3, sec, 3);
    gr_grid_t *grid;
    gr_query_t q = gt_query(0.5, 0.5 - a / 2, 0, 0, 0, 1);
    gr_facet_list_t l;
    double sum = 0;
    int i;
    g.kind = GR_PATH_QUADRATIC;
    grid = build(&g, 1, 0);
    if (!grid) return;
    if (gt_run(grid, &q, &l)) {
        T_NEAR(ratio_of(&l, 0, 0), 1, 0);
        if (entry(&l, 0, 0)) {
            /* (b,w)-normal of facet 0 is (a, a)/|.|: texture (0, 1, 1)/sqrt 2 */
            T_NEAR(entry(&l, 0, 0)->normal[0], 0, 1e-9);
            T_NEAR(entry(&l, 0, 0)->normal[1], M_SQRT1_2, 1e-9);
        }
    }
    q = gt_query(0.5, 0.5, 0.0, 0, 0, 1);
    q.footprint.axis1[0] = 0.05; /* along the path */
    q.footprint.axis2[1] = 0.005;
    if (gt_run(grid, &q, &l)) {
        T_INT_EQ(l.subfootprints, 5);
        for (i = 0; i < l.count; i++) sum += l.facets[i].ratio;
        T_NEAR(sum, 1, 1e-12);
    }
    q.oversample_tol = -1;
    if (gt_run(grid, &q, &l)) T_INT_EQ(l.subfootprints, 1);
    gr_grid_free(grid);
#endif
}

/* Perturbation f(t) = t² on the straight path along +v (t = v, arc
   length). A footprint long along the groove (v in [0.3, 0.7], half-length
   h = 0.2) and r = 0.05 across, from above, sees each slope with the mean
   width a * mean(f) / 2r; mean of t² over [t0-h, t0+h] is t0² + h²/3.
   Without oversampling §4.2's constant profile gives t0² only; k midpoint
   sub-footprints give t0² + (h²/3)(1 - 1/k²) exactly. */
static double square(double t, void *u) { (void)u; return t * t; }
static void perturbation_and_oversampling_converge(void)
{
    const double a = 0.02, sec[6] = {-a, 0, 0, -a, a, 0}, t0 = 0.5, h = 0.2, r = 0.05;
    gr_groove_desc_t g = groove(VPATH, 2, sec, 3);
    gr_grid_t *grid;
    gr_facet_list_t l;
    gr_query_t q = gt_query(0.5, t0, r, 0, 0, 1);
    const double tols[3] = {-1, 0.1, 0.01};
    double exact = a * (t0 * t0 + h * h / 3) / (2 * r), prev_err = HUGE_VAL;
    int i;
    g.perturb = square;
    g.perturb_max = 1;
    grid = build(&g, 1, 0);
    if (!grid) return;
    q.footprint.axis2[1] = h;
    q.max_oversample = 64;
    for (i = 0; i < 3; i++) {
        double k, want, err;
        q.oversample_tol = tols[i];
        if (!gt_run(grid, &q, &l)) continue;
        k = l.subfootprints;
        want = a * (t0 * t0 + h * h / 3 * (1 - 1 / (k * k))) / (2 * r);
        T_NEAR(ratio_of(&l, 0, 0), want, 1e-13);
        T_NEAR(ratio_of(&l, 0, 1), want, 1e-13);
        err = fabs(ratio_of(&l, 0, 0) - exact);
        T_LE(err, a * h * h / (3 * k * k) / (2 * r) + 1e-13);
        if (i > 0) T_LT(err, prev_err);
        prev_err = err;
    }
    T_GE(l.subfootprints, 40);
    /* a constant scale 1/2 halves the section: a/2/2r per slope */
    q = gt_query(0.5, 0.25, r, 0, 0, 1);
    q.oversample_tol = -1;
    if (gt_run(grid, &q, &l)) T_NEAR(ratio_of(&l, 0, 0), a * 0.0625 / (2 * r), 1e-14);
    gr_grid_free(grid);
}

/* perturb_normals: f(s) = s on the path along +v (s = v). Facet 0 of the V
   sweeps X(s, τ) = (0.5 + s a (1-τ), s, -s D τ); dX/ds x dX/dτ =
   s (-D, a D, a): the unit normal (-D, aD, a)/|.|, at any s: the default
   (perturb_normals = 0, or 1). Negative: §4.4's (-D, 0, a)/|.|. */
static double ramp(double t, void *u) { (void)u; return t; }
static void perturbation_tilts_normals(void)
{
    const double a = 0.01, D = 0.02, sec[6] = {-a, 0, 0, -D, a, 0};
    gr_groove_desc_t g = groove(VPATH, 2, sec, 3);
    gr_grid_t *grid;
    gr_query_t q = gt_query(0.5 + a / 2 * 0.6, 0.6, 0, 0, 0, 1);
    gr_facet_list_t l;
    double n1 = sqrt(D * D + a * a * D * D + a * a), n0 = hypot(a, D);
    g.perturb = ramp;
    g.perturb_max = 1;
    int k;
    grid = build(&g, 1, 0);
    if (!grid) return;
    q.perturb_normals = -1;
    if (gt_run(grid, &q, &l) && T_CHECK(entry(&l, 0, 0) != NULL)) {
        T_NEAR(entry(&l, 0, 0)->normal[0], -D / n0, 1e-14);
        T_NEAR(entry(&l, 0, 0)->normal[1], 0, 0);
    }
    for (k = 0; k < 2; k++) {
        q.perturb_normals = k;
        if (gt_run(grid, &q, &l) && T_CHECK(entry(&l, 0, 0) != NULL)) {
            T_NEAR(entry(&l, 0, 0)->normal[0], -D / n1, 1e-9);
            T_NEAR(entry(&l, 0, 0)->normal[1], a * D / n1, 1e-9);
            T_NEAR(entry(&l, 0, 0)->normal[2], a / n1, 1e-9);
            T_NEAR(entry(&l, 0, 0)->ratio, 1, 0);
        }
    }
    gr_grid_free(grid);
}

/* Footprint from differentials on the plane z = 0 with dp/du = (2,0,0),
   dp/dv = (0,2,0) (2 world units per UV unit), the camera ray from
   (0,-1,1) to the origin, offset rays shifted by (0.01, 0, 0) and
   (0, 0, 0.01) at the origin: they meet the plane at (0.01, 0, 0) and
   (0, 0.01, 0), i.e. (du, dv) = (0.005, 0) and (0, 0.005); times the
   default radius 0.5: A1 = (0.0025, 0), A2 = (0, 0.0025). E = -dir
   normalised = (0, -1, 1)/sqrt 2. A sheared parameterisation dp/dv =
   (1,1,0): the point (0.3, 0.2, 0) = u dp/du + v dp/dv gives v = 0.2,
   u = 0.05 (least squares is exact in the plane). */
static void footprint_from_differentials_closed_form(void)
{
    gr_differentials_t rd;
    gr_footprint_t fp;
    gr_frame_t fr;
    double down[3] = {0, -1, 0}, tex[3];
    memset(&rd, 0, sizeof rd);
    rd.n[2] = 3;
    rd.dpdu[0] = 2;
    rd.dpdv[1] = 2;
    rd.uv[0] = 0.25; rd.uv[1] = 0.75;
    rd.dir[1] = 1; rd.dir[2] = -1;
    rd.rx_origin[0] = 0.01; rd.rx_origin[1] = -1; rd.rx_origin[2] = 1;
    rd.rx_dir[1] = 1; rd.rx_dir[2] = -1;
    rd.ry_origin[1] = -1; rd.ry_origin[2] = 1.01;
    rd.ry_dir[1] = 1; rd.ry_dir[2] = -1;
    if (!T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, &fr), GR_OK)) return;
    T_NEAR(fp.center[0], 0.25, 0);
    T_NEAR(fp.center[1], 0.75, 0);
    T_NEAR(fp.axis1[0], 0.0025, 1e-15);
    T_NEAR(fp.axis1[1], 0, 1e-15);
    T_NEAR(fp.axis2[0], 0, 1e-15);
    T_NEAR(fp.axis2[1], 0.0025, 1e-15);
    T_NEAR(fp.view[0], 0, 1e-15);
    T_NEAR(fp.view[1], -M_SQRT1_2, 1e-15);
    T_NEAR(fp.view[2], M_SQRT1_2, 1e-15);
    /* an offset ray parallel to the plane: zero axis (line footprint) */
    rd.ry_dir[2] = 0;
    if (T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, NULL), GR_OK)) {
        T_NEAR(fp.axis2[0], 0, 0);
        T_NEAR(fp.axis2[1], 0, 0);
    }
    /* sheared parameterisation, straight-down rays */
    memset(&rd, 0, sizeof rd);
    rd.n[2] = 1;
    rd.dpdu[0] = 1;
    rd.dpdv[0] = 1; rd.dpdv[1] = 1;
    rd.dir[2] = -1;
    rd.rx_origin[0] = 0.3; rd.rx_origin[1] = 0.2; rd.rx_origin[2] = 5;
    rd.rx_dir[2] = -1;
    rd.ry_dir[2] = -1;
    rd.filter_radius = 1;
    if (T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, &fr), GR_OK)) {
        T_NEAR(fp.axis1[0], 0.1, 1e-15);
        T_NEAR(fp.axis1[1], 0.2, 1e-15);
    }
    /* a left-handed parameterisation: tv follows dp/dv */
    rd.dpdv[0] = 0; rd.dpdv[1] = -1;
    if (T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, &fr), GR_OK)) {
        T_CHECK(gr_frame_to_texture(&fr, down, tex));
        T_NEAR(tex[1], 1, 1e-15);
    }
}

/* A short scratch wholly inside the interior cells of a big footprint box
   is not on the box's boundary cells (§4.1 visits only those); the
   interior anchor lists must still find it. 16x16 cells, scratch from
   (0.5, 0.5) to (0.52, 0.5), footprint r = 0.2 around it: boundary cells
   are columns/rows 4 and 11, the scratch sits in cell (8, 8). */
static void short_groove_inside_large_footprint(void)
{
    const double a = 0.001, sec[6] = {-a, 0, 0, -a, a, 0}, p[4] = {0.5, 0.5, 0.52, 0.5};
    gr_groove_desc_t g = groove(p, 2, sec, 3);
    gr_grid_t *grid = build(&g, 1, 16);
    gr_query_t q = gt_query(0.505, 0.5, 0.2, 0, 0, 1);
    gr_facet_list_t l;
    if (!grid || !gt_run(grid, &q, &l)) return;
    T_INT_EQ(l.grooves, 1);
    T_CHECK(l.flags & GR_LIST_POLYGON); /* its ends take the polygon path (§5) */
    gr_grid_free(grid);
}

/* A groove crossing the nearest one at right angles inside the footprint
   is an intersection (issue 8): the polygon path answers it with both
   grooves. Asked for line samples (not there yet), §4 flags it and uses
   only the nearest groove's parallel family (the one at u = 0.5 through F). */
static void nonparallel_groove_flagged(void)
{
    const double a = 0.01, sec[6] = {-a, 0, 0, -a, a, 0}, across[4] = {0, 0.53, 1, 0.53};
    gr_groove_desc_t g[2];
    gr_grid_t *grid;
    gr_query_t q = gt_query(0.5, 0.5, 0.05, 0, 0, 1);
    gr_facet_list_t l;
    g[0] = groove(VPATH, 2, sec, 3);
    g[1] = groove(across, 2, sec, 3);
    grid = build(g, 2, 0);
    if (!grid || !gt_run(grid, &q, &l)) return;
    T_CHECK(l.flags & GR_LIST_POLYGON);
    T_INT_EQ(l.grooves, 2);
    q.line_samples = 2; /* §5.6: the crossing goes to gr_query_lines() */
    if (!gt_run(grid, &q, &l)) return;
    T_CHECK(l.flags & GR_LIST_NONPARALLEL);
    T_INT_EQ(l.grooves, 2);
    T_NEAR(gt_ratio_sum(&l), 1, 1e-12);
    gr_grid_free(grid);
}

/* gr_shade with a Lambert BRDF (rgb = N.L per unit light): light and view
   straight above a V (a, D): Σ r_i lit_i N_i.L = (1 - a/r) + 2 (a/2r)(a/len),
   len = sqrt(a² + D²). */
static void lambert(void *user, int refl, const double n[3], const double e[3], const double l[3], int k, double rgb[3])
{
    double c = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
    (void)user; (void)refl; (void)e; (void)k;
    rgb[0] = rgb[1] = rgb[2] = c > 0 ? c : 0;
}
static void shade_with_brdf_callback(void)
{
    const double a = 0.01, D = 0.02, r = 0.05, sec[6] = {-a, 0, 0, -D, a, 0}, light[3] = {0, 0, 1};
    gr_groove_desc_t g = groove(VPATH, 2, sec, 3);
    gr_grid_t *grid = build(&g, 1, 0);
    gr_query_t q = gt_query(0.5, 0.5, r, 0, 0, 1);
    size_t need;
    void *scratch;
    double rgb[3];
    if (!grid) return;
    q.lights = light;
    q.light_count = 1;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    T_INT_EQ(gr_shade(grid, &q, scratch, need, lambert, NULL, rgb), GR_OK);
    T_NEAR(rgb[1], (1 - a / r) + (a / r) * (a / hypot(a, D)), 1e-14);
    T_INT_EQ(gr_shade(grid, &q, scratch, need, NULL, NULL, rgb), GR_ERR_INVALID_ARG);
    free(scratch);
    gr_grid_free(grid);
}

/* Many threads query one grid at once (const, allocation-free): each gets
   bit-identical lists to the serial run. */
typedef struct job_t {
    const gr_grid_t *grid;
    int seed, n, mismatches;
} job_t;
static gr_query_t job_query(t_rng_t *rng)
{
    double th = t_rng_range(rng, 0, 1.4), az = t_rng_range(rng, 0, 6.283);
    return gt_query(t_rng_unit(rng), t_rng_unit(rng), t_rng_range(rng, 0, 0.02), sin(th) * cos(az), sin(th) * sin(az), cos(th));
}
static void *job(void *arg)
{
    job_t *j = (job_t *)arg;
    t_rng_t rng;
    size_t need = gr_query_scratch_bytes(j->grid);
    void *scratch = malloc(need);
    int i;
    rng.s = 7;
    for (i = 0; i < j->n; i++) {
        gr_query_t q = job_query(&rng);
        gr_facet_list_t a, b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        gr_query(j->grid, &q, scratch, need, &a);
        gr_query(j->grid, &q, scratch, need, &b);
        if (memcmp(&a, &b, sizeof a) != 0) j->mismatches++;
    }
    free(scratch);
    return NULL;
}
static void many_threads_one_grid(void)
{
    const double a = 0.004, sec[8] = {-a, 0, 0, -a, a * 0.5, a * 0.3, a, 0};
    enum { NG = 60, NT = 4 };
    gr_groove_desc_t g[NG];
    double pts[NG][4];
    gr_grid_t *grid;
    pthread_t th[NT];
    job_t jobs[NT];
    t_rng_t rng = {3};
    int i;
    for (i = 0; i < NG; i++) {
        pts[i][0] = t_rng_unit(&rng); pts[i][1] = t_rng_unit(&rng);
        pts[i][2] = pts[i][0] + 0.3; pts[i][3] = pts[i][1] + 0.1 * (i % 3);
        g[i] = groove(pts[i], 2, sec, 4);
    }
    grid = build(g, NG, 0);
    if (!grid) return;
    for (i = 0; i < NT; i++) {
        jobs[i].grid = grid;
        jobs[i].n = (int)t_count(2000);
        jobs[i].mismatches = 0;
        pthread_create(&th[i], NULL, job, &jobs[i]);
    }
    for (i = 0; i < NT; i++) {
        pthread_join(th[i], NULL);
        T_INT_EQ(jobs[i].mismatches, 0);
    }
    /* and every list has ratios summing to 1 */
    {
        t_rng_t r2 = {7};
        long k, n = t_count(2000);
        double worst = 0;
        for (k = 0; k < n; k++) {
            gr_query_t q = job_query(&r2);
            gr_facet_list_t l;
            double s = 0;
            int e;
            if (!gt_run(grid, &q, &l)) break;
            for (e = 0; e < l.count; e++) {
                s += l.facets[e].ratio;
                if (l.facets[e].ratio < 0 || l.facets[e].ratio > 1 + 1e-12) T_FAIL("ratio %g", l.facets[e].ratio);
            }
            if (fabs(s - 1) > worst) worst = fabs(s - 1);
        }
        T_LE(worst, 1e-9);
    }
    gr_grid_free(grid);
}


/* Invariants on random input (no oracle needed): random sections (repeated
   points, vertical walls, peaks and cuts), random paths of every kind,
   random footprints (including zero axes), views and lights (including
   below the horizon). Every list must have ratios in [0, 1] summing to 1
   (to 1e-9: the sum of |S|-normalised clipped lengths on §4's path, of
   area ratios on the polygon path, which answers the footprints with
   crossings and ends, peaks or not), lit fractions in [0, 1], unit
   normals, and no NaN. */
static void random_scenes_keep_invariants(void)
{
    t_rng_t rng = {2026};
    long scene, scenes = t_count(60), answered = 0, polygon = 0;
    double worst = 0;
    for (scene = 0; scene < scenes; scene++) {
        enum { NG = 12 };
        gr_groove_desc_t g[NG];
        double pts[NG][8], sec[NG][12];
        gr_grid_t *grid;
        int i, k, ns;
        long qn, queries = t_count(300);
        for (i = 0; i < NG; i++) {
            double hw = t_rng_range(&rng, 0.001, 0.03);
            ns = 2 + (int)(t_rng_unit(&rng) * 5);
            sec[i][0] = -hw; sec[i][1] = 0;
            for (k = 1; k < ns - 1; k++) {
                double u = t_rng_unit(&rng);
                sec[i][2 * k] = u < 0.2 ? sec[i][2 * k - 2] : sec[i][2 * k - 2] + t_rng_range(&rng, 0, 2 * hw / ns);
                sec[i][2 * k + 1] = u < 0.1 ? sec[i][2 * k - 1] : t_rng_range(&rng, -hw, 0.5 * hw);
            }
            sec[i][2 * ns - 2] = hw; sec[i][2 * ns - 1] = 0;
            for (k = 0; k < 8; k++) pts[i][k] = t_rng_unit(&rng);
            g[i] = groove(pts[i], 2, sec[i], ns);
#ifndef GR_NO_CURVES
            if (i % 3 == 1) { g[i].kind = GR_PATH_QUADRATIC; g[i].point_count = 3; }
            if (i % 3 == 2) { g[i].kind = GR_PATH_CUBIC; g[i].point_count = 4; }
#endif
            if (i % 4 == 0) { g[i].perturb = square; g[i].perturb_max = 1; }
        }
        grid = build(g, NG, (int)(t_rng_unit(&rng) * 20));
        if (!grid) continue;
        for (qn = 0; qn < queries; qn++) {
            double th = t_rng_range(&rng, 0, 1.5707), az = t_rng_range(&rng, 0, 6.2832), r = t_rng_range(&rng, 0, 0.05);
            double lights[6];
            gr_query_t q = gt_query(t_rng_range(&rng, -1, 2), t_rng_range(&rng, -1, 2), r, sin(th) * cos(az), sin(th) * sin(az), cos(th));
            gr_facet_list_t l;
            double sum = 0;
            if (t_rng_unit(&rng) < 0.2) q.footprint.axis2[1] = 0;
            if (t_rng_unit(&rng) < 0.1) q.footprint.axis1[0] = 0;
            if (t_rng_unit(&rng) < 0.5) { /* oblique axes: the trapezoid weighting */
                double ang = t_rng_range(&rng, 0, 3.1416);
                q.footprint.axis1[1] = q.footprint.axis1[0] * sin(ang);
                q.footprint.axis1[0] *= cos(ang);
                q.footprint.axis2[0] = -q.footprint.axis2[1] * sin(ang) * t_rng_range(&rng, 0, 2);
            }
            for (k = 0; k < 2; k++) {
                double lt = t_rng_range(&rng, 0, 1.8), la = t_rng_range(&rng, 0, 6.2832);
                lights[3 * k] = sin(lt) * cos(la); lights[3 * k + 1] = sin(lt) * sin(la); lights[3 * k + 2] = cos(lt);
            }
            q.lights = lights;
            q.light_count = 2;
            q.perturb_normals = (qn & 1) ? -1 : 0;
            q.ellipse = qn % 3 == 0;
            if (!gt_run(grid, &q, &l)) break;
            if (l.flags & GR_LIST_BELOW_HORIZON) continue;
            answered++;
            if (l.flags & GR_LIST_POLYGON) polygon++;
            for (i = 0; i < l.count; i++) {
                const gr_facet_t *f = &l.facets[i];
                double nn = sqrt(f->normal[0] * f->normal[0] + f->normal[1] * f->normal[1] + f->normal[2] * f->normal[2]);
                sum += f->ratio;
                if (!(f->ratio > 0 && f->ratio <= 1 + 1e-12) || !(fabs(nn - 1) < 1e-9) || !(f->lit[0] >= 0 && f->lit[0] <= 1) ||
                    !(f->lit[1] >= 0 && f->lit[1] <= 1))
                    T_FAIL("scene %ld query %ld entry %d: ratio %g |n| %g lit %g %g", scene, qn, i, f->ratio, nn, f->lit[0], f->lit[1]);
            }
            if (!(fabs(sum - 1) <= worst)) worst = fabs(sum - 1);
            if (!(fabs(sum - 1) <= 1e-9)) T_FAIL("scene %ld query %ld: ratios sum to %.17g", scene, qn, sum);
        }
        gr_grid_free(grid);
    }
    T_LE(worst, 1e-9);
    /* the polygon path took its share (about half of these footprints
       meet a crossing or an end), so the bound above covers it */
#ifndef GR_NO_INTERSECTIONS
    if (answered >= 1000) T_CHECK(polygon > answered / 4);
#endif
    fprintf(stderr, "    %ld footprints, %ld on the polygon path, worst |sum - 1| = %.1e\n", answered, polygon, worst);
}

/* §4.1: only the boundary cells of the enlarged footprint box are read,
   2m + 2(n - 2) of an m x n box (m, n >= 2; a one-cell-wide box reads its
   m n cells once each), and the box grows by h tan θ toward the viewer only
   when something protrudes (issue 7 items 2 and 6). A 20 x 20 grid, one
   short groove far from the footprints (no anchors inside the box); the
   count is read from the query's scratch (gr__gather's private counter). */
static int cells_read(const gr_grid_t *grid, const gr_query_t *q)
{
    size_t need = gr_query_scratch_bytes(grid);
    void *scratch = malloc(need);
    gr_facet_list_t l;
    gr__scratch_t s;
    int v = -1;
    if (T_INT_EQ(gr_query(grid, q, scratch, need, &l), GR_OK)) {
        gr__scratch_layout(grid, scratch, &s);
        v = *s.visited;
    }
    free(scratch);
    return v;
}
static int box_cells(double lo, double hi) { return (int)floor(hi * 20) - (int)floor(lo * 20) + 1; }
static void boundary_cells_visited(void)
{
    const double a = 0.01, vsec[6] = {-a, 0, 0, -a, a, 0}, ridge[6] = {-a, 0, 0, 2 * a, a, 0};
    const double pts[4] = {0.02, 0.02, 0.03, 0.02};
    static const double sizes[4][2] = {{0.1, 0.1}, {0.2, 0.07}, {0.003, 0.3}, {0.001, 0.001}};
    gr_groove_desc_t g = groove(pts, 2, vsec, 3);
    gr_grid_t *cut, *raised;
    int i;
    cut = build(&g, 1, 20);
    g.section = ridge;
    raised = build(&g, 1, 20);
    if (!cut || !raised) return;
    T_NEAR(cut->h, 0, 0);
    T_NEAR(raised->h, 2 * a, 1e-15);
    for (i = 0; i < 4; i++) {
        gr_query_t q = gt_query(0.5, 0.5, 0, 0, 0, 1);
        double ru = sizes[i][0], rv = sizes[i][1], tan_e = 10, ext;
        int m, n, want;
        q.footprint.axis1[0] = ru;
        q.footprint.axis2[1] = rv;
        m = box_cells(0.5 - ru - a, 0.5 + ru + a);
        n = box_cells(0.5 - rv - a, 0.5 + rv + a);
        want = m >= 2 && n >= 2 ? 2 * m + 2 * (n - 2) : m * n;
        T_INT_EQ(cells_read(cut, &q), want);
        T_INT_EQ(cells_read(raised, &q), want); /* from above: no h tan θ */
        /* grazing toward +u (tan θ = 10): the cut grid's box stays, the
           raised one grows by h tan θ = 0.2 toward the viewer */
        q.footprint.view[0] = tan_e / sqrt(1 + tan_e * tan_e);
        q.footprint.view[2] = 1 / sqrt(1 + tan_e * tan_e);
        T_INT_EQ(cells_read(cut, &q), want);
        ext = raised->h * tan_e;
        m = box_cells(0.5 - ru - a, 0.5 + ru + a + ext);
        T_INT_EQ(cells_read(raised, &q), m >= 2 && n >= 2 ? 2 * m + 2 * (n - 2) : m * n);
    }
    gr_grid_free(cut);
    gr_grid_free(raised);
}

/* gr__sort, which the builder and the queries use instead of libc's qsort
   (glibc's mallocs a buffer from 1 KiB): equal to a reference order (the
   key, then the original position, so stable) on 3 000 random arrays of
   up to 700 elements with many equal keys, elements of 28 bytes (the 4 KiB
   merge buffer) and of 260 (the rotations past it). */
typedef struct sort_el_t { int key, pos; unsigned char pad[20]; } sort_el_t;
typedef struct sort_big_t { int key, pos; unsigned char pad[252]; } sort_big_t;
static int sort_by_key(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}
static int sort_by_key_pos(const void *a, const void *b)
{
    const int *x = (const int *)a, *y = (const int *)b;
    return x[0] != y[0] ? (x[0] > y[0]) - (x[0] < y[0]) : (x[1] > y[1]) - (x[1] < y[1]);
}
static void sort_is_stable_in_place(void)
{
    t_rng_t r = {700};
    long trial, m = t_count(3000);
    for (trial = 0; trial < m; trial++) {
        int big = trial % 4 == 3, n = (int)(t_rng_u64(&r) % (big ? 200 : 700)), range = 1 + (int)(t_rng_u64(&r) % 50), i;
        size_t sz = big ? sizeof(sort_big_t) : sizeof(sort_el_t);
        unsigned char *a = (unsigned char *)malloc(sz * (size_t)(n + 1)), *b = (unsigned char *)malloc(sz * (size_t)(n + 1));
        for (i = 0; i < n; i++) {
            int kp[2];
            kp[0] = (int)(t_rng_u64(&r) % (unsigned)range), kp[1] = i;
            memset(a + sz * (size_t)i, i & 255, sz);
            memcpy(a + sz * (size_t)i, kp, sizeof kp);
        }
        memcpy(b, a, sz * (size_t)n);
        gr__sort(a, (size_t)n, sz, sort_by_key);
        qsort(b, (size_t)n, sz, sort_by_key_pos);
        if (!T_CHECK(memcmp(a, b, sz * (size_t)n) == 0)) trial = m;
        free(a), free(b);
    }
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(bounds_and_blockers),
        T_CASE(parallel_grooves_and_mirrored_path),
        T_CASE(facet_list_overflow_folds_into_equal_normals),
        T_CASE(asymmetric_section_backward_path),
        T_CASE(protruding_ridge_shadows_ground),
        T_CASE(straight_beziers_match_segment),
        T_CASE(curved_path_local_frame_and_oversampling),
        T_CASE(boundary_cells_visited),
        T_CASE(perturbation_and_oversampling_converge),
        T_CASE(perturbation_tilts_normals),
        T_CASE(footprint_from_differentials_closed_form),
        T_CASE(short_groove_inside_large_footprint),
        T_CASE(nonparallel_groove_flagged),
        T_CASE(shade_with_brdf_callback),
        T_CASE(many_threads_one_grid),
        T_CASE(random_scenes_keep_invariants),
        T_CASE(sort_is_stable_in_place),
    };
    return T_RUN(argc, argv, cases);
}
