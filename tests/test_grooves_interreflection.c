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
   Transmission (§6, issue 8): a splitting path tracer on the same mesh
   (reflected and refracted rays at every hit, Fresnel or constant
   weights, the medium flipping on transmission, thin panes passing light
   straight through) gives the energy leaving at each bounce up into the
   scene and down into the bulk, for a deep glass V, a glass ridge on
   glass (total internal reflection inside it), a metal frame on a thin
   pane (Figure 21d) and the paper's constants with refraction; the same
   1e-3 bound per (bounce, medium); and a glass ridge across a V and a
   deep V (ridge-over-cut: the ridge bridges the cut, whose underside
   refracted and reflected rays meet), one exact chord.
   Named stiff cases: grazing view (E_w = 0.1), a wall whose mirror ray
   points down into the other wall (a direction from below the texture
   plane, §6.1's inverted masking: E_1 = 0), a protruding ridge, depth 0
   equal to the direct result, transmission through a flat pane (Snell's
   direction), and a footprint that overflows the recursion stack
   (GR_ERR_STACK_FULL). */
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

/* the reference's primary ray (i, j) of n x 8 over the footprint's
   parallelogram, from above everything along -E */
static void primary_ray(const gr_footprint_t *fp, int n, int i, int j, double o[3], double d[3])
{
    double a = -1 + (2 * i + 1.0) / n, c = -1 + (2 * j + 1.0) / 8;
    int k;
    o[0] = fp->center[0] + a * fp->axis1[0] + c * fp->axis2[0] + 0.2 * fp->view[0] / fp->view[2];
    o[1] = fp->center[1] + a * fp->axis1[1] + c * fp->axis2[1] + 0.2 * fp->view[1] / fp->view[2];
    o[2] = 0.2;
    for (k = 0; k < 3; k++) d[k] = -fp->view[k];
}

/* reference: energy reaching the sky after exactly k bounces, k = 0..MAXD */
static void reference(const gro_scene_t *sc, const gr_footprint_t *fp, int n, double *ek)
{
    int i, j, k;
    for (k = 0; k <= MAXD; k++) ek[k] = 0;
    for (j = 0; j < 8; j++)
        for (i = 0; i < n; i++) {
            double o[3], d[3];
            primary_ray(fp, n, i, j, o, d);
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

/* host callback: 1 for light leaving at one (depth, medium) */
typedef struct want_t { int depth, inside, calls; } want_t;
static void want_cb(void *user, const double origin[3], const double dir[3], int depth, int inside, double weight,
                    double rgb[3])
{
    want_t *w = (want_t *)user;
    (void)origin; (void)dir; (void)weight;
    w->calls++;
    rgb[0] = rgb[1] = rgb[2] = depth == w->depth && inside == w->inside ? 1 : 0;
}

/* Our energy leaving at bounce k into medium in (0 up, 1 the bulk), the
   recursion MAXD deep. */
static double shade_split(const gr_grid_t *grid, const gr_query_t *q, const gr_specular_t *spec, int k, int in,
                          void *scratch, size_t need)
{
    gr_indirect_t ind;
    want_t w;
    double rgb[3];
    memset(&ind, 0, sizeof ind);
    w.depth = k;
    w.inside = in;
    w.calls = 0;
    ind.depth = MAXD;
    ind.specular = spec;
    ind.specular_count = 2;
    ind.trace = want_cb;
    ind.trace_user = &w;
    T_INT_EQ(gr_shade_indirect(grid, q, &ind, scratch, need, rgb, NULL), GR_OK);
    return rgb[0];
}

static void shade_depths(const gr_grid_t *grid, const gr_query_t *q, const gr_specular_t *spec, double *ek)
{
    size_t need = gr_query_scratch_bytes(grid);
    void *scratch = malloc(need);
    int k;
    for (k = 0; k <= MAXD; k++) ek[k] = shade_split(grid, q, spec, k, 0, scratch, need); /* mirrors: all up */
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

/* Crossings (X of a V and a ridge, oblique V pair, T, and a self-crossing
   "alpha" polyline at its crossing): one segment (line_samples = 1, A2 =
   0) is exact, so its per-depth energies must match the path tracer on
   the segment's rays (the oracle carves crossings and caps ends, as the
   library does; it gets the alpha as two paths, cut far from the
   crossing, since it never carves a path with itself). */
static void t_crossing_energy_vs_pathtraced(void)
{
    static const double views[3][3] = {{0, 0, 1}, {0.4, 0.3, 0.866}, {-0.6, 0.2, 0.775}};
    gr_specular_t spec[2];
    gro_device_t dev;
    int c, v, k, n;
    double worst = 0;
    if (!mirror_setup(spec, &dev, &n)) return;
    for (c = 0; c < 4; c++) {
        static const double P0[4] = {0.2, 0.5, 0.8, 0.5}, PX[4] = {0.5, 0.2, 0.5, 0.8}, PT[4] = {0.5, 0.8, 0.5, 0.5};
        static const double alpha[10] = {0.2, 0.3, 0.6, 0.7, 0.8, 0.5, 0.6, 0.3, 0.2, 0.7};
        static const double a0[6] = {0.2, 0.3, 0.6, 0.7, 0.8, 0.5}, a1[6] = {0.8, 0.5, 0.6, 0.3, 0.2, 0.7};
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
        if (c == 3) { g[0].points = alpha; g[0].point_count = 5; }
        d.grooves = g; d.groove_count = c == 3 ? 1 : 2; d.no_wrap = 1;
        if (!T_CHECK(gr_grid_build(&d, &grid, NULL) == GR_OK)) return;
        og[0] = gro_from_gr(&g[0]);
        og[1] = gro_from_gr(&g[1]);
        if (c == 3) {
            og[1] = og[0];
            og[0].ctrl = a0; og[1].ctrl = a1;
            og[0].nctrl = og[1].nctrl = 3;
        }
        if (!T_CHECK(gro_scene_build(&sc, dev.dev, og, 2, NULL) == 0)) return;
        for (v = 0; v < 3; v++) {
            gr_query_t q = gt_query(c == 3 ? 0.4 + 0.002 * v : 0.5 + 0.004 * v - 0.003, 0.5 + 0.003 * (c % 3) - 0.002, 0,
                                    views[v][0], views[v][1], views[v][2]);
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

/* Named stiff case (§6.1, directions from below): the V seen at
   E = (0.5, 0, 0.866), a footprint whose view rays all meet the wall
   facing the viewer (u in [0.492, 0.498]): the mirror ray off that wall,
   (0.99, 0, -0.12), points down (E_r,w < 0) into the other wall, so no
   light leaves after one bounce (E_1 = 0), most leaves after two, and
   every depth must match the path tracer on the mesh. */
static void t_direction_from_below(void)
{
    gr_groove_desc_t g;
    gr_grid_t *grid = one_groove(VSEC, 3, &g);
    gro_groove_t og;
    gro_scene_t sc;
    gro_device_t dev;
    gr_specular_t spec[2];
    gr_query_t q = gt_query(0.495, 0.5, 0, 0.5, 0, 0.866);
    double er[MAXD + 1], eg[MAXD + 1];
    int k, n;
    if (!T_CHECK(grid) || !mirror_setup(spec, &dev, &n)) return;
    og = gro_from_gr(&g);
    if (!T_CHECK(gro_scene_build(&sc, dev.dev, &og, 1, NULL) == 0)) return;
    q.footprint.axis1[0] = 0.003;
    q.footprint.axis2[1] = 0.004;
    q.line_samples = 2;
    reference(&sc, &q.footprint, n, er);
    shade_depths(grid, &q, spec, eg);
    printf("  V wall facing the viewer, E_k path-traced / ours:");
    for (k = 0; k <= MAXD; k++) printf(" %.4f/%.4f", er[k], eg[k]);
    printf("\n");
    T_NEAR(eg[1], 0, 1e-12);
    T_NEAR(er[1], 0, 1e-12);
    T_GT(eg[2], 0.5);
    for (k = 0; k <= MAXD; k++) T_NEAR(eg[k], er[k], REF_TOL * 4000 / n);
    gro_scene_free(&sc);
    gr_grid_free(grid);
    gro_device_free(&dev);
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

/* ---- transmission (§6): dielectric and thin facets, path-traced ---- */

/* a material of the reference, mirrored into gr_specular_t (grey) */
typedef struct mat_t { double kr, kt, ior; int fresnel, thin; } mat_t;

/* Unpolarised Fresnel reflectance from index n1 into n2 at cos ci (the
   textbook form with cos t; written here, not taken from the library). */
static double ref_fresnel(double ci, double n1, double n2, double *ct)
{
    double si = sqrt(fmax(0, 1 - ci * ci)), st = n1 / n2 * si, a, b;
    if (st >= 1) { *ct = 0; return 1; }
    *ct = sqrt(1 - st * st);
    a = (n1 * ci - n2 * *ct) / (n1 * ci + n2 * *ct);
    b = (n1 * *ct - n2 * ci) / (n1 * *ct + n2 * ci);
    return 0.5 * (a * a + b * b);
}

/* Splitting path tracer on the explicit mesh: every hit sends a reflected
   and a transmitted ray (weights from the material), the medium flips on
   transmission; energy leaving at bounce k lands in eout[k] (up into the
   scene) or ein[k] (down into the bulk below the grooves, or through a
   thin pane). A hit at bounce MAXD is absorbed (the recursion's depth).
   A ray inside the material is followed BULK_REACH (the header's
   documented reach, 64 scene scales w + h + d) and then counts as bulk
   light; pt_tir sums the energy that met total internal reflection. */
#define BULK_REACH(grid_scale) (64.0 * (grid_scale))
static double pt_tir, pt_scale;
static void pt_split(const gro_scene_t *sc, const mat_t *mats, const double *o, const double *d, int inside, double w,
                     int k, double *eout, double *ein)
{
    gro_hit_t h;
    const mat_t *mt;
    double ci, ct, n1, n2, R, wr, wt, o2[3], d2[3], eta;
    int m, tir;
    if (!(w > 1e-9)) return;
    h = gro_scene_intersect(sc, o, d, 0, inside ? BULK_REACH(pt_scale) : INFINITY);
    if (h.kind == GRO_HIT_NONE) { (inside ? ein : eout)[k] += w; return; }
    if (k == MAXD) return;
    mt = &mats[h.kind == GRO_HIT_GROUND ? 0 : 1];
    ci = -(d[0] * h.n[0] + d[1] * h.n[1] + d[2] * h.n[2]);
    n1 = inside ? mt->ior : 1;
    n2 = inside ? 1 : mt->ior;
    R = ref_fresnel(ci, n1, n2, &ct);
    tir = !mt->thin && ct == 0;
    if (tir) pt_tir += w;
    if (mt->fresnel) {
        if (mt->thin) R = 2 * R / (1 + R);
        wr = mt->kr * R;
        wt = tir ? 0 : mt->kt * (1 - R);
    } else {
        wr = mt->kr + (tir ? mt->kt : 0);
        wt = tir ? 0 : mt->kt;
    }
    for (m = 0; m < 3; m++) {
        d2[m] = d[m] + 2 * ci * h.n[m];
        o2[m] = h.p[m] + sc->eps * h.n[m];
    }
    pt_split(sc, mats, o2, d2, inside, w * wr, k + 1, eout, ein);
    if (!(wt > 0)) return;
    if (mt->thin) { (inside ? eout : ein)[k + 1] += w * wt; return; }
    eta = n1 / n2;
    for (m = 0; m < 3; m++) {
        d2[m] = eta * d[m] + (eta * ci - ct) * h.n[m];
        o2[m] = h.p[m] - sc->eps * h.n[m];
    }
    pt_split(sc, mats, o2, d2, !inside, w * wt, k + 1, eout, ein);
}

static void reference_split(const gro_scene_t *sc, const gr_footprint_t *fp, int n, const mat_t *mats, double *eout,
                            double *ein)
{
    int i, j, k;
    for (k = 0; k <= MAXD; k++) eout[k] = ein[k] = 0;
    for (j = 0; j < 8; j++)
        for (i = 0; i < n; i++) {
            double o[3], d[3];
            primary_ray(fp, n, i, j, o, d);
            pt_split(sc, mats, o, d, 0, 1.0 / (8.0 * n), 0, eout, ein);
        }
}



/* Ours against the path tracer's (eo, ei) at every (bounce, medium):
   printed, asserted within the reference's bound; returns the sum of ours
   and raises *worst. */
static double compare_split(const gr_grid_t *grid, const gr_query_t *q, const gr_specular_t *spec, const double *eo,
                            const double *ei, int n, void *scratch, size_t need, double *worst)
{
    double sum = 0;
    int k, in;
    for (k = 0; k <= MAXD; k++)
        for (in = 0; in < 2; in++) {
            double ours = shade_split(grid, q, spec, k, in, scratch, need), want = in ? ei[k] : eo[k];
            printf(" %.4f|%.4f", want, ours);
            T_NEAR(ours, want, REF_TOL * 4000 / n);
            *worst = fmax(*worst, fabs(ours - want));
            sum += ours;
        }
    return sum;
}

/* The library's materials for the reference's (grey): ids 0 and 1 */
static void spec_of(const mat_t *mats, gr_specular_t spec[2])
{
    int k, c;
    memset(spec, 0, 2 * sizeof *spec);
    for (k = 0; k < 2; k++) {
        for (c = 0; c < 3; c++) {
            spec[k].kr[c] = mats[k].kr;
            spec[k].kt[c] = mats[k].kt;
        }
        spec[k].ior = mats[k].ior;
        spec[k].fresnel = mats[k].fresnel;
        spec[k].thin = mats[k].thin;
    }
}

static void t_transmission_vs_pathtraced(void)
{
    static const double TRAP[8] = {-0.01, 0, -0.006, 0.012, 0.006, 0.012, 0.01, 0};
    static const double views[4][3] = {{0, 0, 1}, {0.5, 0, 0.866}, {-0.7, 0.2, 0.685}, {0.995, 0, 0.0998}};
    static const char *vname[4] = {"top", "oblique", "skew", "grazing"};
    /* (ground, grooves): deep glass V; glass ridge on glass; metal frame on a
       thin pane (Figure 21d); the paper's constants with refraction */
    static const mat_t mats[4][2] = {
        {{1, 1, 1.5, 1, 0}, {1, 1, 1.5, 1, 0}},
        {{1, 1, 1.5, 1, 0}, {1, 1, 1.7, 1, 0}},
        {{1, 1, 1.5, 1, 1}, {0.9, 0, 0, 0, 0}},
        {{0.2, 0.7, 1.3, 0, 0}, {0.3, 0.6, 1.3, 0, 0}},
    };
    static const char *sname[4] = {"glass V", "glass ridge", "frame/pane", "constants"};
    gro_device_t dev;
    int sc_i, v, k, n = (int)(4000 * t_scale());
    double worst = 0, tir_seen = 0;
    if (n < 400) n = 400;
    if (gro_device_init(&dev)) { T_FAIL("embree"); return; }
    for (sc_i = 0; sc_i < 4; sc_i++) {
        gr_groove_desc_t g;
        gr_grid_t *grid = sc_i == 0 ? one_groove(DEEP, 3, &g) : sc_i == 3 ? one_groove(VSEC, 3, &g) : one_groove(TRAP, 4, &g);
        gro_groove_t og = gro_from_gr(&g);
        gro_scene_t sc;
        gr_specular_t spec[2];
        size_t need;
        void *scratch;
        if (!T_CHECK(grid) || !T_CHECK(gro_scene_build(&sc, dev.dev, &og, 1, NULL) == 0)) return;
        spec_of(mats[sc_i], spec);
        need = gr_query_scratch_bytes(grid);
        scratch = malloc(need);
        pt_scale = sc_i == 0 ? 0.01 + 0.05 : sc_i == 3 ? 0.01 + 0.02 : 0.01 + 0.012; /* w + h + d */
        for (v = 0; v < 4; v++) {
            gr_query_t q = gt_query(0.5013, 0.5, 0.014, views[v][0], views[v][1], views[v][2]);
            double eo[MAXD + 1], ei[MAXD + 1], sum_ref = 0, sum_ours = 0;
            q.line_samples = 2;
            pt_tir = 0;
            reference_split(&sc, &q.footprint, n, mats[sc_i], eo, ei);
            if (sc_i < 2) tir_seen += pt_tir;
            printf("  %-11s %-7s E_k out/in path-traced | ours:", sname[sc_i], vname[v]);
            sum_ours = compare_split(grid, &q, spec, eo, ei, n, scratch, need, &worst);
            for (k = 0; k <= MAXD; k++) sum_ref += eo[k] + ei[k];
            printf("  (sum %.4f|%.4f, TIR %.4f)\n", sum_ref, sum_ours, pt_tir);
        }
        free(scratch);
        gro_scene_free(&sc);
        gr_grid_free(grid);
    }
    { /* an X crossing of a glass V and a deep glass V, one chord (exact at
         crossings): refracted rays inside the carved solid. A protrusion
         across a cut: t_transmission_ridge_over_cut. */
        static const double P0[4] = {0.2, 0.5, 0.8, 0.5}, PX[4] = {0.5, 0.2, 0.5, 0.8};
        static const double xviews[2][3] = {{0.4, 0.3, 0.866}, {-0.6, 0.2, 0.775}};
        gr_groove_desc_t g[2];
        gr_grid_desc_t d;
        gr_grid_t *grid = NULL;
        gro_groove_t og[2];
        gro_scene_t sc;
        gr_specular_t spec[2];
        size_t need;
        void *scratch;
        memset(g, 0, sizeof g);
        memset(&d, 0, sizeof d);
        g[0].points = P0; g[0].point_count = 2; g[0].section = VSEC; g[0].section_count = 3; g[0].reflectance = 1;
        g[1] = g[0];
        g[1].points = PX; g[1].section = DEEP;
        d.grooves = g; d.groove_count = 2; d.no_wrap = 1;
        if (!T_CHECK(gr_grid_build(&d, &grid, NULL) == GR_OK)) return;
        og[0] = gro_from_gr(&g[0]);
        og[1] = gro_from_gr(&g[1]);
        if (!T_CHECK(gro_scene_build(&sc, dev.dev, og, 2, NULL) == 0)) return;
        memset(spec, 0, sizeof spec);
        for (k = 0; k < 3; k++) spec[0].kr[k] = spec[0].kt[k] = spec[1].kr[k] = spec[1].kt[k] = 1;
        spec[0].ior = spec[1].ior = 1.5;
        spec[0].fresnel = spec[1].fresnel = 1;
        need = gr_query_scratch_bytes(grid);
        scratch = malloc(need);
        pt_scale = 0.01 + 0.05;
        for (v = 0; v < 2; v++) {
            gr_query_t q = gt_query(0.5 + 0.003 * v - 0.002, 0.501, 0, xviews[v][0], xviews[v][1], xviews[v][2]);
            double eo[MAXD + 1], ei[MAXD + 1];
            q.footprint.axis1[0] = 0.016 * cos(0.3 + v);
            q.footprint.axis1[1] = 0.016 * sin(0.3 + v);
            q.line_samples = 1;
            reference_split(&sc, &q.footprint, n, mats[0], eo, ei);
            printf("  glass X crossing view %d E_k out/in path-traced | ours:", v);
            (void)compare_split(grid, &q, spec, eo, ei, n, scratch, need, &worst);
            printf("\n");
        }
        free(scratch);
        gro_scene_free(&sc);
        gr_grid_free(grid);
    }
    printf("  transmission: worst |E_k - reference| = %.2e (N = %d), total internal reflection met %.3f\n", worst, n,
           tir_seen);
    T_GT(tir_seen, 0.05); /* the dielectric cases exercise it */
    gro_device_free(&dev);
}

/* Named case: a protruding ridge over a cut (ridge-over-cut). A glass
   trapezoid ridge runs across a glass V (and across a deep V); over the
   V's hole the ridge is a bridge, whose underside is the plane w = 0 seen
   from below (the solid is ground - cuts + protrusions), carrying the
   ground's id. Rays refracted into the ridge leave through that underside
   into the V, rays inside the V meet it from below. One chord
   (line_samples = 1, A2 = 0) is exact, so every (bounce, medium) energy
   must match the splitting path tracer on the oracle's mesh, which gives
   the bridge its underside (tests/grooves_oracle.h), within the
   reference's bound. Materials: Fresnel glass everywhere, and constants
   with a different index for the ground (the underside's id) and the
   grooves, so a wrong id or a missing underside shows. */
static void t_transmission_ridge_over_cut(void)
{
    static const double TRAP[8] = {-0.01, 0, -0.006, 0.012, 0.006, 0.012, 0.01, 0};
    static const double PV[4] = {0.2, 0.5, 0.8, 0.5}, PR[4] = {0.5, 0.2, 0.5, 0.8};
    static const double views[4][3] = {{0.3, 0.2, 0.933}, {0.6, -0.3, 0.742}, {-0.2, 0.7, 0.686}, {0.1, -0.85, 0.517}};
    static const mat_t mats[2][2] = {
        {{1, 1, 1.5, 1, 0}, {1, 1, 1.5, 1, 0}},
        {{0.25, 0.7, 1.3, 0, 0}, {0.3, 0.6, 1.6, 0, 0}},
    };
    gro_device_t dev;
    int c, m, v, n = (int)(4000 * t_scale());
    double worst = 0;
    if (n < 400) n = 400;
    if (gro_device_init(&dev)) { T_FAIL("embree"); return; }
    for (c = 0; c < 2; c++) {
        gr_groove_desc_t g[2];
        gr_grid_desc_t d;
        gr_grid_t *grid = NULL;
        gro_groove_t og[2];
        gro_scene_t sc;
        size_t need;
        void *scratch;
        memset(g, 0, sizeof g);
        memset(&d, 0, sizeof d);
        g[0].points = PV; g[0].point_count = 2; g[0].section = c ? DEEP : VSEC; g[0].section_count = 3;
        g[0].reflectance = 1;
        g[1] = g[0];
        g[1].points = PR; g[1].section = TRAP; g[1].section_count = 4;
        d.grooves = g; d.groove_count = 2; d.no_wrap = 1;
        if (!T_CHECK(gr_grid_build(&d, &grid, NULL) == GR_OK)) return;
        og[0] = gro_from_gr(&g[0]);
        og[1] = gro_from_gr(&g[1]);
        if (!T_CHECK(gro_scene_build(&sc, dev.dev, og, 2, NULL) == 0)) return;
        need = gr_query_scratch_bytes(grid);
        scratch = malloc(need);
        pt_scale = 0.01 + 0.012 + (c ? 0.05 : 0.02); /* w + h + d */
        for (m = 0; m < 2; m++) {
            gr_specular_t spec[2];
            spec_of(mats[m], spec);
            for (v = 0; v < 4; v++) {
                gr_query_t q = gt_query(0.5 + 0.002 * v - 0.003, 0.5 - 0.001 * v + 0.001, 0, views[v][0], views[v][1],
                                        views[v][2]);
                double eo[MAXD + 1], ei[MAXD + 1];
                q.footprint.axis1[0] = 0.018 * cos(0.4 + 0.7 * v);
                q.footprint.axis1[1] = 0.018 * sin(0.4 + 0.7 * v);
                q.line_samples = 1;
                reference_split(&sc, &q.footprint, n, mats[m], eo, ei);
                printf("  ridge over %s, %s, view %d E_k out/in path-traced | ours:", c ? "deep V" : "V",
                       m ? "constants" : "glass", v);
                (void)compare_split(grid, &q, spec, eo, ei, n, scratch, need, &worst);
                printf("\n");
            }
        }
        free(scratch);
        gro_scene_free(&sc);
        gr_grid_free(grid);
    }
    printf("  ridge over cut: worst |E_k - reference| = %.2e (N = %d)\n", worst, n);
    gro_device_free(&dev);
}

/* Named stiff case: more pending bounce segments than GR_INDIRECT_STACK.
   16 parallel grooves with a 40-facet sawtooth section under one
   footprint, every facet a lossless dielectric: the first segment alone
   pushes a reflected and a refracted piece per facet run it sees (more
   than 512). The call must say so (GR_ERR_STACK_FULL and the stats flag)
   and still fill the colour: the pieces that did not fit leave along
   their direction to the host, which returns 1 everywhere here, so with
   lossless facets the colour stays 1 up to what the depth limit (8)
   absorbs (measured 1 - 4e-5; bound 1e-2).
   The same scene with a 10-facet section fits (GR_OK, no flag). */
static void one_cb(void *user, const double origin[3], const double dir[3], int depth, int inside, double weight,
                   double rgb[3])
{
    (void)user; (void)origin; (void)dir; (void)depth; (void)inside; (void)weight;
    rgb[0] = rgb[1] = rgb[2] = 1;
}

static void t_stack_full(void)
{
    static const int npts[2] = {41, 11};
    int c, i, k;
    for (c = 0; c < 2; c++) {
        double sec[2 * 41], pts[16][4], rgb[3];
        gr_groove_desc_t g[16];
        gr_grid_desc_t d;
        gr_grid_t *grid = NULL;
        gr_specular_t sp[2];
        gr_indirect_t ind;
        gr_line_stats_t st;
        gr_query_t q;
        gr_result_t r;
        size_t need;
        void *scratch;
        int np = npts[c];
        for (i = 0; i < np; i++) {
            sec[2 * i] = -0.005 + 0.01 * i / (np - 1);
            sec[2 * i + 1] = i == 0 || i == np - 1 ? 0 : (i & 1 ? -0.003 : -0.0005);
        }
        memset(g, 0, sizeof g);
        memset(&d, 0, sizeof d);
        for (i = 0; i < 16; i++) {
            pts[i][0] = pts[i][2] = 0.42 + 0.01 * i;
            pts[i][1] = 0.1;
            pts[i][3] = 0.9;
            g[i].points = pts[i];
            g[i].point_count = 2;
            g[i].section = sec;
            g[i].section_count = np;
            g[i].reflectance = 1;
        }
        d.grooves = g;
        d.groove_count = 16;
        d.no_wrap = 1;
        if (!T_CHECK(gr_grid_build(&d, &grid, NULL) == GR_OK)) return;
        q = gt_query(0.5, 0.5, 0, 0.3, 0, sqrt(0.91));
        q.footprint.axis1[0] = 0.08;
        q.footprint.axis2[1] = 0.01;
        memset(sp, 0, sizeof sp);
        for (k = 0; k < 3; k++) sp[0].kr[k] = sp[0].kt[k] = sp[1].kr[k] = sp[1].kt[k] = 1;
        sp[0].fresnel = sp[1].fresnel = 1;
        memset(&ind, 0, sizeof ind);
        ind.depth = GR_MAX_DEPTH;
        ind.specular = sp;
        ind.specular_count = 2;
        ind.trace = one_cb;
        need = gr_query_scratch_bytes(grid);
        scratch = malloc(need);
        r = gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, &st);
        printf("  %d-facet sawtooth, depth %d: %s, flags %u, %d segments, colour %.6f\n", np - 1, ind.depth,
               gr_result_string(r), st.flags, st.segments, rgb[0]);
        if (c == 0) {
            T_INT_EQ(r, GR_ERR_STACK_FULL);
            T_CHECK(st.flags & GR_STATS_STACK_FULL);
        } else {
            T_INT_EQ(r, GR_OK);
            T_CHECK(!(st.flags & GR_STATS_STACK_FULL));
        }
        T_CHECK(rgb[0] > 0.99 && rgb[0] <= 1 + 1e-9);
        free(scratch);
        gr_grid_free(grid);
    }
}

/* Named stiff cases: scale and grazing views for §6. A glass ridge (TRAP,
   Fresnel, ior 1.5) scaled by 1e-5 and 1e3 about (0.5, 0.5), footprint
   with it, gives the size-1 energies per (bounce, medium); at a grazing
   view (E_w = 1e-3) lossless facets with a host that returns 1 keep the
   colour in [0.99, 1] (energy conserved up to the depth limit). */
static void t_stiff_indirect_scale_grazing(void)
{
    static const double TRAP[8] = {-0.01, 0, -0.006, 0.012, 0.006, 0.012, 0.01, 0};
    static const double scales[3] = {1, 1e-5, 1e3};
    double base[2 * (MAXD + 1)], worst = 0;
    int c, k, in;
    for (c = 0; c < 3; c++) {
        double sec[8], path[4], sc = scales[c];
        gr_groove_desc_t g;
        gr_grid_desc_t d;
        gr_grid_t *grid = NULL;
        gr_specular_t spec[2];
        gr_query_t q = gt_query(0.5 + sc * 0.0013, 0.5, sc * 0.014, 0.5, 0.1, 0.86);
        size_t need;
        void *scratch;
        for (k = 0; k < 8; k++) sec[k] = sc * TRAP[k];
        path[0] = path[2] = 0.5;
        path[1] = 0.5 - 0.45 * sc;
        path[3] = 0.5 + 0.45 * sc;
        memset(&g, 0, sizeof g);
        memset(&d, 0, sizeof d);
        g.points = path; g.point_count = 2; g.section = sec; g.section_count = 4; g.reflectance = 1;
        d.grooves = &g; d.groove_count = 1; d.no_wrap = 1;
        if (!T_CHECK(gr_grid_build(&d, &grid, NULL) == GR_OK)) return;
        memset(spec, 0, sizeof spec);
        for (k = 0; k < 3; k++) spec[0].kr[k] = spec[0].kt[k] = spec[1].kr[k] = spec[1].kt[k] = 1;
        spec[0].fresnel = spec[1].fresnel = 1;
        need = gr_query_scratch_bytes(grid);
        scratch = malloc(need);
        q.line_samples = 2;
        for (k = 0; k <= MAXD; k++)
            for (in = 0; in < 2; in++) {
                double e = shade_split(grid, &q, spec, k, in, scratch, need);
                if (c == 0) base[2 * k + in] = e;
                else worst = fmax(worst, fabs(e - base[2 * k + in]));
            }
        if (c == 0) { /* grazing, lossless, host = 1 */
            gr_indirect_t ind;
            double rgb[3];
            gr_query_t qg = gt_query(0.5013, 0.5, 0.014, 0.9995, 0.01, 1e-3);
            qg.line_samples = 4;
            memset(&ind, 0, sizeof ind);
            ind.depth = GR_MAX_DEPTH; ind.specular = spec; ind.specular_count = 2; ind.trace = one_cb;
            T_INT_EQ(gr_shade_indirect(grid, &qg, &ind, scratch, need, rgb, NULL), GR_OK);
            printf("  grazing E_w = 1e-3, lossless glass ridge, host = 1: colour %.6f\n", rgb[0]);
            T_CHECK(rgb[0] > 0.99 && rgb[0] <= 1 + 1e-9);
        }
        free(scratch);
        gr_grid_free(grid);
    }
    printf("  glass ridge at scales 1e-5 and 1e3: worst |E_k - E_k(scale 1)| = %.1e\n", worst);
    T_LE(worst, 1e-6);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(t_mirror_energy_vs_pathtraced), T_CASE(t_crossing_energy_vs_pathtraced), T_CASE(t_direction_from_below), T_CASE(t_depth0_is_direct),
        T_CASE(t_shadow_from_outside_the_view), T_CASE(t_transmission_to_host), T_CASE(t_transmission_vs_pathtraced), T_CASE(t_transmission_ridge_over_cut),
        T_CASE(t_stack_full), T_CASE(t_stiff_indirect_scale_grazing),
    };
    return T_RUN(argc, argv, cases);
}
