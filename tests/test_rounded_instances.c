/* tests/test_rounded_instances.c — rounded_edges.h under instancing: one
   re_scene object per prototype mesh, placed many times by Embree 3
   instances (rotations, uniform and non-uniform scales, a mirror). The host
   follows docs/rounded_edges.md, "Walk-through", step 7: it queries in
   the prototype's space with the ray mapped there in double, and maps the
   answer back (point by the instance's affine map, normal by its inverse
   transpose). Oracles, per instance in the prototype's space: the analytic
   rounded box, and sphere tracing of the eroded polytope minus r for a
   random convex hull; the hit is the nearest over the instances. */
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include <embree3/rtcore.h>

#define NPROTO 2
#define NXFM 5
#define NINST (NPROTO * NXFM)

/* world = A object + T; row-major A, as Embree's RTC_FORMAT_FLOAT3X4_ROW_MAJOR */
typedef struct xfm_t {
    double A[3][3], T[3];
    double Ai[3][3]; /* the inverse, in double by the host */
} xfm_t;

typedef struct proto_t {
    tm_mesh_t mesh;
    float *fv; /* the positions both Embree and the build read */
    tm_poly_t *poly; /* hull planes (prototype 1) */
    tm_eroded_t eroded;
    double lo[3], hi[3], r, size, bound; /* bound: radius of a ball about the origin holding it */
} proto_t;

static void xfm_apply(const double M[3][3], const double x[3], double y[3])
{
    int i;
    for (i = 0; i < 3; i++) y[i] = M[i][0] * x[0] + M[i][1] * x[1] + M[i][2] * x[2];
}
/* the inverse transpose applied to a normal: n_world = Ai^T n */
static void xfm_normal(const xfm_t *X, const double n[3], double out[3])
{
    int i;
    for (i = 0; i < 3; i++) out[i] = X->Ai[0][i] * n[0] + X->Ai[1][i] * n[1] + X->Ai[2][i] * n[2];
    tm_norm(out);
}
static void xfm_to_object(const xfm_t *X, const double o[3], const double d[3], double oo[3], double od[3])
{
    double q[3];
    tm_sub(o, X->T, q);
    xfm_apply(X->Ai, q, oo);
    xfm_apply(X->Ai, d, od);
}
static void xfm_point_to_world(const xfm_t *X, const double p[3], double w[3])
{
    xfm_apply(X->A, p, w);
    w[0] += X->T[0], w[1] += X->T[1], w[2] += X->T[2];
}

/* the largest stretch of the map (its Frobenius norm bounds it) */
static double inst_size(const xfm_t *X)
{
    double s = 0;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) s += X->A[i][j] * X->A[i][j];
    return sqrt(s);
}
/* |A^-1 d|: lengths along the ray in the prototype's space per unit t */
static double obj_len(const xfm_t *X, const double d[3])
{
    double od[3];
    xfm_apply(X->Ai, d, od);
    return tm_len(od);
}
/* does the ray (prototype space) pass within `R` of the prototype's origin? */
static int ray_near_ball(const double o[3], const double d[3], double R)
{
    double t = -tm_dot(o, d) / tm_dot(d, d), q[3];
    if (t < 0) t = 0;
    q[0] = o[0] + t * d[0], q[1] = o[1] + t * d[1], q[2] = o[2] + t * d[2];
    return tm_dot(q, q) <= R * R;
}

/* Ai from A, by cofactors */
static void xfm_invert(xfm_t *X)
{
    double det;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            X->Ai[j][i] = X->A[i1][j1] * X->A[i2][j2] - X->A[i1][j2] * X->A[i2][j1];
        }
    det = X->A[0][0] * X->Ai[0][0] + X->A[0][1] * X->Ai[1][0] + X->A[0][2] * X->Ai[2][0];
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) X->Ai[i][j] /= det;
}

/* A = R (rotation by `angle` about `axis`) * S (diagonal `scale`), then
   the x axis negated when `mirror` (Ai is left to xfm_invert) */
static void xfm_make(xfm_t *X, const double axis_in[3], double angle, const double scale[3], int mirror, const double T[3])
{
    double a[3] = {axis_in[0], axis_in[1], axis_in[2]}, c = cos(angle), s = sin(angle), R[3][3];
    int i, j;
    tm_norm(a);
    R[0][0] = c + a[0] * a[0] * (1 - c), R[0][1] = a[0] * a[1] * (1 - c) - a[2] * s, R[0][2] = a[0] * a[2] * (1 - c) + a[1] * s;
    R[1][0] = a[1] * a[0] * (1 - c) + a[2] * s, R[1][1] = c + a[1] * a[1] * (1 - c), R[1][2] = a[1] * a[2] * (1 - c) - a[0] * s;
    R[2][0] = a[2] * a[0] * (1 - c) - a[1] * s, R[2][1] = a[2] * a[1] * (1 - c) + a[0] * s, R[2][2] = c + a[2] * a[2] * (1 - c);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) X->A[i][j] = R[i][j] * scale[j] * (mirror && i == 0 ? -1 : 1);
    for (i = 0; i < 3; i++) X->T[i] = T[i];
}

static double proto_sdf(const proto_t *P, int k, const double p[3])
{
    double c[3], h[3];
    int a;
    if (k == 1) return tm_eroded_sdf(&P->eroded, p);
    for (a = 0; a < 3; a++) c[a] = 0.5 * (P->lo[a] + P->hi[a]), h[a] = 0.5 * (P->hi[a] - P->lo[a]);
    return tm_rbox_sdf(c, h, P->r, p);
}
static double sdf_box(const void *ctx, const double p[3]) { return proto_sdf((const proto_t *)ctx, 0, p); }
static double sdf_hull(const void *ctx, const double p[3]) { return proto_sdf((const proto_t *)ctx, 1, p); }

/* the outward normal of the oracle surface at p, in the prototype's space:
   the box's analytic one, the hull's by central differences */
static void proto_normal(const proto_t *P, int k, const double p[3], double n[3])
{
    double c[3], h[3], e = 1e-7 * P->size, q[3];
    int a;
    if (k == 0) {
        for (a = 0; a < 3; a++) c[a] = 0.5 * (P->lo[a] + P->hi[a]), h[a] = 0.5 * (P->hi[a] - P->lo[a]);
        tm_rbox_normal(c, h, P->r, p, n);
        return;
    }
    for (a = 0; a < 3; a++) {
        double f1, f0;
        memcpy(q, p, sizeof q), q[a] += e, f1 = proto_sdf(P, k, q);
        memcpy(q, p, sizeof q), q[a] -= e, f0 = proto_sdf(P, k, q);
        n[a] = f1 - f0;
    }
    tm_norm(n);
}

static void make_protos(proto_t *P, tm_poly_t *poly)
{
    t_rng_t rng = {4242};
    double pts[24][3];
    float fpts[24][3];
    unsigned k;
    int i;
    /* prototype 0: a box with float-exact corners */
    memset(P, 0, NPROTO * sizeof *P);
    P[0].lo[0] = -0.5, P[0].lo[1] = -0.3125, P[0].lo[2] = -0.40625;
    P[0].hi[0] = 0.5, P[0].hi[1] = 0.3125, P[0].hi[2] = 0.40625;
    tm_box(&P[0].mesh, P[0].lo, P[0].hi);
    P[0].r = 0.0625, P[0].size = 1, P[0].bound = 0.75;
    /* prototype 1: the hull of 24 float points on a jittered sphere
       (vertices of degree 3 to 8; the planes from the float positions) */
    for (i = 0; i < 24; i++) {
        double u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v), R = t_rng_range(&rng, 0.45, 0.55);
        /* through a float array: gcc 12.2 -O2's SLP vectorizer dropped the
           rounding of (double)(float)(R w cos u) written in one line */
        fpts[i][0] = (float)(R * w * cos(u)), fpts[i][1] = (float)(R * w * sin(u)), fpts[i][2] = (float)(R * v);
    }
    for (i = 0; i < 24; i++) pts[i][0] = fpts[i][0], pts[i][1] = fpts[i][1], pts[i][2] = fpts[i][2];
    tm_hull((const double(*)[3])pts, 24, &P[1].mesh, poly);
    P[1].poly = poly, P[1].r = 0.05, P[1].size = 1, P[1].bound = 0.6;
    for (i = 0; i < NPROTO; i++) {
        P[i].fv = (float *)malloc(sizeof(float) * 3 * P[i].mesh.nv);
        for (k = 0; k < 3 * P[i].mesh.nv; k++) P[i].fv[k] = (float)P[i].mesh.v[k];
    }
}

/* ten instances: each prototype under five maps, 4 apart along x and y */
static void make_xfms(xfm_t *X)
{
    static const double axes[NXFM][3] = {{0, 0, 1}, {1, 2, 3}, {-2, 1, 0.5}, {0.3, -1, 2}, {1, 1, -1}};
    static const double angles[NXFM] = {0, 0.7, 2.1, -1.3, 0.4};
    static const double scales[NXFM][3] = {{1, 1, 1}, {1, 1, 1}, {2.5, 2.5, 2.5}, {1, 1, 1}, {1, 2, 0.5}};
    static const int mirror[NXFM] = {0, 0, 0, 1, 0};
    int p, k;
    for (p = 0; p < NPROTO; p++)
        for (k = 0; k < NXFM; k++) {
            double T[3] = {4.0 * k, 4.0 * p, 0.5 * k};
            xfm_make(&X[p * NXFM + k], axes[k], angles[k], scales[k], mirror[k], T);
        }
}

static int inside_a_bound(const proto_t *P, const xfm_t *X, const double o[3])
{
    int k;
    for (k = 0; k < NINST; k++) {
        double q[3];
        tm_sub(o, X[k].T, q);
        if (tm_len(q) <= P[k / NXFM].bound * inst_size(&X[k])) return 1;
    }
    return 0;
}

/* How far x lies outside the sharp prototype (its largest plane excess;
   the planes' normals are unit), and the sine between d and that plane. */
static double outside_sharp(const proto_t *P, int k, const double x[3], const double d[3], double *sin_exit)
{
    double best = -HUGE_VAL, n[3] = {0, 0, 0};
    int g, a;
    if (k == 0) {
        for (a = 0; a < 3; a++) {
            double e = fabs(x[a]) - P->hi[a]; /* the box is centred */
            if (e > best) best = e, n[0] = n[1] = n[2] = 0, n[a] = x[a] > 0 ? 1 : -1;
        }
    } else {
        for (g = 0; g < P->poly->np; g++) {
            double e = tm_dot(P->poly->n[g], x) - P->poly->c[g];
            if (e > best) best = e, memcpy(n, P->poly->n[g], sizeof n);
        }
    }
    *sin_exit = tm_dot(n, d) / tm_len(d);
    return best;
}

/* Embree's closest hit of the world ray (o, d) from tnear */
static void world_hit(RTCScene top, const double o[3], const double d[3], float tnear, struct RTCRayHit *rh)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    memset(rh, 0, sizeof *rh);
    rh->ray.org_x = (float)o[0], rh->ray.org_y = (float)o[1], rh->ray.org_z = (float)o[2];
    rh->ray.dir_x = (float)d[0], rh->ray.dir_y = (float)d[1], rh->ray.dir_z = (float)d[2];
    rh->ray.tnear = tnear, rh->ray.tfar = INFINITY, rh->ray.mask = 0xFFFFFFFFu;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID, rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top, &ctx, rh);
}

/* Does the world ray (o, d) meet instance `inst` beyond t_skip? (Its own
   hits up to t_skip are stepped over, as the host's skip filter would.) */
static int own_hit_beyond(RTCScene top, const double o[3], const double d[3], int inst, double t_skip)
{
    float tnear = 0;
    int q;
    for (q = 0; q < 4; q++) {
        struct RTCRayHit rh;
        world_hit(top, o, d, tnear, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || (int)rh.hit.instID[0] != inst) return 0;
        if (rh.ray.tfar > t_skip) return 1;
        tnear = rh.ray.tfar * 1.0000001f;
    }
    return 0;
}

typedef struct answer_t {
    int inst, kind, queries;
    double t, n[3], p[3];
    re_hit_t h; /* in the prototype's space */
} answer_t;

/* the host loop of the protocol, instanced */
static void trace_instanced(RTCScene top, const re_scene_t *rs, const xfm_t *X, const double o[3], const double d[3],
                            int use_uv, answer_t *ans)
{
    double tnear = 0;
    int q;
    ans->inst = -1, ans->kind = -1, ans->queries = 0, ans->t = HUGE_VAL;
    for (q = 0; q < 8; q++) {
        struct RTCRayHit rh;
        double oo[3], od[3], ng;
        const xfm_t *x;
        unsigned inst, proto;
        world_hit(top, o, d, (float)tnear, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
        inst = rh.hit.instID[0], proto = inst / NXFM, x = &X[inst];
        xfm_to_object(x, o, d, oo, od);
        /* Embree's Ng is in the prototype's space: compare it with the
           prototype-space direction (a mirror flips the world one) */
        ng = rh.hit.Ng_x * od[0] + rh.hit.Ng_y * od[1] + rh.hit.Ng_z * od[2];
        if (ng >= 0) { tnear = rh.ray.tfar * (1 + 1e-6); continue; }
        ans->queries++;
        if (use_uv) re_query_uv(rs, oo, od, proto, rh.hit.primID, rh.ray.tfar, rh.hit.u, rh.hit.v, &ans->h);
        else re_query(rs, oo, od, proto, rh.hit.primID, rh.ray.tfar, &ans->h);
        ans->kind = (int)ans->h.kind, ans->inst = (int)inst;
        if (ans->h.kind == RE_PASS_THROUGH) { tnear = ans->h.t * (1 + 1e-6); continue; }
        ans->t = ans->h.t; /* t is the same in both spaces: the map is affine */
        xfm_point_to_world(x, ans->h.point, ans->p);
        xfm_normal(x, ans->h.normal, ans->n);
        break;
    }
}

static void instances_match_the_transformed_oracles(void)
{
    static tm_poly_t poly;
    proto_t P[NPROTO];
    xfm_t X[NINST];
    re_mesh_t meshes[NPROTO];
    re_scene_desc_t desc;
    re_scene_t *rs = NULL;
    re_diag_t dg;
    RTCDevice dev = rtcNewDevice(NULL);
    RTCScene top = rtcNewScene(dev), protos[NPROTO];
    t_rng_t rng = {991};
    long n = t_count(20000), i, bad = 0, bad_n = 0, bad_origin = 0, n_round = 0, n_pass = 0, n_sec = 0;
    long round_per_xfm[NXFM] = {0, 0, 0, 0, 0};
    double out_lo = HUGE_VAL, out_hi = -HUGE_VAL;
    int p, k;
    make_protos(P, &poly);
    make_xfms(X);
    for (p = 0; p < NPROTO; p++) { /* the oracles see the positions Embree and the build read */
        unsigned q, off = 0;
        for (q = 0; q < 3 * P[p].mesh.nv; q++) off += P[p].mesh.v[q] != (double)P[p].fv[q];
        T_INT_EQ(off, 0);
    }
    memset(&desc, 0, sizeof desc);
    for (p = 0; p < NPROTO; p++) {
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        float *vb = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), P[p].mesh.nv);
        unsigned *ib = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                           P[p].mesh.ni / 3);
        memcpy(vb, P[p].fv, sizeof(float) * 3 * P[p].mesh.nv);
        memcpy(ib, P[p].mesh.idx, sizeof(unsigned) * P[p].mesh.ni);
        rtcCommitGeometry(g);
        protos[p] = rtcNewScene(dev);
        rtcAttachGeometry(protos[p], g);
        rtcReleaseGeometry(g);
        rtcCommitScene(protos[p]);
        memset(&meshes[p], 0, sizeof meshes[p]);
        meshes[p].positions = P[p].fv, meshes[p].position_type = RE_FLOAT32, meshes[p].vertex_count = P[p].mesh.nv;
        meshes[p].indices = P[p].mesh.idx, meshes[p].index_count = P[p].mesh.ni, meshes[p].radius = P[p].r;
    }
    for (k = 0; k < NINST; k++) {
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
        float m[12];
        int a, b;
        for (a = 0; a < 3; a++) {
            for (b = 0; b < 3; b++) m[4 * a + b] = (float)X[k].A[a][b];
            m[4 * a + 3] = (float)X[k].T[a];
        }
        /* the host's double map is the float one Embree holds, inverted in double */
        for (a = 0; a < 3; a++) {
            for (b = 0; b < 3; b++) X[k].A[a][b] = m[4 * a + b];
            X[k].T[a] = m[4 * a + 3];
        }
        xfm_invert(&X[k]);
        rtcSetGeometryInstancedScene(g, protos[k / NXFM]);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, m);
        rtcCommitGeometry(g);
        T_INT_EQ(rtcAttachGeometry(top, g), (unsigned)k);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(top);
    desc.objects = meshes, desc.object_count = NPROTO;
    if (!T_INT_EQ(re_build(&desc, &rs, &dg), RE_OK)) return;
    for (p = 0; p < NPROTO; p++) {
        P[p].r = re_object_radius(rs, (unsigned)p);
        T_GT(P[p].r, 0.0);
    }
    tm_erode(&poly, P[1].r);
    P[1].eroded.P = &poly, P[1].eroded.r = P[1].r;
    for (i = 0; i < n; i++) {
        int inst = (int)(t_rng_u64(&rng) % NINST), best = -1, a;
        const proto_t *Q = &P[inst / NXFM];
        const double *vx = Q->mesh.v + 3 * (t_rng_u64(&rng) % Q->mesh.nv), *vy = Q->mesh.v + 3 * (t_rng_u64(&rng) % Q->mesh.nv);
        double tgt_o[3], tgt[3], o[3], d[3], u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        double f = i % 2 ? 0 : t_rng_unit(&rng), t_ref = HUGE_VAL, tol;
        answer_t ans;
        /* aim at a vertex or a chord of the prototype, near its rounding */
        for (a = 0; a < 3; a++) tgt_o[a] = vx[a] + f * (vy[a] - vx[a]) + t_rng_range(&rng, -2, 2) * Q->r;
        xfm_point_to_world(&X[inst], tgt_o, tgt);
        o[0] = tgt[0] + 9 * w * cos(u), o[1] = tgt[1] + 9 * w * sin(u), o[2] = tgt[2] + 9 * v;
        tm_sub(tgt, o, d);
        if (inside_a_bound(P, X, o)) { i--; continue; } /* rays start outside every instance */
        trace_instanced(top, rs, X, o, d, (int)(i % 2), &ans);
        for (k = 0; k < NINST; k++) { /* the oracle: nearest instance, each in its own space */
            double oo[3], od[3], tk;
            const proto_t *R = &P[k / NXFM];
            xfm_to_object(&X[k], o, d, oo, od);
            if (!ray_near_ball(oo, od, R->bound)) continue;
            tk = tm_trace(k / NXFM ? sdf_hull : sdf_box, R, oo, od, 3.0, R->size);
            if (tk < t_ref) t_ref = tk, best = k;
        }
        if (ans.kind == RE_HIT_ROUNDED) n_round++, round_per_xfm[ans.inst % NXFM]++;
        if (ans.queries > 1) n_pass++;
        /* rounded hits are computed in double from the host's ray: to 1e-9 of
           the size on the box (exact), 1e-7 on the hull (the bound
           for polyhedra), in the prototype's space; flat hits carry Embree's
           float t (of a ray of length 9..12) */
        tol = ans.kind != RE_HIT_ROUNDED ? 1e-5 : (ans.inst / NXFM ? 1e-7 : 1e-9) / obj_len(&X[ans.inst], d);
        if (!((ans.t == HUGE_VAL && t_ref == HUGE_VAL) || fabs(ans.t - t_ref) <= tol)) {
            if (bad++ < 5) T_FAIL("ray %ld: instance %d kind %d after %d queries, t %.17g, reference %.17g (instance %d)", i, ans.inst,
                                  ans.kind, ans.queries, ans.t, t_ref, best);
            continue;
        }
        if (ans.kind == RE_HIT_ROUNDED) {
            double oo[3], od[3], pr[3], nr[3], nw[3];
            xfm_to_object(&X[best], o, d, oo, od);
            for (a = 0; a < 3; a++) pr[a] = oo[a] + t_ref * od[a];
            proto_normal(&P[best / NXFM], best / NXFM, pr, nr);
            xfm_normal(&X[best], nr, nw);
            if (!(tm_dot(nw, ans.n) >= 1 - 1e-7)) {
                if (bad_n++ < 5) T_FAIL("ray %ld: world normal off by 1 - cos = %.3g", i, 1 - tm_dot(nw, ans.n));
            }
            for (a = 0; a < 3; a++) pr[a] = o[a] + ans.t * d[a] - ans.p[a]; /* the mapped point is the world ray's */
            if (!(tm_len(pr) <= 1e-12 * (tm_len(o) + ans.t * tm_len(d)))) {
                if (bad_n++ < 5) T_FAIL("ray %ld: world point %.3g off the ray", i, tm_len(pr));
            }
            /* a secondary ray from the rounded hit, into the world hemisphere
               of its normal: re_secondary_origin in the prototype's space,
               mapped back */
            {
                double dw[3], dob[3], org_o[3], org[3], tmp[3], zero[3] = {0, 0, 0}, out, sin_exit;
                const xfm_t *x = &X[ans.inst];
                for (a = 0; a < 3; a++) dw[a] = t_rng_range(&rng, -1, 1);
                if (tm_dot(dw, ans.n) < 0) for (a = 0; a < 3; a++) dw[a] = -dw[a];
                xfm_to_object(x, zero, dw, tmp, dob);
                re_secondary_origin(rs, &ans.h, dob, org_o);
                n_sec++;
                /* in double: just outside the sharp prototype, by the push
                   (RE_ORIGIN_OFFSET_REL times the bounding box's diagonal,
                   1.2 to 1.9 here), where the ray leaves it */
                out = outside_sharp(&P[ans.inst / NXFM], ans.inst / NXFM, org_o, dob, &sin_exit);
                out_lo = fmin(out_lo, out), out_hi = fmax(out_hi, out);
                if (!(out >= 0.5 * RE_ORIGIN_OFFSET_REL && out <= 4 * RE_ORIGIN_OFFSET_REL)) {
                    if (bad_origin++ < 5) T_FAIL("ray %ld: secondary origin %.3g outside the sharp prototype (exit sine %.3g)", i, out, sin_exit);
                }
                /* in the world, through Embree's float instance: the ray meets
                   its own instance again only within float noise of the origin
                   (the host hides it there, walk-through step 4) */
                xfm_point_to_world(x, org_o, org);
                if (own_hit_beyond(top, org, dw, ans.inst, 1e-3 * inst_size(x) / tm_len(dw))) {
                    if (bad_origin++ < 5) T_FAIL("ray %ld: the secondary ray meets its own instance %d again", i, ans.inst);
                }
            }
        }
    }
    fprintf(stderr, "    rays %ld: rounded %ld, passed through %ld, secondaries %ld (origins %.3g..%.3g outside); rounded per map %ld %ld %ld %ld %ld\n", n,
            n_round, n_pass, n_sec, out_lo, out_hi, round_per_xfm[0], round_per_xfm[1], round_per_xfm[2], round_per_xfm[3], round_per_xfm[4]);
    T_INT_EQ(bad, 0);
    T_INT_EQ(bad_n, 0);
    T_INT_EQ(bad_origin, 0);
    T_GT(n_round, n / 10);
    T_GT(n_pass, 0);
    for (k = 0; k < NXFM; k++) T_GT(round_per_xfm[k], n / 100); /* every kind of map is exercised */
    re_free(rs);
    rtcReleaseScene(top);
    for (p = 0; p < NPROTO; p++) rtcReleaseScene(protos[p]), tm_free(&P[p].mesh), free(P[p].fv);
    rtcReleaseDevice(dev);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {T_CASE(instances_match_the_transformed_oracles)};
    return T_RUN(argc, argv, cases);
}
