/* rx_scene.h — the scenes of the rounded-edges example and benchmark.

   Every scene is generated in code, y up, as a list of closed convex objects
   (each its own indexed triangle mesh, CCW from outside) plus unrounded
   props (the ground), materials, lights and a camera. The camera may stand
   inside an object (the Cornell room).
   An object's `radius` is its rounding radius in scene units; 0 leaves it
   sharp in every mode.

   Stb-style: define RX_SCENE_IMPLEMENTATION in one file before including. */
#ifndef FILIGREE_RX_SCENE_H
#define FILIGREE_RX_SCENE_H

#include "ex_mesh.h"
#include "ex_shade.h"
#include "rounded_edges.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rx_object_t {
    ex_mesh_t mesh;   /* sharp mesh, world space */
    int material;     /* index into rx_scene_t.mats */
    double radius;    /* rounding radius, scene units; 0 = never rounded */
    /* by_axis: the material follows the surface's outward normal instead,
       axis_material[2 a + (n_a > 0)] for its largest component a (a room's
       walls in one box: a rounded seam takes the nearer wall's colour in
       every mode alike) */
    int by_axis;
    int axis_material[6];
} rx_object_t;

#define RX_MAX_MATS 16
typedef struct rx_scene_t {
    const char *name;
    rx_object_t *obj;
    int nobj, cap;
    ex_material_t mats[RX_MAX_MATS];
    int nmats;
    ex_rect_light_t lights[2];
    int nlights;
    ex_env_t env;
    ex_v3_t eye, at, up;
    double vfov;          /* degrees */
    double scale;         /* size of the scene's region of interest (offsets scale with it) */
} rx_scene_t;

/* Scene names accepted by rx_scene_make, NULL-terminated. */
extern const char *const rx_scene_names[];

/* Builds scene `name` ("article", "glass", "blocks", "cornell") into *s. `radius_scale`
   multiplies every rounding radius (1 = the scene's default). 0, or -1 when
   the name is unknown or memory runs out (after printing one line). */
int rx_scene_make(rx_scene_t *s, const char *name, double radius_scale);
void rx_scene_free(rx_scene_t *s);
/* Total triangles over all objects. */
size_t rx_scene_triangles(const rx_scene_t *s);
/* The rounded objects (radius > 0) as rounded_edges.h meshes, in object
   order: float positions, the triangles Embree traces. meshes has room for
   s->nobj; object_of (NULL, or s->nobj entries) gets each object's mesh
   index, -1 for an object left sharp. Returns the mesh count. */
unsigned rx_scene_round_meshes(const rx_scene_t *s, re_mesh_t *meshes, int *object_of);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_RX_SCENE_H */

#ifdef RX_SCENE_IMPLEMENTATION
#ifndef RX_SCENE_IMPLEMENTATION_DONE
#define RX_SCENE_IMPLEMENTATION_DONE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const rx_scene_names[] = {"article", "glass", "blocks", "cornell", NULL};

static ex_material_t rx__mat(double r, double g, double b, double spec, double rough)
{
    ex_material_t m;
    memset(&m, 0, sizeof m);
    m.diffuse = ex_v3(r, g, b);
    m.specular = ex_v3(spec, spec, spec);
    m.roughness = rough;
    return m;
}

/* Takes ownership of *m (zeroes it) on success. */
static int rx__add(rx_scene_t *s, ex_mesh_t *m, int material, double radius)
{
    if (s->nobj == s->cap) {
        int cap = s->cap ? 2 * s->cap : 64;
        rx_object_t *o = (rx_object_t *)realloc(s->obj, (size_t)cap * sizeof *o);
        if (!o) return -1;
        s->obj = o;
        s->cap = cap;
    }
    s->obj[s->nobj].mesh = *m;
    s->obj[s->nobj].material = material;
    s->obj[s->nobj].radius = radius;
    s->obj[s->nobj].by_axis = 0;
    s->nobj++;
    memset(m, 0, sizeof *m);
    return 0;
}

/* The axis-aligned box [lo, hi], rotated by `yaw` radians about the vertical
   axis through its centre. */
static int rx__box(ex_mesh_t *m, ex_v3_t lo, ex_v3_t hi, double yaw)
{
    double a[12], c = cos(yaw), sn = sin(yaw);
    ex_v3_t h = ex_scale(ex_sub(hi, lo), 0.5), ctr = ex_scale(ex_add(hi, lo), 0.5);
    if (ex_mesh_cube(m)) return -1;
    /* p -> Ry(yaw) * diag(h) * p + ctr */
    a[0] = c * h.x;  a[1] = 0;   a[2] = sn * h.z;
    a[3] = 0;        a[4] = h.y; a[5] = 0;
    a[6] = -sn * h.x; a[7] = 0;  a[8] = c * h.z;
    a[9] = ctr.x; a[10] = ctr.y; a[11] = ctr.z;
    ex_mesh_transform(m, a);
    return 0;
}

/* A vertical prism with `sides` sides around (cx, cz), radius rad, from y0 to
   y1: a play-block knob. Caps are fans (their diagonals are flat edges). */
static int rx__prism(ex_mesh_t *m, double cx, double cz, double rad, double y0, double y1, int sides)
{
    size_t nv = 2 * (size_t)sides, nt = 2 * (size_t)sides + 2 * (size_t)(sides - 2), t = 0;
    int i;
    memset(m, 0, sizeof *m);
    m->pos = (float *)malloc(3 * sizeof(float) * nv);
    m->idx = (uint32_t *)malloc(3 * sizeof(uint32_t) * nt);
    if (!m->pos || !m->idx) { ex_mesh_free(m); return -1; }
    m->nverts = nv; m->ntris = nt;
    for (i = 0; i < sides; i++) {
        double a = 2 * EX_PI * i / sides;
        float x = (float)(cx + rad * cos(a)), z = (float)(cz - rad * sin(a));
        m->pos[6 * i + 0] = x; m->pos[6 * i + 1] = (float)y0; m->pos[6 * i + 2] = z;
        m->pos[6 * i + 3] = x; m->pos[6 * i + 4] = (float)y1; m->pos[6 * i + 5] = z;
    }
    /* angle grows counter-clockwise seen from above (+y) because z = -sin */
    for (i = 0; i < sides; i++) {
        uint32_t b0 = (uint32_t)(2 * i), t0 = b0 + 1, b1 = (uint32_t)(2 * ((i + 1) % sides)), t1 = b1 + 1;
        uint32_t *q = m->idx + 3 * t;
        q[0] = b0; q[1] = b1; q[2] = t1;
        q[3] = b0; q[4] = t1; q[5] = t0;
        t += 2;
    }
    for (i = 1; i + 1 < sides; i++) {
        uint32_t *q = m->idx + 3 * t;
        q[0] = 1; q[1] = (uint32_t)(2 * i + 1); q[2] = (uint32_t)(2 * i + 3);      /* top, CCW from above */
        q[3] = 0; q[4] = (uint32_t)(2 * i + 2); q[5] = (uint32_t)(2 * i);          /* bottom, CCW from below */
        t += 2;
    }
    return 0;
}

static int rx__icosphere(ex_mesh_t *m, int level, double rad, ex_v3_t c)
{
    double a[12];
    if (ex_mesh_icosphere(m, level)) return -1;
    ex_affine_srt(a, rad, ex_v3(0, 1, 0), 0.3, c);
    ex_mesh_transform(m, a);
    return 0;
}

/* The bevel-shader article's scene: a cube and an icosphere (Blender's
   default, 80 triangles) with sharp edges and a glossy material, on a floor. */
static int rx__article(rx_scene_t *s, double rs)
{
    ex_mesh_t m;
    double a[12];
    s->mats[0] = rx__mat(0.55, 0.55, 0.55, 0.04, 0.6);   /* floor */
    s->mats[1] = rx__mat(0.60, 0.12, 0.08, 0.05, 0.12);  /* glossy red */
    s->mats[2] = rx__mat(0.10, 0.22, 0.60, 0.05, 0.12);  /* glossy blue */
    s->nmats = 3;
    if (ex_mesh_ground(&m, 30) || rx__add(s, &m, 0, 0)) return -1;
    if (ex_mesh_cube(&m)) return -1;
    ex_affine_srt(a, 1.0, ex_v3(0, 1, 0), 0.6, ex_v3(-1.3, 1.0, 0));
    ex_mesh_transform(&m, a);
    if (rx__add(s, &m, 1, 0.08 * rs)) return -1;
    if (rx__icosphere(&m, 1, 1.0, ex_v3(1.3, 1.0, 0.2)) || rx__add(s, &m, 2, 0.06 * rs)) return -1;
    s->lights[0].corner = ex_v3(-3, 6, 2);
    s->lights[0].edge_u = ex_v3(0, 0, 2.5);
    s->lights[0].edge_v = ex_v3(2.5, 0, 0);
    s->lights[0].radiance = ex_v3(9, 9, 8.5);
    s->nlights = 1;
    s->env.zenith = ex_v3(0.35, 0.45, 0.65);
    s->env.horizon = ex_v3(0.6, 0.62, 0.65);
    s->env.ground = ex_v3(0.2, 0.2, 0.2);
    s->eye = ex_v3(0.8, 3.2, 7.0);
    s->at = ex_v3(0, 0.8, 0);
    s->up = ex_v3(0, 1, 0);
    s->vfov = 38;
    s->scale = 5;
    return 0;
}

/* The article's scene with a glass cube (index 1.5): rays refract in
   through its rounded edges and out through them (re_query_exit_uv). */
static int rx__glass(rx_scene_t *s, double rs)
{
    if (rx__article(s, rs)) return -1;
    s->mats[1] = rx__mat(0, 0, 0, 0, 0);
    s->mats[1].ior = 1.5;
    return 0;
}

/* Play blocks like the paper's "Blocks" (Fig. 8d, 276k triangles): 2x4
   bricks, each a box and eight 48-sided knobs (separate convex objects; the
   knobs are sunk into the brick so the crease stays sharp, as moulded),
   stacked in staggered walls with small gaps. 165 bricks, 250 142 triangles
   (1 486 objects: each brick and knob its own solid). */
#define RX__KNOB_SIDES 48
static int rx__blocks(rx_scene_t *s, double rs)
{
    static const double colours[6][3] = {{0.70, 0.06, 0.05}, {0.05, 0.25, 0.70}, {0.85, 0.65, 0.05},
                                         {0.06, 0.45, 0.12}, {0.80, 0.80, 0.78}, {0.05, 0.50, 0.60}};
    const double unit = 0.8, H = 0.96, gap = 0.01, knob_r = 0.24, knob_h = 0.17;
    const double r_body = 0.035 * rs, r_knob = 0.025 * rs;
    ex_mesh_t m;
    unsigned long long rng = 12345;
    int wall, layer, k, i, j, placed = 0;
    s->mats[0] = rx__mat(0.5, 0.5, 0.52, 0.03, 0.7);
    for (i = 0; i < 6; i++) s->mats[1 + i] = rx__mat(colours[i][0], colours[i][1], colours[i][2], 0.05, 0.18);
    s->nmats = 7;
    if (ex_mesh_ground(&m, 60) || rx__add(s, &m, 0, 0)) return -1;
    /* 5 walls, 6 layers high, 6 or 5 bricks per layer (staggered rows) */
    for (wall = 0; wall < 5 && placed < 170; wall++) {
        for (layer = 0; layer < 6 && placed < 170; layer++) {
            int n = layer & 1 ? 5 : 6;
            double x0 = -12.0 + wall * 0.3 + (layer & 1 ? 2 * unit : 0), z0 = -4.0 * wall + 2.0;
            for (k = 0; k < n && placed < 170; k++) {
                double bx = x0 + k * 4 * unit, by = layer * (H + gap), bz = z0;
                int colour;
                rng = rng * 6364136223846793005ull + 1442695040888963407ull;
                colour = 1 + (int)((rng >> 33) % 6);
                if (rx__box(&m, ex_v3(bx + gap, by, bz + gap), ex_v3(bx + 4 * unit - gap, by + H, bz + 2 * unit - gap), 0)
                    || rx__add(s, &m, colour, r_body))
                    return -1;
                for (i = 0; i < 4; i++)
                    for (j = 0; j < 2; j++) {
                        if (rx__prism(&m, bx + (i + 0.5) * unit, bz + (j + 0.5) * unit, knob_r, by + H - 2 * r_knob - 0.01,
                                      by + H + knob_h, RX__KNOB_SIDES)
                            || rx__add(s, &m, colour, r_knob))
                            return -1;
                    }
                placed++;
            }
        }
    }
    s->lights[0].corner = ex_v3(-14, 18, 10);
    s->lights[0].edge_u = ex_v3(0, 0, -8);
    s->lights[0].edge_v = ex_v3(8, 0, 0);
    s->lights[0].radiance = ex_v3(6, 6, 5.6);
    s->nlights = 1;
    s->env.zenith = ex_v3(0.30, 0.40, 0.60);
    s->env.horizon = ex_v3(0.55, 0.58, 0.62);
    s->env.ground = ex_v3(0.2, 0.2, 0.2);
    s->eye = ex_v3(-13.0, 11.0, 13.0);
    s->at = ex_v3(-3.0, 2.0, -6.0);
    s->up = ex_v3(0, 1, 0);
    s->vfov = 40;
    s->scale = 25;
    return 0;
}

/* A Cornell box seen from inside, as the paper's Fig. 12: the room is one
   closed box (a convex solid) with the camera inside it, so every ray meets
   its walls from inside (the host's exit query, re_query_exit_uv) and its
   twelve edges and eight corners, rounded, are the room's concave seams as
   seen from within. The left wall is red, the right green (by the outward
   normal, rx_object_t.by_axis). Inside: a tall box and a short box resting
   on the floor and an icosphere, all rounded. */
static int rx__cornell(rx_scene_t *s, double rs)
{
    static const int walls[6] = {1, 2, 0, 0, 0, 0}; /* -x red, +x green, the rest white */
    ex_mesh_t m;
    s->mats[0] = rx__mat(0.73, 0.73, 0.73, 0.0, 1.0);   /* white */
    s->mats[1] = rx__mat(0.63, 0.07, 0.05, 0.0, 1.0);   /* red */
    s->mats[2] = rx__mat(0.12, 0.45, 0.09, 0.0, 1.0);   /* green */
    s->mats[3] = rx__mat(0.70, 0.70, 0.68, 0.05, 0.15); /* glossy white */
    s->mats[4] = rx__mat(0.75, 0.55, 0.15, 0.6, 0.25);  /* gold-ish */
    s->nmats = 5;
    /* room interior [-1,1] x [0,2] x [-1,2.2]; the camera stands inside it,
       0.2 from the front wall */
    if (rx__box(&m, ex_v3(-1, 0, -1), ex_v3(1, 2, 2.2), 0) || rx__add(s, &m, 0, 0.12 * rs)) return -1;
    s->obj[s->nobj - 1].by_axis = 1;
    memcpy(s->obj[s->nobj - 1].axis_material, walls, sizeof walls);
    if (rx__box(&m, ex_v3(-0.65, 0, -0.55), ex_v3(-0.05, 1.2, 0.05), 0.3) || rx__add(s, &m, 3, 0.04 * rs)) return -1;
    if (rx__box(&m, ex_v3(0.1, 0, 0.0), ex_v3(0.7, 0.6, 0.6), -0.3) || rx__add(s, &m, 3, 0.04 * rs)) return -1;
    if (rx__icosphere(&m, 1, 0.28, ex_v3(0.4, 0.88, 0.3)) || rx__add(s, &m, 4, 0.02 * rs)) return -1;
    s->lights[0].corner = ex_v3(-0.3, 1.99, -0.3);
    s->lights[0].edge_u = ex_v3(0.6, 0, 0);
    s->lights[0].edge_v = ex_v3(0, 0, 0.6);
    s->lights[0].radiance = ex_v3(14, 12.5, 10);
    s->nlights = 1;
    s->eye = ex_v3(0, 1.0, 2.0);
    s->at = ex_v3(0, 0.9, 0);
    s->up = ex_v3(0, 1, 0);
    s->vfov = 56;
    s->scale = 2;
    return 0;
}

int rx_scene_make(rx_scene_t *s, const char *name, double radius_scale)
{
    int rc;
    memset(s, 0, sizeof *s);
    if (!strcmp(name, "article")) rc = rx__article(s, radius_scale);
    else if (!strcmp(name, "glass")) rc = rx__glass(s, radius_scale);
    else if (!strcmp(name, "blocks")) rc = rx__blocks(s, radius_scale);
    else if (!strcmp(name, "cornell")) rc = rx__cornell(s, radius_scale);
    else { fprintf(stderr, "unknown scene '%s' (article, glass, blocks, cornell)\n", name); return -1; }
    if (rc) { fprintf(stderr, "out of memory building scene '%s'\n", name); rx_scene_free(s); return -1; }
    s->name = name;
    return 0;
}

void rx_scene_free(rx_scene_t *s)
{
    int i;
    for (i = 0; i < s->nobj; i++) ex_mesh_free(&s->obj[i].mesh);
    free(s->obj);
    memset(s, 0, sizeof *s);
}

size_t rx_scene_triangles(const rx_scene_t *s)
{
    size_t n = 0;
    int i;
    for (i = 0; i < s->nobj; i++) n += s->obj[i].mesh.ntris;
    return n;
}

unsigned rx_scene_round_meshes(const rx_scene_t *s, re_mesh_t *meshes, int *object_of)
{
    unsigned n = 0;
    int i;
    for (i = 0; i < s->nobj; i++) {
        const rx_object_t *o = &s->obj[i];
        if (object_of) object_of[i] = -1;
        if (!(o->radius > 0)) continue;
        memset(&meshes[n], 0, sizeof meshes[n]);
        meshes[n].positions = o->mesh.pos;
        meshes[n].position_type = RE_FLOAT32;
        meshes[n].vertex_count = (unsigned)o->mesh.nverts;
        meshes[n].indices = o->mesh.idx;
        meshes[n].index_count = (unsigned)(3 * o->mesh.ntris);
        meshes[n].radius = o->radius;
        if (object_of) object_of[i] = (int)n;
        n++;
    }
    return n;
}

#endif /* RX_SCENE_IMPLEMENTATION_DONE */
#endif /* RX_SCENE_IMPLEMENTATION */
