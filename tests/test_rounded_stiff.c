/* tests/test_rounded_stiff.c — rounded_edges.h: the stiff and extreme cases
   of issue 6, one named case each, every one asserting a bound against an
   independent oracle (analytic rounded box, or sphere tracing of the
   eroded polytope). */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"
#include "../examples/common/ex_mesh.c" /* the examples' icosphere: libc/libm only */

static const double BOX_LO[3] = {-0.5, -0.3, -0.2}, BOX_HI[3] = {0.5, 0.3, 0.2};

static void tiny_radius_1e6_of_size_box(void) { box_rays(BOX_LO, BOX_HI, 1e-6, t_count(20000), 1e-9, 3); }

static void tiny_radius_1e6_of_size_hull(void)
{
    static const double q[6][2] = {{-1, -0.4}, {0.3, -0.7}, {1, -0.1}, {0.8, 0.6}, {-0.2, 0.8}, {-0.9, 0.3}};
    tm_mesh_t m = {0};
    static tm_poly_t P;
    tm_prism(&m, &P, q, 6, 0.6);
    poly_rays(&m, &P, 2e-6, t_count(6000), 1e-9, 5, "tiny r prism");
    tm_free(&m);
}

static void largest_valid_radius_box(void)
{
    tm_mesh_t m = {0};
    re_diag_t dg;
    re_scene_t *s;
    re_stats_t st;
    tm_box(&m, BOX_LO, BOX_HI);
    s = build1(&m, 0.2, &dg); /* half the thinnest extent: the eroded box is flat */
    if (T_CHECK(s != NULL)) {
        re_get_stats(s, &st);
        T_INT_EQ(st.clamped, 0);
        T_EQ(re_object_radius(s, 0), 0.2);
        re_free(s);
    }
    box_rays(BOX_LO, BOX_HI, 0.2, t_count(20000), 1e-9, 4);
    tm_free(&m);
}

static int n_clamp_reports;
static void count_clamp(void *u, const re_report_t *r)
{
    (void)u;
    if (r->kind == RE_REPORT_RADIUS_CLAMPED) n_clamp_reports++;
}

static void radius_above_largest_is_clamped(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_diag_t dg;
    tm_box(&m, BOX_LO, BOX_HI);
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.radius = 0.25;
    desc.objects = &mesh, desc.object_count = 1, desc.report = count_clamp;
    n_clamp_reports = 0;
    T_INT_EQ(re_build(&desc, &s, &dg), RE_OK);
    T_INT_EQ(n_clamp_reports, 1);
    T_NEAR(re_object_radius(s, 0), 0.2, 1e-15);
    re_free(s);
    tm_free(&m);
}

static void radius_above_largest_is_rejected(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_diag_t dg;
    tm_box(&m, BOX_LO, BOX_HI);
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.radius = 0.2001;
    desc.objects = &mesh, desc.object_count = 1, desc.radius_policy = RE_RADIUS_REJECT;
    T_INT_EQ(re_build(&desc, &s, &dg), RE_ERR_RADIUS_TOO_LARGE);
    T_INT_EQ(dg.result, RE_ERR_RADIUS_TOO_LARGE);
    T_GE(dg.element, 0);
    T_CHECK(strstr(dg.message, "too large") != NULL);
    T_CHECK(s == NULL);
    tm_free(&m);
}

/* Radius validation per element (issue 6: "an edge shorter than its two
   tangent set-backs, or a slab thinner than its inradius allows"). */
typedef struct clamp_log_t { int n; long long e1, e2; double value; char msg[160]; } clamp_log_t;
static void log_clamp(void *u, const re_report_t *r)
{
    clamp_log_t *L = (clamp_log_t *)u;
    if (r->kind != RE_REPORT_RADIUS_CLAMPED) return;
    L->n++, L->e1 = r->element, L->e2 = r->element2, L->value = r->value;
    snprintf(L->msg, sizeof L->msg, "%s", r->message);
}
/* Builds m at radius r under `policy`; returns the build result, the clamp
   report in *L and the diagnostic in *dg. */
static re_result_t build_policy(const tm_mesh_t *m, double r, re_radius_policy_t policy, clamp_log_t *L, re_diag_t *dg,
                                double *r_out)
{
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_result_t rc;
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    memset(L, 0, sizeof *L);
    mesh.positions = m->v, mesh.vertex_count = m->nv, mesh.indices = m->idx, mesh.index_count = m->ni, mesh.radius = r;
    desc.objects = &mesh, desc.object_count = 1, desc.radius_policy = policy;
    desc.report = log_clamp, desc.report_user = L;
    rc = re_build(&desc, &s, dg);
    *r_out = s ? re_object_radius(s, 0) : 0;
    re_free(s);
    return rc;
}

/* A prism over a pentagon with one side 0.042 long between two 135-degree
   corners: at r = 0.1 the set-backs of its top and bottom edges (r tan 22.5
   degrees at each end) exceed the edge. The edge is named; clamped, the
   radius is the largest at which the edge's cylinder does not turn over,
   and the hits match the eroded polytope there. */
static void short_edge_is_named(void)
{
    double q[5][2] = {{0, 0}, {1, 0}, {1, 0.5}, {0.97, 0.53}, {0, 0.53}};
    tm_mesh_t m = {0};
    static tm_poly_t P;
    clamp_log_t L;
    re_diag_t dg;
    double r = 0, want = 0.03 * sqrt(2.0) / (2 * tan(M_PI / 8));
    tm_prism(&m, &P, (const double(*)[2])q, 5, 0.25);
    T_INT_EQ(build_policy(&m, 0.1, RE_RADIUS_REJECT, &L, &dg, &r), RE_ERR_RADIUS_TOO_LARGE);
    T_CHECK(strstr(dg.message, "shorter than its two set-backs") != NULL);
    T_GE(dg.element, 0);
    T_INT_EQ(build_policy(&m, 0.1, RE_RADIUS_CLAMP, &L, &dg, &r), RE_OK);
    T_GT(L.n, 0);
    T_GE(L.e2, 0); /* an edge: both of its vertices */
    T_NEAR(r, want, 1e-9);
    fprintf(stderr, "    %s\n", L.msg);
    poly_rays(&m, &P, 0.1, t_count(4000), 1e-7, 31, "short edge, clamped");
    tm_free(&m);
}

/* A slab 1 x 1 x 0.02 whose side walls are split into four rows: the top
   corners' ring (their edge neighbours) holds no bottom plane, because the
   vertical edges pass through vertices inside straight edges. At r = 0.015
   the solid is thinner than 2r; the validation follows each straight edge
   chain to its end: the chain is shorter than its two set-backs, and the
   radius is clamped to 0.01 (half the thickness; before, the first 0.005
   segment alone clamped it to 0.005). */
static void thin_slab_with_subdivided_walls(void)
{
    const double xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, h = 0.02;
    tm_mesh_t m = {0};
    static tm_poly_t P;
    clamp_log_t L;
    re_diag_t dg;
    double r = 0;
    unsigned i, l;
    for (i = 0; i < 4; i++)
        for (l = 0; l <= 4; l++) tm_vert(&m, xy[i][0], xy[i][1], h * l / 4);
    tm_quad(&m, 0 * 5 + 4, 1 * 5 + 4, 2 * 5 + 4, 3 * 5 + 4); /* top, CCW from +z */
    tm_quad(&m, 3 * 5, 2 * 5, 1 * 5, 0 * 5);                 /* bottom */
    for (i = 0; i < 4; i++)
        for (l = 0; l < 4; l++) {
            unsigned a = i * 5 + l, b = ((i + 1) % 4) * 5 + l;
            tm_quad(&m, a, b, b + 1, a + 1);
        }
    T_INT_EQ(build_policy(&m, 0.015, RE_RADIUS_REJECT, &L, &dg, &r), RE_ERR_RADIUS_TOO_LARGE);
    T_CHECK(strstr(dg.message, "too large") != NULL);
    T_GE(dg.element, 0);
    T_INT_EQ(build_policy(&m, 0.015, RE_RADIUS_CLAMP, &L, &dg, &r), RE_OK);
    T_GT(L.n, 0);
    T_NEAR(r, 0.01, 1e-12);
    fprintf(stderr, "    %s\n", L.msg);
    T_INT_EQ(build_policy(&m, 0.0099, RE_RADIUS_REJECT, &L, &dg, &r), RE_OK); /* below it: valid */
    /* exact below the limit, where the chain's end spheres are set back past
       the split vertices at 1/4 and 3/4 of the height (their spheres move
       into the chain's span) */
    tm_planes(&m, &P);
    poly_rays(&m, &P, 0.009, t_count(4000), 1e-7, 32, "thin slab, r = 0.009");
    poly_rays(&m, &P, 0.015, t_count(4000), 1e-7, 33, "thin slab, clamped to 0.01");
    tm_free(&m);
}

/* quad a b c d wound so that its normal points along (nx, ny, nz) */
static void quad_facing(tm_mesh_t *m, unsigned a, unsigned b, unsigned c, unsigned d, double nx, double ny, double nz)
{
    double e1[3], e2[3], n[3], want[3];
    want[0] = nx, want[1] = ny, want[2] = nz;
    tm_sub(m->v + 3 * b, m->v + 3 * a, e1);
    tm_sub(m->v + 3 * c, m->v + 3 * a, e2);
    tm_cross(e1, e2, n);
    if (tm_dot(n, want) > 0) tm_quad(m, a, b, c, d);
    else tm_quad(m, d, c, b, a);
}

/* The cube [-1, 1]^3 with a pocket cut into its top face (z = 1; zf < 1)
   or a boss standing on it (zf > 1): rim x in [xa, xb], y in [ya, yb], the
   pocket's floor or the boss's top at z = zf. The rim's corners are mixed,
   so the rim stays sharp; the cube's twelve edges form one rounded patch
   (a boss's top edges another). */
static void pocketed_cube(tm_mesh_t *m, double xa, double xb, double ya, double yb, double zf)
{
    unsigned b[8], o[4], in[4], f[4], i;
    double w = zf < 1 ? 1 : -1; /* walls face into the pocket, out of the boss */
    for (i = 0; i < 8; i++) b[i] = tm_vert(m, i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    o[0] = b[4], o[1] = b[5], o[2] = b[7], o[3] = b[6]; /* the top square, CCW from +z */
    in[0] = tm_vert(m, xa, ya, 1), in[1] = tm_vert(m, xb, ya, 1), in[2] = tm_vert(m, xb, yb, 1), in[3] = tm_vert(m, xa, yb, 1);
    for (i = 0; i < 4; i++) f[i] = tm_vert(m, m->v[3 * in[i]], m->v[3 * in[i] + 1], zf);
    quad_facing(m, b[0], b[1], b[3], b[2], 0, 0, -1);
    quad_facing(m, b[1], b[3], b[7], b[5], 1, 0, 0);
    quad_facing(m, b[0], b[2], b[6], b[4], -1, 0, 0);
    quad_facing(m, b[2], b[3], b[7], b[6], 0, 1, 0);
    quad_facing(m, b[0], b[1], b[5], b[4], 0, -1, 0);
    for (i = 0; i < 4; i++) quad_facing(m, o[i], o[(i + 1) % 4], in[(i + 1) % 4], in[i], 0, 0, 1);
    quad_facing(m, in[0], in[1], f[1], f[0], 0, w, 0);
    quad_facing(m, in[1], in[2], f[2], f[1], -w, 0, 0);
    quad_facing(m, in[2], in[3], f[3], f[2], 0, -w, 0);
    quad_facing(m, in[3], in[0], f[0], f[3], w, 0, 0);
    quad_facing(m, f[0], f[1], f[2], f[3], 0, 0, 1);
}

/* A rounded patch next to a sharp pocket of the same object (construction
   step 7b): at r = 0.3 the rounding of the edge x = z = 1 would cut the
   pocket's wall at x = 0.9. The radius is clamped to 0.1 (the wall's
   distance: the edge's chord zone), naming a wall triangle; rejected under
   RE_RADIUS_REJECT; and the rounding between the edge and the pocket is
   the cylinder of radius 0.1 (before, r stayed 0.3 and the rounded surface
   crossed the pocket). */
static void rounding_beside_a_pocket_is_clamped(void)
{
    tm_mesh_t m = {0};
    clamp_log_t L;
    re_diag_t dg;
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    double r = 0;
    long i, n = t_count(2000), rounded = 0;
    t_rng_t g = {41};
    pocketed_cube(&m, 0.2, 0.9, -0.5, 0.5, 0.6);
    T_INT_EQ(build_policy(&m, 0.3, RE_RADIUS_REJECT, &L, &dg, &r), RE_ERR_RADIUS_TOO_LARGE);
    T_CHECK(strstr(dg.message, "would cut triangle") != NULL);
    T_GE(dg.element, 12); /* a triangle of the pocket (the cube's own faces come first) */
    T_INT_EQ(build_policy(&m, 0.3, RE_RADIUS_CLAMP, &L, &dg, &r), RE_OK);
    T_INT_EQ(L.n, 1);
    T_INT_EQ(L.e2, -2); /* a triangle, not an edge or a vertex */
    T_NEAR(r, 0.1, 1e-9);
    T_GE(r, 0.1);
    fprintf(stderr, "    %s\n", L.msg);
    T_INT_EQ(build_policy(&m, 0.0999, RE_RADIUS_REJECT, &L, &dg, &r), RE_OK); /* below it: valid */
    /* vertical rays onto the strip between the edge and the pocket */
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.radius = 0.3;
    desc.objects = &mesh, desc.object_count = 1;
    if (!T_INT_EQ(re_build(&desc, &s, &dg), RE_OK)) { tm_free(&m); return; }
    for (i = 0; i < n; i++) {
        double x = t_rng_range(&g, 0.9005, 0.9995), o[3], d[3] = {0, 0, -1}, t;
        unsigned tri;
        re_hit_t h;
        o[0] = x, o[1] = t_rng_range(&g, -0.4, 0.4), o[2] = 3;
        if (!T_CHECK(tm_hit(&m, o, d, &t, &tri))) continue;
        if (!T_INT_EQ(re_query(s, o, d, 0, tri, t, &h), RE_HIT_ROUNDED)) continue;
        rounded++;
        T_NEAR(h.point[2], 0.9 + sqrt(0.01 - (x - 0.9) * (x - 0.9)), 1e-9);
    }
    T_GT(rounded, n / 2);
    re_free(s);
    tm_free(&m);
}

/* A boss standing on the strip the rounding of the edge x = z = 1 would
   remove (footprint x in [0.6, 0.9]): its wall only touches the top face's
   plane, from outside, and still bounds the radius to 0.1 (found by
   review: the zone's planes were open, the boss floated over a groove at
   r = 0.3 and rays passed through it). */
static void rounding_beside_a_boss_is_clamped(void)
{
    const double c0[3] = {0, 0, 0}, half[3] = {1, 1, 1}, base[3] = {0.9, 0, 1};
    tm_mesh_t m = {0};
    clamp_log_t L;
    re_diag_t dg;
    double r = 0;
    pocketed_cube(&m, 0.6, 0.9, -0.5, 0.5, 1.3);
    T_INT_EQ(build_policy(&m, 0.3, RE_RADIUS_CLAMP, &L, &dg, &r), RE_OK);
    T_GE(L.n, 1);
    fprintf(stderr, "    %s\n", L.msg);
    T_NEAR(r, 0.1, 1e-9);
    T_LE(tm_rbox_sdf(c0, half, r, base), 1e-12); /* the wall's foot stays on the rounded cube */
    tm_free(&m);
}

/* A checked object (a loose triangle far away makes it so) whose patch is
   a fine convex prism: its own faces are left to the local bounds, so the
   radius stays as asked (found by review: the corners' balls caught the
   prism's own side faces, r 0.1 -> 0.0406). */
static void far_loose_triangle_clamps_nothing(void)
{
    double q[64][2], r = 0;
    tm_mesh_t m = {0};
    static tm_poly_t P;
    clamp_log_t L;
    re_diag_t dg;
    unsigned a;
    int i;
    for (i = 0; i < 64; i++) q[i][0] = cos(2 * M_PI * i / 64), q[i][1] = sin(2 * M_PI * i / 64);
    tm_prism(&m, &P, (const double(*)[2])q, 64, 1.0);
    a = tm_vert(&m, 50, 50, 50);
    tm_vert(&m, 51, 50, 50);
    tm_vert(&m, 50, 51, 50);
    tm_tri(&m, a, a + 1, a + 2);
    T_INT_EQ(build_policy(&m, 0.1, RE_RADIUS_REJECT, &L, &dg, &r), RE_OK);
    T_INT_EQ(L.n, 0);
    T_NEAR(r, 0.1, 0);
    tm_free(&m);
}

/* Another shell inside the solid: an open fin of two triangles from the
   cube's corner (1, 1, 1) (its own vertex there) along the edge's
   removed volume. The zones are open for other shells, but the fin lies
   inside them, so the radius drops to about 0 (found by review: a rule
   that skipped triangles with a corner at the zone's vertex kept 0.294
   and the rounding cut through the fin). */
static void other_shell_inside_the_rounding_clamps(void)
{
    const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    tm_mesh_t m = {0};
    clamp_log_t L;
    re_diag_t dg;
    double r = 1;
    unsigned a;
    tm_box(&m, lo, hi);
    a = tm_vert(&m, 1, 1, 1);
    tm_vert(&m, 0.95, -0.2, 0.95);
    tm_vert(&m, 0.9, -0.2, 0.9);
    tm_vert(&m, 0.9, 0.8, 0.9);
    tm_tri(&m, a, a + 1, a + 2);
    tm_tri(&m, a, a + 2, a + 3);
    T_INT_EQ(build_policy(&m, 0.3, RE_RADIUS_CLAMP, &L, &dg, &r), RE_OK);
    T_GE(L.n, 1);
    T_LT(L.value, 1e-9);
    tm_free(&m);
}

/* A box resting on a cube, both in one object: the cube's rounding gives
   up the contact as when the two are built apart, and whether the object
   is checked at all (a loose triangle far away makes it so) changes
   nothing: the same clamps, the same radii (found by review: the resting
   box's top corners' balls reached below its bottom face and caught the
   cube's top, 0.183 against 0.25). */
static void touching_shells_agree_checked_or_not(void)
{
    const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1}, lo2[3] = {0.5, 0.5, 1}, hi2[3] = {1, 1, 1.5};
    clamp_log_t L[2];
    re_diag_t dg;
    double r[2];
    int k;
    for (k = 0; k < 2; k++) {
        tm_mesh_t m = {0};
        tm_box(&m, lo, hi);
        tm_box(&m, lo2, hi2);
        if (k) {
            unsigned a = tm_vert(&m, 50, 50, 50);
            tm_vert(&m, 51, 50, 50);
            tm_vert(&m, 50, 51, 50);
            tm_tri(&m, a, a + 1, a + 2);
        }
        T_INT_EQ(build_policy(&m, 0.3, RE_RADIUS_CLAMP, &L[k], &dg, &r[k]), RE_OK);
        tm_free(&m);
    }
    T_INT_EQ(L[1].n, L[0].n);
    T_NEAR(L[1].value, L[0].value, 0);
    T_NEAR(r[1], r[0], 0);
    T_NEAR(L[0].value, 0.25, 1e-12); /* the resting box's own edges */
}

/* The same with the pocket next to the corner (1, 1, 1): rim x, y in
   [0.6, 0.9]. The largest radius that keeps the walls out of the rounding
   is 0.1 (the rim's corner (0.9, 0.9, 1) lies on the rounded cube of
   r = 0.1, outside it above). The corner's zone is a ball of 1 + sqrt 3
   times r, so the bound is conservative there: 0.1 / 2.74 <= r <= 0.1,
   and the walls lie inside the rounded cube of the radius built. */
static void rounding_beside_a_pocket_near_a_corner(void)
{
    const double c0[3] = {0, 0, 0}, half[3] = {1, 1, 1};
    tm_mesh_t m = {0};
    clamp_log_t L;
    re_diag_t dg;
    double r = 0, worst = -HUGE_VAL;
    unsigned t, k;
    t_rng_t g = {43};
    pocketed_cube(&m, 0.6, 0.9, 0.6, 0.9, 0.6);
    T_INT_EQ(build_policy(&m, 0.3, RE_RADIUS_CLAMP, &L, &dg, &r), RE_OK);
    T_INT_EQ(L.n, 1);
    fprintf(stderr, "    %s\n", L.msg);
    T_LE(r, 0.1 * (1 + 1e-9));
    T_GE(r, 0.1 / (1 + sqrt(3.0)));
    /* every wall and floor triangle of the pocket (0-11: the cube's other
       faces, 12-19: the top face's ring, the patch's own face) */
    for (t = 20; t < m.ni / 3; t++)
        for (k = 0; k < 200; k++) {
            double a = t_rng_unit(&g), b = t_rng_unit(&g), p[3];
            unsigned j;
            if (a + b > 1) a = 1 - a, b = 1 - b;
            for (j = 0; j < 3; j++)
                p[j] = m.v[3 * m.idx[3 * t] + j] + a * (m.v[3 * m.idx[3 * t + 1] + j] - m.v[3 * m.idx[3 * t] + j]) +
                       b * (m.v[3 * m.idx[3 * t + 2] + j] - m.v[3 * m.idx[3 * t] + j]);
            worst = fmax(worst, tm_rbox_sdf(c0, half, r, p));
        }
    T_LE(worst, 1e-12);
    tm_free(&m);
}


/* a ridge of 179.9 degrees on top of a slab */
static void dihedral_179_9_degrees(void)
{
    double q[5][2] = {{-1, 0}, {1, 0}, {1, 0.5}, {0, 0}, {-1, 0.5}};
    tm_mesh_t m = {0};
    static tm_poly_t P;
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    q[3][1] = 0.5 + tan(0.05 * M_PI / 180);
    tm_prism(&m, &P, (const double(*)[2])q, 5, 0.5);
    s = build1(&m, 0.05, &dg);
    if (T_CHECK(s != NULL)) {
        re_get_stats(s, &st);
        T_INT_EQ(st.rounded_edges, 15); /* 5 + 5 + 5: the ridge is rounded, not merged as flat */
        re_free(s);
    }
    /* in float positions too (its triangles' rounding tilts them by ~1e-6) */
    s = build1_float(&m, 0.05, &dg);
    if (T_CHECK(s != NULL)) {
        re_get_stats(s, &st);
        T_INT_EQ(st.rounded_edges, 15);
        re_free(s);
    }
    poly_rays(&m, &P, 0.05, t_count(8000), 1e-7, 6, "179.9 ridge");
    tm_free(&m);
}

/* a knife wedge: dihedral 1 degree along its apex edge */
static void dihedral_1_degree(void)
{
    double q[3][2] = {{0, 0}, {1, 0}, {1, 0}};
    tm_mesh_t m = {0};
    static tm_poly_t P;
    q[1][1] = -tan(0.5 * M_PI / 180), q[2][1] = tan(0.5 * M_PI / 180);
    tm_prism(&m, &P, (const double(*)[2])q, 3, 0.5);
    poly_rays(&m, &P, 0.003, t_count(8000), 1e-7, 7, "1 degree wedge");
    tm_free(&m);
}

static void icosphere_level1(void)
{
    tm_mesh_t m = {0};
    static tm_poly_t P;
    tm_icosphere(&m, 1, 1.0);
    tm_planes(&m, &P);
    poly_rays(&m, &P, 0.02, t_count(4000), 1e-7, 8, "icosphere");
    tm_free(&m);
}

static void coordinates_offset_1e6(void)
{
    double lo[3], hi[3];
    int a;
    for (a = 0; a < 3; a++) lo[a] = BOX_LO[a] + 1e6, hi[a] = BOX_HI[a] + 1e6;
    /* positions carry ulp(1e6) = 1.2e-10 each: hit points within 1e-9 of the
       size (about 10 ulps), t within that over the cosine of incidence */
    g_t_conditioned = 1;
    box_rays(lo, hi, 0.05, t_count(20000), 1e-9, 9);
    g_t_conditioned = 0;
}

/* A ray at the test box from up to 3 away, aimed near its edges and
   corners in two draws of three per axis. */
static void box_edge_ray(t_rng_t *rng, double o[3], double d[3])
{
    double tgt[3];
    int a;
    for (a = 0; a < 3; a++) {
        double w = t_rng_unit(rng);
        tgt[a] = w < 0.35 ? BOX_LO[a] + 0.08 * t_rng_unit(rng) : w < 0.7 ? BOX_HI[a] - 0.08 * t_rng_unit(rng)
                                                                     : t_rng_range(rng, BOX_LO[a], BOX_HI[a]);
        o[a] = tgt[a] + t_rng_range(rng, -3, 3);
    }
    tm_sub(tgt, o, d);
}

/* The box scaled to the ends of the supported sizes (its diagonal 1.23 s,
   s = 1e-60 and 8e35): every answer is the unit box's scaled (kind, t / s
   and point / s within 1e-9, normals within 1e-9), rounding being
   scale-invariant; the unit box is exact against the analytic one above. */
static void object_sizes_at_both_ends_of_the_range(void)
{
    static const double scales[2] = {1e-60, 8e35};
    tm_mesh_t m1 = {0};
    re_scene_t *s1;
    re_diag_t dg;
    int k, a;
    tm_box(&m1, BOX_LO, BOX_HI);
    s1 = build1(&m1, 0.05, &dg);
    if (!T_CHECK(s1 != NULL)) { tm_free(&m1); return; }
    for (k = 0; k < 2; k++) {
        double lo[3], hi[3], f = scales[k];
        tm_mesh_t ms = {0};
        re_scene_t *ss;
        t_rng_t rng = {60};
        long i, n = t_count(4000), rounded = 0;
        for (a = 0; a < 3; a++) lo[a] = BOX_LO[a] * f, hi[a] = BOX_HI[a] * f;
        tm_box(&ms, lo, hi);
        ss = build1(&ms, 0.05 * f, &dg);
        if (!T_CHECK(ss != NULL)) { tm_free(&ms); continue; }
        for (i = 0; i < n; i++) {
            double o[3], d[3], of[3], t1, tf, u, v;
            unsigned tri1, trif;
            re_hit_t h1, hf;
            box_edge_ray(&rng, o, d);
            for (a = 0; a < 3; a++) of[a] = o[a] * f;
            if (!tm_hit_uv(&m1, o, d, &t1, &tri1, &u, &v) || !tm_hit_uv(&ms, of, d, &tf, &trif, &u, &v)) continue;
            re_query(s1, o, d, 0, tri1, t1, &h1);
            re_query(ss, of, d, 0, trif, tf, &hf);
            rounded += h1.kind == RE_HIT_ROUNDED;
            if (!T_INT_EQ(hf.kind, h1.kind)) continue;
            T_NEAR(hf.t / f, h1.t, 1e-9 * (1 + h1.t));
            for (a = 0; a < 3; a++) {
                T_NEAR(hf.point[a] / f, h1.point[a], 1e-9);
                T_NEAR(hf.normal[a], h1.normal[a], 1e-9);
            }
        }
        T_GT(rounded, n / 10);
        re_free(ss);
        tm_free(&ms);
    }
    re_free(s1);
    tm_free(&m1);
}

/* Beyond them the build fails with RE_ERR_BAD_SCALE and says why: above
   ~3e39 the float detection radii overflowed (the build succeeded and
   every rounded hit came back unchanged), from 1e78 every edge read as
   concave, from 1e155 the box's triangles read as degenerate; below
   ~1e-79 hits moved by 2e-5 of the size, below 1e-81 degenerate again. */
static void object_sizes_outside_the_range_rejected(void)
{
    static const double scales[6] = {1e-62, 1e-80, 1e-90, 1e37, 1e78, 1e160};
    int k, a, n;
    for (k = 0; k < 6; k++) {
        double lo[3], hi[3];
        tm_mesh_t m = {0};
        re_diag_t dg;
        re_scene_t *sc;
        for (a = 0; a < 3; a++) lo[a] = BOX_LO[a] * scales[k], hi[a] = BOX_HI[a] * scales[k];
        tm_box(&m, lo, hi);
        for (n = 0; n < 2; n++) { /* the size, or the first triangle whose squares leave doubles */
            sc = build1(&m, 0.05 * scales[k], &dg);
            T_CHECK(sc == NULL);
            re_free(sc);
            T_INT_EQ(dg.result, RE_ERR_BAD_SCALE);
            T_CHECK(strstr(dg.message, "outside [1e-60, 1e+36]") != NULL);
        }
        tm_free(&m);
    }
}

/* Directions 2^-600 ... 2^600 long (exact scalings of the same rays): the
   query traces them rescaled, so every answer is the unit ray's, its t
   scaled (within 1e-12, the rescaled direction differs from the unit one
   by a power of 2 too), through re_query, re_query_uv, re_query_exit,
   re_query_exit_uv and re_secondary_origin. At 1e+-200 a third of the rounded hits had come
   back unchanged, or with the point left on the sharp face. */
static void extreme_direction_lengths(void)
{
    static const int exps[4] = {-600, -100, 100, 600};
    tm_mesh_t m = {0};
    re_scene_t *sc;
    re_diag_t dg;
    t_rng_t rng = {600};
    long i, n = t_count(3000), rounded = 0;
    int a, k;
    tm_box(&m, BOX_LO, BOX_HI);
    sc = build1(&m, 0.05, &dg);
    if (!T_CHECK(sc != NULL)) { tm_free(&m); return; }
    for (i = 0; i < n; i++) {
        double o[3], d[3], t_host, u, v, so0[3];
        unsigned tri;
        re_hit_t h0, x0;
        box_edge_ray(&rng, o, d);
        if (!tm_hit_uv(&m, o, d, &t_host, &tri, &u, &v)) continue;
        re_query(sc, o, d, 0, tri, t_host, &h0);
        re_query_exit(sc, o, d, 0, tri, t_host, &x0);
        re_secondary_origin(sc, &h0, d, so0);
        rounded += h0.kind == RE_HIT_ROUNDED;
        for (k = 0; k < 4; k++) {
            double ds[3], f = ldexp(1.0, exps[k]), so[3];
            re_hit_t h, hu, x, xu;
            for (a = 0; a < 3; a++) ds[a] = d[a] * f;
            re_query(sc, o, ds, 0, tri, t_host / f, &h);
            re_query_uv(sc, o, ds, 0, tri, t_host / f, u, v, &hu);
            re_query_exit(sc, o, ds, 0, tri, t_host / f, &x);
            re_query_exit_uv(sc, o, ds, 0, tri, t_host / f, u, v, &xu);
            re_secondary_origin(sc, &h, ds, so);
            if (!T_INT_EQ(h.kind, h0.kind) || !T_INT_EQ(hu.kind, h0.kind) || !T_INT_EQ(x.kind, x0.kind) ||
                !T_INT_EQ(xu.kind, x0.kind))
                continue;
            T_NEAR(h.t * f, h0.t, 1e-12 * (1 + h0.t));
            T_NEAR(hu.t * f, h0.t, 1e-12 * (1 + h0.t));
            T_NEAR(x.t * f, x0.t, 1e-12 * (1 + x0.t));
            T_NEAR(xu.t * f, x0.t, 1e-12 * (1 + x0.t));
            for (a = 0; a < 3; a++) {
                T_NEAR(h.point[a], h0.point[a], 1e-12);
                T_NEAR(so[a], so0[a], 1e-12);
            }
        }
    }
    T_GT(rounded, n / 10);
    re_free(sc);
    tm_free(&m);
}

/* A box whose faces are 24 x 24 grids of quads, turned (generic planes),
   built at the origin and moved to (3e5, -2e5, 1e5) plus fractions: there
   each vertex is rounded to 6e-11, which tilts the coplanar pieces (0.03
   high) of a face against each other by up to ~2e-9, above RE__FLAT_SIN.
   They must stay flat (RE__FLAT_ROUNDINGS): the same edge classes,
   corners and spheres as at the origin, nothing clamped. Before, those
   pieces met at convex edges of no visible angle (and a patch with such an
   edge through a corner's own plane got no radius at all). */
typedef struct grid_frame_t { double R[3][3], off[3]; } grid_frame_t; /* x -> R x + off */
static const double GRID_EXT[3] = {1.0, 0.6, 0.4};                     /* the box [0, GRID_EXT] */
/* turned about z by 0.3 and about x by 0.2, then moved by off */
static grid_frame_t grid_frame_turned(const double off[3])
{
    const double ca = cos(0.3), sa = sin(0.3), cb = cos(0.2), sb = sin(0.2);
    grid_frame_t F = {{{ca, -sa, 0}, {cb * sa, cb * ca, -sb}, {sb * sa, sb * ca, cb}}, {0, 0, 0}};
    memcpy(F.off, off, sizeof F.off);
    return F;
}
static unsigned grid_vert(tm_mesh_t *m, unsigned *map, int n, const int g[3], const grid_frame_t *F)
{
    unsigned *slot = map + ((size_t)g[0] * (size_t)(n + 1) + (size_t)g[1]) * (size_t)(n + 1) + (size_t)g[2];
    double p[3], q[3];
    int a;
    if (*slot) return *slot - 1;
    for (a = 0; a < 3; a++) p[a] = GRID_EXT[a] * g[a] / n;
    for (a = 0; a < 3; a++) q[a] = F->R[a][0] * p[0] + F->R[a][1] * p[1] + F->R[a][2] * p[2] + F->off[a];
    *slot = tm_vert(m, q[0], q[1], q[2]) + 1;
    return *slot - 1;
}
static void grid_box(tm_mesh_t *m, int n, const grid_frame_t *F)
{
    unsigned *map = (unsigned *)calloc((size_t)(n + 1) * (size_t)(n + 1) * (size_t)(n + 1), sizeof(unsigned));
    int f, i, j;
    for (f = 0; f < 6; f++) {
        int ax = f / 2, u = (ax + 1) % 3, w = (ax + 2) % 3, side = f % 2;
        for (i = 0; i < n; i++)
            for (j = 0; j < n; j++) {
                int g[4][3], k;
                unsigned v[4];
                for (k = 0; k < 4; k++) g[k][ax] = side ? n : 0;
                g[0][u] = i, g[0][w] = j, g[1][u] = i + 1, g[1][w] = j;
                g[2][u] = i + 1, g[2][w] = j + 1, g[3][u] = i, g[3][w] = j + 1;
                for (k = 0; k < 4; k++) v[k] = grid_vert(m, map, n, g[k], F);
                /* counter-clockwise from outside: u then w is +ax */
                if (side) tm_quad(m, v[0], v[1], v[2], v[3]);
                else tm_quad(m, v[0], v[3], v[2], v[1]);
            }
    }
    free(map);
}
static void coplanar_pieces_far_from_origin_stay_flat(void)
{
    const double at0[3] = {0, 0, 0}, far[3] = {3e5 + 0.1234, -2e5 + 0.5678, 1e5 + 0.9101};
    re_stats_t st[2];
    int k;
    for (k = 0; k < 2; k++) {
        tm_mesh_t m = {0};
        re_scene_t *s;
        re_diag_t dg;
        grid_frame_t F = grid_frame_turned(k ? far : at0);
        grid_box(&m, 24, &F);
        s = build1(&m, 0.05, &dg);
        if (!T_CHECK(s != NULL)) { tm_free(&m); return; }
        re_get_stats(s, &st[k]);
        re_free(s);
        tm_free(&m);
    }
    T_INT_EQ(st[0].convex_edges, 12 * 24); /* the box's 12 edges, in 24 segments each */
    T_INT_EQ(st[1].convex_edges, st[0].convex_edges);
    T_INT_EQ(st[1].flat_edges, st[0].flat_edges);
    T_INT_EQ(st[1].concave_edges, 0);
    T_INT_EQ(st[1].rounded_edges, st[0].rounded_edges);
    T_INT_EQ(st[1].rounded_corners, st[0].rounded_corners);
    T_INT_EQ(st[1].spheres, st[0].spheres);
    T_INT_EQ(st[1].clamped, 0);
}

/* rays aimed exactly at the box's vertices and edge midpoints */
static void rays_exactly_through_edges_and_vertices(void)
{
    tm_mesh_t m = {0};
    rbox_t b;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng = {10};
    long n_round = 0, n_pass = 0, n = 0;
    int a, k, i;
    tm_box(&m, BOX_LO, BOX_HI);
    for (a = 0; a < 3; a++) b.c[a] = 0, b.half[a] = BOX_HI[a];
    b.r = 0.05;
    s = build1(&m, 0.05, &dg);
    if (!T_CHECK(s != NULL)) return;
    for (k = 0; k < 8 + 12; k++) {
        double tgt[3];
        if (k < 8)
            for (a = 0; a < 3; a++) tgt[a] = (k >> a) & 1 ? BOX_HI[a] : BOX_LO[a];
        else {
            int e = k - 8, ax = e / 4;
            for (a = 0; a < 3; a++) tgt[a] = a == ax ? 0 : (((e % 4) >> (a > ax ? a - 1 : a)) & 1) ? BOX_HI[a] : BOX_LO[a];
        }
        for (i = 0; i < 200; i++) {
            double o[3], d[3], u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
            o[0] = tgt[0] + 3 * w * cos(u), o[1] = tgt[1] + 3 * w * sin(u), o[2] = tgt[2] + 3 * v;
            tm_sub(tgt, o, d);
            n += check_box_ray(s, &m, &b, o, d, 1e-9, 1.0, &n_round, &n_pass);
        }
    }
    T_GT(n, 1000); /* most of these rays are changed by the rounding */
    re_free(s);
    tm_free(&m);
}

/* rays nearly parallel to the top face: on its flat part the host hit must
   stand; near its edges the rounded hit must lie on the surface with no
   earlier crossing. */
static void rays_grazing_a_face(void)
{
    tm_mesh_t m = {0};
    rbox_t b;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng = {11};
    long i, n_flat = 0, n_round = 0;
    int a;
    tm_box(&m, BOX_LO, BOX_HI);
    for (a = 0; a < 3; a++) b.c[a] = 0, b.half[a] = BOX_HI[a];
    b.r = 0.05;
    s = build1(&m, 0.05, &dg);
    if (!T_CHECK(s != NULL)) return;
    for (i = 0; i < t_count(20000); i++) {
        double eps = pow(10.0, -(double)(1 + i % 9)), phi = t_rng_range(&rng, 0, 2 * M_PI), tgt[3], d[3], o[3], t_host;
        unsigned tri;
        re_hit_t h;
        int inner = i % 2;
        tgt[0] = inner ? t_rng_range(&rng, -0.4, 0.4) : t_rng_range(&rng, 0.42, 0.5);
        tgt[1] = t_rng_range(&rng, -0.25, 0.25);
        tgt[2] = 0.2;
        d[0] = cos(phi), d[1] = sin(phi), d[2] = -eps;
        for (a = 0; a < 3; a++) o[a] = tgt[a] - 2 * d[a];
        if (!tm_hit(&m, o, d, &t_host, &tri)) continue;
        re_query(s, o, d, 0, tri, t_host, &h);
        if (h.kind == RE_UNCHANGED) {
            double p[3];
            for (a = 0; a < 3; a++) p[a] = o[a] + h.t * d[a];
            T_NEAR(tm_rbox_sdf(b.c, b.half, b.r, p), 0.0, 1e-12);
            n_flat++;
        } else if (h.kind == RE_HIT_ROUNDED) {
            int k;
            T_NEAR(tm_rbox_sdf(b.c, b.half, b.r, h.point), 0.0, 1e-12);
            for (k = 1; k < 64; k++) { /* no earlier entry (sampled) */
                double p[3], tt = h.t * k / 64.0;
                for (a = 0; a < 3; a++) p[a] = o[a] + tt * d[a];
                if (!T_GT(tm_rbox_sdf(b.c, b.half, b.r, p), -1e-12)) break;
            }
            n_round++;
        }
    }
    T_GT(n_flat, t_count(20000) / 4);
    T_GT(n_round, 10);
    re_free(s);
    tm_free(&m);
}

/* Rays per hull and radius: 600, and under the sanitizers' scale still 63,
   a whole period of the tilts (i % 7) and the vertex pairs (i / 3 % 3). */
static long along_face_ray_count(void)
{
    long n = t_count(600);
    return n < 63 ? 63 : n;
}

/* One hull, rays lying exactly in its top face's plane y = 1 through a
   vertex or edge point of that face (found by fuzz_rounded_exact: a ray
   through a vertex, along a face whose edge from it runs 0.9 degrees off
   the ray). Such a ray only touches the rounded solid: tangent to a
   capsule, then on the face's flat part. Whatever the answer, its point
   lies on the rounded surface, or a pass-through's on the sharp hull with
   a face's normal through it, never past the hull, and the ray never goes
   deeper than tol into the rounded solid before it; a rounded hit's
   reflected ray starts on the sharp hull, pushed out (counted in
   *n_round). Returns the rays that hit the hull. */
static long along_face_rays(const double (*pts)[3], int n, double r_rel, t_rng_t *rng, long *bad, long *n_round)
{
    static const double tilt[7] = {0, 1e-16, -1e-16, 1e-13, -1e-13, 1e-10, -1e-10};
    tm_mesh_t m = {0};
    tm_eroded_t E;
    static tm_poly_t P;
    re_scene_t *s;
    re_diag_t dg;
    double scale, tol;
    long i, hits = 0, n_rays = along_face_ray_count();
    int a, k, top[3], nt = 0;
    memset(&P, 0, sizeof P);
    tm_hull(pts, n, &m, &P);
    scale = tm_size(m.v, m.nv);
    tol = 1e-9 * scale;
    s = build1(&m, r_rel * scale, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); return 0; }
    E.P = &P, E.r = re_object_radius(s, 0);
    tm_erode(&P, E.r);
    for (k = 0; k < n && nt < 3; k++)
        if (pts[k][1] == 1) top[nt++] = k;
    for (i = 0; i < n_rays && nt == 3; i++) {
        double phi = t_rng_range(rng, 0, 2 * M_PI), f = i % 3 ? 0 : t_rng_unit(rng), d[3], o[3], p[3], t_host, bu, bv;
        const double *va = pts[top[i / 3 % 3]], *vb = pts[top[(i / 3 + 1) % 3]];
        char why[160];
        unsigned tri;
        re_hit_t h;
        /* in the plane, or tilted by 1e-16, 1e-13 or 1e-10 out of it or into the solid */
        d[0] = cos(phi), d[1] = tilt[i % 7], d[2] = sin(phi);
        for (a = 0; a < 3; a++) o[a] = va[a] + f * (vb[a] - va[a]) - 3 * scale * d[a];
        if (d[1] == 0) o[1] = 1;
        if (!tm_hit_exact_uv(&m, o, d, &t_host, &tri, &bu, &bv)) continue; /* tm_hit_uv's t is noise here */
        hits++;
        re_query(s, o, d, 0, tri, t_host, &h);
        check_query_uv(s, o, d, tri, t_host, bu, bv, &h);
        for (a = 0; a < 3; a++) p[a] = o[a] + h.t * d[a];
        if (!along_answer_on_surface(&P, &E, o, d, t_host, &h, tol, why, sizeof why)) {
            if (++*bad < 5) T_FAIL("r %g ray %ld: %s (host triangle %u)", r_rel, i, why, tri);
            continue;
        }
        if (h.kind == RE_HIT_ROUNDED && !check_feature(s, &h, tol, scale)) {
            if (++*bad < 5) T_FAIL("r %g ray %ld: rounded hit at t %.17g off its feature (host triangle %u)", r_rel, i, h.t, tri);
            continue;
        } else if (h.kind == RE_HIT_ROUNDED) {
            /* the normal the reference's, to what a seam allows (as fuzz_rounded_exact's fx_normal: the
               features' noise e, and p's distance dp from the eroded polytope) */
            double y[3], nref[3], dp = tm_eroded_nearest(&E, p, y) + E.r, e = 1e-12 * (scale + fabs(p[0]) + fabs(p[1]) + fabs(p[2])),
                   dn_ok = 1e-6 + (sqrt(e * (E.r + dp)) + fabs(E.r - dp)) / E.r, dd;
            tm_sub(p, y, nref);
            tm_norm(nref);
            dd = fabs(nref[0] - h.normal[0]) + fabs(nref[1] - h.normal[1]) + fabs(nref[2] - h.normal[2]);
            if (!(dd <= dn_ok) && ++*bad < 5)
                T_FAIL("r %g ray %ld: rounded hit (feature %d %u) at t %.17g, its normal %.3g from the reference's (bound %.3g)", r_rel,
                       i, (int)h.feature, h.feature_index, h.t, dd, dn_ok);
        }
        if (h.kind == RE_HIT_ROUNDED) { /* the reflected ray's origin: on the sharp hull, pushed out */
            ++*n_round;
            if (!along_reflection_starts_on_hull(s, &P, NULL, d, &h, scale, why, sizeof why) && ++*bad < 5)
                T_FAIL("r %g ray %ld: %s", r_rel, i, why);
        }
        if (!along_answer_not_deep(&E, o, d, t_host, &h, scale, tol, 64, why, sizeof why) && ++*bad < 5)
            T_FAIL("r %g ray %ld: %s", r_rel, i, why);
    }
    re_free(s);
    tm_free(&m);
    return hits;
}

/* Rays along the faces of two hulls of fuzz_rounded_exact's mode for rays
   along a face (rays_along_faces_of; as the fuzzer built them, r = 2^-5
   of the size), through every vertex in 2 000 directions in each
   triangle's plane there. On the first, vertex 2 is of degree 5 and so
   narrow that its corner's walk (2.83) spans more than the size (1.9): a
   ray through it in the plane of triangle 2 6 8, tilted by -1e-16, met no
   capsule, and the exit the search found, by the plane of a corner it
   reached, lay far past the face's far edge, 0.93 outside the hull, which
   passed for within reach. On the second, a ray through vertex 5 in the
   plane of triangle 4 8 5 left 0.71 outside the hull, in the detection
   zone of an edge of another face. Before the exit check's edge test
   (re__edge_joins) 9 of the first hull's 43 271 hitting rays fail and 25
   of the second's 56 505 (built with fused multiply-adds; the fuzzer's
   own rays fail without them); with the test near corners only, 4 of the
   second's; with an exit by the face's own plane let through, 1 (0.97
   outside the hull). */
static void rays_along_a_face_past_a_sharp_corner(void)
{
    static const double v1[12][3] = {
        {0.18458838788433662, -0.66100556954299228, 0.5775997558556496}, {-0.0028839551384756135, 0.03953612573434051, -0.93173113603418023},
        {-0.73434042877851535, 0.13887235828183409, 0.4543373769741359}, {0.10795757991912724, -0.84856946669718469, -0.43660639353017472},
        {-0.11305409323262383, -0.88696116578927287, -0.15611505302510109}, {-0.29765774013885715, -0.65429159990844588, 0.24638742656595713},
        {0.5186999313344014, -0.2112001220721752, 0.9356374456397345}, {-0.44963759822995342, -0.94985885404745551, 0.94827191577019909},
        {0.15870908674753959, 0.79699397268635086, -0.27254139009689482}, {-0.55422293430991076, 0.45110246433203627, -0.75005722133211261},
        {-0.37981231403067062, -0.94113069352254519, 0.9675593194476233}, {0.87618829633020523, -0.59795529106584266, 0.45110246433203627}};
    static const unsigned t1[16][3] = {{1, 3, 9}, {1, 11, 3}, {1, 9, 8},  {1, 8, 11}, {2, 6, 8},  {2, 10, 6}, {2, 9, 7},  {2, 7, 10},
                                       {2, 8, 9}, {3, 4, 9},  {3, 10, 4}, {3, 11, 10}, {4, 7, 9}, {4, 10, 7}, {6, 11, 8}, {6, 10, 11}};
    static const double v2[12][3] = {
        {0.99258411535820557, 1, 1}, {1, -0.65609216449225605, -0.99520866712443734}, {-1, 0.25004959182116426, -0.2141298542763409},
        {-0.88149843595025557, -0.0016632333867399041, 0.26189059281300064}, {0.48384832532234689, -0.99194323643854432, 0.51668574044403748},
        {-0.10182345311665519, -0.16191348134584571, 1}, {1, 0.99902342259861143, 1},
        {-0.24980544747081712, -0.93487449454489968, 0.22395666437781347}, {0.5136644541084916, 0.16234073395895332, 0.95510795757991906},
        {-0.26478980697337295, 0.59255359731441204, 0.75930418860151061}, {-0.64461738002594027, 0.78823529411764715, -0.68938735027084763},
        {0.88949416342412446, -0.69057755397878995, -0.93145647364003969}};
    static const unsigned t2[20][3] = {{0, 5, 6},  {0, 9, 5},  {0, 6, 10}, {0, 10, 9}, {1, 6, 4},   {1, 4, 11}, {1, 10, 6},
                                       {1, 11, 10}, {2, 7, 3},  {2, 3, 9},  {2, 11, 7}, {2, 9, 10},  {2, 10, 11}, {3, 7, 5},
                                       {3, 5, 9},  {4, 5, 7},  {4, 8, 5},  {4, 6, 8},  {4, 7, 11}, {5, 8, 6}};
    long nr = t_count(2000), hits1 = 0, hits2 = 0, bad1, bad2;
    bad1 = rays_along_faces_of(v1, 12, t1, 16, 0.03125, 0, nr, &hits1);
    bad2 = rays_along_faces_of(v2, 12, t2, 20, 0.03125, 0, nr, &hits2);
    T_INT_EQ(bad1, 0);
    T_INT_EQ(bad2, 0);
    T_GT(hits1, nr * 16);
    T_GT(hits2, nr * 16);
    fprintf(stderr, "    %ld and %ld rays hit the hulls\n", hits1, hits2);
}

/* Rays along the top face through its vertices and edges (along_face_rays)
   on the fuzzer's hull and on random hulls with a top face at y = 1, at
   radii from 2^-25 to 0.05 of the size. */
static void rays_along_a_face_through_its_vertices(void)
{
    static const double fuzz_hull[10][3] = {
        {0.018600747692072872, 1, -0.99215686274509807},   {0.77315938048371091, -0.30202182040131231, -0.5136339360646982},
        {-0.4514076447699702, -0.52809948882276647, 0.44136720836194399}, {0.31163500419623102, -0.87542534523537041, -0.67376211184863055},
        {0.79583428702220194, 0.24818799114976731, -0.37285420004577707}, {-0.80450141145952547, -0.24217593652246894, 0.93368429083695736},
        {-0.024948500801098672, 0.92336919203479062, -0.3134050507362478}, {-0.48946364538033116, -0.56060120546272985, -0.19316395819027998},
        {-0.01377889677271682, 1, 1}, {1, 1, 1}};
    static const double radii[4] = {2.98023223876953125e-8, 1e-6, 1e-3, 0.05};
    t_rng_t rng = {29};
    long bad = 0, hits = 0, n_round = 0, n_rays = along_face_ray_count();
    int j, h, k;
    for (j = 0; j < 4; j++) hits += along_face_rays(fuzz_hull, 10, radii[j], &rng, &bad, &n_round);
    for (h = 0; h < 12; h++) {
        double pts[9][3];
        for (k = 0; k < 9; k++) {
            double u = t_rng_range(&rng, 0, 2 * M_PI), R = t_rng_range(&rng, 0.3, 1);
            pts[k][0] = R * cos(u), pts[k][2] = R * sin(u);
            pts[k][1] = k < 3 ? 1 : t_rng_range(&rng, -1, 0.8);
        }
        for (j = 0; j < 4; j++) hits += along_face_rays((const double(*)[3])pts, 9, radii[j], &rng, &bad, &n_round);
    }
    T_INT_EQ(bad, 0);
    T_GT(hits, 10000 * n_rays / 600);
    T_GT(n_round, 1000 * n_rays / 600);
    fprintf(stderr, "    %ld rays along the top face hit the hull, %ld rounded hits\n", hits, n_round);
}

/* Rays lying exactly in the top or bottom face's plane, entering through
   the side x = lo at its edge, so tangent to the rounding of that edge and
   to the flat part they run along (found by fuzz_rounded_exact on a hull):
   whatever the answer, its point is on the rounded box, a pass-through
   never enters it, and a rounded hit's normal is the analytic one to 1e-6.
   The ray-cylinder discriminant taken from I a size away could not tell
   such a tangent ray from one meeting the cylinder, and took its normal
   up to 0.011 off at r = 1e-6 (re__quadric_roots). */
static void rays_lying_in_a_face_plane_case(double r)
{
    tm_mesh_t m = {0};
    rbox_t b;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng = {5};
    long i, n = t_count(6000), n_in_plane = 0;
    int a;
    tm_box(&m, BOX_LO, BOX_HI);
    for (a = 0; a < 3; a++) b.c[a] = 0, b.half[a] = BOX_HI[a];
    b.r = r;
    s = build1(&m, r, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); return; }
    for (i = 0; i < n; i++) {
        double phi = t_rng_range(&rng, -1.4, 1.4), d[3], o[3], t_host, nref[3];
        unsigned tri;
        re_hit_t h;
        d[0] = cos(phi), d[1] = sin(phi), d[2] = 0;
        o[0] = BOX_LO[0] - 2 * d[0], o[1] = t_rng_range(&rng, BOX_LO[1], BOX_HI[1]) - 2 * d[1];
        o[2] = i % 2 ? BOX_LO[2] : BOX_HI[2];
        if (!tm_hit(&m, o, d, &t_host, &tri)) continue;
        n_in_plane++;
        re_query(s, o, d, 0, tri, t_host, &h);
        if (h.kind == RE_PASS_THROUGH) {
            int k;
            for (k = 0; k <= 64; k++) { /* never inside the rounded box up to where the host goes on */
                double p[3], tt = t_host + (h.t - t_host) * k / 64.0;
                for (a = 0; a < 3; a++) p[a] = o[a] + tt * d[a];
                if (!T_GT(tm_rbox_sdf(b.c, b.half, b.r, p), -1e-12)) break;
            }
            continue;
        }
        T_NEAR(tm_rbox_sdf(b.c, b.half, b.r, h.point), 0.0, 1e-12);
        if (h.kind == RE_HIT_ROUNDED) {
            tm_rbox_normal(b.c, b.half, b.r, h.point, nref);
            T_LE(fabs(nref[0] - h.normal[0]) + fabs(nref[1] - h.normal[1]) + fabs(nref[2] - h.normal[2]), 1e-6);
        }
    }
    T_GT(n_in_plane, n / 2);
    re_free(s);
    tm_free(&m);
}
static void rays_lying_in_a_face_plane(void)
{
    rays_lying_in_a_face_plane_case(1e-6);
    rays_lying_in_a_face_plane_case(1e-4);
    rays_lying_in_a_face_plane_case(0.05);
}

/* Host hits beside a sharp corner far from the origin, with a tiny radius
   (found by fuzz_rounded_exact): five points whose hull has a degree-4
   corner v3 with faces at sine 0.30-0.74, moved to (1e6, -1e6, 1e6), r =
   2^-25 of the size (5.2e-8). There the flat-part test's slack (query step
   2) was 64 ulps of magnitudes near 4e6, 1.2 r, so a hit 0.8 r outside one
   shifted plane counted as flat and came back unchanged, 4.8 r (2.5e-7)
   off the rounded surface; the slack is now the test's own rounding
   (RE__FLAT_ULPS). Rays from every side at points up to 8 r from the
   corner toward the other vertices: an answer that is not a pass-through
   lies on the rounded surface (the eroded polytope's distance minus r, in
   local coordinates) to 1e-7 of the size, and for a pass-through the
   reference's trace misses the rounded solid. */
static void flat_test_beside_a_sharp_corner_far_out(void)
{
    static const double q[5][3] = {{-0.8370031281374395, -0.6744335087714717, -0.5215381094021723},
                                   {-1.0, -1.0, -1.0},
                                   {-0.32030212867539376, -0.36717784393113106, -0.06883344775997102},
                                   {-0.2888990616193041, -0.45137712673749775, 0.7469443808076903},
                                   {-0.6577096207765862, -0.7367818722268566, -0.7031204699305817}};
    static const double off[3] = {1e6, -1e6, 1e6};
    static tm_poly_t P;
    tm_mesh_t m = {0}, mw = {0};
    tm_eroded_t E;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng;
    double scale, r, worst = 0;
    long i, n_checked = 0, n_pass = 0, n_bad = 0;
    unsigned k, c3 = 3;
    int a;
    rng.s = 11;
    tm_hull(q, 5, &m, &P);
    for (k = 0; k < m.nv; k++) tm_vert(&mw, m.v[3 * k] + off[0], m.v[3 * k + 1] + off[1], m.v[3 * k + 2] + off[2]);
    for (k = 0; k < m.ni; k += 3) tm_tri(&mw, m.idx[k], m.idx[k + 1], m.idx[k + 2]);
    scale = tm_size(q[0], 5);
    for (k = 0; k < m.nv; k++) /* the hull's vertex at q[3] */
        if (m.v[3 * k] == q[3][0] && m.v[3 * k + 1] == q[3][1] && m.v[3 * k + 2] == q[3][2]) c3 = k;
    s = build1(&mw, ldexp(scale, -25), &dg);
    if (!T_CHECK(s != NULL)) { fprintf(stderr, "sharp corner far out: %s\n", dg.message); return; }
    r = re_object_radius(s, 0);
    T_NEAR(r, ldexp(scale, -25), 1e-12 * r);
    E.P = &P, E.r = r;
    tm_erode(&P, r);
    for (i = 0; i < t_count(20000); i++) {
        double tgt[3], o[3], d[3], x[3], t_host, bu, bv, u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1),
               w = sqrt(1 - v * v), sd;
        unsigned tri;
        re_hit_t h;
        const double *vo = mw.v + 3 * (t_rng_u64(&rng) % mw.nv); /* toward another vertex: inside the hull */
        double in[3], rho = t_rng_range(&rng, 0, 8) * r;
        tm_sub(vo, mw.v + 3 * c3, in);
        if (!(tm_len(in) > 0)) continue;
        tm_norm(in);
        for (a = 0; a < 3; a++) tgt[a] = mw.v[3 * c3 + a] + rho * in[a] + t_rng_range(&rng, -1, 1) * r;
        o[0] = tgt[0] + 3 * w * cos(u), o[1] = tgt[1] + 3 * w * sin(u), o[2] = tgt[2] + 3 * v;
        tm_sub(tgt, o, d);
        if (!tm_hit_uv(&mw, o, d, &t_host, &tri, &bu, &bv)) continue;
        re_query(s, o, d, 0, tri, t_host, &h);
        check_query_uv(s, o, d, tri, t_host, bu, bv, &h);
        n_checked++;
        if (h.kind == RE_PASS_THROUGH) { /* the reference misses the rounded solid too */
            double ol[3], t_ref;
            for (a = 0; a < 3; a++) ol[a] = o[a] - off[a];
            t_ref = tm_trace(tm_eroded_sdf, &E, ol, d, 10.0, scale);
            n_pass++;
            if (!(t_ref == HUGE_VAL) && n_bad++ < 5) T_FAIL("ray %ld: pass-through, the reference hits at %.17g", i, t_ref);
            continue;
        }
        for (a = 0; a < 3; a++) x[a] = o[a] + h.t * d[a] - off[a];
        sd = tm_eroded_sdf(&E, x);
        worst = fmax(worst, fabs(sd));
        if (!(fabs(sd) <= 1e-7 * scale) && n_bad++ < 5)
            T_FAIL("ray %ld: kind %d at t %.17g is %.3g off the rounded surface (r %.3g)", i, (int)h.kind, h.t, sd, r);
    }
    T_INT_EQ(n_bad, 0);
    T_GT(n_checked, t_count(20000) / 4);
    T_GT(n_checked - n_pass, t_count(20000) / 400);
    fprintf(stderr, "  sharp corner far out: %ld answers (%ld pass-throughs), worst %.3g of the size off the rounded surface\n",
            n_checked, n_pass, worst / scale);
    re_free(s);
    tm_free(&m);
    tm_free(&mw);
}

/* A box [0, L] x [-h, h]^2 whose four long edges are split into n segments
   (k = 2 corners all along them), its long faces strips of quads; b is the
   rounded box it stands for. */
static void rod_mesh(tm_mesh_t *m, int n, double L, double h, double r, rbox_t *b)
{
    /* the four long edges, counter-clockwise seen from +x: (y,z) corners */
    static const double cy[4] = {-0.5, 0.5, 0.5, -0.5}, cz[4] = {-0.5, -0.5, 0.5, 0.5};
    unsigned rows[4], i;
    int e;
    for (e = 0; e < 4; e++) {
        rows[e] = m->nv;
        for (i = 0; i <= (unsigned)n; i++) tm_vert(m, L * i / n, cy[e] * 2 * h, cz[e] * 2 * h);
    }
    for (e = 0; e < 4; e++) /* long faces as strips between edge e and e+1 */
        for (i = 0; i < (unsigned)n; i++) {
            unsigned a0 = rows[e] + i, b0 = rows[(e + 1) % 4] + i;
            tm_quad(m, a0, a0 + 1, b0 + 1, b0);
        }
    tm_quad(m, rows[0], rows[3], rows[2], rows[1]);                   /* x = 0 */
    tm_quad(m, rows[0] + n, rows[1] + n, rows[2] + n, rows[3] + n);   /* x = L */
    tm_orient_outward(m);
    b->c[0] = L / 2, b->c[1] = 0, b->c[2] = 0, b->half[0] = L / 2, b->half[1] = h, b->half[2] = h, b->r = r;
}

/* A ray o + t d (t = 1 on the face) at a point of the rod's long face f
   (random), within 4 r of one of its edges (the strips), hit from outside
   at a random slant. */
static void rod_edge_ray(t_rng_t *rng, double L, double h, double r, double o[3], double d[3])
{
    unsigned f = (unsigned)t_rng_range(rng, 0, 4) & 3u, ax = 1 + (f & 1u);
    double x = t_rng_range(rng, 0, L), w = t_rng_range(rng, 0, 4 * r), sg = f < 2 ? -1.0 : 1.0, p[3];
    int a;
    p[0] = x, p[ax] = sg * h, p[3 - ax] = (t_rng_range(rng, 0, 1) < 0.5 ? -1 : 1) * (h - w);
    d[0] = t_rng_range(rng, -0.7, 0.7), d[ax] = -sg, d[3 - ax] = t_rng_range(rng, -0.7, 0.7);
    for (a = 0; a < 3; a++) o[a] = p[a] - d[a];
}

/* A 10-long box whose long edges are split into 20 segments. Rays nearly
   parallel to a long edge run inside its removed volume for several
   segments before they meet the cylinder: the query must follow the
   adjacency graph from corner to corner (§3.1). */
static void grazing_along_a_subdivided_edge(void)
{
    const int n = 20;
    const double L = 10, h = 0.5, r = 0.05;
    tm_mesh_t m = {0};
    rbox_t b;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng = {12};
    long k, far = 0, n_round = 0, n_pass = 0;
    int a;
    rod_mesh(&m, n, L, h, r, &b);
    s = build1(&m, r, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); return; }
    for (k = 0; k < t_count(4000); k++) {
        /* start just inside the corner tip of edge (y, z) = (h, h) in cross
           section, drift toward the axis so the cylinder is met after dx */
        double dx = t_rng_range(&rng, 0.3, 6), eps = t_rng_range(&rng, 0.0, 0.004), o[3], d[3], x0 = t_rng_range(&rng, -0.5, 2);
        double gap = (r * sqrt(2.0) - r) - eps * sqrt(2.0), dl = gap / sqrt(2.0) / dx * t_rng_range(&rng, 0.5, 1.5);
        double ys = t_rng_range(&rng, -1, 1) * 1e-3;
        d[0] = 1, d[1] = -dl + ys * dl, d[2] = -dl - ys * dl;
        o[0] = x0 - 1, o[1] = h - eps - d[1] * 1, o[2] = h - eps - d[2] * 1; /* at x0 the ray is eps inside the tip */
        o[1] += 1e-4, o[2] += 1e-4; /* enter from outside the sharp box */
        for (a = 0; a < 3; a++) o[a] -= 0.5 * d[a];
        if (check_box_ray(s, &m, &b, o, d, 1e-9, L, &n_round, &n_pass)) {
            double t_host;
            unsigned tri;
            re_hit_t hh;
            tm_hit(&m, o, d, &t_host, &tri);
            re_query(s, o, d, 0, tri, t_host, &hh);
            if (hh.kind == RE_HIT_ROUNDED && hh.point[0] - (o[0] + t_host * d[0]) > 2 * L / n) far++;
        }
    }
    T_GT(far, t_count(4000) / 10); /* many hits lie two or more segments beyond the entry */
    T_GT(n_round, t_count(4000) / 4);
    re_free(s);
    tm_free(&m);
}

/* The same box with its long edges split into 16 000 segments each
   (128 016 triangles; segments of r / 80), as a fine grid or a CAD export
   splits straight edges. The build walks each straight chain once (its
   strips for the per-triangle bands, its inner spheres): walked from every
   segment, as before 2026-12-04, this mesh took 39 s to build. Each
   segment's cylinder spans its whole chain, so a query near the edge meets
   the chain's two end corners; when every split vertex was a corner on the
   way, the query's 64-corner set overflowed (32 failed checks at 4 000
   segments, 55 at 16 000 with a set of 256). Rays at the long faces near
   their edges, all along the box, through re_query and re_query_uv (which
   answers flat hits from the bands the chains' walks laid), against the
   analytic rounded box. */
static void long_straight_chains(void)
{
    const int n = 16000;
    const double L = 10, h = 0.5, r = 0.05;
    tm_mesh_t m = {0};
    rbox_t b;
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    t_rng_t rng = {77};
    long k, n_round = 0, n_pass = 0, nr = t_count(1500);
    rod_mesh(&m, n, L, h, r, &b);
    s = build1(&m, r, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); return; }
    re_get_stats(s, &st);
    T_INT_EQ(st.rounded_edges, 4 * n + 8);
    /* the corners inside the chains are not stored (their spheres lie on the
       chain's cylinder's axis): 8 box corners, one sphere each, and at most
       the 64 bytes per rounded edge of issue 6 (79-84 when every split
       vertex kept its corner) */
    T_INT_EQ(st.spheres, 8);
    T_INT_EQ(st.rounded_corners, 8);
    T_LE((double)st.bytes / (double)st.rounded_edges, 64.0);
    for (k = 0; k < nr; k++) {
        double o[3], d[3];
        rod_edge_ray(&rng, L, h, r, o, d);
        check_box_ray(s, &m, &b, o, d, 1e-9, 1.0, &n_round, &n_pass);
    }
    T_GT(n_round, nr / 6); /* the chamfers are reached all along */
    /* the kd-tree cuts along the split edges too: when every segment's box
       spans a cell across (the longest axis there), the next axis is tried.
       With the longest axis only, the leaves held 600 references each (280
       in the compact layout, whose nodes cost more); now 3 and 9 */
    T_LE((double)st.kd_leaf_refs / (double)st.kd_leaves, 16.0);
    re_free(s);
    tm_free(&m);
}

/* Dropping the chains' inner corners renumbers every corner and sphere
   after them. One object: a rod whose long edges are split into 40
   segments (radius 0.05), then a level-2 icosphere (degree-5/6 corners with
   extra cylinders, radius 0.06) and a 40-sided pyramid (its apex has more
   planes than the compact layout's 5-bit slots: stored centres, listed by
   sphere id; radius 0.005), the radii through edge_radius, so corners
   carry radius ids. Rays at the rod match the analytic rounded box; rays
   at each other part match, in kind, feature kind, t and normal, the part
   built alone (whose numbering nothing shifted); the counts add up. Both
   layouts. */
static void pyramid_mesh(tm_mesh_t *m, int k)
{
    int i;
    for (i = 0; i < k; i++) tm_vert(m, cos(2 * M_PI * i / k), sin(2 * M_PI * i / k), 0);
    tm_vert(m, 0.23, -0.11, 0.9);
    for (i = 0; i < k; i++) tm_tri(m, (unsigned)i, (unsigned)((i + 1) % k), (unsigned)k);
    for (i = 1; i + 1 < k; i++) tm_tri(m, 0, (unsigned)(i + 1), (unsigned)i);
}
static void chain_corners_dropped_renumber_the_rest(void)
{
    const int n = 40;
    const double L = 4, h = 0.5, r1 = 0.05, rp[2] = {0.06, 0.005}, X[2] = {8, 12};
    int layout, q;
    for (layout = 0; layout < 2; layout++) {
        tm_mesh_t m = {0}, part[2] = {{0}, {0}};
        rbox_t b;
        re_mesh_t mesh;
        re_scene_desc_t desc;
        re_scene_t *s = NULL, *sp[2];
        re_diag_t dg;
        re_stats_t st, stp[2];
        t_rng_t rng = {91};
        double *er;
        unsigned k, first_tri[2];
        long i, n_round = 0, n_pass = 0, nr = t_count(3000) < 600 ? 600 : t_count(3000);
        g_layout = layout ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
        rod_mesh(&m, n, L, h, r1, &b);
        tm_icosphere(&part[0], 2, 1.0);
        pyramid_mesh(&part[1], 40);
        er = (double *)malloc(sizeof(double) * (m.ni + part[0].ni + part[1].ni));
        for (k = 0; k < m.ni; k++) er[k] = r1;
        for (q = 0; q < 2; q++) {
            unsigned base = m.nv;
            first_tri[q] = m.ni / 3;
            for (k = 0; k < part[q].nv; k++) tm_vert(&m, part[q].v[3 * k] + X[q], part[q].v[3 * k + 1], part[q].v[3 * k + 2]);
            for (k = 0; k < part[q].ni; k += 3) {
                er[m.ni] = er[m.ni + 1] = er[m.ni + 2] = rp[q];
                tm_tri(&m, base + part[q].idx[k], base + part[q].idx[k + 1], base + part[q].idx[k + 2]);
            }
        }
        memset(&mesh, 0, sizeof mesh);
        memset(&desc, 0, sizeof desc);
        mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.edge_radius = er;
        desc.layout = g_layout, desc.objects = &mesh, desc.object_count = 1;
        sp[0] = build1(&part[0], rp[0], &dg);
        sp[1] = build1(&part[1], rp[1], &dg);
        if (!T_CHECK(re_build(&desc, &s, &dg) == RE_OK && sp[0] && sp[1])) { fprintf(stderr, "%s\n", dg.message); break; }
        re_get_stats(s, &st);
        re_get_stats(sp[0], &stp[0]);
        re_get_stats(sp[1], &stp[1]);
        T_GT(stp[0].extra_cylinders, 0);
        T_INT_EQ(st.spheres, 8 + stp[0].spheres + stp[1].spheres);
        T_INT_EQ(st.rounded_corners, 8 + stp[0].rounded_corners + stp[1].rounded_corners);
        T_INT_EQ(st.cylinders, 4 * (unsigned long long)n + 8 + stp[0].cylinders + stp[1].cylinders);
        if (layout) T_GT(s->objects[0].n_xsph, 0); /* the apex's centres are stored */
        for (i = 0; i < nr; i++) { /* the rod */
            double o[3], d[3];
            rod_edge_ray(&rng, L, h, r1, o, d);
            check_box_ray(s, &m, &b, o, d, 1e-9, 1.0, &n_round, &n_pass);
        }
        T_GT(n_round, nr / 6);
        for (q = 0; q < 2; q++) {
            long n_part_round = 0;
            for (i = 0; i < nr; i++) { /* toward a vertex (every other ray the last: the apex), within 3 r */
                const double *vx = part[q].v + 3 * (i % 2 ? part[q].nv - 1 : t_rng_u64(&rng) % part[q].nv);
                double o[3], d[3], tgt[3], u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), t_host, bu, bv;
                unsigned tri;
                re_hit_t h1, h2;
                int a;
                for (a = 0; a < 3; a++) tgt[a] = vx[a] + t_rng_range(&rng, -3, 3) * rp[q];
                o[0] = tgt[0] + 3 * sqrt(1 - v * v) * cos(u), o[1] = tgt[1] + 3 * sqrt(1 - v * v) * sin(u), o[2] = tgt[2] + 3 * v;
                tm_sub(tgt, o, d);
                if (!tm_hit_uv(&part[q], o, d, &t_host, &tri, &bu, &bv)) continue;
                re_query(sp[q], o, d, 0, tri, t_host, &h2);
                o[0] += X[q];
                re_query(s, o, d, 0, first_tri[q] + tri, t_host, &h1);
                n_part_round += h2.kind == RE_HIT_ROUNDED;
                if (!T_INT_EQ(h1.kind, h2.kind) || !T_INT_EQ(h1.feature, h2.feature)) continue;
                T_NEAR(h1.t, h2.t, 1e-12 * 3);
                for (a = 0; a < 3; a++) T_NEAR(h1.normal[a], h2.normal[a], 1e-9);
            }
            /* not vacuous: 8% (icosphere) and 12% (pyramid) of these rays
               reach the rounded surface; at least 600 rays even under the
               sanitizers' reduced counts, where 150 left too few for 5% */
            T_GT(n_part_round, nr / 20);
        }
        re_free(s);
        re_free(sp[0]);
        re_free(sp[1]);
        free(er);
        tm_free(&m);
        tm_free(&part[0]);
        tm_free(&part[1]);
    }
    g_layout = RE_LAYOUT_FAST;
}

/* The examples' float icosphere (level 1: 42 vertices, 80 triangles, 120
   convex edges), scaled, rotated and moved, built from float positions.
   Its degree-5 and degree-6 corners have four or more planes through nearly
   one eroded point; float rounding of the moved vertices split those points
   by 1e-9..1e-8 r, which once left the whole sphere sharp ("corner too
   complex"). Asserts every edge rounded, no corner reported, and hits
   against sphere tracing of the eroded polytope of the same float mesh. */
static int ico_report_count;
static void ico_on_report(void *user, const re_report_t *rep)
{
    (void)user;
    if (rep->kind == RE_REPORT_COMPLEX_CORNER || rep->kind == RE_REPORT_UNROUNDABLE_CORNER ||
        rep->kind == RE_REPORT_SHARP_PATCH_EDGE)
        ico_report_count++;
}
static void float_icosphere_case(double sc, const double axis[3], double angle, const double t[3], double r, long nrays,
                                 unsigned long long seed, const char *what)
{
    ex_mesh_t em = {0};
    double a12[12];
    ex_v3_t ax, tr;
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_diag_t dg;
    re_stats_t st;
    tm_mesh_t m = {0};
    static tm_poly_t P;
    size_t i;
    ax.x = axis[0], ax.y = axis[1], ax.z = axis[2];
    tr.x = t[0], tr.y = t[1], tr.z = t[2];
    if (!T_CHECK(ex_mesh_icosphere(&em, 1) == 0)) return;
    T_INT_EQ(em.nverts, 42);
    T_INT_EQ(em.ntris, 80);
    ex_affine_srt(a12, sc, ax, angle, tr);
    ex_mesh_transform(&em, a12);
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = em.pos;
    mesh.position_type = RE_FLOAT32;
    mesh.vertex_count = (unsigned)em.nverts;
    mesh.indices = em.idx;
    mesh.index_count = (unsigned)(3 * em.ntris);
    mesh.radius = r;
    desc.objects = &mesh;
    desc.object_count = 1;
    desc.report = ico_on_report;
    ico_report_count = 0;
    if (!T_CHECK(re_build(&desc, &s, &dg) == RE_OK)) { fprintf(stderr, "%s: %s\n", what, dg.message); ex_mesh_free(&em); return; }
    re_get_stats(s, &st);
    if (!T_INT_EQ(st.rounded_edges, 120)) fprintf(stderr, "%s: %llu of 120 edges rounded\n", what, (unsigned long long)st.rounded_edges);
    T_INT_EQ(st.convex_edges, 120);
    T_INT_EQ(ico_report_count, 0);
    re_free(s);
    /* the same float positions, exactly, for the oracle and the host */
    for (i = 0; i < em.nverts; i++) tm_vert(&m, em.pos[3 * i], em.pos[3 * i + 1], em.pos[3 * i + 2]);
    for (i = 0; i < em.ntris; i++) tm_tri(&m, em.idx[3 * i], em.idx[3 * i + 1], em.idx[3 * i + 2]);
    tm_planes(&m, &P);
    poly_rays(&m, &P, r, nrays, 1e-7, seed, what);
    tm_free(&m);
    ex_mesh_free(&em);
}

/* A rotated box in float positions: its quads are not planar (the halves
   of each tilt against each other by about FLT_EPSILON times the distance
   to the origin over their height: 1e-7 at the origin, 1e-4 at 1e3 sizes
   from it), and the diagonals and grid lines between them must still be
   flat (construction step 2, the float units of RE__FLAT_ROUNDINGS).
   Before, they were convex or concave edges that left every corner mixed:
   nothing rounded on 193 of 200 rotated unit cubes. The oracle is the exact
   rounded box the float mesh rounds to: each answer's point lies within
   delta of its surface, the ray does not go deeper than 2 delta into it
   before that point (so grazing rays need no slack in t), a pass-through
   never goes that deep, and normals agree within delta / r (the tilt delta makes on the rounding),
   delta a few float roundings of the coordinates, per face piece. */
/* An answer against an exact solid given by its distance f (world space)
   whose mesh is only within delta of it (float rounding, facets): the
   answer's point lies within delta of the surface, the ray is nowhere
   2 delta inside the solid before it (nor anywhere, for a pass-through),
   and the normal is f's gradient within delta / r (plus n_slack, the
   facets' own turn where f is smoother than the mesh). Grazing rays need no
   slack in t this way. Returns 1 when the answer passes; *worst and
   *worst_n collect the distances and normal errors seen. */
/* A ray from 3 units away in a random direction at tgt: the host's hit on
   m, re_query's answer (and re_query_uv's, which must agree). 0 if the
   ray misses the mesh. */
static int shoot_at(const re_scene_t *s, const tm_mesh_t *m, const double tgt[3], t_rng_t *rng, double o[3],
                    double d[3], re_hit_t *h)
{
    double u = t_rng_range(rng, 0, 2 * M_PI), v = t_rng_range(rng, -1, 1), w = sqrt(1 - v * v), t_host, bu, bv;
    unsigned tri;
    o[0] = tgt[0] + 3 * w * cos(u), o[1] = tgt[1] + 3 * w * sin(u), o[2] = tgt[2] + 3 * v;
    tm_sub(tgt, o, d);
    if (!tm_hit_uv(m, o, d, &t_host, &tri, &bu, &bv)) return 0;
    re_query(s, o, d, 0, tri, t_host, h);
    check_query_uv(s, o, d, tri, t_host, bu, bv, h);
    return 1;
}

typedef struct sdf_shape_t { tm_sdf_fn f; const void *ctx; double depth; } sdf_shape_t;
static double sdf_deep(const void *ctx, const double p[3])
{
    const sdf_shape_t *q = (const sdf_shape_t *)ctx;
    return q->f(q->ctx, p) + q->depth;
}
static int answer_near_sdf(const re_hit_t *h, const double o[3], const double d[3], tm_sdf_fn f, const void *ctx,
                           double delta, double r, double n_slack, double *worst, double *worst_n)
{
    sdf_shape_t deep;
    double t_in, x[3], g[3], dn[3], sd, e = 1e-7 * r;
    int a;
    deep.f = f, deep.ctx = ctx, deep.depth = 2 * delta;
    t_in = tm_trace(sdf_deep, &deep, o, d, 10.0, 1.0);
    if (h->kind == RE_PASS_THROUGH) return t_in == HUGE_VAL;
    for (a = 0; a < 3; a++) x[a] = o[a] + h->t * d[a];
    sd = f(ctx, x);
    for (a = 0; a < 3; a++) { /* the gradient by central differences */
        double xp[3], xm[3];
        memcpy(xp, x, sizeof x), memcpy(xm, x, sizeof x);
        xp[a] += e, xm[a] -= e;
        g[a] = (f(ctx, xp) - f(ctx, xm)) / (2 * e);
    }
    tm_norm(g);
    tm_sub(h->normal, g, dn);
    *worst = fmax(*worst, fabs(sd));
    *worst_n = fmax(*worst_n, tm_len(dn));
    return fabs(sd) <= delta && !(t_in < h->t) && tm_len(dn) <= delta / r + n_slack;
}

/* the rounded box [0, GRID_EXT] ⊖ r ⊕ r seen through frame F */
typedef struct frame_rbox_t { const grid_frame_t *F; rbox_t b; } frame_rbox_t;
static double frame_rbox_sdf(const void *ctx, const double p[3])
{
    const frame_rbox_t *q = (const frame_rbox_t *)ctx;
    double l[3];
    int a;
    for (a = 0; a < 3; a++)
        l[a] = q->F->R[0][a] * (p[0] - q->F->off[0]) + q->F->R[1][a] * (p[1] - q->F->off[1]) + q->F->R[2][a] * (p[2] - q->F->off[2]);
    return tm_rbox_sdf(q->b.c, q->b.half, q->b.r, l);
}

static void float_box_case(int n, const grid_frame_t *F, long nrays, unsigned long long seed, const char *what)
{
    tm_mesh_t m = {0}, mf = {0};
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    frame_rbox_t box;
    t_rng_t rng;
    double M = 0, delta, r, worst = 0, worst_n = 0;
    long i, n_round = 0, bad = 0;
    unsigned k;
    int a;
    grid_box(&m, n, F);
    /* the float positions, exactly, for the host's mesh */
    for (k = 0; k < m.nv; k++) tm_vert(&mf, (float)m.v[3 * k], (float)m.v[3 * k + 1], (float)m.v[3 * k + 2]);
    for (k = 0; k < 3 * mf.nv; k++) M = fmax(M, fabs(mf.v[k]));
    for (k = 0; k < m.ni; k += 3) tm_tri(&mf, m.idx[k], m.idx[k + 1], m.idx[k + 2]);
    s = build1_float(&mf, 0.08, &dg);
    if (!T_CHECK(s != NULL)) { fprintf(stderr, "%s: %s\n", what, dg.message); goto done; }
    re_get_stats(s, &st);
    T_INT_EQ(st.convex_edges, 12 * n);
    T_INT_EQ(st.concave_edges, 0);
    T_INT_EQ(st.flat_edges, 6 * (2 * n * (n - 1) + n * n)); /* grid lines and diagonals */
    if (!T_INT_EQ(st.rounded_edges, 12 * n)) fprintf(stderr, "%s: %llu of %d edges rounded\n", what, st.rounded_edges, 12 * n);
    T_INT_EQ(st.mixed_vertices, 0);
    T_INT_EQ(st.spheres, 8);
    r = re_object_radius(s, 0);
    T_EQ(r, 0.08);
    box.F = F;
    for (a = 0; a < 3; a++) box.b.c[a] = box.b.half[a] = GRID_EXT[a] / 2;
    box.b.r = r;
    delta = 2.0 * 1.1920928955078125e-07 * M + 1e-9; /* a few of the mesh's own roundings (measured: up to 0.5) */
    rng.s = seed;
    for (i = 0; i < nrays; i++) {
        double o[3], d[3], tgt[3], l[3];
        re_hit_t h;
        /* aimed at a corner or along an edge of the box, within 2 r of it */
        for (a = 0; a < 3; a++) l[a] = (t_rng_u64(&rng) & 1) ? GRID_EXT[a] : 0;
        a = (int)(t_rng_u64(&rng) % 3);
        l[a] = i % 3 ? t_rng_unit(&rng) * GRID_EXT[a] : l[a];
        for (a = 0; a < 3; a++) l[a] += t_rng_range(&rng, -2, 2) * r;
        for (a = 0; a < 3; a++) tgt[a] = F->R[a][0] * l[0] + F->R[a][1] * l[1] + F->R[a][2] * l[2] + F->off[a];
        if (!shoot_at(s, &mf, tgt, &rng, o, d, &h)) continue;
        n_round += h.kind == RE_HIT_ROUNDED;
        if (!answer_near_sdf(&h, o, d, frame_rbox_sdf, &box, delta, r, 0, &worst, &worst_n)) {
            bad++;
            if (bad < 5) T_FAIL("%s ray %ld: kind %d t %.17g is off the exact rounded box (delta %g)", what, i, (int)h.kind, h.t, delta);
        }
    }
    T_INT_EQ(bad, 0);
    T_GT(n_round, nrays / 20);
    if (getenv("FLOAT_BOX_VERBOSE")) fprintf(stderr, "%s: worst %g of delta %g, normal %g of %g, %ld rounded\n", what, worst, delta, worst_n, delta / r, n_round);
    re_free(s);
done:
    tm_free(&m);
    tm_free(&mf);
}

/* Finely tessellated cylinders whose creases fall under the widened flat
   tolerance: 8 000 sides in float positions (7.9e-4 rad, about their thin
   facets' rounding tolerance) and 1 000 sides in doubles with re_mesh_t.flat_sin =
   RE_FLAT_SIN_LIMIT (6.3e-3 rad, under 1e-2). Chained through those "flat"
   creases, their sides became one plane (32 spheres instead of 16 000)
   and their rims were rounded against that one normal; re__flat_chains
   sends such groups back to the strict test, so every crease is rounded
   (the facets are exactly planar: moved, not turned). The doubles' answers
   against the exact rounded cylinder, within the facets' sagitta. */
typedef struct rcyl_t { const grid_frame_t *F; double R, H, r; } rcyl_t;
static double rcyl_sdf(const void *ctx, const double p[3])
{
    const rcyl_t *c = (const rcyl_t *)ctx;
    double l[3], qx, qz, ox, oz;
    int a;
    for (a = 0; a < 3; a++)
        l[a] = c->F->R[0][a] * (p[0] - c->F->off[0]) + c->F->R[1][a] * (p[1] - c->F->off[1]) + c->F->R[2][a] * (p[2] - c->F->off[2]);
    qx = sqrt(l[0] * l[0] + l[1] * l[1]) - (c->R - c->r), qz = fabs(l[2]) - (c->H / 2 - c->r);
    ox = fmax(qx, 0), oz = fmax(qz, 0);
    return sqrt(ox * ox + oz * oz) + fmin(fmax(qx, qz), 0.0) - c->r;
}
static void fine_cylinder_case(int n, int as_float, double flat_sin, int with_rays)
{
    const grid_frame_t F = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0.3, -0.2, 0.1}};
    rcyl_t cyl;
    tm_mesh_t m = {0};
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    t_rng_t rng = {61};
    double delta, worst = 0, worst_n = 0;
    long i, bad = 0, n_round = 0, nrays = !with_rays ? 0 : t_count(2000) < 300 ? 300 : t_count(2000);
    int k, a;
    cyl.F = &F, cyl.R = 1, cyl.H = 1, cyl.r = 0.05;
    for (k = 0; k < n; k++)
        for (a = 0; a < 2; a++) {
            double x = cos(2 * M_PI * k / n) + F.off[0], y = sin(2 * M_PI * k / n) + F.off[1], z = (a ? 0.5 : -0.5) + F.off[2];
            if (as_float) x = (float)x, y = (float)y, z = (float)z; /* the host's mesh is the float one */
            tm_vert(&m, x, y, z);
        }
    for (k = 0; k < n; k++) {
        unsigned j = (unsigned)((k + 1) % n), i2 = 2u * (unsigned)k;
        tm_tri(&m, i2, 2 * j, 2 * j + 1), tm_tri(&m, i2, 2 * j + 1, i2 + 1);
    }
    for (k = 1; k + 1 < n; k++) { /* caps: fans from the first corner */
        unsigned i2 = 2u * (unsigned)k;
        tm_tri(&m, 0, i2 + 2, i2), tm_tri(&m, 1, i2 + 1, i2 + 3);
    }
    s = build1_as(&m, cyl.r, as_float, flat_sin, &dg);
    if (!T_CHECK(s != NULL)) { fprintf(stderr, "fine cylinder: %s\n", dg.message); tm_free(&m); return; }
    re_get_stats(s, &st);
    if (with_rays) { /* the creases and both rims */
        T_INT_EQ(st.convex_edges, 3 * n);
        T_INT_EQ(st.spheres, 2 * n);
    } else { /* the float facets' creases vary with their rounding: where the tolerance
                (4 roundings over a facet's width) passes some, a few facets share a plane */
        T_GE(st.convex_edges, 3 * n - n / 10);
        T_GE(st.spheres, 2 * n - n / 5);
    }
    T_INT_EQ(st.rounded_edges, st.convex_edges);
    T_EQ(re_object_radius(s, 0), cyl.r);
    delta = (1 - cos(M_PI / n)) + 1e-9; /* the facets' sagitta */
    for (i = 0; i < nrays; i++) {
        double tgt[3], o[3], d[3], phi = t_rng_range(&rng, 0, 2 * M_PI);
        re_hit_t h;
        /* at a rim, within 2 r of it */
        tgt[0] = cos(phi) + t_rng_range(&rng, -2, 2) * cyl.r + F.off[0];
        tgt[1] = sin(phi) + t_rng_range(&rng, -2, 2) * cyl.r + F.off[1];
        tgt[2] = (i & 1 ? 0.5 : -0.5) + t_rng_range(&rng, -2, 2) * cyl.r + F.off[2];
        if (!shoot_at(s, &m, tgt, &rng, o, d, &h)) continue;
        n_round += h.kind == RE_HIT_ROUNDED;
        /* normals: the facets turn by up to pi / n against the cylinder's */
        if (!answer_near_sdf(&h, o, d, rcyl_sdf, &cyl, delta, cyl.r, M_PI / n, &worst, &worst_n)) {
            bad++;
            if (bad < 5) T_FAIL("fine cylinder ray %ld: kind %d t %.17g is off the exact rounded cylinder (delta %g)", i, (int)h.kind, h.t, delta);
        }
    }
    T_INT_EQ(bad, 0);
    if (with_rays) T_GT(n_round, nrays / 20);
    if (getenv("FLOAT_BOX_VERBOSE")) fprintf(stderr, "fine cylinder: worst %g of delta %g, normal %g, %ld rounded\n", worst, delta, worst_n, n_round);
    re_free(s);
    tm_free(&m);
}
static void fine_cylinders_do_not_chain_into_one_plane(void)
{
    /* classes only: the float polygon's creases carry its rounding (1e-4 of
       7.9e-4), which the erosion turns into r-sized moves of the corners
       against the ideal cylinder (the float polytope's own rounding is
       exact, but no oracle here erodes 8 000 planes) */
    fine_cylinder_case(8000, 1, 0, 0);
    fine_cylinder_case(1000, 0, RE_FLAT_SIN_LIMIT, 1);
}

/* The exit clearance of every corner of object o (re__corner_t.clear)
   against its definition read off the scene, over every bordering plane:
   the code of D / walk, D the least in-plane distance from the first
   sphere's foot on an own face to the line of a bordering plane that is
   not its own. Returns the corners whose code lies outside the codes of
   D (1 -+ 1e-12). */
static long clearance_mismatches(const re__object_t *o, long *checked)
{
    unsigned i, k, j, q, *deg, *first, *nbr;
    long bad = 0;
    deg = (unsigned *)calloc(o->n_planes + 1, sizeof *deg);
    first = (unsigned *)calloc(o->n_planes + 2, sizeof *first);
    nbr = (unsigned *)malloc(sizeof *nbr * (2 * (size_t)o->n_edge_cyls + 1));
    for (i = 0; i < o->n_edge_cyls; i++) deg[o->cyls[i].p[0]]++, deg[o->cyls[i].p[1]]++;
    for (i = 0; i < o->n_planes; i++) first[i + 1] = first[i] + deg[i], deg[i] = 0;
    for (i = 0; i < o->n_edge_cyls; i++) {
        unsigned p0 = o->cyls[i].p[0], p1 = o->cyls[i].p[1];
        nbr[first[p0] + deg[p0]++] = p1;
        nbr[first[p1] + deg[p1]++] = p0;
    }
    for (k = 0; k < o->n_corners; k++) {
        re__kv_t K = re__kview(o, k);
        unsigned own[RE_MAX_CORNER_PLANES];
        double c0[3], D = HUGE_VAL;
        unsigned char lo, hi;
        re__centre(o, K.sfirst, c0);
        for (j = 0; j < K.np; j++) own[j] = re__corner_plane(o, &K, j);
        for (j = 0; j < K.np; j++) {
            const re__plane_t *g = &o->planes[own[j]];
            double x[3], t = g->c - (g->n[0] * c0[0] + g->n[1] * c0[1] + g->n[2] * c0[2]);
            for (q = 0; q < 3; q++) x[q] = c0[q] + t * g->n[q];
            for (q = first[own[j]]; q < first[own[j] + 1]; q++) {
                const re__plane_t *h = &o->planes[nbr[q]];
                double cs = g->n[0] * h->n[0] + g->n[1] * h->n[1] + g->n[2] * h->n[2], sn = sqrt(fmax(0, 1 - cs * cs));
                unsigned mine = 0, a;
                for (a = 0; a < K.np; a++) mine |= own[a] == nbr[q];
                if (mine || !(sn > 0)) continue;
                D = fmin(D, fmax(0, h->c - (h->n[0] * x[0] + h->n[1] * x[1] + h->n[2] * x[2])) / sn);
            }
        }
        lo = re__clear_code(D * (1 - 1e-12) / (double)o->corners[k].walk);
        hi = re__clear_code(D * (1 + 1e-12) / (double)o->corners[k].walk);
        if (o->corners[k].clear < lo || o->corners[k].clear > hi) {
            if (bad < 3)
                T_FAIL("corner %u: clear %u, its definition %u..%u (D %.17g, walk %g)", k, o->corners[k].clear, lo, hi, D,
                       (double)o->corners[k].walk);
            bad++;
        }
        (*checked)++;
    }
    free(deg), free(first), free(nbr);
    return bad;
}

/* build1 (test_rounded_rays.h: one object, the radius clamped) in the
   given layout (1: compact); NULL, a failed check, when it fails */
static re_scene_t *build1_in(const tm_mesh_t *m, double r, int layout)
{
    re_diag_t dg;
    re_scene_t *s;
    g_layout = layout ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
    s = build1(m, r, &dg);
    g_layout = RE_LAYOUT_FAST;
    if (!T_CHECK(s != NULL)) fprintf(stderr, "    %s\n", dg.message);
    return s;
}

/* A box 1e6 long and 1 wide, r = 1e-4: rays at its four long edges between
   x = -2e4 and -1e4, far from the x = -1e6 end, where the cylinders' axes
   start (the edges' lower vertex). A cylinder's normal is taken
   from the axis point a + h u; from the far end, h's rounding moved that
   point by ulps of the axis length (1.2e-10), which turned the normal by
   about 1e-6 (fuzz_rounded_build: 2e-3 rad at r = 6e-8). From the nearer
   end it is within 4 ulps of the hit's coordinates over r of the exact
   rounded box's. */
static void normals_far_from_a_long_edges_far_end(void)
{
    static const double lo[3] = {-1e6, 0, 0}, hi[3] = {0, 1, 1}; /* tm_box's first vertex, an axis's start, at the far end */
    tm_mesh_t m = {0};
    re_diag_t dg;
    re_scene_t *s;
    t_rng_t rng = {77};
    double r = 1e-4, worst = 0;
    long i, n_round = 0;
    int a;
    tm_box(&m, lo, hi);
    s = build1(&m, r, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); return; }
    for (i = 0; i < 4000; i++) {
        double tgt[3], o[3], d[3], t_host, bu, bv, q[3], nref[3], len, dn = 0, bound;
        unsigned tri;
        re_hit_t h;
        int e = (int)(i % 4);
        tgt[0] = t_rng_range(&rng, -2e4, -1e4), tgt[1] = e & 1 ? 1 : 0, tgt[2] = e & 2 ? 1 : 0;
        d[0] = t_rng_range(&rng, -0.3, 0.3), d[1] = (e & 1 ? -1 : 1) * t_rng_range(&rng, 0.2, 1),
        d[2] = (e & 2 ? -1 : 1) * t_rng_range(&rng, 0.2, 1);
        for (a = 0; a < 3; a++) tgt[a] += t_rng_range(&rng, -2, 2) * r * (a > 0), o[a] = tgt[a] - 3 * d[a];
        if (!tm_hit_uv(&m, o, d, &t_host, &tri, &bu, &bv)) continue;
        re_query(s, o, d, 0, tri, t_host, &h);
        if (h.kind != RE_HIT_ROUNDED) continue;
        n_round++;
        for (a = 0; a < 3; a++) { /* the exact rounded box's normal: from the inner box's nearest point */
            double c = h.point[a] < lo[a] + r ? lo[a] + r : h.point[a] > hi[a] - r ? hi[a] - r : h.point[a];
            q[a] = h.point[a] - c;
        }
        len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (a = 0; a < 3; a++) nref[a] = q[a] / len, dn += fabs(nref[a] - h.normal[a]);
        bound = 4 * RE__DBL_EPS * (fabs(h.point[0]) + fabs(h.point[1]) + fabs(h.point[2])) / r;
        if (dn / bound > worst) worst = dn / bound;
        if (!(dn <= bound)) {
            T_FAIL("ray %ld: rounded hit at x %.17g, normal %.3g off the exact one (bound %.3g)", i, h.point[0], dn, bound);
            break;
        }
    }
    T_GT(n_round, 500);
    fprintf(stderr, "    %ld rounded hits, worst normal %.2f of the bound\n", n_round, worst);
    re_free(s);
    tm_free(&m);
}

/* The fuzzer's family of rays along triangle tri_byte % (its triangle
   count) of the hull of q (n points; fuzz_rounded_exact's mode for rays along a face, compact layout,
   r = 2^-6 of the size) through each of its vertices: 256 angles in the
   plane, 7 tilts up to 1e-10, the host in __float128. Each answer is on
   the rounded surface or a pass-through on the sharp hull, never 1e-9 of
   the size deep before it, and a rounded hit's reflected ray starts on
   the sharp hull, pushed out. */
static void along_face_family_on_hull(const double (*q)[3], unsigned n, unsigned tri_byte)
{
    static const double tilt[7] = {0, 1e-16, -1e-16, 1e-13, -1e-13, 1e-10, -1e-10};
    static tm_poly_t P;
    tm_mesh_t m = {0};
    tm_eroded_t E;
    re_scene_t *s;
    double scale = tm_size(q[0], n), tol = 1e-9 * scale;
    long i, hits = 0, bad = 0, n_round = 0;
    unsigned tri_along;
    int a;
    memset(&P, 0, sizeof P);
    tm_hull(q, n, &m, &P);
    tri_along = tri_byte % (m.ni / 3);
    s = build1_in(&m, 0.015625 * scale, 1);
    if (!s) { tm_free(&m); return; }
    E.P = &P, E.r = re_object_radius(s, 0);
    tm_erode(&P, E.r);
    for (i = 0; i < 3 * 256 * 7; i++) { /* from each vertex, 256 angles in its plane, 7 tilts (the fuzzer's) */
        const unsigned *t = m.idx + 3 * tri_along;
        const double *va = m.v + 3 * t[i / 1792], *vb = m.v + 3 * t[(i / 1792 + 1) % 3];
        double e1[3], e2[3], nt[3], th = (double)(i / 7 % 256) * (2 * M_PI / 256), d[3], o[3], t_host, bu, bv;
        char why[160];
        unsigned tri;
        re_hit_t h;
        tm_sub(m.v + 3 * t[1], m.v + 3 * t[0], e1); /* the normal as the fuzzer takes it */
        tm_sub(m.v + 3 * t[2], m.v + 3 * t[0], e2);
        tm_cross(e1, e2, nt);
        tm_norm(nt);
        tm_sub(vb, va, e1);
        tm_norm(e1);
        tm_cross(nt, e1, e2);
        for (a = 0; a < 3; a++) d[a] = cos(th) * e1[a] + sin(th) * e2[a] + tilt[i % 7] * nt[a], o[a] = va[a] - 3 * scale * d[a];
        if (!tm_hit_exact_uv(&m, o, d, &t_host, &tri, &bu, &bv)) continue;
        hits++;
        re_query(s, o, d, 0, tri, t_host, &h);
        n_round += h.kind == RE_HIT_ROUNDED;
        if ((!along_answer_on_surface(&P, &E, o, d, t_host, &h, tol, why, sizeof why) ||
             !along_answer_not_deep(&E, o, d, t_host, &h, scale, tol, 16, why, sizeof why) ||
             (h.kind == RE_HIT_ROUNDED && !along_reflection_starts_on_hull(s, &P, NULL, d, &h, scale, why, sizeof why))) &&
            ++bad <= 4)
            T_FAIL("vertex %ld, angle %ld/256, tilt %g: %s", i / 1792, i / 7 % 256, tilt[i % 7], why);
    }
    T_INT_EQ(bad, 0);
    T_GT(hits, 1792);
    T_GT(n_round, 0);
    fprintf(stderr, "    %ld rays hit the hull, %ld of them the rounded surface\n", hits, n_round);
    re_free(s);
    tm_free(&m);
}

/* fuzz_rounded_exact, 2026-12-06: its ray along triangle 12 of this hull
   (vertex 0, angle 15/256, tilted 1e-13 into the solid) lost its tangent
   contact with a cylinder and sank under the face. Answered with a
   rounded hit at the contact (re__lost_entry), the cylinder's normal
   there, turned past the seam by the ray's slope, reflected it on into
   the face, and the secondary origin's walk along the face found a
   crossing 0.33 outside the sharp hull. Such a reflection now starts at
   the contact, on the face (re__leaves_on_face); without that, 7 rays
   fail in the clang build (gcc's fused multiply-adds miss them). */
static void lost_contact_along_a_face_reflects_off_it(void)
{
    static const double q[16][3] = {
        {-0.70415808346684972, 0.16182192721446564, -0.007888914320592022}, {0.63338673990997174, 0.31758602273594261, 0.02873273823147926},
        {-0.55358205539024952, -0.011062790875104866, 0.63338673990997174}, {0.31758602273594261, 0.02873273823147926, -0.55358205539024952},
        {-0.089188982986190601, -0.4160677500572213, 0.052079041733424924}, {-0.57177080949111159, 0.47127489127946909, 0.65731288624399187},
        {-0.99765011062790876, -1, -1}, {-1, -1, -1},
        {-0.36699473563744567, -0.70415808346684972, 0.16182192721446564}, {1, 1, 1},
        {-0.98440527962157631, -0.007888914320592022, 0.63338673990997174}, {0.31758602273594261, 0.02873273823147926, -0.6238956282902266},
        {-0.089188982986190601, 0.38100251773861293, -0.89956511787594418}, {-1, -0.99902342259861143, -0.88079652094300753},
        {0.73687342641336695, 0.42302586404211495, 0.9811093308918899}, {-0.99218738078889146, -0.99221789883268485, -0.92968642710002292}};
    along_face_family_on_hull(q, 16, 12);
}

/* fuzz_rounded_exact, 2026-12-07: its ray along triangle 15 of this hull
   (through vertex 0 of the triangle in its plane, untilted) hit a
   cylinder at its end, where the corner's sphere meets another face g,
   and the reflection ran along g to within 3e-17 of its plane: sinking
   too slowly for re__leaves_on_face, it went to the walk's exit, the
   crossing of a plane of the cylinder's far corner, 0.013 outside the
   sharp hull (the true exit, g's edge, lies out of the set's reach).
   Such a reflection now leaves at the hit, through g
   (re__along_out_of_reach). */
static void reflection_along_a_face_from_a_cylinder_end(void)
{
    static const double q[16][3] = {
        {-0.70415808346684972, 0.16182192721446564, -0.007888914320592022}, {0.63338673990997174, 0.31758602273594261, 0.02873273823147926},
        {-0.55358205539024952, -0.089188982986190601, -0.54869916838330668}, {0.47127489127946909, 0.65731288624399187, 0.11174181734950794},
        {0.12153810940718701, 0.37575341420614938, -0.89956511787594418}, {-0.38078889143205918, 0.73687342641336695, 0.42302586404211495},
        {0.9811093308918899, -0.99218738078889146, -0.99221789883268485}, {-1, 0.99240100709544521, 1},
        {1, 1, -0.98712138551918827}, {0.68007934691386285, -0.94634927901121535, -0.45271992065308608},
        {0.16993972686350811, -0.72970168612191966, -0.028549629968719015}, {-0.30873579003585871, 0.71969176775768684, -0.19795529106584264},
        {-0.068833447775997536, 0.053635461966887954, 0.86102082856488904}, {-0.42272068360418102, -0.6857251850156405, 0.38667887388418398},
        {0.99920653086137179, 1, 1}, {1, -0.96850537880521859, -1}};
    along_face_family_on_hull(q, 16, 215);
}

/* fuzz_rounded_exact, 2026-12-06 (compact layout, offset 1e6): a 5-point
   hull at r = 2^-22 of its size, about 4 000 ulps of its coordinates, and
   rays straight up (+z) at points of its edge 0-2 lifted by 0 to 7 r (the
   fuzzer's ray family: 256 fractions, 8 lifts). Face 1 beside that edge
   is within 1e-5 rad of vertical, so such a ray runs along it: the
   fuzzer's ray 6 (fraction 213/255, lift 7) passed the edge's cylinder
   1.8e-11 outside at its seam with face 1, below the coordinates' ulp
   (1.2e-10), then sank below face 1 at a slope of 9.3e-6, 2.1e-6 (4.5 r)
   deep, and was answered with a pass-through at the host's hit. Each
   answer lies on the rounded surface (a pass-through: on the sharp hull),
   and the ray is nowhere 1e-7 of the size deep in the rounded solid
   before it nor, after a pass-through, up to 4 sizes on (the fuzzer's
   bound); a rounded hit's reflected ray starts on the sharp hull, pushed
   out. */
static void ray_sinking_past_a_lost_tangent_contact(void)
{
    static const double q[5][3] = {{-0.89999237048905167, -0.89999237048905167, -0.49999237048905165},
                                   {0.99963378347447929, 0.99374380102235449, 0.1215686274509804},
                                   {0.99963378347447929, 1, -0.98440527962157631},
                                   {0.11723506523231864, -0.99563591973754484, -1},
                                   {-1, -1, 0.99221789883268485}};
    static const double off[3] = {1e6, -1e6, 1e6};
    static tm_poly_t P;
    tm_mesh_t m = {0}, mw = {0};
    tm_eroded_t E;
    re_scene_t *s;
    double scale = tm_size(q[0], 5), tol = 1e-9 * scale, deep_tol = 1e-7 * scale, d[3] = {0, 0, 1};
    long k, hits = 0, bad = 0, n_round = 0;
    unsigned i;
    int a;
    memset(&P, 0, sizeof P);
    tm_hull(q, 5, &m, &P);
    for (i = 0; i < m.nv; i++) tm_vert(&mw, m.v[3 * i] + off[0], m.v[3 * i + 1] + off[1], m.v[3 * i + 2] + off[2]);
    for (i = 0; i < m.ni; i += 3) tm_tri(&mw, m.idx[i], m.idx[i + 1], m.idx[i + 2]);
    s = build1_in(&mw, ldexp(scale, -22), 1);
    if (!s) { tm_free(&m); tm_free(&mw); return; }
    E.P = &P, E.r = re_object_radius(s, 0);
    tm_erode(&P, E.r);
    for (k = 0; k < 256 * 8; k++) {
        double f = (double)(k % 256) / 255.0, o[3], ol[3], t_host, bu, bv, worst = 0, tw = 0;
        char why[160];
        unsigned tri;
        re_hit_t h;
        for (a = 0; a < 3; a++) {
            o[a] = q[0][a] + off[a] + f * (q[2][a] - q[0][a]) + (a == 2 ? (double)(k / 256) * E.r - 3 * scale : 0);
            ol[a] = o[a] - off[a];
        }
        if (!tm_hit_uv(&mw, o, d, &t_host, &tri, &bu, &bv)) continue;
        hits++;
        re_query(s, o, d, 0, tri, t_host, &h);
        n_round += h.kind == RE_HIT_ROUNDED;
        if (!along_answer_on_surface(&P, &E, ol, d, t_host, &h, tol, why, sizeof why) ||
            !along_answer_not_deep(&E, ol, d, t_host, &h, scale, deep_tol, 64, why, sizeof why)) {
            if (++bad <= 4) T_FAIL("fraction %ld/255 lift %ld r: %s", k % 256, k / 256, why);
            continue;
        }
        if (h.kind == RE_HIT_ROUNDED && !along_reflection_starts_on_hull(s, &P, off, d, &h, scale, why, sizeof why) && ++bad <= 4)
            T_FAIL("fraction %ld/255 lift %ld r: %s", k % 256, k / 256, why); /* on the sharp hull, pushed out */
        if (h.kind != RE_PASS_THROUGH) continue;
        for (i = 0; i <= 8192; i++) { /* past a pass-through: outside the rounded solid, to deep_tol */
            double tt = h.t + 4 * scale * i / 8192.0, p[3], sd;
            for (a = 0; a < 3; a++) p[a] = ol[a] + tt * d[a];
            sd = tm_eroded_sdf(&E, p);
            if (sd < worst) worst = sd, tw = tt;
        }
        if (!(worst > -deep_tol) && ++bad <= 4)
            T_FAIL("fraction %ld/255 lift %ld r: pass-through at t %.17g (host %.17g), %.3g deep in the rounded solid at t %.17g",
                   k % 256, k / 256, h.t, t_host, -worst, tw);
    }
    T_INT_EQ(bad, 0);
    T_GT(hits, 256 * 6);
    T_GT(n_round, 0);
    fprintf(stderr, "    %ld rays hit the hull, %ld of them the rounded surface\n", hits, n_round);
    re_free(s);
    tm_free(&m);
    tm_free(&mw);
}

/* Faces bordered by more than RE__CLEAR_TREE_MIN planes (a fine polygon's
   caps) find their corners' exit clearance through an angular tree of
   their neighbours instead of reading them all, which was quadratic: a
   12 000-gon prism built in 1.15 s, 0.2 s after (docs, "Limits"). Regular
   and random convex polygons of 65 to 3 000 sides, fanned caps, radii from
   1e-4 to 0.3 of the size, at the origin and 1e6 away: every corner's code
   as its definition over all neighbours gives it, both layouts. */
static void fine_polygon_exit_clearance_as_defined(void)
{
    static const int sides[] = {65, 66, 200, 3000, 129, 1000};
    static const double radii[] = {1e-4, 0.01, 0.3};
    t_rng_t rng = {2026};
    long checked = 0, bad = 0;
    unsigned it;
    for (it = 0; it < 2 * sizeof sides / sizeof sides[0]; it++) {
        const int n = sides[it % 6];
        const int irregular = it % 6 >= 4, layout = (int)(it / 6);
        double (*q)[2] = (double (*)[2])malloc(sizeof *q * (size_t)n), r = radii[it % 3], off = it % 2 ? 1e6 : 0;
        tm_mesh_t m = {0};
        re_scene_t *s;
        int i;
        for (i = 0; i < n; i++) { /* irregular: jittered angles on an ellipse (convex, edges 0.34..1.66 of the mean) */
            double a = 2 * M_PI * (i + (irregular ? t_rng_range(&rng, -0.33, 0.33) : 0)) / n;
            q[i][0] = (irregular ? 1.2 : 1.0) * cos(a), q[i][1] = (irregular ? 0.8 : 1.0) * sin(a);
        }
        tm_prism(&m, NULL, (const double(*)[2])q, n, 0.5);
        for (i = 0; i < (int)m.nv; i++) m.v[3 * i] += off, m.v[3 * i + 2] -= off;
        if ((s = build1_in(&m, r, layout)) != NULL) {
            T_GE(s->objects[0].n_corners, (unsigned)(2 * n)); /* every rim corner rounded */
            bad += clearance_mismatches(&s->objects[0], &checked);
        }
        re_free(s);
        tm_free(&m);
        free(q);
    }
    T_INT_EQ(bad, 0);
    T_GE(checked, 17840); /* 2 n corners a prism */
}

/* A fine polygon's cap g (74 neighbours: an angular tree) beside a sliver
   face h tilted by theta = 1.2e-8 .. 1.5e-8 about their common edge (a
   convex crease, rounded; double positions at the origin). cos(g, h)
   rounds to 1 - 2^-53, so re__exit_clearance's sine sqrt(1 - cos^2) is
   2.1e-8 while h's part in g, which the tree's unit u divides by, has
   length theta: the distance (c_h - n_h.x) / sin is a - (theta / sin) u.P,
   not a - u.P, and the bound over-reached it by far more than its
   1e-9 / sin slack. Corner X, whose nearest line is h's, skipped h's leaf:
   D 1.48 (its side face's far edge) where the definition gives 1.13 to
   1.41, codes 195 against 189 to 194. The outline: X (-1, 0), B (1, -0.4),
   E (1.05, 0) (h: B E A), A (1, 0.4), a 70-edge arc to T (-0.2, 2.2),
   turned by -3 about y so that h's line sorts last, alone in its leaf. */
static void sliver_crease_beside_fine_cap_exit_clearance(void)
{
    static const double thetas[] = {1.2e-8, 1.4e-8, 1.5e-8}; /* 1.3e-8 leaves the solid sharp */
    long checked = 0, bad = 0;
    unsigned it;
    for (it = 0; it < 2 * sizeof thetas / sizeof thetas[0]; it++) {
        const int narc = 70, n = narc + 4, layout = (int)(it / 3);
        const double H = 1.5, th = thetas[it % 3], psi = -3.0;
        double q[74][2];
        tm_mesh_t m = {0};
        re_scene_t *s;
        unsigned top;
        int i;
        q[0][0] = -1, q[0][1] = 0, q[1][0] = 1, q[1][1] = -0.4, q[2][0] = 1.05, q[2][1] = 0, q[3][0] = 1, q[3][1] = 0.4;
        for (i = 1; i <= narc; i++) { /* quadratic Bezier A, (0.2, 2.2), T: convex */
            double u = (double)i / narc, c0 = (1 - u) * (1 - u), c1 = 2 * u * (1 - u), c2 = u * u;
            q[3 + i][0] = c0 * 1 + c1 * 0.2 + c2 * -0.2, q[3 + i][1] = c0 * 0.4 + c1 * 2.2 + c2 * 2.2;
        }
        for (i = 0; i < 2 * n; i++) {
            double x = q[i % n][0], z = q[i % n][1], y = i < n ? -H / 2 : i == n + 2 ? H / 2 - th * 0.05 : H / 2;
            tm_vert(&m, cos(psi) * x - sin(psi) * z, y, sin(psi) * x + cos(psi) * z);
        }
        for (i = 0; i < n; i++) {
            unsigned a = (unsigned)i, c = (unsigned)((i + 1) % n);
            tm_quad(&m, a, c, c + (unsigned)n, a + (unsigned)n);
        }
        for (i = 1; i + 1 < n; i++) tm_tri(&m, 0, (unsigned)i + 1, (unsigned)i);
        top = (unsigned)n;
        tm_tri(&m, top, top + 1, top + 3); /* g: X B A arc T, fanned from X */
        for (i = 3; i + 1 < n; i++) tm_tri(&m, top, top + (unsigned)i, top + (unsigned)i + 1);
        tm_tri(&m, top + 1, top + 2, top + 3); /* h */
        tm_orient_outward(&m);
        if ((s = build1_in(&m, 0.05, layout)) != NULL) {
            T_INT_EQ(s->objects[0].n_corners, (unsigned)(2 * n)); /* every corner rounded, the crease's too */
            bad += clearance_mismatches(&s->objects[0], &checked);
        }
        re_free(s);
        tm_free(&m);
    }
    T_INT_EQ(bad, 0);
    T_INT_EQ(checked, 6 * 148);
}

/* n-gon prisms with their caps fanned from a rim corner (how triangulated
   n-gons usually come), in float positions, turned and moved up to 100
   times their size from the origin: the fan's thin triangles (altitude
   2e-3 of a 0.48 wide cap at 48 sides, 2.5e-5 at 256) have normals that
   the coordinates' rounding tilts far more than a box's quads, and their
   edges must still be flat (construction step 2: their own tolerance, no
   fixed cap): every edge rounded, one sphere per rim corner. With a fixed
   1e-3 cap (earlier on 2026-12-04) 131 of 200 48-gons at 100 sizes stayed
   sharp. */
static void float_fanned_prisms_far_from_origin(void)
{
    static const int sides[3] = {12, 48, 256};
    t_rng_t rng = {71};
    int it, bad = 0;
    for (it = 0; it < 60; it++) {
        const int n = sides[it % 3];
        const double R = 0.24, H = 0.35;
        grid_frame_t F;
        tm_mesh_t m = {0};
        re_scene_t *s;
        re_diag_t dg;
        re_stats_t st;
        double ax[3], c, sn, angle = t_rng_range(&rng, 0, 2 * M_PI), u = t_rng_range(&rng, 0, 2 * M_PI);
        double v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v), off = pow(10.0, t_rng_range(&rng, -1, 1.7));
        int k, a, b;
        if (n == 256) off = fmin(off, 3.0); /* its fan's thinnest triangles tilt by up to 0.01 there */
        if (it == 58) off = 50;              /* a 48-gon at the far end, always */
        ax[0] = w * cos(u), ax[1] = w * sin(u), ax[2] = v;
        c = cos(angle), sn = sin(angle);
        for (a = 0; a < 3; a++) /* Rodrigues, as in float_boxes_rotated_keep_quads_flat */
            for (b = 0; b < 3; b++) F.R[a][b] = (a == b ? c : 0) + (1 - c) * ax[a] * ax[b];
        F.R[0][1] -= sn * ax[2], F.R[1][0] += sn * ax[2];
        F.R[0][2] += sn * ax[1], F.R[2][0] -= sn * ax[1];
        F.R[1][2] -= sn * ax[0], F.R[2][1] += sn * ax[0];
        for (a = 0; a < 3; a++) F.off[a] = off * (t_rng_unit(&rng) * 2 - 1);
        for (k = 0; k < n; k++)
            for (a = 0; a < 2; a++) {
                double l[3], q[3];
                l[0] = R * cos(2 * M_PI * k / n), l[1] = R * sin(2 * M_PI * k / n), l[2] = a ? H : 0;
                for (b = 0; b < 3; b++) q[b] = F.R[b][0] * l[0] + F.R[b][1] * l[1] + F.R[b][2] * l[2] + F.off[b];
                tm_vert(&m, q[0], q[1], q[2]);
            }
        for (k = 0; k < n; k++) {
            unsigned j = (unsigned)((k + 1) % n), i2 = 2u * (unsigned)k;
            tm_tri(&m, i2, 2 * j, 2 * j + 1), tm_tri(&m, i2, 2 * j + 1, i2 + 1);
        }
        for (k = 1; k + 1 < n; k++) {
            unsigned i2 = 2u * (unsigned)k;
            tm_tri(&m, 0, i2 + 2, i2), tm_tri(&m, 1, i2 + 1, i2 + 3);
        }
        s = build1_float(&m, 0.025, &dg);
        if (!T_CHECK(s != NULL)) { fprintf(stderr, "prism %d: %s\n", it, dg.message); tm_free(&m); continue; }
        re_get_stats(s, &st);
        if (st.rounded_edges != 3ull * (unsigned)n || st.concave_edges || st.spheres != 2ull * (unsigned)n) {
            bad++;
            if (bad < 5)
                T_FAIL("prism %d (%d sides, offset %.3g): %llu of %d edges rounded, %llu concave, %llu spheres", it, n, off,
                       st.rounded_edges, 3 * n, st.concave_edges, st.spheres);
        }
        re_free(s);
        tm_free(&m);
    }
    T_INT_EQ(bad, 0);
}

/* 40 random rotations, offsets from 0.1 to 1e3 box sizes; faces of one quad
   and of 3 x 3 quads */
static void float_boxes_rotated_keep_quads_flat(void)
{
    t_rng_t rng = {47};
    int it;
    for (it = 0; it < 40; it++) {
        grid_frame_t F;
        double ax[3], dir[3], c, sn, off, angle = t_rng_range(&rng, 0, 2 * M_PI);
        double u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        char what[64];
        int a, b;
        ax[0] = w * cos(u), ax[1] = w * sin(u), ax[2] = v;
        u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        dir[0] = w * cos(u), dir[1] = w * sin(u), dir[2] = v;
        off = it == 39 ? 1e3 : pow(10.0, t_rng_range(&rng, -1, 3)); /* the box is about 1 across */
        c = cos(angle), sn = sin(angle);
        for (a = 0; a < 3; a++) /* Rodrigues: R = c I + sn [ax]x + (1 - c) ax ax^T */
            for (b = 0; b < 3; b++) F.R[a][b] = (a == b ? c : 0) + (1 - c) * ax[a] * ax[b];
        F.R[0][1] -= sn * ax[2], F.R[1][0] += sn * ax[2];
        F.R[0][2] += sn * ax[1], F.R[2][0] -= sn * ax[1];
        F.R[1][2] -= sn * ax[0], F.R[2][1] += sn * ax[0];
        for (a = 0; a < 3; a++) F.off[a] = off * dir[a];
        snprintf(what, sizeof what, "float box %d (offset %.3g, %d x %d quads a face)", it, off, 1 + 2 * (it & 1), 1 + 2 * (it & 1));
        float_box_case(1 + 2 * (it & 1), &F, t_count(1500) < 300 ? 300 : t_count(1500), 200 + (unsigned long long)it, what);
    }
}

/* RE_LAYOUT_COMPACT (sphere centres solved at query time, relative to the
   object's centre) on the cases where that precision matters */
static void compact_layout_coordinates_offset_1e6(void) { with_compact_layout(coordinates_offset_1e6); }
static void compact_layout_float_boxes_rotated_keep_quads_flat(void) { with_compact_layout(float_boxes_rotated_keep_quads_flat); }
static void compact_layout_tiny_radius_1e6_of_size_hull(void) { with_compact_layout(tiny_radius_1e6_of_size_hull); }
static void float_icosphere_random_motions(void);
static void compact_layout_float_icosphere_random_motions(void) { with_compact_layout(float_icosphere_random_motions); }
static void compact_layout_long_straight_chains(void) { with_compact_layout(long_straight_chains); }
static void compact_layout_rays_along_a_face_through_its_vertices(void)
{
    with_compact_layout(rays_along_a_face_through_its_vertices);
}
static void compact_layout_grazing_along_a_subdivided_edge(void) { with_compact_layout(grazing_along_a_subdivided_edge); }

/* the example author's repro: rotation 0.3 about y, moved by (1.3, 1, 0.2) */
static void float_icosphere_rotated_translated(void)
{
    static const double ax[3] = {0, 1, 0}, t[3] = {1.3, 1, 0.2};
    float_icosphere_case(1, ax, 0.3, t, 0.06, t_count(4000), 41, "icosphere rot 0.3 y + (1.3, 1, 0.2)");
}

/* 60 random rigid motions and scales (6 under the sanitizers' scale):
   offsets from 0.1 to 1e3 times the size, the last always 1e3 */
static void float_icosphere_random_motions(void)
{
    t_rng_t rng = {43};
    int it, n_it = t_count(60) < 6 ? 6 : (int)t_count(60); /* 6 motions under the sanitizers' scale */
    for (it = 0; it < n_it; it++) {
        double ax[3], t[3], dir[3], sc = t_rng_range(&rng, 0.5, 2), off, angle = t_rng_range(&rng, 0, 2 * M_PI);
        double u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        char what[64];
        int a;
        ax[0] = w * cos(u), ax[1] = w * sin(u), ax[2] = v;
        u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        dir[0] = w * cos(u), dir[1] = w * sin(u), dir[2] = v;
        off = 2 * sc * pow(10.0, t_rng_range(&rng, -1, 3)); /* size = 2 sc */
        if (it == n_it - 1) off = 2e3 * sc;                  /* the far end, always */
        for (a = 0; a < 3; a++) t[a] = off * dir[a];
        snprintf(what, sizeof what, "icosphere motion %d (offset %.3g)", it, off);
        /* at least 200 rays even under the sanitizer scale, so the guard
           "more than 1 in 20 rays hit the rounding" stays meaningful */
        float_icosphere_case(sc, ax, angle, t, 0.06 * sc, t_count(600) < 200 ? 200 : t_count(600),
                             100 + (unsigned long long)it, what);
    }
}

/* A float host reports t early or late by ~1e-7 relative. Early, I lies
   just outside the face plane beside the true crossing, and next to a
   rounding's tangent line the flat-part test failed there; the search then
   took the ray as already inside the sharp mesh and never considered its
   entry through the face (found by review, 2026-12-06): pass-throughs of
   rays that go deep into the solid, and rounded hits inside it with their
   normals 0.4 rad off (r = 1e-6 of the size at t early by 6e-8, r = 0.01
   at 2e-6). Random hulls of 8 to 20 vertices, rays at vertices and along
   chords with jitter of a radius, the host's t early by 6e-8 and 2e-6
   (inside RE__HOST_T_SLACK): every answer against the eroded-polytope
   reference (1e-7 of the size, an unchanged answer also off by the host's
   own error), re_query_uv the same as re_query. */
static void early_host_t_next_to_seams(void)
{
    static const double early[2] = {6e-8, 2e-6}, radii[2] = {2e-6, 0.02};
    t_rng_t rng = {2612};
    int it, k;
    g_poly_jitter = 1.0;
    for (it = 0; it < 4; it++)
        for (k = 0; k < 4; k++) {
            tm_mesh_t m = {0};
            static tm_poly_t P;
            tm_random_hull(&rng, 8 + 4 * it, 0.8, 1.2, &m, &P);
            g_poly_host_early = early[k & 1];
            poly_rays(&m, &P, radii[k >> 1], t_count(500), 1e-7, 700 + (unsigned long long)(4 * it + k), "early host t");
            tm_free(&m);
        }
    g_poly_host_early = 0;
    g_poly_jitter = 3.0;
}

/* A regular k-gon prism (z in [-0.5, 0]) with a low pyramid roof, its apex
   a little off centre at (a, 0.7 a, h): the apex's creases are 0.05 to 0.2
   degrees from flat. The walk puts the eroded corner's k - 2 vertices 1e-7
   to 1e-5 apart, each within the masks' tolerance of every plane; every
   plane pair then looked like an eroded edge, the extra cylinders outgrew
   their cap and the apex was reported unroundable, leaving the whole
   solid sharp (its 90-degree walls too; found by review, 2026-12-06: k = 6,
   a = 0.004096, h = 0.003, and most random apexes at h = 1e-4 for k = 8,
   all at 1e-5). Kept vertices on three common planes are now one. Every
   convex edge rounded, no corner reported, and rays against the eroded
   polytope (1e-7 of the size). */
/* The reference itself (tm_erode) where three of a hull's planes lie
   within 2e-3 rad of each other: the 10 points of a fuzz_rounded_exact
   input (coordinates as its 16-bit codes), r = 2^-25 of the size. Solved
   in double, the triple's point came out 4.3e-8 (0.8 r) outside four
   other planes, inside the double solve's own tolerance, and became a
   vertex of the "eroded polytope": the reference's nearest point moved
   0.3 r off the true edge and the fuzzer blamed the library's normal
   (0.2 rad). Every eroded vertex must lie inside every plane, checked in
   __float128, up to tm_erode's stated 1e-11 (the double planes' own
   rounding, which an eroded polytope shrunk to a point needs). */
static void reference_erosion_at_nearly_parallel_planes(void)
{
    static const unsigned char code[60] = {
        0x61, 0x00, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x59, 0x41, 0x9e, 0x5f, 0x29,
        0xbe, 0xbd, 0x75, 0x9e, 0x1a, 0xdd, 0x9c, 0x73, 0x91, 0x30, 0x89, 0x29, 0x77, 0xb2, 0x15, 0x27, 0xa7, 0x40,
        0xa7, 0x17, 0x00, 0x00, 0x00, 0x00, 0xa7, 0xa7, 0xa7, 0x00, 0xa7, 0x00, 0x00, 0xa7, 0xa7, 0xa7, 0xa7, 0x3b,
        0x61, 0xa7, 0xa7, 0x9e, 0x5f, 0x29};
    double p[10][3], r, worst = -HUGE_VAL;
    static tm_poly_t P;
    tm_mesh_t m = {0};
    int i, g, a;
    for (i = 0; i < 10; i++)
        for (a = 0; a < 3; a++) p[i][a] = (double)(code[6 * i + 2 * a] | code[6 * i + 2 * a + 1] << 8) / 32767.5 - 1.0;
    memset(&P, 0, sizeof P);
    tm_hull((const double(*)[3])p, 10, &m, &P);
    r = ldexp(tm_size(p[0], 10), -25);
    tm_erode(&P, r);
    T_GE(P.nv, 16); /* a hull of 16 triangles, its creases rounded */
    for (i = 0; i < P.nv; i++)
        for (g = 0; g < P.np; g++) {
            __float128 sv = -((__float128)P.c[g] - r);
            for (a = 0; a < 3; a++) sv += (__float128)P.n[g][a] * P.v[i][a];
            worst = fmax(worst, (double)sv);
        }
    T_LE(worst, 1e-11);
    tm_free(&m);
}

static void nearly_flat_off_centre_apex(void)
{
    static const double cases[6][3] = {{6, 0.004096, 0.003}, {8, 0.008, 0.001}, {6, 0.0123, 1e-4},
                                       {7, 0.0071, 1e-4}, {8, 0.0031, 1e-4}, {8, 0.0057, 1e-5}};
    int c;
    for (c = 0; c < 6; c++) {
        tm_mesh_t m = {0};
        static tm_poly_t P;
        int i, k = (int)cases[c][0];
        double a = cases[c][1], h = cases[c][2];
        unsigned apex;
        re_scene_t *s;
        re_diag_t dg;
        re_stats_t st;
        char what[64];
        for (i = 0; i < k; i++) tm_vert(&m, cos(2 * M_PI * i / k), sin(2 * M_PI * i / k), 0);
        for (i = 0; i < k; i++) tm_vert(&m, cos(2 * M_PI * i / k), sin(2 * M_PI * i / k), -0.5);
        apex = tm_vert(&m, a, 0.7 * a, h);
        for (i = 0; i < k; i++) tm_tri(&m, (unsigned)i, (unsigned)((i + 1) % k), apex);
        for (i = 0; i < k; i++) tm_quad(&m, (unsigned)(k + i), (unsigned)(k + (i + 1) % k), (unsigned)((i + 1) % k), (unsigned)i);
        for (i = 1; i + 1 < k; i++) tm_tri(&m, (unsigned)k, (unsigned)(k + i + 1), (unsigned)(k + i));
        tm_planes(&m, &P);
        snprintf(what, sizeof what, "roof k %d apex %g h %g", k, a, h);
        s = build1(&m, 0.05, &dg);
        if (!T_CHECK(s != NULL)) { fprintf(stderr, "%s: %s\n", what, dg.message); tm_free(&m); continue; }
        re_get_stats(s, &st);
        if (!T_INT_EQ(st.rounded_edges, st.convex_edges)) fprintf(stderr, "%s: %llu of %llu convex edges rounded\n", what, (unsigned long long)st.rounded_edges, (unsigned long long)st.convex_edges);
        T_GT(st.convex_edges, 3 * (unsigned long long)k - 1);
        re_free(s);
        poly_rays(&m, &P, 0.05, t_count(600), 1e-7, 900 + (unsigned long long)c, what);
        tm_free(&m);
    }
}

/* A round rim finely tessellated under a large radius: a 512-sided prism
   (rim_prism) rounded with r = 0.4. Every rim vertex is a corner on the
   cap's plane, and at a point near the rim 188 of them are detected, 66
   needed; a query held 64 and dropped the rest silently, so 296 of 3 980
   vertical rays came back sharp or up to 0.0086 deep (found by review,
   2026-12-06). Against the exact rounded prism (rim_rays), in both
   layouts; no answer may be flagged RE_HIT_INCOMPLETE (the set holds
   RE_SET_CAP corners; test_rounded_setcap lowers it). */
static void fine_round_rim_under_a_large_radius(void)
{
    int layout, n = (int)t_count(200);
    if (n < 40) n = 40;
    for (layout = 0; layout < 2; layout++) {
        rim_tally_t t;
        if (!rim_run(512, 0.4, 20 * n, layout, &t)) break;
        T_INT_EQ(t.wrong, 0);
        T_INT_EQ(t.flagged, 0);
        T_GT(t.queries, 1599);
    }
}

/* The same rim with 8 192 sides: more than RE_SET_CAP (1 024) corners near
   the rim are within reach of one point, so the query drops some (about 7%
   of the answers come back sharp or off, docs: Limits) and must flag every
   such answer RE_HIT_INCOMPLETE. The set's table (past 64 corners) is what
   makes these queries affordable: 2.8 ms each before it, 0.19 ms now. */
static void finest_rim_flags_the_corners_it_drops(void)
{
    rim_tally_t t;
    int n = (int)t_count(20);
    if (n < 10) n = 10;
    if (!rim_run(8192, 0.4, 20 * n, 0, &t)) return;
    T_INT_EQ(t.wrong_unflagged, 0);
    T_GT(t.flagged, 0);
}

/* A reflection along a face from a seam hit a little below it: the hit on
   the rounding cylinder of a 4 x 1 x 0.5 box's long top edge (r = 0.05), at
   the middle of its seam with the top face, given 0, 1e-3, 0.25 and 0.45
   of the push below the top plane (a host's rounding far out), the
   direction across the top face, rising by 1e-17 or exactly level. Its
   crossing of the top plane is rounding over rounding: 1e8 sizes on
   before re__crossing_out_of_reach (the origin that far off). The origin
   must lie outside the box by between half the push and the push, and off
   the ray by at most the push, up to the coordinates' rounding. */
static void reflection_along_a_face_from_below_its_seam(void)
{
    static const double lo[3] = {-2, -0.5, -0.25}, hi[3] = {2, 0.5, 0.25};
    static const double below[4] = {0, 1e-3, 0.25, 0.45}, rise[2] = {1e-17, 0};
    tm_mesh_t m = {0};
    re_scene_t *s;
    unsigned c, found = RE__NONE, k, j, a, n = 0;
    double push = RE_ORIGIN_OFFSET_REL * sqrt(16 + 1 + 0.25), tol = 8 * RE__DBL_EPS * 3;
    tm_box(&m, lo, hi);
    s = build1_in(&m, 0.05, 0);
    if (!s) return;
    for (c = 0; c < re_cylinder_count(s, 0); c++) { /* the edge y = 0.5, z = 0.25 */
        re_cylinder_t cy;
        re_get_cylinder(s, 0, c, &cy);
        if (fabs(cy.a[1] - 0.45) < 1e-12 && fabs(cy.a[2] - 0.2) < 1e-12 && fabs(cy.b[1] - 0.45) < 1e-12) found = c;
    }
    if (!T_CHECK(found != RE__NONE)) { re_free(s); tm_free(&m); return; }
    for (k = 0; k < 4; k++)
        for (j = 0; j < 2; j++) {
            re_hit_t h;
            double d[3] = {0, -1, 0}, org[3], w[3], x[3], out = -HUGE_VAL, off;
            memset(&h, 0, sizeof h);
            h.kind = RE_HIT_ROUNDED, h.feature = RE_FEATURE_CYLINDER, h.feature_index = found, h.object = 0;
            h.point[0] = 0.0, h.point[1] = 0.45, h.point[2] = 0.25 - below[k] * push;
            h.normal[2] = 1;
            d[2] = rise[j];
            re_secondary_origin(s, &h, d, org);
            for (a = 0; a < 3; a++) out = fmax(out, fmax(org[a] - hi[a], lo[a] - org[a]));
            tm_sub(org, h.point, w);
            tm_cross(w, d, x);
            off = tm_len(x) / tm_len(d);
            if (!T_GE(out, 0.5 * push - tol) || !T_LE(out, push + tol) || !T_LE(off, push + tol))
                fprintf(stderr, "    %g of the push below, rise %g: origin %.3g outside, %.3g off the ray (push %.3g)\n",
                        below[k], rise[j], out, off, push);
            n++;
        }
    T_INT_EQ(n, 8);
    re_free(s);
    tm_free(&m);
}

/* A corner's reach on its faces (construction step 7: the projected
   sphere centres and the edges' strips; it sizes the bands' corner caps,
   the walk and the detection zones) does not depend on where the object
   sits: random hulls of 6 to 16 points and steep off-centre pyramids
   (corners of degree 3 to 8), r = 0.03 and 0.08 of their size, built at
   the origin and moved to 1e6; every corner's stored walk reach agrees to
   1e-6. It was measured from sphere centres minus the vertex, which carry
   the coordinates' rounding at 1e6 (6e-11, above the tangency test's
   1e-9 r): no centre counted, the reach fell to the edges' strips, and
   the bands called removed points flat (fuzz_rounded_exact, seed
   band_cap_far_from_the_origin: a degree-5 corner's reach 0.013 for
   0.031). Host hits within 5 r of every vertex then get re_query's answer
   from re_query_uv, bit for bit. */
static void corner_reach_far_from_the_origin(void)
{
    static tm_poly_t P;
    t_rng_t rng = {77};
    int hull, rk, k, n = (int)t_count(12);
    long corners = 0, short_reach = 0, queries = 0, differ = 0;
    if (n < 4) n = 4;
    for (hull = 0; hull < n; hull++)
        for (rk = 0; rk < 2; rk++) {
            tm_mesh_t m = {0};
            re_scene_t *s0, *s;
            unsigned t, a, c;
            double r;
            if (hull & 2) { /* a steep off-centre pyramid: an apex of 4 to 8 planes */
                double q[9][3];
                int nb = 4 + hull % 5, i;
                for (i = 0; i < nb; i++) {
                    double ang = 2 * M_PI * (i + 0.3 * t_rng_unit(&rng)) / nb;
                    q[i][0] = cos(ang), q[i][1] = sin(ang), q[i][2] = 0;
                }
                q[nb][0] = t_rng_range(&rng, -0.5, 0.5), q[nb][1] = t_rng_range(&rng, -0.5, 0.5), q[nb][2] = t_rng_range(&rng, 1.5, 4);
                tm_hull((const double(*)[3])q, nb + 1, &m, &P);
            } else
                tm_random_hull(&rng, 6 + hull % 11, 0.6, 1.0, &m, &P);
            r = (rk ? 0.08 : 0.03) * tm_size(m.v, m.nv);
            s0 = build1_in(&m, r, hull & 1);
            for (a = 0; a < 3 * m.nv; a++) m.v[a] += 1e6;
            s = build1_in(&m, r, hull & 1);
            if (s0 && s && T_INT_EQ(s->objects[0].n_corners, s0->objects[0].n_corners))
                for (c = 0; c < s->objects[0].n_corners; c++, corners++)
                    if (!((double)s->objects[0].corners[c].walk >= (1 - 1e-6) * (double)s0->objects[0].corners[c].walk)) {
                        if (short_reach++ < 3)
                            fprintf(stderr, "    hull %d r %g corner %u: walk %.9g at 1e6, %.9g at the origin\n", hull, r, c,
                                    (double)s->objects[0].corners[c].walk, (double)s0->objects[0].corners[c].walk);
                    }
            for (t = 0; s && t < m.ni / 3; t++)
                for (k = 0; k < 24; k++) {
                    const double *pc[3];
                    double e1[3], e2[3], nrm[3], jit[3], X[3], o[3], d[3], l[3], u, v;
                    re_hit_t h, hu;
                    int cc = k % 3;
                    /* within 5 r of corner cc along its two edges */
                    pc[0] = m.v + 3 * m.idx[3 * t], pc[1] = m.v + 3 * m.idx[3 * t + 1], pc[2] = m.v + 3 * m.idx[3 * t + 2];
                    tm_sub(pc[(cc + 1) % 3], pc[cc], e1), tm_sub(pc[(cc + 2) % 3], pc[cc], e2);
                    u = fmin(0.45, 5 * r / tm_len(e1)) * t_rng_unit(&rng), v = fmin(0.45, 5 * r / tm_len(e2)) * t_rng_unit(&rng);
                    l[cc] = 1 - u - v, l[(cc + 1) % 3] = u, l[(cc + 2) % 3] = v;
                    for (a = 0; a < 3; a++) X[a] = l[0] * pc[0][a] + l[1] * pc[1][a] + l[2] * pc[2][a];
                    tm_sub(pc[1], pc[0], e1), tm_sub(pc[2], pc[0], e2), tm_cross(e1, e2, nrm), tm_norm(nrm);
                    tm_rand_dir(&rng, jit);
                    for (a = 0; a < 3; a++) d[a] = -nrm[a] + 0.5 * jit[a];
                    if (!(tm_dot(d, nrm) < -0.3)) continue;
                    for (a = 0; a < 3; a++) o[a] = X[a] - d[a];
                    re_query(s, o, d, 0, t, 1.0, &h);
                    re_query_uv(s, o, d, 0, t, 1.0, l[1], l[2], &hu);
                    queries++;
                    if ((h.kind != hu.kind || h.t != hu.t) && differ++ < 3)
                        fprintf(stderr, "    hull %d r %g triangle %u: re_query kind %d t %.17g, re_query_uv kind %d\n", hull, r, t,
                                (int)h.kind, h.t, (int)hu.kind);
                }
            if (s0) re_free(s0);
            if (s) re_free(s);
            tm_free(&m);
        }
    fprintf(stderr, "    %ld corners, %ld with a shorter reach at 1e6; %ld queries, %ld answers differ\n", corners, short_reach,
            queries, differ);
    T_INT_EQ(short_reach, 0);
    T_INT_EQ(differ, 0);
    T_GT(corners, 4 * n);
    T_GT(queries, 200 * n);
}

/* fuzz_rounded_exact, 2026-12-07: rays along the faces of its tetrahedron
   (float positions, r = 0.04 of its size) through points on their edges,
   in 2 000 directions each (rays_along_faces_of), half of them leaving the
   face over that edge. A ray leaving over the edge at 1e-10 into the face
   crosses its plane just before the edge, where the exact host reports it,
   so I (o + t_host d, 4.9 sizes from o) is off the plane by the rounding
   of o and t_host d: 3.6e-16 when t_host d is rounded before the sum. The
   host-t mend (re__onto_face) took that for a float host's early t, since
   its slack counted |I| only, and moved I 3.6e-6 along the ray onto the
   plane, past the edge and out of the mesh: a pass-through 9.4e-7 outside
   the hull, through the wrong face. Before the mend's slack counted I's
   rounding, 17 of the 31 762 rays that hit failed (up to 5.6e-7 outside)
   in a build without fused multiply-adds, clang's here; gcc's builds fuse
   o + t d into one rounding to I's magnitude and miss them. */
static void rays_along_a_face_over_its_edges(void)
{
    static const double v[4][3] = {{-0.99224841594696045, -1, -0.998687744140625},
                                   {0.35158312320709229, -0.21474021673202515, 0.16581979393959045},
                                   {0.48793774843215942, 0.33040359616279602, 0.62911421060562134},
                                   {-0.35771724581718445, -0.7286335825920105, -0.39195850491523743}};
    static const unsigned t[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    static const double fracs[2] = {0.65490196078431373, 0.3};
    long nr = t_count(2000), hits = 0, bad = 0;
    int k;
    for (k = 0; k < 2; k++) bad += rays_along_faces_of(v, 4, t, 4, 0.02, fracs[k], nr, &hits);
    T_INT_EQ(bad, 0);
    T_GT(hits, nr * 8);
    fprintf(stderr, "    %ld rays hit the tetrahedron\n", hits);
}

#ifdef __clang__
/* The clang build is the unfused one (the Makefile's CLANG_UNFUSED): a * b
   + c as re__madd writes it is rounded twice ((1 + 2^-30)^2 - (1 + 2^-29)
   is 2^-60 fused, 0 not), so this unit's bounds are checked both ways. */
static void clang_build_rounds_every_product(void)
{
    volatile double a = 1 + 0x1p-30, c = -(1 + 0x1p-29);
    double x = a, z = c;
    T_CHECK(x * x + z == 0);
}
#endif

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
#ifdef __clang__
        T_CASE(clang_build_rounds_every_product),
#endif
        T_CASE(tiny_radius_1e6_of_size_box),
        T_CASE(tiny_radius_1e6_of_size_hull),
        T_CASE(largest_valid_radius_box),
        T_CASE(radius_above_largest_is_clamped),
        T_CASE(radius_above_largest_is_rejected),
        T_CASE(short_edge_is_named),
        T_CASE(thin_slab_with_subdivided_walls),
        T_CASE(rounding_beside_a_pocket_is_clamped),
        T_CASE(rounding_beside_a_pocket_near_a_corner),
        T_CASE(rounding_beside_a_boss_is_clamped),
        T_CASE(far_loose_triangle_clamps_nothing),
        T_CASE(other_shell_inside_the_rounding_clamps),
        T_CASE(touching_shells_agree_checked_or_not),
        T_CASE(coplanar_pieces_far_from_origin_stay_flat),
        T_CASE(dihedral_179_9_degrees),
        T_CASE(dihedral_1_degree),
        T_CASE(icosphere_level1),
        T_CASE(coordinates_offset_1e6),
        T_CASE(object_sizes_at_both_ends_of_the_range),
        T_CASE(object_sizes_outside_the_range_rejected),
        T_CASE(extreme_direction_lengths),
        T_CASE(rays_exactly_through_edges_and_vertices),
        T_CASE(rays_grazing_a_face),
        T_CASE(rays_lying_in_a_face_plane),
        T_CASE(rays_along_a_face_through_its_vertices),
        T_CASE(compact_layout_rays_along_a_face_through_its_vertices),
        T_CASE(rays_along_a_face_past_a_sharp_corner),
        T_CASE(ray_sinking_past_a_lost_tangent_contact),
        T_CASE(lost_contact_along_a_face_reflects_off_it),
        T_CASE(reflection_along_a_face_from_a_cylinder_end),
        T_CASE(rays_along_a_face_over_its_edges),
        T_CASE(normals_far_from_a_long_edges_far_end),
        T_CASE(flat_test_beside_a_sharp_corner_far_out),
        T_CASE(grazing_along_a_subdivided_edge),
        T_CASE(long_straight_chains),
        T_CASE(chain_corners_dropped_renumber_the_rest),
        T_CASE(float_icosphere_rotated_translated),
        T_CASE(float_icosphere_random_motions),
        T_CASE(float_boxes_rotated_keep_quads_flat),
        T_CASE(fine_cylinders_do_not_chain_into_one_plane),
        T_CASE(float_fanned_prisms_far_from_origin), T_CASE(fine_polygon_exit_clearance_as_defined),
        T_CASE(sliver_crease_beside_fine_cap_exit_clearance),
        T_CASE(compact_layout_coordinates_offset_1e6),
        T_CASE(compact_layout_tiny_radius_1e6_of_size_hull),
        T_CASE(compact_layout_float_icosphere_random_motions),
        T_CASE(compact_layout_float_boxes_rotated_keep_quads_flat),
        T_CASE(compact_layout_long_straight_chains),
        T_CASE(compact_layout_grazing_along_a_subdivided_edge),
        T_CASE(early_host_t_next_to_seams),
        T_CASE(nearly_flat_off_centre_apex),
        T_CASE(reference_erosion_at_nearly_parallel_planes),
        T_CASE(fine_round_rim_under_a_large_radius),
        T_CASE(finest_rim_flags_the_corners_it_drops),
        T_CASE(reflection_along_a_face_from_below_its_seam),
        T_CASE(corner_reach_far_from_the_origin),
    };
    return T_RUN(argc, argv, cases);
}
