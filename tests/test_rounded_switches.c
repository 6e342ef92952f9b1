/* tests/test_rounded_switches.c — rounded_edges.h built with its feature
   switches RE_NO_BANDS, RE_NO_BASELINES and RE_NO_COMPACT (the header
   compile matrix compiles every combination; this runs one). Without
   bands re_query_uv() answers through the kd-tree on every hit: the box
   and hull batteries still hold against their independent oracles, with
   re_query_uv() equal to re_query() bit for bit and never skipping the
   tree; the scene keeps no bands and re_build_sizes() still sizes it; the
   compact layout is refused by name. */
#define RE_NO_BANDS
#define RE_NO_BASELINES
#define RE_NO_COMPACT
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"

#ifdef RE_BEVEL_MAX_HITS
#error "RE_NO_BASELINES left the bevel baselines in"
#endif

/* The bands' step is gone: no hit is answered by them (check_query_uv
   counts the skips), yet every answer is the oracle's. */
static void no_bands_box_exact_vs_analytic(void)
{
    double lo[3] = {-0.5, -0.3, -0.2}, hi[3] = {0.5, 0.3, 0.2};
    g_uv_skipped = g_uv_calls = 0;
    box_rays(lo, hi, 0.05, t_count(40000), 1e-9, 11);
    T_GT(g_uv_calls, t_count(40000) / 2);
    T_INT_EQ(g_uv_skipped, 0);
}

/* Exact corners (degrees 3 to 8) against sphere tracing of the eroded
   polytope, as test_rounded_core's random hulls. */
static void no_bands_hulls_vs_eroded(void)
{
    t_rng_t rng = {77};
    int it, nit = (int)t_count(6);
    g_uv_skipped = g_uv_calls = 0;
    for (it = 0; it < nit; it++) {
        tm_mesh_t m = {0};
        static tm_poly_t P;
        tm_random_hull(&rng, 12, 0.8, 1.2, &m, &P);
        poly_rays(&m, &P, 0.03, t_count(1500), 1e-7, 300 + (unsigned long long)it, "hull without bands");
        tm_free(&m);
    }
    T_GT(g_uv_calls, 0);
    T_INT_EQ(g_uv_skipped, 0);
}

/* No bands in the block, and the size query agrees with the build; no
   compact layout. */
static void no_bands_scene_holds_none(void)
{
    tm_mesh_t m = {0};
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_sizes_t sz;
    re_diag_t dg;
    re_scene_t *s = NULL, *s2 = NULL;
    re_stats_t st;
    void *mem, *scratch;
    tm_icosphere(&m, 3, 1.0);
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.radius = 0.01;
    desc.objects = &mesh, desc.object_count = 1;
    if (!T_INT_EQ(re_build(&desc, &s, &dg), RE_OK)) { tm_free(&m); return; }
    T_CHECK(s->objects[0].bands == NULL);
    re_get_stats(s, &st);
    T_INT_EQ(st.rounded_edges, m.ni / 2); /* every edge of the closed icosphere */
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_OK);
    T_INT_EQ(sz.scene_bytes, st.bytes);
    mem = malloc(sz.scene_bytes), scratch = malloc(sz.scratch_bytes);
    if (T_CHECK(mem && scratch)) {
        T_INT_EQ(re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s2, &dg), RE_OK);
        if (s2) T_INT_EQ(memcmp(s2->objects[0].planes, s->objects[0].planes, sizeof(re__plane_t) * 8), 0);
    }
    free(mem), free(scratch);
    re_free(s);
    /* RE_NO_COMPACT: the layout is refused, and the message says why */
    desc.layout = RE_LAYOUT_COMPACT;
    s = NULL;
    T_INT_EQ(re_build(&desc, &s, &dg), RE_ERR_INVALID_ARG);
    T_CHECK(s == NULL && strstr(dg.message, "RE_NO_COMPACT") != NULL);
    T_INT_EQ(re_build_sizes(&desc, &sz, &dg), RE_ERR_INVALID_ARG);
    tm_free(&m);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(no_bands_box_exact_vs_analytic),
        T_CASE(no_bands_hulls_vs_eroded),
        T_CASE(no_bands_scene_holds_none),
    };
    return T_RUN(argc, argv, cases);
}
