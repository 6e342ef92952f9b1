/* grooves.h polygon path, first steps (issue 8, §5.2): the footprint as a
   polygon and its projection onto a facet in groove space (eqs. 7-8),
   clipped to the facet's bounds. Oracles: the quad's and rhombus's areas
   4|A1 x A2| and 2|A1 x A2|; a 3D ray-plane intersection written out
   independently in world-like (u, v, w) coordinates; a stratified sample
   of the footprint for the clipped ratio; and gr_query() (part 1, §4) for a
   groove seen from straight above, where nothing is masked. */
#include "grooves.h"
#include "test.h"

static void footprint_polygon_shapes(void)
{
    t_rng_t g = {31};
    long trial, n = t_count(1000);
    for (trial = 0; trial < n; trial++) {
        gr_footprint_t fp;
        double q[8], r[8], cr;
        memset(&fp, 0, sizeof fp);
        fp.center[0] = t_rng_range(&g, -2, 2); fp.center[1] = t_rng_range(&g, -2, 2);
        fp.axis1[0] = t_rng_range(&g, -1, 1); fp.axis1[1] = t_rng_range(&g, -1, 1);
        fp.axis2[0] = t_rng_range(&g, -1, 1); fp.axis2[1] = t_rng_range(&g, -1, 1);
        cr = fabs(fp.axis1[0] * fp.axis2[1] - fp.axis1[1] * fp.axis2[0]);
        gr_footprint_polygon(&fp, GR_FP_QUAD, q);
        gr_footprint_polygon(&fp, GR_FP_RHOMBUS, r);
        T_NEAR(gr_poly_area(q, 4), 4 * cr, 1e-14); /* counter-clockwise: positive */
        T_NEAR(gr_poly_area(r, 4), 2 * cr, 1e-14);
        T_NEAR(q[0] + q[2] + q[4] + q[6], 4 * fp.center[0], 1e-14); /* centred on F */
        T_NEAR(r[1] + r[3] + r[5] + r[7], 4 * fp.center[1], 1e-14);
    }
}

/* independent eq. 7-8: the ray F + t E against the facet plane in (u, v, w) */
static void ray_plane(const gr_facet_geom_t *fc, const double e[3], double u, double v, double out[2])
{
    double T[3] = {fc->tangent[0], fc->tangent[1], 0}, B[3] = {-fc->tangent[1], fc->tangent[0], 0};
    double db = fc->c1[0] - fc->c0[0], dw = fc->c1[1] - fc->c0[1], len = hypot(db, dw);
    double D[3], C[3], N[3], F[3] = {u, v, 0}, X[3], t;
    int k;
    for (k = 0; k < 3; k++) {
        D[k] = db * B[k] + (k == 2 ? dw : 0);
        C[k] = (k < 2 ? fc->point[k] : 0) + fc->c0[0] * B[k] + (k == 2 ? fc->c0[1] : 0);
    }
    N[0] = T[1] * D[2] - T[2] * D[1]; N[1] = T[2] * D[0] - T[0] * D[2]; N[2] = T[0] * D[1] - T[1] * D[0];
    t = (N[0] * (C[0] - F[0]) + N[1] * (C[1] - F[1]) + N[2] * (C[2] - F[2])) / (N[0] * e[0] + N[1] * e[1] + N[2] * e[2]);
    for (k = 0; k < 3; k++) X[k] = F[k] + t * e[k];
    out[0] = T[0] * (X[0] - fc->point[0]) + T[1] * (X[1] - fc->point[1]);
    out[1] = (D[0] * (X[0] - C[0]) + D[1] * (X[1] - C[1]) + D[2] * (X[2] - C[2])) / len;
}

/* random facets, views and footprints: every projected corner matches the
   independent ray-plane point; the clipped ratio matches a 300 x 300
   stratified sample of the footprint (each sample through ray_plane)
   within the sample's boundary error, 4 x 2/300 < 0.027 */
static void facet_clip_vs_ray_plane(void)
{
    t_rng_t g = {57};
    long trial, n = t_count(200);
    const int S = 300;
    for (trial = 0; trial < n; trial++) {
        gr_footprint_t fp;
        gr_facet_geom_t fc;
        double poly[8], proj[8], clip[64], work[64], e[3], th, ph, af, ac, inside = 0;
        int nc, k, i, j;
        memset(&fp, 0, sizeof fp);
        fp.center[0] = t_rng_range(&g, -0.02, 0.02); fp.center[1] = t_rng_range(&g, -0.02, 0.02);
        fp.axis1[0] = t_rng_range(&g, 0.002, 0.02); fp.axis1[1] = t_rng_range(&g, -0.005, 0.005);
        fp.axis2[0] = t_rng_range(&g, -0.005, 0.005); fp.axis2[1] = t_rng_range(&g, 0.002, 0.02);
        th = t_rng_range(&g, 0, 1.3); ph = t_rng_range(&g, 0, 2 * M_PI);
        e[0] = sin(th) * cos(ph); e[1] = sin(th) * sin(ph); e[2] = cos(th);
        ph = t_rng_range(&g, 0, 2 * M_PI);
        fc.point[0] = t_rng_range(&g, -0.01, 0.01); fc.point[1] = t_rng_range(&g, -0.01, 0.01);
        fc.tangent[0] = cos(ph); fc.tangent[1] = sin(ph);
        fc.c0[0] = t_rng_range(&g, -0.02, 0.0); fc.c0[1] = t_rng_range(&g, -0.02, 0);
        fc.c1[0] = fc.c0[0] + t_rng_range(&g, 0.001, 0.02); fc.c1[1] = t_rng_range(&g, -0.02, 0);
        gr_footprint_polygon(&fp, GR_FP_QUAD, poly);
        T_INT_EQ(gr_facet_clip(poly, 4, &fc, e, proj, clip, work, 32, &nc, &af, &ac), GR_OK);
        for (k = 0; k < 4; k++) {
            double want[2];
            ray_plane(&fc, e, poly[2 * k], poly[2 * k + 1], want);
            T_NEAR(proj[2 * k], want[0], 1e-13);
            T_NEAR(proj[2 * k + 1], want[1], 1e-13);
        }
        for (j = 0; j < S; j++)
            for (i = 0; i < S; i++) {
                double a = -1 + (i + 0.5) * 2.0 / S, b = -1 + (j + 0.5) * 2.0 / S, p[2];
                ray_plane(&fc, e, fp.center[0] + a * fp.axis1[0] + b * fp.axis2[0],
                          fp.center[1] + a * fp.axis1[1] + b * fp.axis2[1], p);
                inside += p[1] >= 0 && p[1] <= hypot(fc.c1[0] - fc.c0[0], fc.c1[1] - fc.c0[1]);
            }
        T_GT(af, 0);
        T_NEAR(ac / af, inside / ((double)S * S), 0.027);
    }
}

/* a V groove along v at u = 0.5 seen from straight above: nothing masks,
   so §4's ratios (gr_query) are the clipped-area ratios of §5.2 */
static void vertical_view_matches_query(void)
{
    static const double sec[] = {-0.01, 0, 0, -0.02, 0.01, 0};
    static const double path[] = {0.5, 0, 0.5, 1};
    static unsigned char scratch[1 << 20];
    gr_groove_desc_t gd;
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_query_t q;
    gr_facet_list_t list;
    double offs[3] = {0.005, -0.012, 0.0}, poly[8], proj[8], clip[64], work[64], af, ac;
    int o, f, k, nc;
    memset(&gd, 0, sizeof gd);
    memset(&d, 0, sizeof d);
    gd.points = path; gd.point_count = 2; gd.section = sec; gd.section_count = 3;
    d.grooves = &gd; d.groove_count = 1; d.base_reflectance = 9; gd.reflectance = 3;
    T_INT_EQ(gr_grid_build(&d, &grid, NULL), GR_OK);
    for (o = 0; o < 3; o++) {
        gr_facet_geom_t fc;
        memset(&q, 0, sizeof q);
        q.footprint.center[0] = 0.5 + offs[o]; q.footprint.center[1] = 0.4;
        q.footprint.axis1[0] = 0.008; q.footprint.axis2[1] = 0.008;
        q.footprint.view[2] = 1;
        T_INT_EQ(gr_query(grid, &q, scratch, sizeof scratch, &list), GR_OK);
        gr_footprint_polygon(&q.footprint, GR_FP_QUAD, poly);
        fc.point[0] = 0.5; fc.point[1] = 0.4; fc.tangent[0] = 0; fc.tangent[1] = 1;
        for (f = 0; f < 2; f++) {
            double want = 0;
            fc.c0[0] = sec[2 * f]; fc.c0[1] = sec[2 * f + 1];
            fc.c1[0] = sec[2 * f + 2]; fc.c1[1] = sec[2 * f + 3];
            T_INT_EQ(gr_facet_clip(poly, 4, &fc, q.footprint.view, proj, clip, work, 32, &nc, &af, &ac), GR_OK);
            for (k = 0; k < list.count; k++)
                if (list.facets[k].groove == 0 && list.facets[k].facet == f) want += list.facets[k].ratio;
            T_NEAR(ac / af, want, 1e-12);
        }
    }
    gr_grid_free(grid);
}

/* Stiff: a vertical facet (db = 0) seen from straight above is edge-on:
   eq. 8's denominator is 0; areas 0, no polygon */
static void stiff_edge_on_facet(void)
{
    gr_footprint_t fp;
    gr_facet_geom_t fc;
    double poly[8], proj[8], clip[64], work[64], e[3] = {0, 0, 1}, af = -1, ac = -1;
    int nc = -1;
    memset(&fp, 0, sizeof fp);
    fp.axis1[0] = 0.01; fp.axis2[1] = 0.01;
    memset(&fc, 0, sizeof fc);
    fc.tangent[1] = 1;
    fc.c0[0] = 0.002; fc.c0[1] = 0;
    fc.c1[0] = 0.002; fc.c1[1] = -0.01;
    gr_footprint_polygon(&fp, GR_FP_QUAD, poly);
    T_INT_EQ(gr_facet_clip(poly, 4, &fc, e, proj, clip, work, 32, &nc, &af, &ac), GR_OK);
    T_EQ(af, 0);
    T_EQ(ac, 0);
    T_INT_EQ(nc, 0);
    /* tilted 1e-6 rad it is seen: a thin sliver with a finite ratio */
    e[0] = sin(1e-6); e[2] = cos(1e-6);
    T_INT_EQ(gr_facet_clip(poly, 4, &fc, e, proj, clip, work, 32, &nc, &af, &ac), GR_OK);
    T_GT(af, 0);
    T_LE(ac, af * (1 + 1e-12));
}

static void facet_clip_bad_input(void)
{
    gr_facet_geom_t fc;
    double poly[8] = {0, 0, 1, 0, 1, 1, 0, 1}, proj[8], clip[64], work[64], e[3] = {0, 0, 1}, af, ac;
    int nc;
    memset(&fc, 0, sizeof fc);
    fc.tangent[1] = 1;
    fc.c1[0] = 1;
    T_INT_EQ(gr_facet_clip(NULL, 4, &fc, e, proj, clip, work, 32, &nc, &af, &ac), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_facet_clip(poly, 2, &fc, e, proj, clip, work, 32, &nc, &af, &ac), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_facet_clip(poly, 4, &fc, e, proj, clip, work, 7, &nc, &af, &ac), GR_ERR_INVALID_ARG);
    poly[3] = NAN;
    T_INT_EQ(gr_facet_clip(poly, 4, &fc, e, proj, clip, work, 32, &nc, &af, &ac), GR_ERR_NOT_FINITE);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(footprint_polygon_shapes), T_CASE(facet_clip_vs_ray_plane), T_CASE(vertical_view_matches_query),
        T_CASE(stiff_edge_on_facet), T_CASE(facet_clip_bad_input),
    };
    return T_RUN(argc, argv, cases);
}
