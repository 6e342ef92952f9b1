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
   pieces of a face against each other by up to 2e-9. Found 2026-12-04:
   they met at convex edges of no visible angle, at vertex 2 such a
   piece's plane passed through the corner itself, the largest valid radius
   was 0, and the patch was "rounded" with zero-radius spheres. Now those
   pieces are coplanar (RE__FLAT_ROUNDINGS) and the solid is rounded. */
static const unsigned char k_tilted_coplanar_pieces[] = {
    0x43, 0xb3, 0xb3, 0xb3, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0x1c, 0x00, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0x3b, 0xec, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb,
    0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xfb, 0xb3, 0xb2, 0xb3, 0xb3, 0xb3};

/* A 29-sided prism with per-edge radii, moved to -8e6 (rounding 1.9e-9)
   and its edges split again and again: a patch whose largest valid radius
   is still 0 (a neighbouring face plane through vertex 3). It stays sharp,
   each of its edges reported, instead of being rounded with r = 0 (found
   by the fuzzer once coplanar pieces were merged, 2026-12-04). */
static const unsigned char k_zero_radius_patch[] = {
    0xb0, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85,
    0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85,
    0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0x85, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3,
    0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3,
    0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3,
    0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0x30, 0xb3, 0xb3, 0xb3, 0xb3,
    0xb3, 0xb1, 0xb4, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3,
    0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3,
    0x27, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3,
    0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0x3b, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0xb3, 0x36};

/* The stretched icosahedron with a vertex moved and edges split, float
   positions, welded, as polygons, per-edge radii, two objects, and
   re_mesh_t.flat_sin = 3e-7: below the float positions' own rounding
   (about 1e-5 here). Found 2026-12-05: two of its faces met at 1.3e-7 rad,
   a "crease" the user's flat_sin let through; their planes, each within
   its vertices' rounding, crossed 0.12 away from their common edge, so a
   hit 0.14 from that edge was in the removed volume for re_query()'s
   flat-part test (a rounded hit 0.031 further on) and on the flat part
   for the bands (re_query_uv(): unchanged). A flat_sin below the rounding
   no longer makes creases of the noise. */
static const unsigned char k_noise_crease[] = {
    0x5f, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0x01, 0x07, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7,
    0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd7, 0xd7, 0xd7,
    0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xff, 0xff, 0xff, 0xff, 0x31, 0x00, 0x00, 0x00, 0xff, 0xff,
    0x70, 0x70, 0x70, 0x71, 0x70, 0x70, 0x70, 0x70, 0x70, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x00, 0xff, 0xed, 0xd7,
    0xfb, 0x40, 0x3d, 0x13, 0x40, 0x13, 0x08, 0x03, 0xeb, 0xfb, 0xfb, 0x01, 0xfb, 0x08};

/* A box with edits that fold it through itself, r = 0.25 (found
   2026-12-06 by a 45-minute run): a host hit lay 0.248 inside another
   part's cylinder, and the capsule entry, clamped to the float-host
   slack's earliest point, put a rounded hit there, off its own feature.
   The clamp now holds only within the slack's length of the surface
   (re__capsule_entry); deeper, the capsule counts as not entered. */
static const unsigned char k_hit_deep_in_a_capsule[] = {
    0x5f, 0xd7, 0xd7, 0xd7, 0xd7, 0xd7, 0xcf, 0xd7, 0xd7, 0xd7, 0x01, 0x07, 0x41, 0x13, 0xff, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xce, 0x80,
    0xec, 0x37, 0xbc, 0x97, 0x12, 0xdd, 0x2e, 0x6a, 0xae, 0xb9, 0x4b, 0xae, 0x8d, 0x2f, 0x9f, 0xa2, 0x9c, 0x5a,
    0x28, 0x4c, 0x9e, 0xf7, 0x52, 0x18, 0x29, 0xcf, 0xf4, 0x86, 0x4f, 0x7f, 0x16, 0x28, 0xb5, 0xe3, 0x10, 0xfc,
    0xab, 0x6a, 0x42, 0x00, 0xff, 0xed, 0xd7, 0xfb, 0x40, 0x2d, 0x13, 0x40, 0x13, 0x08, 0x03, 0xeb, 0xfb, 0x1f,
    0x1f, 0x1f, 0x1f, 0xfb, 0x01, 0xfb, 0x08};

static long g_sharp_reports, g_clamp_reports;
static void count_reports(void *user, const re_report_t *r)
{
    (void)user;
    if (r->kind == RE_REPORT_SHARP_PATCH_EDGE && strstr(r->message, "no radius above 0")) g_sharp_reports++;
    if (r->kind == RE_REPORT_RADIUS_CLAMPED && r->value == 0) g_clamp_reports++;
}

/* Replays an input through the fuzz target (its checks must all pass) and
   builds it again with reports counted; *s is the scene (or NULL). */
static void replay(const unsigned char *in_bytes, size_t n, rfz_case_t *k, re_scene_t **s, re_stats_t *st)
{
    rfz_in_t in;
    re_diag_t dg;
    g_rfz_fail = 0;
    LLVMFuzzerTestOneInput(in_bytes, n);
    T_INT_EQ(g_rfz_fail, 0);
    rfz_decode(in_bytes, n, k, &in);
    k->desc.report = count_reports;
    g_sharp_reports = g_clamp_reports = 0;
    *s = NULL;
    if (T_INT_EQ(re_build(&k->desc, s, &dg), RE_OK)) re_get_stats(*s, st);
}

static void tilted_coplanar_pieces_are_flat(void)
{
    static rfz_case_t k;
    re_scene_t *s;
    re_stats_t st;
    re_diag_t dg;
    replay(k_tilted_coplanar_pieces, sizeof k_tilted_coplanar_pieces, &k, &s, &st);
    if (!s) return;
    T_INT_EQ(st.convex_edges, 46); /* the icosahedron's 30 edges, 16 of them split */
    T_INT_EQ(st.rounded_edges, 46);
    T_INT_EQ(st.spheres, 32);
    T_INT_EQ(st.clamped, 0);
    T_INT_EQ(g_sharp_reports, 0);
    re_free(s);
    k.desc.radius_policy = RE_RADIUS_REJECT;
    T_INT_EQ(re_build(&k.desc, &s, &dg), RE_OK);
    re_free(s);
}

static void zero_radius_patch_left_sharp(void)
{
    static rfz_case_t k;
    re_scene_t *s;
    re_stats_t st;
    re_diag_t dg;
    replay(k_zero_radius_patch, sizeof k_zero_radius_patch, &k, &s, &st);
    if (!s) return;
    T_INT_EQ(st.convex_edges, 112);
    T_INT_EQ(st.rounded_edges, 0);
    T_INT_EQ(st.spheres, 0);
    T_INT_EQ(st.clamped, 1);
    T_INT_EQ(g_clamp_reports, 1);
    T_INT_EQ(g_sharp_reports, 112);
    re_free(s);
    /* with RE_RADIUS_REJECT the same input fails, naming the vertex */
    k.desc.radius_policy = RE_RADIUS_REJECT;
    s = NULL;
    T_INT_EQ(re_build(&k.desc, &s, &dg), RE_ERR_RADIUS_TOO_LARGE);
    T_CHECK(s == NULL && strstr(dg.message, "vertex 3") != NULL);
}

static void noise_crease_under_a_low_flat_sin_is_flat(void)
{
    static rfz_case_t k;
    re_scene_t *s;
    re_stats_t st;
    re_hit_t h, h2;
    const double P[3] = {1.1454265416837206, 0.48476139610888913, 1.0833195616217222},
                 d[3] = {-0.60928547660590016, -0.30808636337035, -0.73065313295869316};
    double o[3], dist = 4.01;
    unsigned i;
    replay(k_noise_crease, sizeof k_noise_crease, &k, &s, &st);
    if (!s) return;
    T_NEAR(k.mesh[0].flat_sin, ldexp(RE_FLAT_SIN_LIMIT, -15), 0); /* the fuzzer's choice, 3.05e-7 */
    T_INT_EQ(st.convex_edges, 76);                   /* 78 when the noise crease counted, once per object */
    T_INT_EQ(st.rounded_edges, 76);
    T_INT_EQ(st.flat_edges, 50);
    /* the query that disagreed: both now say the hit stands */
    for (i = 0; i < 3; i++) o[i] = P[i] - dist * d[i];
    T_INT_EQ(re_query(s, o, d, 0, 5, dist, &h), RE_UNCHANGED);
    T_INT_EQ(re_query_uv(s, o, d, 0, 5, dist, 0.015686274509803977, 0.74901960784313726, &h2), RE_UNCHANGED);
    re_free(s);
}

static void hit_deep_in_a_capsule_is_not_clamped(void)
{
    static rfz_case_t k;
    re_scene_t *s;
    re_stats_t st;
    replay(k_hit_deep_in_a_capsule, sizeof k_hit_deep_in_a_capsule, &k, &s, &st); /* rc_feature_ok on every rounded hit */
    if (!s) return;
    T_GT((double)st.rounded_edges, 0.0);
    re_free(s);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(tilted_coplanar_pieces_are_flat),
        T_CASE(zero_radius_patch_left_sharp),
        T_CASE(noise_crease_under_a_low_flat_sin_is_flat),
        T_CASE(hit_deep_in_a_capsule_is_not_clamped),
    };
    return T_RUN(argc, argv, cases);
}
