/* tests/test_rounded_embree.c — rounded_edges.h with a real host tracer:
   Embree 3 traces the sharp meshes (float), re_query() runs from two threads
   at once on one scene, following the integration protocol (pass-through:
   trace on from h.t). Oracle: sphere tracing of the union of the analytic
   rounded boxes. */
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include <embree3/rtcore.h>
#include <pthread.h>

#define NBOX 12
typedef struct world_t {
    double lo[NBOX][3], hi[NBOX][3], r[NBOX];
    RTCScene rtc;
    re_scene_t *re;
} world_t;

static double world_sdf(const void *ctx, const double p[3])
{
    const world_t *w = (const world_t *)ctx;
    double best = HUGE_VAL, c[3], h[3];
    int b, a;
    for (b = 0; b < NBOX; b++) {
        for (a = 0; a < 3; a++) c[a] = 0.5 * (w->lo[b][a] + w->hi[b][a]), h[a] = 0.5 * (w->hi[b][a] - w->lo[b][a]);
        best = fmin(best, tm_rbox_sdf(c, h, w->r[b], p));
    }
    return best;
}

typedef struct job_t {
    const world_t *w;
    const double (*o)[3], (*d)[3];
    long first, count;
    double *t;    /* final t, HUGE_VAL for a miss */
    int *kind;    /* kind of the last query */
    int *queries; /* queries made (pass-throughs continue) */
} job_t;

/* the host loop of the integration protocol */
static void *trace_job(void *arg)
{
    job_t *j = (job_t *)arg;
    long i;
    for (i = j->first; i < j->first + j->count; i++) {
        double tnear = 0;
        int q;
        j->t[i] = HUGE_VAL, j->kind[i] = -1, j->queries[i] = 0;
        for (q = 0; q < 8; q++) {
            struct RTCIntersectContext ctx;
            struct RTCRayHit rh;
            re_hit_t h;
            double ng;
            rtcInitIntersectContext(&ctx);
            memset(&rh, 0, sizeof rh);
            rh.ray.org_x = (float)j->o[i][0], rh.ray.org_y = (float)j->o[i][1], rh.ray.org_z = (float)j->o[i][2];
            rh.ray.dir_x = (float)j->d[i][0], rh.ray.dir_y = (float)j->d[i][1], rh.ray.dir_z = (float)j->d[i][2];
            rh.ray.tnear = (float)tnear, rh.ray.tfar = INFINITY, rh.ray.mask = 0xFFFFFFFFu;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(j->w->rtc, &ctx, &rh);
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
            ng = rh.hit.Ng_x * j->d[i][0] + rh.hit.Ng_y * j->d[i][1] + rh.hit.Ng_z * j->d[i][2];
            if (ng >= 0) { tnear = rh.ray.tfar * (1 + 1e-6); continue; } /* back face: the exit of a pass-through */
            j->queries[i]++;
            re_query(j->w->re, j->o[i], j->d[i], rh.hit.geomID, rh.hit.primID, rh.ray.tfar, &h);
            j->kind[i] = (int)h.kind;
            if (h.kind != RE_PASS_THROUGH) { j->t[i] = h.t; break; }
            tnear = h.t * (1 + 1e-6);
        }
    }
    return NULL;
}

static void embree_host_two_threads(void)
{
    static world_t w;
    tm_mesh_t m[NBOX];
    re_mesh_t meshes[NBOX];
    re_scene_desc_t desc;
    re_diag_t dg;
    RTCDevice dev = rtcNewDevice(NULL);
    float *vb[NBOX];
    t_rng_t rng = {77};
    long n = t_count(40000), i, n_round = 0, n_pass = 0, bad = 0;
    double (*o)[3] = (double(*)[3])malloc(sizeof(double) * 3 * n), (*d)[3] = (double(*)[3])malloc(sizeof(double) * 3 * n);
    double *t = (double *)malloc(sizeof(double) * n);
    int *kind = (int *)malloc(sizeof(int) * n), *queries = (int *)malloc(sizeof(int) * n);
    pthread_t th[2];
    job_t jobs[2];
    int b, a;
    unsigned k;
    w.rtc = rtcNewScene(dev);
    memset(&desc, 0, sizeof desc);
    for (b = 0; b < NBOX; b++) {
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        unsigned *ib;
        memset(&m[b], 0, sizeof m[b]);
        for (a = 0; a < 3; a++) { /* float-exact coordinates: multiples of 1/64 */
            double c = (double)(b % 4) * 1.5 * (a == 0) + (double)(b / 4) * 1.5 * (a == 1);
            double h = (double)(16 + (int)(t_rng_u64(&rng) % 24)) / 64.0;
            w.lo[b][a] = c - h, w.hi[b][a] = c + h;
        }
        w.r[b] = 0.02 + 0.01 * (b % 3);
        tm_box(&m[b], w.lo[b], w.hi[b]);
        vb[b] = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m[b].nv);
        for (k = 0; k < 3 * m[b].nv; k++) vb[b][k] = (float)m[b].v[k];
        ib = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m[b].ni / 3);
        memcpy(ib, m[b].idx, sizeof(unsigned) * m[b].ni);
        rtcCommitGeometry(g);
        T_INT_EQ(rtcAttachGeometry(w.rtc, g), (unsigned)b);
        rtcReleaseGeometry(g);
        memset(&meshes[b], 0, sizeof meshes[b]);
        meshes[b].positions = vb[b], meshes[b].position_type = RE_FLOAT32, meshes[b].vertex_count = m[b].nv;
        meshes[b].indices = m[b].idx, meshes[b].index_count = m[b].ni, meshes[b].radius = w.r[b];
    }
    rtcCommitScene(w.rtc);
    desc.objects = meshes, desc.object_count = NBOX;
    if (!T_INT_EQ(re_build(&desc, &w.re, &dg), RE_OK)) return;
    for (i = 0; i < n; i++) {
        const double *lo = w.lo[t_rng_u64(&rng) % NBOX];
        double tgt[3], u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), s = sqrt(1 - v * v);
        for (a = 0; a < 3; a++) tgt[a] = lo[a] + (t_rng_unit(&rng) < 0.5 ? 0.03 : 0.5) * t_rng_unit(&rng);
        o[i][0] = tgt[0] + 8 * s * cos(u), o[i][1] = tgt[1] + 8 * s * sin(u), o[i][2] = tgt[2] + 8 * v;
        tm_sub(tgt, o[i], d[i]);
    }
    for (a = 0; a < 2; a++) {
        jobs[a].w = &w, jobs[a].o = (const double(*)[3])o, jobs[a].d = (const double(*)[3])d;
        jobs[a].first = a * (n / 2), jobs[a].count = a ? n - n / 2 : n / 2;
        jobs[a].t = t, jobs[a].kind = kind, jobs[a].queries = queries;
        pthread_create(&th[a], NULL, trace_job, &jobs[a]);
    }
    for (a = 0; a < 2; a++) pthread_join(th[a], NULL);
    for (i = 0; i < n; i++) {
        double ref = tm_trace(world_sdf, &w, o[i], d[i], 10.0, 1.0), tol;
        /* rounded hits are computed in double from the host's ray, whatever
           the host's float t; flat hits carry Embree's float t */
        tol = kind[i] == RE_HIT_ROUNDED ? 1e-9 * tm_len(d[i]) : 1e-5;
        if (kind[i] == RE_HIT_ROUNDED) n_round++;
        if (queries[i] > 1) n_pass++;
        if (!((t[i] == HUGE_VAL && ref == HUGE_VAL) || fabs(t[i] - ref) * tm_len(d[i]) <= tol * tm_len(d[i]))) {
            if (bad++ < 5) T_FAIL("ray %ld: kind %d after %d queries, t %.17g, reference %.17g", i, kind[i], queries[i], t[i], ref);
        }
    }
    T_INT_EQ(bad, 0);
    T_GT(n_round, n / 10);
    T_GT(n_pass, 0); /* some rays passed through a removed edge and hit on */
    re_free(w.re);
    rtcReleaseScene(w.rtc);
    rtcReleaseDevice(dev);
    for (b = 0; b < NBOX; b++) tm_free(&m[b]);
    free(o), free(d), free(t), free(kind), free(queries);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {T_CASE(embree_host_two_threads)};
    return T_RUN(argc, argv, cases);
}
