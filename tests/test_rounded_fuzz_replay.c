/* tests/test_rounded_fuzz_replay.c — inputs on which the libFuzzer target
   tests/fuzz_rounded_build.c once failed, replayed through the same target
   with its checks counted (RFZ_FAIL) instead of aborting, and what each
   must give now. The target's own checks: a failed build names what
   failed; a built scene enumerates its features (spheres of radius > 0),
   agrees with re_build_sizes() + re_build_into(), and answers front-face
   host hits with a valid kind, no earlier than the host's t, with a unit
   normal on rounded hits. */
static long g_rfz_fail;
#define RFZ_FAIL() (g_rfz_fail++)
#include "fuzz_rounded_build.c"
#include "test.h"

/* The stretched icosahedron with its edges split again and again (chain
   vertices, faces cut into coplanar pieces), one vertex nudged by 3e-8 and
   the mesh moved to -3e5, where the doubles' rounding (6e-11) tilts the
   pieces of a face against each other by up to ~1e-7: they meet at convex
   edges of almost no angle, and at vertex 2 such a neighbouring piece's
   plane passes through the corner itself, so the largest valid radius of
   the patch is 0. Found 2026-12-04: the build clamped the patch to r = 0
   and "rounded" its 48 edges with zero-radius spheres and cylinders. */
static const unsigned char k_zero_radius_patch[] = {
    0x43, 0xb3, 0xb3, 0xb3, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0x1c, 0x00, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0x3b, 0xec, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xb3, 0xb2, 0xb3, 0xb3, 0xb3};

static long g_sharp_reports, g_clamp_reports;
static void count_reports(void *user, const re_report_t *r)
{
    (void)user;
    if (r->kind == RE_REPORT_SHARP_PATCH_EDGE && strstr(r->message, "no radius above 0")) g_sharp_reports++;
    if (r->kind == RE_REPORT_RADIUS_CLAMPED && r->value == 0) g_clamp_reports++;
}

/* No radius above 0 fits: the patch stays sharp, every edge of it is
   reported, and the target's checks pass (no zero-radius sphere). */
static void zero_radius_patch_left_sharp(void)
{
    static rfz_case_t k;
    rfz_in_t in;
    re_scene_t *s = NULL;
    re_diag_t dg;
    re_stats_t st;
    g_rfz_fail = 0;
    LLVMFuzzerTestOneInput(k_zero_radius_patch, sizeof k_zero_radius_patch);
    T_INT_EQ(g_rfz_fail, 0);
    rfz_decode(k_zero_radius_patch, sizeof k_zero_radius_patch, &k, &in);
    k.desc.report = count_reports;
    g_sharp_reports = g_clamp_reports = 0;
    if (!T_INT_EQ(re_build(&k.desc, &s, &dg), RE_OK)) return;
    re_get_stats(s, &st);
    T_INT_EQ(st.convex_edges, 48);
    T_INT_EQ(st.rounded_edges, 0);
    T_INT_EQ(st.spheres, 0);
    T_INT_EQ(st.clamped, 1);
    T_INT_EQ(g_clamp_reports, 1);
    T_INT_EQ(g_sharp_reports, 48);
    re_free(s);
    /* with RE_RADIUS_REJECT the same input fails, naming the vertex */
    k.desc.radius_policy = RE_RADIUS_REJECT;
    T_INT_EQ(re_build(&k.desc, &s, &dg), RE_ERR_RADIUS_TOO_LARGE);
    T_CHECK(strstr(dg.message, "vertex 2") != NULL);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(zero_radius_patch_left_sharp),
    };
    return T_RUN(argc, argv, cases);
}
