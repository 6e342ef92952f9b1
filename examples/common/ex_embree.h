/* ex_embree.h — thin Embree 3 helpers for the example renderers.

   RTCDevice dev = ex_embree_device();            // NULL (one line printed) on failure
   RTCScene  scn = rtcNewScene(dev);
   unsigned  id  = ex_embree_add_mesh(dev, scn, pos, nverts, idx, ntris);
   if (ex_embree_commit(dev, scn)) exit(1);
   ex_hit_t h = ex_embree_intersect(scn, o, d, 0, INFINITY);
   ex_embree_release(dev, scn);

   Every Embree error is reported on stderr as one line
   "<program>: embree: <error name>: <message>" by the device's error callback. */
#ifndef FILIGREE_EX_EMBREE_H
#define FILIGREE_EX_EMBREE_H

#include <embree3/rtcore.h>
#include <stddef.h>
#include <stdint.h>

#include "ex_math.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One ray query's answer. */
typedef struct ex_hit_t {
    int hit;                 /* 1 when something was hit; the rest is valid only then */
    double t;                /* ray parameter, in the units of the caller's d */
    unsigned geom_id, prim_id;
    ex_v3_t ng;              /* unit geometric normal by the right-hand rule on the
                                triangle's (v0, v1, v2): outward for CCW-from-outside */
    double u, v;             /* barycentrics: p = (1-u-v)·v0 + u·v1 + v·v2 */
} ex_hit_t;

/* A new device whose error callback prints one line per error.
   Returns NULL (after printing why) when Embree cannot start. */
RTCDevice ex_embree_device(void);

/* Adds an indexed triangle mesh (xyz float positions, 3 uint32 indices per
   triangle; the data is copied) to `scene`. Returns its geomID, or
   RTC_INVALID_GEOMETRY_ID after printing one line (bad index, no memory). */
unsigned ex_embree_add_mesh(RTCDevice dev, RTCScene scene, const float *pos, size_t nverts,
                            const uint32_t *idx, size_t ntris);

/* Commits the scene. Returns 0, or -1 when the device reported an error. */
int ex_embree_commit(RTCDevice dev, RTCScene scene);

/* Closest hit along o + t·d, t in [tnear, tfar]. Thread-safe after commit. */
ex_hit_t ex_embree_intersect(RTCScene scene, ex_v3_t o, ex_v3_t d, double tnear, double tfar);

/* 1 when anything blocks o + t·d for t in [tnear, tfar] (shadow rays). */
int ex_embree_occluded(RTCScene scene, ex_v3_t o, ex_v3_t d, double tnear, double tfar);

/* Releases the scene (may be NULL) and the device (may be NULL). */
void ex_embree_release(RTCDevice dev, RTCScene scene);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_EMBREE_H */
