/* tests/test_rounded_baselines_example.c — the example's own geometry code
   against oracles: the tessellated rounded mesh (rx_tess.h, the "tess-N"
   modes and the render benchmark's reference) and its flat-part polygons
   (rx_flat), which serve here as an independent oracle for the library's
   per-triangle bands (re_query_uv, query step 0).

   Oracles: the rounded box is the inner box dilated by a ball, with the
   closed-form volume abc + 2r(ab+bc+ca) + pi r^2 (a+b+c) + 4/3 pi r^3 (a, b,
   c the inner box's sides); the bands are checked against the flat
   polygons and against re_query() itself on brute-force host hits. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#define RX_TESS_IMPLEMENTATION
#include "../examples/rounded_edges/rx_tess.h"
#include "test.h"

#define PI 3.14159265358979323846

/* ---- small meshes (CCW from outside) ------------------------------------- */
static void box_mesh(ex_mesh_t *m, double hx, double hy, double hz)
{
    static const uint32_t q[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    int i;
    m->nverts = 8; m->ntris = 12;
    m->pos = (float *)malloc(sizeof(float) * 24);
    m->idx = (uint32_t *)malloc(sizeof(uint32_t) * 36);
    for (i = 0; i < 8; i++) {
        m->pos[3 * i] = (float)(i & 1 ? hx : -hx);
        m->pos[3 * i + 1] = (float)(i & 2 ? hy : -hy);
        m->pos[3 * i + 2] = (float)(i & 4 ? hz : -hz);
    }
    for (i = 0; i < 6; i++) {
        uint32_t *t = m->idx + 6 * i;
        t[0] = q[i][0]; t[1] = q[i][1]; t[2] = q[i][2];
        t[3] = q[i][0]; t[4] = q[i][2]; t[5] = q[i][3];
    }
}

/* The same box with its four x-edges split into n segments (n + 1 rings of
   four vertices, long faces as strips of quads): straight chains, whose
   inner vertices the library rounds with the chain's one cylinder and no
   sphere. n = 1 is box_mesh's box. */
static void split_box_mesh(ex_mesh_t *m, double hx, double hy, double hz, unsigned n)
{
    static const double ring[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}; /* (y, z) signs, counter-clockwise seen from +x */
    unsigned i, j;
    uint32_t *t;
    m->nverts = 4 * ((size_t)n + 1);
    m->ntris = 8 * (size_t)n + 4;
    m->pos = (float *)malloc(sizeof(float) * 3 * m->nverts);
    m->idx = (uint32_t *)malloc(sizeof(uint32_t) * 3 * m->ntris);
    for (i = 0; i <= n; i++)
        for (j = 0; j < 4; j++) {
            float *p = m->pos + 3 * (4 * i + j);
            p[0] = (float)(-hx + 2 * hx * i / n); p[1] = (float)(ring[j][0] * hy); p[2] = (float)(ring[j][1] * hz);
        }
    t = m->idx;
    for (i = 0; i < n; i++)
        for (j = 0; j < 4; j++) {
            uint32_t a = 4 * i + j, b = 4 * i + (j + 1) % 4, c = b + 4, d = a + 4;
            t[0] = a; t[1] = b; t[2] = c; t[3] = a; t[4] = c; t[5] = d;
            t += 6;
        }
    t[0] = 3; t[1] = 2; t[2] = 1; t[3] = 3; t[4] = 1; t[5] = 0; /* x = -hx, facing -x */
    t += 6;
    t[0] = 4 * n; t[1] = 4 * n + 1; t[2] = 4 * n + 2; t[3] = 4 * n; t[4] = 4 * n + 2; t[5] = 4 * n + 3;
}

/* An icosahedron stretched by (1, 0.8, 1.25): still convex, vertices of
   degree 5 whose offset planes miss one common point, so every corner is
   exact (several spheres and extra cylinders). The regular one would put
   them all at one point, up to float rounding of the vertices. */
static void icosahedron_mesh(ex_mesh_t *m)
{
    static const uint32_t f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    const double g = (1 + sqrt(5.0)) / 2;
    const double v[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                             {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    int i;
    m->nverts = 12; m->ntris = 20;
    m->pos = (float *)malloc(sizeof(float) * 36);
    m->idx = (uint32_t *)malloc(sizeof(uint32_t) * 60);
    for (i = 0; i < 12; i++) {
        m->pos[3 * i] = (float)v[i][0]; m->pos[3 * i + 1] = (float)(0.8 * v[i][1]); m->pos[3 * i + 2] = (float)(1.25 * v[i][2]);
    }
    for (i = 0; i < 20; i++) {
        m->idx[3 * i] = f[i][0]; m->idx[3 * i + 1] = f[i][1]; m->idx[3 * i + 2] = f[i][2];
    }
}

static void mesh_free(ex_mesh_t *m) { free(m->pos); free(m->idx); memset(m, 0, sizeof *m); }

static re_scene_t *build_one(const ex_mesh_t *m, double r)
{
    re_mesh_t rm;
    re_scene_desc_t d;
    re_scene_t *s = NULL;
    re_diag_t diag;
    memset(&rm, 0, sizeof rm);
    memset(&d, 0, sizeof d);
    rm.positions = m->pos;
    rm.position_type = RE_FLOAT32;
    rm.vertex_count = (unsigned)m->nverts;
    rm.indices = m->idx;
    rm.index_count = (unsigned)(3 * m->ntris);
    rm.radius = r;
    d.objects = &rm;
    d.object_count = 1;
    T_INT_EQ(re_build(&d, &s, &diag), RE_OK);
    return s;
}

static ex_v3_t vtx(const ex_mesh_t *m, uint32_t i) { return ex_v3(m->pos[3 * i], m->pos[3 * i + 1], m->pos[3 * i + 2]); }

/* Enclosed volume (divergence theorem) and total area of a range of triangles. */
static double volume(const ex_mesh_t *m)
{
    double v = 0;
    size_t t;
    for (t = 0; t < m->ntris; t++) {
        ex_v3_t a = vtx(m, m->idx[3 * t]), b = vtx(m, m->idx[3 * t + 1]), c = vtx(m, m->idx[3 * t + 2]);
        v += ex_dot(a, ex_cross(b, c)) / 6;
    }
    return v;
}
static double area(const ex_mesh_t *m, size_t t0, size_t t1)
{
    double s = 0;
    size_t t;
    for (t = t0; t < t1; t++) {
        ex_v3_t a = vtx(m, m->idx[3 * t]), b = vtx(m, m->idx[3 * t + 1]), c = vtx(m, m->idx[3 * t + 2]);
        s += 0.5 * ex_len(ex_cross(ex_sub(b, a), ex_sub(c, a)));
    }
    return s;
}

/* Closed and consistently wound: after welding positions within `tol`, every
   directed edge (a, b) has exactly one partner (b, a). Returns the number of
   edges without one (O(E^2) on purpose: simple, meshes here are small). */
static long open_edges(const ex_mesh_t *m, double tol)
{
    size_t nv = m->nverts, i, j, ne = 3 * m->ntris;
    uint32_t *rep = (uint32_t *)malloc(sizeof(uint32_t) * nv);
    uint32_t *ea = (uint32_t *)malloc(sizeof(uint32_t) * ne), *eb = (uint32_t *)malloc(sizeof(uint32_t) * ne);
    long bad = 0;
    for (i = 0; i < nv; i++) {
        rep[i] = (uint32_t)i;
        for (j = 0; j < i; j++)
            if (rep[j] == j && ex_len(ex_sub(vtx(m, (uint32_t)i), vtx(m, (uint32_t)j))) <= tol) { rep[i] = (uint32_t)j; break; }
    }
    for (i = 0; i < m->ntris; i++)
        for (j = 0; j < 3; j++) {
            ea[3 * i + j] = rep[m->idx[3 * i + j]];
            eb[3 * i + j] = rep[m->idx[3 * i + (j + 1) % 3]];
        }
    for (i = 0; i < ne; i++) {
        long partners = 0;
        if (ea[i] == eb[i]) continue; /* a collapsed sliver edge */
        for (j = 0; j < ne; j++)
            if (ea[j] == eb[i] && eb[j] == ea[i]) partners++;
        if (partners != 1) bad++;
    }
    free(rep); free(ea); free(eb);
    return bad;
}

/* Distance from p to the box [-h, h]. */
static double box_dist(ex_v3_t p, ex_v3_t h)
{
    double dx = fmax(fabs(p.x) - h.x, 0), dy = fmax(fabs(p.y) - h.y, 0), dz = fmax(fabs(p.z) - h.z, 0);
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Float positions: a vertex is on the analytic surface to a few float ulps
   of the object size. */
#define TESS_ON_SURFACE_TOL 4e-7

static void tess_box_matches_analytic_rounded_box(void)
{
    static const int levels[4] = {1, 3, 10, 64};
    const double hx = 1.0, hy = 0.5, hz = 0.3, r = 0.1;
    const double a = 2 * (hx - r), b = 2 * (hy - r), c = 2 * (hz - r);
    const double exact = a * b * c + 2 * r * (a * b + b * c + c * a) + PI * r * r * (a + b + c) + 4.0 / 3.0 * PI * r * r * r;
    int shape;
    /* the plain box, and the box whose long edges are straight chains of 7
       segments (each segment enumerates the chain's whole cylinder; the
       inner vertices have no sphere): the same rounded solid */
    for (shape = 0; shape < 2; shape++) {
        ex_mesh_t m;
        re_scene_t *s;
        double prev_err = HUGE_VAL;
        int i;
        memset(&m, 0, sizeof m);
        if (shape == 0) box_mesh(&m, hx, hy, hz);
        else split_box_mesh(&m, hx, hy, hz, 7);
        s = build_one(&m, r);
        if (!s) { mesh_free(&m); return; }
        if (shape == 1) T_INT_EQ(re_cylinder_count(s, 0), 4 * 7 + 8); /* 28 chain segments, 8 short edges */
        for (i = 0; i < 4; i++) {
            ex_mesh_t t;
            size_t first = 0, v;
            double worst = 0, err;
            memset(&t, 0, sizeof t);
            T_INT_EQ(rx_tess_object(s, 0, &m, levels[i], &t, &first), 0);
            for (v = 0; v < t.nverts; v++)
                worst = fmax(worst, fabs(box_dist(vtx(&t, (uint32_t)v), ex_v3(hx - r, hy - r, hz - r)) - r));
            T_LE(worst, TESS_ON_SURFACE_TOL);
            /* the flat parts are exactly the shrunk faces */
            T_REL(area(&t, 0, first), 2 * (a * b + b * c + c * a), 1e-6);
            if (levels[i] <= 10) T_INT_EQ(open_edges(&t, 1e-6), 0);
            /* an inscribed polytope of a convex solid: below the exact volume,
               converging as 1/N^2 (the chord sagitta); a chain's cylinder
               tessellated once per segment would add volume */
            err = exact - volume(&t);
            T_GT(err, -1e-6);
            T_LT(err, prev_err);
            T_LE(err, 2.0 * r * r * (a + b + c + 4 * r) * (PI / (4.0 * levels[i])) * (PI / (4.0 * levels[i])) + 1e-6);
            prev_err = err;
            mesh_free(&t);
        }
        re_free(s);
        mesh_free(&m);
    }
}

/* The icosahedron's corners are exact (spheres plus extra cylinders): the
   tessellation stays closed and its volume grows monotonically toward the
   rounded solid's, below the sharp one. */
static void tess_icosahedron_closed_and_converging(void)
{
    static const int levels[3] = {1, 4, 16};
    ex_mesh_t m;
    re_scene_t *s;
    double sharp, prev = 0;
    int i;
    memset(&m, 0, sizeof m);
    icosahedron_mesh(&m);
    sharp = volume(&m);
    s = build_one(&m, 0.15);
    if (!s) { mesh_free(&m); return; }
    for (i = 0; i < 3; i++) {
        ex_mesh_t t;
        size_t first = 0;
        double v;
        memset(&t, 0, sizeof t);
        T_INT_EQ(rx_tess_object(s, 0, &m, levels[i], &t, &first), 0);
        T_INT_EQ(open_edges(&t, 1e-6), 0);
        v = volume(&t);
        T_GT(v, prev);
        T_LT(v, sharp);
        prev = v;
        mesh_free(&t);
    }
    re_free(s);
    mesh_free(&m);
}

/* Möller-Trumbore in double: the host's hit and its barycentrics u, v. */
static int host_hit(const ex_mesh_t *m, ex_v3_t o, ex_v3_t d, double *t_out, unsigned *tri, double *u_out, double *v_out)
{
    size_t t;
    int found = 0;
    for (t = 0; t < m->ntris; t++) {
        ex_v3_t a = vtx(m, m->idx[3 * t]), b = vtx(m, m->idx[3 * t + 1]), c = vtx(m, m->idx[3 * t + 2]);
        ex_v3_t e1 = ex_sub(b, a), e2 = ex_sub(c, a), p = ex_cross(d, e2), s, q;
        double det = ex_dot(e1, p), u, v, tt;
        if (det <= 0) continue; /* front faces only */
        s = ex_sub(o, a);
        u = ex_dot(s, p) / det;
        if (u < 0 || u > 1) continue;
        q = ex_cross(s, e1);
        v = ex_dot(d, q) / det;
        if (v < 0 || u + v > 1) continue;
        tt = ex_dot(e2, q) / det;
        if (tt > 0 && (!found || tt < *t_out)) { *t_out = tt; *tri = (unsigned)t; *u_out = u; *v_out = v; found = 1; }
    }
    return found;
}

/* The library's per-triangle bands (re_query_uv, query step 0) against the
   flat parts built here from the enumerated spheres (rx_flat, the polygons
   the tessellation uses): whenever the bands call a hit flat, it lies in its
   face's polygon (to 1e-9) and re_query says RE_UNCHANGED; and the bands
   skip nearly every hit the polygons call flat, on a box, on a stretched
   icosahedron (exact corners) and on a box whose long edges are straight
   chains. */
static void bands_agree_with_the_flat_polygons(void)
{
    t_rng_t rng = {42};
    int shape;
    for (shape = 0; shape < 3; shape++) {
        ex_mesh_t m;
        re_scene_t *s;
        rx_flat_t flat;
        long n = t_count(40000), i, hits = 0, poly_flat = 0, band_flat = 0;
        memset(&m, 0, sizeof m);
        if (shape == 0) box_mesh(&m, 1.0, 0.7, 0.5);
        else if (shape == 1) icosahedron_mesh(&m);
        else split_box_mesh(&m, 1.0, 0.7, 0.5, 9);
        s = build_one(&m, 0.08);
        if (!s) { mesh_free(&m); return; }
        T_INT_EQ(rx_flat_build(s, 0, &m, &flat), 0);
        for (i = 0; i < n; i++) {
            ex_v3_t o = ex_v3(t_rng_range(&rng, -4, 4), t_rng_range(&rng, -4, 4), t_rng_range(&rng, -4, 4));
            ex_v3_t target = ex_v3(t_rng_range(&rng, -1, 1), t_rng_range(&rng, -1, 1), t_rng_range(&rng, -1, 1));
            ex_v3_t d = ex_sub(target, o);
            double t = 0, u = 0, v = 0, oo[3], dd[3];
            unsigned tri = 0;
            re_hit_t h;
            if (ex_len(o) < 2.5 || !host_hit(&m, o, d, &t, &tri, &u, &v)) continue;
            hits++;
            oo[0] = o.x; oo[1] = o.y; oo[2] = o.z; dd[0] = d.x; dd[1] = d.y; dd[2] = d.z;
            poly_flat += rx_flat_inside(&flat, tri, ex_madd(o, d, t), 1e-9);
            if (!re__band_flat(&s->objects[0], tri, u, v)) continue;
            band_flat++;
            if (!rx_flat_inside(&flat, tri, ex_madd(o, d, t), -1e-9) || re_query(s, oo, dd, 0, tri, t, &h) != RE_UNCHANGED) {
                T_FAIL("shape %d ray %ld: the bands call a hit flat that the polygon test or re_query does not", shape, i);
                break;
            }
            T_CHECK(1);
        }
        T_GT(hits, n / 10);
        T_GT(poly_flat, hits / 5);
        T_GT(band_flat, (long)(0.95 * (double)poly_flat));
        fprintf(stderr, "    shape %d: %ld host hits, %ld flat by the polygons, %ld by the bands\n", shape, hits, poly_flat,
                band_flat);
        rx_flat_free(&flat);
        re_free(s);
        mesh_free(&m);
    }
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(tess_box_matches_analytic_rounded_box),
        T_CASE(tess_icosahedron_closed_and_converging),
        T_CASE(bands_agree_with_the_flat_polygons),
    };
    return T_RUN(argc, argv, cases);
}
