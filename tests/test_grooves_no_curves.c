/* grooves.h built with GR_NO_CURVES and GR_NO_OVERSAMPLE (issue 7, item 6):
   Bézier paths are refused with a clear error naming the groove, and
   polylines work as usual (the closed-form V-groove from above: a/2r per
   slope). */
#define GR_NO_CURVES
#define GR_NO_OVERSAMPLE
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "test.h"

static void curves_are_refused(void)
{
    static const double sec[6] = {-0.01, 0, 0, -0.01, 0.01, 0};
    static const double quad[6] = {0.1, 0.1, 0.5, 0.9, 0.9, 0.1};
    gr_groove_desc_t g[2];
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_diag_t diag;
    memset(g, 0, sizeof g);
    memset(&d, 0, sizeof d);
    g[0].points = quad; g[0].point_count = 2; g[0].section = sec; g[0].section_count = 3;
    g[1] = g[0];
    g[1].kind = GR_PATH_QUADRATIC;
    g[1].point_count = 3;
    d.grooves = g;
    d.groove_count = 2;
    T_INT_EQ(gr_grid_build(&d, &grid, &diag), GR_ERR_UNSUPPORTED);
    T_CHECK(grid == NULL);
    T_INT_EQ(diag.element, 1);
    T_CHECK(strstr(diag.message, "groove 1: ") != NULL);
    T_CHECK(strstr(diag.message, "GR_NO_CURVES") != NULL);
}

static void polylines_still_work(void)
{
    static const double a = 0.01, r = 0.05, sec[6] = {-0.01, 0, 0, -0.02, 0.01, 0}, path[4] = {0.5, 0, 0.5, 1};
    gr_groove_desc_t g;
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    gr_query_t q;
    gr_facet_list_t l;
    size_t need;
    void *scratch;
    int i;
    double slopes = 0;
    memset(&g, 0, sizeof g);
    memset(&d, 0, sizeof d);
    memset(&q, 0, sizeof q);
    g.points = path; g.point_count = 2; g.section = sec; g.section_count = 3;
    d.grooves = &g;
    d.groove_count = 1;
    if (!T_INT_EQ(gr_grid_build(&d, &grid, NULL), GR_OK)) return;
    q.footprint.center[0] = 0.5; q.footprint.center[1] = 0.5;
    q.footprint.axis1[0] = r; q.footprint.axis2[1] = 0.3; /* long along the groove */
    q.footprint.view[2] = 1;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_OK);
    T_INT_EQ(l.subfootprints, 1);
    for (i = 0; i < l.count; i++) if (l.facets[i].groove == 0) slopes += l.facets[i].ratio;
    T_NEAR(slopes, a / r, 1e-14);
    free(scratch);
    gr_grid_free(grid);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(curves_are_refused),
        T_CASE(polylines_still_work),
    };
    return T_RUN(argc, argv, cases);
}
