/* tests/test_rounded_setcap.c — rounded_edges.h with a query that holds few
   corners (RE_SET_CAP 64; the default is 1024). A finely tessellated round
   rim under a large radius puts more corners than that within reach of one
   point: the query drops some and may answer sharp or off, and must then
   say so (re_hit_t.flags RE_HIT_INCOMPLETE): no wrong answer unflagged.
   Ordinary solids stay exact with such a set. */
#define RE_SET_CAP 64
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"

/* The 512-gon prism of test_rounded_stiff's fine_round_rim_under_a_large_radius
   (r = 0.4: 188 corners detected near the rim, 66 needed): with 64 corners
   about 7% of the answers are wrong; every one is flagged. */
static void dropped_corners_flag_the_answer(void)
{
    int layout, n = (int)t_count(200);
    if (n < 40) n = 40;
    for (layout = 0; layout < 2; layout++) {
        rim_tally_t t;
        if (!rim_run(512, 0.4, 20 * n, layout, &t)) break;
        T_GT(t.wrong, 0);               /* the set is too small here: the check can fail */
        T_INT_EQ(t.wrong_unflagged, 0); /* ... and says so */
        T_GT(t.flagged, t.wrong - 1);
    }
}

static const double BOX_LO[3] = {-0.5, -0.3, -0.2}, BOX_HI[3] = {0.5, 0.3, 0.2};
static void small_set_box_stays_exact(void) { box_rays(BOX_LO, BOX_HI, 0.05, t_count(20000), 1e-9, 11); }

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(dropped_corners_flag_the_answer),
        T_CASE(small_set_box_stays_exact),
    };
    return T_RUN(argc, argv, cases);
}
