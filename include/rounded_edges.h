/* rounded_edges.h — rounded corners and edges for triangle meshes (part of filigree)

   Rounding cylinders and spheres inside the convex edges and corners of a
   triangle mesh, found from a hit on the sharp mesh (Courtin et al. 2019).

   USAGE
     In exactly one C or C++ file:
         #define RE_IMPLEMENTATION
         #include "rounded_edges.h"
     Everywhere else just #include "rounded_edges.h".
   OPTIONS (define before including)
     RE_IMPLEMENTATION  emit the implementation in this translation unit
     RE_STATIC          make every function static (private to this file)
     RE_DEF             linkage of public functions (default extern)
     RE_ASSERT(c)       internal-invariant check (default assert)
     RE_MALLOC(sz,ctx) / RE_FREE(p,ctx)   allocator hooks (default malloc/free)
   CONVENTIONS
     See docs/conventions.md: results are re_result_t codes with RE_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_RE_H
#define FILIGREE_RE_H

#include <stddef.h>
#include <math.h>
#ifndef RE_DEF
#  ifdef RE_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define RE_DEF static __attribute__((unused))
#    else
#      define RE_DEF static
#    endif
#  else
#    define RE_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. RE_OK is 0; re_result_string() names each. */
typedef enum re_result_t {
    RE_OK = 0,
    RE_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    RE_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    RE_RESULT_COUNT_
} re_result_t;

/* A human-readable name for a result code; never NULL. */
RE_DEF const char *re_result_string(re_result_t r);

/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
/* ---- Bevel-shader baselines (issue 6, item 3) --------------------------
   Two normal-only "bevel" shaders that the rounded-edge method is compared
   with. They do not change the geometry: they return a shading normal for a
   hit P with outward normal N on the sharp mesh, by casting probe rays
   through a host-supplied trace callback, so any renderer can run them.
   Both are pure and allocation-free; the caller passes the sample count and
   a seed, so they are deterministic and thread-safe (if the callback is).
   Details and measured behaviour: docs/rounded_edges.md, "Bevel baselines". */

/* One hit reported by the host's tracer. */
typedef struct re_trace_hit_t {
    double t;         /* ray parameter of the hit, in units of the ray's dir */
    double normal[3]; /* unit geometric normal pointing OUT of the solid (the
                         triangle's right-hand normal), not flipped toward the ray */
    unsigned object;  /* host object id of the hit primitive */
} re_trace_hit_t;

/* Host ray cast: the nearest hit with tmin < t < tmax along origin + t*dir.
   Returns nonzero and fills *hit when there is one, 0 otherwise. It must be
   safe to call from several threads at once if the baselines are. */
typedef int (*re_trace_fn)(void *user, const double origin[3], const double dir[3],
                           double tmin, double tmax, re_trace_hit_t *hit);

/* The bevel shader of the OSL blog post (bevel_shader_osl_blog.txt): from the
   point P - delta*N below the surface, cast rays along N + perturb*d, d in the
   tangent disk, and average N with the normals they hit. */
typedef struct re_bevel_blog_desc_t {
    double delta;   /* depth of the probe origin below P along -N, scene units.
                       Required, > 0 (the blog's Delta). */
    double perturb; /* tangent of the probe cone's half angle (the blog's Perturb),
                       > 0. Default (0): 1, which gives a blend band of width
                       about delta on each face of a right-angle edge, i.e. the
                       width of a rounding of radius delta. */
    int rays;       /* probe rays, >= 1. Default (0): 27, the blog's Divisions = 3. */
    unsigned seed;  /* rotates the direction set; every value is valid */
} re_bevel_blog_desc_t;

/* A Cycles-style bevel (Blender's Bevel node): points on the surface of the
   same object within a sphere of radius R around P are found by rays across
   that sphere, through disks sampled with the cubic falloff along one of
   three axes, and their normals are averaged with Cycles' weights (cubic
   falloff of the distance to P, power-heuristic MIS over the three axes). */
typedef struct re_bevel_cycles_desc_t {
    double radius; /* R, scene units. Required, > 0. */
    int samples;   /* disk samples, >= 1. Default (0): 4, Cycles' default. */
    unsigned seed; /* rotates the sample set; every value is valid */
} re_bevel_cycles_desc_t;

typedef struct re_bevel_result_t {
    double normal[3]; /* unit shading normal; N itself when no probe found a surface */
    int rays;         /* calls made to the trace callback */
    int hits;         /* hits that contributed to the average */
} re_bevel_result_t;

/* Most hits on the same object taken along one Cycles-style probe segment
   (Cycles keeps a random subset of 4; a closed mesh gives at most 2 within a
   sphere smaller than its features, so we keep the first 8 in ray order). */
#define RE_BEVEL_MAX_HITS 8
/* After a hit, the next one along a Cycles-style probe is searched from
   t + RE_BEVEL_STEP_REL * R: far above float tracers' self-intersection
   error for R down to 1e-3 of the object, and small enough that two distinct
   surfaces closer than it along one probe count once. */
#define RE_BEVEL_STEP_REL 1e-4

/* Blog bevel at P (on the surface) with unit outward normal n. Returns
   RE_ERR_INVALID_ARG for NULL pointers, a non-finite or non-positive delta or
   perturb, or rays < 0 (out is then untouched). */
RE_DEF re_result_t re_bevel_blog(const re_bevel_blog_desc_t *desc, const double p[3],
                                 const double n[3], re_trace_fn trace, void *user,
                                 re_bevel_result_t *out);
/* Cycles-style bevel at P (on object `object`) with unit outward normal n.
   Hits on other objects are skipped. RE_ERR_INVALID_ARG as above. */
RE_DEF re_result_t re_bevel_cycles(const re_bevel_cycles_desc_t *desc, const double p[3],
                                   const double n[3], unsigned object, re_trace_fn trace,
                                   void *user, re_bevel_result_t *out);
/* ==== [end section: baselines] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_RE_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef RE_IMPLEMENTATION
#ifndef FILIGREE_RE_IMPLEMENTATION_DONE
#define FILIGREE_RE_IMPLEMENTATION_DONE

#ifndef RE_ASSERT
#  include <assert.h>
#  define RE_ASSERT(c) assert(c)
#endif
#if defined(RE_MALLOC) != defined(RE_FREE)
#  error "define both RE_MALLOC and RE_FREE, or neither"
#endif
#ifndef RE_MALLOC
#  include <stdlib.h>
#  define RE_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define RE_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

RE_DEF const char *re_result_string(re_result_t r)
{
    switch (r) {
    case RE_OK: return "ok";
    case RE_ERR_INVALID_ARG: return "invalid argument";
    case RE_ERR_OUT_OF_MEMORY: return "out of memory";
    case RE_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
/* ---- Bevel-shader baselines: implementation ---------------------------- */

#define RE__BV_PI 3.14159265358979323846
/* The golden angle pi(3 - sqrt 5): successive spiral points never line up. */
#define RE__BV_GOLDEN_ANGLE 2.39996322972865332223
/* Convergence of the cubic-falloff radius solve, on the dimensionless x = r/R. */
#define RE__BV_ROOT_EPS 1e-13

static double re__bv_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Unit a into out; returns 0 (out untouched) when a is zero or not finite. */
static int re__bv_unit(const double a[3], double out[3])
{
    double len = sqrt(re__bv_dot(a, a));
    if (!(len > 0) || !(len < HUGE_VAL)) return 0;
    out[0] = a[0] / len; out[1] = a[1] / len; out[2] = a[2] / len;
    return 1;
}

/* Orthonormal t, b completing unit n (Duff et al. 2017, "Building an
   orthonormal basis, revisited"): branch-free apart from the sign, exact for
   axis-aligned n, so probes on a box face run along its edges. */
static void re__bv_frame(const double n[3], double t[3], double b[3])
{
    double s = n[2] >= 0 ? 1.0 : -1.0;
    double a = -1.0 / (s + n[2]);
    double c = n[0] * n[1] * a;
    t[0] = 1.0 + s * n[0] * n[0] * a; t[1] = s * c; t[2] = -s * n[0];
    b[0] = c; b[1] = s + n[1] * n[1] * a; b[2] = -n[1];
}

/* Seed -> uniform [0,1): splitmix64 finaliser, so nearby seeds decorrelate. */
static double re__bv_seed_unit(unsigned seed, unsigned long long stream)
{
    unsigned long long z = (unsigned long long)seed * 0x9E3779B97F4A7C15ull + stream;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* Van der Corput radical inverse in base 2 (the Hammersley second coordinate). */
static double re__bv_radical_inverse(unsigned i)
{
    unsigned long long v = i & 0xFFFFFFFFull, r = 0;
    int k;
    for (k = 0; k < 32; k++) { r = (r << 1) | (v & 1u); v >>= 1; }
    return (double)r * (1.0 / 4294967296.0);
}

static double re__bv_frac(double x) { return x - floor(x); }

static int re__bv_check_common(const double p[3], const double n[3], re_trace_fn trace,
                               const void *desc, const re_bevel_result_t *out)
{
    int k;
    if (!desc || !p || !n || !trace || !out) return 0;
    for (k = 0; k < 3; k++)
        if (!(p[k] - p[k] == 0) || !(n[k] - n[k] == 0)) return 0; /* NaN or Inf */
    return re__bv_dot(n, n) > 0;
}

RE_DEF re_result_t re_bevel_blog(const re_bevel_blog_desc_t *desc, const double p[3],
                                 const double n[3], re_trace_fn trace, void *user,
                                 re_bevel_result_t *out)
{
    double nu[3], t[3], b[3], o[3], sum[3], perturb, phi0;
    int rays, i, k, hits = 0;
    if (!re__bv_check_common(p, n, trace, desc, out)) return RE_ERR_INVALID_ARG;
    perturb = desc->perturb == 0 ? 1.0 : desc->perturb;
    rays = desc->rays == 0 ? 27 : desc->rays;
    if (!(desc->delta > 0) || !(desc->delta < HUGE_VAL) || !(perturb > 0) || !(perturb < HUGE_VAL)
        || rays < 1)
        return RE_ERR_INVALID_ARG;
    if (!re__bv_unit(n, nu)) return RE_ERR_INVALID_ARG;
    re__bv_frame(nu, t, b);
    /* Blog, line 10: the probe origin lies delta below P along -N. */
    for (k = 0; k < 3; k++) { o[k] = p[k] - desc->delta * nu[k]; sum[k] = nu[k]; }
    /* The blog perturbs N by Perlin noise, which it calls "rather awful" for
       its uneven spread. We use a Vogel (golden-angle) spiral instead: the
       i-th offset lies at radius sqrt((i + 1/2)/rays) of the unit tangent
       disk, so the directions cover the cone N + perturb*disk with uniform
       density for any ray count; the seed rotates the spiral. */
    phi0 = 2.0 * RE__BV_PI * re__bv_seed_unit(desc->seed, 1);
    for (i = 0; i < rays; i++) {
        double rho = perturb * sqrt(((double)i + 0.5) / (double)rays);
        double phi = phi0 + RE__BV_GOLDEN_ANGLE * (double)i;
        double cp = rho * cos(phi), sp = rho * sin(phi), d[3], s;
        re_trace_hit_t h;
        for (k = 0; k < 3; k++) d[k] = nu[k] + cp * t[k] + sp * b[k];
        if (!trace(user, o, d, 0.0, HUGE_VAL, &h)) continue;
        /* The blog subtracts OSL's N at the hit, which faces the probe ray;
           adding the hit normal turned along the probe is the same, whatever
           side the host's normal points to. */
        s = re__bv_dot(h.normal, d) >= 0 ? 1.0 : -1.0;
        for (k = 0; k < 3; k++) sum[k] += s * h.normal[k];
        hits++;
    }
    /* The blog divides by the count, then normalises: the division does not
       change the direction, so we only normalise. */
    if (!re__bv_unit(sum, out->normal))
        for (k = 0; k < 3; k++) out->normal[k] = nu[k];
    out->rays = rays;
    out->hits = hits;
    return RE_OK;
}

/* Cubic falloff (R - r)^3 up to its normalisation 10/(pi R^5), which cancels
   in the ratio Cycles takes (svm_bevel: bssrdf_cubic_pdf(r) / pdf(disk_r)). */
static double re__bv_cubic(double radius, double r)
{
    double f = radius - r;
    return r < radius ? f * f * f : 0.0;
}

/* Disk radius x = r/R with the cubic falloff's CDF equal to u:
   10x^2 - 20x^3 + 15x^4 - 4x^5 = u (the integral of 2 pi r (R - r)^3,
   normalised). No closed form; safeguarded Newton (the derivative is
   20x(1-x)^3), as Cycles solves it with Newton-Raphson. */
static double re__bv_cubic_radius(double u)
{
    double lo = 0.0, hi = 1.0, x = sqrt(u / 10.0);
    int it;
    if (x >= 1.0) x = 0.5;
    for (it = 0; it < 100; it++) {
        double x2 = x * x;
        double g = x2 * (10.0 + x * (-20.0 + x * (15.0 - 4.0 * x))) - u;
        double om = 1.0 - x, dg = 20.0 * x * om * om * om, xn;
        if (g < 0) lo = x; else hi = x;
        xn = dg > 0 ? x - g / dg : 0.5 * (lo + hi);
        if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
        if (fabs(xn - x) <= RE__BV_ROOT_EPS) { x = xn; break; }
        x = xn;
    }
    return x;
}

RE_DEF re_result_t re_bevel_cycles(const re_bevel_cycles_desc_t *desc, const double p[3],
                                   const double n[3], unsigned object, re_trace_fn trace,
                                   void *user, re_bevel_result_t *out)
{
    /* pick probabilities of the three disk axes (N, T, B), as Cycles */
    static const double pick[3] = {0.5, 0.25, 0.25};
    double axes[3][3], sum[3] = {0, 0, 0}, R, step, off_u, off_v;
    int samples, i, k, calls = 0, hits = 0;
    if (!re__bv_check_common(p, n, trace, desc, out)) return RE_ERR_INVALID_ARG;
    R = desc->radius;
    samples = desc->samples == 0 ? 4 : desc->samples;
    if (!(R > 0) || !(R < HUGE_VAL) || samples < 1) return RE_ERR_INVALID_ARG;
    if (!re__bv_unit(n, axes[0])) return RE_ERR_INVALID_ARG;
    re__bv_frame(axes[0], axes[1], axes[2]);
    step = RE_BEVEL_STEP_REL * R;
    /* Hammersley points (i + 1/2)/n, radical inverse of i, shifted by a
       seeded Cranley-Patterson rotation: stratified, and unbiased over seeds. */
    off_u = re__bv_seed_unit(desc->seed, 2);
    off_v = re__bv_seed_unit(desc->seed, 3);
    for (i = 0; i < samples; i++) {
        double u = re__bv_frac(((double)i + 0.5) / (double)samples + off_u);
        double v = re__bv_frac(re__bv_radical_inverse((unsigned)i) + off_v);
        const double *dn, *dt, *db;
        double rd, h, phi, o[3], d[3], tmin, pdf_disk;
        int a, nh;
        /* Axis choice: N with probability 1/2, T and B with 1/4 each; u is
           reused for the azimuth after rescaling, as in Cycles. */
        if (u < 0.5) { a = 0; u *= 2.0; }
        else if (u < 0.75) { a = 1; u = (u - 0.5) * 4.0; }
        else { a = 2; u = (u - 0.75) * 4.0; }
        dn = axes[a]; dt = axes[(a + 1) % 3]; db = axes[(a + 2) % 3];
        rd = re__bv_cubic_radius(v) * R;
        if (!(rd < R)) continue; /* u at the top of [0,1): zero-weight sample */
        /* The probe crosses the whole sphere: it starts at height h above the
           disk point and runs 2h along -axis. */
        h = sqrt(R * R - rd * rd);
        phi = 2.0 * RE__BV_PI * u;
        for (k = 0; k < 3; k++) {
            o[k] = p[k] + h * dn[k] + rd * (cos(phi) * dt[k] + sin(phi) * db[k]);
            d[k] = -dn[k];
        }
        pdf_disk = re__bv_cubic(R, rd);
        tmin = 0.0;
        for (nh = 0; nh < RE_BEVEL_MAX_HITS; nh++) {
            re_trace_hit_t hit;
            double pdf[3], hp[3], dist, w;
            calls++;
            if (!trace(user, o, d, tmin, 2.0 * h, &hit)) break;
            tmin = hit.t + step;
            if (hit.object != object) continue; /* same object only, as Cycles' local BVH query */
            for (k = 0; k < 3; k++) {
                pdf[k] = pick[k] * fabs(re__bv_dot(axes[k], hit.normal));
                hp[k] = o[k] + hit.t * d[k] - p[k];
            }
            /* Power-heuristic MIS over the three axes; the disk densities are
               left out of pdf[] and corrected by the falloff ratio below:
               summed over the axes, the estimator is unbiased for the
               falloff-weighted integral of n over the surface in the sphere. */
            w = pdf[a] / (pdf[0] * pdf[0] + pdf[1] * pdf[1] + pdf[2] * pdf[2]);
            if (!(w > 0) || !(w < HUGE_VAL)) continue;
            dist = sqrt(re__bv_dot(hp, hp));
            w *= re__bv_cubic(R, dist) / pdf_disk;
            for (k = 0; k < 3; k++) sum[k] += w * hit.normal[k];
            hits++;
        }
    }
    if (!re__bv_unit(sum, out->normal))
        for (k = 0; k < 3; k++) out->normal[k] = axes[0][k];
    out->rays = calls;
    out->hits = hits;
    return RE_OK;
}
/* ==== [end section: baselines] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_RE_IMPLEMENTATION_DONE */
#endif /* RE_IMPLEMENTATION */

/*
MIT License

Copyright (c) 2026 the filigree authors

Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
*/
