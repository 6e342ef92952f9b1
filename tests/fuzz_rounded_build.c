/* libFuzzer target for rounded_edges.h's builder and queries (make fuzz; a
   short run in make test). The input is read as a base solid and a list of
   edits, so most inputs are nearly valid meshes that reach the deep steps
   (erosion, chains, bands, kd-tree) and the rest are the bad input of
   issue 6 (NaN and huge coordinates, out-of-range and repeated indices,
   flipped and duplicated triangles, open and non-manifold edges):
     byte 0  flags: layout, bad-input policy, radius policy, float positions,
             per-edge radii; base solid (box, icosahedron, prism, pyramid)
     byte 1  radius 2^(b % 32 - 24)
     then    edits of three bytes each (op, a, b), at most RFZ_MAX_EDITS (op
             253 and 254 add a copy touching the mesh along an edge or at
             a vertex, sharing them: rfz_touch); op
             255 ends them, its a: bit 0 hands the mesh over as polygons
             (each pair of triangles (a, b, c), (a, c, d) as the quad
             (a, b, c, d): the same fan triangles), bit 1 builds it as two
             objects (and again in two tasks, which must agree), bit 2 sets re_mesh_t.flat_sin to RE_FLAT_SIN_LIMIT
             2^-(a >> 4), bit 3 gives every triangle corner its own vertex
             and builds with re_mesh_t.weld
     then    queries of six bytes each, at most RFZ_MAX_QUERIES (a first
             byte of 254: a junk query, ids and t out of range, NaN or
             infinite directions)
   Every input must build or fail with a result code and a message, never
   crash or read out of bounds (ASan, UBSan). A built scene must enumerate
   its features, agree with re_build_sizes() + re_build_into(), and answer
   every front-face host hit with a valid kind; a rounded hit or
   pass-through lies no earlier than the host's t (up to the float-host
   slack) and a rounded hit has a unit normal and lies on the feature it
   names (rc_feature_ok, 1e-9 of the coordinates' magnitude). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
/* the build's steps split on threads from the smallest mesh on (THREADS;
   rfz_check_tasks) */
#define RE__SPAN_MIN_SLOTS 1u
#define RE__SPAN_MIN_CORNERS 1u
#define RE__KD_SPLIT_MIN 1u
/* filled blocks: the split build (rfz_check_tasks) gets other bytes than
   the first one, and its blocks must still be the same, alignment padding
   included */
#include "test_fill_alloc.h"
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_checks.h"

/* A failed check: abort for libFuzzer; tests/test_rounded_fuzz_replay.c
   counts it instead (every use is followed by a return or is safe to go
   on from). */
#ifndef RFZ_WHY
#define RFZ_WHY(w) (void)(w) /* the failed check's words (a replay can print them) */
#endif
#ifndef RFZ_FAIL
#define RFZ_FAIL() abort()
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define RFZ_MAX_V 256
#define RFZ_MAX_T 512
#define RFZ_MAX_VU (RFZ_MAX_V + 3 * RFZ_MAX_T) /* room for rfz_unweld's copies */
#define RFZ_MAX_EDITS 48
#define RFZ_MAX_QUERIES 24

typedef struct rfz_in_t { const uint8_t *p; size_t n, at; } rfz_in_t;
static unsigned rfz_byte(rfz_in_t *in) { return in->at < in->n ? in->p[in->at++] : 0u; }

typedef struct rfz_mesh_t {
    double v[3 * RFZ_MAX_VU];
    unsigned idx[3 * RFZ_MAX_T];
    unsigned nv, nt;
} rfz_mesh_t;

static unsigned rfz_vert(rfz_mesh_t *m, double x, double y, double z)
{
    if (m->nv == RFZ_MAX_V) return 0;
    m->v[3 * m->nv] = x, m->v[3 * m->nv + 1] = y, m->v[3 * m->nv + 2] = z;
    return m->nv++;
}
static void rfz_tri(rfz_mesh_t *m, unsigned a, unsigned b, unsigned c)
{
    if (m->nt == RFZ_MAX_T) return;
    m->idx[3 * m->nt] = a, m->idx[3 * m->nt + 1] = b, m->idx[3 * m->nt + 2] = c;
    m->nt++;
}

/* Closed convex bases, counter-clockwise from outside. */
static void rfz_base(rfz_mesh_t *m, unsigned kind, unsigned sides)
{
    unsigned i;
    if (kind == 0) { /* box */
        static const unsigned q[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
        for (i = 0; i < 8; i++) rfz_vert(m, i & 1 ? 1.0 : -1.0, i & 2 ? 0.6 : -0.6, i & 4 ? 0.4 : -0.4);
        for (i = 0; i < 6; i++) rfz_tri(m, q[i][0], q[i][1], q[i][2]), rfz_tri(m, q[i][0], q[i][2], q[i][3]);
    } else if (kind == 1) { /* icosahedron, stretched so its corners are exact */
        static const unsigned f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                          {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                          {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
        const double g = 1.6180339887498949;
        static const double s[12][3] = {{-1, 1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, -1, 0}, {0, -1, 1}, {0, 1, 1},
                                        {0, -1, -1}, {0, 1, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, -1}, {-1, 0, 1}};
        for (i = 0; i < 12; i++) {
            double x = s[i][0] * (i < 4 ? 1 : i < 8 ? 0 : g), y = s[i][1] * (i < 4 ? g : i < 8 ? 1 : 0), z = s[i][2] * (i < 4 ? 0 : i < 8 ? g : 1);
            rfz_vert(m, x, 0.8 * y, 1.25 * z);
        }
        for (i = 0; i < 20; i++) rfz_tri(m, f[i][0], f[i][1], f[i][2]);
    } else { /* prism (kind 2) or pyramid (kind 3) over a regular n-gon */
        unsigned n = 3 + sides % 30, top, bot;
        for (i = 0; i < n; i++) {
            double a = 6.283185307179586 * i / n;
            rfz_vert(m, cos(a), sin(a), -0.5);
            if (kind == 2) rfz_vert(m, cos(a), sin(a), 0.5);
        }
        if (kind == 2) {
            for (i = 0; i < n; i++) {
                unsigned j = (i + 1) % n;
                rfz_tri(m, 2 * i, 2 * j, 2 * j + 1), rfz_tri(m, 2 * i, 2 * j + 1, 2 * i + 1);
            }
            for (i = 1; i + 1 < n; i++) rfz_tri(m, 0, 2 * (i + 1), 2 * i), rfz_tri(m, 1, 2 * i + 1, 2 * (i + 1) + 1);
        } else {
            top = rfz_vert(m, 0.2, -0.1, 0.9); /* off-centre apex: its offset planes miss one point */
            for (i = 0; i < n; i++) rfz_tri(m, i, (i + 1) % n, top);
            bot = 0;
            for (i = 1; i + 1 < n; i++) rfz_tri(m, bot, i + 1, i);
        }
    }
}

static const double rfz_special[8] = {NAN, INFINITY, -INFINITY, 1e300, -0.0, 4.9e-324, 1e6, 1e-12};

/* A copy of the mesh so far touching it (construction step 2a): turned
   half a turn about the line through vertices p and q (an edge: a convex
   solid's copy touches it along that edge), or mirrored through p when
   q == p (a corner: they touch at p, and the mirror flips the winding).
   Vertices the map leaves in place are shared, as a welded mesh would. */
static void rfz_touch(rfz_mesh_t *m, unsigned p, unsigned q)
{
    unsigned i, k, nv = m->nv, nt = m->nt, map[RFZ_MAX_V];
    const double *P = m->v + 3 * p, *Q = m->v + 3 * q;
    double e[3], ee = 0;
    if (nv > RFZ_MAX_V / 2 || nt > RFZ_MAX_T / 2) return;
    for (k = 0; k < 3; k++) e[k] = Q[k] - P[k], ee += e[k] * e[k];
    for (i = 0; i < nv; i++) {
        const double *x = m->v + 3 * i;
        double y[3], s = 0;
        for (k = 0; k < 3; k++) s += (x[k] - P[k]) * e[k];
        s = ee > 0 ? s / ee : 0;
        for (k = 0; k < 3; k++) y[k] = 2 * (P[k] + s * e[k]) - x[k];
        map[i] = y[0] == x[0] && y[1] == x[1] && y[2] == x[2] ? i : rfz_vert(m, y[0], y[1], y[2]);
    }
    for (i = 0; i < nt; i++) {
        unsigned a = m->idx[3 * i], b = m->idx[3 * i + 1], c = m->idx[3 * i + 2];
        a = a < nv ? map[a] : a, b = b < nv ? map[b] : b, c = c < nv ? map[c] : c;
        if (q == p) rfz_tri(m, a, c, b);
        else rfz_tri(m, a, b, c);
    }
}

static void rfz_edit(rfz_mesh_t *m, unsigned op, unsigned a, unsigned b)
{
    unsigned i;
    if (!m->nv || !m->nt) return;
    if (op >= 253) { /* 253: touching along edge b % 3 of triangle a; 254: at vertex a */
        unsigned t = a % m->nt, p = op == 254 ? a % m->nv : m->idx[3 * t + b % 3], q = op == 254 ? p : m->idx[3 * t + (b + 1) % 3];
        if (p < m->nv && q < m->nv) rfz_touch(m, p, q);
        return;
    }
    switch (op % 9) {
    case 0: /* nudge a vertex coordinate (non-planar faces, near-degenerate ones) */
        m->v[3 * (a % m->nv) + b % 3] += ((double)(b >> 2) - 32.0) * (b & 128 ? 1e-9 : 1.0 / 64);
        break;
    case 1: /* a special coordinate */
        m->v[3 * (a % m->nv) + b % 3] = rfz_special[(b >> 2) % 8];
        break;
    case 2: { /* flip a triangle */
        unsigned t = a % m->nt, s = m->idx[3 * t + 1];
        m->idx[3 * t + 1] = m->idx[3 * t + 2], m->idx[3 * t + 2] = s;
        break;
    }
    case 3: /* an index replaced, sometimes out of range */
        m->idx[3 * (a % m->nt) + b % 3] = (b >> 2) % (m->nv + 2);
        break;
    case 4: /* a triangle repeated (non-manifold edges) */
        rfz_tri(m, m->idx[3 * (a % m->nt)], m->idx[3 * (a % m->nt) + 1], m->idx[3 * (a % m->nt) + 2]);
        break;
    case 5: { /* a triangle removed (open mesh) */
        unsigned t = a % m->nt;
        m->nt--;
        for (i = 0; i < 3; i++) m->idx[3 * t + i] = m->idx[3 * m->nt + i];
        break;
    }
    case 6: { /* a triangle split at a point raised above it (higher vertex degrees, small dihedrals) */
        unsigned t = a % m->nt, p0 = m->idx[3 * t], p1 = m->idx[3 * t + 1], p2 = m->idx[3 * t + 2], c, k;
        double q[3], e1[3], e2[3], n[3], h = (double)(b % 16) / 64.0;
        if (p0 >= m->nv || p1 >= m->nv || p2 >= m->nv || m->nt + 2 > RFZ_MAX_T) break;
        for (k = 0; k < 3; k++) {
            q[k] = (m->v[3 * p0 + k] + m->v[3 * p1 + k] + m->v[3 * p2 + k]) / 3;
            e1[k] = m->v[3 * p1 + k] - m->v[3 * p0 + k], e2[k] = m->v[3 * p2 + k] - m->v[3 * p0 + k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        c = rfz_vert(m, q[0] + h * n[0], q[1] + h * n[1], q[2] + h * n[2]);
        m->idx[3 * t + 2] = c;
        rfz_tri(m, p1, p2, c), rfz_tri(m, p2, p0, c);
        break;
    }
    case 7: /* the whole object moved far from the origin */
        for (i = 0; i < 3 * m->nv; i++) m->v[i] += (double)(a % 8) * 1e5 * (b & 1 ? -1 : 1);
        break;
    default: { /* a straight edge split in two at its midpoint (a chain vertex) */
        unsigned t = a % m->nt, k = b % 3, p = m->idx[3 * t + k], q = m->idx[3 * t + (k + 1) % 3], o, mid, j;
        if (p >= m->nv || q >= m->nv || m->nt + 2 > RFZ_MAX_T) break;
        mid = rfz_vert(m, (m->v[3 * p] + m->v[3 * q]) / 2, (m->v[3 * p + 1] + m->v[3 * q + 1]) / 2,
                       (m->v[3 * p + 2] + m->v[3 * q + 2]) / 2);
        /* both triangles on the edge (p, q) are split at mid */
        for (j = 0; j < m->nt; j++)
            for (o = 0; o < 3; o++) {
                unsigned x = m->idx[3 * j + o], y = m->idx[3 * j + (o + 1) % 3], z = m->idx[3 * j + (o + 2) % 3];
                if ((x == p && y == q) || (x == q && y == p)) {
                    m->idx[3 * j + (o + 1) % 3] = mid;
                    rfz_tri(m, mid, y, z);
                    break;
                }
            }
        break;
    }
    }
}

/* The same face left from inside: the ray -d from dist behind P. The exit
   query's answer is a valid kind, the same with u, v, and a leaving point
   between the origin and the face (or the face itself). */
static void rfz_exit_query(const re_scene_t *s, const double P[3], const double d[3], unsigned obj, unsigned t, double dist,
                           double u, double v, unsigned ns, unsigned nc)
{
    double o[3], back[3];
    re_hit_t h, h2;
    re_hit_kind_t kind;
    unsigned k;
    for (k = 0; k < 3; k++) o[k] = P[k] + dist * d[k], back[k] = -d[k];
    kind = re_query_exit(s, o, back, obj, t, dist, &h);
    re_query_exit_uv(s, o, back, obj, t, dist, u, v, &h2);
    if (kind != RE_UNCHANGED && kind != RE_HIT_ROUNDED && kind != RE_PASS_THROUGH) RFZ_FAIL();
    if (h2.kind != kind || h.kind != kind || h2.t != h.t) RFZ_FAIL();
    if (kind == RE_PASS_THROUGH && h.t != dist) RFZ_FAIL();
    if (kind == RE_HIT_ROUNDED) {
        double len = sqrt(h.normal[0] * h.normal[0] + h.normal[1] * h.normal[1] + h.normal[2] * h.normal[2]);
        if (!(h.t >= 0 && h.t <= dist * (1 + 1e-5))) RFZ_FAIL();
        if (!(fabs(len - 1) < 1e-6)) RFZ_FAIL();
        if (h.feature_index >= (h.feature == RE_FEATURE_SPHERE ? ns : nc)) RFZ_FAIL();
    }
}

static void rfz_check_scene(const re_scene_t *s, const rfz_mesh_t *m, rfz_in_t *in)
{
    unsigned i, q, obj, ns = re_sphere_count(s, 0), nc = re_cylinder_count(s, 0);
    for (i = 0; i < ns; i++) {
        re_sphere_t sp;
        if (!re_get_sphere(s, 0, i, &sp) || !(sp.radius > 0)) RFZ_FAIL();
    }
    for (i = 0; i < nc; i++) {
        re_cylinder_t cy;
        if (!re_get_cylinder(s, 0, i, &cy) || cy.sa >= ns || cy.sb >= ns) RFZ_FAIL();
    }
    if (re_get_sphere(s, 0, ns, NULL) || re_get_cylinder(s, 0, nc, NULL)) RFZ_FAIL();
    for (q = 0; q < RFZ_MAX_QUERIES && in->at + 6 <= in->n; q++) {
        unsigned traw = rfz_byte(in), t = traw % (m->nt ? m->nt : 1), k;
        double u = rfz_byte(in) / 255.0, v = rfz_byte(in) / 255.0, d[3], o[3], P[3], e1[3], e2[3], n[3], th, ph, dist, dn;
        const double *a, *b, *c;
        re_hit_t h, h2;
        re_hit_kind_t kind;
        th = rfz_byte(in) * (3.141592653589793 / 255), ph = rfz_byte(in) * (6.283185307179586 / 255);
        dist = 0.01 + rfz_byte(in) / 16.0;
        if (traw == 254) {
            /* junk: any object and triangle id, a t and a direction that
               are not finite or not positive; a valid kind, no crash */
            static const double tj[4] = {NAN, -1.0, INFINITY, 0.0}, dj[4] = {0.0, NAN, 1e300, -INFINITY};
            unsigned obj = (unsigned)(u * 255) % 3, tri = (unsigned)(v * 255) + m->nt - 128;
            double jo[3] = {0.0, 0.0, 0.0}, jd[3];
            jd[0] = dj[(unsigned)(th * 4) % 4], jd[1] = 1.0, jd[2] = dj[(unsigned)(ph * 4) % 4];
            kind = re_query(s, jo, jd, obj, tri, tj[(unsigned)dist % 4], &h);
            if (kind != RE_UNCHANGED && kind != RE_HIT_ROUNDED && kind != RE_PASS_THROUGH) RFZ_FAIL();
            kind = re_query_uv(s, jo, jd, obj, tri, tj[(unsigned)dist % 4], u, v, &h);
            if (kind != RE_UNCHANGED && kind != RE_HIT_ROUNDED && kind != RE_PASS_THROUGH) RFZ_FAIL();
            kind = re_query_exit_uv(s, jo, jd, obj, tri, tj[(unsigned)dist % 4], u, v, &h);
            if (kind != RE_UNCHANGED && kind != RE_HIT_ROUNDED && kind != RE_PASS_THROUGH) RFZ_FAIL();
            continue;
        }
        if (!m->nt || m->idx[3 * t] >= m->nv || m->idx[3 * t + 1] >= m->nv || m->idx[3 * t + 2] >= m->nv) continue;
        if (u + v > 1) u = 1 - u, v = 1 - v;
        a = m->v + 3 * m->idx[3 * t], b = m->v + 3 * m->idx[3 * t + 1], c = m->v + 3 * m->idx[3 * t + 2];
        for (k = 0; k < 3; k++) P[k] = (1 - u - v) * a[k] + u * b[k] + v * c[k], e1[k] = b[k] - a[k], e2[k] = c[k] - a[k];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        d[0] = sin(th) * cos(ph), d[1] = sin(th) * sin(ph), d[2] = cos(th);
        dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        if (!(dn == dn)) continue;
        if (dn > 0) d[0] = -d[0], d[1] = -d[1], d[2] = -d[2]; /* a front-face hit */
        for (k = 0; k < 3; k++) o[k] = P[k] - dist * d[k];
        obj = re_object_count(s) > 1 ? q & 1u : 0u;
        kind = re_query(s, o, d, obj, t, dist, &h);
        re_query_uv(s, o, d, obj, t, dist, u, v, &h2);
        if (kind != RE_UNCHANGED && kind != RE_HIT_ROUNDED && kind != RE_PASS_THROUGH) RFZ_FAIL();
        if (h2.kind != kind || h.kind != kind) RFZ_FAIL();
        rfz_exit_query(s, P, d, obj, t, dist, u, v, ns, nc);
        if (kind == RE_UNCHANGED) continue;
        if (!isfinite(h.t) || h.t < dist - 1e-5 * dist - 1e-300) RFZ_FAIL();
        if (kind == RE_HIT_ROUNDED) {
            double len = sqrt(h.normal[0] * h.normal[0] + h.normal[1] * h.normal[1] + h.normal[2] * h.normal[2]), org[3],
                   mag = fabs(o[0]) + fabs(o[1]) + fabs(o[2]) + h.t;
            char why[256];
            if (!(fabs(len - 1) < 1e-6)) RFZ_FAIL();
            if (h.feature_index >= (h.feature == RE_FEATURE_SPHERE ? ns : nc)) RFZ_FAIL();
            /* on the feature it names, whatever the mesh (rc_feature_ok), or
               an entry before the host's t clamped to the earliest one
               accepted: inside its feature by at most the slack's length
               (docs: "Float hosts"). Capsules stand out of a mesh whose
               noise exceeds r (float positions, r = 2^-25 of the size: a
               chain's middle vertex 1.5e-8 inside a cylinder of r 3e-8),
               and a host hit there is a late one (seed
               clamped_entry_where_a_capsule_stands_out) */
            if (!rc_feature_ok(s, &h, 1e-9 * mag, mag, why, sizeof why) &&
                !(h.t < dist && rc_feature_ok(s, &h, 1e-9 * mag + RE__HOST_T_SLACK * dist * sqrt(tm_dot(d, d)), mag, why, sizeof why))) {
                RFZ_WHY(why);
                RFZ_FAIL();
            }
            re_secondary_origin(s, &h, d, org);
        }
    }
}

/* The input read as a mesh and a build description (see the top); the
   queries' bytes stay in *in. vf and radii are the caller's buffers. */
typedef struct rfz_case_t {
    rfz_mesh_t m;
    float vf[3 * RFZ_MAX_VU];
    double radii[3 * RFZ_MAX_T];
    unsigned poly[3 * RFZ_MAX_T], sizes[RFZ_MAX_T];
    re_mesh_t mesh[2];
    re_scene_desc_t desc;
} rfz_case_t;

/* The triangles as polygons: (a, b, c), (a, c, d) becomes (a, b, c, d),
   whose fan split gives the same two triangles in the same order. */
/* Every triangle corner its own copy of its vertex, as a renderer's
   per-face vertices (normals, UVs) are; re_mesh_t.weld joins them again.
   Out-of-range indices stay as they are. */
static void rfz_unweld(rfz_mesh_t *m)
{
    unsigned i, n = m->nv, a;
    for (i = 0; i < 3 * m->nt; i++)
        if (m->idx[i] < n) {
            for (a = 0; a < 3; a++) m->v[3 * m->nv + a] = m->v[3 * m->idx[i] + a];
            m->idx[i] = m->nv++;
        }
}

static void rfz_polygons(rfz_case_t *k)
{
    const unsigned *x = k->m.idx;
    unsigned t = 0, n = 0, f = 0, j;
    while (t < k->m.nt) {
        unsigned q = t + 1 < k->m.nt && x[3 * t + 3] == x[3 * t] && x[3 * t + 4] == x[3 * t + 2] ? 4u : 3u;
        for (j = 0; j < 3; j++) k->poly[n++] = x[3 * t + j];
        if (q == 4) k->poly[n++] = x[3 * t + 5];
        k->sizes[f++] = q;
        t += q - 2;
    }
    k->mesh[0].indices = k->poly;
    k->mesh[0].index_count = n;
    k->mesh[0].face_sizes = k->sizes;
    k->mesh[0].face_count = f;
}

static void rfz_decode(const uint8_t *data, size_t size, rfz_case_t *k, rfz_in_t *in)
{
    unsigned flags, e, i, ext = 0;
    rfz_mesh_t *m = &k->m;
    re_mesh_t *mesh = &k->mesh[0];
    in->p = data, in->n = size, in->at = 0;
    memset(k, 0, sizeof *k);
    flags = rfz_byte(in);
    rfz_base(m, flags >> 6, flags);
    mesh->radius = ldexp(1.0, (int)(rfz_byte(in) % 32) - 24);
    for (e = 0; e < RFZ_MAX_EDITS && in->at + 3 <= in->n; e++) {
        unsigned op = rfz_byte(in), a = rfz_byte(in), b = rfz_byte(in);
        if (op == 255) { /* the queries start */
            ext = a;
            break;
        }
        rfz_edit(m, op, a, b);
    }
    if (ext & 8) rfz_unweld(m), mesh->weld = 1;
    if (flags & 8) {
        /* the queries' host hits come from m->v: the same (float) vertices */
        for (i = 0; i < 3 * m->nv; i++) k->vf[i] = (float)m->v[i], m->v[i] = (double)k->vf[i];
        mesh->positions = k->vf, mesh->position_type = RE_FLOAT32;
    } else
        mesh->positions = m->v;
    mesh->vertex_count = m->nv;
    mesh->indices = m->idx;
    mesh->index_count = 3 * m->nt;
    if (flags & 16) {
        for (i = 0; i < 3 * m->nt; i++) k->radii[i] = i % 5 == 0 ? mesh->radius * 0.5 : i % 7 == 0 ? -1.0 : mesh->radius;
        mesh->edge_radius = k->radii;
    }
    if (ext & 4) mesh->flat_sin = ldexp(RE_FLAT_SIN_LIMIT, -(int)(ext >> 4));
    if (ext & 1) rfz_polygons(k);
    k->mesh[1] = k->mesh[0];
    k->desc.objects = k->mesh;
    k->desc.object_count = ext & 2 ? 2u : 1u;
    k->desc.layout = flags & 1 ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
    k->desc.bad_input = flags & 2 ? RE_BAD_INPUT_SKIP : RE_BAD_INPUT_REJECT;
    k->desc.radius_policy = flags & 4 ? RE_RADIUS_REJECT : RE_RADIUS_CLAMP;
}

/* A host's parallel-for that runs the tasks on this thread, last first. */
static void rfz_reversed(void *user, unsigned count, re_task_fn task, void *task_ctx)
{
    (void)user;
    while (count-- > 0) task(task_ctx, count);
}

/* Two objects built in two tasks, or one object whose steps are split
   into three (both run last first), give the one-thread build's result,
   diagnostic, counts and bytes (in memory filled with other bytes). */
static void rfz_check_tasks(const rfz_case_t *k, re_result_t rc, const re_diag_t *dg, const re_scene_t *s)
{
    re_scene_desc_t d = k->desc;
    re_scene_t *p = NULL;
    re_diag_t dp;
    re_result_t rc2;
    d.parallel = rfz_reversed, d.threads = d.object_count > 1 ? 2u : 3u;
    test_fill_byte = 0xFF;
    rc2 = re_build(&d, &p, &dp);
    test_fill_byte = 0xA5;
    if (rc2 != rc) RFZ_FAIL();
    else if (rc != RE_OK) {
        if (dp.result != dg->result || dp.object != dg->object || dp.element != dg->element || strcmp(dp.message, dg->message)) RFZ_FAIL();
    } else if (p && s) {
        re_stats_t a, b;
        unsigned o;
        re_get_stats(s, &a);
        re_get_stats(p, &b);
        if (memcmp(&a, &b, sizeof a)) RFZ_FAIL();
        for (o = 0; o < s->n_objects; o++)
            if (s->objects[o].bytes != p->objects[o].bytes ||
                (s->objects[o].bytes && memcmp(s->objects[o].block, p->objects[o].block, s->objects[o].bytes)))
                RFZ_FAIL();
    }
    re_free(p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static rfz_case_t k;
    rfz_in_t in;
    re_scene_t *s = NULL, *s2 = NULL;
    re_diag_t dg;
    re_sizes_t sz;
    re_result_t rc;
    void *mem, *scratch;
    rfz_decode(data, size, &k, &in);
    rc = re_build(&k.desc, &s, &dg);
    rfz_check_tasks(&k, rc, &dg, s);
    if (rc != RE_OK) {
        /* a failed build names what failed */
        if (s || dg.result != rc || !dg.message[0] || !re_result_string(rc)) RFZ_FAIL();
        return 0;
    }
    /* the size query and caller buffers give the same scene */
    if (re_build_sizes(&k.desc, &sz, &dg) != RE_OK) {
        RFZ_FAIL();
        re_free(s);
        return 0;
    }
    mem = malloc(sz.scene_bytes), scratch = malloc(sz.scratch_bytes ? sz.scratch_bytes : 1);
    if (mem && scratch && re_build_into(&k.desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s2, &dg) == RE_OK) {
        re_stats_t a, b;
        re_get_stats(s, &a);
        re_get_stats(s2, &b);
        if (a.bytes != b.bytes || a.bytes != sz.scene_bytes || a.spheres != b.spheres || a.cylinders != b.cylinders)
            RFZ_FAIL();
    } else
        RFZ_FAIL();
    free(scratch);
    free(mem);
    rfz_check_scene(s, &k.m, &in);
    re_free(s);
    return 0;
}
