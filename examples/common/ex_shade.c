/* ex_shade.c — see ex_shade.h */
#include "ex_shade.h"

#include <math.h>

#define EX__SHADE_MIN_ROUGHNESS 0.02
#define EX__SHADE_MIN_COS 1e-6

/* ---------------------------------------------------------------- lobes */

static double ex__shade_lum(ex_v3_t c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

static double ex__shade_alpha(const ex_material_t *m)
{
    double r = ex_clamp(m->roughness, EX__SHADE_MIN_ROUGHNESS, 1.0);
    return r * r;
}

static ex_v3_t ex__shade_fresnel(ex_v3_t f0, double cos_theta)
{
    double k = pow(1 - ex_clamp(cos_theta, 0, 1), 5);
    return ex_add(f0, ex_scale(ex_sub(ex_v3(1, 1, 1), f0), k));
}

/* Normal distribution of half vectors with cos = n·h (normalised: ∫ D cos dω = 1). */
static double ex__shade_ndf(const ex_material_t *m, double a, double cos_h)
{
    if (cos_h <= 0) return 0;
    if (m->lobe == EX_LOBE_BLINN_PHONG) {
        double e = 2 / (a * a) - 2;
        return (e + 2) / (2 * EX_PI) * pow(cos_h, e);
    } else {
        double a2 = a * a, k = cos_h * cos_h * (a2 - 1) + 1;
        return a2 / (EX_PI * k * k);
    }
}

/* Smith masking for GGX (also used, as an approximation, for Blinn-Phong). */
static double ex__shade_g1(double a, double cos_v)
{
    double a2 = a * a;
    return 2 * cos_v / (cos_v + sqrt(a2 + (1 - a2) * cos_v * cos_v));
}

/* Probability of choosing the glossy lobe when sampling from wo. */
static double ex__shade_p_glossy(const ex_material_t *m, double cos_o)
{
    double ws = ex__shade_lum(ex__shade_fresnel(m->specular, cos_o));
    double wd = ex__shade_lum(m->diffuse) * (1 - ex_max_comp(m->specular));
    if (ws <= 0 || ex_max_comp(m->specular) <= 0) return 0;
    if (wd <= 0) return 1;
    return ex_clamp(ws / (ws + wd), 0.1, 0.9);
}

ex_v3_t ex_bsdf_eval(const ex_material_t *m, ex_v3_t n, ex_v3_t wo, ex_v3_t wi, double *pdf)
{
    double cos_o = ex_dot(n, wo), cos_i = ex_dot(n, wi), a = ex__shade_alpha(m);
    double p_gl, cos_h, d, pdf_gl;
    ex_v3_t h, f_diff, f_gl, fr;
    if (pdf) *pdf = 0;
    if (cos_o <= EX__SHADE_MIN_COS || cos_i <= EX__SHADE_MIN_COS) return ex_v3(0, 0, 0);
    h = ex_normalize(ex_add(wo, wi));
    cos_h = ex_dot(n, h);
    d = ex__shade_ndf(m, a, cos_h);
    fr = ex__shade_fresnel(m->specular, ex_dot(wi, h));
    f_diff = ex_scale(m->diffuse, (1 - ex_max_comp(m->specular)) * cos_i / EX_PI);
    /* f·cos_i = D F G / (4 cos_o) */
    f_gl = ex_scale(fr, d * ex__shade_g1(a, cos_o) * ex__shade_g1(a, cos_i) / (4 * cos_o));
    if (ex_max_comp(m->specular) <= 0) f_gl = ex_v3(0, 0, 0);   /* F0 = 0: no glossy lobe at all */
    p_gl = ex__shade_p_glossy(m, cos_o);
    pdf_gl = d * cos_h / (4 * fabs(ex_dot(wo, h)));
    if (pdf) *pdf = p_gl * pdf_gl + (1 - p_gl) * cos_i / EX_PI;
    return ex_add(f_diff, f_gl);
}

/* A half vector around n drawn with density D(h)·(n·h). */
static ex_v3_t ex__shade_sample_half(const ex_material_t *m, double a, ex_v3_t n, double u1, double u2)
{
    ex_v3_t t, b;
    double cos_t, sin_t, phi = 2 * EX_PI * u2;
    if (m->lobe == EX_LOBE_BLINN_PHONG) cos_t = pow(u1, 1 / (2 / (a * a)));
    else cos_t = sqrt((1 - u1) / (1 + (a * a - 1) * u1));
    sin_t = sqrt(fmax(0, 1 - cos_t * cos_t));
    ex_onb(n, &t, &b);
    return ex_from_local(t, b, n, sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

int ex_bsdf_sample(const ex_material_t *m, ex_v3_t n, ex_v3_t wo, ex_rng_t *rng, ex_v3_t *wi, ex_v3_t *weight,
                   double *pdf)
{
    double cos_o = ex_dot(n, wo), u0, u_unused, u1, u2;
    ex_v3_t f;
    ex_rng_2d(rng, &u0, &u_unused);   /* stratified lobe choice: each lobe gets its share of a pixel's samples */
    ex_rng_2d(rng, &u1, &u2);
    if (cos_o <= EX__SHADE_MIN_COS) return 0;
    if (u0 < ex__shade_p_glossy(m, cos_o)) {
        ex_v3_t h = ex__shade_sample_half(m, ex__shade_alpha(m), n, u1, u2);
        *wi = ex_reflect(ex_neg(wo), h);
    } else {
        ex_v3_t t, b;
        double r = sqrt(u1), phi = 2 * EX_PI * u2;
        ex_onb(n, &t, &b);
        *wi = ex_from_local(t, b, n, r * cos(phi), r * sin(phi), sqrt(fmax(0, 1 - u1)));
    }
    f = ex_bsdf_eval(m, n, wo, *wi, pdf);
    if (!(*pdf > 0)) return 0;
    *weight = ex_scale(f, 1 / *pdf);
    return 1;
}

/* ---------------------------------------------------------------- lights */

ex_v3_t ex_env_radiance(const ex_env_t *env, ex_v3_t d)
{
    if (d.y >= 0) {
        double w = sqrt(d.y);
        return ex_add(ex_scale(env->horizon, 1 - w), ex_scale(env->zenith, w));
    } else {
        double w = fmin(1, -d.y * 8);   /* a soft horizon line */
        return ex_add(ex_scale(env->horizon, 1 - w), ex_scale(env->ground, w));
    }
}

ex_rect_light_t ex_rect_light_toward(ex_v3_t center, ex_v3_t target, double width, double height, ex_v3_t radiance)
{
    ex_rect_light_t l;
    ex_v3_t n = ex_normalize(ex_sub(target, center)), t, b;
    ex_onb(n, &t, &b);
    l.edge_u = ex_scale(t, width);
    l.edge_v = ex_scale(b, height);
    if (ex_dot(ex_cross(l.edge_u, l.edge_v), n) < 0) l.edge_v = ex_neg(l.edge_v);
    l.corner = ex_madd(ex_madd(center, l.edge_u, -0.5), l.edge_v, -0.5);
    l.radiance = radiance;
    return l;
}

double ex_rect_light_hit(const ex_rect_light_t *l, ex_v3_t o, ex_v3_t d)
{
    ex_v3_t n = ex_cross(l->edge_u, l->edge_v), q;
    double den = ex_dot(n, d), nn = ex_dot(n, n), t, a, b;
    if (den >= 0 || nn <= 0) return 0;   /* parallel, or seen from behind */
    t = ex_dot(n, ex_sub(l->corner, o)) / den;
    if (!(t > 0)) return 0;
    q = ex_sub(ex_madd(o, d, t), l->corner);
    a = ex_dot(ex_cross(q, l->edge_v), n) / nn;
    b = ex_dot(ex_cross(l->edge_u, q), n) / nn;
    return a >= 0 && a <= 1 && b >= 0 && b <= 1 ? t : 0;
}

/* Solid-angle density of uniform area sampling of l, seen at distance t along
   unit direction d. */
static double ex__shade_light_pdf(const ex_rect_light_t *l, ex_v3_t d, double t)
{
    ex_v3_t n = ex_cross(l->edge_u, l->edge_v);
    double area = ex_len(n), cos_l = -ex_dot(n, d) / area;
    return cos_l > 0 ? t * t / (cos_l * area) : 0;
}

static double ex__shade_power(double a, double b) { return a * a / (a * a + b * b); }

static double ex__shade_eps(const ex_world_t *w, ex_v3_t p)
{
    double e = w->ray_eps > 0 ? w->ray_eps : 1e-4;
    return e * (1 + fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z))) * 1e-3);
}

ex_v3_t ex_direct_light(const ex_world_t *w, const ex_surface_t *s, ex_v3_t wo, ex_rng_t *rng)
{
    ex_v3_t sum = ex_v3(0, 0, 0), o = ex_madd(s->p, s->ng, ex__shade_eps(w, s->p));
    int i;
    for (i = 0; i < w->nlights; i++) {
        const ex_rect_light_t *l = &w->lights[i];
        double u, v, dist, pdf_l, pdf_b;
        ex_v3_t x, wi, f;
        ex_rng_2d(rng, &u, &v);
        x = ex_madd(ex_madd(l->corner, l->edge_u, u), l->edge_v, v);
        wi = ex_sub(x, o);
        dist = ex_len(wi);
        if (!(dist > 0)) continue;
        wi = ex_scale(wi, 1 / dist);
        if (ex_dot(s->ng, wi) <= 0) continue;
        pdf_l = ex__shade_light_pdf(l, wi, dist);
        if (!(pdf_l > 0)) continue;
        f = ex_bsdf_eval(s->mat, s->n, wo, wi, &pdf_b);
        if (ex_max_comp(f) <= 0) continue;
        if (w->occluded(w->user, o, wi, dist * (1 - 1e-6))) continue;
        sum = ex_add(sum, ex_scale(ex_mul(l->radiance, f), ex__shade_power(pdf_l, pdf_b) / pdf_l));
    }
    return sum;
}

/* ---------------------------------------------------------------- paths */

/* Emitters seen along a ray that travels `tmax` before hitting a surface:
   rect lights (MIS-weighted against their NEE unless `pdf_b` is 0, which
   marks a camera ray) and, when nothing is hit, the environment. */
static ex_v3_t ex__shade_emitters(const ex_world_t *w, ex_v3_t o, ex_v3_t d, double tmax, int missed, double pdf_b)
{
    ex_v3_t sum = ex_v3(0, 0, 0);
    int i;
    for (i = 0; i < w->nlights; i++) {
        double t = ex_rect_light_hit(&w->lights[i], o, d), wgt = 1;
        if (!(t > 0) || (!missed && t >= tmax)) continue;
        if (pdf_b > 0) wgt = ex__shade_power(pdf_b, ex__shade_light_pdf(&w->lights[i], d, t));
        sum = ex_madd(sum, w->lights[i].radiance, wgt);
    }
    if (missed) sum = ex_add(sum, ex_env_radiance(&w->env, d));
    return sum;
}

/* Turns the surface towards wo (two-sided) and keeps the shading normal on wo's side. */
static void ex__shade_orient(ex_surface_t *s, ex_v3_t wo)
{
    double c;
    if (ex_dot(s->ng, wo) < 0) { s->ng = ex_neg(s->ng); s->n = ex_neg(s->n); }
    c = ex_dot(s->n, wo);
    if (c < 0.01) s->n = ex_normalize(ex_madd(s->n, wo, 0.01 - c));
}

/* Adds beta·c to L; after the first bounce the term is clamped to `limit`. */
static ex_v3_t ex__shade_accumulate(ex_v3_t L, ex_v3_t beta, ex_v3_t c, int depth, double limit)
{
    ex_v3_t term = ex_mul(beta, c);
    double m = ex_max_comp(term);
    if (depth > 0 && limit > 0 && m > limit) term = ex_scale(term, limit / m);
    return ex_add(L, term);
}

/* A smooth dielectric: wo reflected or refracted across n (n faces wo; eta
   = index on wo's side / index beyond), chosen at random in proportion to
   the exact Fresnel reflectance, so the path's weight stays 1. *through is
   set when it refracts. */
static ex_v3_t ex__shade_dielectric(ex_v3_t n, ex_v3_t wo, double eta, ex_rng_t *rng, int *through)
{
    double c = ex_dot(n, wo), k = 1 - eta * eta * (1 - c * c), ct = 0, F = 1;
    if (k > 0) {
        double rs, rp;
        ct = sqrt(k);
        rs = (eta * c - ct) / (eta * c + ct);
        rp = (c - eta * ct) / (c + eta * ct);
        F = 0.5 * (rs * rs + rp * rp);
    }
    *through = ex_rng_unit(rng) >= F;
    return *through ? ex_normalize(ex_madd(ex_scale(wo, -eta), n, eta * c - ct)) : ex_sub(ex_scale(n, 2 * c), wo);
}

ex_v3_t ex_radiance(const ex_world_t *w, const ex_ray_t *camera_ray, ex_rng_t *rng)
{
    double limit = w->indirect_clamp == 0 ? 8.0 : w->indirect_clamp;
    int bounces = w->max_bounces == 0 ? 3 : w->max_bounces < 0 ? 0 : w->max_bounces, depth;
    ex_v3_t L = ex_v3(0, 0, 0), beta = ex_v3(1, 1, 1);
    ex_ray_t ray = *camera_ray;
    double pdf_b = 0;
    for (depth = 0;; depth++) {
        ex_surface_t s;
        ex_v3_t wo, wi, weight;
        int hit = w->intersect(w->user, &ray, INFINITY, &s), outside;
        L = ex__shade_accumulate(L, beta, ex__shade_emitters(w, ray.o, ray.d, hit ? s.t : INFINITY, !hit, pdf_b),
                                 depth > 1 ? depth : 0, limit);
        if (!hit || depth > bounces) break;
        wo = ex_neg(ray.d);
        outside = ex_dot(s.ng, wo) > 0;
        ex__shade_orient(&s, wo);
        if (s.mat->ior > 0) { /* glass: no direct light, the ray goes on */
            int through;
            ray.d = ex__shade_dielectric(s.n, wo, outside ? 1 / s.mat->ior : s.mat->ior, rng, &through);
            ray.o = ex_madd(s.p, s.ng, through ? -ex__shade_eps(w, s.p) : ex__shade_eps(w, s.p));
            ray.has_differentials = 0;
            pdf_b = 0; /* a specular bounce: emitters seen next count in full */
            continue;
        }
        L = ex__shade_accumulate(L, beta, s.mat->emission, depth, limit);
        L = ex__shade_accumulate(L, beta, ex_direct_light(w, &s, wo, rng), depth, limit);
        if (depth == bounces && w->nlights == 0 && ex_max_comp(w->env.zenith) <= 0 &&
            ex_max_comp(w->env.horizon) <= 0 && ex_max_comp(w->env.ground) <= 0)
            break;
        if (!ex_bsdf_sample(s.mat, s.n, wo, rng, &wi, &weight, &pdf_b)) break;
        if (ex_dot(s.ng, wi) <= 0) break;   /* the shading normal bent it under the surface */
        beta = ex_mul(beta, weight);
        if (depth >= 2) {   /* Russian roulette */
            double q = fmin(0.95, ex_max_comp(beta));
            if (ex_rng_unit(rng) >= q) break;
            beta = ex_scale(beta, 1 / q);
        }
        ray.o = ex_madd(s.p, s.ng, ex__shade_eps(w, s.p));
        ray.d = wi;
        ray.has_differentials = 0;
    }
    if (!(L.x == L.x && L.y == L.y && L.z == L.z) || isinf(L.x + L.y + L.z)) return ex_v3(0, 0, 0);
    return L;
}
