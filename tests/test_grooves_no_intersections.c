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

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(crossing_answered_by_section_4),
    };
    return T_RUN(argc, argv, cases);
}
