/* IV_FAST (round-to-nearest endpoints, NOT rigorous): its pair path
   matches its scalar path, its endpoints are the round-to-nearest values
   (no step), and the __float128 containment oracle of the property tests
   does catch what it gives up (so that oracle can fail). */
#define IV_FAST
#define IV_IMPLEMENTATION
#include "test_interval_gen.h"

static void fast_pair_matches_scalar(void) { ig_pair_matches_scalar(); }
static void fast_arrays_match_per_call(void) { ig_arrays_match_per_call(); }

/* Point operations give exactly the double operation's result. */
static void fast_endpoints_round_to_nearest(void)
{
    t_rng_t r = {5};
    long i, n = t_count(200000), bad = 0;
    for (i = 0; i < n; i++) {
        double a = ig_value(&r), b = ig_value(&r), want[6];
        iv_t z[6];
        int k;
        if (b == 0) b = 1.5;
        z[0] = iv_add(iv_point(a), iv_point(b)); want[0] = a + b;
        z[1] = iv_sub(iv_point(a), iv_point(b)); want[1] = a - b;
        z[2] = iv_mul(iv_point(a), iv_point(b)); want[2] = a * b;
        z[3] = iv_div(iv_point(a), iv_point(b)); want[3] = a / b;
        z[4] = iv_sqrt(iv_point(fabs(a))); want[4] = sqrt(fabs(a));
        z[5] = iv_mul_d(iv_point(a), b); want[5] = a * b;
        for (k = 0; k < 6; k++) {
            /* an overflow to inf keeps its scalar-path clamp at one end */
            if (!(want[k] - want[k] == 0)) continue;
            if (z[k].lo != want[k] || z[k].hi != want[k]) {
                if (bad++ < 5) T_FAIL("op %d on %a, %a: [%a, %a], want %a", k, a, b, z[k].lo, z[k].hi, want[k]);
            }
        }
    }
    T_INT_EQ(bad, 0);
}

/* 0.1 + 0.2 rounds up: the exact sum of the two doubles lies below the
   round-to-nearest point interval; random point operations miss their
   exact value most of the time. */
static void fast_misses_exact_values(void)
{
    t_rng_t r = {6};
    long i, n = t_count(200000), miss = 0;
    iv_t z = iv_add(iv_point(0.1), iv_point(0.2));
    T_CHECK(!ig_in(z, (q_t)0.1 + (q_t)0.2));
    for (i = 0; i < n; i++) {
        double a = t_rng_range(&r, -10, 10), b = t_rng_range(&r, -10, 10);
        if (!ig_in(iv_mul(iv_point(a), iv_point(b)), (q_t)a * (q_t)b)) miss++;
    }
    T_GT(miss, n / 2);
    fprintf(stderr, "    IV_FAST: %ld of %ld random products miss their exact value\n", miss, n);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(fast_pair_matches_scalar),
        T_CASE(fast_arrays_match_per_call),
        T_CASE(fast_endpoints_round_to_nearest),
        T_CASE(fast_misses_exact_values),
    };
    return T_RUN(argc, argv, cases);
}
