/* scripts/fingerprint/fp_interval.c — interval.h's answers, hashed: every
   operation (intervals and affine forms) on random operands drawn with
   signed zeros, denormals, infinities, huge and tiny magnitudes, points and
   intervals straddling 0. */
#define IV_IMPLEMENTATION
#include "interval.h"
#include <math.h>
#include <stdio.h>
#include "test.h"
#include "fp.h"

static double draw(t_rng_t *r)
{
    static const double special[] = {0.0, -0.0, 1.0, -1.0, 2.0, 0.5, HUGE_VAL, -HUGE_VAL, 4.9e-324, -4.9e-324, 1e300, -1e300, 3.141592653589793};
    unsigned long long u = t_rng_u64(r);
    if (u % 8 == 0) return special[(u >> 3) % (sizeof special / sizeof *special)];
    return (u & 16 ? -1 : 1) * ldexp(1 + t_rng_unit(r), (int)((u >> 5) % 41) - 20 + (u % 64 == 1 ? 600 : 0) - (u % 64 == 2 ? 1040 : 0));
}

static iv_t draw_iv(t_rng_t *r)
{
    double a = draw(r), b = t_rng_u64(r) % 4 == 0 ? a : draw(r);
    return a <= b ? iv_make(a, b) : iv_make(b, a);
}

static unsigned long long h_iv(unsigned long long h, iv_t x) { return fp_hash(h, &x, sizeof x); }
static unsigned long long h_af(unsigned long long h, iv_affine_t x) { return fp_hash(h, &x, sizeof x); }

int main(int argc, char **argv)
{
    long n = argc > 1 ? atol(argv[1]) : 200000, q;
    unsigned long long hi = FP_START, ha = FP_START;
    t_rng_t rng;
    rng.s = 2026;
    for (q = 0; q < n; q++) {
        iv_t a = draw_iv(&rng), b = draw_iv(&rng), ext[2];
        double s = draw(&rng);
        int k = (int)(t_rng_u64(&rng) % 11) - 4, np;
        iv_affine_t x = iv_affine_from_iv(a), y = iv_affine_from_iv(b), t = iv_affine_ray_param(-1.0, 2.0 + t_rng_unit(&rng));
        hi = h_iv(hi, iv_add(a, b)), hi = h_iv(hi, iv_sub(a, b)), hi = h_iv(hi, iv_mul(a, b)), hi = h_iv(hi, iv_div(a, b));
        hi = h_iv(hi, iv_add_d(a, s)), hi = h_iv(hi, iv_sub_d(a, s)), hi = h_iv(hi, iv_mul_d(a, s));
        hi = h_iv(hi, iv_neg(a)), hi = h_iv(hi, iv_recip(a)), hi = h_iv(hi, iv_sqr(a)), hi = h_iv(hi, iv_sqrt(a));
        hi = h_iv(hi, iv_pow_n(a, k)), hi = h_iv(hi, iv_pow(a, b)), hi = h_iv(hi, iv_exp(a)), hi = h_iv(hi, iv_log(a));
        hi = h_iv(hi, iv_sin(a)), hi = h_iv(hi, iv_cos(a)), hi = h_iv(hi, iv_tan(a)), hi = h_iv(hi, iv_atan(a));
        hi = h_iv(hi, iv_abs(a)), hi = h_iv(hi, iv_min(a, b)), hi = h_iv(hi, iv_max(a, b)), hi = h_iv(hi, iv_hypot(a, b));
        hi = h_iv(hi, iv_hull(a, b)), hi = h_iv(hi, iv_intersect(a, b));
        np = iv_div_ext(a, b, ext);
        hi = fp_hash(hi, &np, sizeof np);
        if (np > 0) hi = h_iv(hi, ext[0]);
        if (np > 1) hi = h_iv(hi, ext[1]);
        /* affine: a correlated form (x + t) against y, and the ray symbol alone */
        x = iv_affine_add(x, iv_affine_mul_d(t, 0.25));
        ha = h_af(ha, iv_affine_add(x, y)), ha = h_af(ha, iv_affine_sub(x, y)), ha = h_af(ha, iv_affine_mul(x, y));
        ha = h_af(ha, iv_affine_div(x, y)), ha = h_af(ha, iv_affine_sqr(x)), ha = h_af(ha, iv_affine_neg(x));
        ha = h_af(ha, iv_affine_add_d(x, s)), ha = h_af(ha, iv_affine_sub_d(x, s)), ha = h_af(ha, iv_affine_mul_d(x, s));
        ha = h_af(ha, iv_affine_recip(x)), ha = h_af(ha, iv_affine_sqrt(x)), ha = h_af(ha, iv_affine_pow_n(x, k));
        ha = h_af(ha, iv_affine_pow(x, y)), ha = h_af(ha, iv_affine_exp(x)), ha = h_af(ha, iv_affine_log(x));
        ha = h_af(ha, iv_affine_sin(x)), ha = h_af(ha, iv_affine_cos(x)), ha = h_af(ha, iv_affine_tan(x));
        ha = h_af(ha, iv_affine_atan(x)), ha = h_af(ha, iv_affine_abs(x)), ha = h_af(ha, iv_affine_min(x, y));
        ha = h_af(ha, iv_affine_max(x, y)), ha = h_af(ha, iv_affine_hypot(x, y)), ha = h_af(ha, iv_affine_sqr(t));
        ha = h_iv(ha, iv_from_affine(x));
    }
    printf("interval  intervals %016llx  affine %016llx  (%ld operand sets)\n", hi, ha, n);
    return 0;
}
