/* Tests of the test harness itself and of the shared header skeleton pieces
   (result strings), so a broken harness cannot make every other test pass. */
#include "test.h"
#include "interval.h"
#include "rounded_edges.h"
#include "grooves.h"

static void harness_counts_failures(void)
{
    long long p = t_state_.passed, f = t_state_.failed;
    int quiet = t_state_.max_reports;
    t_state_.max_reports = 0; /* do not print the deliberate failures */
    T_NEAR(1.0, 1.5, 0.1);
    T_LE(2.0, 1.0);
    T_CHECK(0);
    T_REL(NAN, 1.0, 1.0);
    {
        long long caught = t_state_.failed - f;
        t_state_.failed = f; /* undo the deliberate failures */
        t_state_.passed = p;
        t_state_.max_reports = quiet;
        T_INT_EQ(caught, 4);
    }
}

static void harness_rng_is_deterministic(void)
{
    t_rng_t a = {42}, b = {42};
    int i, same = 1;
    for (i = 0; i < 100; i++) same &= t_rng_u64(&a) == t_rng_u64(&b);
    T_CHECK(same);
    T_GE(t_rng_unit(&a), 0.0);
    T_LT(t_rng_unit(&a), 1.0);
}

static void result_strings_name_every_code(void)
{
    T_CHECK(strcmp(iv_result_string(IV_OK), "ok") == 0);
    T_CHECK(strcmp(re_result_string(RE_OK), "ok") == 0);
    T_CHECK(strcmp(gr_result_string(GR_OK), "ok") == 0);
    T_CHECK(strcmp(re_result_string((re_result_t)9999), "unknown result") == 0);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(harness_counts_failures),
        T_CASE(harness_rng_is_deterministic),
        T_CASE(result_strings_name_every_code),
    };
    return T_RUN(argc, argv, cases);
}
