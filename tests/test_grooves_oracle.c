/* grooves.h against the geometry oracle (tests/grooves_oracle.h): the same
   grooves swept into an Embree mesh and supersampled with n×n stratified
   primary rays and one shadow ray per light and sample.

   What is compared: for every facet entry grooves.h returns, its ratio r_i
   and its lit share r_i·lit_ik of the footprint, against the oracle's
   fractions summed over the facets with the same texture-space normal and
   reflectance id (grooves.h merges those). Every facet the oracle sees over
   more than the tolerance must be in the list.

   Oracle error: n = 256 gives a standard deviation of at most
   sqrt(B/(2 n^3)) per fraction, B the number of strip boundaries in the
   footprint (tests/grooves_oracle.h): <= 6.8e-4 for B <= 8 (one or a few
   grooves), so 1e-2 is over 14 sigma; the micro-groove case uses n = 1024
   for B ≈ 2000 (sigma <= 1e-3). Mesh error: chord tolerance 1e-4 of the
   groove width, negligible.

   Footprints: one axis along the groove (A2 ∥ T) unless a case says
   otherwise; footprint_oblique_axes turns both axes away from it (the
   footprint's trapezoid density across the groove, same 1e-2 bar). */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "test.h"
#include "grooves_oracle.h"
#include "grooves_test_util.h"

#define TOL 1e-2
#define MAXG 2100

static gro_device_t dev;

typedef struct scene_t {
    gr_groove_desc_t desc[MAXG];
    gro_groove_t geo[MAXG];
    int n;
    int no_wrap;
    gr_grid_t *grid;
} scene_t;

static scene_t S; /* large: static, one scene at a time */

static double worst_ratio, worst_lit; /* largest errors seen, printed per case */
/* query settings compare_tol() passes on (0: defaults) */
static int q_straight;
static double q_oversample_tol;
static int q_max_oversample;
/* 1: match oracle facets to entries by (groove, facet) rather than by
   normal (one groove whose facets' normals turn and tilt far along it) */
static int q_match_ids;

static void scene_begin(void) { memset(&S, 0, sizeof S); }

static void scene_add(gr_path_kind_t kind, const double *pts, int npts, const double *sec, int nsec)
{
    gr_groove_desc_t *d = &S.desc[S.n];
    d->kind = kind; d->points = pts; d->point_count = npts;
    d->section = sec; d->section_count = nsec;
    S.n++;
}

static int scene_build(void)
{
    gr_grid_desc_t gd;
    gr_diag_t diag;
    int i;
    memset(&gd, 0, sizeof gd);
    gd.grooves = S.desc; gd.groove_count = S.n; gd.no_wrap = S.no_wrap;
    for (i = 0; i < S.n; i++) S.geo[i] = gro_from_gr(&S.desc[i]);
    if (gr_grid_build(&gd, &S.grid, &diag) != GR_OK) { T_FAIL("grid build: %s", diag.message); return 0; }
    return 1;
}

static void scene_end(void)
{
    gr_grid_free(S.grid);
    S.grid = NULL;
}

/* Unit tangent of groove g at the path point nearest to (u, v), over the
   wrapped copies (dense sampling; only used to label the oracle's facets). */
static double tangent_cache[MAXG][2];
static char tangent_known[MAXG]; /* cleared per footprint by compare_tol() */
static void tangent_near(int g, double u, double v, double *T)
{
    const gro_groove_t *geo = &S.geo[g];
    double best = INFINITY, bt = 0, p[2], a[2], b[2], l;
    int i, du, dv, w = S.no_wrap ? 0 : 1;
    if (tangent_known[g]) { T[0] = tangent_cache[g][0]; T[1] = tangent_cache[g][1]; return; }
    for (i = 0; i <= 4096; i++)
        for (du = -w; du <= w; du++)
            for (dv = -w; dv <= w; dv++) {
                double d2;
                gro__path_point(geo, i / 4096.0, p);
                d2 = (p[0] + du - u) * (p[0] + du - u) + (p[1] + dv - v) * (p[1] + dv - v);
                if (d2 < best) { best = d2; bt = i / 4096.0; }
            }
    gro__path_point(geo, fmax(0, bt - 1e-6), a);
    gro__path_point(geo, fmin(1, bt + 1e-6), b);
    T[0] = b[0] - a[0]; T[1] = b[1] - a[1];
    l = hypot(T[0], T[1]);
    T[0] /= l; T[1] /= l;
    tangent_cache[g][0] = T[0]; tangent_cache[g][1] = T[1];
    tangent_known[g] = 1;
}

/* Texture-space outward normal of facet k of groove g near (u, v): the
   section normal (-dw, db) turned into (B, W) with B = (-T_v, T_u). */
static void facet_normal(int g, int k, double u, double v, double *n)
{
    const double *c = S.desc[g].section + 2 * k;
    double db = c[2] - c[0], dw = c[3] - c[1], l = hypot(db, dw), T[2];
    tangent_near(g, u, v, T);
    n[0] = -dw / l * -T[1]; n[1] = -dw / l * T[0]; n[2] = db / l;
}

static int refl_of(int g, int k)
{
    return S.desc[g].facet_reflectance ? S.desc[g].facet_reflectance[k] : S.desc[g].reflectance;
}

/* The oracle on one footprint of the scene S (n x n rays, fixed seed);
   0, or -1 after a failed check. */
static int oracle_run(const gr_footprint_t *fp, const double *lights, int nl, int n, gro_result_t *o)
{
    gro_query_t oq;
    memset(&oq, 0, sizeof oq);
    oq.grooves = S.geo; oq.ngrooves = S.n; oq.wrap = !S.no_wrap;
    memcpy(oq.F, fp->center, sizeof oq.F);
    memcpy(oq.A1, fp->axis1, sizeof oq.A1);
    memcpy(oq.A2, fp->axis2, sizeof oq.A2);
    memcpy(oq.E, fp->view, sizeof oq.E);
    oq.lights = lights; oq.nlights = nl; oq.n = n; oq.seed = 12345;
    if (gro_query(&oq, dev.dev, o)) { T_FAIL("oracle failed"); return -1; }
    return 0;
}

/* Point P and unit tangent T of groove 0 of S at path parameter t. */
static void path_frame(double t, double *P, double *T)
{
    double a[2], b[2], l;
    gro__path_point(&S.geo[0], t, P);
    gro__path_point(&S.geo[0], t - 1e-6, a);
    gro__path_point(&S.geo[0], t + 1e-6, b);
    T[0] = b[0] - a[0]; T[1] = b[1] - a[1]; l = hypot(T[0], T[1]); T[0] /= l; T[1] /= l;
}

/* Least cosine between a facet's normal at the footprint centre and the
   entry it is compared with (0.3 rad: a tight bend's turn under a view). */
#define MATCH_COS 0.955

/* Runs both on one footprint and compares; returns the largest ratio error. */
static double compare_tol(const gr_footprint_t *fp, const double *lights, int nl, int n, double tol)
{
    static unsigned char scratch[1 << 22];
    gr_query_t q;
    gr_facet_list_t list;
    gro_result_t o;
    int i, g, k, l;
    double worst = 0, sum = 0;
    static char used[MAXG][GRO_MAX_FACETS];
    static int owner[MAXG][GRO_MAX_FACETS];
    int ground_used = 0;
    memset(&q, 0, sizeof q);
    q.footprint = *fp; q.lights = lights; q.light_count = nl;
    q.straight_occlusion = q_straight;
    q.oversample_tol = q_oversample_tol;
    q.max_oversample = q_max_oversample;
    if (gr_query_scratch_bytes(S.grid) > sizeof scratch) { T_FAIL("scratch too small"); return 1; }
    if (!T_INT_EQ(gr_query(S.grid, &q, scratch, sizeof scratch, &list), GR_OK)) return 1;
    if (oracle_run(fp, lights, nl, n, &o)) return 1;
    T_LE(o.miss, 1e-4);
    memset(used, 0, sizeof used);
    memset(tangent_known, 0, sizeof tangent_known);
    /* each oracle facet goes to the entry of its reflectance id whose normal
       is nearest its own at the footprint centre (equal normals for straight
       grooves, which grooves.h merges; along a curved path grooves.h turns a
       facet's normal to where the view ray meets it, within MATCH_COS) */
    for (g = 0; g < S.n; g++)
        for (k = 0; k + 1 < S.desc[g].section_count; k++) {
            double nn[3], bestd = MATCH_COS;
            owner[g][k] = -1;
            if (gro_vis(&o, g, k) == 0 && (nl == 0 || gro_lit(&o, 0, g, k) == 0)) continue;
            facet_normal(g, k, fp->center[0], fp->center[1], nn);
            if (q_match_ids) {
                for (i = 0; i < list.count; i++)
                    if (list.facets[i].groove == g && list.facets[i].facet == k) owner[g][k] = i;
                continue;
            }
            for (i = 0; i < list.count; i++) {
                const double *m = list.facets[i].normal;
                double dd = nn[0] * m[0] + nn[1] * m[1] + nn[2] * m[2];
                if (list.facets[i].reflectance == refl_of(g, k) && dd > bestd) { bestd = dd; owner[g][k] = i; }
            }
        }
    for (i = 0; i < list.count; i++) {
        const gr_facet_t *e = &list.facets[i];
        double vis = 0, lit[GRO_MAX_LIGHTS] = {0};
        if (e->normal[2] > 1 - 1e-9 && e->reflectance == 0) { /* ground (base id 0) and flat floors */
            vis += o.ground_vis;
            for (l = 0; l < nl; l++) lit[l] += o.ground_lit[l];
            ground_used = 1;
        }
        for (g = 0; g < S.n; g++)
            for (k = 0; k + 1 < S.desc[g].section_count; k++) {
                if (owner[g][k] != i) continue;
                used[g][k] = 1;
                vis += gro_vis(&o, g, k);
                for (l = 0; l < nl; l++) lit[l] += gro_lit(&o, l, g, k);
            }
        if (!T_NEAR(e->ratio, vis, tol))
            fprintf(stderr, "    entry %d (groove %d facet %d, n = %.3f %.3f %.3f)\n", i, e->groove, e->facet,
                    e->normal[0], e->normal[1], e->normal[2]);
        worst = fmax(worst, fabs(e->ratio - vis));
        for (l = 0; l < nl; l++) {
            T_NEAR(e->ratio * e->lit[l], lit[l], tol);
            worst_lit = fmax(worst_lit, fabs(e->ratio * e->lit[l] - lit[l]));
        }
        sum += e->ratio;
    }
    T_NEAR(sum, 1, 1e-9);
    if (!ground_used) T_LE(o.ground_vis, tol);
    for (g = 0; g < S.n; g++)
        for (k = 0; k + 1 < S.desc[g].section_count; k++)
            if (!used[g][k] && gro_vis(&o, g, k) > tol)
                T_FAIL("oracle sees groove %d facet %d over %.4f of the footprint; grooves.h lists no such facet", g,
                       k, gro_vis(&o, g, k));
    gro_result_free(&o);
    worst_ratio = fmax(worst_ratio, worst);
    return worst;
}

/* One footprint checked twice: with the curved model within tol, then with
   §4.3's straight occlusion (q_straight) within tol_straight on n_straight²
   rays. acc[0..3] keep the largest errors: ratio and lit of the first,
   ratio and lit of the second. */
static void compare_curved_and_straight(const gr_footprint_t *f, const double *L, double tol, int n_straight,
                                        double tol_straight, double acc[4])
{
    worst_lit = 0;
    acc[0] = fmax(acc[0], compare_tol(f, L, 1, 256, tol));
    acc[1] = fmax(acc[1], worst_lit);
    q_straight = 1;
    worst_lit = 0;
    acc[2] = fmax(acc[2], compare_tol(f, L, 1, n_straight, tol_straight));
    acc[3] = fmax(acc[3], worst_lit);
    q_straight = 0;
}

static double compare(const gr_footprint_t *fp, const double *lights, int nl, int n)
{
    return compare_tol(fp, lights, nl, n, TOL);
}

/* E or L from elevation above the surface and azimuth, degrees */
static void dir_deg(double elev, double azim, double *d)
{
    double e = elev * M_PI / 180, a = azim * M_PI / 180;
    d[0] = cos(e) * cos(a); d[1] = cos(e) * sin(a); d[2] = sin(e);
}

/* Footprint centred at (u, v), half-extent `across` along B and `along` along T. */
static gr_footprint_t footprint(double u, double v, const double *T, double across, double along, double view_deg,
                                double azim)
{
    gr_footprint_t f;
    memset(&f, 0, sizeof f);
    f.center[0] = u; f.center[1] = v;
    f.axis1[0] = -T[1] * across; f.axis1[1] = T[0] * across;
    f.axis2[0] = T[0] * along; f.axis2[1] = T[1] * along;
    dir_deg(90 - view_deg, azim, f.view);
    return f;
}

static void report(const char *what)
{
    fprintf(stderr, "    %s: max |r_i - oracle| = %.2e, max |r_i lit - oracle| = %.2e\n", what, worst_ratio,
            worst_lit);
    worst_ratio = worst_lit = 0;
}

static const double V_SEC[6] = {-0.01, 0, 0, -0.012, 0.01, 0};
static const double VERTICAL[6] = {0, 1}; /* T of the grooves along v */

/* One V-groove; views 0°..85° at six azimuths, two lights per view at
   elevations 10°..85°, footprints from a third to twice the groove width,
   offset so they straddle rims. */
static void isolated_groove_all_views(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double views[] = {0, 15, 30, 45, 60, 70, 80, 85};
    static const double azims[] = {0, 35, 90, 150, 200, 290};
    static const double elev[] = {10, 30, 60, 85};
    int i, j, step = t_scale() < 1 ? 3 : 1;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 8; i += step)
        for (j = 0; j < 6; j += step) {
            double L[6], size = 0.004 + 0.004 * ((i + j) % 5), off = 0.006 * ((i * 7 + j * 3) % 5 - 2) / 2.0;
            gr_footprint_t f = footprint(0.5 + off, 0.5, VERTICAL, size, 0.5 * size, views[i], azims[j]);
            dir_deg(elev[(i + j) % 4], azims[(j + 2) % 6] + 10, L);
            dir_deg(elev[(i + 2 * j + 1) % 4], azims[(j + 4) % 6] - 20, L + 3);
            compare(&f, L, 2, 256);
        }
    report("isolated");
    scene_end();
}

/* n parallel V-grooves along v at u0 + spacing i, built into S. */
static int vertical_grooves(int n, double u0, double spacing)
{
    static double paths[MAXG][4];
    int i;
    scene_begin();
    for (i = 0; i < n; i++) {
        paths[i][0] = u0 + spacing * i; paths[i][1] = 0; paths[i][2] = paths[i][0]; paths[i][3] = 1;
        scene_add(GR_PATH_POLYLINE, paths[i], 2, V_SEC, 3);
    }
    return scene_build();
}

/* Twelve parallel V-grooves: spaced with ground between, and touching
   (Figure 14's profile); footprints over several grooves; views to 85°. */
static void parallel_grooves_all_views(void)
{
    static const double views[] = {0, 20, 40, 60, 75, 85};
    static const double azims[] = {0, 60, 120, 180, 250, 330};
    int i, j, layout, step = t_scale() < 1 ? 3 : 1;
    for (layout = 0; layout < 2; layout++) {
        double spacing = layout ? 0.02 : 0.035;
        if (!vertical_grooves(12, 0.3, spacing)) return;
        for (i = 0; i < 6; i += step)
            for (j = 0; j < 6; j += step) {
                double L[3], size = 0.01 + 0.02 * ((i + j) % 3);
                gr_footprint_t f = footprint(0.3 + spacing * 5.3 + 0.003 * j, 0.4, VERTICAL, size, 0.01, views[i], azims[j]);
                dir_deg(15 + 12 * ((i + j) % 6), azims[(j + 3) % 6] + 5, L);
                compare(&f, L, 1, 256);
            }
        scene_end();
    }
    report("parallel");
}

/* Protruding ridges between grooves: peaks mask and shadow neighbours far
   from their own width (eq. 1's h·tanθ enlargement). */
static void protruding_ridges_mask_neighbours(void)
{
    static const double sec[10] = {-0.01, 0, -0.004, 0.006, 0.0, -0.008, 0.004, 0.006, 0.01, 0};
    static double paths[6][4];
    static const double views[] = {30, 60, 75, 85};
    int i, j;
    scene_begin();
    for (i = 0; i < 6; i++) {
        double u = 0.4 + 0.03 * i;
        paths[i][0] = u; paths[i][1] = 0; paths[i][2] = u; paths[i][3] = 1;
        scene_add(GR_PATH_POLYLINE, paths[i], 2, sec, 5);
    }
    if (!scene_build()) return;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            double L[3];
            gr_footprint_t f = footprint(0.455 + 0.004 * j, 0.5, VERTICAL, 0.02, 0.01, views[i], j % 2 ? 0 : 180);
            dir_deg(20 + 15 * j, j % 2 ? 180 : 0, L);
            compare(&f, L, 1, 256);
        }
    report("ridges");
    scene_end();
}

/* A groove along a diagonal line, its footprint axes along its own T and B. */
static void diagonal_groove(void)
{
    static const double path[4] = {0.2, 0.3, 0.8, 0.7};
    double T[2] = {0.6, 0.4}, l = hypot(T[0], T[1]);
    int i;
    T[0] /= l; T[1] /= l;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 6; i++) {
        double L[3];
        gr_footprint_t f = footprint(0.5 + 0.002 * i * -T[1], 0.5 + 0.002 * i * T[0], T, 0.008, 0.003, 15 * i, 70 * i);
        dir_deg(25 + 10 * i, 40 * i + 100, L);
        compare(&f, L, 1, 256);
    }
    report("diagonal");
    scene_end();
}

/* Stiff: footprint 1/40 of the groove width, at many places inside it. */
static void groove_much_wider_than_footprint(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 9; i++) {
        /* straddle a boundary: the rim u = 0.5 + a (ground | facet), or the
           apex where it is seen, u = 0.5 ± D tan θ (E toward ±u) */
        double L[3], th = 10 * i * M_PI / 180, sgn = i % 2 ? 1 : -1, apex = 0.5 + sgn * 0.012 * tan(th);
        double c = (i % 2 && fabs(apex - 0.5) < 0.009) ? apex : 0.51;
        gr_footprint_t f = footprint(c + 0.0001 * (i % 3 - 1), 0.5, VERTICAL, 0.00025, 0.00025, 10 * i, i % 2 ? 0 : 180);
        dir_deg(20 + 8 * i, i % 3 ? 0 : 180, L);
        compare(&f, L, 1, 256);
    }
    report("wide groove");
    scene_end();
}

/* Stiff: a scratch 1/50 of the footprint across it. */
static void groove_much_narrower_than_footprint(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double sec[6] = {-0.0004, 0, 0, -0.0005, 0.0004, 0};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, sec, 3);
    if (!scene_build()) return;
    for (i = 0; i < 6; i++) {
        double L[3];
        gr_footprint_t f = footprint(0.5 + 0.003 * (i - 3), 0.5, VERTICAL, 0.02, 0.005, 17 * i, 45 * i);
        dir_deg(30 + 9 * i, 180 + 30 * i, L);
        compare(&f, L, 1, 256);
    }
    report("scratch");
    scene_end();
}

/* Stiff: footprints across the texture seam (u and v), grooves near both edges. */
static void footprint_across_texture_seam(void)
{
    static const double pu[4] = {0.995, 0, 0.995, 1}, pv[4] = {0, 0.004, 1, 0.004};
    static const double views[] = {0, 40, 70};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, pu, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 3; i++) {
        double L[3];
        gr_footprint_t f = footprint(0.002, 0.5, VERTICAL, 0.02, 0.01, views[i], 180 * i);
        dir_deg(40, 180 * (i + 1), L);
        compare(&f, L, 1, 256);
        f = footprint(0.999, 0.5, VERTICAL, 0.02, 0.01, views[i], 180 * i);
        compare(&f, L, 1, 256);
    }
    /* the path's ends, (0.995, 0) and (0.995, 1), meet across the v seam:
       it runs on (closed), so a footprint over the seam sees no path end */
    for (i = 0; i < 3; i++) {
        double L[3];
        gr_query_t q;
        gr_facet_list_t list;
        memset(&q, 0, sizeof q);
        q.footprint = footprint(0.997, i == 2 ? 0.0015 : 0.999, VERTICAL, 0.02, 0.01, views[i], 90 + 180 * i);
        dir_deg(40, 270 - 180 * i, L);
        q.lights = L; q.light_count = 1;
        if (gt_run(S.grid, &q, &list)) T_INT_EQ(list.flags & GR_LIST_PATH_END, 0);
        compare(&q.footprint, L, 1, 256);
    }
    scene_end();
    scene_begin();
    scene_add(GR_PATH_POLYLINE, pv, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 3; i++) {
        double L[3], T[2] = {1, 0};
        gr_footprint_t f = footprint(0.5, 0.996, T, 0.02, 0.01, views[i], 90 + 180 * i);
        dir_deg(35, 270, L);
        compare(&f, L, 1, 256);
    }
    report("seam");
    scene_end();
}

/* Stiff: a light near, at and below the horizon (lit fractions go to 0). */
static void light_near_horizon(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double elev[] = {3, 1, 0.2, 0, -5};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 5; i++) {
        double L[6];
        gr_footprint_t f = footprint(0.5, 0.5, VERTICAL, 0.02, 0.01, 30, 0);
        dir_deg(elev[i], 0, L);
        dir_deg(elev[i], 180, L + 3);
        compare(&f, L, 2, 256);
    }
    report("horizon light");
    scene_end();
}

/* Stiff: grazing views (E_w -> 0), 85° to 89°. */
static void grazing_views(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double views[] = {85, 87, 88, 89};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 4; i++) {
        double L[3];
        gr_footprint_t f = footprint(0.5 + 0.002 * i, 0.5, VERTICAL, 0.015, 0.01, views[i], i % 2 ? 0 : 160);
        dir_deg(45, 20, L);
        compare(&f, L, 1, 256);
    }
    report("grazing");
    scene_end();
}

/* Stiff: vertical facets and a zero-width facet (a repeated section point). */
static void vertical_and_zero_width_facets(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double sec[12] = {-0.01, 0, -0.01, -0.008, -0.003, -0.008, -0.003, -0.008, 0.01, -0.012, 0.01, 0};
    static const double views[] = {0, 25, 50, 75};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, sec, 6);
    if (!scene_build()) return;
    for (i = 0; i < 8; i++) {
        double L[3];
        gr_footprint_t f = footprint(0.5 + 0.001 * (i - 4), 0.5, VERTICAL, 0.012, 0.01, views[i % 4], i < 4 ? 0 : 180);
        dir_deg(30 + 7 * i, i % 2 ? 180 : 0, L);
        compare(&f, L, 1, 256);
    }
    report("vertical/zero-width");
    scene_end();
}

/* Stiff: degenerate footprints. A line (A2 = 0) across the groove, and
   along it; a point (A1 = A2 = 0), where every oracle ray is the same ray
   and the answer is one facet with ratio 1 (or a 0/1 lit fraction). */
static void line_and_point_footprints(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double views[] = {0, 30, 60, 80};
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 4; i++) {
        double L[3];
        gr_footprint_t f = footprint(0.5 + 0.002 * i, 0.5, VERTICAL, 0.015, 0, views[i], i % 2 ? 0 : 180);
        dir_deg(30 + 10 * i, i % 2 ? 180 : 0, L);
        compare(&f, L, 1, 256);                     /* line across */
        f = footprint(0.5 + 0.002 * i, 0.5, VERTICAL, 0, 0.01, views[i], i % 2 ? 0 : 180);
        compare(&f, L, 1, 256);                     /* line along: a point in the section */
        f = footprint(0.497 + 0.002 * i, 0.5, VERTICAL, 0, 0, views[i], i % 2 ? 0 : 180);
        compare(&f, L, 1, 256);                     /* point */
    }
    report("line/point footprints");
    scene_end();
}

/* Curved (cubic Bézier) and perturbed (sinusoidal scale) grooves, footprints
   small against the radius of curvature and perturbation changing by ~1 %
   over the distance a ray travels inside the groove (the paper's local
   straight, constant-profile model holds). */
static double wave(double t, void *u) { (void)u; return 1.0 + 0.2 * sin(4 * t); }
static void curved_and_perturbed_grooves(void)
{
    static const double cubic[8] = {0.2, 0.2, 0.2, 0.6, 0.5, 0.8, 0.85, 0.8};
    static const double line[4] = {0.1, 0.1, 0.9, 0.15};
    static const double views[] = {0, 30, 55, 75};
    double ts[] = {0.3, 0.5, 0.7};
    int i, j;
    scene_begin();
    scene_add(GR_PATH_CUBIC, cubic, 4, V_SEC, 3);
    scene_add(GR_PATH_POLYLINE, line, 2, V_SEC, 3);
    S.desc[1].perturb = wave; S.desc[1].perturb_max = 1.2;
    if (!scene_build()) return;
    for (j = 0; j < 2; j++)
        for (i = 0; i < 3; i++) {
            double P[2], T[2], a[2], b[2], l, L[3];
            gr_footprint_t f;
            gro__path_point(&S.geo[j], ts[i], P);
            gro__path_point(&S.geo[j], ts[i] - 1e-6, a);
            gro__path_point(&S.geo[j], ts[i] + 1e-6, b);
            T[0] = b[0] - a[0]; T[1] = b[1] - a[1]; l = hypot(T[0], T[1]); T[0] /= l; T[1] /= l;
            f = footprint(P[0] + 0.003 * -T[1], P[1] + 0.003 * T[0], T, 0.01, 0.002, views[(i + j) % 4], 60 * i + 90 * j);
            dir_deg(35 + 10 * i, 120 * i, L);
            compare(&f, L, 1, 256);
        }
    report("curved/perturbed");
    scene_end();
}

/* Micro-groove limit: ~2000 touching V-grooves under one footprint. The
   oracle needs n = 1024 here (B ≈ 4000 boundaries: sigma <= 1.4e-3). */
static void thousands_of_grooves_under_one_footprint(void)
{
    static double paths[2000][4], sec[6];
    int i, ng = (int)t_count(2000) < 200 ? 200 : 2000;
    double a = 0.5 / ng; /* touching V-grooves, depth 1.2 a */
    sec[0] = -a; sec[1] = 0; sec[2] = 0; sec[3] = -1.2 * a; sec[4] = a; sec[5] = 0;
    scene_begin();
    for (i = 0; i < ng; i++) {
        double u = (i + 0.5) / ng;
        paths[i][0] = u; paths[i][1] = 0; paths[i][2] = u; paths[i][3] = 1;
        scene_add(GR_PATH_POLYLINE, paths[i], 2, sec, 3);
    }
    if (!scene_build()) return;
    {
        double L[3];
        gr_footprint_t f = footprint(0.5, 0.5, VERTICAL, 0.45, 0.05, 30, 0);
        dir_deg(55, 180, L); /* partial masking (D tan 30° = 0.69 a) and shadowing (0.84 a) */
        compare(&f, L, 1, t_scale() < 1 ? 256 : 1024);
    }
    report("micro-grooves");
    scene_end();
}

/* A perturbation that changes the depth quickly along the path: a ray
   seen obliquely along the groove crosses sections of different scale
   underground. Scale 1 + 0.4 sin 12t changes by ~9 % over that distance.
   §4.2-4.3's constant profile at P (straight_occlusion = 1, the paper's
   model limit) is off by 0.023 (bound 0.05, and above 0.01 so the case is
   sensitive); grooves.h's default takes each section point where the ray
   reaching it meets the groove (gr__ray_point): r_i within the oracle's
   noise (measured 1.6e-4), lit shares 2.6e-3 (the light's rays run along
   the groove too); bound 5e-3 for both. */
static double steep_wave(double t, void *u) { (void)u; return 1.0 + 0.4 * sin(12 * t); }
static void steep_perturbation_depth_change(void)
{
    static const double line[4] = {0.1, 0.1, 0.9, 0.15};
    double acc[4] = {0, 0, 0, 0}; /* curved ratio, lit; straight ratio, lit */
    int i;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, line, 2, V_SEC, 3);
    S.desc[0].perturb = steep_wave; S.desc[0].perturb_max = 1.4;
    if (!scene_build()) return;
    for (i = 0; i < 3; i++) {
        double P[2], T[2], L[3], t = 0.3 + 0.2 * i;
        gr_footprint_t f;
        path_frame(t, P, T);
        f = footprint(P[0] + 0.003 * -T[1], P[1] + 0.003 * T[0], T, 0.01, 0.002, 30 + 25 * i, 90 + 60 * i);
        dir_deg(45, 120 * i, L);
        compare_curved_and_straight(&f, L, 5e-3, 256, 0.05, acc);
    }
    T_GT(acc[2], 0.01);
    fprintf(stderr, "    steep perturbation: max |r_i - oracle| = %.1e, lit %.1e where rays meet the groove; %.3f with §4.3's constant profile\n",
            acc[0], acc[1], acc[2]);
    worst_ratio = worst_lit = 0;
    scene_end();
}

/* By default (perturb_normals >= 0) grooves.h tilts facet normals by the
   perturbation's slope where the view ray meets the facet. The oracle's hit
   normals are the swept mesh's own; their mean per facet must agree with
   the listed normal within 2e-3 rad (measured 3e-4), where the untilted
   §4.4 normal (perturb_normals < 0) is off by up to 0.045 rad for
   1 + 0.4 sin 12t seen from 10°. */
static double angle_between(const double *a, const double *b)
{
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    return acos(fmax(-1, fmin(1, d / (la * lb))));
}
static void perturbed_normals_follow_the_slope(void)
{
    static const double line[4] = {0.1, 0.1, 0.9, 0.15};
    static unsigned char scratch[1 << 20];
    double worst_tilt = 0, worst_flat = 0;
    int i, tilt;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, line, 2, V_SEC, 3);
    S.desc[0].perturb = steep_wave; S.desc[0].perturb_max = 1.4;
    if (!scene_build()) return;
    for (i = 0; i < 5; i++)
        for (tilt = 0; tilt < 2; tilt++) {
            double P[2], T[2], t = 0.2 + 0.15 * i;
            gr_query_t q;
            gr_facet_list_t list;
            gro_result_t o;
            int e;
            path_frame(t, P, T);
            memset(&q, 0, sizeof q);
            q.footprint = footprint(P[0], P[1], T, 0.006, 0.001, 10, 90);
            q.perturb_normals = tilt ? 0 : -1;
            if (!T_INT_EQ(gr_query(S.grid, &q, scratch, sizeof scratch, &list), GR_OK)) continue;
            if (oracle_run(&q.footprint, NULL, 0, 256, &o)) continue;
            for (e = 0; e < list.count; e++) {
                const gr_facet_t *f = &list.facets[e];
                double ang;
                if (f->groove != 0 || gro_vis(&o, 0, f->facet) < 0.05) continue;
                ang = angle_between(f->normal, o.nsum + 3 * f->facet);
                if (tilt) { T_LE(ang, 2e-3); worst_tilt = fmax(worst_tilt, ang); }
                else worst_flat = fmax(worst_flat, ang);
            }
            gro_result_free(&o);
        }
    /* the check is sensitive: the untilted normals are measurably off */
    T_GT(worst_flat, 0.02);
    fprintf(stderr, "    normal angle to the mesh: %.4f rad tilted (default), %.3f rad as §4.4\n", worst_tilt,
            worst_flat);
    scene_end();
}

/* On a tight bend the view ray travels along the path under the surface:
   the curves scene's cubic (radius of curvature 0.11 at t = 0.75) with a
   U-section 0.06 wide, seen 50° from the normal looking along the path.
   grooves.h turns each facet's normal to where the ray meets it
   (gr__hit_normal, the path's own tangent there); the oracle's mean hit
   normal per facet must agree within 5e-3 rad (measured 6e-4), where the
   normal at the footprint centre is off by up to 0.087 rad. */
static void curved_normals_where_the_ray_meets(void)
{
    static const double curve[8] = {0.15, 0.2, 0.3, 0.95, 0.75, -0.1, 0.85, 0.75};
    static const double usec[10] = {-0.03, 0, -0.024, -0.02, 0, -0.028, 0.024, -0.02, 0.03, 0};
    static unsigned char scratch[1 << 20];
    double worst = 0, worst_p = 0;
    int i;
    scene_begin();
    scene_add(GR_PATH_CUBIC, curve, 4, usec, 5);
    S.no_wrap = 1;
    if (!scene_build()) return;
    for (i = 0; i < 6; i++) {
        double P[2], T[2], off = 0.008 * (i % 3 - 1);
        gr_query_t q = {0};
        gr_facet_list_t list;
        gro_result_t o;
        int e;
        path_frame(0.7 + 0.02 * i, P, T); /* down the bend, looking back along it */
        q.footprint = footprint(P[0] - off * T[1], P[1] + off * T[0], T, 0.002, 0.002, 50,
                                atan2(-T[1], -T[0]) * 180 / M_PI + 20 * (i % 2));
        if (!T_INT_EQ(gr_query(S.grid, &q, scratch, sizeof scratch, &list), GR_OK)) continue;
        if (oracle_run(&q.footprint, NULL, 0, 128, &o)) continue;
        memset(tangent_known, 0, sizeof tangent_known);
        for (e = 0; e < list.count; e++) {
            const gr_facet_t *f = &list.facets[e];
            double ang, atp[3];
            if (f->groove != 0 || f->merged != 1 || gro_vis(&o, 0, f->facet) < 0.2) continue;
            ang = angle_between(f->normal, o.nsum + 3 * f->facet);
            T_LE(ang, 5e-3);
            worst = fmax(worst, ang);
            facet_normal(0, f->facet, q.footprint.center[0], q.footprint.center[1], atp);
            worst_p = fmax(worst_p, angle_between(atp, o.nsum + 3 * f->facet));
        }
        gro_result_free(&o);
    }
    T_GT(worst_p, 0.05); /* sensitive: the normal at P is measurably off */
    fprintf(stderr, "    tight bend: normal angle to the mesh %.4f rad where the ray meets, %.3f rad at P\n", worst,
            worst_p);
    scene_end();
}

/* The curves scene's curved groove (examples/grooves, Fig. 2): its cubic,
   radius of curvature down to 0.11, a rounded U 0.06 wide. */
static const double BEND[8] = {0.15, 0.2, 0.3, 0.95, 0.75, -0.1, 0.85, 0.75};
static const double BEND_U[10] = {-0.03, 0, -0.024, -0.02, 0, -0.028, 0.024, -0.02, 0.03, 0};
#define BEND_RATIO_TOL 0.02
#define BEND_NORMAL_TOL 0.02
static double bend_wave(double t, void *u) { (void)u; return 1.0 + 0.45 * sin(6 * M_PI * t); }

/* The bend cases' scene: the cubic with the U section, optionally with the
   curves scene's perturbation; entries matched to the oracle by id. */
static int bend_scene(int perturbed)
{
    scene_begin();
    scene_add(GR_PATH_CUBIC, BEND, 4, BEND_U, 5);
    if (perturbed) { S.desc[0].perturb = bend_wave; S.desc[0].perturb_max = 1.45; }
    S.no_wrap = 1;
    q_match_ids = 1;
    return scene_build();
}

/* After a bend case: default matching and counters, the scene freed. */
static void bend_case_end(void)
{
    q_match_ids = 0;
    worst_ratio = worst_lit = 0;
    scene_end();
}

/* Footprint k of the bend cases: down the bend (t = 0.70 ... 0.84), across
   the groove at b = -0.02, 0, 0.02, seen 50° from the normal looking along
   the path one way or the other, a light at 40° along it. */
static gr_footprint_t bend_footprint(int k, double *L)
{
    double P[2], T[2], off = 0.02 * (k % 3 - 1), az;
    path_frame(0.70 + 0.02 * (k / 2 % 8), P, T);
    az = atan2(T[1], T[0]) * 180 / M_PI + (k % 2 ? 180 : 0);
    dir_deg(40, az + 30, L);
    return footprint(P[0] - off * T[1], P[1] + off * T[0], T, 0.004, 0.003, 50, az + 15);
}

/* On a tight bend a ray seen along the path runs ~0.03 underground, where
   the path has turned and the groove lies farther out (drift ~ kappa run^2
   / 2, a pixel of the curves scene): footprints on the walls and the floor
   of the bend, views 50° and a light 40° from the surface, both along the
   path. §4.3's straight occlusion (straight_occlusion = 1) errs by 0.37 in
   r_i (asserted above 0.1: the case is sensitive). The default moves each
   section point by the bend's drift under the ray reaching it
   (gr__bend_drift, then refined on the path itself, gr__mouth_on_path):
   r_i within 0.035 (measured 0.026: what remains is that the seen
   boundaries tilt across the footprint as the bend turns under it, which
   the footprint's 1D model takes parallel to the path; oversampling at
   tol 0.01, whose count includes that tilt, takes it to 1.6e-3, bound
   5e-3). Each light sees
   the groove from where its rays toward the seen facets enter it
   (gr__light_anchor: on this bend 0.05 farther along, turned by 0.4 rad):
   lit shares within 0.035 (measured 0.026; 0.092 with the light's profile
   taken across the footprint, 0.37 straight). */
static void tight_bend_occlusion(void)
{
    double acc[4] = {0, 0, 0, 0}, worst_os = 0; /* acc: curved ratio, lit; straight ratio, lit */
    int k;
    if (!bend_scene(0)) return;
    for (k = 0; k < 16; k++) {
        double L[3];
        gr_footprint_t f = bend_footprint(k, L);
        worst_ratio = 0;
        compare_curved_and_straight(&f, L, 0.035, 128, 1, acc);
        /* oversampled finer: the parts resolve the tilting boundaries */
        q_oversample_tol = 0.01;
        q_max_oversample = 64;
        worst_ratio = 0;
        compare_tol(&f, L, 1, 256, 0.035);
        worst_os = fmax(worst_os, worst_ratio);
        q_oversample_tol = 0;
        q_max_oversample = 0;
    }
    T_LE(worst_os, 5e-3);
    T_GT(acc[2], 0.1);
    fprintf(stderr, "    tight bend: max |r_i - oracle| = %.3f, lit %.3f where rays meet the groove (r_i %.1e at tol 0.01); %.3f, %.3f straight (§4.3)\n",
            acc[0], acc[1], worst_os, acc[2], acc[3]);
    bend_case_end();
}

/* The same bend with the curves scene's perturbation f = 1 + 0.45 sin 6 pi t
   (the section's scale changes by up to 25 % under one ray), the stress
   case of the curves scene: r_i and lit shares within BEND_RATIO_TOL
   (measured 7.8e-3 and 1.2e-2; 0.057 before the mouth point was refined
   on the path itself: the drift's circle overshoots this bend's true
   sagitta by ~5e-4 where its curvature changes by 30 %), and the listed normal
   of every facet seen over a fifth of the footprint within
   BEND_NORMAL_TOL of the oracle's mean hit normal (measured 0.012 rad;
   §4.4's normal at P is off by 0.38 rad, asserted above 0.05). */
static void bend_with_steep_perturbation(void)
{
    static unsigned char scratch[1 << 20];
    double worst_n = 0, worst_p = 0;
    int k;
    if (!bend_scene(1)) return;
    for (k = 0; k < 16; k++) {
        double L[3];
        gr_query_t q;
        gr_facet_list_t list;
        gro_result_t o;
        int e, paper;
        gr_footprint_t fp = bend_footprint(k, L);
        compare_tol(&fp, L, 1, 256, BEND_RATIO_TOL);
        if (oracle_run(&fp, NULL, 0, 128, &o)) continue;
        for (paper = 0; paper < 2; paper++) {
            memset(&q, 0, sizeof q);
            q.footprint = fp;
            q.perturb_normals = paper ? -1 : 0;
            q.straight_occlusion = paper;
            if (!T_INT_EQ(gr_query(S.grid, &q, scratch, sizeof scratch, &list), GR_OK)) continue;
            for (e = 0; e < list.count; e++) {
                const gr_facet_t *f = &list.facets[e];
                double ang;
                if (f->groove != 0 || gro_vis(&o, 0, f->facet) < 0.2) continue;
                ang = angle_between(f->normal, o.nsum + 3 * f->facet);
                if (paper) worst_p = fmax(worst_p, ang);
                else { T_LE(ang, BEND_NORMAL_TOL); worst_n = fmax(worst_n, ang); }
            }
        }
        gro_result_free(&o);
    }
    T_GT(worst_p, 0.05);
    fprintf(stderr, "    bend + perturbation: max |r_i - oracle| = %.1e, lit %.1e; normals %.1e rad (§4.4: %.3f)\n",
            worst_ratio, worst_lit, worst_n, worst_p);
    bend_case_end();
}

/* The curves scene's straight groove: a V with raised lips (w > 0: it
   masks and shadows beyond its width, §4.1's h tan θ) that shrinks along
   its path, f = 1 - 0.85 t, seen and lit along the path both ways. f is
   linear, so the scale where a ray meets the groove is exact
   (gr__ray_point's first step): r_i and lit within 5e-3 (measured 3.1e-4,
   the oracle's noise); §4.3's constant profile is off by 0.023 (asserted
   above 0.02, so the case is sensitive). */
static double shrink(double t, void *u) { (void)u; return 1.0 - 0.85 * t; }
static void shrinking_lipped_groove(void)
{
    static const double line[4] = {0.08, 0.9, 0.66, 0.93};
    static const double lip[8] = {-0.028, 0, -0.022, 0.006, 0, -0.024, 0.028, 0};
    double acc[4] = {0, 0, 0, 0}; /* curved ratio, lit; straight ratio, lit */
    int k;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, line, 2, lip, 4);
    S.desc[0].perturb = shrink; S.desc[0].perturb_max = 1;
    if (!scene_build()) return;
    for (k = 0; k < 12; k++) {
        double P[2], T[2], L[3], off = 0.012 * (k % 3 - 1), az;
        gr_footprint_t f;
        path_frame(0.2 + 0.15 * (k / 3), P, T);
        az = atan2(T[1], T[0]) * 180 / M_PI + (k % 2 ? 180 : 0);
        f = footprint(P[0] - off * T[1], P[1] + off * T[0], T, 0.004, 0.003, 55, az + 10);
        dir_deg(35, az - 20, L);
        compare_curved_and_straight(&f, L, 5e-3, 128, 1, acc);
    }
    T_GT(acc[2], 0.02);
    fprintf(stderr, "    shrinking lipped groove: max |r_i - oracle| = %.1e (lit %.1e) where rays meet it; %.3f straight\n",
            acc[0], acc[1], acc[2]);
    worst_ratio = worst_lit = 0;
    scene_end();
}

/* §4.2's oversampling (issue 7 item 5) converges toward the geometry as
   its tolerance shrinks: a footprint 0.026 x 0.02 (a pixel of the curves
   scene's bench view, 4x) on the perturbed bend, whose axes are both
   oblique to the path. Largest |r_i - oracle| (n = 512) at tol = none,
   0.05, 0.02, 0.01 with up to 64 parts: measured 1.8e-2, 3.7e-3, 1.0e-3,
   1.4e-3; asserted: each at most the one before plus 1e-3 (the oracle's
   noise and the layout of the parts), the last below 2e-3 and under a
   quarter of the first. Before the parts were cut along both axes (one
   axis only) the error stayed at 0.04 whatever the tolerance. */
static void oversampling_converges_on_bend(void)
{
    static const double tols[4] = {-1, 0.05, 0.02, 0.01};
    gr_footprint_t f;
    double err[4], L[3] = {0, 0, 1};
    int i;
    if (!bend_scene(1)) return;
    memset(&f, 0, sizeof f);
    f.center[0] = 0.75414; f.center[1] = 0.41482;
    f.axis1[0] = 4 * 0.00322; f.axis1[1] = 0;
    f.axis2[0] = 4 * -0.00083; f.axis2[1] = 4 * -0.00488;
    f.view[0] = -0.217; f.view[1] = -0.738; f.view[2] = 0.640;
    for (i = 0; i < 3; i++) f.view[i] /= sqrt(0.217 * 0.217 + 0.738 * 0.738 + 0.64 * 0.64);
    q_max_oversample = 64;
    for (i = 0; i < 4; i++) {
        q_oversample_tol = tols[i];
        err[i] = compare_tol(&f, L, 1, 512, 0.05);
        if (i > 0) T_LE(err[i], err[i - 1] + 1e-3);
    }
    q_max_oversample = 0;
    q_oversample_tol = 0;
    T_LE(err[3], 2e-3);
    T_LT(err[3], err[0] / 4);
    fprintf(stderr, "    oversampling on the bend: max |r_i - oracle| %.1e (none), %.1e, %.1e, %.1e (tol 0.05, 0.02, 0.01)\n",
            err[0], err[1], err[2], err[3]);
    bend_case_end();
}

/* Oblique footprints (neither axis along the groove). The parallelogram
   F + a A1 + b A2 projects onto B as a trapezoid density, not as §4.2's
   uniform segment S; grooves.h integrates the trapezoid (gr__xcdf), which
   for a groove straight over the footprint is exact, so the 1e-2
   holds (measured 6e-4, isolated and parallel, views 0°..85°). The old
   uniform segment erred by up to 0.14 on these very footprints (they are
   comparable to the groove: the weighting decides which rim is seen); 176
   of their 746 checks fail with it (55 of 259 at FILIGREE_TEST_SCALE 0.05).
   Axes at 15°..75° to the groove, ratios 1, 1/2, 1/4 (beta = 1 is the
   widest ramps, no plateau). */
static gr_footprint_t oblique(double u, double v, double big, double ratio, double ang_deg, double view_deg,
                              double azim)
{
    gr_footprint_t f;
    double a = ang_deg * M_PI / 180;
    memset(&f, 0, sizeof f);
    f.center[0] = u; f.center[1] = v;
    f.axis1[0] = big * cos(a); f.axis1[1] = big * sin(a);
    f.axis2[0] = -big * ratio * sin(a); f.axis2[1] = big * ratio * cos(a);
    dir_deg(90 - view_deg, azim, f.view);
    return f;
}

static void footprint_oblique_axes(void)
{
    static const double path[4] = {0.5, 0, 0.5, 1};
    static const double views[] = {0, 20, 40, 60, 75, 85};
    static const double angs[] = {30, 15, 45, 60, 75};
    static const double ratios[] = {0.5, 1, 0.25};
    int i, j, layout, step = t_scale() < 1 ? 2 : 1;
    scene_begin();
    scene_add(GR_PATH_POLYLINE, path, 2, V_SEC, 3);
    if (!scene_build()) return;
    for (i = 0; i < 6; i += step)
        for (j = 0; j < 5; j += step) {
            double L[3], off = 0.004 * ((i * 3 + j * 2) % 5 - 2) / 2.0;
            gr_footprint_t f = oblique(0.5 + off, 0.5, 0.012, ratios[(i + j) % 3], angs[j], views[i], 180 + 40 * i);
            dir_deg(50 - 8 * j, 35 * i + 20 * j, L);
            compare(&f, L, 1, 256);
        }
    report("oblique footprints, isolated groove");
    scene_end();
    /* parallel grooves under one oblique footprint: the merged profile is
       weighted as one (touching grooves, then ground between them) */
    for (layout = 0; layout < 2; layout++) {
        double spacing = layout ? 0.035 : 0.02;
        if (!vertical_grooves(12, 0.3, spacing)) return;
        for (i = 0; i < 6; i += step)
            for (j = 0; j < 5; j += step) {
                double L[3], u = 0.3 + spacing * (4 + (i + j) % 3) + 0.003 * (j - 2);
                gr_footprint_t f = oblique(u, 0.5, 0.025, ratios[(i + 2 * j) % 3], angs[j], views[i], 30 + 50 * i);
                dir_deg(60 - 10 * j, 200 + 30 * i, L);
                compare(&f, L, 1, 256);
            }
        report(layout ? "oblique footprints, spaced parallel grooves" : "oblique footprints, touching parallel grooves");
        scene_end();
    }
    /* over many grooves both projections average the same periodic profile */
    {
        if (!vertical_grooves(40, 0.1, 0.02)) return;
        for (i = 0; i < 4; i++) {
            double L[3], ang = (20 + 15 * i) * M_PI / 180;
            gr_footprint_t f;
            memset(&f, 0, sizeof f);
            f.center[0] = 0.503 + 0.004 * i; f.center[1] = 0.5;
            f.axis1[0] = 0.2 * cos(ang); f.axis1[1] = 0.2 * sin(ang);
            f.axis2[0] = -0.1 * sin(ang); f.axis2[1] = 0.1 * cos(ang);
            dir_deg(50, 20, f.view);
            dir_deg(40, 200, L);
            compare(&f, L, 1, 512);
        }
        report("oblique footprints over ~20 grooves");
    }
    scene_end();
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(isolated_groove_all_views),
        T_CASE(parallel_grooves_all_views),
        T_CASE(protruding_ridges_mask_neighbours),
        T_CASE(diagonal_groove),
        T_CASE(groove_much_wider_than_footprint),
        T_CASE(groove_much_narrower_than_footprint),
        T_CASE(footprint_across_texture_seam),
        T_CASE(light_near_horizon),
        T_CASE(grazing_views),
        T_CASE(vertical_and_zero_width_facets),
        T_CASE(line_and_point_footprints),
        T_CASE(curved_and_perturbed_grooves),
        T_CASE(thousands_of_grooves_under_one_footprint),
        T_CASE(steep_perturbation_depth_change),
        T_CASE(perturbed_normals_follow_the_slope),
        T_CASE(curved_normals_where_the_ray_meets),
        T_CASE(tight_bend_occlusion),
        T_CASE(bend_with_steep_perturbation),
        T_CASE(oversampling_converges_on_bend),
        T_CASE(shrinking_lipped_groove),
        T_CASE(footprint_oblique_axes),
    };
    int rc;
    if (gro_device_init(&dev)) { printf("0 passed, 1 failed\n"); return 1; }
    rc = T_RUN(argc, argv, cases);
    gro_device_free(&dev);
    return rc;
}
