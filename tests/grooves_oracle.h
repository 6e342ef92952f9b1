/* tests/grooves_oracle.h — grooves built as real geometry, the reference
   that include/grooves.h is checked against.

   Independent of grooves.h's algorithm: every groove's polyline cross-section
   is swept along its UV path (lines, polylines, quadratic and cubic Béziers,
   sampled finely) into a triangle mesh in Embree, in texture space (u, v, w),
   w up. The ground w = 0 is an analytic plane with holes: a point of the
   plane belongs to the ground unless it lies inside a groove's mouth, which is
   tested against flat "mouth" quads built from the very same edge vertices as
   the sweep, so ground and grooves meet without gaps or overlaps. A path's
   two ends are closed by caps: the section polygon (closed along w = 0,
   in runs between its points on w = 0), facets GRO_CAP0 (t = 0) and
   GRO_CAP1 (t = 1).

   Crossings (constructive solid geometry): the surface is the ground minus
   the union of the grooves' cut volumes (section parts below w = 0), plus
   their protruding volumes (parts above). Every groove instance is its own
   mesh, so at a crossing a ray would stop on the higher floor, or on a wall
   that the other groove has cut away. An Embree filter therefore drops any
   facet hit that lies strictly inside another instance's volume (the
   section polygon swept along that instance's sampled path, one prism per
   chord; strictly: farther than `eps` from its boundary, so coincident
   floors of equal depth stay), and traversal goes on to the next surface.
   Primary and shadow rays use it alike. Where a protrusion crosses
   another groove's cut it bridges the hole, and the plane w = 0 is the
   bridge's underside: gro_scene_intersect() reports it as the ground seen
   from below (normal down; the ground's material), tested against the
   volumes just above and below the plane (gro__plane_surface). Limits: one instance is never
   tested against itself (a self-crossing path is not carved), and at a
   polyline corner the prisms miss the outer miter wedge (straight paths and
   smooth curves are exact to the chord tolerance).

   gro_query() then supersamples a footprint with n×n stratified rays coming
   from the view direction E, classifies each first hit by (groove, facet) or
   ground, and casts one shadow ray per light. Its fractions are Monte Carlo
   estimates; for a footprint crossed by B straight region boundaries (two per
   visible strip) a stratified n×n estimate has standard deviation at most
   sqrt(B / (2 n^3)) (only the <= 2n cells a line crosses have variance, each
   <= 1/4, divided by N^2 = n^4), e.g. 2.4e-4 for one strip at n = 256.

   Conventions it shares with grooves.h (checked by the tests, not by code):
     - path parameter t in [0, 1]; a polyline's t is proportional to arc length;
     - binormal B = (-T_v, T_u), T the unit tangent; section point (b, w) sits
       at P(t) + s(t)·b·B + s(t)·w·W, s(t) the perturbation scale (1 if none);
     - facet k joins section points k and k+1;
     - footprint: F + a·A1 + c·A2 with a, c in [-1, 1] (A1, A2 half-axes);
     - E and the lights L are unit vectors in texture space pointing away from
       the surface (E toward the viewer); a light with L_w <= 0 lights nothing.
   The example and the benchmark use gro_scene_* as their "real geometry". */
#ifndef FILIGREE_GROOVES_ORACLE_H
#define FILIGREE_GROOVES_ORACLE_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "test_even_odd.h"

#define GRO_MAX_FACETS 32
#define GRO_MAX_LIGHTS 8
/* Result slots per groove: its facets 0..GRO_MAX_FACETS-1, then the end caps. */
#define GRO_CAP0 GRO_MAX_FACETS       /* the cap at t = 0 */
#define GRO_CAP1 (GRO_MAX_FACETS + 1) /* the cap at t = 1 */
#define GRO_SLOTS (GRO_MAX_FACETS + 2)

enum { GRO_LINE = 0, GRO_POLYLINE = 1, GRO_QUADRATIC = 2, GRO_CUBIC = 3 };
enum { GRO_HIT_NONE = 0, GRO_HIT_GROUND = 1, GRO_HIT_FACET = 2 };

/* One groove: a path in UV and a cross-section in the path's (B, W) plane. */
typedef struct gro_groove_t {
    int kind;              /* GRO_LINE (2 points), GRO_POLYLINE (>= 2), GRO_QUADRATIC (chain of
                              2k+1 points), GRO_CUBIC (chain of 3k+1 points); piece j of k
                              covers t in [j/k, (j+1)/k] */
    int nctrl;             /* number of UV points in ctrl */
    const double *ctrl;    /* u0, v0, u1, v1, ... */
    int nsec;              /* section points, 2..GRO_MAX_FACETS+1, first and last with w = 0 */
    const double *sec;     /* b0, w0, b1, w1, ... (UV units; w < 0 cuts into the surface) */
    double (*scale)(double t, void *ctx); /* perturbation s(t); NULL means 1; < 0 and NaN count as 0 */
    void *scale_ctx;
} gro_groove_t;

typedef struct gro_build_t {
    int wrap;              /* 1: the texture repeats, grooves are copied to the 8 neighbouring tiles */
    double period[2];      /* tile size in u and v; 0 → 1 (the tile [0,1)²) */
    double roi[4];         /* u0, v0, u1, v1: only geometry near this box is built; u1 <= u0 → all */
    double origin[2];      /* UV subtracted before conversion to float (keeps precision); default 0 */
    double ground[4];      /* the ground exists only inside u0, v0, u1, v1; u1 <= u0 → everywhere */
    double chord_tol;      /* max deviation of the sampled path from the curve, UV; 0 → 1e-4·width */
} gro_build_t;

struct gro__vol_t;

typedef struct gro_scene_t {
    RTCDevice dev;
    struct gro__vol_t *vol; /* the instances' volumes, for the crossing filter */
    RTCScene mesh;         /* swept cross-sections */
    RTCScene mouths;       /* flat quads at w = 0 covering each groove's mouth */
    int *tri_groove, *tri_facet; /* per triangle of mesh: groove and facet (or GRO_CAP0/1) */
    size_t ntris, nverts, nmouth_tris;
    double origin[2], ground[4];
    double eps;            /* shadow-ray offset, UV units */
    double top;            /* highest point of any section (>= 0), UV */
    int bridges;           /* 1: a protrusion may bridge another instance's cut (w = 0 then has an underside) */
} gro_scene_t;

typedef struct gro_hit_t {
    int kind;              /* GRO_HIT_NONE / GROUND / FACET */
    int groove, facet;     /* valid for GRO_HIT_FACET */
    double t;              /* ray parameter */
    double p[3];           /* hit point, UV (origin added back) */
    double n[3];           /* unit normal facing the ray's origin side */
} gro_hit_t;

/* ------------------------------------------------------------ device */

/* Bytes Embree holds for a device, counted by its memory monitor. */
typedef struct gro_device_t { RTCDevice dev; long long bytes; } gro_device_t;

static bool gro__monitor(void *user, ssize_t bytes, bool post)
{
    (void)post;
    __atomic_add_fetch(&((gro_device_t *)user)->bytes, (long long)bytes, __ATOMIC_RELAXED);
    return true;
}

/* Creates the device; returns 0, or -1 when Embree does not start. */
static int gro_device_init(gro_device_t *d)
{
    d->bytes = 0;
    d->dev = rtcNewDevice(NULL);
    if (!d->dev) return -1;
    rtcSetDeviceMemoryMonitorFunction(d->dev, gro__monitor, d);
    return 0;
}
static void gro_device_free(gro_device_t *d)
{
    if (d->dev) rtcReleaseDevice(d->dev);
    d->dev = NULL;
}

/* ------------------------------------------------------------ paths */

static void gro__lerp2(const double *a, const double *b, double t, double *r)
{
    r[0] = a[0] + (b[0] - a[0]) * t;
    r[1] = a[1] + (b[1] - a[1]) * t;
}

/* Point of the path at t in [0, 1] (de Casteljau for Béziers, arc length for polylines). */
static int gro__bezier_degree(const gro_groove_t *g)
{
    return g->kind == GRO_QUADRATIC ? 2 : g->kind == GRO_CUBIC ? 3 : 0;
}
static int gro__pieces(const gro_groove_t *g)
{
    int deg = gro__bezier_degree(g);
    return deg ? (g->nctrl - 1) / deg : g->nctrl - 1;
}

static void gro__path_point(const gro_groove_t *g, double t, double *p)
{
    const double *c = g->ctrl;
    int deg = gro__bezier_degree(g);
    if (deg) {
        double q[8];
        int n = deg + 1, i, j, k = gro__pieces(g), piece = (int)floor(t * k);
        if (piece < 0) piece = 0;
        if (piece > k - 1) piece = k - 1;
        t = t * k - piece;
        memcpy(q, c + 2 * deg * piece, sizeof(double) * 2 * (size_t)n);
        for (j = n - 1; j > 0; j--)
            for (i = 0; i < j; i++) gro__lerp2(q + 2 * i, q + 2 * i + 2, t, q + 2 * i);
        p[0] = q[0]; p[1] = q[1];
        return;
    }
    {
        int i, nseg = g->nctrl - 1;
        double total = 0, want, acc = 0;
        for (i = 0; i < nseg; i++) total += hypot(c[2 * i + 2] - c[2 * i], c[2 * i + 3] - c[2 * i + 1]);
        want = t * total;
        for (i = 0; i < nseg; i++) {
            double len = hypot(c[2 * i + 2] - c[2 * i], c[2 * i + 3] - c[2 * i + 1]);
            if (acc + len >= want || i == nseg - 1) {
                gro__lerp2(c + 2 * i, c + 2 * i + 2, len > 0 ? (want - acc) / len : 0, p);
                return;
            }
            acc += len;
        }
    }
}

/* Parameters where a polyline or a Bézier chain may have corners (they
   must be sample points). */
static int gro__corners(const gro_groove_t *g, double *ts, int max)
{
    int i, n = 0, nseg = g->nctrl - 1;
    double total = 0, acc = 0;
    const double *c = g->ctrl;
    if (gro__bezier_degree(g)) {
        int k = gro__pieces(g);
        for (i = 1; i < k && n < max; i++) ts[n++] = (double)i / k;
        return n;
    }
    if (g->kind != GRO_POLYLINE) return 0;
    for (i = 0; i < nseg; i++) total += hypot(c[2 * i + 2] - c[2 * i], c[2 * i + 3] - c[2 * i + 1]);
    for (i = 0; i + 1 < nseg && n < max; i++) {
        acc += hypot(c[2 * i + 2] - c[2 * i], c[2 * i + 3] - c[2 * i + 1]);
        ts[n++] = acc / total;
    }
    return n;
}

/* Bound on |P''(t)| for Béziers (0 for lines and polylines between corners). */
static double gro__second_derivative_bound(const gro_groove_t *g)
{
    const double *c = g->ctrl;
    double m = 0;
    int i, n = gro__bezier_degree(g), k = gro__pieces(g);
    if (!n) return 0;
    for (i = 0; i + 2 <= n * k; i++) { /* over every piece; t runs k times faster */
        double du = c[2 * i + 4] - 2 * c[2 * i + 2] + c[2 * i];
        double dv = c[2 * i + 5] - 2 * c[2 * i + 3] + c[2 * i + 1];
        m = fmax(m, hypot(du, dv));
    }
    return n * (n - 1) * m * k * k;
}

static double gro__scale(const gro_groove_t *g, double t)
{
    double s = g->scale ? g->scale(t, g->scale_ctx) : 1.0;
    return s > 0 ? s : 0.0;
}

/* Largest |b| and |w| of a section (before perturbation). */
static void gro__section_extent(const gro_groove_t *g, double *bmax, double *wmax, double *top)
{
    int k;
    *bmax = *wmax = *top = 0;
    for (k = 0; k < g->nsec; k++) {
        *bmax = fmax(*bmax, fabs(g->sec[2 * k]));
        *wmax = fmax(*wmax, fabs(g->sec[2 * k + 1]));
        *top = fmax(*top, g->sec[2 * k + 1]);
    }
}

/* ------------------------------------------------------------ volumes (crossings) */

/* One chord of an instance's sampled path (local coordinates: origin
   subtracted), with the scale at its ends. A point belongs to the chord's
   prism when its projection falls on the chord and its (b, w), divided by
   the scale, is inside the section polygon. */
typedef struct gro__seg_t {
    double p0[2], p1[2], s0, s1, bmax; /* bmax: widest |b| times the larger scale */
    int groove, inst;
    int open0, open1;                  /* 1: that chord end is a path end (capped) */
} gro__seg_t;

typedef struct gro__vol_t {
    gro__seg_t *segs; size_t nsegs, capsegs;
    int *tri_inst;                     /* per mesh triangle: its instance */
    double (*sec)[2 * (GRO_MAX_FACETS + 1)]; /* copies of the sections */
    int *nsec;
    double eps;                        /* boundary margin, UV */
    double box[4]; int gn;             /* uniform grid over the chords' boxes */
    int *cell_start, *cell_items;
} gro__vol_t;

/* Distance from (x, y) to the segment a-b. */
static double gro__seg_dist(double x, double y, const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy, t = 0;
    if (l2 > 0) t = fmin(1, fmax(0, ((x - a[0]) * dx + (y - a[1]) * dy) / l2));
    return hypot(x - a[0] - t * dx, y - a[1] - t * dy);
}

/* 1 when (b, w) lies inside the section polygon (closed along w = 0) by more
   than m: even-odd rule plus a distance test to every edge. */
static int gro__in_section(const double *sec, int n, double b, double w, double m)
{
    int k;
    for (k = 0; k < n; k++)
        if (gro__seg_dist(b, w, sec + 2 * k, sec + 2 * ((k + 1) % n)) <= m) return 0;
    return teo_in_ring(sec, n, b, w);
}

/* 1 when the local point x lies strictly inside an instance other than
   `inst` (-1: any instance). */
static int gro__inside_other(const gro__vol_t *v, const double *x, int inst)
{
    int cu, cv, i;
    if (!v->gn) return 0;
    cu = (int)floor((x[0] - v->box[0]) / (v->box[2] - v->box[0]) * v->gn);
    cv = (int)floor((x[1] - v->box[1]) / (v->box[3] - v->box[1]) * v->gn);
    if (cu < 0 || cv < 0 || cu >= v->gn || cv >= v->gn) return 0;
    for (i = v->cell_start[cv * v->gn + cu]; i < v->cell_start[cv * v->gn + cu + 1]; i++) {
        const gro__seg_t *sg = &v->segs[v->cell_items[i]];
        double d[2] = {sg->p1[0] - sg->p0[0], sg->p1[1] - sg->p0[1]}, len = hypot(d[0], d[1]), a, s, bb;
        if (sg->inst == inst || len <= 0) continue;
        a = ((x[0] - sg->p0[0]) * d[0] + (x[1] - sg->p0[1]) * d[1]) / len; /* along the chord, UV */
        if (a < (sg->open0 ? v->eps : 0) || a > len - (sg->open1 ? v->eps : 0)) continue;
        s = sg->s0 + (sg->s1 - sg->s0) * a / len;
        if (!(s > 0)) continue;
        bb = ((x[0] - sg->p0[0]) * -d[1] + (x[1] - sg->p0[1]) * d[0]) / len; /* along B = (-T_v, T_u) */
        if (gro__in_section(v->sec[sg->groove], v->nsec[sg->groove], bb / s, x[2] / s, v->eps / s)) return 1;
    }
    return 0;
}

/* Embree filter (primary and shadow rays): a hit inside another groove's
   volume is not on the true surface; reject it so traversal continues. */
static void gro__filter(const struct RTCFilterFunctionNArguments *args)
{
    const gro__vol_t *v = (const gro__vol_t *)args->geometryUserPtr;
    unsigned i;
    for (i = 0; i < args->N; i++) {
        double x[3];
        /* RTCRayN / RTCHitN are SoA blocks of N lanes (rtcore_ray.h; its
           accessors are C++ only): org x,y,z, tnear, dir x,y,z, time, tfar, ...;
           Ng x,y,z, u, v, primID, ... */
        const float *ray = (const float *)args->ray;
        const unsigned *hit = (const unsigned *)args->hit, N = args->N;
        int m;
        if (args->valid[i] != -1) continue;
        for (m = 0; m < 3; m++) x[m] = (double)ray[m * N + i] + (double)ray[8 * N + i] * (double)ray[(4 + m) * N + i];
        if (gro__inside_other(v, x, v->tri_inst[hit[5 * N + i]])) args->valid[i] = 0;
    }
}

/* Bins every chord's box (grown by its width) into a gn x gn grid. Returns -1 on OOM. */
static int gro__vol_index(gro__vol_t *v)
{
    size_t i;
    int pass, n = 0, *fill = NULL;
    if (!v->nsegs) return 0;
    v->box[0] = v->box[1] = INFINITY; v->box[2] = v->box[3] = -INFINITY;
    for (i = 0; i < v->nsegs; i++) {
        const gro__seg_t *sg = &v->segs[i];
        v->box[0] = fmin(v->box[0], fmin(sg->p0[0], sg->p1[0]) - sg->bmax);
        v->box[1] = fmin(v->box[1], fmin(sg->p0[1], sg->p1[1]) - sg->bmax);
        v->box[2] = fmax(v->box[2], fmax(sg->p0[0], sg->p1[0]) + sg->bmax);
        v->box[3] = fmax(v->box[3], fmax(sg->p0[1], sg->p1[1]) + sg->bmax);
    }
    v->gn = (int)fmin(256, fmax(1, ceil(sqrt((double)v->nsegs))));
    v->cell_start = (int *)calloc((size_t)v->gn * v->gn + 1, sizeof(int));
    if (!v->cell_start) return -1;
    for (pass = 0; pass < 2; pass++) {
        for (i = 0; i < v->nsegs; i++) {
            const gro__seg_t *sg = &v->segs[i];
            double su = v->gn / (v->box[2] - v->box[0]), sv = v->gn / (v->box[3] - v->box[1]);
            int u0 = (int)((fmin(sg->p0[0], sg->p1[0]) - sg->bmax - v->box[0]) * su);
            int u1 = (int)((fmax(sg->p0[0], sg->p1[0]) + sg->bmax - v->box[0]) * su);
            int v0 = (int)((fmin(sg->p0[1], sg->p1[1]) - sg->bmax - v->box[1]) * sv);
            int v1 = (int)((fmax(sg->p0[1], sg->p1[1]) + sg->bmax - v->box[1]) * sv), a, c;
            for (c = v0 < 0 ? 0 : v0; c <= v1 && c < v->gn; c++)
                for (a = u0 < 0 ? 0 : u0; a <= u1 && a < v->gn; a++) {
                    if (pass == 0) v->cell_start[c * v->gn + a + 1]++;
                    else v->cell_items[fill[c * v->gn + a]++] = (int)i;
                }
        }
        if (pass == 0) {
            int c;
            for (c = 0; c < v->gn * v->gn; c++) v->cell_start[c + 1] += v->cell_start[c];
            n = v->cell_start[v->gn * v->gn];
            v->cell_items = (int *)malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
            fill = (int *)malloc(sizeof(int) * (size_t)v->gn * v->gn);
            if (!v->cell_items || !fill) { free(fill); return -1; }
            memcpy(fill, v->cell_start, sizeof(int) * (size_t)v->gn * v->gn);
        }
    }
    free(fill);
    return 0;
}

static void gro__vol_free(gro__vol_t *v)
{
    if (!v) return;
    free(v->segs); free(v->tri_inst); free(v->sec); free(v->nsec); free(v->cell_start); free(v->cell_items);
    free(v);
}

/* Ear clipping of the section polygon (closed along w = 0) into n - 2
   triangles of section indices; returns the count written (0 if it fails,
   e.g. a self-intersecting section). */
static int gro__ear_clip(const double *sec, int n, uint32_t *tri)
{
    int idx[GRO_MAX_FACETS + 1], m = n, nt = 0, guard = 0, i;
    double area = 0;
    for (i = 0; i < n; i++) {
        idx[i] = i;
        area += sec[2 * i] * sec[2 * ((i + 1) % n) + 1] - sec[2 * ((i + 1) % n)] * sec[2 * i + 1];
    }
    while (m > 3 && guard++ < 4 * n * n) {
        for (i = 0; i < m; i++) {
            const double *a = sec + 2 * idx[(i + m - 1) % m], *b = sec + 2 * idx[i], *c = sec + 2 * idx[(i + 1) % m];
            double cr = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            int j, ok = cr * area > 0;
            for (j = 0; ok && j < m; j++) {
                const double *q = sec + 2 * idx[j];
                double d1, d2, d3;
                if (j == i || j == (i + 1) % m || j == (i + m - 1) % m) continue;
                d1 = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
                d2 = (c[0] - b[0]) * (q[1] - b[1]) - (c[1] - b[1]) * (q[0] - b[0]);
                d3 = (a[0] - c[0]) * (q[1] - c[1]) - (a[1] - c[1]) * (q[0] - c[0]);
                if (d1 * area >= 0 && d2 * area >= 0 && d3 * area >= 0) ok = 0;
            }
            if (!ok) continue;
            tri[3 * nt] = (uint32_t)idx[(i + m - 1) % m]; tri[3 * nt + 1] = (uint32_t)idx[i];
            tri[3 * nt + 2] = (uint32_t)idx[(i + 1) % m];
            nt++;
            memmove(idx + i, idx + i + 1, sizeof(int) * (size_t)(m - i - 1));
            m--;
            break;
        }
    }
    if (m != 3) return 0;
    tri[3 * nt] = (uint32_t)idx[0]; tri[3 * nt + 1] = (uint32_t)idx[1]; tri[3 * nt + 2] = (uint32_t)idx[2];
    return nt + 1;
}

/* The cap: the section closed along w = 0, cut at its points on w = 0
   into runs (a lip above, the cut below, the next lip, ... each a simple
   polygon closed along w = 0: the whole is not simple where the section
   touches w = 0 between its ends), each ear-clipped; triangles of section
   indices, their count. A facet crossing w = 0 between two points is left
   as it is (the whole run is clipped, which fails for a self-crossing one). */
static int gro__cap_triangles(const double *sec, int n, uint32_t *tri)
{
    int i0 = 0, i, nt = 0, k;
    for (i = 1; i < n; i++) {
        int m;
        if (sec[2 * i + 1] != 0 && i + 1 < n) continue;
        if (i - i0 >= 2) {
            m = gro__ear_clip(sec + 2 * i0, i - i0 + 1, tri + 3 * nt);
            for (k = 0; k < 3 * m; k++) tri[3 * nt + k] += (uint32_t)i0;
            nt += m;
        }
        i0 = i;
    }
    return nt;
}

/* ------------------------------------------------------------ sweep */

typedef struct gro__buf_t {
    float *v; size_t nv, capv;       /* mesh vertices */
    uint32_t *t; size_t nt, capt;    /* mesh triangles */
    int *tg, *tf;                    /* per mesh triangle */
    float *mv; size_t nmv, capmv;    /* mouth vertices */
    uint32_t *mt; size_t nmt, capmt; /* mouth triangles */
    gro__vol_t *vol;                 /* chords and per-triangle instance */
    int oom;
} gro__buf_t;

static void *gro__grow(void *p, size_t *cap, size_t need, size_t elem)
{
    size_t c = *cap ? *cap : 1024;
    void *q;
    if (need <= *cap) return p;
    while (c < need) c *= 2;
    q = realloc(p, c * elem);
    if (q) *cap = c;
    return q;
}

/* Per-run state: the sampled parameters of one connected piece of path. */
typedef struct gro__run_t { double *t; int n, cap; } gro__run_t;

static void gro__run_push(gro__run_t *r, double t, int *oom)
{
    if (r->n == r->cap) {
        int c = r->cap ? 2 * r->cap : 256;
        double *q = (double *)realloc(r->t, sizeof(double) * (size_t)c);
        if (!q) { *oom = 1; return; }
        r->t = q; r->cap = c;
    }
    r->t[r->n++] = t;
}

typedef struct gro__ctx_t {
    const gro_groove_t *g;
    double off[2];        /* wrap offset added to the path */
    const double *roi;    /* NULL: no restriction */
    double margin;        /* groove half-width times max scale, plus slack */
    double m2, tol, width;
    int joined;           /* 1: on a repeating texture the path's ends are a
                             whole number of tiles apart, so it runs on across
                             the seam: no end caps */
} gro__ctx_t;

static int gro__near_roi(const gro__ctx_t *c, const double *p0, const double *p1, double dev)
{
    double m = c->margin + dev;
    double u0 = fmin(p0[0], p1[0]) - m, u1 = fmax(p0[0], p1[0]) + m;
    double v0 = fmin(p0[1], p1[1]) - m, v1 = fmax(p0[1], p1[1]) + m;
    if (!c->roi) return 1;
    return !(u1 < c->roi[0] || u0 > c->roi[2] || v1 < c->roi[1] || v0 > c->roi[3]);
}

/* Recursively samples [t0, t1]: splits while the chord deviates from the
   curve by more than tol (|P''| Δt²/8) or the scale is not close to linear,
   drops pieces far from the ROI (ending the current run). */
static void gro__sample(const gro__ctx_t *c, double t0, double t1, int depth, gro__run_t *runs, int *nruns,
                        int maxruns, int *oom)
{
    double p0[2], p1[2], dt = t1 - t0, dev = c->m2 * dt * dt / 8, tm = 0.5 * (t0 + t1);
    double smid = gro__scale(c->g, tm), slin = 0.5 * (gro__scale(c->g, t0) + gro__scale(c->g, t1));
    gro__path_point(c->g, t0, p0);
    gro__path_point(c->g, t1, p1);
    p0[0] += c->off[0]; p0[1] += c->off[1]; p1[0] += c->off[0]; p1[1] += c->off[1];
    if (!gro__near_roi(c, p0, p1, dev)) return; /* the next piece kept starts a new run */
    if (depth < 40 && (dev > c->tol || fabs(smid - slin) * c->width > c->tol)) {
        gro__sample(c, t0, tm, depth + 1, runs, nruns, maxruns, oom);
        gro__sample(c, tm, t1, depth + 1, runs, nruns, maxruns, oom);
        return;
    }
    if (*nruns == 0) *nruns = 1;
    {
        gro__run_t *r = &runs[*nruns - 1];
        if (r->n == 0 || r->t[r->n - 1] != t0) {
            if (r->n > 0) { /* not contiguous: start a new run */
                if (*nruns == maxruns) { *oom = 1; return; }
                r = &runs[(*nruns)++];
            }
            gro__run_push(r, t0, oom);
        }
        gro__run_push(r, t1, oom);
    }
}

/* Sweeps the section along one run of samples: miter offsets at each sample. */
static void gro__sweep_run(const gro__ctx_t *c, int gi, int inst, const gro__run_t *r, gro__buf_t *b,
                           const double *origin)
{
    size_t nt0 = b->nt;
    const gro_groove_t *g = c->g;
    int j, k, ns = g->nsec, n = r->n;
    size_t base = b->nv;
    if (n < 2) return;
    b->v = (float *)gro__grow(b->v, &b->capv, b->nv + (size_t)n * ns, 3 * sizeof(float));
    b->mv = (float *)gro__grow(b->mv, &b->capmv, b->nmv + (size_t)n * 2, 3 * sizeof(float));
    if (!b->v || !b->mv) { b->oom = 1; return; }
    for (j = 0; j < n; j++) {
        double p[2], pa[2], pb[2], ta[2], tb[2], o[2], s = gro__scale(g, r->t[j]), la, lb, cosh;
        int ja = j > 0 ? j - 1 : j, jb = j + 1 < n ? j + 1 : j;
        gro__path_point(g, r->t[j], p);
        gro__path_point(g, r->t[ja], pa);
        gro__path_point(g, r->t[jb], pb);
        if (ja == j) { double h = 1e-9; gro__path_point(g, fmax(0, r->t[j] - h), pa); }
        if (jb == j) { double h = 1e-9; gro__path_point(g, fmin(1, r->t[j] + h), pb); }
        ta[0] = p[0] - pa[0]; ta[1] = p[1] - pa[1];
        tb[0] = pb[0] - p[0]; tb[1] = pb[1] - p[1];
        la = hypot(ta[0], ta[1]); lb = hypot(tb[0], tb[1]);
        if (la == 0) { ta[0] = tb[0]; ta[1] = tb[1]; la = lb; }
        if (lb == 0) { tb[0] = ta[0]; tb[1] = ta[1]; lb = la; }
        ta[0] /= la; ta[1] /= la; tb[0] /= lb; tb[1] /= lb;
        /* miter: the average binormal, lengthened by 1/cos(half turn) */
        o[0] = -(ta[1] + tb[1]); o[1] = ta[0] + tb[0];
        cosh = hypot(o[0], o[1]) / 2;
        o[0] /= 2 * cosh * cosh; o[1] /= 2 * cosh * cosh;
        p[0] += c->off[0] - origin[0]; p[1] += c->off[1] - origin[1];
        for (k = 0; k < ns; k++) {
            float *v = b->v + 3 * (b->nv++);
            double bb = s * g->sec[2 * k], ww = s * g->sec[2 * k + 1];
            v[0] = (float)(p[0] + bb * o[0]); v[1] = (float)(p[1] + bb * o[1]);
            v[2] = (k == 0 || k == ns - 1) ? 0.0f : (float)ww;
        }
        {
            float *m0 = b->mv + 3 * (b->nmv++), *m1 = b->mv + 3 * (b->nmv++);
            const float *v0 = b->v + 3 * (base + (size_t)j * ns), *v1 = v0 + 3 * (ns - 1);
            memcpy(m0, v0, 3 * sizeof(float)); memcpy(m1, v1, 3 * sizeof(float));
            m0[2] = m1[2] = 0.0f;
        }
    }
    b->t = (uint32_t *)gro__grow(b->t, &b->capt, b->nt + (size_t)(n - 1) * (ns - 1) * 2 + 2 * (size_t)ns,
                                 3 * sizeof(uint32_t));
    {
        size_t capg = b->capt;
        b->tg = (int *)realloc(b->tg, capg * sizeof(int));
        b->tf = (int *)realloc(b->tf, capg * sizeof(int));
        b->vol->tri_inst = (int *)realloc(b->vol->tri_inst, capg * sizeof(int));
    }
    b->vol->segs = (gro__seg_t *)gro__grow(b->vol->segs, &b->vol->capsegs, b->vol->nsegs + (size_t)n,
                                            sizeof(gro__seg_t));
    b->mt = (uint32_t *)gro__grow(b->mt, &b->capmt, b->nmt + (size_t)(n - 1) * 2, 3 * sizeof(uint32_t));
    if (!b->t || !b->tg || !b->tf || !b->mt || !b->vol->tri_inst || !b->vol->segs) { b->oom = 1; return; }
    for (j = 0; j + 1 < n; j++) {
        uint32_t a0 = (uint32_t)(base + (size_t)j * ns), a1 = a0 + (uint32_t)ns;
        uint32_t m0 = (uint32_t)(b->nmv - 2 * (size_t)n + 2 * (size_t)j), m1 = m0 + 2;
        uint32_t *mt = b->mt + 3 * b->nmt;
        for (k = 0; k + 1 < ns; k++) {
            uint32_t *t = b->t + 3 * b->nt;
            t[0] = a0 + k; t[1] = a0 + k + 1; t[2] = a1 + k + 1;
            t[3] = a0 + k; t[4] = a1 + k + 1; t[5] = a1 + k;
            b->tg[b->nt] = b->tg[b->nt + 1] = gi;
            b->tf[b->nt] = b->tf[b->nt + 1] = k;
            b->nt += 2;
        }
        mt[0] = m0; mt[1] = m0 + 1; mt[2] = m1 + 1;
        mt[3] = m0; mt[4] = m1 + 1; mt[5] = m1;
        b->nmt += 2;
        { /* the chord's prism, for the crossing filter */
            gro__seg_t *sg = &b->vol->segs[b->vol->nsegs++];
            double q0[2], q1[2], bm, wm, tp;
            gro__path_point(g, r->t[j], q0);
            gro__path_point(g, r->t[j + 1], q1);
            gro__section_extent(g, &bm, &wm, &tp);
            sg->p0[0] = q0[0] + c->off[0] - origin[0]; sg->p0[1] = q0[1] + c->off[1] - origin[1];
            sg->p1[0] = q1[0] + c->off[0] - origin[0]; sg->p1[1] = q1[1] + c->off[1] - origin[1];
            sg->s0 = gro__scale(g, r->t[j]); sg->s1 = gro__scale(g, r->t[j + 1]);
            sg->bmax = bm * fmax(sg->s0, sg->s1);
            sg->groove = gi; sg->inst = inst;
            sg->open0 = !c->joined && j == 0 && r->t[j] == 0.0;
            sg->open1 = !c->joined && j + 2 == n && r->t[j + 1] == 1.0;
        }
    }
    for (j = 0; j < 2; j++) { /* caps at the path's ends (not where the ROI cut the run) */
        uint32_t tri[3 * GRO_MAX_FACETS];
        int m, nc;
        size_t row = j == 0 ? base : base + (size_t)(n - 1) * ns;
        if (c->joined || r->t[j == 0 ? 0 : n - 1] != (j == 0 ? 0.0 : 1.0)) continue;
        nc = gro__cap_triangles(g->sec, ns, tri);
        for (m = 0; m < nc; m++) {
            uint32_t *t = b->t + 3 * b->nt;
            t[0] = (uint32_t)row + tri[3 * m]; t[1] = (uint32_t)row + tri[3 * m + 1];
            t[2] = (uint32_t)row + tri[3 * m + 2];
            b->tg[b->nt] = gi;
            b->tf[b->nt] = j == 0 ? GRO_CAP0 : GRO_CAP1;
            b->nt++;
        }
    }
    for (; nt0 < b->nt; nt0++) b->vol->tri_inst[nt0] = inst;
}

static RTCScene gro__commit_mesh(RTCDevice dev, const float *v, size_t nv, const uint32_t *t, size_t nt,
                                 gro__vol_t *vol)
{
    RTCScene s = rtcNewScene(dev);
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    if (nt > 0) {
        RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        float *gv = (float *)rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                     3 * sizeof(float), nv);
        uint32_t *gt = (uint32_t *)rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                           3 * sizeof(uint32_t), nt);
        if (gv && gt) {
            memcpy(gv, v, nv * 3 * sizeof(float));
            memcpy(gt, t, nt * 3 * sizeof(uint32_t));
        }
        if (vol) { /* the crossing filter (CSG) on primary and shadow rays */
            rtcSetGeometryUserData(geo, vol);
            rtcSetGeometryIntersectFilterFunction(geo, gro__filter);
            rtcSetGeometryOccludedFilterFunction(geo, gro__filter);
        }
        rtcCommitGeometry(geo);
        rtcAttachGeometry(s, geo);
        rtcReleaseGeometry(geo);
    }
    rtcCommitScene(s);
    return s;
}

/* Builds the geometry of ng grooves. Returns 0, or -1 (out of memory, Embree
   error, bad groove). */
static int gro_scene_build(gro_scene_t *sc, RTCDevice dev, const gro_groove_t *gs, int ng, const gro_build_t *opt)
{
    gro__buf_t b;
    gro_build_t o;
    int gi, du, dv, w = 0, inst = 0;
    double per[2];
    double minwidth = INFINITY;
    memset(sc, 0, sizeof *sc);
    memset(&b, 0, sizeof b);
    memset(&o, 0, sizeof o);
    if (opt) o = *opt;
    b.vol = (gro__vol_t *)calloc(1, sizeof(gro__vol_t));
    if (b.vol && ng > 0) {
        b.vol->sec = (double (*)[2 * (GRO_MAX_FACETS + 1)])calloc((size_t)ng, sizeof *b.vol->sec);
        b.vol->nsec = (int *)calloc((size_t)ng, sizeof(int));
    }
    if (!b.vol || (ng > 0 && (!b.vol->sec || !b.vol->nsec))) { gro__vol_free(b.vol); return -1; }
    sc->dev = dev;
    sc->origin[0] = o.origin[0]; sc->origin[1] = o.origin[1];
    memcpy(sc->ground, o.ground, sizeof sc->ground);
    w = o.wrap ? 1 : 0;
    per[0] = o.period[0] > 0 ? o.period[0] : 1.0;
    per[1] = o.period[1] > 0 ? o.period[1] : 1.0;
    for (gi = 0; gi < ng; gi++) {
        const gro_groove_t *g = &gs[gi];
        double bmax, wmax, top, smax = 0, corners[64];
        int i, nc, nint;
        gro__ctx_t c;
        if (g->nsec < 2 || g->nsec > GRO_MAX_FACETS + 1 || g->nctrl < 2) { gro__vol_free(b.vol); return -1; }
        memcpy(b.vol->sec[gi], g->sec, sizeof(double) * 2 * (size_t)g->nsec);
        b.vol->nsec[gi] = g->nsec;
        gro__section_extent(g, &bmax, &wmax, &top);
        for (i = 0; i <= 64; i++) smax = fmax(smax, fabs(gro__scale(g, i / 64.0)));
        sc->top = fmax(sc->top, top * smax);
        minwidth = fmin(minwidth, fmax(bmax, wmax) * smax);
        memset(&c, 0, sizeof c);
        c.g = g;
        c.roi = o.roi[2] > o.roi[0] ? o.roi : NULL;
        c.margin = bmax * smax * 1.5 + 1e-12;
        c.m2 = gro__second_derivative_bound(g);
        c.width = bmax * smax;
        c.tol = o.chord_tol > 0 ? o.chord_tol : 1e-4 * fmax(bmax, wmax) * fmax(smax, 1e-12);
        if (w) {
            double e0[2], e1[2], du0, dv0;
            gro__path_point(g, 0.0, e0);
            gro__path_point(g, 1.0, e1);
            du0 = e1[0] - e0[0]; dv0 = e1[1] - e0[1];
            du0 -= floor(du0 / per[0] + 0.5) * per[0];
            dv0 -= floor(dv0 / per[1] + 0.5) * per[1];
            c.joined = hypot(du0, dv0) <= 1e-12 * hypot(per[0], per[1]);
        }
        nc = gro__corners(g, corners, 64);
        nint = nc + 1;
        for (du = -w; du <= w; du++)
            for (dv = -w; dv <= w; dv++) {
                gro__run_t runs[256];
                int nruns = 0, r, q;
                memset(runs, 0, sizeof runs);
                c.off[0] = du * per[0]; c.off[1] = dv * per[1];
                for (q = 0; q < nint; q++) {
                    double a = q == 0 ? 0 : corners[q - 1], e = q == nint - 1 ? 1 : corners[q];
                    int m, nsub = 64;
                    for (m = 0; m < nsub; m++)
                        gro__sample(&c, a + (e - a) * m / nsub, a + (e - a) * (m + 1) / nsub, 0, runs, &nruns, 256,
                                    &b.oom);
                }
                for (r = 0; r < nruns; r++) {
                    if (!b.oom) gro__sweep_run(&c, gi, inst, &runs[r], &b, sc->origin);
                    free(runs[r].t);
                }
                inst++;
            }
    }
    if (b.oom || gro__vol_index(b.vol)) {
        free(b.v); free(b.t); free(b.tg); free(b.tf); free(b.mv); free(b.mt);
        gro__vol_free(b.vol);
        return -1;
    }
    /* shadow-ray offset: above float noise of the coordinates (ulp 6e-8 of
       their magnitude), else a small fraction of the narrowest groove */
    {
        double ext = 0;
        size_t i;
        for (i = 0; i < 3 * b.nv; i++) ext = fmax(ext, fabs((double)b.v[i]));
        sc->eps = fmax(1e-5 * (minwidth < INFINITY ? minwidth : 1.0), 1e-6 * ext);
    }
    /* the filter's boundary margin: the shadow offset, so a shadow ray's
       origin nudged off a floor shared by two grooves is not "inside" */
    b.vol->eps = 2 * sc->eps;
    sc->vol = b.vol;
    { /* one instance near the ROI cannot cross another: no filter, no cost */
        size_t i;
        int several = 0;
        for (i = 1; i < b.vol->nsegs; i++) several |= b.vol->segs[i].inst != b.vol->segs[0].inst;
        sc->mesh = gro__commit_mesh(dev, b.v, b.nv, b.t, b.nt, several ? b.vol : NULL);
        if (several) { /* a section part below w = 0 and one above it: a bridge is possible */
            int cut = 0, prot = 0, k;
            for (gi = 0; gi < ng; gi++)
                for (k = 0; k < gs[gi].nsec; k++) {
                    cut |= gs[gi].sec[2 * k + 1] < 0;
                    prot |= gs[gi].sec[2 * k + 1] > 0;
                }
            sc->bridges = cut && prot;
        }
    }
    sc->mouths = gro__commit_mesh(dev, b.mv, b.nmv, b.mt, b.nmt, NULL);
    sc->tri_groove = b.tg; sc->tri_facet = b.tf;
    sc->ntris = b.nt; sc->nverts = b.nv; sc->nmouth_tris = b.nmt;
    free(b.v); free(b.t); free(b.mv); free(b.mt);
    return rtcGetDeviceError(dev) == RTC_ERROR_NONE ? 0 : -1;
}

static void gro_scene_free(gro_scene_t *sc)
{
    if (sc->mesh) rtcReleaseScene(sc->mesh);
    if (sc->mouths) rtcReleaseScene(sc->mouths);
    free(sc->tri_groove); free(sc->tri_facet);
    gro__vol_free(sc->vol);
    memset(sc, 0, sizeof *sc);
}

/* ------------------------------------------------------------ rays */

static void gro__ray(struct RTCRay *r, const gro_scene_t *sc, const double *o, const double *d, double tnear, double tfar)
{
    r->org_x = (float)(o[0] - sc->origin[0]); r->org_y = (float)(o[1] - sc->origin[1]); r->org_z = (float)o[2];
    r->dir_x = (float)d[0]; r->dir_y = (float)d[1]; r->dir_z = (float)d[2];
    r->tnear = (float)tnear; r->tfar = (float)tfar;
    r->time = 0; r->mask = 0xFFFFFFFFu; r->id = 0; r->flags = 0;
}

/* 1 when the UV point (u, v) of the plane w = 0 is on the surface: the
   ground (inside its extent and outside every groove mouth), or the
   underside of a protrusion bridging another groove's cut. The solid is
   the ground minus the cuts plus the protrusions, so w = 0 is a surface
   where the solid's state differs just above and just below it: no mouth
   (ground below, air above), or a cut below and a protrusion above (a
   bridge seen from inside the cut); a point of a mouth with only a cut
   or only a protrusion there is not. The volumes are tested 2 filter
   margins off the plane, so the bridge is exact up to that margin at its
   borders. may_bridge = 0 skips that test (a ray coming down from above
   every protrusion meets a bar's top before its underside). */
static int gro__plane_surface(const gro_scene_t *sc, double u, double v, int may_bridge)
{
    struct RTCRay r;
    struct RTCIntersectContext ctx;
    double o[3], d[3] = {0, 0, -1};
    if (sc->ground[2] > sc->ground[0] &&
        (u < sc->ground[0] || u > sc->ground[2] || v < sc->ground[1] || v > sc->ground[3]))
        return 0;
    o[0] = u; o[1] = v; o[2] = 1;
    gro__ray(&r, sc, o, d, 0, 2);
    rtcInitIntersectContext(&ctx);
    rtcOccluded1(sc->mouths, &ctx, &r);
    if (!(r.tfar < 0)) return 1; /* Embree sets tfar = -inf on occlusion */
    if (sc->bridges && may_bridge) {
        double below[3], above[3];
        below[0] = above[0] = u - sc->origin[0];
        below[1] = above[1] = v - sc->origin[1];
        below[2] = -2 * sc->vol->eps;
        above[2] = 2 * sc->vol->eps;
        return gro__inside_other(sc->vol, below, -1) && gro__inside_other(sc->vol, above, -1);
    }
    return 0;
}
static int gro_is_ground(const gro_scene_t *sc, double u, double v) { return gro__plane_surface(sc, u, v, 1); }

/* First hit along o + t·d, t in (tnear, tfar): a facet of the mesh, or the
   ground plane w = 0 where no groove's mouth covers it. */
static gro_hit_t gro_scene_intersect(const gro_scene_t *sc, const double *o, const double *d, double tnear, double tfar)
{
    gro_hit_t h;
    struct RTCRayHit rh;
    struct RTCIntersectContext ctx;
    double tg = INFINITY;
    memset(&h, 0, sizeof h);
    h.t = INFINITY;
    gro__ray(&rh.ray, sc, o, d, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(sc->mesh, &ctx, &rh);
    if (d[2] != 0) {
        tg = -o[2] / d[2];
        if (!(tg > tnear && tg < tfar)) tg = INFINITY;
    }
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        double n[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}, l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double s = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) > 0 ? -1.0 : 1.0;
        h.kind = GRO_HIT_FACET;
        h.t = rh.ray.tfar;
        h.groove = sc->tri_groove[rh.hit.primID];
        h.facet = sc->tri_facet[rh.hit.primID];
        h.n[0] = s * n[0] / l; h.n[1] = s * n[1] / l; h.n[2] = s * n[2] / l;
    }
    if (tg < h.t) {
        double u = o[0] + tg * d[0], v = o[1] + tg * d[1];
        if (gro__plane_surface(sc, u, v, !(d[2] < 0 && o[2] >= sc->top))) {
            h.kind = GRO_HIT_GROUND;
            h.t = tg;
            h.n[0] = 0; h.n[1] = 0; h.n[2] = d[2] < 0 ? 1 : -1;
        }
    }
    if (h.kind != GRO_HIT_NONE) {
        int i;
        for (i = 0; i < 3; i++) h.p[i] = o[i] + h.t * d[i];
        if (h.kind == GRO_HIT_GROUND) h.p[2] = 0;
    }
    return h;
}

/* 1 when the hit point sees the direction L (unit) unblocked. A light at or
   below the horizon (L_w <= 0), or behind the hit's own facet, lights nothing. */
static int gro_scene_lit(const gro_scene_t *sc, const gro_hit_t *h, const double *L)
{
    struct RTCRay r;
    struct RTCIntersectContext ctx;
    double o[3];
    int i;
    if (h->kind == GRO_HIT_NONE || L[2] <= 0) return 0;
    if (h->n[0] * L[0] + h->n[1] * L[1] + h->n[2] * L[2] <= 0) return 0;
    for (i = 0; i < 3; i++) o[i] = h->p[i] + sc->eps * h->n[i];
    if (o[2] < 0) { /* the ray must leave through a mouth, not through the ground (a bridge's
                       underside needs no test: the ray would meet the bridge from inside) */
        double tc = -o[2] / L[2];
        if (gro__plane_surface(sc, o[0] + tc * L[0], o[1] + tc * L[1], 0)) return 0;
    }
    gro__ray(&r, sc, o, L, 0, INFINITY);
    rtcInitIntersectContext(&ctx);
    rtcOccluded1(sc->mesh, &ctx, &r);
    return !(r.tfar < 0);
}

/* ------------------------------------------------------------ footprint query */

typedef struct gro_query_t {
    const gro_groove_t *grooves;
    int ngrooves;
    int wrap;                     /* 1: repeating texture, tile size period (0 → 1) */
    double period[2];
    double F[2], A1[2], A2[2];    /* footprint F + a·A1 + c·A2, a, c in [-1, 1] */
    double E[3];                  /* unit, toward the viewer, E_w > 0 */
    const double *lights;         /* nlights unit vectors, 3 doubles each */
    int nlights;
    int n;                        /* n×n rays; 0 → 256 */
    uint64_t seed;
} gro_query_t;

typedef struct gro_result_t {
    int ngrooves;
    long long nsamples;
    double *vis;                  /* [g*GRO_SLOTS + k]: fraction of the footprint where facet k of groove g
                                     is seen (k = GRO_CAP0/GRO_CAP1: its end caps) */
    double *lit;                  /* [(l*ngrooves + g)*GRO_SLOTS + k]: ... seen and lit by light l */
    double *nsum;                 /* [3*(g*GRO_SLOTS + k)]: sum of the unit normals hit on that facet */
    double ground_vis, ground_lit[GRO_MAX_LIGHTS];
    double miss;                  /* rays that hit nothing (should be 0) */
} gro_result_t;

static double gro_vis(const gro_result_t *r, int g, int k) { return r->vis[g * GRO_SLOTS + k]; }
static double gro_lit(const gro_result_t *r, int l, int g, int k)
{
    return r->lit[(l * r->ngrooves + g) * GRO_SLOTS + k];
}
/* Visible fraction of facet k summed over every groove (parallel identical grooves). */
static double gro_vis_all(const gro_result_t *r, int k)
{
    double s = 0;
    int g;
    for (g = 0; g < r->ngrooves; g++) s += gro_vis(r, g, k);
    return s;
}
static double gro_lit_all(const gro_result_t *r, int l, int k)
{
    double s = 0;
    int g;
    for (g = 0; g < r->ngrooves; g++) s += gro_lit(r, l, g, k);
    return s;
}

static void gro_result_free(gro_result_t *r)
{
    free(r->vis); free(r->lit); free(r->nsum);
    memset(r, 0, sizeof *r);
}

static uint64_t gro__rng(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static double gro__unit(uint64_t *s) { return (double)(gro__rng(s) >> 11) * (1.0 / 9007199254740992.0); }

/* Supersamples the footprint against real geometry. Returns 0, or -1. */
static int gro_query(const gro_query_t *q, RTCDevice dev, gro_result_t *res)
{
    gro_scene_t sc;
    gro_build_t b;
    int n = q->n > 0 ? q->n : 256, i, j, l, g, nl = q->nlights < GRO_MAX_LIGHTS ? q->nlights : GRO_MAX_LIGHTS;
    double reach = 0, top = 0, tanE, ext[2], start;
    uint64_t seed = q->seed ^ 0x5DEECE66Dull;
    memset(res, 0, sizeof *res);
    /* How far from the footprint geometry can matter: the widest groove, and
       what E and the light rays pass over or under on their way: protrusions
       (eq. 1) and, since a ray inside a groove can run along it, the depth. */
    for (g = 0; g < q->ngrooves; g++) {
        double bm, wm, tp, smax = 0;
        int k;
        gro__section_extent(&q->grooves[g], &bm, &wm, &tp);
        for (k = 0; k <= 64; k++) smax = fmax(smax, fabs(gro__scale(&q->grooves[g], k / 64.0)));
        reach = fmax(reach, 2 * bm * smax);
        top = fmax(top, fmax(tp, wm) * smax);
    }
    tanE = sqrt(fmax(0, 1 - q->E[2] * q->E[2])) / fmax(q->E[2], 1e-6);
    {
        double tanL = 0;
        for (l = 0; l < nl; l++) {
            const double *L = q->lights + 3 * l;
            if (L[2] > 0) tanL = fmax(tanL, fmin(sqrt(fmax(0, 1 - L[2] * L[2])) / L[2], 1e3));
        }
        reach += top * (fmin(tanE, 1e3) + tanL);
    }
    ext[0] = fabs(q->A1[0]) + fabs(q->A2[0]);
    ext[1] = fabs(q->A1[1]) + fabs(q->A2[1]);
    memset(&b, 0, sizeof b);
    b.wrap = q->wrap;
    b.period[0] = q->period[0]; b.period[1] = q->period[1];
    b.roi[0] = q->F[0] - ext[0] - reach; b.roi[2] = q->F[0] + ext[0] + reach;
    b.roi[1] = q->F[1] - ext[1] - reach; b.roi[3] = q->F[1] + ext[1] + reach;
    b.origin[0] = q->F[0]; b.origin[1] = q->F[1];
    if (gro_scene_build(&sc, dev, q->grooves, q->ngrooves, &b)) { gro_scene_free(&sc); return -1; }
    res->ngrooves = q->ngrooves;
    res->vis = (double *)calloc((size_t)q->ngrooves * GRO_SLOTS + 1, sizeof(double));
    res->lit = (double *)calloc((size_t)(nl > 0 ? nl : 1) * q->ngrooves * GRO_SLOTS + 1, sizeof(double));
    res->nsum = (double *)calloc((size_t)q->ngrooves * GRO_SLOTS * 3 + 1, sizeof(double));
    if (!res->vis || !res->lit || !res->nsum) { gro_scene_free(&sc); gro_result_free(res); return -1; }
    /* rays start above the highest protrusion, at a distance in UV scale */
    start = (sc.top + 1e3 * sc.eps) / fmax(q->E[2], 1e-9); /* just above the highest protrusion */
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            double a = -1 + 2 * (i + gro__unit(&seed)) / n, c = -1 + 2 * (j + gro__unit(&seed)) / n;
            double x[3], o[3], d[3];
            gro_hit_t h;
            int m;
            x[0] = q->F[0] + a * q->A1[0] + c * q->A2[0];
            x[1] = q->F[1] + a * q->A1[1] + c * q->A2[1];
            x[2] = 0;
            for (m = 0; m < 3; m++) { o[m] = x[m] + start * q->E[m]; d[m] = -q->E[m]; }
            h = gro_scene_intersect(&sc, o, d, 0, INFINITY);
            if (h.kind == GRO_HIT_NONE) { res->miss += 1; continue; }
            if (h.kind == GRO_HIT_GROUND) res->ground_vis += 1;
            else {
                double *ns = res->nsum + 3 * (h.groove * GRO_SLOTS + h.facet);
                res->vis[h.groove * GRO_SLOTS + h.facet] += 1;
                ns[0] += h.n[0]; ns[1] += h.n[1]; ns[2] += h.n[2];
            }
            for (l = 0; l < nl; l++) {
                if (!gro_scene_lit(&sc, &h, q->lights + 3 * l)) continue;
                if (h.kind == GRO_HIT_GROUND) res->ground_lit[l] += 1;
                else res->lit[(l * q->ngrooves + h.groove) * GRO_SLOTS + h.facet] += 1;
            }
        }
    res->nsamples = (long long)n * n;
    {
        double inv = 1.0 / (double)res->nsamples;
        size_t k;
        for (k = 0; k < (size_t)q->ngrooves * GRO_SLOTS; k++) res->vis[k] *= inv;
        for (k = 0; k < (size_t)(nl > 0 ? nl : 1) * q->ngrooves * GRO_SLOTS; k++) res->lit[k] *= inv;
        res->ground_vis *= inv;
        for (l = 0; l < nl; l++) res->ground_lit[l] *= inv;
        res->miss *= inv;
    }
    gro_scene_free(&sc);
    return 0;
}

/* ------------------------------------------------------------ from grooves.h */
#ifdef FILIGREE_GR_H
/* The same groove as grooves.h describes it (reads the public description
   only). The arrays stay the caller's. */
static gro_groove_t gro_from_gr(const gr_groove_desc_t *d)
{
    gro_groove_t g;
    memset(&g, 0, sizeof g);
    g.kind = d->kind == GR_PATH_QUADRATIC ? GRO_QUADRATIC : d->kind == GR_PATH_CUBIC ? GRO_CUBIC : GRO_POLYLINE;
    g.nctrl = d->point_count; g.ctrl = d->points;
    g.nsec = d->section_count; g.sec = d->section;
    g.scale = d->perturb; g.scale_ctx = d->perturb_user;
    return g;
}
#endif

#endif /* FILIGREE_GROOVES_ORACLE_H */
