/* grooves.h detection of intersections and ends (issue 8 item 1, §5) and
   the §5.1 search box. Scenes are built by hand so each expected junction,
   point and box edge is known exactly; the cubic self-intersection is
   checked against a bisection on the curve's symmetry. Shared section: a
   V groove of half width w = 0.01 and depth 0.02 (so w_g + w_h = 0.02). */
#include "grooves.h"
#include "test.h"

static const double vsec[] = {-0.01, 0, 0, -0.02, 0.01, 0};

/* grooves from polylines given as (count, points...) */
static gr_grid_t *build(const double *const *paths, const int *counts, int n, const double *sec, int nsec, int kind)
{
    gr_groove_desc_t g[8];
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_diag_t diag;
    int i;
    memset(&d, 0, sizeof d);
    memset(g, 0, sizeof g);
    for (i = 0; i < n; i++) {
        g[i].kind = (gr_path_kind_t)kind;
        g[i].points = paths[i];
        g[i].point_count = counts[i];
        g[i].section = sec;
        g[i].section_count = nsec;
    }
    d.grooves = g;
    d.groove_count = n;
    d.no_wrap = 1;
    if (gr_grid_build(&d, &grid, &diag) != GR_OK) T_FAIL("build: %s", diag.message);
    return grid;
}

static gr_junctions_t detect_at(const gr_grid_t *grid, double u, double v, double half, const double *view,
                                const gr_self_hit_t *self, int nself)
{
    static unsigned char scratch[1 << 20];
    gr_query_t q;
    gr_junctions_t out;
    memset(&q, 0, sizeof q);
    q.footprint.center[0] = u;
    q.footprint.center[1] = v;
    q.footprint.axis1[0] = half;
    q.footprint.axis2[1] = half;
    q.footprint.view[2] = 1;
    if (view) memcpy(q.footprint.view, view, sizeof q.footprint.view);
    T_CHECK(gr_query_scratch_bytes(grid) <= sizeof scratch);
    T_INT_EQ(gr_detect(grid, &q, self, nself, scratch, sizeof scratch, &out), GR_OK);
    return out;
}

static void detect_x_crossing(void)
{
    const double h[] = {0.1, 0.5, 0.9, 0.5}, v[] = {0.5, 0.1, 0.5, 0.9};
    const double *paths[] = {h, v};
    const int counts[] = {2, 2};
    gr_grid_t *grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
    gr_junctions_t j = detect_at(grid, 0.5, 0.5, 0.005, NULL, NULL, 0);
    T_INT_EQ(j.grooves, 2);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
    T_INT_EQ(j.items[0].groove + j.items[0].other, 1);
    T_NEAR(j.items[0].point[0], 0.5, 1e-15);
    T_NEAR(j.items[0].point[1], 0.5, 1e-15);
    /* 0.2 along the horizontal groove: the vertical one is 0.2 away, far
       beyond the box (half size 0.005 + w) */
    j = detect_at(grid, 0.3, 0.5, 0.005, NULL, NULL, 0);
    T_INT_EQ(j.grooves, 1);
    T_INT_EQ(j.count, 0);
    gr_grid_free(grid);
}

/* 30 degrees through (0.4, 0.5) against the horizontal; then 0.01 rad,
   parallel under the default tolerance 0.02 and crossing under 0.005 */
static void detect_oblique_and_parallel(void)
{
    double h[] = {0.1, 0.5, 0.9, 0.5}, o[4], p[4], a = M_PI / 6, e = 0.01;
    const double *paths[] = {h, o};
    const int counts[] = {2, 2};
    static unsigned char scratch[1 << 20];
    gr_grid_t *grid;
    gr_junctions_t j;
    gr_query_t q;
    o[0] = 0.4 - 0.3 * cos(a); o[1] = 0.5 - 0.3 * sin(a); o[2] = 0.4 + 0.3 * cos(a); o[3] = 0.5 + 0.3 * sin(a);
    grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
    j = detect_at(grid, 0.41, 0.5, 0.004, NULL, NULL, 0);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
    T_NEAR(j.items[0].point[0], 0.4, 1e-14);
    T_NEAR(j.items[0].point[1], 0.5, 1e-14);
    gr_grid_free(grid);
    p[0] = 0.1; p[1] = 0.5 - 0.3 * tan(e); p[2] = 0.9; p[3] = 0.5 + 0.5 * tan(e);
    paths[1] = p;
    grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
    j = detect_at(grid, 0.4, 0.5, 0.004, NULL, NULL, 0);
    T_INT_EQ(j.grooves, 2);
    T_INT_EQ(j.count, 0);
    memset(&q, 0, sizeof q);
    q.footprint.center[0] = 0.4; q.footprint.center[1] = 0.5;
    q.footprint.axis1[0] = q.footprint.axis2[1] = 0.004;
    q.footprint.view[2] = 1;
    q.parallel_tol = 0.005;
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_OK);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
    gr_grid_free(grid);
}

/* Two grooves 0.05 rad apart (not parallel at the default 0.02) whose
   lines meet 0.24 away from the footprint, but whose strips (half width
   0.01 each) overlap under it: 0.012 apart at u = 0.5. A crossing, with the
   footprint centre itself as the point (it lies in the overlap); before
   the overlap rule it was missed, and §4 answered with the nearest
   groove alone. 0.025 apart the strips overlap only from 0.1 away, and
   the path stays outside the box: none. */
static void detect_overlap_far_from_meeting(void)
{
    double h[] = {0.1, 0.5, 0.9, 0.5}, o[4], a = 0.05;
    const double *paths[] = {h, o};
    const int counts[] = {2, 2};
    gr_grid_t *grid;
    gr_junctions_t j;
    int k;
    for (k = 0; k < 2; k++) {
        double gap = k == 0 ? 0.012 : 0.025;
        o[0] = 0.1; o[1] = 0.5 + gap - 0.4 * tan(a); o[2] = 0.9; o[3] = 0.5 + gap + 0.4 * tan(a);
        grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
        j = detect_at(grid, 0.5, 0.505, 0.004, NULL, NULL, 0);
        T_INT_EQ(j.grooves, 2 - k);
        if (k == 0) {
            T_INT_EQ(j.count, 1);
            T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
            T_NEAR(j.items[0].point[0], 0.5, 1e-15);
            T_NEAR(j.items[0].point[1], 0.505, 1e-15);
        } else {
            T_INT_EQ(j.count, 0);
        }
        gr_grid_free(grid);
    }
}

/* T: a groove ending on another is an intersected end, not a crossing */
static void detect_t_intersected_end(void)
{
    const double h[] = {0.1, 0.5, 0.9, 0.5}, v[] = {0.5, 0.9, 0.5, 0.5};
    const double *paths[] = {h, v};
    const int counts[] = {2, 2};
    gr_grid_t *grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
    gr_junctions_t j = detect_at(grid, 0.5, 0.505, 0.005, NULL, NULL, 0);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_INTERSECTED_END);
    T_INT_EQ(j.items[0].groove, 1);
    T_INT_EQ(j.items[0].other, 0);
    T_INT_EQ(j.items[0].end, 1); /* the path's last point */
    T_EQ(j.items[0].point[0], 0.5);
    T_EQ(j.items[0].point[1], 0.5);
    gr_grid_free(grid);
}

static void detect_isolated_end(void)
{
    const double v[] = {0.5, 0.5, 0.5, 0.9};
    const double *paths[] = {v};
    const int counts[] = {2};
    gr_grid_t *grid = build(paths, counts, 1, vsec, 3, GR_PATH_POLYLINE);
    gr_junctions_t j = detect_at(grid, 0.5, 0.5, 0.003, NULL, NULL, 0);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_ISOLATED_END);
    T_INT_EQ(j.items[0].end, 0);
    T_INT_EQ(j.items[0].other, -1);
    j = detect_at(grid, 0.5, 0.7, 0.003, NULL, NULL, 0); /* mid groove: nothing */
    T_INT_EQ(j.count, 0);
    gr_grid_free(grid);
}

/* L: two ends at one point make a corner, reported once, no crossing */
static void detect_corner(void)
{
    const double h[] = {0.1, 0.5, 0.5, 0.5}, v[] = {0.5, 0.5, 0.5, 0.9};
    const double *paths[] = {h, v};
    const int counts[] = {2, 2};
    gr_grid_t *grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
    gr_junctions_t j = detect_at(grid, 0.5, 0.5, 0.004, NULL, NULL, 0);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_CORNER);
    T_INT_EQ(j.items[0].groove, 0);
    T_INT_EQ(j.items[0].end, 1);
    T_INT_EQ(j.items[0].other, 1);
    T_INT_EQ(j.items[0].other_end, 0);
    gr_grid_free(grid);
}

/* Stiff: the distance test at its threshold. A vertical groove ends at
   gap g above the horizontal path; w_g + w_h = 0.02. g = 0.02 - 1e-9 is an
   intersected end, g = 0.02 + 1e-9 an isolated end, and then the two are
   not a crossing either (the vertical path stops short of the other). */
static void stiff_distance_test_threshold(void)
{
    int side;
    for (side = 0; side < 2; side++) {
        double gap = 0.02 + (side ? 1e-9 : -1e-9);
        double h[] = {0.1, 0.5, 0.9, 0.5}, v[] = {0.5, 0.5, 0.5, 0.9};
        const double *paths[] = {h, v};
        const int counts[] = {2, 2};
        gr_grid_t *grid;
        gr_junctions_t j;
        v[1] = 0.5 + gap;
        grid = build(paths, counts, 2, vsec, 3, GR_PATH_POLYLINE);
        j = detect_at(grid, 0.5, 0.5 + gap, 0.012, NULL, NULL, 0); /* box reaches v = 0.498 */
        T_INT_EQ(j.grooves, 2);
        T_INT_EQ(j.count, 1);
        T_INT_EQ(j.items[0].kind, side ? GR_JUNCTION_ISOLATED_END : GR_JUNCTION_INTERSECTED_END);
        gr_grid_free(grid);
    }
}

/* a polyline crossing itself: segments 0 and 2 meet at (0.5, 0.5) */
static void self_intersection_polyline(void)
{
    const double z[] = {0.2, 0.2, 0.8, 0.8, 0.8, 0.2, 0.2, 0.8};
    const double *paths[] = {z};
    const int counts[] = {4};
    gr_grid_t *grid = build(paths, counts, 1, vsec, 3, GR_PATH_POLYLINE);
    gr_self_hit_t hit[4];
    gr_junctions_t j;
    int n = -1;
    memset(hit, 0, sizeof hit);
    double l0 = sqrt(0.72), len = 2 * l0 + 0.6;
    T_INT_EQ(gr_self_intersections(grid, hit, 4, &n), GR_OK);
    T_INT_EQ(n, 1);
    T_NEAR(hit[0].point[0], 0.5, 1e-15);
    T_NEAR(hit[0].point[1], 0.5, 1e-15);
    T_NEAR(hit[0].param[0], 0.5 * l0 / len, 1e-15);
    T_NEAR(hit[0].param[1], (1.5 * l0 + 0.6) / len, 1e-15);
    T_INT_EQ(gr_self_intersections(grid, hit, 0, &n), GR_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(n, 1);
    /* the builder cut the groove between the two passes (§5): they meet
       as a crossing of the groove with itself, beside the point itself */
    j = detect_at(grid, 0.5, 0.5, 0.004, NULL, hit, 1);
    T_INT_EQ(j.count, 2);
    T_INT_EQ(j.grooves, 2);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
    T_INT_EQ(j.items[0].groove, 0);
    T_INT_EQ(j.items[0].other, 0);
    T_NEAR(j.items[0].point[0], 0.5, 1e-15);
    T_NEAR(j.items[0].point[1], 0.5, 1e-15);
    T_INT_EQ(j.items[1].kind, GR_JUNCTION_SELF);
    /* without the caller's list, the builder's */
    j = detect_at(grid, 0.5, 0.5, 0.004, NULL, NULL, 0);
    T_INT_EQ(j.count, 2);
    T_INT_EQ(j.items[1].kind, GR_JUNCTION_SELF);
    /* on the path, 0.28 from the point and 0.14 from the first end: nothing
       (one groove: its pieces are taken only about a crossing) */
    j = detect_at(grid, 0.3, 0.3, 0.004, NULL, hit, 1);
    T_INT_EQ(j.count, 0);
    T_INT_EQ(j.grooves, 1);
    gr_grid_free(grid);
}

/* a polyline with two loops one after the other, crossing itself at
   (0.2, 0.5) and at (0.65, 0.5): the builder cuts it twice (two disjoint
   parameter intervals, sorted before the pieces are made: the sort no
   test had reached), and each crossing is then one of two pieces */
static void self_intersection_two_loops(void)
{
    const double z[] = {0.1, 0.3, 0.3, 0.7, 0.4, 0.5, 0.3, 0.3, 0.1, 0.7, 0.1, 0.9, 0.5, 0.9,
                        0.55, 0.3, 0.75, 0.7, 0.85, 0.5, 0.75, 0.3, 0.55, 0.7};
    const double *paths[] = {z};
    const int counts[] = {12};
    const double at[2][2] = {{0.2, 0.5}, {0.65, 0.5}};
    gr_grid_t *grid = build(paths, counts, 1, vsec, 3, GR_PATH_POLYLINE);
    gr_self_hit_t hit[4];
    gr_junctions_t j;
    int n = -1, k;
    memset(hit, 0, sizeof hit);
    T_INT_EQ(gr_self_intersections(grid, hit, 4, &n), GR_OK);
    T_INT_EQ(n, 2);
    for (k = 0; k < 2 && k < n; k++) {
        int w = hit[k].point[0] > 0.4; /* which loop */
        T_NEAR(hit[k].point[0], at[w][0], 1e-15);
        T_NEAR(hit[k].point[1], at[w][1], 1e-15);
    }
    for (k = 0; k < 2; k++) {
        j = detect_at(grid, at[k][0], at[k][1], 0.004, NULL, NULL, 0);
        T_INT_EQ(j.count, 2);
        T_INT_EQ(j.grooves, 2);
        T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
        T_NEAR(j.items[0].point[0], at[k][0], 1e-15);
        T_NEAR(j.items[0].point[1], at[k][1], 1e-15);
        T_INT_EQ(j.items[1].kind, GR_JUNCTION_SELF);
    }
    /* on the path between the loops, far from both crossings: nothing */
    j = detect_at(grid, 0.3, 0.9, 0.004, NULL, NULL, 0);
    T_INT_EQ(j.count, 0);
    T_INT_EQ(j.grooves, 1);
    gr_grid_free(grid);
}

#ifndef GR_NO_CURVES
/* a looping cubic symmetric about u = 0.5 (P_k.u + P_3-k.u = 1, P_k.v =
   P_3-k.v): it crosses itself where u(τ) = 0.5 with τ < 0.5, found here by
   bisection. The 32-chord flattening is off the curve by at most the
   sagitta |P''| / (8 x 32^2) <= 6 x 1.8 / 8192 = 1.3e-3 (|P''| <= 6 x the
   largest second difference of the control points, 1.8 here). */
static double cub(const double *p, double t, int k)
{
    double s = 1 - t;
    return s * s * s * p[k] + 3 * s * s * t * p[2 + k] + 3 * s * t * t * p[4 + k] + t * t * t * p[6 + k];
}
/* a chain of three straight cubic pieces (control points a third apart)
   in a Z, crossing itself at (0.5, 0.5) between its first and last piece:
   the crossing's parameters span joints 1 and 2, the cut falls on joint 2,
   and both pieces are whole Bézier pieces (a branch no test had reached);
   each piece is where the polyline Z is, so what detection finds along
   the path is what it finds on the polyline */
static void self_intersection_chain_cut_at_a_joint(void)
{
    const double zc[] = {0.2, 0.2, 0.4, 0.4, 0.6, 0.6, 0.8, 0.8, 0.8, 0.6, 0.8, 0.4, 0.8, 0.2, 0.6, 0.4, 0.4, 0.6, 0.2, 0.8};
    const double zp[] = {0.2, 0.2, 0.8, 0.8, 0.8, 0.2, 0.2, 0.8};
    const double *pc[] = {zc}, *pp[] = {zp};
    const int cc[] = {10}, cp[] = {4};
    const double probe[5][2] = {{0.5, 0.5}, {0.8, 0.5}, {0.3, 0.3}, {0.7, 0.3}, {0.79, 0.79}};
    gr_grid_t *chain = build(pc, cc, 1, vsec, 3, GR_PATH_CUBIC), *poly = build(pp, cp, 1, vsec, 3, GR_PATH_POLYLINE);
    gr_self_hit_t hit[4];
    int n = -1, k;
    T_INT_EQ(gr_self_intersections(chain, hit, 4, &n), GR_OK);
    T_INT_EQ(n, 1);
    T_NEAR(hit[0].point[0], 0.5, 1e-12);
    T_NEAR(hit[0].point[1], 0.5, 1e-12);
    for (k = 0; k < 5; k++) {
        gr_junctions_t a = detect_at(chain, probe[k][0], probe[k][1], 0.004, NULL, NULL, 0);
        gr_junctions_t b = detect_at(poly, probe[k][0], probe[k][1], 0.004, NULL, NULL, 0);
        int i;
        T_INT_EQ(a.grooves, b.grooves);
        if (!T_INT_EQ(a.count, b.count)) continue;
        for (i = 0; i < a.count; i++) {
            T_INT_EQ(a.items[i].kind, b.items[i].kind);
            T_NEAR(a.items[i].point[0], b.items[i].point[0], 1e-12);
            T_NEAR(a.items[i].point[1], b.items[i].point[1], 1e-12);
        }
    }
    {
        gr_junctions_t a = detect_at(chain, 0.5, 0.5, 0.004, NULL, NULL, 0);
        T_INT_EQ(a.count, 2);
        T_INT_EQ(a.grooves, 2);
        T_INT_EQ(a.items[0].kind, GR_JUNCTION_CROSSING);
    }
    gr_grid_free(chain);
    gr_grid_free(poly);
}
static void self_intersection_cubic(void)
{
    const double c[] = {0.2, 0.2, 1.0, 0.8, 0.0, 0.8, 0.8, 0.2};
    const double *paths[] = {c};
    const int counts[] = {4};
    gr_grid_t *grid = build(paths, counts, 1, vsec, 3, GR_PATH_CUBIC);
    gr_self_hit_t hit[4];
    double lo = 0, hi = 0.4, t;
    int n = -1, k;
    memset(hit, 0, sizeof hit);
    /* u(τ) climbs through 0.5 on [0, 0.4], turns, and returns to 0.5 at
       τ = 0.5 (the symmetry point, not a crossing) */
    T_LT(cub(c, lo, 0), 0.5);
    T_GT(cub(c, hi, 0), 0.5);
    for (k = 0; k < 100; k++) {
        t = 0.5 * (lo + hi);
        if (cub(c, t, 0) < 0.5) lo = t; else hi = t;
    }
    T_INT_EQ(gr_self_intersections(grid, hit, 4, &n), GR_OK);
    T_INT_EQ(n, 1);
    T_NEAR(hit[0].point[0], 0.5, 1.3e-3);
    T_NEAR(hit[0].point[1], cub(c, lo, 1), 1.3e-3);
    T_NEAR(hit[0].param[0], lo, 2e-3);
    T_NEAR(hit[0].param[1], 1 - lo, 2e-3);
    gr_grid_free(grid);
}
#endif

/* §5.1: the box grows by w on all sides, h tan θ_r toward the viewer,
   d tan θ_r away from it and (h + d) tan θ_i toward the light; a groove
   only w'_E away is found only with that view */
static void search_box_enlargement(void)
{
    static const double sec[] = {-0.01, 0, -0.005, 0.01, 0, -0.03, 0.01, 0}; /* w 0.01, h 0.01, d 0.03 */
    static unsigned char scratch[1 << 20];
    const double v[] = {0.248, 0.1, 0.248, 0.9};
    const double *paths[] = {v};
    const int counts[] = {2};
    gr_grid_t *grid = build(paths, counts, 1, sec, 4, GR_PATH_POLYLINE);
    double t60 = tan(M_PI / 3), light[3] = {0, -sqrt(0.5), sqrt(0.5)};
    gr_query_t q;
    gr_junctions_t j;
    T_EQ(grid->h, 0.01);
    T_EQ(grid->d, 0.03);
    memset(&q, 0, sizeof q);
    q.footprint.center[0] = 0.3; q.footprint.center[1] = 0.5;
    q.footprint.axis1[0] = 0.002; q.footprint.axis2[1] = 0.001;
    q.footprint.view[0] = sin(M_PI / 3); q.footprint.view[2] = cos(M_PI / 3);
    q.lights = light;
    q.light_count = 1;
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_OK);
    T_NEAR(j.box[0], 0.3 - 0.012 - 0.03 * t60, 1e-15);
    T_NEAR(j.box[2], 0.3 + 0.012 + 0.01 * t60, 1e-15);
    T_NEAR(j.box[1], 0.5 - 0.011 - 0.04, 1e-15);
    T_NEAR(j.box[3], 0.5 + 0.011, 1e-15);
    T_INT_EQ(j.grooves, 1); /* 0.052 to the left, inside w'_E = 0.052 + ... */
    q.footprint.view[0] = 0; q.footprint.view[2] = 1;
    q.light_count = 0;
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_OK);
    T_INT_EQ(j.grooves, 0);
    T_NEAR(j.box[0], 0.3 - 0.012, 1e-15);
    q.footprint.view[0] = -sin(M_PI / 3); q.footprint.view[2] = cos(M_PI / 3); /* viewer on the other side */
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_OK);
    T_INT_EQ(j.grooves, 0);
    gr_grid_free(grid);
}

/* the texture seam: grooves running across a repeating tile (their ends
   meet across the seam, so they are not ends) cross at u = 0.001, which
   the footprint at u = 0.999 sees at u = 1.001 in its own image */
static void detect_across_seam(void)
{
    const double h[] = {0, 0.5, 1, 0.5}, v[] = {0.001, 0, 0.001, 1};
    gr_groove_desc_t g[2];
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_junctions_t j;
    memset(&d, 0, sizeof d);
    memset(g, 0, sizeof g);
    g[0].points = h; g[0].point_count = 2; g[0].section = vsec; g[0].section_count = 3;
    g[1].points = v; g[1].point_count = 2; g[1].section = vsec; g[1].section_count = 3;
    d.grooves = g;
    d.groove_count = 2;
    T_INT_EQ(gr_grid_build(&d, &grid, NULL), GR_OK);
    j = detect_at(grid, 0.999, 0.5, 0.003, NULL, NULL, 0);
    T_INT_EQ(j.grooves, 2);
    T_INT_EQ(j.count, 1);
    T_INT_EQ(j.items[0].kind, GR_JUNCTION_CROSSING);
    T_NEAR(j.items[0].point[0], 1.001, 1e-15);
    T_NEAR(j.items[0].point[1], 0.5, 1e-15);
    j = detect_at(grid, 0.5, 0.999, 0.003, NULL, NULL, 0); /* the seam in v: nothing */
    T_INT_EQ(j.count, 0);
    gr_grid_free(grid);
}

static void detect_bad_input(void)
{
    static unsigned char scratch[1 << 20];
    const double h[] = {0.1, 0.5, 0.9, 0.5};
    const double *paths[] = {h};
    const int counts[] = {2};
    gr_grid_t *grid = build(paths, counts, 1, vsec, 3, GR_PATH_POLYLINE);
    gr_query_t q;
    gr_junctions_t j;
    gr_self_hit_t bad;
    int n;
    memset(&q, 0, sizeof q);
    memset(&bad, 0, sizeof bad);
    q.footprint.view[2] = 1;
    T_INT_EQ(gr_detect(NULL, &q, NULL, 0, scratch, sizeof scratch, &j), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, gr_query_scratch_bytes(grid) - 1, &j), GR_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(gr_detect(grid, &q, NULL, 1, scratch, sizeof scratch, &j), GR_ERR_INVALID_ARG);
    bad.groove = 5;
    T_INT_EQ(gr_detect(grid, &q, &bad, 1, scratch, sizeof scratch, &j), GR_ERR_INVALID_ARG);
    q.light_count = GR_MAX_LIGHTS + 1;
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_ERR_INVALID_ARG);
    q.light_count = 0;
    q.footprint.center[0] = NAN;
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_ERR_NOT_FINITE);
    q.footprint.center[0] = 0.5;
    q.footprint.view[2] = -1; /* below the horizon: no junctions, not an error */
    T_INT_EQ(gr_detect(grid, &q, NULL, 0, scratch, sizeof scratch, &j), GR_OK);
    T_INT_EQ(j.count, 0);
    T_INT_EQ(gr_self_intersections(NULL, NULL, 0, &n), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_self_intersections(grid, NULL, 1, &n), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_self_intersections(grid, NULL, 0, &n), GR_OK);
    T_INT_EQ(n, 0);
    gr_grid_free(grid);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(detect_x_crossing), T_CASE(detect_oblique_and_parallel), T_CASE(detect_overlap_far_from_meeting),
        T_CASE(detect_t_intersected_end),
        T_CASE(detect_isolated_end), T_CASE(detect_corner), T_CASE(stiff_distance_test_threshold),
        T_CASE(self_intersection_polyline),
        T_CASE(self_intersection_two_loops),
#ifndef GR_NO_CURVES
        T_CASE(self_intersection_cubic),
        T_CASE(self_intersection_chain_cut_at_a_joint),
#endif
        T_CASE(search_box_enlargement), T_CASE(detect_across_seam), T_CASE(detect_bad_input),
    };
    return T_RUN(argc, argv, cases);
}
