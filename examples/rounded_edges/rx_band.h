/* rx_band.h — when a renderer may skip re_query(): the rounding band of an
   object (header-only, static functions; used by rx_render.h and tested by
   tests/test_rounded_baselines_example.c). */
#ifndef FILIGREE_RX_BAND_H
#define FILIGREE_RX_BAND_H

#include <math.h>

#include "ex_math.h"
#include "ex_mesh.h"
#include "rounded_edges.h"

/* A distance beyond which no point of object k's faces is rounded: every
   rounding sphere belongs to a mesh vertex v and lies within |c - v| + r of
   it, every cylinder runs between two such spheres, and the flat part of a
   face begins where the spheres and cylinders stop touching it. A hit whose
   distance to its own triangle's boundary exceeds the band is farther than
   that from every mesh edge and vertex (the straight path to any of them
   crosses the triangle's boundary first), so it is on the flat part and
   re_query would say RE_UNCHANGED: the renderer skips the call (profiling
   showed the query at a quarter of the render time). RX_BAND_SAFETY covers
   float positions. */
#define RX_BAND_SAFETY 1e-5
static double rx_band(const re_scene_t *rs, unsigned k, const ex_mesh_t *m)
{
    unsigned i, n = re_sphere_count(rs, k);
    double band = 0;
    for (i = 0; i < n; i++) {
        re_sphere_t sp;
        ex_v3_t v;
        if (!re_get_sphere(rs, k, i, &sp) || sp.vertex >= m->nverts) return HUGE_VAL; /* unknown: always query */
        v = ex_v3(m->pos[3 * sp.vertex], m->pos[3 * sp.vertex + 1], m->pos[3 * sp.vertex + 2]);
        band = fmax(band, ex_len(ex_sub(ex_v3(sp.center[0], sp.center[1], sp.center[2]), v)) + sp.radius);
    }
    return band * (1 + RX_BAND_SAFETY) + RX_BAND_SAFETY * sqrt(band * band + 1e-300);
}

static double rx__seg_dist2(ex_v3_t p, ex_v3_t a, ex_v3_t b)
{
    ex_v3_t ab = ex_sub(b, a), ap = ex_sub(p, a);
    double l2 = ex_dot(ab, ab), t = l2 > 0 ? ex_clamp(ex_dot(ap, ab) / l2, 0, 1) : 0;
    ex_v3_t d = ex_sub(ap, ex_scale(ab, t));
    return ex_dot(d, d);
}

/* 1 when point p of triangle tri of mesh m is within `band` of the triangle's boundary. */
static int rx_near_boundary(const ex_mesh_t *m, unsigned tri, ex_v3_t p, double band)
{
    const uint32_t *q = m->idx + 3 * (size_t)tri;
    ex_v3_t v0 = ex_v3(m->pos[3 * q[0]], m->pos[3 * q[0] + 1], m->pos[3 * q[0] + 2]);
    ex_v3_t v1 = ex_v3(m->pos[3 * q[1]], m->pos[3 * q[1] + 1], m->pos[3 * q[1] + 2]);
    ex_v3_t v2 = ex_v3(m->pos[3 * q[2]], m->pos[3 * q[2] + 1], m->pos[3 * q[2] + 2]);
    double b2 = band * band;
    return rx__seg_dist2(p, v0, v1) <= b2 || rx__seg_dist2(p, v1, v2) <= b2 || rx__seg_dist2(p, v2, v0) <= b2;
}

#endif /* FILIGREE_RX_BAND_H */
