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
   vertex of the object is neither a rounded corner (it has a sphere) nor
   inside a straight chain (an edge split by vertices where only its two
   faces meet: the chain's one cylinder, enumerated by each of its
   segments, is tessellated once): the build left it sharp and reported
   why, and the shrunk-face construction needs every corner rounded, so
   *out is then a copy of the sharp mesh; -1 when out of memory. */
int rx_tess_object(const re_scene_t *rs, unsigned re_obj, const ex_mesh_t *sharp, int level, ex_mesh_t *out,
                   size_t *first_round);

/* The flat parts of a fully rounded object's faces, as convex polygons
   built from the enumerated spheres (the polygons the tessellation fills):
   a hit strictly inside its face's shrunk polygon is where re_query() says
   RE_UNCHANGED. The renderer does not need it (re_query_uv's per-triangle
   bands answer that question inside the library); the tests use it as an
   independent oracle for those bands. */
typedef struct rx_flat_t {
    size_t ntris;        /* 0: no polygons (object not fully rounded): never claim flat */
    size_t *tri_lines;   /* 2 per triangle of the sharp mesh: its face polygon's edges
                            are lines[4*tri_lines[2t] .. 4*tri_lines[2t+1]) (one load per
                            hit instead of triangle -> face -> range: the renderer calls
                            this on every hit of a rounded object) */
    double *lines;       /* 4 per polygon edge: inward in-plane unit normal m, offset m.a */
} rx_flat_t;

/* 0; 1 when some vertex is not rounded, as for rx_tess_object (f stays
   empty); -1 out of memory. */
int rx_flat_build(const re_scene_t *rs, unsigned re_obj, const ex_mesh_t *sharp, rx_flat_t *f);
void rx_flat_free(rx_flat_t *f);
/* 1 when p (on triangle tri) lies inside its face's flat part by more than `margin`. */
static inline int rx_flat_inside(const rx_flat_t *f, unsigned tri, ex_v3_t p, double margin)
{
    size_t e, e0, e1;
    if (tri >= f->ntris) return 0;
    e0 = f->tri_lines[2 * (size_t)tri];
    e1 = f->tri_lines[2 * (size_t)tri + 1];
    for (e = e0; e < e1; e++) {
        const double *l = f->lines + 4 * e;
        if (l[0] * p.x + l[1] * p.y + l[2] * p.z < l[3] + margin) return 0;
    }
    return e1 > e0;
}

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

/* The shrunk faces (see the top comment): plane groups of the sharp mesh's
   triangles, and per group the polygon of the sphere centres on its offset
   plane pushed out by r, counter-clockwise around the group's normal. */
typedef struct rx__faces_t {
    size_t n;            /* groups */
    ex_v3_t *normal;     /* per group */
    size_t *first;       /* n + 1: corners of group g are pts[first[g] .. first[g+1]) (none: < 3 corners) */
    ex_v3_t *pts;
    unsigned *tri_face;  /* per triangle */
} rx__faces_t;

static void rx__faces_free(rx__faces_t *f)
{
    free(f->normal); free(f->first); free(f->pts); free(f->tri_face);
    memset(f, 0, sizeof *f);
}

static int rx__faces_build(const re_sphere_t *sp, unsigned nsp, const ex_mesh_t *sharp, double size, rx__faces_t *f)
{
    double *pd = (double *)malloc(sizeof(double) * (sharp->ntris + 1));
    double *ang = (double *)malloc(sizeof(double) * (nsp + 1));
    size_t t, np_total = 0;
    unsigned i;
    memset(f, 0, sizeof *f);
    f->normal = (ex_v3_t *)malloc(sizeof(ex_v3_t) * (sharp->ntris + 1));
    f->first = (size_t *)malloc(sizeof(size_t) * (sharp->ntris + 2));
    f->tri_face = (unsigned *)malloc(sizeof(unsigned) * (sharp->ntris + 1));
    if (!pd || !ang || !f->normal || !f->first || !f->tri_face) {
        free(pd); free(ang); rx__faces_free(f); return -1;
    }
    for (t = 0; t < sharp->ntris; t++) {
        const uint32_t *q = sharp->idx + 3 * t;
        ex_v3_t a = ex_v3(sharp->pos[3 * q[0]], sharp->pos[3 * q[0] + 1], sharp->pos[3 * q[0] + 2]);
        ex_v3_t bb = ex_v3(sharp->pos[3 * q[1]], sharp->pos[3 * q[1] + 1], sharp->pos[3 * q[1] + 2]);
        ex_v3_t c = ex_v3(sharp->pos[3 * q[2]], sharp->pos[3 * q[2] + 1], sharp->pos[3 * q[2] + 2]);
        ex_v3_t n = ex_normalize(ex_cross(ex_sub(bb, a), ex_sub(c, a)));
        double d = ex_dot(n, a);
        size_t k;
        for (k = 0; k < f->n; k++)
            if (ex_dot(f->normal[k], n) > 1 - 1e-6 && fabs(pd[k] - d) < 1e-6 * size) break;
        if (k == f->n) { f->normal[k] = n; pd[k] = d; f->n++; }
        f->tri_face[t] = (unsigned)k;
    }
    /* a corner can lie on every plane: room for nsp corners per face */
    f->pts = (ex_v3_t *)malloc(sizeof(ex_v3_t) * ((size_t)nsp * f->n + 1));
    if (!f->pts) { free(pd); free(ang); rx__faces_free(f); return -1; }
    for (t = 0; t < f->n; t++) {
        ex_v3_t n = f->normal[t], tt, bt, ctr = ex_v3(0, 0, 0), *pts;
        size_t np = 0, k;
        f->first[t] = np_total;
        pts = f->pts + np_total;
        for (i = 0; i < nsp; i++) {
            ex_v3_t p = ex_madd(ex_v3(sp[i].center[0], sp[i].center[1], sp[i].center[2]), n, sp[i].radius);
            int dup = 0;
            if (fabs(ex_dot(n, p) - pd[t]) > 1e-5 * size) continue;
            for (k = 0; k < np; k++)
                if (ex_len(ex_sub(pts[k], p)) < 1e-9 * size) dup = 1;
            if (!dup) pts[np++] = p;
        }
        if (np < 3) continue; /* a face consumed by its rounding */
        for (k = 0; k < np; k++) ctr = ex_add(ctr, pts[k]);
        ctr = ex_scale(ctr, 1.0 / (double)np);
        ex_onb(n, &tt, &bt);
        for (k = 0; k < np; k++) {
            ex_v3_t r = ex_sub(pts[k], ctr);
            ang[k] = atan2(ex_dot(r, bt), ex_dot(r, tt));
        }
        for (k = 1; k < np; k++) { /* insertion sort by angle: counter-clockwise around n */
            size_t j = k;
            while (j > 0 && ang[j - 1] > ang[j]) {
                double sa = ang[j]; ex_v3_t sv = pts[j];
                ang[j] = ang[j - 1]; pts[j] = pts[j - 1];
                ang[j - 1] = sa; pts[j - 1] = sv;
                j--;
            }
        }
        np_total += np;
    }
    f->first[f->n] = np_total;
    free(pd); free(ang);
    return 0;
}

/* On the segment between mesh vertices i and j, strictly inside it (float
   positions: to RX__ON_SEGMENT times the object's size). */
#define RX__ON_SEGMENT 1e-6

static int rx__inside_segment(const ex_mesh_t *m, size_t v, long long i, long long j, double size)
{
    ex_v3_t a, b, p, ab, ap;
    double l2, t;
    if (i < 0 || j < 0 || (size_t)i >= m->nverts || (size_t)j >= m->nverts || (size_t)i == v || (size_t)j == v) return 0;
    a = ex_v3(m->pos[3 * i], m->pos[3 * i + 1], m->pos[3 * i + 2]);
    b = ex_v3(m->pos[3 * j], m->pos[3 * j + 1], m->pos[3 * j + 2]);
    p = ex_v3(m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
    ab = ex_sub(b, a);
    ap = ex_sub(p, a);
    l2 = ex_dot(ab, ab);
    if (!(l2 > 0)) return 0;
    t = ex_dot(ap, ab) / l2;
    return t > 0 && t < 1 && ex_len(ex_sub(ap, ex_scale(ab, t))) <= RX__ON_SEGMENT * size;
}

/* Every vertex of the sharp mesh is rounded (the shrunk-face construction
   needs every corner rounded): it has a sphere, or it lies inside a
   straight chain, an edge split by vertices where only its two faces meet,
   which the library rounds with one cylinder between the chain's end
   vertices and no sphere inside. Returns at the first vertex that is
   neither, so objects with sharp corners cost one pass over the cylinders. */
static int rx__all_corners_rounded(const re_sphere_t *sp, unsigned ns, const re_cylinder_t *cy, unsigned nc,
                                   const ex_mesh_t *sharp, double size)
{
    unsigned char *has = (unsigned char *)calloc(sharp->nverts + 1, 1);
    size_t v;
    unsigned i;
    int all = 1;
    if (!has) return -1;
    for (i = 0; i < ns; i++)
        if (sp[i].vertex < sharp->nverts) has[sp[i].vertex] = 1;
    for (v = 0; v < sharp->nverts && all; v++) {
        if (has[v]) continue;
        for (i = 0; i < nc; i++)
            if (rx__inside_segment(sharp, v, cy[i].edge_v0, cy[i].edge_v1, size)) break;
        if (i == nc) all = 0;
    }
    free(has);
    return all;
}

/* Cylinders ordered by their sphere pair. */
static int rx__cmp_cyl(const void *x, const void *y)
{
    const re_cylinder_t *a = (const re_cylinder_t *)x, *b = (const re_cylinder_t *)y;
    if (a->sa != b->sa) return a->sa < b->sa ? -1 : 1;
    return a->sb < b->sb ? -1 : a->sb > b->sb;
}
/* The enumerated cylinders, each once: every segment of a straight chain
   enumerates the chain's whole cylinder (re_cylinder_t), the same
   sphere pair. Returns the count kept at the front of cy. */
static unsigned rx__unique_cylinders(re_cylinder_t *cy, unsigned nc)
{
    unsigned i, n = 0;
    qsort(cy, nc, sizeof *cy, rx__cmp_cyl);
    for (i = 0; i < nc; i++)
        if (!n || cy[i].sa != cy[n - 1].sa || cy[i].sb != cy[n - 1].sb) cy[n++] = cy[i];
    return n;
}

static double rx__mesh_size(const ex_mesh_t *m)
{
    double size = 0;
    size_t v;
    for (v = 0; v < 3 * m->nverts; v++) size = fmax(size, fabs(m->pos[v]));
    return size > 0 ? size : 1;
}

static int rx__tess_faces(rx__tb_t *b, const re_sphere_t *sp, unsigned nsp, const ex_mesh_t *sharp, double size)
{
    rx__faces_t f;
    size_t g, k;
    if (rx__faces_build(sp, nsp, sharp, size, &f)) return -1;
    for (g = 0; g < f.n; g++) {
        uint32_t first, prev;
        if (f.first[g + 1] - f.first[g] < 3) continue;
        first = rx__tb_vertex(b, f.pts[f.first[g]]);
        prev = rx__tb_vertex(b, f.pts[f.first[g] + 1]);
        for (k = f.first[g] + 2; k < f.first[g + 1]; k++) {
            uint32_t cur = rx__tb_vertex(b, f.pts[k]);
            rx__tb_tri(b, first, prev, cur, f.normal[g]);
            prev = cur;
        }
    }
    rx__faces_free(&f);
    return b->oom ? -1 : 0;
}

int rx_flat_build(const re_scene_t *rs, unsigned re_obj, const ex_mesh_t *sharp, rx_flat_t *out)
{
    unsigned ns = re_sphere_count(rs, re_obj), nc = re_cylinder_count(rs, re_obj), i;
    re_sphere_t *sp = (re_sphere_t *)malloc(sizeof *sp * (ns + 1));
    re_cylinder_t *cy = (re_cylinder_t *)malloc(sizeof *cy * (nc + 1));
    rx__faces_t f;
    size_t g, k, ne;
    double size = rx__mesh_size(sharp);
    int all;
    memset(out, 0, sizeof *out);
    if (!sp || !cy) { free(sp); free(cy); return -1; }
    for (i = 0; i < ns; i++) re_get_sphere(rs, re_obj, i, &sp[i]);
    for (i = 0; i < nc; i++) re_get_cylinder(rs, re_obj, i, &cy[i]);
    all = rx__all_corners_rounded(sp, ns, cy, nc, sharp, size);
    free(cy);
    if (all != 1) { free(sp); return all < 0 ? -1 : 1; }
    if (rx__faces_build(sp, ns, sharp, size, &f)) { free(sp); return -1; }
    free(sp);
    ne = f.first[f.n];
    out->tri_lines = (size_t *)malloc(sizeof(size_t) * 2 * (sharp->ntris + 1));
    out->lines = (double *)malloc(sizeof(double) * 4 * (ne + 1));
    if (!out->tri_lines || !out->lines) { rx__faces_free(&f); rx_flat_free(out); return -1; }
    for (k = 0; k < sharp->ntris; k++) {
        out->tri_lines[2 * k] = f.first[f.tri_face[k]];
        out->tri_lines[2 * k + 1] = f.first[f.tri_face[k] + 1];
    }
    for (g = 0; g < f.n; g++) {
        size_t a0 = f.first[g], cnt = f.first[g + 1] - a0;
        for (k = 0; k < cnt; k++) {
            ex_v3_t a = f.pts[a0 + k], b = f.pts[a0 + (k + 1) % cnt];
            ex_v3_t m = ex_normalize(ex_cross(f.normal[g], ex_sub(b, a))); /* inward for a CCW polygon */
            double *l = out->lines + 4 * (a0 + k);
            l[0] = m.x; l[1] = m.y; l[2] = m.z; l[3] = ex_dot(m, a);
        }
    }
    out->ntris = sharp->ntris;
    rx__faces_free(&f);
    return 0;
}

void rx_flat_free(rx_flat_t *f)
{
    free(f->tri_lines); free(f->lines);
    memset(f, 0, sizeof *f);
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
    double size;
    int rc = 0;
    memset(out, 0, sizeof *out);
    memset(&b, 0, sizeof b);
    b.m = out;
    if (!sp || !cy || level < 1) { free(sp); free(cy); return -1; }
    for (i = 0; i < ns; i++) re_get_sphere(rs, re_obj, i, &sp[i]);
    for (i = 0; i < nc; i++) re_get_cylinder(rs, re_obj, i, &cy[i]);
    size = rx__mesh_size(sharp);
    nc = rx__unique_cylinders(cy, nc);
    {
        /* every vertex needs a sphere or a chain, else fall back to the sharp mesh */
        int all = rx__all_corners_rounded(sp, ns, cy, nc, sharp, size);
        if (all != 1) {
            free(sp); free(cy);
            if (all < 0) return -1;
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
    if (rx__tess_faces(&b, sp, ns, sharp, size)) rc = -1;
    *first_round = out->ntris;
    for (i = 0; rc == 0 && i < nc; i++) rx__tess_cylinder(&b, &cy[i], level);
    for (i = 0; rc == 0 && i < ns; i++) rc = rx__tess_sphere(&b, &sp[i], i, cy, nc, level);
    free(sp); free(cy);
    if (rc || b.oom) { free(out->pos); free(out->idx); memset(out, 0, sizeof *out); return -1; }
    return 0;
}

#endif /* RX_TESS_IMPLEMENTATION_DONE */
#endif /* RX_TESS_IMPLEMENTATION */
