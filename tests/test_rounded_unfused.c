/* tests/test_rounded_unfused.c — rounded_edges.h built without fused
   multiply-adds (-ffp-contract=off; the Makefile's TEST_FLAGS_), as a host
   compiled for baseline x86-64 builds it, and as the fuzzers do. The other
   tests are built with -march=native and contraction, where o + t d is one
   fma rounded to I's own magnitude; unfused, t d is rounded first, to the
   magnitude of t d, and a query that takes I's rounding for a signal goes
   wrong only here. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"

/* Rays along the faces of fuzz_rounded_exact's tetrahedron (float
   positions, r = 0.04 of its size) through points on their edges, in 2 000
   directions each (rays_along_faces_of), half of them leaving the face over
   that edge. A ray leaving over the edge at 1e-10 into the face crosses
   its plane just before the edge, where the exact host reports it, so I
   (o + t_host d, 4.9 sizes from o) is off the plane by the rounding of o
   and t_host d: 3.6e-16. The host-t mend (re__onto_face) took that for a
   float host's early t, since its slack counted |I| only, and moved I
   3.6e-6 along the ray onto the plane, past the edge and out of the mesh:
   a pass-through 9.4e-7 outside the hull, through the wrong face. Before
   the mend's slack counted I's rounding, 17 of the 31 762 rays that hit
   failed (up to 5.6e-7 outside). */
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


static const double BOX_LO[3] = {-0.5, -0.3, -0.2}, BOX_HI[3] = {0.5, 0.3, 0.2};
/* the exactness battery of an axis-aligned box (box_rays), unfused */
static void box_stays_exact_unfused(void) { box_rays(BOX_LO, BOX_HI, 0.05, t_count(20000), 1e-9, 13); }

/* This unit is what it says: a * b + c written as re__madd writes it is
   rounded twice ((1 + 2^-30)^2 - (1 + 2^-29) is 2^-60 fused, 0 not). */
static void built_without_fused_multiply_adds(void)
{
    volatile double a = 1 + 0x1p-30, c = -(1 + 0x1p-29);
    double x = a, z = c;
    T_CHECK(x * x + z == 0);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(built_without_fused_multiply_adds),
        T_CASE(rays_along_a_face_over_its_edges),
        T_CASE(box_stays_exact_unfused),
    };
    return T_RUN(argc, argv, cases);
}
