/* grooves.h built with GR_NO_INTERSECTIONS: §5-6 left out. A footprint on
   a crossing gets §4's answer with its flag (no polygon path), still a
   partition, and the query scratch is only §4's. */
#define GR_NO_INTERSECTIONS
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "test.h"
#include "grooves_test_util.h"

static void crossing_answered_by_section_4(void)
{
    static const double a[4] = {0.2, 0.5, 0.8, 0.5}, b[4] = {0.5, 0.2, 0.5, 0.8};
    static const double sec[6] = {-0.01, 0, 0, -0.02, 0.01, 0};
    gr_groove_desc_t g[2];
    gr_grid_desc_t gd;
    gr_grid_t *grid;
    gr_facet_list_t list;
    gr_query_t q = gt_query(0.5, 0.5, 0.01, 0.2, 0.1, 1);
    memset(g, 0, sizeof g);
    g[0].points = a; g[1].points = b;
    g[0].point_count = g[1].point_count = 2;
    g[0].section = g[1].section = sec;
    g[0].section_count = g[1].section_count = 3;
    memset(&gd, 0, sizeof gd);
    gd.grooves = g; gd.groove_count = 2; gd.no_wrap = 1;
    if (!T_INT_EQ(gr_grid_build(&gd, &grid, NULL), GR_OK)) return;
    T_LE(gr_query_scratch_bytes(grid), 1 << 16);
    if (gt_run(grid, &q, &list)) {
        T_CHECK(list.flags & GR_LIST_NONPARALLEL);
        T_CHECK(!(list.flags & GR_LIST_POLYGON));
        T_NEAR(gt_ratio_sum(&list), 1, 1e-9);
    }
    gr_grid_free(grid);
}

/* A polyline whose first or last point is repeated has the same ends as
   without the repeat: §4's nearest point skips the zero-length piece, and
   the end was taken only on the first and last piece (so it was never
   seen, and a footprint before the start got walls of a groove that is
   not there). Footprints along the path past both ends and across it,
   against the path without the repeats. */
static void repeated_end_points_keep_the_ends(void)
{
    static const double ab[4] = {0.3, 0.5, 0.7, 0.5}, aab[6] = {0.3, 0.5, 0.3, 0.5, 0.7, 0.5}, abb[6] = {0.3, 0.5, 0.7, 0.5, 0.7, 0.5};
    static const double sec[6] = {-0.02, 0, 0, -0.03, 0.02, 0};
    const double *paths[3] = {ab, aab, abb};
    gr_grid_t *grid[3] = {NULL, NULL, NULL};
    int p, i, k, moved = 0;
    for (p = 0; p < 3; p++) {
        gr_groove_desc_t g;
        gr_grid_desc_t gd;
        memset(&g, 0, sizeof g);
        memset(&gd, 0, sizeof gd);
        g.points = paths[p], g.point_count = p ? 3 : 2, g.section = sec, g.section_count = 3;
        gd.grooves = &g, gd.groove_count = 1, gd.no_wrap = 1;
        if (!T_INT_EQ(gr_grid_build(&gd, &grid[p], NULL), GR_OK)) goto done;
    }
    for (i = 0; i <= 60; i++) {
        double u = 0.26 + 0.48 * i / 60.0; /* from before the start to past the end */
        gr_facet_list_t l[3];
        gr_query_t q = gt_query(u, 0.5 + 0.004 * (i % 5), 0.005, 0.1 * (i % 3), 0.05, 1);
        for (p = 0; p < 3; p++) gt_run(grid[p], &q, &l[p]);
        moved += l[0].count == 1; /* some footprints miss the groove: the ends are crossed */
        for (p = 1; p < 3; p++) {
            T_INT_EQ(l[p].flags, l[0].flags);
            if (!T_INT_EQ(l[p].count, l[0].count)) continue;
            for (k = 0; k < l[0].count; k++) T_NEAR(gt_ratio_of(&l[p], l[0].facets[k].facet), l[0].facets[k].ratio, 1e-12);
        }
    }
    T_GT(moved, 4);
done:
    for (p = 0; p < 3; p++) gr_grid_free(grid[p]);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(crossing_answered_by_section_4),
        T_CASE(repeated_end_points_keep_the_ends),
    };
    return T_RUN(argc, argv, cases);
}
