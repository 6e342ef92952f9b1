/* libFuzzer target for interval.h (make fuzz; a short run in make test).
   The random property tests (test_interval_props) draw their inputs from
   fixed classes; here the fuzzer steers raw bit patterns (NaN, infinities,
   denormals, lo > hi, ends one double apart) toward new code paths, and
   every input is checked against the __float128 references of
   test_interval_oracle.h:
     byte 0  what to check: 0 one operation on intervals, 1 one operation
             on affine forms, 2 the array forms against the per-call ones,
             3 the set operations (hull, intersect, split, div_ext, width,
             mid, contains)
     byte 1  the operation (test_interval_oracle.h's OP_ codes, modulo)
     byte 2  pow_n's exponent (a signed byte), the affine linearisation
             (modulo 4), or the array length (modulo 17)
     then    up to FZ_DOUBLES doubles, 8 raw bytes each (missing bytes 0):
             the operands' ends (made by iv_make, so bad ends give the
             empty interval) and the raw values of the sample points
   Checks: an empty operand gives the empty result; a non-empty result is a
   valid interval; it contains f at every sampled point of the operands
   (their ends, a middle point and points picked by the input); + - * /
   sqrt sqr ends at most one double outside the correctly rounded ones;
   exp log sin cos tan atan pow of a point within the documented ulp
   bound; the pair path equal to the scalar path; affine forms within their
   error radius at sampled symbol values, and a form with an infinite part
   answering as the unbounded form (0, 0, inf) does; the array forms equal to the
   per-call forms bit for bit. A failed check aborts (a crash for
   libFuzzer), after printing the case. */
#define IV_IMPLEMENTATION
#include "test_interval_oracle.h"
#include "fuzz_check.h"
#include <stdint.h>

#define FZ_DOUBLES 13


static int fz_finite(double x) { return x - x == 0; }

/* A finite point of the non-empty interval x picked by the raw double s:
   s itself when it lies in x, else a point found from its fraction. */
static double fz_point(iv_t x, double s)
{
    double f, p;
    if (fz_finite(s) && x.lo <= s && s <= x.hi) return s;
    if (!fz_finite(s)) s = 0.5;
    f = fabs(s) - floor(fabs(s));
    if (x.lo == -HUGE_VAL && x.hi == HUGE_VAL) return s;
    if (x.lo == -HUGE_VAL) p = x.hi - fabs(s);
    else if (x.hi == HUGE_VAL) p = x.lo + fabs(s);
    else {
        p = x.lo + (x.hi - x.lo) * f;
        if (!fz_finite(p)) p = x.lo * (1 - f) + x.hi * f;
    }
    if (!fz_finite(p)) p = p > 0 ? DBL_MAX : -DBL_MAX;
    return p < x.lo ? x.lo : p > x.hi ? x.hi : p;
}

/* The sample points of x: its finite ends, its middle, two picked ones. */
static int fz_points(iv_t x, double s0, double s1, double out[5])
{
    int n = 0;
    if (iv_is_empty(x)) return 0;
    if (x.lo > -HUGE_VAL) out[n++] = x.lo;
    if (x.hi < HUGE_VAL) out[n++] = x.hi;
    out[n++] = fz_point(x, 0.5);
    out[n++] = fz_point(x, s0);
    out[n++] = fz_point(x, s1);
    return n;
}

static void fz_valid(iv_t z, const char *what)
{
    if (iv_is_empty(z)) {
        FUZZ_CHECK(z.lo != z.lo && z.hi != z.hi, "%s: an empty result [%a,%a] must have NaN ends", what, z.lo, z.hi);
        return;
    }
    FUZZ_CHECK(z.lo <= z.hi && z.lo < HUGE_VAL && z.hi > -HUGE_VAL, "%s: [%a,%a] is not an interval", what, z.lo, z.hi);
}

static int fz_unary(int op) { return !is_binary(op); }

/* One operation on intervals. */
static void fz_interval(int op, int n, const double *d)
{
    iv_t a = iv_make(d[0], d[1]), b = iv_make(d[2], d[3]), z;
    double xs[5], ys[5];
    int nx, ny, i, j;
    if (is_scalar(op)) {
        z = eval_iv(op, a, iv__raw(d[2], d[2]), n); /* the scalar forms read b.lo */
        if (!fz_finite(d[2])) {
            FUZZ_CHECK(iv_is_empty(z), "%s([%a,%a], %a) = [%a,%a]: a bad scalar gives the empty interval", op_name[op],
                       a.lo, a.hi, d[2], z.lo, z.hi);
            return;
        }
        b = iv_point(d[2]);
    } else {
        if (op == OP_SQRT || op == OP_LOG || op == OP_POW) a = iv_make(fabs(d[0]), fabs(d[1])); /* mostly in the domain */
        if (op == OP_POW && d[3] == 0) b = iv_point(d[2]); /* a point exponent */
        z = eval_iv(op, a, b, n);
    }
    fz_valid(z, op_name[op]);
    if (iv_is_empty(a) || (!fz_unary(op) && iv_is_empty(b))) {
        FUZZ_CHECK(iv_is_empty(z), "%s: [%a,%a], [%a,%a]: an empty operand gives the empty result, not [%a,%a]",
                   op_name[op], a.lo, a.hi, b.lo, b.hi, z.lo, z.hi);
        return;
    }
    /* containment at the sample points */
    nx = fz_points(a, d[4], d[5], xs);
    ny = fz_unary(op) ? 1 : fz_points(b, d[6], d[7], ys);
    if (fz_unary(op)) ys[0] = 0;
    for (i = 0; i < nx; i++)
        for (j = 0; j < ny; j++) {
            q_t v = ref(op, (q_t)xs[i], (q_t)ys[j], n);
            char buf[64];
            if (v != v) continue; /* outside f's domain */
            quadmath_snprintf(buf, sizeof buf, "%.36Qg", v);
            FUZZ_CHECK(!iv_is_empty(z) && ig_in(z, v), "%s(n=%d): x=%a in [%a,%a], y=%a in [%a,%a]: f=%s not in [%a,%a]",
                       op_name[op], n, xs[i], a.lo, a.hi, ys[j], b.lo, b.hi, buf, z.lo, z.hi);
        }
    /* + - * / sqrt sqr: at most one double outside the correctly rounded ends */
    if ((op == OP_ADD || op == OP_SUB || op == OP_MUL || op == OP_DIV || op == OP_SQRT || op == OP_SQR) &&
        fz_finite(a.lo) && fz_finite(a.hi) && fz_finite(b.lo) && fz_finite(b.hi) && !iv_is_empty(z) &&
        (op != OP_DIV || b.lo > 0 || b.hi < 0) && (op != OP_SQRT || a.lo >= 0)) {
        long long g = tight_gap(op, a, b, z);
        FUZZ_CHECK(g >= 0 && g <= 1, "%s: [%a,%a], [%a,%a] = [%a,%a]: %lld doubles outside the correctly rounded ends",
                   op_name[op], a.lo, a.hi, b.lo, b.hi, z.lo, z.hi, g);
    }
    /* the libm-based functions at a point: the documented ulp bound */
    if ((op == OP_EXP || op == OP_LOG || op == OP_SIN || op == OP_COS || op == OP_TAN || op == OP_ATAN ||
         (op == OP_POW && b.lo == b.hi)) && a.lo == a.hi && !iv_is_empty(z)) {
        q_t v = ref(op, (q_t)a.lo, (q_t)b.lo, n);
        if (v == v && fabsq(v) >= (q_t)DBL_MIN) {
            double rd = ig_rd(v), ru = ig_ru(v);
            /* sin, cos, tan of |x| >= 2^20 go through the header's own reduction */
            int bound = (op == OP_SIN || op == OP_COS || op == OP_TAN) && fabs(a.lo) >= 1048576.0 ? LIBM_REDUCED_BOUND : LIBM_BOUND;
            FUZZ_CHECK((rd == -HUGE_VAL || ig_ulps(z.lo, rd) <= bound) && (ru == HUGE_VAL || ig_ulps(ru, z.hi) <= bound),
                       "%s(%a, %a) = [%a,%a]: more than %d doubles outside [%a,%a]", op_name[op], a.lo, b.lo, z.lo, z.hi,
                       bound, rd, ru);
        }
    }
#ifdef IV__PAIR
    /* the pair path gives the scalar path's intervals */
    FUZZ_CHECK(ig_same(iv__add2(a, b), iv__add1(a, b)) && ig_same(iv__sub2(a, b), iv__sub1(a, b)) &&
               ig_same(iv__mul2(a, b), iv__mul1(a, b)) && ig_same(iv__mul_d2(a, d[2]), iv__mul_d1(a, d[2])) &&
               ig_same(iv__sqr2(a), iv__sqr1(a)) && ig_same(iv__sqrt2(a), iv__sqrt1(a)) &&
               (!(b.lo > 0) || ig_same(iv__div_pos2(a, b), iv__div_pos1(a, b))),
               "[%a,%a], [%a,%a], d=%a: the pair path differs from the scalar path", a.lo, a.hi, b.lo, b.hi, d[2]);
#endif
}

#ifndef IV_NO_AFFINE
/* A form from raw doubles, e made >= 0: finite parts as they are, any
   NaN part the empty form, else (some part infinite) the parts as they are:
   a form with an infinite part, which interval.h reads as the unbounded
   form (0, 0, inf). */
static iv_affine_t fz_form(double c, double t, double e)
{
    iv_affine_t f;
    f.c = c, f.t = t, f.e = fabs(e);
    if (c != c || t != t || e != e) f.c = f.t = f.e = NAN;
    return f;
}
static int fz_infinite_part(iv_affine_t f) { return !iv_affine_is_empty(f) && !(fz_finite(f.c) && fz_finite(f.t) && fz_finite(f.e)); }
/* the unbounded form a form with an infinite part stands for */
static iv_affine_t fz_canonical(iv_affine_t f)
{
    if (fz_infinite_part(f)) f.c = f.t = 0, f.e = HUGE_VAL;
    return f;
}
/* the same set: both empty, both unbounded (e = inf or an infinite part:
   neg keeps the parts, negated), or the same parts */
static int fz_same_form(iv_affine_t x, iv_affine_t y)
{
    int ux = !iv_affine_is_empty(x) && (x.e == HUGE_VAL || fz_infinite_part(x));
    int uy = !iv_affine_is_empty(y) && (y.e == HUGE_VAL || fz_infinite_part(y));
    if (iv_affine_is_empty(x) || iv_affine_is_empty(y)) return iv_affine_is_empty(x) && iv_affine_is_empty(y);
    if (ux || uy) return ux && uy;
    return memcmp(&x, &y, sizeof x) == 0;
}

/* a noise symbol's value in [-1, 1] from a raw double */
static q_t fz_eps(double s) { return !fz_finite(s) ? 1 : (q_t)(2 * (fabs(s) - floor(fabs(s))) - 1); }

/* One operation on affine forms: at each sampled (eps_t, eps_a, eps_b),
   f(a, b) is within z.e of z.c + z.t eps_t, and in iv_from_affine(z)
   (the same claim and slack as test_interval_props' affine_worker). */
static void fz_affine(int op, int n, int method, const double *d)
{
    iv_affine_t a = fz_form(d[0], d[1], d[2]), b = fz_form(d[3], d[4], d[5]), z;
    iv_t zi;
    int k;
    if (op == OP_SQR) b = a;
    z = eval_aff(op, a, b, d[6], n, method);
    zi = iv_from_affine(z);
    fz_valid(zi, "iv_from_affine");
    /* a form with an infinite part answers as the unbounded form (interval.h) */
    if (fz_infinite_part(a) || (is_binary(op) && !is_scalar(op) && fz_infinite_part(b))) {
        iv_affine_t w = eval_aff(op, fz_canonical(a), is_binary(op) && !is_scalar(op) ? fz_canonical(b) : b, d[6], n, method);
        iv_t wi = iv_from_affine(fz_canonical(a));
        FUZZ_CHECK(fz_same_form(z, w), "affine %s(n=%d, method %d): a=(%a,%a,%a) b=(%a,%a,%a) d=%a -> (%a,%a,%a), as (0,0,inf): (%a,%a,%a)",
                   op_name[op], n, method, a.c, a.t, a.e, b.c, b.t, b.e, d[6], z.c, z.t, z.e, w.c, w.t, w.e);
        FUZZ_CHECK(!fz_infinite_part(a) || (wi.lo == -HUGE_VAL && wi.hi == HUGE_VAL && iv_from_affine(a).lo == -HUGE_VAL &&
                                            iv_from_affine(a).hi == HUGE_VAL),
                   "iv_from_affine(%a,%a,%a) is not the entire line", a.c, a.t, a.e);
        return;
    }
    if (iv_affine_is_empty(a) || (is_binary(op) && !is_scalar(op) && iv_affine_is_empty(b)) ||
        (is_scalar(op) && !fz_finite(d[6]))) {
        FUZZ_CHECK(iv_affine_is_empty(z), "affine %s: an empty operand gives the empty form, not (%a,%a,%a)", op_name[op],
                   z.c, z.t, z.e);
        return;
    }
    FUZZ_CHECK(iv_affine_is_empty(z) || (z.e >= 0 && fz_finite(z.c) && fz_finite(z.t)),
               "affine %s: (%a,%a,%a) is not a form", op_name[op], z.c, z.t, z.e);
    if (a.e == HUGE_VAL || b.e == HUGE_VAL || fz_infinite_part(a) || fz_infinite_part(b)) return;
    for (k = 0; k < 4; k++) {
        q_t et = k == 0 ? 1 : k == 1 ? -1 : fz_eps(d[7 + k]), ea = fz_eps(d[8 + k]), eb = fz_eps(d[9 + k]), v, dev, slack;
        q_t x = form_at(a, et, ea), y = is_scalar(op) ? (q_t)d[6] : form_at(b, et, eb);
        if (!is_binary(op)) y = 0;
        char buf[64];
        if (op == OP_SQR) y = x;
        v = ref(op, x, y, n);
        if (v != v || isinfq(v) || fabsq(x) > (q_t)DBL_MAX || fabsq(y) > (q_t)DBL_MAX) continue;
        /* the quad reference is rounded too (x and y are sums of doubles
           up to 2^2000 apart): 2^-96 of the magnitudes */
        slack = ldexpq(fabsq(v) + fabsq(x) + fabsq(y), -96);
        dev = fabsq(v - form_at(z, et, 0)) - slack;
        quadmath_snprintf(buf, sizeof buf, "%.30Qg", v);
        FUZZ_CHECK(!iv_affine_is_empty(z) && (dev <= (q_t)z.e || z.e == HUGE_VAL) &&
                   (q_t)zi.lo - slack <= v && v <= (q_t)zi.hi + slack,
                   "affine %s(n=%d, method %d): a=(%a,%a,%a) b=(%a,%a,%a) d=%a -> (%a,%a,%a), f=%s", op_name[op], n, method,
                   a.c, a.t, a.e, b.c, b.t, b.e, d[6], z.c, z.t, z.e, buf);
    }
}
#endif

/* The array forms of + - * give the per-call intervals bit for bit (signs
   of zeros included), at every length up to 16, in place too. */
static void fz_arrays(int op, unsigned len, const double *d)
{
    iv_t a[16], b[16], want[16], got[16];
    double alo[16], ahi[16], blo[16], bhi[16], olo[16], ohi[16];
    unsigned i;
    op %= 3;
    for (i = 0; i < len; i++) {
        a[i] = iv_make(d[i % FZ_DOUBLES], d[(i * 5 + 1) % FZ_DOUBLES]);
        b[i] = iv_make(d[(i * 7 + 2) % FZ_DOUBLES], d[(i * 3 + 3) % FZ_DOUBLES]);
        want[i] = op == 0 ? iv_add(a[i], b[i]) : op == 1 ? iv_sub(a[i], b[i]) : iv_mul(a[i], b[i]);
        alo[i] = a[i].lo, ahi[i] = a[i].hi, blo[i] = b[i].lo, bhi[i] = b[i].hi;
    }
    if (op == 0) iv_add_n(got, a, b, len), iv_add_soa(olo, ohi, alo, ahi, blo, bhi, len);
    else if (op == 1) iv_sub_n(got, a, b, len), iv_sub_soa(olo, ohi, alo, ahi, blo, bhi, len);
    else iv_mul_n(got, a, b, len), iv_mul_soa(olo, ohi, alo, ahi, blo, bhi, len);
    for (i = 0; i < len; i++)
        FUZZ_CHECK(ig_same_bits(got[i], want[i]) && ig_same_bits(iv__raw(olo[i], ohi[i]), want[i]),
                   "array op %d, n %u, element %u: [%a,%a], [%a,%a]: arrays [%a,%a] and [%a,%a], per call [%a,%a]", op,
                   len, i, a[i].lo, a[i].hi, b[i].lo, b[i].hi, got[i].lo, got[i].hi, olo[i], ohi[i], want[i].lo, want[i].hi);
    /* in place: the output is the first operand */
    if (op == 0) iv_add_n(a, a, b, len);
    else if (op == 1) iv_sub_n(a, a, b, len);
    else iv_mul_n(a, a, b, len);
    for (i = 0; i < len; i++)
        FUZZ_CHECK(ig_same_bits(a[i], want[i]), "array op %d in place, n %u, element %u: [%a,%a], per call [%a,%a]", op, len,
                   i, a[i].lo, a[i].hi, want[i].lo, want[i].hi);
}

/* hull, intersect, split, div_ext, width, mid, contains at sampled points. */
static void fz_sets(const double *d)
{
    iv_t a = iv_make(d[0], d[1]), b = iv_make(d[2], d[3]), h = iv_hull(a, b), m = iv_intersect(a, b), l, r, piece[2];
    double xs[5], ys[5];
    int nx = fz_points(a, d[4], d[5], xs), ny = fz_points(b, d[6], d[7], ys), i, j, np;
    fz_valid(h, "hull");
    fz_valid(m, "intersect");
    for (i = 0; i < nx; i++) {
        FUZZ_CHECK(iv_contains(a, xs[i]) && iv_contains(h, xs[i]), "hull/contains: %a in [%a,%a], hull [%a,%a]", xs[i], a.lo,
                   a.hi, h.lo, h.hi);
        FUZZ_CHECK(iv_contains(m, xs[i]) == iv_contains(b, xs[i]), "intersect: %a in [%a,%a] and [%a,%a]: [%a,%a]", xs[i],
                   a.lo, a.hi, b.lo, b.hi, m.lo, m.hi);
    }
    if (!iv_is_empty(a)) {
        double w = iv_width(a), mid = iv_mid(a);
        FUZZ_CHECK((q_t)w >= (q_t)a.hi - (q_t)a.lo && iv_contains(a, mid), "width/mid of [%a,%a]: %a, %a", a.lo, a.hi, w, mid);
        int sp = iv_split(a, &l, &r);
        fz_valid(l, "split");
        fz_valid(r, "split");
        FUZZ_CHECK(l.lo == a.lo && r.hi == a.hi && l.hi == r.lo && l.hi >= a.lo && l.hi <= a.hi,
                   "split [%a,%a] into [%a,%a] and [%a,%a]", a.lo, a.hi, l.lo, l.hi, r.lo, r.hi);
        /* proper halves exactly when a double lies strictly inside */
        FUZZ_CHECK(sp == (nextafter(a.lo, HUGE_VAL) < a.hi) && (sp ? l.hi > a.lo && l.hi < a.hi : l.hi == a.lo || l.hi == a.hi),
                   "split [%a,%a] returned %d with m = %a", a.lo, a.hi, sp, l.hi);
    }
    /* a / b as pieces: every quotient lies in one of them */
    np = iv_div_ext(a, b, piece);
    FUZZ_CHECK(np >= 0 && np <= 2, "div_ext gave %d pieces", np);
    for (i = 0; i < np; i++) fz_valid(piece[i], "div_ext");
    for (i = 0; i < nx; i++)
        for (j = 0; j < ny; j++) {
            q_t v = (q_t)xs[i] / (q_t)ys[j];
            int k, in = 0;
            if (ys[j] == 0) continue;
            for (k = 0; k < np; k++) in |= !iv_is_empty(piece[k]) && ig_in(piece[k], v);
            FUZZ_CHECK(in, "div_ext [%a,%a] / [%a,%a]: %a / %a in none of %d pieces", a.lo, a.hi, b.lo, b.hi, xs[i], ys[j], np);
        }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    double d[FZ_DOUBLES];
    uint8_t raw[8 * FZ_DOUBLES];
    int mode, op, k;
    if (size < 3) return 0;
    memset(raw, 0, sizeof raw);
    memcpy(raw, data + 3, size - 3 < sizeof raw ? size - 3 : sizeof raw);
    memcpy(d, raw, sizeof d);
    mode = data[0] % 4, op = data[1] % OP_COUNT, k = (int)(int8_t)data[2];
    if (mode == 0) fz_interval(op, k, d);
#ifndef IV_NO_AFFINE
    else if (mode == 1) fz_affine(op, pow_ns[(unsigned)data[2] % (sizeof pow_ns / sizeof pow_ns[0])], data[2] % 4, d);
#endif
    else if (mode == 2) fz_arrays(op, data[2] % 17u, d);
    else if (mode == 3) fz_sets(d);
    return 0;
}
