/* tests/test_rounded_touching.c — rounded_edges.h, construction step 2a:
   solids that touch at a vertex or along an edge and share it (voxel art's
   diagonal neighbours, touching parts welded with re_mesh_t.weld) are
   rounded each as if it stood alone. The oracle is the union of the
   analytic rounded boxes (each the inner box (+) a ball), traced by the
   host protocol (pass-throughs continued); the same solids built with
   vertices of their own must give the same answers. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"

#define MAX_BOXES 4

typedef struct reports_t {
    int n[16];
    long long max_vertex;   /* largest vertex a vertex or edge report names */
    long long mixed[8];     /* the vertices of mixed-vertex reports */
    int n_mixed;
    char mixed_msg[8][160];
} reports_t;
static void collect(void *u, const re_report_t *r)
{
    reports_t *c = (reports_t *)u;
    if ((int)r->kind < 16) c->n[r->kind]++;
    if (r->kind != RE_REPORT_SKIPPED_TRIANGLE) {
        if (r->element > c->max_vertex) c->max_vertex = r->element;
        if (r->element2 > c->max_vertex) c->max_vertex = r->element2;
    }
    if (r->kind == RE_REPORT_MIXED_VERTEX && c->n_mixed < 8) {
        c->mixed[c->n_mixed] = r->element;
        snprintf(c->mixed_msg[c->n_mixed], sizeof c->mixed_msg[0], "%s", r->message);
        c->n_mixed++;
    }
}

/* the vertex at (x, y, z): an existing one when `share`, else a new one */
static unsigned vert_at(tm_mesh_t *m, double x, double y, double z, int share)
{
    unsigned i;
    for (i = 0; share && i < m->nv; i++)
        if (m->v[3 * i] == x && m->v[3 * i + 1] == y && m->v[3 * i + 2] == z) return i;
    return tm_vert(m, x, y, z);
}
/* axis-aligned box [lo, hi], wound outward (as tm_box) */
static void box_into(tm_mesh_t *m, const double lo[3], const double hi[3], int share)
{
    unsigned b[8], i;
    for (i = 0; i < 8; i++) b[i] = vert_at(m, i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2], share);
    tm_box_faces(m, b);
}
/* every triangle corner its own vertex (per-face normals or UVs) */
static void unshare(const tm_mesh_t *m, tm_mesh_t *u)
{
    unsigned i;
    for (i = 0; i < m->ni; i++) {
        const double *p = m->v + 3 * m->idx[i];
        tm_vert(u, p[0], p[1], p[2]);
    }
    for (i = 0; i < m->ni; i += 3) tm_tri(u, i, i + 1, i + 2);
}

static re_scene_t *build(const tm_mesh_t *m, double r, int weld, re_layout_t layout, reports_t *rep)
{
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_diag_t dg;
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m->v, mesh.vertex_count = m->nv, mesh.indices = m->idx, mesh.index_count = m->ni;
    mesh.radius = r, mesh.weld = weld;
    desc.objects = &mesh, desc.object_count = 1, desc.layout = layout;
    if (rep) memset(rep, 0, sizeof *rep), rep->max_vertex = -1, desc.report = collect, desc.report_user = rep;
    if (!T_INT_EQ(re_build(&desc, &s, &dg), RE_OK)) fprintf(stderr, "    %s\n", dg.message);
    return s;
}

typedef struct boxes_t {
    int n;
    double c[MAX_BOXES][3], half[MAX_BOXES][3], r;
} boxes_t;
static double boxes_sdf(const void *ctx, const double p[3])
{
    const boxes_t *b = (const boxes_t *)ctx;
    double d = HUGE_VAL;
    int i;
    for (i = 0; i < b->n; i++) d = fmin(d, tm_rbox_sdf(b->c[i], b->half[i], b->r, p));
    return d;
}
static void boxes_normal(const boxes_t *b, const double p[3], double n[3])
{
    int i, best = 0;
    for (i = 1; i < b->n; i++)
        if (tm_rbox_sdf(b->c[i], b->half[i], b->r, p) < tm_rbox_sdf(b->c[best], b->half[best], b->r, p)) best = i;
    tm_rbox_normal(b->c[best], b->half[best], b->r, p, n);
}

/* The host protocol on the sharp mesh: the nearest front face after the
   last pass-through, asked again until the answer is not a pass-through.
   0 when the ray leaves the mesh. */
static int host_trace(const re_scene_t *s, const tm_mesh_t *m, const double o[3], const double d[3], re_hit_t *h)
{
    double from = 0;
    int k;
    for (k = 0; k < 16; k++) {
        double oo[3], t;
        unsigned tri;
        oo[0] = o[0] + from * d[0], oo[1] = o[1] + from * d[1], oo[2] = o[2] + from * d[2];
        if (!tm_hit(m, oo, d, &t, &tri)) return 0;
        re_query(s, o, d, 0, tri, from + t, h);
        if (h->kind != RE_PASS_THROUGH) return 1;
        if (!T_GT(h->t, from)) return 0;
        from = h->t;
    }
    return 0;
}

/* Rays at the solids (half of them aimed within 0.3 of `at`, where they
   touch): answers against the union of rounded boxes to rel, and against
   the same boxes built with vertices of their own (`apart`) to 1e-12. */
static void rays_against_boxes(const tm_mesh_t *m, const tm_mesh_t *apart, const boxes_t *b, const double at[3],
                               re_layout_t layout, long nrays, unsigned long long seed)
{
    re_scene_t *s = build(m, b->r, 0, layout, NULL), *sa = build(apart, b->r, 0, layout, NULL);
    t_rng_t rng;
    long i, n_round = 0, n_near = 0;
    int a;
    rng.s = seed;
    if (!s || !sa) goto done;
    for (i = 0; i < nrays; i++) {
        double o[3], d[3], tgt[3], u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        double t_ref, p[3], n[3];
        re_hit_t h, ha;
        int hit, hit_a;
        for (a = 0; a < 3; a++) tgt[a] = i % 2 ? at[a] + t_rng_range(&rng, -0.3, 0.3) : t_rng_range(&rng, -0.1, 2.1);
        o[0] = tgt[0] + 6 * w * cos(u), o[1] = tgt[1] + 6 * w * sin(u), o[2] = tgt[2] + 6 * v;
        tm_sub(tgt, o, d);
        hit = host_trace(s, m, o, d, &h);
        hit_a = host_trace(sa, apart, o, d, &ha);
        t_ref = tm_trace(boxes_sdf, b, o, d, 1e3, 2.0);
        if (!T_INT_EQ(hit, hit_a)) continue;
        if (!hit) {
            T_EQ(t_ref, HUGE_VAL);
            continue;
        }
        for (a = 0; a < 3; a++) p[a] = o[a] + h.t * d[a];
        n_near += fabs(p[0] - at[0]) < 0.3 && fabs(p[1] - at[1]) < 0.3 && fabs(p[2] - at[2]) < 0.3;
        T_INT_EQ(h.kind, ha.kind);
        T_NEAR(h.t, ha.t, 1e-12 * (1 + fabs(ha.t)));
        for (a = 0; a < 3; a++) T_NEAR(h.normal[a], ha.normal[a], 1e-12);
        if (!T_NEAR(h.t, t_ref, 1e-9 * (1 + t_ref))) continue;
        if (h.kind == RE_HIT_ROUNDED) {
            n_round++;
            boxes_normal(b, p, n);
            for (a = 0; a < 3; a++) T_NEAR(h.normal[a], n[a], 1e-7);
        }
    }
    T_GT(n_round, nrays / 20); /* the rays do reach the rounded surface */
    T_GT(n_near, nrays / 20);  /* and the place where the solids touch */
done:
    re_free(s), re_free(sa);
}

/* stats of a mesh of n boxes, each rounded alone: 12 edges, 8 spheres */
static void expect_each_box_rounded(const re_scene_t *s, const reports_t *rep, int n, unsigned nv)
{
    re_stats_t st;
    if (!s) return;
    re_get_stats(s, &st);
    T_INT_EQ(st.rounded_edges, 12 * n);
    T_INT_EQ(st.convex_edges, 12 * n);
    T_INT_EQ(st.spheres, 8 * n);
    T_INT_EQ(st.rounded_corners, 8 * n);
    T_INT_EQ(st.mixed_vertices, 0);
    T_INT_EQ(st.nonmanifold_edges, 0);
    T_INT_EQ(st.boundary_edges, 0);
    T_INT_EQ(rep->n[RE_REPORT_MIXED_VERTEX] + rep->n[RE_REPORT_SHARP_PATCH_EDGE] + rep->n[RE_REPORT_NONMANIFOLD_EDGE], 0);
    T_LT(rep->max_vertex, (long long)nv);
}

/* the spheres naming mesh vertex v (one per solid at a split vertex) */
static int spheres_at(const re_scene_t *s, unsigned v, unsigned nv)
{
    unsigned i, n = 0;
    for (i = 0; s && i < re_sphere_count(s, 0); i++) {
        re_sphere_t sp;
        re_get_sphere(s, 0, i, &sp);
        T_LT(sp.vertex, nv); /* mesh ids, never step 2a's */
        n += sp.vertex == v;
    }
    return (int)n;
}
/* the boxes that have the point p as a corner */
static int boxes_cornered_at(const boxes_t *b, const double p[3])
{
    int i, a, n = 0;
    for (i = 0; i < b->n; i++) {
        for (a = 0; a < 3; a++)
            if (fabs(fabs(p[a] - b->c[i][a]) - b->half[i][a]) > 1e-15) break;
        n += a == 3;
    }
    return n;
}

static void touching_case(const boxes_t *b, const double at[3], long nrays, unsigned long long seed)
{
    tm_mesh_t m = {0}, apart = {0}, u = {0};
    re_scene_t *s;
    reports_t rep;
    double lo[3], hi[3];
    int i, a;
    for (i = 0; i < b->n; i++) {
        for (a = 0; a < 3; a++) lo[a] = b->c[i][a] - b->half[i][a], hi[a] = b->c[i][a] + b->half[i][a];
        box_into(&m, lo, hi, 1);
        box_into(&apart, lo, hi, 0);
    }
    T_LT(m.nv, 8u * (unsigned)b->n); /* they do share vertices */
    s = build(&m, b->r, 0, RE_LAYOUT_FAST, &rep);
    expect_each_box_rounded(s, &rep, b->n, m.nv);
    for (i = 0; i < (int)m.nv; i++) /* a sphere per solid at each vertex, named by its mesh id */
        T_INT_EQ(spheres_at(s, (unsigned)i, m.nv), boxes_cornered_at(b, m.v + 3 * i));
    re_free(s);
    /* the same through re_mesh_t.weld: touching parts of a per-face mesh */
    unshare(&m, &u);
    s = build(&u, b->r, 1, RE_LAYOUT_FAST, &rep);
    expect_each_box_rounded(s, &rep, b->n, u.nv);
    re_free(s);
    rays_against_boxes(&m, &apart, b, at, RE_LAYOUT_FAST, nrays, seed);
    rays_against_boxes(&m, &apart, b, at, RE_LAYOUT_COMPACT, nrays / 4, seed + 1);
    tm_free(&m), tm_free(&apart), tm_free(&u);
}

static void set_box(boxes_t *b, double x, double y, double z)
{
    int i = b->n++;
    b->c[i][0] = x + 0.5, b->c[i][1] = y + 0.5, b->c[i][2] = z + 0.5;
    b->half[i][0] = b->half[i][1] = b->half[i][2] = 0.5;
}

/* two unit cubes welded at one corner (a bowtie vertex, two fans) */
static void boxes_sharing_a_corner_round_each(void)
{
    boxes_t b = {0};
    const double at[3] = {1, 1, 1};
    b.r = 0.1;
    set_box(&b, 0, 0, 0), set_box(&b, 1, 1, 1);
    touching_case(&b, at, t_count(20000), 101);
}

/* two unit cubes welded along an edge (four triangles on it) */
static void boxes_sharing_an_edge_round_each(void)
{
    boxes_t b = {0};
    const double at[3] = {1, 1, 0.5};
    b.r = 0.1;
    set_box(&b, 0, 0, 0), set_box(&b, 1, 1, 0);
    touching_case(&b, at, t_count(20000), 202);
    b.n = 0, b.r = 0.45; /* nearly the largest radius: the cubes' roundings nearly meet at the edge */
    set_box(&b, 0, 0, 0), set_box(&b, 1, 1, 0);
    touching_case(&b, at, t_count(10000), 203);
}

/* a 2x2x2 checkerboard of four cubes: each pair shares an edge and all
   four the centre vertex (four fans; six four-triangle edges) */
static void checkerboard_cubes_round_each(void)
{
    boxes_t b = {0};
    const double at[3] = {1, 1, 1};
    b.r = 0.08;
    set_box(&b, 0, 0, 0), set_box(&b, 1, 1, 0), set_box(&b, 1, 0, 1), set_box(&b, 0, 1, 1);
    touching_case(&b, at, t_count(20000), 303);
}

/* A pyramid over a star-shaped octagon (its apex and inner corners join
   convex and concave edges: mixed vertices) with a cube standing on its
   apex. The apex has two fans: the cube's corner rounds, the pyramid stays
   sharp, and the reports name the apex by its mesh id whichever solid
   comes first. */
static void star_pyramid(tm_mesh_t *m, unsigned apex)
{
    unsigned ring[8], c = tm_vert(m, 0, 0, 0), i;
    for (i = 0; i < 8; i++) {
        double a = M_PI / 4 * i, rad = i % 2 ? 0.4 : 1.0;
        ring[i] = tm_vert(m, rad * cos(a), rad * sin(a), 0);
    }
    for (i = 0; i < 8; i++) tm_tri(m, apex, ring[i], ring[(i + 1) % 8]), tm_tri(m, c, ring[(i + 1) % 8], ring[i]);
}
static void mixed_apex_touching_a_cube(void)
{
    int order;
    for (order = 0; order < 2; order++) {
        tm_mesh_t m = {0};
        re_scene_t *s;
        reports_t rep;
        re_stats_t st;
        const double lo[3] = {0, 0, 1}, hi[3] = {1, 1, 2};
        unsigned apex;
        int i, n_apex;
        char want[32];
        if (order == 0) box_into(&m, lo, hi, 1);
        apex = vert_at(&m, 0, 0, 1, 1);
        star_pyramid(&m, apex);
        if (order == 1) box_into(&m, lo, hi, 1);
        T_INT_EQ(m.nv, 17); /* the apex is the cube's corner */
        s = build(&m, 0.1, 0, RE_LAYOUT_FAST, &rep);
        if (!s) continue;
        re_get_stats(s, &st);
        T_INT_EQ(st.rounded_edges, 12); /* the cube */
        T_INT_EQ(st.spheres, 8);
        T_INT_EQ(st.mixed_vertices, 5); /* the pyramid's apex and inner corners */
        T_INT_EQ(rep.n_mixed, 5);
        for (i = 0, n_apex = 0; i < rep.n_mixed && i < 8; i++)
            if (rep.mixed[i] == apex) {
                n_apex++;
                snprintf(want, sizeof want, "vertex %u ", apex);
                T_CHECK(strstr(rep.mixed_msg[i], want) != NULL);
            }
        T_INT_EQ(n_apex, 1);
        T_INT_EQ(rep.n[RE_REPORT_CONCAVE_EDGE], 4);
        T_LT(rep.max_vertex, (long long)m.nv);
        T_INT_EQ(spheres_at(s, apex, m.nv), 1);
        re_free(s);
        tm_free(&m);
    }
}

/* A closed fan and an open one at a vertex (a cube and a loose triangle
   touching its corner): the cube's fan gets a vertex of its own and the
   cube rounds; the triangle keeps the vertex, its edges boundaries. With
   the triangle's vertices numbered first, step 4's fan walk at the
   vertex starts in the open fan (re__several_fans walks it both ways). */
static void open_fan_at_a_vertex_splits_off_the_solid(void)
{
    int order;
    for (order = 0; order < 2; order++) {
        tm_mesh_t m = {0};
        re_scene_t *s;
        reports_t rep;
        re_stats_t st;
        const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
        unsigned v, a = 0, b = 1;
        if (order == 1) tm_vert(&m, 2, 1.5, 1.5), tm_vert(&m, 1.5, 2, 1.5);
        box_into(&m, lo, hi, 1);
        if (order == 0) a = tm_vert(&m, 2, 1.5, 1.5), b = tm_vert(&m, 1.5, 2, 1.5);
        v = vert_at(&m, 1, 1, 1, 1);
        tm_tri(&m, v, a, b);
        s = build(&m, 0.1, 0, RE_LAYOUT_FAST, &rep);
        if (!s) continue;
        re_get_stats(s, &st);
        T_INT_EQ(st.rounded_edges, 12);
        T_INT_EQ(st.spheres, 8);
        T_INT_EQ(st.boundary_edges, 3);
        T_INT_EQ(st.mixed_vertices, 0);
        T_INT_EQ(rep.n[RE_REPORT_BOUNDARY_EDGE], 3);
        T_INT_EQ(rep.n_mixed, 0);
        T_INT_EQ(spheres_at(s, v, m.nv), 1);
        T_LT(rep.max_vertex, (long long)m.nv);
        re_free(s);
        tm_free(&m);
    }
}

/* Open fans keep their vertex together: a cube with a fin on its edge
   5-7 (three triangles there, none paired: the cube's fan and the fin's
   are open at vertex 5) and a second cube touching the first at vertex 5
   (closed). Only the second cube's fan is split off: it rounds, and the
   fin's edge stays one non-manifold edge, the first cube sharp. Had the
   open fans been split apart too, the first cube's half of the edge
   would have become an edge of its own. */
static void open_fans_keep_their_vertex(void)
{
    tm_mesh_t m = {0};
    re_scene_t *s;
    reports_t rep;
    re_stats_t st;
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, lo2[3] = {1, -1, 1}, hi2[3] = {2, 0, 2};
    unsigned v5, v7;
    box_into(&m, lo, hi, 1);
    v5 = vert_at(&m, 1, 0, 1, 1), v7 = vert_at(&m, 1, 1, 1, 1);
    tm_tri(&m, v5, v7, tm_vert(&m, 1.6, 0.5, 1.4));
    box_into(&m, lo2, hi2, 1);
    T_INT_EQ(vert_at(&m, 1, 0, 1, 1), v5);
    s = build(&m, 0.1, 0, RE_LAYOUT_FAST, &rep);
    if (!s) return;
    re_get_stats(s, &st);
    T_INT_EQ(st.rounded_edges, 12); /* the second cube */
    T_INT_EQ(st.spheres, 8);
    T_INT_EQ(st.nonmanifold_edges, 1);
    T_INT_EQ(spheres_at(s, v5, m.nv), 1);
    T_LT(rep.max_vertex, (long long)m.nv);
    re_free(s);
    tm_free(&m);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(boxes_sharing_a_corner_round_each), T_CASE(boxes_sharing_an_edge_round_each),
        T_CASE(checkerboard_cubes_round_each), T_CASE(mixed_apex_touching_a_cube), T_CASE(open_fan_at_a_vertex_splits_off_the_solid),
        T_CASE(open_fans_keep_their_vertex),
    };
    return T_RUN(argc, argv, cases);
}
