/* tests/test_frep_ref_models.h -- the example models of frep.h in
   __float128 closed forms, g(t) = f(o + t d): independent oracles for the
   ray tests (tests/test_frep_prepared.c) and the ray-casting bench
   (bench/bench_frep_trace.c). Constants are the doubles the parser reads
   from examples/models/ *.hf. CSG models by the signs of their alpha = 0
   R-functions (min and max). */
#ifndef FILIGREE_TEST_FREP_REF_MODELS_H
#define FILIGREE_TEST_FREP_REF_MODELS_H

#include <math.h>
#include <quadmath.h>

/* The tangle cube: -(x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8). */
static __float128 tangle_q(const double *o, const double *d, __float128 t)
{
    __float128 s = 11.8Q;
    int k;
    for (k = 0; k < 3; k++) {
        __float128 x = (__float128)o[k] + t * (__float128)d[k], x2 = x * x;
        s += x2 * x2 - 5 * x2;
    }
    return -s;
}

/* The cup: max(min(S1, -S2, 0.75 - z), min(C, z + 0.55, -0.25 - z)), S1 and
   S2 spheres of radius 1 and 0.92 about (0, 0, 0.6), C the double cone
   hfConeZ about (0, 0, -0.2) of radius 0.8. */
static __float128 cup_q(const double *o, const double *d, __float128 t)
{
    __float128 x = (__float128)o[0] + t * d[0], y = (__float128)o[1] + t * d[1], z = (__float128)o[2] + t * d[2];
    __float128 r2 = x * x + y * y + (z - 0.6) * (z - 0.6), s1 = 1 - r2, s2 = (__float128)0.92 * 0.92 - r2;
    __float128 ez = z - (-0.2), cone = ez * ez - (x * x + y * y) / ((__float128)0.8 * 0.8);
    __float128 cut = fminq(fminq(s1, -s2), (__float128)0.75 - z);
    __float128 stand = fminq(fminq(cone, z + (__float128)0.55), (__float128)-0.25 - z);
    return fmaxq(cut, stand);
}

/* Barth's sextic clipped by the ball of radius 3.4 (barth_sextic.hf), the
   golden ratio and its square as the parser's doubles. */
static __float128 barth_q(const double *o, const double *d, __float128 t)
{
    const double p = (1 + sqrt(5.0)) / 2, p2 = p * p;
    __float128 x = (__float128)o[0] + t * d[0], y = (__float128)o[1] + t * d[1], z = (__float128)o[2] + t * d[2];
    __float128 xx = x * x, yy = y * y, zz = z * z, s1 = xx + yy + zz - 1;
    __float128 f = 4 * ((__float128)p2 * xx - yy) * ((__float128)p2 * yy - zz) * ((__float128)p2 * zz - xx) -
                   (__float128)(1 + 2 * p) * s1 * s1;
    return fminq(f, (__float128)3.4 * 3.4 - (xx + yy + zz));
}

#endif
