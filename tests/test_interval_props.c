/* Property-based containment tests of interval.h against __float128
   references (issue 3): at least 10^7 random interval cases and 10^7 random
   affine cases per normal run, over every operation, with the input classes
   of test_interval_gen.h. Zero violations allowed. Public functions not
   checked here: the array forms (bit for bit against the per-call forms,
   test_interval_basic), iv_fp_env_* (test_interval_fp_env),
   iv_result_string, and iv_make, iv_point, iv_empty, iv_entire,
   iv_is_empty, iv_contains, iv_affine_const, iv_affine_from_iv,
   iv_affine_is_empty, iv_from_affine only as the checks' own tools. */
#define IV_IMPLEMENTATION
#include "test_interval_oracle.h"
/* cases per property (test_interval_props_nosimd.c runs fewer) */
#ifndef IV_PROPS_CASES
#define IV_PROPS_CASES 10000000
#endif
#include <pthread.h>

/* Each property test runs in two threads over disjoint seeds (the tests
   must fit the suite's time budget on 2 cores); the harness's checks are
   made afterwards from the main thread. */
typedef struct job_t {
    unsigned long long seed;
    long n, bad, checked;
    long per_op[32];
    char first[8][600];
} job_t;
#define JOB_FAIL(j, ...) do { if ((j)->bad < 8) snprintf((j)->first[(j)->bad], sizeof (j)->first[0], __VA_ARGS__); (j)->bad++; } while (0)

static void run_jobs(void *(*fn)(void *), long n, unsigned long long seed, job_t *out)
{
    pthread_t th[2];
    job_t *j = (job_t *)calloc(2, sizeof(job_t));
    int k, m;
    for (k = 0; k < 2; k++) { j[k].seed = seed + (unsigned long long)k * 1000003ull; j[k].n = n / 2 + (k ? n % 2 : 0); }
    for (k = 0; k < 2; k++) pthread_create(&th[k], NULL, fn, &j[k]);
    for (k = 0; k < 2; k++) pthread_join(th[k], NULL);
    memset(out, 0, sizeof *out);
    for (k = 0; k < 2; k++) {
        for (m = 0; m < 8 && m < j[k].bad; m++) T_FAIL("%.500s", j[k].first[m]);
        out->bad += j[k].bad; out->checked += j[k].checked; out->n += j[k].n;
        for (m = 0; m < 32; m++) out->per_op[m] += j[k].per_op[m];
    }
    free(j);
}

/* Inputs biased toward each operation's interesting region. */
static iv_t input_for(t_rng_t *r, int op)
{
    iv_t x = ig_interval(r);
    if ((op == OP_EXP || op == OP_POW) && t_rng_u64(r) % 2) {
        double a = t_rng_range(r, -800, 800);
        x = iv_make(a, a + t_rng_range(r, 0, 5) * (double)(t_rng_u64(r) % 2));
    }
    if ((op == OP_LOG || op == OP_SQRT || op == OP_POW) && t_rng_u64(r) % 2) x = iv_abs(x);
    return x;
}

/* The set operations at a point x of a (y of b): x lies in the hull and
   in a half of iv_split(a), in the intersection exactly when y = x lies
   in b too; iv_mid(a) lies in a and iv_width(a) is at least hi - lo. */
static int sets_hold(iv_t a, iv_t b, double x)
{
    iv_t l, h;
    int in = iv_contains(iv_hull(a, b), x) && iv_contains(iv_intersect(a, b), x) == iv_contains(b, x);
    iv_split(a, &l, &h);
    return in && (iv_contains(l, x) || iv_contains(h, x)) && iv_contains(a, iv_mid(a)) &&
           (q_t)iv_width(a) >= (q_t)a.hi - (q_t)a.lo;
}

static void *interval_worker(void *arg)
{
    job_t *j = (job_t *)arg;
    t_rng_t r;
    long i;
    r.s = j->seed;
    for (i = 0; i < j->n; i++) {
        int op = (int)(t_rng_u64(&r) % OP_COUNT), k, np = 0;
        int pn = pow_ns[t_rng_u64(&r) % (sizeof pow_ns / sizeof pow_ns[0])];
        iv_t a = input_for(&r, op), b = input_for(&r, op), z, piece[2];
        if (is_scalar(op)) { double d = ig_value(&r); b = iv_point(d); }
        if (op == OP_POW && t_rng_u64(&r) % 2) b = iv_make(-3 + 6 * t_rng_unit(&r), 3);
        z = eval_iv(op, a, b, pn);
        if (op == OP_DIV) np = iv_div_ext(a, b, piece);
        j->per_op[op]++;
        for (k = 0; k < 2; k++) {
            double x = ig_point(&r, a), y = is_binary(op) ? ig_point(&r, b) : 0.0;
            q_t v = ref(op, (q_t)x, (q_t)y, pn);
            if (k == 0 && !sets_hold(a, b, x))
                JOB_FAIL(j, "hull, intersect, split, mid or width: x=%a in [%a,%a], [%a,%a]", x, a.lo, a.hi, b.lo, b.hi);
            if (v != v) continue; /* outside the domain */
            j->checked++;
            /* iv_div_ext: the quotient lies in one of its pieces */
            if (op == OP_DIV && !((np > 0 && ig_in(piece[0], v)) || (np > 1 && ig_in(piece[1], v)))) {
                char buf[64];
                quadmath_snprintf(buf, sizeof buf, "%.36Qg", v);
                JOB_FAIL(j, "div_ext: x=%a in [%a,%a], y=%a in [%a,%a]: f=%s in none of %d pieces", x, a.lo, a.hi, y, b.lo,
                         b.hi, buf, np);
            }
            if (iv_is_empty(z) || !ig_in(z, v)) {
                char buf[64];
                quadmath_snprintf(buf, sizeof buf, "%.36Qg", v);
                JOB_FAIL(j, "%s(n=%d): x=%a in [%a,%a], y=%a in [%a,%a]: f=%s not in [%a,%a]", op_name[op], pn, x,
                         a.lo, a.hi, y, b.lo, b.hi, buf, z.lo, z.hi);
            }
        }
    }
    return NULL;
}

static void containment_intervals(void)
{
    job_t t;
    long n = t_count(IV_PROPS_CASES), i;
    run_jobs(interval_worker, n, 12345, &t);
    T_INT_EQ(t.bad, 0);
    T_GT(t.checked, n / 2);
    for (i = 0; i < OP_COUNT; i++) T_GT(t.per_op[i], n / (2 * OP_COUNT));
    fprintf(stderr, "    %ld interval cases, %ld points checked, %ld violations\n", n, t.checked, t.bad);
}

#ifndef IV_NO_AFFINE
/* A random affine form; its eps_x value is chosen per sample. */
static iv_affine_t rand_form(t_rng_t *r)
{
    unsigned k = (unsigned)(t_rng_u64(r) % 10);
    double c = ig_value(r), s;
    iv_affine_t f;
    iv_t x;
    if (k == 0) return iv_affine_const(c);
    if (k == 1) return iv_affine_from_iv(ig_interval(r));
    if (k == 8) { /* the ray parameter over a finite range */
        x = ig_interval(r);
        return x.lo > -HUGE_VAL && x.hi < HUGE_VAL ? iv_affine_ray_param(x.lo, x.hi) : iv_affine_from_iv(x);
    }
    s = k <= 4 ? fabs(c) * pow(10.0, t_rng_range(r, -6, 0)) : pow(10.0, t_rng_range(r, -3, 1));
    f.c = k == 7 ? t_rng_range(r, -3, 3) : c;
    f.t = s * t_rng_range(r, -1, 1);
    f.e = (t_rng_u64(r) % 3) ? 0.0 : s * t_rng_unit(r) * 0.3;
    if (k == 9) { /* infinite parts: an unbounded form that is not the canonical (0, 0, inf) */
        unsigned m = (unsigned)(t_rng_u64(r) % 7) + 1;
        if (m & 1) f.c = t_rng_u64(r) % 2 ? HUGE_VAL : -HUGE_VAL;
        if (m & 2) f.t = t_rng_u64(r) % 2 ? HUGE_VAL : -HUGE_VAL;
        if (m & 4) f.e = HUGE_VAL;
    }
    return f;
}

/* A form with an infinite part is unbounded: it stands for any real
   (docs/interval.md, "Affine arithmetic"). */
static int unbounded(iv_affine_t f) { return fabs(f.c) == HUGE_VAL || fabs(f.t) == HUGE_VAL || f.e == HUGE_VAL; }

/* The affine claim is stronger than range containment: for every input
   point (eps_t, eps_a, eps_b), f(a, b) differs from z.c + z.t*eps_t (the
   same eps_t) by at most z.e. The interval iv_from_affine(z) must contain
   f as well. An unbounded operand takes any real value (a random double
   of every class, at every eps_t); the result must then still be a form
   (finite parts, or the unbounded form) whose claim holds, and
   iv_from_affine of an unbounded operand is the entire line. */
static void *affine_worker(void *arg)
{
    job_t *j = (job_t *)arg;
    t_rng_t r;
    long i;
    r.s = j->seed;
    for (i = 0; i < j->n; i++) {
        int op = (int)(t_rng_u64(&r) % OP_COUNT), k;
        int pn = pow_ns[t_rng_u64(&r) % (sizeof pow_ns / sizeof pow_ns[0])];
        iv_affine_t a = rand_form(&r), b = rand_form(&r), z;
        double d = ig_value(&r), t0 = ig_value(&r), t1 = t0 + fabs(ig_value(&r));
        iv_t zi;
        /* iv_affine_ray_param's claim: every t in [t0, t1] is c + t eps_t */
        z = iv_affine_ray_param(t0, t1);
        if (t1 < HUGE_VAL && !(z.e == 0 && (q_t)z.c - fabsq((q_t)z.t) <= (q_t)t0 && (q_t)z.c + fabsq((q_t)z.t) >= (q_t)t1))
            JOB_FAIL(j, "ray_param(%a, %a) = (%a,%a,%a)", t0, t1, z.c, z.t, z.e);
        if ((op == OP_LOG || op == OP_SQRT || op == OP_POW) && a.c < 0 && t_rng_u64(&r) % 2) a.c = -a.c;
        if (op == OP_EXP && fabs(a.c) > 700 && fabs(a.c) < HUGE_VAL) a.c = fmod(a.c, 700.0);
        z = eval_aff(op, a, b, d, pn, (int)(t_rng_u64(&r) % 4));
        zi = iv_from_affine(z);
        if (unbounded(a) && !(iv_from_affine(a).lo == -HUGE_VAL && iv_from_affine(a).hi == HUGE_VAL))
            JOB_FAIL(j, "iv_from_affine(%a,%a,%a) = [%a,%a], not the entire line", a.c, a.t, a.e, iv_from_affine(a).lo,
                     iv_from_affine(a).hi);
        if (!iv_affine_is_empty(z) && !(z.e >= 0 && z.c == z.c && z.t == z.t))
            JOB_FAIL(j, "affine %s(n=%d): a=(%a,%a,%a) b=(%a,%a,%a) d=%a -> (%a,%a,%a) is not a form", op_name[op], pn, a.c, a.t,
                     a.e, b.c, b.t, b.e, d, z.c, z.t, z.e);
        for (k = 0; k < 2; k++) {
            q_t et = (q_t)(k == 0 ? (t_rng_u64(&r) % 2 ? 1.0 : -1.0) : t_rng_range(&r, -1, 1));
            q_t ea = (q_t)t_rng_range(&r, -1, 1), eb = (q_t)t_rng_range(&r, -1, 1);
            q_t x = unbounded(a) ? (q_t)ig_value(&r) : form_at(a, et, ea), v, dev;
            q_t y = is_scalar(op) ? (q_t)d : unbounded(b) ? (q_t)ig_value(&r) : form_at(b, et, eb);
            if (op == OP_SQR) y = x;
            v = ref(op, x, y, pn);
            if (v != v || isinfq(v)) continue;
            if (fabsq(x) > (q_t)1.7976931348623157e308 || fabsq(y) > (q_t)1.7976931348623157e308) continue;
            j->checked++;
            /* the quad reference itself is rounded (about 2^-112 relative,
               times the condition number of f for the rounded input):
               allow 2^-96 of the magnitudes involved, far below the 2^-53
               size of any double rounding error the form must account for */
            dev = fabsq(v - form_at(z, et, 0)) - ldexpq(fabsq(v) + fabsq(x) + fabsq(y), -96);
            if (iv_affine_is_empty(z) || !(dev <= (q_t)z.e || unbounded(z)) || !ig_in(zi, v)) {
                char buf[64];
                quadmath_snprintf(buf, sizeof buf, "%.30Qg", v);
                JOB_FAIL(j, "affine %s(n=%d): a=(%a,%a,%a) b=(%a,%a,%a) d=%a -> (%a,%a,%a), f=%s", op_name[op], pn,
                         a.c, a.t, a.e, b.c, b.t, b.e, d, z.c, z.t, z.e, buf);
            }
        }
    }
    return NULL;
}

static void containment_affine(void)
{
    job_t t;
    long n = t_count(IV_PROPS_CASES);
    run_jobs(affine_worker, n, 777, &t);
    T_INT_EQ(t.bad, 0);
    T_GT(t.checked, n / 2);
    fprintf(stderr, "    %ld affine cases, %ld points checked, %ld violations\n", n, t.checked, t.bad);
}
#endif

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(containment_intervals),
#ifndef IV_NO_AFFINE
        T_CASE(containment_affine),
#endif
    };
    return T_RUN(argc, argv, cases);
}
