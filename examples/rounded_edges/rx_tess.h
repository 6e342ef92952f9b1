/* rx_tess.h — a real triangle mesh of the rounded solid, for the "tess-N"
   modes: the same rounding cylinders and spheres that rounded_edges.h ray
   traces (re_get_cylinder / re_get_sphere), plus the shrunk flat faces.

   Level N puts N segments on every quarter turn of arc (at least one per
   arc), so a cylinder whose faces meet at angle theta gets ceil(N theta/(pi/2))
   strips and a corner patch the same density: the paper's "subdivisions"
   for a right-angle edge. Arcs are shared point for point between a
   cylinder and the corner patches at its ends, so the mesh has no cracks.

   Shrunk faces are found from the spheres: for a convex object, the flat
   part of face plane f is the face of the eroded polytope on f's offset
   plane moved back out by r, i.e. the polygon of the sphere centres c with
   n_f . c = d_f - r, each pushed by r n_f. This holds for the convex objects
   the method rounds (boxes, prisms, icospheres here).

   Stb-style: define RX_TESS_IMPLEMENTATION in one file. */
#ifndef FILIGREE_RX_TESS_H
#define FILIGREE_RX_TESS_H

#include <stddef.h>

#include "ex_mesh.h"
#include "rounded_edges.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Tessellates object `re_obj` of `rs` (built from `sharp`) at `level` >= 1
   into *out (zeroed on entry; free out->pos and out->idx with free()). *first_round is the
   number of flat-face triangles, which come first. Returns 0; 1 when some
   vertex of the object got no rounding sphere (the build left it sharp and
   reported why): the shrunk-face construction needs every corner rounded,
   so *out is then a copy of the sharp mesh; -1 when out of memory. */
int rx_tess_object(const re_scene_t *rs, unsigned re_obj, const ex_mesh_t *sharp, int level, ex_mesh_t *out,
                   size_t *first_round);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_RX_TESS_H */

#ifdef RX_TESS_IMPLEMENTATION
#ifndef RX_TESS_IMPLEMENTATION_DONE
#define RX_TESS_IMPLEMENTATION_DONE
#include <stdlib.h>
#include <string.h>

typedef struct rx__tb_t { ex_mesh_t *m; size_t vcap, tcap; int oom; } rx__tb_t;

static uint32_t rx__tb_vertex(rx__tb_t *b, ex_v3_t p)
{
    ex_mesh_t *m = b->m;
    if (m->nverts == b->vcap) {
        size_t cap = b->vcap ? 2 * b->vcap : 256;
        float *q = (float *)realloc(m->pos, 3 * sizeof(float) * cap);
        if (!q) { b->oom = 1; return 0; }
        m->pos = q;
        b->vcap = cap;
    }
    m->pos[3 * m->nverts] = (float)p.x;
    m->pos[3 * m->nverts + 1] = (float)p.y;
    m->pos[3 * m->nverts + 2] = (float)p.z;
    return (uint32_t)m->nverts++;
}

/* Triangle (a, b, c) turned so that its right-hand normal points along `out`. */
static void rx__tb_tri(rx__tb_t *b, uint32_t i0, uint32_t i1, uint32_t i2, ex_v3_t out)
{
    ex_mesh_t *m = b->m;
    ex_v3_t p0, p1, p2;
    if (b->oom) return;
    if (m->ntris == b->tcap) {
        size_t cap = b->tcap ? 2 * b->tcap : 256;
        uint32_t *q = (uint32_t *)realloc(m->idx, 3 * sizeof(uint32_t) * cap);
        if (!q) { b->oom = 1; return; }
        m->idx = q;
        b->tcap = cap;
    }
    p0 = ex_v3(m->pos[3 * i0], m->pos[3 * i0 + 1], m->pos[3 * i0 + 2]);
    p1 = ex_v3(m->pos[3 * i1], m->pos[3 * i1 + 1], m->pos[3 * i1 + 2]);
    p2 = ex_v3(m->pos[3 * i2], m->pos[3 * i2 + 1], m->pos[3 * i2 + 2]);
    if (ex_dot(ex_cross(ex_sub(p1, p0), ex_sub(p2, p0)), out) < 0) { uint32_t s = i1; i1 = i2; i2 = s; }
    m->idx[3 * m->ntris] = i0;
    m->idx[3 * m->ntris + 1] = i1;
    m->idx[3 * m->ntris + 2] = i2;
    m->ntris++;
}

static ex_v3_t rx__v3(const double a[3]) { return ex_v3(a[0], a[1], a[2]); }

/* Great-circle interpolation between unit a and b. */
static ex_v3_t rx__slerp(ex_v3_t a, ex_v3_t b, double s)
{
    double c = ex_clamp(ex_dot(a, b), -1, 1), th = acos(c), sn = sin(th);
    if (sn < 1e-12) return a;
    return ex_add(ex_scale(a, sin((1 - s) * th) / sn), ex_scale(b, sin(s * th) / sn));
}

static int rx__segments(int level, double angle)
{
    int k = (int)ceil(level * angle / (EX_PI / 2) - 1e-9);
    return k < 1 ? 1 : k;
}

static double rx__angle(ex_v3_t a, ex_v3_t b) { return acos(ex_clamp(ex_dot(a, b), -1, 1)); }

/* Same unit normal, to the rounding of the core's double arithmetic. */
#define RX__SAME_NORMAL 1e-9

typedef struct rx__plane_t { ex_v3_t n; double d; } rx__plane_t;

/* Flat parts of the faces (see the top comment). */
static int rx__tess_faces(rx__tb_t *b, const re_sphere_t *sp, unsigned nsp, const ex_mesh_t *sharp, double size)
{
    rx__plane_t *pl = (rx__plane_t *)malloc(sizeof *pl * (sharp->ntris + 1));
    ex_v3_t *pts = (ex_v3_t *)malloc(sizeof *pts * (nsp + 1));
    double *ang = (double *)malloc(sizeof *ang * (nsp + 1));
    size_t npl = 0, t;
    unsigned i;
    if (!pl || !pts || !ang) { free(pl); free(pts); free(ang); return -1; }
    for (t = 0; t < sharp->ntris; t++) {
        const uint32_t *q = sharp->idx + 3 * t;
        ex_v3_t a = ex_v3(sharp->pos[3 * q[0]], sharp->pos[3 * q[0] + 1], sharp->pos[3 * q[0] + 2]);
        ex_v3_t bb = ex_v3(sharp->pos[3 * q[1]], sharp->pos[3 * q[1] + 1], sharp->pos[3 * q[1] + 2]);
        ex_v3_t c = ex_v3(sharp->pos[3 * q[2]], sharp->pos[3 * q[2] + 1], sharp->pos[3 * q[2] + 2]);
        ex_v3_t n = ex_normalize(ex_cross(ex_sub(bb, a), ex_sub(c, a)));
        double d = ex_dot(n, a);
        size_t k;
        for (k = 0; k < npl; k++)
            if (ex_dot(pl[k].n, n) > 1 - 1e-6 && fabs(pl[k].d - d) < 1e-6 * size) break;
        if (k == npl) { pl[npl].n = n; pl[npl].d = d; npl++; }
    }
    for (t = 0; t < npl; t++) {
        ex_v3_t n = pl[t].n, tt, bt, ctr = ex_v3(0, 0, 0);
        size_t np = 0, k;
        uint32_t first, prev;
        for (i = 0; i < nsp; i++) {
            ex_v3_t c = rx__v3(sp[i].center), p = ex_madd(c, n, sp[i].radius);
            int dup = 0;
            if (fabs(ex_dot(n, p) - pl[t].d) > 1e-5 * size) continue;
            for (k = 0; k < np; k++)
                if (ex_len(ex_sub(pts[k], p)) < 1e-9 * size) dup = 1;
            if (!dup) pts[np++] = p;
        }
        if (np < 3) continue;
        for (k = 0; k < np; k++) ctr = ex_add(ctr, pts[k]);
        ctr = ex_scale(ctr, 1.0 / (double)np);
        ex_onb(n, &tt, &bt);
        for (k = 0; k < np; k++) {
            ex_v3_t r = ex_sub(pts[k], ctr);
            ang[k] = atan2(ex_dot(r, bt), ex_dot(r, tt));
        }
        /* insertion sort by angle: a face has few corners */
        for (k = 1; k < np; k++) {
            size_t j = k;
            while (j > 0 && ang[j - 1] > ang[j]) {
                double sa = ang[j]; ex_v3_t sv = pts[j];
                ang[j] = ang[j - 1]; pts[j] = pts[j - 1];
                ang[j - 1] = sa; pts[j - 1] = sv;
                j--;
            }
        }
        first = rx__tb_vertex(b, pts[0]);
        prev = rx__tb_vertex(b, pts[1]);
        for (k = 2; k < np; k++) {
            uint32_t cur = rx__tb_vertex(b, pts[k]);
            rx__tb_tri(b, first, prev, cur, n);
            prev = cur;
        }
    }
    free(pl); free(pts); free(ang);
    return b->oom ? -1 : 0;
}

static void rx__tess_cylinder(rx__tb_t *b, const re_cylinder_t *c, int level)
{
    ex_v3_t n0 = rx__v3(c->n0), n1 = rx__v3(c->n1), a = rx__v3(c->a), e = rx__v3(c->b);
    int k = rx__segments(level, rx__angle(n0, n1)), j;
    uint32_t pa = 0, pb = 0;
    for (j = 0; j <= k; j++) {
        ex_v3_t n = rx__slerp(n0, n1, (double)j / k);
        uint32_t va = rx__tb_vertex(b, ex_madd(a, n, c->radius)), vb = rx__tb_vertex(b, ex_madd(e, n, c->radius));
        if (j > 0) {
            ex_v3_t out = ex_normalize(ex_add(n, rx__slerp(n0, n1, (j - 0.5) / k)));
            rx__tb_tri(b, pa, pb, vb, out);
            rx__tb_tri(b, pa, vb, va, out);
        }
        pa = va; pb = vb;
    }
}

/* The corner patch of sphere `si`: its boundary is the closed chain of the
   arcs of its cylinders (generated exactly as rx__tess_cylinder does);
   rings of radial great-circle arcs from the mean normal fill it. */
static int rx__tess_sphere(rx__tb_t *b, const re_sphere_t *s, unsigned si, const re_cylinder_t *cy, unsigned ncy,
                           int level)
{
    unsigned *arcs = (unsigned *)malloc(sizeof(unsigned) * (ncy + 1));
    ex_v3_t *ring = NULL, m = ex_v3(0, 0, 0), start, end;
    unsigned na = 0, i, used = 0;
    size_t nb = 0, cap = 0;
    unsigned char *done;
    int R = 1, rc = 0;
    if (!arcs) return -1;
    for (i = 0; i < ncy; i++)
        if (cy[i].sa == si || cy[i].sb == si) arcs[na++] = i;
    done = (unsigned char *)calloc(na + 1, 1);
    if (na < 2 || !done) { free(arcs); free(done); return na < 2 ? 0 : -1; }
    start = rx__v3(cy[arcs[0]].n0);
    end = start;
    while (used < na) {
        unsigned a, found = na;
        int rev = 0, k, j;
        ex_v3_t n0, n1;
        for (a = 0; a < na && found == na; a++) {
            if (done[a]) continue;
            if (ex_dot(rx__v3(cy[arcs[a]].n0), end) > 1 - RX__SAME_NORMAL) { found = a; rev = 0; }
            else if (ex_dot(rx__v3(cy[arcs[a]].n1), end) > 1 - RX__SAME_NORMAL) { found = a; rev = 1; }
        }
        if (found == na) { rc = 1; break; } /* the chain does not close: leave this corner out */
        done[found] = 1;
        used++;
        n0 = rx__v3(cy[arcs[found]].n0);
        n1 = rx__v3(cy[arcs[found]].n1);
        k = rx__segments(level, rx__angle(n0, n1));
        if (nb + (size_t)k + 1 > cap) {
            size_t nc = 2 * (nb + (size_t)k + 1);
            ex_v3_t *r2 = (ex_v3_t *)realloc(ring, sizeof *ring * nc);
            if (!r2) { rc = -1; break; }
            ring = r2;
            cap = nc;
        }
        /* the same parameter values as the cylinder, walked either way */
        for (j = 0; j < k; j++) {
            int jj = rev ? k - j : j;
            ring[nb++] = rx__slerp(n0, n1, (double)jj / k);
        }
        end = rev ? n0 : n1;
    }
    if (rc == 0 && ex_dot(end, start) < 1 - RX__SAME_NORMAL) rc = 1;
    if (rc == 0 && nb >= 3) {
        size_t q;
        int rho;
        ex_v3_t c = rx__v3(s->center);
        uint32_t apex, *prev = (uint32_t *)malloc(sizeof(uint32_t) * (nb + 1) * 2);
        double maxang = 0;
        if (!prev) { free(arcs); free(done); free(ring); return -1; }
        for (q = 0; q < nb; q++) m = ex_add(m, ring[q]);
        m = ex_normalize(m);
        for (q = 0; q < nb; q++) maxang = fmax(maxang, rx__angle(m, ring[q]));
        R = rx__segments(level, maxang);
        apex = rx__tb_vertex(b, ex_madd(c, m, s->radius));
        /* prev[q] = vertex of radial line q at the previous ring */
        for (q = 0; q < nb; q++) prev[q] = apex;
        for (rho = 1; rho <= R; rho++) {
            uint32_t *cur = prev + nb;
            for (q = 0; q < nb; q++)
                cur[q] = rx__tb_vertex(b, ex_madd(c, rx__slerp(m, ring[q], (double)rho / R), s->radius));
            for (q = 0; q < nb; q++) {
                size_t q1 = (q + 1) % nb;
                ex_v3_t out = rx__slerp(m, ex_normalize(ex_add(ring[q], ring[q1])), (rho - 0.5) / R);
                if (rho == 1) rx__tb_tri(b, apex, cur[q], cur[q1], out);
                else {
                    rx__tb_tri(b, prev[q], cur[q], cur[q1], out);
                    rx__tb_tri(b, prev[q], cur[q1], prev[q1], out);
                }
            }
            memcpy(prev, cur, sizeof(uint32_t) * nb);
        }
        free(prev);
        rc = 0;
    } else if (rc == 1)
        rc = 0; /* reported through the crack, not fatal */
    free(arcs); free(done); free(ring);
    return b->oom ? -1 : rc;
}

int rx_tess_object(const re_scene_t *rs, unsigned re_obj, const ex_mesh_t *sharp, int level, ex_mesh_t *out,
                   size_t *first_round)
{
    unsigned ns = re_sphere_count(rs, re_obj), nc = re_cylinder_count(rs, re_obj), i;
    re_sphere_t *sp = (re_sphere_t *)malloc(sizeof *sp * (ns + 1));
    re_cylinder_t *cy = (re_cylinder_t *)malloc(sizeof *cy * (nc + 1));
    rx__tb_t b;
    double size = 0;
    size_t v;
    int rc = 0;
    memset(out, 0, sizeof *out);
    memset(&b, 0, sizeof b);
    b.m = out;
    if (!sp || !cy || level < 1) { free(sp); free(cy); return -1; }
    for (i = 0; i < ns; i++) re_get_sphere(rs, re_obj, i, &sp[i]);
    for (i = 0; i < nc; i++) re_get_cylinder(rs, re_obj, i, &cy[i]);
    {
        /* every vertex needs a sphere, else fall back to the sharp mesh */
        unsigned char *has = (unsigned char *)calloc(sharp->nverts + 1, 1);
        int partial = 0;
        if (!has) { free(sp); free(cy); return -1; }
        for (i = 0; i < ns; i++)
            if (sp[i].vertex < sharp->nverts) has[sp[i].vertex] = 1;
        for (v = 0; v < sharp->nverts; v++)
            if (!has[v]) partial = 1;
        free(has);
        if (partial) {
            free(sp); free(cy);
            out->pos = (float *)malloc(3 * sizeof(float) * (sharp->nverts + 1));
            out->idx = (uint32_t *)malloc(3 * sizeof(uint32_t) * (sharp->ntris + 1));
            if (!out->pos || !out->idx) { free(out->pos); free(out->idx); memset(out, 0, sizeof *out); return -1; }
            memcpy(out->pos, sharp->pos, 3 * sizeof(float) * sharp->nverts);
            memcpy(out->idx, sharp->idx, 3 * sizeof(uint32_t) * sharp->ntris);
            out->nverts = sharp->nverts;
            out->ntris = sharp->ntris;
            *first_round = sharp->ntris;
            return 1;
        }
    }
    for (v = 0; v < 3 * sharp->nverts; v++) size = fmax(size, fabs(sharp->pos[v]));
    if (rx__tess_faces(&b, sp, ns, sharp, size > 0 ? size : 1)) rc = -1;
    *first_round = out->ntris;
    for (i = 0; rc == 0 && i < nc; i++) rx__tess_cylinder(&b, &cy[i], level);
    for (i = 0; rc == 0 && i < ns; i++) rc = rx__tess_sphere(&b, &sp[i], i, cy, nc, level);
    free(sp); free(cy);
    if (rc || b.oom) { free(out->pos); free(out->idx); memset(out, 0, sizeof *out); return -1; }
    return 0;
}

#endif /* RX_TESS_IMPLEMENTATION_DONE */
#endif /* RX_TESS_IMPLEMENTATION */
