/* ex_mesh.c — see ex_mesh.h */
#include "ex_mesh.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern char *program_invocation_short_name; /* glibc */

void ex_mesh_free(ex_mesh_t *m)
{
    free(m->pos);
    free(m->idx);
    memset(m, 0, sizeof *m);
}

static int ex__mesh_alloc(ex_mesh_t *m, size_t nverts, size_t ntris)
{
    memset(m, 0, sizeof *m);
    m->pos = (float *)malloc(3 * sizeof(float) * (nverts ? nverts : 1));
    m->idx = (uint32_t *)malloc(3 * sizeof(uint32_t) * (ntris ? ntris : 1));
    if (!m->pos || !m->idx) { ex_mesh_free(m); return -1; }
    m->nverts = nverts;
    m->ntris = ntris;
    return 0;
}

static ex_v3_t ex__mesh_vertex(const ex_mesh_t *m, uint32_t i)
{
    return ex_v3(m->pos[3 * i], m->pos[3 * i + 1], m->pos[3 * i + 2]);
}

static void ex__mesh_set_vertex(ex_mesh_t *m, size_t i, ex_v3_t p)
{
    m->pos[3 * i] = (float)p.x; m->pos[3 * i + 1] = (float)p.y; m->pos[3 * i + 2] = (float)p.z;
}

/* Stores triangle t as (a, b, c), swapping b and c if its right-hand normal
   points against `outward`. */
static void ex__mesh_set_tri(ex_mesh_t *m, size_t t, uint32_t a, uint32_t b, uint32_t c, ex_v3_t outward)
{
    ex_v3_t pa = ex__mesh_vertex(m, a), pb = ex__mesh_vertex(m, b), pc = ex__mesh_vertex(m, c);
    ex_v3_t n = ex_cross(ex_sub(pb, pa), ex_sub(pc, pa));
    if (ex_dot(n, outward) < 0) { uint32_t s = b; b = c; c = s; }
    m->idx[3 * t] = a; m->idx[3 * t + 1] = b; m->idx[3 * t + 2] = c;
}

int ex_mesh_cube(ex_mesh_t *m)
{
    /* vertex i has coordinate bits (x, y, z) = (i&1, i&2, i&4) */
    static const uint32_t quads[6][4] = {
        {0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    static const double dirs[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    size_t i;
    if (ex__mesh_alloc(m, 8, 12)) return -1;
    for (i = 0; i < 8; i++)
        ex__mesh_set_vertex(m, i, ex_v3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    for (i = 0; i < 6; i++) {
        ex_v3_t out = ex_v3(dirs[i][0], dirs[i][1], dirs[i][2]);
        ex__mesh_set_tri(m, 2 * i, quads[i][0], quads[i][1], quads[i][2], out);
        ex__mesh_set_tri(m, 2 * i + 1, quads[i][0], quads[i][2], quads[i][3], out);
    }
    return 0;
}

int ex_mesh_ground(ex_mesh_t *m, double h)
{
    if (!(h > 0)) return -1;
    if (ex__mesh_alloc(m, 4, 2)) return -1;
    ex__mesh_set_vertex(m, 0, ex_v3(-h, 0, -h));
    ex__mesh_set_vertex(m, 1, ex_v3(h, 0, -h));
    ex__mesh_set_vertex(m, 2, ex_v3(h, 0, h));
    ex__mesh_set_vertex(m, 3, ex_v3(-h, 0, h));
    ex__mesh_set_tri(m, 0, 0, 1, 2, ex_v3(0, 1, 0));
    ex__mesh_set_tri(m, 1, 0, 2, 3, ex_v3(0, 1, 0));
    return 0;
}

/* ---------------------------------------------------------------- welding */

/* Open-addressing map from a key (three 32-bit words) to a vertex index. */
typedef struct ex__mesh_map_t {
    uint32_t *keys;   /* 3 per slot */
    uint32_t *vals;   /* UINT32_MAX = empty */
    size_t cap;       /* power of two */
} ex__mesh_map_t;

static int ex__mesh_map_init(ex__mesh_map_t *h, size_t n)
{
    size_t cap = 16;
    while (cap < 2 * n + 16) cap *= 2;
    h->keys = (uint32_t *)malloc(3 * sizeof(uint32_t) * cap);
    h->vals = (uint32_t *)malloc(sizeof(uint32_t) * cap);
    h->cap = cap;
    if (!h->keys || !h->vals) { free(h->keys); free(h->vals); return -1; }
    memset(h->vals, 0xff, sizeof(uint32_t) * cap);
    return 0;
}

static void ex__mesh_map_free(ex__mesh_map_t *h) { free(h->keys); free(h->vals); }

/* The value stored under k, or inserts `v` and returns it. */
static uint32_t ex__mesh_map_get_or_put(ex__mesh_map_t *h, const uint32_t k[3], uint32_t v)
{
    uint64_t z = ((uint64_t)k[0] * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)k[1] * 0xC2B2AE3D27D4EB4Full) ^
                 ((uint64_t)k[2] * 0x165667B19E3779F9ull);
    size_t i = (size_t)(z ^ (z >> 29)) & (h->cap - 1);
    for (;; i = (i + 1) & (h->cap - 1)) {
        uint32_t *s = h->keys + 3 * i;
        if (h->vals[i] == UINT32_MAX) {
            s[0] = k[0]; s[1] = k[1]; s[2] = k[2];
            h->vals[i] = v;
            return v;
        }
        if (s[0] == k[0] && s[1] == k[1] && s[2] == k[2]) return h->vals[i];
    }
}

/* Merges vertices with bit-identical positions; drops the unused ones. */
static int ex__mesh_weld(ex_mesh_t *m)
{
    ex__mesh_map_t h;
    uint32_t *remap = (uint32_t *)malloc(sizeof(uint32_t) * (m->nverts ? m->nverts : 1));
    size_t i, n = 0;
    if (!remap || ex__mesh_map_init(&h, m->nverts)) { free(remap); return -1; }
    for (i = 0; i < m->nverts; i++) {
        uint32_t k[3];
        memcpy(k, m->pos + 3 * i, sizeof k);
        remap[i] = ex__mesh_map_get_or_put(&h, k, (uint32_t)n);
        if (remap[i] == n) { memmove(m->pos + 3 * n, m->pos + 3 * i, 3 * sizeof(float)); n++; }
    }
    for (i = 0; i < 3 * m->ntris; i++) m->idx[i] = remap[m->idx[i]];
    m->nverts = n;
    ex__mesh_map_free(&h);
    free(remap);
    return 0;
}

/* ---------------------------------------------------------------- rounded cube */

/* Maps a point q of the cube [-1,1]^3 surface onto the rounded cube. */
static ex_v3_t ex__mesh_round(ex_v3_t q, double r)
{
    double c = 1 - r;
    ex_v3_t in = ex_v3(ex_clamp(q.x, -c, c), ex_clamp(q.y, -c, c), ex_clamp(q.z, -c, c));
    return ex_madd(in, ex_normalize(ex_sub(q, in)), r);
}

int ex_mesh_rounded_cube(ex_mesh_t *m, double radius, int segments)
{
    double coord[2 * 64 + 2];
    int nc = 0, k, face, i, j;
    size_t v = 0, t = 0;
    if (!(radius > 0 && radius <= 1) || segments < 1 || segments > 64) return -1;
    /* band offsets spaced so that the arc angles are uniform */
    for (k = 0; k <= segments; k++) coord[nc++] = -1 + radius - radius * tan(EX_PI / 4 * (segments - k) / segments);
    for (k = radius < 1 ? 0 : 1; k <= segments; k++) coord[nc++] = 1 - radius + radius * tan(EX_PI / 4 * k / segments);
    coord[0] = -1; coord[nc - 1] = 1;
    if (ex__mesh_alloc(m, (size_t)(6 * nc * nc), (size_t)(6 * 2 * (nc - 1) * (nc - 1)))) return -1;
    for (face = 0; face < 6; face++) {
        int axis = face / 2;
        double side = face & 1 ? 1.0 : -1.0;
        size_t base = v;
        ex_v3_t out = ex_v3(axis == 0 ? side : 0, axis == 1 ? side : 0, axis == 2 ? side : 0);
        for (i = 0; i < nc; i++)
            for (j = 0; j < nc; j++) {
                double q[3];
                q[axis] = side;
                q[(axis + 1) % 3] = coord[i];
                q[(axis + 2) % 3] = coord[j];
                ex__mesh_set_vertex(m, v++, ex__mesh_round(ex_v3(q[0], q[1], q[2]), radius));
            }
        for (i = 0; i + 1 < nc; i++)
            for (j = 0; j + 1 < nc; j++) {
                uint32_t a = (uint32_t)(base + (size_t)(i * nc + j)), b = a + 1;
                uint32_t c = a + (uint32_t)nc, d = c + 1;
                /* orientation from the quad's centre direction: the body is convex */
                ex_v3_t mid = ex_scale(ex_add(ex__mesh_vertex(m, a), ex__mesh_vertex(m, d)), 0.5);
                ex__mesh_set_tri(m, t++, a, c, d, ex_dot(mid, out) > 0 ? mid : out);
                ex__mesh_set_tri(m, t++, a, d, b, ex_dot(mid, out) > 0 ? mid : out);
            }
    }
    return ex__mesh_weld(m);
}

/* ---------------------------------------------------------------- icosphere */

int ex_mesh_icosphere(ex_mesh_t *m, int level)
{
    static const uint32_t faces[20][3] = {
        {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
        {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    const double g = (1 + sqrt(5.0)) / 2;
    const double base[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    size_t nv_final, nt_final, nv, nt, i;
    int l;
    if (level < 0 || level > 8) return -1;
    nv_final = 10 * ((size_t)1 << (2 * level)) + 2;
    nt_final = 20 * ((size_t)1 << (2 * level));
    if (ex__mesh_alloc(m, nv_final, nt_final)) return -1;
    for (i = 0; i < 12; i++) ex__mesh_set_vertex(m, i, ex_normalize(ex_v3(base[i][0], base[i][1], base[i][2])));
    for (i = 0; i < 20; i++) {
        ex_v3_t c = ex_add(ex_add(ex__mesh_vertex(m, faces[i][0]), ex__mesh_vertex(m, faces[i][1])),
                           ex__mesh_vertex(m, faces[i][2]));
        ex__mesh_set_tri(m, i, faces[i][0], faces[i][1], faces[i][2], c);
    }
    nv = 12; nt = 20;
    for (l = 0; l < level; l++) {
        /* each triangle (a, b, c) becomes four through the edge midpoints */
        uint32_t *old = (uint32_t *)malloc(3 * sizeof(uint32_t) * nt);
        ex__mesh_map_t mid;
        size_t t;
        if (!old || ex__mesh_map_init(&mid, 3 * nt)) { free(old); ex_mesh_free(m); return -1; }
        memcpy(old, m->idx, 3 * sizeof(uint32_t) * nt);
        for (t = 0; t < nt; t++) {
            uint32_t v[3], w[3];
            int e;
            for (e = 0; e < 3; e++) v[e] = old[3 * t + e];
            for (e = 0; e < 3; e++) {
                uint32_t a = v[e], b = v[(e + 1) % 3];
                uint32_t key[3];
                key[0] = a < b ? a : b; key[1] = a < b ? b : a; key[2] = 0;
                w[e] = ex__mesh_map_get_or_put(&mid, key, (uint32_t)nv);
                if (w[e] == nv)
                    ex__mesh_set_vertex(m, nv++, ex_normalize(ex_add(ex__mesh_vertex(m, a), ex__mesh_vertex(m, b))));
            }
            /* corners keep (a, b, c)'s orientation; midpoints w0=ab, w1=bc, w2=ca */
            m->idx[3 * t] = v[0]; m->idx[3 * t + 1] = w[0]; m->idx[3 * t + 2] = w[2];
            m->idx[3 * (nt + 3 * t)] = v[1]; m->idx[3 * (nt + 3 * t) + 1] = w[1]; m->idx[3 * (nt + 3 * t) + 2] = w[0];
            m->idx[3 * (nt + 3 * t + 1)] = v[2]; m->idx[3 * (nt + 3 * t + 1) + 1] = w[2]; m->idx[3 * (nt + 3 * t + 1) + 2] = w[1];
            m->idx[3 * (nt + 3 * t + 2)] = w[0]; m->idx[3 * (nt + 3 * t + 2) + 1] = w[1]; m->idx[3 * (nt + 3 * t + 2) + 2] = w[2];
        }
        nt *= 4;
        ex__mesh_map_free(&mid);
        free(old);
    }
    return 0;
}

/* ---------------------------------------------------------------- combining */

int ex_mesh_append(ex_mesh_t *dst, const ex_mesh_t *src)
{
    size_t nv = dst->nverts + src->nverts, nt = dst->ntris + src->ntris, i;
    float *pos;
    uint32_t *idx;
    if (nv > UINT32_MAX) return -1;
    pos = (float *)realloc(dst->pos, 3 * sizeof(float) * (nv ? nv : 1));
    if (!pos) return -1;
    dst->pos = pos;
    idx = (uint32_t *)realloc(dst->idx, 3 * sizeof(uint32_t) * (nt ? nt : 1));
    if (!idx) return -1;
    dst->idx = idx;
    memcpy(dst->pos + 3 * dst->nverts, src->pos, 3 * sizeof(float) * src->nverts);
    for (i = 0; i < 3 * src->ntris; i++) dst->idx[3 * dst->ntris + i] = src->idx[i] + (uint32_t)dst->nverts;
    dst->nverts = nv;
    dst->ntris = nt;
    return 0;
}

void ex_mesh_transform(ex_mesh_t *m, const double a[12])
{
    double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                 a[2] * (a[3] * a[7] - a[4] * a[6]);
    size_t i;
    for (i = 0; i < m->nverts; i++) {
        ex_v3_t p = ex__mesh_vertex(m, (uint32_t)i);
        ex__mesh_set_vertex(m, i, ex_v3(a[0] * p.x + a[1] * p.y + a[2] * p.z + a[9],
                                        a[3] * p.x + a[4] * p.y + a[5] * p.z + a[10],
                                        a[6] * p.x + a[7] * p.y + a[8] * p.z + a[11]));
    }
    if (det < 0)
        for (i = 0; i < m->ntris; i++) {
            uint32_t s = m->idx[3 * i + 1];
            m->idx[3 * i + 1] = m->idx[3 * i + 2];
            m->idx[3 * i + 2] = s;
        }
}

void ex_affine_srt(double a[12], double s, ex_v3_t axis, double angle, ex_v3_t t)
{
    /* Rodrigues: R = cI + (1-c) k kᵀ + sin·[k]× */
    ex_v3_t k = ex_normalize(axis);
    double c = cos(angle), sn = sin(angle), C = 1 - c;
    a[0] = s * (c + C * k.x * k.x);       a[1] = s * (C * k.x * k.y - sn * k.z); a[2] = s * (C * k.x * k.z + sn * k.y);
    a[3] = s * (C * k.y * k.x + sn * k.z); a[4] = s * (c + C * k.y * k.y);      a[5] = s * (C * k.y * k.z - sn * k.x);
    a[6] = s * (C * k.z * k.x - sn * k.y); a[7] = s * (C * k.z * k.y + sn * k.x); a[8] = s * (c + C * k.z * k.z);
    a[9] = t.x; a[10] = t.y; a[11] = t.z;
}

int ex_mesh_write_obj(const ex_mesh_t *m, const char *path)
{
    FILE *f = fopen(path, "w");
    size_t i;
    if (!f) { fprintf(stderr, "%s: cannot write %s: %s\n", program_invocation_short_name, path, strerror(errno)); return -1; }
    fprintf(f, "# filigree example mesh: %zu vertices, %zu triangles\n", m->nverts, m->ntris);
    for (i = 0; i < m->nverts; i++) fprintf(f, "v %.9g %.9g %.9g\n", m->pos[3 * i], m->pos[3 * i + 1], m->pos[3 * i + 2]);
    for (i = 0; i < m->ntris; i++)
        fprintf(f, "f %u %u %u\n", m->idx[3 * i] + 1, m->idx[3 * i + 1] + 1, m->idx[3 * i + 2] + 1);
    if (fclose(f) != 0) {
        fprintf(stderr, "%s: cannot write %s: %s\n", program_invocation_short_name, path, strerror(errno));
        return -1;
    }
    return 0;
}
