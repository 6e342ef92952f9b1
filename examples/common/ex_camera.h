/* ex_camera.h — a pinhole camera producing primary rays with ray differentials.

   Pixel coordinates are continuous: pixel (x, y) covers [x, x+1) × [y, y+1),
   its centre is (x+0.5, y+0.5), row 0 is the top of the image. Directions are
   unit length. The differentials follow pbrt: rx_* / ry_* are the rays one
   pixel to the right / one pixel down (for a pinhole, same origin). */
#ifndef FILIGREE_EX_CAMERA_H
#define FILIGREE_EX_CAMERA_H

#include "ex_math.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A ray o + t·d, optionally with its pixel-offset neighbours. */
typedef struct ex_ray_t {
    ex_v3_t o, d;
    int has_differentials;    /* 1 for camera rays, 0 for secondary rays */
    ex_v3_t rx_o, rx_d;       /* the ray through (px + 1, py) */
    ex_v3_t ry_o, ry_d;       /* the ray through (px, py + 1) */
} ex_ray_t;

typedef struct ex_camera_t {
    ex_v3_t eye;
    ex_v3_t forward, right, up;   /* orthonormal, right-handed view frame */
    double half_h;                 /* tan(vfov / 2) */
    int width, height;
} ex_camera_t;

/* Sets up a camera at `from` looking at `at`, `up` roughly upward, vertical
   field of view in degrees (0 < vfov < 180), image size in pixels.
   Returns 0, or -1 when the frame is degenerate (from == at, up parallel to
   the view direction, bad fov or size). */
int ex_camera_init(ex_camera_t *cam, ex_v3_t from, ex_v3_t at, ex_v3_t up,
                   double vfov_degrees, int width, int height);

/* The unit direction through continuous pixel position (px, py). */
ex_v3_t ex_camera_dir(const ex_camera_t *cam, double px, double py);

/* The primary ray through (px, py), with differentials. */
ex_ray_t ex_camera_ray(const ex_camera_t *cam, double px, double py);

/* pbrt-style transfer of a ray's differentials to the tangent plane at the
   hit point p with normal n: the change of the hit point per pixel in x and y.
   Sets both to zero when the ray has no differentials or grazes the plane. */
void ex_ray_footprint(const ex_ray_t *ray, ex_v3_t p, ex_v3_t n, ex_v3_t *dpdx, ex_v3_t *dpdy);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_CAMERA_H */
