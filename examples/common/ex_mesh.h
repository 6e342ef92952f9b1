/* ex_mesh.h — indexed triangle meshes and the generators examples share.

   Positions are xyz floats (what Embree takes), indices uint32, three per
   triangle, counter-clockwise seen from outside (right-hand normal points out).
   Every generator fills a zeroed or freed mesh and returns 0, or -1 when out
   of memory or given a bad argument; free with ex_mesh_free. */
#ifndef FILIGREE_EX_MESH_H
#define FILIGREE_EX_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "ex_math.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ex_mesh_t {
    float *pos;         /* 3 * nverts */
    uint32_t *idx;      /* 3 * ntris */
    size_t nverts, ntris;
} ex_mesh_t;

/* The cube [-1,1]^3 with sharp edges: 8 shared vertices, 12 triangles (no
   bevel; every edge is shared by exactly two triangles). */
int ex_mesh_cube(ex_mesh_t *m);

/* Reference geometry: the cube [-1,1]^3 with its edges and corners truly
   rounded to `radius` (0 < radius <= 1), `segments` quads across each
   rounded band (>= 1). Closed, welded. */
int ex_mesh_rounded_cube(ex_mesh_t *m, double radius, int segments);

/* Unit icosphere: an icosahedron subdivided `level` times (0..8), vertices
   projected to the unit sphere; 10·4^level + 2 vertices, 20·4^level triangles. */
int ex_mesh_icosphere(ex_mesh_t *m, int level);

/* A square in the plane y = 0, [-half, half] in x and z, facing +y (2 triangles). */
int ex_mesh_ground(ex_mesh_t *m, double half_size);

/* Appends src's vertices and triangles to dst (dst may be empty). */
int ex_mesh_append(ex_mesh_t *dst, const ex_mesh_t *src);

/* Applies the affine map p → M·p + t, M row-major 3×3 in m[0..8], t in m[9..11].
   Reverses the winding when det M < 0 so triangles stay outward. */
void ex_mesh_transform(ex_mesh_t *m, const double m12[12]);

/* Fills m12 with scale s (uniform), then rotation by `angle` radians about unit
   `axis`, then translation t. */
void ex_affine_srt(double m12[12], double s, ex_v3_t axis, double angle, ex_v3_t t);

/* Writes a Wavefront OBJ (for debugging in any viewer). 0, or -1 after
   printing one line. */
int ex_mesh_write_obj(const ex_mesh_t *m, const char *path);

void ex_mesh_free(ex_mesh_t *m);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_MESH_H */
