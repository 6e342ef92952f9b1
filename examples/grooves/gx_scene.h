/* gx_scene.h — the grooves example's scenes and its two renderers, shared
   with bench/bench_grooves.c (header-only, static functions).

   World space is texture space: the grooved plane is z = 0 over the tile
   [0,1]², u = x, v = y, W = z up. Every scene is rendered two ways with one
   shading model (ex_bsdf_eval from examples/common, directional lights, a
   constant ambient term):
     ours      the plane is two triangles in Embree; at each hit the footprint
               comes from the camera's ray differentials and gr_query() returns
               the visible facets, shaded by eq. 6 (1 sample per pixel), with
               grooves.h's default normals (tilted by f'(t), turned along
               curved paths where the view ray meets each facet);
     geometry  the same grooves swept into a triangle mesh in Embree
               (tests/grooves_oracle.h) and ray traced at N jittered samples
               per pixel with one shadow ray per light. */
#ifndef GX_SCENE_H
#define GX_SCENE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grooves.h"
#include "grooves_oracle.h"
#include "ex_camera.h"
#include "ex_embree.h"
#include "ex_math.h"
#include "ex_render.h"
#include "ex_shade.h"

#define GX_MAX_MATS 4
#define GX_MAX_LIGHTS 2
#define GX_SCRATCH (1 << 21) /* per-pixel stack scratch for gr_query (the polygon path's boolean work) */

typedef struct gx_scene_t {
    const char *name, *title;
    gr_groove_desc_t *desc;       /* grooves as grooves.h describes them */
    gro_groove_t *geo;            /* the same, for the geometry renderer */
    int ngrooves;
    double *store;                /* points and sections of every groove */
    ex_material_t mats[GX_MAX_MATS]; /* by reflectance id; 0 is the base surface */
    double light[GX_MAX_LIGHTS][3];  /* unit directions toward the lights */
    ex_v3_t radiance[GX_MAX_LIGHTS];
    int nlights;
    ex_v3_t ambient, background;
    ex_v3_t eye, at;
    double fov;                   /* vertical, degrees */
    ex_v3_t bench_eye, bench_at;  /* a closer view that sees only the tile (no plane edge, */
    double bench_fov;             /* no sky): bench_grooves measures grooves, not silhouettes */
    double exposure;              /* stops, for the PNG */
    /* [inter-reflection scenes, §6] depth > 0: specular bounces, both
       renderers; spec by reflectance id; below: radiance of what lies
       behind a transmitting facet (the room behind the glass) */
    int depth;
    gr_specular_t spec[GX_MAX_MATS];
    ex_v3_t below;
    int lines_panel;              /* --demo adds a panel with 2 line samples (§5.6) at junctions */
} gx_scene_t;

static ex_material_t gx_material(double r, double g, double b, double f0r, double f0g, double f0b, double rough)
{
    ex_material_t m;
    memset(&m, 0, sizeof m);
    m.diffuse = ex_v3(r, g, b);
    m.specular = ex_v3(f0r, f0g, f0b);
    m.roughness = rough;
    return m;
}

static void gx_dir(double elev_deg, double azim_deg, double *d)
{
    double e = elev_deg * EX_PI / 180, a = azim_deg * EX_PI / 180;
    d[0] = cos(e) * cos(a); d[1] = cos(e) * sin(a); d[2] = sin(e);
}

static int gx_alloc(gx_scene_t *s, int ngrooves, size_t ndoubles)
{
    s->ngrooves = ngrooves;
    s->desc = (gr_groove_desc_t *)calloc((size_t)ngrooves, sizeof *s->desc);
    s->geo = (gro_groove_t *)calloc((size_t)ngrooves, sizeof *s->geo);
    s->store = (double *)calloc(ndoubles, sizeof(double));
    return s->desc && s->geo && s->store ? 0 : -1;
}

static void gx_scene_free(gx_scene_t *s)
{
    free(s->desc); free(s->geo); free(s->store);
    memset(s, 0, sizeof *s);
}

/* Figure 14: 250 touching parallel V-grooves running away from the viewer,
   a few pixels wide in front and hundreds per pixel at the horizon (macro-
   to micro-geometry), lit from low on the right so that one wall of each V
   is lit and the other in shadow; masking changes from left to right. */
static int gx_scene_parallel(gx_scene_t *s)
{
    int i, n = 250;
    double a = 0.5 / n, *sec, *pts;
    memset(s, 0, sizeof *s);
    s->name = "parallel"; s->title = "250 parallel V-grooves, near to far (Fig. 14)";
    if (gx_alloc(s, n, 6 + 4 * (size_t)n)) return -1;
    sec = s->store; pts = s->store + 6;
    sec[0] = -a; sec[1] = 0; sec[2] = 0.2 * a; sec[3] = -1.1 * a; sec[4] = a; sec[5] = 0; /* asymmetric V */
    for (i = 0; i < n; i++) {
        double u = (i + 0.5) / n;
        pts[4 * i] = u; pts[4 * i + 1] = 0; pts[4 * i + 2] = u; pts[4 * i + 3] = 1;
        s->desc[i].points = pts + 4 * i; s->desc[i].point_count = 2;
        s->desc[i].section = sec; s->desc[i].section_count = 3;
        s->desc[i].reflectance = 1;
    }
    s->mats[0] = gx_material(0.5, 0.5, 0.5, 0.04, 0.04, 0.04, 0.5);
    s->mats[1] = gx_material(0.40, 0.25, 0.14, 0.9, 0.64, 0.35, 0.3); /* brushed copper */
    s->nlights = 2;
    gx_dir(30, 10, s->light[0]); s->radiance[0] = ex_v3(3.2, 3.0, 2.7);
    gx_dir(55, 120, s->light[1]); s->radiance[1] = ex_v3(0.45, 0.5, 0.65);
    s->ambient = ex_v3(0.06, 0.07, 0.09);
    s->background = ex_v3(0.20, 0.24, 0.32);
    s->eye = ex_v3(0.45, -0.06, 0.035); s->at = ex_v3(0.52, 0.6, 0.0); s->fov = 50;
    s->bench_eye = ex_v3(0.5, 0.03, 0.06); s->bench_at = ex_v3(0.52, 0.22, 0.0); s->bench_fov = 20;
    return 0;
}

/* Figure 2: a curved groove with a sinusoidal perturbation and a straight
   one that shrinks along its path, each with its own BRDF. */
static double gx_sine(double t, void *u) { (void)u; return 1.0 + 0.45 * sin(6 * EX_PI * t); }
static double gx_shrink(double t, void *u) { (void)u; return 1.0 - 0.85 * t; }
static int gx_scene_curves(gx_scene_t *s)
{
    static const double curve[8] = {0.15, 0.2, 0.3, 0.95, 0.75, -0.1, 0.85, 0.75};
    static const double line[4] = {0.08, 0.9, 0.66, 0.93};
    double *sec;
    memset(s, 0, sizeof *s);
    s->name = "curves"; s->title = "curved groove (sine perturbation), straight groove (shrinking) (Fig. 2)";
    if (gx_alloc(s, 2, 18)) return -1;
    sec = s->store;
    /* rounded U (curved groove), and a V with a raised lip (straight groove) */
    {
        static const double u[10] = {-0.03, 0, -0.024, -0.02, 0, -0.028, 0.024, -0.02, 0.03, 0};
        static const double v[8] = {-0.028, 0, -0.022, 0.006, 0, -0.024, 0.028, 0};
        memcpy(sec, u, sizeof u);
        memcpy(sec + 10, v, sizeof v);
    }
    s->desc[0].kind = GR_PATH_CUBIC; s->desc[0].points = curve; s->desc[0].point_count = 4;
    s->desc[0].section = sec; s->desc[0].section_count = 5; s->desc[0].reflectance = 1;
    s->desc[0].perturb = gx_sine; s->desc[0].perturb_max = 1.45;
    s->desc[1].points = line; s->desc[1].point_count = 2;
    s->desc[1].section = sec + 10; s->desc[1].section_count = 4; s->desc[1].reflectance = 2;
    s->desc[1].perturb = gx_shrink; s->desc[1].perturb_max = 1.0;
    s->mats[0] = gx_material(0.62, 0.60, 0.55, 0.04, 0.04, 0.04, 0.45);  /* pale stone */
    s->mats[1] = gx_material(0.05, 0.12, 0.35, 0.3, 0.35, 0.45, 0.2);    /* blue glaze */
    s->mats[2] = gx_material(0.45, 0.08, 0.05, 0.05, 0.05, 0.05, 0.3);   /* red lacquer */
    s->nlights = 2;
    gx_dir(40, 200, s->light[0]); s->radiance[0] = ex_v3(2.6, 2.5, 2.3);
    gx_dir(70, 10, s->light[1]); s->radiance[1] = ex_v3(0.6, 0.65, 0.8);
    s->ambient = ex_v3(0.10, 0.11, 0.13);
    s->background = ex_v3(0.20, 0.24, 0.32);
    s->eye = ex_v3(0.5, -0.45, 0.75); s->at = ex_v3(0.5, 0.5, 0.0); s->fov = 50;
    s->bench_eye = s->eye; s->bench_at = ex_v3(0.5, 0.45, 0.0); s->bench_fov = 16;
    return 0;
}

/* Scratches on polished metal: 60 thin isolated V-grooves (lines and
   quadratic curves), far narrower than a pixel, catching a low light. */
static int gx_scene_scratches(gx_scene_t *s)
{
    int i, n = 60;
    double *sec, *pts;
    ex_rng_t rng = ex_rng_for_sample(0x5eed, 0, 0, 0);
    memset(s, 0, sizeof *s);
    s->name = "scratches"; s->title = "scratches on polished metal (isolated thin grooves)";
    if (gx_alloc(s, n, 8 + 6 * (size_t)n)) return -1;
    sec = s->store; pts = s->store + 8;
    sec[0] = -0.0006; sec[1] = 0; sec[2] = 0.0001; sec[3] = -0.0005; sec[4] = 0.0006; sec[5] = 0;
    for (i = 0; i < n; i++) {
        double cu = 0.1 + 0.8 * ex_rng_unit(&rng), cv = 0.1 + 0.8 * ex_rng_unit(&rng);
        double ang = EX_PI * ex_rng_unit(&rng), len = 0.1 + 0.3 * ex_rng_unit(&rng), bend = 0.15 * (ex_rng_unit(&rng) - 0.5);
        double du = 0.5 * len * cos(ang), dv = 0.5 * len * sin(ang);
        double *p = pts + 6 * i;
        p[0] = cu - du; p[1] = cv - dv;
        p[2] = cu - bend * dv; p[3] = cv + bend * du;
        p[4] = cu + du; p[5] = cv + dv;
        s->desc[i].kind = GR_PATH_QUADRATIC; s->desc[i].points = p; s->desc[i].point_count = 3;
        s->desc[i].section = sec; s->desc[i].section_count = 3;
        s->desc[i].reflectance = 0;
    }
    s->mats[0] = gx_material(0.02, 0.02, 0.02, 0.95, 0.93, 0.88, 0.12);   /* polished steel */
    s->nlights = 2;
    gx_dir(35, 80, s->light[0]); s->radiance[0] = ex_v3(4.0, 3.9, 3.6);
    gx_dir(50, 250, s->light[1]); s->radiance[1] = ex_v3(1.2, 1.25, 1.4);
    s->ambient = ex_v3(0.15, 0.16, 0.18);
    s->background = ex_v3(0.20, 0.24, 0.32);
    s->eye = ex_v3(0.5, -0.35, 0.45); s->at = ex_v3(0.5, 0.55, 0.0); s->fov = 45;
    s->bench_eye = s->eye; s->bench_at = ex_v3(0.5, 0.5, 0.0); s->bench_fov = 16;
    return 0;
}

/* [inter-reflection scenes, §6] */
static void gx_spec(gr_specular_t *sp, double kr, double kt, double ior)
{
    sp->kr[0] = sp->kr[1] = sp->kr[2] = kr;
    sp->kt[0] = sp->kt[1] = sp->kt[2] = kt;
    sp->ior = ior;
}

/* Groove i: the straight path (u0, v0)-(u1, v1), stored at pts + 4 i. */
static void gx_line_groove(gx_scene_t *s, int i, double *pts, double u0, double v0, double u1, double v1,
                           const double *sec, int nsec, int refl)
{
    double *p = pts + 4 * i;
    p[0] = u0; p[1] = v0; p[2] = u1; p[3] = v1;
    s->desc[i].points = p; s->desc[i].point_count = 2;
    s->desc[i].section = sec; s->desc[i].section_count = nsec; s->desc[i].reflectance = refl;
}

/* Start a scene of n straight grooves: its points array, or NULL. */
static double *gx_begin(gx_scene_t *s, const char *name, const char *title, int n)
{
    memset(s, 0, sizeof *s);
    s->name = name; s->title = title;
    return gx_alloc(s, n, 4 * (size_t)n) ? NULL : s->store;
}

/* One sun, sky colour, and the camera (the bench view is the same place
   looking narrower). */
static void gx_sun_view(gx_scene_t *s, double elev, double azim, ex_v3_t rad, ex_v3_t sky, ex_v3_t eye, ex_v3_t at)
{
    s->nlights = 1;
    gx_dir(elev, azim, s->light[0]); s->radiance[0] = rad;
    s->background = sky;
    s->eye = eye; s->at = at; s->fov = 45;
    s->bench_eye = eye; s->bench_at = at; s->bench_fov = 20;
}

/* Figure 21d: a window frame protruding over glass, with inter-reflection:
   three mullions each way (raised bars crossing at right angles) over a
   thin glass pane (ior 1.5, Fresnel: about 8 % reflected at normal
   incidence for both faces, more at grazing angles; the rest goes
   straight through to the room behind, the host's callback); the frame
   is glossy paint reflecting 25 %. */
static int gx_scene_frame(gx_scene_t *s)
{
    static const double bar[10] = {-0.018, 0, -0.016, 0.03, 0, 0.036, 0.016, 0.03, 0.018, 0};
    int i;
    double *pts = gx_begin(s, "frame", "window frame protruding over glass, inter-reflection depth 2 (Fig. 21d)", 6);
    if (!pts) return -1;
    for (i = 0; i < 6; i++) {
        double c = 0.2 + 0.3 * (i % 3);
        if (i < 3) gx_line_groove(s, i, pts, 0.05, c, 0.95, c, bar, 5, 1);
        else gx_line_groove(s, i, pts, c, 0.05, c, 0.95, bar, 5, 1);
    }
    s->mats[0] = gx_material(0.0, 0.0, 0.0, 0.04, 0.04, 0.04, 0.05);     /* glass (its reflection is k_r) */
    s->mats[1] = gx_material(0.55, 0.52, 0.46, 0.04, 0.04, 0.04, 0.35);  /* painted frame */
    gx_spec(&s->spec[0], 1, 1, 1.5);
    s->spec[0].fresnel = 1;
    s->spec[0].thin = 1;
    gx_spec(&s->spec[1], 0.25, 0, 0);
    s->depth = 2;
    s->below = ex_v3(0.9, 0.7, 0.45);                                    /* a warm room */
    gx_sun_view(s, 35, 60, ex_v3(3.0, 2.9, 2.7), ex_v3(0.35, 0.45, 0.65), ex_v3(0.35, -0.25, 0.35), ex_v3(0.5, 0.45, 0.0));
    return 0;
}

/* Figure 17: inter-reflections inside grooves: polished gold V-grooves of
   three opening angles, one crossing them, rendered with 3 bounces (the
   deep ones light up from their walls' mirror images). */
static int gx_scene_interreflect(gx_scene_t *s)
{
    static const double v1[6] = {-0.03, 0, 0, -0.03, 0.03, 0}, v2[6] = {-0.02, 0, 0, -0.05, 0.02, 0};
    static const double v3[6] = {-0.04, 0, 0, -0.015, 0.04, 0};
    static const double *secs[4] = {v1, v2, v3, v1};
    int i;
    double *pts = gx_begin(s, "interreflect", "inter-reflections in gold V-grooves, depth 3 (Fig. 17)", 4);
    if (!pts) return -1;
    for (i = 0; i < 4; i++) {
        double c = 0.25 + 0.25 * i;
        if (i < 3) gx_line_groove(s, i, pts, c, 0.05, c, 0.95, secs[i], 3, 1);
        else gx_line_groove(s, i, pts, 0.05, 0.6, 0.95, 0.6, secs[i], 3, 1);
    }
    s->mats[0] = gx_material(0.35, 0.33, 0.3, 0.04, 0.04, 0.04, 0.5);    /* matte stone */
    s->mats[1] = gx_material(0.02, 0.015, 0.005, 0.9, 0.7, 0.3, 0.15);   /* polished gold */
    gx_spec(&s->spec[1], 0.8, 0, 0);
    s->depth = 3;
    gx_sun_view(s, 50, 100, ex_v3(3.2, 3.0, 2.8), ex_v3(0.3, 0.38, 0.55), ex_v3(0.5, -0.35, 0.5), ex_v3(0.5, 0.5, 0.0));
    return 0;
}

/* Two directional lights (elevation, azimuth in degrees, radiance), an
   ambient term and the usual sky. */
static void gx_two_lights(gx_scene_t *s, const double l0[5], const double l1[5], ex_v3_t ambient)
{
    s->nlights = 2;
    gx_dir(l0[0], l0[1], s->light[0]); s->radiance[0] = ex_v3(l0[2], l0[3], l0[4]);
    gx_dir(l1[0], l1[1], s->light[1]); s->radiance[1] = ex_v3(l1[2], l1[3], l1[4]);
    s->ambient = ambient;
    s->background = ex_v3(0.20, 0.24, 0.32);
}

/* Figures 15/16: a tiled floor, 12 x 12 tiles whose grout lines cross at
   every corner (gr_query takes the polygon path there, §5.2-5.5, or 2 line
   samples in the demo's second panel); the grout (reflectance 1) differs
   from the glazed tiles (0). */
static int gx_scene_tiles(gx_scene_t *s)
{
    int i, n = 13;
    double *sec, *pts, a = 0.006;
    memset(s, 0, sizeof *s);
    s->name = "tiles"; s->title = "tiled floor: crossing grout lines (Figs. 15-16)";
    if (gx_alloc(s, 2 * n, 8 + 8 * (size_t)n)) return -1;
    sec = s->store; pts = s->store + 8;
    sec[0] = -a; sec[1] = 0; sec[2] = -0.6 * a; sec[3] = -0.6 * a; sec[4] = 0.6 * a; sec[5] = -0.6 * a;
    sec[6] = a; sec[7] = 0;
    for (i = 0; i < n; i++) {
        double c = (i + 0.5) / n;
        double *p = pts + 8 * i;
        p[0] = c; p[1] = 0; p[2] = c; p[3] = 1;  /* along v */
        p[4] = 0; p[5] = c; p[6] = 1; p[7] = c;  /* along u */
        s->desc[2 * i].points = p; s->desc[2 * i + 1].points = p + 4;
        s->desc[2 * i].point_count = s->desc[2 * i + 1].point_count = 2;
        s->desc[2 * i].section = s->desc[2 * i + 1].section = sec;
        s->desc[2 * i].section_count = s->desc[2 * i + 1].section_count = 4;
        s->desc[2 * i].reflectance = s->desc[2 * i + 1].reflectance = 1;
    }
    s->mats[0] = gx_material(0.55, 0.50, 0.42, 0.06, 0.06, 0.06, 0.15); /* glazed tile */
    s->mats[1] = gx_material(0.30, 0.29, 0.27, 0.02, 0.02, 0.02, 0.8);  /* grout */
    {
        static const double key[5] = {25, 60, 3.0, 2.9, 2.6}, fill[5] = {60, 220, 0.5, 0.55, 0.7};
        gx_two_lights(s, key, fill, ex_v3(0.08, 0.08, 0.09));
    }
    s->eye = ex_v3(0.5, -0.25, 0.3); s->at = ex_v3(0.5, 0.45, 0.0); s->fov = 50;
    s->bench_eye = ex_v3(0.5, 0.1, 0.12); s->bench_at = ex_v3(0.5, 0.4, 0.0); s->bench_fov = 20;
    s->lines_panel = 1; /* Fig. 16: polygons, 2 line samples, geometry */
    return 0;
}

/* Figure 21c: bricks in running bond. Bed joints run the whole width; each
   head joint ends on the bed joints above and below it (intersected ends,
   T junctions). The mortar's walls (1) and its floor (2) differ from the
   brick (0): per-facet reflectance ids. */
static int gx_scene_bricks(gx_scene_t *s)
{
    static const int mortar[3] = {1, 2, 1};
    int i, j, rows = 16, cols = 8, n = (rows + 1) + rows * cols, g = 0;
    double *sec, *pts, a = 0.005, h = 1.0 / rows;
    memset(s, 0, sizeof *s);
    s->name = "bricks"; s->title = "bricks with mortar: T junctions, per-facet materials (Fig. 21c)";
    if (gx_alloc(s, n, 8 + 4 * (size_t)n)) return -1;
    sec = s->store; pts = s->store + 8;
    sec[0] = -a; sec[1] = 0; sec[2] = -a; sec[3] = -0.6 * a; sec[4] = a; sec[5] = -0.6 * a; sec[6] = a; sec[7] = 0;
    for (i = 0; i <= rows; i++, g++) { /* bed joints */
        double *p = pts + 4 * g;
        p[0] = 0; p[1] = i * h; p[2] = 1; p[3] = i * h;
        s->desc[g].points = p;
    }
    for (i = 0; i < rows; i++)
        for (j = 0; j < cols; j++, g++) { /* head joints, staggered by half a brick */
            double *p = pts + 4 * g, u = (j + 0.5 * (i % 2) + 0.25) / cols;
            p[0] = u; p[1] = i * h; p[2] = u; p[3] = (i + 1) * h;
            s->desc[g].points = p;
        }
    for (g = 0; g < n; g++) {
        s->desc[g].point_count = 2;
        s->desc[g].section = sec; s->desc[g].section_count = 4;
        s->desc[g].facet_reflectance = mortar;
    }
    s->mats[0] = gx_material(0.45, 0.17, 0.10, 0.03, 0.03, 0.03, 0.7); /* brick */
    s->mats[1] = gx_material(0.55, 0.53, 0.48, 0.02, 0.02, 0.02, 0.9); /* mortar walls */
    s->mats[2] = gx_material(0.40, 0.39, 0.36, 0.02, 0.02, 0.02, 0.9); /* mortar bed */
    {
        static const double key[5] = {30, 150, 3.0, 2.8, 2.5}, fill[5] = {65, 20, 0.5, 0.55, 0.7};
        gx_two_lights(s, key, fill, ex_v3(0.08, 0.08, 0.09));
    }
    s->eye = ex_v3(0.5, -0.35, 0.5); s->at = ex_v3(0.5, 0.5, 0.0); s->fov = 50;
    s->bench_eye = ex_v3(0.5, 0.15, 0.2); s->bench_at = ex_v3(0.5, 0.45, 0.0); s->bench_fov = 20;
    return 0;
}

/* A scratch field (issue 8's scene list): 140 scratches on brushed
   aluminium, long and short, straight and bent, that cross one another
   and end in view, several pixels wide near the camera. Half are clean
   (asymmetric) V cuts; the others have the lips a stylus ploughs up beside
   the cut (w > 0: protrusions at the crossings). A low raking light
   catches their walls. gr_query() answers the footprints at their
   crossings, ends and corners with the polygon path (§5.2-5.5), so this
   is its cost in a render; --demo adds a panel with 2 line samples. */
static int gx_scene_scratchfield(gx_scene_t *s)
{
    static const double v[6] = {-1, 0, 0.15, -0.9, 1, 0};
    static const double lips[14] = {-1.6, 0, -1.2, 0.22, -0.8, 0, 0, -0.8, 0.8, 0, 1.2, 0.22, 1.6, 0};
    int i, k, n = 140;
    double *store;
    ex_rng_t rng = ex_rng_for_sample(0x5c7a7c4, 1, 2, 3);
    memset(s, 0, sizeof *s);
    s->name = "scratchfield"; s->title = "a scratch field: scratches that cross and end (polygons, §5)";
    if (gx_alloc(s, n, 20 * (size_t)n)) return -1;
    store = s->store;
    for (i = 0; i < n; i++) {
        double cu = 0.05 + 0.9 * ex_rng_unit(&rng), cv = 0.05 + 0.9 * ex_rng_unit(&rng);
        double ang = EX_PI * ex_rng_unit(&rng), len = 0.04 + 0.36 * ex_rng_unit(&rng) * ex_rng_unit(&rng);
        double bend = ex_rng_unit(&rng) < 0.35 ? 0.25 * (ex_rng_unit(&rng) - 0.5) : 0;
        double half = 0.0015 + 0.0035 * ex_rng_unit(&rng);
        double du = 0.5 * len * cos(ang), dv = 0.5 * len * sin(ang), *p = store + 20 * i, *sec = p + 6;
        int lipped = ex_rng_unit(&rng) < 0.5, ns = lipped ? 7 : 3;
        p[0] = cu - du; p[1] = cv - dv;
        p[2] = cu - bend * dv; p[3] = cv + bend * du;
        p[4] = cu + du; p[5] = cv + dv;
        for (k = 0; k < 2 * ns; k++) sec[k] = half * (lipped ? lips[k] : v[k]);
        if (bend != 0) {
            s->desc[i].kind = GR_PATH_QUADRATIC;
            s->desc[i].point_count = 3;
        } else { /* a segment: its end points */
            p[2] = p[4]; p[3] = p[5];
            s->desc[i].point_count = 2;
        }
        s->desc[i].points = p;
        s->desc[i].section = sec;
        s->desc[i].section_count = ns;
        s->desc[i].reflectance = 0;
    }
    s->mats[0] = gx_material(0.10, 0.10, 0.11, 0.91, 0.92, 0.93, 0.2); /* brushed aluminium */
    {
        static const double key[5] = {20, -35, 4.0, 3.9, 3.6}, fill[5] = {50, 215, 0.8, 0.85, 1.0};
        gx_two_lights(s, key, fill, ex_v3(0.12, 0.13, 0.15));
    }
    s->eye = ex_v3(0.5, -0.12, 0.32); s->at = ex_v3(0.5, 0.5, 0.0); s->fov = 45;
    s->bench_eye = ex_v3(0.5, 0.12, 0.16); s->bench_at = ex_v3(0.5, 0.5, 0.0); s->bench_fov = 22;
    s->lines_panel = 1;
    return 0;
}

typedef int (*gx_scene_fn)(gx_scene_t *);
static const char *const gx_scene_names[] = {"parallel", "curves",      "scratches", "tiles", "bricks",
                                             "frame",    "interreflect", "scratchfield", NULL};
static const gx_scene_fn gx_scene_makers[] = {gx_scene_parallel, gx_scene_curves,       gx_scene_scratches,
                                              gx_scene_tiles,    gx_scene_bricks,       gx_scene_frame,
                                              gx_scene_interreflect, gx_scene_scratchfield};

/* Switches the scene to its benchmark view. */
static void gx_scene_bench_view(gx_scene_t *s)
{
    s->eye = s->bench_eye; s->at = s->bench_at; s->fov = s->bench_fov;
}

/* Builds scene `name`; 0, or -1 for an unknown name or no memory. */
static int gx_scene_make(gx_scene_t *s, const char *name)
{
    int i, j;
    for (i = 0; gx_scene_names[i]; i++)
        if (!strcmp(name, gx_scene_names[i])) {
            if (gx_scene_makers[i](s)) return -1;
            for (j = 0; j < s->ngrooves; j++) s->geo[j] = gro_from_gr(&s->desc[j]);
            return 0;
        }
    return -1;
}

/* The shading both renderers share: ambient plus the directional lights. */
static ex_v3_t gx_shade(const gx_scene_t *s, int refl, const double *n, const double *e, const unsigned *lit_mask,
                        const double *lit_frac)
{
    const ex_material_t *m = &s->mats[refl >= 0 && refl < GX_MAX_MATS ? refl : 0];
    ex_v3_t nn = ex_v3(n[0], n[1], n[2]), wo = ex_v3(e[0], e[1], e[2]);
    ex_v3_t c = ex_mul(s->ambient, m->diffuse);
    int k;
    for (k = 0; k < s->nlights; k++) {
        double w = lit_frac ? lit_frac[k] : (double)((*lit_mask >> k) & 1u);
        if (w > 0) {
            ex_v3_t f = ex_bsdf_eval(m, nn, wo, ex_v3(s->light[k][0], s->light[k][1], s->light[k][2]), NULL);
            c = ex_madd(c, ex_mul(f, s->radiance[k]), w);
        }
    }
    return c;
}

static int gx_camera(const gx_scene_t *s, ex_camera_t *cam, int w, int h)
{
    return ex_camera_init(cam, s->eye, s->at, ex_v3(0, 0, 1), s->fov, w, h);
}

/* ---------------------------------------------------------------- ours */

typedef struct gx_ours_t {
    const gx_scene_t *s;
    gr_grid_t *grid;
    size_t grid_bytes;
    gro_device_t dev;
    RTCScene plane;
    long long embree_bytes;       /* Embree's bytes once the plane is committed */
    int perturb_normals;          /* gr_query_t.perturb_normals: 0 true normals, -1 §4.4's */
    int straight_occlusion;       /* gr_query_t.straight_occlusion: 0 the ray profile, 1 §4.3's */
    int line_samples;             /* gr_query_t.line_samples: 0 polygons at crossings and ends,
                                     n > 0 n line samples (§5.6); the §6 scenes take 2 for 0 */
    ex_camera_t cam;
} gx_ours_t;

/* Builds the grid and the two-triangle plane. 0, or -1 after one line. */
static int gx_ours_init(gx_ours_t *o, const gx_scene_t *s, int w, int h)
{
    static const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    gr_grid_desc_t gd;
    gr_diag_t diag;
    gr_result_t r;
    memset(o, 0, sizeof *o);
    o->s = s;
    memset(&gd, 0, sizeof gd);
    gd.grooves = s->desc; gd.groove_count = s->ngrooves; gd.no_wrap = 1;
    r = gr_grid_build(&gd, &o->grid, &diag);
    if (r != GR_OK) { fprintf(stderr, "grooves: %s: %s\n", s->name, diag.message); return -1; }
    if (gr_grid_size(&gd, &o->grid_bytes, NULL) != GR_OK) o->grid_bytes = 0;
    if (gr_query_scratch_bytes(o->grid) > GX_SCRATCH) {
        fprintf(stderr, "grooves: %s needs %zu bytes of query scratch (more than %d)\n", s->name,
                gr_query_scratch_bytes(o->grid), GX_SCRATCH);
        return -1;
    }
    if (gro_device_init(&o->dev)) { fprintf(stderr, "grooves: Embree does not start\n"); return -1; }
    o->plane = rtcNewScene(o->dev.dev);
    if (ex_embree_add_mesh(o->dev.dev, o->plane, pos, 4, idx, 2) == RTC_INVALID_GEOMETRY_ID ||
        ex_embree_commit(o->dev.dev, o->plane))
        return -1;
    o->embree_bytes = o->dev.bytes;
    return gx_camera(s, &o->cam, w, h) ? -1 : 0;
}

static void gx_ours_free(gx_ours_t *o)
{
    if (o->plane) rtcReleaseScene(o->plane);
    gro_device_free(&o->dev);
    gr_grid_free(o->grid);
    memset(o, 0, sizeof *o);
}

/* Bytes ours keeps: the grid and Embree's plane as committed (the query
   scratch, gr_query_scratch_bytes per thread, lives on the stack). */
static long long gx_ours_bytes(const gx_ours_t *o) { return (long long)o->grid_bytes + o->embree_bytes; }

/* [inter-reflection scenes, §6] the direct term per light, and the host's
   ray tracer: the sky above, the room behind transmitting facets. The
   grooved plane is z = 0 in world = texture space (the frame is the
   identity), so directions need no transform. */
static void gx_brdf_cb(void *user, int refl, const double n[3], const double e[3], const double l[3], int light,
                       double rgb[3])
{
    const gx_scene_t *s = (const gx_scene_t *)user;
    const ex_material_t *m = &s->mats[refl >= 0 && refl < GX_MAX_MATS ? refl : 0];
    ex_v3_t f = ex_bsdf_eval(m, ex_v3(n[0], n[1], n[2]), ex_v3(e[0], e[1], e[2]), ex_v3(l[0], l[1], l[2]), NULL);
    f = ex_mul(f, s->radiance[light]);
    rgb[0] = f.x; rgb[1] = f.y; rgb[2] = f.z;
}

static void gx_trace_cb(void *user, const double origin[3], const double dir[3], int depth, int inside, double weight,
                        double rgb[3])
{
    const gx_scene_t *s = (const gx_scene_t *)user;
    ex_v3_t c = inside ? s->below : s->background;
    (void)origin; (void)dir; (void)depth; (void)weight;
    rgb[0] = c.x; rgb[1] = c.y; rgb[2] = c.z;
}

static ex_v3_t gx_ours_indirect(const gx_ours_t *o, gr_query_t *q, const gr_frame_t *frame, void *scratch, size_t bytes)
{
    const gx_scene_t *s = o->s;
    gr_indirect_t ind;
    gr_result_t r;
    double rgb[3];
    (void)frame;
    memset(&ind, 0, sizeof ind);
    ind.depth = s->depth;
    ind.specular = s->spec;
    ind.specular_count = GX_MAX_MATS;
    ind.brdf = gx_brdf_cb; ind.brdf_user = (void *)s;
    ind.trace = gx_trace_cb; ind.trace_user = (void *)s;
    if (q->line_samples == 0) q->line_samples = 2;
    r = gr_shade_indirect(o->grid, q, &ind, scratch, bytes, rgb, NULL);
    if (r != GR_OK && r != GR_ERR_STACK_FULL) return s->background; /* a full stack still gives a colour */
    return ex_v3(rgb[0], rgb[1], rgb[2]);
}

/* Radiance through continuous pixel position (px, py). */
static ex_v3_t gx_ours_radiance(const gx_ours_t *o, double px, double py)
{
    const gx_scene_t *s = o->s;
    unsigned char scratch[GX_SCRATCH];
    ex_ray_t ray = ex_camera_ray(&o->cam, px, py);
    ex_hit_t h = ex_embree_intersect(o->plane, ray.o, ray.d, 0, INFINITY);
    gr_differentials_t rd;
    gr_query_t q;
    gr_frame_t frame;
    gr_facet_list_t list;
    double L[GX_MAX_LIGHTS * 3];
    ex_v3_t c = ex_v3(0, 0, 0), p;
    int i, k;
    if (!h.hit) return s->background;
    p = ex_madd(ray.o, ray.d, h.t);
    memset(&rd, 0, sizeof rd);
    rd.p[0] = p.x; rd.p[1] = p.y; rd.p[2] = p.z;
    rd.n[2] = 1; rd.dpdu[0] = 1; rd.dpdv[1] = 1;
    rd.uv[0] = p.x; rd.uv[1] = p.y;
    rd.dir[0] = ray.d.x; rd.dir[1] = ray.d.y; rd.dir[2] = ray.d.z;
    rd.rx_origin[0] = ray.rx_o.x; rd.rx_origin[1] = ray.rx_o.y; rd.rx_origin[2] = ray.rx_o.z;
    rd.rx_dir[0] = ray.rx_d.x; rd.rx_dir[1] = ray.rx_d.y; rd.rx_dir[2] = ray.rx_d.z;
    rd.ry_origin[0] = ray.ry_o.x; rd.ry_origin[1] = ray.ry_o.y; rd.ry_origin[2] = ray.ry_o.z;
    rd.ry_dir[0] = ray.ry_d.x; rd.ry_dir[1] = ray.ry_d.y; rd.ry_dir[2] = ray.ry_d.z;
    memset(&q, 0, sizeof q);
    q.perturb_normals = o->perturb_normals;
    q.straight_occlusion = o->straight_occlusion;
    q.line_samples = o->line_samples;
    if (gr_footprint_from_differentials(&rd, &q.footprint, &frame) != GR_OK) return s->background;
    for (k = 0; k < s->nlights; k++) gr_frame_to_texture(&frame, s->light[k], L + 3 * k);
    q.lights = L; q.light_count = s->nlights;
    if (s->depth > 0) return gx_ours_indirect(o, &q, &frame, scratch, sizeof scratch);
    if (gr_query(o->grid, &q, scratch, sizeof scratch, &list) != GR_OK) return s->background;
    for (i = 0; i < list.count; i++) {
        const gr_facet_t *f = &list.facets[i];
        c = ex_madd(c, gx_shade(s, f->reflectance, f->normal, q.footprint.view, NULL, f->lit), f->ratio);
    }
    return c;
}

/* ---------------------------------------------------------------- geometry */

typedef struct gx_geo_t {
    const gx_scene_t *s;
    gro_device_t dev;
    gro_scene_t sc;
    long long embree_bytes;       /* Embree's bytes once the meshes are committed */
    ex_camera_t cam;
} gx_geo_t;

static int gx_geo_init(gx_geo_t *g, const gx_scene_t *s, int w, int h)
{
    gro_build_t b;
    memset(g, 0, sizeof *g);
    g->s = s;
    if (gro_device_init(&g->dev)) { fprintf(stderr, "grooves: Embree does not start\n"); return -1; }
    memset(&b, 0, sizeof b);
    b.ground[0] = 0; b.ground[1] = 0; b.ground[2] = 1; b.ground[3] = 1;
    if (gro_scene_build(&g->sc, g->dev.dev, s->geo, s->ngrooves, &b)) {
        fprintf(stderr, "grooves: %s: cannot build the geometry (out of memory?)\n", s->name);
        return -1;
    }
    g->embree_bytes = g->dev.bytes;
    return gx_camera(s, &g->cam, w, h) ? -1 : 0;
}

static void gx_geo_free(gx_geo_t *g)
{
    gro_scene_free(&g->sc);
    gro_device_free(&g->dev);
    memset(g, 0, sizeof *g);
}

/* Bytes the geometry keeps: Embree's once committed (BVH, vertex and index
   buffers, as its memory monitor counts them) and the per-triangle facet
   labels. */
static long long gx_geo_bytes(const gx_geo_t *g)
{
    return g->embree_bytes + (long long)g->sc.ntris * 2 * (long long)sizeof(int);
}

/* Unpolarised Fresnel reflectance entering glass of index n from air at
   cos ci (the geometry renderer's own, for the thin pane). */
static double gx_fresnel(double ci, double n)
{
    double st = sqrt(ci < 1 ? 1 - ci * ci : 0) / n, ct = sqrt(1 - st * st);
    double a = (ci - n * ct) / (ci + n * ct), b = (ct - n * ci) / (ct + n * ci);
    return 0.5 * (a * a + b * b);
}

static ex_v3_t gx_geo_radiance(const gx_geo_t *g, double px, double py)
{
    const gx_scene_t *s = g->s;
    ex_v3_t d = ex_camera_dir(&g->cam, px, py), c = ex_v3(0, 0, 0), thr = ex_v3(1, 1, 1);
    double o[3] = {g->cam.eye.x, g->cam.eye.y, g->cam.eye.z}, dd[3] = {d.x, d.y, d.z}, e[3];
    int level;
    /* [inter-reflection scenes, §6] mirror bounces up to s->depth; k_t of a
       transmitting facet sees s->below */
    for (level = 0; level <= s->depth; level++) {
        gro_hit_t h = gro_scene_intersect(&g->sc, o, dd, 0, INFINITY);
        const gr_specular_t *sp;
        unsigned mask = 0;
        double dn;
        int k, refl;
        if (h.kind == GRO_HIT_NONE) return ex_add(c, ex_mul(thr, s->background));
        for (k = 0; k < s->nlights; k++)
            if (gro_scene_lit(&g->sc, &h, s->light[k])) mask |= 1u << k;
        refl = 0;
        if (h.kind == GRO_HIT_FACET && h.facet < GRO_MAX_FACETS) {
            const gr_groove_desc_t *gd = &s->desc[h.groove];
            refl = gd->facet_reflectance ? gd->facet_reflectance[h.facet] : gd->reflectance;
        } else if (h.kind == GRO_HIT_FACET) {
            refl = s->desc[h.groove].reflectance; /* end caps */
        }
        e[0] = -dd[0]; e[1] = -dd[1]; e[2] = -dd[2];
        c = ex_add(c, ex_mul(thr, gx_shade(s, refl, h.n, e, &mask, NULL)));
        if (level == s->depth || refl < 0 || refl >= GX_MAX_MATS) break;
        sp = &s->spec[refl];
        dn = dd[0] * h.n[0] + dd[1] * h.n[1] + dd[2] * h.n[2];
        {   /* the pane's (or facet's) reflected and transmitted shares:
               constants, or a thin pane's two Fresnel faces (the scenes
               here transmit only through thin panes) */
            double R = 1, T = 1;
            if (sp->fresnel) {
                double f = gx_fresnel(-dn, sp->ior > 0 ? sp->ior : 1.5);
                R = sp->thin ? 2 * f / (1 + f) : f;
                T = 1 - R;
            }
            c = ex_add(c, ex_mul(thr, ex_mul(ex_v3(T * sp->kt[0], T * sp->kt[1], T * sp->kt[2]), s->below)));
            thr = ex_mul(thr, ex_v3(R * sp->kr[0], R * sp->kr[1], R * sp->kr[2]));
        }
        if (!(thr.x > 0 || thr.y > 0 || thr.z > 0)) break;
        for (k = 0; k < 3; k++) {
            dd[k] -= 2 * dn * h.n[k];
            o[k] = h.p[k] + g->sc.eps * h.n[k];
        }
    }
    return c;
}

/* ex_render callbacks */
static void gx_ours_pixel(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3])
{
    ex_v3_t c = gx_ours_radiance((const gx_ours_t *)user, x + 0.5, y + 0.5);
    (void)sample; (void)rng;
    rgb[0] = (float)c.x; rgb[1] = (float)c.y; rgb[2] = (float)c.z;
}

static void gx_geo_pixel(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3])
{
    double jx = ex_rng_unit(rng), jy = ex_rng_unit(rng);
    ex_v3_t c = gx_geo_radiance((const gx_geo_t *)user, x + jx, y + jy);
    (void)sample;
    rgb[0] = (float)c.x; rgb[1] = (float)c.y; rgb[2] = (float)c.z;
}

#endif /* GX_SCENE_H */
