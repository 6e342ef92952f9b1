/* ex_shade.h — a small path tracer for the example renderers.

   Materials are a Lambertian lobe plus one glossy lobe (GGX or normalised
   Blinn-Phong) with Schlick Fresnel. Light comes from rectangular area lights,
   sampled by next-event estimation and combined with BSDF sampling by multiple
   importance sampling (power heuristic), and from a gradient environment.
   The renderer supplies geometry through two callbacks, so the same shading
   serves Embree meshes, rounded-edge normals, grooves and FRep solids:

   static int hit(void *u, const ex_ray_t *r, double tmax, ex_surface_t *s) {...}
   static int occ(void *u, ex_v3_t o, ex_v3_t d, double tmax) {...}
   ex_world_t w = {0};
   w.intersect = hit; w.occluded = occ; w.user = &scene;
   w.lights = lights; w.nlights = 2; w.env = sky;
   ex_v3_t L = ex_radiance(&w, &camera_ray, rng);      // in the pixel callback

   Directions wo and wi point away from the surface. Colours are linear RGB. */
#ifndef FILIGREE_EX_SHADE_H
#define FILIGREE_EX_SHADE_H

#include "ex_camera.h"
#include "ex_math.h"
#include "ex_rng.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ex_lobe_t { EX_LOBE_GGX = 0, EX_LOBE_BLINN_PHONG = 1 } ex_lobe_t;

typedef struct ex_material_t {
    ex_v3_t diffuse;     /* Lambertian albedo */
    ex_v3_t specular;    /* reflectance at normal incidence F0: ~0.04 for plastics, the colour for
                            metals; 0 = no glossy lobe (purely diffuse) */
    double roughness;    /* 0..1, clamped to >= 0.02; GGX alpha = roughness², Blinn-Phong
                            exponent = 2/alpha² - 2 */
    ex_lobe_t lobe;      /* default (0) GGX */
    ex_v3_t emission;    /* emitted radiance, usually 0 */
    double ior;          /* > 0: smooth clear dielectric of this index (glass ~1.5), which
                            reflects or refracts by the Fresnel equations; diffuse, specular
                            and roughness are then unused. 0 = opaque */
} ex_material_t;

/* Emits `radiance` from the parallelogram corner + a·edge_u + b·edge_v,
   a, b in [0, 1], on the side of cross(edge_u, edge_v) only. */
typedef struct ex_rect_light_t {
    ex_v3_t corner, edge_u, edge_v;
    ex_v3_t radiance;
} ex_rect_light_t;

/* A width × height light centred at `center`, its emitting side facing
   `target` (saves working out which way edge_u × edge_v points). */
ex_rect_light_t ex_rect_light_toward(ex_v3_t center, ex_v3_t target, double width, double height, ex_v3_t radiance);

/* Sky radiance: `zenith` straight up (+y), `horizon` at the horizon, blended
   smoothly; `ground` for every direction below the horizon. All zero = black. */
typedef struct ex_env_t { ex_v3_t zenith, horizon, ground; } ex_env_t;

/* What the intersect callback reports. */
typedef struct ex_surface_t {
    double t;                     /* ray parameter of the hit */
    ex_v3_t p;                    /* hit point */
    ex_v3_t n;                    /* unit shading normal, outward */
    ex_v3_t ng;                   /* unit geometric normal, outward */
    const ex_material_t *mat;     /* must not be NULL */
} ex_surface_t;

/* Closest hit of ray in (0, tmax): fills *s and returns 1, or returns 0.
   `ray->has_differentials` is 1 only for camera rays. Called concurrently. */
typedef int (*ex_intersect_fn)(void *user, const ex_ray_t *ray, double tmax, ex_surface_t *s);
/* 1 when something blocks o + t·d, t in (0, tmax). Called concurrently. */
typedef int (*ex_occluded_fn)(void *user, ex_v3_t o, ex_v3_t d, double tmax);

typedef struct ex_world_t {
    ex_intersect_fn intersect;    /* required */
    ex_occluded_fn occluded;      /* required */
    void *user;                   /* passed to both callbacks */
    const ex_rect_light_t *lights;
    int nlights;
    ex_env_t env;
    int max_bounces;              /* indirect bounces; 0 → 3, negative → direct light only */
    double ray_eps;               /* secondary-ray offset along ng, scene units; 0 → 1e-4 */
    double indirect_clamp;        /* each contribution after the first bounce is clamped to this
                                     max component (kills fireflies, slightly biased);
                                     0 → 8, negative → no clamp */
} ex_world_t;

/* Radiance arriving along `ray` (one path sample). */
ex_v3_t ex_radiance(const ex_world_t *w, const ex_ray_t *ray, ex_rng_t *rng);

/* Next-event estimate of the light from every rect light reflected at s
   towards wo (one light sample each, MIS-weighted against BSDF sampling). */
ex_v3_t ex_direct_light(const ex_world_t *w, const ex_surface_t *s, ex_v3_t wo, ex_rng_t *rng);

/* f(wo, wi)·|n·wi| for unit n, wo, wi; *pdf (may be NULL) receives the
   solid-angle density with which ex_bsdf_sample picks wi. */
ex_v3_t ex_bsdf_eval(const ex_material_t *m, ex_v3_t n, ex_v3_t wo, ex_v3_t wi, double *pdf);

/* Samples wi; *weight = f·|n·wi| / pdf. Returns 0 when the sample is void
   (below the surface). */
int ex_bsdf_sample(const ex_material_t *m, ex_v3_t n, ex_v3_t wo, ex_rng_t *rng,
                   ex_v3_t *wi, ex_v3_t *weight, double *pdf);

/* The environment's radiance in unit direction d. */
ex_v3_t ex_env_radiance(const ex_env_t *env, ex_v3_t d);

/* Distance along o + t·d (unit d) to the light's front face, or 0 if missed. */
double ex_rect_light_hit(const ex_rect_light_t *l, ex_v3_t o, ex_v3_t d);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_SHADE_H */
