/* rx_render.h — one rendering "world" per mode for the rounded-edges example
   and its benchmark: Embree traces the sharp (or tessellated) meshes, and the
   mode decides what a hit on a rounded object becomes.

     sharp           the host hit as is
     rounded         rounded_edges.h: re_query_uv() on every front-face hit of a
                     rounded object, re_query_exit_uv() on every back-face hit
                     (the integration protocol, docs/rounded_edges.md)
     bevel-blog-N    re_bevel_blog() shading normal, N probe rays, delta = r
     bevel-cycles-N  re_bevel_cycles() shading normal, N samples, R = r
     tess-N          a triangle mesh of the same rounded solid (rx_tess.h), N
                     segments per quarter turn of arc, flat shaded

   Stb-style: define RX_RENDER_IMPLEMENTATION in one file (which must also
   define RE_IMPLEMENTATION, RX_SCENE_IMPLEMENTATION and RX_TESS_IMPLEMENTATION
   or link them). */
#ifndef FILIGREE_RX_RENDER_H
#define FILIGREE_RX_RENDER_H

#include <embree3/rtcore.h>

#include "ex_camera.h"
#include "ex_shade.h"
#include "rounded_edges.h"
#include "rx_scene.h"
#include "rx_tess.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rx_mode_kind_t { RX_SHARP, RX_ROUNDED, RX_BLOG, RX_CYCLES, RX_TESS } rx_mode_kind_t;
typedef struct rx_mode_t {
    rx_mode_kind_t kind;
    int n; /* probe rays (blog), samples (cycles), level (tess); 1 for rounded-compact (RE_LAYOUT_COMPACT); else 0 */
} rx_mode_t;

/* "sharp", "rounded", "rounded-compact", "bevel-blog-N", "bevel-cycles-N", "tess-N" -> *m; 0 or -1. */
int rx_mode_parse(const char *s, rx_mode_t *m);
/* The same names back. Returns buf. */
const char *rx_mode_name(rx_mode_t m, char *buf, size_t size);

typedef struct rx_world_t {
    const rx_scene_t *scene;
    rx_mode_t mode;
    RTCDevice dev;
    RTCScene rtc;
    re_scene_t *round;          /* rounded mode only */
    int *re_object;             /* scene object -> re object, -1 if not rounded */
    size_t *tess_first_round;   /* tess mode: first rounded-part triangle per object */
    ex_world_t shade;
    ex_camera_t cam;
    /* figures */
    double build_seconds;       /* Embree + rounding structure or tessellation */
    double round_seconds;       /* rounding structure or tessellation alone */
    long long embree_bytes;     /* live bytes of the Embree device after the build */
    size_t round_bytes;         /* re_get_stats().bytes */
    size_t triangles;           /* triangles given to Embree */
    re_stats_t round_stats;
    long long concave_reports;  /* build reports of edges/vertices left sharp */
    int tess_sharp_objects;     /* tess mode: objects left sharp (a corner without sphere) */
    int glass;                  /* rounded mode: some rounded object is glass (rx__glass_hit) */
    /* counters, updated atomically during rendering */
    long long rays;             /* path rays (camera and bounce; shadow rays not counted) */
    long long chamfer_rays;     /* of those, the ones the rounding changed */
    long long embree_mem_live;  /* device memory monitor */
} rx_world_t;

/* Builds everything mode `m` needs for scene s and a width x height camera,
   the rounding on `threads` threads (0: every core). 0, or -1 after
   printing one line. */
int rx_world_build(rx_world_t *w, const rx_scene_t *s, rx_mode_t m, int width, int height, int threads);
void rx_world_free(rx_world_t *w);
/* Renders spp samples per pixel into rgb (width*height*3). Returns the
   seconds spent, or a negative value after printing one line. */
double rx_world_render(rx_world_t *w, int spp, int threads, unsigned long long seed, int quiet, float *rgb);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_RX_RENDER_H */

#ifdef RX_RENDER_IMPLEMENTATION
#ifndef RX_RENDER_IMPLEMENTATION_DONE
#define RX_RENDER_IMPLEMENTATION_DONE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ex_embree.h"
#include "ex_render.h"
#include "ex_timer.h"
#include "rx_tess.h"

int rx_mode_parse(const char *s, rx_mode_t *m)
{
    char *end;
    long n;
    const char *num = NULL;
    memset(m, 0, sizeof *m);
    if (!strcmp(s, "sharp")) { m->kind = RX_SHARP; return 0; }
    if (!strcmp(s, "rounded")) { m->kind = RX_ROUNDED; return 0; }
    if (!strcmp(s, "rounded-compact")) { m->kind = RX_ROUNDED; m->n = 1; return 0; }
    if (!strncmp(s, "bevel-blog-", 11)) { m->kind = RX_BLOG; num = s + 11; }
    else if (!strncmp(s, "bevel-cycles-", 13)) { m->kind = RX_CYCLES; num = s + 13; }
    else if (!strncmp(s, "tess-", 5)) { m->kind = RX_TESS; num = s + 5; }
    else return -1;
    n = strtol(num, &end, 10);
    if (end == num || *end || n < 1 || n > 4096) return -1;
    m->n = (int)n;
    return 0;
}

const char *rx_mode_name(rx_mode_t m, char *buf, size_t size)
{
    switch (m.kind) {
    case RX_SHARP: snprintf(buf, size, "sharp"); break;
    case RX_ROUNDED: snprintf(buf, size, m.n ? "rounded-compact" : "rounded"); break;
    case RX_BLOG: snprintf(buf, size, "bevel-blog-%d", m.n); break;
    case RX_CYCLES: snprintf(buf, size, "bevel-cycles-%d", m.n); break;
    case RX_TESS: snprintf(buf, size, "tess-%d", m.n); break;
    }
    return buf;
}

static bool rx__memory_monitor(void *user, ssize_t bytes, bool post)
{
    (void)post;
    __atomic_fetch_add((long long *)user, (long long)bytes, __ATOMIC_RELAXED);
    return true;
}

/* Called from the build's threads (rx__build_round): counts atomically. */
static void rx__count_report(void *user, const re_report_t *r)
{
    if (r->kind == RE_REPORT_CONCAVE_EDGE || r->kind == RE_REPORT_MIXED_VERTEX ||
        r->kind == RE_REPORT_SHARP_PATCH_EDGE || r->kind == RE_REPORT_BOUNDARY_EDGE)
        __atomic_add_fetch((long long *)user, 1, __ATOMIC_RELAXED);
}

/* re_parallel_fn over the examples' parallel-for: one thread per task. */
static void rx__parallel(void *user, unsigned count, re_task_fn task, void *task_ctx)
{
    (void)user;
    ex_parallel_for(count, task, task_ctx);
}

/* The rounding structure over the scene's rounded objects (float positions,
   the same triangles Embree traces). */
static int rx__build_round(rx_world_t *w, int threads)
{
    const rx_scene_t *s = w->scene;
    re_mesh_t *meshes = (re_mesh_t *)calloc((size_t)s->nobj + 1, sizeof *meshes);
    re_scene_desc_t desc;
    re_diag_t diag;
    re_result_t rc;
    unsigned n;
    if (!meshes) return -1;
    n = rx_scene_round_meshes(s, meshes, w->re_object);
    memset(&desc, 0, sizeof desc);
    memset(&diag, 0, sizeof diag);
    desc.objects = meshes;
    desc.object_count = n;
    desc.report = rx__count_report;
    desc.report_user = &w->concave_reports;
    desc.layout = w->mode.kind == RX_ROUNDED && w->mode.n == 1 ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
    desc.parallel = rx__parallel;
    desc.threads = (unsigned)(threads > 0 ? threads : ex_cpu_count());
    rc = re_build(&desc, &w->round, &diag);
    free(meshes);
    if (rc != RE_OK) {
        fprintf(stderr, "rounded_edges: build failed: %s (%s)\n", re_result_string(rc), diag.message);
        return -1;
    }
    re_get_stats(w->round, &w->round_stats);
    w->round_bytes = w->round_stats.bytes;
    return 0;
}

int rx_world_build(rx_world_t *w, const rx_scene_t *s, rx_mode_t m, int width, int height, int threads)
{
    double t0 = ex_now(), t1;
    int i;
    memset(w, 0, sizeof *w);
    w->scene = s;
    w->mode = m;
    w->re_object = (int *)malloc(sizeof(int) * (size_t)(s->nobj + 1));
    w->tess_first_round = (size_t *)calloc((size_t)s->nobj + 1, sizeof(size_t));
    if (!w->re_object || !w->tess_first_round) { fprintf(stderr, "out of memory\n"); rx_world_free(w); return -1; }
    if (!(w->dev = ex_embree_device())) { rx_world_free(w); return -1; }
    rtcSetDeviceMemoryMonitorFunction(w->dev, rx__memory_monitor, &w->embree_mem_live);
    w->rtc = rtcNewScene(w->dev);
    /* rounded mode hides exit faces with an intersect-context filter; the
       Cycles-style bevel traces P's object alone through one
       (rx__bevel_trace_object) */
    if (m.kind == RX_ROUNDED || m.kind == RX_CYCLES) rtcSetSceneFlags(w->rtc, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    if ((m.kind == RX_ROUNDED || m.kind == RX_TESS) && rx__build_round(w, threads)) { rx_world_free(w); return -1; }
    for (i = 0; i < s->nobj; i++) w->glass |= m.kind == RX_ROUNDED && s->obj[i].radius > 0 && s->mats[s->obj[i].material].ior > 0;
    t1 = ex_now();
    for (i = 0; i < s->nobj; i++) {
        const rx_object_t *o = &s->obj[i];
        unsigned id;
        if (m.kind == RX_TESS && o->radius > 0) {
            ex_mesh_t t;
            int rc;
            memset(&t, 0, sizeof t);
            rc = rx_tess_object(w->round, (unsigned)w->re_object[i], &o->mesh, m.n, &t, &w->tess_first_round[i]);
            if (rc < 0) {
                fprintf(stderr, "out of memory tessellating object %d\n", i);
                rx_world_free(w);
                return -1;
            }
            if (rc == 1) w->tess_sharp_objects++;
            id = ex_embree_add_mesh(w->dev, w->rtc, t.pos, t.nverts, t.idx, t.ntris);
            w->triangles += t.ntris;
            ex_mesh_free(&t);
        } else {
            id = ex_embree_add_mesh(w->dev, w->rtc, o->mesh.pos, o->mesh.nverts, o->mesh.idx, o->mesh.ntris);
            w->tess_first_round[i] = o->mesh.ntris;
            w->triangles += o->mesh.ntris;
        }
        if (id != (unsigned)i) { fprintf(stderr, "embree: unexpected geometry id %u\n", id); rx_world_free(w); return -1; }
    }
    if (m.kind == RX_TESS) {
        /* the tessellation replaces the rounding structure: count it, drop it */
        w->round_seconds = ex_now() - t0; /* includes copying into Embree */
        re_free(w->round);
        w->round = NULL;
        w->round_bytes = 0;
    }
    else if (m.kind == RX_ROUNDED) w->round_seconds = t1 - t0;
    if (ex_embree_commit(w->dev, w->rtc)) { rx_world_free(w); return -1; }
    w->build_seconds = ex_now() - t0;
    w->embree_bytes = w->embree_mem_live;
    if (ex_camera_init(&w->cam, s->eye, s->at, s->up, s->vfov, width, height)) {
        fprintf(stderr, "bad camera for scene %s\n", s->name);
        rx_world_free(w);
        return -1;
    }
    return 0;
}

void rx_world_free(rx_world_t *w)
{
    if (w->round) re_free(w->round);
    ex_embree_release(w->dev, w->rtc);
    free(w->re_object);
    free(w->tess_first_round);
    memset(w, 0, sizeof *w);
}

/* ---- tracing ------------------------------------------------------------- */

/* Past a hit at t, the next search starts at t * (1 + RX_STEP_REL) + RX_STEP_REL * scale:
   above Embree's single-precision self-intersection error at both small and
   large t, far below any feature of our scenes. */
#define RX_STEP_REL 1e-5

static double rx__next_t(const rx_world_t *w, double t)
{
    return t * (1 + RX_STEP_REL) + RX_STEP_REL * w->scene->scale;
}

/* Object g's material at a surface with outward normal n (rx_object_t.by_axis). */
static const ex_material_t *rx__material(const rx_world_t *w, unsigned g, ex_v3_t n)
{
    const rx_object_t *ob = &w->scene->obj[g];
    double ax, ay, az;
    int a;
    if (!ob->by_axis) return &w->scene->mats[ob->material]; /* every hit of every other object */
    ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
    a = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
    return &w->scene->mats[ob->axis_material[2 * a + ((a == 0 ? n.x : a == 1 ? n.y : n.z) > 0)]];
}

static void rx__surface_from_hit(const rx_world_t *w, const ex_ray_t *ray, const ex_hit_t *h, ex_surface_t *s)
{
    s->t = h->t;
    s->p = ex_madd(ray->o, ray->d, h->t);
    s->ng = h->ng;
    s->n = h->ng;
    s->mat = rx__material(w, h->geom_id, h->ng);
}

/* The surface of a rounded-edges answer on object g (a rounded hit or
   exit): its t, point and normal, as the shading normal too, and the
   material there. */
static void rx__surface_from_answer(const rx_world_t *w, unsigned g, const re_hit_t *q, ex_surface_t *s)
{
    s->t = q->t;
    s->p = ex_v3(q->point[0], q->point[1], q->point[2]);
    s->n = s->ng = ex_v3(q->normal[0], q->normal[1], q->normal[2]);
    s->mat = rx__material(w, g, s->ng);
}

/* Host trace callback for the bevel baselines: Embree, object = geometry id. */
/* An Embree hit as the baselines' callbacks report it; 0 for a miss. */
static int rx__bevel_hit(ex_hit_t h, re_trace_hit_t *hit)
{
    if (!h.hit) return 0;
    hit->t = h.t;
    hit->normal[0] = h.ng.x; hit->normal[1] = h.ng.y; hit->normal[2] = h.ng.z;
    hit->object = h.geom_id;
    return 1;
}
static int rx__bevel_trace(void *user, const double o[3], const double d[3], double tmin, double tmax,
                           re_trace_hit_t *hit)
{
    const rx_world_t *w = (const rx_world_t *)user;
    return rx__bevel_hit(ex_embree_intersect(w->rtc, ex_v3(o[0], o[1], o[2]), ex_v3(d[0], d[1], d[2]), tmin, tmax), hit);
}

static int rx__bevel_trace_object(void *user, unsigned object, const double o[3], const double d[3], double tmin,
                                  double tmax, re_trace_hit_t *hit);

/* A per-ray seed for the bevel baselines from the ray's bits: the callback
   has no access to the path's random stream, and this keeps it deterministic. */
static unsigned rx__ray_seed(const ex_ray_t *ray)
{
    unsigned long long z = 0;
    double v[6];
    int i;
    v[0] = ray->o.x; v[1] = ray->o.y; v[2] = ray->o.z; v[3] = ray->d.x; v[4] = ray->d.y; v[5] = ray->d.z;
    for (i = 0; i < 6; i++) {
        unsigned long long b;
        memcpy(&b, &v[i], sizeof b);
        z = (z ^ b) * 0x9E3779B97F4A7C15ull;
        z ^= z >> 29;
    }
    return (unsigned)(z >> 32);
}

/* The closest hit of the mode's surface along ray, (0, tmax). *chamfer is
   set when the rounding (or bevel, or tessellated rounding) changed it. */
/* An intersect context that hides the hits of one geometry up to a distance:
   after a pass-through, or when a ray that started in a removed volume
   leaves its object, the host must skip that object's exit face but still
   see any other surface at the same distance (a cube resting on a floor
   leaves through its bottom face exactly where the floor is). */
typedef struct rx__ctx_t {
    struct RTCIntersectContext ctx; /* first: Embree passes its address to the filter */
    unsigned skip_geom;
    float skip_t;
} rx__ctx_t;

static void rx__skip_filter(const struct RTCFilterFunctionNArguments *args)
{
    const rx__ctx_t *c = (const rx__ctx_t *)args->context;
    unsigned i;
    /* SOA access as Embree's C++ helpers RTCHitN_geomID / RTCRayN_tfar do
       (those are not available in C): geomID is the 7th field of RTCHitN,
       tfar the 9th of RTCRayN; tfar holds the candidate's t. */
    const unsigned *geom = (const unsigned *)args->hit + 6 * args->N;
    const float *tfar = (const float *)args->ray + 8 * args->N;
    for (i = 0; i < args->N; i++)
        if (args->valid[i] == -1 && geom[i] == c->skip_geom && tfar[i] <= c->skip_t) args->valid[i] = 0;
}

/* The Embree ray o + t d, t in [tnear, tfar] (r zeroed). */
static void rx__rtc_ray(struct RTCRay *r, ex_v3_t o, ex_v3_t d, double tnear, double tfar)
{
    r->org_x = (float)o.x; r->org_y = (float)o.y; r->org_z = (float)o.z;
    r->dir_x = (float)d.x; r->dir_y = (float)d.y; r->dir_z = (float)d.z;
    r->tnear = (float)tnear;
    r->tfar = tfar < 3e38 ? (float)tfar : INFINITY;
    r->mask = 0xFFFFFFFFu;
}

/* The closest hit in [tnear, tfar] that the filter of ctx lets through. */
static ex_hit_t rx__intersect_in(const rx_world_t *w, struct RTCIntersectContext *ctx, ex_v3_t o, ex_v3_t d, double tnear,
                                 double tfar)
{
    struct RTCRayHit rh;
    ex_hit_t h;
    memset(&h, 0, sizeof h);
    memset(&rh, 0, sizeof rh);
    rx__rtc_ray(&rh.ray, o, d, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(w->rtc, ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.hit = 1;
    h.t = rh.ray.tfar;
    h.geom_id = rh.hit.geomID;
    h.prim_id = rh.hit.primID;
    h.ng = ex_normalize(ex_v3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z)); /* right-hand normal, as ex_embree */
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    return h;
}

/* ex_embree_intersect, hiding geometry skip_geom's hits at t <= skip_t. */
static ex_hit_t rx__intersect_skip(const rx_world_t *w, ex_v3_t o, ex_v3_t d, double tnear, double tfar,
                                   unsigned skip_geom, double skip_t)
{
    rx__ctx_t c;
    if (skip_geom == RTC_INVALID_GEOMETRY_ID) return ex_embree_intersect(w->rtc, o, d, tnear, tfar);
    rtcInitIntersectContext(&c.ctx);
    c.ctx.filter = rx__skip_filter;
    c.skip_geom = skip_geom;
    c.skip_t = (float)skip_t;
    return rx__intersect_in(w, &c.ctx, o, d, tnear, tfar);
}

/* Shadow rays in one occlusion traversal. The filter decides each candidate
   hit on its own, so Embree may visit them in any order: a hit of the skipped
   geometry before skip_t is ignored; a hit on an object that is not rounded
   blocks; a front-face hit blocks when re_query_uv finds the flat face or a
   rounding before tmax, and is ignored on a pass-through; a back-face hit of
   a rounded object (the ray leaves it) asks re_query_exit_uv, as rx__trace
   does: it blocks unless the segment misses the rounded solid there
   (RE_PASS_THROUGH). Each answer is whether the segment meets that
   object's rounded solid around this face, which is what occlusion asks. */
typedef struct rx__occ_ctx_t {
    rx__ctx_t skip; /* first (its ctx is first): Embree passes its address to the filter */
    const rx_world_t *w;
    double o[3], d[3], tmax;
} rx__occ_ctx_t;

static void rx__occlude_filter(const struct RTCFilterFunctionNArguments *args)
{
    const rx__occ_ctx_t *c = (const rx__occ_ctx_t *)args->context;
    const rx_world_t *w = c->w;
    unsigned i, N = args->N;
    /* SOA fields of RTCHitN (Ng_x, Ng_y, Ng_z, u, v, primID, geomID) and
       RTCRayN (tfar is the 9th field), as in rx__skip_filter */
    const float *ng = (const float *)args->hit, *uu = ng + 3 * N, *vv = ng + 4 * N;
    const unsigned *prim = (const unsigned *)args->hit + 5 * N, *geom = (const unsigned *)args->hit + 6 * N;
    const float *tfar = (const float *)args->ray + 8 * N;
    for (i = 0; i < N; i++) {
        unsigned g = geom[i];
        double t = tfar[i], nd;
        re_hit_t q;
        re_hit_kind_t k;
        int obj;
        if (args->valid[i] != -1) continue;
        if (g == c->skip.skip_geom && tfar[i] <= c->skip.skip_t) { args->valid[i] = 0; continue; }
        if ((obj = w->re_object[g]) < 0) continue; /* not rounded: blocks */
        nd = ng[i] * c->d[0] + ng[i + N] * c->d[1] + ng[i + 2 * N] * c->d[2];
        if (nd < 0) {
            k = re_query_uv(w->round, c->o, c->d, (unsigned)obj, prim[i], t, uu[i], vv[i], &q);
            if (k == RE_PASS_THROUGH || (k == RE_HIT_ROUNDED && q.t >= c->tmax)) args->valid[i] = 0;
        } else if (re_query_exit_uv(w->round, c->o, c->d, (unsigned)obj, prim[i], t, uu[i], vv[i], &q) == RE_PASS_THROUGH) {
            args->valid[i] = 0;
        }
    }
}

/* 1 when the segment o + t d, t in (0, tmax), meets the mode's surfaces,
   hiding geometry skip_geom's hits at t <= skip_t. */
static int rx__occluded_round(const rx_world_t *w, ex_v3_t o, ex_v3_t d, double tmax, unsigned skip_geom, double skip_t)
{
    rx__occ_ctx_t c;
    struct RTCRay r;
    memset(&r, 0, sizeof r);
    rtcInitIntersectContext(&c.skip.ctx);
    c.skip.ctx.filter = rx__occlude_filter;
    c.w = w;
    c.skip.skip_geom = skip_geom;
    c.skip.skip_t = (float)skip_t;
    c.o[0] = o.x; c.o[1] = o.y; c.o[2] = o.z;
    c.d[0] = d.x; c.d[1] = d.y; c.d[2] = d.z;
    c.tmax = tmax;
    rx__rtc_ray(&r, o, d, 0, tmax);
    rtcOccluded1(w->rtc, &c.skip.ctx, &r);
    return r.tfar < 0;
}

/* Secondary rays from a rounded hit (protocol step 4). The shared path
   tracer (examples/common) picks a ray's direction after shading and starts
   it at the hit point pushed out along the normal, so it cannot ask for
   re_secondary_origin() itself. Each render thread therefore remembers the
   last rounded hit its intersect callback returned; a ray starting there
   (the shadow rays and the bounce ray of that path vertex) hides its own
   object up to I'', where it leaves the sharp mesh, and needs no second
   trace and no reversed query. Other surfaces in the removed volume (a floor
   under a resting cube's rounded edge) are still found. */
#ifdef __cplusplus
#define RX_THREAD_LOCAL thread_local
#else
#define RX_THREAD_LOCAL _Thread_local
#endif
typedef struct rx__spawn_t {
    const rx_world_t *w; /* NULL: the last hit was not on a rounding */
    unsigned geom;
    re_hit_t hit;
    /* the last hit on a rounded glass object (ex_material_t.ior > 0), flat
       or rounded: a ray that starts there and goes into the object
       (refracted) starts inside it */
    const rx_world_t *in_w; /* NULL: none */
    unsigned in_geom;
    ex_v3_t in_p, in_n; /* point, outward normal */
} rx__spawn_t;
static RX_THREAD_LOCAL rx__spawn_t rx__spawn;

/* When ray (o, d) starts at this thread's last rounded hit: *skip_geom and
   *skip_t to hide that object's sharp mesh up to where the ray leaves it. */
static void rx__spawn_skip(const rx_world_t *w, ex_v3_t o, ex_v3_t d, unsigned *skip_geom, double *skip_t)
{
    const rx__spawn_t *sp = &rx__spawn;
    ex_v3_t p, e;
    double dir[3], org[3], t, tol;
    *skip_geom = RTC_INVALID_GEOMETRY_ID;
    *skip_t = 0;
    if (sp->w != w) return;
    tol = 1e-4 * w->scene->scale;
    p = ex_v3(sp->hit.point[0], sp->hit.point[1], sp->hit.point[2]);
    if (ex_dot(ex_sub(o, p), ex_sub(o, p)) > tol * tol) return;
    /* a ray into the solid (refracted) hides nothing: its next hit is the
       face it leaves by, from inside (rx__trace asks re_query_exit_uv) */
    if (d.x * sp->hit.normal[0] + d.y * sp->hit.normal[1] + d.z * sp->hit.normal[2] <= 0) return;
    dir[0] = d.x; dir[1] = d.y; dir[2] = d.z;
    re_secondary_origin(w->round, &sp->hit, dir, org);
    e = ex_sub(ex_v3(org[0], org[1], org[2]), o);
    t = ex_dot(e, d) / ex_dot(d, d);
    if (!(t > 0)) return;
    *skip_geom = sp->geom;
    *skip_t = rx__next_t(w, t);
}

/* The closest hit of the mode's surface along ray, (0, tmax), hiding
   geometry skip_geom0's hits up to skip_t0 (RTC_INVALID_GEOMETRY_ID: none).
   *chamfer is set when the rounding (or bevel, or tessellated rounding)
   changed it; *rounded (when not NULL) gets the rounded hit, if that is
   what it returns, and *geom the geometry it returns. */
static int rx__trace(rx_world_t *w, const ex_ray_t *ray, double tmax, unsigned skip_geom0, double skip_t0, ex_surface_t *s,
                     int *chamfer_out, re_hit_t *rounded, unsigned *geom)
{
    const rx_scene_t *sc = w->scene;
    double tnear = 0, skip_t = skip_t0;
    unsigned skip_geom = skip_geom0;
    int chamfer = 0;
    int iter, found = 0;
    for (iter = 0; iter < 64; iter++) {
        ex_hit_t h = rx__intersect_skip(w, ray->o, ray->d, tnear, tmax, skip_geom, skip_t);
        const rx_object_t *ob;
        int front;
        if (!h.hit) break;
        ob = &sc->obj[h.geom_id];
        front = ex_dot(h.ng, ray->d) < 0;
        rx__surface_from_hit(w, ray, &h, s);
        found = 1;
        if (geom) *geom = h.geom_id;
        if (!(ob->radius > 0)) break;
        if (w->mode.kind == RX_ROUNDED) {
            double o[3], d[3];
            re_hit_t q;
            re_hit_kind_t k;
            o[0] = ray->o.x; o[1] = ray->o.y; o[2] = ray->o.z;
            d[0] = ray->d.x; d[1] = ray->d.y; d[2] = ray->d.z;
            if (!front) {
                /* The ray leaves object k's sharp mesh from inside: it started
                   inside the solid (a camera or bounce ray in the Cornell
                   room, a refracted ray in glass) or in the removed volume (a
                   secondary ray from a rounded hit, whose origin is I' pushed
                   out along the rounded normal, or a ray from another surface
                   lying under a chamfer, such as the floor under a cube's
                   rounded bottom edge). re_query_exit_uv
                   asks about the ray reversed at this exit face: if the
                   segment meets the rounded solid (through its rounding or
                   its flat face) it says where it leaves it; otherwise the
                   exit is the paper's I'' and we go on. */
                k = re_query_exit_uv(w->round, o, d, (unsigned)w->re_object[h.geom_id], h.prim_id, h.t, h.u, h.v, &q);
                if (k == RE_UNCHANGED) break; /* through the flat face: the solid blocks it here */
                if (k == RE_HIT_ROUNDED) {
                    /* where the ray leaves the rounded solid: the Cornell
                       room's rounded seams seen from inside, a ray born under
                       a chamfer; exact for visibility (shadow rays) */
                    chamfer = 1;
                    rx__surface_from_answer(w, h.geom_id, &q, s);
                    break;
                }
                found = 0;
                if (skip_geom != RTC_INVALID_GEOMETRY_ID) tnear = skip_t; /* earlier skips are behind */
                skip_geom = h.geom_id;
                skip_t = rx__next_t(w, h.t);
                continue;
            }
            /* Embree's barycentrics let the query recognise the flat part
               of a face from three per-triangle bands (query step 0) */
            k = re_query_uv(w->round, o, d, (unsigned)w->re_object[h.geom_id], h.prim_id, h.t, h.u, h.v, &q);
            if (k == RE_HIT_ROUNDED) {
                chamfer = 1;
                if (rounded) *rounded = q;
                rx__surface_from_answer(w, h.geom_id, &q, s);
                break;
            }
            if (k == RE_PASS_THROUGH) {
                chamfer = 1;
                found = 0;
                if (skip_geom != RTC_INVALID_GEOMETRY_ID) tnear = skip_t;
                skip_geom = h.geom_id;
                skip_t = rx__next_t(w, q.t);
                continue;
            }
            break;
        }
        /* the bevels take the outward normal from either side: seen from
           inside a solid (the Cornell room) they probe its faces from
           within, as a bevel node does on any surface it shades */
        if (w->mode.kind == RX_BLOG || w->mode.kind == RX_CYCLES) {
            double p[3], n[3];
            re_bevel_result_t b;
            re_result_t rc;
            p[0] = s->p.x; p[1] = s->p.y; p[2] = s->p.z;
            n[0] = h.ng.x; n[1] = h.ng.y; n[2] = h.ng.z;
            if (w->mode.kind == RX_BLOG) {
                re_bevel_blog_desc_t bd;
                memset(&bd, 0, sizeof bd);
                bd.delta = ob->radius;
                bd.rays = w->mode.n;
                bd.seed = rx__ray_seed(ray);
                rc = re_bevel_blog(&bd, p, n, rx__bevel_trace, w, &b);
            } else {
                re_bevel_cycles_desc_t cd;
                memset(&cd, 0, sizeof cd);
                cd.radius = ob->radius;
                cd.samples = w->mode.n;
                cd.seed = rx__ray_seed(ray);
                cd.trace_object = rx__bevel_trace_object; /* P's object alone, as Cycles */
                rc = re_bevel_cycles(&cd, p, n, h.geom_id, rx__bevel_trace, w, &b);
            }
            if (rc == RE_OK) {
                ex_v3_t bn = ex_v3(b.normal[0], b.normal[1], b.normal[2]);
                if (ex_dot(bn, h.ng) < 1 - 1e-12) chamfer = 1;
                s->n = bn;
            }
        }
        if (w->mode.kind == RX_TESS && h.prim_id >= w->tess_first_round[h.geom_id]) chamfer = 1;
        break;
    }
    *chamfer_out = chamfer;
    return found;
}

/* The rounded object ray starts inside (refracted into it at this thread's
   last hit), or RTC_INVALID_GEOMETRY_ID. */
static unsigned rx__inside(const rx_world_t *w, const ex_ray_t *ray)
{
    const rx__spawn_t *sp = &rx__spawn;
    double tol = 1e-4 * w->scene->scale;
    ex_v3_t e;
    if (sp->in_w != w) return RTC_INVALID_GEOMETRY_ID;
    e = ex_sub(ray->o, sp->in_p);
    if (ex_dot(e, e) > tol * tol || ex_dot(ray->d, sp->in_n) >= 0) return RTC_INVALID_GEOMETRY_ID;
    return sp->in_geom;
}

/* Embree context that sees one geometry only (rx__exit_first). */
typedef struct rx__only_ctx_t {
    struct RTCIntersectContext ctx; /* first: Embree passes its address to the filter */
    unsigned geom;
} rx__only_ctx_t;
static void rx__only_filter(const struct RTCFilterFunctionNArguments *args)
{
    const rx__only_ctx_t *c = (const rx__only_ctx_t *)args->context;
    const unsigned *geom = (const unsigned *)args->hit + 6 * args->N; /* as rx__skip_filter */
    unsigned i;
    for (i = 0; i < args->N; i++)
        if (args->valid[i] == -1 && geom[i] != c->geom) args->valid[i] = 0;
}

/* rx__bevel_trace on one object only (re_bevel_cycles_desc_t.trace_object):
   a box resting on the floor has its bottom face where the floor is, and the
   any-object trace found the floor there (found by review, 2026-12-06). */
static int rx__bevel_trace_object(void *user, unsigned object, const double o[3], const double d[3], double tmin,
                                  double tmax, re_trace_hit_t *hit)
{
    const rx_world_t *w = (const rx_world_t *)user;
    rx__only_ctx_t c;
    rtcInitIntersectContext(&c.ctx);
    c.ctx.filter = rx__only_filter;
    c.geom = object;
    return rx__bevel_hit(rx__intersect_in(w, &c.ctx, ex_v3(o[0], o[1], o[2]), ex_v3(d[0], d[1], d[2]), tmin, tmax), hit);
}

/* A ray inside rounded object g leaves its rounded solid before it meets
   anything else, but a surface lying in the removed volume under a
   rounding (the floor under a resting glass cube's bottom edge) comes
   before g's exit face, so the trace found it without asking the exit
   query. Trace g alone to just past that hit; where the ray leaves g there
   and re_query_exit_uv puts the exit on a rounding first, the exit becomes
   the hit (returns 1). */
static int rx__exit_first(const rx_world_t *w, const ex_ray_t *ray, unsigned g, ex_surface_t *s, int *chamfer)
{
    rx__only_ctx_t c;
    ex_hit_t h;
    double o[3], d[3];
    re_hit_t q;
    rtcInitIntersectContext(&c.ctx);
    c.ctx.filter = rx__only_filter;
    c.geom = g;
    h = rx__intersect_in(w, &c.ctx, ray->o, ray->d, 0, rx__next_t(w, s->t));
    if (!h.hit || ex_dot(h.ng, ray->d) <= 0) return 0; /* no hit, or not leaving g */
    o[0] = ray->o.x; o[1] = ray->o.y; o[2] = ray->o.z;
    d[0] = ray->d.x; d[1] = ray->d.y; d[2] = ray->d.z;
    if (re_query_exit_uv(w->round, o, d, (unsigned)w->re_object[g], h.prim_id, h.t, h.u, h.v, &q) != RE_HIT_ROUNDED ||
        !(q.t < s->t))
        return 0;
    rx__surface_from_answer(w, g, &q, s);
    *chamfer = 1;
    return 1;
}

/* Glass (ex_material_t.ior > 0), rounded mode, after the trace: a ray that
   started inside a rounded glass object leaves it first (rx__exit_first);
   then this hit is remembered if it is on one. Out of line: scenes without
   glass never call it (rx_world_t.glass), and keep rx__intersect lean. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void rx__glass_hit(const rx_world_t *w, const ex_ray_t *ray, int found, unsigned *geom, ex_surface_t *s, int *chamfer,
                          re_hit_t *q)
{
    unsigned inside = rx__inside(w, ray);
    if (found && inside != RTC_INVALID_GEOMETRY_ID && *geom != inside && rx__exit_first(w, ray, inside, s, chamfer))
        *geom = inside, q->kind = RE_UNCHANGED; /* an exit: nothing for rx__spawn_skip to hide */
    rx__spawn.in_w = found && w->scene->obj[*geom].radius > 0 && s->mat->ior > 0 ? w : NULL;
    if (rx__spawn.in_w) rx__spawn.in_geom = *geom, rx__spawn.in_p = s->p, rx__spawn.in_n = s->ng;
}

static int rx__intersect(void *user, const ex_ray_t *ray, double tmax, ex_surface_t *s)
{
    rx_world_t *w = (rx_world_t *)user;
    unsigned skip_geom = RTC_INVALID_GEOMETRY_ID;
    double skip_t = 0;
    re_hit_t q;
    unsigned geom = 0;
    int chamfer, found;
    if (w->mode.kind == RX_ROUNDED && rx__spawn.w) rx__spawn_skip(w, ray->o, ray->d, &skip_geom, &skip_t);
    q.kind = RE_UNCHANGED;
    found = rx__trace(w, ray, tmax, skip_geom, skip_t, s, &chamfer, &q, &geom);
    if (w->mode.kind == RX_ROUNDED) {
        if (w->glass) rx__glass_hit(w, ray, found, &geom, s, &chamfer, &q);
        rx__spawn.w = found && q.kind == RE_HIT_ROUNDED ? w : NULL;
        if (rx__spawn.w) rx__spawn.geom = geom, rx__spawn.hit = q;
    }
    __atomic_fetch_add(&w->rays, 1, __ATOMIC_RELAXED);
    if (chamfer) __atomic_fetch_add(&w->chamfer_rays, 1, __ATOMIC_RELAXED);
    return found;
}

static int rx__occluded(void *user, ex_v3_t o, ex_v3_t d, double tmax)
{
    rx_world_t *w = (rx_world_t *)user;
    unsigned skip_geom = RTC_INVALID_GEOMETRY_ID;
    double skip_t = 0;
    if (w->mode.kind != RX_ROUNDED) return ex_embree_occluded(w->rtc, o, d, 0, tmax);
    if (rx__spawn.w) rx__spawn_skip(w, o, d, &skip_geom, &skip_t);
    return rx__occluded_round(w, o, d, tmax, skip_geom, skip_t);
}

static void rx__pixel(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3])
{
    rx_world_t *w = (rx_world_t *)user;
    ex_ray_t ray = ex_camera_ray(&w->cam, x + ex_rng_unit(rng), y + ex_rng_unit(rng));
    ex_v3_t L = ex_radiance(&w->shade, &ray, rng);
    (void)sample;
    rgb[0] = (float)L.x; rgb[1] = (float)L.y; rgb[2] = (float)L.z;
}

double rx_world_render(rx_world_t *w, int spp, int threads, unsigned long long seed, int quiet, float *rgb)
{
    ex_render_desc_t d;
    double t0;
    char name[64];
    memset(&w->shade, 0, sizeof w->shade);
    w->shade.intersect = rx__intersect;
    w->shade.occluded = rx__occluded;
    w->shade.user = w;
    w->shade.lights = w->scene->lights;
    w->shade.nlights = w->scene->nlights;
    w->shade.env = w->scene->env;
    w->shade.max_bounces = 3;
    w->shade.ray_eps = 1e-5 * w->scene->scale;
    memset(&d, 0, sizeof d);
    d.width = w->cam.width;
    d.height = w->cam.height;
    d.spp = spp;
    d.threads = threads;
    d.seed = seed;
    d.label = rx_mode_name(w->mode, name, sizeof name);
    d.quiet = quiet;
    w->rays = w->chamfer_rays = 0;
    t0 = ex_now();
    if (ex_render(&d, rx__pixel, w, rgb)) return -1;
    return ex_now() - t0;
}

#endif /* RX_RENDER_IMPLEMENTATION_DONE */
#endif /* RX_RENDER_IMPLEMENTATION */
