/* grooves.h — grooved and scratched surfaces (part of filigree)

   Grooves as UV paths with polyline cross-sections, shaded exactly per pixel
   footprint with clipping, masking and shadowing (Bosch et al. 2006, §3–4:
   isolated and parallel grooves; §5: crossings, ends and corners by
   polygon footprints, protruding and self-crossing grooves too, or by line
   samples; §6: specular inter-reflection and transmission).

   The host renderer builds a grid once from a list of grooves, then for each
   shading point turns its ray differentials into a footprint and asks for the
   facet list: for every visible facet its texture-space normal, reflectance
   id, visible ratio r_i and lit fraction per light. It shades
   Σ r_i ρ_i(N_i, E, L) with its own BRDFs (or lets gr_shade() call one).
   Full guide: docs/grooves.md.

   USAGE
     In exactly one C or C++ file:
         #define GR_IMPLEMENTATION
         #include "grooves.h"
     Everywhere else just #include "grooves.h".
   OPTIONS (define before including)
     GR_IMPLEMENTATION  emit the implementation in this translation unit
     GR_STATIC          make every function static (private to this file)
     GR_DEF             linkage of public functions (default extern)
     GR_ASSERT(c)       internal-invariant check (default assert)
     GR_MALLOC(sz,ctx) / GR_FREE(p,ctx)   allocator hooks (default malloc/free)
     GR_MAX_LIGHTS      lights per query (default 4)
     GR_MAX_FACETS      entries in a gr_facet_list_t (default 32)
     GR_MAX_JUNCTIONS   crossings/ends gr_detect() stores per footprint (default 16)
     GR_POLY_MAX_GROOVES grooves the polygon path takes in one footprint's
                        search box (default 16; more are §4's)
     GR_NO_CURVES       leave out Bézier paths (the builder then rejects them
                        with GR_ERR_UNSUPPORTED)
     GR_NO_OVERSAMPLE   leave out footprint oversampling (§4.2)
     GR_NO_INTERSECTIONS leave out §5-6 (the 2D polygon routines, gr_detect,
                        the polygon path): footprints with crossings or
                        ends then get §4's answer with its flags
     GR_NO_LINE_SAMPLES leave out gr_query_lines() (§5.6 line samples;
                        implied by GR_NO_INTERSECTIONS)
     GR_NO_INTERREFLECTION leave out gr_shade_indirect() (§6; implied by
                        GR_NO_INTERSECTIONS)
   CONVENTIONS
     See docs/conventions.md: results are gr_result_t codes with GR_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_GR_H
#define FILIGREE_GR_H

#include <stddef.h>
#include <math.h>
#ifndef GR_DEF
#  ifdef GR_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define GR_DEF static __attribute__((unused))
#    else
#      define GR_DEF static
#    endif
#  else
#    define GR_DEF extern
#  endif
#endif
#ifndef GR_MAX_LIGHTS
#  define GR_MAX_LIGHTS 4
#endif
#ifndef GR_MAX_FACETS
#  define GR_MAX_FACETS 32
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. GR_OK is 0; gr_result_string() names each. */
typedef enum gr_result_t {
    GR_OK = 0,
    GR_ERR_INVALID_ARG,      /* a NULL pointer or an out-of-range parameter */
    GR_ERR_OUT_OF_MEMORY,    /* the allocator hook returned NULL */
    GR_ERR_BUFFER_TOO_SMALL, /* a caller buffer is smaller than the size query said */
    GR_ERR_NOT_FINITE,       /* a NaN or infinite coordinate */
    GR_ERR_EMPTY_GRID,       /* no grooves, or an empty UV domain */
    GR_ERR_PATH_POINTS,      /* wrong point count for the path kind */
    GR_ERR_ZERO_LENGTH_PATH, /* a path whose points all coincide */
    GR_ERR_SECTION_POINTS,   /* a cross-section with fewer than 2 points */
    GR_ERR_SECTION_ENDS,     /* a cross-section whose first or last w is not 0 */
    GR_ERR_SECTION_ORDER,    /* a cross-section whose last b is not above its first b */
    GR_ERR_PERTURBATION,     /* a perturbation without a valid perturb_max */
    GR_ERR_UNSUPPORTED,      /* a feature left out at compile time (GR_NO_...) */
    GR_ERR_STACK_FULL,       /* gr_shade_indirect(): the bounces needed more than
                                GR_INDIRECT_STACK pending segments; the colour is
                                filled but approximate (see there) */
    GR_RESULT_COUNT_
} gr_result_t;

/* A human-readable name for a result code; never NULL. */
GR_DEF const char *gr_result_string(gr_result_t r);

/* Filled by a builder that rejects user data, when the caller passes one. */
typedef struct gr_diag_t {
    gr_result_t result;
    long long element;    /* index of the offending groove, -1 if none */
    char message[160];    /* "groove 12: cross-section has 1 point" */
} gr_diag_t;

/* ---- Representation (§3) ------------------------------------------------ */

/* How a groove's path points are read. All paths lie in UV. */
typedef enum gr_path_kind_t {
    GR_PATH_POLYLINE = 0,  /* >= 2 points; 2 points make a line segment */
    GR_PATH_QUADRATIC = 1, /* chain of quadratic Béziers: 2k+1 points (k >= 1),
                              pieces share end points */
    GR_PATH_CUBIC = 2      /* chain of cubic Béziers: 3k+1 points (k >= 1) */
} gr_path_kind_t;

/* Optional perturbation f(t) of a groove (§3): every cross-section point is
   multiplied by f(t) at path parameter t in [0,1]. t grows with arc length
   along a polyline and uniformly per piece along a Bézier chain (piece j of
   k covers [j/k, (j+1)/k]). Must be pure and thread-safe; values below 0
   (and NaN) count as 0. */
typedef double (*gr_perturb_fn)(double t, void *user);

/* One groove. The builder copies everything except perturb/perturb_user, so
   the caller's arrays may be freed after the build. Zero means default. */
typedef struct gr_groove_desc_t {
    gr_path_kind_t kind;          /* default GR_PATH_POLYLINE */
    const double *points;         /* point_count (u, v) pairs, UV units */
    int point_count;
    /* Cross-section C_i = (b, w), section_count pairs, UV units: b is the
       signed distance from the path along the binormal B = (-T_v, T_u)
       (left of the direction of travel is b > 0), w the height: w < 0 cuts
       in, w > 0 protrudes. First and last w must be 0 and the last b must be
       above the first (points run from left to right, so facet normals
       (-dw, db)/|(db, dw)| point out of the material). */
    const double *section;
    int section_count;            /* >= 2 */
    int reflectance;              /* host id of every facet's BRDF, default 0 */
    const int *facet_reflectance; /* optional: section_count-1 ids, one per
                                     facet R_i = [C_i, C_i+1]; overrides reflectance */
    gr_perturb_fn perturb;        /* optional scale f(t) (default: none, f = 1) */
    void *perturb_user;
    double perturb_max;           /* required with perturb: an upper bound of f
                                     on [0,1], used for the global bounds w, h, d */
} gr_groove_desc_t;

/* Grid build options (§4.1). Zero means default. */
typedef struct gr_grid_desc_t {
    const gr_groove_desc_t *grooves;
    int groove_count;             /* >= 1 */
    double domain[4];             /* u0, v0, u1, v1 of the texture tile; all 0
                                     means [0,1]x[0,1] */
    int no_wrap;                  /* 0 (default): the tile repeats, paths and
                                     footprints wrap around (§4.1); 1: no repeat */
    int cells_u, cells_v;         /* grid resolution; 0 picks one from the
                                     groove count and path lengths */
    int base_reflectance;         /* id of the base surface (ground facets),
                                     default 0 */
    void *alloc_ctx;              /* passed to GR_MALLOC/GR_FREE */
} gr_grid_desc_t;

struct gr__groove_t; /* private per-groove record */

/* The built grid: grooves in flat arrays and the uniform cell lists. Treat
   every field as read-only; the layout of the arrays is private and may
   change. One allocation (or the caller's buffer) holds everything. */
typedef struct gr_grid_t {
    /* global bounds of all cross-sections times perturb_max (§3, Figure 3):
       w: largest |b| (distance of a cross-section point from its path),
       h: largest w above the surface (0 if nothing protrudes),
       d: largest depth -w below the surface */
    double w, h, d;
    int groove_count;
    int cells_u, cells_v;
    double domain[4];
    int wrap;
    int base_reflectance;
    /* private */
    size_t bytes;
    void *alloc_ctx;
    int owns_memory;
    struct gr__groove_t *grooves_;
    double *points_;         /* path points, all grooves */
    double *section_;        /* cross-section points (shared by consecutive equal sections) */
    int *facet_refl_;        /* one id per facet, all grooves */
    int *blocker_start_;     /* per section point, into blockers_ */
    int *blockers_;
    int *cell_start_;        /* cells_u*cells_v + 1 */
    int *cell_count_;        /* items used in each cell */
    int *cell_items_;
    int *anchor_start_;      /* grooves whose first point lies in the cell */
    int *anchor_items_;
    int *row_anchor_sum_;    /* per row, prefix counts of anchors */
    int total_points_, total_section_, total_facets_, item_capacity_;
    /* §5 self-intersections, found by the builder: the hits, and each
       self-crossing groove cut into pieces (records after the grooves,
       listed in no cell) that the polygon path takes as separate grooves */
    struct gr_self_hit_t *self_;
    int self_count_, split_records_;
} gr_grid_t;

/* Size query for gr_grid_build_into(): *bytes receives the buffer size. It
   validates every groove (with a diagnostic naming the first bad one). */
GR_DEF gr_result_t gr_grid_size(const gr_grid_desc_t *desc, size_t *bytes, gr_diag_t *diag);
/* Build into a caller buffer of at least gr_grid_size() bytes, aligned for
   double. *grid points into the buffer; gr_grid_free() is not needed. */
GR_DEF gr_result_t gr_grid_build_into(const gr_grid_desc_t *desc, void *buffer, size_t bytes,
                                      gr_grid_t **grid, gr_diag_t *diag);
/* Build with GR_MALLOC(desc->alloc_ctx); release with gr_grid_free(). */
GR_DEF gr_result_t gr_grid_build(const gr_grid_desc_t *desc, gr_grid_t **grid, gr_diag_t *diag);
/* Free a grid from gr_grid_build(); a NULL grid or one built into a caller
   buffer is ignored. */
GR_DEF void gr_grid_free(gr_grid_t *grid);

/* The facets of a groove's cross-section that may block facet `facet`
   (§3: those with a point higher than the lowest point of this facet).
   Returns the count and sets *list (valid while the grid lives); 0 for
   out-of-range indices. */
GR_DEF int gr_facet_blockers(const gr_grid_t *grid, int groove, int facet, const int **list);

/* ---- Footprint (§4, eq. 1) --------------------------------------------- */

/* A pixel footprint in texture space: centre F and half-axes A1, A2 (the
   footprint is the parallelogram/ellipse F + a A1 + b A2, |a|,|b| <= 1), plus
   the unit direction E from the surface toward the viewer in texture space
   (U, V, W), W the surface normal. A1 = A2 = 0 is a point sample. At
   intersections and ends (the polygon path, line samples) a view or light
   less than 1e-6 (sine of its elevation) above the horizon is taken at
   1e-6, where the answer has reached its grazing limit (blockers farther
   than 1e6 scene scales along it are not found); §4 takes any. */
typedef struct gr_footprint_t {
    double center[2];
    double axis1[2];
    double axis2[2];
    double view[3];
} gr_footprint_t;

/* Orthonormal texture-space frame at a hit: tu along dp/du, tw the unit
   normal, tv = tw x tu. Texture space is assumed locally conformal (dp/du
   and dp/dv orthogonal and of equal length); otherwise the grooves are seen
   through this closest orthonormal frame. */
typedef struct gr_frame_t {
    double tu[3], tv[3], tw[3];
} gr_frame_t;

/* A hit with ray differentials, as a ray tracer has it (pbrt's model). */
typedef struct gr_differentials_t {
    double p[3];           /* hit point, world space */
    double n[3];           /* surface normal (any length, on the viewer's side) */
    double dpdu[3], dpdv[3]; /* surface partial derivatives */
    double uv[2];          /* texture coordinates at p */
    double dir[3];         /* main ray direction (any length) */
    double rx_origin[3], rx_dir[3]; /* ray offset one pixel in x */
    double ry_origin[3], ry_dir[3]; /* ray offset one pixel in y */
    double filter_radius;  /* footprint half-size in pixels; 0 means 0.5 (a
                              box pixel) */
} gr_differentials_t;

/* The footprint from ray differentials: the offset rays meet the tangent
   plane at p; their offsets are solved for (du, dv) by least squares against
   dp/du, dp/dv (as pbrt-v4 does), scaled by filter_radius. Also fills the
   texture frame (for transforming light directions) when frame is non-NULL.
   Offset rays parallel to the tangent plane give a zero axis (a line or
   point footprint). Errors: GR_ERR_INVALID_ARG for NULL, GR_ERR_NOT_FINITE
   for NaN input, degenerate dp/du x dp/dv or a zero-length ray direction. */
GR_DEF gr_result_t gr_footprint_from_differentials(const gr_differentials_t *rd,
                                                  gr_footprint_t *fp, gr_frame_t *frame);

/* A world direction in texture space (U, V, W), normalised. Returns 0 (and
   zeros) for a zero vector. */
GR_DEF int gr_frame_to_texture(const gr_frame_t *frame, const double world[3], double tex[3]);

/* ---- Query (§4.1-4.4) --------------------------------------------------- */

/* One query. Zero means default. */
typedef struct gr_query_t {
    gr_footprint_t footprint;
    const double *lights;  /* light_count unit directions toward the lights,
                              texture space, 3 doubles each; L_w <= 0 means at
                              or below the horizon: lit fraction 0 */
    int light_count;       /* 0..GR_MAX_LIGHTS; 0 skips all shadowing work */
    double oversample_tol; /* §4.2: split the footprint when the straight-line
                              approximation of a path, or the change of the
                              perturbation, exceeds this fraction of the groove
                              width across the footprint; default 0 means
                              0.05; negative disables oversampling */
    int max_oversample;    /* most sub-footprints; default 0 means 8, at most 64 */
    double parallel_tol;   /* grooves whose tangent differs from the nearest
                              groove's by more than this angle (radians) are
                              not parallel (§4.2); default 0 means 0.02 */
    int line_samples;      /* intersections and ends (§5, issue 8): 0 (default)
                              answers footprints that gr_detect() finds
                              crossings or path ends in with the exact
                              polygon path (§5.2-5.5); n = 1..32 asks for n
                              line samples (§5.6, gr_query_lines()) for
                              footprints whose §4 search flags
                              GR_LIST_NONPARALLEL or GR_LIST_PATH_END, or
                              that a self-crossing reaches (§4's profile
                              is then skipped; without GR_NO_LINE_SAMPLES;
                              with it they keep §4's answer and its flags) */
    int perturb_normals;   /* 0 (default) or positive: the true normal of the
                              swept, scaled section where the view ray meets
                              each facet: §4.4's (0, N_b, N_w) tilted along T
                              by the perturbation's slope,
                              f'(s) (b dw - w db)/|(db, dw)| (f' averaged
                              across the footprint), with the groove frame
                              turned as a curved path turns between P and
                              that point. Negative: §4.4's normals in the
                              frame at P, as the paper has them */
    int ellipse;           /* 0 (default): the footprint is the parallelogram
                              F + a A1 + b A2, |a|, |b| <= 1 (a box pixel, as
                              gr_footprint_from_differentials gives it). 1: the
                              ellipse a^2 + b^2 <= 1 (Gaussian-like filters) */
    double line_exit_tol;  /* §5.6 early exit of line samples: stop when
                              Σ r_i >= 1 - tol; default 0 means 1e-3;
                              negative disables */
    int straight_occlusion; /* 0 (default): §4.3's masking and shadowing
                              with each cross-section point taken where
                              the ray that reaches it meets the groove: the
                              section scaled by f there (the depth change
                              along the ray's way, exact for a linear f)
                              and, on a curved path, moved by the bend's
                              drift under a ray running along it (exact
                              for a circular arc). Nonzero: the straight
                              groove with the constant profile at P, as
                              the paper has it (§4.2-4.3) */
} gr_query_t;

/* One entry of the facet list: a texture-space facet orientation with its
   share of the footprint. Facets of several grooves with the same normal and
   reflectance id are merged into one entry (their ratios add, lit fractions
   are ratio-weighted), so parallel grooves with one cross-section give one
   entry per facet, whatever their number. The pieces of one facet of one
   groove from oversampled sub-footprints also make one entry, its normal
   the ratio-weighted mean (they differ along curved paths, whose frame
   turns, and with perturbed normals). */
typedef struct gr_facet_t {
    double normal[3];          /* unit, texture space (U, V, W), out of the material */
    double ratio;              /* r_i: visible fraction of the footprint (§4.4) */
    double lit[GR_MAX_LIGHTS]; /* fraction of the visible part lit by light k */
    int reflectance;           /* the facet's id, or base_reflectance for ground */
    int groove;                /* first contributing groove, -1 for ground */
    int facet;                 /* its facet index R_i, -1 for ground */
    int merged;                /* how many pieces were merged into this entry */
} gr_facet_t;

/* gr_facet_list_t.flags */
#define GR_LIST_BELOW_HORIZON 1u  /* E_w <= 0: the surface is not seen; no facets */
#define GR_LIST_APPROX_MERGE  2u  /* more than GR_MAX_FACETS distinct facets:
                                     extra ones merged into the closest normal */
#define GR_LIST_NONPARALLEL   4u  /* non-parallel grooves reach the footprint
                                     (intersections, issue 8): only the grooves
                                     parallel to the nearest one were used */
#define GR_LIST_PATH_END      8u  /* a path ends inside the footprint: treated
                                     as continuing until the footprint centre
                                     passes the end */
#define GR_LIST_OVERLAP      16u  /* parallel cross-sections overlap in UV:
                                     joined in path order, approximate */
#define GR_LIST_POLYGON      32u  /* answered by the polygon path (§5.2-5.5):
                                     crossings and path ends are exact; end
                                     caps are listed with facet index
                                     section_count-1 (first end) or
                                     section_count (last end) */

/* The query result: caller-owned, fixed maximum size. The ratios sum to 1
   (to rounding) unless GR_LIST_BELOW_HORIZON is set. */
typedef struct gr_facet_list_t {
    int count;
    unsigned flags;
    int grooves;       /* grooves in the merged cross-section(s) */
    int subfootprints; /* 1, or the oversampling count */
    gr_facet_t facets[GR_MAX_FACETS];
} gr_facet_list_t;

/* Scratch bytes any query on this grid needs (bounded by the grid size). */
GR_DEF size_t gr_query_scratch_bytes(const gr_grid_t *grid);

/* The facet list for one footprint. Const on the grid, allocation-free,
   thread-safe (each thread its own scratch and list). Errors:
   GR_ERR_INVALID_ARG (NULL, light_count or line_samples out of range),
   GR_ERR_BUFFER_TOO_SMALL (scratch), GR_ERR_NOT_FINITE (NaN footprint). */
GR_DEF gr_result_t gr_query(const gr_grid_t *grid, const gr_query_t *query,
                            void *scratch, size_t scratch_bytes, gr_facet_list_t *list);

/* Host BRDF for gr_shade(): reflected radiance toward e from light k along
   l, for a facet with normal n and reflectance id, cosine and light
   intensity included; all vectors unit, texture space. */
typedef void (*gr_brdf_fn)(void *user, int reflectance, const double n[3],
                           const double e[3], const double l[3], int light, double rgb[3]);

/* Convenience: gr_query() then rgb = Σ_i r_i Σ_k lit_ik brdf(...) (eq. 6). */
GR_DEF gr_result_t gr_shade(const gr_grid_t *grid, const gr_query_t *query, void *scratch,
                            size_t scratch_bytes, gr_brdf_fn brdf, void *user, double rgb[3]);

/* ==== [section: intersections] declarations (issue 8: §5–6) ==== */
#ifndef GR_NO_INTERSECTIONS

/* ---- 2D polygons (§5.2-5.5) ---------------------------------------------- */
/* At intersections and ends the footprint is a polygon (§5.2): it is clipped
   to a facet's bounds, the projected cross-sections of crossing grooves and
   the occlusion profiles are subtracted from it (§5.3-5.4), and the facet's
   ratio is an area ratio r_i = A_R / A_F (§5.5). These routines do that 2D
   work. A polygon is a ring of (x, y) pairs in either orientation, closed
   implicitly (the last point joins the first); repeated and collinear points
   are allowed. */

/* Signed area by the shoelace formula: > 0 counter-clockwise, 0 for fewer
   than 3 points or a NULL pointer. */
GR_DEF double gr_poly_area(const double *xy, int n);

/* Sutherland-Hodgman: subject ∩ clip, for a convex clip ring (either
   orientation, collinear points allowed; a clip of zero area gives an empty
   result). out and work each hold `cap` points; *nout receives the result's
   point count (0 when empty). cap = ns + nc suffices for a convex subject;
   a non-convex subject can need more (the call then fails cleanly). A
   non-convex subject cut into pieces comes back as
   one ring joined by zero-width bridges along the clip edges: its area is
   exact, but use gr_poly_boolean() for separate pieces. out and work must
   not overlap the subject or each other. Errors:
   GR_ERR_INVALID_ARG (NULL, a negative count, a clip with fewer than 3
   points or not convex), GR_ERR_NOT_FINITE, GR_ERR_BUFFER_TOO_SMALL (more
   than cap points needed; *nout is then 0). */
GR_DEF gr_result_t gr_poly_clip_convex(const double *subject, int ns, const double *clip, int nc,
                                       double *out, double *work, int cap, int *nout);

/* Boolean operations for gr_poly_boolean(). */
typedef enum gr_poly_op_t {
    GR_POLY_INTERSECTION = 0, /* a ∩ b */
    GR_POLY_DIFFERENCE = 1,   /* a \ b */
    GR_POLY_UNION = 2,        /* a ∪ b */
    GR_POLY_XOR = 3           /* (a \ b) ∪ (b \ a) */
} gr_poly_op_t;

/* A set of rings. A point belongs to the set when it lies inside any of
   its rings, each ring taken by the even-odd rule (so overlapping rings
   unite, a self-intersecting ring such as a bow tie is its two lobes, and
   there are no holes). */
typedef struct gr_polyset_t {
    const double *points;   /* (x, y) pairs, ring after ring */
    int point_count;
    const int *ring_sizes;  /* points in each ring; NULL: ring_count rings of
                               point_count / ring_count points each (so the
                               trapezoids from gr_poly_boolean() feed back in
                               with ring_count = their count) */
    int ring_count;         /* 0 or 1 with ring_sizes NULL: one ring */
} gr_polyset_t;

/* Scratch bytes gr_poly_boolean() needs for two sets with `total_points`
   points together (it grows as total_points^2: crossings of edge pairs). */
GR_DEF size_t gr_poly_boolean_scratch_bytes(int total_points);

/* a op b for arbitrary (non-convex, self-intersecting, touching, collinear)
   rings, by a slab sweep: the plane is cut at every vertex height and every
   edge crossing, so inside a slab the edges are straight and never cross
   and the result is a set of trapezoids, exact up to the rounding of the
   crossing heights. *area (optional) receives the result's area. traps
   (optional, NULL for the area only) receives up to trap_cap trapezoids, 8
   doubles each: 4 counter-clockwise (x, y) corners, bottom edge first (a
   trapezoid runs on through the slabs while its two sides are the same
   edges, so a region is not cut at every vertex height);
   *trap_count (optional) receives how many the result has. The trapezoids
   do not overlap and their union is the result. Errors: GR_ERR_INVALID_ARG
   (NULL sets or scratch, negative counts, ring sizes that do not add up),
   GR_ERR_NOT_FINITE, GR_ERR_BUFFER_TOO_SMALL (scratch below
   gr_poly_boolean_scratch_bytes(), or more trapezoids than trap_cap: *area
   and *trap_count are still right, traps holds the first trap_cap). */
GR_DEF gr_result_t gr_poly_boolean(const gr_polyset_t *a, const gr_polyset_t *b, gr_poly_op_t op,
                                   void *scratch, size_t scratch_bytes,
                                   double *traps, int trap_cap, int *trap_count, double *area);

/* ---- Intersections and ends: detection (§5, §5.1) ------------------------ */

/* Entries in a gr_junctions_t (default 16). */
#ifndef GR_MAX_JUNCTIONS
#  define GR_MAX_JUNCTIONS 16
#endif
/* Grooves the polygon path takes in a footprint's §5.1 box (default 16);
   beyond, §4 answers with its flags. Its scratch grows with it (about
   16 KiB a groove): 8 cuts the cost of the densest footprints several
   times and leaves them to §4's approximation (docs/grooves.md, What is
   left). */
#ifndef GR_POLY_MAX_GROOVES
#  define GR_POLY_MAX_GROOVES 16
#endif

/* What a footprint meets besides isolated or parallel grooves (§5, Figure 7). */
typedef enum gr_junction_kind_t {
    GR_JUNCTION_CROSSING = 0,        /* two non-parallel grooves (Figure 7a) */
    GR_JUNCTION_INTERSECTED_END = 1, /* a path end closer to another groove's
                                        path than the sum of their widths w:
                                        a half intersection (Figure 7b) */
    GR_JUNCTION_ISOLATED_END = 2,    /* a path end with no groove that near (Figure 7c) */
    GR_JUNCTION_CORNER = 3,          /* two path ends closer than the sum of
                                        their widths */
    GR_JUNCTION_SELF = 4             /* a groove crossing itself, at a point
                                        from gr_self_intersections() */
} gr_junction_kind_t;

typedef struct gr_junction_t {
    gr_junction_kind_t kind;
    int groove;      /* the (first) groove; for ends, the ending groove */
    int other;       /* crossing: the second groove; intersected end: the
                        groove it ends in; corner: the other ending groove;
                        otherwise -1 */
    int end;         /* ends and corners: 0 at the path's first point, 1 at
                        its last; otherwise -1 */
    int other_end;   /* corner: the other groove's end (0 or 1); otherwise -1 */
    double point[2]; /* UV, in the footprint's tile image: the path end, the
                        self-intersection point, or for a crossing the
                        meeting point of the two tangent lines at the paths'
                        points nearest the footprint centre (when that lies
                        far away, the point nearest the centre where the
                        two grooves' strips overlap) */
} gr_junction_t;

/* The result of gr_detect(): caller-owned, fixed size. */
typedef struct gr_junctions_t {
    int count;
    int dropped;      /* junctions beyond GR_MAX_JUNCTIONS, not stored */
    int grooves;      /* grooves that reach the enlarged box */
    double box[4];    /* the enlarged search box u0, v0, u1, v1 (§5.1) */
    gr_junction_t items[GR_MAX_JUNCTIONS];
} gr_junctions_t;

/* A self-intersection of one groove's path (§5: found before rendering). */
typedef struct gr_self_hit_t {
    int groove;
    double point[2];  /* UV */
    double param[2];  /* the path parameters t (as for perturbations, §3) of
                         the two passes, param[0] < param[1] */
} gr_self_hit_t;

/* Every self-intersection of every path, computed once after the build.
   Polylines exactly (pairs of non-adjacent segments that cross or touch);
   Bézier pieces through a flattening into 32 chords each, so their points
   are as accurate as that chord polygon.
   Writes up to cap hits; *count receives how many there are. Errors:
   GR_ERR_INVALID_ARG (NULL grid or count, cap < 0, out NULL with cap > 0),
   GR_ERR_BUFFER_TOO_SMALL (more than cap: out holds the first cap). */
GR_DEF gr_result_t gr_self_intersections(const gr_grid_t *grid, gr_self_hit_t *out, int cap, int *count);

/* Detection (§5): which intersections and ends a footprint contains, so the
   host (or the polygon path, when it lands) knows §4's isolated/parallel
   answer from gr_query() is not the whole story. The footprint's box is
   enlarged (§4.1 and §5.1) by the grid's w on all sides; by h tan θ_r
   toward the viewer; by w'_E = d tan θ_r away from the viewer, where a
   crossing groove can expose deep facets (Figure 8a); and by
   w_L = (h + d) tan θ_i toward each light above the horizon (Figure 8b).
   Grooves are gathered from the grid over that box, and a groove counts
   when its path enters the box (Bézier paths through 32 chords per piece).
   Among them:
     - two grooves whose tangents differ by more than query->parallel_tol
       (default 0.02 rad) cross (the paper's test: tangents T differ),
       provided their tangent lines meet near the footprint and within the
       sum of their widths of both paths, or (nearly parallel grooves that
       meet far away) their strips of half width w overlap near the
       footprint: the point is then the overlap's point nearest the
       footprint centre;
     - a path end inside the box is an intersected end when its distance to
       another counted groove's path is below the sum of their widths w (the
       paper's distance test), a corner when another end is that close, and
       an isolated end otherwise; an end's pair is never also reported as
       a crossing;
     - a self-intersection from `self` (optional, from
       gr_self_intersections()) inside the box is reported as such; the
       polygon path then treats the groove as two grooves.
   Uses the gr_query() scratch (gr_query_scratch_bytes()); const,
   allocation-free, thread-safe. Errors as gr_query(); a view at or below
   the horizon is not an error (no junctions, box of the footprint plus w). */
GR_DEF gr_result_t gr_detect(const gr_grid_t *grid, const gr_query_t *query, const gr_self_hit_t *self,
                             int self_count, void *scratch, size_t scratch_bytes, gr_junctions_t *out);

/* ---- The polygon path, first steps (§5.2) -------------------------------- */

/* Footprint polygon shapes (§5.2). */
typedef enum gr_fp_shape_t {
    GR_FP_QUAD = 0,   /* the parallelogram F ± A1 ± A2 (the box-filter footprint) */
    GR_FP_RHOMBUS = 1 /* F ± A1, F ± A2: the tips of the ellipse's axes */
} gr_fp_shape_t;

/* The footprint as a polygon (§5.2): 4 UV points, counter-clockwise. A
   degenerate footprint (A1 x A2 = 0) gives a ring of zero area. */
GR_DEF void gr_footprint_polygon(const gr_footprint_t *fp, gr_fp_shape_t shape, double out[8]);

/* One facet of a locally straight groove, for gr_facet_clip(). */
typedef struct gr_facet_geom_t {
    double point[2];   /* P: the path point the groove space is built on, UV */
    double tangent[2]; /* T: unit path tangent there; B = (-T_v, T_u) */
    double c0[2], c1[2]; /* the facet's section points (b, w), scaled */
} gr_facet_geom_t;

/* §5.2, eqs. 7-8: a UV polygon (n points) projected along the view E onto
   the facet's plane in groove space, then clipped to the facet's bounds.
   Facet coordinates: x along T, y along the facet from C_0 toward C_1 (so
   the facet is the strip 0 <= y <= |C_1 - C_0|). proj receives the n
   projected points; clipped (with work, each `cap` points) the clipped
   polygon, *nclipped its size; *area_f = A_F and *area_clip its area,
   both >= 0, so r = area_clip / area_f before intersection and occlusion.
   A facet seen edge-on (|N'.E'| <= 1e-12 |N'||E'|) or a zero-length facet gives zero
   areas and *nclipped = 0. A back-facing facet (N'.E' < 0) is projected
   all the same: §4.3's self-masking test is the caller's. Errors:
   GR_ERR_INVALID_ARG (NULL, n < 3, cap < n + 4), GR_ERR_NOT_FINITE,
   GR_ERR_BUFFER_TOO_SMALL (a non-convex polygon outgrowing cap). */
GR_DEF gr_result_t gr_facet_clip(const double *poly, int n, const gr_facet_geom_t *facet, const double e[3],
                                 double *proj, double *clipped, double *work, int cap, int *nclipped,
                                 double *area_f, double *area_clip);

/* §5.3: the cross-section of a crossing groove (path point p2, unit
   tangent t2, section sec2 of n2 (b, w) points, scaled) projected along
   its direction T_2 onto the facet's plane, in gr_facet_clip()'s facet
   coordinates: the part of the facet that groove carves away, to be
   subtracted (gr_poly_boolean, GR_POLY_DIFFERENCE) from the clipped
   footprint. Generally one ring of n2 points (the section closed by its
   mouth at w = 0). A facet parallel to UV (the ground, or a flat groove
   floor) is the special case where T_2 lies in the facet plane: the cut is
   then a set of strips along T_2, one per interval where the section
   spans the facet's height, each clipped to `bounds` (x0, y0, x1, y1 in
   facet coordinates; pass the clipped footprint's box). The result goes to
   `points` (cap points) as rings of `sizes` (ring_cap entries); *cut
   receives the set (points, point_count, ring_sizes, ring_count). Grooves
   parallel to the facet's (|B_1.T_2| <= 1e-12) do not cut it: an empty
   set (§5.3 skips them). cap = 5 n2 + 8 points and ring_cap = n2 / 2 + 1
   always suffice. Errors: GR_ERR_INVALID_ARG (NULL, n2 < 2, a degenerate
   facet), GR_ERR_NOT_FINITE, GR_ERR_BUFFER_TOO_SMALL (below n2 + 8 points,
   or too small for the strips found). */
GR_DEF gr_result_t gr_section_on_facet(const gr_facet_geom_t *facet, const double p2[2], const double t2[2],
                                       const double *sec2, int n2, const double bounds[4], double *points, int cap,
                                       int *sizes, int ring_cap, gr_polyset_t *cut);

#endif /* GR_NO_INTERSECTIONS */
/* ==== [end section: intersections] ==== */

/* ==== [section: line samples] declarations (issue 8: §5.6) ==== */
#ifdef GR_NO_INTERSECTIONS /* §5-6 left out: line samples and §6 with them */
#  ifndef GR_NO_LINE_SAMPLES
#    define GR_NO_LINE_SAMPLES
#  endif
#  ifndef GR_NO_INTERREFLECTION
#    define GR_NO_INTERREFLECTION
#  endif
#endif
/* Most line samples per footprint (gr_query_t.line_samples): 16 chords
   along each axis. gr_query() checks the range in every build. */
#define GR_LINE_MAX_SAMPLES 32
#if !defined(GR_NO_LINE_SAMPLES) || !defined(GR_NO_INTERREFLECTION)
/* Local grooves one line-sample evaluation keeps (the nearest), facet
   planes (the ground, facets and end walls of those grooves) and the
   breakpoints it can hold per segment; beyond any of them the result is
   approximate and flagged GR_LIST_LINE_APPROX. They size the scratch
   (with GR_LINE_MAX_EDGES and GR_INDIRECT_STACK about 320 KB with these
   defaults, within the polygon path's share of gr_query_scratch_bytes()). */
#ifndef GR_LINE_MAX_GROOVES
#  define GR_LINE_MAX_GROOVES 16
#endif
#ifndef GR_LINE_MAX_PLANES
#  define GR_LINE_MAX_PLANES 192
#endif
#ifndef GR_LINE_MAX_BREAKS
#  define GR_LINE_MAX_BREAKS 1024
#endif
#ifndef GR_LINE_MAX_EDGES /* edge lines kept per scene; beyond, found per segment (slower, same answer) */
#  define GR_LINE_MAX_EDGES 2048
#endif
/* gr_facet_list_t.flags: line samples dropped grooves or breakpoints.
   (32u until 2026-12-05: the bit of GR_LIST_POLYGON, so a line-sampled
   answer that dropped grooves claimed the polygon path.) */
#define GR_LIST_LINE_APPROX 64u

/* gr_line_stats_t.flags */
#define GR_STATS_LINE_APPROX 1u /* a segment's scene dropped grooves, planes or
                                   breakpoints (GR_LIST_LINE_APPROX) */
#define GR_STATS_STACK_FULL  2u /* gr_shade_indirect(): more pending bounce
                                   segments than GR_INDIRECT_STACK (it then
                                   returns GR_ERR_STACK_FULL) */

/* Optional counters from gr_query_lines() (and gr_shade_indirect()). */
typedef struct gr_line_stats_t {
    unsigned flags;    /* GR_STATS_... */
    int segments;      /* segments evaluated (line samples and bounces) */
    int intervals;     /* 1D intervals the segments were cut into */
    int evaluated;     /* intervals whose facet was found (the rest were
                          skipped by the §5.6 early exit) */
    int early_exits;   /* segments that stopped at Σ r_i >= 1 - tol */
    double weight[GR_LINE_MAX_SAMPLES]; /* Jones & Perry weight Σ sin²α of
                          each top-level segment */
} gr_line_stats_t;

/* §5.6's cache between neighbouring footprints, owned by the caller (one
   per thread: queries stay pure). It keeps the grooves found around a
   footprint, in their straight approximation, for a box GR_LINE_CACHE_GROW
   times the footprint's search box; a later footprint whose box lies
   inside reuses them and skips the grid search and the nearest-point
   solves. Only straight, unperturbed grooves (2-point paths) are cached:
   their straight approximation is the groove itself, the same from every
   footprint, so the answer is bit for bit the uncached one; a box with a
   curve, a polyline, a perturbed groove, or more grooves than
   GR_LINE_MAX_GROOVES, is not cached. Zero-initialise before use; it
   refers to one grid (another grid refills it). */
#define GR_LINE_CACHE_GROW 3.0
typedef struct gr_line_cache_t {
    const gr_grid_t *grid;  /* the grid it was filled from */
    double box[4];          /* the UV box it covers */
    int valid, count;
    long long hits, misses; /* footprints served from it / that refilled it */
    double store_[GR_LINE_MAX_GROOVES * 16]; /* private */
} gr_line_cache_t;
#endif

#ifndef GR_NO_LINE_SAMPLES
/* §5.6 line samples. The footprint F + a A1 + b A2 is sampled by
   n = query->line_samples line segments (0 means 2) in two families: the
   first ceil(n/2) run along A1, the other floor(n/2) along A2, each family
   a set of parallel chords across the whole footprint at the midpoints of
   equal strata of the other axis, so n = 2 is the paper's pair of axes
   through F and more lines are a stratified quadrature of the footprint's
   area (its error falls with n). Each chord is processed as a 1D version
   of §5.2-5.4: the rays from the viewer through it form a plane; every
   groove near the footprint, in its local straight approximation (§4.2)
   scaled by its perturbation, cuts that plane along its facets, and the
   chord is cut into intervals wherever an edge of the scene pierces the
   plane (section points swept along T, the crossing lines of two grooves'
   facets: §5.3's intersection profiles) or an edge's shadow along a light
   falls on a facet the chord sees (§5.4). Inside one interval the visible
   facet and its lit state are constant, so one ray per interval
   classifies it: the solid is the ground w <= 0 minus every groove's cut
   (the part of its section below w = 0) plus every protrusion, path ends
   closed by flat walls of the section's shape (listed with facet index
   section_count - 1 at the first end, section_count at the last). A
   self-crossing groove whose crossing lies near is taken as its pieces
   (§5, as the polygon path does), so its two passes cross like two
   grooves; entries name the groove. r_i is facet i's length share; a family's share is the area-weighted mean of
   its chords'. The families are combined with Jones & Perry 2000's
   weights: a chord weighs Σ sin²α over the edges it crosses (α between
   the chord and the edge's image in UV), a family the mean of its chords,
   so a family running along the edges counts little; when neither crosses
   an edge they are averaged. Early exit (§5.6): intervals are classified
   longest first and a chord stops once Σ r_i >= 1 - query->line_exit_tol;
   the unclassified rest (< tol) is shared in proportion (each r_i of a
   chord moves by at most tol). Uses gr_query_scratch_bytes() of scratch;
   stats is optional. Errors as gr_query(), plus GR_ERR_INVALID_ARG for
   line_samples outside 0..GR_LINE_MAX_SAMPLES. */
GR_DEF gr_result_t gr_query_lines(const gr_grid_t *grid, const gr_query_t *query, void *scratch,
                                  size_t scratch_bytes, gr_facet_list_t *list, gr_line_stats_t *stats);

/* gr_query_lines() with a cache (NULL: none). The same result, bit for bit:
   facets, groove count and flags (docs/grooves.md, "Cache"). */
GR_DEF gr_result_t gr_query_lines_cached(const gr_grid_t *grid, const gr_query_t *query, gr_line_cache_t *cache,
                                         void *scratch, size_t scratch_bytes, gr_facet_list_t *list,
                                         gr_line_stats_t *stats);
#endif
/* ==== [end section: line samples] ==== */

/* ==== [section: interreflection] declarations (issue 8: §6) ==== */
#ifndef GR_NO_INTERREFLECTION
/* Deepest recursion gr_shade_indirect() accepts. */
#define GR_MAX_DEPTH 8
/* Pending bounce segments gr_shade_indirect() can hold (in the query
   scratch, about 110 bytes each); a footprint that needs more gets
   GR_ERR_STACK_FULL. Each segment of a bounce pushes up to two per facet
   it sees (reflected and transmitted), so the need grows with the depth
   and the facets per segment. */
#ifndef GR_INDIRECT_STACK
#  define GR_INDIRECT_STACK 512
#endif

/* Specular behaviour of one reflectance id (the per-facet ids of
   gr_groove_desc_t.facet_reflectance and the grid's base_reflectance). */
typedef struct gr_specular_t {
    double kr[3];  /* specular reflectance k_r per channel (0: no bounce) */
    double kt[3];  /* specular transmittance k_t per channel (0: none) */
    double ior;    /* index of refraction of the material behind the facet
                      (the solid's side); 0 means 1.5 */
    int fresnel;   /* 0 (default): k_r and k_t are the bounce weights, as the
                      paper's constants (under total internal reflection
                      k_t is reflected too). 1: a dielectric: reflection
                      k_r F, transmission k_t (1 - F), F the unpolarised
                      Fresnel reflectance for the ior at the angle of
                      incidence (1 under total internal reflection) */
    int thin;      /* 0 (default): transmitted light refracts (Snell, ior)
                      and is followed inside the solid, where it may leave
                      through another facet or be reflected back from
                      inside (§6.1's rays from below); what reaches the bulk
                      below the grooves goes to trace() with inside = 1.
                      1: a thin pane (window glass, Figure 21d): transmitted
                      light keeps its direction and goes straight to trace()
                      with inside = 1; with fresnel, the pane's two faces
                      sum to R' = 2F/(1 + F), T' = (1 - F)/(1 + F) */
} gr_specular_t;

/* Host ray-trace callback (§6.2): the radiance arriving along dir (unit,
   texture space) at origin (texture space u, v, w: the centre of the
   segment piece the rays leave from). inside = 0: rays that left the
   grooved surface upward (Σ r_i < 1 at that bounce); inside = 1: rays in
   the material that reached the bulk below the grooves, or passed a thin
   pane (the host owns what lies there, e.g. the room behind a window).
   depth: the bounce it leaves at (0 = the footprint's own rays). weight:
   the mean throughput it carries (informative, e.g. for Russian roulette;
   the library applies it). */
typedef void (*gr_trace_fn)(void *user, const double origin[3], const double dir[3], int depth, int inside,
                            double weight, double rgb[3]);

/* Indirect illumination settings (§6). Zero means default. */
typedef struct gr_indirect_t {
    int depth;                      /* specular bounces, 0..GR_MAX_DEPTH; 0 = direct only */
    const gr_specular_t *specular;  /* indexed by reflectance id; ids outside
                                       [0, specular_count) neither reflect nor transmit */
    int specular_count;
    gr_brdf_fn brdf;                /* direct term at every bounce (optional) */
    void *brdf_user;
    gr_trace_fn trace;              /* §6.2 (optional: without it escaping light is 0) */
    void *trace_user;
} gr_indirect_t;

/* §6: specular inter-reflection and transmission inside and between
   grooves, on gr_query_lines()'s segments (query->line_samples of them,
   combined with the same Jones & Perry weights). On each segment, each
   interval's facet gets its direct term Σ_k lit_k brdf(...) (eq. 6); if
   depth allows and its id reflects or transmits (gr_specular_t), the
   facet's visible piece becomes the next footprint (§6.1: the piece of the
   facet the segment sees, a 3D segment on the facet; projecting it back to
   UV along E_r, as the paper does, gives the same rays), seen along the
   mirror direction E_r with throughput r_i k_r, and along the refracted
   direction E_t (Snell with the id's ior) with r_i k_t; with fresnel set,
   k_r F and k_t (1 - F). Refracted rays run inside the solid: they leave
   it through another facet (refracted again, or reflected back inside,
   totally when past the critical angle), or reach the bulk below the
   grooves. Rays of a bounce may leave from below the texture plane and
   point up or down (E_w < 0 in the paper's terms): the 1D ray
   classification is the same for any direction and either medium, which
   is §6.1's inverted masking order. What a bounce's rays do not meet
   (Σ r_i < 1) goes to trace() with weight 1 - Σ r_i (§6.2): inside = 0 for
   rays leaving up into the scene, inside = 1 for rays reaching the bulk
   (or passing a thin pane). Rays inside the material are followed 64
   scene scales (w + h + d) along the surface; beyond, they count as bulk
   light. Direct light (brdf) is added on the outside only. Recursion runs
   on an explicit stack of GR_INDIRECT_STACK segments in the scratch: when
   a footprint needs more, the pieces that do not fit leave along their
   direction to trace() unexamined, stats->flags gets GR_STATS_STACK_FULL
   and the call returns GR_ERR_STACK_FULL with rgb filled (approximate).
   Uses gr_query_scratch_bytes() of scratch. Errors as gr_query_lines(),
   plus GR_ERR_INVALID_ARG for a NULL indirect or rgb, depth outside
   0..GR_MAX_DEPTH, specular_count < 0 or specular NULL with a count. */
GR_DEF gr_result_t gr_shade_indirect(const gr_grid_t *grid, const gr_query_t *query, const gr_indirect_t *indirect,
                                     void *scratch, size_t scratch_bytes, double rgb[3], gr_line_stats_t *stats);
#endif
/* ==== [end section: interreflection] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_GR_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef GR_IMPLEMENTATION
#ifndef FILIGREE_GR_IMPLEMENTATION_DONE
#define FILIGREE_GR_IMPLEMENTATION_DONE

#ifndef GR_ASSERT
#  include <assert.h>
#  define GR_ASSERT(c) assert(c)
#endif
#if defined(GR_MALLOC) != defined(GR_FREE)
#  error "define both GR_MALLOC and GR_FREE, or neither"
#endif
#ifndef GR_MALLOC
#  include <stdlib.h>
#  define GR_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define GR_FREE(p, ctx) ((void)(ctx), free(p))
#endif
#include <stdio.h>  /* snprintf for diagnostics */
#include <float.h>  /* DBL_EPSILON */
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Named tolerances ---------------------------------------------------- */
/* A cross-section end with |w| below this fraction of the section's extent
   counts as w = 0 (and is snapped to 0): authoring tools round. */
#define GR__SECTION_END_REL 1e-12
/* A path shorter than this fraction of the tile diagonal has zero length. */
#define GR__ZERO_LENGTH_REL 1e-12
/* A footprint segment S shorter than this fraction of the grooves' half
   width w is a point sample: its ratios become 0 or 1 (the limit). */
#define GR__POINT_FOOTPRINT_REL 1e-12
/* Facet normals (unit vectors) closer than this per component are the same
   orientation and share one facet-list entry. */
#define GR__NORMAL_MERGE_EPS 1e-9
/* dp/du x dp/dv below this fraction of |dp/du||dp/dv| is a degenerate
   parameterisation (no footprint can be solved for). */
#define GR__DEGENERATE_UV_REL 1e-12
/* Bézier pieces are cut into this many sub-pieces for gridding; each
   sub-piece's control points bound it (convex hull), so gridding is exact
   up to that bound. */
#define GR__CURVE_GRID_SPLITS 8
/* Nearest point on a Bézier piece: samples to start from, Newton steps. */
#define GR__CURVE_SAMPLES 8
#define GR__CURVE_NEWTON 8
/* Smallest step in the path parameter t for the perturbation's slope. */
#define GR__PERTURB_STEP 1e-6
/* Grazing directions: the projection's (E_b, E_w) is scaled to unit max
   norm and E_w raised to at least this, i.e. |tan θ'| <= 1e150, so that
   E_w x stays far above underflow; steeper views give their limit to
   double precision (every height projects 1e150 times farther than any
   footprint). */
#define GR__GRAZING_MIN_W 1e-150
/* The region methods (the polygon path, line samples and the bounces
   of gr_shade_indirect) take a view or a light lower than this (the sine
   of its elevation) at this elevation, with its azimuth. Their search box
   grows by (h + d) / e_w and the coordinates with it, while the areas
   must resolve the tie tolerance (1e-9 of the sections' size): at an X
   crossing the polygon path's ratios summed to 1 within 1e-10 at
   e_w = 1e-7, 3e-8 at 1e-9, 5e-6 at 3e-12 and 0.92 below 2e-12; line
   samples lost the ground's share from 3e-15 and every groove at the
   smallest subnormal. At this elevation every ray from the footprint runs
   1e6 scene scales (w + h + d) before it leaves the grooves' depth range,
   so the answer is the grazing limit for footprints and blockers within
   that reach (test_grooves_stiff: extreme_views_at_a_crossing,
   extreme_lights_at_a_crossing_and_an_end). */
#define GR__REGION_MIN_ELEVATION 1e-6
/* Default query settings (documented in gr_query_t). */
#define GR__DEFAULT_OVERSAMPLE_TOL 0.05
#define GR__DEFAULT_MAX_OVERSAMPLE 8
#define GR__LIMIT_MAX_OVERSAMPLE 64
#define GR__DEFAULT_PARALLEL_TOL 0.02
/* Path ends this close (relative to the tile diagonal) modulo the tile of
   a repeating texture meet across the seam: the path is closed. */
#define GR__SEAM_CLOSED_REL 1e-12
/* Largest turn (radians) of a facet normal along a curved path between the
   footprint and where the view ray meets the facet (gr__hit_normal): past
   it the straight approximation of the occlusion means little anyway. */
#define GR__TURN_MAX 1.0
/* Smallest stretch 1 - kappa f b of a curved sweep taken (gr__stretch),
   and smallest denominator of the secant solve for the scale where a ray
   meets a perturbed groove (gr__ray_point; below it the secant's own end
   is used): both only guard the local model past its range. */
#define GR__STRETCH_MIN 0.25
#define GR__RAY_SECANT_MIN 0.5
/* gr__ray_point takes its second secant step only when the first moved
   the scale by more than this fraction of f. */
#define GR__RAY_SECOND_STEP 1e-3
#define GR__PI 3.14159265358979323846
/* Intervals shorter than this fraction of an elliptical footprint's radius
   integrate its semicircle density by the midpoint rule (relative error
   ~ 1e-9 away from the rim) rather than as a difference of its integral,
   which would lose their relative precision (gr__xmass). */
#define GR__DISC_MIDPOINT 1e-4
/* Automatic grid resolution: about this many cells per groove and axis,
   capped, so a small footprint box meets few paths. */
#define GR__AUTO_CELLS_PER_SQRT_GROOVE 2.0
#define GR__AUTO_ITEMS_PER_CELL 8.0
#define GR__AUTO_CELLS_MAX 512

GR_DEF const char *gr_result_string(gr_result_t r)
{
    switch (r) {
    case GR_OK: return "ok";
    case GR_ERR_INVALID_ARG: return "invalid argument";
    case GR_ERR_OUT_OF_MEMORY: return "out of memory";
    case GR_ERR_BUFFER_TOO_SMALL: return "buffer too small";
    case GR_ERR_NOT_FINITE: return "NaN or infinite coordinate";
    case GR_ERR_EMPTY_GRID: return "empty grid (no grooves or empty domain)";
    case GR_ERR_PATH_POINTS: return "wrong number of path points";
    case GR_ERR_ZERO_LENGTH_PATH: return "zero-length path";
    case GR_ERR_SECTION_POINTS: return "cross-section has fewer than 2 points";
    case GR_ERR_SECTION_ENDS: return "cross-section first or last w is not 0";
    case GR_ERR_SECTION_ORDER: return "cross-section does not run from low to high b";
    case GR_ERR_PERTURBATION: return "perturbation without a valid perturb_max";
    case GR_ERR_UNSUPPORTED: return "feature left out at compile time";
    case GR_ERR_STACK_FULL: return "indirect light: recursion stack full (result approximate)";
    case GR_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* ---- Private records ---------------------------------------------------- */

typedef struct gr__groove_t {
    int kind;              /* gr_path_kind_t */
    int first_point;       /* index of its first (u, v) pair in points_ */
    int point_count;
    int first_sec;         /* index of its first (b, w) pair in section_ */
    int sec_count;
    int first_facet;       /* into facet_refl_ and blocker_start_ */
    int pieces;            /* segments (polyline) or Bézier pieces */
    int closed;            /* first point == last point, or on a repeating
                              tile the same point across the seam: no ends */
    double length;         /* polyline arc length (t = s / length) */
    double half_width;     /* max |b| of the section, times fmax */
    double up, down;       /* max w and max -w of the section, times fmax */
    double fmax;           /* perturb_max, or 1 */
    double bbox[4];        /* control-point bounds of the path */
    gr_perturb_fn perturb;
    void *perturb_user;
    /* self-crossing grooves (§5): a groove's pieces are records
       first_split .. first_split + split_count - 1; a piece covers the
       parameters [t0, t1] of its groove `parent` (itself for a groove),
       and its ends with join[e] set continue into the next piece */
    int parent, first_split, split_count, join[2];
    double t0, t1;
} gr__groove_t;

static void gr__diag(gr_diag_t *diag, gr_result_t r, long long element, const char *msg)
{
    if (!diag) return;
    diag->result = r;
    diag->element = element;
    if (element >= 0) snprintf(diag->message, sizeof diag->message, "groove %lld: %s", element, msg);
    else snprintf(diag->message, sizeof diag->message, "%s", msg);
}

static int gr__finite(double x) { return x - x == 0.0; }

/* Number of pieces a path of this kind and point count has; 0 if invalid. */
static int gr__pieces(int kind, int n)
{
    if (kind == GR_PATH_POLYLINE) return n >= 2 ? n - 1 : 0;
    if (kind == GR_PATH_QUADRATIC) return n >= 3 && (n - 1) % 2 == 0 ? (n - 1) / 2 : 0;
    if (kind == GR_PATH_CUBIC) return n >= 4 && (n - 1) % 3 == 0 ? (n - 1) / 3 : 0;
    return 0;
}
static int gr__degree(int kind) { return kind == GR_PATH_QUADRATIC ? 2 : kind == GR_PATH_CUBIC ? 3 : 1; }

/* The tile [u0,u1]x[v0,v1] of a desc (all zero means the unit square). */
static void gr__domain(const gr_grid_desc_t *desc, double dom[4])
{
    if (desc->domain[0] == 0 && desc->domain[1] == 0 && desc->domain[2] == 0 && desc->domain[3] == 0) {
        dom[0] = 0; dom[1] = 0; dom[2] = 1; dom[3] = 1;
    } else {
        memcpy(dom, desc->domain, sizeof(double) * 4);
    }
}

/* Validate one groove description; on error fill diag and return the code. */
static gr_result_t gr__check_groove(const gr_groove_desc_t *g, long long idx, double diag_len, gr_diag_t *diag)
{
    char msg[120];
    int i, pieces;
    double len = 0, ext = 0;
    if (g->kind != GR_PATH_POLYLINE && g->kind != GR_PATH_QUADRATIC && g->kind != GR_PATH_CUBIC) {
        gr__diag(diag, GR_ERR_INVALID_ARG, idx, "unknown path kind");
        return GR_ERR_INVALID_ARG;
    }
#ifdef GR_NO_CURVES
    if (g->kind != GR_PATH_POLYLINE) {
        gr__diag(diag, GR_ERR_UNSUPPORTED, idx, "Bézier path, but built with GR_NO_CURVES");
        return GR_ERR_UNSUPPORTED;
    }
#endif
    if (!g->points) { gr__diag(diag, GR_ERR_INVALID_ARG, idx, "points is NULL"); return GR_ERR_INVALID_ARG; }
    pieces = gr__pieces((int)g->kind, g->point_count);
    if (!pieces) {
        snprintf(msg, sizeof msg, "path has %d point%s; %s", g->point_count, g->point_count == 1 ? "" : "s",
                 g->kind == GR_PATH_QUADRATIC ? "a quadratic chain needs 2k+1 (k >= 1)"
                 : g->kind == GR_PATH_CUBIC   ? "a cubic chain needs 3k+1 (k >= 1)"
                                              : "a polyline needs at least 2");
        gr__diag(diag, GR_ERR_PATH_POINTS, idx, msg);
        return GR_ERR_PATH_POINTS;
    }
    for (i = 0; i < 2 * g->point_count; i++)
        if (!gr__finite(g->points[i])) {
            snprintf(msg, sizeof msg, "path point %d is not finite", i / 2);
            gr__diag(diag, GR_ERR_NOT_FINITE, idx, msg);
            return GR_ERR_NOT_FINITE;
        }
    /* control-polygon length: zero exactly when every point coincides */
    for (i = 1; i < g->point_count; i++)
        len += hypot(g->points[2 * i] - g->points[2 * i - 2], g->points[2 * i + 1] - g->points[2 * i - 1]);
    if (!(len > GR__ZERO_LENGTH_REL * diag_len)) {
        gr__diag(diag, GR_ERR_ZERO_LENGTH_PATH, idx, "path has zero length");
        return GR_ERR_ZERO_LENGTH_PATH;
    }
    if (!g->section) { gr__diag(diag, GR_ERR_INVALID_ARG, idx, "section is NULL"); return GR_ERR_INVALID_ARG; }
    if (g->section_count < 2) {
        snprintf(msg, sizeof msg, "cross-section has %d point%s", g->section_count, g->section_count == 1 ? "" : "s");
        gr__diag(diag, GR_ERR_SECTION_POINTS, idx, msg);
        return GR_ERR_SECTION_POINTS;
    }
    for (i = 0; i < 2 * g->section_count; i++) {
        if (!gr__finite(g->section[i])) {
            snprintf(msg, sizeof msg, "cross-section point %d is not finite", i / 2);
            gr__diag(diag, GR_ERR_NOT_FINITE, idx, msg);
            return GR_ERR_NOT_FINITE;
        }
        if (fabs(g->section[i]) > ext) ext = fabs(g->section[i]);
    }
    if (fabs(g->section[1]) > GR__SECTION_END_REL * ext ||
        fabs(g->section[2 * g->section_count - 1]) > GR__SECTION_END_REL * ext) {
        snprintf(msg, sizeof msg, "cross-section %s point has w = %g, not 0",
                 fabs(g->section[1]) > GR__SECTION_END_REL * ext ? "first" : "last",
                 fabs(g->section[1]) > GR__SECTION_END_REL * ext ? g->section[1] : g->section[2 * g->section_count - 1]);
        gr__diag(diag, GR_ERR_SECTION_ENDS, idx, msg);
        return GR_ERR_SECTION_ENDS;
    }
    if (!(g->section[2 * g->section_count - 2] > g->section[0])) {
        gr__diag(diag, GR_ERR_SECTION_ORDER, idx, "cross-section's last b is not above its first b");
        return GR_ERR_SECTION_ORDER;
    }
    if (g->perturb && !(gr__finite(g->perturb_max) && g->perturb_max > 0)) {
        snprintf(msg, sizeof msg, "perturbation needs perturb_max > 0 (got %g)", g->perturb_max);
        gr__diag(diag, GR_ERR_PERTURBATION, idx, msg);
        return GR_ERR_PERTURBATION;
    }
    return GR_OK;
}

/* Grid geometry shared by the builder and the query. */
typedef struct gr__cells_t {
    double u0, v0, cu, cv; /* origin and cell size */
    int nu, nv, wrap;
} gr__cells_t;

static int gr__imod(long long a, int n) { long long r = a % n; return (int)(r < 0 ? r + n : r); }

/* Unwrapped cell coordinate of u (floor), clamped to a safe integer range. */
static long long gr__cell_coord(double x, double origin, double size)
{
    double c = floor((x - origin) / size);
    if (c > 1e15) c = 1e15;
    if (c < -1e15) c = -1e15;
    return (long long)c;
}

/* Map an unwrapped cell range [a, b] to at most n indices (wrapping or
   clamping); returns the first index and count of the range. */
static void gr__cell_range(long long a, long long b, int n, int wrap, int *first, int *count)
{
    if (wrap) {
        if (b - a + 1 >= n) { *first = 0; *count = n; return; }
        *first = gr__imod(a, n);
        *count = (int)(b - a + 1);
        return;
    }
    if (a < 0) a = 0;
    if (b > n - 1) b = n - 1;
    if (a > n - 1) a = n - 1;
    if (b < 0) b = 0;
    *first = (int)a;
    *count = (int)(b - a + 1);
}

/* Visit every cell of a UV box: counts (counts != NULL) or appends groove g
   to each cell's list, skipping a cell whose last item already is g. */
static void gr__mark_box(const gr__cells_t *c, const double box[4], int g, int *counts,
                         const int *start, int *fill, int *items)
{
    int fu, nu_, fv, nv_, i, j;
    gr__cell_range(gr__cell_coord(box[0], c->u0, c->cu), gr__cell_coord(box[2], c->u0, c->cu), c->nu, c->wrap, &fu, &nu_);
    gr__cell_range(gr__cell_coord(box[1], c->v0, c->cv), gr__cell_coord(box[3], c->v0, c->cv), c->nv, c->wrap, &fv, &nv_);
    for (j = 0; j < nv_; j++)
        for (i = 0; i < nu_; i++) {
            int cell = ((fv + j) % c->nv) * c->nu + (fu + i) % c->nu;
            if (counts) { counts[cell]++; continue; }
            if (fill[cell] > 0 && items[start[cell] + fill[cell] - 1] == g) continue;
            items[start[cell] + fill[cell]++] = g;
        }
}

/* Bounds of control points p[0..n-1] (pairs). */
static void gr__bounds(const double *p, int n, double box[4])
{
    int i;
    box[0] = box[2] = p[0];
    box[1] = box[3] = p[1];
    for (i = 1; i < n; i++) {
        if (p[2 * i] < box[0]) box[0] = p[2 * i];
        if (p[2 * i] > box[2]) box[2] = p[2 * i];
        if (p[2 * i + 1] < box[1]) box[1] = p[2 * i + 1];
        if (p[2 * i + 1] > box[3]) box[3] = p[2 * i + 1];
    }
}

/* de Casteljau split of a degree-n Bézier (n <= 3) at t: left and right
   control points (either may be NULL). */
static void gr__bezier_split(const double *p, int n, double t, double *left, double *right)
{
    double q[8];
    int k, i;
    memcpy(q, p, sizeof(double) * 2 * (size_t)(n + 1));
    for (k = 0; k <= n; k++) {
        /* level k holds n-k+1 points: its first is left[k], its last right[n-k] */
        if (left) { left[2 * k] = q[0]; left[2 * k + 1] = q[1]; }
        if (right) { right[2 * (n - k)] = q[2 * (n - k)]; right[2 * (n - k) + 1] = q[2 * (n - k) + 1]; }
        for (i = 0; i < n - k; i++) {
            q[2 * i] = (1 - t) * q[2 * i] + t * q[2 * i + 2];
            q[2 * i + 1] = (1 - t) * q[2 * i + 1] + t * q[2 * i + 3];
        }
    }
}

/* Control points of the Bézier restricted to [t0, t1]. */
static void gr__bezier_sub(const double *p, int n, double t0, double t1, double *out)
{
    double l[8];
    gr__bezier_split(p, n, t1, l, NULL);
    gr__bezier_split(l, n, t1 > 0 ? t0 / t1 : 0, NULL, out);
}

/* ---- Grid build (§3 bounds and blockers, §4.1 uniform grid) ------------- */

#ifndef GR_NO_INTERSECTIONS
/* [section: intersections] the builder's part of §5: a path's
   self-intersections, and the cut of a self-crossing groove into pieces */
static int gr__path_self_hits(const double *pts, int kind, int n, int closed, int g, struct gr_self_hit_t *out, int cap);
static void gr__split_groove(gr_grid_t *gr, int g, struct gr_self_hit_t *hits, int nh, int *next, int *pt);
static int gr__path_closed(const double *p, int n, int wrap, const double dom[4]);
#endif

/* Everything the size query and the builder agree on. */
typedef struct gr__plan_t {
    double dom[4];
    gr__cells_t cells;
    int groove_count, total_points, total_section, total_facets, total_blockers;
    int self_hits, split_records, split_points; /* §5: upper bounds for the pieces */
    long long item_capacity;
    size_t off_grooves, off_points, off_section, off_refl, off_bstart, off_blockers,
        off_cstart, off_ccount, off_items, off_astart, off_aitems, off_rowsum, off_self, bytes;
} gr__plan_t;

static size_t gr__align8(size_t x) { return (x + 7u) & ~(size_t)7u; }

/* Calls fn for each gridding box of a groove's path: one per polyline
   segment, GR__CURVE_GRID_SPLITS control-point boxes per Bézier piece. */
static long long gr__path_boxes(const gr__cells_t *c, const double *pts, int kind, int n, int g,
                                int *counts, const int *start, int *fill, int *items)
{
    int deg = gr__degree(kind), pieces = gr__pieces(kind, n), k, s;
    long long cells = 0;
    for (k = 0; k < pieces; k++) {
        const double *p = pts + 2 * k * deg;
        int splits = deg == 1 ? 1 : GR__CURVE_GRID_SPLITS;
        for (s = 0; s < splits; s++) {
            double sub[8], box[4];
            int fu, nu_, fv, nv_;
            if (deg == 1) memcpy(sub, p, sizeof(double) * 4);
            else gr__bezier_sub(p, deg, (double)s / splits, (double)(s + 1) / splits, sub);
            gr__bounds(sub, deg + 1, box);
            gr__cell_range(gr__cell_coord(box[0], c->u0, c->cu), gr__cell_coord(box[2], c->u0, c->cu), c->nu, c->wrap, &fu, &nu_);
            gr__cell_range(gr__cell_coord(box[1], c->v0, c->cv), gr__cell_coord(box[3], c->v0, c->cv), c->nv, c->wrap, &fv, &nv_);
            cells += (long long)nu_ * nv_;
            if (counts || items) gr__mark_box(c, box, g, counts, start, fill, items);
        }
    }
    return cells;
}

/* Anchor cell of a groove: the cell of its first point. */
static int gr__anchor_cell(const gr__cells_t *c, const double *p)
{
    int fu, nu_, fv, nv_;
    long long a = gr__cell_coord(p[0], c->u0, c->cu), b = gr__cell_coord(p[1], c->v0, c->cv);
    gr__cell_range(a, a, c->nu, c->wrap, &fu, &nu_);
    gr__cell_range(b, b, c->nv, c->wrap, &fv, &nv_);
    return fv * c->nu + fu;
}

static int gr__facet_blocks(const double *sec, int i, int j)
{
    double lowest_i = sec[2 * i + 1] < sec[2 * i + 3] ? sec[2 * i + 1] : sec[2 * i + 3];
    return j != i && (sec[2 * j + 1] > lowest_i || sec[2 * j + 3] > lowest_i);
}

/* Consecutive grooves passing the same section array share its storage
   and blocker lists (§3: one cross-section for many paths is the rule). */
static int gr__shares_section(const gr_grid_desc_t *desc, int g)
{
    return g > 0 && desc->grooves[g].section == desc->grooves[g - 1].section &&
           desc->grooves[g].section_count == desc->grooves[g - 1].section_count;
}

/* The grid's domain and its cell counts as asked: GR_OK, or the error. */
static gr_result_t gr__plan_domain(const gr_grid_desc_t *desc, gr__plan_t *pl, gr_diag_t *diag)
{
    int i;
    gr__domain(desc, pl->dom);
    for (i = 0; i < 4; i++)
        if (!gr__finite(pl->dom[i])) { gr__diag(diag, GR_ERR_NOT_FINITE, -1, "domain is not finite"); return GR_ERR_NOT_FINITE; }
    if (!(pl->dom[2] > pl->dom[0] && pl->dom[3] > pl->dom[1])) {
        gr__diag(diag, GR_ERR_EMPTY_GRID, -1, "domain is empty (u1 <= u0 or v1 <= v0)");
        return GR_ERR_EMPTY_GRID;
    }
    if (desc->cells_u < 0 || desc->cells_v < 0 || desc->cells_u > 65536 || desc->cells_v > 65536 ||
        (long long)desc->cells_u * desc->cells_v > 16777216LL) {
        gr__diag(diag, GR_ERR_INVALID_ARG, -1, "cells_u, cells_v out of range (0..65536, product <= 2^24)");
        return GR_ERR_INVALID_ARG;
    }
    return GR_OK;
}

/* Each groove checked, and the totals of points, section points, facets
   and blockers (shared sections counted once). */
static gr_result_t gr__plan_totals(const gr_grid_desc_t *desc, gr__plan_t *pl, gr_diag_t *diag)
{
    double diag_len = hypot(pl->dom[2] - pl->dom[0], pl->dom[3] - pl->dom[1]);
    int g, i, j;
    for (g = 0; g < desc->groove_count; g++) {
        const gr_groove_desc_t *gd = &desc->grooves[g];
        gr_result_t r = gr__check_groove(gd, g, diag_len, diag);
        if (r != GR_OK) return r;
        pl->total_points += gd->point_count;
        pl->total_facets += gd->section_count - 1;
        if (!gr__shares_section(desc, g)) {
            pl->total_section += gd->section_count;
            for (i = 0; i + 1 < gd->section_count; i++)
                for (j = 0; j + 1 < gd->section_count; j++) pl->total_blockers += gr__facet_blocks(gd->section, i, j);
        }
        if (pl->total_points > 100000000 || pl->total_section > 100000000 || pl->total_blockers > 200000000) {
            gr__diag(diag, GR_ERR_INVALID_ARG, g, "too many points in total (> 1e8)");
            return GR_ERR_INVALID_ARG;
        }
    }
    return GR_OK;
}

/* The automatic cell count per axis: long paths cross about n cells per
   tile length, so aim at GR__AUTO_ITEMS_PER_CELL paths per cell, and at
   least GR__AUTO_CELLS_PER_SQRT_GROOVE sqrt(G) cells per axis for short
   ones. */
static int gr__auto_cells(const gr_grid_desc_t *desc, const double dom[4])
{
    double total = 0, tile = 0.5 * ((dom[2] - dom[0]) + (dom[3] - dom[1])), want;
    int g, i;
    for (g = 0; g < desc->groove_count; g++) {
        const gr_groove_desc_t *gd = &desc->grooves[g];
        for (i = 1; i < gd->point_count; i++)
            total += sqrt((gd->points[2 * i] - gd->points[2 * i - 2]) * (gd->points[2 * i] - gd->points[2 * i - 2]) +
                          (gd->points[2 * i + 1] - gd->points[2 * i - 1]) * (gd->points[2 * i + 1] - gd->points[2 * i - 1]));
    }
    want = GR__AUTO_CELLS_PER_SQRT_GROOVE * sqrt((double)desc->groove_count);
    if (total / tile / GR__AUTO_ITEMS_PER_CELL > want) want = total / tile / GR__AUTO_ITEMS_PER_CELL;
    return want < GR__AUTO_CELLS_MAX ? (int)ceil(want) : GR__AUTO_CELLS_MAX;
}

#ifndef GR_NO_INTERSECTIONS
/* §5: the self-intersections, and room for the pieces they cut a groove
   into (at most three cuts per hit, gr__split_groove). */
static gr_result_t gr__plan_self_hits(const gr_grid_desc_t *desc, gr__plan_t *pl, gr_diag_t *diag)
{
    int g;
    for (g = 0; g < desc->groove_count; g++) {
        const gr_groove_desc_t *gd = &desc->grooves[g];
        int nh = gr__path_self_hits(gd->points, (int)gd->kind, gd->point_count,
                                    gr__path_closed(gd->points, gd->point_count, pl->cells.wrap, pl->dom), g, NULL, 0);
        if (nh > 100000000 - pl->self_hits) {
            gr__diag(diag, GR_ERR_INVALID_ARG, g, "too many self-intersections in total (> 1e8)");
            return GR_ERR_INVALID_ARG;
        }
        pl->self_hits += nh;
        if (nh > 0) {
            pl->split_records += 3 * nh + 1;
            pl->split_points += gd->point_count + 4 * (3 * nh + 1);
        }
    }
    return GR_OK;
}
#endif

/* The grid block's layout: each array's offset, and its size. */
static void gr__plan_layout(gr__plan_t *pl)
{
    size_t nc = (size_t)pl->cells.nu * (size_t)pl->cells.nv, off = gr__align8(sizeof(gr_grid_t));
    pl->off_grooves = off;
    off = gr__align8(off + sizeof(gr__groove_t) * ((size_t)pl->groove_count + (size_t)pl->split_records));
    pl->off_points = off;
    off = gr__align8(off + sizeof(double) * 2 * ((size_t)pl->total_points + (size_t)pl->split_points));
    pl->off_section = off; off = gr__align8(off + sizeof(double) * 2 * (size_t)pl->total_section);
    pl->off_refl = off; off = gr__align8(off + sizeof(int) * (size_t)pl->total_facets);
    pl->off_bstart = off; off = gr__align8(off + sizeof(int) * ((size_t)pl->total_section + 1));
    pl->off_blockers = off; off = gr__align8(off + sizeof(int) * (size_t)pl->total_blockers);
    pl->off_cstart = off; off = gr__align8(off + sizeof(int) * (nc + 1));
    pl->off_ccount = off; off = gr__align8(off + sizeof(int) * nc);
    pl->off_items = off; off = gr__align8(off + sizeof(int) * (size_t)pl->item_capacity);
    pl->off_astart = off; off = gr__align8(off + sizeof(int) * (nc + 1));
    pl->off_aitems = off; off = gr__align8(off + sizeof(int) * (size_t)pl->groove_count);
    pl->off_rowsum = off; off = gr__align8(off + sizeof(int) * (size_t)pl->cells.nv * ((size_t)pl->cells.nu + 1));
#ifndef GR_NO_INTERSECTIONS
    pl->off_self = off; off = gr__align8(off + sizeof(gr_self_hit_t) * (size_t)pl->self_hits);
#endif
    pl->bytes = off;
}

static gr_result_t gr__plan(const gr_grid_desc_t *desc, gr__plan_t *pl, gr_diag_t *diag)
{
    int g, autoc;
    gr_result_t r;
    if (diag) { diag->result = GR_OK; diag->element = -1; diag->message[0] = 0; }
    if (!desc) { gr__diag(diag, GR_ERR_INVALID_ARG, -1, "desc is NULL"); return GR_ERR_INVALID_ARG; }
    memset(pl, 0, sizeof *pl);
    if (desc->groove_count <= 0 || !desc->grooves) {
        gr__diag(diag, GR_ERR_EMPTY_GRID, -1, "grid has no grooves");
        return GR_ERR_EMPTY_GRID;
    }
    if ((r = gr__plan_domain(desc, pl, diag)) != GR_OK || (r = gr__plan_totals(desc, pl, diag)) != GR_OK) return r;
    pl->groove_count = desc->groove_count;
    autoc = desc->cells_u && desc->cells_v ? 0 : gr__auto_cells(desc, pl->dom);
    pl->cells.nu = desc->cells_u ? desc->cells_u : autoc;
    pl->cells.nv = desc->cells_v ? desc->cells_v : autoc;
    pl->cells.u0 = pl->dom[0];
    pl->cells.v0 = pl->dom[1];
    pl->cells.cu = (pl->dom[2] - pl->dom[0]) / pl->cells.nu;
    pl->cells.cv = (pl->dom[3] - pl->dom[1]) / pl->cells.nv;
    pl->cells.wrap = !desc->no_wrap;
#ifndef GR_NO_INTERSECTIONS
    if ((r = gr__plan_self_hits(desc, pl, diag)) != GR_OK) return r;
#endif
    for (g = 0; g < desc->groove_count; g++) {
        const gr_groove_desc_t *gd = &desc->grooves[g];
        pl->item_capacity += gr__path_boxes(&pl->cells, gd->points, (int)gd->kind, gd->point_count, g, NULL, NULL, NULL, NULL);
        if (pl->item_capacity > 400000000LL) {
            gr__diag(diag, GR_ERR_INVALID_ARG, g, "grid cell lists too large (> 4e8 entries): use fewer cells");
            return GR_ERR_INVALID_ARG;
        }
    }
    gr__plan_layout(pl);
    return GR_OK;
}

GR_DEF gr_result_t gr_grid_size(const gr_grid_desc_t *desc, size_t *bytes, gr_diag_t *diag)
{
    gr__plan_t pl;
    gr_result_t r;
    if (!bytes) { gr__diag(diag, GR_ERR_INVALID_ARG, -1, "bytes is NULL"); return GR_ERR_INVALID_ARG; }
    r = gr__plan(desc, &pl, diag);
    *bytes = r == GR_OK ? pl.bytes : 0;
    return r;
}

/* A path with no ends: its first point is its last or, on a repeating
   tile, the same point across the seam (ends a whole number of tiles
   apart: the path runs on across it, §4.1 wrap, as one closed path). */
static int gr__path_closed(const double *p, int n, int wrap, const double dom[4])
{
    int last = n - 1;
    double wu = dom[2] - dom[0], wv = dom[3] - dom[1], du = p[2 * last] - p[0], dv = p[2 * last + 1] - p[1];
    if (p[0] == p[2 * last] && p[1] == p[2 * last + 1]) return 1;
    if (!wrap) return 0;
    du -= floor(du / wu + 0.5) * wu;
    dv -= floor(dv / wv + 0.5) * wv;
    return hypot(du, dv) <= GR__SEAM_CLOSED_REL * hypot(wu, wv);
}

/* Copy one groove into the flat arrays and fill its record (§3 bounds).
   A section shared with the previous groove is not copied again. */
static void gr__store_groove(gr_grid_t *gr, const gr_groove_desc_t *gd, int g, int shared, int *pt, int *sc, int *fc, int *bc)
{
    gr__groove_t *rec = &gr->grooves_[g];
    int n = gd->section_count, i, j, first_sec = shared ? gr->grooves_[g - 1].first_sec : *sc;
    double maxb = 0, maxw = 0, minw = 0;
    memset(rec, 0, sizeof *rec);
    rec->kind = (int)gd->kind;
    rec->first_point = *pt;
    rec->point_count = gd->point_count;
    rec->first_sec = first_sec;
    rec->sec_count = n;
    rec->first_facet = *fc;
    rec->pieces = gr__pieces(rec->kind, gd->point_count);
    rec->fmax = gd->perturb ? gd->perturb_max : 1.0;
    rec->perturb = gd->perturb;
    rec->perturb_user = gd->perturb_user;
    memcpy(gr->points_ + 2 * *pt, gd->points, sizeof(double) * 2 * (size_t)gd->point_count);
    if (!shared) {
        memcpy(gr->section_ + 2 * first_sec, gd->section, sizeof(double) * 2 * (size_t)n);
        /* snap rounded ends to exactly 0 (checked against GR__SECTION_END_REL) */
        gr->section_[2 * first_sec + 1] = 0;
        gr->section_[2 * (first_sec + n - 1) + 1] = 0;
        /* blockers of facet i: blockers_[blocker_start_[s+i] .. blocker_start_[s+i+1]) */
        for (i = 0; i + 1 < n; i++) {
            gr->blocker_start_[first_sec + i] = *bc;
            for (j = 0; j + 1 < n; j++)
                if (gr__facet_blocks(gd->section, i, j)) gr->blockers_[(*bc)++] = j;
        }
        gr->blocker_start_[first_sec + n - 1] = *bc;
        gr->blocker_start_[first_sec + n] = *bc;
        *sc += n;
    }
    for (i = 0; i < n; i++) {
        double b = gr->section_[2 * (first_sec + i)], w = gr->section_[2 * (first_sec + i) + 1];
        if (fabs(b) > maxb) maxb = fabs(b);
        if (w > maxw) maxw = w;
        if (w < minw) minw = w;
    }
    rec->half_width = maxb * rec->fmax;
    rec->up = maxw * rec->fmax;
    rec->down = -minw * rec->fmax;
    gr__bounds(gd->points, gd->point_count, rec->bbox);
    rec->parent = g;
    rec->t1 = 1;
    {
        const double *p = gd->points;
        int last = gd->point_count - 1;
        rec->closed = gr__path_closed(p, gd->point_count, gr->wrap, gr->domain);
        rec->length = 0;
        if (rec->kind == GR_PATH_POLYLINE)
            for (i = 0; i < last; i++) rec->length += hypot(p[2 * i + 2] - p[2 * i], p[2 * i + 3] - p[2 * i + 1]);
    }
    for (i = 0; i + 1 < n; i++)
        gr->facet_refl_[*fc + i] = gd->facet_reflectance ? gd->facet_reflectance[i] : gd->reflectance;
    *pt += gd->point_count;
    *fc += n - 1;
}

static gr__cells_t gr__grid_cells(const gr_grid_t *gr)
{
    gr__cells_t c;
    c.u0 = gr->domain[0];
    c.v0 = gr->domain[1];
    c.nu = gr->cells_u;
    c.nv = gr->cells_v;
    c.cu = (gr->domain[2] - gr->domain[0]) / c.nu;
    c.cv = (gr->domain[3] - gr->domain[1]) / c.nv;
    c.wrap = gr->wrap;
    return c;
}

/* The grid's header and its arrays' places in the block (plan pl). */
static gr_grid_t *gr__grid_header(const gr_grid_desc_t *desc, const gr__plan_t *pl, char *base)
{
    gr_grid_t *gr = (gr_grid_t *)(void *)base;
    memset(gr, 0, sizeof *gr);
    gr->groove_count = pl->groove_count;
    gr->cells_u = pl->cells.nu;
    gr->cells_v = pl->cells.nv;
    memcpy(gr->domain, pl->dom, sizeof pl->dom);
    gr->wrap = pl->cells.wrap;
    gr->base_reflectance = desc->base_reflectance;
    gr->bytes = pl->bytes;
    gr->alloc_ctx = desc->alloc_ctx;
    gr->grooves_ = (gr__groove_t *)(void *)(base + pl->off_grooves);
    gr->points_ = (double *)(void *)(base + pl->off_points);
    gr->section_ = (double *)(void *)(base + pl->off_section);
    gr->facet_refl_ = (int *)(void *)(base + pl->off_refl);
    gr->blocker_start_ = (int *)(void *)(base + pl->off_bstart);
    gr->blockers_ = (int *)(void *)(base + pl->off_blockers);
    gr->cell_start_ = (int *)(void *)(base + pl->off_cstart);
    gr->cell_count_ = (int *)(void *)(base + pl->off_ccount);
    gr->cell_items_ = (int *)(void *)(base + pl->off_items);
    gr->anchor_start_ = (int *)(void *)(base + pl->off_astart);
    gr->anchor_items_ = (int *)(void *)(base + pl->off_aitems);
    gr->row_anchor_sum_ = (int *)(void *)(base + pl->off_rowsum);
    gr->total_points_ = pl->total_points;
    gr->total_section_ = pl->total_section;
    gr->total_facets_ = pl->total_facets;
    gr->item_capacity_ = (int)pl->item_capacity;
#ifndef GR_NO_INTERSECTIONS
    gr->self_ = (gr_self_hit_t *)(void *)(base + pl->off_self);
#endif
    return gr;
}

#ifndef GR_NO_INTERSECTIONS
/* §5: self-intersections found once, each self-crossing groove cut into
   pieces after the grooves (the grid's cells list the grooves only); *pt
   is the next free point. */
static void gr__split_self_hits(gr_grid_t *gr, const gr__plan_t *pl, int *pt)
{
    int next = pl->groove_count, h0, g;
    for (g = 0; g < pl->groove_count; g++) {
        const gr__groove_t *rec = &gr->grooves_[g];
        h0 = gr->self_count_;
        gr->self_count_ += gr__path_self_hits(gr->points_ + 2 * rec->first_point, rec->kind, rec->point_count, rec->closed, g,
                                              gr->self_ + h0, pl->self_hits - h0);
        if (gr->self_count_ > h0) gr__split_groove(gr, g, gr->self_ + h0, gr->self_count_ - h0, &next, pt);
    }
    GR_ASSERT(gr->self_count_ == pl->self_hits && next <= pl->groove_count + pl->split_records);
    gr->split_records_ = next - pl->groove_count;
}
#endif

/* The cell lists: counted (an upper bound), prefix-summed, filled without
   repeats. */
static void gr__fill_cells(gr_grid_t *gr, const gr__plan_t *pl)
{
    int g, i, nc = pl->cells.nu * pl->cells.nv;
    memset(gr->cell_start_, 0, sizeof(int) * ((size_t)nc + 1));
    memset(gr->cell_count_, 0, sizeof(int) * (size_t)nc);
    for (g = 0; g < pl->groove_count; g++) {
        const gr__groove_t *rec = &gr->grooves_[g];
        gr__path_boxes(&pl->cells, gr->points_ + 2 * rec->first_point, rec->kind, rec->point_count, g, gr->cell_start_ + 1, NULL,
                       NULL, NULL);
    }
    for (i = 0; i < nc; i++) gr->cell_start_[i + 1] += gr->cell_start_[i];
    GR_ASSERT(gr->cell_start_[nc] == pl->item_capacity);
    for (g = 0; g < pl->groove_count; g++) {
        const gr__groove_t *rec = &gr->grooves_[g];
        gr__path_boxes(&pl->cells, gr->points_ + 2 * rec->first_point, rec->kind, rec->point_count, g, NULL, gr->cell_start_,
                       gr->cell_count_, gr->cell_items_);
    }
}

/* The anchors: each groove in the cell of its first point, for grooves
   that lie wholly inside a footprint box (missed by the boundary cells),
   and their prefix sums along each row. */
static void gr__fill_anchors(gr_grid_t *gr, const gr__plan_t *pl)
{
    int g, i, j, nc = pl->cells.nu * pl->cells.nv, *cursor = gr->row_anchor_sum_; /* borrowed as a per-cell fill cursor */
    memset(gr->anchor_start_, 0, sizeof(int) * ((size_t)nc + 1));
    for (g = 0; g < pl->groove_count; g++)
        gr->anchor_start_[gr__anchor_cell(&pl->cells, gr->points_ + 2 * gr->grooves_[g].first_point) + 1]++;
    for (i = 0; i < nc; i++) gr->anchor_start_[i + 1] += gr->anchor_start_[i];
    memset(cursor, 0, sizeof(int) * (size_t)nc);
    for (g = 0; g < pl->groove_count; g++) {
        int cell = gr__anchor_cell(&pl->cells, gr->points_ + 2 * gr->grooves_[g].first_point);
        gr->anchor_items_[gr->anchor_start_[cell] + cursor[cell]++] = g;
    }
    for (j = 0; j < pl->cells.nv; j++) {
        int *row = gr->row_anchor_sum_ + (size_t)j * (size_t)(pl->cells.nu + 1);
        row[0] = 0;
        for (i = 0; i < pl->cells.nu; i++) {
            int cell = j * pl->cells.nu + i;
            row[i + 1] = row[i] + gr->anchor_start_[cell + 1] - gr->anchor_start_[cell];
        }
    }
}

GR_DEF gr_result_t gr_grid_build_into(const gr_grid_desc_t *desc, void *buffer, size_t bytes,
                                      gr_grid_t **grid, gr_diag_t *diag)
{
    gr__plan_t pl;
    gr_result_t r;
    gr_grid_t *gr;
    int g, pt = 0, sc = 0, fc = 0, bc = 0;
    if (!buffer || !grid) { gr__diag(diag, GR_ERR_INVALID_ARG, -1, "buffer or grid is NULL"); return GR_ERR_INVALID_ARG; }
    *grid = NULL;
    r = gr__plan(desc, &pl, diag);
    if (r != GR_OK) return r;
    if (bytes < pl.bytes) {
        gr__diag(diag, GR_ERR_BUFFER_TOO_SMALL, -1, "buffer smaller than gr_grid_size()");
        return GR_ERR_BUFFER_TOO_SMALL;
    }
    gr = gr__grid_header(desc, &pl, (char *)buffer);
    for (g = 0; g < pl.groove_count; g++) {
        const gr__groove_t *rec;
        gr__store_groove(gr, &desc->grooves[g], g, gr__shares_section(desc, g), &pt, &sc, &fc, &bc);
        rec = &gr->grooves_[g];
        if (rec->half_width > gr->w) gr->w = rec->half_width;
        if (rec->up > gr->h) gr->h = rec->up;
        if (rec->down > gr->d) gr->d = rec->down;
    }
#ifndef GR_NO_INTERSECTIONS
    gr__split_self_hits(gr, &pl, &pt);
#endif
    gr__fill_cells(gr, &pl);
    gr__fill_anchors(gr, &pl);
    *grid = gr;
    return GR_OK;
}

GR_DEF gr_result_t gr_grid_build(const gr_grid_desc_t *desc, gr_grid_t **grid, gr_diag_t *diag)
{
    size_t bytes = 0;
    void *mem;
    gr_result_t r;
    if (!grid) { gr__diag(diag, GR_ERR_INVALID_ARG, -1, "grid is NULL"); return GR_ERR_INVALID_ARG; }
    *grid = NULL;
    r = gr_grid_size(desc, &bytes, diag);
    if (r != GR_OK) return r;
    mem = GR_MALLOC(bytes, desc->alloc_ctx);
    if (!mem) { gr__diag(diag, GR_ERR_OUT_OF_MEMORY, -1, "allocator returned NULL"); return GR_ERR_OUT_OF_MEMORY; }
    r = gr_grid_build_into(desc, mem, bytes, grid, diag);
    if (r != GR_OK) { GR_FREE(mem, desc->alloc_ctx); return r; }
    (*grid)->owns_memory = 1;
    return GR_OK;
}

GR_DEF void gr_grid_free(gr_grid_t *grid)
{
    if (!grid || !grid->owns_memory) return;
    GR_FREE((void *)grid, grid->alloc_ctx);
}

GR_DEF int gr_facet_blockers(const gr_grid_t *grid, int groove, int facet, const int **list)
{
    const gr__groove_t *rec;
    int f;
    if (list) *list = NULL;
    if (!grid || groove < 0 || groove >= grid->groove_count) return 0;
    rec = &grid->grooves_[groove];
    if (facet < 0 || facet >= rec->sec_count - 1) return 0;
    f = rec->first_sec + facet;
    if (list) *list = grid->blockers_ + grid->blocker_start_[f];
    return grid->blocker_start_[f + 1] - grid->blocker_start_[f];
}

/* ---- Footprint from ray differentials (§4; pbrt-v4's least squares) ----- */

static double gr__dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void gr__cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static int gr__finite_n(const double *a, int n)
{
    int i;
    for (i = 0; i < n; i++) if (!gr__finite(a[i])) return 0;
    return 1;
}

GR_DEF int gr_frame_to_texture(const gr_frame_t *frame, const double world[3], double tex[3])
{
    double t[3], len;
    t[0] = gr__dot3(world, frame->tu);
    t[1] = gr__dot3(world, frame->tv);
    t[2] = gr__dot3(world, frame->tw);
    len = sqrt(gr__dot3(t, t));
    if (!(len > 0) || !gr__finite(len)) { tex[0] = tex[1] = tex[2] = 0; return 0; }
    tex[0] = t[0] / len;
    tex[1] = t[1] / len;
    tex[2] = t[2] / len;
    return 1;
}

/* (du, dv) of the point where ray (o, d) meets the tangent plane at p,
   solved in the least-squares sense against dp/du, dp/dv. A ray parallel to
   the plane (or meeting it at infinity) gives (0, 0). */
static void gr__offset_uv(const gr_differentials_t *rd, const double *n, const double *o, const double *d,
                          double a00, double a01, double a11, double det, double out[2])
{
    double dn = gr__dot3(n, d), t, px[3], dp[3], b0, b1;
    int i;
    out[0] = out[1] = 0;
    if (dn == 0) return;
    t = (gr__dot3(n, rd->p) - gr__dot3(n, o)) / dn;
    if (!gr__finite(t)) return;
    for (i = 0; i < 3; i++) { px[i] = o[i] + t * d[i]; dp[i] = px[i] - rd->p[i]; }
    b0 = gr__dot3(rd->dpdu, dp);
    b1 = gr__dot3(rd->dpdv, dp);
    out[0] = (a11 * b0 - a01 * b1) / det;
    out[1] = (a00 * b1 - a01 * b0) / det;
    if (!gr__finite(out[0]) || !gr__finite(out[1])) out[0] = out[1] = 0;
}

GR_DEF gr_result_t gr_footprint_from_differentials(const gr_differentials_t *rd, gr_footprint_t *fp, gr_frame_t *frame)
{
    double n[3], nl, a00, a01, a11, det, c[3], radius, dx[2], dy[2], neg[3];
    gr_frame_t fr;
    int i;
    if (!rd || !fp) return GR_ERR_INVALID_ARG;
    if (!gr__finite_n(rd->p, 3) || !gr__finite_n(rd->n, 3) || !gr__finite_n(rd->dpdu, 3) ||
        !gr__finite_n(rd->dpdv, 3) || !gr__finite_n(rd->uv, 2) || !gr__finite_n(rd->dir, 3) ||
        !gr__finite_n(rd->rx_origin, 3) || !gr__finite_n(rd->rx_dir, 3) || !gr__finite_n(rd->ry_origin, 3) ||
        !gr__finite_n(rd->ry_dir, 3) || !gr__finite(rd->filter_radius) || rd->filter_radius < 0)
        return GR_ERR_NOT_FINITE;
    nl = sqrt(gr__dot3(rd->n, rd->n));
    a00 = gr__dot3(rd->dpdu, rd->dpdu);
    a01 = gr__dot3(rd->dpdu, rd->dpdv);
    a11 = gr__dot3(rd->dpdv, rd->dpdv);
    gr__cross3(rd->dpdu, rd->dpdv, c);
    det = a00 * a11 - a01 * a01;
    if (!(nl > 0) || !(gr__dot3(c, c) > GR__DEGENERATE_UV_REL * GR__DEGENERATE_UV_REL * a00 * a11) ||
        !(gr__dot3(rd->dir, rd->dir) > 0))
        return GR_ERR_INVALID_ARG;
    for (i = 0; i < 3; i++) n[i] = rd->n[i] / nl;
    radius = rd->filter_radius > 0 ? rd->filter_radius : 0.5;
    gr__offset_uv(rd, n, rd->rx_origin, rd->rx_dir, a00, a01, a11, det, dx);
    gr__offset_uv(rd, n, rd->ry_origin, rd->ry_dir, a00, a01, a11, det, dy);
    fp->center[0] = rd->uv[0];
    fp->center[1] = rd->uv[1];
    fp->axis1[0] = radius * dx[0];
    fp->axis1[1] = radius * dx[1];
    fp->axis2[0] = radius * dy[0];
    fp->axis2[1] = radius * dy[1];
    /* orthonormal frame: tu along dp/du, tw the normal, tv following dp/dv */
    {
        double pu = gr__dot3(rd->dpdu, n), ul;
        for (i = 0; i < 3; i++) fr.tu[i] = rd->dpdu[i] - pu * n[i];
        ul = sqrt(gr__dot3(fr.tu, fr.tu));
        if (!(ul > 0)) return GR_ERR_INVALID_ARG;
        for (i = 0; i < 3; i++) { fr.tu[i] /= ul; fr.tw[i] = n[i]; }
        gr__cross3(fr.tw, fr.tu, fr.tv);
        if (gr__dot3(fr.tv, rd->dpdv) < 0)
            for (i = 0; i < 3; i++) fr.tv[i] = -fr.tv[i];
    }
    for (i = 0; i < 3; i++) neg[i] = -rd->dir[i];
    gr_frame_to_texture(&fr, neg, fp->view);
    if (frame) *frame = fr;
    return GR_OK;
}

/* ---- Query (§4.1-4.4) ---------------------------------------------------- */

/* A groove found near the footprint, in its local straight approximation. */
typedef struct gr__cand_t {
    int groove;
    int sigma;      /* +1 if its tangent agrees with the reference, -1 if opposite */
    int end;        /* -1/+1: the footprint centre lies before/after an open path end */
    double p[2];    /* nearest path point P (§4.2) */
    double t[2];    /* unit tangent T at P */
    double fc[2];   /* the footprint centre's periodic image nearest to the path */
    double dist;    /* |F - P| */
    double d;       /* d_P = B . (F - P), B = (-T_v, T_u) (eq. 2) */
    double param;   /* path parameter at P, in [0,1] */
    double dtds;    /* d param / d arc length at P */
    double dtds2;   /* its derivative per unit arc length (Bézier speed changes) */
    double kappa;   /* signed path curvature at P (> 0: T turns counter-clockwise) */
    double dkds;    /* its derivative per unit arc length */
    double f;       /* perturbation scale f(param) */
    double dfds;    /* its slope per unit arc length, averaged across the footprint */
    double xmin;    /* leftmost point of its section in the merged profile */
} gr__cand_t;

/* One facet of the merged cross-section. */
typedef struct gr__mfacet_t {
    double n[3];
    int groove, facet, refl;
    int cand;    /* its candidate groove in the query's scratch, -1 for ground */
} gr__mfacet_t;

/* Sort key of a groove in the merged cross-section. */
typedef struct gr__key_t {
    double x;  /* leftmost point */
    int cand;  /* index into the candidates */
    int groove;
} gr__key_t;

typedef struct gr__scratch_t {
    unsigned char *seen; /* one bit per groove, cleared per footprint */
    int *ids;
    gr__cand_t *cand;
    gr__key_t *key;
    double *x, *w, *q, *lo, *hi, *va, *vb, *lit;
    gr__mfacet_t *mf;
    /* per merged point: its candidate (-1 for ground) and its point of the
       unscaled section (b, w); the view's projection */
    int *pc;
    double *bs, *ws, *qe;
    int *visited; /* cell lists the last §4 footprint read (gr__gather) */
} gr__scratch_t;

static size_t gr__scratch_layout(const gr_grid_t *g, void *base, gr__scratch_t *s)
{
    /* a self-crossing groove's pieces (§5) are candidates of their own in
       gr_detect(): room for them, and for two end states each */
    size_t off = 0, np = (size_t)g->total_facets_ + (size_t)g->groove_count + 2 + 2 * (size_t)g->split_records_;
    size_t nid = (size_t)g->groove_count;
    char *b = (char *)base;
    gr__scratch_t tmp;
    if (!s) s = &tmp;
#define GR__CARVE(field, type, count) \
    s->field = (type *)(void *)(b ? b + off : NULL); off = gr__align8(off + sizeof(type) * (count));
    GR__CARVE(seen, unsigned char, nid / 8 + 1)
    GR__CARVE(ids, int, nid)
    GR__CARVE(cand, gr__cand_t, (size_t)g->groove_count + (size_t)g->split_records_)
    GR__CARVE(key, gr__key_t, (size_t)g->groove_count)
    GR__CARVE(x, double, np)
    GR__CARVE(w, double, np)
    GR__CARVE(q, double, np)
    GR__CARVE(lo, double, np)
    GR__CARVE(hi, double, np)
    GR__CARVE(va, double, np)
    GR__CARVE(vb, double, np)
    GR__CARVE(lit, double, np * GR_MAX_LIGHTS)
    GR__CARVE(mf, gr__mfacet_t, np)
    GR__CARVE(pc, int, np)
    GR__CARVE(bs, double, np)
    GR__CARVE(ws, double, np)
    GR__CARVE(qe, double, np)
    GR__CARVE(visited, int, 1)
#undef GR__CARVE
    return off;
}

#ifndef GR_NO_INTERSECTIONS
/* The polygon path (§5.2-5.5, [section: intersections]) uses the scratch
   after the §4 layout. */
static size_t gr__pp_scratch_bytes(void);
static int gr__pp_dispatch(const gr_grid_t *grid, const gr_query_t *q, void *scratch, size_t bytes,
                           const gr__scratch_t *s, gr_facet_list_t *list);
#else
static size_t gr__pp_scratch_bytes(void) { return 0; }
#endif
/* [section: line samples] its scratch also follows the query's (the two
   paths never run at once) */
#if !defined(GR_NO_LINE_SAMPLES) || !defined(GR_NO_INTERREFLECTION)
struct gr__lscratch_t;
static size_t gr__line_scratch(void *base, struct gr__lscratch_t *ls);
#  define GR__LINE_SCRATCH_BYTES gr__line_scratch(NULL, NULL)
#else
#  define GR__LINE_SCRATCH_BYTES 0
#endif

GR_DEF size_t gr_query_scratch_bytes(const gr_grid_t *grid)
{
    size_t pp = gr__pp_scratch_bytes(), ls = GR__LINE_SCRATCH_BYTES;
    return grid ? gr__align8(gr__scratch_layout(grid, NULL, NULL)) + (pp > ls ? pp : ls) : 0;
}

#ifndef GR_NO_CURVES
/* Bézier position, first and second derivative at tau (degree n <= 3). */
static void gr__bezier_eval(const double *p, int n, double tau, double b[2], double d1[2], double d2[2])
{
    double s = 1 - tau;
    int k;
    for (k = 0; k < 2; k++) {
        if (n == 2) {
            b[k] = s * s * p[k] + 2 * s * tau * p[2 + k] + tau * tau * p[4 + k];
            d1[k] = 2 * (s * (p[2 + k] - p[k]) + tau * (p[4 + k] - p[2 + k]));
            d2[k] = 2 * (p[4 + k] - 2 * p[2 + k] + p[k]);
        } else {
            b[k] = s * s * s * p[k] + 3 * s * s * tau * p[2 + k] + 3 * s * tau * tau * p[4 + k] + tau * tau * tau * p[6 + k];
            d1[k] = 3 * (s * s * (p[2 + k] - p[k]) + 2 * s * tau * (p[4 + k] - p[2 + k]) + tau * tau * (p[6 + k] - p[4 + k]));
            d2[k] = 6 * (s * (p[4 + k] - 2 * p[2 + k] + p[k]) + tau * (p[6 + k] - 2 * p[4 + k] + p[2 + k]));
        }
    }
}

/* Groove rec's Bézier path at parameter param, clamped to [0, 1] (piece k
   of n covers [k/n, (k+1)/n], uniformly): position and derivatives with
   respect to the piece's own parameter; returns the piece's control points. */
static const double *gr__bezier_at(const gr_grid_t *grid, const gr__groove_t *rec, double param, double b[2],
                                   double d1[2], double d2[2])
{
    int deg = gr__degree(rec->kind), k;
    const double *a;
    param = param < 0 ? 0 : param > 1 ? 1 : param;
    k = (int)(param * rec->pieces);
    if (k >= rec->pieces) k = rec->pieces - 1;
    a = grid->points_ + 2 * (rec->first_point + k * deg);
    gr__bezier_eval(a, deg, param * rec->pieces - k, b, d1, d2);
    return a;
}

/* The local frame of a candidate at a point of Bézier piece a (degree deg,
   one of `pieces`) with position b and derivatives d1, d2 there (|d1| > 0):
   P, unit T, d param / ds and its slope, signed curvature and its slope
   (from the third derivative, constant per piece: 6 (p3 - 3 p2 + 3 p1 -
   p0) for a cubic, 0 for a quadratic). */
static void gr__bezier_frame(const double *a, int deg, int pieces, const double b[2], const double d1[2],
                             const double d2[2], gr__cand_t *c)
{
    double sp = sqrt(d1[0] * d1[0] + d1[1] * d1[1]), cr = d1[0] * d2[1] - d1[1] * d2[0], d3[2] = {0, 0}, dcr;
    double s2 = sp * sp;
    if (deg == 3) {
        d3[0] = 6 * (a[6] - 3 * a[4] + 3 * a[2] - a[0]);
        d3[1] = 6 * (a[7] - 3 * a[5] + 3 * a[3] - a[1]);
    }
    dcr = d1[0] * d3[1] - d1[1] * d3[0];
    c->p[0] = b[0]; c->p[1] = b[1];
    c->t[0] = d1[0] / sp; c->t[1] = d1[1] / sp;
    c->dtds = 1 / (pieces * sp);
    c->dtds2 = -(d1[0] * d2[0] + d1[1] * d2[1]) / (pieces * s2 * s2);
    c->kappa = cr / (s2 * sp);
    c->dkds = (dcr * s2 - 3 * cr * (d1[0] * d2[0] + d1[1] * d2[1])) / (s2 * s2 * s2);
}
#endif

/* Distance from x to the interval [lo, hi]. */
static double gr__interval_dist(double x, double lo, double hi) { return x < lo ? lo - x : x > hi ? x - hi : 0; }

/* Squared length of polyline piece k (0 for a repeated point). */
static double gr__piece_len2(const double *pts, int k)
{
    const double *a = pts + 2 * k;
    double ex = a[2] - a[0], ey = a[3] - a[1];
    return ex * ex + ey * ey;
}

/* Nearest point of a groove's path to f (§4.2), among points closer than
   sqrt(limit2): fills p, t, param, dtds, kappa, end and dist of c and
   returns 1, or returns 0 when no point is that close. */
static int gr__nearest(const gr_grid_t *grid, const gr__groove_t *rec, const double f[2], double limit2, gr__cand_t *c)
{
    const double *pts = grid->points_ + 2 * rec->first_point;
    double best = limit2;
    int found = 0;
    int k;
    if (rec->kind == GR_PATH_POLYLINE) {
        double acc = 0;
        int first = 0, last = rec->pieces - 1; /* the end pieces, past repeated end points */
        while (first < last && gr__piece_len2(pts, first) == 0) first++;
        while (last > first && gr__piece_len2(pts, last) == 0) last--;
        for (k = 0; k < rec->pieces; k++) {
            const double *a = pts + 2 * k;
            double ex = a[2] - a[0], ey = a[3] - a[1], len2 = ex * ex + ey * ey, len = sqrt(len2);
            double s = len2 > 0 ? ((f[0] - a[0]) * ex + (f[1] - a[1]) * ey) / len2 : 0, raw = s, px, py, d2;
            if (s < 0) s = 0;
            if (s > 1) s = 1;
            px = a[0] + s * ex;
            py = a[1] + s * ey;
            d2 = (f[0] - px) * (f[0] - px) + (f[1] - py) * (f[1] - py);
            if (len2 > 0 && d2 < best) {
                best = d2;
                found = 1;
                c->p[0] = px; c->p[1] = py;
                c->t[0] = ex / len; c->t[1] = ey / len;
                c->param = (acc + s * len) / rec->length;
                c->dtds = 1 / rec->length;
                c->dtds2 = 0;
                c->kappa = 0;
                c->dkds = 0;
                c->end = rec->closed ? 0 : (k == first && raw < 0) ? -1 : (k == last && raw > 1) ? 1 : 0;
            }
            acc += len;
        }
    }
#ifndef GR_NO_CURVES
    else {
        int deg = gr__degree(rec->kind);
        for (k = 0; k < rec->pieces; k++) {
            const double *a = pts + 2 * k * deg;
            double box[4], dx, dy, bt = 0, bd = HUGE_VAL, b[2], d1[2], d2[2], sp;
            int s, it;
            /* the control polygon bounds the piece: skip it when farther */
            gr__bounds(a, deg + 1, box);
            dx = gr__interval_dist(f[0], box[0], box[2]);
            dy = gr__interval_dist(f[1], box[1], box[3]);
            if (dx * dx + dy * dy > best) continue;
            for (s = 0; s <= GR__CURVE_SAMPLES; s++) {
                double tau = (double)s / GR__CURVE_SAMPLES, dd;
                gr__bezier_eval(a, deg, tau, b, d1, d2);
                dd = (b[0] - f[0]) * (b[0] - f[0]) + (b[1] - f[1]) * (b[1] - f[1]);
                if (dd < bd) { bd = dd; bt = tau; }
            }
            for (it = 0; it < GR__CURVE_NEWTON; it++) {
                double g, gp, nt;
                gr__bezier_eval(a, deg, bt, b, d1, d2);
                g = (b[0] - f[0]) * d1[0] + (b[1] - f[1]) * d1[1];
                gp = d1[0] * d1[0] + d1[1] * d1[1] + (b[0] - f[0]) * d2[0] + (b[1] - f[1]) * d2[1];
                if (!(gp > 0)) break;
                nt = bt - g / gp;
                if (nt < 0) nt = 0;
                if (nt > 1) nt = 1;
                if (fabs(nt - bt) < 1e-14) { bt = nt; break; }
                bt = nt;
            }
            gr__bezier_eval(a, deg, bt, b, d1, d2);
            bd = (b[0] - f[0]) * (b[0] - f[0]) + (b[1] - f[1]) * (b[1] - f[1]);
            sp = sqrt(d1[0] * d1[0] + d1[1] * d1[1]);
            if (bd < best && sp > 0) {
                best = bd;
                found = 1;
                gr__bezier_frame(a, deg, rec->pieces, b, d1, d2, c);
                c->param = (k + bt) / rec->pieces;
                c->end = 0;
                if (!rec->closed && k == 0 && bt == 0 && (f[0] - b[0]) * d1[0] + (f[1] - b[1]) * d1[1] < 0) c->end = -1;
                if (!rec->closed && k == rec->pieces - 1 && bt == 1 && (f[0] - b[0]) * d1[0] + (f[1] - b[1]) * d1[1] > 0) c->end = 1;
            }
        }
    }
#endif
    if (found) c->dist = sqrt(best);
    return found;
}

/* The groove's nearest approach within distance `reach` over the periodic
   images of the footprint centre (§4.1: repeating textures). The image
   nearest the path's box is tried first (the box distance separates per
   axis), so the others are usually pruned by their box. Returns 0 when no
   image of the path comes within reach. */
static int gr__locate(const gr_grid_t *grid, int g, const double f[2], double reach, gr__cand_t *c)
{
    const gr__groove_t *rec = &grid->grooves_[g];
    double wu = grid->domain[2] - grid->domain[0], wv = grid->domain[3] - grid->domain[1];
    double du[3], dv[3], limit2 = reach * reach;
    int k, ku, kv, bu = 1, bv = 1, found = 0;
    for (k = 0; k < 3; k++) {
        du[k] = grid->wrap || k == 1 ? gr__interval_dist(f[0] + (k - 1) * wu, rec->bbox[0], rec->bbox[2]) : HUGE_VAL;
        dv[k] = grid->wrap || k == 1 ? gr__interval_dist(f[1] + (k - 1) * wv, rec->bbox[1], rec->bbox[3]) : HUGE_VAL;
    }
    for (k = 0; k < 3; k += 2) {
        if (du[k] < du[bu]) bu = k;
        if (dv[k] < dv[bv]) bv = k;
    }
    c->groove = g;
    if (!(du[bu] * du[bu] + dv[bv] * dv[bv] <= limit2)) return 0; /* no image within reach */
    for (k = -1; k < 9; k++) {
        double fi[2];
        if (k < 0) { ku = bu; kv = bv; }
        else {
            ku = k - 3 * (k / 3);
            kv = k / 3;
            if (ku == bu && kv == bv) continue;
        }
        if (!(du[ku] * du[ku] + dv[kv] * dv[kv] <= limit2)) continue;
        fi[0] = f[0] + (ku - 1) * wu;
        fi[1] = f[1] + (kv - 1) * wv;
        if (gr__nearest(grid, rec, fi, limit2, c)) {
            found = 1;
            limit2 = c->dist * c->dist;
            c->fc[0] = fi[0];
            c->fc[1] = fi[1];
        }
        if (!grid->wrap) break; /* one image only */
    }
    c->groove = g;
    return found;
}

/* ---- Sorting without allocation ----------------------------------------------
   libc's qsort may malloc a buffer (glibc does for arrays of 1 KiB and
   more), which a query must not and a builder may only through GR_MALLOC.
   gr__sort is stable (equal keys keep their order, as glibc's merge sort
   kept them), in place and allocation-free: insertion sort on runs of
   GR__SORT_RUN, then runs merged pairwise, through a 4 KiB buffer on the
   stack while the left run fits in it, else by rotations (the longer
   run's middle element is placed by binary search in the other, the two
   pieces between are swapped by three reversals, and each side is merged
   again: O(n log n) compares and O(n log^2 n) element moves). cmp as
   qsort's. */
typedef int (*gr__cmp_fn)(const void *, const void *);
#define GR__SORT_RUN 16
static void gr__elem_swap(unsigned char *a, unsigned char *b, size_t size)
{
    unsigned char t[64];
    while (size) { /* in pieces of 64 bytes: elements of any size */
        size_t k = size < sizeof t ? size : sizeof t;
        memcpy(t, a, k);
        memcpy(a, b, k);
        memcpy(b, t, k);
        a += k, b += k, size -= k;
    }
}
static void gr__reverse(unsigned char *base, size_t size, size_t lo, size_t hi) /* [lo, hi) */
{
    while (hi > lo + 1) gr__elem_swap(base + lo++ * size, base + --hi * size, size);
}
/* [a, m) [m, b) -> [m, b) [a, m) */
static void gr__rotate(unsigned char *base, size_t size, size_t a, size_t m, size_t b)
{
    if (a == m || m == b) return;
    gr__reverse(base, size, a, m);
    gr__reverse(base, size, m, b);
    gr__reverse(base, size, a, b);
}
/* First index in [lo, hi) whose element is not below x (below: strictly
   less; upper: less or equal, for x from the left run). */
static size_t gr__bound(const unsigned char *base, size_t size, gr__cmp_fn cmp, size_t lo, size_t hi, const void *x, int upper)
{
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = cmp(base + mid * size, x);
        if (c < 0 || (upper && c == 0)) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}
/* Merge the sorted runs [a, m) and [m, b) stably, in place. */
static void gr__merge_runs(unsigned char *base, size_t size, gr__cmp_fn cmp, size_t a, size_t m, size_t b)
{
    while (a < m && m < b) {
        size_t c1, c2, nm;
        if (b - a == 2) {
            if (cmp(base + m * size, base + a * size) < 0) gr__elem_swap(base + a * size, base + m * size, size);
            return;
        }
        if (m - a >= b - m) { /* the left run's middle, after the right run's smaller elements */
            c1 = a + (m - a) / 2;
            c2 = gr__bound(base, size, cmp, m, b, base + c1 * size, 0);
        } else { /* the right run's middle, after the left run's elements not above it */
            c2 = m + (b - m) / 2;
            c1 = gr__bound(base, size, cmp, a, m, base + c2 * size, 1);
        }
        gr__rotate(base, size, c1, m, c2);
        nm = c1 + (c2 - m);
        /* the smaller side recursively, the larger one by the loop: depth log n */
        if (nm - a < b - nm) {
            gr__merge_runs(base, size, cmp, a, c1, nm);
            a = nm, m = c2;
        } else {
            gr__merge_runs(base, size, cmp, nm, c2, b);
            b = nm, m = c1;
        }
    }
}
/* The same merge with the left run copied out to buf first (it fits):
   each element moves once; the left run's element goes first on ties. */
static void gr__merge_buffered(unsigned char *base, size_t size, gr__cmp_fn cmp, size_t a, size_t m, size_t b, unsigned char *buf)
{
    size_t i = 0, nl = m - a, j = m, k = a;
    memcpy(buf, base + a * size, nl * size);
    while (i < nl && j < b) {
        if (cmp(base + j * size, buf + i * size) < 0) memcpy(base + k++ * size, base + j++ * size, size);
        else memcpy(base + k++ * size, buf + i++ * size, size);
    }
    if (i < nl) memcpy(base + k * size, buf + i * size, (nl - i) * size);
}
static void gr__sort(void *base_v, size_t n, size_t size, gr__cmp_fn cmp)
{
    unsigned char *base = (unsigned char *)base_v, buf[4096]; /* merges whose left run fits skip the rotations */
    size_t r, i, j, w;
    for (r = 0; r < n; r += GR__SORT_RUN) { /* runs by insertion (adjacent swaps) */
        size_t end = r + GR__SORT_RUN < n ? r + GR__SORT_RUN : n;
        for (i = r + 1; i < end; i++)
            for (j = i; j > r && cmp(base + j * size, base + (j - 1) * size) < 0; j--)
                gr__elem_swap(base + j * size, base + (j - 1) * size, size);
    }
    for (w = GR__SORT_RUN; w < n; w *= 2)
        for (r = 0; r + w < n; r += 2 * w) {
            size_t b = r + 2 * w < n ? r + 2 * w : n;
            if (w * size <= sizeof buf) gr__merge_buffered(base, size, cmp, r, r + w, b, buf);
            else gr__merge_runs(base, size, cmp, r, r + w, b);
        }
}

static int gr__key_less(const gr__key_t *a, const gr__key_t *b)
{
    return a->x < b->x || (a->x == b->x && a->groove < b->groove);
}
static int gr__cmp_key(const void *a, const void *b)
{
    const gr__key_t *x = (const gr__key_t *)a, *y = (const gr__key_t *)b;
    return gr__key_less(x, y) ? -1 : gr__key_less(y, x);
}
/* Candidates arrive nearly in order for parallel families: insertion sort
   while short, gr__sort beyond. */
static void gr__sort_keys(gr__key_t *k, int n)
{
    int i, j;
    if (n > 32) { gr__sort(k, (size_t)n, sizeof *k, gr__cmp_key); return; }
    for (i = 1; i < n; i++) {
        gr__key_t t = k[i];
        for (j = i; j > 0 && gr__key_less(&t, &k[j - 1]); j--) k[j] = k[j - 1];
        k[j] = t;
    }
}

/* Append the grooves of list[0..count) not seen yet. */
static int gr__append_new(const int *list, int count, unsigned char *seen, int *ids, int n)
{
    int k;
    for (k = 0; k < count; k++) {
        int g = list[k];
        if (seen[g >> 3] & (1u << (g & 7))) continue;
        seen[g >> 3] = (unsigned char)(seen[g >> 3] | (1u << (g & 7)));
        ids[n++] = g;
    }
    return n;
}

/* Grooves whose paths cross the boundary cells of box (2m + 2(n-2) cells,
   §4.1), plus those anchored inside it (paths wholly inside the box, which
   the boundary cells would miss). Returns the count of unique ids, in the
   order found; `seen` (one bit per groove) is scratch. *visited, when
   given, receives the number of cell lists read (tests check §4.1's
   count). */
static int gr__gather(const gr_grid_t *grid, const double box[4], unsigned char *seen, int *ids, int *visited)
{
    gr__cells_t c = gr__grid_cells(grid);
    int fu, mu, fv, mv, i, j, n = 0, nv = 0;
    memset(seen, 0, (size_t)grid->groove_count / 8 + 1);
    gr__cell_range(gr__cell_coord(box[0], c.u0, c.cu), gr__cell_coord(box[2], c.u0, c.cu), c.nu, c.wrap, &fu, &mu);
    gr__cell_range(gr__cell_coord(box[1], c.v0, c.cv), gr__cell_coord(box[3], c.v0, c.cv), c.nv, c.wrap, &fv, &mv);
    for (j = 0; j < mv; j++) {
        int row = (fv + j) % c.nv;
        int edge_row = j == 0 || j == mv - 1;
        for (i = 0; i < mu; i += edge_row || mu == 1 ? 1 : mu - 1) {
            int cell = row * c.nu + (fu + i) % c.nu;
            n = gr__append_new(grid->cell_items_ + grid->cell_start_[cell], grid->cell_count_[cell], seen, ids, n);
            nv++;
            if (!edge_row && mu == 1) break;
        }
    }
    /* interior rows: anchors, checked per row with prefix sums */
    for (j = 1; j + 1 < mv; j++) {
        int row = (fv + j) % c.nv, a = fu + 1, b = fu + mu - 2; /* columns a..b, may pass nu */
        const int *sum = grid->row_anchor_sum_ + (size_t)row * (size_t)(c.nu + 1);
        int part;
        if (b < a) continue;
        for (part = 0; part < 2; part++) {
            int lo = part == 0 ? a : 0, hi = part == 0 ? (b < c.nu ? b : c.nu - 1) : b - c.nu;
            if (part == 0 && a >= c.nu) { lo = a - c.nu; hi = b - c.nu; }
            else if (part == 1 && (a >= c.nu || b < c.nu)) break;
            if (hi < lo || sum[hi + 1] - sum[lo] == 0) continue;
            for (i = lo; i <= hi; i++) {
                int cell = row * c.nu + i;
                n = gr__append_new(grid->anchor_items_ + grid->anchor_start_[cell],
                                   grid->anchor_start_[cell + 1] - grid->anchor_start_[cell], seen, ids, n);
                nv++;
            }
        }
    }
    if (visited) *visited = nv;
    return n;
}

/* Per-query settings after defaults. */
typedef struct gr__qset_t {
    const double *lights;
    int light_count;
    double oversample_tol;
    int max_oversample;
    double parallel_sin;
    int perturb_normals;
    int ellipse;
    int ray_profile; /* !straight_occlusion */
} gr__qset_t;

/* Visible (or lit) interval per facet of a profile with projected points q
   (eq. 4). Points are visited in the order the direction meets them: left
   to right (reverse = 0) keeping the running maximum, or right to left
   keeping the running minimum. Facet i is seen on [lo_i, hi_i] when
   hi_i > lo_i; a back-facing or masked facet gets hi_i <= lo_i. */
static void gr__sweep(const double *q, int npts, int reverse, double *lo, double *hi)
{
    int i;
    if (!reverse) {
        double m = -HUGE_VAL;
        for (i = 0; i + 1 < npts; i++) {
            if (q[i] > m) m = q[i];
            lo[i] = m;
            hi[i] = q[i + 1];
        }
    } else {
        double m = HUGE_VAL;
        for (i = npts - 2; i >= 0; i--) {
            if (q[i + 1] < m) m = q[i + 1];
            lo[i] = q[i];
            hi[i] = m;
        }
    }
}

/* The pieces of a self-crossing groove (§5) run in two directions, so the
   list keeps them apart as they are added; once it is complete, each entry
   is named by its groove. */
#ifndef GR_NO_INTERSECTIONS
static void gr__list_name_parents(const gr_grid_t *grid, gr_facet_list_t *list)
{
    int i;
    for (i = 0; i < list->count; i++)
        if (list->facets[i].groove >= 0) list->facets[i].groove = grid->grooves_[list->facets[i].groove].parent;
}
#endif

/* Add weight * (facet's share) to the list, merging equal orientations. */
static void gr__list_add(gr_facet_list_t *list, const gr__mfacet_t *m, double ratio, const double *lit, int nl)
{
    int e, k, best = -1;
    double bestd = HUGE_VAL;
    gr_facet_t *f;
    for (e = 0; e < list->count; e++) {
        f = &list->facets[e];
        if (f->reflectance != m->refl) continue;
        if (fabs(f->normal[0] - m->n[0]) <= GR__NORMAL_MERGE_EPS && fabs(f->normal[1] - m->n[1]) <= GR__NORMAL_MERGE_EPS &&
            fabs(f->normal[2] - m->n[2]) <= GR__NORMAL_MERGE_EPS)
            break;
        /* one facet of one groove seen in several sub-footprints (§4.2
           oversampling) stays one entry, its normal ratio-averaged */
        if (m->groove >= 0 && f->groove == m->groove && f->facet == m->facet) break;
    }
    if (e == list->count) {
        if (list->count < GR_MAX_FACETS) {
            f = &list->facets[list->count++];
            memset(f, 0, sizeof *f);
            f->normal[0] = m->n[0]; f->normal[1] = m->n[1]; f->normal[2] = m->n[2];
            f->reflectance = m->refl;
            f->groove = m->groove;
            f->facet = m->facet;
        } else {
            /* full: fold into the closest orientation, the same id only
               breaking ties (an id bonus larger than any normal distance, as
               this once had, folded a V-groove's second wall into its first
               and averaged the two into the flat normal) */
            int best_same = 0;
            for (e = 0; e < list->count; e++) {
                const gr_facet_t *g = &list->facets[e];
                double dd = (g->normal[0] - m->n[0]) * (g->normal[0] - m->n[0]) + (g->normal[1] - m->n[1]) * (g->normal[1] - m->n[1]) +
                            (g->normal[2] - m->n[2]) * (g->normal[2] - m->n[2]);
                int same = g->reflectance == m->refl;
                if (dd < bestd || (dd == bestd && same && !best_same)) { bestd = dd; best = e; best_same = same; }
            }
            e = best;
            list->flags |= GR_LIST_APPROX_MERGE;
        }
    }
    f = &list->facets[e];
    if (f->ratio > 0 && (f->normal[0] != m->n[0] || f->normal[1] != m->n[1] || f->normal[2] != m->n[2])) {
        double n[3], len;
        for (k = 0; k < 3; k++) n[k] = f->ratio * f->normal[k] + ratio * m->n[k];
        len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len > 0)
            for (k = 0; k < 3; k++) f->normal[k] = n[k] / len;
    }
    f->ratio += ratio;
    f->merged++;
    for (k = 0; k < nl; k++) f->lit[k] += ratio * lit[k]; /* normalised in gr__list_finish */
}

static void gr__list_finish(gr_facet_list_t *list, int nl)
{
    int e, k;
    for (e = 0; e < list->count; e++) {
        gr_facet_t *f = &list->facets[e];
        for (k = 0; k < nl; k++) {
            double v = f->ratio > 0 ? f->lit[k] / f->ratio : 0;
            f->lit[k] = v < 0 ? 0 : v > 1 ? 1 : v;
        }
    }
}

static double gr__perturb(const gr__groove_t *rec, double t)
{
    double v;
    if (!rec->perturb) return 1;
    v = rec->perturb(t < 0 ? 0 : t > 1 ? 1 : t, rec->perturb_user);
    return v > 0 ? v : 0; /* NaN and negatives count as 0 */
}

/* (E_b, E_w) of a direction above the surface, scaled to max norm 1 with
   E_w >= GR__GRAZING_MIN_W: the same order of projected points (§4.2),
   without underflow at grazing angles. */
static void gr__grazing_scale(double *b, double *w)
{
    double m = fabs(*b) > *w ? fabs(*b) : *w;
    *b /= m;
    *w /= m;
    if (*w < GR__GRAZING_MIN_W) *w = GR__GRAZING_MIN_W;
}

#if !defined(GR_NO_INTERSECTIONS) || !defined(GR_NO_LINE_SAMPLES) || !defined(GR_NO_INTERREFLECTION)
/* A direction above the surface raised to GR__REGION_MIN_ELEVATION when
   it is lower (any other direction is copied). */
static void gr__raise_direction(const double *in, double *out)
{
    double hl = hypot(in[0], in[1]), s;
    out[0] = in[0], out[1] = in[1], out[2] = in[2];
    if (!(in[2] > 0) || !(in[2] < GR__REGION_MIN_ELEVATION * hypot(hl, in[2]))) return;
    s = sqrt(1 - GR__REGION_MIN_ELEVATION * GR__REGION_MIN_ELEVATION) / hl;
    out[0] = in[0] * s, out[1] = in[1] * s, out[2] = GR__REGION_MIN_ELEVATION;
}
/* c's image in the tile (the domain) when the texture repeats, else c. */
static void gr__tile_image(const gr_grid_t *grid, const double *c, double f[2])
{
    f[0] = c[0];
    f[1] = c[1];
    if (grid->wrap) {
        double wu = grid->domain[2] - grid->domain[0], wv = grid->domain[3] - grid->domain[1];
        f[0] -= floor((f[0] - grid->domain[0]) / wu) * wu;
        f[1] -= floor((f[1] - grid->domain[1]) / wv) * wv;
    }
}
/* *out = q as the region methods take it: its view and lights raised,
   and (recentre, for answers that hold no positions) with a repeating
   texture its footprint's centre moved to the tile image (a whole number
   of tiles: the same answer, in coordinates that resolve the footprint;
   at u = 1e15 + 0.5 line samples had coalesced a 0.02 footprint into one
   breakpoint and found nothing). lights: room for GR_MAX_LIGHTS;
   q->light_count checked by the caller. */
static void gr__region_query(const gr_grid_t *grid, const gr_query_t *q, int recentre, gr_query_t *out, double *lights)
{
    int k;
    *out = *q;
    if (recentre) gr__tile_image(grid, q->footprint.center, out->footprint.center);
    gr__raise_direction(q->footprint.view, out->footprint.view);
    for (k = 0; k < q->light_count; k++) gr__raise_direction(q->lights + 3 * k, lights + 3 * k);
    if (q->light_count > 0) out->lights = lights;
}
#endif

/* tan θ of a direction (eq. 1), for box enlargement; huge near grazing. */
static double gr__tan(const double *dir) { return sqrt(dir[0] * dir[0] + dir[1] * dir[1]) / dir[2]; }

/* The shared part of the footprint's extent: half-extent of F + aA1 + bA2
   along unit vector v. */
static double gr__extent(const gr_footprint_t *fp, const double v[2])
{
    return fabs(fp->axis1[0] * v[0] + fp->axis1[1] * v[1]) + fabs(fp->axis2[0] * v[0] + fp->axis2[1] * v[1]);
}

/* The perturbation's slope df/ds (per unit arc length) around path
   parameter param: a central difference over the footprint's extent ext
   along T (at least GR__PERTURB_STEP in the parameter), so the tilt it
   gives the facets is the footprint's average. */
static double gr__perturb_slope(const gr__groove_t *rec, double dtds, double param, double ext)
{
    double h = ext * dtds, ta, tb;
    if (!(h > GR__PERTURB_STEP)) h = GR__PERTURB_STEP;
    ta = param - h < 0 ? 0 : param - h;
    tb = param + h > 1 ? 1 : param + h;
    return tb > ta ? (gr__perturb(rec, tb) - gr__perturb(rec, ta)) / (tb - ta) * dtds : 0;
}

/* Texture-space normal of facet R_j = [C_j, C_j+1] of candidate c (§4.4:
   (0, N_b, N_w) in groove space), with the groove frame turned by phi about
   W and tilted by the perturbation's slope dfds: beyond §4.4, with
   X = P(s) + f(s)(b B + w W) and dB/ds = -kappa T,
   dX/ds x dX/dtau is parallel to (f'(s)(b dw - w db)/alpha, -dw, db) in
   (T, B, W), alpha = 1 - kappa f b at the point (1 on a straight path: the
   bend stretches the outer side of the sweep, which flattens its tilt). */
static void gr__section_normal(const gr__cand_t *c, const double *sec, int j, double phi, double dfds, double alpha,
                               double n[3])
{
    double db = sec[2 * j + 2] - sec[2 * j], dw = sec[2 * j + 3] - sec[2 * j + 1], len = sqrt(db * db + dw * dw);
    double nb = len > 0 ? -dw / len : 0, nw = len > 0 ? db / len : 1, nt = 0, nlen, t[2];
    t[0] = c->t[0];
    t[1] = c->t[1];
    if (phi != 0) {
        double cs = cos(phi), sn = sin(phi);
        t[0] = cs * c->t[0] - sn * c->t[1];
        t[1] = sn * c->t[0] + cs * c->t[1];
    }
    if (dfds != 0 && len > 0) nt = dfds * (sec[2 * j] * dw - sec[2 * j + 1] * db) / (len * alpha);
    nlen = sqrt(nb * nb + nw * nw + nt * nt);
    n[0] = (-t[1] * nb + t[0] * nt) / nlen;
    n[1] = (t[0] * nb + t[1] * nt) / nlen;
    n[2] = nw / nlen;
}

/* 1 - kappa f b (the sweep's stretch along T at distance f b from a path
   of curvature kappa), kept at or above GR__STRETCH_MIN: past the centre
   of curvature the sweep folds and the local model means nothing. */
static double gr__stretch(const gr__cand_t *c, double fb)
{
    double a = 1 - c->kappa * fb;
    return a >= GR__STRETCH_MIN ? a : GR__STRETCH_MIN;
}

/* The path parameter an arc length ds from P (second order: a Bézier's
   speed changes along it). */
static double gr__param_at(const gr__cand_t *c, double ds)
{
    return c->param + ds * (c->dtds + 0.5 * c->dtds2 * ds);
}

/* Where the ray along a direction D (tau = (D . T) / D_w) that reaches the
   point (bs, ws) of candidate c's unscaled section meets the groove:
   returns the distance it has run along T from the mouth, and the scale
   *fh of the section there. §4.2-4.3 take the section at P (f(s)); a ray
   reaching depth w has run w tau along the path, where the section is
   scaled by f(s + w tau), w = fh ws: fh solves h(x) = f(s + x ws tau) - x
   = 0, by two secant steps from x = f (two calls of the perturbation; the
   first step is exact for a linear f, the second is skipped when the first
   barely moved f). The run is kept within one path
   length (grazing directions); steps that would leave [0, perturb_max]
   stop at the last good estimate. */
static double gr__ray_point(const gr__groove_t *rec, const gr__cand_t *c, double bs, double ws, double tau, double *fh)
{
    double f = c->f, lim = 1 / c->dtds, run, d0;
    *fh = f;
    if (ws == 0 || tau == 0) return 0;
    if (rec->perturb && f > 0) {
        double a = 1 / gr__stretch(c, f * bs); /* path arc per unit run */
        d0 = f * ws * tau;
        if (!(fabs(d0) <= lim)) d0 = d0 < 0 ? -lim : lim;
        if (d0 != 0) {
            double fb = gr__perturb(rec, gr__param_at(c, d0 * a)), h0 = fb - f;
            double den = 1 - h0 / d0 * ws * tau, x1 = den >= GR__RAY_SECANT_MIN ? f / den : fb;
            if (x1 > rec->fmax) x1 = rec->fmax;
            *fh = x1;
            /* the second step only where the first moved f noticeably
               (its own error is second order in that move) */
            if (fabs(x1 - f) > GR__RAY_SECOND_STEP * f && fabs(x1 * ws * tau) <= lim) {
                double h1 = gr__perturb(rec, gr__param_at(c, x1 * ws * tau * a)) - x1, x2;
                x2 = h1 != h0 ? x1 - h1 * (x1 - f) / (h1 - h0) : x1;
                if (x2 >= 0 && x2 <= rec->fmax) *fh = x2;
            }
        }
    }
    run = *fh * ws * tau;
    if (!(fabs(run) <= lim)) run = run < 0 ? -lim : lim;
    return run;
}

/* The bend's drift: a ray that has run `run` along T from the mouth of a
   groove whose path curves (signed kappa) ends that much farther from the
   centre of curvature than the straight line puts it, so the mouth point
   of the ray reaching b lies at b - D_b + drift (eq. 2's frame), with
   drift = sgn(kappa) (rho - sqrt(rho^2 - run^2)) and rho = 1/|kappa| -
   sgn(kappa) b the point's distance from the centre: exact for a circular
   arc. A curvature that changes along the path (dkds) enters as the
   circle whose sagitta over the run matches the path's to third order,
   kappa + dkds run / 3 (the path leaves its tangent by
   kappa run^2/2 + dkds run^3/6). */
static double gr__bend_drift(double kappa, double dkds, double b, double run)
{
    double rho, r2;
    kappa += dkds * run / 3;
    if (kappa == 0 || run == 0) return 0;
    rho = 1 / fabs(kappa) - (kappa > 0 ? b : -b);
    if (!(rho > 0)) return 0;
    r2 = run * run < rho * rho ? run * run : rho * rho;
    return (kappa > 0 ? 1 : -1) * r2 / (rho + sqrt(rho * rho - r2));
}

/* Candidate c re-anchored an arc length ds along its path: parameter,
   scale and, on a Bézier path, the frame there. Its offset d is kept: a
   light's sweep compares points of one footprint with each other, so only
   their relative positions matter. */
static void gr__cand_shift(const gr_grid_t *grid, const gr__cand_t *c, double ds, gr__cand_t *out)
{
    const gr__groove_t *rec = &grid->grooves_[c->groove];
    double param = gr__param_at(c, ds);
    *out = *c;
    param = param < 0 ? 0 : param > 1 ? 1 : param;
    out->param = param;
    if (rec->perturb) out->f = gr__perturb(rec, param);
#ifndef GR_NO_CURVES
    if (c->kappa != 0 || c->dkds != 0) {
        double b[2], d1[2], d2[2];
        const double *a = gr__bezier_at(grid, rec, param, b, d1, d2);
        if (d1[0] * d1[0] + d1[1] * d1[1] > 0) gr__bezier_frame(a, gr__degree(rec->kind), rec->pieces, b, d1, d2, out);
    }
#else
    (void)grid;
#endif
}

#ifndef GR_NO_CURVES
/* The mouth coordinate B . (M - P) (candidate c's frame at P) of the ray
   along dir that reaches the section point (bs, ws) of a Bézier groove,
   refined on the path itself: the local model (scale fh, run) puts the hit
   at arc run / (1 - kappa f b) from P; there the true point H = P(s) +
   f(s) (bs B(s) + ws W) has its mouth point M = H - (f(s) ws / dir_w)
   dir_uv, whose offset v = T . (M - P) along the path is the model's
   residual; the ray entering on P's cross line (v = 0) enters at
   B . (M - P) - v tan(turn) (one Newton step along the groove, which runs
   at that turn there). Exact where the model is, second order in its
   residual elsewhere (the bend's changing curvature). */
static double gr__mouth_on_path(const gr_grid_t *grid, const gr__cand_t *c, double bs, double ws, const double *dir,
                                double fh, double run)
{
    const gr__groove_t *rec = &grid->grooves_[c->groove];
    double param = gr__param_at(c, run / gr__stretch(c, fh * bs)), b[2], d1[2], d2[2], sp, th[2], f, w, m[2], u, v, ct;
    param = param < 0 ? 0 : param > 1 ? 1 : param;
    gr__bezier_at(grid, rec, param, b, d1, d2);
    sp = sqrt(d1[0] * d1[0] + d1[1] * d1[1]);
    if (!(sp > 0)) return fh * bs + gr__bend_drift(c->kappa, c->dkds, fh * bs, run) - fh * ws * (dir[0] * -c->t[1] + dir[1] * c->t[0]) / dir[2];
    th[0] = d1[0] / sp;
    th[1] = d1[1] / sp;
    f = rec->perturb ? gr__perturb(rec, param) : c->f;
    w = f * ws;
    m[0] = b[0] - f * bs * th[1] - w * dir[0] / dir[2] - c->p[0];
    m[1] = b[1] + f * bs * th[0] - w * dir[1] / dir[2] - c->p[1];
    u = -c->t[1] * m[0] + c->t[0] * m[1];
    v = c->t[0] * m[0] + c->t[1] * m[1];
    ct = c->t[0] * th[0] + c->t[1] * th[1];
    if (ct < GR__STRETCH_MIN) ct = GR__STRETCH_MIN;
    return u - v * (-c->t[1] * th[0] + c->t[0] * th[1]) / ct;
}
#endif

/* The merged points projected along direction dir (above the surface):
   q_i = dw x_i - db w_i, (db, dw) its (dir . B_ref, dir_w) scaled by
   inv_m (gr__grazing_scale; §4.2's signed tan θ' times dw). With the ray
   profile each groove point is taken where the ray along dir that reaches
   it meets the groove (gr__ray_point, gr__bend_drift), the rays entering
   the mouth an arc length `anchor` along the path from the footprint: 0
   for the view; for a light, where its rays toward the seen facets enter
   (gr__light_anchor), the groove then taken in its own frame there (on a
   bend the light sees it turned). Ground points stay. */
static void gr__project(const gr_grid_t *grid, const gr__qset_t *qs, const gr__scratch_t *s, int np, const double *dir,
                        double db, double dw, double inv_m, double anchor, double *q)
{
    gr__cand_t cs;
    int i, last = -1;
    double dbi = db;
    for (i = 0; i < np; i++) {
        const gr__cand_t *c;
        double tau, fh, run, x, w;
        if (!qs->ray_profile || s->pc[i] < 0 || (s->ws[i] == 0 && anchor == 0)) {
            q[i] = dw * s->x[i] - db * s->w[i];
            continue;
        }
        c = &s->cand[s->pc[i]];
        if (c->kappa == 0 && c->dkds == 0 && !grid->grooves_[c->groove].perturb) {
            q[i] = dw * s->x[i] - db * s->w[i];
            continue;
        }
        if (anchor != 0) {
            if (s->pc[i] != last) {
                gr__cand_shift(grid, c, anchor, &cs);
                /* the direction across the groove there, in the same scale */
                dbi = c->sigma * (-dir[0] * cs.t[1] + dir[1] * cs.t[0]) * inv_m;
            }
            last = s->pc[i];
            c = &cs;
        } else
            dbi = db;
        tau = (dir[0] * c->t[0] + dir[1] * c->t[1]) / dir[2];
        run = gr__ray_point(&grid->grooves_[c->groove], c, s->bs[i], s->ws[i], tau, &fh);
#ifndef GR_NO_CURVES
        if ((c->kappa != 0 || c->dkds != 0) && run != 0) { /* on the path itself: q = dw times the mouth coordinate */
            q[i] = dw * c->sigma * (gr__mouth_on_path(grid, c, s->bs[i], s->ws[i], dir, fh, run) - c->d);
            continue;
        }
#endif
        x = c->sigma * (fh * s->bs[i] - c->d + gr__bend_drift(c->kappa, c->dkds, fh * s->bs[i], run));
        w = fh * s->ws[i];
        q[i] = dw * x - dbi * w;
    }
}

/* Where the rays of light l toward the seen facets enter the mouth, as an
   arc length along the path from the footprint: the view ray runs run_E
   to a facet's seen middle, the light ray from there up runs back run_L,
   so it entered at run_E - run_L. Weighted by the facets' seen lengths
   (one anchor per light and footprint); 0 without the ray profile or
   where nothing curved or perturbed is seen. */
static double gr__light_anchor(const gr_grid_t *grid, const gr__qset_t *qs, const gr__scratch_t *s, int nf,
                               const double *e, const double *l)
{
    double sum = 0, wsum = 0;
    int i;
    if (!qs->ray_profile) return 0;
    for (i = 0; i < nf; i++) {
        const gr__cand_t *c;
        const gr__groove_t *rec;
        double de, mid, bs, ws, fh, len;
        if (s->pc[i] < 0 || s->pc[i] != s->pc[i + 1] || !(s->vb[i] > s->va[i])) continue;
        c = &s->cand[s->pc[i]];
        rec = &grid->grooves_[c->groove];
        if (c->kappa == 0 && c->dkds == 0 && !rec->perturb) continue;
        de = s->qe[i + 1] - s->qe[i];
        mid = de != 0 ? (0.5 * (s->va[i] + s->vb[i]) - s->qe[i]) / de : 0.5;
        mid = mid < 0 ? 0 : mid > 1 ? 1 : mid;
        bs = s->bs[i] + mid * (s->bs[i + 1] - s->bs[i]);
        ws = s->ws[i] + mid * (s->ws[i + 1] - s->ws[i]);
        len = s->vb[i] - s->va[i];
        sum += len * (gr__ray_point(rec, c, bs, ws, (e[0] * c->t[0] + e[1] * c->t[1]) / e[2], &fh) -
                      gr__ray_point(rec, c, bs, ws, (l[0] * c->t[0] + l[1] * c->t[1]) / l[2], &fh));
        wsum += len;
    }
    return wsum > 0 ? sum / wsum : 0;
}

#ifndef GR_NO_CURVES
/* A Bézier path at parameter param (piece k of n covers [k/n, (k+1)/n],
   uniformly): the angle (radians, counter-clockwise) from the unit tangent
   t0 to its tangent there, and d param / d arc length there. */
static double gr__turn_to(const gr_grid_t *grid, const gr__groove_t *rec, double param, const double t0[2],
                          double *dtds)
{
    double b[2], d1[2], d2[2], sp;
    gr__bezier_at(grid, rec, param, b, d1, d2);
    sp = sqrt(d1[0] * d1[0] + d1[1] * d1[1]);
    if (sp > 0) *dtds = 1 / (rec->pieces * sp);
    return atan2(t0[0] * d1[1] - t0[1] * d1[0], t0[0] * d1[0] + t0[1] * d1[1]);
}
#endif

/* The normal where the view ray really meets a visible facet (i, of
   candidate c). The ray reaches the facet's visible part at its middle,
   the point (bs, ws) of the unscaled section, after running `run` along
   T (gr__ray_point), i.e. run / (1 - kappa f b) along the path (reached
   through d param / ds and its slope). There a curved path has turned (the
   path's own tangent there; at most
   GR__TURN_MAX), and the perturbation has its own slope (a central
   difference across the footprint's extent along T): on a tight bend, or
   a perturbation that changes within the ray's way through the groove,
   these decide where a highlight falls. */
static void gr__hit_normal(const gr_grid_t *grid, const gr__scratch_t *s, const gr_footprint_t *fp, int i, int point,
                           gr__mfacet_t *m)
{
    const gr__cand_t *c = &s->cand[m->cand];
    const gr__groove_t *rec = &grid->grooves_[c->groove];
    const double *e = fp->view;
    double de = s->qe[i + 1] - s->qe[i], mid, bs, ws, fh, run, phi, dfds, alpha, th, dtds;
    if (c->kappa == 0 && c->dfds == 0) return;
    mid = point ? 0 : 0.5 * (s->va[i] + s->vb[i]);
    mid = de != 0 ? (mid - s->qe[i]) / de : 0.5;
    if (!(mid >= 0)) mid = 0;
    if (mid > 1) mid = 1;
    bs = s->bs[i] + mid * (s->bs[i + 1] - s->bs[i]);
    ws = s->ws[i] + mid * (s->ws[i + 1] - s->ws[i]);
    run = gr__ray_point(rec, c, bs, ws, (e[0] * c->t[0] + e[1] * c->t[1]) / e[2], &fh);
    alpha = gr__stretch(c, fh * bs);
    phi = 0;
    dtds = c->dtds;
    th = gr__param_at(c, run / alpha);
#ifndef GR_NO_CURVES
    if (c->kappa != 0) phi = gr__turn_to(grid, rec, th, c->t, &dtds);
#endif
    if (phi > GR__TURN_MAX) phi = GR__TURN_MAX;
    if (phi < -GR__TURN_MAX) phi = -GR__TURN_MAX;
    dfds = c->dfds != 0 ? gr__perturb_slope(rec, dtds, th, gr__extent(fp, c->t)) : 0;
    gr__section_normal(c, grid->section_ + 2 * rec->first_sec, m->facet, phi, dfds, alpha, m->n);
}

#ifndef GR_NO_OVERSAMPLE
/* Oversampling count asked for by this groove (§4.2): the path's sagitta
   across the footprint, and the change of the perturbation, as fractions of
   the groove width, against the tolerance. */
static int gr__oversample_need(const gr_grid_t *grid, const gr__cand_t *c, const gr_footprint_t *fp, double tol)
{
    const gr__groove_t *rec = &grid->grooves_[c->groove];
    double ext = gr__extent(fp, c->t), width = 2 * rec->half_width / rec->fmax * c->f;
    double need = 1;
    if (!(width > 0) || !(ext > 0)) return 1;
    if (c->kappa != 0) {
        double sag = 0.5 * fabs(c->kappa) * ext * ext;
        double k = ceil(sqrt(sag / (tol * width)));
        /* the seen boundaries tilt across the footprint as the groove turns
           under it: a view ray running `run` along the path at the deepest
           point shifts by about kappa ext run from one end of the
           footprint to the other (run kept within one path length) */
        double run = rec->down / rec->fmax * c->f * fabs(fp->view[0] * c->t[0] + fp->view[1] * c->t[1]);
        run = run < fp->view[2] / c->dtds ? run / fp->view[2] : 1 / c->dtds;
        if (k > need) need = k;
        k = ceil(fabs(c->kappa) * ext * run / (tol * width));
        if (k > need) need = k;
    }
    if (rec->perturb) {
        double dt = ext * c->dtds, fa = gr__perturb(rec, c->param - dt), fb = gr__perturb(rec, c->param + dt);
        double fm = c->f > fa ? c->f : fa;
        if (fb > fm) fm = fb;
        if (fm > 0) {
            double k = ceil(fabs(fb - fa) / fm / tol);
            if (k > need) need = k;
        }
    }
    return need > 1e6 ? 1000000 : (int)need;
}

#endif

/* The footprint's bounding box around centre f, enlarged by the widest
   cross-section w (§4.1). The view- and light-dependent enlargements differ
   between the isolated case (§4.1, eq. 1) and intersections (§5.1), so the
   callers add them. ext_u, ext_v: the footprint's half-extents. */
static void gr__footprint_box(const gr_grid_t *grid, const gr_footprint_t *fp, const double f[2], double *ext_u,
                              double *ext_v, double box[4])
{
    *ext_u = fabs(fp->axis1[0]) + fabs(fp->axis2[0]);
    *ext_v = fabs(fp->axis1[1]) + fabs(fp->axis2[1]);
    box[0] = f[0] - *ext_u - grid->w;
    box[2] = f[0] + *ext_u + grid->w;
    box[1] = f[1] - *ext_v - grid->w;
    box[3] = f[1] + *ext_v + grid->w;
}

/* The footprint's share on [q0, q0 + len] across the groove (the clipping
   of eq. 3, weighted). For a groove locally straight over the footprint the
   visibility only depends on the coordinate x = B . (X - F), so each
   visible interval counts with the integral of the footprint's length
   density along x. The parallelogram F + a A1 + b A2, |a|,|b| <= 1 (what a
   box pixel filter covers) projects to x = a p1 + b p2, p_k = A_k . B: the
   sum of two uniform variables, a trapezoid of half-width big + small
   (big >= small the |p_k|) and plateau |x| <= big - small. In u = x / big,
   beta = small / big, the density is 1/2 on the plateau and falls linearly
   to 0 on the ramps, (1 + beta - |u|) / (4 beta); linear per piece, so each
   piece integrates exactly as its length times the density at its middle.
   beta = 0 is §4.2's segment S = [-big, big] with uniform weight (one axis
   along the groove): the ramps are empty, no division by zero is reached.
   The length is passed apart from q0 so a short interval far from the
   centre keeps its relative precision (lit fractions of 1e-12 stay exact).
   beta < 0 asks for the ellipse a^2 + b^2 <= 1 instead: it projects to the
   semicircle density 2 sqrt(1 - u^2) / pi, u = x / big, big = |(p1, p2)|,
   whose integral is gr__disc_cdf (intervals shorter than
   GR__DISC_MIDPOINT take the midpoint rule, for the same precision).
   q0, len and big are in the same (E_w-scaled) units. */
static double gr__disc_cdf(double u)
{
    return u <= -1 ? 0 : u >= 1 ? 1 : 0.5 + (u * sqrt(1 - u * u) + asin(u)) / GR__PI;
}
static double gr__xmass(double q0, double len, double big, double beta)
{
    double u0 = q0 / big, du = len / big, u1 = u0 + du, m = 0, e[4];
    int k;
    if (beta < 0) {
        double a = u0 > -1 ? u0 : -1, b = u1 < 1 ? u1 : 1, mid = 0.5 * (a + b);
        if (!(b > a)) return 0;
        if (a == u0 && b == u1 && du < GR__DISC_MIDPOINT) return du * 2 / GR__PI * sqrt(1 - mid * mid);
        return gr__disc_cdf(b) - gr__disc_cdf(a);
    }
    if (u0 >= beta - 1 && u1 <= 1 - beta) return 0.5 * du; /* on the plateau (all of S when beta = 0) */
    e[0] = -1 - beta; e[1] = beta - 1; e[2] = 1 - beta; e[3] = 1 + beta;
    for (k = 0; k < 3; k++) {
        double lo = u0 > e[k] ? u0 : e[k], hi = u1 < e[k + 1] ? u1 : e[k + 1], mid = 0.5 * (lo + hi);
        if (!(hi > lo)) continue;
        m += (lo == u0 && hi == u1 ? du : hi - lo) *
             (k == 1 ? 0.5 : (k == 0 ? mid + 1 + beta : 1 + beta - mid) / (4 * beta));
    }
    return m;
}

#ifndef GR_NO_LINE_SAMPLES
static int gr__self_in_box(const gr_grid_t *grid, int g, const double *box, const double *f);
#endif
/* gr__query_one()'s answer when `divert` found crossings or ends (line
   samples answer those, §5.6): nothing was added. */
#define GR__DIVERT (-1)
#ifndef GR_NO_LINE_SAMPLES
#  define GR__LINES_WANTED(query) ((query)->line_samples > 0)
#else
#  define GR__LINES_WANTED(query) 0
#endif

/* §4.1: the footprint's box around f (its centre, in the tile when the
   grid wraps), enlarged by w, and by h tan θ toward the viewer and each
   light (eq. 1) when something protrudes. Returns the largest tan θ of the
   view and the lights above the horizon; *radius is the footprint's. */
static double gr__query_box(const gr_grid_t *grid, const gr__qset_t *qs, const gr_footprint_t *fp, const double f[2],
                            double box[4], double *radius)
{
    const double *e = fp->view;
    double ext_u, ext_v, tanmax;
    int k;
    gr__footprint_box(grid, fp, f, &ext_u, &ext_v, box);
    *radius = sqrt(ext_u * ext_u + ext_v * ext_v);
    tanmax = gr__tan(e);
    if (grid->h > 0) {
        for (k = -1; k < qs->light_count; k++) {
            const double *dir = k < 0 ? e : qs->lights + 3 * k;
            double su, sv;
            if (!(dir[2] > 0)) continue;
            su = grid->h * dir[0] / dir[2];
            sv = grid->h * dir[1] / dir[2];
            if (k >= 0 && gr__tan(dir) > tanmax) tanmax = gr__tan(dir);
            if (su < 0) box[0] += su; else box[2] += su;
            if (sv < 0) box[1] += sv; else box[3] += sv;
        }
    }
    return tanmax;
}

/* §4.2: the grooves of the box whose section can reach the footprint,
   each with its nearest point, tangent, distance and perturbation, into
   s->cand; flags path ends in the list, and *self_cross when (with
   divert) a groove's self-crossing lies in the box. Returns their count,
   *ref the nearest one (-1: none). */
static int gr__nearby_grooves(const gr_grid_t *grid, const gr__qset_t *qs, const gr_footprint_t *fp, const gr__scratch_t *s,
                              gr_facet_list_t *list, const double f[2], const double box[4], double radius, double tanmax,
                              int divert, int *ref, int *self_cross)
{
    int n = gr__gather(grid, box, s->seen, s->ids, s->visited), k, npar = 0;
    *ref = -1;
    for (k = 0; k < n; k++) {
        gr__cand_t *c = &s->cand[npar];
        const gr__groove_t *rec = &grid->grooves_[s->ids[k]];
        double bn[2], reach = rec->half_width + (rec->up > 0 ? rec->up * tanmax : 0);
        /* a groove farther than its half width plus the footprint's radius
           (and its peaks' projected height) cannot touch the footprint */
        if (!gr__locate(grid, s->ids[k], f, reach + radius, c)) continue;
        bn[0] = -c->t[1];
        bn[1] = c->t[0];
        c->d = bn[0] * (c->fc[0] - c->p[0]) + bn[1] * (c->fc[1] - c->p[1]);
        if (!(fabs(c->d) <= reach + gr__extent(fp, bn))) continue;
        if (c->end) {
            double along = fabs(c->t[0] * (c->fc[0] - c->p[0]) + c->t[1] * (c->fc[1] - c->p[1]));
            if (along <= gr__extent(fp, c->t) + rec->half_width) list->flags |= GR_LIST_PATH_END;
            continue;
        }
        if (!rec->closed) { /* an end inside the footprint (issue 8 treats ends) */
            double to_end = (c->param < 1 - c->param ? c->param : 1 - c->param) / c->dtds;
            if (to_end < gr__extent(fp, c->t)) list->flags |= GR_LIST_PATH_END;
        }
#ifndef GR_NO_LINE_SAMPLES
        if (divert && gr__self_in_box(grid, c->groove, box, f)) *self_cross = 1;
#else
        (void)divert, (void)self_cross;
#endif
        c->f = gr__perturb(rec, c->param);
        c->dfds = rec->perturb && qs->perturb_normals ? gr__perturb_slope(rec, c->dtds, c->param, gr__extent(fp, c->t)) : 0;
        if (*ref < 0 || fabs(c->d) < fabs(s->cand[*ref].d)) *ref = npar;
        npar++;
    }
    return npar;
}

/* §4.2: keeps the candidates parallel to the nearest one (ref; the others
   are intersections, flagged), each with its orientation sigma relative to
   it; bref = its B (the x axis without candidates). Returns their count. */
static int gr__keep_parallel(const gr__qset_t *qs, const gr__scratch_t *s, gr_facet_list_t *list, int npar, int ref,
                             double bref[2])
{
    gr__cand_t rc;
    int k, m = 0;
    if (ref < 0) {
        bref[0] = 1;
        bref[1] = 0;
        return npar;
    }
    rc = s->cand[ref];
    for (k = 0; k < npar; k++) {
        gr__cand_t *c = &s->cand[k];
        double cr = c->t[0] * rc.t[1] - c->t[1] * rc.t[0], dt = c->t[0] * rc.t[0] + c->t[1] * rc.t[1];
        if (fabs(cr) > qs->parallel_sin || dt == 0) { list->flags |= GR_LIST_NONPARALLEL; continue; }
        c->sigma = dt > 0 ? 1 : -1;
        s->cand[m++] = *c;
    }
    bref[0] = -rc.t[1];
    bref[1] = rc.t[0];
    return m;
}

/* The footprint across the grooves (direction bref): §4.2's segment
   S = [-pm, pm] from the larger axis projection, widened by the smaller
   one pn into the parallelogram's trapezoid density (gr__xmass) on
   [-half, half], or the ellipse's semicircle; a footprint narrower than
   GR__POINT_FOOTPRINT_REL of the widest half-width (grid->w) is a point. */
typedef struct gr__across_t {
    double pm, half, beta; /* gr__xmass's big (before the E_w scale) and beta */
    int point;
} gr__across_t;
static gr__across_t gr__footprint_across(const gr_grid_t *grid, const gr__qset_t *qs, const gr_footprint_t *fp,
                                         const double bref[2])
{
    gr__across_t a;
    double pm = fabs(fp->axis1[0] * bref[0] + fp->axis1[1] * bref[1]), pn = fabs(fp->axis2[0] * bref[0] + fp->axis2[1] * bref[1]);
    if (pn > pm) { double t = pm; pm = pn; pn = t; }
    a.half = pm + pn;
    a.point = pm <= GR__POINT_FOOTPRINT_REL * grid->w;
    a.beta = a.point ? 0 : pn / pm;
    if (qs->ellipse) { /* the semicircle of radius |(p1, p2)| (gr__xmass) */
        pm = a.half = sqrt(pm * pm + pn * pn);
        if (!a.point) a.beta = -1;
    }
    a.pm = pm;
    return a;
}

/* The merged cross-section (§4.2, Figure 5b) into s->x, s->w and s->mf:
   the sections shifted by d_P, mirrored when their tangent is opposite,
   sorted, ground in between and beyond [-half, half]. Returns its point
   count; flags overlapping sections. */
static int gr__merge_sections(const gr_grid_t *grid, const gr__scratch_t *s, gr_facet_list_t *list, int npar, double half)
{
    gr__mfacet_t ground;
    double maxhalf = 0, margin;
    int k, i, np = 0;
    for (k = 0; k < npar; k++) {
        gr__cand_t *c = &s->cand[k];
        const gr__groove_t *rec = &grid->grooves_[c->groove];
        const double *sec = grid->section_ + 2 * rec->first_sec;
        c->xmin = c->sigma > 0 ? c->f * sec[0] - c->d : c->d - c->f * sec[2 * (rec->sec_count - 1)];
        if (rec->half_width / rec->fmax * c->f > maxhalf) maxhalf = rec->half_width / rec->fmax * c->f;
        s->key[k].x = c->xmin;
        s->key[k].cand = k;
        s->key[k].groove = c->groove;
    }
    gr__sort_keys(s->key, npar);
    margin = half + maxhalf;
    if (!(margin > 0)) margin = 1;
    ground.n[0] = 0; ground.n[1] = 0; ground.n[2] = 1;
    ground.groove = -1; ground.facet = -1; ground.refl = grid->base_reflectance; ground.cand = -1;
    s->x[np] = (npar ? (s->key[0].x < -half ? s->key[0].x : -half) : -half) - margin;
    s->pc[np] = -1;
    s->w[np++] = 0;
    for (k = 0; k < npar; k++) {
        const gr__cand_t *c = &s->cand[s->key[k].cand];
        const gr__groove_t *rec = &grid->grooves_[c->groove];
        const double *sec = grid->section_ + 2 * rec->first_sec;
        const int nsec = rec->sec_count;
        if (c->xmin < s->x[np - 1]) list->flags |= GR_LIST_OVERLAP;
        s->mf[np - 1] = ground; /* the ground facet leading to this groove */
        for (i = 0; i < nsec; i++) {
            int src = c->sigma > 0 ? i : nsec - 1 - i;
            s->x[np] = c->sigma * (c->f * sec[2 * src] - c->d);
            s->w[np] = c->f * sec[2 * src + 1];
            s->pc[np] = s->key[k].cand;
            s->bs[np] = sec[2 * src];
            s->ws[np] = sec[2 * src + 1];
            if (i + 1 < nsec) {
                /* facet R_j = [C_j, C_j+1] in the groove's own orientation */
                int j = c->sigma > 0 ? i : nsec - 2 - i;
                gr__mfacet_t *m = &s->mf[np];
                gr__section_normal(c, sec, j, 0, c->dfds, 1, m->n);
                m->groove = c->groove;
                m->facet = j;
                m->refl = grid->facet_refl_[rec->first_facet + j];
                m->cand = s->key[k].cand;
            }
            np++;
        }
    }
    s->mf[np - 1] = ground;
    s->x[np] = (s->x[np - 1] > half ? s->x[np - 1] : half) + margin;
    s->pc[np] = -1;
    s->w[np++] = 0;
    return np;
}

/* The visible part [va, vb] of each of the nf = np - 1 facets in the
   view's projection (§4.2), scaled by E_w so grazing views stay finite:
   q = E_w proj = E_w x - E_b w (each groove point where the view ray
   reaching it meets the groove, gr__project), masked (eq. 4) and clipped
   to the footprint (eq. 3; a point footprint keeps the facet under its
   centre, [0, 0]). Returns E_w's scale, the unit of va, vb. */
static double gr__visible_parts(const gr_grid_t *grid, const gr__qset_t *qs, const gr__scratch_t *s, int np, const double e[3],
                                const double bref[2], const gr__across_t *a)
{
    double eb = e[0] * bref[0] + e[1] * bref[1], ew = e[2], sq0, sq1;
    int i;
    gr__grazing_scale(&eb, &ew);
    gr__project(grid, qs, s, np, e, eb, ew, 1, 0, s->qe);
    gr__sweep(s->qe, np, eb > 0, s->lo, s->hi); /* masking, eq. 4 */
    sq0 = -a->half * ew;
    sq1 = a->half * ew;
    for (i = 0; i < np - 1; i++) { /* clipping, eq. 3 */
        double lo = s->lo[i], hi = s->hi[i];
        if (a->point) {
            if (lo <= 0 && 0 < hi) { s->va[i] = 0; s->vb[i] = 0; }
            else s->va[i] = s->vb[i] = HUGE_VAL;
            continue;
        }
        if (lo < sq0) lo = sq0;
        if (hi > sq1) hi = sq1;
        s->va[i] = lo;
        s->vb[i] = hi;
    }
    return ew;
}

/* Shadowing (§4.3): the same projection and masking per light, intersected
   with each facet's visible part in the facet's own parameter and weighted
   by the footprint's density across (big = pm E_w), into s->lit. */
static void gr__shadow_lights(const gr_grid_t *grid, const gr__qset_t *qs, const gr__scratch_t *s, int np, const double e[3],
                              const double bref[2], const gr__across_t *a, double big)
{
    int k, i, nf = np - 1;
    for (k = 0; k < qs->light_count; k++) {
        const double *l = qs->lights + 3 * k;
        double lb = l[0] * bref[0] + l[1] * bref[1], lw = l[2], inv_m = 1 / (fabs(lb) > lw ? fabs(lb) : lw);
        if (!(l[2] > 0)) { /* at or below the horizon */
            for (i = 0; i < nf; i++) s->lit[(size_t)i * GR_MAX_LIGHTS + k] = 0;
            continue;
        }
        gr__grazing_scale(&lb, &lw);
        gr__project(grid, qs, s, np, l, lb, lw, inv_m, gr__light_anchor(grid, qs, s, nf, e, l), s->q);
        gr__sweep(s->q, np, lb > 0, s->lo, s->hi);
        for (i = 0; i < nf; i++) {
            double de, sa, sb, la, lbb, dl, ov, v;
            if (!(s->vb[i] > s->va[i]) && !(a->point && s->va[i] == 0)) continue;
            de = s->qe[i + 1] - s->qe[i];
            sa = (s->va[i] - s->qe[i]) / de;
            sb = (s->vb[i] - s->qe[i]) / de;
            if (!(s->hi[i] > s->lo[i])) { s->lit[(size_t)i * GR_MAX_LIGHTS + k] = 0; continue; }
            dl = s->q[i + 1] - s->q[i];
            la = (s->lo[i] - s->q[i]) / dl;
            lbb = (s->hi[i] - s->q[i]) / dl;
            if (a->point || !(sb > sa)) v = la <= sa && sa <= lbb;
            else {
                /* the lit part of the visible interval, back in view
                   projection, weighted by the footprint density */
                double oa = sa > la ? sa : la, ob = sb < lbb ? sb : lbb, qv = s->qe[i];
                double wv = gr__xmass(s->va[i], s->vb[i] - s->va[i], big, a->beta);
                ov = ob - oa;
                if (!(ov > 0)) v = 0;
                else if (wv > 0) v = gr__xmass(qv + oa * de, ov * de, big, a->beta) / wv;
                else v = ov / (sb - sa);
            }
            s->lit[(size_t)i * GR_MAX_LIGHTS + k] = v;
        }
    }
}

/* One footprint: gather, approximate, merge, project, clip, mask, shadow
   (§4.1-4.4), adding weight x ratios to the list. With allow_split it
   returns the oversampling count needed (> 1: nothing was added). With
   divert, a footprint that a non-parallel groove, a path end (the flags
   GR_LIST_NONPARALLEL, GR_LIST_PATH_END) or a groove's self-crossing
   reaches returns GR__DIVERT right after the search (§4.1-4.2) and the
   oversampling count, before any profile work: line samples will answer
   it (a footprint to be oversampled is left to its parts' flags, as §4's
   answer always was, unless a self-crossing reaches it). */
static int gr__query_one(const gr_grid_t *grid, const gr__qset_t *qs, const gr_footprint_t *fp, double weight,
                         const gr__scratch_t *s, gr_facet_list_t *list, int allow_split, int divert, double split_t[2])
{
    double f[2], box[4], radius, tanmax, bref[2], ew;
    int k, ref, np, npar, i, self_cross = 0;
    gr__across_t a;
    f[0] = fp->center[0];
    f[1] = fp->center[1];
    if (grid->wrap) { /* the centre's image in the tile */
        double wu = grid->domain[2] - grid->domain[0], wv = grid->domain[3] - grid->domain[1];
        f[0] -= floor((f[0] - grid->domain[0]) / wu) * wu;
        f[1] -= floor((f[1] - grid->domain[1]) / wv) * wv;
    }
    tanmax = gr__query_box(grid, qs, fp, f, box, &radius);
    npar = gr__nearby_grooves(grid, qs, fp, s, list, f, box, radius, tanmax, divert, &ref, &self_cross);
    npar = gr__keep_parallel(qs, s, list, npar, ref, bref);
#ifndef GR_NO_OVERSAMPLE
    if (allow_split && qs->oversample_tol > 0 && qs->max_oversample > 1) {
        int need = 1;
        for (k = 0; k < npar; k++) {
            int nk = gr__oversample_need(grid, &s->cand[k], fp, qs->oversample_tol);
            if (nk > need) { need = nk; split_t[0] = s->cand[k].t[0]; split_t[1] = s->cand[k].t[1]; }
        }
        if (need > 1 && !(divert && self_cross))
            return need > GR__LIMIT_MAX_OVERSAMPLE * GR__LIMIT_MAX_OVERSAMPLE ? GR__LIMIT_MAX_OVERSAMPLE * GR__LIMIT_MAX_OVERSAMPLE : need;
    }
#else
    (void)allow_split;
    (void)split_t;
    (void)k;
#endif
    /* an oversampled footprint's parts decide by their own flags (the
       caller); a self-crossing diverts at once */
    if (divert && (self_cross || (list->flags & (GR_LIST_NONPARALLEL | GR_LIST_PATH_END)))) return GR__DIVERT;
    a = gr__footprint_across(grid, qs, fp, bref);
    np = gr__merge_sections(grid, s, list, npar, a.half);
    if (list->grooves < npar) list->grooves = npar;
    ew = gr__visible_parts(grid, qs, s, np, fp->view, bref, &a);
    gr__shadow_lights(grid, qs, s, np, fp->view, bref, &a, a.pm * ew);
    for (i = 0; i < np - 1; i++) { /* ratios r_i (§4.4) into the list */
        double r;
        if (a.point) r = s->va[i] == 0 ? 1 : 0;
        else r = s->vb[i] > s->va[i] ? gr__xmass(s->va[i], s->vb[i] - s->va[i], a.pm * ew, a.beta) : 0;
        if (r > 0) {
            gr__mfacet_t m = s->mf[i];
            if (m.cand >= 0 && qs->perturb_normals) gr__hit_normal(grid, s, fp, i, a.point, &m);
            gr__list_add(list, &m, weight * r, s->lit + (size_t)i * GR_MAX_LIGHTS, qs->light_count);
        }
    }
    return 1;
}

/* The query's settings with their defaults (gr_query_t), after checking
   that its numbers are finite (its light count is checked):
   GR_ERR_NOT_FINITE or GR_OK. */
static gr_result_t gr__query_settings(const gr_query_t *query, gr__qset_t *qs)
{
    const gr_footprint_t *fp = &query->footprint;
    int k;
    if (!gr__finite_n(fp->center, 2) || !gr__finite_n(fp->axis1, 2) || !gr__finite_n(fp->axis2, 2) ||
        !gr__finite_n(fp->view, 3) || !gr__finite(query->oversample_tol) || !gr__finite(query->parallel_tol))
        return GR_ERR_NOT_FINITE;
    for (k = 0; k < 3 * query->light_count; k++)
        if (!gr__finite(query->lights[k])) return GR_ERR_NOT_FINITE;
    qs->lights = query->lights;
    qs->light_count = query->light_count;
    qs->oversample_tol = query->oversample_tol == 0 ? GR__DEFAULT_OVERSAMPLE_TOL : query->oversample_tol;
    qs->max_oversample = query->max_oversample <= 0 ? GR__DEFAULT_MAX_OVERSAMPLE : query->max_oversample;
    if (qs->max_oversample > GR__LIMIT_MAX_OVERSAMPLE) qs->max_oversample = GR__LIMIT_MAX_OVERSAMPLE;
    qs->perturb_normals = query->perturb_normals >= 0;
    qs->ray_profile = query->straight_occlusion == 0;
    qs->ellipse = query->ellipse != 0;
    qs->parallel_sin = sin(fabs(query->parallel_tol == 0 ? GR__DEFAULT_PARALLEL_TOL : query->parallel_tol));
    return GR_OK;
}

/* §4.2 oversampling of an ellipse: slabs across its axis a most along the
   groove (extents p along it), taken as parallelograms of the slab's area
   (weight) and mean chord (the other axis): an approximation. */
static void gr__oversample_ellipse(const gr_grid_t *grid, const gr__qset_t *qs, const gr_footprint_t *fp, const gr__scratch_t *s,
                                   gr_facet_list_t *list, int need, const double p[2], double t[2])
{
    gr_footprint_t sub = *fp;
    gr__qset_t qsub = *qs;
    int a = p[0] >= p[1] ? 0 : 1, k;
    const double *ax = a ? fp->axis2 : fp->axis1, *other = a ? fp->axis1 : fp->axis2;
    double *sa = a ? sub.axis2 : sub.axis1, *so = a ? sub.axis1 : sub.axis2;
    qsub.ellipse = 0;
    if (need > qs->max_oversample) need = qs->max_oversample;
    sa[0] = ax[0] / need;
    sa[1] = ax[1] / need;
    for (k = 0; k < need; k++) {
        double o = (2.0 * k + 1) / need - 1, a0 = -1 + 2.0 * k / need, a1 = a0 + 2.0 / need, wk, hbar;
        wk = gr__disc_cdf(a1) - gr__disc_cdf(a0);
        hbar = GR__PI * wk / (2 * (a1 - a0)); /* slab area / (2 width), unit disc */
        so[0] = other[0] * hbar;
        so[1] = other[1] * hbar;
        sub.center[0] = fp->center[0] + o * ax[0];
        sub.center[1] = fp->center[1] + o * ax[1];
        gr__query_one(grid, &qsub, &sub, wk, s, list, 0, 0, t);
    }
    list->subfootprints = need;
}

/* §4.2 oversampling of a parallelogram: into n1 x n2 parallelograms
   (exact weights), each axis cut in proportion to its own extent p[k]
   along the groove, so every part spans 1/need of the extent: an axis
   oblique to the groove runs along it too, and cutting only the other
   would leave that part of the extent whole (the answer would not
   converge as the tolerance shrinks). Past max_oversample parts, the
   split that makes the parts' extent p1/n1 + p2/n2 least with
   n1 n2 <= max_oversample. */
static void gr__oversample_parallelogram(const gr_grid_t *grid, const gr__qset_t *qs, const gr_footprint_t *fp,
                                         const gr__scratch_t *s, gr_facet_list_t *list, int need, const double p[2], double t[2])
{
    gr_footprint_t sub = *fp;
    int n[2], k, j1, j2;
    for (k = 0; k < 2; k++) {
        n[k] = (int)ceil(need * p[k] / (p[0] + p[1]) - 1e-9);
        if (n[k] < 1) n[k] = 1;
    }
    if (n[0] * n[1] > qs->max_oversample) {
        int m = qs->max_oversample;
        n[0] = p[1] > 0 ? (int)floor(sqrt(m * p[0] / p[1]) + 0.5) : m;
        n[0] = n[0] < 1 ? 1 : n[0] > m ? m : n[0];
        n[1] = m / n[0];
    }
    sub.axis1[0] = fp->axis1[0] / n[0];
    sub.axis1[1] = fp->axis1[1] / n[0];
    sub.axis2[0] = fp->axis2[0] / n[1];
    sub.axis2[1] = fp->axis2[1] / n[1];
    for (j1 = 0; j1 < n[0]; j1++)
        for (j2 = 0; j2 < n[1]; j2++) {
            double o1 = (2.0 * j1 + 1) / n[0] - 1, o2 = (2.0 * j2 + 1) / n[1] - 1;
            sub.center[0] = fp->center[0] + o1 * fp->axis1[0] + o2 * fp->axis2[0];
            sub.center[1] = fp->center[1] + o1 * fp->axis1[1] + o2 * fp->axis2[1];
            gr__query_one(grid, qs, &sub, 1.0 / (n[0] * n[1]), s, list, 0, 0, t);
        }
    list->subfootprints = n[0] * n[1];
}

GR_DEF gr_result_t gr_query(const gr_grid_t *grid, const gr_query_t *query, void *scratch, size_t scratch_bytes,
                            gr_facet_list_t *list)
{
    gr__qset_t qs;
    gr__scratch_t s;
    const gr_footprint_t *fp;
    double el, t[2] = {0, 1};
    int need;
    gr_result_t r;
    if (!grid || !query || !scratch || !list) return GR_ERR_INVALID_ARG;
    list->count = 0;
    list->flags = 0;
    list->grooves = 0;
    list->subfootprints = 1;
    if (query->light_count < 0 || query->light_count > GR_MAX_LIGHTS || (query->light_count > 0 && !query->lights) ||
        query->line_samples < 0 || query->line_samples > GR_LINE_MAX_SAMPLES) /* whatever the footprint meets */
        return GR_ERR_INVALID_ARG;
    if (scratch_bytes < gr_query_scratch_bytes(grid)) return GR_ERR_BUFFER_TOO_SMALL;
    if ((r = gr__query_settings(query, &qs)) != GR_OK) return r;
    fp = &query->footprint;
    el = sqrt(gr__dot3(fp->view, fp->view));
    if (!(fp->view[2] > 0) || !(el > 0)) { list->flags |= GR_LIST_BELOW_HORIZON; return GR_OK; }
    gr__scratch_layout(grid, scratch, &s);
    /* §5: crossings and path ends in the footprint take the polygon path
       (line samples, §5.6, for line_samples > 0: see the end) */
#ifndef GR_NO_INTERSECTIONS
    if (query->line_samples == 0 && gr__pp_dispatch(grid, query, scratch, scratch_bytes, &s, list)) {
        gr__list_finish(list, qs.light_count);
        return GR_OK;
    }
#endif
    need = gr__query_one(grid, &qs, fp, 1.0, &s, list, 1, GR__LINES_WANTED(query), t);
#ifndef GR_NO_LINE_SAMPLES
    /* §5.6 ([section: line samples]): crossings, ends and self-crossings
       take query->line_samples line samples, found by §4's search alone */
    if (need == GR__DIVERT) return gr_query_lines(grid, query, scratch, scratch_bytes, list, NULL);
#endif
    if (need > 1) {
        /* §4.2 oversampling: the footprint's extent along the groove (t) is
           cut `need` times, each part with its own straight approximation */
        double p[2];
        p[0] = fabs(fp->axis1[0] * t[0] + fp->axis1[1] * t[1]);
        p[1] = fabs(fp->axis2[0] * t[0] + fp->axis2[1] * t[1]);
        list->count = 0;
        list->flags = 0;
        list->grooves = 0;
        if (qs.ellipse) gr__oversample_ellipse(grid, &qs, fp, &s, list, need, p, t);
        else gr__oversample_parallelogram(grid, &qs, fp, &s, list, need, p, t);
    }
#ifndef GR_NO_LINE_SAMPLES
    /* an oversampled footprint's parts may still flag them */
    if (query->line_samples > 0 && (list->flags & (GR_LIST_NONPARALLEL | GR_LIST_PATH_END)))
        return gr_query_lines(grid, query, scratch, scratch_bytes, list, NULL);
#endif
    gr__list_finish(list, qs.light_count);
    return GR_OK;
}

GR_DEF gr_result_t gr_shade(const gr_grid_t *grid, const gr_query_t *query, void *scratch, size_t scratch_bytes,
                            gr_brdf_fn brdf, void *user, double rgb[3])
{
    gr_facet_list_t list;
    gr_result_t r;
    int i, k;
    if (!brdf || !rgb) return GR_ERR_INVALID_ARG;
    rgb[0] = rgb[1] = rgb[2] = 0;
    r = gr_query(grid, query, scratch, scratch_bytes, &list);
    if (r != GR_OK) return r;
    for (i = 0; i < list.count; i++) {
        const gr_facet_t *f = &list.facets[i];
        for (k = 0; k < query->light_count; k++) {
            double c[3] = {0, 0, 0};
            if (!(f->lit[k] > 0)) continue;
            brdf(user, f->reflectance, f->normal, query->footprint.view, query->lights + 3 * k, k, c);
            rgb[0] += f->ratio * f->lit[k] * c[0];
            rgb[1] += f->ratio * f->lit[k] * c[1];
            rgb[2] += f->ratio * f->lit[k] * c[2];
        }
    }
    return GR_OK;
}

/* ==== [section: intersections] implementation (issue 8: §5–6) ==== */
#ifndef GR_NO_INTERSECTIONS

/* ---- 2D polygons (§5.2-5.5) ---------------------------------------------- */

static double gr__cross2(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

GR_DEF double gr_poly_area(const double *xy, int n)
{
    double s = 0;
    int i;
    if (!xy || n < 3) return 0;
    /* shoelace about the first point: smaller terms, less cancellation */
    for (i = 1; i + 1 < n; i++) s += gr__cross2(xy, xy + 2 * i, xy + 2 * i + 2);
    return 0.5 * s;
}

/* A ring is convex when every turn has one sign and it winds once: the x
   direction of its edges changes sign at most twice (a pentagram turns one
   way throughout but winds twice). */
static int gr__ring_convex(const double *p, int n, double orient)
{
    int i, changes = 0, last = 0;
    for (i = 0; i < n; i++) {
        const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n), *c = p + 2 * ((i + 2) % n);
        double dx = b[0] - a[0];
        int sx = dx > 0 ? 1 : dx < 0 ? -1 : 0;
        if (orient * gr__cross2(a, b, c) < 0) return 0;
        if (sx != 0) {
            if (last != 0 && sx != last) changes++;
            last = sx;
        }
    }
    return changes <= 2;
}

GR_DEF gr_result_t gr_poly_clip_convex(const double *subject, int ns, const double *clip, int nc,
                                       double *out, double *work, int cap, int *nout)
{
    double orient;
    const double *src;
    double *dst;
    int n, j, i, stages;
    if (nout) *nout = 0;
    if (!nout || (!subject && ns > 0) || !clip || !out || !work || ns < 0 || nc < 3 || cap < 0)
        return GR_ERR_INVALID_ARG;
    if (!gr__finite_n(subject, 2 * ns) || !gr__finite_n(clip, 2 * nc)) return GR_ERR_NOT_FINITE;
    orient = gr_poly_area(clip, nc);
    if (orient == 0 || ns < 3) return GR_OK; /* empty clip region or subject */
    orient = orient > 0 ? 1 : -1;
    if (!gr__ring_convex(clip, nc, orient)) return GR_ERR_INVALID_ARG;
    if (ns > cap) return GR_ERR_BUFFER_TOO_SMALL;
    /* each clip edge is one stage; stages ping-pong so the last lands in out */
    stages = 0;
    for (j = 0; j < nc; j++) {
        const double *c0 = clip + 2 * j, *c1 = clip + 2 * ((j + 1) % nc);
        if (c0[0] != c1[0] || c0[1] != c1[1]) stages++;
    }
    src = subject;
    n = ns;
    dst = stages % 2 ? out : work;
    for (j = 0; j < nc && n > 0; j++) {
        const double *c0 = clip + 2 * j, *c1 = clip + 2 * ((j + 1) % nc);
        int m = 0;
        if (c0[0] == c1[0] && c0[1] == c1[1]) continue; /* repeated clip point */
        for (i = 0; i < n; i++) {
            const double *p = src + 2 * i, *q = src + 2 * ((i + 1) % n);
            /* signed side of each end against the clip line, > 0 inside */
            double dp = orient * gr__cross2(c0, c1, p), dq = orient * gr__cross2(c0, c1, q);
            if ((dp >= 0) != (dq >= 0)) { /* the edge crosses: emit the crossing */
                double t = dp / (dp - dq);
                if (m >= cap) return GR_ERR_BUFFER_TOO_SMALL;
                dst[2 * m] = p[0] + t * (q[0] - p[0]);
                dst[2 * m + 1] = p[1] + t * (q[1] - p[1]);
                m++;
            }
            if (dq >= 0) {
                if (m >= cap) return GR_ERR_BUFFER_TOO_SMALL;
                dst[2 * m] = q[0];
                dst[2 * m + 1] = q[1];
                m++;
            }
        }
        n = m;
        src = dst;
        dst = dst == out ? work : out;
    }
    GR_ASSERT(n == 0 || src == out);
    if (n > 0 && src != out) memcpy(out, src, sizeof(double) * 2 * (size_t)n);
    *nout = n < 3 ? 0 : n;
    return GR_OK;
}

/* gr_poly_boolean: one edge, stored bottom to top. */
typedef struct gr__pedge_t {
    double x0, y0, x1, y1;
    int set;  /* 0: a, 1: b */
    int ring; /* global ring index (a's rings first) */
    int id;   /* its place among the edges as made (the sort's tie-break) */
} gr__pedge_t;

/* A crossing of an edge with a slab's mid line. */
typedef struct gr__pcross_t {
    double x;
    int edge;
} gr__pcross_t;

static double gr__pedge_x(const gr__pedge_t *e, double y)
{
    double t = (y - e->y0) / (e->y1 - e->y0);
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    return e->x0 + t * (e->x1 - e->x0);
}

/* Sorting for the sweep: the lists run from a few entries to a few
   hundred, where Shell sort (Ciura's gaps; the last, 1, is insertion sort)
   with inlined compares beats qsort's indirect ones several times over.
   GR__SHELL_SORT(T, a, n, AFTER) sorts a[0..n) of type T, AFTER(p, x)
   being true when element p goes after x. */
#define GR__SHELL_SORT(T, a, n, AFTER)                                              \
    do {                                                                            \
        static const int gr__gaps[] = {701, 301, 132, 57, 23, 10, 4, 1};            \
        int gr__g, gr__i, gr__j;                                                    \
        for (gr__g = 0; gr__g < 8; gr__g++) {                                       \
            int gr__h = gr__gaps[gr__g];                                            \
            for (gr__i = gr__h; gr__i < (n); gr__i++) {                             \
                T gr__x = (a)[gr__i];                                               \
                for (gr__j = gr__i; gr__j >= gr__h && AFTER((a)[gr__j - gr__h], gr__x); gr__j -= gr__h) \
                    (a)[gr__j] = (a)[gr__j - gr__h];                                \
                (a)[gr__j] = gr__x;                                                 \
            }                                                                       \
        }                                                                           \
    } while (0)
#define GR__AFTER_DOUBLE(p, x) ((p) > (x))
#define GR__AFTER_EDGE(p, x) ((p).y0 > (x).y0 || ((p).y0 == (x).y0 && (p).id > (x).id))

/* Doubles: the crossing heights of a sweep (up to E (E - 1) / 2 for E
   edges) and a trace's section crossings. */
static void gr__sort_doubles(double *a, int n) { GR__SHELL_SORT(double, a, n, GR__AFTER_DOUBLE); }

/* Crossings of a slab's mid line by (x, edge), a total order, so the same
   as any sort; by insertion, as the list comes nearly sorted. */
static void gr__sort_pcross_nearly(gr__pcross_t *a, int n)
{
    int i, j;
    for (i = 1; i < n; i++) {
        gr__pcross_t x = a[i];
        for (j = i; j > 0 && (a[j - 1].x > x.x || (a[j - 1].x == x.x && a[j - 1].edge > x.edge)); j--) a[j] = a[j - 1];
        a[j] = x;
    }
}

/* Edges by their lower end (the sweep's insertion order), ties in the
   order they were made: by (y0, id), a total order. */
static void gr__sort_pedges_by_y0(gr__pedge_t *a, int n) { GR__SHELL_SORT(gr__pedge_t, a, n, GR__AFTER_EDGE); }
#undef GR__AFTER_EDGE
#undef GR__AFTER_DOUBLE
#undef GR__SHELL_SORT

/* Scratch of gr_poly_boolean for E edges (= points). */
typedef struct gr__pscratch_t {
    gr__pedge_t *edge;
    double *ys;
    gr__pcross_t *cross, *ia, *ib;
    int *active; /* edges spanning the current slab (the sweep's active list) */
    int *run;    /* the previous and this slab's trapezoids: (left edge, right edge, index) */
    unsigned char *parity;
} gr__pscratch_t;

/* Crossing heights gr_poly_boolean() has room for with E edges: every
   pair may cross (as ys holds crossings only, E (E - 1) / 2). */
static size_t gr__pcross_cap(int e) { size_t ne = e > 0 ? (size_t)e : 1; return ne * (ne - 1) / 2 + 1; }

static size_t gr__pscratch_layout(int e, size_t max_cross, void *base, gr__pscratch_t *s)
{
    size_t off = 0, ne = e > 0 ? (size_t)e : 1, ny = max_cross;
    char *b = (char *)base;
#define GR__PCARVE(field, type, count) \
    s->field = (type *)(void *)(b ? b + off : NULL); off = gr__align8(off + sizeof(type) * (count));
    GR__PCARVE(edge, gr__pedge_t, ne)
    GR__PCARVE(ys, double, ny)
    GR__PCARVE(cross, gr__pcross_t, ne)
    GR__PCARVE(ia, gr__pcross_t, ne)
    GR__PCARVE(ib, gr__pcross_t, ne)
    GR__PCARVE(active, int, ne)
    GR__PCARVE(run, int, 6 * ne + 6)
    GR__PCARVE(parity, unsigned char, ne)
#undef GR__PCARVE
    return off;
}

GR_DEF size_t gr_poly_boolean_scratch_bytes(int total_points)
{
    gr__pscratch_t s;
    return total_points < 0 ? 0 : gr__pscratch_layout(total_points, gr__pcross_cap(total_points), NULL, &s);
}

/* Ring sizes of a set: the r-th ring's size, or -1 when they do not add up. */
static int gr__pset_rings(const gr_polyset_t *p)
{
    if (p->ring_sizes) return p->ring_count;
    return p->ring_count > 1 ? p->ring_count : 1;
}
static int gr__pset_size(const gr_polyset_t *p, int r)
{
    if (p->ring_sizes) return p->ring_sizes[r];
    return p->ring_count > 1 ? p->point_count / p->ring_count : p->point_count;
}

static gr_result_t gr__pset_check(const gr_polyset_t *p)
{
    int r, sum = 0, nr;
    if (p->point_count < 0 || p->ring_count < 0 || (p->point_count > 0 && !p->points)) return GR_ERR_INVALID_ARG;
    nr = gr__pset_rings(p);
    if (!p->ring_sizes && nr > 1 && p->point_count % nr != 0) return GR_ERR_INVALID_ARG;
    for (r = 0; r < nr; r++) {
        if (gr__pset_size(p, r) < 0) return GR_ERR_INVALID_ARG;
        sum += gr__pset_size(p, r);
    }
    if (sum != p->point_count) return GR_ERR_INVALID_ARG;
    return gr__finite_n(p->points, 2 * p->point_count) ? GR_OK : GR_ERR_NOT_FINITE;
}

/* Non-horizontal edges of a set into e[], returns the new edge count. Rings
   with fewer than 3 points enclose nothing and are skipped; the others are
   numbered from *ring on (so ring ids stay below points / 3). */
static int gr__pset_edges(const gr_polyset_t *p, int set, int *ring, gr__pedge_t *e, int ne)
{
    int r, i, first = 0, nr = gr__pset_rings(p);
    for (r = 0; r < nr; r++) {
        int n = gr__pset_size(p, r), id = *ring;
        if (n >= 3) (*ring)++;
        for (i = 0; n >= 3 && i < n; i++) {
            const double *u = p->points + 2 * (first + i), *v = p->points + 2 * (first + (i + 1) % n);
            gr__pedge_t *d;
            if (u[1] == v[1]) continue; /* horizontal: never crosses a slab's mid line */
            d = &e[ne++];
            if (u[1] < v[1]) { d->x0 = u[0]; d->y0 = u[1]; d->x1 = v[0]; d->y1 = v[1]; }
            else { d->x0 = v[0]; d->y0 = v[1]; d->x1 = u[0]; d->y1 = u[1]; }
            d->set = set;
            d->ring = id;
            d->id = ne - 1;
        }
        first += n;
    }
    return ne;
}

/* Heights where two edges cross properly (strictly inside both): the slab
   boundaries besides the vertex heights. The edges come sorted by their
   lower end, so the partners of edge i that share some height with it are
   the run after it that starts below its top. */
static int gr__pedge_crossings(const gr__pedge_t *e, int ne, double *ys, int ny, size_t cap)
{
    int i, j;
    for (i = 0; i < ne; i++)
        for (j = i + 1; j < ne && e[j].y0 < e[i].y1; j++) {
            const gr__pedge_t *p = &e[i], *q = &e[j];
            double lo = q->y0, hi = p->y1 < q->y1 ? p->y1 : q->y1;
            double a0, a1, b0, b1, d0, d1;
            if (!(hi > lo)) continue;
            /* signed horizontal gap at both ends of the shared height range */
            a0 = gr__pedge_x(p, lo); a1 = gr__pedge_x(p, hi);
            b0 = gr__pedge_x(q, lo); b1 = gr__pedge_x(q, hi);
            d0 = a0 - b0;
            d1 = a1 - b1;
            if ((d0 < 0 && d1 > 0) || (d0 > 0 && d1 < 0)) {
                double y = lo + (hi - lo) * (d0 / (d0 - d1));
                if (!(y > lo && y < hi)) continue;
                if ((size_t)ny >= cap) return -1;
                ys[ny++] = y;
            }
        }
    return ny;
}

/* The union of one set's rings along a slab's mid line: sorted crossings
   in, intervals out as (left, right) pairs of crossings. Each ring keeps
   its even-odd parity; the set is inside while any ring is. */
static int gr__pset_intervals(const gr__pcross_t *cr, int nc, const gr__pedge_t *e, int set,
                              unsigned char *parity, gr__pcross_t *iv)
{
    int k, inside = 0, n = 0;
    for (k = 0; k < nc; k++) {
        const gr__pedge_t *d = &e[cr[k].edge];
        if (d->set != set) continue;
        parity[d->ring] ^= 1u;
        if (parity[d->ring]) {
            if (inside++ == 0) iv[n++] = cr[k];
        } else if (--inside == 0) {
            iv[n++] = cr[k];
        }
    }
    GR_ASSERT(inside == 0);
    return n;
}

static int gr__pop_in(gr_poly_op_t op, int in_a, int in_b)
{
    switch (op) {
    case GR_POLY_INTERSECTION: return in_a && in_b;
    case GR_POLY_DIFFERENCE: return in_a && !in_b;
    case GR_POLY_UNION: return in_a || in_b;
    default: return in_a != in_b;
    }
}

/* gr_poly_boolean() on valid sets, with room for max_cross crossing
   heights in its scratch (GR_ERR_BUFFER_TOO_SMALL when more): the polygon
   path's sets have a few, and its scratch need not hold every pair. */
/* gr__poly_boolean's sweep between slabs. */
typedef struct gr__sweep_t {
    gr__pscratch_t s;
    int ne, nx;          /* edges (sorted by their lower end), crossing heights (sorted) */
    int next, nact, ci;  /* the next edge to join, the active edges (s.active), the next crossing height */
    int *prev, *now_run; /* (left edge, right edge, id) of the trapezoids that end at run_top, and of this slab's */
    int nprev;
    double run_top, total; /* the area so far */
    double *traps;
    int trap_cap, ntrap, over; /* over: a trapezoid past trap_cap */
} gr__sweep_t;

/* The slab above y0: the edges ending at y0 leave the active list, those
   starting there join, and its top is the lowest of the next edge's lower
   end, the active edges' upper ends and the next crossing height
   (HUGE_VAL: above every edge). So an edge joins the active list once and
   leaves it for good, and each slab visits only the edges that span it,
   with no sort of all the heights. */
static double gr__sweep_slab_top(gr__sweep_t *W, double y0)
{
    gr__pscratch_t *s = &W->s;
    double y1 = HUGE_VAL;
    int m, kept;
    for (m = 0, kept = 0; m < W->nact; m++)
        if (s->edge[s->active[m]].y1 > y0) {
            s->active[kept++] = s->active[m];
            if (s->edge[s->active[m]].y1 < y1) y1 = s->edge[s->active[m]].y1;
        }
    W->nact = kept;
    for (; W->next < W->ne && s->edge[W->next].y0 <= y0; W->next++)
        if (s->edge[W->next].y1 > y0) {
            s->active[W->nact++] = W->next;
            if (s->edge[W->next].y1 < y1) y1 = s->edge[W->next].y1;
        }
    if (W->next < W->ne && s->edge[W->next].y0 < y1) y1 = s->edge[W->next].y0;
    while (W->ci < W->nx && s->ys[W->ci] <= y0) W->ci++;
    if (W->ci < W->nx && s->ys[W->ci] < y1) y1 = s->ys[W->ci];
    return y1;
}

/* Trapezoid [left.x, x] x [y0, y1] between edges left.edge and edge: its
   area (its mid-line width times the slab height is exact: the sides are
   straight in the slab), and its corners, or the top of the trapezoid
   below that it goes on (same two edges, ending at y0). */
static void gr__sweep_trapezoid(gr__sweep_t *W, const gr__pcross_t *left, double x, int edge, double y0, double y1, int *nnow)
{
    const gr__pedge_t *el = &W->s.edge[left->edge], *er = &W->s.edge[edge];
    int p, id = -1;
    W->total += (x - left->x) * (y1 - y0);
    if (W->run_top == y0)
        for (p = 0; p < W->nprev && id < 0; p++)
            if (W->prev[3 * p] == left->edge && W->prev[3 * p + 1] == edge) id = W->prev[3 * p + 2];
    if (id >= 0) { /* the trapezoid below goes on */
        if (W->traps && id < W->trap_cap) {
            double *t = W->traps + 8 * id;
            t[4] = gr__pedge_x(er, y1); t[5] = y1;
            t[6] = gr__pedge_x(el, y1); t[7] = y1;
        }
    } else {
        id = W->ntrap++;
        if (W->traps && id < W->trap_cap) {
            double *t = W->traps + 8 * id;
            t[0] = gr__pedge_x(el, y0); t[1] = y0;
            t[2] = gr__pedge_x(er, y0); t[3] = y0;
            t[4] = gr__pedge_x(er, y1); t[5] = y1;
            t[6] = gr__pedge_x(el, y1); t[7] = y1;
        } else if (W->traps) W->over = 1;
    }
    W->now_run[3 * *nnow] = left->edge;
    W->now_run[3 * *nnow + 1] = edge;
    W->now_run[3 * *nnow + 2] = id;
    (*nnow)++;
}

/* The slab [y0, y1] (mid line ym) of a op b: the active edges' crossings
   with the mid line, in x order, as the two polygons' inside intervals,
   merged into trapezoids. */
static void gr__sweep_slab(gr__sweep_t *W, gr_poly_op_t op, double y0, double y1, double ym)
{
    gr__pscratch_t *s = &W->s;
    gr__pcross_t left;
    int nc = 0, na, nb, i = 0, j = 0, in_a = 0, in_b = 0, was = 0, m, nnow = 0, *sw;
    left.x = 0;
    left.edge = -1;
    for (m = 0; m < W->nact; m++) {
        int e = s->active[m];
        s->cross[nc].x = gr__pedge_x(&s->edge[e], ym);
        s->cross[nc++].edge = e;
    }
    /* the active list is kept in the last slab's x order, so the crossings
       come nearly sorted (only new edges and the swaps at crossing heights
       move): insertion sort, linear in practice */
    gr__sort_pcross_nearly(s->cross, nc);
    for (m = 0; m < nc; m++) s->active[m] = s->cross[m].edge;
    na = gr__pset_intervals(s->cross, nc, s->edge, 0, s->parity, s->ia);
    nb = gr__pset_intervals(s->cross, nc, s->edge, 1, s->parity, s->ib);
    /* merge the two interval lists; all boundaries at one x are applied
       together, so coincident edges (a polygon against itself) give no
       sliver */
    while (i < na || j < nb) {
        double x = i < na && (j >= nb || s->ia[i].x <= s->ib[j].x) ? s->ia[i].x : s->ib[j].x;
        int edge = -1, now;
        while (i < na && s->ia[i].x == x) { in_a = !(i & 1); edge = s->ia[i].edge; i++; }
        while (j < nb && s->ib[j].x == x) { in_b = !(j & 1); edge = s->ib[j].edge; j++; }
        now = gr__pop_in(op, in_a, in_b);
        if (now && !was) { left.x = x; left.edge = edge; }
        else if (!now && was && x > left.x) gr__sweep_trapezoid(W, &left, x, edge, y0, y1, &nnow);
        was = now;
    }
    sw = W->prev; W->prev = W->now_run; W->now_run = sw;
    W->nprev = nnow;
    W->run_top = y1;
}

static gr_result_t gr__poly_boolean(const gr_polyset_t *a, const gr_polyset_t *b, gr_poly_op_t op, void *scratch,
                                    size_t max_cross, double *traps, int trap_cap, int *trap_count, double *area)
{
    gr__sweep_t W;
    gr__pscratch_t *s = &W.s;
    double y0;
    int rings = 0;
    if (area) *area = 0;
    if (trap_count) *trap_count = 0;
    memset(&W, 0, sizeof W);
    W.traps = traps;
    W.trap_cap = trap_cap;
    gr__pscratch_layout(a->point_count + b->point_count, max_cross, scratch, s);
    W.prev = s->run;
    W.now_run = s->run + 3 * (a->point_count + b->point_count + 1);
    W.ne = gr__pset_edges(a, 0, &rings, s->edge, 0);
    W.ne = gr__pset_edges(b, 1, &rings, s->edge, W.ne);
    memset(s->parity, 0, (size_t)rings);
    /* slab boundaries: every vertex height and every edge crossing; the
       sweep rises from event to event (gr__sweep_slab_top) */
    gr__sort_pedges_by_y0(s->edge, W.ne);
    W.nx = gr__pedge_crossings(s->edge, W.ne, s->ys, 0, max_cross);
    if (W.nx < 0) return GR_ERR_BUFFER_TOO_SMALL;
    gr__sort_doubles(s->ys, W.nx);
    /* a trapezoid whose two edges go on into the next slab is extended
       there instead of starting another (its sides are those edges, so
       the union is exact): regions do not fragment at every height */
    y0 = W.ne > 0 ? s->edge[0].y0 : 0;
    while (W.ne > 0) {
        double y1 = gr__sweep_slab_top(&W, y0), ym;
        if (y1 == HUGE_VAL) break; /* above every edge */
        ym = 0.5 * (y0 + y1);
        /* two adjacent doubles: the mid line would fall on a vertex height,
           where the strict crossing test loses a pass-through vertex */
        if ((y0 < ym && ym < y1) && W.nact > 0) gr__sweep_slab(&W, op, y0, y1, ym);
        y0 = y1;
    }
    if (area) *area = W.total;
    if (trap_count) *trap_count = W.ntrap;
    return W.over ? GR_ERR_BUFFER_TOO_SMALL : GR_OK;
}

GR_DEF gr_result_t gr_poly_boolean(const gr_polyset_t *a, const gr_polyset_t *b, gr_poly_op_t op,
                                   void *scratch, size_t scratch_bytes,
                                   double *traps, int trap_cap, int *trap_count, double *area)
{
    gr_result_t r;
    if (area) *area = 0;
    if (trap_count) *trap_count = 0;
    if (!a || !b || !scratch || (traps && trap_cap < 0) || (int)op < 0 || (int)op > 3) return GR_ERR_INVALID_ARG;
    if ((r = gr__pset_check(a)) != GR_OK || (r = gr__pset_check(b)) != GR_OK) return r;
    if (scratch_bytes < gr_poly_boolean_scratch_bytes(a->point_count + b->point_count)) return GR_ERR_BUFFER_TOO_SMALL;
    return gr__poly_boolean(a, b, op, scratch, gr__pcross_cap(a->point_count + b->point_count), traps, trap_cap,
                            trap_count, area);
}

/* ---- Intersections and ends: detection (§5, §5.1) ------------------------ */

/* Chords per Bézier piece when looking for self-intersections: the chord
   polygon is within (1/32)^2 / 8 of the piece's control-polygon size. */
#define GR__SELF_FLATTEN 32


/* Where segments ab and cd cross: 1 with s on ab and u on cd, each in
   [0, 1) (half-open, so a crossing at a shared vertex counts once), 0 when
   they miss or overlap collinearly. Orientation signs decide, so the
   answer does not depend on a tolerance. */
static int gr__seg_cross(const double *a, const double *b, const double *c, const double *d, double *s, double *u)
{
    double d1 = gr__cross2(a, b, c), d2 = gr__cross2(a, b, d), d3 = gr__cross2(c, d, a), d4 = gr__cross2(c, d, b);
    if ((d1 > 0 && d2 > 0) || (d1 < 0 && d2 < 0) || (d3 > 0 && d4 > 0) || (d3 < 0 && d4 < 0)) return 0;
    if ((d1 == 0 && d2 == 0) || d3 == d4) return 0;
    *s = d3 / (d3 - d4);
    *u = d1 / (d1 - d2);
    return *s < 1 && *u < 1;
}

/* A crossing of chords kk (a b, parameters ta) and ll (c d, tc), kk < ll,
   of one path with m chords, appended to out (up to cap); 1 if there is one. */
static int gr__chord_pair_hit(const double *a, const double *b, const double *ta, const double *c, const double *d,
                              const double *tc, int kk, int ll, int m, int closed, int g, gr_self_hit_t *out, int cap,
                              int nh)
{
    double sv, u;
    if (ll == kk + 1) return 0;                     /* neighbours share a point */
    if (closed && kk == 0 && ll == m - 1) return 0; /* neighbours across the closing point */
    if ((c[0] < a[0] && c[0] < b[0] && d[0] < a[0] && d[0] < b[0]) ||
        (c[0] > a[0] && c[0] > b[0] && d[0] > a[0] && d[0] > b[0]) ||
        (c[1] < a[1] && c[1] < b[1] && d[1] < a[1] && d[1] < b[1]) ||
        (c[1] > a[1] && c[1] > b[1] && d[1] > a[1] && d[1] > b[1]))
        return 0; /* boxes apart */
    if (!gr__seg_cross(a, b, c, d, &sv, &u)) return 0;
    if (out && nh < cap) {
        out[nh].groove = g;
        out[nh].point[0] = a[0] + sv * (b[0] - a[0]);
        out[nh].point[1] = a[1] + sv * (b[1] - a[1]);
        out[nh].param[0] = ta[0] + sv * (ta[1] - ta[0]);
        out[nh].param[1] = tc[0] + u * (tc[1] - tc[0]);
    }
    return 1;
}

/* Every crossing of two non-adjacent chords of one path (§5: found before
   rendering): polyline segments exactly, Bézier pieces through
   GR__SELF_FLATTEN chords each (two pieces whose control points' boxes
   are apart cannot cross; each piece's chord ends are evaluated once per
   pair of pieces). Writes up to cap hits (out may be NULL), returns how
   many there are. */
static int gr__path_self_hits(const double *pts, int kind, int n, int closed, int g, gr_self_hit_t *out, int cap)
{
    int pieces = gr__pieces(kind, n), k, l, nh = 0;
    if (kind == GR_PATH_POLYLINE) {
        double len = 0, acc_k = 0;
        for (k = 0; k < pieces; k++) len += hypot(pts[2 * k + 2] - pts[2 * k], pts[2 * k + 3] - pts[2 * k + 1]);
        for (k = 0; k < pieces; k++) {
            const double *a = pts + 2 * k, *b = a + 2;
            double lk = hypot(b[0] - a[0], b[1] - a[1]), acc_l = acc_k + lk, ta[2];
            ta[0] = acc_k / len;
            ta[1] = (acc_k + lk) / len;
            for (l = k + 1; l < pieces; l++) {
                const double *c = pts + 2 * l, *d = c + 2;
                double ll = hypot(d[0] - c[0], d[1] - c[1]), tc[2];
                tc[0] = acc_l / len;
                tc[1] = (acc_l + ll) / len;
                acc_l += ll;
                nh += gr__chord_pair_hit(a, b, ta, c, d, tc, k, l, pieces, closed, g, out, cap, nh);
            }
            acc_k += lk;
        }
        return nh;
    }
#ifndef GR_NO_CURVES
    {
        int deg = gr__degree(kind), m = pieces * GR__SELF_FLATTEN, P, Q, i;
        double pa[2 * (GR__SELF_FLATTEN + 1)], pb[2 * (GR__SELF_FLATTEN + 1)], d1[2], d2[2];
        for (P = 0; P < pieces; P++) {
            double ba[4];
            gr__bounds(pts + 2 * deg * P, deg + 1, ba);
            for (i = 0; i <= GR__SELF_FLATTEN; i++)
                gr__bezier_eval(pts + 2 * deg * P, deg, (double)i / GR__SELF_FLATTEN, pa + 2 * i, d1, d2);
            for (Q = P; Q < pieces; Q++) {
                double bb[4];
                const double *qb = pa;
                gr__bounds(pts + 2 * deg * Q, deg + 1, bb);
                if (Q > P && (bb[0] > ba[2] || bb[2] < ba[0] || bb[1] > ba[3] || bb[3] < ba[1])) continue;
                if (Q > P) {
                    for (i = 0; i <= GR__SELF_FLATTEN; i++)
                        gr__bezier_eval(pts + 2 * deg * Q, deg, (double)i / GR__SELF_FLATTEN, pb + 2 * i, d1, d2);
                    qb = pb;
                }
                for (k = 0; k < GR__SELF_FLATTEN; k++)
                    for (l = Q > P ? 0 : k + 1; l < GR__SELF_FLATTEN; l++) {
                        double ta[2], tc[2];
                        ta[0] = (P + (double)k / GR__SELF_FLATTEN) / pieces;
                        ta[1] = (P + (double)(k + 1) / GR__SELF_FLATTEN) / pieces;
                        tc[0] = (Q + (double)l / GR__SELF_FLATTEN) / pieces;
                        tc[1] = (Q + (double)(l + 1) / GR__SELF_FLATTEN) / pieces;
                        nh += gr__chord_pair_hit(pa + 2 * k, pa + 2 * k + 2, ta, qb + 2 * l, qb + 2 * l + 2, tc,
                                                 P * GR__SELF_FLATTEN + k, Q * GR__SELF_FLATTEN + l, m, closed, g, out,
                                                 cap, nh);
                    }
            }
        }
    }
#else
    (void)l;
#endif
    return nh;
}

static int gr__cmp_hit_t2(const void *pa, const void *pb)
{
    double a = ((const gr_self_hit_t *)pa)->param[1], b = ((const gr_self_hit_t *)pb)->param[1];
    return (a > b) - (a < b);
}
static int gr__cmp_rec_t0(const void *pa, const void *pb)
{
    double a = ((const gr__groove_t *)pa)->t0, b = ((const gr__groove_t *)pb)->t0;
    return (a > b) - (a < b);
}

/* Point of a polyline at arc-length parameter t (t in [0, 1], len its length). */
static void gr__polyline_at(const double *pts, int n, double len, double t, double q[2])
{
    double want = t * len, acc = 0;
    int k;
    for (k = 0; k + 1 < n; k++) {
        double l = hypot(pts[2 * k + 2] - pts[2 * k], pts[2 * k + 3] - pts[2 * k + 1]);
        if (acc + l >= want || k + 2 == n) {
            double s = l > 0 ? (want - acc) / l : 0;
            s = s < 0 ? 0 : s > 1 ? 1 : s;
            q[0] = pts[2 * k] + s * (pts[2 * k + 2] - pts[2 * k]);
            q[1] = pts[2 * k + 1] + s * (pts[2 * k + 3] - pts[2 * k + 1]);
            return;
        }
        acc += l;
    }
    q[0] = pts[0];
    q[1] = pts[1];
}

/* The cuts of groove par (gr__split_groove: greedy interval stabbing over
   its nh hits, sorted here by their second parameter), in piece units for
   a chain (joints are integers), into rec[].t0 ascending, each once and
   strictly inside; returns how many. */
static int gr__self_cuts(const gr__groove_t *par, gr_self_hit_t *hits, int nh, gr__groove_t *rec)
{
    int k, i, nb = 0, n = par->pieces, bez = par->kind != GR_PATH_POLYLINE;
    double lo = 0, hi = -1;
    gr__sort(hits, (size_t)nh, sizeof *hits, gr__cmp_hit_t2);
    for (k = 0; k <= nh; k++) {
        if (k < nh && hi > lo && hits[k].param[0] < hi) { /* overlaps the group: narrow it */
            if (hits[k].param[0] > lo) lo = hits[k].param[0];
            continue;
        }
        if (hi > lo) { /* the group's cut */
            double mid = 0.5 * (lo + hi);
            if (!bez) rec[nb++].t0 = mid;
            else {
                double u = mid * n, j = floor(u + 0.5);
                if (j > lo * n && j < hi * n && j > 0 && j < n) rec[nb++].t0 = j;
                else {
                    rec[nb++].t0 = u;
                    if (floor(u) > 0) rec[nb++].t0 = floor(u);
                    if (floor(u) + 1 < n) rec[nb++].t0 = floor(u) + 1;
                }
            }
        }
        if (k < nh) { lo = hits[k].param[0]; hi = hits[k].param[1]; }
    }
    gr__sort(rec, (size_t)nb, sizeof *rec, gr__cmp_rec_t0);
    for (i = 0, k = 0; k < nb; k++) /* unique, strictly inside */
        if (rec[k].t0 > 0 && rec[k].t0 < (bez ? n : 1) && (i == 0 || rec[k].t0 > rec[i - 1].t0)) rec[i++].t0 = rec[k].t0;
    return i;
}

/* The points of groove par between parameters ua and ub (its own units:
   arc length in [0, 1] for a polyline, piece units for a chain) into q;
   returns how many. */
static int gr__piece_points(const gr__groove_t *par, const double *pts, double ua, double ub, double *q)
{
    int k, np = 0;
    if (par->kind == GR_PATH_POLYLINE) {
        double acc = 0;
        gr__polyline_at(pts, par->point_count, par->length, ua, q);
        np = 1;
        for (k = 1; k + 1 < par->point_count; k++) { /* the vertices strictly inside */
            double t;
            acc += hypot(pts[2 * k] - pts[2 * k - 2], pts[2 * k + 1] - pts[2 * k - 1]);
            t = acc / par->length;
            if (t > ua && t < ub) { q[2 * np] = pts[2 * k]; q[2 * np + 1] = pts[2 * k + 1]; np++; }
        }
        gr__polyline_at(pts, par->point_count, par->length, ub, q + 2 * np);
        return np + 1;
    }
#ifndef GR_NO_CURVES
    {
        int deg = gr__degree(par->kind), j = (int)floor(ua);
        if (ua == floor(ua) && ub == floor(ub)) { /* whole pieces */
            np = deg * (int)(ub - ua) + 1;
            memcpy(q, pts + 2 * deg * (int)ua, sizeof(double) * 2 * (size_t)np);
            return np;
        }
        /* part of one piece */
        GR_ASSERT(ub <= j + 1);
        gr__bezier_sub(pts + 2 * deg * j, deg, ua - j, ub - j, q);
        return deg + 1;
    }
#else
    return np;
#endif
}

/* §5: "the groove should be simply treated as two independent grooves".
   The hits of groove g (sorted here by their second parameter) are
   intervals (t1, t2) of its path parameter; a cut inside each separates
   the two passes of its crossing. Greedy interval stabbing gives the
   fewest cuts, each in the middle of the parameters it serves (far from
   the crossings, where the pieces meet end to end). A Bézier chain is cut
   at a joint where one serves, or else inside a piece and also at that
   piece's two joints, so every piece is whole Bézier pieces or part of
   one: its uniform parameter maps affinely onto the groove's. The pieces
   go to records *next, ... with their own points from *pt on. */
static void gr__split_groove(gr_grid_t *gr, int g, gr_self_hit_t *hits, int nh, int *next, int *pt)
{
    gr__groove_t *par = &gr->grooves_[g], *rec = gr->grooves_ + *next;
    const double *pts = gr->points_ + 2 * par->first_point;
    int k, i, n = par->pieces, bez = par->kind != GR_PATH_POLYLINE, nb = gr__self_cuts(par, hits, nh, rec);
    par->first_split = *next;
    par->split_count = nb + 1;
    /* piece i covers [b_(i-1), b_i]: made from the last down, so each reads
       its upper bound (its own t0 slot) before writing over it */
    for (i = nb; i >= 0; i--) {
        double ua = i > 0 ? rec[i - 1].t0 : 0, ub = i < nb ? rec[i].t0 : (bez ? n : 1);
        gr__groove_t *r = &rec[i];
        double *q = gr->points_ + 2 * *pt;
        int np = gr__piece_points(par, pts, ua, ub, q);
        *r = *par;
        r->first_point = *pt;
        r->point_count = np;
        r->pieces = gr__pieces(r->kind, np);
        r->closed = 0;
        r->parent = g;
        r->first_split = r->split_count = 0;
        r->t0 = bez ? ua / n : ua;
        r->t1 = bez ? ub / n : ub;
        /* an end of a piece is the groove's own only at t = 0 or 1 of an open path */
        r->join[0] = ua > 0 || par->closed;
        r->join[1] = ub < (bez ? n : 1) || par->closed;
        gr__bounds(q, np, r->bbox);
        r->length = 0;
        if (!bez)
            for (k = 0; k + 1 < np; k++) r->length += hypot(q[2 * k + 2] - q[2 * k], q[2 * k + 3] - q[2 * k + 1]);
        *pt += np;
    }
    *next += nb + 1;
}

/* The hits were found by the builder (gr__path_self_hits), each groove's
   sorted by its second parameter. */
GR_DEF gr_result_t gr_self_intersections(const gr_grid_t *grid, gr_self_hit_t *out, int cap, int *count)
{
    if (count) *count = 0;
    if (!grid || !count || cap < 0 || (!out && cap > 0)) return GR_ERR_INVALID_ARG;
    *count = grid->self_count_;
    if (cap > 0) memcpy(out, grid->self_, sizeof *out * (size_t)(grid->self_count_ < cap ? grid->self_count_ : cap));
    return grid->self_count_ > cap ? GR_ERR_BUFFER_TOO_SMALL : GR_OK;
}

/* The search box (§4.1, §5.1) about the footprint centre f: the
   footprint's box grown by w; by h tan θ_r toward the viewer (peaks seen
   beyond the groove, eq. 1); by w'_E = d tan θ_r away from the viewer
   (deep facets seen through a crossing, Figure 8a); by w_L = (h + d) tan θ_i
   toward each light above the horizon (peaks and cut blocking facets,
   Figure 8b). Each shift is along the direction's UV projection. */
static void gr__search_box(const gr_grid_t *grid, const gr_footprint_t *fp, const double f[2], const double *lights,
                           int nl, double box[4])
{
    double ext_u, ext_v;
    int k;
    gr__footprint_box(grid, fp, f, &ext_u, &ext_v, box);
    for (k = -2; k < nl; k++) {
        const double *dir = k < 0 ? fp->view : lights + 3 * k;
        double len = k == -2 ? grid->h : k == -1 ? -grid->d : grid->h + grid->d, su, sv;
        if (!(dir[2] > 0) || len == 0) continue;
        su = len * dir[0] / dir[2];
        sv = len * dir[1] / dir[2];
        if (su < 0) box[0] += su; else box[2] += su;
        if (sv < 0) box[1] += sv; else box[3] += sv;
    }
}

static void gr__junction_add(gr_junctions_t *out, gr_junction_kind_t kind, int g, int other, int end, int other_end,
                             const double p[2])
{
    gr_junction_t *j;
    if (out->count >= GR_MAX_JUNCTIONS) { out->dropped++; return; }
    j = &out->items[out->count++];
    j->kind = kind;
    j->groove = g;
    j->other = other;
    j->end = end;
    j->other_end = other_end;
    j->point[0] = p[0];
    j->point[1] = p[1];
}

/* Does segment ab meet the box? (Liang-Barsky: the parameter range left
   after the four slabs is not empty.) */
static int gr__seg_box(const double *a, const double *b, const double *box)
{
    double t0 = 0, t1 = 1, d[2];
    int k;
    d[0] = b[0] - a[0];
    d[1] = b[1] - a[1];
    for (k = 0; k < 2; k++) {
        double lo = box[k] - a[k], hi = box[k + 2] - a[k];
        if (d[k] == 0) {
            if (lo > 0 || hi < 0) return 0;
            continue;
        }
        lo /= d[k];
        hi /= d[k];
        if (lo > hi) { double t = lo; lo = hi; hi = t; }
        if (lo > t0) t0 = lo;
        if (hi < t1) t1 = hi;
        if (t0 > t1) return 0;
    }
    return 1;
}

/* Does a groove's path (its chords; curves flattened as for
   self-intersections) enter the box, in any periodic image? */
static int gr__path_in_box(const gr_grid_t *grid, const gr__groove_t *rec, const double *box)
{
    double wu = grid->domain[2] - grid->domain[0], wv = grid->domain[3] - grid->domain[1];
    int k, i;
    for (i = 0; i < 9; i++) {
        double sb[4], du = (i % 3 - 1) * wu, dv = (i / 3 - 1) * wv;
        if (!grid->wrap && i != 4) continue;
        sb[0] = box[0] - du; sb[2] = box[2] - du;
        sb[1] = box[1] - dv; sb[3] = box[3] - dv;
        if (sb[0] > rec->bbox[2] + rec->half_width || sb[2] < rec->bbox[0] - rec->half_width ||
            sb[1] > rec->bbox[3] + rec->half_width || sb[3] < rec->bbox[1] - rec->half_width)
            continue; /* control points bound the path */
        if (rec->kind == GR_PATH_POLYLINE) {
            const double *pts = grid->points_ + 2 * rec->first_point;
            for (k = 0; k < rec->pieces; k++)
                if (gr__seg_box(pts + 2 * k, pts + 2 * k + 2, sb)) return 1;
            continue;
        }
#ifndef GR_NO_CURVES
        { /* a Bézier piece whose control points lie off the box is skipped
             (they bound it); each chord end is evaluated once */
            int deg = gr__degree(rec->kind), piece, c;
            const double *pts = grid->points_ + 2 * rec->first_point;
            for (piece = 0; piece < rec->pieces; piece++) {
                const double *q = pts + 2 * deg * piece;
                double cb[4], a[2], b[2], d1[2], d2[2];
                gr__bounds(q, deg + 1, cb);
                if (cb[0] > sb[2] || cb[2] < sb[0] || cb[1] > sb[3] || cb[3] < sb[1]) continue;
                a[0] = q[0]; a[1] = q[1];
                for (c = 1; c <= GR__SELF_FLATTEN; c++) {
                    gr__bezier_eval(q, deg, (double)c / GR__SELF_FLATTEN, b, d1, d2);
                    if (gr__seg_box(a, b, sb)) return 1;
                    a[0] = b[0]; a[1] = b[1];
                }
            }
        }
#endif
    }
    return 0;
}

/* Is the pair (g, h) already joined by an end junction? Then it is not
   also a crossing (§5: the end is the intersection). */
static int gr__pair_joined(const gr_junctions_t *out, int g, int h)
{
    int k;
    for (k = 0; k < out->count; k++) {
        const gr_junction_t *j = &out->items[k];
        if (j->kind != GR_JUNCTION_INTERSECTED_END && j->kind != GR_JUNCTION_CORNER) continue;
        if ((j->groove == g && j->other == h) || (j->groove == h && j->other == g)) return 1;
    }
    return 0;
}

static int gr__in_box(const double *box, const double *p)
{
    return p[0] >= box[0] && p[0] <= box[2] && p[1] >= box[1] && p[1] <= box[3];
}

/* The periodic image of p nearest to f (p itself without wrap). */
static void gr__image_near(const gr_grid_t *grid, const double *p, const double *f, double q[2])
{
    q[0] = p[0];
    q[1] = p[1];
    if (grid->wrap) {
        double wu = grid->domain[2] - grid->domain[0], wv = grid->domain[3] - grid->domain[1];
        q[0] += wu * floor((f[0] - p[0]) / wu + 0.5);
        q[1] += wv * floor((f[1] - p[1]) / wv + 0.5);
    }
}

/* §5 ends: each open path end of a counted groove inside the box becomes a
   corner, an intersected end or an isolated end (the distance test).
   state (2 per counted groove: 0 outside, 1 inside, 2 already in a
   corner) is scratch. */
static void gr__end_point(const gr_grid_t *grid, int g, int e, const double *f, double p[2])
{
    const gr__groove_t *rec = &grid->grooves_[g];
    gr__image_near(grid, grid->points_ + 2 * (rec->first_point + (e ? rec->point_count - 1 : 0)), f, p);
}

static void gr__detect_ends(const gr_grid_t *grid, const gr__cand_t *cand, int n, const double *box, const double *f,
                            double *state, gr_junctions_t *out)
{
    int i, e, k, e2;
    for (i = 0; i < n; i++) {
        double p[2][2];
        /* closed covers a path whose ends meet across the seam of a
           repeating tile (gr__store_groove): it runs on, no end (§4.1) */
        for (e = 0; e < 2; e++) gr__end_point(grid, cand[i].groove, e, f, p[e]);
        for (e = 0; e < 2; e++) /* a piece's cut end (§5, self-crossing) runs on too */
            state[2 * i + e] = !grid->grooves_[cand[i].groove].closed && !grid->grooves_[cand[i].groove].join[e] &&
                               gr__in_box(box, p[e]);
    }
    for (i = 0; i < n; i++)
        for (e = 0; e < 2; e++) {
            double p[2], wi = grid->grooves_[cand[i].groove].half_width, best = HUGE_VAL;
            int other = -1;
            if (state[2 * i + e] != 1) continue;
            gr__end_point(grid, cand[i].groove, e, f, p);
            /* corners first: two ends closer than the sum of their widths */
            for (k = i + 1; k < n && other < 0; k++)
                for (e2 = 0; e2 < 2 && other < 0; e2++) {
                    double q[2], lim = wi + grid->grooves_[cand[k].groove].half_width;
                    gr__end_point(grid, cand[k].groove, e2, f, q);
                    if (state[2 * k + e2] == 1 && hypot(p[0] - q[0], p[1] - q[1]) < lim) {
                        gr__junction_add(out, GR_JUNCTION_CORNER, cand[i].groove, cand[k].groove, e, e2, p);
                        state[2 * i + e] = state[2 * k + e2] = 2;
                        other = k;
                    }
                }
            if (other >= 0) continue;
            /* the distance from the end to every other path (cf. eq. 2):
               below the sum of the widths it is an intersected end */
            for (k = 0; k < n; k++) {
                gr__cand_t c;
                double lim = wi + grid->grooves_[cand[k].groove].half_width;
                if (k == i || !gr__locate(grid, cand[k].groove, p, lim, &c) || !(c.dist < best)) continue;
                best = c.dist;
                other = k;
            }
            if (other >= 0)
                gr__junction_add(out, GR_JUNCTION_INTERSECTED_END, cand[i].groove, cand[other].groove, e, -1, p);
            else
                gr__junction_add(out, GR_JUNCTION_ISOLATED_END, cand[i].groove, -1, e, -1, p);
        }
}

/* The footprint centre's image in the tile (as gr_query()), where
   gr_detect() and the polygon path place the grooves' nearest points. */
/* The point nearest f of the overlap of two strips, |B_a.(x - pa)| <= wa
   and |B_b.(x - pb)| <= wb about crossing lines (cr = T_a x T_b != 0):
   the rhombus with corners p ± (wb / s) T_a ± (wa / s) T_b, p the lines'
   meeting point, s = |cr|. f itself when it lies inside. */
static void gr__overlap_nearest(const double *pa, const double *ta, double wa, const double *pb, const double *tb,
                                double wb, double cr, const double *f, double q[2])
{
    double s = fabs(cr), m = ((pb[0] - pa[0]) * tb[1] - (pb[1] - pa[1]) * tb[0]) / cr, c[8], best = HUGE_VAL;
    double p[2] = {pa[0] + m * ta[0], pa[1] + m * ta[1]}, da = wb / s, db = wa / s;
    int k, inside = 1;
    for (k = 0; k < 4; k++) { /* counter-clockwise or clockwise: the side test below takes either */
        double sa = k == 0 || k == 3 ? 1 : -1, sb = k < 2 ? 1 : -1;
        c[2 * k] = p[0] + sa * da * ta[0] + sb * db * tb[0];
        c[2 * k + 1] = p[1] + sa * da * ta[1] + sb * db * tb[1];
    }
    for (k = 0; k < 4; k++) {
        const double *u = c + 2 * k, *v = c + 2 * ((k + 1) % 4);
        double ex = v[0] - u[0], ey = v[1] - u[1], l2 = ex * ex + ey * ey;
        double t = l2 > 0 ? ((f[0] - u[0]) * ex + (f[1] - u[1]) * ey) / l2 : 0, x, y, d;
        if (gr__cross2(u, v, f) * gr__cross2(u, v, c + 2 * ((k + 2) % 4)) < 0) inside = 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        x = u[0] + t * ex;
        y = u[1] + t * ey;
        d = hypot(f[0] - x, f[1] - y);
        if (d < best) { best = d; q[0] = x; q[1] = y; }
    }
    if (inside) { q[0] = f[0]; q[1] = f[1]; }
}

/* Does one of groove g's self-intersections (§5), in its image nearest
   f, lie in the box? Then the groove is taken as its pieces there. The
   builder stores the hits groove by groove, so g's run is found by
   bisection. */
static int gr__self_in_box(const gr_grid_t *grid, int g, const double *box, const double *f)
{
    int lo = 0, hi = grid->self_count_, h;
    if (grid->grooves_[g].split_count == 0) return 0;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (grid->self_[mid].groove < g) lo = mid + 1;
        else hi = mid;
    }
    for (h = lo; h < grid->self_count_ && grid->self_[h].groove == g; h++) {
        double p[2];
        gr__image_near(grid, grid->self_[h].point, f, p);
        if (gr__in_box(box, p)) return 1;
    }
    return 0;
}

/* Piece `id` of a self-crossing groove as a candidate near f: 0 when it
   does not enter the box, lies beyond reach, or its nearest point to f
   is one of its cut ends with f beyond that end (the neighbouring piece's
   approach). Its parameter and rate become the groove's. */
static int gr__piece_locate(const gr_grid_t *grid, int id, const double *box, const double *f, double reach,
                            gr__cand_t *c)
{
    const gr__groove_t *pc = &grid->grooves_[id];
    if (!gr__path_in_box(grid, pc, box) || !gr__locate(grid, id, f, reach, c)) return 0;
    if ((c->end < 0 && pc->join[0]) || (c->end > 0 && pc->join[1])) return 0;
    c->param = pc->t0 + (pc->t1 - pc->t0) * c->param;
    c->dtds *= pc->t1 - pc->t0;
    return 1;
}

/* A self-crossing groove's candidate replaced by one per piece (§5: "two
   independent grooves with different directions"), when one of its
   crossings lies in the box (gr__piece_locate drops the pieces that do
   not reach it). Returns the new count. */
static int gr__split_candidates(const gr_grid_t *grid, gr__cand_t *cand, int m, int cap, const double *box,
                                const double *f, double reach)
{
    int i, n = m, k;
    for (i = 0; i < m; i++) {
        const gr__groove_t *rec = &grid->grooves_[cand[i].groove];
        int first = n;
        if (n + rec->split_count > cap || !gr__self_in_box(grid, cand[i].groove, box, f)) continue;
        for (k = 0; k < rec->split_count; k++)
            if (gr__piece_locate(grid, rec->first_split + k, box, f, 2 * reach, &cand[n])) n++;
        if (n == first) continue; /* no piece near after all: keep the groove */
        cand[i] = cand[--n];      /* the last piece takes the groove's place */
    }
    return n;
}

/* gr_detect() with the grooves named as the polygon path needs them: a
   self-crossing groove's pieces by their records (indices from
   groove_count on). */
static gr_result_t gr__detect(const gr_grid_t *grid, const gr_query_t *query, const gr_self_hit_t *self,
                              int self_count, void *scratch, size_t scratch_bytes, gr_junctions_t *out)
{
    const gr_footprint_t *fp;
    gr__scratch_t s;
    double f[2], reach = 0, psin;
    int k, i, j, n, m = 0;
    if (!grid || !query || !scratch || !out || self_count < 0 || (self_count > 0 && !self)) return GR_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (query->light_count < 0 || query->light_count > GR_MAX_LIGHTS || (query->light_count > 0 && !query->lights))
        return GR_ERR_INVALID_ARG;
    if (scratch_bytes < gr_query_scratch_bytes(grid)) return GR_ERR_BUFFER_TOO_SMALL;
    fp = &query->footprint;
    if (!gr__finite_n(fp->center, 2) || !gr__finite_n(fp->axis1, 2) || !gr__finite_n(fp->axis2, 2) ||
        !gr__finite_n(fp->view, 3) || !gr__finite(query->parallel_tol) || !gr__finite_n(query->lights, 3 * query->light_count))
        return GR_ERR_NOT_FINITE;
    for (k = 0; k < self_count; k++)
        if (self[k].groove < 0 || self[k].groove >= grid->groove_count) return GR_ERR_INVALID_ARG;
    gr__scratch_layout(grid, scratch, &s);
    gr__tile_image(grid, fp->center, f);
    gr__search_box(grid, fp, f, query->lights, fp->view[2] > 0 ? query->light_count : 0, out->box);
    if (!(fp->view[2] > 0)) return GR_OK;
    /* a groove counts when its path enters the box (the box has its w
       margin); its nearest point to f then lies within the disc about f
       holding the box */
    for (k = 0; k < 4; k++) {
        double du = out->box[k & 1 ? 2 : 0] - f[0], dv = out->box[k & 2 ? 3 : 1] - f[1];
        if (hypot(du, dv) > reach) reach = hypot(du, dv);
    }
    n = gr__gather(grid, out->box, s.seen, s.ids, NULL);
    for (k = 0; k < n; k++)
        if (gr__path_in_box(grid, &grid->grooves_[s.ids[k]], out->box) && gr__locate(grid, s.ids[k], f, 2 * reach, &s.cand[m]))
            m++;
    if (grid->split_records_ > 0)
        m = gr__split_candidates(grid, s.cand, m, grid->groove_count + grid->split_records_, out->box, f, reach);
    out->grooves = m;
    gr__detect_ends(grid, s.cand, m, out->box, f, s.x, out); /* s.x holds >= 2 per candidate */
    /* crossings: tangents that differ by more than the parallel tolerance */
    psin = sin(fabs(query->parallel_tol == 0 ? GR__DEFAULT_PARALLEL_TOL : query->parallel_tol));
    for (i = 0; i < m; i++)
        for (j = i + 1; j < m; j++) {
            const gr__cand_t *a = &s.cand[i], *b = &s.cand[j];
            double cr = a->t[0] * b->t[1] - a->t[1] * b->t[0], pa[2], pb[2], sa, p[2], lim;
            gr__cand_t c;
            if (!(fabs(cr) > psin) || gr__pair_joined(out, a->groove, b->groove)) continue;
            /* the tangent lines at the nearest points, in the footprint's image */
            pa[0] = a->p[0] + f[0] - a->fc[0]; pa[1] = a->p[1] + f[1] - a->fc[1];
            pb[0] = b->p[0] + f[0] - b->fc[0]; pb[1] = b->p[1] + f[1] - b->fc[1];
            sa = ((pb[0] - pa[0]) * b->t[1] - (pb[1] - pa[1]) * b->t[0]) / cr;
            p[0] = pa[0] + sa * a->t[0];
            p[1] = pa[1] + sa * a->t[1];
            /* the meeting point must be near the footprint and on (within
               the widths of) both paths: a path that stops short of the
               other is an isolated end and a normal groove, simulated
               apart (§5) */
            lim = grid->grooves_[a->groove].half_width + grid->grooves_[b->groove].half_width;
            if (!(hypot(p[0] - f[0], p[1] - f[1]) <= reach + lim)) {
                /* nearly parallel grooves meet far away, but their strips
                   can overlap near the footprint all the same: then the
                   overlap's point nearest the footprint stands for p */
                gr__overlap_nearest(pa, a->t, grid->grooves_[a->groove].half_width, pb, b->t,
                                    grid->grooves_[b->groove].half_width, cr, f, p);
                if (!(hypot(p[0] - f[0], p[1] - f[1]) <= reach)) continue;
            }
            if (!gr__locate(grid, a->groove, p, lim, &c) || !gr__locate(grid, b->groove, p, lim, &c)) continue;
            gr__junction_add(out, GR_JUNCTION_CROSSING, a->groove, b->groove, -1, -1, p);
        }
    /* self-intersections (§5): precomputed points inside the box, the
       builder's unless the caller passes its own */
    if (!self) {
        self = grid->self_;
        self_count = grid->self_count_;
    }
    for (k = 0; k < self_count; k++) {
        double p[2];
        gr__image_near(grid, self[k].point, f, p);
        if (gr__in_box(out->box, p)) gr__junction_add(out, GR_JUNCTION_SELF, self[k].groove, -1, -1, -1, p);
    }
    return GR_OK;
}

GR_DEF gr_result_t gr_detect(const gr_grid_t *grid, const gr_query_t *query, const gr_self_hit_t *self,
                             int self_count, void *scratch, size_t scratch_bytes, gr_junctions_t *out)
{
    gr_result_t r = gr__detect(grid, query, self, self_count, scratch, scratch_bytes, out);
    int k;
    /* pieces of a self-crossing groove are named by their groove */
    for (k = 0; r == GR_OK && k < out->count; k++) {
        gr_junction_t *j = &out->items[k];
        if (j->groove >= 0) j->groove = grid->grooves_[j->groove].parent;
        if (j->other >= 0) j->other = grid->grooves_[j->other].parent;
    }
    return r;
}

/* ---- The polygon path, first steps (§5.2) -------------------------------- */

/* A facet whose plane makes an angle below this (radians, as a sine) with
   the view is seen edge-on: eq. 8's denominator N'.E' vanishes and the
   projected footprint has no area. */
#define GR__EDGE_ON_REL 1e-12

GR_DEF void gr_footprint_polygon(const gr_footprint_t *fp, gr_fp_shape_t shape, double out[8])
{
    const double *a = fp->axis1, *b = fp->axis2, *f = fp->center;
    double sa[4], sb[4];
    int k, flip = a[0] * b[1] - a[1] * b[0] < 0;
    /* corners in the order that turns counter-clockwise for A1 x A2 > 0 */
    if (shape == GR_FP_RHOMBUS) {
        sa[0] = 1; sb[0] = 0; sa[1] = 0; sb[1] = 1; sa[2] = -1; sb[2] = 0; sa[3] = 0; sb[3] = -1;
    } else {
        sa[0] = 1; sb[0] = -1; sa[1] = 1; sb[1] = 1; sa[2] = -1; sb[2] = 1; sa[3] = -1; sb[3] = -1;
    }
    for (k = 0; k < 4; k++) {
        int j = flip ? 3 - k : k;
        out[2 * k] = f[0] + sa[j] * a[0] + sb[j] * b[0];
        out[2 * k + 1] = f[1] + sa[j] * a[1] + sb[j] * b[1];
    }
}

GR_DEF gr_result_t gr_facet_clip(const double *poly, int n, const gr_facet_geom_t *facet, const double e[3],
                                 double *proj, double *clipped, double *work, int cap, int *nclipped,
                                 double *area_f, double *area_clip)
{
    const double *t = facet ? facet->tangent : NULL;
    double bn[2], db, dw, len, eg[3], ne, xmin = HUGE_VAL, xmax = -HUGE_VAL, strip[8], margin;
    gr_result_t r;
    int k;
    if (nclipped) *nclipped = 0;
    if (area_f) *area_f = 0;
    if (area_clip) *area_clip = 0;
    if (!poly || !facet || !e || !proj || !clipped || !work || !nclipped || !area_f || !area_clip || n < 3 || cap < n + 4)
        return GR_ERR_INVALID_ARG;
    if (!gr__finite_n(poly, 2 * n) || !gr__finite_n(facet->point, 2) || !gr__finite_n(t, 2) ||
        !gr__finite_n(facet->c0, 2) || !gr__finite_n(facet->c1, 2) || !gr__finite_n(e, 3))
        return GR_ERR_NOT_FINITE;
    bn[0] = -t[1];
    bn[1] = t[0];
    db = facet->c1[0] - facet->c0[0];
    dw = facet->c1[1] - facet->c0[1];
    len = sqrt(db * db + dw * dw);
    /* E' in groove space (T, B, W); the facet plane has normal
       N' = (0, -dw, db) through C' = (0, b0, w0) (§5.2) */
    eg[0] = t[0] * e[0] + t[1] * e[1];
    eg[1] = bn[0] * e[0] + bn[1] * e[1];
    eg[2] = e[2];
    ne = -dw * eg[1] + db * eg[2];
    /* no facet, or one seen edge-on (within GR__EDGE_ON_REL of grazing):
       its projection has no area */
    if (!(len > 0) || !(fabs(ne) > GR__EDGE_ON_REL * len * sqrt(gr__dot3(eg, eg)))) return GR_OK;
    for (k = 0; k < n; k++) {
        double du = poly[2 * k] - facet->point[0], dv = poly[2 * k + 1] - facet->point[1];
        double fx = t[0] * du + t[1] * dv, fb = bn[0] * du + bn[1] * dv; /* F'_i, F'_w = 0 */
        /* eq. 8: t = N'.(C' - F') / N'.E', then eq. 7: F' + t E' */
        double tt = (-dw * (facet->c0[0] - fb) + db * facet->c0[1]) / ne;
        double px = fx + tt * eg[0], pb = fb + tt * eg[1], pw = tt * eg[2];
        proj[2 * k] = px;
        proj[2 * k + 1] = ((pb - facet->c0[0]) * db + (pw - facet->c0[1]) * dw) / len;
        if (px < xmin) xmin = px;
        if (px > xmax) xmax = px;
    }
    *area_f = fabs(gr_poly_area(proj, n));
    /* the facet's bounds: two lines y = 0 and y = len (Figure 9, right),
       closed into a rectangle wider than the projected polygon */
    margin = xmax - xmin + len;
    strip[0] = xmin - margin; strip[1] = 0;
    strip[2] = xmax + margin; strip[3] = 0;
    strip[4] = xmax + margin; strip[5] = len;
    strip[6] = xmin - margin; strip[7] = len;
    k = 0;
    r = gr_poly_clip_convex(proj, n, strip, 4, clipped, work, cap, &k);
    if (r != GR_OK) return r; /* a non-convex polygon can outgrow cap */
    *nclipped = k;
    *area_clip = fabs(gr_poly_area(clipped, k));
    return GR_OK;
}

/* A groove-space point (x along T, b along B, w) in facet coordinates
   (x, y), y along the facet from C_0 (§5.2, Figure 9 right). */
static void gr__facet_xy(const gr_facet_geom_t *fc, double x, double b, double w, double out[2])
{
    double db = fc->c1[0] - fc->c0[0], dw = fc->c1[1] - fc->c0[1];
    out[0] = x;
    out[1] = ((b - fc->c0[0]) * db + (w - fc->c0[1]) * dw) / sqrt(db * db + dw * dw);
}

/* UV offset from the facet's path point P in groove space: (T.d, B.d). */
static void gr__groove_xb(const gr_facet_geom_t *fc, double du, double dv, double *x, double *b)
{
    *x = fc->tangent[0] * du + fc->tangent[1] * dv;
    *b = -fc->tangent[1] * du + fc->tangent[0] * dv;
}

/* The strip k0 + kx x + ky y in [lo, hi] inside the rectangle `bounds`,
   by Sutherland-Hodgman against the strip as a long parallelogram. */
static int gr__strip_in_box(const double *bounds, double k0, double kx, double ky, double lo, double hi, double *out,
                            double *work, int cap)
{
    double rect[8], par[8], c[2], g2 = kx * kx + ky * ky, d[2], q[4], len;
    int k, n = 0;
    rect[0] = bounds[0]; rect[1] = bounds[1]; rect[2] = bounds[2]; rect[3] = bounds[1];
    rect[4] = bounds[2]; rect[5] = bounds[3]; rect[6] = bounds[0]; rect[7] = bounds[3];
    c[0] = 0.5 * (bounds[0] + bounds[2]);
    c[1] = 0.5 * (bounds[1] + bounds[3]);
    d[0] = -ky / sqrt(g2);
    d[1] = kx / sqrt(g2);
    len = hypot(bounds[2] - bounds[0], bounds[3] - bounds[1]);
    for (k = 0; k < 2; k++) { /* the point of each side line nearest c */
        double s = ((k ? hi : lo) - (k0 + kx * c[0] + ky * c[1])) / g2;
        q[2 * k] = c[0] + s * kx;
        q[2 * k + 1] = c[1] + s * ky;
        len += 2 * hypot(q[2 * k] - c[0], q[2 * k + 1] - c[1]);
    }
    par[0] = q[0] - len * d[0]; par[1] = q[1] - len * d[1];
    par[2] = q[0] + len * d[0]; par[3] = q[1] + len * d[1];
    par[4] = q[2] + len * d[0]; par[5] = q[3] + len * d[1];
    par[6] = q[2] - len * d[0]; par[7] = q[3] - len * d[1];
    if (gr_poly_clip_convex(rect, 4, par, 4, out, work, cap, &n) != GR_OK) return 0;
    return n;
}

GR_DEF gr_result_t gr_section_on_facet(const gr_facet_geom_t *facet, const double p2[2], const double t2[2],
                                       const double *sec2, int n2, const double bounds[4], double *points, int cap,
                                       int *sizes, int ring_cap, gr_polyset_t *cut)
{
    double db, dw, len, b1t2, n3[3], t3[3];
    int k;
    if (cut) memset(cut, 0, sizeof *cut);
    if (!facet || !p2 || !t2 || !sec2 || !bounds || !points || !sizes || !cut || n2 < 2) return GR_ERR_INVALID_ARG;
    if (!gr__finite_n(facet->point, 2) || !gr__finite_n(facet->tangent, 2) || !gr__finite_n(facet->c0, 2) ||
        !gr__finite_n(facet->c1, 2) || !gr__finite_n(p2, 2) || !gr__finite_n(t2, 2) || !gr__finite_n(sec2, 2 * n2) ||
        !gr__finite_n(bounds, 4))
        return GR_ERR_NOT_FINITE;
    if (cap < n2 + 8 || ring_cap < n2 / 2 + 1) return GR_ERR_BUFFER_TOO_SMALL;
    cut->points = points;
    cut->ring_sizes = sizes;
    db = facet->c1[0] - facet->c0[0];
    dw = facet->c1[1] - facet->c0[1];
    len = sqrt(db * db + dw * dw);
    if (!(len > 0)) return GR_ERR_INVALID_ARG;
    b1t2 = -facet->tangent[1] * t2[0] + facet->tangent[0] * t2[1];
    if (!(fabs(b1t2) > GR__EDGE_ON_REL)) return GR_OK; /* parallel grooves: no cut */
    if (fabs(dw) > GR__EDGE_ON_REL * len) {
        /* eqs. 7-8 with T_2 as the direction: each section point of the
           crossing groove slides along T_2 onto the facet plane, whose
           normal is N' = -dw B_1 + db W through C' = P_1 + b_0 B_1 + w_0 W */
        n3[0] = dw * facet->tangent[1];
        n3[1] = -dw * facet->tangent[0];
        n3[2] = db;
        t3[0] = t2[0]; t3[1] = t2[1]; t3[2] = 0;
        for (k = 0; k < n2; k++) {
            double x3[3], c3[3], s, x, b;
            x3[0] = p2[0] - t2[1] * sec2[2 * k];
            x3[1] = p2[1] + t2[0] * sec2[2 * k];
            x3[2] = sec2[2 * k + 1];
            c3[0] = facet->point[0] - facet->tangent[1] * facet->c0[0];
            c3[1] = facet->point[1] + facet->tangent[0] * facet->c0[0];
            c3[2] = facet->c0[1];
            s = (n3[0] * (c3[0] - x3[0]) + n3[1] * (c3[1] - x3[1]) + n3[2] * (c3[2] - x3[2])) / gr__dot3(n3, t3);
            gr__groove_xb(facet, x3[0] + s * t3[0] - facet->point[0], x3[1] + s * t3[1] - facet->point[1], &x, &b);
            gr__facet_xy(facet, x, b, x3[2], points + 2 * k);
        }
        sizes[0] = n2;
        cut->point_count = n2;
        cut->ring_count = 1;
        return GR_OK;
    }
    /* §5.3's special case: a facet parallel to UV at height w0. The cut is
       where the section (closed by its mouth) spans w0: intervals of b_2
       from the section's crossings with w = w0 (half-open, so a point at w0
       counts once), each a strip along T_2 */
    {
        /* the crossings b_2 are kept at the end of `points`, the strips
           are written from its start */
        double w0 = facet->c0[1], *bs = points + 2 * cap - n2, k0, kx, ky, sgn = db > 0 ? 1 : -1, tmp[16], wk[16];
        int nb = 0, used = 0, r = 0;
        for (k = 0; k < n2; k++) {
            const double *a = sec2 + 2 * k, *c = sec2 + 2 * ((k + 1) % n2);
            if ((a[1] >= w0) != (c[1] >= w0)) bs[nb++] = a[0] + (w0 - a[1]) * (c[0] - a[0]) / (c[1] - a[1]);
        }
        gr__sort_doubles(bs, nb);
        /* b_2 at facet point (x, y) is B_2 . (P_1 + x T_1 + (b_0 + sgn y) B_1 - P_2) */
        kx = -t2[1] * facet->tangent[0] + t2[0] * facet->tangent[1]; /* B_2 . T_1 */
        ky = t2[0] * facet->tangent[0] + t2[1] * facet->tangent[1];  /* B_2 . B_1 */
        k0 = -t2[1] * (facet->point[0] - p2[0]) + t2[0] * (facet->point[1] - p2[1]) + facet->c0[0] * ky;
        ky *= sgn;
        for (k = 0; k + 1 < nb; k += 2) {
            int m = gr__strip_in_box(bounds, k0, kx, ky, bs[k], bs[k + 1], tmp, wk, 8);
            if (m == 0) continue;
            if (2 * (used + m) > 2 * cap - n2 || r >= ring_cap) return GR_ERR_BUFFER_TOO_SMALL;
            memcpy(points + 2 * used, tmp, sizeof(double) * 2 * (size_t)m);
            sizes[r++] = m;
            used += m;
        }
        cut->point_count = used;
        cut->ring_count = r;
    }
    return GR_OK;
}

/* ---- The polygon path: visibility at intersections and ends (§5.2-5.5) --- */

/* Limits of the polygon path; a footprint beyond them is answered by §4
   (flags GR_LIST_NONPARALLEL / GR_LIST_PATH_END as before). */
#define GR__PP_MAX_GROOVES GR_POLY_MAX_GROOVES /* grooves in the §5.1 search box */
#define GR__PP_RING 80        /* points of one piece's clipped ring, or one cut */
#define GR__PP_TRAPS 512      /* trapezoids of an intermediate region (before merging) */
#define GR__PP_EDGES 400      /* edges of both operands of one boolean */
#define GR__PP_CROSS 4096     /* crossing heights of one boolean (the random tests' largest: ~1000) */
/* Sides of the polygon standing for an elliptical footprint (query.ellipse):
   of the ellipse's area, its boundary within 0.33 % of the radius
   (vertices at 1.0032, edge middles at 0.9984) */
#define GR__PP_ELLIPSE_SIDES 32
#define GR__PP_MAX_PIECES (8 * GR_POLY_MAX_GROOVES)   /* facets and end caps of those grooves */
#define GR__PP_SURF_TRAPS (128 * GR_POLY_MAX_GROOVES) /* trapezoids of all pieces' surfaces (the random tests' largest: ~300) */
#define GR__PP_OCC_POINTS 200 /* points of the occluder rings subtracted in one boolean */
#define GR__PP_OCC_RINGS 64
/* Coplanar pieces of two grooves (equal floors at a crossing): the lower
   groove index keeps the overlap; the cut plane is moved by this fraction
   of the grid's largest section size to decide it. */
#define GR__PP_TIE_REL 1e-9
/* A plane is seen edge-on along D when |N.D| falls below this (unit vectors):
   its projection has no area (as GR__EDGE_ON_REL for eq. 8). */
#define GR__PP_EDGE_ON 1e-9
/* A footprint whose area 4 |A1 x A2| is below this fraction of 4 |A1| |A2|
   has no area for the polygon path (its axes are parallel to rounding). */
#define GR__PP_FLAT_REL 1e-12
/* ... and one narrower than this many tie tolerances (GR__PP_TIE_REL of
   the sections' size) is a line there too: its ratios are differences of
   areas that rounding at the tie scale swamps (a footprint 1e-16 wide at
   an X crossing summed to 1.1, from 1e-20 to an empty list). */
#define GR__PP_MIN_WIDTH_TIES 64

/* One locally straight groove near the footprint, in coordinates relative
   to the footprint centre's tile image f (§4.2's straight approximation). */
typedef struct gr__ppg_t {
    double p[2], t[2];  /* nearest path point and unit tangent (direction of travel) */
    double x0, x1;      /* the groove exists for x = T.(q - P) in [x0, x1] (path ends, §5) */
    int end[2];         /* 1 when that path end (0: first point, 1: last) lies in the box */
    const double *sec;  /* section (b, w) pairs, unscaled */
    int nsec;
    double s;           /* perturbation scale f at P */
    int groove;
} gr__ppg_t;

/* A planar piece of the true surface: a facet strip of one groove, or an
   end cap (the section at a path end). 2D coordinates (a, c) map to
   o + a X + c Y; n is the unit normal out of the material. */
typedef struct gr__ppp_t {
    double o[3], x[3], y[3], n[3];
    int g;              /* index into the ppg array */
    int facet;          /* facet index; nsec-1 + end for caps */
    int refl;
    int nring;
    double ring[2 * (GR_MAX_FACETS + 2)];
} gr__ppp_t;

/* Scratch of the polygon path, after the §4 layout. */
typedef struct gr__pps_t {
    gr__ppg_t *g;
    gr__ppp_t *p;
    double *ra, *rb, *rc, *rv, *cut, *tmp, *tmp2; /* region ping-pong (traps), occluder, visible, cuts, rings */
    double *mouth;      /* the grooves' openings at w = 0 (UV strips, 4 points each) */
    int nmouth;
    int *sizes;
    double *surf;       /* every piece's surface: trapezoids, surf_count[j] from surf_first[j] */
    double *surf_box;   /* and its box, 4 per piece */
    int *surf_first, *surf_count;
    double *occ;        /* occluder rings gathered for one boolean */
    int *occ_sizes;
    void *bool_scratch;
    size_t bool_bytes;
} gr__pps_t;

static size_t gr__pp_layout(void *base, gr__pps_t *s)
{
    size_t off = 0;
    char *b = (char *)base;
    gr__pps_t tmp;
    if (!s) s = &tmp;
#define GR__PPCARVE(field, type, count) \
    s->field = (type *)(void *)(b ? b + off : NULL); off = gr__align8(off + sizeof(type) * (count));
    GR__PPCARVE(g, gr__ppg_t, GR__PP_MAX_GROOVES)
    GR__PPCARVE(p, gr__ppp_t, GR__PP_MAX_PIECES)
    GR__PPCARVE(ra, double, 8 * GR__PP_TRAPS)
    GR__PPCARVE(rb, double, 8 * GR__PP_TRAPS)
    GR__PPCARVE(rc, double, 8 * GR__PP_TRAPS)
    GR__PPCARVE(rv, double, 8 * GR__PP_TRAPS)
    GR__PPCARVE(cut, double, 2 * GR__PP_RING * GR__PP_MAX_GROOVES)
    GR__PPCARVE(tmp, double, 2 * GR__PP_RING)
    GR__PPCARVE(mouth, double, 2 * GR__PP_RING * GR__PP_MAX_GROOVES)
    GR__PPCARVE(tmp2, double, 2 * GR__PP_RING)
    GR__PPCARVE(sizes, int, 4 * GR__PP_MAX_GROOVES + 4)
    GR__PPCARVE(surf, double, 8 * GR__PP_SURF_TRAPS)
    GR__PPCARVE(surf_box, double, 4 * (GR__PP_MAX_PIECES + 1))
    GR__PPCARVE(surf_first, int, GR__PP_MAX_PIECES + 1)
    GR__PPCARVE(surf_count, int, GR__PP_MAX_PIECES + 1)
    GR__PPCARVE(occ, double, 2 * GR__PP_OCC_POINTS)
    GR__PPCARVE(occ_sizes, int, GR__PP_OCC_RINGS)
#undef GR__PPCARVE
    {
        gr__pscratch_t ptmp;
        s->bool_bytes = gr__pscratch_layout(GR__PP_EDGES, GR__PP_CROSS, NULL, &ptmp);
    }
    s->bool_scratch = b ? b + off : NULL;
    return off + s->bool_bytes;
}

static void gr__pp_point(const gr__ppp_t *pc, double a, double c, double q[3])
{
    int k;
    for (k = 0; k < 3; k++) q[k] = pc->o[k] + a * pc->x[k] + c * pc->y[k];
}

/* q slid along D onto the piece's plane, in its 2D coordinates (eqs. 7-8
   for any plane); D must not lie in the plane. */
static void gr__pp_onto(const gr__ppp_t *pc, const double q[3], const double *d, double out[2])
{
    double r[3], s = ((q[0] - pc->o[0]) * pc->n[0] + (q[1] - pc->o[1]) * pc->n[1] + (q[2] - pc->o[2]) * pc->n[2]) /
                     gr__dot3(pc->n, d);
    int k;
    for (k = 0; k < 3; k++) r[k] = q[k] - s * d[k] - pc->o[k];
    out[0] = gr__dot3(r, pc->x);
    out[1] = gr__dot3(r, pc->y);
}

/* Sutherland-Hodgman against one half-plane ka a + kc c + k0 >= 0. */
static int gr__pp_halfplane(const double *in, int n, double ka, double kc, double k0, double *out)
{
    int i, m = 0;
    for (i = 0; i < n; i++) {
        const double *a = in + 2 * i, *b = in + 2 * ((i + 1) % n);
        double da = ka * a[0] + kc * a[1] + k0, db = ka * b[0] + kc * b[1] + k0;
        if (da >= 0) { out[2 * m] = a[0]; out[2 * m + 1] = a[1]; m++; }
        if ((da >= 0) != (db >= 0)) {
            double t = da / (da - db);
            out[2 * m] = a[0] + t * (b[0] - a[0]);
            out[2 * m + 1] = a[1] + t * (b[1] - a[1]);
            m++;
        }
    }
    return m;
}

/* The groove coordinates (x along T, b along B, w) of the piece's point
   (a, c) are affine: q = k + a ga + c gc. */
static void gr__pp_groove_affine(const gr__ppp_t *pc, const gr__ppg_t *g, double k[3], double ga[3], double gc[3])
{
    double o[3] = {pc->o[0] - g->p[0], pc->o[1] - g->p[1], pc->o[2]};
    double t3[3] = {g->t[0], g->t[1], 0}, b3[3] = {-g->t[1], g->t[0], 0};
    k[0] = gr__dot3(o, t3); k[1] = gr__dot3(o, b3); k[2] = o[2];
    ga[0] = gr__dot3(pc->x, t3); ga[1] = gr__dot3(pc->x, b3); ga[2] = pc->x[2];
    gc[0] = gr__dot3(pc->y, t3); gc[1] = gr__dot3(pc->y, b3); gc[2] = pc->y[2];
}

/* gr__pp_cut where the plane crosses T: the section mapped back onto the
   plane by the inverse of its (b, w) map (det its determinant), clipped
   to x in [x0, x1], into tmp (tmp2 is work). Returns its points, fewer
   than 3 when nothing is left, -1 when a ring would overflow. */
static int gr__pp_cut_across(const gr__ppp_t *pc, const gr__ppg_t *g, const double k[3], const double ga[3],
                             const double gc[3], double det, double shift, double *tmp, double *tmp2)
{
    double s = g->s, tn = pc->n[0] * g->t[0] + pc->n[1] * g->t[1];
    int i, n;
    for (i = 0; i < g->nsec; i++) { /* (b, w) -> (a, c) by the inverse 2x2 map */
        double db = s * g->sec[2 * i] - k[1], dw = s * g->sec[2 * i + 1] - k[2];
        tmp[2 * i] = (db * gc[2] - dw * gc[1]) / det;
        tmp[2 * i + 1] = (ga[1] * dw - ga[2] * db) / det;
    }
    n = g->nsec;
    /* x in [x0, x1]: two half-planes. A plane across T (x constant on
       it) lying on an end x0 or x1 decides by the shifted x */
    if (fabs(ga[0]) + fabs(gc[0]) <= GR__PP_EDGE_ON) {
        double x = k[0], xs = k[0] + shift * tn;
        if (fabs(x - g->x0) <= fabs(shift)) x = xs;
        if (fabs(x - g->x1) <= fabs(shift)) x = xs;
        return x >= g->x0 && x <= g->x1 ? n : 0;
    }
    /* a half-plane at most doubles a ring's points (a non-convex section
       crosses the line at most once per edge) */
    n = gr__pp_halfplane(tmp, n, ga[0], gc[0], k[0] - g->x0, tmp2);
    if (2 * n > GR__PP_RING) return -1;
    return gr__pp_halfplane(tmp2, n, -ga[0], -gc[0], g->x1 - k[0], tmp);
}

/* gr__pp_cut where the plane holds T: along the unit direction u (in 2D)
   across T the plane's trace runs through the section; the intervals
   where it is inside become strips u-interval x [x0, x1] along T,
   appended to out as gr__pp_cut does. Returns 0, or -1 when out is full. */
static int gr__pp_cut_along(const gr__ppp_t *pc, const gr__ppg_t *g, const double k[3], const double ga[3],
                            const double gc[3], double big, double shift, double *out, int cap, int *npts, int *sizes,
                            int *nrings)
{
    double tl = hypot(ga[0], gc[0]), ua, uc, bs[2 * (GR_MAX_FACETS + 2)], db, dw, ta, tc, tol = fabs(shift), s = g->s;
    double nb_ = -pc->n[0] * g->t[1] + pc->n[1] * g->t[0];
    int i, nb = 0, on_pos;
    if (!(tl > 0)) return 0;
    ta = ga[0] / tl; tc = gc[0] / tl; /* 2D direction of T */
    ua = -tc; uc = ta;
    db = ua * ga[1] + uc * gc[1];
    dw = ua * ga[2] + uc * gc[2];
    /* a section point on the trace (within tol) takes the side the moved
       plane would leave it on: c - shift (db n_w - dw n_b) */
    on_pos = -shift * (db * pc->n[2] - dw * nb_) > 0;
    for (i = 0; i < g->nsec; i++) { /* crossings of the trace (b, w) = k + u (db, dw) with the closed section */
        const double *p0 = g->sec + 2 * i, *p1 = g->sec + 2 * ((i + 1) % g->nsec);
        double e0[2] = {s * p0[0] - k[1], s * p0[1] - k[2]}, e1[2] = {s * p1[0] - k[1], s * p1[1] - k[2]};
        double c0 = db * e0[1] - dw * e0[0], c1 = db * e1[1] - dw * e1[0]; /* side of the trace */
        int s0, s1;
        if (fabs(c0) <= tol) c0 = 0;
        if (fabs(c1) <= tol) c1 = 0;
        s0 = c0 == 0 ? on_pos : c0 > 0;
        s1 = c1 == 0 ? on_pos : c1 > 0;
        if (s0 != s1) {
            double t = c0 / (c0 - c1), q[2] = {e0[0] + t * (e1[0] - e0[0]), e0[1] + t * (e1[1] - e0[1])};
            bs[nb++] = (q[0] * db + q[1] * dw) / (db * db + dw * dw);
        }
    }
    gr__sort_doubles(bs, nb);
    for (i = 0; i + 1 < nb; i += 2) {
        /* x along T at 2D point (a, c): k0 + a ga0 + c gc0; the strip's ends
           x0, x1 (or +-big) */
        double xa = fmax(g->x0, k[0] - big), xb = fmin(g->x1, k[0] + big), m;
        int j;
        if (!(xb > xa)) continue;
        if (*npts + 4 > cap || *nrings >= 4 * GR__PP_MAX_GROOVES) return -1;
        for (j = 0; j < 4; j++) {
            double u = j == 0 || j == 3 ? bs[i] : bs[i + 1], x = j < 2 ? xa : xb;
            m = (x - k[0]) / tl; /* along T from the point u ua, u uc, where x = k0 (T is across u) */
            out[2 * (*npts + j)] = u * ua + m * ta;
            out[2 * (*npts + j) + 1] = u * uc + m * tc;
        }
        *npts += 4;
        sizes[(*nrings)++] = 4;
    }
    return 0;
}

/* §5.3: the part of the piece's plane inside groove g's volume (its
   section swept along T over [x0, x1]), as rings in the piece's 2D
   coordinates appended to out (*npts points, sizes[*nrings++]). The
   general case maps the section back onto the plane (gr__pp_cut_across);
   a plane holding T (the ground, floors, or a cap across a perpendicular
   groove) meets the volume in strips along T where the plane's trace
   crosses the section (gr__pp_cut_along). Returns 0, or -1 when out is
   full. */
static int gr__pp_cut(const gr__ppp_t *pc, const gr__ppg_t *g, double big, double shift, double *out, int cap,
                      int *npts, int *sizes, int *nrings, double *tmp, double *tmp2)
{
    /* a plane on the volume's boundary (equal floors of crossing grooves,
       the ground at every mouth, a wall where a groove ends) decides as if
       moved by `shift` along its normal, so exactly one of two coplanar
       pieces keeps the overlap. Only the decision moves, not the geometry:
       |shift| is the tolerance within which a point counts as on the
       boundary, and the strips' edges stay where the unmoved plane has
       them (moving the plane itself would move every cut by |shift| / the
       section's slope, a partition error of that order) */
    double k[3], ga[3], gc[3], det;
    int n;
    gr__pp_groove_affine(pc, g, k, ga, gc);
    /* the plane holds T when its (b, w) map is singular; X and Y are unit
       vectors, so |det| is the sine of the angle between the plane and T
       (a bound relative to the (b, w) parts alone would call the rounding
       of a plane holding T, ~1e-17 under fused multiply-adds, regular) */
    det = ga[1] * gc[2] - ga[2] * gc[1];
    if (!(fabs(det) > GR__PP_EDGE_ON)) return gr__pp_cut_along(pc, g, k, ga, gc, big, shift, out, cap, npts, sizes, nrings);
    n = gr__pp_cut_across(pc, g, k, ga, gc, det, shift, tmp, tmp2);
    if (n < 0) return -1;
    if (n < 3) return 0;
    if (*npts + n > cap || *nrings >= 4 * GR__PP_MAX_GROOVES) return -1;
    memcpy(out + 2 * *npts, tmp, sizeof(double) * 2 * (size_t)n);
    *npts += n;
    sizes[(*nrings)++] = n;
    return 0;
}

/* Joins trapezoids stacked in consecutive slabs whose shared edge matches
   and whose sides continue straight (within GR__PP_MERGE_REL of their
   size): the slab sweep cuts a region at every vertex height of both
   operands, and without this a chain of operations fragments it. */
#define GR__PP_MERGE_REL 1e-12
typedef struct gr__trap_t { double v[8]; } gr__trap_t;
static int gr__cmp_trap(const void *pa, const void *pb)
{
    const double *a = ((const gr__trap_t *)pa)->v, *b = ((const gr__trap_t *)pb)->v;
    return a[1] < b[1] ? -1 : a[1] > b[1] ? 1 : a[0] < b[0] ? -1 : a[0] > b[0];
}
static int gr__pp_merge(double *t, int n)
{
    gr__trap_t *tr = (gr__trap_t *)(void *)t;
    unsigned char gone[GR__PP_TRAPS];
    int i, m = 0;
    if (n < 2) return n;
    /* by bottom height, then left end: a trapezoid's upper neighbour is
       found by bisection on its top height */
    gr__sort(tr, (size_t)n, sizeof *tr, gr__cmp_trap);
    memset(gone, 0, (size_t)n);
    for (i = 0; i < n; i++) {
        double *a = tr[i].v;
        int again = 1;
        if (gone[i]) continue;
        while (again) {
            int lo = i + 1, hi = n, j;
            again = 0;
            while (lo < hi) { /* first index with bottom y >= a's top y */
                int mid = (lo + hi) / 2;
                if (tr[mid].v[1] < a[5]) lo = mid + 1; else hi = mid;
            }
            for (j = lo; j < n && tr[j].v[1] == a[5]; j++) {
                const double *b = tr[j].v;
                double sz = fabs(a[2] - a[0]) + fabs(a[5] - a[1]) + fabs(b[2] - b[0]) + fabs(b[5] - b[1]), cl, cr;
                if (gone[j] || fabs(a[6] - b[0]) > GR__PP_MERGE_REL * sz || fabs(a[4] - b[2]) > GR__PP_MERGE_REL * sz)
                    continue;
                cl = (a[6] - a[0]) * (b[7] - b[1]) - (a[7] - a[1]) * (b[6] - b[0]);
                cr = (a[4] - a[2]) * (b[5] - b[3]) - (a[5] - a[3]) * (b[4] - b[2]);
                if (fabs(cl) > GR__PP_MERGE_REL * sz * sz || fabs(cr) > GR__PP_MERGE_REL * sz * sz) continue;
                a[4] = b[4]; a[5] = b[5]; a[6] = b[6]; a[7] = b[7];
                gone[j] = 1;
                again = 1;
                break;
            }
        }
    }
    for (i = 0; i < n; i++)
        if (!gone[i]) tr[m++] = tr[i];
    return m;
}

/* a op b into out (GR__PP_TRAPS trapezoids); the count, or -1 when a
   buffer is too small (the caller then leaves the footprint to §4). A
   trapezoid set a too large for one sweep is taken in chunks: its
   trapezoids are disjoint, so (a1 ∪ a2) op b = (a1 op b) ∪ (a2 op b) for
   intersection and difference. */
static int gr__pp_bool(const gr__pps_t *ps, const gr_polyset_t *a, const gr_polyset_t *b, gr_poly_op_t op, double *out,
                       double *area)
{
    int n = 0, first, chunk, total = 0;
    double part;
    if (a->point_count + b->point_count <= GR__PP_EDGES) {
        if (gr__poly_boolean(a, b, op, ps->bool_scratch, GR__PP_CROSS, out, out ? GR__PP_TRAPS : 0, &n, area) != GR_OK)
            return -1;
        return out ? gr__pp_merge(out, n) : n;
    }
    chunk = (GR__PP_EDGES - b->point_count) / 4;
    if (a->ring_sizes || a->ring_count < 2 || chunk < 1 || op == GR_POLY_UNION || op == GR_POLY_XOR) return -1;
    *area = 0;
    for (first = 0; first < a->ring_count; first += chunk) {
        int m = a->ring_count - first < chunk ? a->ring_count - first : chunk;
        gr_polyset_t sub;
        sub.points = a->points + 8 * first;
        sub.point_count = 4 * m;
        sub.ring_sizes = NULL;
        sub.ring_count = m;
        if (gr__poly_boolean(&sub, b, op, ps->bool_scratch, GR__PP_CROSS, out ? out + 8 * total : NULL,
                             out ? GR__PP_TRAPS - total : 0, &n, &part) != GR_OK)
            return -1;
        *area += part;
        total += n;
    }
    return out ? gr__pp_merge(out, total) : total;
}

static gr_polyset_t gr__pp_set(const double *pts, int npts, const int *sizes, int nrings)
{
    gr_polyset_t p;
    p.points = pts;
    p.point_count = npts;
    p.ring_sizes = sizes;
    p.ring_count = nrings;
    return p;
}

/* Traps as a set (4 points per ring). */
static gr_polyset_t gr__pp_traps(const double *t, int n) { return gr__pp_set(t, 4 * n, NULL, n); }

/* Cuts of piece pc by every groove but its own (§5.3), in its 2D
   coordinates, into ps->cut / ps->sizes. Returns the ring count, -1 if full. */
static int gr__pp_cuts(const gr__pps_t *ps, const gr__ppp_t *pc, int ng, double big, double tie, int *npts)
{
    int h, nr = 0;
    *npts = 0;
    for (h = 0; h < ng; h++) {
        if (h == pc->g) continue;
        if (gr__pp_cut(pc, &ps->g[h], big, h < pc->g ? tie : -tie, ps->cut, GR__PP_RING * GR__PP_MAX_GROOVES, npts,
                       ps->sizes, &nr, ps->tmp, ps->tmp2))
            return -1;
    }
    return nr;
}

/* Bounding box (x0, y0, x1, y1) of n points. */
/* The surface of every piece (§5.3): its strip (or cap, or the ground)
   minus what the other grooves carve away, as trapezoids in its own
   coordinates, into the pool ps->surf. A piece's surface does not depend
   on the direction it is seen or lit from, so it is made once per
   footprint and serves both as the piece's own start and as an occluder
   of the others (§5.4: blocking facets and their prolongations, cut where
   a crossing groove removes them). Returns 0, or -1 when a buffer is full. */
static int gr__pp_surfaces(gr__pps_t *ps, int np, int ng, const double *box, double big, double tie)
{
    int j, used = 0;
    for (j = 0; j < np; j++) {
        const gr__ppp_t *pc = &ps->p[j];
        gr_polyset_t a, b;
        double area, *r0 = ps->tmp, *r1 = ps->tmp2;
        int nr, npts, n, side;
        /* only its part over the §5.1 search box matters: every ray from
           the footprint toward the viewer or a light stays over the box
           (that is how the box was grown), and so does every point of the
           surface such a ray meets. The box's four sides pulled back onto
           the plane (u(a, c) = o_u + a X_u + c Y_u is affine on it) */
        memcpy(r0, pc->ring, sizeof(double) * 2 * (size_t)pc->nring);
        n = pc->nring;
        for (side = 0; side < 4 && n >= 3; side++) {
            int ax = side & 1, hi = side >> 1;
            double sg = hi ? -1 : 1, *t = r0;
            if (2 * n > GR__PP_RING) return -1; /* a half-plane at most doubles it */
            n = gr__pp_halfplane(r0, n, sg * pc->x[ax], sg * pc->y[ax], sg * (pc->o[ax] - box[ax + 2 * hi]), r1);
            r0 = r1; r1 = t;
        }
        ps->surf_first[j] = used;
        ps->surf_count[j] = 0;
        if (n < 3) continue;
        memcpy(ps->rc, r0, sizeof(double) * 2 * (size_t)n);
        a = gr__pp_set(ps->rc, n, NULL, 1);
        nr = gr__pp_cuts(ps, pc, ng, big, tie, &npts);
        if (nr < 0) return -1;
        b = gr__pp_set(nr > 0 ? ps->cut : NULL, nr > 0 ? npts : 0, nr > 0 ? ps->sizes : NULL, nr);
        n = gr__pp_bool(ps, &a, &b, nr > 0 ? GR_POLY_DIFFERENCE : GR_POLY_UNION, ps->ra, &area);
        if (n < 0 || used + n > GR__PP_SURF_TRAPS) return -1;
        memcpy(ps->surf + 8 * used, ps->ra, sizeof(double) * 8 * (size_t)n);
        ps->surf_first[j] = used;
        ps->surf_count[j] = n;
        if (n > 0) gr__bounds(ps->ra, 4 * n, ps->surf_box + 4 * j);
        else ps->surf_box[4 * j] = ps->surf_box[4 * j + 1] = HUGE_VAL, ps->surf_box[4 * j + 2] = ps->surf_box[4 * j + 3] = -HUGE_VAL;
        used += n;
    }
    return 0;
}

/* cur minus the occluder rings gathered in ps->occ (one boolean: the rings
   of a set unite); the new count in *ncur, swapping cur and nxt. -1 when
   a buffer is too small. */
static int gr__pp_occlude(const gr__pps_t *ps, double **cur, double **nxt, int *ncur, int npts, int nrings, double *area)
{
    gr_polyset_t a = gr__pp_traps(*cur, *ncur), b = gr__pp_set(ps->occ, npts, ps->occ_sizes, nrings);
    double *sw;
    int n;
    if (nrings == 0) return 0;
    n = gr__pp_bool(ps, &a, &b, GR_POLY_DIFFERENCE, *nxt, area);
    if (n < 0) return -1;
    sw = *cur; *cur = *nxt; *nxt = sw;
    *ncur = n;
    return 0;
}

/* The part of piece i seen along d (§5.2-5.4): the piece's surface
   clipped to the footprint's pre-image (fpoly, local UV; or the
   trapezoids `start` instead, already on the surface), minus every other
   piece's surface in front of it along d
   (blocking facets and their prolongations into the crossing groove,
   §5.4), all of them in one boolean; pieces 0 .. np - 1 and the ground
   (piece np). The result (trapezoids in ps->ra or
   ps->rb) is returned in *res; the count, or -1 when a buffer overflows. */
static int gr__pp_region(const gr__pps_t *ps, int np, int i, const double *d, const double *fpoly, int nfp,
                         const double *start, int nstart, double tie, double **res, double *area)
{
    const gr__ppp_t *pc = &ps->p[i];
    double *cur = ps->ra, *nxt = ps->rb, cb[4];
    gr_polyset_t a, b;
    int k, j, ncur;
    *area = 0;
    *res = cur;
    if (start) {
        if (nstart > GR__PP_TRAPS) return -1;
        memcpy(cur, start, sizeof(double) * 8 * (size_t)nstart);
        ncur = nstart;
        for (k = 0; k < ncur; k++) *area += fabs(gr_poly_area(cur + 8 * k, 4));
    } else {
        double pre[2 * GR__PP_ELLIPSE_SIDES];
        for (k = 0; k < nfp; k++) {
            double p3[3] = {fpoly[2 * k], fpoly[2 * k + 1], 0};
            gr__pp_onto(pc, p3, d, pre + 2 * k);
        }
        if (ps->surf_count[i] == 0) return 0;
        gr__bounds(pre, nfp, cb);
        if (cb[0] >= ps->surf_box[4 * i + 2] || cb[2] <= ps->surf_box[4 * i] || cb[1] >= ps->surf_box[4 * i + 3] ||
            cb[3] <= ps->surf_box[4 * i + 1])
            return 0; /* the footprint misses the piece */
        a = gr__pp_traps(ps->surf + 8 * ps->surf_first[i], ps->surf_count[i]);
        b = gr__pp_set(pre, nfp, NULL, 1);
        ncur = gr__pp_bool(ps, &a, &b, GR_POLY_INTERSECTION, cur, area);
    }
    if (ncur <= 0) return ncur;
    /* §5.4: occlusion by every other piece's surface in front along d; only
       the parts whose box meets the region's are kept. The ground (piece
       np, the plane minus the grooves' mouths) is one of them: a ray from
       below w = 0 must leave through a mouth, and one from above never
       meets it (its part in front of this plane, slid along d, lies below
       w = 0, off any piece above) */
    gr__bounds(cur, 4 * ncur, cb);
    {
        double sg = gr__dot3(pc->n, d) > 0 ? 1 : -1;
        int npts = 0, nrings = 0;
        for (j = 0; j <= np && ncur > 0; j++) {
            const gr__ppp_t *oc = &ps->p[j];
            const double *st = ps->surf + 8 * ps->surf_first[j];
            double dd[3], ka, kc, k0;
            int m, t, flat = 1;
            if (j == i || ps->surf_count[j] == 0 || fabs(gr__dot3(oc->n, d)) <= GR__PP_EDGE_ON) continue;
            for (m = 0; m < 3; m++) dd[m] = oc->o[m] - pc->o[m];
            /* its part on the viewer's side of this plane; a coplanar piece
               (every corner within the tie margin) hides nothing, its
               overlap is settled by the cuts */
            ka = sg * gr__dot3(pc->n, oc->x); kc = sg * gr__dot3(pc->n, oc->y); k0 = sg * gr__dot3(pc->n, dd);
            for (m = 0; m < oc->nring && flat; m++) flat = fabs(ka * oc->ring[2 * m] + kc * oc->ring[2 * m + 1] + k0) <= tie;
            if (flat) continue;
            for (t = 0; t < ps->surf_count[j]; t++) {
                double *q = ps->occ + 2 * npts, bx[4];
                int nf = gr__pp_halfplane(st + 8 * t, 4, ka, kc, k0, ps->tmp);
                if (nf < 3) continue;
                for (m = 0; m < nf; m++) {
                    double p3[3];
                    gr__pp_point(oc, ps->tmp[2 * m], ps->tmp[2 * m + 1], p3);
                    gr__pp_onto(pc, p3, d, q + 2 * m);
                }
                gr__bounds(q, nf, bx);
                if (bx[0] >= cb[2] || bx[2] <= cb[0] || bx[1] >= cb[3] || bx[3] <= cb[1]) continue;
                ps->occ_sizes[nrings++] = nf;
                npts += nf;
                /* full: subtract what is gathered. A trapezoid cut by one
                   half-plane has 5 corners, but a degenerate one (its
                   sides collinear to rounding) can classify its corners
                   in and out alternately: 2 per side, 8 at most */
                if (npts + 8 > GR__PP_OCC_POINTS || nrings == GR__PP_OCC_RINGS) {
                    if (gr__pp_occlude(ps, &cur, &nxt, &ncur, npts, nrings, area) < 0) return -1;
                    npts = nrings = 0;
                    if (ncur == 0) break;
                }
            }
        }
        if (ncur > 0 && gr__pp_occlude(ps, &cur, &nxt, &ncur, npts, nrings, area) < 0) return -1;
    }
    *res = cur;
    if (ncur <= 0) *area = 0;
    return ncur;
}

/* Each groove of the footprint in UV about f (the candidates s->cand):
   its point, tangent, scale and section, unbounded along its path. */
static int gr__pp_grooves(const gr_grid_t *grid, const gr__scratch_t *s, int ng, gr__pps_t *ps)
{
    int i;
    for (i = 0; i < ng; i++) {
        const gr__cand_t *c = &s->cand[i];
        const gr__groove_t *rec = &grid->grooves_[c->groove];
        gr__ppg_t *g = &ps->g[i];
        if (rec->sec_count > GR_MAX_FACETS + 1) return -1;
        g->p[0] = c->p[0] - c->fc[0];
        g->p[1] = c->p[1] - c->fc[1];
        g->t[0] = c->t[0];
        g->t[1] = c->t[1];
        g->s = gr__perturb(rec, c->param); /* §3: the scale at P, constant across the footprint */
        g->sec = grid->section_ + 2 * rec->first_sec;
        g->nsec = rec->sec_count;
        g->groove = c->groove;
        g->x0 = -HUGE_VAL;
        g->x1 = HUGE_VAL;
        g->end[0] = g->end[1] = 0;
    }
    return 0;
}

/* Path ends (§5: intersected, isolated, corners): the groove stops at the
   end's position along its tangent, x0 for the first point. */
static void gr__pp_ends(const gr_grid_t *grid, const gr_junctions_t *jn, const double *f, gr__pps_t *ps)
{
    int k, e, i, ng = jn->grooves;
    for (k = 0; k < jn->count; k++) {
        const gr_junction_t *j = &jn->items[k];
        for (e = 0; e < 2; e++) {
            int gid = e == 0 ? j->groove : j->other, end = e == 0 ? j->end : j->other_end;
            double p[2], x;
            if (j->kind == GR_JUNCTION_CROSSING || j->kind == GR_JUNCTION_SELF || end < 0 || gid < 0) continue;
            if (e == 1 && j->kind != GR_JUNCTION_CORNER) continue;
            for (i = 0; i < ng && ps->g[i].groove != gid; i++) {}
            if (i == ng) continue;
            gr__end_point(grid, gid, end, f, p);
            x = (p[0] - f[0] - ps->g[i].p[0]) * ps->g[i].t[0] + (p[1] - f[1] - ps->g[i].p[1]) * ps->g[i].t[1];
            if (end == 0) ps->g[i].x0 = x; else ps->g[i].x1 = x;
            ps->g[i].end[end] = 1;
        }
    }
}

/* Groove i's facets as pieces from np on, over [xa, xb] along its path.
   Returns the new piece count. */
static int gr__pp_facets(const gr_grid_t *grid, gr__pps_t *ps, int i, double xa, double xb, int np)
{
    const gr__ppg_t *g = &ps->g[i];
    const gr__groove_t *rec = &grid->grooves_[g->groove];
    double bx = -g->t[1], by = g->t[0];
    int k;
    for (k = 0; k + 1 < g->nsec; k++) {
        gr__ppp_t *pc = &ps->p[np];
        double b0 = g->s * g->sec[2 * k], w0 = g->s * g->sec[2 * k + 1];
        double db = g->s * (g->sec[2 * k + 2] - g->sec[2 * k]), dw = g->s * (g->sec[2 * k + 3] - g->sec[2 * k + 1]);
        double len = sqrt(db * db + dw * dw);
        /* no facet, or one lying in the ground plane (a flat section):
           that is ground */
        if (!(len > 0) || (w0 == 0 && dw == 0)) continue;
        /* facet k in groove space (§5.2): through C_k, along T and C_k C_k+1 */
        pc->o[0] = g->p[0] + b0 * bx; pc->o[1] = g->p[1] + b0 * by; pc->o[2] = w0;
        pc->x[0] = g->t[0]; pc->x[1] = g->t[1]; pc->x[2] = 0;
        pc->y[0] = bx * db / len; pc->y[1] = by * db / len; pc->y[2] = dw / len;
        pc->n[0] = -bx * dw / len; pc->n[1] = -by * dw / len; pc->n[2] = db / len;
        pc->ring[0] = xa; pc->ring[1] = 0; pc->ring[2] = xb; pc->ring[3] = 0;
        pc->ring[4] = xb; pc->ring[5] = len; pc->ring[6] = xa; pc->ring[7] = len;
        pc->nring = 4;
        pc->g = i;
        pc->facet = k;
        pc->refl = grid->facet_refl_[rec->first_facet + k];
        np++;
    }
    return np;
}

/* Groove i's end caps as pieces from np on: the section standing across
   the path at each end within big. Its part below w = 0 closes the
   groove's cut and faces into the groove; its part above closes a
   protrusion and faces out of it, away from the groove. Returns the new
   piece count, -1 when a part has more points than a piece holds. */
static int gr__pp_caps(const gr_grid_t *grid, gr__pps_t *ps, int i, double big, int np)
{
    const gr__ppg_t *g = &ps->g[i];
    const gr__groove_t *rec = &grid->grooves_[g->groove];
    double bx = -g->t[1], by = g->t[0];
    int e, k, side;
    for (e = 0; e < 2; e++) {
        double x = e == 0 ? g->x0 : g->x1, sg = e == 0 ? 1 : -1, sec[2 * (GR_MAX_FACETS + 1)];
        double half[4 * (GR_MAX_FACETS + 1)];
        if (!g->end[e] || fabs(x) > big) continue;
        for (k = 0; k < g->nsec; k++) {
            sec[2 * k] = g->s * g->sec[2 * k];
            sec[2 * k + 1] = g->s * g->sec[2 * k + 1];
        }
        for (side = 0; side < 2; side++) {
            gr__ppp_t *pc = &ps->p[np];
            double su = side ? -sg : sg;
            /* the section's part on one side of w = 0: up to twice its
               points for a section crossing w = 0 on every facet, beyond a
               piece's ring for long sections (then declined) */
            int nh = gr__pp_halfplane(sec, g->nsec, 0, side ? 1 : -1, 0, half);
            if (nh > GR_MAX_FACETS + 2) return -1;
            memcpy(pc->ring, half, sizeof(double) * 2 * (size_t)nh);
            pc->nring = nh;
            if (pc->nring < 3 || !(fabs(gr_poly_area(pc->ring, pc->nring)) > 0)) continue;
            pc->o[0] = g->p[0] + x * g->t[0]; pc->o[1] = g->p[1] + x * g->t[1]; pc->o[2] = 0;
            pc->x[0] = bx; pc->x[1] = by; pc->x[2] = 0;
            pc->y[0] = 0; pc->y[1] = 0; pc->y[2] = 1;
            pc->n[0] = su * g->t[0]; pc->n[1] = su * g->t[1]; pc->n[2] = 0;
            pc->g = i;
            pc->facet = g->nsec - 1 + e;
            pc->refl = grid->facet_refl_[rec->first_facet];
            np++;
        }
    }
    return np;
}

/* Builds the grooves and pieces of a footprint from gr_detect()'s
   candidates and junctions. Returns the piece count, or -1 (not handled). */
static int gr__pp_build(const gr_grid_t *grid, const gr__scratch_t *s, const gr_junctions_t *jn, const double *f,
                        double big, gr__pps_t *ps)
{
    int ng = jn->grooves, i, np = 0;
    if (gr__pp_grooves(grid, s, ng, ps) < 0) return -1;
    gr__pp_ends(grid, jn, f, ps);
    for (i = 0; i < ng; i++) {
        double xa = fmax(ps->g[i].x0, -big), xb = fmin(ps->g[i].x1, big);
        if (!(xb > xa)) continue;
        if (np + ps->g[i].nsec + 3 > GR__PP_MAX_PIECES) return -1;
        np = gr__pp_facets(grid, ps, i, xa, xb, np);
        if ((np = gr__pp_caps(grid, ps, i, big, np)) < 0) return -1;
    }
    return np;
}

/* The polygon path (§5.2-5.5) for a footprint with intersections or ends:
   r_i = A_R / A_F for every piece, measured in UV (the projection along E
   scales a plane's areas by |N.E| / E_w), lit fractions the same way along
   each light. Protruding sections (w > 0) take the same path: their
   facets are pieces like any other, in front of what they hide (§5.4's
   prolongations are the pieces' own extent along T). Returns 1 when it
   filled the list, 0 to leave it to §4: too many grooves or junctions, a
   footprint without area, or a region outgrowing its buffers. */
/* The footprint as a polygon about its centre (§5.2): the parallelogram
   F ± A1 ± A2, or for query.ellipse the GR__PP_ELLIPSE_SIDES-gon inscribed
   in F + A1 cos a + A2 sin a and scaled to the ellipse's area, pi |A1 x A2|
   (the paper's rhombus through the axes' tips has 2/pi of it). Returns
   A_F from the axes (the shoelace sum of a flat quad's corners is not
   exactly 0 under fused multiply-adds), 0 for a footprint without area (a
   line or a point), which is §4's: A_R / A_F would divide rounding by
   rounding. */
static double gr__pp_footprint(const gr_query_t *q, double fpoly[2 * GR__PP_ELLIPSE_SIDES], int *nfp)
{
    const gr_footprint_t *fp = &q->footprint;
    double cr = fabs(fp->axis1[0] * fp->axis2[1] - fp->axis1[1] * fp->axis2[0]);
    int k;
    if (!(cr > GR__PP_FLAT_REL * hypot(fp->axis1[0], fp->axis1[1]) * hypot(fp->axis2[0], fp->axis2[1]))) return 0;
    if (q->ellipse) {
        double step = 2 * GR__PI / GR__PP_ELLIPSE_SIDES, rho = sqrt(2 * GR__PI / (GR__PP_ELLIPSE_SIDES * sin(step)));
        *nfp = GR__PP_ELLIPSE_SIDES;
        for (k = 0; k < *nfp; k++) {
            double c = rho * cos(k * step), sn = rho * sin(k * step);
            fpoly[2 * k] = c * fp->axis1[0] + sn * fp->axis2[0];
            fpoly[2 * k + 1] = c * fp->axis1[1] + sn * fp->axis2[1];
        }
        return GR__PI * cr;
    }
    *nfp = 4;
    gr_footprint_polygon(fp, GR_FP_QUAD, fpoly);
    for (k = 0; k < 4; k++) { fpoly[2 * k] -= fp->center[0]; fpoly[2 * k + 1] -= fp->center[1]; }
    return 4 * cr;
}

/* The ground as piece gp: the plane w = 0 (UV coordinates about f) over
   [-big, big]^2; gr__pp_cuts then cuts it by every groove. */
static void gr__pp_ground(const gr_grid_t *grid, gr__ppp_t *gp, double big)
{
    memset(gp, 0, sizeof *gp);
    gp->x[0] = 1; gp->y[1] = 1; gp->n[2] = 1;
    gp->ring[0] = -big; gp->ring[1] = -big; gp->ring[2] = big; gp->ring[3] = -big;
    gp->ring[4] = big; gp->ring[5] = big; gp->ring[6] = -big; gp->ring[7] = big;
    gp->nring = 4;
    gp->g = -1;
    gp->facet = -1;
    gp->refl = grid->base_reflectance;
}

/* Piece i's share of the footprint seen along e (its visible region's
   area over the footprint's, af) and each light's share of that, added to
   the list. 0, or -1 when a region ran out of room. */
static int gr__pp_add_piece(const gr_query_t *q, gr__pps_t *ps, int np, int i, const double e[3], const double *fpoly, int nfp,
                            double af, double tie, gr_facet_list_t *list)
{
    const gr__ppp_t *pc = &ps->p[i];
    double ne = gr__dot3(pc->n, e), ratio, area, *vis, lit[GR_MAX_LIGHTS];
    gr__mfacet_t m;
    int nv, l, k;
    /* back-facing or edge-on (§4.3); relative to e_w, because the ratio
       is area * ne / e_w: the ground (ne = e_w) is never edge-on */
    if (!(ne > GR__PP_EDGE_ON * e[2])) return 0;
    nv = gr__pp_region(ps, np, i, e, fpoly, nfp, NULL, 0, tie, &vis, &area);
    if (nv < 0) return -1;
    ratio = fmin(area * ne / e[2] / af, 1); /* a whole footprint, to rounding */
    if (!(ratio > 0)) return 0;
    /* keep the visible trapezoids while each light's region is built */
    memcpy(ps->rv, vis, sizeof(double) * 8 * (size_t)nv);
    for (l = 0; l < q->light_count; l++) {
        const double *L0 = q->lights + 3 * l;
        double L[3], ll = sqrt(gr__dot3(L0, L0)), la, *lr;
        lit[l] = 0;
        if (!(ll > 0) || !(L0[2] > 0)) continue;
        for (k = 0; k < 3; k++) L[k] = L0[k] / ll;
        if (!(gr__dot3(pc->n, L) > GR__PP_EDGE_ON * L[2])) continue;
        if (gr__pp_region(ps, np, i, L, NULL, 0, ps->rv, nv, tie, &lr, &la) < 0) return -1;
        lit[l] = area > 0 ? la / area : 0;
    }
    m.n[0] = pc->n[0]; m.n[1] = pc->n[1]; m.n[2] = pc->n[2];
    m.groove = pc->g >= 0 ? ps->g[pc->g].groove : -1; /* a piece's record until the list is done */
    m.facet = pc->facet;
    m.refl = pc->refl;
    gr__list_add(list, &m, ratio, lit, q->light_count);
    return 0;
}

static int gr__pp_query(const gr_grid_t *grid, const gr_query_t *q, const gr__scratch_t *s, const gr_junctions_t *jn,
                        void *base, gr_facet_list_t *list)
{
    const gr_footprint_t *fp = &q->footprint;
    gr__pps_t ps;
    double e[3], el, fpoly[2 * GR__PP_ELLIPSE_SIDES], af, f[2], big, tie;
    int ng = jn->grooves, np, i, k, npts, nfp = 4;
    /* the path needs every path end (its grooves' extents), not every
       crossing: detection lists the ends first, so a full list whose last
       entry is a crossing or a self-intersection dropped none of them */
    if (ng < 1 || ng > GR__PP_MAX_GROOVES) return 0;
    if (jn->dropped && jn->items[jn->count - 1].kind != GR_JUNCTION_CROSSING &&
        jn->items[jn->count - 1].kind != GR_JUNCTION_SELF)
        return 0;
    if (!((af = gr__pp_footprint(q, fpoly, &nfp)) > 0)) return 0;
    tie = GR__PP_TIE_REL * (grid->w + grid->d + grid->h);
    { /* af / (4 max |A_i|): half the footprint's narrow width (a parallelogram's exactly) */
        double a1 = hypot(fp->axis1[0], fp->axis1[1]), a2 = hypot(fp->axis2[0], fp->axis2[1]);
        if (!(af >= 4.0 * (a1 > a2 ? a1 : a2) * GR__PP_MIN_WIDTH_TIES * tie)) return 0;
    }
    el = sqrt(gr__dot3(fp->view, fp->view));
    for (k = 0; k < 3; k++) e[k] = fp->view[k] / el;
    gr__tile_image(grid, fp->center, f);
    /* pieces reach beyond the search box by its size: far enough that no
       ray from the footprint toward the viewer or a light meets their ends */
    big = 2 * (jn->box[2] - jn->box[0] + jn->box[3] - jn->box[1]) + grid->w + grid->d;
    gr__pp_layout(base, &ps);
    np = gr__pp_build(grid, s, jn, f, big, &ps);
    if (np < 0 || np >= GR__PP_MAX_PIECES) return 0;
    /* the ground, after the pieces; its cuts just below w = 0 are the
       openings that rays from inside the grooves leave through */
    gr__pp_ground(grid, &ps.p[np], big);
    ps.nmouth = gr__pp_cuts(&ps, &ps.p[np], ng, big, tie, &npts);
    if (ps.nmouth < 0 || npts != 4 * ps.nmouth) return 0;
    memcpy(ps.mouth, ps.cut, sizeof(double) * 2 * (size_t)npts);
    {
        /* the search box about f, a little larger (it bounds what matters) */
        double bx[4], mg = 1e-6 * (jn->box[2] - jn->box[0] + jn->box[3] - jn->box[1]);
        bx[0] = jn->box[0] - f[0] - mg; bx[1] = jn->box[1] - f[1] - mg;
        bx[2] = jn->box[2] - f[0] + mg; bx[3] = jn->box[3] - f[1] + mg;
        if (gr__pp_surfaces(&ps, np + 1, ng, bx, big, tie) < 0) return 0;
    }
    list->count = 0;
    list->flags = 0;
    for (i = 0; i <= np; i++)
        if (gr__pp_add_piece(q, &ps, np, i, e, fpoly, nfp, af, tie, list) < 0) return 0;
    gr__list_name_parents(grid, list);
    list->grooves = ng;
    list->subfootprints = 1;
    list->flags |= GR_LIST_POLYGON;
    return 1;
}

/* gr_query()'s entry to the polygon path: 1 when it answered. Its scratch
   follows the §4 layout. */
static int gr__pp_dispatch(const gr_grid_t *grid, const gr_query_t *q0, void *scratch, size_t bytes,
                           const gr__scratch_t *s, gr_facet_list_t *list)
{
    gr_junctions_t jn;
    gr_query_t q;
    double lights[3 * GR_MAX_LIGHTS];
    size_t base = gr__align8(gr__scratch_layout(grid, NULL, NULL));
    gr__region_query(grid, q0, 1, &q, lights);
    if (gr__detect(grid, &q, NULL, 0, scratch, bytes, &jn) != GR_OK || jn.count == 0) return 0;
    if (gr__pp_query(grid, &q, s, &jn, (char *)scratch + base, list)) return 1;
    /* declined part way (a buffer outgrown): §4 starts from an empty list */
    list->count = 0;
    list->flags = 0;
    list->grooves = 0;
    return 0;
}

static size_t gr__pp_scratch_bytes(void) { return gr__pp_layout(NULL, NULL); }

#endif /* GR_NO_INTERSECTIONS */
/* ==== [end section: intersections] ==== */

/* ==== [section: line samples] implementation (issue 8: §5.6) ==== */
#if !defined(GR_NO_LINE_SAMPLES) || !defined(GR_NO_INTERREFLECTION)

/* A point lies on a facet when its parameter along the facet is within
   this fraction of the facet's length of [0, 1] (crossing lines found at a
   facet's very end must not be lost to rounding; extra breakpoints only
   cut an interval in two). */
#define GR__LINE_ON_FACET_REL 1e-9
/* Breakpoints closer than this (in the segment parameter s in [-1, 1])
   coalesce: intervals that short carry no measurable ratio. To it adds
   the rounding of the breakpoints' positions, GR__LINE_SNAP_ULPS units
   of the largest texture coordinate along the rays, in units of the
   segment (gr__sheet_snap): a footprint far smaller than its coordinates
   would otherwise keep slivers whose class is rounding noise, and Jones &
   Perry would count their edges. */
#define GR__LINE_SNAP 1e-12
#define GR__LINE_SNAP_ULPS 16.0
/* Shadow and bounce rays start this fraction of the scene scale
   (w + h + d of the grid) off their facet, along its normal, so the facet
   they leave is not found again through rounding. */
#define GR__LINE_OFFSET_REL 1e-9
/* Rays (nearly) parallel to UV are followed at most this many scene
   scales plus the segment's length (the search box must stay finite). */
#define GR__LINE_TRAVEL_REL 64.0
/* Rays are followed this fraction of the scene scale past the highest
   and lowest section points. */
#define GR__LINE_CLEAR_REL 1e-6
/* Default early-exit tolerance of §5.6 (gr_query_t.line_exit_tol). */
#define GR__LINE_DEFAULT_EXIT 1e-3

/* A groove near the segment, locally straight (§4.2), in this frame's UV. */
typedef struct gr__lg_t {
    double p[2], t[2], bn[2]; /* path point, tangent T, binormal B */
    double f;                 /* perturbation scale: section points are f (b, w) */
    double reach;             /* f times the section's largest |b| */
    double lo, hi;            /* the path's extent along T from p (arc
                                 length; +-HUGE_VAL for closed paths) */
    const double *sec;
    int nsec, groove, first_facet;
} gr__lg_t;

/* A facet plane n.x = h (texture space); plane 0 is the ground w = 0. */
typedef struct gr__plane_t {
    double n[3], h;
    double c0[2], c1[2];      /* scaled section points (b, w) bounding it */
    int lg, facet, refl;      /* lg -1 for the ground */
    int cap;                  /* 1: the flat wall closing a path end */
} gr__plane_t;

typedef struct gr__brk_t { double s, sin2; int plane; } gr__brk_t; /* plane: a shadow's facet */

/* One interval of a segment: plane hit (-1: escaped, -2: not classified). */
typedef struct gr__ivl_t {
    double s0, s1, sin2;      /* sin2: the edge at s0 (Jones & Perry) */
    int plane;
    unsigned lit;
} gr__ivl_t;

typedef struct gr__xing_t { double t; int plane; } gr__xing_t;

/* An edge line of the scene: points q + λ D, λ in [l0, l1] (where it lies
   on the facets it bounds), between planes p1 and p2 (both -1 for a
   section point's line). */
typedef struct gr__edge_t { double q[3], D[3], l0, l1; int p1, p2; } gr__edge_t;

/* A segment of rays o + s a + t d, s in [-1, 1], t >= 0 (§5.6; §6.1 for
   bounces), with the throughput it carries; inside: the rays run in the
   material (refracted into it by a transmitting facet). */
typedef struct gr__sheet_t {
    double o[3], a[3], d[3], thr[3];
    int level, inside;
} gr__sheet_t;

typedef struct gr__lscratch_t {
    gr__lg_t *lg;
    gr__plane_t *pl;
    gr__xing_t *xs;
    gr__brk_t *brk;
    gr__ivl_t *iv, *iv2;      /* intervals; iv2: after the shadow split */
    gr__edge_t *ed;           /* the scene's edges, found once per scene */
    double *acc;              /* per plane: ratio, then lit per light */
    gr__sheet_t *stack;       /* gr_shade_indirect's pending segments */
} gr__lscratch_t;

#define GR__LINE_MAX_PLANES GR_LINE_MAX_PLANES

static size_t gr__line_scratch(void *base, struct gr__lscratch_t *ls)
{
    size_t off = 0;
    char *b = (char *)base;
    gr__lscratch_t tmp;
    if (!ls) ls = &tmp;
#define GR__LCARVE(field, type, count) \
    ls->field = (type *)(void *)(b ? b + off : NULL); off = gr__align8(off + sizeof(type) * (size_t)(count));
    GR__LCARVE(lg, gr__lg_t, GR_LINE_MAX_GROOVES)
    GR__LCARVE(pl, gr__plane_t, GR__LINE_MAX_PLANES)
    GR__LCARVE(xs, gr__xing_t, GR__LINE_MAX_PLANES)
    GR__LCARVE(brk, gr__brk_t, GR_LINE_MAX_BREAKS)
    GR__LCARVE(iv, gr__ivl_t, GR_LINE_MAX_BREAKS + 1)
    GR__LCARVE(iv2, gr__ivl_t, GR_LINE_MAX_BREAKS + 1)
    GR__LCARVE(ed, gr__edge_t, GR_LINE_MAX_EDGES)
    GR__LCARVE(acc, double, 2 * GR__LINE_MAX_PLANES * (1 + GR_MAX_LIGHTS))
#ifndef GR_NO_INTERREFLECTION
    GR__LCARVE(stack, gr__sheet_t, GR_INDIRECT_STACK)
#else
    ls->stack = NULL;
#endif
#undef GR__LCARVE
    return off;
}

/* The local scene of one evaluation: grooves, planes, and scales. */
typedef struct gr__lscene_t {
    const gr_grid_t *grid;
    gr__lscratch_t ls;
    int nlg, npl, ned;         /* ned -1: more than GR_LINE_MAX_EDGES, found per segment */
    double top, bottom, scale; /* highest w, lowest w, w + h + d */
    double box[4];             /* UV box holding every ray of the scene's segments */
    unsigned flags;
} gr__lscene_t;


static void gr__sec_pt(const gr__lg_t *g, int k, double c[2])
{
    c[0] = g->f * g->sec[2 * k];
    c[1] = g->f * g->sec[2 * k + 1];
}

/* Groove coordinates (b, w) of a texture-space point. */
static void gr__to_groove(const gr__lg_t *g, const double *x, double bw[2])
{
    bw[0] = g->bn[0] * (x[0] - g->p[0]) + g->bn[1] * (x[1] - g->p[1]);
    bw[1] = x[2];
}

/* Even-odd test against the section closed by its mouth (w = 0). */
static int gr__in_section(const gr__lg_t *g, const double bw[2])
{
    int i, j, in = 0;
    double ci[2], cj[2];
    for (i = 0, j = g->nsec - 1; i < g->nsec; j = i++) {
        gr__sec_pt(g, i, ci);
        gr__sec_pt(g, j, cj);
        if ((ci[1] > bw[1]) != (cj[1] > bw[1]) && bw[0] < (cj[0] - ci[0]) * (bw[1] - ci[1]) / (cj[1] - ci[1]) + ci[0])
            in = !in;
    }
    return in;
}

/* Inside the path's extent along T (ends are flat walls across it). */
static int gr__along_in(const gr__lg_t *g, const double *x)
{
    double a = g->t[0] * (x[0] - g->p[0]) + g->t[1] * (x[1] - g->p[1]);
    return a >= g->lo && a <= g->hi;
}

/* The solid: the ground w <= 0 minus the grooves' cuts, plus their
   protrusions (§3: a section below w = 0 carves, above it adds). */
static int gr__solid(const gr__lscene_t *sc, const double *x)
{
    int g, cut = 0;
    if (x[2] > sc->top) return 0;
    for (g = 0; g < sc->nlg; g++) {
        const gr__lg_t *lg = &sc->ls.lg[g];
        double bw[2];
        gr__to_groove(lg, x, bw);
        if (fabs(bw[0]) > lg->reach || !gr__along_in(lg, x)) continue;
        if (!gr__in_section(lg, bw)) continue;
        if (x[2] > 0) return 1;
        cut = 1;
    }
    return x[2] <= 0 && !cut;
}

/* Parameter u of groove point bw along facet [c0, c1]. */
static double gr__facet_param(const gr__plane_t *p, const double bw[2])
{
    double db = p->c1[0] - p->c0[0], dw = p->c1[1] - p->c0[1];
    return ((bw[0] - p->c0[0]) * db + (bw[1] - p->c0[1]) * dw) / (db * db + dw * dw);
}

static int gr__on_plane(const gr__lscene_t *sc, int i, const double *x)
{
    const gr__plane_t *p = &sc->ls.pl[i];
    double bw[2], u;
    if (p->lg < 0 || p->cap) return 1; /* the ground and end walls: their holes are the solid's business */
    gr__to_groove(&sc->ls.lg[p->lg], x, bw);
    u = gr__facet_param(p, bw);
    return u >= -GR__LINE_ON_FACET_REL && u <= 1 + GR__LINE_ON_FACET_REL;
}

/* The first change of medium along o + t d, t in (0, tmax]: for a ray in
   the air (inside = 0) the first entry into the solid, for a ray inside
   the material (inside = 1, refracted by a transmitting facet, §6.1) the
   first exit from it; the plane crossed there (its index) and *thit, or
   -1 when the ray leaves the groove layer unchanged (§6.2: upward into the
   scene from the air, downward into the bulk from inside). The ray is cut
   at every crossing of a facet or the ground; the solid's state is
   constant between crossings, so one point per piece decides. */
static int gr__ray_hit(const gr__lscene_t *sc, const double *o, const double *d, double tmax, int inside, double *thit)
{
    gr__xing_t *xs = sc->ls.xs;
    int i, j, m = 0;
    double prev = 0, x[3];
    for (i = 0; i < sc->npl; i++) {
        const gr__plane_t *p = &sc->ls.pl[i];
        double t;
        if (p->lg < 0 || p->cap) {
            double nd = gr__dot3(p->n, d), xc[3], bw[2];
            if (nd == 0) continue;
            t = (p->h - gr__dot3(p->n, o)) / nd;
            if (p->cap) { /* the wall is the section's shape */
                for (j = 0; j < 3; j++) xc[j] = o[j] + t * d[j];
                gr__to_groove(&sc->ls.lg[p->lg], xc, bw);
                if (!gr__in_section(&sc->ls.lg[p->lg], bw)) continue;
            }
        } else {
            const gr__lg_t *g = &sc->ls.lg[p->lg];
            double b0[2], bd = g->bn[0] * d[0] + g->bn[1] * d[1], db = p->c1[0] - p->c0[0], dw = p->c1[1] - p->c0[1];
            double det = -bd * dw + db * d[2], rb, rw, u;
            if (det == 0) continue;
            gr__to_groove(g, o, b0);
            rb = p->c0[0] - b0[0];
            rw = p->c0[1] - b0[1];
            t = (-rb * dw + db * rw) / det;
            u = (bd * rw - d[2] * rb) / det;
            if (u < -GR__LINE_ON_FACET_REL || u > 1 + GR__LINE_ON_FACET_REL) continue;
        }
        if (!(t > 0) || !(t <= tmax)) continue;
        for (j = m; j > 0 && xs[j - 1].t > t; j--) xs[j] = xs[j - 1];
        xs[j].t = t;
        xs[j].plane = i;
        m++;
    }
    for (i = 0; i <= m; i++) {
        double next = i < m ? xs[i].t : tmax, mid = 0.5 * (prev + next);
        if (i == m && !(tmax < HUGE_VAL)) mid = prev + sc->scale / sqrt(gr__dot3(d, d));
        for (j = 0; j < 3; j++) x[j] = o[j] + mid * d[j];
        if (gr__solid(sc, x) != inside) {
            if (i == 0) { *thit = 0; return -2; } /* started in the other medium: rounding at a touching facet */
            *thit = prev;
            return xs[i - 1].plane;
        }
        prev = next;
    }
    return -1;
}

/* Ray length beyond which nothing can be met (above the top, below the
   bottom), capped for rays along UV. */
static double gr__ray_tmax(const gr__lscene_t *sc, const double *o, const double *d, double seglen)
{
    double cap = (GR__LINE_TRAVEL_REL * sc->scale + seglen) / sqrt(gr__dot3(d, d)), t = cap;
    /* just past the top and bottom, so the last piece of the ray is
       tested clear of them */
    double clear = GR__LINE_CLEAR_REL * sc->scale;
    if (d[2] > 0) t = (sc->top + clear - o[2]) / d[2];
    else if (d[2] < 0) t = (sc->bottom - clear - o[2]) / d[2];
    return t < cap ? (t > 0 ? t : 0) : cap;
}

/* The plane's normal turned to face rays along d: the side a ray meets
   (the ground plane seen from below is the underside of a protrusion
   over a groove's hole, which faces down). */
static void gr__facing(const gr__lscene_t *sc, int plane, const double *d, double n[3])
{
    const gr__plane_t *p = &sc->ls.pl[plane];
    double sgn = gr__dot3(p->n, d) > 0 ? -1 : 1;
    n[0] = sgn * p->n[0];
    n[1] = sgn * p->n[1];
    n[2] = sgn * p->n[2];
}

/* Lit: the facet's seen side faces the light and nothing solid lies
   toward it (§4.3). */
static int gr__lit(const gr__lscene_t *sc, int plane, const double *d, const double *x, const double *l, double seglen)
{
    double o[3], th, off = GR__LINE_OFFSET_REL * sc->scale, n[3];
    int k;
    gr__facing(sc, plane, d, n);
    if (!(l[2] > 0) || !(gr__dot3(n, l) > 0)) return 0;
    for (k = 0; k < 3; k++) o[k] = x[k] + off * n[k];
    return gr__ray_hit(sc, o, l, gr__ray_tmax(sc, o, l, seglen), 0, &th) == -1;
}

/* Gather the grooves that can meet rays from the segment (box: the
   segment and where its rays cross the top and bottom, enlarged by w,
   §4.1/§5.1) and build their facet planes, nearest GR_LINE_MAX_GROOVES. */
/* A straight, unperturbed segment: its straight approximation is
   the groove itself, the same from every footprint (§5.6's cache keeps
   only these). */
static int gr__line_cacheable(const gr__groove_t *rec)
{
    return rec->kind == GR_PATH_POLYLINE && rec->point_count == 2 && !rec->perturb;
}

/* Groove id (not a piece) is straight: its straight approximation is the
   groove itself, anchored at its first point, the same from any footprint. */
static int gr__line_anchored(const gr_grid_t *grid, int id)
{
    const gr__groove_t *rec = &grid->grooves_[id];
    return rec->parent == id && gr__line_cacheable(rec);
}

/* Groove (or piece of a self-crossing groove) id in its straight
   approximation at cd, its point nearest c (parameter and rate the
   groove's). A piece runs on straight past its cut ends (they join the
   next piece, §5), and has walls only at the groove's own ends. */
static int gr__lg_from(const gr_grid_t *grid, int id, const gr__cand_t *cd0, const double *c, gr__lg_t *g)
{
    const gr__groove_t *rec = &grid->grooves_[id];
    gr__cand_t cd = *cd0;
    g->p[0] = cd.p[0] + c[0] - cd.fc[0];
    g->p[1] = cd.p[1] + c[1] - cd.fc[1];
    g->t[0] = cd.t[0];
    g->t[1] = cd.t[1];
    g->bn[0] = -cd.t[1];
    g->bn[1] = cd.t[0];
    g->f = gr__perturb(rec, cd.param);
    g->reach = rec->half_width / rec->fmax * g->f;
    g->sec = grid->section_ + 2 * rec->first_sec;
    g->nsec = rec->sec_count;
    g->groove = id;
    g->first_facet = rec->first_facet;
    g->lo = rec->closed || rec->join[0] ? -HUGE_VAL : -(cd.param - rec->t0) / cd.dtds;
    g->hi = rec->closed || rec->join[1] ? HUGE_VAL : (rec->t1 - cd.param) / cd.dtds;
    if (gr__line_anchored(grid, id)) {
        const double *a = grid->points_ + 2 * rec->first_point;
        g->p[0] = a[0] + (c[0] - cd.fc[0]); /* the image shift: a whole number of tiles, 0 without wrap */
        g->p[1] = a[1] + (c[1] - cd.fc[1]);
        if (!rec->closed) {
            g->lo = 0;
            g->hi = rec->length;
        }
    }
    return g->f > 0; /* scaled away here otherwise */
}

/* Groove id in its straight approximation at the point nearest c, found
   from ci, c's image in the tile (gr__locate looks one tile around). */
static int gr__lg_make(const gr_grid_t *grid, int id, const double *c, const double *ci, double reach, gr__lg_t *g)
{
    gr__cand_t cd;
    memset(&cd, 0, sizeof cd);
    if (!gr__locate(grid, id, ci, reach + grid->grooves_[id].half_width, &cd)) return 0;
    return gr__lg_from(grid, id, &cd, c, g);
}


/* The UV points whose convex hull holds every ray a segment casts: its
   ends, where their view rays leave the slab, and those points moved
   along each light to the top (shadow rays, §5.4). */
typedef struct gr__region_t { double p[2 * 4 * (1 + GR_MAX_LIGHTS)]; int n; } gr__region_t;

/* Whether the band of a straight groove, [lo, hi] along t and g->reach
   either side, meets the box sc->box: separating axes u, v, t
   and bn. A straight groove is the same record from any footprint, so
   this decides the same way whether it came from the grid or from the
   cache (§5.6), which gathers over a grown box and would otherwise keep
   grooves whose line passes near the footprint and whose segment ends far
   from it: gr_query_lines_cached() promises gr_query_lines()'s answer,
   groove count and flags included. */
static int gr__lg_band_meets_box(const gr__lscene_t *sc, const gr__lg_t *g)
{
    const double *box = sc->box;
    double hu = 0.5 * (box[2] - box[0]), hv = 0.5 * (box[3] - box[1]);
    double du = 0.5 * (box[0] + box[2]) - g->p[0], dv = 0.5 * (box[1] + box[3]) - g->p[1];
    double a0 = g->t[0] * du + g->t[1] * dv, b0 = g->bn[0] * du + g->bn[1] * dv;
    double et = hu * fabs(g->t[0]) + hv * fabs(g->t[1]), eb = hu * fabs(g->bn[0]) + hv * fabs(g->bn[1]);
    int k;
    if (!(a0 + et >= g->lo && a0 - et <= g->hi) || !(fabs(b0) <= g->reach + eb)) return 0;
    for (k = 0; k < 2; k++) { /* the box's own axes */
        double e0 = g->p[k] + g->lo * g->t[k], e1 = g->p[k] + g->hi * g->t[k], w = g->reach * fabs(g->bn[k]);
        double lo = (e0 < e1 ? e0 : e1) - w, hi = (e0 < e1 ? e1 : e0) + w;
        if (hi < box[k] || lo > box[k + 2]) return 0;
    }
    return 1;
}

/* Keep g if its band reaches the box (centre c, radius reach) and, when
   tight, the region the segment's rays sweep; the nearest
   GR_LINE_MAX_GROOVES stay. */
static void gr__lg_keep(gr__lscene_t *sc, const gr__lg_t *g, const double *c, double reach, const gr__region_t *quad)
{
    double bc = fabs(g->bn[0] * (c[0] - g->p[0]) + g->bn[1] * (c[1] - g->p[1]));
    double a0 = g->t[0] * (c[0] - g->p[0]) + g->t[1] * (c[1] - g->p[1]);
    int i, e;
    if (bc > reach + g->reach) return; /* its band misses the box */
    if (gr__line_anchored(sc->grid, g->groove) && !sc->grid->grooves_[g->groove].closed && !gr__lg_band_meets_box(sc, g))
        return;
    if (quad) { /* ... or the region this segment's rays sweep */
        double bl = HUGE_VAL, bh = -HUGE_VAL, al = HUGE_VAL, ah = -HUGE_VAL;
        for (e = 0; e < quad->n; e++) {
            double du = quad->p[2 * e] - g->p[0], dv = quad->p[2 * e + 1] - g->p[1];
            double bb = g->bn[0] * du + g->bn[1] * dv, aa = g->t[0] * du + g->t[1] * dv;
            if (bb < bl) bl = bb;
            if (bb > bh) bh = bb;
            if (aa < al) al = aa;
            if (aa > ah) ah = aa;
        }
        if (bl > g->reach || bh < -g->reach || al > g->hi + g->reach || ah < g->lo - g->reach) return;
    }
    if (a0 - g->lo <= reach + g->reach || g->hi - a0 <= reach + g->reach)
        sc->flags |= GR_LIST_PATH_END; /* an end near: closed by a wall (planes below) */
    if (sc->nlg == GR_LINE_MAX_GROOVES) {
        int far = 0;
        double fd = -1;
        sc->flags |= GR_LIST_LINE_APPROX;
        for (i = 0; i < sc->nlg; i++) {
            const gr__lg_t *o = &sc->ls.lg[i];
            double di = fabs(o->bn[0] * (c[0] - o->p[0]) + o->bn[1] * (c[1] - o->p[1]));
            if (di > fd) { fd = di; far = i; }
        }
        if (!(bc < fd)) return;
        sc->ls.lg[far] = *g;
    } else {
        sc->ls.lg[sc->nlg++] = *g;
    }
}

/* A self-crossing groove whose crossing lies in the box is taken as its
   pieces (§5, as the polygon path does: gr__split_candidates), each in its
   own straight approximation; 0 when none is near (the groove then stands
   for itself). Pieces are never cached (their groove is no segment). */
static int gr__lg_pieces(gr__lscene_t *sc, int id, const double *box, const double *c, const double *ci, double reach,
                         const gr__region_t *quad)
{
    const gr_grid_t *grid = sc->grid;
    const gr__groove_t *rec = &grid->grooves_[id];
    double bc[2];
    int k, n = 0;
    bc[0] = 0.5 * (box[0] + box[2]);
    bc[1] = 0.5 * (box[1] + box[3]);
    if (!gr__self_in_box(grid, id, box, bc)) return 0;
    for (k = 0; k < rec->split_count; k++) {
        int pid = rec->first_split + k;
        gr__cand_t cd;
        gr__lg_t g;
        memset(&cd, 0, sizeof cd);
        if (!gr__piece_locate(grid, pid, box, ci, reach + rec->half_width, &cd) || !gr__lg_from(grid, pid, &cd, c, &g))
            continue;
        gr__lg_keep(sc, &g, c, reach, quad);
        n++;
    }
    return n;
}

/* The grid search (§4.1) around box, centre c: every groove in its
   straight approximation, passed to gr__lg_keep, or stored in the cache
   (returns 0 when the cache cannot hold them all, or one is not straight). */
static int gr__line_gather(const gr_grid_t *grid, const gr__scratch_t *s, gr__lscene_t *sc, double *box,
                           const double *c, double reach, const gr__region_t *quad, gr_line_cache_t *fill)
{
    int k, n;
    double ci[2]; /* c moved with the box: the grooves are located from there */
    ci[0] = c[0], ci[1] = c[1];
    if (grid->wrap) { /* gather around the centre's image in the tile */
        double wu = grid->domain[2] - grid->domain[0], wv = grid->domain[3] - grid->domain[1];
        double su = floor((c[0] - grid->domain[0]) / wu) * wu, sv = floor((c[1] - grid->domain[1]) / wv) * wv;
        box[0] -= su; box[2] -= su; box[1] -= sv; box[3] -= sv;
        ci[0] -= su, ci[1] -= sv;
    }
    n = gr__gather(grid, box, s->seen, s->ids, NULL);
    for (k = 0; k < n; k++) {
        gr__lg_t g;
        if (!fill && grid->split_records_ > 0 && gr__lg_pieces(sc, s->ids[k], box, c, ci, reach, quad)) continue;
        if (!gr__lg_make(grid, s->ids[k], c, ci, reach, &g)) continue;
        if (!fill) { gr__lg_keep(sc, &g, c, reach, quad); continue; }
        if (fill->count == GR_LINE_MAX_GROOVES || !gr__line_cacheable(&grid->grooves_[s->ids[k]])) return 0;
        memcpy(fill->store_ + 16 * fill->count++, &g, sizeof g);
    }
    return 1;
}

typedef char gr__lg_fits_cache[sizeof(gr__lg_t) <= 16 * sizeof(double) ? 1 : -1];

static void gr__edge_list(gr__lscene_t *sc);

/* The UV box the sheet's rays can see grooves in: both ends of the sheet
   from entry to tmax, widened by w, and quad, the swept region's points
   and their shadow casters toward the lights (§5.1's w_L), which the box
   also holds. */
static void gr__sheet_box(const gr_grid_t *grid, const gr__lscene_t *sc, const gr__sheet_t *sh, const double *lights, int nl,
                          double box[4], gr__region_t *quad, double view_c[2])
{
    double seglen = 2 * sqrt(gr__dot3(sh->a, sh->a));
    int i, k, e;
    box[0] = box[1] = HUGE_VAL;
    box[2] = box[3] = -HUGE_VAL;
    for (e = -1; e <= 1; e += 2) {
        double o[3], tmax;
        for (k = 0; k < 3; k++) o[k] = sh->o[k] + e * sh->a[k];
        tmax = gr__ray_tmax(sc, o, sh->d, seglen);
        for (i = 0; i < 2; i++) {
            double t = i ? tmax : 0, u = o[0] + t * sh->d[0], v = o[1] + t * sh->d[1];
            if (u < box[0]) box[0] = u;
            if (u > box[2]) box[2] = u;
            if (v < box[1]) box[1] = v;
            if (v > box[3]) box[3] = v;
        }
    }
    view_c[0] = 0.5 * (box[0] + box[2]); /* the view rays' region, before the lights stretch the box */
    view_c[1] = 0.5 * (box[1] + box[3]);
    for (k = 0; k < 4; k++) box[k] += k < 2 ? -grid->w : grid->w;
    quad->n = 0;
    for (e = 0; e < 4; e++) { /* the swept region's points (UV), for pruning */
        double o[3], tq, x[3];
        int l;
        for (k = 0; k < 3; k++) o[k] = sh->o[k] + (e & 1 ? 1 : -1) * sh->a[k];
        tq = e & 2 ? gr__ray_tmax(sc, o, sh->d, seglen) : 0;
        for (k = 0; k < 3; k++) x[k] = o[k] + tq * sh->d[k];
        quad->p[2 * quad->n] = x[0];
        quad->p[2 * quad->n + 1] = x[1];
        quad->n++;
        for (l = 0; l < nl; l++) {
            const double *L = lights + 3 * l;
            double tl;
            if (!(L[2] > 0)) continue;
            tl = x[2] < sc->top ? (sc->top - x[2]) / L[2] : 0;
            quad->p[2 * quad->n] = x[0] + tl * L[0];
            quad->p[2 * quad->n + 1] = x[1] + tl * L[1];
            quad->n++;
        }
    }
    for (e = 0; e < quad->n; e++) { /* §5.1's w_L: shadow casters toward the lights */
        if (quad->p[2 * e] - grid->w < box[0]) box[0] = quad->p[2 * e] - grid->w;
        if (quad->p[2 * e] + grid->w > box[2]) box[2] = quad->p[2 * e] + grid->w;
        if (quad->p[2 * e + 1] - grid->w < box[1]) box[1] = quad->p[2 * e + 1] - grid->w;
        if (quad->p[2 * e + 1] + grid->w > box[3]) box[3] = quad->p[2 * e + 1] + grid->w;
    }
}

/* The grooves within reach of c that the box holds (pruned by quad when
   it is not NULL) into sc->ls.lg, in groove order: from the grid, or
   (§5.6) from the cache of a neighbour's grooves, refilled over a grown
   box when this box leaves it. */
/* Is the box wider than a quarter of the tile in a repeating direction? */
static int gr__box_beyond_quarter_tile(const gr_grid_t *grid, const double box[4])
{
    if (!grid->wrap) return 0;
    return !(box[2] - box[0] <= 0.25 * (grid->domain[2] - grid->domain[0]) &&
             box[3] - box[1] <= 0.25 * (grid->domain[3] - grid->domain[1]));
}

static void gr__line_grooves(const gr_grid_t *grid, const gr__scratch_t *s, gr__lscene_t *sc, const double box[4],
                             const double c[2], double reach, const gr__region_t *quad, gr_line_cache_t *cache)
{
    double b[4]; /* gr__line_gather moves its box into the tile */
    int i, k;
    memcpy(b, box, sizeof b);
    if (!cache) {
        gr__line_gather(grid, s, sc, b, c, reach, quad, NULL);
    } else {
        int hit = cache->valid && cache->grid == grid && box[0] >= cache->box[0] && box[1] >= cache->box[1] &&
                  box[2] <= cache->box[2] && box[3] <= cache->box[3];
        if (!hit) {
            double big[4], bc[2], br, gu = 0.5 * (GR_LINE_CACHE_GROW - 1) * (box[2] - box[0]),
                                      gv = 0.5 * (GR_LINE_CACHE_GROW - 1) * (box[3] - box[1]);
            big[0] = box[0] - gu; big[2] = box[2] + gu;
            big[1] = box[1] - gv; big[3] = box[3] + gv;
            memcpy(cache->box, big, sizeof big);
            bc[0] = c[0]; bc[1] = c[1];
            br = GR_LINE_CACHE_GROW * reach;
            cache->grid = grid;
            cache->count = 0;
            /* with a repeating texture each groove is held at its image
               nearest the filling centre, the right one for every
               footprint within a quarter tile of it; a box wider than
               that (low lights, grazing views) is not cached (found by
               review: a box 3.6 x 4.2 tiles wide served a footprint the
               wrong images, ground instead of a wall) */
            cache->valid = !gr__box_beyond_quarter_tile(grid, big) && gr__line_gather(grid, s, sc, big, bc, br, NULL, cache);
            cache->misses++;
        } else {
            cache->hits++;
        }
        if (cache->valid) {
            for (k = 0; k < cache->count; k++) {
                gr__lg_t g;
                memcpy(&g, cache->store_ + 16 * k, sizeof g);
                gr__lg_keep(sc, &g, c, reach, quad);
            }
        } else {
            gr__line_gather(grid, s, sc, b, c, reach, quad, NULL);
        }
    }
    for (i = 1; i < sc->nlg; i++) { /* in groove order, however they were found (cache or grid) */
        gr__lg_t x = sc->ls.lg[i];
        for (k = i; k > 0 && sc->ls.lg[k - 1].groove > x.groove; k--) sc->ls.lg[k] = sc->ls.lg[k - 1];
        sc->ls.lg[k] = x;
    }
}

/* The planes of groove i's facets (§3), out of the material. */
static void gr__facet_planes(gr__lscene_t *sc, int i)
{
    const gr__lg_t *g = &sc->ls.lg[i];
    int k;
    for (k = 0; k + 1 < g->nsec; k++) {
        gr__plane_t *p = &sc->ls.pl[sc->npl];
        double db, dw, len, nb, nw, q[3];
        gr__sec_pt(g, k, p->c0);
        gr__sec_pt(g, k + 1, p->c1);
        db = p->c1[0] - p->c0[0];
        dw = p->c1[1] - p->c0[1];
        len = sqrt(db * db + dw * dw);
        if (!(len > 0)) continue;
        if (sc->npl == GR__LINE_MAX_PLANES) { sc->flags |= GR_LIST_LINE_APPROX; return; }
        nb = -dw / len; /* (-Δw, Δb)/|.|: out of the material (§3) */
        nw = db / len;
        p->n[0] = nb * g->bn[0];
        p->n[1] = nb * g->bn[1];
        p->n[2] = nw;
        q[0] = g->p[0] + p->c0[0] * g->bn[0];
        q[1] = g->p[1] + p->c0[0] * g->bn[1];
        q[2] = p->c0[1];
        p->h = gr__dot3(p->n, q);
        p->lg = i;
        p->facet = k;
        p->refl = sc->grid->facet_refl_[g->first_facet + k];
        p->cap = 0;
        sc->npl++;
    }
}

/* Groove i's path ends within reach of c: flat walls across the path (§5,
   Figure 7c, with the section's shape), facing into a cut groove (out of
   a protrusion); facet index section_count - 1 (first end) or
   section_count (last end). */
static void gr__end_planes(gr__lscene_t *sc, int i, const double c[2], double reach)
{
    const gr__lg_t *g = &sc->ls.lg[i];
    int k, j;
    for (k = 0; k < 2; k++) {
        double at = k ? g->hi : g->lo, sgn = k ? 1 : -1, wmin = 0, cb;
        gr__plane_t *p = &sc->ls.pl[sc->npl];
        if (!(fabs(at - (g->t[0] * (c[0] - g->p[0]) + g->t[1] * (c[1] - g->p[1]))) <= reach + g->reach)) continue;
        if (sc->npl == GR__LINE_MAX_PLANES) { sc->flags |= GR_LIST_LINE_APPROX; return; }
        for (j = 0; j < g->nsec; j++)
            if (g->sec[2 * j + 1] < wmin) wmin = g->sec[2 * j + 1];
        cb = wmin < 0 ? -sgn : sgn;
        memset(p, 0, sizeof *p);
        p->n[0] = cb * g->t[0];
        p->n[1] = cb * g->t[1];
        p->h = p->n[0] * (g->p[0] + at * g->t[0]) + p->n[1] * (g->p[1] + at * g->t[1]);
        p->lg = i;
        p->facet = g->nsec - 1 + k;
        p->refl = sc->grid->facet_refl_[g->first_facet];
        p->cap = 1;
        sc->npl++;
    }
}

/* The scene a sheet of line samples sees (§5.6): its box, the grooves
   within reach (tight: pruned to the swept region), and their planes
   after the ground's, then the edge list. */
static void gr__line_scene(const gr_grid_t *grid, const gr__scratch_t *s, gr__lscene_t *sc, const gr__sheet_t *sh,
                           int tight, gr_line_cache_t *cache, const double *lights, int nl)
{
    double box[4], c[2], reach;
    gr__region_t quad;
    int i;
    sc->grid = grid;
    sc->top = grid->h;
    sc->bottom = -grid->d;
    sc->scale = grid->w + grid->h + grid->d;
    sc->nlg = 0;
    sc->flags = 0;
    /* the grooves are located (their periodic image, the point of their
       straight approximation) from c, the centre of the view rays' region:
       a low light stretches the box toward it by (h + d) / L_w, and from
       that box's centre the groove under the footprint was taken a tile
       away (wrap) or from 1e18 away (L_w = 1e-20); reach still holds the
       whole box */
    gr__sheet_box(grid, sc, sh, lights, nl, box, &quad, c);
    memcpy(sc->box, box, sizeof box);
    { /* to the box's farthest corner */
        double du = fmax(c[0] - box[0], box[2] - c[0]), dv = fmax(c[1] - box[1], box[3] - c[1]);
        reach = sqrt(du * du + dv * dv);
    }
    gr__line_grooves(grid, s, sc, box, c, reach, tight ? &quad : NULL, cache);
    /* planes: the ground, then every facet of every groove (§3) */
    memset(&sc->ls.pl[0], 0, sizeof sc->ls.pl[0]);
    sc->ls.pl[0].n[2] = 1;
    sc->ls.pl[0].lg = -1;
    sc->ls.pl[0].facet = -1;
    sc->ls.pl[0].refl = grid->base_reflectance;
    sc->ls.pl[0].cap = 0;
    sc->npl = 1;
    for (i = 0; i < sc->nlg; i++) {
        gr__facet_planes(sc, i);
        gr__end_planes(sc, i, c, reach);
    }
    gr__edge_list(sc);
}

/* sin²α between the segment (UV part of a) and a 3D edge direction D seen
   along the rays d, i.e. D's image on the plane w = 0 (Jones & Perry's α,
   in texture space as §5.6 does). */
static double gr__edge_sin2(const double *a, const double *dir, const double *D)
{
    double e[2], cr, aa, ee;
    e[0] = D[0];
    e[1] = D[1];
    if (dir[2] != 0) {
        e[0] -= D[2] / dir[2] * dir[0];
        e[1] -= D[2] / dir[2] * dir[1];
    }
    cr = a[0] * e[1] - a[1] * e[0];
    aa = a[0] * a[0] + a[1] * a[1];
    ee = e[0] * e[0] + e[1] * e[1];
    return aa > 0 && ee > 0 ? cr * cr / (aa * ee) : 0;
}

static void gr__brk_add(gr__lscene_t *sc, int *nb, double s, double sin2, int plane)
{
    if (!(s > -1 && s < 1)) return;
    if (*nb == GR_LINE_MAX_BREAKS) { sc->flags |= GR_LIST_LINE_APPROX; return; }
    sc->ls.brk[*nb].s = s;
    sc->ls.brk[*nb].sin2 = sin2;
    sc->ls.brk[*nb].plane = plane;
    (*nb)++;
}


/* Walks the edge lines: every section point's line, then the line of
   each pair of planes i < j of different grooves (or with an end wall). */
typedef struct gr__edge_it_t { int g, k, i, j, n; gr__edge_t e; } gr__edge_it_t;

static int gr__edge_next(const gr__lscene_t *sc, gr__edge_it_t *it, gr__edge_t *e)
{
    int m;
    e->l0 = -HUGE_VAL;
    e->l1 = HUGE_VAL;
    while (it->g < sc->nlg) { /* a section point swept along T */
        const gr__lg_t *lg = &sc->ls.lg[it->g];
        double c[2];
        if (it->k >= lg->nsec) { it->g++; it->k = 0; continue; }
        gr__sec_pt(lg, it->k++, c);
        e->q[0] = lg->p[0] + c[0] * lg->bn[0];
        e->q[1] = lg->p[1] + c[0] * lg->bn[1];
        e->q[2] = c[1];
        e->D[0] = lg->t[0];
        e->D[1] = lg->t[1];
        e->D[2] = 0;
        e->p1 = e->p2 = -1;
        return 1;
    }
    for (; it->i < sc->npl; it->i++, it->j = it->i + 1) {
        if (it->j <= it->i) it->j = it->i + 1;
        while (it->j < sc->npl) { /* the line of planes i < j (§5.3) */
            const gr__plane_t *a = &sc->ls.pl[it->i], *b = &sc->ls.pl[it->j++];
            double nj_d[3], d_ni[3], dd;
            if (a->lg == b->lg && !a->cap && !b->cap) continue;
            gr__cross3(a->n, b->n, e->D);
            dd = gr__dot3(e->D, e->D);
            if (!(dd > 1e-24)) continue;
            gr__cross3(b->n, e->D, nj_d);
            gr__cross3(e->D, a->n, d_ni);
            for (m = 0; m < 3; m++) e->q[m] = (a->h * nj_d[m] + b->h * d_ni[m]) / dd;
            e->p1 = it->i;
            e->p2 = it->j - 1;
            return 1;
        }
    }
    return 0;
}

/* Narrow e's λ range to where it lies on plane i's facet (its section
   segment, padded by GR__LINE_ON_FACET_REL, as gr__on_plane); the ground
   and end walls leave it (their holes are the solid's business). 0 when
   the range is empty. */
static int gr__edge_on_facet(const gr__lscene_t *sc, int i, gr__edge_t *e)
{
    const gr__plane_t *p;
    const gr__lg_t *g;
    double bw[2], db, dw, l2, u0, u1, lo, hi, eps = GR__LINE_ON_FACET_REL;
    if (i < 0) return 1;
    p = &sc->ls.pl[i];
    if (p->lg < 0 || p->cap) return 1;
    g = &sc->ls.lg[p->lg];
    gr__to_groove(g, e->q, bw);
    u0 = gr__facet_param(p, bw);
    db = p->c1[0] - p->c0[0];
    dw = p->c1[1] - p->c0[1];
    l2 = db * db + dw * dw;
    u1 = ((g->bn[0] * e->D[0] + g->bn[1] * e->D[1]) * db + e->D[2] * dw) / l2;
    if (u1 == 0) return u0 >= -eps && u0 <= 1 + eps;
    lo = (-eps - u0) / u1;
    hi = (1 + eps - u0) / u1;
    if (lo > hi) { double t = lo; lo = hi; hi = t; }
    if (lo > e->l0) e->l0 = lo;
    if (hi < e->l1) e->l1 = hi;
    return e->l0 <= e->l1;
}

/* Narrow e's λ range to the scene's box (no ray of its segments meets an
   edge, or passes one toward a light, outside it). 0 when empty. */
static int gr__edge_in_box(const gr__lscene_t *sc, gr__edge_t *e)
{
    int k;
    for (k = 0; k < 2; k++) {
        double lo, hi;
        if (e->D[k] == 0) {
            if (e->q[k] < sc->box[k] || e->q[k] > sc->box[k + 2]) return 0;
            continue;
        }
        lo = (sc->box[k] - e->q[k]) / e->D[k];
        hi = (sc->box[k + 2] - e->q[k]) / e->D[k];
        if (lo > hi) { double t = lo; lo = hi; hi = t; }
        if (lo > e->l0) e->l0 = lo;
        if (hi < e->l1) e->l1 = hi;
    }
    return e->l0 <= e->l1;
}

/* The next edge that exists (lies on both its facets somewhere in the
   scene's box): from the scene's list, or found afresh (into it->e) when
   the list overflowed. NULL at the end. */
static const gr__edge_t *gr__edge_fetch(const gr__lscene_t *sc, gr__edge_it_t *it)
{
    if (sc->ned >= 0) return it->n < sc->ned ? &sc->ls.ed[it->n++] : NULL;
    while (gr__edge_next(sc, it, &it->e))
        if (gr__edge_on_facet(sc, it->e.p1, &it->e) && gr__edge_on_facet(sc, it->e.p2, &it->e) &&
            gr__edge_in_box(sc, &it->e))
            return &it->e;
    return NULL;
}

/* The scene's edge list (once per scene: every segment of a footprint
   and both its passes reuse it). */
static void gr__edge_list(gr__lscene_t *sc)
{
    gr__edge_it_t it;
    const gr__edge_t *e;
    int n = 0;
    memset(&it, 0, sizeof it);
    sc->ned = -1; /* fetch afresh while filling */
    while ((e = gr__edge_fetch(sc, &it)) != NULL) {
        if (n == GR_LINE_MAX_EDGES) return; /* overflow: stays -1 */
        sc->ls.ed[n++] = *e;
    }
    sc->ned = n;
}

/* Cut the segment where its first surface can change (seen = NULL: §5.6,
   the 1D version of §5.2-5.3), or where a shadow boundary can fall on a
   facet it sees (seen[m] != 0; §5.4: every edge's shadow along each
   light on that facet); appended from brk[nb], returns the new count. */
static int gr__sheet_breaks(gr__lscene_t *sc, const gr__sheet_t *sh, const double *lights, int nl,
                            const unsigned char *seen, int nb)
{
    int m, l, v;
    const gr__edge_t *ep;
    gr__edge_it_t it;
    double nS[3], ns2, pad = GR__LINE_ON_FACET_REL * sc->scale;
    /* the seen planes, with their dot products against the segment's
       a, d and o, for the 2x2 system of a ray meeting two planes, per plane once) */
    int vis[GR_LINE_MAX_PLANES], nvis = 0;
    double pv[GR_LINE_MAX_PLANES][4], aadd = gr__dot3(sh->a, sh->a) * gr__dot3(sh->d, sh->d);
    gr__cross3(sh->a, sh->d, nS); /* the normal of the segment's plane of rays */
    ns2 = gr__dot3(nS, nS);
    for (m = 0; seen && m < sc->npl; m++)
        if (seen[m]) {
            const gr__plane_t *p = &sc->ls.pl[m];
            pv[nvis][0] = gr__dot3(p->n, sh->a);
            pv[nvis][1] = gr__dot3(p->n, sh->d);
            pv[nvis][2] = p->h - gr__dot3(p->n, sh->o);
            pv[nvis][3] = gr__dot3(p->n, p->n) * aadd;
            vis[nvis++] = m;
        }
    memset(&it, 0, sizeof it);
    while ((ep = gr__edge_fetch(sc, &it)) != NULL) {
        const gr__edge_t e = *ep;
        double s, t, x[3], r[3], c[3], nD[3], dd = gr__dot3(e.D, e.D), den = gr__dot3(nS, e.D);
        if (!seen && fabs(den) > 1e-14 * sqrt(ns2 * dd)) {
            /* where the edge pierces the plane of rays: x = q + λ D = o + s a + t d */
            double lam;
            for (m = 0; m < 3; m++) r[m] = sh->o[m] - e.q[m];
            lam = gr__dot3(nS, r) / den;
            if (lam >= e.l0 && lam <= e.l1) {
                for (m = 0; m < 3; m++) r[m] = e.q[m] + lam * e.D[m] - sh->o[m];
                gr__cross3(r, sh->d, c);
                s = gr__dot3(c, nS) / ns2;
                gr__cross3(sh->a, r, c);
                t = gr__dot3(c, nS) / ns2;
                if (t >= 0) gr__brk_add(sc, &nb, s, gr__edge_sin2(sh->a, sh->d, e.D), -1);
            }
        }
        /* §5.4: the edge's shadow along each light on each seen facet */
        for (l = 0; seen && l < nl; l++) {
            const double *L = lights + 3 * l;
            double nd2, lpad = pad / sqrt(dd), a11, a12, r1;
            if (!(L[2] > 0)) continue;
            gr__cross3(e.D, L, nD); /* the plane through the edge along L */
            nd2 = gr__dot3(nD, nD);
            if (!(nd2 > 1e-24 * dd)) continue;
            a11 = gr__dot3(nD, sh->a);
            a12 = gr__dot3(nD, sh->d);
            r1 = gr__dot3(nD, e.q) - gr__dot3(nD, sh->o);
            for (v = 0; v < nvis; v++) {
                double dir[3], lam, mu, det = a11 * pv[v][1] - a12 * pv[v][0];
                int k;
                m = vis[v];
                if (m == e.p1 || m == e.p2) continue;
                /* the ray (s, t) meeting this plane and facet m: Cramer on n.(o + s a + t d) = h */
                if (!(fabs(det) > 1e-14 * sqrt(nd2 * pv[v][3]))) continue;
                s = (r1 * pv[v][1] - a12 * pv[v][2]) / det;
                t = (a11 * pv[v][2] - r1 * pv[v][0]) / det;
                if (t < 0 || !(s > -1 && s < 1)) continue;
                for (k = 0; k < 3; k++) x[k] = sh->o[k] + s * sh->a[k] + t * sh->d[k];
                if (!gr__on_plane(sc, m, x)) continue;
                /* x = q + λ D + μ L: cast by the edge's existing part
                   (λ in range), which lies toward the light (μ <= 0) */
                for (k = 0; k < 3; k++) r[k] = x[k] - e.q[k];
                gr__cross3(r, L, c);
                lam = gr__dot3(c, nD) / nd2;
                gr__cross3(e.D, r, c);
                mu = gr__dot3(c, nD) / nd2;
                if (lam < e.l0 - lpad || lam > e.l1 + lpad || mu > pad) continue;
                gr__cross3(nD, sc->ls.pl[m].n, dir);
                gr__brk_add(sc, &nb, s, gr__edge_sin2(sh->a, sh->d, dir), m);
            }
        }
    }
    return nb;
}

#define GR__LINE_SMALL_SORT 24 /* insertion sort below, gr__sort above */
static int gr__cmp_brk(const void *a, const void *b)
{
    double x = ((const gr__brk_t *)a)->s, y = ((const gr__brk_t *)b)->s;
    return (x > y) - (x < y);
}

/* Sort breakpoints by s (insertion for short lists, gr__sort beyond). */
static void gr__brk_sort(gr__lscene_t *sc, int nb)
{
    if (nb > GR__LINE_SMALL_SORT) gr__sort(sc->ls.brk, (size_t)nb, sizeof(gr__brk_t), gr__cmp_brk);
    else {
        int i, j;
        for (i = 1; i < nb; i++) {
            gr__brk_t x = sc->ls.brk[i];
            for (j = i; j > 0 && sc->ls.brk[j - 1].s > x.s; j--) sc->ls.brk[j] = sc->ls.brk[j - 1];
            sc->ls.brk[j] = x;
        }
    }
}

/* Point of the segment's ray at s on plane p. */
static void gr__sheet_point(const gr__lscene_t *sc, const gr__sheet_t *sh, int p, double s, double x[3])
{
    const gr__plane_t *pl = &sc->ls.pl[p];
    double o[3], t, nd = gr__dot3(pl->n, sh->d);
    int k;
    for (k = 0; k < 3; k++) o[k] = sh->o[k] + s * sh->a[k];
    t = nd != 0 ? (pl->h - gr__dot3(pl->n, o)) / nd : 0;
    for (k = 0; k < 3; k++) x[k] = o[k] + t * sh->d[k];
}

/* The facet an interval sees (one ray at its middle). */
static void gr__classify(const gr__lscene_t *sc, const gr__sheet_t *sh, gr__ivl_t *iv)
{
    double o[3], th, seglen = 2 * sqrt(gr__dot3(sh->a, sh->a)), sm = 0.5 * (iv->s0 + iv->s1);
    int k;
    for (k = 0; k < 3; k++) o[k] = sh->o[k] + sm * sh->a[k];
    iv->plane = gr__ray_hit(sc, o, sh->d, gr__ray_tmax(sc, o, sh->d, seglen), sh->inside, &th);
    if (iv->plane == -2) iv->plane = -1; /* inside at the start: counted as leaving */
    iv->lit = 0;
}

/* The coalescing distance of a segment's breakpoints (GR__LINE_SNAP). */
static double gr__sheet_snap(const gr__lscene_t *sc, const gr__sheet_t *sh)
{
    double mag = fabs(sh->o[0]), al = sqrt(gr__dot3(sh->a, sh->a));
    if (fabs(sh->o[1]) > mag) mag = fabs(sh->o[1]);
    if (fabs(sh->o[2]) > mag) mag = fabs(sh->o[2]);
    mag += GR__LINE_TRAVEL_REL * sc->scale;
    return al > 0 ? GR__LINE_SNAP + GR__LINE_SNAP_ULPS * DBL_EPSILON * mag / al : GR__LINE_SNAP;
}

/* §5.4 on one segment: split the seen intervals at the shadow boundaries
   on their facets, then one shadow ray per piece and light. */
static int gr__shadow_split(gr__lscene_t *sc, const gr__sheet_t *sh, const double *lights, int nl, int n)
{
    gr__ivl_t *iv = sc->ls.iv, *out = sc->ls.iv2;
    unsigned char seen[GR_LINE_MAX_PLANES];
    double seglen = 2 * sqrt(gr__dot3(sh->a, sh->a)), snap = gr__sheet_snap(sc, sh);
    int i, k, nb, b = 0, m = 0;
    memset(seen, 0, (size_t)sc->npl);
    for (i = 0; i < n; i++)
        if (iv[i].plane >= 0) seen[iv[i].plane] = 1;
    nb = gr__sheet_breaks(sc, sh, lights, nl, seen, 0);
    gr__brk_sort(sc, nb);
    for (i = 0; i < n; i++) {
        double s0 = iv[i].s0, open = iv[i].sin2; /* open: the edge starting the piece */
        while (b < nb && sc->ls.brk[b].s <= s0) b++;
        for (;;) {
            double s1 = iv[i].s1, next = 0;
            int j;
            if (iv[i].plane >= 0 && m + (n - i) < GR_LINE_MAX_BREAKS + 1) {
                for (j = b; j < nb && sc->ls.brk[j].s < iv[i].s1; j++)
                    if (sc->ls.brk[j].plane == iv[i].plane && sc->ls.brk[j].s - s0 > snap &&
                        iv[i].s1 - sc->ls.brk[j].s > snap) {
                        s1 = sc->ls.brk[j].s;
                        next = sc->ls.brk[j].sin2;
                        b = j + 1;
                        break;
                    }
            } else if (iv[i].plane >= 0) {
                sc->flags |= GR_LIST_LINE_APPROX; /* no room to split further */
            }
            out[m] = iv[i];
            out[m].s0 = s0;
            out[m].s1 = s1;
            out[m].sin2 = open;
            if (out[m].plane >= 0) {
                double x[3];
                gr__sheet_point(sc, sh, out[m].plane, 0.5 * (s0 + s1), x);
                for (k = 0; k < nl; k++)
                    if (gr__lit(sc, out[m].plane, sh->d, x, lights + 3 * k, seglen)) out[m].lit |= 1u << k;
            }
            m++;
            if (s1 >= iv[i].s1) break;
            s0 = s1;
            open = next;
        }
    }
    memcpy(iv, out, sizeof *iv * (size_t)m);
    return m;
}

/* Intervals sorted by length, longest first (by_len), or by position:
   insertion sort for short lists, qsort beyond. */
static int gr__cmp_ivl_len(const void *a, const void *b);
static int gr__cmp_ivl_pos(const void *a, const void *b);
static void gr__ivl_sort(gr__ivl_t *iv, int n, int by_len)
{
    int i, j;
    if (n > GR__LINE_SMALL_SORT) {
        gr__sort(iv, (size_t)n, sizeof *iv, by_len ? gr__cmp_ivl_len : gr__cmp_ivl_pos);
        return;
    }
    for (i = 1; i < n; i++) {
        gr__ivl_t x = iv[i];
        double kx = by_len ? x.s0 - x.s1 : x.s0;
        for (j = i; j > 0 && (by_len ? iv[j - 1].s0 - iv[j - 1].s1 : iv[j - 1].s0) > kx; j--) iv[j] = iv[j - 1];
        iv[j] = x;
    }
}

static int gr__cmp_ivl_len(const void *a, const void *b)
{
    const gr__ivl_t *x = (const gr__ivl_t *)a, *y = (const gr__ivl_t *)b;
    double lx = x->s1 - x->s0, ly = y->s1 - y->s0;
    return (lx < ly) - (lx > ly);
}
static int gr__cmp_ivl_pos(const void *a, const void *b)
{
    const gr__ivl_t *x = (const gr__ivl_t *)a, *y = (const gr__ivl_t *)b;
    return (x->s0 > y->s0) - (x->s0 < y->s0);
}

/* One segment: cut into intervals, classify (longest first, stopping at
   Σ r_i >= 1 - tol, §5.6), back in position order. Returns the interval
   count; *weight receives Σ sin²α over the edges where the class changes
   (Jones & Perry 2000); *classified the length fraction classified. */
static int gr__sheet_eval(gr__lscene_t *sc, const gr__sheet_t *sh, const double *lights, int nl, double tol,
                          double *weight, double *classified, gr_line_stats_t *st)
{
    gr__ivl_t *iv = sc->ls.iv;
    int nb = sc->nlg ? gr__sheet_breaks(sc, sh, lights, nl, NULL, 0) : 0, n = 0, i;
    double last = -1, sin2 = 0, done = 0, snap = gr__sheet_snap(sc, sh);
    gr__brk_sort(sc, nb);
    for (i = 0; i <= nb; i++) {
        double s = i < nb ? sc->ls.brk[i].s : 1;
        /* coalesce (keep the steepest edge), but keep one interval: a
           segment shorter than the snap (a footprint narrower than 16 ulps
           of its coordinates, at u = 1e15 for a 0.02 footprint) is one
           class, its midpoint's (it was dropped: an empty list) */
        if (s - last <= snap && (i < nb || n > 0)) {
            if (i < nb && sc->ls.brk[i].sin2 > sin2) sin2 = sc->ls.brk[i].sin2;
            continue;
        }
        iv[n].s0 = last;
        iv[n].s1 = s;
        iv[n].sin2 = n ? sin2 : 0;
        iv[n].plane = -2;
        iv[n].lit = 0;
        n++;
        last = s;
        sin2 = i < nb ? sc->ls.brk[i].sin2 : 0;
    }
    if (tol > 0) gr__ivl_sort(iv, n, 1); /* longest first, for the early exit */
    for (i = 0; i < n; i++) {
        if (tol > 0 && done >= 2 * (1 - tol)) { if (st) st->early_exits++; break; }
        gr__classify(sc, sh, &iv[i]);
        done += iv[i].s1 - iv[i].s0;
        if (st) st->evaluated++;
    }
    if (tol > 0) gr__ivl_sort(iv, n, 0);
    if (st) { st->segments++; st->intervals += n; } /* (view intervals; shadows split them below) */
    if (nl > 0) n = gr__shadow_split(sc, sh, lights, nl, n);
    *weight = 0;
    for (i = 1; i < n; i++)
        if (iv[i].plane != iv[i - 1].plane || iv[i].lit != iv[i - 1].lit || iv[i].plane == -2) *weight += iv[i].sin2;
    *classified = done / 2;
    return n;
}

/* Line j of the n line samples of a footprint (§5.6), rays coming down
   along -E from above everything. The lines come in two families: the
   first ceil(n/2) run along A1, the other floor(n/2) along A2, each
   family spread across the footprint as parallel chords at the midpoints
   of equal strata of the other axis (offset c_i = -1 + (2i + 1)/count).
   n = 2 is the paper's pair of axes through F; with more lines each
   family is a stratified quadrature of the footprint's area: a chord
   gives the exact length shares at its offset, and the family's answer is
   the area-weighted mean of its chords, so its error falls with the
   number of chords (lines through F at rotated angles would converge to a
   density peaked at F instead). The chord spans the footprint: the full
   side for the parallelogram, |a| <= sqrt(1 - c^2) for the ellipse
   (query.ellipse), whose strata weigh their exact area (the semicircle
   law). Returns the chord's weight within its family (the weights of a
   family sum to 1); *family gets 0 or 1. */
static double gr__top_sheet(const gr_grid_t *grid, const gr_query_t *q, int j, int n, gr__sheet_t *sh, int *family)
{
    const gr_footprint_t *fp = &q->footprint;
    int n0 = (n + 1) / 2, fam = j < n0 ? 0 : 1, count = fam ? n - n0 : n0, i = fam ? j - n0 : j, k;
    const double *along = fam ? fp->axis2 : fp->axis1, *across = fam ? fp->axis1 : fp->axis2;
    double lo = -1 + 2.0 * i / count, hi = -1 + 2.0 * (i + 1) / count, c = 0.5 * (lo + hi), half = 1, weight;
    double ew = fp->view[2], lift, f[2], scale = grid->h + grid->w + grid->d;
    if (q->ellipse) {
        half = sqrt(1 - c * c);
        weight = gr__disc_cdf(hi) - gr__disc_cdf(lo);
    } else {
        weight = 1.0 / count;
    }
    if (ew < GR__GRAZING_MIN_W) ew = GR__GRAZING_MIN_W;
    /* start just above every protrusion (GR__LINE_CLEAR_REL over the top),
       but no farther from F than half the rays' reach (GR__LINE_TRAVEL_REL
       scene scales), so grazing views keep their rays near the footprint
       (a protrusion farther along the view is not seen then) */
    lift = (grid->h + GR__LINE_CLEAR_REL * scale) / ew;
    if (lift > 0.5 * GR__LINE_TRAVEL_REL * scale) lift = 0.5 * GR__LINE_TRAVEL_REL * scale;
    f[0] = fp->center[0] + c * across[0];
    f[1] = fp->center[1] + c * across[1];
    sh->o[0] = f[0] + lift * fp->view[0];
    sh->o[1] = f[1] + lift * fp->view[1];
    sh->o[2] = lift * fp->view[2];
    sh->a[0] = half * along[0];
    sh->a[1] = half * along[1];
    sh->a[2] = 0;
    for (k = 0; k < 3; k++) sh->d[k] = -fp->view[k];
    sh->thr[0] = sh->thr[1] = sh->thr[2] = 1;
    sh->level = 0;
    sh->inside = 0;
    *family = fam;
    return weight;
}


/* Shared argument checks of gr_query_lines / gr_shade_indirect. */
static gr_result_t gr__line_check(const gr_grid_t *grid, const gr_query_t *q, void *scratch, size_t bytes)
{
    int k;
    if (!grid || !q || !scratch) return GR_ERR_INVALID_ARG;
    if (q->light_count < 0 || q->light_count > GR_MAX_LIGHTS || (q->light_count > 0 && !q->lights) ||
        q->line_samples < 0 || q->line_samples > GR_LINE_MAX_SAMPLES)
        return GR_ERR_INVALID_ARG;
    if (bytes < gr_query_scratch_bytes(grid)) return GR_ERR_BUFFER_TOO_SMALL;
    if (!gr__finite_n(q->footprint.center, 2) || !gr__finite_n(q->footprint.axis1, 2) ||
        !gr__finite_n(q->footprint.axis2, 2) || !gr__finite_n(q->footprint.view, 3) || !gr__finite(q->line_exit_tol))
        return GR_ERR_NOT_FINITE;
    for (k = 0; k < 3 * q->light_count; k++)
        if (!gr__finite(q->lights[k])) return GR_ERR_NOT_FINITE;
    return GR_OK;
}

static double gr__exit_tol(const gr_query_t *q)
{
    return q->line_exit_tol == 0 ? GR__LINE_DEFAULT_EXIT : q->line_exit_tol;
}

/* Scratch views: the query's part, then ours. */
static void gr__line_layout(const gr_grid_t *grid, void *scratch, gr__scratch_t *s, gr__lscene_t *sc)
{
    size_t off = gr__align8(gr__scratch_layout(grid, scratch, s));
    gr__line_scratch((char *)scratch + off, &sc->ls);
}

#endif /* line-sample engine */

#ifndef GR_NO_LINE_SAMPLES
/* The sheet whose scene (gr__line_scene, not tight) holds every top-level
   line's rays: centred on F, spanning the footprint's UV box. */
static void gr__footprint_sheet(const gr_grid_t *grid, const gr_query_t *q, gr__sheet_t *all)
{
    const gr_footprint_t *fp = &q->footprint;
    int fam;
    (void)gr__top_sheet(grid, q, 0, 1, all, &fam);
    all->a[0] = fabs(fp->axis1[0]) + fabs(fp->axis2[0]);
    all->a[1] = fabs(fp->axis1[1]) + fabs(fp->axis2[1]);
}

GR_DEF gr_result_t gr_query_lines(const gr_grid_t *grid, const gr_query_t *query, void *scratch,
                                  size_t scratch_bytes, gr_facet_list_t *list, gr_line_stats_t *stats)
{
    return gr_query_lines_cached(grid, query, NULL, scratch, scratch_bytes, list, stats);
}

/* acc holds each family's area-weighted sums per plane (family f at
   [f npl, (f + 1) npl), 1 + nl doubles each: the seen length, then the
   length lit by each light). Adds the m intervals of one line sample,
   weight wa, in family fam; the unclassified rest of the line (cl the
   classified length) is shared in proportion. */
static void gr__lines_add_sample(const gr__lscene_t *sc, int m, int fam, double wa, double cl, int nl, double *acc)
{
    int i, q, stride = 1 + nl;
    for (i = 0; i < m; i++) {
        const gr__ivl_t *v = &sc->ls.iv[i];
        double len, *a;
        if (v->plane < 0 || !(cl > 0)) continue;
        len = wa * (v->s1 - v->s0) / (2 * cl);
        a = acc + (fam * sc->npl + v->plane) * stride;
        a[0] += len;
        for (q = 0; q < nl; q++)
            if (v->lit & (1u << q)) a[1 + q] += len;
    }
}

/* The families' sums combined into the list: by their mean Jones & Perry
   weights wfam, or plainly when neither crosses an edge. */
static void gr__lines_to_list(const gr__lscene_t *sc, const double *acc, int nfam, const double wfam[2], int nl,
                              gr_facet_list_t *list)
{
    int i, k, f, stride = 1 + nl;
    double wf[2], wsum = wfam[0] + wfam[1];
    for (f = 0; f < 2; f++) wf[f] = f >= nfam ? 0 : wsum > 0 ? wfam[f] / wsum : 1.0 / nfam;
    for (i = 0; i < sc->npl; i++) {
        const gr__plane_t *p = &sc->ls.pl[i];
        gr__mfacet_t mf;
        double lit[GR_MAX_LIGHTS], ratio = 0;
        for (k = 0; k < nl; k++) lit[k] = 0;
        for (f = 0; f < nfam; f++) {
            const double *a = acc + (f * sc->npl + i) * stride;
            ratio += wf[f] * a[0];
            for (k = 0; k < nl; k++) lit[k] += wf[f] * a[1 + k];
        }
        if (!(ratio > 0)) continue;
        for (k = 0; k < nl; k++) lit[k] /= ratio;
        for (k = 0; k < 3; k++) mf.n[k] = p->n[k];
        mf.groove = p->lg < 0 ? -1 : sc->ls.lg[p->lg].groove; /* a piece's record until the list is done */
        mf.facet = p->facet;
        mf.refl = p->refl;
        gr__list_add(list, &mf, ratio, lit, nl);
    }
}

/* Whether two of the footprint's grooves are not parallel. */
static int gr__lines_nonparallel(const gr__lscene_t *sc)
{
    int i, k;
    for (i = 0; i < sc->nlg; i++)
        for (k = 0; k < i; k++) {
            const gr__lg_t *a = &sc->ls.lg[i], *b = &sc->ls.lg[k];
            if (fabs(a->t[0] * b->t[1] - a->t[1] * b->t[0]) > sin(GR__DEFAULT_PARALLEL_TOL)) return 1;
        }
    return 0;
}

GR_DEF gr_result_t gr_query_lines_cached(const gr_grid_t *grid, const gr_query_t *query, gr_line_cache_t *cache,
                                         void *scratch, size_t scratch_bytes, gr_facet_list_t *list,
                                         gr_line_stats_t *stats)
{
    gr__scratch_t s;
    gr__lscene_t sc;
    gr__sheet_t sh;
    gr_query_t raised;
    const gr_footprint_t *fp;
    double wfam[2] = {0, 0}, tol, *acc, lights[3 * GR_MAX_LIGHTS];
    int n, j, nl;
    gr_result_t r;
    if (!list) return GR_ERR_INVALID_ARG;
    list->count = 0;
    list->flags = 0;
    list->grooves = 0;
    list->subfootprints = 1;
    if (stats) memset(stats, 0, sizeof *stats);
    r = gr__line_check(grid, query, scratch, scratch_bytes);
    if (r != GR_OK) return r;
    gr__region_query(grid, query, 1, &raised, lights);
    query = &raised;
    fp = &query->footprint;
    if (!(fp->view[2] > 0)) { list->flags |= GR_LIST_BELOW_HORIZON; return GR_OK; }
    n = query->line_samples ? query->line_samples : 2;
    nl = query->light_count;
    tol = gr__exit_tol(query);
    gr__line_layout(grid, scratch, &s, &sc);
    acc = sc.ls.acc;
    {
        gr__sheet_t all;
        gr__footprint_sheet(grid, query, &all); /* every line shares the footprint's scene */
        gr__line_scene(grid, &s, &sc, &all, 0, cache, query->lights, nl);
    }
    /* each family's sums (gr__lines_add_sample), combined by their weights */
    memset(acc, 0, sizeof(double) * (size_t)(2 * sc.npl * (1 + nl)));
    for (j = 0; j < n; j++) {
        double wj, cl, wa;
        int m, fam;
        wa = gr__top_sheet(grid, query, j, n, &sh, &fam);
        m = gr__sheet_eval(&sc, &sh, query->lights, nl, tol, &wj, &cl, stats);
        if (stats && j < GR_LINE_MAX_SAMPLES) stats->weight[j] = wj;
        wfam[fam] += wa * wj;
        gr__lines_add_sample(&sc, m, fam, wa, cl, nl, acc);
    }
    gr__lines_to_list(&sc, acc, n > 1 ? 2 : 1, wfam, nl, list);
    gr__list_name_parents(grid, list);
    if (gr__lines_nonparallel(&sc)) list->flags |= GR_LIST_NONPARALLEL;
    list->flags |= sc.flags;
    list->grooves = sc.nlg;
    if (stats && (sc.flags & GR_LIST_LINE_APPROX)) stats->flags |= GR_STATS_LINE_APPROX;
    gr__list_finish(list, nl);
    return GR_OK;
}
#endif
/* ==== [end section: line samples] ==== */

/* ==== [section: interreflection] implementation (issue 8: §6) ==== */
#ifndef GR_NO_INTERREFLECTION
/* Default index of refraction of a transmitting facet. */
#define GR__DEFAULT_IOR 1.5

static const gr_specular_t *gr__spec(const gr_indirect_t *ind, int refl)
{
    return refl >= 0 && refl < ind->specular_count ? &ind->specular[refl] : NULL;
}

static int gr__nonzero3(const double *v) { return v[0] > 0 || v[1] > 0 || v[2] > 0; }

/* Hand light leaving a bounce to the host (§6.2), times throughput. */
static void gr__to_host(const gr_indirect_t *ind, const double *origin, const double *dir, int depth, int inside,
                        const double *thr, double frac, double *rgb)
{
    double c[3] = {0, 0, 0}, u[3], len = sqrt(gr__dot3(dir, dir)), w = frac * (thr[0] + thr[1] + thr[2]) / 3;
    int k;
    if (!ind->trace || !(frac > 0) || !(len > 0)) return;
    for (k = 0; k < 3; k++) u[k] = dir[k] / len;
    ind->trace(ind->trace_user, origin, u, depth, inside, w, c);
    for (k = 0; k < 3; k++) rgb[k] += thr[k] * frac * c[k];
}

/* Unpolarised Fresnel reflectance at an interface met at cos ci > 0, eta
   = n_from / n_to; 1 under total internal reflection. *ct: the
   transmitted cosine (0 under total internal reflection). */
static double gr__fresnel(double ci, double eta, double *ct)
{
    double st2 = eta * eta * (1 - ci * ci), rs, rp;
    if (st2 >= 1) { *ct = 0; return 1; }
    *ct = sqrt(1 - st2);
    rs = (eta * ci - *ct) / (eta * ci + *ct);
    rp = (ci - eta * *ct) / (ci + eta * *ct);
    return 0.5 * (rs * rs + rp * rp);
}

/* The pending-segment stack of gr_shade_indirect() (§6.1's recursion). */
typedef struct gr__stack_t { gr__sheet_t *s; int top, full; } gr__stack_t;

/* Push the piece [x0, x1] (3D, on the facet) as the next footprint, seen
   along dir in the given medium, carrying thr; when the stack is full the
   piece leaves along dir unexamined (§6.2's host) and the stack says so. */
static void gr__push_piece(const gr_indirect_t *ind, gr__stack_t *st, const double *x0, const double *x1,
                           const double *side, const double *dir, const double *thr, int level, int inside,
                           double *rgb)
{
    double mid[3];
    int k;
    for (k = 0; k < 3; k++) mid[k] = 0.5 * (x0[k] + x1[k]) + side[k];
    if (st->top == GR_INDIRECT_STACK) {
        st->full = 1;
        gr__to_host(ind, mid, dir, level, inside, thr, 1, rgb);
        return;
    }
    {
        gr__sheet_t *c = &st->s[st->top++];
        for (k = 0; k < 3; k++) {
            c->o[k] = mid[k];
            c->a[k] = 0.5 * (x1[k] - x0[k]);
            c->d[k] = dir[k];
            c->thr[k] = thr[k];
        }
        c->level = level;
        c->inside = inside;
    }
}

/* One evaluated segment: direct terms, then the pieces that bounce
   (§6.1: each facet run's visible piece becomes the next footprint, seen
   along the mirror direction E_r and, for a transmitting facet, along the
   refracted one E_t), and what leaves to the host (§6.2). */
static void gr__bounce(const gr__lscene_t *sc, const gr__sheet_t *sh, int m, const gr_query_t *q,
                       const gr_indirect_t *ind, gr__stack_t *stack, double *rgb)
{
    const gr__ivl_t *iv = sc->ls.iv;
    double e[3], dd[3], esc = 0, esc_s = 0, off = GR__LINE_OFFSET_REL * sc->scale;
    int i, j, k, l;
    {
        double len = sqrt(gr__dot3(sh->d, sh->d));
        for (k = 0; k < 3; k++) {
            dd[k] = sh->d[k] / len;
            e[k] = -dd[k];
        }
    }
    for (i = 0; i < m; i = j) {
        const gr__plane_t *p;
        const gr_specular_t *sp;
        double frac, x0[3], x1[3], nf[3], wr[3], wt[3], dr[3], dt[3], up[3], down[3], ci, ct, eta, F;
        int tir, thin;
        /* a run of intervals on one facet */
        for (j = i + 1; j < m && iv[j].plane == iv[i].plane; j++) {}
        frac = (iv[j - 1].s1 - iv[i].s0) / 2;
        if (iv[i].plane == -2) continue; /* skipped by the early exit */
        if (iv[i].plane < 0) { /* nothing met: the rays leave */
            esc += frac;
            esc_s += frac * 0.5 * (iv[i].s0 + iv[j - 1].s1);
            continue;
        }
        p = &sc->ls.pl[iv[i].plane];
        gr__facing(sc, iv[i].plane, sh->d, nf); /* toward the side the rays come from */
        if (ind->brdf && !sh->inside) /* direct light: on the outside only */
            for (l = i; l < j; l++)
                for (k = 0; k < q->light_count; k++) {
                    double c[3] = {0, 0, 0}, fl = (iv[l].s1 - iv[l].s0) / 2;
                    int ch;
                    if (!(iv[l].lit & (1u << k))) continue;
                    ind->brdf(ind->brdf_user, p->refl, nf, e, q->lights + 3 * k, k, c);
                    for (ch = 0; ch < 3; ch++) rgb[ch] += sh->thr[ch] * fl * c[ch];
                }
        sp = gr__spec(ind, p->refl);
        if (sh->level >= ind->depth || !sp) continue;
        /* the bounce weights: Fresnel or the constants, thin or solid */
        ci = -gr__dot3(dd, nf);
        eta = sp->ior > 0 ? sp->ior : GR__DEFAULT_IOR;
        eta = sh->inside ? eta : 1 / eta;
        thin = sp->thin != 0;
        F = gr__fresnel(ci, eta, &ct);
        tir = !thin && ct == 0;
        for (k = 0; k < 3; k++) {
            if (sp->fresnel) {
                double R = thin ? 2 * F / (1 + F) : F;
                wr[k] = sp->kr[k] * R;
                wt[k] = tir ? 0 : sp->kt[k] * (1 - R);
            } else {
                wr[k] = sp->kr[k] + (tir ? sp->kt[k] : 0);
                wt[k] = tir ? 0 : sp->kt[k];
            }
            wr[k] *= sh->thr[k] * frac;
            wt[k] *= sh->thr[k] * frac;
            dr[k] = dd[k] + 2 * ci * nf[k];
            dt[k] = thin ? dd[k] : eta * dd[k] + (eta * ci - ct) * nf[k];
            up[k] = off * nf[k];
            down[k] = -off * nf[k];
        }
        gr__sheet_point(sc, sh, iv[i].plane, iv[i].s0, x0);
        gr__sheet_point(sc, sh, iv[i].plane, iv[j - 1].s1, x1);
        if (gr__nonzero3(wr)) gr__push_piece(ind, stack, x0, x1, up, dr, wr, sh->level + 1, sh->inside, rgb);
        if (gr__nonzero3(wt)) {
            if (thin) { /* through the pane, to the host behind it */
                double mid[3];
                for (k = 0; k < 3; k++) mid[k] = 0.5 * (x0[k] + x1[k]) + down[k];
                gr__to_host(ind, mid, dt, sh->level + 1, !sh->inside, wt, 1, rgb);
            } else {
                gr__push_piece(ind, stack, x0, x1, down, dt, wt, sh->level + 1, !sh->inside, rgb);
            }
        }
    }
    if (esc > 0) { /* §6.2: 1 - Σ r_i leaves: up into the scene, or into the bulk */
        double o[3], sm = esc_s / esc;
        for (k = 0; k < 3; k++) o[k] = sh->o[k] + sm * sh->a[k];
        gr__to_host(ind, o, sh->d, sh->level, sh->inside, sh->thr, esc, rgb);
    }
}

GR_DEF gr_result_t gr_shade_indirect(const gr_grid_t *grid, const gr_query_t *query, const gr_indirect_t *indirect,
                                     void *scratch, size_t scratch_bytes, double rgb[3], gr_line_stats_t *stats)
{
    gr__scratch_t s;
    gr__lscene_t sc;
    gr__stack_t stack;
    gr_query_t raised;
    const gr_footprint_t *fp;
    double wfam[2] = {0, 0}, cfam[2][3] = {{0, 0, 0}, {0, 0, 0}}, tol, lights[3 * GR_MAX_LIGHTS];
    int n, j, k, full = 0;
    unsigned approx = 0;
    gr_result_t r;
    if (!indirect || !rgb) return GR_ERR_INVALID_ARG;
    rgb[0] = rgb[1] = rgb[2] = 0;
    if (stats) memset(stats, 0, sizeof *stats);
    if (indirect->depth < 0 || indirect->depth > GR_MAX_DEPTH || indirect->specular_count < 0 ||
        (indirect->specular_count > 0 && !indirect->specular))
        return GR_ERR_INVALID_ARG;
    r = gr__line_check(grid, query, scratch, scratch_bytes);
    if (r != GR_OK) return r;
    gr__region_query(grid, query, 0, &raised, lights); /* the bounces' origins go to the host */
    query = &raised;
    fp = &query->footprint;
    if (!(fp->view[2] > 0)) return GR_OK;
    n = query->line_samples ? query->line_samples : 2;
    tol = gr__exit_tol(query);
    gr__line_layout(grid, scratch, &s, &sc);
    stack.s = sc.ls.stack;
    for (j = 0; j < n; j++) {
        double cj[3] = {0, 0, 0}, wj = 0, wa;
        int fam;
        stack.top = 1;
        stack.full = 0;
        wa = gr__top_sheet(grid, query, j, n, &stack.s[0], &fam);
        while (stack.top > 0) {
            gr__sheet_t sh = stack.s[--stack.top];
            double w, cl;
            int m, nl = sh.inside ? 0 : query->light_count; /* no direct light inside the material */
            gr__line_scene(grid, &s, &sc, &sh, 1, NULL, query->lights, nl);
            /* the early exit (§5.6) would leave unclassified gaps, which
               here would read as light leaving: bounces classify all */
            m = gr__sheet_eval(&sc, &sh, query->lights, nl, sh.level ? -1 : tol, &w, &cl, stats);
            approx |= sc.flags & GR_LIST_LINE_APPROX;
            if (sh.level == 0) {
                wj = w;
                if (stats && j < GR_LINE_MAX_SAMPLES) stats->weight[j] = w;
                if (cl > 0 && cl < 1) /* share the unclassified rest in proportion */
                    for (k = 0; k < 3; k++) sh.thr[k] /= cl;
            }
            gr__bounce(&sc, &sh, m, query, indirect, &stack, cj);
        }
        full |= stack.full;
        wfam[fam] += wa * wj; /* families combined as in gr_query_lines() */
        for (k = 0; k < 3; k++) cfam[fam][k] += wa * cj[k];
    }
    {
        int nfam = n > 1 ? 2 : 1, f;
        double wsum = wfam[0] + wfam[1];
        for (f = 0; f < nfam; f++) {
            double wf = wsum > 0 ? wfam[f] / wsum : 1.0 / nfam;
            for (k = 0; k < 3; k++) rgb[k] += wf * cfam[f][k];
        }
    }
    if (stats) stats->flags = (approx ? GR_STATS_LINE_APPROX : 0u) | (full ? GR_STATS_STACK_FULL : 0u);
    return full ? GR_ERR_STACK_FULL : GR_OK;
}
#endif
/* ==== [end section: interreflection] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_GR_IMPLEMENTATION_DONE */
#endif /* GR_IMPLEMENTATION */

/*
MIT License

Copyright (c) 2026 the filigree authors

Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
*/
