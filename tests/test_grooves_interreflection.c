/* grooves.h §6 specular inter-reflection (issue 8 item 5): gr_shade_indirect().
   Reference: a path tracer written here on the explicit groove geometry
   (tests/grooves_oracle.h builds the swept mesh and the holed ground in
   Embree); every facet is a perfect mirror, rays are traced from the
   footprint (stratified N x N over its parallelogram) and bounced until
   they reach the sky. E_k = the fraction of the footprint's energy that
   reaches the sky after exactly k bounces (k = 1..3); the footprint is
   sampled 4000 x 8 (across x along the groove, where nothing changes).
   gr_shade_indirect()
   reports the same through its host callback (§6.2), called per bounce
   with the depth. The grooves are straight and long and the footprint's
   A1 runs across them, so the line samples are exact here (the segment
   along the groove crosses no edge: Jones & Perry weight 0) and the bound
   is the reference's stratification, O(edges / 4000): 1e-3 per depth
   (4e-3 at FILIGREE_TEST_SCALE's 400 rays across).
   Named stiff cases: grazing view (E_w = 0.1), a deep groove whose first
   bounce points down into the other wall (a direction from below the
   texture plane, §6.1's inverted masking), a protruding ridge, depth 0
   equal to the direct result, and transmission handed to the host. */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "test.h"
#include "grooves_test_util.h"
#include "grooves_oracle.h"

#define REF_TOL 1e-3
#define MAXD 3

static const double VSEC[6] = {-0.01, 0, 0, -0.02, 0.01, 0};
static const double DEEP[6] = {-0.01, 0, 0, -0.05, 0.01, 0};
static const double RSEC[10] = {-0.01, 0, -0.005, -0.01, 0, 0.006, 0.005, -0.01, 0.01, 0};
static const double PATH[4] = {0.5, 0.05, 0.5, 0.95};

typedef struct cb_t { int want; double got; int calls; double inside; double dir[3]; } cb_t;

static void trace_cb(void *user, const double origin[3], const double dir[3], int depth, int inside, double weight,
                     double rgb[3])
{
    cb_t *c = (cb_t *)user;
    (void)origin;
    (void)weight;
    c->calls++;
    rgb[0] = rgb[1] = rgb[2] = 0;
    if (inside) {
        c->dir[0] = dir[0]; c->dir[1] = dir[1]; c->dir[2] = dir[2];
        rgb[0] = rgb[1] = rgb[2] = 1;
        return;
    }
    if (depth == c->want) rgb[0] = rgb[1] = rgb[2] = 1;
}

/* reference: energy reaching the sky after exactly k bounces, k = 0..MAXD */
static void reference(const gro_scene_t *sc, const gr_footprint_t *fp, int n, double *ek)
{
    int i, j, k;
    for (k = 0; k <= MAXD; k++) ek[k] = 0;
    for (j = 0; j < 8; j++)
        for (i = 0; i < n; i++) {
            double a = -1 + (2 * i + 1.0) / n, c = -1 + (2 * j + 1.0) / 8, o[3], d[3];
            o[0] = fp->center[0] + a * fp->axis1[0] + c * fp->axis2[0] + 0.2 * fp->view[0] / fp->view[2];
            o[1] = fp->center[1] + a * fp->axis1[1] + c * fp->axis2[1] + 0.2 * fp->view[1] / fp->view[2];
            o[2] = 0.2;
            for (k = 0; k < 3; k++) d[k] = -fp->view[k];
            for (k = 0; k <= MAXD + 1; k++) {
                gro_hit_t h = gro_scene_intersect(sc, o, d, 0, INFINITY);
                double dn;
                int m;
                if (h.kind == GRO_HIT_NONE) {
                    if (k <= MAXD) ek[k] += 1.0 / (8.0 * n);
                    break;
                }
                dn = d[0] * h.n[0] + d[1] * h.n[1] + d[2] * h.n[2];
                for (m = 0; m < 3; m++) {
                    d[m] -= 2 * dn * h.n[m];
                    o[m] = h.p[m] + sc->eps * h.n[m];
                }
            }
        }
}

static void shade_depths(const gr_grid_t *grid, const gr_query_t *q, const gr_specular_t *spec, double *ek)
{
    size_t need = gr_query_scratch_bytes(grid);
    void *scratch = malloc(need);
    int k;
    for (k = 0; k <= MAXD; k++) {
        gr_indirect_t ind;
        cb_t cb;
        double rgb[3];
        memset(&ind, 0, sizeof ind);
        memset(&cb, 0, sizeof cb);
        cb.want = k;
        ind.depth = MAXD;
        ind.specular = spec;
        ind.specular_count = 2;
        ind.trace = trace_cb;
        ind.trace_user = &cb;
        T_INT_EQ(gr_shade_indirect(grid, q, &ind, scratch, need, rgb, NULL), GR_OK);
        ek[k] = rgb[0];
    }
    free(scratch);
}

static gr_grid_t *one_groove(const double *sec, int nsec, gr_groove_desc_t *g)
{
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    memset(g, 0, sizeof *g);
    memset(&d, 0, sizeof d);
    g->points = PATH;
    g->point_count = 2;
    g->section = sec;
    g->section_count = nsec;
    g->reflectance = 1;
    d.grooves = g;
    d.groove_count = 1;
    d.no_wrap = 1;
    if (gr_grid_build(&d, &grid, NULL) != GR_OK) return NULL;
    return grid;
}

/* all-mirror materials (ids 0 and 1), the Embree device, and the
   reference's rays across the footprint */
static int mirror_setup(gr_specular_t *spec, gro_device_t *dev, int *n)
{
    int k;
    *n = (int)(4000 * t_scale());
    if (*n < 400) *n = 400;
    memset(spec, 0, 2 * sizeof *spec);
    for (k = 0; k < 3; k++) spec[0].kr[k] = spec[1].kr[k] = 1;
    if (gro_device_init(dev)) { T_FAIL("embree"); return 0; }
    return 1;
}

static void t_mirror_energy_vs_pathtraced(void)
{
    static const double views[5][3] = {{0, 0, 1}, {0.5, 0, 0.866}, {-0.7, 0.2, 0.685}, {0.995, 0, 0.0998}, {0.3, 0.3, 0.905}};
    static const char *vname[5] = {"top", "oblique", "oblique2", "grazing", "skew"};
    const double *secs[3] = {VSEC, DEEP, RSEC};
    static const int nsecs[3] = {3, 3, 5};
    static const char *sname[3] = {"V", "deep V", "ridge"};
    gr_specular_t spec[2];
    gro_device_t dev;
    int s, v, k, n;
    double worst = 0;
    if (!mirror_setup(spec, &dev, &n)) return;
    for (s = 0; s < 3; s++) {
        gr_groove_desc_t g;
        gr_grid_t *grid = one_groove(secs[s], nsecs[s], &g);
        gro_groove_t og = gro_from_gr(&g);
        gro_scene_t sc;
        if (!T_CHECK(grid) || !T_CHECK(gro_scene_build(&sc, dev.dev, &og, 1, NULL) == 0)) return;
        for (v = 0; v < 5; v++) {
            gr_query_t q = gt_query(0.5013, 0.5, 0.014, views[v][0], views[v][1], views[v][2]);
            double er[MAXD + 1], eg[MAXD + 1];
            q.line_samples = 2;
            reference(&sc, &q.footprint, n, er);
            shade_depths(grid, &q, spec, eg);
            printf("  %-7s %-8s E_k path-traced / line samples:", sname[s], vname[v]);
            for (k = 0; k <= MAXD; k++) {
                printf(" %.4f/%.4f", er[k], eg[k]);
                T_NEAR(eg[k], er[k], REF_TOL * 4000 / n);
                if (fabs(eg[k] - er[k]) > worst) worst = fabs(eg[k] - er[k]);
            }
            printf("\n");
            T_NEAR(er[0], 0, 1e-12); /* the surface covers the view */
        }
        gro_scene_free(&sc);
        gr_grid_free(grid);
    }
    printf("  worst |E_k - reference| = %.2e (N = %d)\n", worst, n);
    gro_device_free(&dev);
}

/* Crossings (X of a V and a ridge, oblique V pair, T): one segment
   (line_samples = 1, A2 = 0) is exact, so its per-depth energies must
   match the path tracer on the segment's rays (the oracle carves
   crossings and caps ends, as the library does). */
static void t_crossing_energy_vs_pathtraced(void)
{
    static const double views[3][3] = {{0, 0, 1}, {0.4, 0.3, 0.866}, {-0.6, 0.2, 0.775}};
    gr_specular_t spec[2];
    gro_device_t dev;
    int c, v, k, n;
    double worst = 0;
    if (!mirror_setup(spec, &dev, &n)) return;
    for (c = 0; c < 3; c++) {
        static const double P0[4] = {0.2, 0.5, 0.8, 0.5}, PX[4] = {0.5, 0.2, 0.5, 0.8}, PT[4] = {0.5, 0.8, 0.5, 0.5};
        double PO[4] = {0.5 - 0.3 * cos(1.047), 0.5 - 0.3 * sin(1.047), 0.5 + 0.3 * cos(1.047), 0.5 + 0.3 * sin(1.047)};
        gr_groove_desc_t g[2];
        gr_grid_desc_t d;
        gr_grid_t *grid = NULL;
        gro_groove_t og[2];
        gro_scene_t sc;
        memset(g, 0, sizeof g);
        memset(&d, 0, sizeof d);
        g[0].points = P0; g[0].point_count = 2; g[0].section = VSEC; g[0].section_count = 3; g[0].reflectance = 1;
        g[1] = g[0];
        g[1].points = c == 0 ? PX : c == 1 ? PO : PT;
        if (c == 0) { g[1].section = RSEC; g[1].section_count = 5; }
        d.grooves = g; d.groove_count = 2; d.no_wrap = 1;
        if (!T_CHECK(gr_grid_build(&d, &grid, NULL) == GR_OK)) return;
        og[0] = gro_from_gr(&g[0]);
        og[1] = gro_from_gr(&g[1]);
        if (!T_CHECK(gro_scene_build(&sc, dev.dev, og, 2, NULL) == 0)) return;
        for (v = 0; v < 3; v++) {
            gr_query_t q = gt_query(0.5 + 0.004 * v - 0.003, 0.5 + 0.003 * c - 0.002, 0, views[v][0], views[v][1], views[v][2]);
            double er[MAXD + 1], eg[MAXD + 1];
            q.footprint.axis1[0] = 0.016 * cos(0.3 + v);
            q.footprint.axis1[1] = 0.016 * sin(0.3 + v);
            q.line_samples = 1;
            reference(&sc, &q.footprint, n, er);
            shade_depths(grid, &q, spec, eg);
            printf("  crossing %d view %d E_k path-traced / one segment:", c, v);
            for (k = 0; k <= MAXD; k++) {
                printf(" %.4f/%.4f", er[k], eg[k]);
                T_NEAR(eg[k], er[k], REF_TOL * 4000 / n);
                worst = fmax(worst, fabs(eg[k] - er[k]));
            }
            printf("\n");
        }
        gro_scene_free(&sc);
        gr_grid_free(grid);
    }
    printf("  crossings: worst |E_k - reference| = %.2e\n", worst);
    gro_device_free(&dev);
}

/* the deep V at E = (0.5, 0, 0.866): the first bounce off the wall facing
   the viewer heads down into the other wall (E_r,w < 0) */
static void t_direction_from_below(void)
{
    /* facet 1 of DEEP runs from (0, -0.05) to (0.01, 0): outward normal
       (-Δw, Δb)/|.| in (B, W), B = (-T_v, T_u) = (-1, 0) for T = (0, 1) */
    double db = 0.01, dw = 0.05, len = sqrt(db * db + dw * dw), nb = -dw / len, nw = db / len;
    double n[3] = {-nb, 0, nw}, d[3] = {-0.5, 0, -0.866}, dn = d[0] * n[0] + d[2] * n[2];
    T_LT(dn, 0);                     /* the viewer sees that wall */
    T_LT(d[2] - 2 * dn * n[2], 0);   /* and its mirror ray goes down */
}

static void brdf_cb(void *user, int refl, const double n[3], const double e[3], const double l[3], int light,
                    double rgb[3])
{
    double c = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
    (void)user; (void)e;
    if (c < 0) c = 0;
    rgb[0] = c * (refl + 1);
    rgb[1] = c * 0.5 * (light + 1);
    rgb[2] = c * e[2];
}

static void t_depth0_is_direct(void)
{
    static const double lights[6] = {0.6, 0.1, 0.78, -0.3, 0.5, 0.81};
    gr_groove_desc_t g;
    gr_grid_t *grid = one_groove(RSEC, 5, &g);
    gr_specular_t spec[2];
    size_t need;
    void *scratch;
    int k, v;
    if (!T_CHECK(grid)) return;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    memset(spec, 0, sizeof spec);
    for (k = 0; k < 3; k++) spec[0].kr[k] = spec[1].kr[k] = 0.8;
    for (v = 0; v < 6; v++) {
        gr_query_t q = gt_query(0.5 - 0.01 + 0.004 * v, 0.5 + 0.002 * v, 0.006, 0.1 * v - 0.2, 0.05 * v, 0.9);
        gr_facet_list_t l;
        gr_indirect_t ind;
        double rgb[3], want[3] = {0, 0, 0};
        int i, j;
        q.lights = lights;
        q.light_count = 2;
        q.line_samples = 2 + (v % 3) * 2;
        q.line_exit_tol = -1;
        T_INT_EQ(gr_query_lines(grid, &q, scratch, need, &l, NULL), GR_OK);
        for (i = 0; i < l.count; i++)
            for (j = 0; j < 2; j++) {
                double c[3];
                brdf_cb(NULL, l.facets[i].reflectance, l.facets[i].normal, q.footprint.view, lights + 3 * j, j, c);
                for (k = 0; k < 3; k++) want[k] += l.facets[i].ratio * l.facets[i].lit[j] * c[k];
            }
        memset(&ind, 0, sizeof ind);
        ind.depth = 0;
        ind.specular = spec;
        ind.specular_count = 2;
        ind.brdf = brdf_cb;
        T_INT_EQ(gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, NULL), GR_OK);
        for (k = 0; k < 3; k++) T_NEAR(rgb[k], want[k], 1e-12);
    }
    free(scratch);
    gr_grid_free(grid);
}

/* a tall bar's shadow falling on ground far outside the view rays'
   reach, for gr_query_lines() and a bounce's scene alike (the bar must
   not be pruned: shadow rays reach further than view rays, §5.1's w_L) */
static void t_shadow_from_outside_the_view(void)
{
    static const double bar[10] = {-0.018, 0, -0.016, 0.03, 0, 0.036, 0.016, 0.03, 0.018, 0};
    static const double lights[2][3] = {{-0.8, 0, 0.6}, {-0.9, 0, 0.436}};
    static const double at[2] = {0.53, 0.565};
    gr_groove_desc_t g;
    gr_grid_t *grid = one_groove(bar, 5, &g);
    size_t need;
    void *scratch;
    int c;
    if (!T_CHECK(grid)) return;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    for (c = 0; c < 2; c++) {
        const double *light = lights[c];
        gr_facet_list_t l;
        gr_indirect_t ind;
        double rgb[3], want[3];
        gr_query_t q = gt_query(at[c], 0.5, 0.004, 0.1, 0, 0.99);
        q.lights = light;
        q.light_count = 1;
        q.line_exit_tol = -1;
        T_INT_EQ(gr_query_lines(grid, &q, scratch, need, &l, NULL), GR_OK);
        T_INT_EQ(l.count, 1);
        T_NEAR(l.facets[0].lit[0], 0, 1e-12); /* in the bar's shadow */
        brdf_cb(NULL, l.facets[0].reflectance, l.facets[0].normal, q.footprint.view, light, 0, want);
        memset(&ind, 0, sizeof ind);
        ind.brdf = brdf_cb;
        T_INT_EQ(gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, NULL), GR_OK);
        T_NEAR(rgb[0], 0, 1e-12);
        T_GT(want[0], 0.1); /* it would be lit */
    }
    free(scratch);
    gr_grid_free(grid);
}

/* a glass ground: k_t of it goes to the host, refracted by Snell's law */
static void t_transmission_to_host(void)
{
    gr_groove_desc_t g;
    gr_grid_t *grid = one_groove(VSEC, 3, &g);
    gr_specular_t spec[2];
    gr_indirect_t ind;
    gr_facet_list_t l;
    cb_t cb;
    size_t need;
    void *scratch;
    double rgb[3], sin_i, sin_t;
    gr_query_t q = gt_query(0.52, 0.5, 0.004, 0.6, 0, 0.8); /* ground only */
    if (!T_CHECK(grid)) return;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    memset(spec, 0, sizeof spec);
    spec[0].kt[0] = spec[0].kt[1] = spec[0].kt[2] = 0.5;
    spec[0].ior = 1.5;
    memset(&ind, 0, sizeof ind);
    memset(&cb, 0, sizeof cb);
    cb.want = -1;
    ind.depth = 1;
    ind.specular = spec;
    ind.specular_count = 2;
    ind.trace = trace_cb;
    ind.trace_user = &cb;
    T_INT_EQ(gr_query_lines(grid, &q, scratch, need, &l, NULL), GR_OK);
    T_INT_EQ(gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, NULL), GR_OK);
    T_NEAR(rgb[0], 0.5 * gt_ratio_of(&l, -1), 1e-12);
    sin_i = 0.6;
    sin_t = sqrt(cb.dir[0] * cb.dir[0] + cb.dir[1] * cb.dir[1]);
    T_NEAR(sin_t, sin_i / 1.5, 1e-12);
    T_LT(cb.dir[2], 0);
    /* bad input */
    ind.depth = GR_MAX_DEPTH + 1;
    T_INT_EQ(gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, NULL), GR_ERR_INVALID_ARG);
    ind.depth = 1;
    ind.specular = NULL;
    T_INT_EQ(gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, NULL), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_shade_indirect(grid, &q, NULL, scratch, need, rgb, NULL), GR_ERR_INVALID_ARG);
    free(scratch);
    gr_grid_free(grid);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(t_mirror_energy_vs_pathtraced), T_CASE(t_crossing_energy_vs_pathtraced), T_CASE(t_direction_from_below), T_CASE(t_depth0_is_direct),
        T_CASE(t_shadow_from_outside_the_view), T_CASE(t_transmission_to_host),
    };
    return T_RUN(argc, argv, cases);
}
