/* tests/test_frep_alloc.c — frep.h under an allocator that fails: every
   allocation of the builder, fr_builder_finish, fr_parse and fr_prepare
   made to fail in turn returns FR_ERR_OUT_OF_MEMORY with its message,
   leaves nothing allocated (test_count_alloc.h counts the live blocks)
   and never crashes; with no failure the models equal the default
   allocator's. Every allocation gets the user's context. */
#include "test_count_alloc.h"
#define FR_MALLOC(sz, ctx) ta_malloc((sz), (ctx))
#define FR_FREE(p, ctx) ta_free((p), (ctx))
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include "test.h"

static double ball(const double p[3], void *user)
{
    (void)user;
    return 0.25 - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
}

/* 200 spheres on a helix united, a black-box ball, a colour attribute:
   the builder's code, Lipschitz and callback arrays grow several times. */
static fr_result_t build_model(ta_alloc_t *al, fr_tape_t *t, fr_diag_t *d)
{
    fr_builder_t b;
    fr_builder_desc_t desc;
    fr_callback_t cb;
    fr_node_t f, attr;
    fr_p3_t X;
    fr_result_t r;
    int i;
    memset(&desc, 0, sizeof desc);
    memset(&cb, 0, sizeof cb);
    desc.alloc_ctx = al;
    if ((r = fr_builder_init(&b, &desc)) != FR_OK) return r;
    X = fr_coords(&b);
    cb.point = ball;
    f = fr_callback(&b, X, &cb);
    for (i = 0; i < 200; i++) {
        double c[3] = {cos(0.1 * i), sin(0.1 * i), 0.01 * i};
        f = fr_union(&b, f, fr_sphere(&b, X, c, 0.2), 0);
    }
    attr = fr_add(&b, X.z, fr_const(&b, 1));
    r = fr_builder_finish(&b, f, &attr, 1, t, d);
    fr_builder_free(&b);
    return r;
}

static const char *CUP = "cup(x[3], a[1]) {\n"
                         "  array c[3], foot[3];\n"
                         "  c = [0, 0, 0.6]; foot = [0, 0, -0.2];\n"
                         "  shell = hfSphere(x, c, 1.0) \\ hfSphere(x, c, 0.92);\n"
                         "  cut = shell & (0.75 - x[3]);\n"
                         "  stand = hfConeZ(x, foot, 0.8) & (x[3] + 0.55) & (-0.25 - x[3]);\n"
                         "  cup = cut | stand;\n"
                         "}\n";

static fr_result_t parse_model(ta_alloc_t *al, fr_tape_t *t, fr_diag_t *d)
{
    fr_parse_desc_t desc;
    memset(&desc, 0, sizeof desc);
    desc.alloc_ctx = al;
    return fr_parse(CUP, strlen(CUP), &desc, t, d);
}

typedef fr_result_t (*make_fn)(ta_alloc_t *al, fr_tape_t *t, fr_diag_t *d);

/* Makes the tape, prepares it in a box; returns the first failure. */
static fr_result_t make_and_prepare(make_fn make, ta_alloc_t *al, fr_diag_t *d, double *value)
{
    static const double box[6] = {-2, -2, -2, 2, 2, 3};
    static const double p[3] = {0.3, -0.2, 0.4};
    fr_tape_t t;
    fr_prepared_t pr;
    fr_result_t r;
    memset(d, 0, sizeof *d);
    if ((r = make(al, &t, d)) != FR_OK) {
        T_CHECK(t.code == NULL);
        return r;
    }
    if (value) {
        char scratch[1 << 16];
        T_LE(fr_scratch_size(&t, FR_EVAL_POINT), sizeof scratch);
        *value = fr_eval(&t, p, scratch);
    }
    r = fr_prepare(&t, box, &pr);
    if (r == FR_OK) fr_prepared_free(&pr);
    fr_tape_free(&t);
    return r;
}

static void each_allocation_fails(make_fn make, long at_least)
{
    ta_alloc_t *count = ta_alloc_new(0);
    fr_diag_t d;
    double with_hook = 0, plain = 0;
    long at, n_calls, n_oom = 0;
    T_INT_EQ(make_and_prepare(make, count, &d, &with_hook), FR_OK);
    T_INT_EQ(count->live, 0);
    n_calls = count->calls;
    ta_alloc_delete(count);
    T_GE(n_calls, at_least);
    /* the default allocator's model (a NULL context) gives the same value */
    T_INT_EQ(make_and_prepare(make, NULL, &d, &plain), FR_OK);
    T_CHECK(with_hook == plain && with_hook == with_hook);
    ta_null_context = 0;
    for (at = 1; at <= n_calls; at++) {
        ta_alloc_t *al = ta_alloc_new(at);
        fr_result_t r = make_and_prepare(make, al, &d, NULL);
        if (r != FR_ERR_OUT_OF_MEMORY) T_FAIL("allocation %ld failing: %s", at, fr_result_string(r));
        /* fr_prepare has no diagnostic: its failure leaves d as the tape left it */
        else if (d.result == FR_ERR_OUT_OF_MEMORY && !strstr(d.message, "out of memory"))
            T_FAIL("allocation %ld failing: message '%s'", at, d.message);
        else
            n_oom++;
        if (al->live) T_FAIL("allocation %ld failing: %ld blocks left", at, al->live);
        ta_alloc_delete(al);
    }
    T_INT_EQ(n_oom, n_calls);
    T_INT_EQ(ta_null_context, 0);
}

static void builder_finish_and_prepare_survive_each_failure(void) { each_allocation_fails(build_model, 8); }
static void parse_and_prepare_survive_each_failure(void) { each_allocation_fails(parse_model, 4); }

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(builder_finish_and_prepare_survive_each_failure),
        T_CASE(parse_and_prepare_survive_each_failure),
    };
    return T_RUN(argc, argv, cases);
}
