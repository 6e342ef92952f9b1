/* bench/bench_rounded_build.c — rounded_edges.h build cost and memory, on
   generated scenes sized like the paper's Table 1 (42k-276k triangles), and
   the cost of one query near the edges.
   Usage: build/bench/bench_rounded_build [out_dir]   (CSV: out_dir/rounded_build.csv)
   Table on stdout, progress on stderr. The build is exact (no accuracy is
   traded), so the table shows time and memory only; the paper's times are
   the 'cylinders generated in' figures of its Fig. 8.
   compact = the same for desc.layout = RE_LAYOUT_COMPACT (sphere centres
   solved at query time; the times and query ns are the default layout's).
   B/edge = re_stats_t.bytes (the whole scene block: header, per-triangle
   plane ids, planes, spheres, cylinders, detection radii, corners, radii,
   adjacency lists, kd nodes and leaf references) / rounded edges.
   refs/leaf = kd leaf references / kd leaves (detection candidates per leaf).
   build ms = re_build() (on Linux its blocks get huge pages, see MEMORY in
   the header), faults = its minor page faults; fresh 4K = re_build_into()
   into buffers mapped just before, 4 KiB pages (the first touch of each
   page is a fault: the line above the table gives its cost here); into ms
   = re_build_into() into reused buffers (no faults: the arithmetic alone).
   speedup = paper ms / build ms.
   Threads table (CSV rounded_build_threads.csv): the same scenes as one
   object and with one object per solid (box, block, sphere), re_build() on
   one thread and with desc.parallel on the machine's cores
   (FILIGREE_BENCH_THREADS overrides; one object: its longest steps split,
   many: the objects spread), wall clock, the four builds in turn, best of
   7; gain = 1 thread / threads; speedup 1 / split / objects n = paper ms /
   one object on one thread / split / objects on threads; B/edge 1 / n =
   bytes per rounded edge as one object / one object per solid (default
   layout: every object has a header and its arrays' alignment).
   query ns = one re_query_uv() (the host passes its barycentrics, so a hit
   on a face's flat part is answered by the per-triangle bands). */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "ex_render.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/mman.h>
#include <sys/resource.h>
#endif

typedef struct mesh_t {
    double *v;
    unsigned nv, cv;
    unsigned *idx;
    unsigned ni, ci;
} mesh_t;

static unsigned vert(mesh_t *m, double x, double y, double z)
{
    if (m->nv == m->cv) m->cv = m->cv ? 2 * m->cv : 1024, m->v = (double *)realloc(m->v, sizeof(double) * 3 * m->cv);
    m->v[3 * m->nv] = x, m->v[3 * m->nv + 1] = y, m->v[3 * m->nv + 2] = z;
    return m->nv++;
}
static void tri(mesh_t *m, unsigned a, unsigned b, unsigned c)
{
    if (m->ni + 3 > m->ci) m->ci = m->ci ? 2 * m->ci : 3072, m->idx = (unsigned *)realloc(m->idx, sizeof(unsigned) * m->ci);
    m->idx[m->ni++] = a, m->idx[m->ni++] = b, m->idx[m->ni++] = c;
}
static void quad(mesh_t *m, unsigned a, unsigned b, unsigned c, unsigned d) { tri(m, a, b, c), tri(m, a, c, d); }

/* the six faces of a box whose corner i (bit 0: x, 1: y, 2: z high) is vertex b[i] */
static void box_faces(mesh_t *m, const unsigned b[8])
{
    quad(m, b[0], b[2], b[3], b[1]), quad(m, b[4], b[5], b[7], b[6]), quad(m, b[0], b[1], b[5], b[4]);
    quad(m, b[2], b[6], b[7], b[3]), quad(m, b[0], b[4], b[6], b[2]), quad(m, b[1], b[3], b[7], b[5]);
}
static void box(mesh_t *m, double x0, double y0, double z0, double x1, double y1, double z1)
{
    unsigned b[8], i;
    for (i = 0; i < 8; i++) b[i] = vert(m, i & 1 ? x1 : x0, i & 2 ? y1 : y0, i & 4 ? z1 : z0);
    box_faces(m, b);
}
/* a closed cylinder (knob) of n segments standing on z = z0 */
static void knob(mesh_t *m, double cx, double cy, double z0, double rad, double h, int n)
{
    unsigned b = m->nv, i, un = (unsigned)n;
    for (i = 0; i < un; i++) {
        double a = 2 * M_PI * i / n;
        vert(m, cx + rad * cos(a), cy + rad * sin(a), z0);
        vert(m, cx + rad * cos(a), cy + rad * sin(a), z0 + h);
    }
    for (i = 0; i < un; i++) quad(m, b + 2 * i, b + 2 * ((i + 1) % un), b + 2 * ((i + 1) % un) + 1, b + 2 * i + 1);
    for (i = 1; i + 1 < un; i++) tri(m, b, b + 2 * (i + 1), b + 2 * i), tri(m, b + 1, b + 2 * i + 1, b + 2 * (i + 1) + 1);
}
/* a 2x4 play block: a box and 8 knobs, each a closed convex part */
static void block(mesh_t *m, double x, double y, double z)
{
    int i, j;
    box(m, x, y, z, x + 3.2, y + 1.6, z + 0.96);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 2; j++) knob(m, x + 0.4 + 0.8 * i, y + 0.4 + 0.8 * j, z + 0.96, 0.24, 0.17, 24);
}
static unsigned mid(mesh_t *m, unsigned *cache, unsigned a, unsigned b)
{
    /* cache: per (a,b) edge key in a simple open-addressing table */
    unsigned long long key = a < b ? ((unsigned long long)a << 32) | b : ((unsigned long long)b << 32) | a;
    unsigned cap = cache[0], h = (unsigned)((key * 0x9E3779B97F4A7C15ull) >> 40) % cap;
    double p[3], l;
    while (cache[1 + 3 * h + 2]) {
        if (((unsigned long long)cache[1 + 3 * h] << 32 | cache[1 + 3 * h + 1]) == key) return cache[1 + 3 * h + 2] - 1;
        h = (h + 1) % cap;
    }
    p[0] = m->v[3 * a] + m->v[3 * b], p[1] = m->v[3 * a + 1] + m->v[3 * b + 1], p[2] = m->v[3 * a + 2] + m->v[3 * b + 2];
    l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    cache[1 + 3 * h] = (unsigned)(key >> 32), cache[1 + 3 * h + 1] = (unsigned)key;
    cache[1 + 3 * h + 2] = vert(m, p[0] / l, p[1] / l, p[2] / l) + 1;
    return cache[1 + 3 * h + 2] - 1;
}
static void icosphere(mesh_t *out, int level, double ox, double oy, double oz, double R)
{
    static const unsigned f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    double t = (1 + sqrt(5.0)) / 2, v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    mesh_t cur;
    int i, l;
    unsigned k, base;
    memset(&cur, 0, sizeof cur);
    for (i = 0; i < 12; i++) {
        double n = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
        vert(&cur, v[i][0] / n, v[i][1] / n, v[i][2] / n);
    }
    for (i = 0; i < 20; i++) tri(&cur, f[i][0], f[i][1], f[i][2]);
    for (l = 0; l < level; l++) {
        mesh_t nx;
        unsigned cap = 4 * cur.ni + 7, *cache = (unsigned *)calloc(1 + 3 * (size_t)cap, sizeof(unsigned));
        cache[0] = cap;
        memset(&nx, 0, sizeof nx);
        for (k = 0; k < cur.nv; k++) vert(&nx, cur.v[3 * k], cur.v[3 * k + 1], cur.v[3 * k + 2]);
        for (k = 0; k < cur.ni; k += 3) {
            unsigned a = cur.idx[k], b = cur.idx[k + 1], c = cur.idx[k + 2];
            unsigned ab = mid(&nx, cache, a, b), bc = mid(&nx, cache, b, c), ca = mid(&nx, cache, c, a);
            tri(&nx, a, ab, ca), tri(&nx, b, bc, ab), tri(&nx, c, ca, bc), tri(&nx, ab, bc, ca);
        }
        free(cache), free(cur.v), free(cur.idx);
        cur = nx;
    }
    base = out->nv;
    for (k = 0; k < cur.nv; k++) vert(out, ox + R * cur.v[3 * k], oy + R * cur.v[3 * k + 1], oz + R * cur.v[3 * k + 2]);
    for (k = 0; k < cur.ni; k += 3) tri(out, base + cur.idx[k], base + cur.idx[k + 1], base + cur.idx[k + 2]);
    free(cur.v), free(cur.idx);
}

/* a box [0, 10] x [0, 1]^2 whose four long edges are split into n segments
   (straight chains: vertices where only two planes meet), its long faces
   strips of quads, as fine grids and CAD exports split straight edges */
static void rod(mesh_t *m, unsigned n)
{
    static const double yz[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}; /* counter-clockwise seen from +x */
    unsigned i, c, b = m->nv;
    for (i = 0; i <= n; i++)
        for (c = 0; c < 4; c++) vert(m, 10.0 * i / n, yz[c][0], yz[c][1]);
    for (i = 0; i < n; i++)
        for (c = 0; c < 4; c++) {
            unsigned c1 = (c + 1) % 4;
            quad(m, b + 4 * i + c, b + 4 * i + c1, b + 4 * (i + 1) + c1, b + 4 * (i + 1) + c);
        }
    quad(m, b + 0, b + 3, b + 2, b + 1);
    quad(m, b + 4 * n, b + 4 * n + 1, b + 4 * n + 2, b + 4 * n + 3);
}

/* an n-gon prism of radius 1 and height 1 whose caps are fanned from a rim
   corner (how exporters triangulate n-gons), with a unit box 20 away in the
   same object: a cap plane borders n side planes, and the object has two
   patches, so the radius check of the rest of the object runs */
static void fine_prism(mesh_t *m, unsigned n)
{
    unsigned i, b = m->nv;
    for (i = 0; i < n; i++) vert(m, cos(2 * M_PI * i / n), sin(2 * M_PI * i / n), 0);
    for (i = 0; i < n; i++) vert(m, cos(2 * M_PI * i / n), sin(2 * M_PI * i / n), 1);
    for (i = 0; i < n; i++) quad(m, b + i, b + (i + 1) % n, b + n + (i + 1) % n, b + n + i);
    for (i = 1; i + 1 < n; i++) tri(m, b, b + i + 1, b + i), tri(m, b + n, b + n + i, b + n + i + 1);
    box(m, 20, 20, 20, 21, 21, 21);
}

/* ns per re_query() for rays at the rod's long faces within 4 r of their
   edges, at random slants, the host hit given exactly (its triangle from
   the rod's layout: face c of segment i is quad(4i + c), split along its
   diagonal) */
static double now(void);
/* minor page faults of this process so far (0 where getrusage is missing) */
static long minor_faults(void)
{
#if defined(__linux__)
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
#else
    return 0;
#endif
}
/* memory no process has touched yet: an anonymous mapping on Linux (malloc
   may hand back pages it kept from an earlier free) */
static void *fresh_pages(size_t n)
{
#if defined(__linux__)
    void *p = mmap(NULL, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    return p == MAP_FAILED ? NULL : p;
#else
    return malloc(n);
#endif
}
static void fresh_free(void *p, size_t n)
{
#if defined(__linux__)
    if (p) munmap(p, n);
#else
    (void)n, free(p);
#endif
}
/* what one fresh 4 KiB page costs on this machine: touch 64 MiB that was
   just mapped (the first touch of each page faults it in) */
static double fault_us_per_page(void)
{
    size_t n = (size_t)64 << 20, i;
    double best = HUGE_VAL;
    int rep;
    for (rep = 0; rep < 3; rep++) {
        volatile unsigned char *p = (volatile unsigned char *)fresh_pages(n);
        double t0;
        if (!p) return 0;
        t0 = now();
        for (i = 0; i < n; i += 4096) p[i] = 1;
        t0 = now() - t0;
        if (t0 < best) best = t0;
        fresh_free((void *)p, n);
    }
    return best * 1e6 / (double)(n / 4096);
}
static double rod_query_ns(const re_scene_t *s, unsigned n, double *sink)
{
    static const double yz[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    unsigned long long rng = 99;
    int q, nq = 300000;
    double t0 = now();
    for (q = 0; q < nq; q++) {
        unsigned c, c1, i, tri;
        double x, sp, tp, o[3], d[3], p[3], e[2], nin[2];
        re_hit_t h;
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        c = (unsigned)(rng >> 62), c1 = (c + 1) % 4;
        x = 10.0 * (double)((rng >> 11) & 0xFFFFF) / 1048576.0;
        sp = 0.2 * (double)((rng >> 31) & 0xFFFF) / 65536.0;
        if (rng & 1) sp = 1 - sp;
        i = (unsigned)(x / 10.0 * n);
        if (i >= n) i = n - 1;
        tp = x * n / 10.0 - i;
        tri = 2 * (4 * i + c) + (sp >= tp ? 0u : 1u);
        e[0] = yz[c1][0] - yz[c][0], e[1] = yz[c1][1] - yz[c][1];
        nin[0] = -e[1], nin[1] = e[0]; /* the ring is counter-clockwise seen from +x: inward is to the left */
        p[0] = x, p[1] = yz[c][0] + sp * e[0], p[2] = yz[c][1] + sp * e[1];
        d[0] = 0.7 * (double)((int)((rng >> 3) & 127) - 64) / 64.0;
        d[1] = nin[0] + 0.5 * e[0] * (double)((int)((rng >> 10) & 127) - 64) / 64.0;
        d[2] = nin[1] + 0.5 * e[1] * (double)((int)((rng >> 10) & 127) - 64) / 64.0;
        o[0] = p[0] - d[0], o[1] = p[1] - d[1], o[2] = p[2] - d[2];
        re_query(s, o, d, 0, tri, 1.0, &h);
        *sink += h.t;
    }
    return (now() - t0) / nq * 1e9;
}

/* thread CPU time: the build is single-threaded, and this stays fair on a
   machine shared with other jobs */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct scene_t {
    const char *name;
    double paper_s; /* the paper's cylinder generation time for its scene of this size */
    mesh_t m;
    double r;
    unsigned n_parts, part_ni[4000]; /* index count at the end of each solid */
} scene_t;

/* the solid just added ends here: one object when the scene is built as
   one object per solid (a Blender scene holds each block or sphere so) */
static void end_part(scene_t *s) { s->part_ni[s->n_parts++] = s->m.ni; }

/* ---- the build on the host's threads (re_scene_desc_t.parallel) ---------- */

/* the host's parallel-for: the examples' (one thread per task) */
static void host_parallel(void *user, unsigned count, re_task_fn task, void *task_ctx)
{
    (void)user;
    ex_parallel_for(count, task, task_ctx);
}
static double wall(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
/* A 3-D checkerboard of n^3 / 2 unit cubes (voxel art's diagonal
   neighbours): each pair of neighbours touches along an edge, and up to
   four cubes meet at a vertex. share: the cubes' corners are one vertex
   where they touch (a welded voxel mesh), else each cube has its own. */
static void voxels(mesh_t *m, int n, int share)
{
    unsigned *grid = (unsigned *)malloc(sizeof(unsigned) * (size_t)(n + 1) * (n + 1) * (n + 1));
    int x, y, z, k;
    memset(grid, 0xFF, sizeof(unsigned) * (size_t)(n + 1) * (n + 1) * (n + 1));
    for (x = 0; x < n; x++)
        for (y = 0; y < n; y++)
            for (z = 0; z < n; z++) {
                unsigned b[8];
                if ((x + y + z) % 2) continue;
                for (k = 0; k < 8; k++) {
                    int cx = x + (k & 1), cy = y + (k >> 1 & 1), cz = z + (k >> 2 & 1);
                    unsigned *g = &grid[((size_t)cx * (n + 1) + cy) * (n + 1) + cz];
                    if (!share || *g == ~0u) *g = vert(m, cx, cy, cz);
                    b[k] = *g;
                }
                box_faces(m, b);
            }
    free(grid);
}

/* wall-clock ms of one re_build() */
static double build_wall_ms(const re_scene_desc_t *desc)
{
    re_scene_t *s = NULL;
    re_diag_t dg;
    double t0 = wall();
    if (re_build(desc, &s, &dg) != RE_OK) {
        fprintf(stderr, "build failed: %s\n", dg.message);
        exit(1);
    }
    t0 = wall() - t0;
    re_free(s);
    return t0 * 1e3;
}
/* One object on one thread and with its steps split on `threads` threads,
   and one object per solid on one thread and on `threads` threads, in turn
   for 7 rounds (best of each): wall clock. */
static void threads_row(const scene_t *sc, unsigned threads, FILE *csv)
{
    re_mesh_t one, *parts = (re_mesh_t *)calloc(sc->n_parts, sizeof *parts);
    unsigned **idx = (unsigned **)calloc(sc->n_parts, sizeof *idx), p, j;
    re_scene_desc_t d1, d1p, dn, dp;
    double best[4] = {HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL}, bpe[2];
    int rep, mode;
    memset(&one, 0, sizeof one);
    one.positions = sc->m.v, one.vertex_count = sc->m.nv, one.indices = sc->m.idx, one.index_count = sc->m.ni, one.radius = sc->r;
    for (p = 0; p < sc->n_parts; p++) { /* each solid's own vertices, indices from its first */
        unsigned i0 = p ? sc->part_ni[p - 1] : 0, n = sc->part_ni[p] - i0, vlo = ~0u, vhi = 0;
        for (j = 0; j < n; j++) {
            unsigned v = sc->m.idx[i0 + j];
            vlo = v < vlo ? v : vlo, vhi = v > vhi ? v : vhi;
        }
        idx[p] = (unsigned *)malloc(sizeof(unsigned) * n);
        for (j = 0; j < n; j++) idx[p][j] = sc->m.idx[i0 + j] - vlo;
        parts[p].positions = sc->m.v + 3 * (size_t)vlo, parts[p].vertex_count = vhi - vlo + 1;
        parts[p].indices = idx[p], parts[p].index_count = n, parts[p].radius = sc->r;
    }
    memset(&d1, 0, sizeof d1);
    d1.objects = &one, d1.object_count = 1;
    d1p = d1, d1p.parallel = host_parallel, d1p.threads = threads; /* one object: its steps split */
    dn = d1, dn.objects = parts, dn.object_count = sc->n_parts;
    dp = dn, dp.parallel = host_parallel, dp.threads = threads;
    for (rep = 0; rep < 7; rep++)
        for (mode = 0; mode < 4; mode++) {
            int m = (mode + rep) % 4;
            double t = build_wall_ms(m == 0 ? &d1 : m == 1 ? &dn : m == 2 ? &dp : &d1p);
            if (t < best[m]) best[m] = t;
        }
    { /* the memory of many small objects: each has its header and its own arrays' alignment */
        re_scene_t *s1 = NULL, *sn = NULL;
        re_stats_t a, b;
        if (re_build(&d1, &s1, NULL) != RE_OK || re_build(&dn, &sn, NULL) != RE_OK) exit(1);
        re_get_stats(s1, &a), re_get_stats(sn, &b);
        re_free(s1), re_free(sn);
        bpe[0] = (double)a.bytes / (double)a.rounded_edges, bpe[1] = (double)b.bytes / (double)b.rounded_edges;
    }
    printf("%-20s %8u %12.1f %12.1f %9.2fx %12.1f %12.1f %9.2fx %9.0fx %9.0fx %9.0fx %8.1f %8.1f\n", sc->name, sc->n_parts, best[0], best[3],
           best[0] / best[3], best[1], best[2], best[1] / best[2], sc->paper_s * 1e3 / best[0], sc->paper_s * 1e3 / best[3],
           sc->paper_s * 1e3 / best[2], bpe[0], bpe[1]);
    fflush(stdout);
    if (csv)
        fprintf(csv, "%s,%u,%u,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.1f,%.1f,%.1f,%.2f,%.2f\n", sc->name, sc->n_parts, threads, best[0], best[3],
                best[0] / best[3], best[1], best[2], best[1] / best[2], sc->paper_s * 1e3 / best[0], sc->paper_s * 1e3 / best[3],
                sc->paper_s * 1e3 / best[2], bpe[0], bpe[1]);
    for (p = 0; p < sc->n_parts; p++) free(idx[p]);
    free(idx), free(parts);
}

/* The best of reps re_build() calls on m (one object, radius r), in
   seconds, or a negative value when one fails; the last scene stays in
   *last. */
static double best_build(const mesh_t *m, double r, int reps, re_scene_t **last)
{
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_diag_t dg;
    double best = HUGE_VAL;
    int rep;
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    mesh.positions = m->v, mesh.vertex_count = m->nv, mesh.indices = m->idx, mesh.index_count = m->ni, mesh.radius = r;
    desc.objects = &mesh, desc.object_count = 1;
    *last = NULL;
    for (rep = 0; rep < reps; rep++) {
        double t0;
        re_free(*last);
        *last = NULL;
        t0 = now();
        if (re_build(&desc, last, &dg) != RE_OK) {
            fprintf(stderr, "build failed: %s\n", dg.message);
            return -1;
        }
        t0 = now() - t0;
        if (t0 < best) best = t0;
    }
    return best;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    scene_t sc[4];
    char path[512];
    FILE *csv;
    int i, k;
    memset(sc, 0, sizeof sc);
    /* like Scene 1 (42k triangles): many small boxes */
    sc[0].name = "boxes-42k", sc[0].paper_s = 1.5, sc[0].r = 0.02;
    for (i = 0; i < 3500; i++) box(&sc[0].m, (i % 70) * 1.5, (i / 70) * 1.5, 0, (i % 70) * 1.5 + 1, (i / 70) * 1.5 + 0.7, 0.5), end_part(&sc[0]);
    /* like Scene 2 (103k): five level-5 icospheres (vertices of degree 5-6: exact corners everywhere) */
    sc[1].name = "icospheres-102k", sc[1].paper_s = 3.6, sc[1].r = 0.004;
    for (i = 0; i < 5; i++) icosphere(&sc[1].m, 5, 3.0 * i, 0, 0, 1), end_part(&sc[1]);
    /* like Scene 3 (252k): play blocks mixed with icospheres */
    sc[2].name = "blocks+spheres-252k", sc[2].paper_s = 9.7, sc[2].r = 0.01;
    for (i = 0; i < 200; i++) block(&sc[2].m, (i % 20) * 3.6, (i / 20) * 2.0, 0), end_part(&sc[2]);
    for (i = 0; i < 5; i++) icosphere(&sc[2].m, 5, 3.0 * i, -5, 0, 1), end_part(&sc[2]);
    /* like Blocks (276k): 2x4 play blocks, 8 knobs of 24 segments each */
    sc[3].name = "blocks-276k", sc[3].paper_s = 9.5, sc[3].r = 0.02;
    for (i = 0; i < 369; i++) block(&sc[3].m, (i % 24) * 3.6, (i / 24) * 2.0, 0), end_part(&sc[3]);
    snprintf(path, sizeof path, "%s/rounded_build.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "scene,triangles,rounded_edges,spheres,cylinders,extra_cylinders,build_ms,build_faults,fresh_4k_ms,into_ms,paper_ms,speedup,bytes,bytes_per_rounded_edge,compact_bytes_per_rounded_edge,query_ns,kd_leaves,kd_refs_per_leaf\n");
    printf("a fresh 4 KiB page costs %.2f us to fault in on this machine (64 MiB just mapped, best of 3)\n", fault_us_per_page());
    printf("%-20s %9s %8s %8s %9s %7s %9s %7s %9s %8s %8s %8s %10s %7s %8s %8s %8s %9s\n", "scene", "triangles", "rounded", "spheres", "cylinders",
           "extra", "build ms", "faults", "fresh 4K", "into ms", "paper ms", "speedup", "bytes", "B/edge", "compact", "query ns", "leaves", "refs/leaf");
    for (k = 0; k < 4; k++) {
        re_mesh_t mesh;
        re_scene_desc_t desc;
        re_scene_t *s = NULL;
        re_stats_t st;
        re_diag_t dg;
        double best = HUGE_VAL, best_into = HUGE_VAL, best_fresh = HUGE_VAL, tq, sink = 0, compact_bpe = 0;
        long faults = 0;
        re_sizes_t sz;
        void *mem, *scratch;
        int rep, nq = 300000, q;
        unsigned long long rng = 12345;
        memset(&mesh, 0, sizeof mesh);
        memset(&desc, 0, sizeof desc);
        mesh.positions = sc[k].m.v, mesh.vertex_count = sc[k].m.nv, mesh.indices = sc[k].m.idx;
        mesh.index_count = sc[k].m.ni, mesh.radius = sc[k].r;
        desc.objects = &mesh, desc.object_count = 1;
        fprintf(stderr, "  %s: %u triangles\n", sc[k].name, sc[k].m.ni / 3);
        for (rep = 0; rep < 5; rep++) {
            long f0 = minor_faults();
            double t0 = now();
            if (re_build(&desc, &s, &dg) != RE_OK) { fprintf(stderr, "build failed: %s\n", dg.message); return 1; }
            t0 = now() - t0;
            if (t0 < best) best = t0, faults = minor_faults() - f0;
            if (rep < 4) re_free(s), s = NULL;
        }
        re_get_stats(s, &st);
        /* the compact layout (sphere centres solved at query time): its size */
        {
            re_scene_t *sc2 = NULL;
            re_stats_t st2;
            desc.layout = RE_LAYOUT_COMPACT;
            if (re_build(&desc, &sc2, &dg) != RE_OK) { fprintf(stderr, "compact build failed: %s\n", dg.message); return 1; }
            re_get_stats(sc2, &st2);
            compact_bpe = (double)st2.bytes / (double)st2.rounded_edges;
            re_free(sc2);
            desc.layout = RE_LAYOUT_FAST;
        }
        /* caller buffers, reused from build to build (a renderer rebuilding per frame) */
        if (re_build_sizes(&desc, &sz, &dg) != RE_OK) return 1;
        /* fresh 4 KiB pages: into buffers never touched before, without the
           huge-page advice re_build() gives its own blocks on Linux (what
           re_build() cost before it; the difference is page faults) */
        for (rep = 0; rep < 5; rep++) {
            re_scene_t *s2;
            double t0 = now();
            mem = fresh_pages(sz.scene_bytes), scratch = fresh_pages(sz.scratch_bytes);
            if (!mem || !scratch || re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s2, &dg) != RE_OK) return 1;
            fresh_free(mem, sz.scene_bytes), fresh_free(scratch, sz.scratch_bytes);
            t0 = now() - t0;
            if (t0 < best_fresh) best_fresh = t0;
        }
        mem = malloc(sz.scene_bytes), scratch = malloc(sz.scratch_bytes);
        for (rep = 0; rep < 5; rep++) {
            re_scene_t *s2;
            double t0 = now();
            if (re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s2, &dg) != RE_OK) return 1;
            t0 = now() - t0;
            if (t0 < best_into) best_into = t0;
        }
        free(mem), free(scratch);
        /* query cost: rays toward random points of random triangles, the
           host hit given exactly (t = 1); about a third land in rounded zones */
        tq = now();
        for (q = 0; q < nq; q++) {
            unsigned t, a;
            double u, v, p[3], o[3], d[3], n[3], e1[3], e2[3], l;
            re_hit_t h;
            const double *A, *B, *C;
            rng = rng * 6364136223846793005ull + 1442695040888963407ull;
            t = (unsigned)((rng >> 33) % (sc[k].m.ni / 3));
            u = (double)((rng >> 11) & 0xFFFF) / 65536.0, v = (double)((rng >> 27) & 0xFFFF) / 65536.0;
            if (u + v > 1) u = 1 - u, v = 1 - v;
            A = sc[k].m.v + 3 * sc[k].m.idx[3 * t], B = sc[k].m.v + 3 * sc[k].m.idx[3 * t + 1], C = sc[k].m.v + 3 * sc[k].m.idx[3 * t + 2];
            for (a = 0; a < 3; a++) p[a] = A[a] + u * (B[a] - A[a]) + v * (C[a] - A[a]), e1[a] = B[a] - A[a], e2[a] = C[a] - A[a];
            n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (a = 0; a < 3; a++) d[a] = -n[a] / l + 0.7 * (double)((int)((rng >> (a * 7)) & 127) - 64) / 64.0;
            if (d[0] * n[0] + d[1] * n[1] + d[2] * n[2] >= 0) for (a = 0; a < 3; a++) d[a] = -n[a];
            for (a = 0; a < 3; a++) o[a] = p[a] - d[a];
            re_query_uv(s, o, d, 0, t, 1.0, u, v, &h);
            sink += h.t;
        }
        tq = (now() - tq) / nq * 1e9;
        printf("%-20s %9llu %8llu %8llu %9llu %7llu %9.1f %7ld %9.1f %8.1f %8.0f %7.0fx %10zu %7.1f %8.1f %8.0f %8llu %9.1f\n", sc[k].name, st.triangles,
               st.rounded_edges, st.spheres, st.cylinders, st.extra_cylinders, best * 1e3, faults, best_fresh * 1e3, best_into * 1e3, sc[k].paper_s * 1e3,
               sc[k].paper_s / best, st.bytes, (double)st.bytes / (double)st.rounded_edges, compact_bpe, tq, st.kd_leaves,
               st.kd_leaves ? (double)st.kd_leaf_refs / (double)st.kd_leaves : 0.0);
        fflush(stdout);
        if (csv)
            fprintf(csv, "%s,%llu,%llu,%llu,%llu,%llu,%.3f,%ld,%.3f,%.3f,%.0f,%.1f,%zu,%.2f,%.2f,%.1f,%llu,%.2f\n", sc[k].name, st.triangles, st.rounded_edges,
                    st.spheres, st.cylinders, st.extra_cylinders, best * 1e3, faults, best_fresh * 1e3, best_into * 1e3, sc[k].paper_s * 1e3,
                    sc[k].paper_s / best, st.bytes, (double)st.bytes / (double)st.rounded_edges, compact_bpe, tq, st.kd_leaves,
                    st.kd_leaves ? (double)st.kd_leaf_refs / (double)st.kd_leaves : 0.0);
        if (sink == 12345.678) printf(" ");
        re_free(s);
    }
    if (csv) fclose(csv);
    /* The same scenes built on the host's threads (re_scene_desc_t.parallel),
       as one object and as one object per solid: wall clock, since the work
       is spread. */
    {
        const char *env = getenv("FILIGREE_BENCH_THREADS");
        long nt = env ? atol(env) : sysconf(_SC_NPROCESSORS_ONLN);
        unsigned threads = nt < 2 ? 2u : nt > RE_MAX_BUILD_TASKS ? (unsigned)RE_MAX_BUILD_TASKS : (unsigned)nt;
        snprintf(path, sizeof path, "%s/rounded_build_threads.csv", dir);
        csv = fopen(path, "w");
        if (csv) fprintf(csv, "scene,objects,threads,one_object_ms,one_object_threads_ms,one_object_gain,objects_1_thread_ms,objects_threads_ms,objects_gain,speedup_one_object,speedup_one_object_threads,speedup_objects_threads,bytes_per_rounded_edge_one_object,bytes_per_rounded_edge_objects\n");
        printf("\nbuild on the host's threads: re_build() wall-clock ms, best of 7 rounds (the four in turn), %u threads: the scene as one object\n"
               "(on one thread; its steps split on the threads) and as one object per solid (on one thread; the objects on the threads)\n", threads);
        printf("%-20s %8s %12s %12s %10s %12s %12s %10s %10s %10s %10s %8s %8s\n", "scene", "objects", "one object", "1 obj split", "gain", "objects 1 t",
               "objects n t", "gain", "speedup 1", "split", "objects n", "B/edge 1", "B/edge n");
        for (k = 0; k < 4; k++) {
            fprintf(stderr, "  %s: threads\n", sc[k].name);
            threads_row(&sc[k], threads, csv);
            free(sc[k].m.v), free(sc[k].m.idx);
        }
        if (csv) fclose(csv);
    }
    /* Build time against chain length: linear since 2026-12-04 (each chain's
       strips and inner spheres are walked once; from every segment they
       were quadratic: 2.5 s at n = 4000, 39 s at 16000), and the query near
       the split edges (rod_query_ns). */
    snprintf(path, sizeof path, "%s/rounded_build_chains.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "segments,triangles,rounded_edges,spheres,build_ms,ns_per_triangle,query_ns,bytes_per_rounded_edge,compact_bytes_per_rounded_edge\n");
    printf("\nstraight chains: a 10 x 1 x 1 box whose 4 long edges are split into n segments (r = 0.05), re_build()\n");
    printf("%10s %10s %10s %8s %10s %12s %10s %8s %8s\n", "segments", "triangles", "rounded", "spheres", "build ms", "ns/triangle", "query ns",
           "B/edge", "compact");
    for (k = 0; k < 4; k++) {
        unsigned n = 1000u << (2 * k);
        mesh_t m;
        re_mesh_t mesh;
        re_scene_desc_t desc;
        re_scene_t *s = NULL;
        re_diag_t dg;
        re_stats_t st;
        double best, tq, sink = 0, compact_bpe;
        memset(&m, 0, sizeof m);
        rod(&m, n);
        fprintf(stderr, "  chains: %u segments\n", n);
        if ((best = best_build(&m, 0.05, 3, &s)) < 0) return 1;
        re_get_stats(s, &st);
        tq = rod_query_ns(s, n, &sink);
        re_free(s);
        {
            re_stats_t stc;
            memset(&mesh, 0, sizeof mesh);
            memset(&desc, 0, sizeof desc);
            mesh.positions = m.v, mesh.vertex_count = m.nv, mesh.indices = m.idx, mesh.index_count = m.ni, mesh.radius = 0.05;
            desc.objects = &mesh, desc.object_count = 1;
            desc.layout = RE_LAYOUT_COMPACT;
            if (re_build(&desc, &s, &dg) != RE_OK) { fprintf(stderr, "compact build failed: %s\n", dg.message); return 1; }
            re_get_stats(s, &stc);
            re_free(s);
            compact_bpe = (double)stc.bytes / (double)stc.rounded_edges;
        }
        printf("%10u %10u %10llu %8llu %10.1f %12.0f %10.0f %8.1f %8.1f\n", n, m.ni / 3, st.rounded_edges, st.spheres, best * 1e3,
               best * 1e9 / (m.ni / 3), tq, (double)st.bytes / (double)st.rounded_edges, compact_bpe);
        if (csv)
            fprintf(csv, "%u,%u,%llu,%llu,%.3f,%.1f,%.1f,%.2f,%.2f\n", n, m.ni / 3, st.rounded_edges, st.spheres, best * 1e3,
                    best * 1e9 / (m.ni / 3), tq, (double)st.bytes / (double)st.rounded_edges, compact_bpe);
        free(m.v), free(m.idx);
        if (sink == 12345.678) printf(" ");
    }
    if (csv) fclose(csv);
    /* Solids that touch (construction step 2a): the same cubes with shared
       vertices (split per solid by the build) and with their own. */
    snprintf(path, sizeof path, "%s/rounded_build_touching.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "vertices,cubes,triangles,rounded_edges,spheres,build_ms,bytes_per_rounded_edge\n");
    printf("\ntouching solids: a 3-D checkerboard of unit cubes (r = 0.1), re_build() thread CPU ms, best of 7 (the two in turn)\n");
    printf("%-10s %8s %10s %10s %8s %10s %8s\n", "vertices", "cubes", "triangles", "rounded", "spheres", "build ms", "B/edge");
    {
        mesh_t m[2];
        re_mesh_t mesh[2];
        re_scene_desc_t desc[2];
        double best[2] = {HUGE_VAL, HUGE_VAL};
        int rep, q;
        fprintf(stderr, "  touching solids\n");
        for (q = 0; q < 2; q++) {
            memset(&m[q], 0, sizeof m[q]);
            voxels(&m[q], 20, q == 0);
            memset(&mesh[q], 0, sizeof mesh[q]);
            memset(&desc[q], 0, sizeof desc[q]);
            mesh[q].positions = m[q].v, mesh[q].vertex_count = m[q].nv, mesh[q].indices = m[q].idx, mesh[q].index_count = m[q].ni;
            mesh[q].radius = 0.1;
            desc[q].objects = &mesh[q], desc[q].object_count = 1;
        }
        for (rep = 0; rep < 7; rep++)
            for (q = 0; q < 2; q++) {
                re_scene_t *s = NULL;
                re_diag_t dg;
                int w = (q + rep) % 2;
                double t0 = now();
                if (re_build(&desc[w], &s, &dg) != RE_OK) { fprintf(stderr, "build failed: %s\n", dg.message); return 1; }
                t0 = now() - t0;
                if (t0 < best[w]) best[w] = t0;
                if (rep == 6) {
                    re_stats_t st;
                    re_get_stats(s, &st);
                    printf("%-10s %8u %10llu %10llu %8llu %10.1f %8.1f\n", w == 0 ? "shared" : "own", m[w].ni / 36, st.triangles,
                           st.rounded_edges, st.spheres, best[w] * 1e3, (double)st.bytes / (double)st.rounded_edges);
                    if (csv)
                        fprintf(csv, "%s,%u,%llu,%llu,%llu,%.3f,%.2f\n", w == 0 ? "shared" : "own", m[w].ni / 36, st.triangles, st.rounded_edges,
                                st.spheres, best[w] * 1e3, (double)st.bytes / (double)st.rounded_edges);
                }
                re_free(s);
            }
        printf("shared / own: %.2fx\n", best[0] / best[1]);
        for (q = 0; q < 2; q++) free(m[q].v), free(m[q].idx);
    }
    if (csv) fclose(csv);
    /* Fine polygons (2026-12-06): each corner's exit clearance read every
       neighbour of its cap (quadratic: 16 000 sides took 4.6 s), and with a
       second patch the rest-of-object check met the cap's own fans from
       every edge; now an angular tree and patch-tagged nodes. What grows
       faster than n is the bands' far strips: each rim edge's strip
       crosses about sqrt(2 r / R) n / pi fan triangles (docs, "Limits"). */
    snprintf(path, sizeof path, "%s/rounded_build_fine_polygons.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "sides,triangles,rounded_edges,build_ms,ns_per_triangle\n");
    printf("\nfine polygons: an n-gon prism (radius 1, caps fanned from a rim corner) and a far box in one object (r = 0.001), re_build()\n");
    printf("%10s %10s %10s %10s %12s\n", "sides", "triangles", "rounded", "build ms", "ns/triangle");
    for (k = 0; k < 4; k++) {
        unsigned n = 1000u << (2 * k);
        mesh_t m;
        re_scene_t *s = NULL;
        re_stats_t st;
        double best;
        memset(&m, 0, sizeof m);
        fine_prism(&m, n);
        fprintf(stderr, "  fine polygons: %u sides\n", n);
        if ((best = best_build(&m, 0.001, k < 3 ? 3 : 1, &s)) < 0) return 1;
        re_get_stats(s, &st);
        re_free(s);
        printf("%10u %10u %10llu %10.1f %12.0f\n", n, m.ni / 3, st.rounded_edges, best * 1e3, best * 1e9 / (m.ni / 3));
        if (csv) fprintf(csv, "%u,%u,%llu,%.3f,%.1f\n", n, m.ni / 3, st.rounded_edges, best * 1e3, best * 1e9 / (m.ni / 3));
        free(m.v), free(m.idx);
    }
    if (csv) fclose(csv);
    return 0;
}
