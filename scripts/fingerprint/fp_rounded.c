/* scripts/fingerprint/fp_rounded.c — rounded_edges.h's builds and answers,
   hashed: each scene's block as re_build_into() writes it at a fixed
   address (so its pointers are the same from run to run), in both layouts;
   its features as re_get_sphere()/re_get_cylinder() list them; re_query,
   re_query_uv, re_query_exit and re_secondary_origin on rays through random
   points of every object's triangles (a third near an edge); and the same
   from re_build() on two threads. Linux (MAP_FIXED_NOREPLACE). */
#define _GNU_SOURCE
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#define RX_SCENE_IMPLEMENTATION
#include "../../examples/rounded_edges/rx_scene.h"
#include <stdio.h>
#include <sys/mman.h>
#include "ex_render.h"
#include "test.h"
#include "test_rounded_util.h"
#include "fp.h"

#define FP_BLOCK_AT ((void *)0x7e0000000000ull)

static void fp_parallel(void *user, unsigned count, re_task_fn task, void *ctx)
{
    (void)user;
    ex_parallel_for(count, task, ctx);
}

static unsigned long long fp_features(const re_scene_t *s)
{
    unsigned long long h = FP_START;
    unsigned o, i;
    re_stats_t st;
    re_get_stats(s, &st);
    st.bytes = 0; /* the allocation's rounding, not the build's */
    h = fp_hash(h, &st, sizeof st);
    for (o = 0; o < re_object_count(s); o++) {
        for (i = 0; i < re_sphere_count(s, o); i++) {
            re_sphere_t sp;
            memset(&sp, 0, sizeof sp);
            re_get_sphere(s, o, i, &sp);
            h = fp_hash(h, &sp, sizeof sp);
        }
        for (i = 0; i < re_cylinder_count(s, o); i++) {
            re_cylinder_t c;
            memset(&c, 0, sizeof c);
            re_get_cylinder(s, o, i, &c);
            h = fp_hash(h, &c, sizeof c);
        }
    }
    return h;
}

static void fp_vertex(const re_mesh_t *m, unsigned v, double x[3])
{
    if (m->position_type == RE_FLOAT32) {
        const float *f = (const float *)m->positions + 3 * (size_t)v;
        x[0] = f[0], x[1] = f[1], x[2] = f[2];
    } else {
        const double *d = (const double *)m->positions + 3 * (size_t)v;
        x[0] = d[0], x[1] = d[1], x[2] = d[2];
    }
}

static unsigned long long fp_queries(const re_scene_t *s, const re_mesh_t *m, unsigned nm)
{
    unsigned long long h = FP_START;
    unsigned k, o, per = nm > 40 ? 60u : 4000u;
    t_rng_t rng;
    rng.s = 7;
    for (o = 0; o < nm; o++)
        for (k = 0; k < per; k++) {
            unsigned t = (unsigned)(t_rng_u64(&rng) % (m[o].index_count / 3)), j;
            double P[3] = {0, 0, 0}, w[3], ws, d[3], org[3], back = 3;
            re_hit_t out, out2;
            w[0] = t_rng_unit(&rng), w[1] = t_rng_unit(&rng), w[2] = t_rng_unit(&rng);
            if (k & 1) w[t_rng_u64(&rng) % 3] *= 1e-3;
            ws = w[0] + w[1] + w[2];
            for (j = 0; j < 3; j++) {
                double x[3];
                fp_vertex(&m[o], m[o].indices[3 * t + j], x);
                P[0] += w[j] / ws * x[0], P[1] += w[j] / ws * x[1], P[2] += w[j] / ws * x[2];
            }
            tm_rand_dir(&rng, d);
            for (j = 0; j < 3; j++) org[j] = P[j] - back * d[j];
            re_query(s, org, d, o, t, back, &out);
            h = fp_hash(h, &out, sizeof out);
            re_query_uv(s, org, d, o, t, back, w[1] / ws, w[2] / ws, &out2);
            h = fp_hash(h, &out2, sizeof out2);
            if (out.kind == RE_HIT_ROUNDED) {
                double so[3];
                re_secondary_origin(s, &out, d, so);
                h = fp_hash(h, so, sizeof so);
            }
            re_query_exit(s, org, d, o, t, back, &out2);
            h = fp_hash(h, &out2, sizeof out2);
        }
    return h;
}

static void fp_case(const char *name, re_mesh_t *m, unsigned nm)
{
    int layout;
    for (layout = 0; layout < 2; layout++) {
        re_scene_desc_t desc;
        re_sizes_t sz;
        re_scene_t *s = NULL;
        void *mem, *scratch;
        unsigned long long hb, hf, hq, hp;
        memset(&desc, 0, sizeof desc);
        desc.objects = m;
        desc.object_count = nm;
        desc.layout = layout ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
        if (re_build_sizes(&desc, &sz, NULL)) { printf("rounded   %-14s sizes failed\n", name); return; }
        mem = mmap(FP_BLOCK_AT, sz.scene_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED_NOREPLACE, -1, 0);
        scratch = calloc(1, sz.scratch_bytes);
        if (mem != FP_BLOCK_AT || !scratch || re_build_into(&desc, mem, sz.scene_bytes, scratch, sz.scratch_bytes, &s, NULL)) {
            printf("rounded   %-14s build failed\n", name);
            return;
        }
        hb = fp_hash(FP_START, mem, sz.scene_bytes);
        hf = fp_features(s);
        hq = fp_queries(s, m, nm);
        munmap(mem, sz.scene_bytes);
        free(scratch);
        desc.parallel = fp_parallel, desc.threads = 2;
        if (re_build(&desc, &s, NULL)) { printf("rounded   %-14s build failed\n", name); return; }
        hp = fp_features(s) ^ fp_queries(s, m, nm);
        re_free(s);
        printf("rounded   %-14s %s block %016llx features %016llx queries %016llx  2 threads %s\n", name,
               layout ? "compact" : "fast   ", hb, hf, hq, hp == (hf ^ hq) ? "same" : "DIFFER");
    }
}

static void fp_example_scene(const char *scene, double radius_scale)
{
    rx_scene_t sc;
    re_mesh_t *mm;
    unsigned n;
    char name[64];
    memset(&sc, 0, sizeof sc);
    if (rx_scene_make(&sc, scene, radius_scale)) return;
    mm = (re_mesh_t *)calloc((size_t)sc.nobj + 1, sizeof *mm);
    n = rx_scene_round_meshes(&sc, mm, NULL);
    snprintf(name, sizeof name, "%s-%g", scene, radius_scale);
    fp_case(name, mm, n);
    free(mm);
    rx_scene_free(&sc);
}

static re_mesh_t fp_mesh(const tm_mesh_t *m, double r)
{
    re_mesh_t x;
    memset(&x, 0, sizeof x);
    x.positions = m->v, x.vertex_count = m->nv, x.indices = m->idx, x.index_count = m->ni, x.radius = r;
    return x;
}

/* Five icospheres in one object, the first of level 5 (exact corners). */
static void fp_icospheres(tm_mesh_t *out)
{
    unsigned i, k;
    for (i = 0; i < 5; i++) {
        tm_mesh_t s = {0};
        unsigned b = out->nv;
        tm_icosphere(&s, i == 0 ? 5 : 3, 1.0);
        for (k = 0; k < s.nv; k++) tm_vert(out, s.v[3 * k] + 3.0 * i, s.v[3 * k + 1], s.v[3 * k + 2]);
        for (k = 0; k < s.ni; k += 3) tm_tri(out, b + s.idx[k], b + s.idx[k + 1], b + s.idx[k + 2]);
        tm_free(&s);
    }
}

/* A box whose faces are n x n grids of quads: straight chains everywhere. */
static void fp_grid_box(tm_mesh_t *m, int n)
{
    int a, i, j;
    for (a = 0; a < 6; a++) {
        unsigned base = m->nv;
        int ax = a / 2;
        for (i = 0; i <= n; i++)
            for (j = 0; j <= n; j++) {
                double p[3];
                p[ax] = a & 1 ? 1 : -1;
                p[(ax + 1) % 3] = -1 + 2.0 * i / n;
                p[(ax + 2) % 3] = -1 + 2.0 * j / n;
                tm_vert(m, p[0], p[1], p[2]);
            }
        for (i = 0; i < n; i++)
            for (j = 0; j < n; j++) {
                unsigned q0 = base + (unsigned)(i * (n + 1) + j), q1 = q0 + (unsigned)(n + 1), q2 = q1 + 1, q3 = q0 + 1;
                if (a & 1) tm_quad(m, q0, q1, q2, q3); else tm_quad(m, q0, q3, q2, q1);
            }
    }
}

int main(void)
{
    static tm_mesh_t ico, hulls[40], mix, grid;
    static double edge_r[1 << 16];
    re_mesh_t mm[40];
    t_rng_t rng;
    unsigned i, k;
    fp_example_scene("article", 1), fp_example_scene("article", 0.44), fp_example_scene("blocks", 1);
    fp_example_scene("blocks", 0.44), fp_example_scene("cornell", 1);
    fp_icospheres(&ico);
    mm[0] = fp_mesh(&ico, 0.004);
    fp_case("icospheres", mm, 1);
    rng.s = 99;
    for (i = 0; i < 40; i++) {
        tm_poly_t P;
        tm_random_hull(&rng, 4 + (int)i % 30, 0.5, 1.5, &hulls[i], &P);
        mm[i] = fp_mesh(&hulls[i], 0.02 + 0.01 * (i % 7));
    }
    fp_case("hulls", mm, 40);
    /* 12 hulls in one object, a radius per solid: several patches and radii */
    for (i = 0; i < 12; i++) {
        unsigned b = mix.nv;
        for (k = 0; k < hulls[i].nv; k++) tm_vert(&mix, hulls[i].v[3 * k] + 4.0 * i, hulls[i].v[3 * k + 1], hulls[i].v[3 * k + 2]);
        for (k = 0; k < hulls[i].ni; k += 3) {
            edge_r[mix.ni] = edge_r[mix.ni + 1] = edge_r[mix.ni + 2] = 0.01 + 0.01 * (i % 4);
            tm_tri(&mix, b + hulls[i].idx[k], b + hulls[i].idx[k + 1], b + hulls[i].idx[k + 2]);
        }
    }
    mm[0] = fp_mesh(&mix, 0);
    mm[0].edge_radius = edge_r;
    fp_case("hullmix", mm, 1);
    fp_grid_box(&grid, 12);
    mm[0] = fp_mesh(&grid, 0.05);
    mm[0].weld = 1;
    fp_case("gridbox", mm, 1);
    return 0;
}
