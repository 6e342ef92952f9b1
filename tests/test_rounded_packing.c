/* tests/test_rounded_packing.c — rounded_edges.h storage fallbacks that the
   benchmark scenes seldom or never take: with the spans forced tiny, most
   packed id blocks are stored whole (re__pk_t), the kd leaf lists are cut
   into many 16-bit runs (re__kd_narrow), and in the compact layout most
   edge cylinders keep their second sphere in the sorted far list
   (re__cyl_s1) and every sphere centre whose plane slots reach 3 is
   stored and found by rank (re__xsph_rank). The exactness batteries must still hold: the box
   against the analytic rounded box, random hulls against the eroded
   polytope, in both layouts. */
#define RE__PK_SPAN 2u
#define RE__LEAF_RUN_SPAN 3u
#define RE__SOLVED_SLOTS 3u
#define RE__DS1_SPAN 2u
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

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(packing_fallbacks_box),
        T_CASE(packing_fallbacks_hulls),
        T_CASE(compact_layout_packing_fallbacks_box),
        T_CASE(compact_layout_packing_fallbacks_hulls),
    };
    return T_RUN(argc, argv, cases);
}
