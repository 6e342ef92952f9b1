/* tests/test_rounded_input.c — rounded_edges.h: bad input (each case gets a
   clear error naming the element, or a documented skip), classification
   reports, the input variants (float, stride, polygons, several objects,
   per-edge radii), caller buffers, and the query's guards. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"

static const double LO[3] = {-0.5, -0.3, -0.2}, HI[3] = {0.5, 0.3, 0.2};

typedef struct counts_t {
    int n[16];
    char skipped[160];  /* the last skipped triangle's message */
    char boundary[160]; /* the last boundary edge's message */
} counts_t;
static void count_reports(void *u, const re_report_t *r)
{
    counts_t *c = (counts_t *)u;
    if ((int)r->kind < 16) c->n[r->kind]++;
    if (!r->message || !r->message[0]) c->n[15] = -1000; /* every report has a message */
    else if (r->kind == RE_REPORT_SKIPPED_TRIANGLE) snprintf(c->skipped, sizeof c->skipped, "%s", r->message);
    else if (r->kind == RE_REPORT_BOUNDARY_EDGE) snprintf(c->boundary, sizeof c->boundary, "%s", r->message);
}

static re_mesh_t mesh_of(const tm_mesh_t *m, double r)
{
    re_mesh_t mesh;
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = m->v, mesh.vertex_count = m->nv, mesh.indices = m->idx, mesh.index_count = m->ni, mesh.radius = r;
    return mesh;
}

static re_result_t try_build(const re_mesh_t *mesh, re_bad_input_t bad, counts_t *c, re_diag_t *dg, re_scene_t **out)
{
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_result_t rc;
    memset(&desc, 0, sizeof desc);
    desc.objects = mesh, desc.object_count = 1, desc.bad_input = bad;
    if (c) memset(c, 0, sizeof *c), desc.report = count_reports, desc.report_user = c;
    rc = re_build(&desc, &s, dg);
    if (out) *out = s;
    else re_free(s);
    if (rc != RE_OK) T_CHECK(s == NULL);
    return rc;
}

/* the box with one vertex set to v, expecting code rc naming `element`;
   under RE_BAD_INPUT_SKIP the build goes on without the triangles that
   use the vertex, each reported by number (docs: "triangle skipped,
   reported"), and their neighbours' edges turn into boundaries */
static void box_with_bad_vertex(double v, re_result_t rc)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    re_scene_t *s = NULL;
    counts_t cn;
    unsigned t, k, users = 0, last = 0;
    char want[32];
    tm_box(&m, LO, HI);
    m.v[3 * 5 + 1] = v;
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), rc);
    T_INT_EQ(dg.result, rc);
    T_INT_EQ(dg.element, 5);
    T_CHECK(strstr(dg.message, "vertex 5") != NULL);
    for (t = 0; t < m.ni / 3; t++)
        for (k = 0; k < 3; k++)
            if (m.idx[3 * t + k] == 5) users++, last = t;
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_SKIP, &cn, &dg, &s), RE_OK);
    T_INT_EQ(cn.n[RE_REPORT_SKIPPED_TRIANGLE], users);
    snprintf(want, sizeof want, "triangle %u", last);
    T_CHECK(strstr(cn.skipped, want) != NULL);
    T_GT(cn.n[RE_REPORT_BOUNDARY_EDGE], 0);
    T_GE(cn.n[15], 0);
    re_free(s);
    tm_free(&m);
}
static void nan_position(void) { box_with_bad_vertex(NAN, RE_ERR_NAN_VERTEX); }
static void inf_position(void) { box_with_bad_vertex(INFINITY, RE_ERR_NAN_VERTEX); }

static void nan_in_unused_vertex_is_ignored(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    tm_box(&m, LO, HI);
    tm_vert(&m, NAN, 0, 0); /* referenced by no triangle */
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_OK);
    tm_free(&m);
}

/* the box plus one bad triangle (index 12): rejected naming it, or skipped
   with a report that names the same, while the box still rounds all 12
   edges */
static void box_plus_triangle(unsigned a, unsigned b, unsigned c, re_result_t rc, const char *needle)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    re_scene_t *s;
    re_stats_t st;
    counts_t cn;
    tm_box(&m, LO, HI);
    tm_vert(&m, 0.1, 0.1, 0.5);
    tm_vert(&m, 0.2, 0.2, 0.5);
    tm_vert(&m, 0.3, 0.3, 0.5); /* 8, 9, 10: collinear; 11: copy of 8 */
    tm_vert(&m, 0.1, 0.1, 0.5);
    tm_tri(&m, a, b, c);
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), rc);
    T_INT_EQ(dg.element, rc == RE_ERR_INDEX_OUT_OF_RANGE || rc == RE_ERR_DEGENERATE_TRIANGLE ? 12 : dg.element);
    T_CHECK(strstr(dg.message, needle) != NULL);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_SKIP, &cn, &dg, &s), RE_OK);
    T_INT_EQ(cn.n[RE_REPORT_SKIPPED_TRIANGLE], 1);
    T_CHECK(strstr(cn.skipped, needle) != NULL);
    if (s) {
        re_get_stats(s, &st);
        T_INT_EQ(st.rounded_edges, 12);
        re_free(s);
    }
    tm_free(&m);
}
static void degenerate_repeated_index(void) { box_plus_triangle(8, 8, 9, RE_ERR_DEGENERATE_TRIANGLE, "triangle 12"); }
static void zero_area_collinear(void) { box_plus_triangle(8, 9, 10, RE_ERR_DEGENERATE_TRIANGLE, "degenerate"); }
static void zero_length_edge(void) { box_plus_triangle(8, 11, 9, RE_ERR_DEGENERATE_TRIANGLE, "zero-length"); }
static void out_of_range_index(void) { box_plus_triangle(8, 9, 99, RE_ERR_INDEX_OUT_OF_RANGE, "index 99"); }
/* both policies name the first bad index (skipping named the last) */
static void two_out_of_range_indices(void) { box_plus_triangle(8, 99, 98, RE_ERR_INDEX_OUT_OF_RANGE, "index 99"); }

/* the top face built from its own copies of the corners: the mesh is open
   along the copies (edges match by index). Documented: boundary edges and
   their vertices stay sharp, the patch loses its rounding, all reported. */
static void duplicate_vertices_make_a_seam(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    re_scene_t *s;
    re_stats_t st;
    counts_t cn;
    unsigned k, t;
    tm_box(&m, LO, HI);
    for (k = 4; k < 8; k++) tm_vert(&m, m.v[3 * k], m.v[3 * k + 1], m.v[3 * k + 2]); /* 8..11 = copies of 4..7 */
    for (t = 2; t < 4; t++) /* triangles 2, 3 are the z+ face */
        for (k = 0; k < 3; k++) m.idx[3 * t + k] += 4;
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK);
    if (s) {
        re_get_stats(s, &st);
        T_INT_EQ(st.boundary_edges, 8);
        T_INT_EQ(cn.n[RE_REPORT_BOUNDARY_EDGE], 8);
        T_GT(cn.n[RE_REPORT_MIXED_VERTEX], 0);
        T_INT_EQ(st.rounded_edges, 0);
        T_GE(cn.n[15], 0);
        T_CHECK(strstr(cn.boundary, "re_mesh_t.weld") != NULL); /* the report points at the fix */
        re_free(s);
    }
    tm_free(&m);
}

static void non_manifold_edge_left_sharp(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    re_scene_t *s;
    re_stats_t st;
    counts_t cn;
    unsigned x;
    tm_box(&m, LO, HI);
    x = tm_vert(&m, 0.9, 0, 0.6);
    tm_tri(&m, 5, 7, x); /* a fin on edge 5-7: three triangles share it */
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK);
    if (s) {
        re_get_stats(s, &st);
        T_INT_EQ(st.nonmanifold_edges, 1);
        T_INT_EQ(cn.n[RE_REPORT_NONMANIFOLD_EDGE], 1);
        re_free(s);
    }
    tm_free(&m);
}

static void open_mesh_left_sharp(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    re_scene_t *s;
    re_stats_t st;
    counts_t cn;
    re_hit_t h;
    double o[3] = {0.49, 0, 1}, d[3] = {0, 0, -1};
    tm_box(&m, LO, HI);
    m.ni -= 6; /* drop the x+ face */
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK);
    if (s) {
        re_get_stats(s, &st);
        T_INT_EQ(st.boundary_edges, 4);
        T_INT_EQ(cn.n[RE_REPORT_BOUNDARY_EDGE], 4);
        T_INT_EQ(st.mixed_vertices, 4);
        T_INT_EQ(st.rounded_edges, 0); /* the patch reaches the open rim */
        T_INT_EQ(re_query(s, o, d, 0, 2, 0.8, &h), RE_UNCHANGED);
        re_free(s);
    }
    tm_free(&m);
}

static void inconsistent_winding(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    re_scene_t *s;
    re_stats_t st;
    counts_t cn;
    unsigned x;
    tm_box(&m, LO, HI);
    x = m.idx[3 * 7 + 1], m.idx[3 * 7 + 1] = m.idx[3 * 7 + 2], m.idx[3 * 7 + 2] = x;
    mesh = mesh_of(&m, 0.05);
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_INCONSISTENT_WINDING);
    /* both triangles named: 7 and the neighbour across the edge it runs
       through the same way */
    {
        unsigned other = 0, found = 0, a, e;
        char want[64];
        for (e = 0; e < 3 && !found; e++) {
            unsigned u0 = m.idx[3 * 7 + e], u1 = m.idx[3 * 7 + (e + 1) % 3];
            for (a = 0; a < m.ni / 3; a++) {
                unsigned j;
                if (a == 7) continue;
                for (j = 0; j < 3; j++)
                    if (m.idx[3 * a + j] == u0 && m.idx[3 * a + (j + 1) % 3] == u1) other = a, found = 1;
            }
        }
        T_CHECK(found);
        snprintf(want, sizeof want, "triangles %u and %u", other < 7 ? other : 7u, other < 7 ? 7u : other);
        if (!T_CHECK(strstr(dg.message, want) != NULL)) fprintf(stderr, "    %s (want '%s')\n", dg.message, want);
        T_INT_EQ(dg.element, other < 7 ? 7 : other);
    }
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_SKIP, &cn, &dg, &s), RE_OK);
    if (s) {
        re_get_stats(s, &st);
        T_INT_EQ(st.nonmanifold_edges, 3); /* the flipped triangle's three edges */
        re_free(s);
    }
    tm_free(&m);
}

static void bad_polygon_sizes(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    unsigned sizes[3] = {4, 2, 6};
    tm_box(&m, LO, HI);
    mesh = mesh_of(&m, 0.05);
    mesh.face_sizes = sizes, mesh.face_count = 3;
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_BAD_FACE);
    T_INT_EQ(dg.element, 1);
    sizes[1] = 3; /* 13 != 36 */
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_BAD_FACE);
    mesh.face_sizes = NULL, mesh.index_count = 35;
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_BAD_FACE);
    tm_free(&m);
}

static void bad_radius(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    double r[3] = {0, -1, NAN};
    int i;
    tm_box(&m, LO, HI);
    for (i = 0; i < 3; i++) {
        mesh = mesh_of(&m, r[i]);
        T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_BAD_RADIUS);
        T_CHECK(strstr(dg.message, "radius") != NULL);
    }
    tm_free(&m);
}

/* re_mesh_t.flat_sin: 0 or in (0, RE_FLAT_SIN_LIMIT], else refused by name */
static void bad_flat_sin(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    const double bad[4] = {-1e-6, NAN, 2 * RE_FLAT_SIN_LIMIT, INFINITY};
    int i;
    tm_box(&m, LO, HI);
    mesh = mesh_of(&m, 0.05);
    for (i = 0; i < 4; i++) {
        mesh.flat_sin = bad[i];
        T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_INVALID_ARG);
        T_CHECK(strstr(dg.message, "flat_sin") != NULL);
    }
    mesh.flat_sin = RE_FLAT_SIN_LIMIT;
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_OK);
    tm_free(&m);
}

/* Doubles that carry a coarser rounding than their own: a turned box
   written with 6 decimals (an OBJ file's %f). Its quads' halves tilt by
   ~1e-6, above what doubles' rounding explains, so the automatic test
   leaves the diagonals convex or concave (documented: docs/rounded_edges.md,
   construction step 2); re_mesh_t.flat_sin = 1e-5 joins them and rounds
   the box. */
static void flat_sin_for_coarsely_rounded_doubles(void)
{
    const double c = cos(0.7), s = sin(0.7), cb = cos(0.4), sb = sin(0.4);
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *sc;
    re_diag_t dg;
    re_stats_t st;
    unsigned k;
    tm_box(&m, LO, HI);
    for (k = 0; k < m.nv; k++) {
        double *p = m.v + 3 * k, x = c * p[0] - s * p[1], y = s * p[0] + c * p[1], z = p[2];
        p[0] = round(1e6 * x) / 1e6, p[1] = round(1e6 * (cb * y - sb * z)) / 1e6, p[2] = round(1e6 * (sb * y + cb * z)) / 1e6;
    }
    mesh = mesh_of(&m, 0.05);
    if (T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, &sc), RE_OK)) {
        re_get_stats(sc, &st);
        T_LT(st.flat_edges, 6); /* the automatic test sees creases */
        T_LT(st.rounded_edges, 12);
        re_free(sc);
    }
    mesh.flat_sin = 1e-5;
    if (T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, &sc), RE_OK)) {
        re_get_stats(sc, &st);
        T_INT_EQ(st.flat_edges, 6);
        T_INT_EQ(st.concave_edges, 0);
        T_INT_EQ(st.rounded_edges, 12);
        T_INT_EQ(st.spheres, 8);
        re_free(sc);
    }
    tm_free(&m);
}

static void null_and_junk_arguments(void)
{
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_sizes_t sz;
    re_diag_t dg;
    re_mesh_t mesh;
    memset(&desc, 0, sizeof desc);
    memset(&mesh, 0, sizeof mesh);
    T_INT_EQ(re_build(NULL, &s, &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(re_build(&desc, NULL, &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(dg.result, RE_ERR_INVALID_ARG), T_CHECK(strstr(dg.message, "NULL scene") != NULL);
    desc.object_count = 1;
    T_INT_EQ(re_build(&desc, &s, &dg), RE_ERR_INVALID_ARG);
    desc.objects = &mesh;
    mesh.index_count = 3, mesh.vertex_count = 3, mesh.radius = 1; /* NULL arrays */
    T_INT_EQ(re_build(&desc, &s, &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(re_build_sizes(&desc, NULL, &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(dg.result, RE_ERR_INVALID_ARG);
    desc.radius_policy = (re_radius_policy_t)7;
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_ERR_INVALID_ARG);
    desc.radius_policy = RE_RADIUS_CLAMP;
    {   /* a stride shorter than one vertex, double and float, named */
        static const double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        static const unsigned idx[3] = {0, 1, 2};
        mesh.positions = pos, mesh.indices = idx, mesh.position_stride = 2 * sizeof(double);
        T_INT_EQ(re_build(&desc, &s, &dg), RE_ERR_INVALID_ARG);
        T_CHECK(strstr(dg.message, "position_stride") != NULL);
        mesh.position_type = RE_FLOAT32, mesh.position_stride = 2 * sizeof(float);
        T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_ERR_INVALID_ARG);
        T_CHECK(strstr(dg.message, "position_stride") != NULL);
    }
    T_CHECK(s == NULL);
    re_free(NULL);
}

static void empty_scene(void)
{
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_stats_t st;
    memset(&desc, 0, sizeof desc);
    T_INT_EQ(re_build(&desc, &s, NULL), RE_OK);
    re_get_stats(s, &st);
    T_INT_EQ(st.rounded_edges, 0);
    T_INT_EQ(re_object_count(s), 0);
    re_free(s);
}

static void result_strings(void)
{
    int i, j;
    for (i = 0; i < RE_RESULT_COUNT_; i++) {
        T_CHECK(strcmp(re_result_string((re_result_t)i), "unknown result") != 0);
        for (j = 0; j < i; j++) T_CHECK(strcmp(re_result_string((re_result_t)i), re_result_string((re_result_t)j)) != 0);
    }
    T_CHECK(strcmp(re_result_string((re_result_t)999), "unknown result") == 0);
}

static void query_guards(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *s;
    re_diag_t dg;
    re_hit_t h;
    double o[3] = {0.49, 0, 1}, d[3] = {0, 0, -1}, bad[3] = {NAN, 0, 0};
    tm_box(&m, LO, HI);
    mesh = mesh_of(&m, 0.05);
    if (!T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, &s), RE_OK)) return;
    T_INT_EQ(re_query(s, o, d, 0, 2, 0.8, &h), RE_HIT_ROUNDED); /* sanity: near the x+ top edge */
    T_INT_EQ(re_query(s, o, d, 1, 2, 0.8, &h), RE_UNCHANGED);   /* no object 1 */
    T_INT_EQ(re_query(s, o, d, 0, 12, 0.8, &h), RE_UNCHANGED);  /* no triangle 12 */
    T_INT_EQ(re_query(s, bad, d, 0, 2, 0.8, &h), RE_UNCHANGED);
    T_INT_EQ(re_query(s, o, bad, 0, 2, 0.8, &h), RE_UNCHANGED);
    T_INT_EQ(re_query(s, o, d, 0, 2, NAN, &h), RE_UNCHANGED);
    T_INT_EQ(re_query(NULL, o, d, 0, 2, 0.8, &h), RE_UNCHANGED);
    T_INT_EQ(re_query(s, o, d, 0, 2, 0.8, NULL), RE_UNCHANGED);
    T_INT_EQ(re_get_sphere(s, 0, 99999, NULL), 0);
    re_free(s);
    tm_free(&m);
}

/* same box five ways: doubles, floats with a stride, quads as polygons,
   doubles with a stride (positions interleaved with normals), caller
   buffers. Queries must agree. */
static void input_variants_agree(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh[4];
    re_scene_desc_t desc;
    re_scene_t *s[4];
    re_sizes_t sz;
    re_diag_t dg;
    float fpos[8][4];
    unsigned char dbytes[1 + 8 * 28]; /* doubles at an odd address, a stride of 28: no alignment at all */
    unsigned quads[24], sizes[6], i, k;
    void *mem, *scratch;
    t_rng_t rng = {5};
    tm_box(&m, LO, HI);
    for (i = 0; i < 8; i++) for (k = 0; k < 3; k++) fpos[i][k] = (float)m.v[3 * i + k];
    memset(dbytes, 0x7F, sizeof dbytes);
    for (i = 0; i < 8; i++) memcpy(dbytes + 1 + 28 * i, m.v + 3 * i, 3 * sizeof(double));
    for (i = 0; i < 6; i++) { /* the quad a b c d behind triangles (a b c), (a c d) */
        quads[4 * i] = m.idx[6 * i], quads[4 * i + 1] = m.idx[6 * i + 1], quads[4 * i + 2] = m.idx[6 * i + 2], quads[4 * i + 3] = m.idx[6 * i + 5];
        sizes[i] = 4;
    }
    mesh[0] = mesh_of(&m, 0.05);
    mesh[1] = mesh[0];
    mesh[1].positions = fpos, mesh[1].position_type = RE_FLOAT32, mesh[1].position_stride = sizeof fpos[0];
    mesh[2] = mesh[0];
    mesh[2].indices = quads, mesh[2].index_count = 24, mesh[2].face_sizes = sizes, mesh[2].face_count = 6;
    mesh[3] = mesh[0];
    mesh[3].positions = dbytes + 1, mesh[3].position_stride = 28;
    memset(&desc, 0, sizeof desc);
    desc.objects = mesh, desc.object_count = 4;
    T_INT_EQ(re_build(&desc, &s[0], &dg), RE_OK);
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_OK);
    mem = malloc(sz.scene_bytes), scratch = malloc(sz.scratch_bytes);
    /* each refusal fills the diagnostic with its code and a reason */
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes - 16, scratch, sz.scratch_bytes, &s[1], &dg), RE_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(dg.result, RE_ERR_BUFFER_TOO_SMALL), T_CHECK(strstr(dg.message, "scene_bytes") != NULL);
    T_INT_EQ(re_build_into(&desc, mem, 8, scratch, sz.scratch_bytes, &s[1], &dg), RE_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(dg.result, RE_ERR_BUFFER_TOO_SMALL), T_CHECK(strstr(dg.message, "scene_bytes") != NULL);
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes / 2, &s[1], &dg), RE_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(dg.result, RE_ERR_BUFFER_TOO_SMALL), T_CHECK(strstr(dg.message, "scratch") != NULL);
    T_INT_EQ(re_build_into(&desc, (char *)mem + 8, sz.scene_bytes - 16, scratch, sz.scratch_bytes, &s[1], &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(dg.result, RE_ERR_INVALID_ARG), T_CHECK(strstr(dg.message, "aligned") != NULL);
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, (char *)scratch + 4, sz.scratch_bytes - 16, &s[1], &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(dg.result, RE_ERR_INVALID_ARG), T_CHECK(strstr(dg.message, "scratch") != NULL);
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, NULL, &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(dg.result, RE_ERR_INVALID_ARG), T_CHECK(strstr(dg.message, "NULL") != NULL);
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s[1], &dg), RE_OK);
    {
        re_stats_t a, b;
        re_get_stats(s[0], &a);
        re_get_stats(s[1], &b);
        T_INT_EQ(a.bytes, b.bytes - 0); /* one block or several, same payload */
        T_INT_EQ(a.rounded_edges, 48);
        T_INT_EQ(b.spheres, 32);
    }
    for (i = 0; i < (unsigned)t_count(5000); i++) {
        double o[3], d[3], tgt[3], t;
        unsigned tri, obj, a;
        re_hit_t h0, h;
        for (a = 0; a < 3; a++) tgt[a] = t_rng_range(&rng, LO[a], HI[a]) * 1.05;
        for (a = 0; a < 3; a++) o[a] = tgt[a] + t_rng_range(&rng, -2, 2);
        tm_sub(tgt, o, d);
        if (!tm_hit(&m, o, d, &t, &tri)) continue;
        re_query(s[0], o, d, 0, tri, t, &h0);
        for (obj = 0; obj < 4; obj++) {
            /* float positions round 0.3 and 0.2 by ~1e-8 */
            double tol = obj == 1 ? 1e-6 : 1e-15;
            re_query(s[0], o, d, obj, tri, t, &h);
            if (obj != 1) T_INT_EQ(h.kind, h0.kind);
            T_NEAR(h.t, h0.t, tol);
            if (obj == 3) T_EQ(h.t, h0.t); /* the same doubles, read through the stride */
            re_query(s[1], o, d, obj, tri, t, &h);
            if (obj != 1) T_INT_EQ(h.kind, h0.kind);
            T_NEAR(h.t, h0.t, tol);
        }
    }
    re_free(s[0]);
    free(mem), free(scratch);
    tm_free(&m);
}

/* re_mesh_t.weld: a mesh whose every triangle has its own three vertices
   (a renderer's per-face normals or UVs) has nothing but boundary edges,
   so nothing is rounded; with weld = 1 it builds the welded mesh's scene:
   the same classes, radii, spheres and cylinders, and the same answer to
   every host hit (triangle ids are the host's either way), in double and
   in float positions. A NaN vertex is not welded to anything and is named
   by its own index. */
static void unweld(const tm_mesh_t *m, tm_mesh_t *u)
{
    unsigned t, k;
    for (t = 0; t < m->ni / 3; t++) {
        unsigned c[3];
        for (k = 0; k < 3; k++) {
            const double *p = m->v + 3 * m->idx[3 * t + k];
            c[k] = tm_vert(u, p[0], p[1], p[2]);
        }
        tm_tri(u, c[0], c[1], c[2]);
    }
}
static void weld_case(const tm_mesh_t *m, double r, re_scalar_t type, long nrays, unsigned long long seed)
{
    tm_mesh_t u = {0};
    re_mesh_t mesh[2];
    re_scene_t *s[2] = {NULL, NULL};
    re_stats_t st[2];
    re_diag_t dg;
    t_rng_t rng;
    float *fp[2] = {NULL, NULL};
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    long i, n_changed = 0;
    unsigned k, q;
    /* The same geometry through other vertex ids (another first vertex for
       each corner's fan): to rounding in double. The float icosphere's
       corners are near degenerate, where eroded vertices within
       RE__CORNER_MERGE (1e-7 r) are merged and which one stands for them
       follows the fan's order (measured: t within 1.9e-9, normals 3e-8). */
    const double tol = type == RE_FLOAT32 ? 1e-7 : 1e-12;
    unweld(m, &u);
    mesh[0] = mesh_of(m, r);
    mesh[1] = mesh_of(&u, r);
    if (type == RE_FLOAT32)
        for (q = 0; q < 2; q++) {
            const tm_mesh_t *src = q ? &u : m;
            fp[q] = (float *)malloc(sizeof(float) * 3 * src->nv);
            for (k = 0; k < 3 * src->nv; k++) fp[q][k] = (float)src->v[k];
            mesh[q].positions = fp[q], mesh[q].position_type = RE_FLOAT32;
        }
    T_INT_EQ(try_build(&mesh[1], RE_BAD_INPUT_REJECT, NULL, &dg, &s[1]), RE_OK);
    re_get_stats(s[1], &st[1]);
    T_INT_EQ(st[1].boundary_edges, m->ni); /* each triangle side its own edge */
    T_INT_EQ(st[1].rounded_edges, 0);
    re_free(s[1]);
    mesh[1].weld = 1;
    T_INT_EQ(try_build(&mesh[0], RE_BAD_INPUT_REJECT, NULL, &dg, &s[0]), RE_OK);
    T_INT_EQ(try_build(&mesh[1], RE_BAD_INPUT_REJECT, NULL, &dg, &s[1]), RE_OK);
    if (!s[0] || !s[1]) goto done;
    for (q = 0; q < 2; q++) re_get_stats(s[q], &st[q]);
    T_INT_EQ(st[1].boundary_edges, 0);
    T_INT_EQ(st[1].flat_edges, st[0].flat_edges);
    T_INT_EQ(st[1].convex_edges, st[0].convex_edges);
    T_INT_EQ(st[1].rounded_edges, st[0].rounded_edges);
    T_GT(st[1].rounded_edges, 0);
    T_INT_EQ(st[1].spheres, st[0].spheres);
    T_INT_EQ(st[1].cylinders, st[0].cylinders);
    T_EQ(re_object_radius(s[1], 0), re_object_radius(s[0], 0));
    for (k = 0; k < m->nv; k++)
        for (q = 0; q < 3; q++) lo[q] = fmin(lo[q], m->v[3 * k + q]), hi[q] = fmax(hi[q], m->v[3 * k + q]);
    rng.s = seed;
    for (i = 0; i < nrays; i++) {
        double o[3], d[3], tgt[3], t;
        unsigned tri;
        re_hit_t h0, h1;
        for (q = 0; q < 3; q++) tgt[q] = t_rng_range(&rng, lo[q], hi[q]) * 1.05;
        for (q = 0; q < 3; q++) o[q] = tgt[q] + t_rng_range(&rng, -2, 2) * (hi[q] - lo[q]);
        tm_sub(tgt, o, d);
        if (!tm_hit(m, o, d, &t, &tri)) continue;
        re_query(s[0], o, d, 0, tri, t, &h0);
        re_query(s[1], o, d, 0, tri, t, &h1);
        n_changed += h0.kind != RE_UNCHANGED;
        if (!T_INT_EQ(h1.kind, h0.kind)) continue;
        T_NEAR(h1.t, h0.t, tol * (1 + fabs(h0.t)));
        for (q = 0; q < 3; q++) T_NEAR(h1.normal[q], h0.normal[q], 10 * tol);
    }
    T_GT(n_changed, nrays / 20);
done:
    re_free(s[0]), re_free(s[1]);
    free(fp[0]), free(fp[1]);
    tm_free(&u);
}
static void unwelded_mesh_rounds_with_weld(void)
{
    tm_mesh_t m = {0}, u = {0};
    re_mesh_t mesh;
    re_diag_t dg;
    tm_box(&m, LO, HI);
    weld_case(&m, 0.05, RE_FLOAT64, t_count(20000), 11);
    weld_case(&m, 0.05, RE_FLOAT32, t_count(20000), 12);
    unweld(&m, &u);
    u.v[3 * 5 + 1] = NAN; /* the second corner of triangle 1 */
    mesh = mesh_of(&u, 0.05);
    mesh.weld = 1;
    T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, NULL), RE_ERR_NAN_VERTEX);
    T_INT_EQ(dg.element, 5);
    tm_free(&u);
    tm_free(&m);
    tm_icosphere(&m, 2, 1.0);
    weld_case(&m, 0.08, RE_FLOAT64, t_count(20000), 13);
    weld_case(&m, 0.08, RE_FLOAT32, t_count(20000), 14);
    tm_free(&m);
}

/* re_build()'s huge-page advice (MEMORY, at the header's top) covers the
   whole 2 MiB pages inside a block and never a byte outside it; blocks
   under two huge pages are left alone. */
static void huge_page_range_inside_the_block(void)
{
    const size_t H = (size_t)2 << 20;
    t_rng_t rng = {77};
    long i, n_bad = 0, n_advised = 0;
    for (i = 0; i < t_count(200000); i++) {
        size_t p = (size_t)(t_rng_u64(&rng) >> 24) * 16, n = (size_t)(t_rng_u64(&rng) % (24ull << 20)), a, b;
        if (i % 4 == 1) p = (p / H) * H;                   /* aligned starts */
        if (i % 8 == 2) n = 2 * H - 1 + (size_t)(i % 3);  /* around the smallest advised size */
        if (i % 16 == 3) p = (size_t)-1 - n / 2;           /* would wrap */
        re__huge_range(p, n, &a, &b);
        if (n < 2 * H || p > (size_t)-1 - n) n_bad += a != b;
        else {
            n_advised++;
            n_bad += !(b > a && a % H == 0 && b % H == 0 && a >= p && b <= p + n && a - p < H && p + n - b < H);
        }
    }
    T_INT_EQ(n_bad, 0);
    T_GT(n_advised, t_count(200000) / 2);
}

/* The kernel's flags of the mapping holding address a (Linux), or "". */
static void mapping_flags(size_t a, char *flags, size_t cap)
{
    FILE *f = fopen("/proc/self/smaps", "r");
    char line[512];
    int in = 0;
    flags[0] = 0;
    if (!f) return;
    while (fgets(line, sizeof line, f)) {
        unsigned long long lo, hi;
        if (sscanf(line, "%llx-%llx ", &lo, &hi) == 2 && strchr(line, '-') < strchr(line, ' ')) in = lo <= a && a < hi;
        else if (in && !strncmp(line, "VmFlags:", 8)) {
            size_t n = strlen(line + 8);
            if (n >= cap) n = cap - 1;
            memcpy(flags, line + 8, n);
            flags[n] = 0;
            break;
        }
    }
    fclose(f);
}

/* A scene whose blocks get the huge-page advice: re_build() answers as
   re_build_into() does into plain buffers, feature for feature, and on a
   Linux kernel with transparent huge pages the scene block's mapping
   carries the advice (VmFlags "hg"). */
static void large_build_with_huge_pages_matches_into(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s0 = NULL, *s1 = NULL;
    re_sizes_t sz;
    re_diag_t dg;
    re_stats_t a, b;
    void *mem, *scratch;
    unsigned i, n_diff = 0;
    for (i = 0; i < 7000; i++) {
        double lo[3], hi[3];
        lo[0] = (i % 100) * 1.5, lo[1] = (i / 100) * 1.5, lo[2] = 0;
        hi[0] = lo[0] + 1, hi[1] = lo[1] + 0.7, hi[2] = 0.5;
        tm_box(&m, lo, hi);
    }
    mesh = mesh_of(&m, 0.02);
    memset(&desc, 0, sizeof desc);
    desc.objects = &mesh, desc.object_count = 1;
    T_INT_EQ(re_build(&desc, &s0, &dg), RE_OK);
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_OK);
    T_GT(sz.scene_bytes, 4u << 20);
    mem = malloc(sz.scene_bytes), scratch = malloc(sz.scratch_bytes);
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s1, &dg), RE_OK);
    if (!s0 || !s1) goto done;
    re_get_stats(s0, &a), re_get_stats(s1, &b);
    T_INT_EQ(a.spheres, b.spheres);
    T_INT_EQ(a.cylinders, b.cylinders);
    T_INT_EQ(a.rounded_edges, 7000 * 12);
    for (i = 0; i < re_sphere_count(s0, 0); i++) {
        re_sphere_t p, q;
        re_get_sphere(s0, 0, i, &p), re_get_sphere(s1, 0, i, &q);
        n_diff += memcmp(p.center, q.center, sizeof p.center) != 0 || p.radius != q.radius || p.vertex != q.vertex;
    }
    for (i = 0; i < re_cylinder_count(s0, 0); i++) {
        re_cylinder_t p, q;
        re_get_cylinder(s0, 0, i, &p), re_get_cylinder(s1, 0, i, &q);
        n_diff += memcmp(p.a, q.a, sizeof p.a) != 0 || memcmp(p.b, q.b, sizeof p.b) != 0 || p.sa != q.sa || p.sb != q.sb;
    }
    T_INT_EQ(n_diff, 0);
#if defined(RE__HUGEPAGES)
    {
        FILE *thp = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
        if (thp) {
            size_t lo, hi;
            char flags[256];
            fclose(thp);
            re__huge_range((size_t)s0->objects[0].block, s0->objects[0].bytes, &lo, &hi);
            T_CHECK(hi > lo);
            mapping_flags(lo, flags, sizeof flags);
            if (!strstr(flags, " hg")) T_FAIL("scene block at %#zx: VmFlags '%s' lack hg (no huge-page advice)", lo, flags);
        }
    }
#endif
done:
    re_free(s0);
    free(mem), free(scratch);
    tm_free(&m);
}

/* two boxes in one object with their own radii; a third box where one edge
   asks for less: its patch takes the smallest (reported) */
static void per_edge_radius(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *s;
    re_diag_t dg;
    counts_t cn;
    double lo2[3] = {2, 0, 0}, hi2[3] = {3, 1, 1}, lo3[3] = {5, 0, 0}, hi3[3] = {6, 1, 1}, *er;
    unsigned i, n;
    tm_box(&m, LO, HI);
    tm_box(&m, lo2, hi2);
    tm_box(&m, lo3, hi3);
    er = (double *)malloc(sizeof(double) * m.ni);
    for (i = 0; i < m.ni; i++) er[i] = i < 36 ? 0.05 : i < 72 ? 0.1 : 0.2;
    er[72] = 0.15; /* one half-edge of box 3 (its edge 16-18) asks for less */
    mesh = mesh_of(&m, 0);
    mesh.edge_radius = er;
    if (T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK)) {
        n = re_sphere_count(s, 0);
        T_INT_EQ(n, 24);
        for (i = 0; i < n; i++) {
            re_sphere_t sp;
            re_get_sphere(s, 0, i, &sp);
            T_EQ(sp.radius, sp.vertex < 8 ? 0.05 : sp.vertex < 16 ? 0.1 : 0.15);
        }
        T_INT_EQ(cn.n[RE_REPORT_RADIUS_MISMATCH], 1);
        re_free(s);
    }
    /* an edge whose radius is not given (<= 0, NaN; infinite counts as
       none) with no object radius to fall back to: RE_ERR_BAD_RADIUS
       naming one of the edge's vertices */
    {
        static const double bad[3] = {-1.0, NAN, INFINITY};
        for (i = 0; i < 3; i++) {
            unsigned k, t = 12; /* box 2's first triangle: its edge 0 is a box edge */
            er[3 * t] = bad[i];
            for (k = 0; k < m.ni; k++)
                if (k != 3 * t && m.idx[k] == m.idx[3 * t + 1] && m.idx[k % 3 == 2 ? k - 2 : k + 1] == m.idx[3 * t])
                    er[k] = bad[i]; /* the edge's other half-edge too */
            T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_ERR_BAD_RADIUS);
            T_CHECK(dg.element == (long long)m.idx[3 * t] || dg.element == (long long)m.idx[3 * t + 1]);
            T_CHECK(strstr(dg.message, "radius") != NULL);
            for (k = 0; k < m.ni; k++) er[k] = k < 36 ? 0.05 : k < 72 ? 0.1 : 0.2;
        }
    }
    free(er);
    tm_free(&m);
}

/* A pyramid over a 70-gon: its apex has 70 face planes, more than
   RE_MAX_CORNER_PLANES. It stays sharp and is reported once as a complex
   corner, with a message; the rounded patch it belongs to (every edge of
   the pyramid: they are linked through the base corners) stays sharp, each
   edge reported, and nothing is stored. */
static void corner_over_the_plane_limit_reported(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    counts_t cn;
    unsigned i, k = 70, apex;
    T_CHECK(k > RE_MAX_CORNER_PLANES);
    for (i = 0; i < k; i++) tm_vert(&m, cos(2 * M_PI * i / k), sin(2 * M_PI * i / k), 0);
    apex = tm_vert(&m, 0.1, 0.05, 0.8);
    for (i = 0; i < k; i++) tm_tri(&m, i, (i + 1) % k, apex);
    for (i = 1; i + 1 < k; i++) tm_tri(&m, 0, i + 1, i);
    mesh = mesh_of(&m, 0.01);
    if (T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK)) {
        re_get_stats(s, &st);
        T_INT_EQ(cn.n[RE_REPORT_COMPLEX_CORNER], 1);
        T_INT_EQ(cn.n[RE_REPORT_SHARP_PATCH_EDGE], 2 * (int)k);
        T_INT_EQ(cn.n[15], 0); /* every report has a message */
        T_INT_EQ(st.convex_edges, 2 * k);
        T_INT_EQ(st.rounded_edges, 0);
        T_INT_EQ(re_sphere_count(s, 0), 0);
        T_INT_EQ(re_cylinder_count(s, 0), 0);
        re_free(s);
    }
    tm_free(&m);
}

/* an L-shaped prism: the re-entrant edge is concave, its ends are mixed;
   both are reported and nothing is faked there */
static void concave_edges_and_mixed_vertices_reported(void)
{
    static const double q[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    counts_t cn;
    unsigned i;
    /* extrude by hand: the fan must start at the reflex vertex 3 */
    for (i = 0; i < 6; i++) tm_vert(&m, q[i][0], q[i][1], 0);
    for (i = 0; i < 6; i++) tm_vert(&m, q[i][0], q[i][1], 1);
    for (i = 0; i < 6; i++) tm_quad(&m, i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6);
    for (i = 1; i < 5; i++) {
        unsigned a = (3 + i) % 6, b = (3 + i + 1) % 6;
        tm_tri(&m, 3, b, a);
        tm_tri(&m, 9, a + 6, b + 6);
    }
    mesh = mesh_of(&m, 0.05);
    if (T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK)) {
        re_get_stats(s, &st);
        T_INT_EQ(st.concave_edges, 1);
        T_INT_EQ(cn.n[RE_REPORT_CONCAVE_EDGE], 1);
        T_INT_EQ(st.mixed_vertices, 2);
        T_INT_EQ(cn.n[RE_REPORT_MIXED_VERTEX], 2);
        T_INT_EQ(st.convex_edges, 17); /* 12 outline + 5 vertical */
        T_INT_EQ(st.rounded_edges, 0);  /* one patch, reaching the mixed vertices */
        T_INT_EQ(cn.n[RE_REPORT_SHARP_PATCH_EDGE], 17); /* each convex edge left sharp is named */
        re_free(s);
    }
    /* no more than the patch: a separate box in the same mesh is still rounded */
    {
        const double lo[3] = {3, 0, 0}, hi[3] = {4, 1, 1};
        tm_box(&m, lo, hi);
        mesh = mesh_of(&m, 0.05);
        if (T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, &cn, &dg, &s), RE_OK)) {
            re_get_stats(s, &st);
            T_INT_EQ(st.rounded_edges, 12);
            T_INT_EQ(cn.n[RE_REPORT_SHARP_PATCH_EDGE], 17);
            T_INT_EQ(cn.n[RE_REPORT_MIXED_VERTEX], 2);
            re_free(s);
        }
    }
    tm_free(&m);
}

/* 2^30 triangles or more are too many for the 32-bit counters (4 T bands
   per triangle); with polygons that was checked, a plain triangle list of
   up to 1.4e9 triangles was not (found by review, 2026-12-06: not run, it
   needs 13 GB of indices). Rejected before any index is read. */
static void huge_triangle_count_rejected(void)
{
    static const double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const unsigned idx[3] = {0, 1, 2};
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_sizes_t sz;
    re_diag_t dg;
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = pos, mesh.vertex_count = 3, mesh.indices = idx, mesh.radius = 0.1;
    mesh.index_count = 3u * 0x40000000u; /* only the count: nothing past idx[2] may be read */
    desc.objects = &mesh, desc.object_count = 1;
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_ERR_TOO_LARGE);
    T_INT_EQ(dg.result, RE_ERR_TOO_LARGE);
}

/* re_secondary_origin() puts I'' on the sharp mesh, just outside */
static void secondary_origin_on_the_sharp_mesh(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng = {9};
    long i, n = 0, n_tangent = 0;
    tm_box(&m, LO, HI);
    mesh = mesh_of(&m, 0.05);
    if (!T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, &s), RE_OK)) return;
    for (i = 0; i < t_count(20000); i++) {
        double o[3], d[3], tgt[3], t, dir[3], org[3], dist = HUGE_VAL, inside = -HUGE_VAL;
        unsigned tri, a;
        re_hit_t h;
        for (a = 0; a < 3; a++) tgt[a] = (t_rng_unit(&rng) < 0.5 ? LO[a] : HI[a]) * t_rng_range(&rng, 0.85, 1.0);
        for (a = 0; a < 3; a++) o[a] = tgt[a] * 4 + t_rng_range(&rng, -0.5, 0.5);
        tm_sub(tgt, o, d);
        if (!tm_hit(&m, o, d, &t, &tri)) continue;
        if (re_query(s, o, d, 0, tri, t, &h) != RE_HIT_ROUNDED) continue;
        /* a reflected direction leaves the rounded surface */
        {
            double dn = tm_dot(d, h.normal);
            for (a = 0; a < 3; a++) dir[a] = d[a] - 2 * dn * h.normal[a];
        }
        re_secondary_origin(s, &h, dir, org);
        /* on the sharp box (distance to its surface <= 1e-8), just outside */
        for (a = 0; a < 3; a++) {
            inside = fmax(inside, fmax(org[a] - HI[a], LO[a] - org[a]));
            dist = fmin(dist, fmin(fabs(org[a] - HI[a]), fabs(org[a] - LO[a])));
        }
        T_GE(inside, 0.0);
        T_LE(inside, 1e-8);
        /* a direction into the solid (refraction; outside the documented
           use) gets the hit point itself: the exit walk had sent such
           origins up to 60 sizes away (found by review, 2026-12-06) */
        for (a = 0; a < 3; a++) dir[a] = d[a] / tm_len(d) - 0.3 * h.normal[a];
        re_secondary_origin(s, &h, dir, org);
        T_CHECK(org[0] == h.point[0] && org[1] == h.point[1] && org[2] == h.point[2]);
        /* a tangent direction ((-n_y, n_x, 0): dir . normal is 0, or a
           rounding of the products either way) leaves: pushed outside the
           box like a reflection. An exactly tangent one got the unpushed
           hit point before 2026-12-06 (found by fuzz_rounded_exact) */
        if (fabs(h.normal[0]) + fabs(h.normal[1]) > 0.1) {
            dir[0] = -h.normal[1], dir[1] = h.normal[0], dir[2] = 0;
            re_secondary_origin(s, &h, dir, org);
            inside = -HUGE_VAL;
            for (a = 0; a < 3; a++) inside = fmax(inside, fmax(org[a] - HI[a], LO[a] - org[a]));
            T_GT(inside, 0.0);
            T_LE(inside, 1e-8);
            n_tangent++;
        }
        n++;
    }
    T_GT(n, 100);
    T_GT(n_tangent, 10);
    re_free(s);
    tm_free(&m);
}

/* re_secondary_origin() on random convex hulls of 4 to 12 points, radii
   from 1e-3 of the size to the largest valid one (the eroded polytope then
   a point or a segment, every corner's sphere in one place): rays reflected
   at rounded hits, some grazing a face for long, must start on the sharp
   hull, outside it by the push (RE_ORIGIN_OFFSET_REL of the diagonal,
   between 1 and sqrt(3) times the size) and on their ray to the push, up
   to a few ulps of the coordinates. Until 2026-12-05 the exit took the
   planes of the hit feature's corners only: 19 origins of 18 205 rounded
   hits were past the hull's true exit (up to 0.4 of the size out, the ray
   leaving through a neighbouring corner's face first) or left inside it
   (no plane of the corner ahead of the ray). */
static void secondary_origin_on_random_hulls(void)
{
    t_rng_t rng = {77};
    long hull, i, n_hits = 0, n_bad = 0;
    double worst = 0;
    for (hull = 0; hull < t_count(300); hull++) {
        static tm_poly_t P;
        tm_mesh_t m = {0};
        re_mesh_t mesh;
        re_scene_t *s = NULL;
        re_diag_t dg;
        double scale, lo, hi;
        tm_random_hull(&rng, 4 + (int)(hull % 9), 0.3, 1.0, &m, &P);
        scale = tm_size(m.v, m.nv);
        lo = RE_ORIGIN_OFFSET_REL * scale, hi = RE_ORIGIN_OFFSET_REL * sqrt(3.0) * scale;
        mesh = mesh_of(&m, hull % 3 == 0 ? 10 * scale : scale * t_rng_range(&rng, 1e-3, 0.1));
        if (!T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, &s), RE_OK)) {
            tm_free(&m);
            continue;
        }
        for (i = 0; i < 410; i++) {
            double dir[3], tgt[3], o[3], t, d2[3], org[3], w[3], dn, out, off_line, tol;
            const double *vx = m.v + 3 * (size_t)(t_rng_u64(&rng) % m.nv);
            unsigned tri, a;
            re_hit_t h;
            tm_rand_dir(&rng, dir);
            tm_rand_dir(&rng, w);
            for (a = 0; a < 3; a++) tgt[a] = vx[a] + 0.2 * scale * t_rng_unit(&rng) * w[a], o[a] = tgt[a] - 3 * scale * dir[a];
            if (!tm_hit(&m, o, dir, &t, &tri) || re_query(s, o, dir, 0, tri, t, &h) != RE_HIT_ROUNDED) continue;
            dn = tm_dot(dir, h.normal);
            for (a = 0; a < 3; a++) d2[a] = dir[a] - 2 * dn * h.normal[a];
            re_secondary_origin(s, &h, d2, org);
            tol = 8 * DBL_EPSILON * (scale + fabs(org[0]) + fabs(org[1]) + fabs(org[2]));
            n_hits++;
            if (!tm_origin_ok(&P, org, h.point, d2, lo, hi, tol, &out, &off_line)) n_bad++;
            worst = fmax(worst, fmax(fabs(out - 0.5 * (lo + hi)), off_line) / scale);
        }
        re_free(s);
        tm_free(&m);
    }
    fprintf(stderr, "  secondary origins: %ld of %ld off the sharp hull or their ray (worst %.3g of the size)\n", n_bad, n_hits, worst);
    T_INT_EQ(n_bad, 0);
    T_GT(n_hits, t_count(300) * 20); /* about 60 a hull */
}

/* the enumeration a tessellator reads: the box's inner box corners as
   spheres, its 12 edges as cylinders between them, arcs between face normals */
static void enumeration_of_box_features(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_t *s;
    re_diag_t dg;
    unsigned i;
    int a;
    tm_box(&m, LO, HI);
    mesh = mesh_of(&m, 0.05);
    if (!T_INT_EQ(try_build(&mesh, RE_BAD_INPUT_REJECT, NULL, &dg, &s), RE_OK)) return;
    T_INT_EQ(re_object_count(s), 1);
    T_INT_EQ(re_sphere_count(s, 0), 8);
    T_INT_EQ(re_cylinder_count(s, 0), 12);
    for (i = 0; i < 8; i++) {
        re_sphere_t sp;
        T_CHECK(re_get_sphere(s, 0, i, &sp));
        T_EQ(sp.radius, 0.05);
        for (a = 0; a < 3; a++) T_NEAR(fabs(sp.center[a]), HI[a] - 0.05, 1e-15);
        for (a = 0; a < 3; a++) T_EQ(sp.center[a] > 0, m.v[3 * sp.vertex + a] > 0); /* its own corner */
    }
    for (i = 0; i < 12; i++) {
        re_cylinder_t cy;
        re_sphere_t sa, sb;
        double ab[3], el[3];
        T_CHECK(re_get_cylinder(s, 0, i, &cy));
        re_get_sphere(s, 0, cy.sa, &sa);
        re_get_sphere(s, 0, cy.sb, &sb);
        for (a = 0; a < 3; a++) T_EQ(cy.a[a], sa.center[a]), T_EQ(cy.b[a], sb.center[a]);
        T_NEAR(tm_dot(cy.n0, cy.n1), 0.0, 1e-15); /* a right-angle edge: a quarter arc */
        T_GE(cy.edge_v0, 0);
        tm_sub(cy.b, cy.a, ab);
        tm_sub(m.v + 3 * cy.edge_v1, m.v + 3 * cy.edge_v0, el);
        T_NEAR(tm_len(ab), tm_len(el) - 0.1, 1e-15); /* set back by r at both ends */
    }
    T_INT_EQ(re_get_cylinder(s, 0, 12, NULL), 0);
    re_free(s);
    tm_free(&m);
}

/* random soups: few vertices, many triangles (bowties, fins, folds,
   repeated faces), both policies; the build and queries must neither crash
   nor read out of bounds (the ASan pass), and a rejected build names an
   element. */
static void random_soups_do_not_crash(void)
{
    t_rng_t rng = {99};
    int it, nit = (int)t_count(400);
    long built = 0;
    for (it = 0; it < nit; it++) {
        tm_mesh_t m = {0};
        re_mesh_t mesh;
        re_scene_t *s;
        re_diag_t dg;
        unsigned nv = 4 + (unsigned)(t_rng_u64(&rng) % 12), nt = 2 + (unsigned)(t_rng_u64(&rng) % 40), i;
        re_result_t rc;
        for (i = 0; i < nv; i++)
            tm_vert(&m, (double)(t_rng_u64(&rng) % 5), (double)(t_rng_u64(&rng) % 5), (double)(t_rng_u64(&rng) % 5));
        if (it % 3 == 0) { tm_free(&m); tm_icosphere(&m, 0, 1.0); nv = m.nv; } /* a closed start, then damage */
        for (i = 0; i < nt; i++)
            tm_tri(&m, (unsigned)(t_rng_u64(&rng) % (nv + (it % 7 == 0))), (unsigned)(t_rng_u64(&rng) % nv), (unsigned)(t_rng_u64(&rng) % nv));
        mesh = mesh_of(&m, t_rng_range(&rng, 0.01, 2.0));
        rc = try_build(&mesh, it % 2 ? RE_BAD_INPUT_SKIP : RE_BAD_INPUT_REJECT, NULL, &dg, &s);
        if (rc != RE_OK) {
            T_CHECK(dg.message[0] != 0);
            tm_free(&m);
            continue;
        }
        built++;
        for (i = 0; i < 200; i++) {
            double o[3], d[3];
            re_hit_t h;
            int a;
            for (a = 0; a < 3; a++) o[a] = t_rng_range(&rng, -3, 8), d[a] = t_rng_range(&rng, -1, 1);
            re_query(s, o, d, 0, (unsigned)(t_rng_u64(&rng) % (m.ni / 3 + 1)), t_rng_range(&rng, 0, 3), &h);
            T_CHECK(h.kind == RE_UNCHANGED || h.kind == RE_HIT_ROUNDED || h.kind == RE_PASS_THROUGH);
        }
        re_free(s);
        tm_free(&m);
    }
    T_GT(built, nit / 10);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(nan_position), T_CASE(inf_position), T_CASE(nan_in_unused_vertex_is_ignored),
        T_CASE(degenerate_repeated_index), T_CASE(zero_area_collinear), T_CASE(zero_length_edge),
        T_CASE(out_of_range_index), T_CASE(two_out_of_range_indices), T_CASE(duplicate_vertices_make_a_seam), T_CASE(non_manifold_edge_left_sharp),
        T_CASE(open_mesh_left_sharp), T_CASE(inconsistent_winding), T_CASE(bad_polygon_sizes), T_CASE(bad_radius), T_CASE(bad_flat_sin), T_CASE(flat_sin_for_coarsely_rounded_doubles),
        T_CASE(null_and_junk_arguments), T_CASE(empty_scene), T_CASE(result_strings), T_CASE(query_guards),
        T_CASE(input_variants_agree), T_CASE(unwelded_mesh_rounds_with_weld), T_CASE(huge_page_range_inside_the_block),
        T_CASE(large_build_with_huge_pages_matches_into), T_CASE(per_edge_radius), T_CASE(corner_over_the_plane_limit_reported),
        T_CASE(concave_edges_and_mixed_vertices_reported),
        T_CASE(huge_triangle_count_rejected), T_CASE(secondary_origin_on_the_sharp_mesh), T_CASE(secondary_origin_on_random_hulls), T_CASE(enumeration_of_box_features),
        T_CASE(random_soups_do_not_crash),
    };
    return T_RUN(argc, argv, cases);
}
