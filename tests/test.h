/* tests/test.h — filigree's in-house test harness (no framework dependency).

   A test binary lists its cases and hands them to t_main():

       #include "test.h"
       static void sqrt_of_four(void) { T_NEAR(sqrt(4.0), 2.0, 0.0); }
       int main(int argc, char **argv) {
           static const t_case_t cases[] = { T_CASE(sqrt_of_four) };
           return T_RUN(argc, argv, cases);
       }

   Every check counts toward the totals. A failure prints file:line, the
   expression, and expected/actual values with %.17g. Arguments select cases by
   substring: `build/tests/test_interval sin cos` runs the cases whose names
   contain "sin" or "cos". `--list` prints the case names.

   The last line a binary prints is `N passed, M failed`; its exit status is
   non-zero when any check failed. tests/run_all.sh sums these lines.

   t_scale() is 1 in the normal pass and smaller under the sanitizer pass
   (env FILIGREE_TEST_SCALE), so property tests can size their loops:
       long n = t_count(10000000);   // 1e7 normally, fewer under ASan
*/
#ifndef FILIGREE_TEST_H
#define FILIGREE_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct t_case_t {
    const char *name;
    void (*fn)(void);
} t_case_t;

typedef struct t_state_t {
    long long passed;
    long long failed;
    int max_reports; /* failures printed per case before going quiet */
    int reported;
    const char *current;
} t_state_t;

static t_state_t t_state_ = {0, 0, 20, 0, "?"};

#define T_CASE(fn) {#fn, fn}
/* A module's xx_result_string(): every code below count has a name of its
   own, never NULL nor "unknown result", which the count and beyond get. */
#define T_RESULT_NAMES(fn, type, count)                                                        \
    do {                                                                                       \
        int i_, j_;                                                                            \
        for (i_ = 0; i_ < (int)(count); i_++) {                                                \
            T_CHECK(fn((type)i_) != NULL);                                                     \
            T_CHECK(strcmp(fn((type)i_), "unknown result") != 0);                              \
            for (j_ = 0; j_ < i_; j_++) T_CHECK(strcmp(fn((type)i_), fn((type)j_)) != 0);      \
        }                                                                                      \
        T_CHECK(strcmp(fn((type)(count)), "unknown result") == 0);                             \
        T_CHECK(strcmp(fn((type)999), "unknown result") == 0);                                 \
    } while (0)
#define T_RUN(argc, argv, cases) t_main((argc), (argv), (cases), (int)(sizeof(cases) / sizeof((cases)[0])))

static void t_report_(const char *file, int line, const char *expr, const char *detail)
{
    t_state_.failed++;
    if (t_state_.reported++ < t_state_.max_reports)
        fprintf(stderr, "%s:%d: FAIL [%s] %s%s%s\n", file, line, t_state_.current, expr,
                detail[0] ? "  " : "", detail);
    else if (t_state_.reported == t_state_.max_reports + 1)
        fprintf(stderr, "  (further failures in %s not shown)\n", t_state_.current);
}

static int t_check_(int ok, const char *file, int line, const char *expr)
{
    if (ok) { t_state_.passed++; return 1; }
    t_report_(file, line, expr, "");
    return 0;
}

/* a op b for doubles; NaN never satisfies a comparison. */
static int t_cmp_(double a, double b, int op, const char *file, int line, const char *ea, const char *eb)
{
    static const char *const ops[] = {"==", "<=", ">=", "<", ">", "!="};
    int ok = op == 0 ? a == b : op == 1 ? a <= b : op == 2 ? a >= b : op == 3 ? a < b : op == 4 ? a > b : a != b;
    char expr[512], detail[160];
    if (ok) { t_state_.passed++; return 1; }
    snprintf(expr, sizeof expr, "%s %s %s", ea, ops[op], eb);
    snprintf(detail, sizeof detail, "lhs %.17g, rhs %.17g", a, b);
    t_report_(file, line, expr, detail);
    return 0;
}

/* |actual - expected| <= tol (absolute). */
static int t_near_(double actual, double expected, double tol, const char *file, int line, const char *ea, const char *eb)
{
    double err = fabs(actual - expected);
    char expr[512], detail[200];
    if (err <= tol) { t_state_.passed++; return 1; }
    snprintf(expr, sizeof expr, "|%s - %s| <= tol", ea, eb);
    snprintf(detail, sizeof detail, "expected %.17g, actual %.17g, error %.3g > tol %.3g", expected, actual, err, tol);
    t_report_(file, line, expr, detail);
    return 0;
}

/* |actual - expected| <= rel * max(|expected|, tiny) (relative). */
static int t_rel_(double actual, double expected, double rel, const char *file, int line, const char *ea, const char *eb)
{
    double scale = fabs(expected) > 1e-300 ? fabs(expected) : 1e-300;
    double err = fabs(actual - expected) / scale;
    char expr[512], detail[200];
    if (err <= rel) { t_state_.passed++; return 1; }
    snprintf(expr, sizeof expr, "rel(%s, %s) <= rel", ea, eb);
    snprintf(detail, sizeof detail, "expected %.17g, actual %.17g, rel error %.3g > %.3g", expected, actual, err, rel);
    t_report_(file, line, expr, detail);
    return 0;
}

static int t_int_eq_(long long a, long long b, const char *file, int line, const char *ea, const char *eb)
{
    char expr[512], detail[120];
    if (a == b) { t_state_.passed++; return 1; }
    snprintf(expr, sizeof expr, "%s == %s", ea, eb);
    snprintf(detail, sizeof detail, "lhs %lld, rhs %lld", a, b);
    t_report_(file, line, expr, detail);
    return 0;
}

#define T_CHECK(e) t_check_(!!(e), __FILE__, __LINE__, #e)
#define T_EQ(a, b) t_cmp_((double)(a), (double)(b), 0, __FILE__, __LINE__, #a, #b)
#define T_LE(a, b) t_cmp_((double)(a), (double)(b), 1, __FILE__, __LINE__, #a, #b)
#define T_GE(a, b) t_cmp_((double)(a), (double)(b), 2, __FILE__, __LINE__, #a, #b)
#define T_LT(a, b) t_cmp_((double)(a), (double)(b), 3, __FILE__, __LINE__, #a, #b)
#define T_GT(a, b) t_cmp_((double)(a), (double)(b), 4, __FILE__, __LINE__, #a, #b)
#define T_NEAR(a, b, tol) t_near_((double)(a), (double)(b), (double)(tol), __FILE__, __LINE__, #a, #b)
#define T_REL(a, b, rel) t_rel_((double)(a), (double)(b), (double)(rel), __FILE__, __LINE__, #a, #b)
#define T_INT_EQ(a, b) t_int_eq_((long long)(a), (long long)(b), __FILE__, __LINE__, #a, #b)
/* A failure with a free-form message (for property loops that found a counterexample). */
#define T_FAIL(...) do { char t_msg_[512]; snprintf(t_msg_, sizeof t_msg_, __VA_ARGS__); \
    t_report_(__FILE__, __LINE__, "T_FAIL", t_msg_); } while (0)

/* 1 in the normal pass; FILIGREE_TEST_SCALE (e.g. 0.02) under sanitizers. */
static double t_scale(void)
{
    const char *s = getenv("FILIGREE_TEST_SCALE");
    double v = s ? atof(s) : 1.0;
    return v > 0 && v <= 1 ? v : 1.0;
}
static long t_count(long n)
{
    long m = (long)((double)n * t_scale());
    return m < 1 ? 1 : m;
}

/* Deterministic, seedable random numbers (splitmix64), independent of libc. */
typedef struct t_rng_t { unsigned long long s; } t_rng_t;
static unsigned long long t_rng_u64(t_rng_t *r)
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static double t_rng_unit(t_rng_t *r) { return (double)(t_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0); }
static double t_rng_range(t_rng_t *r, double a, double b) { return a + (b - a) * t_rng_unit(r); }

static int t_selected_(const char *name, int argc, char **argv)
{
    int i, any = 0;
    for (i = 1; i < argc; i++) {
        if (argv[i][0] == '-') continue;
        any = 1;
        if (strstr(name, argv[i])) return 1;
    }
    return !any;
}

static int t_main(int argc, char **argv, const t_case_t *cases, int n)
{
    int i;
    for (i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--list")) {
            int k;
            for (k = 0; k < n; k++) printf("%s\n", cases[k].name);
            return 0;
        }
    for (i = 0; i < n; i++) {
        long long before_fail = t_state_.failed, before_pass = t_state_.passed;
        if (!t_selected_(cases[i].name, argc, argv)) continue;
        t_state_.current = cases[i].name;
        t_state_.reported = 0;
        cases[i].fn();
        fprintf(stderr, "  %-48s %s (%lld checks)\n", cases[i].name,
                t_state_.failed == before_fail ? "ok" : "FAILED",
                (t_state_.passed - before_pass) + (t_state_.failed - before_fail));
    }
    printf("%lld passed, %lld failed\n", t_state_.passed, t_state_.failed);
    return t_state_.failed ? 1 : 0;
}

#endif /* FILIGREE_TEST_H */
