/* grooves.h §5.2-5.3 at crossings (issue 8): footprint polygons projected
   onto each facet and clipped (gr_facet_clip), minus the crossing groove's
   cross-section projected onto that facet (gr_section_on_facet, with the
   ground as the facet parallel to UV), measured with gr_poly_boolean.
   Seen from straight above nothing is masked (§5.4 has no work), so the
   ratios r_i = A_R / A_F must match an independent raster of the carved
   surface (800 x 800 samples; at each, the deepest groove floor, since the
   grooves remove the union of their prisms) within 1e-2, and the facets
   and the ground must partition the footprint (Σ r_i = 1 to rounding).
   The Embree oracle (tests/grooves_oracle.h) is not used here: it sweeps
   each groove's floor independently and does not carve at crossings, so
   a ray stops on the higher of two overlapping floors (measured: it
   matches a raster of max(z_0, z_1), not of min, to 4e-4). */
#include "grooves.h"
#include "test.h"
static const double VSEC[6] = {-0.01, 0, 0, -0.02, 0.01, 0};

/* the groove through (0.5, 0.5) at angle a, frame at the point nearest c */
static void frame_at(double a, const double c[2], gr_facet_geom_t *fc)
{
    double t[2] = {cos(a), sin(a)}, s = (c[0] - 0.5) * t[0] + (c[1] - 0.5) * t[1];
    memset(fc, 0, sizeof *fc);
    fc->tangent[0] = t[0];
    fc->tangent[1] = t[1];
    fc->point[0] = 0.5 + s * t[0];
    fc->point[1] = 0.5 + s * t[1];
}

static double area_minus(const double *ring, int n, const gr_polyset_t *cut, double *traps, int *ntraps)
{
    static unsigned char scratch[1 << 20];
    gr_polyset_t a;
    double area = -1;
    memset(&a, 0, sizeof a);
    a.points = ring;
    a.point_count = n;
    T_INT_EQ(gr_poly_boolean(&a, cut, GR_POLY_DIFFERENCE, scratch, sizeof scratch, traps, 1024, ntraps, &area), GR_OK);
    return area;
}

/* r_i of facet f of groove g (angle ang[g]) crossed by the other groove;
   f = -1: the ground (in groove 0's frame), minus both mouths */
static double ratio(const double *ang, int g, int f, const gr_footprint_t *fp)
{
    static double traps[8 * 1024];
    gr_facet_geom_t fc, oc;
    gr_polyset_t cut;
    double poly[8], proj[8], clip[64], work[64], pts[64], af, ac, bounds[4], ar;
    int sizes[16], nc, k, o = 1 - g, nt = 0;
    frame_at(ang[g], fp->center, &fc);
    frame_at(ang[o], fp->center, &oc);
    if (f < 0) { fc.c0[0] = -1; fc.c1[0] = 1; }
    else { memcpy(fc.c0, VSEC + 2 * f, sizeof fc.c0); memcpy(fc.c1, VSEC + 2 * f + 2, sizeof fc.c1); }
    gr_footprint_polygon(fp, GR_FP_QUAD, poly);
    T_INT_EQ(gr_facet_clip(poly, 4, &fc, fp->view, proj, clip, work, 32, &nc, &af, &ac), GR_OK);
    if (nc == 0) return 0;
    bounds[0] = bounds[1] = HUGE_VAL;
    bounds[2] = bounds[3] = -HUGE_VAL;
    for (k = 0; k < nc; k++) {
        bounds[0] = fmin(bounds[0], clip[2 * k]); bounds[2] = fmax(bounds[2], clip[2 * k]);
        bounds[1] = fmin(bounds[1], clip[2 * k + 1]); bounds[3] = fmax(bounds[3], clip[2 * k + 1]);
    }
    T_INT_EQ(gr_section_on_facet(&fc, oc.point, oc.tangent, VSEC, 3, bounds, pts, 32, sizes, 16, &cut), GR_OK);
    ar = area_minus(clip, nc, &cut, traps, &nt);
    if (f < 0) { /* the own mouth: y = b + 1 in [0.99, 1.01] */
        double mouth[8] = {bounds[0], 0.99, bounds[2], 0.99, bounds[2], 1.01, bounds[0], 1.01};
        gr_polyset_t rest, m;
        static unsigned char scratch[1 << 20];
        memset(&rest, 0, sizeof rest);
        memset(&m, 0, sizeof m);
        rest.points = traps; rest.point_count = 4 * nt; rest.ring_count = nt;
        m.points = mouth; m.point_count = 4;
        if (nt == 0) return 0;
        T_INT_EQ(gr_poly_boolean(&rest, &m, GR_POLY_DIFFERENCE, scratch, sizeof scratch, NULL, 0, NULL, &ar), GR_OK);
    }
    return ar / af;
}

/* height and facet of a V section at signed distance b (-1: outside) */
static double floor_at(double b, int *facet)
{
    int k;
    for (k = 0; k < 2; k++)
        if (b >= VSEC[2 * k] && b <= VSEC[2 * k + 2]) {
            double t = (b - VSEC[2 * k]) / (VSEC[2 * k + 2] - VSEC[2 * k]);
            *facet = k;
            return VSEC[2 * k + 1] + t * (VSEC[2 * k + 3] - VSEC[2 * k + 1]);
        }
    *facet = -1;
    return 0;
}

/* the raster oracle: fractions of the footprint where facet f of groove g
   is the surface (index 2g + f), and the ground (index 4) */
static void raster(const double *ang, const gr_footprint_t *fp, double frac[5])
{
    const int N = 800;
    int i, j, g, k;
    for (k = 0; k < 5; k++) frac[k] = 0;
    for (j = 0; j < N; j++)
        for (i = 0; i < N; i++) {
            double a = -1 + (i + 0.5) * 2.0 / N, c = -1 + (j + 0.5) * 2.0 / N, best = 0;
            double u = fp->center[0] + a * fp->axis1[0] + c * fp->axis2[0];
            double v = fp->center[1] + a * fp->axis1[1] + c * fp->axis2[1];
            int who = 4;
            for (g = 0; g < 2; g++) {
                double b = -sin(ang[g]) * (u - 0.5) + cos(ang[g]) * (v - 0.5), z;
                int f;
                z = floor_at(b, &f);
                if (f >= 0 && z < best) { best = z; who = 2 * g + f; }
            }
            frac[who] += 1.0 / ((double)N * N);
        }
}

static double check_crossing(double a1, double u, double v, double half)
{
    double ang[2] = {M_PI / 2, a1}, sum = 0, worst = 0, r, want[5];
    gr_footprint_t fp;
    int g, f;
    memset(&fp, 0, sizeof fp);
    fp.center[0] = u; fp.center[1] = v;
    fp.axis1[0] = half; fp.axis2[1] = half;
    fp.view[2] = 1;
    raster(ang, &fp, want);
    for (g = 0; g < 2; g++)
        for (f = 0; f < 2; f++) {
            r = ratio(ang, g, f, &fp);
            sum += r;
            T_NEAR(r, want[2 * g + f], 1e-2);
            worst = fmax(worst, fabs(r - want[2 * g + f]));
        }
    r = ratio(ang, 0, -1, &fp);
    sum += r;
    T_NEAR(r, want[4], 1e-2);
    worst = fmax(worst, fabs(r - want[4]));
    T_NEAR(sum, 1, 1e-12);
    return worst;
}

/* X: perpendicular V grooves, footprints at, beside and around the crossing */
static void x_crossing_vs_raster(void)
{
    double w = 0;
    w = fmax(w, check_crossing(0, 0.5, 0.5, 0.012));
    w = fmax(w, check_crossing(0, 0.506, 0.493, 0.008));
    w = fmax(w, check_crossing(0, 0.51, 0.5, 0.03));
    printf("    X crossing: largest |r - raster| %.2e\n", w);
}

/* oblique: 60 and 20 degrees between the grooves */
static void oblique_crossing_vs_raster(void)
{
    double w = 0;
    w = fmax(w, check_crossing(M_PI / 2 - M_PI / 3, 0.5, 0.5, 0.012));
    w = fmax(w, check_crossing(M_PI / 2 - M_PI / 3, 0.503, 0.51, 0.02));
    w = fmax(w, check_crossing(M_PI / 2 - 0.35, 0.5, 0.5, 0.015));
    printf("    oblique crossings: largest |r - raster| %.2e\n", w);
}

/* the ground's special case alone: a flat floor (a U groove's bottom,
   parallel to UV at w = -0.02) cut by a V groove crossing at 90 degrees
   keeps the part outside the V's width at that depth, which is zero
   (the V reaches -0.02 only at its axis): the cut is a zero-width strip */
static void stiff_floor_at_v_tip(void)
{
    gr_facet_geom_t fc;
    gr_polyset_t cut;
    double p2[2] = {0.5, 0.5}, t2[2] = {1, 0}, bounds[4] = {-0.05, 0, 0.05, 0.02}, pts[64];
    int sizes[16];
    memset(&fc, 0, sizeof fc);
    fc.point[0] = 0.5; fc.point[1] = 0.5; fc.tangent[1] = 1;
    fc.c0[0] = -0.01; fc.c0[1] = -0.01; fc.c1[0] = 0.01; fc.c1[1] = -0.01; /* floor at w = -0.01 */
    T_INT_EQ(gr_section_on_facet(&fc, p2, t2, VSEC, 3, bounds, pts, 32, sizes, 16, &cut), GR_OK);
    T_INT_EQ(cut.ring_count, 1);
    /* the V is 0.01 wide at w = -0.01: a strip across x of width 0.01 */
    T_NEAR(gr_poly_area(pts, sizes[0]), 0.01 * 0.02, 1e-17);
    fc.c0[1] = fc.c1[1] = -0.02; /* at the V's tip: a strip of width 0 */
    T_INT_EQ(gr_section_on_facet(&fc, p2, t2, VSEC, 3, bounds, pts, 32, sizes, 16, &cut), GR_OK);
    T_LE(cut.ring_count == 0 ? 0 : fabs(gr_poly_area(pts, sizes[0])), 1e-18);
    t2[0] = 0; t2[1] = 1; /* parallel grooves do not cut */
    T_INT_EQ(gr_section_on_facet(&fc, p2, t2, VSEC, 3, bounds, pts, 32, sizes, 16, &cut), GR_OK);
    T_INT_EQ(cut.ring_count, 0);
    T_INT_EQ(gr_section_on_facet(&fc, p2, t2, VSEC, 3, bounds, pts, 10, sizes, 16, &cut), GR_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(gr_section_on_facet(NULL, p2, t2, VSEC, 3, bounds, pts, 32, sizes, 16, &cut), GR_ERR_INVALID_ARG);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(x_crossing_vs_raster), T_CASE(oblique_crossing_vs_raster), T_CASE(stiff_floor_at_v_tip),
    };
    return T_RUN(argc, argv, cases);
}
