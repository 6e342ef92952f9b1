/* ex_math.h — the little vector math the example renderers share.
   Private to examples/ (not part of filigree's API). Doubles, right-handed. */
#ifndef FILIGREE_EX_MATH_H
#define FILIGREE_EX_MATH_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

#define EX_PI 3.14159265358979323846

typedef struct ex_v3_t { double x, y, z; } ex_v3_t;

static inline ex_v3_t ex_v3(double x, double y, double z) { ex_v3_t r; r.x = x; r.y = y; r.z = z; return r; }
static inline ex_v3_t ex_add(ex_v3_t a, ex_v3_t b) { return ex_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline ex_v3_t ex_sub(ex_v3_t a, ex_v3_t b) { return ex_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline ex_v3_t ex_scale(ex_v3_t a, double s) { return ex_v3(a.x * s, a.y * s, a.z * s); }
/* a + b*s */
static inline ex_v3_t ex_madd(ex_v3_t a, ex_v3_t b, double s) { return ex_v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
/* component-wise product (colours) */
static inline ex_v3_t ex_mul(ex_v3_t a, ex_v3_t b) { return ex_v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline ex_v3_t ex_neg(ex_v3_t a) { return ex_v3(-a.x, -a.y, -a.z); }
static inline double ex_dot(ex_v3_t a, ex_v3_t b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline ex_v3_t ex_cross(ex_v3_t a, ex_v3_t b)
{
    return ex_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double ex_len(ex_v3_t a) { return sqrt(ex_dot(a, a)); }
/* a / |a|; the zero vector stays zero. */
static inline ex_v3_t ex_normalize(ex_v3_t a)
{
    double l = ex_len(a);
    return l > 0 ? ex_scale(a, 1.0 / l) : a;
}
static inline double ex_max_comp(ex_v3_t a) { return fmax(a.x, fmax(a.y, a.z)); }
static inline double ex_clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }
/* mirror d about unit n */
static inline ex_v3_t ex_reflect(ex_v3_t d, ex_v3_t n) { return ex_madd(d, n, -2.0 * ex_dot(d, n)); }

/* Orthonormal basis (t, b, n) around unit n (Duff et al. 2017, branchless). */
static inline void ex_onb(ex_v3_t n, ex_v3_t *t, ex_v3_t *b)
{
    double s = n.z >= 0 ? 1.0 : -1.0;
    double a = -1.0 / (s + n.z), c = n.x * n.y * a;
    *t = ex_v3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    *b = ex_v3(c, s + n.y * n.y * a, -n.y);
}
/* local (x, y, z) in the basis (t, b, n) to world */
static inline ex_v3_t ex_from_local(ex_v3_t t, ex_v3_t b, ex_v3_t n, double x, double y, double z)
{
    return ex_add(ex_add(ex_scale(t, x), ex_scale(b, y)), ex_scale(n, z));
}

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_MATH_H */
