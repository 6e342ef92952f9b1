/* ex_embree.c — see ex_embree.h */
#include "ex_embree.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

extern char *program_invocation_short_name; /* glibc */

static const char *ex__embree_error_name(enum RTCError e)
{
    switch (e) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unknown error";
}

static void ex__embree_on_error(void *user, enum RTCError code, const char *msg)
{
    (void)user;
    fprintf(stderr, "%s: embree: %s: %s\n", program_invocation_short_name, ex__embree_error_name(code),
            msg && *msg ? msg : "(no message)");
}

RTCDevice ex_embree_device(void)
{
    RTCDevice dev = rtcNewDevice(NULL);
    if (!dev) {
        fprintf(stderr, "%s: embree: cannot create a device: %s\n", program_invocation_short_name,
                ex__embree_error_name(rtcGetDeviceError(NULL)));
        return NULL;
    }
    rtcSetDeviceErrorFunction(dev, ex__embree_on_error, NULL);
    return dev;
}

unsigned ex_embree_add_mesh(RTCDevice dev, RTCScene scene, const float *pos, size_t nverts,
                            const uint32_t *idx, size_t ntris)
{
    RTCGeometry g;
    float *vb;
    uint32_t *ib;
    unsigned id;
    size_t i;
    for (i = 0; i < 3 * ntris; i++)
        if (idx[i] >= nverts) {
            fprintf(stderr, "%s: embree: triangle %zu uses vertex %u but the mesh has %zu vertices\n",
                    program_invocation_short_name, i / 3, idx[i], nverts);
            return RTC_INVALID_GEOMETRY_ID;
        }
    g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g) return RTC_INVALID_GEOMETRY_ID;
    vb = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nverts);
    ib = (uint32_t *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), ntris);
    if (!vb || !ib) { rtcReleaseGeometry(g); return RTC_INVALID_GEOMETRY_ID; }
    memcpy(vb, pos, 3 * sizeof(float) * nverts);
    memcpy(ib, idx, 3 * sizeof(uint32_t) * ntris);
    rtcCommitGeometry(g);
    id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return id;
}

int ex_embree_commit(RTCDevice dev, RTCScene scene)
{
    rtcCommitScene(scene);
    return rtcGetDeviceError(dev) == RTC_ERROR_NONE ? 0 : -1;
}

static void ex__embree_fill_ray(struct RTCRay *r, ex_v3_t o, ex_v3_t d, double tnear, double tfar)
{
    r->org_x = (float)o.x; r->org_y = (float)o.y; r->org_z = (float)o.z;
    r->dir_x = (float)d.x; r->dir_y = (float)d.y; r->dir_z = (float)d.z;
    r->tnear = (float)tnear;
    r->tfar = isinf(tfar) ? INFINITY : (float)tfar;
    r->time = 0;
    r->mask = 0xFFFFFFFFu;
    r->id = 0;
    r->flags = 0;
}

ex_hit_t ex_embree_intersect(RTCScene scene, ex_v3_t o, ex_v3_t d, double tnear, double tfar)
{
    struct RTCIntersectContext ctx;
    struct RTCRayHit rh;
    ex_hit_t h;
    memset(&h, 0, sizeof h);
    rtcInitIntersectContext(&ctx);
    ex__embree_fill_ray(&rh.ray, o, d, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.hit = 1;
    h.t = rh.ray.tfar;
    h.geom_id = rh.hit.geomID;
    h.prim_id = rh.hit.primID;
    /* Embree's Ng is the right-hand normal (v1-v0)×(v2-v0), unnormalised */
    h.ng = ex_normalize(ex_v3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    return h;
}

int ex_embree_occluded(RTCScene scene, ex_v3_t o, ex_v3_t d, double tnear, double tfar)
{
    struct RTCIntersectContext ctx;
    struct RTCRay r;
    rtcInitIntersectContext(&ctx);
    ex__embree_fill_ray(&r, o, d, tnear, tfar);
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0;   /* Embree sets tfar to -inf on a hit */
}

void ex_embree_release(RTCDevice dev, RTCScene scene)
{
    if (scene) rtcReleaseScene(scene);
    if (dev) rtcReleaseDevice(dev);
}
