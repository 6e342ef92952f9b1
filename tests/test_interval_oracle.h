/* tests/test_interval_oracle.h — the operations of interval.h as one
   table and their __float128 references, shared by the property tests
   (test_interval_props), the tightness test (test_interval_basic) and the
   fuzz target (fuzz_interval_ops): op codes, f(x, y) in quad, the interval
   and affine evaluation of each op, the exact hull of + - * / sqrt sqr over
   an input box. */
#ifndef FILIGREE_INTERVAL_ORACLE_H
#define FILIGREE_INTERVAL_ORACLE_H

#include "test_interval_gen.h"

enum {
    OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_NEG, OP_RECIP, OP_SQR, OP_SQRT, OP_ABS,
    OP_MIN, OP_MAX, OP_ADD_D, OP_MUL_D, OP_EXP, OP_LOG, OP_SIN, OP_COS, OP_TAN,
    OP_ATAN, OP_POW, OP_HYPOT, OP_POW_N, OP_SUB_D, OP_DIV_D, OP_COUNT
};
static const char *const op_name[OP_COUNT] = {
    "add", "sub", "mul", "div", "neg", "recip", "sqr", "sqrt", "abs", "min", "max", "add_d", "mul_d",
    "exp", "log", "sin", "cos", "tan", "atan", "pow", "hypot", "pow_n", "sub_d", "div_d"};
static const int pow_ns[] = {-5, -3, -2, -1, 2, 3, 4, 5, 7, 10, 33};

/* f(x, y) in quad; NaN when (x, y) is outside f's domain. */
static q_t ref(int op, q_t x, q_t y, int n)
{
    switch (op) {
    case OP_ADD: case OP_ADD_D: return x + y;
    case OP_SUB: case OP_SUB_D: return x - y;
    case OP_MUL: case OP_MUL_D: return x * y;
    case OP_DIV: case OP_DIV_D: return y == 0 ? (q_t)NAN : x / y;
    case OP_NEG: return -x;
    case OP_RECIP: return x == 0 ? (q_t)NAN : 1 / x;
    case OP_SQR: return x * x;
    case OP_SQRT: return x < 0 ? (q_t)NAN : sqrtq(x);
    case OP_ABS: return fabsq(x);
    case OP_MIN: return x < y ? x : y;
    case OP_MAX: return x > y ? x : y;
    case OP_EXP: return expq(x);
    case OP_LOG: return x <= 0 ? (q_t)NAN : logq(x);
    case OP_SIN: return sinq(x);
    case OP_COS: return cosq(x);
    case OP_TAN: return tanq(x);
    case OP_ATAN: return atanq(x);
    case OP_POW: return (x < 0 || (x == 0 && y <= 0)) ? (q_t)NAN : powq(x, y);
    case OP_HYPOT: return sqrtq(x * x + y * y);
    default: return (x == 0 && n < 0) ? (q_t)NAN : powq(x, (q_t)n);
    }
}

/* the scalar forms (iv_add_d, ...): the second operand is a double */
static int is_scalar(int op) { return op == OP_ADD_D || op == OP_MUL_D || op == OP_SUB_D || op == OP_DIV_D; }

static int is_binary(int op)
{
    return op == OP_ADD || op == OP_SUB || op == OP_MUL || op == OP_DIV || op == OP_MIN || op == OP_MAX ||
           is_scalar(op) || op == OP_POW || op == OP_HYPOT;
}

static iv_t eval_iv(int op, iv_t a, iv_t b, int n)
{
    switch (op) {
    case OP_ADD: return iv_add(a, b);
    case OP_SUB: return iv_sub(a, b);
    case OP_MUL: return iv_mul(a, b);
    case OP_DIV: return iv_div(a, b);
    case OP_NEG: return iv_neg(a);
    case OP_RECIP: return iv_recip(a);
    case OP_SQR: return iv_sqr(a);
    case OP_SQRT: return iv_sqrt(a);
    case OP_ABS: return iv_abs(a);
    case OP_MIN: return iv_min(a, b);
    case OP_MAX: return iv_max(a, b);
    case OP_ADD_D: return iv_add_d(a, b.lo);
    case OP_MUL_D: return iv_mul_d(a, b.lo);
    case OP_SUB_D: return iv_sub_d(a, b.lo);
    case OP_DIV_D: return iv_div_d(a, b.lo);
    case OP_EXP: return iv_exp(a);
    case OP_LOG: return iv_log(a);
    case OP_SIN: return iv_sin(a);
    case OP_COS: return iv_cos(a);
    case OP_TAN: return iv_tan(a);
    case OP_ATAN: return iv_atan(a);
    case OP_POW: return iv_pow(a, b);
    case OP_HYPOT: return iv_hypot(a, b);
    default: return iv_pow_n(a, n);
    }
}

/* The exact hull of op (OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_SQRT or OP_SQR)
   over the box a x b of finite endpoints, as quad: over the corners, the
   pieces being monotone (b must not hold 0 for OP_DIV). Sums and
   differences of doubles far apart in exponent are rounded in quad, which
   only moves the reference within a double's spacing toward the result. */
static void exact_bounds(int op, iv_t a, iv_t b, q_t *lo, q_t *hi)
{
    q_t al = a.lo, ah = a.hi, bl = b.lo, bh = b.hi, c[4];
    int i;
    switch (op) {
    case OP_ADD: *lo = al + bl; *hi = ah + bh; return;
    case OP_SUB: *lo = al - bh; *hi = ah - bl; return;
    case OP_MUL: c[0] = al * bl; c[1] = al * bh; c[2] = ah * bl; c[3] = ah * bh; break;
    case OP_DIV: c[0] = al / bl; c[1] = al / bh; c[2] = ah / bl; c[3] = ah / bh; break;
    case OP_SQRT: *lo = sqrtq(al < 0 ? 0 : al); *hi = sqrtq(ah); return;
    default:
        c[0] = c[1] = al * al; c[2] = c[3] = ah * ah;
        if (al < 0 && ah > 0) c[0] = 0;
        break;
    }
    *lo = *hi = c[0];
    for (i = 1; i < 4; i++) { if (c[i] < *lo) *lo = c[i]; if (c[i] > *hi) *hi = c[i]; }
}

/* How far z's finite ends lie outside the correctly rounded ends of the
   exact hull (exact_bounds), in doubles (the larger of the two, saturated
   at 1000); -1 when z misses the exact hull. */
static long long tight_gap(int op, iv_t a, iv_t b, iv_t z)
{
    q_t lo, hi;
    double rd, ru;
    long long g = 0;
    exact_bounds(op, a, b, &lo, &hi);
    if (!((q_t)z.lo <= lo && (q_t)z.hi >= hi)) return -1;
    rd = ig_rd(lo);
    ru = ig_ru(hi);
    if (rd > -HUGE_VAL && ig_ulps(z.lo, rd) > g) g = ig_ulps(z.lo, rd);
    if (ru < HUGE_VAL && ig_ulps(ru, z.hi) > g) g = ig_ulps(ru, z.hi);
    return g;
}

#ifndef IV_NO_AFFINE
/* method: which linearisation the non-affine operations use (Taylor,
   Chebyshev, min-range or the default per-range choice), so that every
   one of them is checked; the default goes through the public functions
   (iv_affine_atan and the general iv_affine_pow_n had been reached only
   through iv__aff_unary, never themselves). */
static iv_affine_t eval_aff(int op, iv_affine_t a, iv_affine_t b, double d, int n, int method)
{
    if (method != IV__LIN_DEFAULT) {
        switch (op) {
        case OP_EXP: return iv__aff_unary(a, IV__F_EXP, 0, method);
        case OP_LOG: return iv__aff_unary(a, IV__F_LOG, 0, method);
        case OP_SQRT: return iv__aff_unary(a, IV__F_SQRT, 0, method);
        case OP_RECIP: return iv__aff_unary(a, IV__F_RECIP, -1, method);
        case OP_ATAN: return iv__aff_unary(a, IV__F_ATAN, 0, method);
        case OP_SIN: return iv__aff_unary(a, IV__F_SIN, 0, method);
        case OP_COS: return iv__aff_unary(a, IV__F_COS, 0, method);
        case OP_TAN: return iv__aff_unary(a, IV__F_TAN, 0, method);
        case OP_POW_N: if (n != 1 && n != 2 && n != 0 && n != -1) return iv__aff_unary(a, IV__F_POWN, n, method); break;
        default: break;
        }
        return eval_aff(op, a, b, d, n, IV__LIN_DEFAULT); /* an affine or fixed-method operation */
    }
    switch (op) {
    case OP_ADD: return iv_affine_add(a, b);
    case OP_SUB: return iv_affine_sub(a, b);
    case OP_MUL: return iv_affine_mul(a, b);
    case OP_DIV: return iv_affine_div(a, b);
    case OP_NEG: return iv_affine_neg(a);
    case OP_RECIP: return iv_affine_recip(a);
    case OP_SQR: return iv_affine_sqr(a);
    case OP_SQRT: return iv_affine_sqrt(a);
    case OP_ABS: return iv_affine_abs(a);
    case OP_MIN: return iv_affine_min(a, b);
    case OP_MAX: return iv_affine_max(a, b);
    case OP_ADD_D: return iv_affine_add_d(a, d);
    case OP_MUL_D: return iv_affine_mul_d(a, d);
    case OP_SUB_D: return iv_affine_sub_d(a, d);
    case OP_DIV_D: return iv_affine_div_d(a, d);
    case OP_EXP: return iv_affine_exp(a);
    case OP_LOG: return iv_affine_log(a);
    case OP_SIN: return iv_affine_sin(a);
    case OP_COS: return iv_affine_cos(a);
    case OP_TAN: return iv_affine_tan(a);
    case OP_ATAN: return iv_affine_atan(a);
    case OP_POW: return iv_affine_pow(a, b);
    case OP_HYPOT: return iv_affine_hypot(a, b);
    default: return iv_affine_pow_n(a, n);
    }
}

/* The value of form f at eps_t = et, eps_x = ex, exactly in quad. */
static q_t form_at(iv_affine_t f, q_t et, q_t ex) { return (q_t)f.c + (q_t)f.t * et + (q_t)f.e * ex; }

#endif

#endif
