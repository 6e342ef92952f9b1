/* ex_camera.c — see ex_camera.h */
#include "ex_camera.h"

int ex_camera_init(ex_camera_t *cam, ex_v3_t from, ex_v3_t at, ex_v3_t up,
                   double vfov_degrees, int width, int height)
{
    ex_v3_t f = ex_sub(at, from), r;
    if (!(vfov_degrees > 0 && vfov_degrees < 180) || width <= 0 || height <= 0) return -1;
    if (!(ex_len(f) > 0)) return -1;
    f = ex_normalize(f);
    r = ex_cross(f, up);
    if (!(ex_len(r) > 1e-9 * ex_len(up))) return -1;
    cam->eye = from;
    cam->forward = f;
    cam->right = ex_normalize(r);
    cam->up = ex_cross(cam->right, f);
    cam->half_h = tan(0.5 * vfov_degrees * EX_PI / 180.0);
    cam->width = width;
    cam->height = height;
    return 0;
}

ex_v3_t ex_camera_dir(const ex_camera_t *cam, double px, double py)
{
    /* screen plane at distance 1; pixels are square */
    double half_w = cam->half_h * (double)cam->width / (double)cam->height;
    double sx = (2.0 * px / cam->width - 1.0) * half_w;
    double sy = (1.0 - 2.0 * py / cam->height) * cam->half_h;
    ex_v3_t d = ex_add(cam->forward, ex_add(ex_scale(cam->right, sx), ex_scale(cam->up, sy)));
    return ex_normalize(d);
}

ex_ray_t ex_camera_ray(const ex_camera_t *cam, double px, double py)
{
    ex_ray_t r;
    r.o = r.rx_o = r.ry_o = cam->eye;
    r.d = ex_camera_dir(cam, px, py);
    r.rx_d = ex_camera_dir(cam, px + 1.0, py);
    r.ry_d = ex_camera_dir(cam, px, py + 1.0);
    r.has_differentials = 1;
    return r;
}

/* Where the offset ray o + t·d meets the plane through p with normal n. */
static int ex__camera_plane_hit(ex_v3_t o, ex_v3_t d, ex_v3_t p, ex_v3_t n, ex_v3_t *q)
{
    double den = ex_dot(n, d);
    double t;
    if (fabs(den) < 1e-12 * ex_len(d)) return 0;
    t = ex_dot(n, ex_sub(p, o)) / den;
    *q = ex_madd(o, d, t);
    return 1;
}

void ex_ray_footprint(const ex_ray_t *ray, ex_v3_t p, ex_v3_t n, ex_v3_t *dpdx, ex_v3_t *dpdy)
{
    ex_v3_t px, py;
    *dpdx = *dpdy = ex_v3(0, 0, 0);
    if (!ray->has_differentials) return;
    if (!ex__camera_plane_hit(ray->rx_o, ray->rx_d, p, n, &px)) return;
    if (!ex__camera_plane_hit(ray->ry_o, ray->ry_d, p, n, &py)) return;
    *dpdx = ex_sub(px, p);
    *dpdy = ex_sub(py, p);
}
