/* tests/test_rounded_packing.c — rounded_edges.h storage fallbacks that the
   benchmark scenes seldom or never take: with the spans forced tiny, most
   packed id blocks are stored whole (re__pk_t), the kd leaf lists are cut
   into many 16-bit runs (re__kd_narrow), and in the compact layout most
   edge cylinders keep their second sphere in the sorted far list
   (re__cyl_s1) and every sphere centre whose plane slots reach 3 is
   stored and found by rank (re__xsph_rank). The exactness batteries must still hold: the box
   against the analytic rounded box, random hulls against the eroded
   polytope, in both layouts. re_build()'s first scratch guess is cut to
   almost nothing, so every object is analysed again with twice the
   scratch until it fits (re__build_object); the reports must not repeat.
   And a block's bytes, alignment padding included, do not depend on what
   the memory held before (the allocator here fills every block with
   test_fill_byte, tests/test_fill_alloc.h). */
#define RE__SCRATCH_PER_TRIANGLE 8u
#define RE__SCRATCH_BASE 64u
#define RE__PK_SPAN 2u
#define RE__LEAF_RUN_SPAN 3u
#define RE__SOLVED_SLOTS 3u
#define RE__DS1_SPAN 2u
#include "test_fill_alloc.h"
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"

/* How many of the fallbacks a built scene uses: full packed blocks (of the
   corners' first references), continued kd leaf runs, far second spheres,
   stored centres. */
static void count_fallbacks(const re_scene_t *s, unsigned *full, unsigned *runs, unsigned *far, unsigned *stored)
{
    const re__object_t *o = &s->objects[0];
    unsigned b, n;
    for (b = 0; b * RE__PK_BLOCK < o->n_corners; b++) *full += o->k_first.base[b] & RE__PK_FULL ? 1u : 0u;
    for (n = 0; n < o->n_nodes; n++)
        if ((o->nodes[n].info & 3u) == 3u) *runs += o->leaf16[o->nodes[n].info >> 2] >> 15;
    *far += o->n_xs1;
    *stored += o->compact ? o->n_xsph : 0u;
}

/* The reports of re_build() (short scratch: retried) and re_build_sizes()
   (retried too) against re_build_into() with exact buffers (never
   retried): the same sequence, once each. An open box (boundary edges,
   mixed vertices, its convex edges left sharp) and a thin box whose
   radius is clamped: reports from steps 2, 4, 5 and 7 of the build. */
typedef struct rep_log_t {
    int n;
    char line[64][200];
} rep_log_t;
static void log_report(void *u, const re_report_t *r)
{
    rep_log_t *l = (rep_log_t *)u;
    if (l->n < 64) snprintf(l->line[l->n], sizeof l->line[0], "%d %lld %lld %.17g %s", (int)r->kind, r->element, r->element2, r->value, r->message);
    l->n++;
}
static void scratch_retries_repeat_no_report(void)
{
    tm_mesh_t m = {0};
    double lo[3] = {-0.5, -0.3, -0.2}, hi[3] = {0.5, 0.3, 0.2}, lo2[3] = {2, 0, 0}, hi2[3] = {3, 1, 0.04};
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_sizes_t sz;
    re_diag_t dg;
    static rep_log_t want, got;
    void *mem, *scratch;
    int i;
    tm_box(&m, lo, hi);
    m.ni -= 6; /* open: no x+ face */
    tm_box(&m, lo2, hi2);
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.radius = 0.05;
    desc.objects = &mesh, desc.object_count = 1, desc.report = log_report;
    desc.report_user = &got;
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_OK);
    T_GT(sz.scratch_bytes, 4 * (128u * m.nv + RE__SCRATCH_PER_TRIANGLE * m.ni / 3 + RE__SCRATCH_BASE)); /* at least two retries */
    mem = malloc(sz.scene_bytes), scratch = malloc(sz.scratch_bytes);
    desc.report_user = &want, want.n = 0;
    T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s, &dg), RE_OK);
    T_GT(want.n, 8);
    T_LE(want.n, 64);
    for (i = 0; i < 2; i++) {
        got.n = 0;
        desc.report_user = &got;
        if (i == 0) {
            re_scene_t *s2 = NULL;
            T_INT_EQ(re_build(&desc, &s2, &dg), RE_OK);
            re_free(s2);
        } else
            T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_OK);
        if (T_INT_EQ(got.n, want.n)) {
            int k;
            for (k = 0; k < want.n && k < 64; k++) T_CHECK(strcmp(got.line[k], want.line[k]) == 0);
        }
    }
    free(mem), free(scratch);
    tm_free(&m);
}

static void packing_fallbacks_box(void)
{
    double lo[3] = {-0.5, -0.3, -0.2}, hi[3] = {0.5, 0.3, 0.2};
    box_rays(lo, hi, 0.05, t_count(20000), 1e-9, 21);
}

/* Random hulls (vertices of degree 3 to 8) against the eroded polytope. */
static void packing_fallbacks_hulls(void)
{
    t_rng_t rng = {29};
    int it, nit = (int)t_count(8);
    unsigned full = 0, runs = 0, far = 0, stored = 0;
    for (it = 0; it < nit; it++) {
        int n = 24 + (int)(t_rng_u64(&rng) % 16);
        tm_mesh_t m = {0};
        static tm_poly_t P;
        re_scene_t *s;
        re_diag_t dg;
        tm_random_hull(&rng, n, 0.9, 1.1, &m, &P);
        s = build1(&m, 0.02, &dg);
        T_CHECK(s != NULL);
        if (s) count_fallbacks(s, &full, &runs, &far, &stored), re_free(s);
        poly_rays(&m, &P, 0.02, t_count(1500), 1e-7, 300 + (unsigned long long)it, "hull (packing fallbacks)");
        tm_free(&m);
    }
    /* the fallbacks ran */
    T_GT(full, 0);
    T_GT(runs, 0);
    if (g_layout == RE_LAYOUT_COMPACT) T_GT(far, 0), T_GT(stored, 0); /* the fast layout keeps both whole */
}

static void compact_layout_packing_fallbacks_box(void) { with_compact_layout(packing_fallbacks_box); }
static void compact_layout_packing_fallbacks_hulls(void) { with_compact_layout(packing_fallbacks_hulls); }

/* The same mesh built into memory that held 0x00 and 0xFF before: every
   block the same bytes (re_build()), and the packed part of the caller's
   buffer the same (re_build_into()), and the whole buffer when built again
   at the same address (until 2026-12-05 the 8 bytes between the header's
   object records and the first array were left as found), in both
   layouts: a box, a random hull and an icosphere, with the fallbacks above
   (many arrays, many gaps). */
static void blocks_do_not_depend_on_fresh_memory(void)
{
    t_rng_t rng = {41};
    tm_mesh_t m[3];
    static tm_poly_t P;
    double lo[3] = {-0.5, -0.3, -0.2}, hi[3] = {0.5, 0.3, 0.2};
    unsigned k, lay, n_same = 0, n_into = 0, n_whole = 0;
    memset(m, 0, sizeof m);
    tm_box(&m[0], lo, hi);
    tm_random_hull(&rng, 30, 0.9, 1.1, &m[1], &P);
    tm_icosphere(&m[2], 2, 1.0);
    for (lay = 0; lay < 2; lay++)
        for (k = 0; k < 3; k++) {
            re_mesh_t mesh;
            re_scene_desc_t d;
            re_scene_t *s[2] = {NULL, NULL};
            re_sizes_t z;
            re_diag_t dg;
            unsigned char *mem[2], *scr[2];
            int f;
            memset(&mesh, 0, sizeof mesh);
            memset(&d, 0, sizeof d);
            mesh.positions = m[k].v, mesh.vertex_count = m[k].nv, mesh.indices = m[k].idx, mesh.index_count = m[k].ni, mesh.radius = 0.03;
            d.objects = &mesh, d.object_count = 1, d.layout = lay ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
            for (f = 0; f < 2; f++) {
                test_fill_byte = f ? 0xFF : 0x00;
                T_INT_EQ(re_build(&d, &s[f], &dg), RE_OK);
            }
            test_fill_byte = 0xA5;
            if (s[0] && s[1] && T_INT_EQ(s[0]->objects[0].bytes, s[1]->objects[0].bytes))
                n_same += memcmp(s[0]->objects[0].block, s[1]->objects[0].block, s[0]->objects[0].bytes) == 0;
            re_free(s[0]), re_free(s[1]);
            if (!T_INT_EQ(re_build_sizes(&d, &z, &dg), RE_OK)) continue;
            for (f = 0; f < 2; f++) {
                mem[f] = (unsigned char *)malloc(z.scene_bytes), scr[f] = (unsigned char *)malloc(z.scratch_bytes + 1);
                memset(mem[f], f ? 0xFF : 0x00, z.scene_bytes), memset(scr[f], f ? 0xFF : 0x00, z.scratch_bytes + 1);
                T_INT_EQ(re_build_into(&d, mem[f], z.scene_bytes, scr[f], z.scratch_bytes, &s[f], &dg), RE_OK);
            }
            {
                size_t h = re__header_bytes(1);
                n_into += memcmp(mem[0] + h, mem[1] + h, z.scene_bytes - h) == 0;
            }
            /* again into the first buffer, filled with 0xFF: all of it the
               same, the header's alignment gaps too (its pointers are) */
            memcpy(mem[1], mem[0], z.scene_bytes);
            memset(mem[0], 0xFF, z.scene_bytes);
            T_INT_EQ(re_build_into(&d, mem[0], z.scene_bytes, scr[1], z.scratch_bytes, &s[0], &dg), RE_OK);
            n_whole += memcmp(mem[0], mem[1], z.scene_bytes) == 0;
            for (f = 0; f < 2; f++) free(mem[f]), free(scr[f]);
        }
    T_INT_EQ(n_same, 6);
    T_INT_EQ(n_into, 6);
    T_INT_EQ(n_whole, 6);
    for (k = 0; k < 3; k++) tm_free(&m[k]);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(scratch_retries_repeat_no_report), T_CASE(packing_fallbacks_box),
        T_CASE(packing_fallbacks_hulls),
        T_CASE(compact_layout_packing_fallbacks_box),
        T_CASE(compact_layout_packing_fallbacks_hulls),
        T_CASE(blocks_do_not_depend_on_fresh_memory),
    };
    return T_RUN(argc, argv, cases);
}
