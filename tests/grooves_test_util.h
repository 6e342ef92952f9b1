/* Helpers shared by the grooves.h tests: a square footprint query, running
   it with scratch of the size the grid asks for, and reading the facet list.
   Include after test.h and grooves.h. */
#ifndef FILIGREE_GROOVES_TEST_UTIL_H
#define FILIGREE_GROOVES_TEST_UTIL_H

/* A square footprint of half-size r centred on (cu, cv), seen from the
   direction (ex, ey, ez) (texture space, normalised here). */
static gr_query_t gt_query(double cu, double cv, double r, double ex, double ey, double ez)
{
    gr_query_t q;
    double len = sqrt(ex * ex + ey * ey + ez * ez);
    memset(&q, 0, sizeof q);
    q.footprint.center[0] = cu;
    q.footprint.center[1] = cv;
    q.footprint.axis1[0] = r;
    q.footprint.axis2[1] = r;
    q.footprint.view[0] = ex / len;
    q.footprint.view[1] = ey / len;
    q.footprint.view[2] = ez / len;
    return q;
}

/* gr_query with exactly gr_query_scratch_bytes() of scratch (so ASan sees
   any overrun); one check that it succeeded. */
static int gt_run(const gr_grid_t *grid, const gr_query_t *q, gr_facet_list_t *list)
{
    size_t need = gr_query_scratch_bytes(grid);
    void *scratch = malloc(need);
    gr_result_t r = gr_query(grid, q, scratch, need, list);
    free(scratch);
    T_INT_EQ(r, GR_OK);
    return r == GR_OK;
}

/* The entry of facet index `facet` (-1: ground), NULL if absent. */
static const gr_facet_t *gt_entry(const gr_facet_list_t *l, int facet)
{
    int i;
    for (i = 0; i < l->count; i++)
        if (l->facets[i].facet == facet) return &l->facets[i];
    return NULL;
}
static double gt_ratio_of(const gr_facet_list_t *l, int facet)
{
    const gr_facet_t *f = gt_entry(l, facet);
    return f ? f->ratio : 0.0;
}
/* The summed ratio of (groove g, facet f) in a list; g = f = -1 the ground. */
static double gt_ratio_gf(const gr_facet_list_t *l, int g, int f)
{
    double s = 0;
    int i;
    for (i = 0; i < l->count; i++)
        if (l->facets[i].groove == g && l->facets[i].facet == f) s += l->facets[i].ratio;
    return s;
}
static double gt_ratio_sum(const gr_facet_list_t *l)
{
    double s = 0;
    int i;
    for (i = 0; i < l->count; i++) s += l->facets[i].ratio;
    return s;
}

/* A cubic Bézier (4 points) split at t by de Casteljau into its halves
   h0 (t in [0, t]) and h1 ([t, 1]), 4 points each: the oracle gets a
   self-crossing loop as two paths (it never carves a path with itself). */
static void gt_cubic_halves(const double *cub, double t, double *h0, double *h1)
{
    double q[8];
    int k, i;
    memcpy(q, cub, sizeof q);
    h0[0] = cub[0]; h0[1] = cub[1];
    h1[6] = cub[6]; h1[7] = cub[7];
    for (k = 0; k < 3; k++) {
        for (i = 0; i < 3 - k; i++) {
            q[2 * i] = (1 - t) * q[2 * i] + t * q[2 * i + 2];
            q[2 * i + 1] = (1 - t) * q[2 * i + 1] + t * q[2 * i + 3];
        }
        h0[2 * (k + 1)] = q[0]; h0[2 * (k + 1) + 1] = q[1];
        h1[2 * (2 - k)] = q[2 * (2 - k)]; h1[2 * (2 - k) + 1] = q[2 * (2 - k) + 1];
    }
}

#endif
