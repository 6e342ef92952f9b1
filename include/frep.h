/* frep.h — FRep solids and ray-surface root finding (part of filigree)

   Function-representation solids f(x) >= 0: primitives, R-functions, blends and
   space maps as an instruction tape, evaluated in points, intervals, affine
   forms and gradients; ray-surface intersection and polynomial solvers.

   USAGE
     In exactly one C or C++ file:
         #define FR_IMPLEMENTATION
         #include "frep.h"
     Everywhere else just #include "frep.h".
     With interval evaluation (the default) define IV_IMPLEMENTATION in one
     file too, or include interval.h there with it.
   OPTIONS (define before including)
     FR_IMPLEMENTATION  emit the implementation in this translation unit
     FR_STATIC          make every function static (private to this file)
     FR_DEF             linkage of public functions (default extern)
     FR_ASSERT(c)       internal-invariant check (default assert)
     FR_MALLOC(sz,ctx) / FR_FREE(p,ctx)   allocator hooks (default malloc/free)
     FR_NO_INTERVAL      leave out interval/affine evaluation (no interval.h)
     FR_NO_PARSER        leave out the HyperFun-subset text front end
   CONVENTIONS
     See docs/conventions.md: results are fr_result_t codes with FR_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.
   THE MODEL (docs/frep.md, "Model")
     f >= 0 inside, 0 on the surface (paper section 3). Build a model with
     fr_builder_* and the primitive/operation functions, or fr_parse() a
     HyperFun subset; both give one fr_tape_t, which fr_eval, fr_eval_batch,
     fr_eval_grad (exact, forward-mode AD), fr_eval_interval and
     fr_eval_affine evaluate with caller scratch of fr_scratch_size() bytes,
     and fr_prune / fr_prune_ex shorten for a box. Interval and affine
     results enclose f over their inputs (rigorous with interval.h's default
     rounding); a model whose black-box callback has no interval function
     says so (FR_ERR_NO_INTERVAL) instead of guessing. The entry points
     whose answers rest on exact rounding (interval and affine evaluation,
     pruning, fr_bound_box, fr_prepare, fr_trace, fr_solve_poly) run in
     round to nearest with gradual underflow whatever the host set (x86
     flush-to-zero and denormals-are-zero, which Embree recommends, or
     another rounding mode) and restore the host's environment after
     (interval.h's iv_fp_env_enter; docs/frep.md "Floating-point
     environment").
   RAYS (docs/frep.md, "Polynomial solvers and ray intersection")
     fr_trace finds the first root of f(o + t d) by the analytic, stepping,
     interval-bisection or sphere-tracing method; fr_bound_box gives a box
     around the solid for fr_trace_desc_t.bounds, fr_prepare a prepared
     model for fr_trace_desc_t.prepared (per-model work done once: quadric
     CSG leaves in monomial form, the CSG sign tree, leaf and node boxes,
     fixed-degree Taylor programs), and the any_hit, footprint and
     interval_newton options serve renderers.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_FR_H
#define FILIGREE_FR_H

#include <stddef.h>
#include <math.h>
#ifndef FR_NO_INTERVAL
#include "interval.h"
#endif
#ifndef FR_DEF
#  ifdef FR_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define FR_DEF static __attribute__((unused))
#    else
#      define FR_DEF static
#    endif
#  else
#    define FR_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. FR_OK is 0; fr_result_string() names each. */
typedef enum fr_result_t {
    FR_OK = 0,
    FR_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    FR_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    FR_ERR_LIMIT,         /* a model exceeds a documented size limit */
    FR_ERR_NO_INTERVAL,   /* a callback has no interval function */
    FR_ERR_NO_GRADIENT,   /* a callback has no gradient function */
    FR_ERR_BUFFER_TOO_SMALL, /* a caller buffer is smaller than required */
    FR_ERR_PARSE,         /* model text rejected (see fr_diag_t line:column) */
    FR_ERR_NOT_POLYNOMIAL, /* the tape is not a polynomial in the ray parameter */
    FR_ERR_NO_LIPSCHITZ,  /* sphere tracing needs a finite Lipschitz bound */
    FR_ERR_ITERATIONS,    /* fr_trace: max_iters ran out before the segment was decided */
    FR_RESULT_COUNT_
} fr_result_t;

/* A human-readable name for a result code; never NULL. */
FR_DEF const char *fr_result_string(fr_result_t r);

/* ==== [section: model] declarations: tape, primitives, operations, evaluation, parser ==== */
/* ---------------------------------------------------------------- model --
   SIGN CONVENTION (FRep, paper section 3 "Function representation")
     f(p) >= 0 inside the solid, f(p) = 0 on its surface, f(p) < 0 outside.
     A signed-distance function d (negative inside) enters a model through
     fr_from_sdf(), which negates it and records its Lipschitz bound.

   THE TAPE
     A model is a flat array of instructions (fr_instr_t) in evaluation order,
     in static single assignment form: instruction i writes slot i, and reads
     only slots j < i through its operands a, b, c. There are no other
     registers. Constants live in the instruction itself (field k); the four
     parameters of each gradient-noise instruction live in tape->params at
     index aux; black-box callbacks live in tape->callbacks at index aux.
     tape->outputs[0] is the shape slot, outputs[1..n_outputs-1] are
     attribute (colour) slots evaluated with it.

     op            reads        meaning of the slot value
     CONST         -            k
     VAR_X/Y/Z     -            the point's x / y / z
     NEG SQR SQRT  a            -a, a*a, sqrt(a)
     ABS EXP LOG   a            |a|, e^a, ln a
     SIN COS ATAN  a            sin a, cos a, atan a
     POWI          a            a^k, k a small integer (stored as double)
     POWC          a            a^k for a >= 0, k a real constant (pow)
     ADD SUB MUL   a b          a+b, a-b, a*b
     DIV MIN MAX   a b          a/b, min, max
     RUNI          a b          R-union  a+b+sqrt(a^2+b^2-2 k a b), k = alpha;
                                max(a,b) when k == 1 (HyperFun's rule)
     RINT          a b          R-intersection a+b-sqrt(...); min when k == 1
     SMAX SMIN     a b          polynomial smooth max / min of width k > 0
     NOISE         a b c        params[aux..aux+4] = amp, freq, ox, oy, oz:
                                amp * gnoise(freq*(a,b,c) + (ox,oy,oz))
     CALL          a b c        callbacks[aux].point((a,b,c))
   Every evaluator walks the same array; a new evaluator needs only a switch
   over these opcodes. The set is closed: the builder lowers primitives and
   operations into it (a sphere is SUBs, SQRs, ADDs), so pruning, interval and
   Taylor evaluators see elementary operations only.
*/

/* A handle to a node (= a tape slot) while building. */
typedef unsigned int fr_node_t;
#define FR_NODE_NONE 0xFFFFFFFFu

/* A point as three nodes: the coordinates after any space maps. */
typedef struct fr_p3_t {
    fr_node_t x, y, z;
} fr_p3_t;

typedef enum fr_op_t {
    FR_OP_CONST = 0,
    FR_OP_VAR_X, FR_OP_VAR_Y, FR_OP_VAR_Z,
    FR_OP_NEG, FR_OP_SQR, FR_OP_SQRT, FR_OP_ABS, FR_OP_EXP, FR_OP_LOG,
    FR_OP_SIN, FR_OP_COS, FR_OP_ATAN, FR_OP_POWI, FR_OP_POWC,
    FR_OP_ADD, FR_OP_SUB, FR_OP_MUL, FR_OP_DIV, FR_OP_MIN, FR_OP_MAX,
    FR_OP_RUNI, FR_OP_RINT, FR_OP_SMAX, FR_OP_SMIN,
    FR_OP_NOISE, FR_OP_CALL,
    FR_OP_COUNT_
} fr_op_t;

/* One instruction: 32 bytes. Unused operands are 0. */
typedef struct fr_instr_t {
    unsigned int op;      /* fr_op_t */
    unsigned int a, b, c; /* operand slots, each < this instruction's index */
    unsigned int aux;     /* NOISE: index into params; CALL: callback index */
    double k;             /* CONST value, alpha, exponent or smoothing width */
} fr_instr_t;

#define FR_MAX_OUTPUTS 8   /* shape + up to 7 attributes */
#define FR_NOISE_PARAMS 5  /* amp, freq, ox, oy, oz per NOISE instruction */

/* Tape flags. */
#define FR_TAPE_NO_INTERVAL 1u /* a callback lacks an interval function */
#define FR_TAPE_NO_GRADIENT 2u /* a callback lacks a gradient function */
#define FR_TAPE_SIGN_ONLY   4u /* pruned with sign-preserving replacements:
                                  the sign matches the full tape, the value
                                  need not */

/* A black-box primitive. point is required; interval and grad are optional
   and open the interval/affine and gradient paths for this tape. */
typedef struct fr_callback_t {
    double (*point)(const double p[3], void *user);
    /* value and gradient at p; may be NULL */
    double (*grad)(const double p[3], void *user, double g[3]);
#ifndef FR_NO_INTERVAL
    /* an enclosure of f over the box; may be NULL */
    iv_t (*interval)(const iv_t box[3], void *user);
#endif
    void *user;
} fr_callback_t;

/* A finished model. Read-only once built: any number of threads may
   evaluate one tape at once, each with its own scratch. */
typedef struct fr_tape_t {
    const fr_instr_t *code;
    unsigned int n_code;
    const double *params;            /* NOISE parameters */
    unsigned int n_params;
    const fr_callback_t *callbacks;
    unsigned int n_callbacks;
    unsigned int outputs[FR_MAX_OUTPUTS]; /* [0] shape, then attributes */
    unsigned int n_outputs;
    unsigned int flags;              /* FR_TAPE_* */
    double lipschitz;                /* |grad f| <= lipschitz everywhere
                                        (a distance bound when <= 1);
                                        INFINITY when unknown */
    void *alloc_ctx;                 /* for fr_tape_free */
    void *owned;                     /* NULL for tapes in caller buffers */
} fr_tape_t;

/* A diagnostic for rejected input. element is the node index for builder
   errors; line and column (1-based) locate parser errors, 0 otherwise. */
typedef struct fr_diag_t {
    fr_result_t result;
    long long element;
    int line, column;
    char message[160];
} fr_diag_t;

/* Builder options; zero means defaults. */
typedef struct fr_builder_desc_t {
    void *alloc_ctx;        /* passed to FR_MALLOC / FR_FREE */
    unsigned int max_nodes; /* 0: 1<<24. Building more fails with
                               FR_ERR_LIMIT */
} fr_builder_desc_t;

/* The builder: grows a tape node by node. Every node function returns
   FR_NODE_NONE once an error has occurred (the error is sticky and is
   reported by fr_builder_finish), so expressions can be nested freely. */
typedef struct fr_builder_t {
    fr_instr_t *code;
    double *lip;            /* per node: declared Lipschitz bound, 0 = none */
    double *params;
    fr_callback_t *callbacks;
    unsigned int n, cap, n_params, cap_params, n_callbacks, cap_callbacks;
    unsigned int max_nodes;
    fr_node_t var[3];
    void *alloc_ctx;
    fr_diag_t diag;         /* the first error */
} fr_builder_t;

FR_DEF fr_result_t fr_builder_init(fr_builder_t *b, const fr_builder_desc_t *desc);
FR_DEF void fr_builder_free(fr_builder_t *b);
/* Compile the nodes reachable from shape (and attrs) into *out, dropping
   the rest. *out owns its memory: release it with fr_tape_free. */
FR_DEF fr_result_t fr_builder_finish(fr_builder_t *b, fr_node_t shape, const fr_node_t *attrs,
                                     unsigned int n_attrs, fr_tape_t *out, fr_diag_t *diag);
FR_DEF void fr_tape_free(fr_tape_t *t);

/* ---- elementary nodes */
FR_DEF fr_p3_t fr_coords(fr_builder_t *b);
FR_DEF fr_node_t fr_const(fr_builder_t *b, double v);
FR_DEF fr_node_t fr_unary(fr_builder_t *b, fr_op_t op, fr_node_t a);
FR_DEF fr_node_t fr_binary(fr_builder_t *b, fr_op_t op, fr_node_t a, fr_node_t c);
FR_DEF fr_node_t fr_powi(fr_builder_t *b, fr_node_t a, int n);
FR_DEF fr_node_t fr_powc(fr_builder_t *b, fr_node_t a, double e);
FR_DEF fr_node_t fr_add(fr_builder_t *b, fr_node_t a, fr_node_t c);
FR_DEF fr_node_t fr_sub(fr_builder_t *b, fr_node_t a, fr_node_t c);
FR_DEF fr_node_t fr_mul(fr_builder_t *b, fr_node_t a, fr_node_t c);
FR_DEF fr_node_t fr_div(fr_builder_t *b, fr_node_t a, fr_node_t c);

/* ---- primitives (HyperFun's library forms; f >= 0 inside) */
/* r^2 - |p-c|^2 (hfSphere) */
FR_DEF fr_node_t fr_sphere(fr_builder_t *b, fr_p3_t p, const double c[3], double r);
/* 1 - (dx/a)^2 - (dy/b)^2 - (dz/c)^2 (hfEllipsoid) */
FR_DEF fr_node_t fr_ellipsoid(fr_builder_t *b, fr_p3_t p, const double c[3], double ra, double rb, double rc);
/* slabs (x-v)(v+d-x) intersected with R-functions of alpha (hfBlock) */
FR_DEF fr_node_t fr_block(fr_builder_t *b, fr_p3_t p, const double vertex[3], const double size[3], double alpha);
/* axis 0,1,2 = x,y,z: r^2 - (off-axis distance)^2 (hfCylinderX/Y/Z) */
FR_DEF fr_node_t fr_cylinder(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double r);
/* 1 - (u/ra)^2 - (v/rb)^2, (u,v) the off-axis offsets in x,y,z order (hfEllCylX/Y/Z) */
FR_DEF fr_node_t fr_ell_cylinder(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double ra, double rb);
/* any axis through point q with direction dir (need not be unit) */
FR_DEF fr_node_t fr_cylinder_axis(fr_builder_t *b, fr_p3_t p, const double q[3], const double dir[3], double r);
/* (along-axis offset)^2 - (off-axis distance / r)^2: double cone of radius r at unit height (hfConeX/Y/Z) */
FR_DEF fr_node_t fr_cone(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double r);
/* r0^2 - |p-c|^2 - R^2 + 2 R rho, rho the distance to the axis (hfTorusX/Y/Z) */
FR_DEF fr_node_t fr_torus(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double R, double r0);
/* the half-space n.p <= d (its boundary is the plane n.p = d): d - n.p */
FR_DEF fr_node_t fr_halfspace(fr_builder_t *b, fr_p3_t p, const double n[3], double d);
/* 1 - (|x'|^(2/s2) + |y'|^(2/s2))^(s2/s1) - |z'|^(2/s1), x' = (x-cx)/a ... (hfSuperell) */
FR_DEF fr_node_t fr_superellipsoid(fr_builder_t *b, fr_p3_t p, const double c[3], const double abc[3],
                                   double s1, double s2);

/* Skeletal primitives: sum over elements of weight * kernel(r) - threshold,
   r the distance to a point (a == b) or to the segment ab. */
typedef enum fr_kernel_t {
    FR_KERNEL_BLOBBY,   /* Blinn: weight * exp(-width * r^2) (hfBlobby: b, a) */
    FR_KERNEL_METABALL, /* Nishimura: weight * (1 - 3q^2) for q = r/width <= 1/3,
                           weight * 1.5 (1-q)^2 for q <= 1, else 0 */
    FR_KERNEL_SOFT      /* Wyvill: weight * (1 - 22s/9 + 17s^2/9 - 4s^3/9),
                           s = r^2/width^2 <= 1, else 0 (hfSoft) */
} fr_kernel_t;
typedef struct fr_skeleton_t {
    double a[3], b[3]; /* a point when a == b, else the segment ab */
    double width;      /* kernel width (see fr_kernel_t), > 0 */
    double weight;     /* kernel weight */
} fr_skeleton_t;
FR_DEF fr_node_t fr_skeletal(fr_builder_t *b, fr_p3_t p, fr_kernel_t kernel, const fr_skeleton_t *el,
                             unsigned int n, double threshold);
/* Convolution surface: sum of weight * integral over the segment of the
   Cauchy kernel 1/(1+width^2 r^2)^2 (closed form), minus threshold. */
FR_DEF fr_node_t fr_convolution(fr_builder_t *b, fr_p3_t p, const fr_skeleton_t *segments,
                                unsigned int n, double threshold);
/* Gradient noise amp * g(freq * p + offset) with |g| <= 2 and
   |g(u)-g(v)| <= 8.5 |u-v|_1, so interval evaluation stays rigorous. */
FR_DEF fr_node_t fr_noise(fr_builder_t *b, fr_p3_t p, double amp, double freq, const double offset[3]);
/* HyperFun's hfNoiseG (Gardner series), |value| <= (1.855 amp)^3. */
FR_DEF fr_node_t fr_noise_gardner(fr_builder_t *b, fr_p3_t p, double amp, double freq, double phase);
/* A black-box primitive; *cb is copied. */
FR_DEF fr_node_t fr_callback(fr_builder_t *b, fr_p3_t p, const fr_callback_t *cb);
/* Wrap a signed distance (negative inside): returns -sdf and records that
   the result's gradient is bounded by lipschitz (1 for an exact SDF). */
FR_DEF fr_node_t fr_from_sdf(fr_builder_t *b, fr_node_t sdf, double lipschitz);

/* ---- operations */
/* R-functions with HyperFun's alpha in [0,1]: f1+f2 +- sqrt(f1^2+f2^2-2 alpha f1 f2),
   min/max for alpha == 1. difference = f1 & ~f2, negation = -f. */
FR_DEF fr_node_t fr_union(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double alpha);
FR_DEF fr_node_t fr_intersect(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double alpha);
FR_DEF fr_node_t fr_subtract(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double alpha);
FR_DEF fr_node_t fr_negate(fr_builder_t *b, fr_node_t f);
/* R-union/intersection (alpha 0) + a0 / (1 + (f1/a1)^2 + (f2/a2)^2) (hfBlendUni/Int) */
FR_DEF fr_node_t fr_blend_union(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double a0, double a1, double a2);
FR_DEF fr_node_t fr_blend_intersect(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double a0, double a1, double a2);
/* polynomial smooth max (union) / min (intersection) of width k > 0:
   equal to max/min where |f1-f2| >= k */
FR_DEF fr_node_t fr_smooth_union(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double k);
FR_DEF fr_node_t fr_smooth_intersect(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double k);
/* f + d: grows the solid for d > 0 (by d when f is a distance) */
FR_DEF fr_node_t fr_offset(fr_builder_t *b, fr_node_t f, double d);
/* metamorphosis (1-t) f1 + t f2 */
FR_DEF fr_node_t fr_morph(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double t);

/* ---- space maps: each returns the inverse-mapped point that primitives
   are then evaluated at (HyperFun's convention), so the solid moves forward */
FR_DEF fr_p3_t fr_translate(fr_builder_t *b, fr_p3_t p, const double d[3]);   /* hfShift3D */
FR_DEF fr_p3_t fr_scale(fr_builder_t *b, fr_p3_t p, const double s[3]);       /* hfScale3D */
FR_DEF fr_p3_t fr_rotate(fr_builder_t *b, fr_p3_t p, int axis, double theta); /* hfRotate3DX/Y/Z */
/* p' = m p + t with m row-major 3x3: the inverse of the wanted transform */
FR_DEF fr_p3_t fr_affine(fr_builder_t *b, fr_p3_t p, const double m[9], const double t[3]);
/* rotation about axis by theta(s), theta linear from th1 at s1 to th2 at s2 (hfTwistX/Y/Z) */
FR_DEF fr_p3_t fr_twist(fr_builder_t *b, fr_p3_t p, int axis, double s1, double s2, double th1, double th2);
/* off-axis coordinates divided by a scale that goes from sc1 at s1 to sc2 at
   s2, constant outside (hfTaperX/Y/Z); sc1, sc2 > 0 */
FR_DEF fr_p3_t fr_taper(fr_builder_t *b, fr_p3_t p, int axis, double s1, double s2, double sc1, double sc2);
/* c + (p - c) / s per axis (hfStretch3D) */
FR_DEF fr_p3_t fr_stretch(fr_builder_t *b, fr_p3_t p, const double c[3], const double s[3]);
/* bend: rotate the plane normal to axis by the angle k * (coordinate along
   the next axis), axis 2 bends x into y by k*x */
FR_DEF fr_p3_t fr_bend(fr_builder_t *b, fr_p3_t p, int axis, double k);

/* ---- evaluation. Scratch: a caller buffer of fr_scratch_size() bytes,
   aligned for double (malloc is fine), one per thread. */
typedef enum fr_eval_kind_t {
    FR_EVAL_POINT, FR_EVAL_BATCH, FR_EVAL_GRAD, FR_EVAL_INTERVAL, FR_EVAL_AFFINE, FR_EVAL_PRUNE
} fr_eval_kind_t;
#define FR_BATCH 32 /* points per inner batch */
FR_DEF size_t fr_scratch_size(const fr_tape_t *t, fr_eval_kind_t kind);
/* f(p) (shape). */
FR_DEF double fr_eval(const fr_tape_t *t, const double p[3], void *scratch);
/* all outputs: out[0] shape, out[1..] attributes (n_outputs values). */
FR_DEF void fr_eval_outputs(const fr_tape_t *t, const double p[3], void *scratch, double *out);
/* out[i] = f(x[i], y[i], z[i]) for i < n. */
FR_DEF void fr_eval_batch(const fr_tape_t *t, size_t n, const double *x, const double *y, const double *z,
                          double *out, void *scratch);
/* value and exact gradient (forward-mode AD). FR_ERR_NO_GRADIENT when a
   callback has no gradient function. At a kink (min/max/abs of equal
   arguments) the gradient of one side is returned; where the derivative
   is infinite (sqrt at 0, POWC with exponent < 1 at 0) it is inf or NaN. */
FR_DEF fr_result_t fr_eval_grad(const fr_tape_t *t, const double p[3], void *scratch, double *value,
                                double grad[3]);

#ifndef FR_NO_INTERVAL
/* An enclosure of f over the box (rigorous unless interval.h is built with
   IV_FAST). FR_ERR_NO_INTERVAL when a callback has no interval function. */
FR_DEF fr_result_t fr_eval_interval(const fr_tape_t *t, const iv_t box[3], void *scratch, iv_t *out);
#ifndef IV_NO_AFFINE
/* An affine enclosure of f for affine inputs, e.g. x(t) = o.x + t d.x with
   t from iv_affine_ray_param(t0, t1), so the result stays correlated with t. */
FR_DEF fr_result_t fr_eval_affine(const fr_tape_t *t, const iv_affine_t p[3], void *scratch, iv_affine_t *out);
#endif
/* Tape pruning (libfive; Keeter 2020): a shorter tape valid inside box.
   Choice nodes whose interval decides them on the box are replaced by the
   operand they take: min/max, alpha = 1 R-functions and smooth min/max
   keep the value exactly; an alpha < 1 R-function whose other operand has a
   fixed sign is replaced by the deciding operand, which keeps the sign only
   (FR_TAPE_SIGN_ONLY is then set), and only where the result reaches the
   shape through sign-preserving operations (negation, min/max, R-functions).
   The result lives in code_buf (cap >= t->n_code instructions) and shares
   params and callbacks with t: do not free it, keep t alive. Attribute
   outputs are dropped. *range (optional) receives f's enclosure on box.
   Allocation-free; scratch of fr_scratch_size(t, FR_EVAL_PRUNE) bytes.
   fr_prune is fr_prune_ex with FR_PRUNE_DEFAULT. */
FR_DEF fr_result_t fr_prune(const fr_tape_t *t, const iv_t box[3], void *scratch, fr_instr_t *code_buf,
                            unsigned int cap, fr_tape_t *out, iv_t *range);
typedef enum fr_prune_mode_t {
    FR_PRUNE_DEFAULT = 0, /* as fr_prune: exact min/max, sign-only alpha < 1 R-functions */
    FR_PRUNE_EXACT,       /* value-exact replacements only: the result keeps the
                             value and the Lipschitz bound (for sphere tracing) */
    FR_PRUNE_SIGN         /* also drop a min/max operand whose sign alone settles
                             the result's sign (a union operand < 0 on the box):
                             shortest tapes, for sign-based root isolation */
} fr_prune_mode_t;
FR_DEF fr_result_t fr_prune_ex(const fr_tape_t *t, const iv_t box[3], fr_prune_mode_t mode, void *scratch,
                               fr_instr_t *code_buf, unsigned int cap, fr_tape_t *out, iv_t *range);
#endif


#ifndef FR_NO_PARSER
/* ---- the HyperFun-subset text front end

     my_model(x[3], a[2], s[3]) {          -- coordinates, parameters, attributes
         array c[3], xt[3];                 -- arrays are declared
         c = [0, 0, 0.5];  xt = x;          -- literals and copies
         hfShift3D(xt, a[1], 0, 0);         -- space maps change xt in place
         r = hfSphere(xt, c, 1) | hfCylinderZ(x, c, 0.3) \ hfBlock(x, c, 1, 1, 1);
         s[1] = abs(x[1]);                  -- attribute outputs
         my_model = r & ~(0.5 - x[3]^2);
     }
   Scalars need no declaration; indices are 1-based constants. Operators,
   loosest first: | & \ (R-union, intersection, difference, alpha from
   fr_parse_desc_t), + -, * /, unary - and ~ (negation), ^ (right
   associative). Functions: sqrt exp log sin cos atan abs and the library
   calls hfSphere hfEllipsoid hfBlock hfCylinderX/Y/Z hfConeX/Y/Z
   hfTorusX/Y/Z hfSuperEll (also hfSuperell) hfBlobby hfSoft hfNoiseG
   hfBlendUni hfBlendInt hfShift3D hfScale3D hfRotate3DX/Y/Z hfTwistX/Y/Z
   hfTaperX/Y/Z hfStretch3D, with HyperFun's argument orders. Comments:
   -- or // to the end of the line, and block comments. Constant
   subexpressions are folded. Numbers read as strtod reads them in the "C"
   locale, whatever LC_NUMERIC the host set (a decimal comma changes
   nothing). */
typedef struct fr_parse_desc_t {
    void *alloc_ctx;        /* passed to FR_MALLOC / FR_FREE */
    const double *params;   /* values of the model's second array (a[]); missing ones are 0 */
    unsigned int n_params;
    double alpha;           /* alpha of | & \ (HyperFun's ALPHA): default 0,
                               1 gives min/max; must be in [0, 1] */
    unsigned int max_nodes; /* 0: 1<<20 */
} fr_parse_desc_t;

/* Parse len bytes of text into *out (free with fr_tape_free). On error
   returns FR_ERR_PARSE (or FR_ERR_LIMIT / FR_ERR_OUT_OF_MEMORY, or
   FR_ERR_INVALID_ARG for a call parameter out of range, hfSphere(x, c, -1))
   and fills diag with line:column and a message. Never reads past text +
   len. */
FR_DEF fr_result_t fr_parse(const char *text, size_t len, const fr_parse_desc_t *desc, fr_tape_t *out,
                            fr_diag_t *diag);
#endif

/* ==== [end section: model] ==== */

/* ==== [section: solvers] declarations: polynomial solvers ==== */

/* Real roots of polynomials, for analytic ray intersection (paper §3.1.1, §4.1.2).

   Coefficients are in increasing degree: c[0] + c[1] t + ... + c[n] t^n.
   Real roots come back in ascending order in r, and the count is returned;
   r must have room for `degree` doubles (2, 3, 4 for the fixed-degree forms).
   A multiple root (or two roots closer than the precision can separate) is
   returned once. Leading zero coefficients lower the degree; exact zero
   roots are split off first. A polynomial that is identically zero has no
   isolated roots: 0 is returned. Invalid input -- a NULL pointer, a degree
   outside [0, FR_POLY_MAX_DEGREE], a non-finite coefficient, t0 > t1 or a
   NaN bound -- returns -1.

   Guarantee (measured in tests/test_frep_solve.c and docs/benchmarks.md):
   every returned root is within a few ulps of a true root of the polynomial
   whose coefficients are the given doubles, unless the roots are so close
   that double-double evaluation cannot separate them (then it is within
   about 1e-16 relative of the cluster). Method: derivative-sequence
   isolation (the roots of p' cut p into monotone pieces, recursively), a
   safeguarded Newton iteration in each piece, and a final Newton polish
   whose residual comes from compensated Horner evaluation (Graillat,
   Langlois & Louvet 2005), so roots are found as if the polynomial were
   evaluated in twice the working precision. Coefficients are rescaled by
   powers of two only (exact), so scales from 1e-300 to 1e300 behave alike.
   Quadratics, cubics and quartics first try closed-form estimates that must
   certify themselves (the discriminant's sign with an error bound fixes the
   number of distinct real roots; each estimate must converge under a
   compensated third-order polish; all must be distinct), which is 6-28x
   faster than gsl_poly_complex_solve on random quartics; cubics and
   quartics whose roots are spread so far that the coefficients' Newton
   polygon splits them into groups are solved group by group, every root
   certified by a sign change; anything uncertain takes the general path
   above, with its breakpoints from the fast path on the highest
   derivative that certifies. */

#define FR_POLY_MAX_DEGREE 16 /* at most 16: fr__ceil_div has a table per divisor */

FR_DEF int fr_solve_quadratic(const double c[3], double r[2]);
FR_DEF int fr_solve_cubic(const double c[4], double r[3]);
FR_DEF int fr_solve_quartic(const double c[5], double r[4]);
/* Roots in [t0, t1] only (either bound may be infinite); degree <= FR_POLY_MAX_DEGREE. */
FR_DEF int fr_solve_poly(const double *c, int degree, double t0, double t1, double *r);

/* p(t) by compensated Horner evaluation: as accurate as Horner in twice the
   working precision, then rounded. If abs_bound is not NULL it receives
   sum |c_i| |t|^i, which scales the remaining error: the result differs
   from the exact value by at most u |p(t)| + 4 n^2 u^2 abs_bound, u = 2^-53. */
FR_DEF double fr_poly_eval_compensated(const double *c, int degree, double t, double *abs_bound);

/* ==== [end section: solvers] ==== */

/* ==== [section: trace] declarations: ray-surface intersection ==== */

/* Ray-surface intersection (paper §3.1, §4.1). The ray is o + t d for t in
   [t0, t1]; t is in the units of the caller's d. The hit is the first root of
   g(t) = f(o + t d) in the segment: where the ray enters or leaves the solid
   (or touches it). Five methods trade accuracy for speed
   (docs/frep.md "Polynomial solvers and ray intersection"):

   FR_METHOD_ANALYTIC  the paper's §3.1.1 / §4.1.2: if the whole tape is a
       polynomial in t, its coefficients (fr_ray_poly) go to fr_solve_poly;
       otherwise every polynomial leaf under min/max/R-function nodes is
       solved, the leaf roots are sorted, and the first one where f changes
       sign is the hit (CSG of polynomial primitives). The sign change is
       found without evaluating f near the root: each leaf's crossings
       (roots where its sign changes, from the signs between its roots) flip
       that leaf's sign in the CSG tree, so grazing rays keep their entry.
   FR_METHOD_STEP      §3.1.3 / §4.1.1: march to the first sign change with a
       fixed step, or with steps |g| / (L |d|) from the Lipschitz bound L;
       then Illinois regula falsi (default), Newton or Brent, each with a
       bisection fallback. May miss features thinner than the step.
   FR_METHOD_INTERVAL  §3.1.2 / §4.1.3: interval bisection on t with an
       explicit stack, affine forms (reduced affine arithmetic, Knoll et al.
       2009) or plain intervals, and the tape pruned per segment. Never
       misses a root: the hit is the leftmost segment of width <= tol whose
       enclosure contains 0 (a near miss closer than the enclosure width may
       be reported as a touch). On a polynomial tape a segment where the
       enclosure of g' excludes 0 holds at most one root: with a sign change
       it goes to regula falsi (to tol, bracketed), without one it is
       dropped once its ends' enclosures share a strict sign.
   FR_METHOD_SPHERE    sphere tracing for distance bounds (Hart 1996) with
       Keinert et al. 2014's over-relaxation as an option. Needs a finite
       Lipschitz bound (tape->lipschitz or desc->lipschitz).
   FR_METHOD_AUTO (0)  ANALYTIC when the tape is polynomial of degree <=
       FR_POLY_MAX_DEGREE, else INTERVAL when the tape allows it, else STEP. */

typedef enum fr_method_t {
    FR_METHOD_AUTO = 0,
    FR_METHOD_ANALYTIC,
    FR_METHOD_STEP,
    FR_METHOD_INTERVAL,
    FR_METHOD_SPHERE,
    FR_METHOD_COUNT_
} fr_method_t;

typedef enum fr_refine_t {
    FR_REFINE_ILLINOIS = 0, /* regula falsi, Illinois variant (Dowell & Jarratt 1971) */
    FR_REFINE_NEWTON,       /* Newton on g' = grad f . d (AD), safeguarded */
    FR_REFINE_BRENT,        /* Brent 1973, zeroin */
    FR_REFINE_BISECT        /* plain bisection */
} fr_refine_t;

typedef enum fr_normal_mode_t {
    FR_NORMAL_AD = 0, /* exact gradient by forward-mode AD (fr_eval_grad) */
    FR_NORMAL_FD,     /* central finite differences (black boxes without gradients) */
    FR_NORMAL_NONE    /* skip the normal */
} fr_normal_mode_t;

struct fr_prepared_t; /* fr_prepare, below */

/* Method and parameters; zero means the documented default. */
typedef struct fr_trace_desc_t {
    fr_method_t method;
    /* the t tolerance of STEP, INTERVAL and SPHERE: a root is located within
       tol (absolute, t units). SPHERE stops where the surface is within a
       distance tol of the point, then looks up to 126 tol ahead for the
       sign change and refines it (any ray steeper than 0.45 degrees to the
       surface); a ray that comes within tol and turns away (grazing)
       crosses nowhere and is a hit at its stop with t_err = tol as a
       distance. 0: 1e-9 * (t1 - t0) for finite segments,
       otherwise 1e-9 * (1 + |t0|) (|t1| when t0 is infinite, 0 when both
       are). Negative asks for the limit of doubles: a few ulps of the
       finite ends. */
    double tol;
    /* STEP: the step length in t units. 0: the step comes from the
       Lipschitz bound, |g(t)| / (L |d|), never below tol; with no finite
       bound, (t1 - t0) / 256. */
    double step;
    fr_refine_t refine;       /* STEP: the refinement (default Illinois) */
    double lipschitz;         /* |grad f| bound; 0: tape->lipschitz */
    double over_relax;        /* SPHERE: Keinert's omega in [1, 2); 0: 1.6. 1 turns it off */
    int plain_intervals;      /* INTERVAL: 1 uses intervals, 0 (default) affine forms */
    int no_prune;             /* INTERVAL: 1 keeps the full tape on every segment */
    /* INTERVAL: on a tape that is a polynomial in t (tangle cube, Barth's
       sextic without its clip), segments are bounded by the centred form of
       the ray polynomial, computed once per ray, instead of the tape in
       affine forms: tighter and about 20x cheaper. 1 turns that off (affine
       forms, as with a non-polynomial tape). plain_intervals also does. */
    int no_poly_range;
    /* INTERVAL on a polynomial tape (with the centred form above): 1 adds
       an interval Newton step (Moore 1966) before each bisection: with an
       enclosure G' of g' free of 0, the segment is narrowed to its meet
       with m - g(m) / G', or dropped when they do not meet. Rigorous like
       the bisection (no root is lost); ignored on other tapes (no interval
       derivative there). Default 0. Where G' excludes 0 the default
       monotone hand-over (FR_METHOD_INTERVAL above) already decides the
       segment, so Newton only acts on the segments that leaves open. */
    int interval_newton;
    unsigned int max_iters;   /* iteration cap of every loop; 0: 100000. STEP,
                                 INTERVAL and SPHERE stopped by it with part of
                                 the segment undecided: FR_ERR_ITERATIONS */
    fr_normal_mode_t normal;  /* default AD */
    double fd_step;           /* FD normals: step relative to max(1, |p|); 0: 1e-6 */
    /* Every method: NULL, or 6 doubles lo x, y, z then hi x, y, z of a box
       that holds the whole solid {f >= 0} (fr_bound_box computes one). The
       segment is clipped to it first, so rays that miss the box cost a slab
       test (and report a miss with hit->method = desc->method, unresolved).
       A box that does not hold the solid loses hits outside it. */
    const double *bounds;
    /* INTERVAL: the pixel footprint, a cone's half-width per unit t (for a
       pinhole camera, about the pixel's angular size in radians). 0 (the
       default): off. When > 0, bisection stops at segments [a, b] no wider
       than tol + footprint |b|: with a sign change at the ends, Illinois
       regula falsi then brings the root to tol with point evaluations;
       without one, the segment is bisected FR__TOUCH_SCALE further as
       usual. A feature is still never missed: only the resolution at which
       interval bisection hands over to regula falsi changes. */
    double footprint;
    /* Shadow rays: 1 reports as soon as a root is proven somewhere in the
       segment, not necessarily the first one, with no refinement: t is then
       only within t_err of a root. INTERVAL stops at the first segment whose
       ends have opposite signs (a sign change at t0 and t1 costs no
       interval evaluation at all); STEP skips the refinement. Default 0. */
    int any_hit;
    /* NULL (default), or a prepared model of this very tape (fr_prepare):
       fr_trace then clips the segment to its box as well and uses its
       precomputed structures (see fr_prepare). One made for another tape
       is ignored. */
    const struct fr_prepared_t *prepared;
} fr_trace_desc_t;

typedef struct fr_hit_t {
    int hit;                /* 1 if the segment meets the surface */
    double t;               /* the ray parameter of the hit */
    double point[3];        /* o + t d */
    double normal[3];       /* unit outward normal (along -grad f); 0 if unknown */
    double t_err;           /* the root is within t +- t_err (tolerance reached;
                               for ANALYTIC an error estimate from the polish,
                               of the rounded polynomial's root: on grazing
                               rays (small |g'|) the true root is farther,
                               docs/frep.md "Ray methods";
                               for SPHERE's grazing stop that crosses nowhere,
                               desc.tol as a distance: see tol) */
    unsigned long long evals;      /* tape evaluations (any arithmetic) */
    unsigned long long iterations; /* loop iterations (steps, bisections, polish) */
    fr_method_t method;     /* the method used (AUTO resolved) */
} fr_hit_t;

/* Bytes of scratch fr_trace needs for this tape and method (one buffer per
   thread; malloc alignment is enough). */
FR_DEF size_t fr_trace_scratch_size(const fr_tape_t *t, const fr_trace_desc_t *desc);

/* The first intersection of o + t d, t in [t0, t1], with the surface of t.
   desc may be NULL (defaults). Errors: FR_ERR_INVALID_ARG (NULL, NaN, t0 >
   t1, d = 0, an infinite segment for INTERVAL or for a STEP without step
   length or Lipschitz bound), FR_ERR_NOT_POLYNOMIAL (ANALYTIC on a shape
   that is not min/max/R-functions over polynomial leaves, or whose ray
   polynomial overflows or has subnormal coefficients on this ray: AUTO
   takes such rays to intervals; docs/frep.md "Scale"; d may have any
   length: far from 1 it is traced rescaled by a power of 2),
   FR_ERR_NO_INTERVAL, FR_ERR_NO_GRADIENT (NEWTON refinement with a
   gradient-less callback; AD normals fall back to differences there),
   FR_ERR_NO_LIPSCHITZ (SPHERE), FR_ERR_ITERATIONS (STEP, INTERVAL or
   SPHERE used desc->max_iters up with part of the segment undecided: no
   root was found before hit->t - hit->t_err, the first root, if any, lies
   in hit->t +- hit->t_err, and hit->hit is 0; a renderer may take it as a
   miss or trace on from there). A miss is FR_OK with hit->hit = 0 (for
   INTERVAL, a proof that the segment holds no root). */
FR_DEF fr_result_t fr_trace(const fr_tape_t *t, const double o[3], const double d[3], double t0, double t1,
                            const fr_trace_desc_t *desc, void *scratch, fr_hit_t *hit);

#ifndef FR_NO_INTERVAL
/* A box holding the solid {f >= 0} inside the search box [lo, hi], by
   interval subdivision (paper §4.1.3's interval test, applied to space):
   octree cells whose interval enclosure of f lies below 0 hold no solid and
   are dropped, cells inside the box found so far are skipped, and the
   result is the bounding box of the cells that survive at depth `depth`
   (cell size (hi - lo) / 2^depth; 0 means 6; at most 10). Interval
   overestimation may keep a few empty cells beside the solid (the tangle
   cube's box at depth 6 is 2.66 for an extent of 2.27). Conservative: the
   part of the solid inside [lo, hi] lies inside [out_lo, out_hi]; no solid
   there gives out_lo > out_hi. Scratch: fr_scratch_size(t,
   FR_EVAL_INTERVAL) bytes. Use it for fr_trace_desc_t.bounds. Errors:
   FR_ERR_INVALID_ARG (NULL, non-finite or inverted box),
   FR_ERR_NO_INTERVAL. */
FR_DEF fr_result_t fr_bound_box(const fr_tape_t *t, const double lo[3], const double hi[3], int depth, void *scratch,
                                double out_lo[3], double out_hi[3]);
#endif

/* The coefficients of g(t) = f(o + t d), lowest degree first, by evaluating
   the tape in truncated Taylor (polynomial) arithmetic: coef must hold
   FR_POLY_MAX_DEGREE + 1 doubles, *degree receives the degree (trailing
   zero coefficients trimmed). FR_ERR_NOT_POLYNOMIAL when an operation is not
   polynomial (sqrt, min, R-functions, noise, callbacks, division by a
   non-constant) or the degree exceeds FR_POLY_MAX_DEGREE, and where a
   coefficient overflowed or a product's top one underflowed (it would
   have dropped the degree unseen: docs/frep.md "Scale"). Scratch:
   fr_ray_poly_scratch_size(t) bytes. */
FR_DEF size_t fr_ray_poly_scratch_size(const fr_tape_t *t);
FR_DEF fr_result_t fr_ray_poly(const fr_tape_t *t, const double o[3], const double d[3], void *scratch,
                               double *coef, int *degree);

/* PREPARED MODELS: what every ray of fr_trace recomputes from the tape,
   worked out once per model (paper §3.1.1's analytic method, for renderers
   that trace millions of rays through one model). fr_prepare analyses the
   tape and the box `bounds` (6 doubles, lo x y z then hi x y z, holding
   the whole solid, as fr_bound_box gives; NULL: no box) and fills *out:

   FR_PREPARED_POLY  the shape is a polynomial in x, y, z (tangle cube,
       Barth's sextic without its clip): the tape's polynomial slots as a
       straight-line Taylor program of fixed degrees, run once per ray for
       ANALYTIC and, with its magnitude run fused into the same pass, for
       INTERVAL's centred form. Same operations in the same order as
       fr_ray_poly, so the same coefficients (ulps apart at most where a
       zero component of d lowers a degree).
   FR_PREPARED_CSG   the shape is min/max/R-function/negation nodes over
       polynomial leaves (cup, Barth's sextic with its clip): the CSG tree
       as a boolean structure over the leaves' signs, and per leaf of
       degree <= 2 (spheres, cylinders, cones, planes, any quadric) its 10
       monomial coefficients about the centre of the box holding its zero
       set (by interval subdivision of `bounds`), so a ray's leaf
       polynomial is a few dozen flops and its roots come from the
       quadratic formula with Kahan's fma discriminant (roots within a few
       ulps of those of the ray polynomial's double coefficients; extreme
       scales go to fr_solve_poly). Higher-degree leaves keep the Taylor
       program. A ray that misses a leaf's box costs that leaf one value
       (its sign); the sorted roots are classified by flipping the sign of
       their leaf and re-evaluating the boolean tree, not the tape; the
       normal is the leaf's exact gradient (what AD through the CSG nodes
       gives, up to a positive factor), oriented by the crossing.
       ANALYTIC and AUTO use it; other methods trace as without it.
   FR_PREPARED_NONE  nothing to precompute (other tapes); fr_trace traces as
       without it.

   Hits agree with the unprepared fr_trace to rounding
   (tests/test_frep_prepared.c); in both, a leaf root exactly at t0 counts
   as before the segment (a ray starting on the surface is no hit at t0).
   The box given here also clips every ray, like fr_trace_desc_t.bounds. The
   prepared model refers to the tape and must not outlive it; it is
   read-only, so threads share it. Memory comes from FR_MALLOC with the
   tape's alloc_ctx; free it with fr_prepared_free. Without a box, CSG
   leaves keep the Taylor program and no leaf or node is culled.
   Errors: FR_ERR_INVALID_ARG (NULL, empty tape, non-finite or inverted
   box), FR_ERR_OUT_OF_MEMORY. */
typedef enum fr_prepared_kind_t {
    FR_PREPARED_NONE = 0,
    FR_PREPARED_POLY,
    FR_PREPARED_CSG
} fr_prepared_kind_t;

typedef struct fr_prepared_t {
    const fr_tape_t *tape;       /* the tape it serves */
    fr_prepared_kind_t kind;
    int has_box;                 /* box holds the bounds given to fr_prepare */
    double box[6];
    unsigned int n_prog;         /* instructions of the Taylor program */
    unsigned int n_leaves;       /* CSG leaves, of which n_quadrics in monomial form */
    unsigned int n_quadrics;
    unsigned int n_nodes;        /* CSG nodes */
    void *mem;                   /* one block: program, leaves, nodes */
    void *alloc_ctx;
} fr_prepared_t;

FR_DEF fr_result_t fr_prepare(const fr_tape_t *t, const double *bounds, fr_prepared_t *out);
FR_DEF void fr_prepared_free(fr_prepared_t *p);

/* ==== [end section: trace] ==== */


#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_FR_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef FR_IMPLEMENTATION
#ifndef FILIGREE_FR_IMPLEMENTATION_DONE
#define FILIGREE_FR_IMPLEMENTATION_DONE

#ifndef FR_ASSERT
#  include <assert.h>
#  define FR_ASSERT(c) assert(c)
#endif
#if defined(FR_MALLOC) != defined(FR_FREE)
#  error "define both FR_MALLOC and FR_FREE, or neither"
#endif
#ifndef FR_MALLOC
#  include <stdlib.h>
#  define FR_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define FR_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

FR_DEF const char *fr_result_string(fr_result_t r)
{
    switch (r) {
    case FR_OK: return "ok";
    case FR_ERR_INVALID_ARG: return "invalid argument";
    case FR_ERR_OUT_OF_MEMORY: return "out of memory";
    case FR_ERR_LIMIT: return "size limit exceeded";
    case FR_ERR_NO_INTERVAL: return "interval evaluation unavailable (a callback has no interval function)";
    case FR_ERR_NO_GRADIENT: return "gradient unavailable (a callback has no gradient function)";
    case FR_ERR_BUFFER_TOO_SMALL: return "buffer too small";
    case FR_ERR_PARSE: return "parse error";
    case FR_ERR_NOT_POLYNOMIAL: return "not a polynomial along the ray";
    case FR_ERR_NO_LIPSCHITZ: return "no Lipschitz bound for sphere tracing";
    case FR_ERR_ITERATIONS: return "iteration cap reached before the ray was decided";
    case FR_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* ==== [section: model] implementation: tape, primitives, operations, evaluation, parser ==== */
#include <string.h>
#include <stdio.h>
#include <float.h>
/* The public entry points whose answers rest on exact rounding (interval
   and affine evaluation, pruning, the bounding box, preparing, tracing,
   the polynomial solver) run call in the environment interval.h's
   guarantee assumes and restore the host's after (iv_fp_env_enter: one
   register read when the host's is that already). A host that keeps
   flush-to-zero on for Embree gets the answers it would get without.
   User callbacks run in that environment too. Without interval.h
   (FR_NO_INTERVAL) the host's environment stays. */
#if defined(__GNUC__) || defined(__clang__)
#  define FR__NOINLINE __attribute__((noinline)) /* compilers may move arithmetic across the */
#elif defined(_MSC_VER)                          /* MXCSR writes, not across a call */
#  define FR__NOINLINE __declspec(noinline)
#else
#  define FR__NOINLINE
#endif
#ifndef FR_NO_INTERVAL
#  define FR__IN_FP_ENV(type, call)                                                    \
    do {                                                                               \
        iv_fp_env_t fr__env = iv_fp_env_enter();                                       \
        type fr__result = (call);                                                      \
        iv_fp_env_leave(fr__env);                                                      \
        return fr__result;                                                             \
    } while (0)
#else
#  define FR__IN_FP_ENV(type, call) return (call)
#endif

/* ---- builder internals */

static fr_node_t fr__fail(fr_builder_t *b, fr_result_t r, const char *msg)
{
    if (b->diag.result == FR_OK) {
        b->diag.result = r;
        b->diag.element = (long long)b->n;
        snprintf(b->diag.message, sizeof b->diag.message, "node %u: %s", b->n, msg);
    }
    return FR_NODE_NONE;
}

static int fr__grow(fr_builder_t *b, void **arr, unsigned int *cap, unsigned int need, size_t elem)
{
    unsigned int nc;
    void *p;
    if (need <= *cap) return 1;
    nc = *cap ? *cap : 64u;
    while (nc < need) nc *= 2u;
    p = FR_MALLOC((size_t)nc * elem, b->alloc_ctx);
    if (!p) return 0;
    if (*arr) {
        memcpy(p, *arr, (size_t)*cap * elem);
        FR_FREE(*arr, b->alloc_ctx);
    }
    *arr = p;
    *cap = nc;
    return 1;
}

static int fr__ok(const fr_builder_t *b, fr_node_t a) { return a != FR_NODE_NONE && a < b->n; }

static fr_node_t fr__emit(fr_builder_t *b, fr_op_t op, fr_node_t a, fr_node_t c, fr_node_t d,
                          unsigned int aux, double k)
{
    unsigned int cap = b->cap, cap2 = b->cap;
    fr_instr_t *in;
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (b->n >= b->max_nodes) return fr__fail(b, FR_ERR_LIMIT, "too many nodes (fr_builder_desc_t.max_nodes)");
    if (b->n + 1 > b->cap) {
        if (!fr__grow(b, (void **)&b->code, &cap, b->n + 1, sizeof(fr_instr_t)) ||
            !fr__grow(b, (void **)&b->lip, &cap2, b->n + 1, sizeof(double)))
            return fr__fail(b, FR_ERR_OUT_OF_MEMORY, "out of memory");
        b->cap = cap < cap2 ? cap : cap2;
    }
    in = &b->code[b->n];
    in->op = (unsigned int)op;
    in->a = a;
    in->b = c;
    in->c = d;
    in->aux = aux;
    in->k = k;
    b->lip[b->n] = 0.0;
    return b->n++;
}

/* operand arity of each opcode */
static int fr__arity(unsigned int op)
{
    if (op <= FR_OP_VAR_Z) return 0;
    if (op <= FR_OP_POWC) return 1;
    if (op <= FR_OP_SMIN) return 2;
    return 3;
}

FR_DEF fr_result_t fr_builder_init(fr_builder_t *b, const fr_builder_desc_t *desc)
{
    if (!b) return FR_ERR_INVALID_ARG;
    memset(b, 0, sizeof *b);
    b->diag.element = -1;
    b->alloc_ctx = desc ? desc->alloc_ctx : NULL;
    b->max_nodes = desc && desc->max_nodes ? desc->max_nodes : (1u << 24);
    b->var[0] = b->var[1] = b->var[2] = FR_NODE_NONE;
    return FR_OK;
}

FR_DEF void fr_builder_free(fr_builder_t *b)
{
    if (!b) return;
    if (b->code) FR_FREE(b->code, b->alloc_ctx);
    if (b->lip) FR_FREE(b->lip, b->alloc_ctx);
    if (b->params) FR_FREE(b->params, b->alloc_ctx);
    if (b->callbacks) FR_FREE(b->callbacks, b->alloc_ctx);
    memset(b, 0, sizeof *b);
}

/* ---- elementary nodes */

FR_DEF fr_p3_t fr_coords(fr_builder_t *b)
{
    fr_p3_t p;
    int i;
    for (i = 0; i < 3; i++)
        if (b && (b->var[i] == FR_NODE_NONE || b->var[i] >= b->n))
            b->var[i] = fr__emit(b, (fr_op_t)(FR_OP_VAR_X + i), 0, 0, 0, 0, 0.0);
    p.x = b ? b->var[0] : FR_NODE_NONE;
    p.y = b ? b->var[1] : FR_NODE_NONE;
    p.z = b ? b->var[2] : FR_NODE_NONE;
    return p;
}

FR_DEF fr_node_t fr_const(fr_builder_t *b, double v)
{
    if (!b) return FR_NODE_NONE;
    if (!isfinite(v)) return fr__fail(b, FR_ERR_INVALID_ARG, "constant is not finite");
    return fr__emit(b, FR_OP_CONST, 0, 0, 0, 0, v);
}

FR_DEF fr_node_t fr_unary(fr_builder_t *b, fr_op_t op, fr_node_t a)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (fr__arity((unsigned int)op) != 1 || op == FR_OP_POWI || op == FR_OP_POWC)
        return fr__fail(b, FR_ERR_INVALID_ARG, "fr_unary: not a unary opcode");
    if (!fr__ok(b, a)) return fr__fail(b, FR_ERR_INVALID_ARG, "invalid operand node");
    return fr__emit(b, op, a, 0, 0, 0, 0.0);
}

FR_DEF fr_node_t fr_binary(fr_builder_t *b, fr_op_t op, fr_node_t a, fr_node_t c)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (op < FR_OP_ADD || op > FR_OP_MAX) return fr__fail(b, FR_ERR_INVALID_ARG, "fr_binary: not a binary opcode");
    if (!fr__ok(b, a) || !fr__ok(b, c)) return fr__fail(b, FR_ERR_INVALID_ARG, "invalid operand node");
    return fr__emit(b, op, a, c, 0, 0, 0.0);
}

FR_DEF fr_node_t fr_powi(fr_builder_t *b, fr_node_t a, int n)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!fr__ok(b, a)) return fr__fail(b, FR_ERR_INVALID_ARG, "invalid operand node");
    if (n < -64 || n > 64) return fr__fail(b, FR_ERR_INVALID_ARG, "integer power outside [-64, 64]");
    return fr__emit(b, FR_OP_POWI, a, 0, 0, 0, (double)n);
}

FR_DEF fr_node_t fr_powc(fr_builder_t *b, fr_node_t a, double e)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!fr__ok(b, a)) return fr__fail(b, FR_ERR_INVALID_ARG, "invalid operand node");
    if (!isfinite(e) || e <= 0) return fr__fail(b, FR_ERR_INVALID_ARG, "real power exponent must be finite and > 0");
    return fr__emit(b, FR_OP_POWC, a, 0, 0, 0, e);
}

FR_DEF fr_node_t fr_add(fr_builder_t *b, fr_node_t a, fr_node_t c) { return fr_binary(b, FR_OP_ADD, a, c); }
FR_DEF fr_node_t fr_sub(fr_builder_t *b, fr_node_t a, fr_node_t c) { return fr_binary(b, FR_OP_SUB, a, c); }
FR_DEF fr_node_t fr_mul(fr_builder_t *b, fr_node_t a, fr_node_t c) { return fr_binary(b, FR_OP_MUL, a, c); }
FR_DEF fr_node_t fr_div(fr_builder_t *b, fr_node_t a, fr_node_t c) { return fr_binary(b, FR_OP_DIV, a, c); }

/* small private helpers: node op constant */
static fr_node_t fr__sqr(fr_builder_t *b, fr_node_t a) { return fr_unary(b, FR_OP_SQR, a); }
static fr_node_t fr__addk(fr_builder_t *b, fr_node_t a, double k) { return k == 0 ? a : fr_add(b, a, fr_const(b, k)); }
static fr_node_t fr__subk(fr_builder_t *b, fr_node_t a, double k) { return k == 0 ? a : fr_sub(b, a, fr_const(b, k)); }
static fr_node_t fr__mulk(fr_builder_t *b, fr_node_t a, double k) { return k == 1 ? a : fr_mul(b, a, fr_const(b, k)); }
static fr_node_t fr__ksub(fr_builder_t *b, double k, fr_node_t a) { return fr_sub(b, fr_const(b, k), a); }
static fr_node_t fr__coord(fr_p3_t p, int i) { return i == 0 ? p.x : i == 1 ? p.y : p.z; }
static int fr__finite_pos(double v) { return isfinite(v) && v > 0; }
static int fr__finite3(const double *v) { return v && isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }
static int fr__p3_ok(const fr_builder_t *b, fr_p3_t p) { return fr__ok(b, p.x) && fr__ok(b, p.y) && fr__ok(b, p.z); }

/* checks shared by every primitive: point nodes valid, centre finite */
static int fr__prim_ok(fr_builder_t *b, fr_p3_t p, const double *c, const char *name)
{
    char msg[120];
    if (!b || b->diag.result != FR_OK) return 0;
    if (!fr__p3_ok(b, p)) {
        snprintf(msg, sizeof msg, "%s: invalid point node", name);
        fr__fail(b, FR_ERR_INVALID_ARG, msg);
        return 0;
    }
    if (c && !fr__finite3(c)) {
        snprintf(msg, sizeof msg, "%s: centre/vector is NULL or not finite", name);
        fr__fail(b, FR_ERR_INVALID_ARG, msg);
        return 0;
    }
    return 1;
}
static int fr__param_fail(fr_builder_t *b, const char *name, const char *what)
{
    char msg[140];
    snprintf(msg, sizeof msg, "%s: %s", name, what);
    fr__fail(b, FR_ERR_INVALID_ARG, msg);
    return 0;
}

/* ---- primitives */

/* sum of (p_i - c_i)^2 over the axes whose bit is set in mask, each divided by s_i if s given */
static fr_node_t fr__sumsq(fr_builder_t *b, fr_p3_t p, const double c[3], const double *s, int mask)
{
    fr_node_t acc = FR_NODE_NONE;
    int i;
    for (i = 0; i < 3; i++) {
        fr_node_t t;
        if (!(mask & (1 << i))) continue;
        t = fr__subk(b, fr__coord(p, i), c[i]);
        if (s) t = fr__mulk(b, t, 1.0 / s[i]);
        t = fr__sqr(b, t);
        acc = acc == FR_NODE_NONE ? t : fr_add(b, acc, t);
    }
    return acc;
}

FR_DEF fr_node_t fr_sphere(fr_builder_t *b, fr_p3_t p, const double c[3], double r)
{
    if (!fr__prim_ok(b, p, c, "sphere")) return FR_NODE_NONE;
    if (!fr__finite_pos(r)) return fr__param_fail(b, "sphere", "radius must be finite and > 0"), FR_NODE_NONE;
    return fr__ksub(b, r * r, fr__sumsq(b, p, c, NULL, 7));
}

FR_DEF fr_node_t fr_ellipsoid(fr_builder_t *b, fr_p3_t p, const double c[3], double ra, double rb, double rc)
{
    double s[3];
    if (!fr__prim_ok(b, p, c, "ellipsoid")) return FR_NODE_NONE;
    if (!fr__finite_pos(ra) || !fr__finite_pos(rb) || !fr__finite_pos(rc))
        return fr__param_fail(b, "ellipsoid", "half-axes must be finite and > 0"), FR_NODE_NONE;
    s[0] = ra; s[1] = rb; s[2] = rc;
    return fr__ksub(b, 1.0, fr__sumsq(b, p, c, s, 7));
}

static int fr__alpha_ok(fr_builder_t *b, double alpha, const char *name)
{
    if (!(alpha >= 0 && alpha <= 1)) return fr__param_fail(b, name, "alpha must be in [0, 1]");
    return 1;
}

FR_DEF fr_node_t fr_block(fr_builder_t *b, fr_p3_t p, const double vertex[3], const double size[3], double alpha)
{
    fr_node_t f = FR_NODE_NONE;
    int i;
    if (!fr__prim_ok(b, p, vertex, "block")) return FR_NODE_NONE;
    if (!size || !fr__finite_pos(size[0]) || !fr__finite_pos(size[1]) || !fr__finite_pos(size[2]))
        return fr__param_fail(b, "block", "edge lengths must be finite and > 0"), FR_NODE_NONE;
    if (!fr__alpha_ok(b, alpha, "block")) return FR_NODE_NONE;
    for (i = 0; i < 3; i++) {
        fr_node_t q = fr__coord(p, i);
        /* (x - v)(v + d - x): the slab, positive between its two planes */
        fr_node_t s = fr_mul(b, fr__subk(b, q, vertex[i]), fr__ksub(b, vertex[i] + size[i], q));
        f = i == 0 ? s : fr_intersect(b, f, s, alpha);
    }
    return f;
}

static int fr__axis_ok(fr_builder_t *b, int axis, const char *name)
{
    if (axis < 0 || axis > 2) return fr__param_fail(b, name, "axis must be 0, 1 or 2");
    return 1;
}

FR_DEF fr_node_t fr_cylinder(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double r)
{
    if (!fr__prim_ok(b, p, c, "cylinder") || !fr__axis_ok(b, axis, "cylinder")) return FR_NODE_NONE;
    if (!fr__finite_pos(r)) return fr__param_fail(b, "cylinder", "radius must be finite and > 0"), FR_NODE_NONE;
    return fr__ksub(b, r * r, fr__sumsq(b, p, c, NULL, 7 & ~(1 << axis)));
}

FR_DEF fr_node_t fr_ell_cylinder(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double ra, double rb)
{
    double s[3];
    if (!fr__prim_ok(b, p, c, "elliptic cylinder") || !fr__axis_ok(b, axis, "elliptic cylinder")) return FR_NODE_NONE;
    if (!fr__finite_pos(ra) || !fr__finite_pos(rb))
        return fr__param_fail(b, "elliptic cylinder", "radii must be finite and > 0"), FR_NODE_NONE;
    s[axis] = 1.0;
    s[axis == 0 ? 1 : 0] = ra;
    s[axis == 2 ? 1 : 2] = rb;
    return fr__ksub(b, 1.0, fr__sumsq(b, p, c, s, 7 & ~(1 << axis)));
}

FR_DEF fr_node_t fr_cylinder_axis(fr_builder_t *b, fr_p3_t p, const double q[3], const double dir[3], double r)
{
    double len, u[3];
    fr_node_t d[3], along, sq;
    int i;
    if (!fr__prim_ok(b, p, q, "cylinder") || !fr__prim_ok(b, p, dir, "cylinder")) return FR_NODE_NONE;
    len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0) || !isfinite(len)) return fr__param_fail(b, "cylinder", "axis direction is zero"), FR_NODE_NONE;
    if (!fr__finite_pos(r)) return fr__param_fail(b, "cylinder", "radius must be finite and > 0"), FR_NODE_NONE;
    for (i = 0; i < 3; i++) {
        u[i] = dir[i] / len;
        d[i] = fr__subk(b, fr__coord(p, i), q[i]);
    }
    /* |d|^2 - (d.u)^2 is the squared distance to the axis */
    along = fr_add(b, fr_add(b, fr__mulk(b, d[0], u[0]), fr__mulk(b, d[1], u[1])), fr__mulk(b, d[2], u[2]));
    sq = fr_add(b, fr_add(b, fr__sqr(b, d[0]), fr__sqr(b, d[1])), fr__sqr(b, d[2]));
    return fr_sub(b, fr_add(b, fr_const(b, r * r), fr__sqr(b, along)), sq);
}

FR_DEF fr_node_t fr_cone(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double r)
{
    double s[3];
    fr_node_t t;
    if (!fr__prim_ok(b, p, c, "cone") || !fr__axis_ok(b, axis, "cone")) return FR_NODE_NONE;
    if (!fr__finite_pos(r)) return fr__param_fail(b, "cone", "radius must be finite and > 0"), FR_NODE_NONE;
    s[0] = s[1] = s[2] = r;
    t = fr__subk(b, fr__coord(p, axis), c[axis]);
    return fr_sub(b, fr__sqr(b, t), fr__sumsq(b, p, c, s, 7 & ~(1 << axis)));
}

FR_DEF fr_node_t fr_torus(fr_builder_t *b, fr_p3_t p, int axis, const double c[3], double R, double r0)
{
    fr_node_t rho2, all2;
    if (!fr__prim_ok(b, p, c, "torus") || !fr__axis_ok(b, axis, "torus")) return FR_NODE_NONE;
    if (!fr__finite_pos(R) || !fr__finite_pos(r0))
        return fr__param_fail(b, "torus", "radii must be finite and > 0"), FR_NODE_NONE;
    rho2 = fr__sumsq(b, p, c, NULL, 7 & ~(1 << axis));
    all2 = fr_add(b, rho2, fr__sqr(b, fr__subk(b, fr__coord(p, axis), c[axis])));
    /* r0^2 - R^2 - |d|^2 + 2 R rho */
    return fr_add(b, fr__ksub(b, r0 * r0 - R * R, all2), fr__mulk(b, fr_unary(b, FR_OP_SQRT, rho2), 2.0 * R));
}

FR_DEF fr_node_t fr_halfspace(fr_builder_t *b, fr_p3_t p, const double n[3], double d)
{
    fr_node_t dot;
    if (!fr__prim_ok(b, p, n, "half-space")) return FR_NODE_NONE;
    if (!isfinite(d)) return fr__param_fail(b, "half-space", "offset must be finite"), FR_NODE_NONE;
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) return fr__param_fail(b, "half-space", "normal is zero"), FR_NODE_NONE;
    dot = fr_add(b, fr_add(b, fr__mulk(b, p.x, n[0]), fr__mulk(b, p.y, n[1])), fr__mulk(b, p.z, n[2]));
    return fr__ksub(b, d, dot);
}

FR_DEF fr_node_t fr_superellipsoid(fr_builder_t *b, fr_p3_t p, const double c[3], const double abc[3], double s1,
                                   double s2)
{
    fr_node_t t[3], xy;
    int i;
    if (!fr__prim_ok(b, p, c, "superellipsoid")) return FR_NODE_NONE;
    if (!abc || !fr__finite_pos(abc[0]) || !fr__finite_pos(abc[1]) || !fr__finite_pos(abc[2]) ||
        !fr__finite_pos(s1) || !fr__finite_pos(s2))
        return fr__param_fail(b, "superellipsoid", "half-axes and shape exponents must be finite and > 0"),
               FR_NODE_NONE;
    for (i = 0; i < 3; i++)
        t[i] = fr_unary(b, FR_OP_ABS, fr__mulk(b, fr__subk(b, fr__coord(p, i), c[i]), 1.0 / abc[i]));
    xy = fr_add(b, fr_powc(b, t[0], 2.0 / s2), fr_powc(b, t[1], 2.0 / s2));
    return fr_sub(b, fr__ksub(b, 1.0, fr_powc(b, xy, s2 / s1)), fr_powc(b, t[2], 2.0 / s1));
}

/* ---- skeletal primitives */

/* squared distance from p to the point a or the segment ab: the segment
   parameter is clamped with min/max so the expression stays elementary */
static fr_node_t fr__dist2(fr_builder_t *b, fr_p3_t p, const double a[3], const double e[3])
{
    double ab[3], l2;
    fr_node_t d[3], t, r2 = FR_NODE_NONE;
    int i;
    for (i = 0; i < 3; i++) {
        ab[i] = e[i] - a[i];
        d[i] = fr__subk(b, fr__coord(p, i), a[i]);
    }
    l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    if (l2 == 0) return fr__sumsq(b, p, a, NULL, 7);
    t = fr_add(b, fr_add(b, fr__mulk(b, d[0], ab[0] / l2), fr__mulk(b, d[1], ab[1] / l2)), fr__mulk(b, d[2], ab[2] / l2));
    t = fr_binary(b, FR_OP_MIN, fr_binary(b, FR_OP_MAX, t, fr_const(b, 0.0)), fr_const(b, 1.0));
    for (i = 0; i < 3; i++) {
        fr_node_t q = fr__sqr(b, fr_sub(b, d[i], fr__mulk(b, t, ab[i])));
        r2 = i == 0 ? q : fr_add(b, r2, q);
    }
    return r2;
}

/* Nishimura's metaball profile of q = r/width, written with min/max:
   g1(min(q,1/3)) + g2(clamp(q,1/3,1)) - 2/3, g1 = 1-3q^2, g2 = 1.5(1-q)^2,
   both 2/3 at q = 1/3, so each branch contributes only on its own piece */
static fr_node_t fr__metaball_profile(fr_builder_t *b, fr_node_t q)
{
    fr_node_t lo = fr_binary(b, FR_OP_MIN, q, fr_const(b, 1.0 / 3.0));
    fr_node_t mid = fr_binary(b, FR_OP_MIN, fr_binary(b, FR_OP_MAX, q, fr_const(b, 1.0 / 3.0)), fr_const(b, 1.0));
    fr_node_t g1 = fr__ksub(b, 1.0, fr__mulk(b, fr__sqr(b, lo), 3.0));
    fr_node_t g2 = fr__mulk(b, fr__sqr(b, fr__ksub(b, 1.0, mid)), 1.5);
    return fr__subk(b, fr_add(b, g1, g2), 2.0 / 3.0);
}

/* Wyvill's soft-object polynomial of s = min(r^2/width^2, 1); zero at s = 1 */
static fr_node_t fr__soft_profile(fr_builder_t *b, fr_node_t s)
{
    fr_node_t c = fr_binary(b, FR_OP_MIN, s, fr_const(b, 1.0));
    /* Horner: 1 + s(-22/9 + s(17/9 - 4/9 s)) */
    fr_node_t h = fr__ksub(b, 17.0 / 9.0, fr__mulk(b, c, 4.0 / 9.0));
    h = fr__addk(b, fr_mul(b, c, h), -22.0 / 9.0);
    return fr__addk(b, fr_mul(b, c, h), 1.0);
}

static int fr__skel_ok(fr_builder_t *b, fr_p3_t p, const fr_skeleton_t *el, unsigned int n, const char *name)
{
    unsigned int i;
    char msg[120];
    if (!fr__prim_ok(b, p, NULL, name)) return 0;
    if (!el || n == 0) return fr__param_fail(b, name, "no skeleton elements");
    for (i = 0; i < n; i++)
        if (!fr__finite3(el[i].a) || !fr__finite3(el[i].b) || !fr__finite_pos(el[i].width) ||
            !isfinite(el[i].weight)) {
            snprintf(msg, sizeof msg, "element %u: non-finite point or width <= 0", i);
            return fr__param_fail(b, name, msg);
        }
    return 1;
}

FR_DEF fr_node_t fr_skeletal(fr_builder_t *b, fr_p3_t p, fr_kernel_t kernel, const fr_skeleton_t *el,
                             unsigned int n, double threshold)
{
    fr_node_t sum = FR_NODE_NONE;
    unsigned int i;
    if (!fr__skel_ok(b, p, el, n, "skeletal")) return FR_NODE_NONE;
    if (!isfinite(threshold)) return fr__param_fail(b, "skeletal", "threshold must be finite"), FR_NODE_NONE;
    if (kernel != FR_KERNEL_BLOBBY && kernel != FR_KERNEL_METABALL && kernel != FR_KERNEL_SOFT)
        return fr__param_fail(b, "skeletal", "unknown kernel"), FR_NODE_NONE;
    for (i = 0; i < n; i++) {
        fr_node_t r2 = fr__dist2(b, p, el[i].a, el[i].b), term;
        double w = el[i].width;
        if (kernel == FR_KERNEL_BLOBBY)
            term = fr_unary(b, FR_OP_EXP, fr__mulk(b, r2, -w));
        else if (kernel == FR_KERNEL_METABALL)
            term = fr__metaball_profile(b, fr__mulk(b, fr_unary(b, FR_OP_SQRT, r2), 1.0 / w));
        else
            term = fr__soft_profile(b, fr__mulk(b, r2, 1.0 / (w * w)));
        term = fr__mulk(b, term, el[i].weight);
        sum = i == 0 ? term : fr_add(b, sum, term);
    }
    return fr__subk(b, sum, threshold);
}

FR_DEF fr_node_t fr_convolution(fr_builder_t *b, fr_p3_t p, const fr_skeleton_t *seg, unsigned int n,
                                double threshold)
{
    fr_node_t sum = FR_NODE_NONE;
    unsigned int i;
    if (!fr__skel_ok(b, p, seg, n, "convolution")) return FR_NODE_NONE;
    if (!isfinite(threshold)) return fr__param_fail(b, "convolution", "threshold must be finite"), FR_NODE_NONE;
    for (i = 0; i < n; i++) {
        double ab[3], l, s = seg[i].width;
        fr_node_t d[3], x, lx, c2, c, t1, t2, t3, F;
        int j;
        for (j = 0; j < 3; j++) ab[j] = seg[i].b[j] - seg[i].a[j];
        l = sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
        if (!(l > 0)) return fr__param_fail(b, "convolution", "a segment has zero length"), FR_NODE_NONE;
        for (j = 0; j < 3; j++) d[j] = fr__subk(b, fr__coord(p, j), seg[i].a[j]);
        /* x = along-segment coordinate, c^2 = 1 + s^2 (distance to the line)^2 >= 1:
           int_{-x}^{l-x} du/(c^2+s^2u^2)^2 = [u/(2c^2(c^2+s^2u^2)) + atan(su/c)/(2sc^3)] */
        x = fr_add(b, fr_add(b, fr__mulk(b, d[0], ab[0] / l), fr__mulk(b, d[1], ab[1] / l)), fr__mulk(b, d[2], ab[2] / l));
        lx = fr__ksub(b, l, x);
        c2 = fr_sub(b, fr_add(b, fr_add(b, fr__sqr(b, d[0]), fr__sqr(b, d[1])), fr__sqr(b, d[2])), fr__sqr(b, x));
        c2 = fr__addk(b, fr__mulk(b, fr_binary(b, FR_OP_MAX, c2, fr_const(b, 0.0)), s * s), 1.0);
        c = fr_unary(b, FR_OP_SQRT, c2);
        t1 = fr_div(b, x, fr__mulk(b, fr_mul(b, c2, fr_add(b, c2, fr__mulk(b, fr__sqr(b, x), s * s))), 2.0));
        t2 = fr_div(b, lx, fr__mulk(b, fr_mul(b, c2, fr_add(b, c2, fr__mulk(b, fr__sqr(b, lx), s * s))), 2.0));
        t3 = fr_add(b, fr_unary(b, FR_OP_ATAN, fr_div(b, fr__mulk(b, x, s), c)),
                    fr_unary(b, FR_OP_ATAN, fr_div(b, fr__mulk(b, lx, s), c)));
        t3 = fr_div(b, t3, fr__mulk(b, fr_mul(b, c2, c), 2.0 * s));
        F = fr__mulk(b, fr_add(b, fr_add(b, t1, t2), t3), seg[i].weight);
        sum = i == 0 ? F : fr_add(b, sum, F);
    }
    return fr__subk(b, sum, threshold);
}

FR_DEF fr_node_t fr_noise(fr_builder_t *b, fr_p3_t p, double amp, double freq, const double offset[3])
{
    unsigned int cap = b ? b->cap_params : 0;
    double *q;
    if (!fr__prim_ok(b, p, offset, "noise")) return FR_NODE_NONE;
    if (!isfinite(amp) || !fr__finite_pos(freq))
        return fr__param_fail(b, "noise", "amplitude must be finite and frequency finite and > 0"), FR_NODE_NONE;
    if (!fr__grow(b, (void **)&b->params, &cap, b->n_params + FR_NOISE_PARAMS, sizeof(double)))
        return fr__fail(b, FR_ERR_OUT_OF_MEMORY, "out of memory");
    b->cap_params = cap;
    q = b->params + b->n_params;
    q[0] = amp; q[1] = freq; q[2] = offset[0]; q[3] = offset[1]; q[4] = offset[2];
    b->n_params += FR_NOISE_PARAMS;
    return fr__emit(b, FR_OP_NOISE, p.x, p.y, p.z, b->n_params - FR_NOISE_PARAMS, 0.0);
}

FR_DEF fr_node_t fr_noise_gardner(fr_builder_t *b, fr_p3_t p, double amp, double freq, double phase)
{
    fr_node_t s[3], ser[3];
    int i;
    if (!fr__prim_ok(b, p, NULL, "hfNoiseG")) return FR_NODE_NONE;
    if (!isfinite(amp) || !isfinite(freq) || !isfinite(phase))
        return fr__param_fail(b, "hfNoiseG", "parameters must be finite"), FR_NODE_NONE;
    for (i = 0; i < 3; i++) s[i] = fr_unary(b, FR_OP_SIN, fr__mulk(b, fr__coord(p, i), freq));
    /* Gardner's series: each axis term is modulated by the sine of the next-but-one axis */
    for (i = 0; i < 3; i++) {
        fr_node_t arg = fr_add(b, fr__mulk(b, fr__coord(p, i), freq / 1.35), fr__mulk(b, s[(i + 2) % 3], phase));
        ser[i] = fr_add(b, fr__mulk(b, s[i], amp), fr__mulk(b, fr_unary(b, FR_OP_SIN, arg), amp / 1.17));
    }
    return fr_mul(b, fr_mul(b, ser[0], ser[1]), ser[2]);
}

FR_DEF fr_node_t fr_callback(fr_builder_t *b, fr_p3_t p, const fr_callback_t *cb)
{
    unsigned int cap = b ? b->cap_callbacks : 0;
    if (!fr__prim_ok(b, p, NULL, "callback")) return FR_NODE_NONE;
    if (!cb || !cb->point) return fr__param_fail(b, "callback", "point function is NULL"), FR_NODE_NONE;
    if (!fr__grow(b, (void **)&b->callbacks, &cap, b->n_callbacks + 1, sizeof(fr_callback_t)))
        return fr__fail(b, FR_ERR_OUT_OF_MEMORY, "out of memory");
    b->cap_callbacks = cap;
    b->callbacks[b->n_callbacks] = *cb;
    return fr__emit(b, FR_OP_CALL, p.x, p.y, p.z, b->n_callbacks++, 0.0);
}

FR_DEF fr_node_t fr_from_sdf(fr_builder_t *b, fr_node_t sdf, double lipschitz)
{
    fr_node_t f;
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!fr__finite_pos(lipschitz)) return fr__param_fail(b, "sdf", "Lipschitz bound must be finite and > 0"), FR_NODE_NONE;
    f = fr_unary(b, FR_OP_NEG, sdf);
    if (f != FR_NODE_NONE) b->lip[f] = lipschitz;
    return f;
}

/* ---- operations */

static fr_node_t fr__rop(fr_builder_t *b, fr_op_t op, fr_node_t f1, fr_node_t f2, double alpha, const char *name)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!fr__ok(b, f1) || !fr__ok(b, f2)) return fr__param_fail(b, name, "invalid operand node"), FR_NODE_NONE;
    if (!fr__alpha_ok(b, alpha, name)) return FR_NODE_NONE;
    return fr__emit(b, op, f1, f2, 0, 0, alpha);
}

FR_DEF fr_node_t fr_union(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double alpha)
{
    return fr__rop(b, FR_OP_RUNI, f1, f2, alpha, "union");
}
FR_DEF fr_node_t fr_intersect(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double alpha)
{
    return fr__rop(b, FR_OP_RINT, f1, f2, alpha, "intersection");
}
FR_DEF fr_node_t fr_negate(fr_builder_t *b, fr_node_t f) { return fr_unary(b, FR_OP_NEG, f); }
FR_DEF fr_node_t fr_subtract(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double alpha)
{
    return fr__rop(b, FR_OP_RINT, f1, fr_negate(b, f2), alpha, "difference");
}

static fr_node_t fr__blend(fr_builder_t *b, fr_op_t op, fr_node_t f1, fr_node_t f2, double a0, double a1, double a2,
                           const char *name)
{
    fr_node_t den;
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!isfinite(a0) || !isfinite(a1) || !isfinite(a2) || a1 == 0 || a2 == 0)
        return fr__param_fail(b, name, "a0 must be finite, a1 and a2 finite and non-zero"), FR_NODE_NONE;
    /* HyperFun's displacement: the squares are summed in the denominator */
    den = fr__addk(b, fr_add(b, fr__sqr(b, fr__mulk(b, f1, 1.0 / a1)), fr__sqr(b, fr__mulk(b, f2, 1.0 / a2))), 1.0);
    return fr_add(b, fr__rop(b, op, f1, f2, 0.0, name), fr_div(b, fr_const(b, a0), den));
}
FR_DEF fr_node_t fr_blend_union(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double a0, double a1, double a2)
{
    return fr__blend(b, FR_OP_RUNI, f1, f2, a0, a1, a2, "blend union");
}
FR_DEF fr_node_t fr_blend_intersect(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double a0, double a1, double a2)
{
    return fr__blend(b, FR_OP_RINT, f1, f2, a0, a1, a2, "blend intersection");
}

static fr_node_t fr__smooth(fr_builder_t *b, fr_op_t op, fr_node_t f1, fr_node_t f2, double k, const char *name)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!fr__ok(b, f1) || !fr__ok(b, f2)) return fr__param_fail(b, name, "invalid operand node"), FR_NODE_NONE;
    if (!fr__finite_pos(k)) return fr__param_fail(b, name, "width must be finite and > 0"), FR_NODE_NONE;
    return fr__emit(b, op, f1, f2, 0, 0, k);
}
FR_DEF fr_node_t fr_smooth_union(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double k)
{
    return fr__smooth(b, FR_OP_SMAX, f1, f2, k, "smooth union");
}
FR_DEF fr_node_t fr_smooth_intersect(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double k)
{
    return fr__smooth(b, FR_OP_SMIN, f1, f2, k, "smooth intersection");
}

FR_DEF fr_node_t fr_offset(fr_builder_t *b, fr_node_t f, double d)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!isfinite(d)) return fr__param_fail(b, "offset", "distance must be finite"), FR_NODE_NONE;
    return fr_add(b, f, fr_const(b, d));
}

FR_DEF fr_node_t fr_morph(fr_builder_t *b, fr_node_t f1, fr_node_t f2, double t)
{
    if (!b || b->diag.result != FR_OK) return FR_NODE_NONE;
    if (!isfinite(t)) return fr__param_fail(b, "metamorphosis", "parameter must be finite"), FR_NODE_NONE;
    return fr_add(b, fr__mulk(b, f1, 1.0 - t), fr__mulk(b, f2, t));
}

/* ---- space maps */

static fr_p3_t fr__p3(fr_node_t x, fr_node_t y, fr_node_t z)
{
    fr_p3_t p;
    p.x = x; p.y = y; p.z = z;
    return p;
}
static fr_p3_t fr__p3_none(void) { return fr__p3(FR_NODE_NONE, FR_NODE_NONE, FR_NODE_NONE); }
static fr_p3_t fr__p3_set(fr_p3_t p, int i, fr_node_t v)
{
    if (i == 0) p.x = v; else if (i == 1) p.y = v; else p.z = v;
    return p;
}

FR_DEF fr_p3_t fr_translate(fr_builder_t *b, fr_p3_t p, const double d[3])
{
    if (!fr__prim_ok(b, p, d, "shift")) return fr__p3_none();
    return fr__p3(fr__subk(b, p.x, d[0]), fr__subk(b, p.y, d[1]), fr__subk(b, p.z, d[2]));
}

FR_DEF fr_p3_t fr_scale(fr_builder_t *b, fr_p3_t p, const double s[3])
{
    if (!fr__prim_ok(b, p, s, "scale")) return fr__p3_none();
    if (s[0] == 0 || s[1] == 0 || s[2] == 0) return fr__param_fail(b, "scale", "a factor is zero"), fr__p3_none();
    return fr__p3(fr__mulk(b, p.x, 1.0 / s[0]), fr__mulk(b, p.y, 1.0 / s[1]), fr__mulk(b, p.z, 1.0 / s[2]));
}

/* (u, v) -> (u cos + v sin, -u sin + v cos) with (u, v) the cyclic pair
   after axis: (y,z) for x, (z,x) for y, (x,y) for z, as HyperFun's
   hfRotate3D and hfTwist have it; the angle is a node (twist, bend) or a
   constant (rotate) */
static fr_p3_t fr__rotate_by(fr_builder_t *b, fr_p3_t p, int axis, fr_node_t ct, fr_node_t st)
{
    int iu = (axis + 1) % 3, iv = (axis + 2) % 3;
    fr_node_t u = fr__coord(p, iu), v = fr__coord(p, iv);
    fr_node_t nu = fr_add(b, fr_mul(b, u, ct), fr_mul(b, v, st));
    fr_node_t nv = fr_sub(b, fr_mul(b, v, ct), fr_mul(b, u, st));
    return fr__p3_set(fr__p3_set(p, iu, nu), iv, nv);
}

FR_DEF fr_p3_t fr_rotate(fr_builder_t *b, fr_p3_t p, int axis, double theta)
{
    if (!fr__prim_ok(b, p, NULL, "rotate") || !fr__axis_ok(b, axis, "rotate")) return fr__p3_none();
    if (!isfinite(theta)) return fr__param_fail(b, "rotate", "angle must be finite"), fr__p3_none();
    return fr__rotate_by(b, p, axis, fr_const(b, cos(theta)), fr_const(b, sin(theta)));
}

FR_DEF fr_p3_t fr_affine(fr_builder_t *b, fr_p3_t p, const double m[9], const double t[3])
{
    fr_node_t r[3];
    int i, j;
    if (!fr__prim_ok(b, p, t, "affine")) return fr__p3_none();
    for (i = 0; i < 9; i++)
        if (!m || !isfinite(m[i])) return fr__param_fail(b, "affine", "matrix is NULL or not finite"), fr__p3_none();
    for (i = 0; i < 3; i++) {
        fr_node_t acc = fr_const(b, t[i]);
        for (j = 0; j < 3; j++)
            if (m[3 * i + j] != 0) acc = fr_add(b, acc, fr__mulk(b, fr__coord(p, j), m[3 * i + j]));
        r[i] = acc;
    }
    return fr__p3(r[0], r[1], r[2]);
}

FR_DEF fr_p3_t fr_twist(fr_builder_t *b, fr_p3_t p, int axis, double s1, double s2, double th1, double th2)
{
    fr_node_t t, th;
    if (!fr__prim_ok(b, p, NULL, "twist") || !fr__axis_ok(b, axis, "twist")) return fr__p3_none();
    if (!isfinite(s1) || !isfinite(s2) || !isfinite(th1) || !isfinite(th2) || s1 == s2)
        return fr__param_fail(b, "twist", "parameters must be finite with s1 != s2"), fr__p3_none();
    t = fr__mulk(b, fr__subk(b, fr__coord(p, axis), s1), 1.0 / (s2 - s1));
    th = fr__addk(b, fr__mulk(b, t, th2 - th1), th1);
    return fr__rotate_by(b, p, axis, fr_unary(b, FR_OP_COS, th), fr_unary(b, FR_OP_SIN, th));
}

FR_DEF fr_p3_t fr_taper(fr_builder_t *b, fr_p3_t p, int axis, double s1, double s2, double sc1, double sc2)
{
    fr_node_t t, sc;
    int i;
    if (!fr__prim_ok(b, p, NULL, "taper") || !fr__axis_ok(b, axis, "taper")) return fr__p3_none();
    if (!isfinite(s1) || !isfinite(s2) || !(s2 > s1) || !fr__finite_pos(sc1) || !fr__finite_pos(sc2))
        return fr__param_fail(b, "taper", "need s2 > s1 and positive finite scales"), fr__p3_none();
    t = fr__mulk(b, fr__subk(b, fr__coord(p, axis), s1), 1.0 / (s2 - s1));
    t = fr_binary(b, FR_OP_MIN, fr_binary(b, FR_OP_MAX, t, fr_const(b, 0.0)), fr_const(b, 1.0));
    sc = fr__addk(b, fr__mulk(b, t, sc2 - sc1), sc1);
    for (i = 0; i < 3; i++)
        if (i != axis) p = fr__p3_set(p, i, fr_div(b, fr__coord(p, i), sc));
    return p;
}

FR_DEF fr_p3_t fr_stretch(fr_builder_t *b, fr_p3_t p, const double c[3], const double s[3])
{
    int i;
    if (!fr__prim_ok(b, p, c, "stretch") || !fr__prim_ok(b, p, s, "stretch")) return fr__p3_none();
    if (s[0] == 0 || s[1] == 0 || s[2] == 0) return fr__param_fail(b, "stretch", "a factor is zero"), fr__p3_none();
    for (i = 0; i < 3; i++)
        p = fr__p3_set(p, i, fr__addk(b, fr__mulk(b, fr__subk(b, fr__coord(p, i), c[i]), 1.0 / s[i]), c[i]));
    return p;
}

FR_DEF fr_p3_t fr_bend(fr_builder_t *b, fr_p3_t p, int axis, double k)
{
    int iu = (axis + 1) % 3;
    fr_node_t th;
    if (!fr__prim_ok(b, p, NULL, "bend") || !fr__axis_ok(b, axis, "bend")) return fr__p3_none();
    if (!isfinite(k)) return fr__param_fail(b, "bend", "curvature must be finite"), fr__p3_none();
    th = fr__mulk(b, fr__coord(p, iu), k);
    return fr__rotate_by(b, p, axis, fr_unary(b, FR_OP_COS, th), fr_unary(b, FR_OP_SIN, th));
}

/* ---- finishing: keep what the outputs use */

/* Lipschitz bound of each slot from its operands (Euclidean gradient norm);
   INFINITY where no simple rule applies. A declared bound (fr_from_sdf)
   takes precedence. */
static double fr__lip_rule(const fr_instr_t *in, const double *L, const fr_instr_t *code)
{
    double la = L[in->a], lb = L[in->b];
    switch ((fr_op_t)in->op) {
    case FR_OP_CONST: return 0.0;
    case FR_OP_VAR_X: case FR_OP_VAR_Y: case FR_OP_VAR_Z: return 1.0;
    case FR_OP_NEG: case FR_OP_ABS: return la;
    case FR_OP_ADD: case FR_OP_SUB: return la + lb;
    case FR_OP_MIN: case FR_OP_MAX: case FR_OP_SMAX: case FR_OP_SMIN: return la > lb ? la : lb;
    case FR_OP_RUNI: case FR_OP_RINT: return in->k == 1.0 ? (la > lb ? la : lb) : INFINITY;
    case FR_OP_MUL:
        if (code[in->a].op == FR_OP_CONST) return fabs(code[in->a].k) * lb;
        if (code[in->b].op == FR_OP_CONST) return fabs(code[in->b].k) * la;
        return INFINITY;
    case FR_OP_DIV:
        if (code[in->b].op == FR_OP_CONST) return la / fabs(code[in->b].k);
        return INFINITY;
    case FR_OP_SIN: case FR_OP_COS: case FR_OP_ATAN: return la;
    default: return INFINITY;
    }
}

/* Copy the live instructions of src (those reachable from outs through rep,
   where rep[i] is the slot standing in for slot i) into dst in order, and
   renumber. live and newidx are scratch of n entries. Returns the count. */
static unsigned int fr__compact(const fr_instr_t *src, unsigned int n, const unsigned int *rep, const unsigned int *outs,
                                unsigned int n_outs, unsigned char *live, unsigned int *newidx, fr_instr_t *dst,
                                unsigned int *new_outs)
{
    unsigned int i, m = 0;
    memset(live, 0, n);
    for (i = 0; i < n_outs; i++) live[rep[outs[i]]] = 1;
    for (i = n; i-- > 0;) {
        int ar;
        if (!live[i]) continue;
        FR_ASSERT(rep[i] == i);
        ar = fr__arity(src[i].op);
        if (ar >= 1) live[rep[src[i].a]] = 1;
        if (ar >= 2) live[rep[src[i].b]] = 1;
        if (ar >= 3) live[rep[src[i].c]] = 1;
    }
    for (i = 0; i < n; i++) {
        fr_instr_t in;
        int ar;
        if (!live[i]) continue;
        in = src[i];
        ar = fr__arity(in.op);
        in.a = ar >= 1 ? newidx[rep[in.a]] : 0;
        in.b = ar >= 2 ? newidx[rep[in.b]] : 0;
        in.c = ar >= 3 ? newidx[rep[in.c]] : 0;
        newidx[i] = m;
        dst[m++] = in;
    }
    for (i = 0; i < n_outs; i++) new_outs[i] = newidx[rep[outs[i]]];
    return m;
}

FR_DEF fr_result_t fr_builder_finish(fr_builder_t *b, fr_node_t shape, const fr_node_t *attrs, unsigned int n_attrs,
                                     fr_tape_t *out, fr_diag_t *diag)
{
    unsigned int outs[FR_MAX_OUTPUTS], i, n, m;
    size_t code_bytes, param_bytes, cb_bytes, work_bytes;
    unsigned char *mem, *live;
    unsigned int *rep, *newidx;
    fr_instr_t *code;
    double *L;
    fr_result_t r = FR_OK;
    if (diag) {
        memset(diag, 0, sizeof *diag);
        diag->element = -1;
    }
    if (!b || !out) return FR_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (b->diag.result == FR_OK) {
        if (!fr__ok(b, shape)) fr__fail(b, FR_ERR_INVALID_ARG, "finish: invalid shape node");
        else if (n_attrs > FR_MAX_OUTPUTS - 1 || (n_attrs && !attrs))
            fr__fail(b, FR_ERR_INVALID_ARG, "finish: too many attributes (FR_MAX_OUTPUTS)");
        else
            for (i = 0; i < n_attrs; i++)
                if (!fr__ok(b, attrs[i])) fr__fail(b, FR_ERR_INVALID_ARG, "finish: invalid attribute node");
    }
    if (b->diag.result != FR_OK) {
        if (diag) *diag = b->diag;
        return b->diag.result;
    }
    n = b->n;
    outs[0] = shape;
    for (i = 0; i < n_attrs; i++) outs[i + 1] = attrs[i];
    code_bytes = (size_t)n * sizeof(fr_instr_t);
    param_bytes = (size_t)b->n_params * sizeof(double);
    cb_bytes = (size_t)b->n_callbacks * sizeof(fr_callback_t);
    work_bytes = (size_t)n * (2 * sizeof(unsigned int) + sizeof(double) + 1);
    mem = (unsigned char *)FR_MALLOC(code_bytes + param_bytes + cb_bytes + work_bytes + 16, b->alloc_ctx);
    if (!mem) {
        r = FR_ERR_OUT_OF_MEMORY;
        if (diag) {
            diag->result = r;
            snprintf(diag->message, sizeof diag->message, "out of memory compiling %u nodes", n);
        }
        return r;
    }
    code = (fr_instr_t *)mem;
    if (param_bytes) memcpy(mem + code_bytes, b->params, param_bytes);
    if (cb_bytes) memcpy(mem + code_bytes + param_bytes, b->callbacks, cb_bytes);
    /* work area after the kept data; it is reused, never exposed */
    L = (double *)(void *)(mem + code_bytes + param_bytes + cb_bytes);
    rep = (unsigned int *)(void *)(L + n);
    newidx = rep + n;
    live = (unsigned char *)(newidx + n);
    for (i = 0; i < n; i++) {
        rep[i] = i;
        L[i] = 0.0;
    }
    m = fr__compact(b->code, n, rep, outs, n_attrs + 1, live, newidx, code, out->outputs);
    /* Lipschitz bounds on the compacted tape, with declared bounds carried over */
    {
        unsigned int j = 0;
        for (i = 0; i < n; i++)
            if (live[i]) {
                double d = b->lip[i];
                L[j] = d > 0 ? d : fr__lip_rule(&code[j], L, code);
                j++;
            }
        out->lipschitz = m ? L[out->outputs[0]] : INFINITY;
    }
    out->code = code;
    out->n_code = m;
    out->params = b->n_params ? (const double *)(void *)(mem + code_bytes) : NULL;
    out->n_params = b->n_params;
    out->callbacks = b->n_callbacks ? (const fr_callback_t *)(void *)(mem + code_bytes + param_bytes) : NULL;
    out->n_callbacks = b->n_callbacks;
    out->n_outputs = n_attrs + 1;
    out->alloc_ctx = b->alloc_ctx;
    out->owned = mem;
    for (i = 0; i < b->n_callbacks; i++) {
        if (!b->callbacks[i].grad) out->flags |= FR_TAPE_NO_GRADIENT;
#ifndef FR_NO_INTERVAL
        if (!b->callbacks[i].interval) out->flags |= FR_TAPE_NO_INTERVAL;
#endif
    }
    return FR_OK;
}

FR_DEF void fr_tape_free(fr_tape_t *t)
{
    if (!t) return;
    if (t->owned) FR_FREE(t->owned, t->alloc_ctx);
    memset(t, 0, sizeof *t);
}

/* ---- gradient noise (Perlin's improved noise, our own tables) */

static const unsigned char fr__perm[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};
/* the 12 cube-edge directions, padded to 16 (two non-zero unit components each) */
static const signed char fr__grad3[16][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
                                             {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1},
                                             {1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1}};

/* Value and gradient of the noise at u. Each of the 8 lattice corners
   contributes w(corner) * (g . d) with |g . d| <= 2 (two unit components,
   |d_i| <= 1) and the weights a partition of unity: |value| <= 2. The
   fade 6t^5-15t^4+10t^3 has slope <= 15/8, so |d value/du_i| <=
   2 * 15/8 * 2 + 1 = 8.5: the bounds FR__NOISE_MAX and FR__NOISE_LIP. */
#define FR__NOISE_MAX 2.0
#define FR__NOISE_LIP 8.5
static double fr__gnoise(const double u[3], double g[3])
{
    double fl[3], fr[3], w[3], dw[3], v = 0;
    int i, cx, cy, cz, ix[3];
    for (i = 0; i < 3; i++) {
        double t;
        fl[i] = floor(u[i]);
        fr[i] = u[i] - fl[i];
        t = fr[i];
        w[i] = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
        dw[i] = 30.0 * t * t * (t * (t - 2.0) + 1.0);
        ix[i] = (int)(fmod(fl[i], 256.0) + 256.0) & 255;
    }
    if (g) g[0] = g[1] = g[2] = 0;
    for (cx = 0; cx < 2; cx++)
        for (cy = 0; cy < 2; cy++)
            for (cz = 0; cz < 2; cz++) {
                int h = fr__perm[(fr__perm[(fr__perm[(ix[0] + cx) & 255] + ix[1] + cy) & 255] + ix[2] + cz) & 255] & 15;
                double d0 = fr[0] - cx, d1 = fr[1] - cy, d2 = fr[2] - cz;
                double dot = fr__grad3[h][0] * d0 + fr__grad3[h][1] * d1 + fr__grad3[h][2] * d2;
                double wx = cx ? w[0] : 1 - w[0], wy = cy ? w[1] : 1 - w[1], wz = cz ? w[2] : 1 - w[2];
                double sx = cx ? dw[0] : -dw[0], sy = cy ? dw[1] : -dw[1], sz = cz ? dw[2] : -dw[2];
                v += wx * wy * wz * dot;
                if (g) {
                    g[0] += sx * wy * wz * dot + wx * wy * wz * fr__grad3[h][0];
                    g[1] += wx * sy * wz * dot + wx * wy * wz * fr__grad3[h][1];
                    g[2] += wx * wy * sz * dot + wx * wy * wz * fr__grad3[h][2];
                }
            }
    return v;
}

static double fr__noise_at(const double *q, double x, double y, double z, double g[3])
{
    double u[3], v;
    u[0] = q[1] * x + q[2];
    u[1] = q[1] * y + q[3];
    u[2] = q[1] * z + q[4];
    v = q[0] * fr__gnoise(u, g);
    if (g) {
        g[0] *= q[0] * q[1];
        g[1] *= q[0] * q[1];
        g[2] *= q[0] * q[1];
    }
    return v;
}

/* ---- scalar semantics of each opcode, shared by the point and batch paths */

/* R-functions (HyperFun): alpha == 1 is exactly max/min; otherwise
   a + b +- sqrt(a^2 + b^2 - 2 alpha a b), with the radicand written as
   (a - alpha b)^2 + (1 - alpha^2) b^2 so it is never negative. */
/* sqrt((a - alpha b)^2 + (1 - alpha^2) b^2), rescaled when the squares
   would overflow or underflow (|arguments| beyond 2^+-500), so blends of
   huge or tiny field values stay finite */
#define FR__RROOT_BIG 3.2733906078961419e150   /* 2^500 */
#define FR__RROOT_SMALL 3.0549363634996047e-151 /* 2^-500 */
static inline double fr__rroot(double a, double b, double al)
{
    double t = a - al * b, u = b, m = fabs(t) > fabs(u) ? fabs(t) : fabs(u);
    if (m > FR__RROOT_BIG || (m < FR__RROOT_SMALL && m > 0)) {
        t /= m;
        u /= m;
        return m * sqrt(t * t + (1.0 - al * al) * u * u);
    }
    return sqrt(t * t + (1.0 - al * al) * u * u);
}
/* a + b + sg s, sg = 1 (R-union) or -1 (R-intersection), s = fr__rroot.
   Where a + b and sg s have opposite signs the sum cancels: with alpha = 0
   the intersection of a = 1e17 and b = -1 came out 0 (on the surface) for
   a point 1 outside of b. There it is computed as 2 (1 + alpha) a b /
   (a + b - sg s), the same value since (a + b)^2 - s^2 = 2 (1 + alpha) a b,
   with no difference of near-equal terms; the product is formed as
   a (b / (a + b - sg s)) so that a b cannot overflow. Every other case
   (no cancellation, or a + b overflowing) adds as written. */
static inline double fr__rsum(double a, double b, double al, double s, double sg)
{
    double t = a + b;
    if (sg * t < 0 && fabs(t) < HUGE_VAL) return (2.0 * (1.0 + al)) * (a * (b / (t - sg * s)));
    return t + sg * s;
}
static inline double fr__runi(double a, double b, double al)
{
    return al == 1.0 ? (a > b ? a : b) : fr__rsum(a, b, al, fr__rroot(a, b, al), 1.0);
}
static inline double fr__rint(double a, double b, double al)
{
    return al == 1.0 ? (a < b ? a : b) : fr__rsum(a, b, al, fr__rroot(a, b, al), -1.0);
}
/* polynomial smooth max/min: h = max(k - |a-b|, 0)/k, max + h^2 k/4 */
static inline double fr__smax(double a, double b, double k)
{
    double h = k - fabs(a - b);
    h = h > 0 ? h / k : 0;
    return (a > b ? a : b) + h * h * k * 0.25;
}
static inline double fr__smin(double a, double b, double k)
{
    double h = k - fabs(a - b);
    h = h > 0 ? h / k : 0;
    return (a < b ? a : b) - h * h * k * 0.25;
}
static inline double fr__powi(double a, int n)
{
    double r = 1.0, x = a;
    unsigned int m = (unsigned int)(n < 0 ? -n : n);
    while (m) {
        if (m & 1u) r *= x;
        x *= x;
        m >>= 1;
    }
    return n < 0 ? 1.0 / r : r;
}

static double fr__call_point(const fr_tape_t *t, const fr_instr_t *in, double x, double y, double z)
{
    double p[3];
    p[0] = x; p[1] = y; p[2] = z;
    return t->callbacks[in->aux].point(p, t->callbacks[in->aux].user);
}

/* ---- point evaluation */

static void fr__run_point(const fr_tape_t *t, const double p[3], double *v)
{
    const fr_instr_t *code = t->code;
    unsigned int i, n = t->n_code;
    for (i = 0; i < n; i++) {
        const fr_instr_t *in = &code[i];
        double a = v[in->a], c = v[in->b], r;
        switch ((fr_op_t)in->op) {
        case FR_OP_CONST: r = in->k; break;
        case FR_OP_VAR_X: r = p[0]; break;
        case FR_OP_VAR_Y: r = p[1]; break;
        case FR_OP_VAR_Z: r = p[2]; break;
        case FR_OP_NEG: r = -a; break;
        case FR_OP_SQR: r = a * a; break;
        case FR_OP_SQRT: r = sqrt(a); break;
        case FR_OP_ABS: r = fabs(a); break;
        case FR_OP_EXP: r = exp(a); break;
        case FR_OP_LOG: r = log(a); break;
        case FR_OP_SIN: r = sin(a); break;
        case FR_OP_COS: r = cos(a); break;
        case FR_OP_ATAN: r = atan(a); break;
        case FR_OP_POWI: r = fr__powi(a, (int)in->k); break;
        case FR_OP_POWC: r = pow(a, in->k); break;
        case FR_OP_ADD: r = a + c; break;
        case FR_OP_SUB: r = a - c; break;
        case FR_OP_MUL: r = a * c; break;
        case FR_OP_DIV: r = a / c; break;
        case FR_OP_MIN: r = a < c ? a : c; break;
        case FR_OP_MAX: r = a > c ? a : c; break;
        case FR_OP_RUNI: r = fr__runi(a, c, in->k); break;
        case FR_OP_RINT: r = fr__rint(a, c, in->k); break;
        case FR_OP_SMAX: r = fr__smax(a, c, in->k); break;
        case FR_OP_SMIN: r = fr__smin(a, c, in->k); break;
        case FR_OP_NOISE: r = fr__noise_at(t->params + in->aux, a, c, v[in->c], NULL); break;
        case FR_OP_CALL: r = fr__call_point(t, in, a, c, v[in->c]); break;
        default: r = NAN; break;
        }
        v[i] = r;
    }
}

/* Scratch bytes per instruction of each evaluation kind. */
static inline size_t fr__scratch_per_instr(fr_eval_kind_t kind)
{
    switch (kind) {
    case FR_EVAL_POINT: return sizeof(double);
    case FR_EVAL_BATCH: return FR_BATCH * sizeof(double);
    case FR_EVAL_GRAD: return 4 * sizeof(double);
#ifndef FR_NO_INTERVAL
    case FR_EVAL_INTERVAL: return sizeof(iv_t);
#ifndef IV_NO_AFFINE
    case FR_EVAL_AFFINE: return sizeof(iv_affine_t) + sizeof(iv_t);
#else
    case FR_EVAL_AFFINE: return 0;
#endif
    case FR_EVAL_PRUNE: return sizeof(iv_t) + 3 * sizeof(unsigned int) + 2;
#else
    case FR_EVAL_INTERVAL: case FR_EVAL_AFFINE: case FR_EVAL_PRUNE: return 0;
#endif
    }
    return 0;
}

FR_DEF size_t fr_scratch_size(const fr_tape_t *t, fr_eval_kind_t kind)
{
    size_t n = t ? (size_t)t->n_code : 0;
    if (n == 0) n = 1;
    return n * fr__scratch_per_instr(kind);
}

FR_DEF double fr_eval(const fr_tape_t *t, const double p[3], void *scratch)
{
    double *v = (double *)scratch;
    if (!t || !p || !v || t->n_code == 0) return NAN;
    fr__run_point(t, p, v);
    return v[t->outputs[0]];
}

FR_DEF void fr_eval_outputs(const fr_tape_t *t, const double p[3], void *scratch, double *out)
{
    double *v = (double *)scratch;
    unsigned int i;
    if (!t || !p || !v || !out || t->n_code == 0) return;
    fr__run_point(t, p, v);
    for (i = 0; i < t->n_outputs; i++) out[i] = v[t->outputs[i]];
}

/* ---- batch evaluation: one instruction at a time over FR_BATCH lanes, so
   each case is a plain loop over contiguous doubles that the compiler
   vectorises; transcendental cases call libm per lane */
/* The lanes of one instruction never overlap its operands' lanes (slot i
   reads slots < i), which the compiler cannot see; we tell it, and every
   loop runs exactly FR_BATCH lanes so no scalar epilogue is needed (gcc's
   -O2 cost model vectorises only such loops). */
#if defined(__clang__)
   /* clang vectorises these loops with a run-time overlap check at -O2; a
      forced request would be reported (-Wpass-failed) where it cannot */
#  define FR__IVDEP
#elif defined(__GNUC__)
#  define FR__IVDEP _Pragma("GCC ivdep")
#else
#  define FR__IVDEP
#endif
#define FR__LANES(expr)                                      \
    do {                                                     \
        FR__IVDEP                                            \
        for (j = 0; j < FR_BATCH; j++) r[j] = (expr);        \
    } while (0)
/* lanes that call out (noise, callbacks, pow): no vectorisation request,
   which clang would otherwise report as failed */
#define FR__LANES_CALL(expr)                                 \
    do {                                                     \
        for (j = 0; j < FR_BATCH; j++) r[j] = (expr);        \
    } while (0)

static void fr__run_batch(const fr_tape_t *t, const double *x, const double *y, const double *z, double *v)
{
    const fr_instr_t *code = t->code;
    unsigned int i, j, n = t->n_code;
    for (i = 0; i < n; i++) {
        const fr_instr_t *in = &code[i];
        double *r = v + (size_t)i * FR_BATCH;
        const double *A = v + (size_t)in->a * FR_BATCH, *B = v + (size_t)in->b * FR_BATCH;
        const double k = in->k;
        switch ((fr_op_t)in->op) {
        case FR_OP_CONST: FR__LANES(k); break;
        case FR_OP_VAR_X: FR__LANES(x[j]); break;
        case FR_OP_VAR_Y: FR__LANES(y[j]); break;
        case FR_OP_VAR_Z: FR__LANES(z[j]); break;
        case FR_OP_NEG: FR__LANES(-A[j]); break;
        case FR_OP_SQR: FR__LANES(A[j] * A[j]); break;
        case FR_OP_SQRT: FR__LANES(sqrt(A[j])); break;
        case FR_OP_ABS: FR__LANES(fabs(A[j])); break;
        case FR_OP_EXP: FR__LANES(exp(A[j])); break;
        case FR_OP_LOG: FR__LANES(log(A[j])); break;
        case FR_OP_SIN: FR__LANES(sin(A[j])); break;
        case FR_OP_COS: FR__LANES(cos(A[j])); break;
        case FR_OP_ATAN: FR__LANES(atan(A[j])); break;
        case FR_OP_POWI: FR__LANES(fr__powi(A[j], (int)k)); break;
        case FR_OP_POWC: FR__LANES(pow(A[j], k)); break;
        case FR_OP_ADD: FR__LANES(A[j] + B[j]); break;
        case FR_OP_SUB: FR__LANES(A[j] - B[j]); break;
        case FR_OP_MUL: FR__LANES(A[j] * B[j]); break;
        case FR_OP_DIV: FR__LANES(A[j] / B[j]); break;
        case FR_OP_MIN: FR__LANES(A[j] < B[j] ? A[j] : B[j]); break;
        case FR_OP_MAX: FR__LANES(A[j] > B[j] ? A[j] : B[j]); break;
        case FR_OP_RUNI: FR__LANES(fr__runi(A[j], B[j], k)); break;
        case FR_OP_RINT: FR__LANES(fr__rint(A[j], B[j], k)); break;
        case FR_OP_SMAX: FR__LANES(fr__smax(A[j], B[j], k)); break;
        case FR_OP_SMIN: FR__LANES(fr__smin(A[j], B[j], k)); break;
        case FR_OP_NOISE: {
            const double *C = v + (size_t)in->c * FR_BATCH;
            FR__LANES_CALL(fr__noise_at(t->params + in->aux, A[j], B[j], C[j], NULL));
            break;
        }
        case FR_OP_CALL: {
            const double *C = v + (size_t)in->c * FR_BATCH;
            FR__LANES_CALL(fr__call_point(t, in, A[j], B[j], C[j]));
            break;
        }
        default: FR__LANES(NAN); break;
        }
    }
}
#undef FR__LANES
#undef FR__LANES_CALL
#undef FR__IVDEP

FR_DEF void fr_eval_batch(const fr_tape_t *t, size_t n, const double *x, const double *y, const double *z, double *out,
                          void *scratch)
{
    double *v = (double *)scratch;
    size_t s;
    if (!t || !x || !y || !z || !out || !v || t->n_code == 0) return;
    for (s = 0; s < n; s += FR_BATCH) {
        unsigned int m = (unsigned int)(n - s < FR_BATCH ? n - s : FR_BATCH), j;
        const double *r = v + (size_t)t->outputs[0] * FR_BATCH;
        if (m == FR_BATCH)
            fr__run_batch(t, x + s, y + s, z + s, v);
        else { /* the tail: pad a full batch with copies of the last point */
            double px[FR_BATCH], py[FR_BATCH], pz[FR_BATCH];
            for (j = 0; j < FR_BATCH; j++) {
                size_t q = s + (j < m ? j : m - 1);
                px[j] = x[q];
                py[j] = y[q];
                pz[j] = z[q];
            }
            fr__run_batch(t, px, py, pz, v);
        }
        for (j = 0; j < m; j++) out[s + j] = r[j];
    }
}

/* ---- forward-mode AD: each slot holds (value, d/dx, d/dy, d/dz) */

static fr_result_t fr__run_grad(const fr_tape_t *t, const double p[3], double *v)
{
    const fr_instr_t *code = t->code;
    unsigned int i, n = t->n_code;
    int d;
    for (i = 0; i < n; i++) {
        const fr_instr_t *in = &code[i];
        const double *A = v + 4 * (size_t)in->a, *B = v + 4 * (size_t)in->b;
        double *R = v + 4 * (size_t)i;
        double a = A[0], c = B[0], da = 0, db = 0, val; /* R' = da A' + db B' */
        switch ((fr_op_t)in->op) {
        case FR_OP_CONST: R[0] = in->k; R[1] = R[2] = R[3] = 0; continue;
        case FR_OP_VAR_X: case FR_OP_VAR_Y: case FR_OP_VAR_Z:
            R[0] = p[in->op - FR_OP_VAR_X];
            R[1] = R[2] = R[3] = 0;
            R[1 + in->op - FR_OP_VAR_X] = 1;
            continue;
        case FR_OP_NEG: val = -a; da = -1; break;
        case FR_OP_SQR: val = a * a; da = 2 * a; break;
        case FR_OP_SQRT: val = sqrt(a); da = 0.5 / val; break;
        case FR_OP_ABS: val = fabs(a); da = a < 0 ? -1 : 1; break;
        case FR_OP_EXP: val = exp(a); da = val; break;
        case FR_OP_LOG: val = log(a); da = 1 / a; break;
        case FR_OP_SIN: val = sin(a); da = cos(a); break;
        case FR_OP_COS: val = cos(a); da = -sin(a); break;
        case FR_OP_ATAN: val = atan(a); da = 1 / (1 + a * a); break;
        /* x^0 is the constant 1: its derivative 0, not 0 * inf at x = 0 */
        case FR_OP_POWI: val = fr__powi(a, (int)in->k); da = in->k == 0 ? 0.0 : in->k * fr__powi(a, (int)in->k - 1); break;
        case FR_OP_POWC: val = pow(a, in->k); da = in->k * pow(a, in->k - 1); break;
        case FR_OP_ADD: val = a + c; da = 1; db = 1; break;
        case FR_OP_SUB: val = a - c; da = 1; db = -1; break;
        case FR_OP_MUL: val = a * c; da = c; db = a; break;
        case FR_OP_DIV: val = a / c; da = 1 / c; db = -val / c; break;
        case FR_OP_MIN: if (a <= c) { val = a; da = 1; } else { val = c; db = 1; } break;
        case FR_OP_MAX: if (a >= c) { val = a; da = 1; } else { val = c; db = 1; } break;
        case FR_OP_RUNI: case FR_OP_RINT: {
            double al = in->k, sg = in->op == FR_OP_RUNI ? 1.0 : -1.0;
            if (al == 1.0) {
                int first = in->op == FR_OP_RUNI ? a >= c : a <= c;
                val = first ? a : c;
                da = first; db = !first;
            } else {
                double s = fr__rroot(a, c, al);
                val = fr__rsum(a, c, al, s, sg);
                /* d s = ((a - alpha c) da + (c - alpha a) dc) / s; 0 at the kink s = 0 */
                da = 1 + (s > 0 ? sg * (a - al * c) / s : 0);
                db = 1 + (s > 0 ? sg * (c - al * a) / s : 0);
            }
            break;
        }
        case FR_OP_SMAX: case FR_OP_SMIN: {
            double k = in->k, h = k - fabs(a - c), sg = in->op == FR_OP_SMAX ? 1.0 : -1.0;
            int first = in->op == FR_OP_SMAX ? a >= c : a <= c;
            double e = h > 0 ? h / k : 0, de; /* d(h^2 k/4)/d(a-c) = -e/2 sign(a-c) */
            val = (first ? a : c) + sg * e * e * k * 0.25;
            de = sg * 0.5 * e * (a >= c ? -1.0 : 1.0);
            da = (first ? 1.0 : 0.0) + de;
            db = (first ? 0.0 : 1.0) - de;
            break;
        }
        case FR_OP_NOISE: case FR_OP_CALL: {
            const double *C = v + 4 * (size_t)in->c;
            double q[3], g[3];
            q[0] = a; q[1] = c; q[2] = C[0];
            if (in->op == FR_OP_NOISE)
                val = fr__noise_at(t->params + in->aux, a, c, C[0], g);
            else {
                const fr_callback_t *cb = &t->callbacks[in->aux];
                if (!cb->grad) return FR_ERR_NO_GRADIENT;
                val = cb->grad(q, cb->user, g);
            }
            R[0] = val;
            for (d = 1; d < 4; d++) R[d] = g[0] * A[d] + g[1] * B[d] + g[2] * C[d];
            continue;
        }
        default: val = NAN; break;
        }
        R[0] = val;
        for (d = 1; d < 4; d++) R[d] = (da != 0 ? da * A[d] : 0) + (db != 0 ? db * B[d] : 0);
    }
    return FR_OK;
}

FR_DEF fr_result_t fr_eval_grad(const fr_tape_t *t, const double p[3], void *scratch, double *value, double grad[3])
{
    double *v = (double *)scratch, *o;
    fr_result_t r;
    if (!t || !p || !v || !value || !grad || t->n_code == 0) return FR_ERR_INVALID_ARG;
    r = fr__run_grad(t, p, v);
    if (r != FR_OK) return r;
    o = v + 4 * (size_t)t->outputs[0];
    *value = o[0];
    grad[0] = o[1]; grad[1] = o[2]; grad[2] = o[3];
    return FR_OK;
}

#ifndef FR_NO_INTERVAL
/* ---- interval evaluation (paper section 3.1.2: Moore's inclusion) */

/* Rounding slack for values computed in plain double arithmetic (R-function
   and smooth-max endpoints, the noise centre value): each is a short
   expression whose rounding error is below 8 ulps of the magnitudes
   involved; 16 leaves a factor of two, relative to mag. */
#define FR__ROUND_SLACK (16.0 * DBL_EPSILON)
static iv_t fr__widen(double lo, double hi, double mag)
{
    double s = FR__ROUND_SLACK * mag + DBL_MIN;
    /* an overflowed corner value (inf or NaN) says nothing: open that end */
    lo = isfinite(lo) ? lo - s : -HUGE_VAL;
    hi = isfinite(hi) ? hi + s : HUGE_VAL;
    return iv_make(lo, hi);
}
static double fr__mag2(iv_t a, iv_t b)
{
    double m = fabs(a.lo);
    if (fabs(a.hi) > m) m = fabs(a.hi);
    if (fabs(b.lo) > m) m = fabs(b.lo);
    if (fabs(b.hi) > m) m = fabs(b.hi);
    return 4.0 * m;
}

/* R-functions with alpha in [0,1] and the smooth max/min are monotone
   non-decreasing in both arguments (|d sqrt/da| <= 1 since the radicand is
   (a - alpha b)^2 + (1 - alpha^2) b^2 >= (a - alpha b)^2), so their exact
   range over a box is spanned by the two corner values. */
static iv_t fr__iv_monotone2(const fr_instr_t *in, iv_t a, iv_t b)
{
    double lo, hi;
    if (iv_is_empty(a) || iv_is_empty(b)) return iv_empty();
    switch ((fr_op_t)in->op) {
    case FR_OP_RUNI:
        if (in->k == 1.0) return iv_max(a, b);
        lo = fr__runi(a.lo, b.lo, in->k); hi = fr__runi(a.hi, b.hi, in->k);
        break;
    case FR_OP_RINT:
        if (in->k == 1.0) return iv_min(a, b);
        lo = fr__rint(a.lo, b.lo, in->k); hi = fr__rint(a.hi, b.hi, in->k);
        break;
    case FR_OP_SMAX: lo = fr__smax(a.lo, b.lo, in->k); hi = fr__smax(a.hi, b.hi, in->k); break;
    default: lo = fr__smin(a.lo, b.lo, in->k); hi = fr__smin(a.hi, b.hi, in->k); break;
    }
    /* the smooth ops' k is a field value (their h^2 k / 4 term); an
       R-function's is alpha, a pure number: as a pad it swamped fields
       below 1e-15 (an alpha = 0.5 lens at 1e-100 enclosed as +-1.8e-15) */
    return fr__widen(lo, hi, fr__mag2(a, b) + (in->op == FR_OP_SMAX || in->op == FR_OP_SMIN ? in->k : 0.0));
}

/* Noise over a box: the value at the centre plus the Lipschitz bound times
   the l1 radius, clipped to |value| <= amp * FR__NOISE_MAX. The centre and
   radius are rounded outward; the slack covers the noise evaluation's own
   rounding and that of freq * x + offset. */
static iv_t fr__iv_noise(const double *q, iv_t x, iv_t y, iv_t z)
{
    iv_t box[3];
    double c[3], r = 0, v, amp = fabs(q[0]), bound = amp * FR__NOISE_MAX, scale = 0, slack;
    int i;
    box[0] = x; box[1] = y; box[2] = z;
    for (i = 0; i < 3; i++) {
        if (iv_is_empty(box[i])) return iv_empty();
        if (!isfinite(box[i].lo) || !isfinite(box[i].hi)) return iv_make(-bound, bound);
        c[i] = 0.5 * box[i].lo + 0.5 * box[i].hi;
        r += (box[i].hi - c[i] > c[i] - box[i].lo ? box[i].hi - c[i] : c[i] - box[i].lo);
        scale += fabs(q[1] * c[i]) + fabs(q[2 + i]);
    }
    r *= 1.0 + 4.0 * DBL_EPSILON;
    v = fr__noise_at(q, c[0], c[1], c[2], NULL);
    slack = FR__ROUND_SLACK * amp * (FR__NOISE_MAX + FR__NOISE_LIP * (scale + 1.0));
    r = amp * q[1] * FR__NOISE_LIP * r + slack;
    return iv_make(v - r > -bound ? v - r : -bound, v + r < bound ? v + r : bound);
}

/* x^n for 2 <= n <= FR__POWI_FAST by outward-rounded products, which for
   these n is as tight as iv_pow_n's double-double powering (the endpoints
   move by at most n ulps) and many times cheaper; the tangle cube and
   Barth's sextic spend most of their interval time here otherwise. Even n:
   |x|^n from the non-negative interval |x| (products of non-negative
   intervals are monotone, so exact up to rounding). Odd n: x^n is
   increasing, so it is the enclosures of lo^n and hi^n. */
#define FR__POWI_FAST 8
static iv_t fr__iv_powi(iv_t a, int n)
{
    iv_t r, m;
    int k;
    if (n < 2 || n > FR__POWI_FAST || !(a.lo > -HUGE_VAL && a.hi < HUGE_VAL)) return iv_pow_n(a, n);
    if (n % 2 == 0) {
        m = iv_abs(a);
        for (r = m, k = 1; k < n; k++) r = iv_mul(r, m);
        return r;
    }
    {
        iv_t lo = iv_point(a.lo), hi = iv_point(a.hi), pl = lo, ph = hi;
        for (k = 1; k < n; k++) { pl = iv_mul(pl, lo); ph = iv_mul(ph, hi); }
        return iv_make(pl.lo, ph.hi);
    }
}

/* one instruction in interval arithmetic; box is the VAR inputs */
static iv_t fr__iv_step(const fr_tape_t *t, const fr_instr_t *in, const iv_t *v, const iv_t box[3])
{
    iv_t a = v[in->a], c = v[in->b];
    switch ((fr_op_t)in->op) {
    case FR_OP_CONST: return iv_point(in->k);
    case FR_OP_VAR_X: return box[0];
    case FR_OP_VAR_Y: return box[1];
    case FR_OP_VAR_Z: return box[2];
    case FR_OP_NEG: return iv_neg(a);
    case FR_OP_SQR: return iv_sqr(a);
    case FR_OP_SQRT: return iv_sqrt(a);
    case FR_OP_ABS: return iv_abs(a);
    case FR_OP_EXP: return iv_exp(a);
    case FR_OP_LOG: return iv_log(a);
    case FR_OP_SIN: return iv_sin(a);
    case FR_OP_COS: return iv_cos(a);
    case FR_OP_ATAN: return iv_atan(a);
    case FR_OP_POWI: return fr__iv_powi(a, (int)in->k);
    case FR_OP_POWC: return iv_pow(a, iv_point(in->k));
    case FR_OP_ADD: return iv_add(a, c);
    case FR_OP_SUB: return iv_sub(a, c);
    case FR_OP_MUL: return iv_mul(a, c);
    case FR_OP_DIV: return iv_div(a, c);
    case FR_OP_MIN: return iv_min(a, c);
    case FR_OP_MAX: return iv_max(a, c);
    case FR_OP_RUNI: case FR_OP_RINT: case FR_OP_SMAX: case FR_OP_SMIN: return fr__iv_monotone2(in, a, c);
    case FR_OP_NOISE: return fr__iv_noise(t->params + in->aux, a, c, v[in->c]);
    case FR_OP_CALL: {
        const fr_callback_t *cb = &t->callbacks[in->aux];
        iv_t q[3];
        q[0] = a; q[1] = c; q[2] = v[in->c];
        /* tapes with a callback lacking an interval function are refused up front */
        return cb->interval ? cb->interval(q, cb->user) : iv_entire();
    }
    default: return iv_entire();
    }
}

static fr_result_t fr__run_interval(const fr_tape_t *t, const iv_t box[3], iv_t *v)
{
    unsigned int i, n = t->n_code;
    if (t->flags & FR_TAPE_NO_INTERVAL) return FR_ERR_NO_INTERVAL;
    for (i = 0; i < n; i++) v[i] = fr__iv_step(t, &t->code[i], v, box);
    return FR_OK;
}

static FR__NOINLINE fr_result_t fr__eval_interval(const fr_tape_t *t, const iv_t box[3], void *scratch, iv_t *out)
{
    iv_t *v = (iv_t *)scratch;
    fr_result_t r;
    if (!t || !box || !v || !out || t->n_code == 0) return FR_ERR_INVALID_ARG;
    if (t->flags & FR_TAPE_NO_INTERVAL) return FR_ERR_NO_INTERVAL;
    r = fr__run_interval(t, box, v);
    if (r == FR_OK) *out = v[t->outputs[0]];
    return r;
}

FR_DEF fr_result_t fr_eval_interval(const fr_tape_t *t, const iv_t box[3], void *scratch, iv_t *out)
{
    FR__IN_FP_ENV(fr_result_t, fr__eval_interval(t, box, scratch, out));
}

#ifndef IV_NO_AFFINE
/* ---- affine evaluation: elementary operations keep the correlation with
   the ray symbol; choice operations without an affine rule go through their
   exact interval image */
static iv_affine_t fr__af_monotone2(const fr_instr_t *in, iv_affine_t a, iv_affine_t b)
{
    iv_t r = fr__iv_monotone2(in, iv_from_affine(a), iv_from_affine(b));
    if ((in->op == FR_OP_RUNI || in->op == FR_OP_RINT) && in->k != 1.0) {
        /* a + b +- sqrt((a - alpha b)^2 + (1 - alpha^2) b^2) keeps eps_t; use it
           when it is the tighter of the two enclosures */
        iv_affine_t d = iv_affine_sub(a, iv_affine_mul_d(b, in->k));
        iv_affine_t s = iv_affine_sqrt(iv_affine_add(iv_affine_sqr(d), iv_affine_mul_d(iv_affine_sqr(b), 1.0 - in->k * in->k)));
        iv_affine_t f = in->op == FR_OP_RUNI ? iv_affine_add(iv_affine_add(a, b), s) : iv_affine_sub(iv_affine_add(a, b), s);
        iv_t fi = iv_from_affine(f);
        if (!iv_affine_is_empty(f) && iv_width(fi) < iv_width(r)) return f;
    }
    if (in->op == FR_OP_RUNI && in->k == 1.0) return iv_affine_max(a, b);
    if (in->op == FR_OP_RINT && in->k == 1.0) return iv_affine_min(a, b);
    return iv_affine_from_iv(r);
}

/* Affine evaluation runs an interval shadow beside the forms. Forms keep
   their correlation with the ray symbol even where they are wider than the
   interval (x^4 - 5x^2 cancels only in affine form); the shadow, the
   intersection of both enclosures, repairs an operand whose form leaves an
   operation's domain (an affine square dipping below 0 under a sqrt or a
   blend's denominator straddling 0) and bounds the output, so the result is
   never wider than plain interval evaluation. */
static iv_affine_t fr__af_repair(iv_affine_t x, iv_t shadow, int need_pos, int avoid_zero)
{
    iv_t r = iv_from_affine(x);
    if (iv_affine_is_empty(x) || !isfinite(r.lo) || !isfinite(r.hi) || (need_pos && r.lo < 0 && shadow.lo >= 0) ||
        (avoid_zero && r.lo <= 0 && r.hi >= 0 && !(shadow.lo <= 0 && shadow.hi >= 0)))
        return iv_affine_from_iv(shadow);
    return x;
}

static FR__NOINLINE fr_result_t fr__eval_affine(const fr_tape_t *t, const iv_affine_t p[3], void *scratch, iv_affine_t *out)
{
    iv_affine_t *v = (iv_affine_t *)scratch;
    iv_t *w, box[3];
    iv_affine_t zero;
    const fr_instr_t *code;
    unsigned int i, n;
    zero.c = zero.t = zero.e = 0.0;
    if (!t || !p || !v || !out || t->n_code == 0) return FR_ERR_INVALID_ARG;
    if (t->flags & FR_TAPE_NO_INTERVAL) return FR_ERR_NO_INTERVAL;
    code = t->code;
    n = t->n_code;
    w = (iv_t *)(void *)(v + n);
    for (i = 0; i < 3; i++) box[i] = iv_from_affine(p[i]);
    for (i = 0; i < n; i++) {
        const fr_instr_t *in = &code[i];
        int ar = fr__arity(in->op), dom = in->op == FR_OP_SQRT || in->op == FR_OP_LOG || in->op == FR_OP_POWC;
        iv_affine_t a = ar >= 1 ? fr__af_repair(v[in->a], w[in->a], dom, 0) : zero;
        iv_affine_t c = ar >= 2 ? fr__af_repair(v[in->b], w[in->b], 0, in->op == FR_OP_DIV) : zero;
        iv_affine_t r;
        iv_t ri, wi = fr__iv_step(t, in, w, box);
        switch ((fr_op_t)in->op) {
        case FR_OP_CONST: r = iv_affine_const(in->k); break;
        case FR_OP_VAR_X: r = p[0]; break;
        case FR_OP_VAR_Y: r = p[1]; break;
        case FR_OP_VAR_Z: r = p[2]; break;
        case FR_OP_NEG: r = iv_affine_neg(a); break;
        case FR_OP_SQR: r = iv_affine_sqr(a); break;
        case FR_OP_SQRT: r = iv_affine_sqrt(a); break;
        case FR_OP_ABS: r = iv_affine_abs(a); break;
        case FR_OP_EXP: r = iv_affine_exp(a); break;
        case FR_OP_LOG: r = iv_affine_log(a); break;
        case FR_OP_SIN: r = iv_affine_sin(a); break;
        case FR_OP_COS: r = iv_affine_cos(a); break;
        case FR_OP_ATAN: r = iv_affine_atan(a); break;
        case FR_OP_POWI:
            /* x^3 = x x^2, x^4 = (x^2)^2 in affine products: tighter than
               the Taylor form of iv_affine_pow_n (its remainder takes the
               worst f'' over the whole range) and far cheaper */
            r = in->k == 4.0 ? iv_affine_sqr(iv_affine_sqr(a))
              : in->k == 3.0 ? iv_affine_mul(a, iv_affine_sqr(a))
                             : iv_affine_pow_n(a, (int)in->k);
            break;
        case FR_OP_POWC: r = iv_affine_pow(a, iv_affine_const(in->k)); break;
        case FR_OP_ADD:
            /* a constant operand keeps the other form's error radius exact */
            r = code[in->b].op == FR_OP_CONST ? iv_affine_add_d(a, code[in->b].k) : iv_affine_add(a, c);
            break;
        case FR_OP_SUB:
            r = code[in->b].op == FR_OP_CONST ? iv_affine_sub_d(a, code[in->b].k) : iv_affine_sub(a, c);
            break;
        case FR_OP_MUL:
            r = code[in->b].op == FR_OP_CONST   ? iv_affine_mul_d(a, code[in->b].k)
                : code[in->a].op == FR_OP_CONST ? iv_affine_mul_d(c, code[in->a].k)
                                                : iv_affine_mul(a, c);
            break;
        case FR_OP_DIV: r = iv_affine_div(a, c); break;
        case FR_OP_MIN: r = iv_affine_min(a, c); break;
        case FR_OP_MAX: r = iv_affine_max(a, c); break;
        case FR_OP_RUNI: case FR_OP_RINT: case FR_OP_SMAX: case FR_OP_SMIN: r = fr__af_monotone2(in, a, c); break;
        default: r = iv_affine_from_iv(wi); break; /* NOISE, CALL: their interval image */
        }
        ri = iv_from_affine(r);
        if (iv_affine_is_empty(r) && !iv_is_empty(wi)) {
            r = iv_affine_from_iv(wi);
            ri = iv_from_affine(r);
        }
        /* both enclose the slot's range: the shadow keeps their intersection */
        {
            iv_t x = iv_intersect(wi, ri);
            w[i] = iv_is_empty(x) ? wi : x;
        }
        v[i] = r;
    }
    {
        unsigned int o = t->outputs[0];
        *out = iv_width(iv_from_affine(v[o])) <= iv_width(w[o]) ? v[o] : iv_affine_from_iv(w[o]);
    }
    return FR_OK;
}

FR_DEF fr_result_t fr_eval_affine(const fr_tape_t *t, const iv_affine_t p[3], void *scratch, iv_affine_t *out)
{
    FR__IN_FP_ENV(fr_result_t, fr__eval_affine(t, p, scratch, out));
}
#endif /* IV_NO_AFFINE */

/* ---- pruning (libfive; Keeter 2020, section 3): evaluate the box in
   intervals, record which operand each choice node takes there, then keep
   only what the shape still reaches. */

/* Choice decided on a box: 0 undecided, 1 the first operand, 2 the second.
   *exact says the replacement has the same value, not only the same sign. */
static int fr__choose(const fr_instr_t *in, iv_t a, iv_t b, fr_prune_mode_t mode, int *exact)
{
    int ch = 0, unionlike, alpha1;
    *exact = 1;
    if (iv_is_empty(a) || iv_is_empty(b)) return 0;
    switch ((fr_op_t)in->op) {
    case FR_OP_SMAX: return a.lo - b.hi >= in->k ? 1 : b.lo - a.hi >= in->k ? 2 : 0;
    case FR_OP_SMIN: return b.lo - a.hi >= in->k ? 1 : a.lo - b.hi >= in->k ? 2 : 0;
    case FR_OP_MAX: case FR_OP_MIN: case FR_OP_RUNI: case FR_OP_RINT: break;
    default: return 0;
    }
    unionlike = in->op == FR_OP_MAX || in->op == FR_OP_RUNI;
    alpha1 = in->op == FR_OP_MAX || in->op == FR_OP_MIN || in->k == 1.0;
    if (alpha1) { /* max/min: one operand dominates on the whole box */
        ch = unionlike ? (a.lo >= b.hi ? 1 : b.lo >= a.hi ? 2 : 0) : (a.hi <= b.lo ? 1 : b.hi <= a.lo ? 2 : 0);
        if (ch || mode != FR_PRUNE_SIGN) return ch;
    } else if (mode == FR_PRUNE_EXACT)
        return 0;
    /* An R-function has the sign of max (union) or min (intersection) of its
       arguments (Rvachev): a union with b < 0 on the whole box has the sign
       of a, an intersection with b > 0 that of a. Sign only. */
    *exact = 0;
    if (unionlike) return b.hi < 0 ? 1 : a.hi < 0 ? 2 : 0;
    return b.lo > 0 ? 1 : a.lo > 0 ? 2 : 0;
}

/* operations whose result's sign depends only on their operands' signs */
static int fr__sign_preserving(unsigned int op)
{
    return op == FR_OP_NEG || op == FR_OP_MIN || op == FR_OP_MAX || op == FR_OP_RUNI || op == FR_OP_RINT;
}

FR_DEF fr_result_t fr_prune(const fr_tape_t *t, const iv_t box[3], void *scratch, fr_instr_t *code_buf,
                            unsigned int cap, fr_tape_t *out, iv_t *range)
{
    return fr_prune_ex(t, box, FR_PRUNE_DEFAULT, scratch, code_buf, cap, out, range);
}

static FR__NOINLINE fr_result_t fr__prune_ex(const fr_tape_t *t, const iv_t box[3], fr_prune_mode_t mode, void *scratch,
                               fr_instr_t *code_buf, unsigned int cap, fr_tape_t *out, iv_t *range)
{
    iv_t *v = (iv_t *)scratch;
    unsigned int n, i, *rep, *newidx, outs[1];
    unsigned char *live, *sign_ctx;
    int sign_only = 0;
    fr_result_t r;
    if (!t || !box || !scratch || !code_buf || !out || t->n_code == 0) return FR_ERR_INVALID_ARG;
    if (t->flags & FR_TAPE_NO_INTERVAL) return FR_ERR_NO_INTERVAL;
    n = t->n_code;
    if (cap < n) return FR_ERR_BUFFER_TOO_SMALL;
    rep = (unsigned int *)(void *)(v + n);
    newidx = rep + n;
    live = (unsigned char *)(newidx + n);
    sign_ctx = live + n;
    r = fr__run_interval(t, box, v);
    if (r != FR_OK) return r;
    if (range) *range = v[t->outputs[0]];
    /* sign context: every use of the slot is a sign-preserving operation
       that is itself in sign context, down to the shape output */
    memset(sign_ctx, 1, n);
    for (i = 0; i < t->n_outputs; i++) sign_ctx[t->outputs[i]] = i == 0 ? sign_ctx[t->outputs[i]] : 0;
    for (i = n; i-- > 0;) {
        const fr_instr_t *in = &t->code[i];
        int ar = fr__arity(in->op), pass = fr__sign_preserving(in->op) && sign_ctx[i];
        if (pass) continue;
        if (ar >= 1) sign_ctx[in->a] = 0;
        if (ar >= 2) sign_ctx[in->b] = 0;
        if (ar >= 3) sign_ctx[in->c] = 0;
    }
    for (i = 0; i < n; i++) {
        const fr_instr_t *in = &t->code[i];
        int exact, ch = fr__arity(in->op) == 2 ? fr__choose(in, v[in->a], v[in->b], mode, &exact) : 0;
        rep[i] = i;
        if (ch && (exact || sign_ctx[i])) {
            rep[i] = rep[ch == 1 ? in->a : in->b];
            if (!exact) sign_only = 1;
        }
    }
    outs[0] = t->outputs[0];
    *out = *t;
    out->n_code = fr__compact(t->code, n, rep, outs, 1, live, newidx, code_buf, out->outputs);
    out->code = code_buf;
    out->n_outputs = 1;
    out->owned = NULL;
    if (sign_only) {
        out->flags |= FR_TAPE_SIGN_ONLY;
        out->lipschitz = INFINITY;
    }
    return FR_OK;
}

FR_DEF fr_result_t fr_prune_ex(const fr_tape_t *t, const iv_t box[3], fr_prune_mode_t mode, void *scratch,
                               fr_instr_t *code_buf, unsigned int cap, fr_tape_t *out, iv_t *range)
{
    FR__IN_FP_ENV(fr_result_t, fr__prune_ex(t, box, mode, scratch, code_buf, cap, out, range));
}
#endif /* FR_NO_INTERVAL */


#ifndef FR_NO_PARSER
/* ---- parser: a recursive-descent reader that calls the builder directly */

#define FR__P_MAX_SYMS 256      /* variables and arrays per model */
#define FR__P_MAX_NAME 48       /* identifier length */
#define FR__P_POOL 16384        /* array elements in all */
#define FR__P_MAX_DEPTH 200     /* expression nesting */
#define FR__P_MAX_ARGS 16
#define FR__P_MAX_NUMBER 72     /* a literal's buffer: 69 characters, room for an exponent's sign, NUL */

typedef enum fr__tok_t {
    FR__T_END, FR__T_NUM, FR__T_ID, FR__T_PUNCT
} fr__tok_t;

typedef struct fr__sym_t {
    char name[FR__P_MAX_NAME];
    int is_array;
    unsigned int len;  /* array length */
    unsigned int off;  /* array: first element in pool; scalar: unused */
    fr_node_t node;    /* scalar value */
    int assigned;
} fr__sym_t;

typedef struct fr__parser_t {
    const char *s;
    size_t len, pos;
    int line, col;
    /* current token */
    fr__tok_t tok;
    char punct;
    double num;
    char id[FR__P_MAX_NAME];
    int tline, tcol;
    fr_builder_t b;
    fr_diag_t *diag;
    fr_result_t err;
    int depth;
    double alpha;
    fr__sym_t *syms;
    unsigned int n_syms;
    fr_node_t *pool;
    unsigned int n_pool;
    int coords, params, attrs, model; /* symbol indices, -1 if none */
} fr__parser_t;

static void fr__perr(fr__parser_t *p, fr_result_t r, const char *msg)
{
    if (p->err != FR_OK) return;
    p->err = r;
    if (p->diag) {
        p->diag->result = r;
        p->diag->line = p->tline;
        p->diag->column = p->tcol;
        p->diag->element = -1;
        snprintf(p->diag->message, sizeof p->diag->message, "%d:%d: %.130s", p->tline, p->tcol, msg);
    }
}

/* an error at an earlier token's position */
static void fr__perr_at(fr__parser_t *p, int line, int col, const char *msg)
{
    p->tline = line;
    p->tcol = col;
    fr__perr(p, FR_ERR_PARSE, msg);
}

static int fr__pc(const fr__parser_t *p, size_t k) { return p->pos + k < p->len ? (unsigned char)p->s[p->pos + k] : -1; }
static void fr__padv(fr__parser_t *p)
{
    if (p->s[p->pos] == '\n') {
        p->line++;
        p->col = 1;
    } else
        p->col++;
    p->pos++;
}
static int fr__isalpha(int c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
static int fr__isdigit(int c) { return c >= '0' && c <= '9'; }

/* The literal in s (digits with at most one point, then optionally e or E,
   a sign and digits) as strtod reads it in the "C" locale, correctly
   rounded. strtod's decimal point is the host's LC_NUMERIC one (a comma in
   de_DE: "0.5" would stop at the point), so it gets the digits without the
   point and the exponent moved by the digits after it ("12.5e-3" is
   "125e-4"), a form every locale reads alike. 0 when malformed. */
static int fr__decimal(const char *s, double *v)
{
    char digits[FR__P_MAX_NUMBER + 24];
    size_t n = 0, i = 0;
    long e = 0, shift = 0;
    int point = 0, neg = 0, edigits = 0;
    for (; s[i] == '.' || fr__isdigit(s[i]); i++) {
        if (s[i] == '.') {
            if (point++) return 0;
        } else {
            if (n + 1 >= FR__P_MAX_NUMBER) return 0;
            digits[n++] = s[i];
            shift -= point;
        }
    }
    if (n == 0) return 0;
    if (s[i] == 'e' || s[i] == 'E') {
        i++;
        if (s[i] == '+' || s[i] == '-') neg = s[i++] == '-';
        for (; fr__isdigit(s[i]); i++, edigits++)
            if (e < 100000) e = 10 * e + (s[i] - '0'); /* far past any double's range either way */
        if (!edigits) return 0;
    }
    if (s[i]) return 0;
    snprintf(digits + n, sizeof digits - n, "e%ld", (neg ? -e : e) + shift);
    *v = strtod(digits, NULL);
    return 1;
}

/* Past blanks and comments (-- and // to the end of the line, slash-star
   blocks); 0 after an unterminated block comment (the error is set). */
static int fr__skip_blanks(fr__parser_t *p)
{
    for (;;) {
        int c = fr__pc(p, 0);
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
            fr__padv(p);
        } else if ((c == '-' && fr__pc(p, 1) == '-') || (c == '/' && fr__pc(p, 1) == '/')) {
            while (fr__pc(p, 0) != -1 && fr__pc(p, 0) != '\n') fr__padv(p);
        } else if (c == '/' && fr__pc(p, 1) == '*') {
            p->tline = p->line;
            p->tcol = p->col;
            fr__padv(p);
            fr__padv(p);
            while (fr__pc(p, 0) != -1 && !(fr__pc(p, 0) == '*' && fr__pc(p, 1) == '/')) fr__padv(p);
            if (fr__pc(p, 0) == -1) {
                fr__perr(p, FR_ERR_PARSE, "unterminated comment");
                return 0;
            }
            fr__padv(p);
            fr__padv(p);
        } else
            return 1;
    }
}

/* An identifier token from the current letter. */
static void fr__ident(fr__parser_t *p)
{
    size_t n = 0;
    while (fr__isalpha(fr__pc(p, 0)) || fr__isdigit(fr__pc(p, 0))) {
        if (n + 1 >= FR__P_MAX_NAME) {
            fr__perr(p, FR_ERR_PARSE, "identifier too long");
            p->tok = FR__T_END;
            return;
        }
        p->id[n++] = (char)fr__pc(p, 0);
        fr__padv(p);
    }
    p->id[n] = 0;
    p->tok = FR__T_ID;
}

/* A number token from the current digit or point: the characters a
   literal may hold (digits, points, one exponent with its sign), read by
   fr__decimal. */
static void fr__number(fr__parser_t *p)
{
    char buf[FR__P_MAX_NUMBER], msg[96];
    size_t n = 0;
    int e = 0;
    /* Room for one more character, an exponent's sign after it and the
       NUL: an 'e' and its sign take two slots in one step. */
    while (n + 2 < sizeof buf) {
        int d = fr__pc(p, 0);
        if (fr__isdigit(d) || d == '.' || ((d == 'e' || d == 'E') && !e)) {
            if (d == 'e' || d == 'E') {
                e = 1;
                buf[n++] = (char)d;
                fr__padv(p);
                d = fr__pc(p, 0);
                if (d == '+' || d == '-') {
                    buf[n++] = (char)d;
                    fr__padv(p);
                }
                continue;
            }
            buf[n++] = (char)d;
            fr__padv(p);
        } else
            break;
    }
    buf[n] = 0;
    if (n + 2 >= sizeof buf) {
        fr__perr(p, FR_ERR_PARSE, "number too long");
        p->tok = FR__T_END;
        return;
    }
    if (!fr__decimal(buf, &p->num)) {
        snprintf(msg, sizeof msg, "malformed number '%.40s'", buf);
        fr__perr(p, FR_ERR_PARSE, msg);
    } else if (!isfinite(p->num) || fabs(p->num) > 1e300) {
        snprintf(msg, sizeof msg, "number out of range '%.40s'", buf);
        fr__perr(p, FR_ERR_PARSE, msg);
    }
    p->tok = FR__T_NUM;
}

/* The next token. */
static void fr__next(fr__parser_t *p)
{
    int c;
    char msg[96];
    if (!fr__skip_blanks(p)) {
        p->tok = FR__T_END;
        return;
    }
    c = fr__pc(p, 0);
    p->tline = p->line;
    p->tcol = p->col;
    if (c == -1) {
        p->tok = FR__T_END;
        return;
    }
    if (fr__isalpha(c)) {
        fr__ident(p);
        return;
    }
    if (fr__isdigit(c) || (c == '.' && fr__isdigit(fr__pc(p, 1)))) {
        fr__number(p);
        return;
    }
    if (strchr("()[]{},;=+-*/^|&\\~", c) && c != 0) {
        p->punct = (char)c;
        p->tok = FR__T_PUNCT;
        fr__padv(p);
        return;
    }
    if (c >= 32 && c < 127)
        snprintf(msg, sizeof msg, "unexpected character '%c'", c);
    else
        snprintf(msg, sizeof msg, "unexpected byte 0x%02x", (unsigned int)c);
    fr__perr(p, FR_ERR_PARSE, msg);
    p->tok = FR__T_END;
}

static int fr__is(const fr__parser_t *p, char c) { return p->tok == FR__T_PUNCT && p->punct == c; }
static int fr__expect(fr__parser_t *p, char c, const char *ctx)
{
    char msg[120];
    if (p->err != FR_OK) return 0;
    if (fr__is(p, c)) {
        fr__next(p);
        return 1;
    }
    snprintf(msg, sizeof msg, "expected '%c' %s", c, ctx);
    fr__perr(p, FR_ERR_PARSE, msg);
    return 0;
}

static int fr__find_sym(const fr__parser_t *p, const char *name)
{
    unsigned int i;
    for (i = 0; i < p->n_syms; i++)
        if (!strcmp(p->syms[i].name, name)) return (int)i;
    return -1;
}
static int fr__new_sym(fr__parser_t *p, const char *name, int is_array, unsigned int len, int line, int col)
{
    fr__sym_t *s;
    const char *limit = NULL;
    if (p->n_syms >= FR__P_MAX_SYMS) limit = "too many variables";
    else if (is_array && len == 0) limit = "array length must be at least 1";
    else if (is_array && len > FR__P_POOL - p->n_pool) limit = "arrays too large in total";
    if (limit) { /* reported at line:col, where the caller's name or length stands */
        p->tline = line;
        p->tcol = col;
        fr__perr(p, FR_ERR_LIMIT, limit);
        return -1;
    }
    s = &p->syms[p->n_syms];
    memset(s, 0, sizeof *s);
    memcpy(s->name, name, strlen(name) + 1);
    s->is_array = is_array;
    s->len = len;
    s->node = FR_NODE_NONE;
    if (is_array) {
        unsigned int i;
        s->off = p->n_pool;
        for (i = 0; i < len; i++) p->pool[p->n_pool + i] = FR_NODE_NONE;
        p->n_pool += len;
    }
    return (int)p->n_syms++;
}

/* ---- values: an expression is a scalar node or a whole array (by symbol) */
typedef struct fr__val_t {
    fr_node_t node;
    int array; /* symbol index of an array value, -1 for scalars */
} fr__val_t;

static fr__val_t fr__scalar(fr_node_t n)
{
    fr__val_t v;
    v.node = n;
    v.array = -1;
    return v;
}

static int fr__is_const(const fr__parser_t *p, fr_node_t n, double *v)
{
    if (n == FR_NODE_NONE || n >= p->b.n || p->b.code[n].op != FR_OP_CONST) return 0;
    if (v) *v = p->b.code[n].k;
    return 1;
}

/* node from a builder call; a builder error becomes a parse error at the current token */
static fr_node_t fr__chk(fr__parser_t *p, fr_node_t n)
{
    if (n == FR_NODE_NONE && p->err == FR_OK) {
        const char *m = p->b.diag.message;
        fr__perr(p, p->b.diag.result != FR_OK ? p->b.diag.result : FR_ERR_PARSE, *m ? m : "invalid expression");
    }
    return n;
}

/* arithmetic with constant folding */
static fr_node_t fr__arith(fr__parser_t *p, char op, fr_node_t a, fr_node_t c)
{
    double x, y, r = 0;
    if (p->err != FR_OK) return FR_NODE_NONE;
    if (fr__is_const(p, a, &x) && fr__is_const(p, c, &y) && op != '|' && op != '&' && op != '\\') {
        switch (op) {
        case '+': r = x + y; break;
        case '-': r = x - y; break;
        case '*': r = x * y; break;
        case '/': r = x / y; break;
        default: r = NAN; break;
        }
        if (!isfinite(r)) {
            fr__perr(p, FR_ERR_PARSE, "constant expression is not finite (division by zero or overflow)");
            return FR_NODE_NONE;
        }
        return fr__chk(p, fr_const(&p->b, r));
    }
    switch (op) {
    case '+': return fr__chk(p, fr_add(&p->b, a, c));
    case '-': return fr__chk(p, fr_sub(&p->b, a, c));
    case '*': return fr__chk(p, fr_mul(&p->b, a, c));
    case '/': return fr__chk(p, fr_div(&p->b, a, c));
    case '|': return fr__chk(p, fr_union(&p->b, a, c, p->alpha));
    case '&': return fr__chk(p, fr_intersect(&p->b, a, c, p->alpha));
    default: return fr__chk(p, fr_subtract(&p->b, a, c, p->alpha));
    }
}

static fr_node_t fr__power(fr__parser_t *p, fr_node_t a, fr_node_t e)
{
    double x, y;
    if (p->err != FR_OK) return FR_NODE_NONE;
    if (fr__is_const(p, e, &y)) {
        if (fr__is_const(p, a, &x)) {
            double r = pow(x, y);
            if (!isfinite(r)) {
                fr__perr(p, FR_ERR_PARSE, "constant power is not finite");
                return FR_NODE_NONE;
            }
            return fr__chk(p, fr_const(&p->b, r));
        }
        if (y == floor(y) && fabs(y) <= 64) return fr__chk(p, fr_powi(&p->b, a, (int)y));
        if (y > 0) return fr__chk(p, fr_powc(&p->b, a, y));
    }
    /* general a^e = exp(e ln a), as C's pow for a > 0 */
    return fr__chk(p, fr_unary(&p->b, FR_OP_EXP, fr_mul(&p->b, e, fr_unary(&p->b, FR_OP_LOG, a))));
}

static fr__val_t fr__expr(fr__parser_t *p);

static fr_node_t fr__scalar_expr(fr__parser_t *p, const char *ctx)
{
    fr__val_t v = fr__expr(p);
    char msg[120];
    if (p->err == FR_OK && v.array >= 0) {
        snprintf(msg, sizeof msg, "array '%s' used where a number is expected %s", p->syms[v.array].name, ctx);
        fr__perr(p, FR_ERR_PARSE, msg);
        return FR_NODE_NONE;
    }
    return v.node;
}

/* a constant 1-based index into symbol si, as a pool offset */
static int fr__index(fr__parser_t *p, int si, unsigned int *slot)
{
    fr_node_t n;
    double v;
    char msg[120];
    int line = p->tline, col = p->tcol;
    n = fr__scalar_expr(p, "as an index");
    if (p->err != FR_OK) return 0;
    if (!fr__is_const(p, n, &v)) {
        fr__perr_at(p, line, col, "array index must be a constant");
        return 0;
    }
    if (v != floor(v) || v < 1 || v > (double)p->syms[si].len) {
        snprintf(msg, sizeof msg, "index %g out of range 1..%u for '%s'", v, p->syms[si].len, p->syms[si].name);
        fr__perr_at(p, line, col, msg);
        return 0;
    }
    *slot = p->syms[si].off + (unsigned int)v - 1;
    return 1;
}

/* ---- library calls */

typedef enum fr__fn_t {
    FR__F_SQRT, FR__F_EXP, FR__F_LOG, FR__F_SIN, FR__F_COS, FR__F_ATAN, FR__F_ABS,
    FR__F_SPHERE, FR__F_ELLIPSOID, FR__F_BLOCK, FR__F_CYL, FR__F_CONE, FR__F_TORUS, FR__F_SUPERELL,
    FR__F_BLOBBY, FR__F_SOFT, FR__F_NOISEG, FR__F_BLENDUNI, FR__F_BLENDINT,
    FR__F_SHIFT, FR__F_SCALE, FR__F_ROTATE, FR__F_TWIST, FR__F_TAPER, FR__F_STRETCH
} fr__fn_t;

typedef struct fr__fninfo_t {
    const char *name;
    int fn, axis, nargs;
    const char *sig; /* per argument: p point array (3), a constant array, k constant, n node, m mutable point array */
} fr__fninfo_t;

static const fr__fninfo_t fr__fns[] = {
    {"sqrt", FR__F_SQRT, 0, 1, "n"}, {"exp", FR__F_EXP, 0, 1, "n"}, {"log", FR__F_LOG, 0, 1, "n"},
    {"sin", FR__F_SIN, 0, 1, "n"}, {"cos", FR__F_COS, 0, 1, "n"}, {"atan", FR__F_ATAN, 0, 1, "n"},
    {"abs", FR__F_ABS, 0, 1, "n"},
    {"hfSphere", FR__F_SPHERE, 0, 3, "pak"}, {"hfEllipsoid", FR__F_ELLIPSOID, 0, 5, "pakkk"},
    {"hfBlock", FR__F_BLOCK, 0, 5, "pakkk"},
    {"hfCylinderX", FR__F_CYL, 0, 3, "pak"}, {"hfCylinderY", FR__F_CYL, 1, 3, "pak"},
    {"hfCylinderZ", FR__F_CYL, 2, 3, "pak"},
    {"hfConeX", FR__F_CONE, 0, 3, "pak"}, {"hfConeY", FR__F_CONE, 1, 3, "pak"}, {"hfConeZ", FR__F_CONE, 2, 3, "pak"},
    {"hfTorusX", FR__F_TORUS, 0, 4, "pakk"}, {"hfTorusY", FR__F_TORUS, 1, 4, "pakk"},
    {"hfTorusZ", FR__F_TORUS, 2, 4, "pakk"},
    {"hfSuperEll", FR__F_SUPERELL, 0, 7, "pakkkkk"}, {"hfSuperell", FR__F_SUPERELL, 0, 7, "pakkkkk"},
    {"hfBlobby", FR__F_BLOBBY, 0, 7, "paaaaak"}, {"hfSoft", FR__F_SOFT, 0, 6, "paaaak"},
    {"hfNoiseG", FR__F_NOISEG, 0, 4, "pkkk"},
    {"hfBlendUni", FR__F_BLENDUNI, 0, 5, "nnkkk"}, {"hfBlendInt", FR__F_BLENDINT, 0, 5, "nnkkk"},
    {"hfShift3D", FR__F_SHIFT, 0, 4, "mkkk"}, {"hfScale3D", FR__F_SCALE, 0, 4, "mkkk"},
    {"hfRotate3DX", FR__F_ROTATE, 0, 2, "mk"}, {"hfRotate3DY", FR__F_ROTATE, 1, 2, "mk"},
    {"hfRotate3DZ", FR__F_ROTATE, 2, 2, "mk"},
    {"hfTwistX", FR__F_TWIST, 0, 5, "mkkkk"}, {"hfTwistY", FR__F_TWIST, 1, 5, "mkkkk"},
    {"hfTwistZ", FR__F_TWIST, 2, 5, "mkkkk"},
    {"hfTaperX", FR__F_TAPER, 0, 5, "mkkkk"}, {"hfTaperY", FR__F_TAPER, 1, 5, "mkkkk"},
    {"hfTaperZ", FR__F_TAPER, 2, 5, "mkkkk"},
    {"hfStretch3D", FR__F_STRETCH, 0, 5, "makkk"},
};

typedef struct fr__args_t {
    fr__val_t v[FR__P_MAX_ARGS];
    double k[FR__P_MAX_ARGS];
    int n;
} fr__args_t;

static fr_p3_t fr__arr_p3(const fr__parser_t *p, int si)
{
    fr_p3_t q;
    q.x = p->pool[p->syms[si].off];
    q.y = p->pool[p->syms[si].off + 1];
    q.z = p->pool[p->syms[si].off + 2];
    return q;
}

/* check the arguments against the signature; constant arrays are copied to k-space by the caller */
static int fr__check_args(fr__parser_t *p, const fr__fninfo_t *f, fr__args_t *a)
{
    int i;
    char msg[150];
    if (a->n != f->nargs) {
        snprintf(msg, sizeof msg, "%s expects %d argument%s, got %d", f->name, f->nargs, f->nargs == 1 ? "" : "s", a->n);
        fr__perr(p, FR_ERR_PARSE, msg);
        return 0;
    }
    for (i = 0; i < a->n; i++) {
        char c = f->sig[i];
        int si = a->v[i].array;
        if (c == 'n' || c == 'k') {
            if (si >= 0) {
                snprintf(msg, sizeof msg, "%s argument %d must be a number, not array '%s'", f->name, i + 1, p->syms[si].name);
                fr__perr(p, FR_ERR_PARSE, msg);
                return 0;
            }
            if (c == 'k' && !fr__is_const(p, a->v[i].node, &a->k[i])) {
                snprintf(msg, sizeof msg, "%s argument %d must be a constant", f->name, i + 1);
                fr__perr(p, FR_ERR_PARSE, msg);
                return 0;
            }
        } else {
            unsigned int j;
            if (si < 0) {
                snprintf(msg, sizeof msg, "%s argument %d must be an array", f->name, i + 1);
                fr__perr(p, FR_ERR_PARSE, msg);
                return 0;
            }
            if ((c == 'p' || c == 'm') && p->syms[si].len != 3) {
                snprintf(msg, sizeof msg, "%s argument %d must be an array of 3 coordinates", f->name, i + 1);
                fr__perr(p, FR_ERR_PARSE, msg);
                return 0;
            }
            if (c == 'm' && (si == p->coords || si == p->params)) {
                snprintf(msg, sizeof msg, "%s cannot change '%s'; copy it to a local array first", f->name, p->syms[si].name);
                fr__perr(p, FR_ERR_PARSE, msg);
                return 0;
            }
            for (j = 0; j < p->syms[si].len; j++) {
                fr_node_t e = p->pool[p->syms[si].off + j];
                if (e == FR_NODE_NONE) {
                    snprintf(msg, sizeof msg, "array '%s' element %u is used before it is set", p->syms[si].name, j + 1);
                    fr__perr(p, FR_ERR_PARSE, msg);
                    return 0;
                }
                if (c == 'a' && !fr__is_const(p, e, NULL)) {
                    snprintf(msg, sizeof msg, "%s argument %d must be an array of constants", f->name, i + 1);
                    fr__perr(p, FR_ERR_PARSE, msg);
                    return 0;
                }
            }
        }
    }
    return 1;
}

static double fr__arr_k(const fr__parser_t *p, int si, unsigned int j)
{
    return p->b.code[p->pool[p->syms[si].off + j]].k;
}

static int fr__arr3(fr__parser_t *p, int si, double out[3], const char *fname)
{
    char msg[120];
    if (p->syms[si].len != 3) {
        snprintf(msg, sizeof msg, "%s: array '%s' must have 3 elements", fname, p->syms[si].name);
        fr__perr(p, FR_ERR_PARSE, msg);
        return 0;
    }
    out[0] = fr__arr_k(p, si, 0);
    out[1] = fr__arr_k(p, si, 1);
    out[2] = fr__arr_k(p, si, 2);
    return 1;
}

/* skeleton arrays x0,y0,z0 + per-element parameters (HyperFun argument order) */
static fr_node_t fr__skeletal_call(fr__parser_t *p, const fr__fninfo_t *f, fr__args_t *a)
{
    fr_skeleton_t el[64];
    unsigned int n = p->syms[a->v[1].array].len, i;
    int k, np = f->fn == FR__F_BLOBBY ? 6 : 5; /* arrays are arguments 1 .. np-1, the threshold is argument np */
    for (k = 1; k < np; k++)
        if (p->syms[a->v[k].array].len != n) {
            char msg[120];
            snprintf(msg, sizeof msg, "%s: arrays must have equal lengths", f->name);
            fr__perr(p, FR_ERR_PARSE, msg);
            return FR_NODE_NONE;
        }
    if (n > 64) {
        fr__perr(p, FR_ERR_LIMIT, "at most 64 skeleton elements per call");
        return FR_NODE_NONE;
    }
    for (i = 0; i < n; i++) {
        el[i].a[0] = el[i].b[0] = fr__arr_k(p, a->v[1].array, i);
        el[i].a[1] = el[i].b[1] = fr__arr_k(p, a->v[2].array, i);
        el[i].a[2] = el[i].b[2] = fr__arr_k(p, a->v[3].array, i);
        if (f->fn == FR__F_BLOBBY) { /* hfBlobby(x, x0, y0, z0, a, b, T): b exp(-a r^2) */
            el[i].width = fr__arr_k(p, a->v[4].array, i);
            el[i].weight = fr__arr_k(p, a->v[5].array, i);
        } else { /* hfSoft(x, x0, y0, z0, d, T) */
            el[i].width = fr__arr_k(p, a->v[4].array, i);
            el[i].weight = 1.0;
        }
    }
    return fr_skeletal(&p->b, fr__arr_p3(p, a->v[0].array), f->fn == FR__F_BLOBBY ? FR_KERNEL_BLOBBY : FR_KERNEL_SOFT,
                       el, n, a->k[np]);
}

static void fr__set_p3(fr__parser_t *p, int si, fr_p3_t q)
{
    if (q.x == FR_NODE_NONE) return;
    p->pool[p->syms[si].off] = q.x;
    p->pool[p->syms[si].off + 1] = q.y;
    p->pool[p->syms[si].off + 2] = q.z;
}

static fr__val_t fr__call(fr__parser_t *p, const fr__fninfo_t *f, fr__args_t *a)
{
    fr_builder_t *b = &p->b;
    fr_node_t r = FR_NODE_NONE;
    double c[3], s[3];
    fr_p3_t X;
    if (!fr__check_args(p, f, a)) return fr__scalar(FR_NODE_NONE);
    X = a->v[0].array >= 0 ? fr__arr_p3(p, a->v[0].array) : fr_coords(b);
    if (f->nargs > 1 && f->sig[1] == 'a' && f->fn != FR__F_BLOBBY && f->fn != FR__F_SOFT &&
        !fr__arr3(p, a->v[1].array, c, f->name))
        return fr__scalar(FR_NODE_NONE);
    switch ((fr__fn_t)f->fn) {
    case FR__F_SQRT: case FR__F_EXP: case FR__F_LOG: case FR__F_SIN: case FR__F_COS: case FR__F_ATAN:
    case FR__F_ABS: {
        static const fr_op_t ops[] = {FR_OP_SQRT, FR_OP_EXP, FR_OP_LOG, FR_OP_SIN, FR_OP_COS, FR_OP_ATAN, FR_OP_ABS};
        double v;
        if (fr__is_const(p, a->v[0].node, &v)) {
            double rv = f->fn == FR__F_SQRT ? sqrt(v) : f->fn == FR__F_EXP ? exp(v) : f->fn == FR__F_LOG ? log(v)
                      : f->fn == FR__F_SIN ? sin(v) : f->fn == FR__F_COS ? cos(v) : f->fn == FR__F_ATAN ? atan(v) : fabs(v);
            if (!isfinite(rv)) {
                fr__perr(p, FR_ERR_PARSE, "constant function value is not finite");
                return fr__scalar(FR_NODE_NONE);
            }
            r = fr_const(b, rv);
        } else
            r = fr_unary(b, ops[f->fn - FR__F_SQRT], a->v[0].node);
        break;
    }
    case FR__F_SPHERE: r = fr_sphere(b, X, c, a->k[2]); break;
    case FR__F_ELLIPSOID: r = fr_ellipsoid(b, X, c, a->k[2], a->k[3], a->k[4]); break;
    case FR__F_BLOCK: s[0] = a->k[2]; s[1] = a->k[3]; s[2] = a->k[4]; r = fr_block(b, X, c, s, p->alpha); break;
    case FR__F_CYL: r = fr_cylinder(b, X, f->axis, c, a->k[2]); break;
    case FR__F_CONE: r = fr_cone(b, X, f->axis, c, a->k[2]); break;
    case FR__F_TORUS: r = fr_torus(b, X, f->axis, c, a->k[2], a->k[3]); break;
    case FR__F_SUPERELL: s[0] = a->k[2]; s[1] = a->k[3]; s[2] = a->k[4]; r = fr_superellipsoid(b, X, c, s, a->k[5], a->k[6]); break;
    case FR__F_BLOBBY: case FR__F_SOFT: r = fr__skeletal_call(p, f, a); break;
    case FR__F_NOISEG: r = fr_noise_gardner(b, X, a->k[1], a->k[2], a->k[3]); break;
    case FR__F_BLENDUNI: r = fr_blend_union(b, a->v[0].node, a->v[1].node, a->k[2], a->k[3], a->k[4]); break;
    case FR__F_BLENDINT: r = fr_blend_intersect(b, a->v[0].node, a->v[1].node, a->k[2], a->k[3], a->k[4]); break;
    case FR__F_SHIFT: s[0] = a->k[1]; s[1] = a->k[2]; s[2] = a->k[3]; X = fr_translate(b, X, s); break;
    case FR__F_SCALE: s[0] = a->k[1]; s[1] = a->k[2]; s[2] = a->k[3]; X = fr_scale(b, X, s); break;
    case FR__F_ROTATE: X = fr_rotate(b, X, f->axis, a->k[1]); break;
    case FR__F_TWIST: X = fr_twist(b, X, f->axis, a->k[1], a->k[2], a->k[3], a->k[4]); break;
    case FR__F_TAPER: X = fr_taper(b, X, f->axis, a->k[1], a->k[2], a->k[3], a->k[4]); break;
    case FR__F_STRETCH: s[0] = a->k[2]; s[1] = a->k[3]; s[2] = a->k[4]; X = fr_stretch(b, X, c, s); break;
    }
    if (f->sig[0] == 'm') {
        /* space maps change their array in place and return 1, as in HyperFun */
        if (X.x == FR_NODE_NONE) return fr__scalar(fr__chk(p, FR_NODE_NONE));
        fr__set_p3(p, a->v[0].array, X);
        r = fr_const(b, 1.0);
    }
    return fr__scalar(fr__chk(p, r));
}

static const fr__fninfo_t *fr__lookup_fn(const char *name)
{
    size_t i;
    for (i = 0; i < sizeof fr__fns / sizeof fr__fns[0]; i++)
        if (!strcmp(fr__fns[i].name, name)) return &fr__fns[i];
    return NULL;
}

/* ---- expressions */

/* A call of `name` (at nline:ncol), its '(' the current token. */
static fr__val_t fr__call_expr(fr__parser_t *p, const char *name, int nline, int ncol)
{
    const fr__fninfo_t *f = fr__lookup_fn(name);
    fr__args_t a;
    char msg[120];
    int tl, tc;
    fr__val_t v;
    if (!f) {
        snprintf(msg, sizeof msg, "unknown function '%s'", name);
        fr__perr_at(p, nline, ncol, msg);
        return fr__scalar(FR_NODE_NONE);
    }
    fr__next(p);
    a.n = 0;
    if (!fr__is(p, ')'))
        for (;;) {
            v = fr__expr(p);
            if (p->err != FR_OK) return fr__scalar(FR_NODE_NONE);
            if (a.n >= FR__P_MAX_ARGS) {
                snprintf(msg, sizeof msg, "%s: too many arguments", name);
                fr__perr(p, FR_ERR_PARSE, msg);
                return fr__scalar(FR_NODE_NONE);
            }
            a.v[a.n++] = v;
            if (!fr__is(p, ',')) break;
            fr__next(p);
        }
    if (!fr__expect(p, ')', "to close the argument list")) return fr__scalar(FR_NODE_NONE);
    /* errors in the call itself point at the function name */
    tl = p->tline, tc = p->tcol;
    p->tline = nline;
    p->tcol = ncol;
    v = fr__call(p, f, &a);
    p->tline = tl;
    p->tcol = tc;
    return v;
}

/* The variable `name` (at nline:ncol), an element of it, or the whole
   array; the token after the name is current. */
static fr__val_t fr__name_expr(fr__parser_t *p, const char *name, int nline, int ncol)
{
    char msg[120];
    int si = fr__find_sym(p, name);
    if (si < 0) {
        snprintf(msg, sizeof msg, "unknown variable '%s'", name);
        fr__perr_at(p, nline, ncol, msg);
        return fr__scalar(FR_NODE_NONE);
    }
    if (fr__is(p, '[')) {
        unsigned int slot;
        if (!p->syms[si].is_array) {
            snprintf(msg, sizeof msg, "'%s' is not an array", name);
            fr__perr(p, FR_ERR_PARSE, msg);
            return fr__scalar(FR_NODE_NONE);
        }
        fr__next(p);
        if (!fr__index(p, si, &slot) || !fr__expect(p, ']', "after the index")) return fr__scalar(FR_NODE_NONE);
        if (p->pool[slot] == FR_NODE_NONE) {
            snprintf(msg, sizeof msg, "'%s[%u]' is used before it is set", name, slot - p->syms[si].off + 1);
            fr__perr(p, FR_ERR_PARSE, msg);
        }
        return fr__scalar(p->pool[slot]);
    }
    if (p->syms[si].is_array) {
        fr__val_t v;
        v.node = FR_NODE_NONE;
        v.array = si;
        return v;
    }
    if (!p->syms[si].assigned) {
        snprintf(msg, sizeof msg, "'%s' is used before it is set", name);
        fr__perr(p, FR_ERR_PARSE, msg);
    }
    return fr__scalar(p->syms[si].node);
}

static fr__val_t fr__primary(fr__parser_t *p)
{
    char msg[120], name[FR__P_MAX_NAME];
    int nline, ncol;
    if (p->err != FR_OK) return fr__scalar(FR_NODE_NONE);
    if (p->tok == FR__T_NUM) {
        double v = p->num;
        fr__next(p);
        return fr__scalar(fr__chk(p, fr_const(&p->b, v)));
    }
    if (fr__is(p, '(')) {
        fr__val_t v;
        fr__next(p);
        v = fr__expr(p);
        fr__expect(p, ')', "to close '('");
        return v;
    }
    if (p->tok != FR__T_ID) {
        if (p->tok == FR__T_END) fr__perr(p, FR_ERR_PARSE, "unexpected end of input in an expression");
        else {
            snprintf(msg, sizeof msg, "unexpected '%c' in an expression", p->punct);
            fr__perr(p, FR_ERR_PARSE, msg);
        }
        return fr__scalar(FR_NODE_NONE);
    }
    memcpy(name, p->id, sizeof name);
    nline = p->tline;
    ncol = p->tcol;
    fr__next(p);
    return fr__is(p, '(') ? fr__call_expr(p, name, nline, ncol) : fr__name_expr(p, name, nline, ncol);
}

static fr__val_t fr__unary_expr(fr__parser_t *p);

static fr__val_t fr__power_expr(fr__parser_t *p)
{
    fr__val_t v = fr__primary(p);
    if (p->err == FR_OK && fr__is(p, '^')) {
        fr_node_t e;
        if (v.array >= 0) {
            fr__perr(p, FR_ERR_PARSE, "'^' needs a number on its left");
            return v;
        }
        fr__next(p);
        e = fr__unary_expr(p).node; /* right associative: a^b^c = a^(b^c) */
        return fr__scalar(fr__power(p, v.node, e));
    }
    return v;
}

static fr__val_t fr__unary_expr(fr__parser_t *p)
{
    fr__val_t v;
    if (p->err != FR_OK) return fr__scalar(FR_NODE_NONE);
    if (++p->depth > FR__P_MAX_DEPTH) {
        fr__perr(p, FR_ERR_LIMIT, "expression nested too deeply");
        return fr__scalar(FR_NODE_NONE);
    }
    if (fr__is(p, '-') || fr__is(p, '~') || fr__is(p, '+')) {
        char op = p->punct;
        double k;
        fr__next(p);
        v = fr__unary_expr(p);
        if (p->err == FR_OK && v.array >= 0) fr__perr(p, FR_ERR_PARSE, "unary operator applied to an array");
        if (p->err == FR_OK && op != '+')
            v.node = fr__is_const(p, v.node, &k) ? fr__chk(p, fr_const(&p->b, -k)) : fr__chk(p, fr_negate(&p->b, v.node));
    } else
        v = fr__power_expr(p);
    p->depth--;
    return v;
}

static fr__val_t fr__binary_level(fr__parser_t *p, int level)
{
    static const char *const ops[3] = {"|&\\", "+-", "*/"};
    fr__val_t v = level == 2 ? fr__unary_expr(p) : fr__binary_level(p, level + 1);
    while (p->err == FR_OK && p->tok == FR__T_PUNCT && strchr(ops[level], p->punct)) {
        char op = p->punct;
        fr__val_t w;
        fr__next(p);
        w = level == 2 ? fr__unary_expr(p) : fr__binary_level(p, level + 1);
        if (p->err != FR_OK) break;
        if (v.array >= 0 || w.array >= 0) {
            fr__perr(p, FR_ERR_PARSE, "arithmetic on a whole array");
            break;
        }
        v = fr__scalar(fr__arith(p, op, v.node, w.node));
    }
    return v;
}

static fr__val_t fr__expr(fr__parser_t *p)
{
    fr__val_t v;
    if (++p->depth > FR__P_MAX_DEPTH) {
        fr__perr(p, FR_ERR_LIMIT, "expression nested too deeply");
        return fr__scalar(FR_NODE_NONE);
    }
    v = fr__binary_level(p, 0);
    p->depth--;
    return v;
}

/* ---- statements */

/* The head `NAME [ NUMBER` shared by array declarations and the model's
   array parameters: a new name and a numeric length. The caller checks the
   length's range (it differs) and then the closing ']'. Returns 0 after
   reporting an error. */
static int fr__array_head(fr__parser_t *p, const char *expected, const char *after_name,
                          char name[FR__P_MAX_NAME], double *n)
{
    char msg[120];
    if (p->tok != FR__T_ID) {
        fr__perr(p, FR_ERR_PARSE, expected);
        return 0;
    }
    memcpy(name, p->id, FR__P_MAX_NAME);
    if (fr__find_sym(p, name) >= 0) {
        snprintf(msg, sizeof msg, "'%s' is already defined", name);
        fr__perr(p, FR_ERR_PARSE, msg);
        return 0;
    }
    fr__next(p);
    if (!fr__expect(p, '[', after_name)) return 0;
    if (p->tok != FR__T_NUM) {
        fr__perr(p, FR_ERR_PARSE, "array length must be a number");
        return 0;
    }
    *n = p->num;
    return 1;
}

static void fr__array_decl(fr__parser_t *p)
{
    fr__next(p); /* 'array' */
    for (;;) {
        char name[FR__P_MAX_NAME];
        double n;
        if (!fr__array_head(p, "expected an array name after 'array'", "after the array name", name, &n)) return;
        if (n != floor(n) || n < 1 || n > FR__P_POOL) {
            fr__perr(p, FR_ERR_PARSE, "array length must be an integer from 1 to 16384");
            return;
        }
        fr__next(p);
        if (!fr__expect(p, ']', "after the array length")) return;
        if (fr__new_sym(p, name, 1, (unsigned int)n, p->tline, p->tcol) < 0) return;
        if (!fr__is(p, ',')) break;
        fr__next(p);
    }
    fr__expect(p, ';', "after the array declaration");
}

static void fr__assign_array(fr__parser_t *p, int si)
{
    char msg[120];
    fr__sym_t *s = &p->syms[si];
    if (si == p->coords || si == p->params) {
        snprintf(msg, sizeof msg, "'%s' cannot be assigned", s->name);
        fr__perr(p, FR_ERR_PARSE, msg);
        return;
    }
    if (fr__is(p, '[')) { /* literal [e1, e2, ...] */
        unsigned int i = 0;
        fr__next(p);
        for (;;) {
            fr_node_t n = fr__scalar_expr(p, "in an array literal");
            if (p->err != FR_OK) return;
            if (i >= s->len) {
                snprintf(msg, sizeof msg, "too many elements for '%s[%u]'", s->name, s->len);
                fr__perr(p, FR_ERR_PARSE, msg);
                return;
            }
            p->pool[s->off + i++] = n;
            if (!fr__is(p, ',')) break;
            fr__next(p);
        }
        if (!fr__expect(p, ']', "to close the array literal")) return;
        if (i != s->len) {
            snprintf(msg, sizeof msg, "'%s' has %u elements, the literal %u", s->name, s->len, i);
            fr__perr(p, FR_ERR_PARSE, msg);
            return;
        }
    } else {
        fr__val_t v = fr__expr(p);
        if (p->err != FR_OK) return;
        if (v.array < 0 || p->syms[v.array].len != s->len) {
            snprintf(msg, sizeof msg, "'%s' needs an array of %u elements", s->name, s->len);
            fr__perr(p, FR_ERR_PARSE, msg);
            return;
        }
        memmove(p->pool + s->off, p->pool + p->syms[v.array].off, s->len * sizeof(fr_node_t));
    }
}

static void fr__statement(fr__parser_t *p)
{
    char msg[120], name[FR__P_MAX_NAME];
    int si;
    if (p->tok == FR__T_ID && !strcmp(p->id, "array")) {
        fr__array_decl(p);
        return;
    }
    if (p->tok == FR__T_ID) {
        const fr__fninfo_t *f = fr__lookup_fn(p->id);
        if (!f) {
            int nline = p->tline, ncol = p->tcol;
            memcpy(name, p->id, sizeof name);
            fr__next(p);
            si = fr__find_sym(p, name);
            if (fr__is(p, '[')) {
                unsigned int slot;
                if (si < 0 || !p->syms[si].is_array) {
                    snprintf(msg, sizeof msg, "'%s' is not an array", name);
                    fr__perr(p, FR_ERR_PARSE, msg);
                    return;
                }
                if (si == p->coords || si == p->params) {
                    snprintf(msg, sizeof msg, "'%s' cannot be assigned", name);
                    fr__perr(p, FR_ERR_PARSE, msg);
                    return;
                }
                fr__next(p);
                if (!fr__index(p, si, &slot) || !fr__expect(p, ']', "after the index") ||
                    !fr__expect(p, '=', "in an element assignment"))
                    return;
                p->pool[slot] = fr__scalar_expr(p, "in an element assignment");
            } else {
                if (!fr__expect(p, '=', "(a statement is an assignment or a call)")) return;
                if (si >= 0 && p->syms[si].is_array) {
                    fr__assign_array(p, si);
                } else {
                    fr_node_t n = fr__scalar_expr(p, "on the right of '='");
                    if (p->err != FR_OK) return;
                    if (si < 0) si = fr__new_sym(p, name, 0, 0, nline, ncol); /* a limit points at its name */
                    if (si < 0) return;
                    p->syms[si].node = n;
                    p->syms[si].assigned = 1;
                }
            }
            fr__expect(p, ';', "after the statement");
            return;
        }
    }
    fr__expr(p); /* a call statement such as hfShift3D(xt, 1, 0, 0); */
    fr__expect(p, ';', "after the statement");
}

static void fr__header(fr__parser_t *p)
{
    int k = 0;
    if (p->tok == FR__T_END) {
        if (p->err == FR_OK) fr__perr(p, FR_ERR_PARSE, "empty input: expected a model 'name(x[3], a[1]) { ... }'");
        return;
    }
    if (p->tok != FR__T_ID) {
        fr__perr(p, FR_ERR_PARSE, "expected the model name");
        return;
    }
    p->model = fr__new_sym(p, p->id, 0, 0, p->tline, p->tcol);
    fr__next(p);
    if (!fr__expect(p, '(', "after the model name")) return;
    for (;;) {
        char name[FR__P_MAX_NAME];
        double n;
        int si;
        if (!fr__array_head(p, "expected an array parameter like x[3]", "after the parameter name", name, &n))
            return;
        if (n != floor(n) || n < 1 || n > (k == 2 ? FR_MAX_OUTPUTS - 1 : 1024) || (k == 0 && n != 3)) {
            fr__perr(p, FR_ERR_PARSE, k == 0 ? "the coordinate array must be x[3]"
                                             : k == 2 ? "at most 7 attributes" : "bad parameter array length");
            return;
        }
        fr__next(p);
        if (!fr__expect(p, ']', "after the array length")) return;
        si = fr__new_sym(p, name, 1, (unsigned int)n, p->tline, p->tcol);
        if (si < 0) return;
        if (k == 0) {
            fr_p3_t X = fr_coords(&p->b);
            p->coords = si;
            fr__set_p3(p, si, X);
        } else if (k == 1)
            p->params = si;
        else if (k == 2)
            p->attrs = si;
        else {
            fr__perr(p, FR_ERR_PARSE, "at most three array parameters (coordinates, parameters, attributes)");
            return;
        }
        k++;
        if (!fr__is(p, ',')) break;
        fr__next(p);
    }
    fr__expect(p, ')', "after the parameter list");
}

FR_DEF fr_result_t fr_parse(const char *text, size_t len, const fr_parse_desc_t *desc, fr_tape_t *out,
                            fr_diag_t *diag)
{
    fr__parser_t *p;
    fr_builder_desc_t bd;
    void *ctx = desc ? desc->alloc_ctx : NULL;
    fr_result_t r;
    unsigned int i;
    if (diag) {
        memset(diag, 0, sizeof *diag);
        diag->element = -1;
    }
    if (!out || (!text && len)) return FR_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (desc && !(desc->alpha >= 0 && desc->alpha <= 1)) {
        if (diag) {
            diag->result = FR_ERR_INVALID_ARG;
            snprintf(diag->message, sizeof diag->message, "fr_parse_desc_t.alpha must be in [0, 1]");
        }
        return FR_ERR_INVALID_ARG;
    }
    p = (fr__parser_t *)FR_MALLOC(sizeof *p, ctx);
    if (!p) return FR_ERR_OUT_OF_MEMORY;
    memset(p, 0, sizeof *p);
    p->syms = (fr__sym_t *)FR_MALLOC(FR__P_MAX_SYMS * sizeof(fr__sym_t), ctx);
    p->pool = (fr_node_t *)FR_MALLOC(FR__P_POOL * sizeof(fr_node_t), ctx);
    memset(&bd, 0, sizeof bd);
    bd.alloc_ctx = ctx;
    bd.max_nodes = desc && desc->max_nodes ? desc->max_nodes : (1u << 20);
    fr_builder_init(&p->b, &bd);
    if (!p->syms || !p->pool) {
        r = FR_ERR_OUT_OF_MEMORY;
        goto done;
    }
    p->s = text ? text : "";
    p->len = text ? len : 0;
    p->line = p->col = 1;
    p->diag = diag;
    p->alpha = desc ? desc->alpha : 0.0;
    p->coords = p->params = p->attrs = p->model = -1;
    fr__next(p);
    fr__header(p);
    /* parameter values are constants: missing ones are 0 */
    if (p->err == FR_OK && p->params >= 0)
        for (i = 0; i < p->syms[p->params].len; i++)
            p->pool[p->syms[p->params].off + i] =
                fr__chk(p, fr_const(&p->b, desc && i < desc->n_params && desc->params ? desc->params[i] : 0.0));
    fr__expect(p, '{', "to open the model body");
    while (p->err == FR_OK && !fr__is(p, '}')) {
        if (p->tok == FR__T_END) {
            fr__perr(p, FR_ERR_PARSE, "unbalanced braces: expected '}' before the end of input");
            break;
        }
        fr__statement(p);
    }
    fr__expect(p, '}', "to close the model body");
    if (p->err == FR_OK && p->tok != FR__T_END) fr__perr(p, FR_ERR_PARSE, "text after the end of the model");
    if (p->err == FR_OK && !p->syms[p->model].assigned) {
        char msg[120];
        snprintf(msg, sizeof msg, "the model value '%s' is never assigned", p->syms[p->model].name);
        fr__perr(p, FR_ERR_PARSE, msg);
    }
    r = p->err;
    if (r == FR_OK) {
        fr_node_t attrs[FR_MAX_OUTPUTS];
        unsigned int na = 0;
        if (p->attrs >= 0) {
            na = p->syms[p->attrs].len;
            for (i = 0; i < na; i++) {
                fr_node_t n = p->pool[p->syms[p->attrs].off + i];
                attrs[i] = n == FR_NODE_NONE ? fr_const(&p->b, 0.0) : n; /* unset attributes are 0 */
            }
        }
        r = fr_builder_finish(&p->b, p->syms[p->model].node, attrs, na, out, diag);
    }
done:
    fr_builder_free(&p->b);
    if (p->syms) FR_FREE(p->syms, ctx);
    if (p->pool) FR_FREE(p->pool, ctx);
    FR_FREE(p, ctx);
    return r;
}
#endif /* FR_NO_PARSER */

/* ==== [end section: model] ==== */

/* ==== [section: solvers] implementation: polynomial solvers ==== */

#include <limits.h>
#include <string.h>

#if defined(__GNUC__) || defined(__clang__)
#define FR__HOT_INLINE __attribute__((always_inline)) inline /* hot loops specialised per call site */
#else
#define FR__HOT_INLINE inline
#endif

/* Unit roundoff of double, 2^-53. */
#define FR__U 1.1102230246251565404e-16
/* A value within FR__ZERO_K n^2 u^2 sum|c_i||t|^i of zero has no certain sign
   after compensated evaluation (its a-priori bound is 4 n^2 u^2 sum|c_i||t|^i);
   the factor 8 also covers the few-ulp error of the critical point at which
   we evaluate, which moves p by p'' dt^2 / 2, again of order u^2. */
#define FR__ZERO_K 8.0
/* Widest band of root magnitudes, in bits times the degree, solved with one
   power-of-two scaling: inside it no term of the scaled polynomial leaves the
   normal double range, so compensated evaluation keeps its accuracy. */
#define FR__BAND_BITS 900
/* Iteration caps: safeguarded Newton halves the bracket at worst, and a band
   spans at most FR__BAND_BITS bits, bisected geometrically. */
/* Coefficient exponents at most FR__DIRECT_EXP, with the constant and the
   leading coefficient at least 2^-FR__DIRECT_EXP, go to the degree 2..4
   fast paths unscaled: roots then lie within 2^+-122 (Fujiwara's bounds;
   small middle coefficients only tighten them), so the terms that balance
   at a root, and the rounding errors TwoProd recovers from them, stay far
   from underflow; discriminant terms (products of six coefficients) stay
   below 2^370, and the ones made of the ends alone (a^3 e^3 and its kin)
   above 2^-370. Middle coefficients as small as 1e-162 (Orellana and De
   Michele's remark family) then need no scaling. */
#define FR__DIRECT_EXP 60
/* Absolute slack of the fast paths' sign tests: products that underflow
   lose up to 2^-1074 each, and a discriminant has fewer than 200
   operations, so 1e-300 covers them; next to the ends' terms (above
   2^-370) it changes nothing. */
#define FR__UNDERFLOW_SLACK 1e-300
#define FR__PLAIN_ITERS 120
#define FR__POLISH_ITERS 80

/* ilogb and ldexp without the library call for normal numbers (they were a
   quarter of a quartic solve): the exponent field read and written directly. */
static int fr__ilogb(double x)
{
    unsigned long long u;
    int e;
    memcpy(&u, &x, sizeof u);
    e = (int)((u >> 52) & 0x7ff);
    return e == 0 || e == 0x7ff ? ilogb(x) : e - 1023;
}

static double fr__ldexp(double x, int e)
{
    if (e >= -1022 && e <= 1023) {
        unsigned long long u = (unsigned long long)(e + 1023) << 52;
        double p;
        memcpy(&p, &u, sizeof p);
        return x * p; /* exact unless the result leaves the normal range */
    }
    return ldexp(x, e);
}

/* Plain Horner with derivative, for Newton steps. */
static inline double fr__horner_deriv(const double *c, int n, double x, double *dp)
{
    double p = c[n], d = 0.0;
    int i;
    for (i = n - 1; i >= 0; i--) {
        d = d * x + p;
        p = p * x + c[i];
    }
    *dp = d;
    return p;
}

/* Compensated Horner for coefficients hi[i] + lo[i] (lo may be NULL): TwoProd
   by fma and TwoSum keep each step's rounding error, and the errors are
   summed by a second Horner pass (Graillat, Langlois & Louvet 2005, Alg. 4).
   Each error-free step's product is used by a non-add operation, so compilers
   cannot contract it into an fma under -ffp-contract=fast. The plain
   derivative comes along in *deriv (the polish needs both per step). */
static double fr__horner_comp(const double *hi, const double *lo, int n, double x, double *abs_poly, double *deriv)
{
    double s = hi[n], err = lo ? lo[n] : 0.0, a = fabs(hi[n]), ax = fabs(x), d = 0.0;
    int i;
    for (i = n - 1; i >= 0; i--) {
        double p = s * x;
        double pe = fma(s, x, -p);
        double t = p + hi[i];
        double z = t - p;
        double te = (p - (t - z)) + (hi[i] - z);
        d = d * x + s;
        err = err * x + (pe + te + (lo ? lo[i] : 0.0));
        s = t;
        a = a * ax + fabs(hi[i]);
    }
    *abs_poly = a;
    *deriv = d;
    return s + err;
}

/* The compensated value (fr__horner_comp), its plain derivative, and its
   sign as -1, 0, +1, 0 meaning "zero within what compensated evaluation
   can resolve" (a root, possibly multiple, at x): FR__ZERO_K n^2 u^2
   sum|c_i||x|^i. */
static int fr__sign_comp(const double *hi, const double *lo, int n, double x, double *value, double *deriv)
{
    double a, v = fr__horner_comp(hi, lo, n, x, &a, deriv);
    *value = v;
    if (fabs(v) <= FR__ZERO_K * (double)(n * n) * FR__U * FR__U * a) return 0;
    return v > 0 ? 1 : -1;
}

/* fr__sign_comp at four points at once (structure of arrays, one AVX
   vector per step; the same operations per lane, so the same certificate):
   sign[j], value[j] and the plain derivative deriv[j] at x[j], on the
   coefficients hi + j qs (qs = 0: shared; as fr__polish_lanes). */
static FR__HOT_INLINE void fr__sign_comp_lanes(const double *hi, int qs, const double *lo, int n, const double *x,
                                               int *sign, double *value, double *deriv)
{
    double X[4], AX[4], S[4], E[4], A[4], D[4];
    int i, j;
    for (j = 0; j < 4; j++) {
        X[j] = x[j]; AX[j] = fabs(x[j]);
        S[j] = hi[j * qs + n]; E[j] = lo ? lo[n] : 0.0; A[j] = fabs(S[j]); D[j] = 0.0;
    }
    for (i = n - 1; i >= 0; i--) {
        double cl = lo ? lo[i] : 0.0;
        for (j = 0; j < 4; j++) {
            double c = hi[j * qs + i], p = S[j] * X[j], pe = fma(S[j], X[j], -p), t = p + c, z = t - p;
            double te = (p - (t - z)) + (c - z);
            D[j] = D[j] * X[j] + S[j];
            E[j] = E[j] * X[j] + (pe + te + cl);
            S[j] = t;
            A[j] = A[j] * AX[j] + fabs(c);
        }
    }
    for (j = 0; j < 4; j++) {
        double v = S[j] + E[j];
        value[j] = v;
        deriv[j] = D[j];
        sign[j] = fabs(v) <= FR__ZERO_K * (double)(n * n) * FR__U * FR__U * A[j] ? 0 : v > 0 ? 1 : -1;
    }
}

/* fr__sign_comp_lanes on one shared polynomial (the quartic brackets). */
static void fr__sign_comp4(const double *hi, const double *lo, int n, const double *x, int *sign, double *value,
                           double *deriv)
{
    fr__sign_comp_lanes(hi, 0, lo, n, x, sign, value, deriv);
}

/* Plain Horner value of p(x) and, in *bound, sum |c_i| |x|^i: the scale of
   the value's rounding error (gamma_2n times it, Higham 2002 eq. 5.3). */
static double fr__horner_bound(const double *c, int n, double x, double *bound)
{
    double v = c[n], a = fabs(c[n]), ax = fabs(x);
    int i;
    for (i = n - 1; i >= 0; i--) {
        v = v * x + c[i];
        a = a * ax + fabs(c[i]);
    }
    *bound = a;
    return v;
}

/* Sign of p(x) as -1, 0, +1, where 0 means "zero within what compensated
   evaluation can resolve" (a root, possibly multiple, at x). Plain Horner
   decides first when its value exceeds its error bound gamma_2n sum|c_i||x|^i
   (Higham 2002, eq. 5.3; lo adds at most u of that); compensated evaluation
   only runs near a root. */
static int fr__sign_at(const double *hi, const double *lo, int n, double x, double *value)
{
    double a, v = fr__horner_bound(hi, n, x, &a), d;
    if (fabs(v) > (2.0 * n + 2.0) * FR__U * a) {
        *value = v;
        return v > 0 ? 1 : -1;
    }
    return fr__sign_comp(hi, lo, n, x, value, &d);
}

/* A bisection point of [a, b]: when the ends differ a lot in magnitude it
   halves the exponent range instead of the length (0 first, if the ends have
   opposite signs), so a root of 1e-30 in [-1e20, 1] takes dozens of steps,
   not hundreds. tiny > 0 is the smallest root magnitude possible here, and
   stands in for an end at 0. */
static double fr__split_point(double a, double b, double tiny)
{
    double lo = a < b ? a : b, hi = a < b ? b : a;
    if (lo >= 0) {
        double l = lo > tiny ? lo : tiny;
        return hi > 16.0 * l ? sqrt(l) * sqrt(hi) : 0.5 * (lo + hi);
    }
    if (hi <= 0) return -fr__split_point(-hi, -lo, tiny);
    return (hi > -16.0 * lo || -lo > 16.0 * hi) ? 0.0 : 0.5 * (lo + hi);
}

/* Next iterate inside the bracket (a, b): the Newton point if it stays
   strictly inside, else a split point. Newton far from a root of p ~ x^k
   only shrinks x by (k-1)/k per step, so after two steps in a row that did
   not shrink by 4x (no sign of quadratic convergence) one split is forced.
   st[0] is the last step length, st[1] counts slow steps. */
static double fr__newton_or_split(double x, double dx, double a, double b, double tiny, double st[2])
{
    double lo = a < b ? a : b, hi = a < b ? b : a, xn = x - dx, step;
    int newton = xn > lo && xn < hi && st[1] < 2.0;
    if (!newton) xn = fr__split_point(lo, hi, tiny);
    step = fabs(xn - x);
    st[1] = newton && step > 0.25 * st[0] ? st[1] + 1.0 : 0.0;
    st[0] = step;
    return xn;
}

/* The single root of p in the monotone piece (l, r), where p(l) has sign sl
   and p(r) the other sign. Phase 1: safeguarded Newton in plain arithmetic,
   until the step is an ulp or the value sinks below plain Horner's rounding
   error (2n u sum|c_i||x|^i, Higham 2002 eq. 5.3). Phase 2: Newton with
   compensated residuals inside the original bracket, with bisection wherever
   a step leaves it; it alone decides the last bits, so sign noise in phase
   1 cannot mislead it. */
static double fr__root_in_piece(const double *hi, const double *lo, int n, double l, double r,
                                double vl, double vr, int sl, double start, double tiny)
{
    double a = l, b = r, x, f, df, st[2];
    int it;
    /* the caller's estimate, else regula falsi (inside: vl, vr differ in sign) */
    x = start > l && start < r ? start : l - vl * ((r - l) / (vr - vl));
    if (!(x > l && x < r)) x = fr__split_point(l, r, tiny);
    st[0] = r - l;
    st[1] = 0.0;
    for (it = 0; it < FR__PLAIN_ITERS; it++) {
        double dx, ab = fabs(hi[n]), ax = fabs(x);
        int i;
        f = fr__horner_deriv(hi, n, x, &df);
        for (i = n - 1; i >= 0; i--) ab = ab * ax + fabs(hi[i]);
        if (fabs(f) <= 2.0 * n * FR__U * ab) break;
        dx = f / df;
        if (fabs(dx) <= 4.0 * FR__U * ax) { x -= dx; break; }
        if ((f > 0) == (sl > 0)) a = x; else b = x;
        x = fr__newton_or_split(x, dx, a, b, tiny, st);
    }
    if (!(x >= (l < r ? l : r) && x <= (l < r ? r : l))) x = fr__split_point(l, r, tiny);
    a = l; b = r;
    st[0] = r - l;
    st[1] = 0.0;
    for (it = 0; it < FR__POLISH_ITERS; it++) {
        double v, xn;
        int s = fr__sign_comp(hi, lo, n, x, &v, &df);
        if (s == 0) break;
        if (s == sl) a = x; else b = x;
        if (fabs(v / df) <= 2.0 * FR__U * fabs(x)) { x -= v / df; break; } /* an ulp */
        xn = fr__newton_or_split(x, v / df, a, b, tiny, st);
        if (fabs(xn - x) <= 2.0 * FR__U * fabs(x)) { x = xn; break; }
        x = xn;
    }
    return x;
}

/* Estimate-grade elementary functions, without libm calls (acos, cos and
   cbrt were half the time of a quartic's estimates). They only seed Newton
   iterations that a compensated polish finishes, so ~1e-8 is plenty. */

/* acos(x) to 2.2e-8 absolute (Abramowitz & Stegun 4.4.46 on [0, 1],
   acos(-x) = pi - acos(x) below). */
static double fr__acos_est(double x)
{
    double ax = fabs(x), p = -0.0012624911;
    p = p * ax + 0.0066700901; p = p * ax - 0.0170881256; p = p * ax + 0.0308918810;
    p = p * ax - 0.0501743046; p = p * ax + 0.0889789874; p = p * ax - 0.2145988016;
    p = (p * ax + 1.5707963050) * sqrt(1.0 - (ax < 1.0 ? ax : 1.0));
    return x < 0 ? 3.141592653589793 - p : p;
}

/* cos and sin of t in [0, pi/3] by Taylor series to t^12 (error < 3e-10). */
static void fr__cos_sin_est(double t, double *c, double *s)
{
    double t2 = t * t;
    *c = 1.0 + t2 * (-1.0 / 2 + t2 * (1.0 / 24 + t2 * (-1.0 / 720 + t2 * (1.0 / 40320 + t2 * (-1.0 / 3628800 +
                                                                                             t2 / 479001600.0)))));
    *s = t * (1.0 + t2 * (-1.0 / 6 + t2 * (1.0 / 120 + t2 * (-1.0 / 5040 + t2 * (1.0 / 362880 - t2 / 39916800.0)))));
}

/* cbrt(x) for x >= 0: the exponent divided by 3 in the bit pattern (about
   6% off), then two Halley steps (cubic convergence, below 1e-14). Outside
   the normal range the bit trick fails, so libm takes over (not for 0, a
   depressed cubic's common case). */
static double fr__cbrt_est(double x)
{
    unsigned long long u;
    double y;
    int it;
    if (x == 0) return 0.0;
    if (!(x >= 1e-300 && x <= 1e300)) return cbrt(x);
    memcpy(&u, &x, sizeof u);
    u = u / 3u + 0x2A9F7893782DA1CEull;
    memcpy(&y, &u, sizeof y);
    for (it = 0; it < 2; it++) {
        double y3 = y * y * y;
        y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    }
    return y;
}

/* The two other roots of y^3 + a y^2 + b y + c from an estimate L of its
   largest root in magnitude: dividing y - L out from the low end, C = -c / L
   and B = (C - b) / L for the factor y^2 + B y + C (stable: the dropped root
   is the largest), gives them to about L's relative error. Cardano's forms
   give small roots only to ~1e-8 |L| absolute: ~1 relative when |L| is 1e8
   times theirs (a fast path's polish took 4 passes instead of 1), or, when
   rounding puts R^2 >= Q^3, not at all (a second fast-path attempt).
   Starting points only: the certificate is the caller's. Returns 2 with
   est[0..1] set when the pair is real and both are below |L| / 16, 0 when
   it is complex (rounding can put a complex pair beside a large root into
   the trigonometric form, whose two small estimates are then noise), -1
   otherwise. */
static int fr__deflated_pair(double L, double b, double c, double *est)
{
    double C = -c / L, B = (C - b) / L, disc = B * B - 4.0 * C, t;
    if (disc < 0) return 0;
    if (!(disc >= 0)) return -1;
    t = -0.5 * (B + (B < 0 ? -sqrt(disc) : sqrt(disc)));
    if (!(t != 0 && 16.0 * fabs(t) <= fabs(L))) return -1;
    est[0] = t;
    est[1] = C / t;
    return 2;
}

/* Closed-form estimates (Cardano; trigonometric form when three roots are
   real, Numerical Recipes 5.6) of the real roots of y^3 + a y^2 + b y + c.
   In the trigonometric case, with psi = acos(-R / Q^(3/2)) / 3 in
   [0, pi/3], the roots are 2 sqrt(Q) cos(psi) (the largest) and
   -sqrt(Q) (cos(psi) +- sqrt(3) sin(psi)), shifted by -a/3: one cosine and
   one sine instead of three cosines. With largest_only, only the largest
   root is produced (Ferrari's resolvent needs no other). */
static int fr__cubic_estimates(double a, double b, double c, double *est, int largest_only)
{
    /* estimates only: constant divisions become products (a few ulps) */
    const double third = 1.0 / 3.0;
    double Q = (a * a - 3.0 * b) * (1.0 / 9.0), R = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) * (1.0 / 54.0);
    double Q3 = Q * Q * Q, shift = a * third;
    if (R * R < Q3) {
        double sQ = sqrt(Q), cs, sn;
        fr__cos_sin_est(fr__acos_est(-R / (sQ * Q)) * third, &cs, &sn);
        est[0] = 2.0 * sQ * cs - shift;
        if (largest_only) return 1;
        est[1] = -sQ * (cs + 1.7320508075688772 * sn) - shift;
        est[2] = -sQ * (cs - 1.7320508075688772 * sn) - shift;
        if (fabs(est[1]) > fabs(est[0])) { double t = est[0]; est[0] = est[1]; est[1] = t; }
        if (16.0 * fabs(est[1]) <= fabs(est[0]) && 16.0 * fabs(est[2]) <= fabs(est[0]) &&
            fr__deflated_pair(est[0], b, c, est + 1) == 0) /* spread: the small pair from the low end */
            return 1;
        return 3;
    } else {
        double A = -(R < 0 ? -1.0 : 1.0) * fr__cbrt_est(fabs(R) + sqrt(R * R - Q3));
        est[0] = A + (A != 0 ? Q / A : 0.0) - shift;
        if (largest_only || est[0] == 0) return 1;
        return fr__deflated_pair(est[0], b, c, est + 1) > 0 ? 3 : 1; /* a spread pair that rounding hid */
    }
}

/* Closed-form estimates of the real roots for degree <= 4 (quadratic formula,
   Cardano, Ferrari, as the paper's §3.1.1 uses them), in plain arithmetic.
   They only seed Newton inside pieces that the derivative sequence has
   already certified; an estimate that is wrong or missing (Ferrari fails on
   Flocke's and Strobach's quartics) costs iterations, never a root. */
static int fr__estimate_roots(const double *c, int n, double *est)
{
    double a, b, cc, d;
    if (n < 2 || n > 4 || c[n] == 0) return 0;
    if (n == 2) {
        double disc, q;
        b = c[1] / c[2]; cc = c[0] / c[2];
        disc = b * b - 4.0 * cc;
        if (disc < 0) return 0;
        q = -0.5 * (b + (b < 0 ? -sqrt(disc) : sqrt(disc)));
        est[0] = q;
        est[1] = q != 0 ? cc / q : 0.0;
        return 2;
    }
    if (n == 3) return fr__cubic_estimates(c[2] / c[3], c[1] / c[3], c[0] / c[3], est, 0);
    {
        /* depressed quartic y^4 + p y^2 + q y + r, x = y - a/4; Ferrari's
           resolvent m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0 */
        double p, q, r, m, s2, inv = 1.0 / c[4];
        int ny = 0, k;
        a = c[3] * inv; b = c[2] * inv; cc = c[1] * inv; d = c[0] * inv;
        p = b - 0.375 * a * a;
        q = cc - 0.5 * a * b + 0.125 * a * a * a;
        r = d - 0.25 * a * cc + a * a * b * 0.0625 - 3.0 * a * a * a * a * 0.00390625;
        /* q y negligible next to p y^2 and r at the roots' scale
           (|p|^(1/2) or |r|^(1/4)): the quartic is biquadratic, y^2 = z with
           z^2 + p z + r = 0. Ferrari's resolvent would have the root m ~ q^2,
           rounded or underflowed (the 1e-162 odd coefficients of Orellana
           and De Michele's remark family), and nothing positive when q = 0. */
        m = 0.0;
        if (!(fabs(q) <= 1e-8 * (fabs(p) * sqrt(fabs(p)) + sqrt(sqrt(fabs(r))) * sqrt(fabs(r)))))
            fr__cubic_estimates(p, p * p * 0.25 - r, -q * q * 0.125, &m, 1);
        if (!(m > 0)) {
            double disc = p * p - 4.0 * r, z[2];
            if (!(disc >= 0)) return 0;
            z[0] = -0.5 * (p + (p < 0 ? -sqrt(disc) : sqrt(disc)));
            z[1] = z[0] != 0 ? r / z[0] : 0.0;
            for (k = 0; k < 2; k++)
                if (z[k] > 0) {
                    est[ny++] = sqrt(z[k]) - 0.25 * a;
                    est[ny++] = -sqrt(z[k]) - 0.25 * a;
                }
            return ny;
        }
        s2 = sqrt(2.0 * m);
        for (k = -1; k <= 1; k += 2) {
            /* y^2 + k s2 y + h, without cancellation (h q0 = product of roots) */
            double h = 0.5 * p + m - k * q * (0.5 / s2), disc = 2.0 * m - 4.0 * h, q0;
            if (disc < 0) continue;
            q0 = -0.5 * (k * s2 + (k > 0 ? sqrt(disc) : -sqrt(disc)));
            est[ny++] = q0 - 0.25 * a;
            est[ny++] = (q0 != 0 ? h / q0 : 0.0) - 0.25 * a;
        }
        return ny;
    }
}

/* Where p, with p'(e) = 0 and value v at the critical point e, meets zero on
   the side `side` (+1 right, -1 left) if it is the parabola
   v + p''(e) (x - e)^2 / 2 there (order 2): e + side sqrt(-v / (p''(e)/2));
   NaN when the curvature does not bend p towards zero. Order 3 is the
   same for the cubic v + p'''(e) (x - e)^3 / 6, for a critical point that
   is (nearly) a double root of p' too, where p'' vanishes: a triple root
   that rounding split (ODM's case 15), whose real root sits ~u^(1/3) from
   the critical point, where the parabola is far off. */
static double fr__critical_end_start(const double *hi, int n, double e, double v, int side, int order)
{
    double h3 = 0.0, h2 = 0.0, d = 0.0, p = hi[n], w;
    int i;
    for (i = n - 1; i >= 0; i--) { /* p'''/6, p''/2, p', p by Horner */
        h3 = h3 * e + h2;
        h2 = h2 * e + d;
        d = d * e + p;
        p = p * e + hi[i];
    }
    if (order == 2) {
        w = -v / h2;
        return w > 0 ? e + (side > 0 ? sqrt(w) : -sqrt(w)) : (double)NAN;
    }
    w = -v / h3; /* v + h3 t^3 = 0: t = cbrt(w), on the side's sign */
    return (w > 0) == (side > 0) && w != 0 ? e + (side > 0 ? 1.0 : -1.0) * fr__cbrt_est(fabs(w)) : (double)NAN;
}

/* |p(x)| / sum |c_i| |x|^i by plain Horner: how close x is to a root, in
   units of what rounding alone can resolve (2n u, Higham 2002 eq. 5.3). */
static double fr__abs_value_ratio(const double *hi, int n, double x)
{
    double a, v = fr__horner_bound(hi, n, x, &a);
    return a > 0 ? fabs(v) / a : 0.0;
}

/* Closed-form estimates that a failed quartic fast path computed, kept for
   the derivative sequence's level 0 (the same polynomial: Ferrari's
   estimates, 250-400 instructions, are not computed twice); n < 0: none. */
typedef struct fr__est_t { int n; double x[4]; } fr__est_t;

static void fr__keep_estimates(fr__est_t *keep, const double *est, int n)
{
    int i;
    if (!keep) return;
    for (i = 0; i < n; i++) keep->x[i] = est[i];
    keep->n = n;
}

/* Roots of p (degree n, hi + lo) in [ya, yb], given the ascending roots bp of
   p' there: between consecutive breakpoints p is monotone, so a sign change
   means exactly one root; a breakpoint where p is zero is a multiple root.
   Newton starts in each piece from the best closed-form estimate, or, when
   none is at rounding level, from the best of it and the parabolas at the
   piece's critical ends (smallest |p| relative to its rounding): with
   roots spread over many magnitudes the closed forms lose the small ones to
   cancellation, and a critical end is where plain Newton, with p' = 0,
   would leave the piece; the parabola also splits a near-double root's pair
   at its critical point to about the relative size of the cubic term. */
static int fr__roots_between(const double *hi, const double *lo, int n, double ya, double yb,
                             const double *bp, int nbp, double tiny, const fr__est_t *known, double *out)
{
    double xl = ya, vl, xr, vr, est[4];
    int sl = fr__sign_at(hi, lo, n, ya, &vl), sr, j, k, cnt = 0, nest;
    if (known && known->n >= 0) /* the failed fast path's, of this very polynomial */
        for (nest = 0; nest < known->n; nest++) est[nest] = known->x[nest];
    else
        nest = fr__estimate_roots(hi, n, est);
    if (sl == 0) out[cnt++] = ya;
    for (j = 0; j <= nbp && cnt < n; j++) {
        xr = j < nbp ? bp[j] : yb;
        if (!(xr > xl)) continue;
        sr = fr__sign_at(hi, lo, n, xr, &vr);
        if (sl * sr < 0) {
            double start = xl, best = HUGE_VAL; /* none: regula falsi */
            for (k = 0; k < nest; k++)
                if (est[k] > xl && est[k] < xr) {
                    double v = fr__abs_value_ratio(hi, n, est[k]);
                    if (v < best) { best = v; start = est[k]; }
                }
            if (n >= 2 && !(best <= 64.0 * n * FR__U)) { /* no closed form at rounding level: the parabolas */
                for (k = 0; k < 4; k++) { /* the parabolas, then the cubics if neither is at rounding level */
                    int order = k < 2 ? 2 : 3, left = !(k & 1); /* the critical end xl = bp[j - 1], or xr = bp[j] */
                    double x;
                    if ((left ? j == 0 : j == nbp) || (order == 3 && best <= 64.0 * n * FR__U)) continue;
                    x = left ? fr__critical_end_start(hi, n, xl, vl, 1, order) : fr__critical_end_start(hi, n, xr, vr, -1, order);
                    if (x > xl && x < xr) {
                        double v = fr__abs_value_ratio(hi, n, x);
                        if (v < best) { best = v; start = x; }
                    }
                }
            }
            out[cnt++] = fr__root_in_piece(hi, lo, n, xl, xr, vl, vr, sl, start, tiny);
        }
        if (sr == 0 && cnt < n) out[cnt++] = xr;
        xl = xr; sl = sr; vl = vr;
    }
    return cnt;
}

/* Most compensated Newton steps a fast path allows one root before it gives
   up and leaves the polynomial to the derivative sequence. */
#define FR__FAST_POLISH_ITERS 6

/* Polish of the k <= 4 estimates x[] of roots of q (degree n), all in
   lockstep, by Chebyshev's third-order method, x -= dx + A2 dx^2 with dx = p / p' and
   A2 = p'' / (2 p'), whose residual p comes from compensated Horner
   evaluation (as fr__horner_comp), so the last bits are those of twice the
   working precision. A root is settled when its step was at most 2 ulps,
   or when the method's asymptotic error (Traub 1964, sec. 5.3:
   |2 A2^2 - A3| dx^3, A3 = p''' / (6 p')) puts the next step below a
   quarter ulp: from a closed-form estimate good to ~1e-8 (Ferrari's and
   Cardano's on random quartics and cubics: 6e-7 at worst) that usually
   takes one evaluation per root, where Newton took a plain step and one or
   two compensated ones (measured: 45% of quartics with four real roots
   needed a second). The roots' iterations are independent and run in four
   lanes (structure of arrays, one AVX vector), so the CPU overlaps their
   dependency chains. Lane j polishes on the coefficients q + j qs: qs = 0
   shares q, qs > 0 gives each lane its own polynomial (all four lanes'
   filled; the split path's roots, each in its own scaling). Returns 0 when
   a root does not settle or is not finite (the caller then falls back). */
static FR__HOT_INLINE int fr__polish_lanes(const double *q, int qs, const double *lo, int n, double *x, int k)
{
    /* unused lanes repeat root 0 */
    double X[4], S[4], E[4], D[4], H[4], T[4], DX[4], ERR[4];
    int it, i, j, left;
    for (j = 0; j < 4; j++) X[j] = x[j < k ? j : 0];
    for (it = 0; it < FR__FAST_POLISH_ITERS; it++) {
        for (j = 0; j < 4; j++) { S[j] = q[j * qs + n]; E[j] = lo ? lo[n] : 0.0; D[j] = 0.0; H[j] = 0.0; T[j] = 0.0; }
        for (i = n - 1; i >= 0; i--)
            for (j = 0; j < 4; j++) {
                double c = q[j * qs + i], p = S[j] * X[j], pe = fma(S[j], X[j], -p), t = p + c, z = t - p;
                double te = (p - (t - z)) + (c - z);
                E[j] = E[j] * X[j] + (pe + te + (lo ? lo[i] : 0.0));
                T[j] = T[j] * X[j] + H[j]; /* third derivative / 6 */
                H[j] = H[j] * X[j] + D[j]; /* second derivative / 2 */
                D[j] = D[j] * X[j] + S[j]; /* first derivative */
                S[j] = t;
            }
        for (j = 0; j < 4; j++) {
            double v = S[j] + E[j], a2 = H[j] / D[j], k3 = fabs(2.0 * a2 * a2 - T[j] / D[j]);
            DX[j] = v == 0 ? 0.0 : v / D[j];
            ERR[j] = k3 * fabs(DX[j]) * DX[j] * DX[j];
            X[j] -= DX[j] + (v == 0 ? 0.0 : a2 * DX[j] * DX[j]);
        }
        for (j = left = 0; j < k; j++)
            left += !(fabs(DX[j]) <= 2.0 * FR__U * fabs(X[j]) ||
                      (fabs(DX[j]) <= 1e-4 * fabs(X[j]) && ERR[j] <= 0.25 * FR__U * fabs(X[j])));
        if (left == 0) break;
    }
    for (j = 0; j < k; j++) {
        if (!(X[j] - X[j] == 0)) return 0;
        x[j] = X[j];
    }
    return it < FR__FAST_POLISH_ITERS;
}

/* fr__polish_lanes without lo (the fast paths on p itself, where every
   cycle counts) and with it (derivative levels), each compiled for its case. */
static int fr__polish_all(const double *q, const double *lo, int n, double *x, int k)
{
    return lo ? fr__polish_lanes(q, 0, lo, n, x, k) : fr__polish_lanes(q, 0, NULL, n, x, k);
}

/* The common tail of the certified fast paths: polish the k estimates,
   sort them, and demand that they be distinct (64 ulps apart), so each
   stands for its own root of the certified count; -1 otherwise. */
static int fr__fast_finish(const double *q, const double *lo, int n, double *x, int k)
{
    int i;
    if (!fr__polish_all(q, lo, n, x, k)) return -1;
    for (i = 1; i < k; i++) {
        double v = x[i];
        int j = i;
        while (j > 0 && x[j - 1] > v) { x[j] = x[j - 1]; j--; }
        x[j] = v;
    }
    for (i = 1; i < k; i++) {
        double m = fabs(x[i]) > fabs(x[i - 1]) ? fabs(x[i]) : fabs(x[i - 1]);
        if (!(x[i] - x[i - 1] > 64.0 * FR__U * m)) return -1;
    }
    return k;
}

/* Fast path for quadratics (every sphere, cylinder and cone on a ray): the
   discriminant b^2 - 4ac is computed with its products split exactly by
   fma (Kahan 2004), so its error is below 3u|D| + 2u^2 (b^2 + |4ac|) and
   its sign is certain outside that band; the cancellation-free formula
   q = -(b + sign(b) sqrt(D)) / 2, roots q/a and c/q, then a compensated
   polish. -1 (near-double roots, no convergence) falls back. */
static int fr__quadratic_fast(const double *q, const double *lo, double *out)
{
    double a = q[2], b = q[1], c = q[0], p = b * b, dp = fma(b, b, -p), f = 4.0 * a * c, df = fma(4.0 * a, c, -f);
    double D = (p - f) + (dp - df), h, tol = (lo ? 3.0 * FR__U : 8.0 * FR__U * FR__U) * (p + fabs(f));
    if (!(fabs(D) > tol + FR__UNDERFLOW_SLACK)) return -1;
    if (D < 0) return 0;
    h = -0.5 * (b + (b < 0 ? -sqrt(D) : sqrt(D)));
    if (h == 0) return -1;
    out[0] = h / a;
    out[1] = c / h;
    return fr__fast_finish(q, lo, 2, out, 2);
}

/* Sum of t[0..7] and of their magnitudes, as a balanced tree: 3 additions
   deep instead of 7, so sums of discriminant terms are not a chain of
   dependent adds, and each term goes through at most 3 roundings. */
static double fr__sum8(const double *t, double *abs_sum)
{
    *abs_sum = ((fabs(t[0]) + fabs(t[1])) + (fabs(t[2]) + fabs(t[3]))) +
               ((fabs(t[4]) + fabs(t[5])) + (fabs(t[6]) + fabs(t[7])));
    return ((t[0] + t[1]) + (t[2] + t[3])) + ((t[4] + t[5]) + (t[6] + t[7]));
}

/* Second chance for a fast path whose closed-form estimates est[0..ne-1]
   did not give the certified number want of distinct real roots, or did
   not converge: where the roots' magnitudes are spread, the closed forms
   lose the small roots to cancellation (and may turn a complex pair into
   two real estimates), while the same formulas on the reversed polynomial
   x^n p(1/x) lose the large ones instead. The candidates from both are
   ranked by |p(x)| / sum |c_i||x|^i, and the want best that are 1e-6 apart
   (relative) and at most 1e-4 (a closed form's, not noise) are polished
   and certified by fr__fast_finish like the first ones; -1 otherwise. When
   all n roots are real and one is still missing (a middle root of roots
   spread both ways, which neither direction resolves), it is the product
   of the roots, (-1)^n c_0 / c_n, divided by the others': no cancellation.
   When a quartic's two middle roots are missing, x^2 - S x + P, their
   factor, follows from the two found, r and s, by the coefficients of x^2
   and x: e2 = P + S (r + s) + r s and e3 = P (r + s) + S r s (e_k the
   elementary symmetric functions, c_4 e2 = c_2, c_4 e3 = -c_1), a 2x2
   system with determinant r^2 + r s + s^2 > 0, well conditioned when r
   and s are the extreme roots. Only the starting points differ, so the
   certificate is the fast path's own. */
static int fr__fast_retry(const double *q, const double *lo, int n, int want, const double *est, int ne, double *out)
{
    double cand[8], rank[8], rev[5], er[4] = {0, 0, 0, 0}; /* zeroed for gcc -O3's -Wmaybe-uninitialized */
    int nc = 0, i, j, k = 0, nr;
    for (i = 0; i < ne; i++) cand[nc++] = est[i];
    for (i = 0; i <= n; i++) rev[i] = q[n - i];
    nr = fr__estimate_roots(rev, n, er);
    for (i = 0; i < nr; i++)
        if (er[i] != 0) cand[nc++] = 1.0 / er[i];
    for (i = 0; i < nc; i++) rank[i] = fr__abs_value_ratio(q, n, cand[i]);
    while (k < want) {
        int b = -1;
        for (i = 0; i < nc; i++)
            if (rank[i] <= 1e-4 && (b < 0 || rank[i] < rank[b])) b = i; /* NaN and used (2) never */
        if (b < 0) break;
        rank[b] = 2.0;
        for (j = 0; j < k && !(fabs(cand[b] - out[j]) <= 1e-6 * fabs(cand[b])); j++) continue;
        if (j == k) out[k++] = cand[b];
    }
    if (k == n - 1 && want == n) {
        double prod = out[0];
        for (i = 1; i < k; i++) prod *= out[i];
        out[k++] = ((n & 1) ? -q[0] : q[0]) / q[n] / prod;
    } else if (k == 2 && want == 4 && n == 4) {
        double r = out[0], t = out[1], rs = r * t, sum = r + t, det = sum * sum - rs;
        double b1 = q[2] / q[4] - rs, e3 = -q[1] / q[4], S = (b1 * sum - e3) / det, P = (sum * e3 - rs * b1) / det;
        double disc = S * S - 4.0 * P, h;
        if (!(disc >= 0) || !(det > 0)) return -1;
        h = 0.5 * (S + (S < 0 ? -sqrt(disc) : sqrt(disc))); /* no cancellation; the other is P / h */
        if (h == 0) return -1;
        out[k++] = h;
        out[k++] = P / h;
    }
    if (k < want) return -1;
    return fr__fast_finish(q, lo, n, out, want);
}

/* The fast paths' common end: the n estimates est[] must be the certified
   number want of roots and certify, else fr__fast_retry. */
static int fr__fast_certify(const double *q, const double *lo, int n, int want, const double *est, int ne, double *out)
{
    int i;
    for (i = 0; i < ne; i++) out[i] = est[i];
    if (ne == want && fr__fast_finish(q, lo, n, out, want) == want) return want;
    return fr__fast_retry(q, lo, n, want, est, ne, out);
}

/* The same certified fast path for cubics: the discriminant
   18abcd - 4b^3 d + b^2 c^2 - 4ac^3 - 27a^2 d^2 is > 0 for three distinct
   real roots and < 0 for one. Each term carries at most 5 roundings and
   their (pairwise) sum 3 more, so 32 u sum|terms| bounds the error and outside it the
   sign is certain. Cardano's (or the trigonometric) estimates must give
   that many roots, and fr__fast_finish must certify them. */
static int fr__cubic_fast(const double *q, const double *lo, double *out)
{
    double a = q[3], b = q[2], c = q[1], d = q[0], b2 = b * b, c2 = c * c, t[5], D, S, est[3];
    int n, want;
    t[0] = 18.0 * a * b * c * d; t[1] = -4.0 * b2 * b * d; t[2] = b2 * c2;
    t[3] = -4.0 * a * c2 * c;    t[4] = -27.0 * a * a * d * d;
    D = ((t[0] + t[1]) + (t[2] + t[3])) + t[4];
    S = ((fabs(t[0]) + fabs(t[1])) + (fabs(t[2]) + fabs(t[3]))) + fabs(t[4]);
    if (!(fabs(D) > (lo ? 37.0 : 32.0) * FR__U * S + FR__UNDERFLOW_SLACK)) return -1;
    want = D > 0 ? 3 : 1;
    n = fr__estimate_roots(q, 3, est);
    return fr__fast_certify(q, lo, 3, want, est, n, out);
}

/* Four real roots certified one by one, where the discriminant's sign is
   uncertain (clusters, roots of spread magnitudes): Ferrari's estimates
   polished by fr__fast_finish (converged, sorted, 64 ulps apart), then a
   certain sign change of the compensated value across x -+ 2u|x| around
   each (fr__sign_comp, outside its rounding band). Four disjoint brackets
   with a root each hold all of a quartic's roots, each returned root within
   2u of its own. -1 otherwise, at once when two estimates are closer than
   1e-5 relative: near-multiple roots, which rounding splits by about u^(1/2)
   or u^(1/3), do not certify, and polishing them costs more than the
   derivative sequence. */
static int fr__quartic_brackets(const double *q, const double *lo, double *out, fr__est_t *keep)
{
    double v, val[4], der[4], xa[4], xb[4], prev = -HUGE_VAL;
    int i, j, sg[4], sa[4], sb[4], ne = fr__estimate_roots(q, 4, out);
    fr__keep_estimates(keep, out, ne);
    if (ne != 4) return -1;
    for (i = 1; i < 4; i++) /* sorted, for the gaps */
        for (j = i; j > 0 && out[j] < out[j - 1]; j--) { v = out[j]; out[j] = out[j - 1]; out[j - 1] = v; }
    for (i = 1; i < 4; i++)
        if (!(out[i] - out[i - 1] > 1e-5 * (fabs(out[i]) > fabs(out[i - 1]) ? fabs(out[i]) : fabs(out[i - 1]))))
            return -1;
    if (fr__fast_finish(q, lo, 4, out, 4) != 4) return -1;
    /* one more Newton step on the compensated value: where the roots
       crowd, fr__polish_all's plain p' is off in its sixth digit and its
       early stop leaves a root a few ulps out (cluster 2, 2.001, 2.002,
       2.003: 7 ulps) */
    fr__sign_comp4(q, lo, 4, out, sg, val, der);
    for (j = 0; j < 4; j++) {
        double dlt;
        if (sg[j] != 0 && der[j] != 0) out[j] -= val[j] / der[j];
        dlt = 2.0 * FR__U * fabs(out[j]);
        if (!(out[j] - dlt > prev)) return -1; /* brackets disjoint, in order */
        prev = out[j] + dlt;
        xa[j] = out[j] - dlt;
        xb[j] = prev;
    }
    fr__sign_comp4(q, lo, 4, xa, sa, val, der);
    fr__sign_comp4(q, lo, 4, xb, sb, val, der);
    for (j = 0; j < 4; j++)
        if (sa[j] == 0 || sb[j] == 0 || sa[j] == sb[j]) return -1;
    return 4;
}

/* A fast path for quartics that is taken only when it can certify itself:
   the signs of the discriminant and of Lazard's P and D, each computed with
   a running error bound, give the number of distinct real roots (a^6 times
   the product of squared root differences: < 0 two real roots, > 0 with
   P < 0 and D < 0 four, otherwise none). Ferrari's estimates must then
   supply exactly that many roots, each must converge under compensated
   Newton to an ulp, and they must be distinct; otherwise -1 sends the
   quartic to the derivative sequence. Near-multiple roots, where the
   discriminant's sign is uncertain, always take the general path. */
static int fr__quartic_fast(const double *q, const double *lo, double *out, fr__est_t *keep)
{
    double a = q[4], b = q[3], c = q[2], d = q[1], e = q[0], t[16], D, S, P, SP, L, SL, est[4] = {0};
    double a2 = a * a, b2 = b * b, c2 = c * c, d2 = d * d, e2 = e * e;
    int n, want;
    t[0] = 256 * a2 * a * e2 * e;       t[1] = -192 * a2 * b * d * e2;
    t[2] = -128 * a2 * c2 * e2;         t[3] = 144 * a2 * c * d2 * e;
    t[4] = -27 * a2 * d2 * d2;          t[5] = 144 * a * b2 * c * e2;
    t[6] = -6 * a * b2 * d2 * e;        t[7] = -80 * a * b * c2 * d * e;
    t[8] = 18 * a * b * c * d2 * d;     t[9] = 16 * a * c2 * c2 * e;
    t[10] = -4 * a * c2 * c * d2;       t[11] = -27 * b2 * b2 * e2;
    t[12] = 18 * b2 * b * c * d * e;    t[13] = -4 * b2 * b * d2 * d;
    t[14] = -4 * b2 * c2 * c * e;       t[15] = b2 * c2 * d2;
    {
        double S2;
        D = fr__sum8(t, &S) + fr__sum8(t + 8, &S2);
        S += S2;
    }
    /* each term has < 8 roundings, the sum 4; lo: see fr__solve_fast */
    if (!(fabs(D) > (lo ? 71.0 : 64.0) * FR__U * S + FR__UNDERFLOW_SLACK)) return fr__quartic_brackets(q, lo, out, keep);
    if (D < 0) want = 2;
    else {
        P = 8 * a * c - 3 * b2; SP = 8 * fabs(a * c) + 3 * b2;
        L = 64 * a2 * a * e - 16 * a2 * c2 + 16 * a * b2 * c - 16 * a2 * b * d - 3 * b2 * b2;
        SL = 64 * fabs(a2 * a * e) + 16 * a2 * c2 + 16 * fabs(a * b2 * c) + 16 * fabs(a2 * b * d) + 3 * b2 * b2;
        if (!(fabs(P) > (lo ? 19.0 : 16.0) * FR__U * SP + FR__UNDERFLOW_SLACK) ||
            !(fabs(L) > (lo ? 37.0 : 32.0) * FR__U * SL + FR__UNDERFLOW_SLACK))
            return fr__quartic_brackets(q, lo, out, keep);
        want = P < 0 && L < 0 ? 4 : 0;
    }
    if (want == 0) return 0;
    n = fr__estimate_roots(q, 4, est);
    if ((want = fr__fast_certify(q, lo, 4, want, est, n, out)) < 0) fr__keep_estimates(keep, est, n);
    return want;
}

/* The certified fast path of degree n (2..4, q[n] != 0), or -1, for the
   polynomial q + lo (lo NULL or |lo[i]| <= u |q[i]|: a derivative level's
   exact split). The discriminants are taken from q alone; a term of degree
   g in the coefficients then differs from the exact polynomial's by at
   most ((1 + u)^g - 1) |term| < (g + 1) u |term|, which the sign tests'
   bounds add (g = 2 for b^2 - 4ac, 4 for the cubic's, 6 for the quartic's,
   2 and 4 for Lazard's P and D); the polish and the brackets use q + lo.
   keep (NULL, or set to n = -1 by the caller) receives a quartic's
   closed-form estimates when its fast path fails after computing them. */
static int fr__solve_fast(const double *q, const double *lo, int n, double *out, fr__est_t *keep)
{
    if (q[n] == 0) return -1;
    if (n == 2) return fr__quadratic_fast(q, lo, out);
    if (n == 3) return fr__cubic_fast(q, lo, out);
    if (n == 4) return fr__quartic_fast(q, lo, out, keep);
    return -1;
}

/* The derivative level D_k = p^(k)/k! of q (degree n): coefficients
   q[i+k] C(i+k, k), i = 0..n-k, each product split exactly into hi + lo by
   fma, so every level is evaluated as accurately as p itself. */
static void fr__derivative_level(const double *q, int n, int k, double *hi, double *lo)
{
    double binom = 1.0; /* C(i + k, k), exact */
    int i;
    for (i = 0; i <= n - k; i++) {
        if (i > 0) binom = binom * (double)(i + k) / (double)i;
        hi[i] = q[i + k] * binom;
        lo[i] = fma(q[i + k], binom, -hi[i]);
    }
}

/* Roots of c (degree n, c[0] != 0) with x in [xa, xb], a band inside
   |x| <= 2^K. The substitution x = 2^K y (exact) maps the band into [-1, 1],
   and the coefficients are normalised by a power of two. Each derivative
   level D_k = p^(k)/k! has coefficients q[i+k] C(i+k, k); the products are
   split exactly into hi + lo by fma, so every level is evaluated as
   accurately as p itself. */
static int fr__solve_band(const double *c, const int *ex, int n, int K, int Elo, double xa, double xb, int try_fast,
                          const fr__est_t *known, double *out)
{
    fr__est_t est0;
    double q[FR_POLY_MAX_DEGREE + 1] = {0}, hi[FR_POLY_MAX_DEGREE + 1], lo[FR_POLY_MAX_DEGREE + 1];
    double bp[FR_POLY_MAX_DEGREE + 1], cur[FR_POLY_MAX_DEGREE + 1];
    double ya = fr__ldexp(xa, -K), yb = fr__ldexp(xb, -K);
    int i, k, k0, nbp = 0, ncur = 0, M = INT_MIN;
    if (ya < -1.0) ya = -1.0;
    if (yb > 1.0) yb = 1.0;
    if (!(ya <= yb)) return 0;
    for (i = 0; i <= n; i++)
        if (c[i] != 0 && ex[i] + K * i > M) M = ex[i] + K * i;
    for (i = 0; i <= n; i++) q[i] = c[i] != 0 ? fr__ldexp(c[i], K * i - M) : 0.0;
    if (n == 1 && q[1] != 0) { /* a correctly rounded root */
        double y = -q[0] / q[1];
        if (y >= ya && y <= yb) { out[0] = fr__ldexp(y, K); return 1; }
        return 0;
    }
    est0.n = -1;
    if (known) /* estimates of c, in x: to y */
        for (est0.n = 0; est0.n < known->n; est0.n++) est0.x[est0.n] = fr__ldexp(known->x[est0.n], -K);
    if (try_fast && (ncur = fr__solve_fast(q, NULL, n, cur, &est0)) >= 0) {
        for (i = k = 0; i < ncur; i++)
            if (cur[i] >= ya && cur[i] <= yb) out[k++] = fr__ldexp(cur[i], K);
        return k;
    }
    /* The highest derivative level of degree 2..4 whose fast path certifies
       its real roots supplies the breakpoints, and the levels above it are
       skipped (for a quartic, p' by the cubic fast path instead of p''',
       p'' and p' by the sequence); a level whose fast path fails (multiple
       critical points) hands over to the next lower degree. */
    for (k0 = n - 1, k = n - 4 > 1 ? n - 4 : 1; k <= n - 2; k++) {
        fr__derivative_level(q, n, k, hi, lo);
        if ((ncur = fr__solve_fast(hi, lo, n - k, cur, NULL)) >= 0) {
            for (i = 0; i < ncur; i++)
                if (cur[i] > ya && cur[i] < yb) bp[nbp++] = cur[i];
            k0 = k - 1;
            break;
        }
    }
    for (k = k0; k >= 0; k--) {
        fr__derivative_level(q, n, k, hi, lo);
        ncur = fr__roots_between(hi, lo, n - k, ya, yb, bp, nbp, fr__ldexp(1.0, Elo - K), k == 0 ? &est0 : NULL, cur);
        for (i = 0; i < ncur; i++) bp[i] = cur[i];
        nbp = ncur;
    }
    for (i = 0; i < ncur; i++) out[i] = fr__ldexp(cur[i], K);
    return ncur;
}

/* ceil(a / b) for b in [1, FR_POLY_MAX_DEGREE] and |a| < 2^20, without a
   division (integer division was a tenth of a quartic solve): a + b - 1 is
   moved to nonnegative values by an offset that every b divides (twice
   lcm(1..16)), and x / b for x < 2^21 is exactly (x m_b) >> 32 with
   m_b = floor((2^32 - 1) / b) + 1 (Granlund & Montgomery 1994; checked for
   every such a and b). Modular unsigned arithmetic keeps the sum exact. */
static int fr__ceil_div(int a, int b)
{
    static const unsigned long long m[17] = {0, 0x100000000ull, 0x80000000ull, 0x55555556ull, 0x40000000ull,
        0x33333334ull, 0x2AAAAAABull, 0x24924925ull, 0x20000000ull, 0x1C71C71Dull, 0x1999999Aull, 0x1745D175ull,
        0x15555556ull, 0x13B13B14ull, 0x12492493ull, 0x11111112ull, 0x10000000ull};
    const unsigned long long off = 1441440;
    return (int)(((unsigned long long)(a + b - 1) + off) * m[b] >> 32) - (int)(off * m[b] >> 32);
}

/* Widest gap, in bits, between the Newton polygon's groups of root
   magnitudes at which fr__split_solve cuts p into truncated polynomials:
   the terms it drops are then below 2^-FR__SPLIT_GAP of the kept ones in
   the group's annulus, so the truncated roots start the polish ~1e-6 off. */
#define FR__SPLIT_GAP 20

/* The m roots of d (degree m, d[0] != 0, exponents ex[]) near x[], each
   polished and certified in its own power-of-two scaling x = 2^K y, |y| in
   [1/2, 1): the terms that balance at the root then stay far from overflow
   and underflow, whatever the other roots' magnitudes. The m scaled
   polynomials are polished in one call, a lane each. root[] gets the roots
   and 1 is returned when the polish converges and, for every root, the
   compensated value changes sign, certainly, across y -+ 2u|y| (the root is
   within 2u|x|). */
static int fr__certified_roots_near(const double *d, const int *ex, int m, const double *x, double *root)
{
    double q[4][5], y[4], ys[4], v[4], der[4];
    int i, j, s, K[4], sg[2][4];
    for (j = 0; j < 4; j++) {
        int M = INT_MIN, l = j < m ? j : 0;
        K[j] = fr__ilogb(x[l]) + 1;
        for (i = 0; i <= m; i++)
            if (ex[i] != INT_MIN && ex[i] + K[j] * i > M) M = ex[i] + K[j] * i;
        for (i = 0; i <= m; i++) q[j][i] = ex[i] != INT_MIN ? fr__ldexp(d[i], K[j] * i - M) : 0.0;
        y[j] = fr__ldexp(x[l], -K[j]);
    }
    if (!fr__polish_lanes(q[0], 5, NULL, m, y, m)) return 0;
    for (s = 0; s < 2; s++) { /* y -+ 2u|y| */
        for (j = 0; j < 4; j++) ys[j] = y[j] + (s ? 2.0 : -2.0) * FR__U * fabs(y[j]);
        fr__sign_comp_lanes(q[0], 5, NULL, m, ys, sg[s], v, der);
    }
    for (j = 0; j < m; j++) {
        root[j] = fr__ldexp(y[j], K[j]);
        if (!(sg[0][j] != 0 && sg[1][j] != 0 && sg[0][j] != sg[1][j])) return 0;
    }
    return 1;
}

/* Roots of spread magnitudes, split by the Newton polygon (degree m of 3
   or 4, d[0], d[m] != 0, coefficient exponents ex[], INT_MIN for a zero).
   A cut after coefficient k at radius 2^s, where every other term is below
   2^-FR__SPLIT_GAP of |d_k| 2^(k s), also satisfies Pellet's theorem: k
   roots lie inside |x| < 2^s and the rest outside. Between consecutive cuts
   the group's roots are those of the truncated polynomial d_l + ... + d_h
   x^(h-l) (its closed form, in its own scaling), up to the dropped terms.
   They are only starting points: each is polished on p and certified by a
   sign change across x -+ 2u|x| (fr__certified_roots_near); m disjoint such
   brackets hold all of p's roots. Anything else (no cut, a group whose
   truncated roots are complex, closer than 1e-5 relative (near-multiple:
   they would not certify) or do not certify) returns -1, for the
   derivative sequence; every group's estimates are checked before any
   root is polished, so a failure costs little. ODM's cases 22 and 24 (roots 1, 10, 1e152, 1e154;
   -1e30, 1e-30, 1, 1e30) take this path. */
static int fr__split_solve(const double *d, const int *ex, int m, double *out)
{
    int cut[5], ncut = 1, k, i, g, cnt = 0;
    double est[4];
    cut[0] = 0;
    for (k = 1; k < m; k++) {
        int lo = INT_MIN, hi = INT_MAX;
        if (ex[k] == INT_MIN) continue;
        /* necessary, from the neighbours alone: 2 ex[k] - ex[k-1] - ex[k+1] >= 2 (gap + 1) */
        if (ex[k - 1] != INT_MIN && ex[k + 1] != INT_MIN && 2 * ex[k] - ex[k - 1] - ex[k + 1] < 2 * FR__SPLIT_GAP + 2)
            continue;
        for (i = 0; i <= m; i++) {
            int num;
            if (i == k || ex[i] == INT_MIN) continue;
            num = ex[i] - ex[k] + 1 + FR__SPLIT_GAP; /* ex[k] + k s >= ex[i] + 1 + i s + gap */
            if (i < k) { int b = fr__ceil_div(num, k - i); if (b > lo) lo = b; }
            else { int b = -fr__ceil_div(num, i - k); if (b < hi) hi = b; } /* s <= floor(-num / (i - k)) */
        }
        if (lo <= hi) cut[ncut++] = k;
    }
    if (ncut == 1) return -1;
    cut[ncut] = m;
    for (g = 0; g < ncut; g++) {
        int l = cut[g], h = cut[g + 1], n = h - l, K, M = INT_MIN, ne;
        double t[5], *e = est + cnt;
        /* the truncated polynomial, scaled to its roots' geometric mean */
        K = -fr__ceil_div(ex[h] - ex[l], n); /* floor((ex[l] - ex[h]) / n) */
        for (i = l; i <= h; i++)
            if (ex[i] != INT_MIN && ex[i] + K * (i - l) > M) M = ex[i] + K * (i - l);
        for (i = l; i <= h; i++) t[i - l] = ex[i] != INT_MIN ? fr__ldexp(d[i], K * (i - l) - M) : 0.0;
        if (n == 1) { e[0] = -t[0] / t[1]; ne = 1; }
        else ne = fr__estimate_roots(t, n, e);
        if (ne != n) return -1; /* complex, or lost: not for this path */
        for (i = 0; i < n; i++) {
            for (k = 0; k < i; k++)
                if (!(fabs(e[i] - e[k]) > 1e-5 * fabs(e[i]))) return -1;
            if (!(e[i] != 0)) return -1;
            e[i] = fr__ldexp(e[i], K);
        }
        cnt += n;
    }
    if (!fr__certified_roots_near(d, ex, m, est, out)) return -1;
    for (i = 1; i < m; i++) { /* sorted, brackets disjoint */
        double v = out[i];
        int j = i;
        while (j > 0 && out[j - 1] > v) { out[j] = out[j - 1]; j--; }
        out[j] = v;
    }
    for (i = 1; i < m; i++)
        if (!(out[i] - 2.0 * FR__U * fabs(out[i]) > out[i - 1] + 2.0 * FR__U * fabs(out[i - 1]))) return -1;
    return m;
}

/* Exponents with 2^lo < |x| < 2^hi for every root x (Fujiwara's bound
   |x| <= 2 max |c_i / c_n|^(1/(n-i)), and the same on the reversed
   coefficients for 1/|x|), from the coefficients' exponents ex[] (INT_MIN
   for a zero coefficient), so that it cannot overflow. Both in one pass:
   they share every divisor. */
static void fr__root_exponent_bounds(const int *ex, int n, int *lo, int *hi)
{
    int i, H = INT_MIN, L = INT_MIN;
    for (i = 0; i < n; i++) {
        if (ex[i] != INT_MIN) {
            int e = fr__ceil_div(ex[i] - ex[n] + 1, n - i) + 1;
            if (e > H) H = e;
        }
        if (ex[n - i] != INT_MIN) {
            int e = fr__ceil_div(ex[n - i] - ex[0] + 1, n - i) + 1;
            if (e > L) L = e;
        }
    }
    *hi = H == INT_MIN ? 0 : H;
    *lo = L == INT_MIN ? 0 : -L;
}

FR_DEF double fr_poly_eval_compensated(const double *c, int degree, double t, double *abs_bound)
{
    double a, v, d;
    if (!c || degree < 0) { if (abs_bound) *abs_bound = 0; return 0.0; }
    v = fr__horner_comp(c, NULL, degree, t, &a, &d);
    if (abs_bound) *abs_bound = a;
    return v;
}

/* Descartes' rule of signs on d (degree m): no sign change in d (in d(-x))
   means no positive (negative) root, so that side is not searched (the
   empty bands of roots spread beyond one band, the negative pieces of
   every derivative level when all roots are positive); [*t0, *t1] is
   narrowed to the sides that may hold roots. 0 when neither does. */
static int fr__descartes(const double *d, int m, double *t0, double *t1)
{
    int i, i0 = -1, pos = 0, neg = 0;
    for (i = 0; i <= m; i++)
        if (d[i] != 0) {
            if (i0 >= 0) {
                int flip = (d[i] > 0) != (d[i0] > 0);
                pos += flip;
                neg += ((i - i0) & 1) ? !flip : flip;
            }
            i0 = i;
        }
    if (!pos && *t1 > 0) *t1 = 0;
    if (!neg && *t0 < 0) *t0 = 0;
    return pos || neg;
}

/* The roots of d (degree m >= 1, d[0] != 0, exponents ex) in [t0, t1],
   ascending, into buf: in one band when their magnitudes span at most
   W = FR__BAND_BITS / m bits, else in bands of at most W bits each,
   negative side from the largest magnitude down, then positive. try_fast:
   the fast paths were not tried yet (fr__solve_band). Returns their count. */
static int fr__solve_bands(const double *d, const int *ex, int m, double t0, double t1, int try_fast, fr__est_t *known,
                           double *buf)
{
    int Elo, Ehi, W = FR__BAND_BITS / m, e, side, cnt = 0;
    fr__root_exponent_bounds(ex, m, &Elo, &Ehi); /* every root has 2^Elo < |x| < 2^Ehi */
    if (Ehi - Elo <= W) {
        double B = fr__ldexp(1.0, Ehi);
        return fr__solve_band(d, ex, m, Ehi, Elo, t0 > -B ? t0 : -B, t1 < B ? t1 : B, try_fast, known, buf);
    }
    for (side = -1; side <= 1; side += 2) {
        for (e = 0; e < Ehi - Elo; e += W) {
            int e1 = side < 0 ? Ehi - e : Elo + e + W, e0 = e1 - W;
            double lo = fr__ldexp(1.0, e0 < Elo ? Elo : e0), hi = fr__ldexp(1.0, e1 > Ehi ? Ehi : e1);
            double xa = side < 0 ? -hi : lo, xb = side < 0 ? -lo : hi;
            if (xa < t0) xa = t0;
            if (xb > t1) xb = t1;
            if (xa <= xb && cnt < m) {
                double band[FR_POLY_MAX_DEGREE + 1];
                int k, nb = fr__solve_band(d, ex, m, e1 > Ehi ? Ehi : e1, Elo, xa, xb, try_fast, known, band);
                for (k = 0; k < nb && cnt < m; k++)
                    if (cnt == 0 || band[k] > buf[cnt - 1]) buf[cnt++] = band[k];
            }
        }
    }
    return cnt;
}

/* The cnt ascending roots of buf inside [t0, t1], with the zero root
   (when z > 0 and 0 is inside) merged in order, distinct, into r. Returns
   their count. */
static int fr__merge_roots(const double *buf, int cnt, int z, double t0, double t1, double *r)
{
    int i, k = 0, zdone = !(z > 0 && t0 <= 0 && 0 <= t1);
    for (i = 0; i < cnt; i++) {
        double x = buf[i];
        if (!zdone && x >= 0) { r[k++] = 0.0; zdone = 1; if (x == 0) continue; }
        if (x >= t0 && x <= t1 && x - x == 0 && (k == 0 || x > r[k - 1])) r[k++] = x;
    }
    if (!zdone) r[k++] = 0.0;
    return k;
}

static FR__NOINLINE int fr__solve_poly(const double *c, int degree, double t0, double t1, double *r)
{
    double buf[FR_POLY_MAX_DEGREE + 1];
    const double *d;
    int i, n, z, m, cnt = 0, emax = INT_MIN, direct, split, ex[FR_POLY_MAX_DEGREE + 1] = {0};
    fr__est_t known;
    known.n = -1;
    if (!c || !r || degree < 0 || degree > FR_POLY_MAX_DEGREE || !(t0 <= t1)) return -1;
    for (i = 0; i <= degree; i++)
        if (!(c[i] - c[i] == 0)) return -1; /* NaN or infinite */
    n = degree;
    while (n > 0 && c[n] == 0) n--;
    z = 0;
    while (z < n && c[z] == 0) z++;
    if (n == 0) return 0;
    d = c + z; /* zero roots split off: d has d[0] != 0 */
    m = n - z;
    for (i = 0; i <= m; i++) {
        ex[i] = d[i] != 0 ? fr__ilogb(d[i]) : INT_MIN; /* once, for all below */
        if (ex[i] > emax) emax = ex[i];
    }
    if (-ex[0] > emax) emax = -ex[0]; /* the ends bound the roots away from 0 and infinity */
    if (-ex[m] > emax) emax = -ex[m];
    /* Coefficients below 2^FR__DIRECT_EXP, the ends above 2^-FR__DIRECT_EXP:
       the fast paths run on them as they are. The band's power-of-two
       scaling is exact, so it would give the same roots, and the bounds and
       scaling below cost a quarter of a quartic solve. */
    /* -2: not tried; -1: tried and not certified, which the band's exact
       scaling would not change, so the band skips the fast path */
    direct = z == 0 && m >= 2 && m <= 4 && emax <= FR__DIRECT_EXP ? fr__solve_fast(d, NULL, m, buf, &known) : -2;
    if (direct >= 0) {
        cnt = direct; /* certified; filtered below */
    } else if (z == 0 && (m == 3 || m == 4) && (split = fr__split_solve(d, ex, m, buf)) >= 0) {
        cnt = split; /* roots of spread magnitudes, certified; filtered below */
    } else if (z == 0 && m == 1 && emax <= FR__DIRECT_EXP) {
        /* a plane's leaf in analytic CSG: the band below would scale by
           powers of two and divide, the same correctly rounded quotient
           (no underflow or overflow within 2^+-FR__DIRECT_EXP) */
        buf[0] = -d[0] / d[1];
        cnt = 1;
    } else if (m > 0 && fr__descartes(d, m, &t0, &t1)) {
        cnt = fr__solve_bands(d, ex, m, t0, t1, direct == -2, &known, buf);
    }
    return fr__merge_roots(buf, cnt, z, t0, t1, r);
}

FR_DEF int fr_solve_poly(const double *c, int degree, double t0, double t1, double *r)
{
    FR__IN_FP_ENV(int, fr__solve_poly(c, degree, t0, t1, r));
}

FR_DEF int fr_solve_quadratic(const double c[3], double r[2]) { return fr_solve_poly(c, 2, -HUGE_VAL, HUGE_VAL, r); }
FR_DEF int fr_solve_cubic(const double c[4], double r[3]) { return fr_solve_poly(c, 3, -HUGE_VAL, HUGE_VAL, r); }
FR_DEF int fr_solve_quartic(const double c[5], double r[4]) { return fr_solve_poly(c, 4, -HUGE_VAL, HUGE_VAL, r); }

/* ==== [end section: solvers] ==== */

/* ==== [section: trace] implementation: ray-surface intersection ==== */

#define FR__TAYLOR_N (FR_POLY_MAX_DEGREE + 1)
/* Interval bisection depth limit: 2^-62 of a segment is below any useful
   tolerance, and the explicit stack needs one entry per level. */
#define FR__TRACE_MAX_DEPTH 62
/* The tape is pruned on every FR__PRUNE_EVERY-th bisection level; a pruned
   tape is kept per level group, so scratch holds this many tape buffers. */
#define FR__PRUNE_EVERY 4
#define FR__PRUNE_LEVELS (FR__TRACE_MAX_DEPTH / FR__PRUNE_EVERY + 2)
/* Interval leaves without a sign change are bisected down to tol times
   this before they count as a touch (2^-10: ten more levels). */
#define FR__TOUCH_SCALE (1.0 / 1024.0)
/* Analytic CSG: a leaf root is on the solid's surface when f changes sign
   across it within this many ulps of the point's scale |t| + |o|/|d| (the
   point o + t d itself is only known to that accuracy). */
#define FR__CSG_SIGN_ULPS 64.0
/* Default t tolerance, relative to the segment length. */
#define FR__TRACE_TOL_REL 1e-9
#define FR__TRACE_MAX_ITERS 100000u
/* Sphere tracing: default over-relaxation (Keinert et al. 2014 use 1.2-1.6). */
#define FR__SPHERE_OMEGA 1.6
/* Finite-difference normal step, relative to max(1, |p|). */
#define FR__FD_STEP 1e-6

static size_t fr__align8(size_t n) { return (n + 7u) & ~(size_t)7u; }

/* Scratch layout, every part 8-aligned:
     [eval]   max of the point/grad/interval/affine/prune evaluator scratch
     [taylor] n * FR__TAYLOR_N doubles, then n ints (degree, -1 = not polynomial)
     [mag]    the same again for the magnitude run (interval, polynomial tapes)
     [flags]  n bytes (analytic CSG: slot needed)
     [list]   n unsigned ints (analytic CSG: the needed slots, ascending)
     [cand]   n * FR_POLY_MAX_DEGREE doubles (analytic CSG candidate roots)
     [cleaf]  n * FR_POLY_MAX_DEGREE unsigned ints (prepared CSG: each candidate's leaf)
     [sgn]    4n signed chars (prepared CSG: leaf and node signs either side of a candidate, culled nodes, live slots)
     [prune]  FR__PRUNE_LEVELS * n instructions (interval: pruned tapes) */
typedef struct fr__trace_mem_t {
    void *eval;
    double *taylor, *taylor_mag; /* plain and magnitude runs (fr__taylor_run) */
    int *deg, *deg_mag;
    unsigned char *need;
    unsigned int *list;
    double *cand;
    unsigned int *cleaf;
    signed char *sgn;
    fr_instr_t *prune;
} fr__trace_mem_t;

static size_t fr__eval_scratch_max(const fr_tape_t *t)
{
    /* every kind's scratch is n times its bytes per instruction (fr_trace
       runs this per ray: the constant maximum, multiplied out once) */
    size_t m = fr__scratch_per_instr(FR_EVAL_GRAD), s, n = t->n_code ? (size_t)t->n_code : 1;
    s = fr__scratch_per_instr(FR_EVAL_INTERVAL); if (s > m) m = s;
    s = fr__scratch_per_instr(FR_EVAL_AFFINE); if (s > m) m = s;
    s = fr__scratch_per_instr(FR_EVAL_PRUNE); if (s > m) m = s;
    return fr__align8(n * m);
}

static size_t fr__trace_layout(const fr_tape_t *t, void *base, fr__trace_mem_t *mem)
{
    /* n rounded up to a multiple of 8 keeps every part 8-aligned with no
       per-part rounding (fr_trace lays this out per ray) */
    size_t n = ((t->n_code ? (size_t)t->n_code : 1) + 7u) & ~(size_t)7u, off;
    unsigned char *b = (unsigned char *)base;
    off = fr__eval_scratch_max(t);
    if (mem) {
        mem->eval = b;
        mem->taylor = (double *)(void *)(b + off);
        mem->deg = (int *)(void *)(b + off + n * FR__TAYLOR_N * sizeof(double));
    }
    off += n * (FR__TAYLOR_N * sizeof(double) + sizeof(int));
    if (mem) {
        mem->taylor_mag = (double *)(void *)(b + off);
        mem->deg_mag = (int *)(void *)(b + off + n * FR__TAYLOR_N * sizeof(double));
    }
    off += n * (FR__TAYLOR_N * sizeof(double) + sizeof(int));
    if (mem) {
        mem->need = b + off;
        mem->list = (unsigned int *)(void *)(b + off + n);
        mem->cand = (double *)(void *)(b + off + n + n * sizeof(unsigned int));
        mem->cleaf = (unsigned int *)(void *)(b + off + n + n * sizeof(unsigned int) + n * FR_POLY_MAX_DEGREE * sizeof(double));
    }
    off += n + n * sizeof(unsigned int) + n * FR_POLY_MAX_DEGREE * (sizeof(double) + sizeof(unsigned int));
    if (mem) mem->sgn = (signed char *)(void *)(b + off);
    off += 4 * n;
    if (mem) mem->prune = (fr_instr_t *)(void *)(b + off);
#ifndef FR_NO_INTERVAL
    off += fr__align8((size_t)FR__PRUNE_LEVELS * n * sizeof(fr_instr_t));
#endif
    return off;
}

FR_DEF size_t fr_trace_scratch_size(const fr_tape_t *t, const fr_trace_desc_t *desc)
{
    (void)desc;
    if (!t) return 0;
    return fr__trace_layout(t, NULL, NULL);
}

FR_DEF size_t fr_ray_poly_scratch_size(const fr_tape_t *t)
{
    size_t n = t && t->n_code ? (size_t)t->n_code : 1;
    return fr__align8(n * FR__TAYLOR_N * sizeof(double)) + fr__align8(n * sizeof(int));
}

/* ---------------------------------------------------------------- Taylor arithmetic */

/* The top coefficient of a product or quotient of nonzero tops is
   nonzero and normal unless it underflowed; then it is NaN, so the ray
   takes the path an overflow takes (fr__checked_degree). An ellipsoid
   1e162 across through its centre has the t^2 coefficient -1/a^2 =
   -1e-324: it rounded to 0, the polynomial read as the constant 1, and
   ANALYTIC, AUTO and INTERVAL's centred form reported no hit (found by
   review, 2026-12-06). Lower coefficients are not checked: all of a
   coefficient's terms underflow only where higher ones dominate it. */
static FR__HOT_INLINE void fr__tpoly_top_underflow(double *c, int dc, int nonzero_tops)
{
    if (nonzero_tops && !(fabs(c[dc]) >= DBL_MIN)) c[dc] = NAN;
}

/* c = a * b truncated; returns the degree or -1 if it would exceed the cap.
   c may be a or b (or both): coefficient k is written after every read of
   a[i], b[j] with i, j <= k, from the top down, so no temporary is needed
   (a copy per product was a tenth of the ray-polynomial time). */
static int fr__tpoly_mul(const double *a, int da, const double *b, int db, double *c)
{
    int i, k, dc = da + db;
    double at, bt;
    if (dc > FR_POLY_MAX_DEGREE) return -1;
    at = a[da], bt = b[db]; /* read before c, which may alias them, is written */
    if (da <= 2 && db <= 2) {
        /* Products of linear and quadratic factors (o + t d, quadrics, the
           squares inside x^4) are most of a quadric or quartic tape: the
           operands are read into registers first (so c may alias them) and
           the sums are the general loop's, unrolled (a third of the
           ray-polynomial time went to the loop's bounds). */
        double a0 = a[0], a1 = da >= 1 ? a[1] : 0.0, a2 = da >= 2 ? a[2] : 0.0;
        double b0 = b[0], b1 = db >= 1 ? b[1] : 0.0, b2 = db >= 2 ? b[2] : 0.0;
        c[0] = a0 * b0;
        if (dc >= 1) c[1] = a0 * b1 + a1 * b0;
        if (dc >= 2) c[2] = (a0 * b2 + a1 * b1) + a2 * b0;
        if (dc >= 3) c[3] = a1 * b2 + a2 * b1;
        if (dc >= 4) c[4] = a2 * b2;
    } else {
        for (k = dc; k >= 0; k--) {
            int lo = k - db > 0 ? k - db : 0, hi = k < da ? k : da;
            double sum = 0.0;
            for (i = lo; i <= hi; i++) sum += a[i] * b[k - i];
            c[k] = sum;
        }
    }
    fr__tpoly_top_underflow(c, dc, at != 0 && bt != 0);
    return dc;
}

static int fr__tpoly_trim(const double *c, int d)
{
    while (d > 0 && c[d] == 0) d--;
    return d;
}

/* A scalar op on constant operands (degree 0), so constant subtrees that the
   builder did not fold stay polynomial. Returns 0 if the op is not handled. */
static int fr__tpoly_const_op(const fr_instr_t *in, double a, double b, double *out)
{
    switch ((fr_op_t)in->op) {
    case FR_OP_SQRT: *out = sqrt(a); return 1;
    case FR_OP_ABS: *out = fabs(a); return 1;
    case FR_OP_EXP: *out = exp(a); return 1;
    case FR_OP_LOG: *out = log(a); return 1;
    case FR_OP_SIN: *out = sin(a); return 1;
    case FR_OP_COS: *out = cos(a); return 1;
    case FR_OP_ATAN: *out = atan(a); return 1;
    case FR_OP_POWC: *out = pow(a, in->k); return 1;
    case FR_OP_MIN: *out = a < b ? a : b; return 1;
    case FR_OP_MAX: *out = a > b ? a : b; return 1;
    default: return 0;
    }
}

/* c = a^n truncated (n >= 0), c distinct from a; returns the degree or -1. */
static FR__HOT_INLINE int fr__tpoly_powi(const double *a, int da, int n, double *c)
{
    double base[FR__TAYLOR_N];
    int k, db = da, dc;
    if (n >= 2 && (n & (n - 1)) == 0) {
        /* x^2, x^4, x^8 (the tangle cube's powers): squarings in place, no
           copy of the base and no product with 1 */
        dc = fr__tpoly_mul(a, da, a, da, c);
        for (n >>= 1; n > 1 && dc >= 0; n >>= 1) dc = fr__tpoly_mul(c, dc, c, dc, c);
        return dc;
    }
    for (k = 0; k <= da; k++) base[k] = a[k];
    c[0] = a[0] - a[0] + 1.0; /* 1, or NaN for a non-finite base */
    dc = 0;
    while (n > 0 && dc >= 0) { /* binary powering */
        if (n & 1) dc = fr__tpoly_mul(c, dc, base, db, c);
        n >>= 1;
        if (n > 0) db = fr__tpoly_mul(base, db, base, db, base);
        if (db < 0) return -1;
    }
    return dc;
}

/* The degree of slot `in` as a polynomial in t from its operands' degrees
   da, db (-1: not a polynomial), var_deg the degree of a coordinate (1, or
   0 where the ray's direction has no such component); -1 when the result
   is not a polynomial of degree <= FR_POLY_MAX_DEGREE. */
static FR__HOT_INLINE int fr__tpoly_degree(const fr_instr_t *in, int da, int db, int var_deg)
{
    switch ((fr_op_t)in->op) {
    case FR_OP_CONST: return 0;
    case FR_OP_VAR_X: case FR_OP_VAR_Y: case FR_OP_VAR_Z: return var_deg;
    case FR_OP_NEG: return da;
    case FR_OP_ADD: case FR_OP_SUB: return da >= 0 && db >= 0 ? (da > db ? da : db) : -1;
    case FR_OP_MUL: return da >= 0 && db >= 0 && da + db <= FR_POLY_MAX_DEGREE ? da + db : -1;
    case FR_OP_SQR: return da >= 0 && 2 * da <= FR_POLY_MAX_DEGREE ? 2 * da : -1;
    case FR_OP_POWI:
        return da >= 0 && in->k >= 0 && in->k == floor(in->k) && in->k * da <= FR_POLY_MAX_DEGREE ? (int)in->k * da
                                                                                                  : -1;
    case FR_OP_DIV: return da >= 0 && db == 0 ? da : -1;
    case FR_OP_MIN: case FR_OP_MAX: return da == 0 && db == 0 ? 0 : -1;
    case FR_OP_SQRT: case FR_OP_ABS: case FR_OP_EXP: case FR_OP_LOG: case FR_OP_SIN: case FR_OP_COS:
    case FR_OP_ATAN: case FR_OP_POWC: return da == 0 ? 0 : -1;
    default: return -1;
    }
}

/* The magnitude of a constant op's result (the magnitude run,
   fr__tpoly_step), from the plain operand (pa), the plain result (fc) and
   the operands' magnitudes ma, mb. Sums and
   products carry their operands' errors through absolute values; these
   ops amplify them: the plain operand is within rho ma of the exact one,
   and a result that moves by up to L rho ma (L bounding |f'| near a) is
   covered by fc + 2 L ma. Where the operand came from a cancellation (ma
   much larger than |a|) or f is ill-conditioned there (sin of a large
   argument, log near 1, a power or division near 0), |fc| alone was no
   bound: 1e16 sin(13 y) on a ray with d_y = 0, 13 y rounded 2e-16 off
   2 pi, flipped the sign of the whole polynomial and INTERVAL proved a
   miss (found by review, 2026-12-06). The bounds assume rho ma <= |a| / 10
   (and <= 0.6 for exp): the centred form is used only where rho <=
   2.002e-3 (fr__interval_poly_form: 160 n u < 1e-3), so ma < 50 |a| (ma
   < 300) suffices; beyond it the magnitude is inf and the centred form
   gives up on the ray. */
#define FR__MAG_COND 50.0
static double fr__amplified_mag(const fr_instr_t *in, double pa, double fc, double ma, double mb)
{
    double ra = fabs(pa), f = fabs(fc);
    switch ((fr_op_t)in->op) {
    case FR_OP_ABS: case FR_OP_SIN: case FR_OP_COS: case FR_OP_ATAN: return f + 2.0 * ma; /* |f'| <= 1 */
    case FR_OP_MIN: case FR_OP_MAX: return f + 2.0 * (ma + mb);
    case FR_OP_EXP: return ma < 300.0 ? f + 4.0 * f * ma : HUGE_VAL; /* f' = f, within e^0.6 f */
    default: break;
    }
    if (ma == 0) return f; /* an exact operand */
    if (!(ma < FR__MAG_COND * ra)) return HUGE_VAL;
    switch ((fr_op_t)in->op) {
    case FR_OP_LOG: return f + 4.0 * ma / ra;        /* 1/a, within 1.2/|a| */
    case FR_OP_SQRT: return f + 2.0 * ma / sqrt(ra); /* 1/(2 sqrt a), within 0.53/sqrt|a| */
    case FR_OP_POWC: /* k a^(k-1), within 1.2 |k| f/|a| when (|k| + 1) rho ma <= |a| / 10 */
        return (fabs(in->k) + 1.0) * ma < FR__MAG_COND * ra ? f + 4.0 * fabs(in->k) * f * ma / ra : HUGE_VAL;
    default: return HUGE_VAL;
    }
}

/* One slot of a Taylor run: c from its operands A (degree da) and B (db),
   whose result's degree fr__tpoly_degree gives. With plain != NULL (the slot's
   plain coefficients; pa, pb the plain operands) it is the magnitude run
   instead: every input and constant by its absolute value and every
   subtraction an addition, so each coefficient is the sum of the absolute
   values of the terms whose rounded sum the plain run computed; divisions
   and constant ops add what they amplify (fr__amplified_mag). It scales
   the plain coefficients' rounding error (fr__poly_range). An invalid
   operand of a constant op (a division by 0, a non-finite argument) gives
   NaN, which every later op keeps. */
static FR__HOT_INLINE void fr__tpoly_step(const fr_instr_t *in, const double *A, int da, const double *B, int db,
                                  const double o[3], const double d[3], double *c, const double *plain,
                                  const double *pa, const double *pb)
{
    int k, mag = plain != NULL;
    switch ((fr_op_t)in->op) {
    case FR_OP_CONST: c[0] = mag ? fabs(in->k) : in->k; break;
    case FR_OP_VAR_X: case FR_OP_VAR_Y: case FR_OP_VAR_Z: {
        int ax = (int)in->op - (int)FR_OP_VAR_X;
        c[0] = mag ? fabs(o[ax]) : o[ax]; c[1] = mag ? fabs(d[ax]) : d[ax];
        break;
    }
    case FR_OP_NEG: for (k = 0; k <= da; k++) c[k] = mag ? A[k] : -A[k]; break;
    case FR_OP_ADD: case FR_OP_SUB: {
        double sgn = in->op == FR_OP_ADD || mag ? 1.0 : -1.0;
        int lo = da < db ? da : db;
        for (k = 0; k <= lo; k++) c[k] = A[k] + sgn * B[k];
        for (; k <= da; k++) c[k] = A[k];
        for (; k <= db; k++) c[k] = sgn * B[k];
        break;
    }
    case FR_OP_MUL: fr__tpoly_mul(A, da, B, db, c); break;
    case FR_OP_SQR: fr__tpoly_mul(A, da, A, da, c); break;
    case FR_OP_POWI: fr__tpoly_powi(A, da, (int)in->k, c); break;
    case FR_OP_DIV: {
        double q = B[0] != 0 ? B[0] : NAN;
        if (mag) { /* A / q_exact: the numerator's share over |q| / 1.1, |c| |dq| / |q| (1.12) the divisor's */
            double aq = fabs(pb[0]), mq = B[0];
            int bounded = mq == 0 || mq < FR__MAG_COND * aq;
            for (k = 0; k <= da; k++) c[k] = bounded ? (1.25 * A[k] + 2.0 * fabs(plain[k]) * mq) / aq : HUGE_VAL;
        } else {
            for (k = 0; k <= da; k++) c[k] = A[k] / q;
            fr__tpoly_top_underflow(c, da, A[da] != 0);
        }
        break;
    }
    default: /* an op on constants */
        if (mag) c[0] = fr__amplified_mag(in, pa[0], plain[0], A[0], db >= 0 ? B[0] : 0.0);
        else if (!(A[0] - A[0] == 0) || ((in->op == FR_OP_MIN || in->op == FR_OP_MAX) && !(B[0] - B[0] == 0)) ||
                 !fr__tpoly_const_op(in, A[0], B[0], c))
            c[0] = NAN;
        break;
    }
}

/* The degree of a slot's coefficients c of degree dg (-1: none), trailing
   zeros trimmed; -1 if any is not finite (an overflow on this ray) or,
   nonzero, below min_abs in magnitude. The ray tracers pass
   FR__TRACE_MIN_COEF: subnormal coefficients have lost their relative
   precision (a quartic model 1e-80 across has f ~ 1e-320 on the ray, and
   so does a direction 1e-80 long in the t^4 term), roots and error bounds
   from them would be wrong by orders of magnitude while claiming double
   accuracy, so the ray takes the path an overflow takes (fr_trace's AUTO:
   the interval method, which never certifies from such values alone;
   ANALYTIC: FR_ERR_NOT_POLYNOMIAL). fr_ray_poly passes 0. */
#define FR__TRACE_MIN_COEF DBL_MIN
static int fr__checked_degree(const double *c, int dg, double min_abs)
{
    int k;
    for (k = 0; k <= dg; k++)
        if (!(c[k] - c[k] == 0) || (c[k] != 0 && fabs(c[k]) < min_abs)) return -1;
    return dg >= 0 ? fr__tpoly_trim(c, dg) : -1;
}

/* Evaluate every slot of the tape as a polynomial in t (paper §3.1.1: turn
   f(X) = 0 into g(t) = 0). deg[i] = -1 marks a slot that is not a
   polynomial of degree <= FR_POLY_MAX_DEGREE; such slots propagate.
   With signed_P (the result of a plain run) it is the magnitude run
   (fr__tpoly_step). Sums are trimmed of trailing zero coefficients. An
   overflow is not checked per slot: inf and NaN propagate through every
   op (fr__tpoly_step turns invalid constant ops into NaN), so the slots
   that are used -- the output, CSG leaves -- are checked where they are
   read (fr__checked_degree); a check per slot was a quarter of the run. */
static void fr__taylor_run(const fr_tape_t *t, const double o[3], const double d[3], double *P, int *deg,
                           const double *signed_P)
{
    unsigned int i;
    for (i = 0; i < t->n_code; i++) {
        const fr_instr_t *in = &t->code[i];
        double *c = P + (size_t)i * FR__TAYLOR_N;
        const double *A = P + (size_t)in->a * FR__TAYLOR_N, *B = P + (size_t)in->b * FR__TAYLOR_N;
        int da = i > 0 ? deg[in->a] : -1, db = i > 0 ? deg[in->b] : -1, dc;
        int vd = in->op >= FR_OP_VAR_X && in->op <= FR_OP_VAR_Z ? d[in->op - FR_OP_VAR_X] != 0 : 1;
        dc = fr__tpoly_degree(in, da, db, vd);
        if (dc >= 0) {
            fr__tpoly_step(in, A, da, B, db, o, d, c, signed_P ? signed_P + (size_t)i * FR__TAYLOR_N : NULL,
                           signed_P ? signed_P + (size_t)in->a * FR__TAYLOR_N : NULL,
                           signed_P ? signed_P + (size_t)in->b * FR__TAYLOR_N : NULL);
            if (in->op == FR_OP_ADD || in->op == FR_OP_SUB) dc = fr__tpoly_trim(c, dc);
        }
        deg[i] = dc;
    }
}

FR_DEF fr_result_t fr_ray_poly(const fr_tape_t *t, const double o[3], const double d[3], void *scratch,
                               double *coef, int *degree)
{
    double *P;
    int *deg, k, dg;
    unsigned int out;
    if (!t || !o || !d || !scratch || !coef || !degree || t->n_code == 0) return FR_ERR_INVALID_ARG;
    P = (double *)scratch;
    deg = (int *)(void *)((unsigned char *)scratch + fr__align8((size_t)t->n_code * FR__TAYLOR_N * sizeof(double)));
    fr__taylor_run(t, o, d, P, deg, NULL);
    out = t->outputs[0];
    dg = fr__checked_degree(P + (size_t)out * FR__TAYLOR_N, deg[out], 0);
    if (dg < 0) return FR_ERR_NOT_POLYNOMIAL;
    for (k = 0; k <= FR_POLY_MAX_DEGREE; k++) coef[k] = k <= dg ? P[(size_t)out * FR__TAYLOR_N + (size_t)k] : 0.0;
    *degree = dg;
    return FR_OK;
}

/* ---------------------------------------------------------------- prepared models: the parts */

/* One instruction of a prepared Taylor program: tape slot `slot` with the
   degrees fr__tpoly_degree gives for a direction without zero components,
   an upper bound for every ray (a zero component, or a cancellation, only
   leaves exact zeros on top, which fr__prog_degree trims). */
typedef struct fr__tp_t {
    unsigned int slot, a, b;           /* the tape's slot and its operands (0 if unused), */
    unsigned int oc, oa, ob;           /* and their offsets in a Taylor array (slot * FR__TAYLOR_N) */
    unsigned char da, db, dc, kernel; /* kernel: FR__K_*, chosen by fr__prog_kernel */
} fr__tp_t;

/* Kernels of fr__prog_run, plain and magnitude run side by side: products
   by a constant, squares of linear and quadratic factors and fourth powers
   of linear ones (a quadric or quartic tape is mostly these) written out;
   the rest through fr__tpoly_step. A doubled product 2 a_i a_j is rounded
   once where fr__tpoly_mul rounds a_i a_j + a_j a_i twice, within the same
   bound (fr__poly_range_of). */
#define FR__K_STEP 0
#define FR__K_MULK 1 /* b of degree 0 */
#define FR__K_KMUL 2 /* a of degree 0 */
#define FR__K_SQR1 3 /* a^2, a linear */
#define FR__K_SQR2 4 /* a^2, a quadratic */
#define FR__K_POW4 5 /* a^4, a linear */
#define FR__K_ADD 6
#define FR__K_SUB 7
#define FR__K_CONST 8
#define FR__K_VAR 9
#define FR__K_NEG 10
static unsigned char fr__prog_kernel(const fr_instr_t *in, int da, int db)
{
    int sq = in->op == FR_OP_SQR || (in->op == FR_OP_POWI && in->k == 2);
    if (in->op == FR_OP_CONST) return FR__K_CONST;
    if (in->op >= FR_OP_VAR_X && in->op <= FR_OP_VAR_Z) return FR__K_VAR;
    if (in->op == FR_OP_NEG) return FR__K_NEG;
    if (in->op == FR_OP_MUL && db == 0) return FR__K_MULK;
    if (in->op == FR_OP_MUL && da == 0) return FR__K_KMUL;
    if (sq && da == 1) return FR__K_SQR1;
    if (sq && da == 2) return FR__K_SQR2;
    if (in->op == FR_OP_POWI && in->k == 4 && da == 1) return FR__K_POW4;
    if (in->op == FR_OP_ADD) return FR__K_ADD;
    if (in->op == FR_OP_SUB) return FR__K_SUB;
    return FR__K_STEP;
}

/* c = a^2, a of degree 2 (5 coefficients), c may alias nothing. */
static FR__HOT_INLINE void fr__sqr2(double a0, double a1, double a2, double *c)
{
    c[0] = a0 * a0;
    c[1] = 2.0 * (a0 * a1);
    c[2] = a1 * a1 + 2.0 * (a0 * a2);
    c[3] = 2.0 * (a1 * a2);
    c[4] = a2 * a2;
}

/* A CSG leaf of a prepared model. For a quadric (degree <= 2, `quadric`)
   its monomial form about e: f(e + q) = k + b.q + q^T A q with q[0] = k,
   q[1..3] = b, q[4..6] = A's diagonal, q[7..9] = A's xy, xz, yz entries
   (half the monomial coefficients). `box` holds the leaf's zero set inside
   the prepared box when `boxed`. */
typedef struct fr__leaf_t {
    unsigned int slot;
    int degree, quadric, boxed;
    int shape; /* quadrics: FR__LEAF_LINEAR (A = 0), FR__LEAF_DIAGONAL, FR__LEAF_FULL */
    double e[3], q[10], box[6];
    /* decides[s]: with the leaf of sign 2s - 1 throughout the segment and
       the boxed nodes of needs[s] missed (-1), the shape has one sign
       throughout, so there is no hit (fr__prepare_decides) */
    int decides[2];
    unsigned long long needs[2];
} fr__leaf_t;
#define FR__LEAF_LINEAR 1
#define FR__LEAF_DIAGONAL 2
#define FR__LEAF_FULL 3

/* A CSG node over signs; a and b index leaves [0, n_leaves), then nodes. */
typedef struct fr__csg_node_t {
    unsigned int op, a, b; /* FR__CSG_NEG, FR__CSG_MIN (intersections), FR__CSG_MAX (unions) */
    unsigned int slot;
    int boxed;             /* box holds the node's solid {f >= 0} */
    double box[6];
    /* boxed nodes (the first 64): the node's own bit, and the leaves
       (when n_leaves <= 64) and boxed nodes only it reaches, whose work a
       ray missing its box skips (fr__prepare_masks) */
    unsigned long long bit, leaf_mask, node_mask;
} fr__csg_node_t;

/* The head of fr_prepared_t.mem: the box, padded once as fr__clip_box
   pads it per ray. */
typedef struct fr__prep_head_t {
    double box[6];
    unsigned int n_boxed_nodes;
} fr__prep_head_t;

#define FR__CSG_NEG 0u
#define FR__CSG_MIN 1u
#define FR__CSG_MAX 2u

/* The block of fr_prepared_t.mem: head, leaves, nodes, program. */
static size_t fr__prep_layout(unsigned int nl, unsigned int nn, unsigned int np, fr__leaf_t **L, fr__csg_node_t **N,
                              fr__tp_t **P, void *mem)
{
    size_t off = fr__align8(sizeof(fr__prep_head_t));
    unsigned char *b = (unsigned char *)mem;
    if (L) *L = (fr__leaf_t *)(void *)(b + off);
    off += fr__align8((size_t)nl * sizeof(fr__leaf_t));
    if (N) *N = (fr__csg_node_t *)(void *)(b + off);
    off += fr__align8((size_t)nn * sizeof(fr__csg_node_t));
    if (P) *P = (fr__tp_t *)(void *)(b + off);
    off += fr__align8((size_t)np * sizeof(fr__tp_t));
    return off;
}

/* Run a prepared Taylor program on the ray o + s d: the plain run into P
   and, if M is not NULL, the magnitude run into M in the same pass (the
   two runs of fr__taylor_run, per slot side by side). */
/* One pass of fr__prog_run, mag constant so each caller gets its own copy. */
static FR__HOT_INLINE void fr__prog_pass(const fr_tape_t *t, const fr__tp_t *prog, unsigned int np, const double o[3],
                                         const double d[3], double *P, double *M, int mag)
{
    unsigned int j;
    int k;
    for (j = 0; j < np; j++) {
        const fr__tp_t *pi = &prog[j];
        const double *A = P + pi->oa, *B = P + pi->ob, *MA = M + pi->oa, *MB = M + pi->ob;
        double *c = P + pi->oc, *mc = M + pi->oc;
        int da = pi->da, db = pi->db;
        switch (pi->kernel) {
        case FR__K_CONST: {
            double v = t->code[pi->slot].k;
            c[0] = v;
            if (mag) mc[0] = fabs(v);
            break;
        }
        case FR__K_VAR: {
            int ax = (int)t->code[pi->slot].op - (int)FR_OP_VAR_X;
            c[0] = o[ax]; c[1] = d[ax];
            if (mag) { mc[0] = fabs(o[ax]); mc[1] = fabs(d[ax]); }
            break;
        }
        case FR__K_NEG:
            for (k = 0; k <= da; k++) c[k] = -A[k];
            if (mag) for (k = 0; k <= da; k++) mc[k] = MA[k];
            break;
        case FR__K_MULK:
            for (k = 0; k <= da; k++) c[k] = A[k] * B[0];
            fr__tpoly_top_underflow(c, da, A[da] != 0 && B[0] != 0);
            if (mag) for (k = 0; k <= da; k++) mc[k] = MA[k] * MB[0];
            break;
        case FR__K_KMUL:
            for (k = 0; k <= db; k++) c[k] = A[0] * B[k];
            fr__tpoly_top_underflow(c, db, A[0] != 0 && B[db] != 0);
            if (mag) for (k = 0; k <= db; k++) mc[k] = MA[0] * MB[k];
            break;
        case FR__K_SQR1:
            c[0] = A[0] * A[0]; c[1] = 2.0 * (A[0] * A[1]); c[2] = A[1] * A[1];
            fr__tpoly_top_underflow(c, 2, A[1] != 0);
            if (mag) { mc[0] = MA[0] * MA[0]; mc[1] = 2.0 * (MA[0] * MA[1]); mc[2] = MA[1] * MA[1]; }
            break;
        case FR__K_SQR2:
            fr__sqr2(A[0], A[1], A[2], c);
            fr__tpoly_top_underflow(c, 4, A[2] != 0);
            if (mag) fr__sqr2(MA[0], MA[1], MA[2], mc);
            break;
        case FR__K_POW4:
            fr__sqr2(A[0] * A[0], 2.0 * (A[0] * A[1]), A[1] * A[1], c);
            fr__tpoly_top_underflow(c, 4, A[1] != 0);
            if (mag) fr__sqr2(MA[0] * MA[0], 2.0 * (MA[0] * MA[1]), MA[1] * MA[1], mc);
            break;
        case FR__K_ADD: case FR__K_SUB: {
            double sg = pi->kernel == FR__K_ADD ? 1.0 : -1.0;
            int lo = da < db ? da : db;
            for (k = 0; k <= lo; k++) c[k] = A[k] + sg * B[k];
            for (; k <= da; k++) c[k] = A[k];
            for (; k <= db; k++) c[k] = sg * B[k];
            if (mag) {
                for (k = 0; k <= lo; k++) mc[k] = MA[k] + MB[k];
                for (; k <= da; k++) mc[k] = MA[k];
                for (; k <= db; k++) mc[k] = MB[k];
            }
            break;
        }
        default: {
            const fr_instr_t *in = &t->code[pi->slot];
            fr__tpoly_step(in, A, da, B, db, o, d, c, NULL, NULL, NULL);
            if (mag) fr__tpoly_step(in, MA, da, MB, db, o, d, mc, c, A, B);
            break;
        }
        }
    }
}

static void fr__prog_run(const fr_tape_t *t, const fr__tp_t *prog, unsigned int np, const double o[3], const double d[3],
                         double *P, double *M)
{
    if (M) fr__prog_pass(t, prog, np, o, d, P, M, 1);
    else fr__prog_pass(t, prog, np, o, d, P, P, 0);
}


/* ---------------------------------------------------------------- shared helpers */

typedef struct fr__ray_t {
    const fr_tape_t *tape;
    double o[3], d[3], t0, t1, tol;
    double footprint; /* INTERVAL: desc->footprint */
    int any_hit;      /* desc->any_hit */
    /* INTERVAL on a polynomial tape: g(ts + s) = sum pc[k] s^k, each
       coefficient within rho pm[k] (fr__poly_range); pc NULL otherwise.
       dc, dm, drho: the same for g' (interval Newton). */
    const double *pc, *pm;
    int pdeg, mdeg;
    double ts, rho;
    double dc[FR_POLY_MAX_DEGREE + 1], dm[FR_POLY_MAX_DEGREE + 1], drho;
    int newton;       /* desc->interval_newton, and pc set */
    int mono;         /* pc set and g' available: monotone segments hand over (fr__trace_interval) */
    double gam, dgam; /* gamma_{2n+2} for g's and g''s degrees n (fr__poly_range_of) */
    const fr_prepared_t *prep; /* desc->prepared, if made for this tape */
    double inv[3];    /* 1 / d[k] (0 where d[k] = 0), when have_inv: from fr__ray_inv */
    double tpad;      /* and max_k 8u |o[k]| |inv[k]|: o's rounding in t (fr__slab_meets) */
    int have_inv;
    void *eval;
    unsigned long long evals, iters;
    unsigned int max_iters;
    /* a method stopped by max_iters: [undecided_lo, undecided_hi] is what
       it had not decided (fr__trace returns FR_ERR_ITERATIONS) */
    int capped;
    double undecided_lo, undecided_hi;
} fr__ray_t;

/* g(t). With the ray polynomial at hand (R->pc: INTERVAL on a polynomial
   tape) by Horner's rule on its coefficients about ts, a few flops instead
   of a pass over the tape (the end-point sign tests and the regula falsi of
   footprint leaves were a sixth of the tangle cube's time). Both are plain
   floating-point values of the same g; a sign change they show is what
   ANALYTIC accepts too, and the never-miss guarantee rests on the
   enclosures, not on these values. */
static double fr__g(fr__ray_t *R, double t)
{
    double p[3];
    if (R->pc) {
        double s = t - R->ts, r = R->pc[R->pdeg];
        int k = R->pdeg;
        while (k-- > 0) r = r * s + R->pc[k];
        R->evals++;
        return r;
    }
    p[0] = R->o[0] + t * R->d[0];
    p[1] = R->o[1] + t * R->d[1];
    p[2] = R->o[2] + t * R->d[2];
    R->evals++;
    return fr_eval(R->tape, p, R->eval);
}

/* g'(t) = grad f . d by AD; 0 if unavailable. */
static double fr__dg(fr__ray_t *R, double t, double *g)
{
    double p[3], gr[3];
    p[0] = R->o[0] + t * R->d[0];
    p[1] = R->o[1] + t * R->d[1];
    p[2] = R->o[2] + t * R->d[2];
    R->evals++;
    if (fr_eval_grad(R->tape, p, R->eval, g, gr) != FR_OK) { *g = fr_eval(R->tape, p, R->eval); return 0.0; }
    return gr[0] * R->d[0] + gr[1] * R->d[1] + gr[2] * R->d[2];
}

static int fr__opposite(double a, double b) { return (a < 0 && b > 0) || (a > 0 && b < 0); }

/* ---------------------------------------------------------------- refinement (§3.1.3, §4.1.1) */

/* Brent's method (Brent 1973, "zeroin"): inverse quadratic interpolation or
   secant steps while they shrink the bracket fast enough, bisection
   otherwise. b is the best estimate, [b, c] brackets the root. */
static double fr__brent(fr__ray_t *R, double a, double b, double ga, double gb, double *t_err)
{
    double c = b, gc = gb, dstep = b - a, estep = dstep;
    unsigned int it;
    for (it = 0; it < R->max_iters; it++) {
        double tol1, xm;
        R->iters++;
        if ((gb > 0 && gc > 0) || (gb < 0 && gc < 0)) { c = a; gc = ga; dstep = estep = b - a; }
        if (fabs(gc) < fabs(gb)) { a = b; b = c; c = a; ga = gb; gb = gc; gc = ga; }
        tol1 = 2.0 * FR__U * fabs(b) + 0.5 * R->tol;
        xm = 0.5 * (c - b);
        if (fabs(xm) <= tol1 || gb == 0) break;
        if (fabs(estep) >= tol1 && fabs(ga) > fabs(gb)) {
            double p, q, r, sr = gb / ga, lim1, lim2;
            if (a == c) { p = 2.0 * xm * sr; q = 1.0 - sr; }
            else {
                q = ga / gc; r = gb / gc;
                p = sr * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0));
                q = (q - 1.0) * (r - 1.0) * (sr - 1.0);
            }
            if (p > 0) q = -q;
            p = fabs(p);
            lim1 = 3.0 * xm * q - fabs(tol1 * q);
            lim2 = fabs(estep * q);
            if (2.0 * p < (lim1 < lim2 ? lim1 : lim2)) { estep = dstep; dstep = p / q; }
            else { dstep = xm; estep = dstep; }
        } else { dstep = xm; estep = dstep; }
        a = b; ga = gb;
        b += fabs(dstep) > tol1 ? dstep : (xm > 0 ? tol1 : -tol1);
        gb = fr__g(R, b);
        if (!(gb == gb)) { b = 0.5 * (a + c); gb = fr__g(R, b); } /* NaN inside: bisect */
    }
    *t_err = fabs(c - b);
    return b;
}

/* Refine a sign change of g on [a, b] (ga, gb of opposite signs, a < b) to a
   bracket no wider than 2 tol. Every method keeps a valid bracket and falls
   back to bisection when its step leaves it, so all converge. */
static double fr__refine(fr__ray_t *R, fr_refine_t m, double a, double b, double ga, double gb, double *t_err)
{
    double x = 0.5 * (a + b), gx;
    int side = 0; /* Illinois: which end moved last */
    unsigned int it;
    if (m == FR_REFINE_BRENT) return fr__brent(R, a, b, ga, gb, t_err);
    for (it = 0; it < R->max_iters && b - a > 2.0 * R->tol; it++) {
        R->iters++;
        if (m == FR_REFINE_NEWTON) {
            double dg = fr__dg(R, x, &gx), xn;
            if (gx == 0) { *t_err = 0; return x; }
            if (fr__opposite(ga, gx)) { b = x; gb = gx; } else { a = x; ga = gx; }
            xn = dg != 0 ? x - gx / dg : 0.5 * (a + b);
            if (!(xn > a && xn < b)) xn = 0.5 * (a + b);
            if (fabs(xn - x) <= 0.5 * R->tol) { *t_err = fabs(xn - x); return xn; }
            x = xn;
            continue;
        }
        if (m == FR_REFINE_ILLINOIS) {
            x = (a * gb - b * ga) / (gb - ga);
            if (!(x > a && x < b)) x = 0.5 * (a + b);
        } else {
            x = 0.5 * (a + b);
        }
        gx = fr__g(R, x);
        if (gx == 0) { *t_err = 0; return x; }
        if (!(gx == gx)) { x = 0.5 * (a + b); gx = fr__g(R, x); if (!(gx == gx)) break; }
        if (fr__opposite(ga, gx)) {
            b = x; gb = gx;
            if (side == -1) ga *= 0.5; /* Illinois: halve the stale end's value */
            side = -1;
        } else {
            a = x; ga = gx;
            if (side == 1) gb *= 0.5;
            side = 1;
        }
    }
    *t_err = 0.5 * (b - a);
    return 0.5 * (a + b);
}

/* A method ran out of iterations with [lo, hi] undecided. */
static void fr__capped(fr__ray_t *R, double lo, double hi)
{
    R->capped = 1;
    R->undecided_lo = lo;
    R->undecided_hi = hi;
}

/* ---------------------------------------------------------------- stepping */

static int fr__trace_step(fr__ray_t *R, double step, fr_refine_t refine, double L, double *t_hit, double *t_err)
{
    double ta = R->t0, ga = fr__g(R, ta), dn = sqrt(R->d[0] * R->d[0] + R->d[1] * R->d[1] + R->d[2] * R->d[2]);
    unsigned int it;
    if (ga == 0) { *t_hit = ta; *t_err = 0; return 1; }
    for (it = 0; it < R->max_iters && ta < R->t1; it++) {
        double h = step, tb, gb;
        R->iters++;
        if (h <= 0) { /* Lipschitz step: no root within |g| / (L |d|) */
            h = ga == ga ? fabs(ga) / (L * dn) : R->tol;
            if (h < R->tol) h = R->tol;
        }
        tb = ta + h > R->t1 ? R->t1 : ta + h;
        gb = fr__g(R, tb);
        if (gb == 0) { *t_hit = tb; *t_err = 0; return 1; }
        if (fr__opposite(ga, gb)) { /* NaN never opposes: no root is claimed in a NaN region */
            if (R->any_hit) { *t_hit = 0.5 * (ta + tb); *t_err = 0.5 * (tb - ta); return 1; }
            *t_hit = fr__refine(R, refine, ta, tb, ga, gb, t_err);
            return 1;
        }
        ta = tb; ga = gb;
    }
    if (ta < R->t1) fr__capped(R, ta, R->t1);
    return 0;
}

/* ---------------------------------------------------------------- sphere tracing */

/* SPHERE's stop within tol of the surface is a distance, and on an oblique
   ray the root can lie up to tol / sin(angle) farther along it (9.5 tol
   at 5.7 degrees). From the stop we look ahead for a sign change: steps
   of 2 tol doubling each time (or the safe step r when longer), at most
   this many, while |g| keeps falling (a ray that came within tol and
   turns away, grazing, crosses nowhere: the stop stands, t_err = tol as
   a distance). A bracket found is refined as STEP refines one, so t_err
   bounds a root. 6 probes reach 126 tol: any ray steeper than 0.45
   degrees to the surface; the first probe brackets any steeper than 30. */
#define FR__SPHERE_BRACKET_PROBES 6
static int fr__sphere_bracket(fr__ray_t *R, double L, double dn, double ta, double ga, double *t_hit, double *t_err)
{
    double h = 2.0 * R->tol;
    int k;
    if (ga == 0) { *t_hit = ta; *t_err = 0; return 1; }
    for (k = 0; k < FR__SPHERE_BRACKET_PROBES && ta < R->t1; k++) {
        double r = fabs(ga) / (L * dn), tb = ta + (r > h ? r : h), gb;
        if (tb > R->t1) tb = R->t1;
        gb = fr__g(R, tb);
        R->iters++;
        if (gb == 0) { *t_hit = tb; *t_err = 0; return 1; }
        if (fr__opposite(ga, gb)) { *t_hit = fr__refine(R, FR_REFINE_ILLINOIS, ta, tb, ga, gb, t_err); return 1; }
        if (!(fabs(gb) < fabs(ga))) break; /* NaN, or moving away */
        ta = tb, ga = gb, h *= 2;
    }
    return 0;
}

/* Hart 1996 with Keinert et al. 2014's over-relaxation: steps of omega r,
   r = |g| / (L |d|) the unbounding radius; if the new sphere does not
   overlap the previous one, the relaxed step may have skipped the surface,
   so we return to the safe step and continue with omega = 1. */
static int fr__trace_sphere(fr__ray_t *R, double L, double omega, double *t_hit, double *t_err)
{
    double dn = sqrt(R->d[0] * R->d[0] + R->d[1] * R->d[1] + R->d[2] * R->d[2]);
    double t = R->t0, t_prev = R->t0, r_prev = 0.0, g_prev = 0.0;
    int have_prev = 0;
    unsigned int it;
    for (it = 0; it < R->max_iters && t <= R->t1; it++) {
        double g = fr__g(R, t), r;
        R->iters++;
        if (!(g == g)) return 0; /* NaN: the bound says nothing, no hit is claimed */
        r = fabs(g) / (L * dn);
        /* a relaxed step that crossed the surface: its sphere may still
           overlap the previous one (on a plane hit head-on the overshoot
           is exactly the new radius), so the sign decides; an unrelaxed
           step crosses only by rounding or a loose L: the root is there */
        if (have_prev && fr__opposite(g_prev, g)) {
            if (omega > 1.0) {
                t = t_prev + r_prev;
                omega = 1.0;
                continue;
            }
            *t_hit = fr__refine(R, FR_REFINE_ILLINOIS, t_prev, t, g_prev, g, t_err);
            return 1;
        }
        if (omega > 1.0 && have_prev && r + r_prev < t - t_prev) {
            t = t_prev + r_prev;
            omega = 1.0;
            continue;
        }
        if (r <= R->tol) {
            if (!fr__sphere_bracket(R, L, dn, t, g, t_hit, t_err)) *t_hit = t, *t_err = R->tol;
            return 1;
        }
        t_prev = t; r_prev = r; g_prev = g; have_prev = 1;
        t += omega * r;
        /* a relaxed step past t1 is unchecked: the safe step decides */
        if (t > R->t1 && omega > 1.0) {
            t = t_prev + r_prev;
            omega = 1.0;
        }
    }
    if (t <= R->t1) fr__capped(R, have_prev ? t_prev : t, R->t1); /* the last step is not yet checked */
    return 0;
}

/* ---------------------------------------------------------------- interval bisection */

#ifndef FR_NO_INTERVAL
typedef struct fr__seg_t {
    double a, b;
    int depth;
} fr__seg_t;

static void fr__ray_box(const fr__ray_t *R, double a, double b, iv_t box[3])
{
    int k;
    for (k = 0; k < 3; k++) box[k] = iv_add(iv_point(R->o[k]), iv_mul(iv_make(a, b), iv_point(R->d[k])));
}

/* The centred form hands over to affine evaluation when its rounding
   bound is more than this share of its radius (fr__g_range). */
#define FR__POLY_PAD_SHARE 0.25
/* gamma_m = m u / (1 - m u), Higham's bound for m roundings in a row. */
static double fr__gamma(double m) { return m * FR__U / (1.0 - m * FR__U); }

/* Taylor shift q(s) -> q(s + mu), degree n, by repeated synthetic division
   (the order fr__poly_range_of's rounding bound counts). */
static FR__HOT_INLINE void fr__taylor_shift(double *q, int n, double mu)
{
    int i, k;
    for (i = 0; i < n; i++)
        for (k = n - 1; k >= i; k--) q[k] += mu * q[k + 1];
}

/* fr__poly_range_of's three sums for degree 3 and 4 (a quartic's g' and
   the quartic: tangle cube, tori), written out (the loops' bookkeeping was
   half the cost): q = pc shifted by mu (the order of fr__taylor_shift),
   rad = sum_{j >= 1} |q_j| r^j, pad = pm(x) by Horner. */
static void fr__shift_sum3(const double *pc, const double *pm, double mu, double r, double x, double *q, double *rad,
                           double *pad)
{
    double q0 = pc[0], q1 = pc[1], q2 = pc[2], q3 = pc[3], r2 = r * r;
    q2 += mu * q3; q1 += mu * q2; q0 += mu * q1;
    q2 += mu * q3; q1 += mu * q2;
    q2 += mu * q3;
    q[0] = q0;
    *rad = (fabs(q1) * r + fabs(q2) * r2) + fabs(q3) * (r2 * r);
    *pad = ((pm[3] * x + pm[2]) * x + pm[1]) * x + pm[0];
}
static void fr__shift_sum4(const double *pc, const double *pm, double mu, double r, double x, double *q, double *rad,
                           double *pad)
{
    double q0 = pc[0], q1 = pc[1], q2 = pc[2], q3 = pc[3], q4 = pc[4], r2 = r * r;
    q3 += mu * q4; q2 += mu * q3; q1 += mu * q2; q0 += mu * q1;
    q3 += mu * q4; q2 += mu * q3; q1 += mu * q2;
    q3 += mu * q4; q2 += mu * q3;
    q3 += mu * q4;
    q[0] = q0;
    *rad = (fabs(q1) * r + fabs(q2) * r2) + (fabs(q3) * r + fabs(q4) * r2) * r2;
    *pad = (((pm[4] * x + pm[3]) * x + pm[2]) * x + pm[1]) * x + pm[0];
}

/* The enclosure of g over [a, b] from the ray polynomial (a centred form):
   shift the coefficients to the segment's midpoint mu, then g lies in
   q0 +- (sum |q_j| r^j), r the half-width; a Taylor model that converges
   quadratically as segments shrink, for the price of two O(n^2) shifts
   instead of a pass over the tape. Rigour: each coefficient is within
   rho pm[k] of the exact one, pm the magnitude run (fr__taylor_run).
   fr_trace sets rho = 2 gamma_{160 n}, n the tape length: per slot a
   coefficient is a sum of at most 17 products (gamma_18), POWI's binary
   powering chains at most 8 of those (144), 16 more cover the rounding of
   the expansion point o + ts d, and a path through the tape has at most n
   slots; the factor 2 covers the rounding of pm itself. The bound is
   loose by orders of magnitude, which only matters near a root (see
   fr__g_range);
   and the shift and the sums add gamma_{2n+2} of the shifted magnitudes,
   so the radius gets (rho + 2 gamma_{2n+2}) Q_j r^j with Q the magnitudes
   shifted by |mu|, and s = t - ts is widened by its own rounding. */
/* *pad_share: 1 when the rounding pad is FR__POLY_PAD_SHARE of the radius
   or more (fr__g_range then asks the affine forms too), else 0. */
static iv_t fr__poly_range_of(const fr__ray_t *R, const double *pc, const double *pm, int pdeg, int mdeg, double rho,
                              double gam, double a, double b, double *pad_share)
{
    double q[FR__TAYLOR_N], sa, sb, mu, amu, r, rad = 0, pad = 0, rj = 1, g, x;
    int n = mdeg, k;
    sa = a - R->ts; sb = b - R->ts;
    sa -= 2.0 * FR__U * (fabs(a) + fabs(R->ts));
    sb += 2.0 * FR__U * (fabs(b) + fabs(R->ts));
    mu = 0.5 * sa + 0.5 * sb;
    r = (sb - mu > mu - sa ? sb - mu : mu - sa) * (1.0 + 4.0 * FR__U);
    amu = fabs(mu);
    if (n < 0) { *pad_share = 0; return iv_point(0.0); } /* the zero polynomial */
    g = rho + 2.0 * gam; /* gam = gamma_{2n+2}, once per ray */
    /* sum_j Q_j r^j, Q = pm shifted by |mu|, is pm(|mu| + r) exactly (a
       shift then an evaluation at r is an evaluation at |mu| + r): one
       Horner pass of nonnegative terms instead of a second O(n^2) shift
       (a third of this function's time). Its rounding, relative and below
       gamma_{2n} with |mu| + r rounded up, is covered by one more factor
       1 + gamma_{2n+2}. */
    x = (amu + r) * (1.0 + 2.0 * FR__U); /* |mu| + r rounded up */
    if (pdeg == n && n == 4) fr__shift_sum4(pc, pm, mu, r, x, q, &rad, &pad);
    else if (pdeg == n && n == 3) fr__shift_sum3(pc, pm, mu, r, x, q, &rad, &pad);
    else {
        for (k = 0; k <= n; k++) q[k] = k <= pdeg ? pc[k] : 0.0;
        fr__taylor_shift(q, n, mu);
        for (k = 1; k <= n; k++) {
            rj *= r;
            rad += fabs(q[k]) * rj;
        }
        pad = pm[n];
        for (k = n; k-- > 0;) pad = pad * x + pm[k];
    }
    pad *= 1.0 + gam;
    /* the rounding pad's share of the radius, compared without a division */
    *pad_share = g * pad >= FR__POLY_PAD_SHARE * (rad + g * pad) ? 1.0 : 0.0;
    rad = (rad + g * pad) * (1.0 + gam) + 2.0 * FR__U * fabs(q[0]) + DBL_MIN;
    if (!(rad < HUGE_VAL) || q[0] != q[0]) return iv_entire();
    return iv_make(q[0] - rad, q[0] + rad);
}
static iv_t fr__poly_range(const fr__ray_t *R, double a, double b, double *pad_share)
{
    return fr__poly_range_of(R, R->pc, R->pm, R->pdeg, R->mdeg, R->rho, R->gam, a, b, pad_share);
}

/* Interval Newton (Moore 1966; Hansen 1992) on [a, b] for a polynomial
   tape: with G' an enclosure of g' over the segment that excludes 0, every
   root lies in N = m - g(m) / G' (mean value theorem), m the midpoint and
   g(m) enclosed by the centred form at the point m; dg is G' (the
   caller's, fr__trace_interval). Narrows [*a, *b] to
   its intersection with N; returns 0 when that is empty (no root), 1
   otherwise. A G' containing 0 leaves the segment unchanged. */
static int fr__newton_narrow(fr__ray_t *R, iv_t dg, double *a, double *b)
{
    double share, m = 0.5 * *a + 0.5 * *b;
    iv_t gm, nw;
    if (iv_contains(dg, 0.0) || iv_is_empty(dg)) return 1;
    gm = fr__poly_range(R, m, m, &share);
    nw = iv_sub(iv_point(m), iv_div(gm, dg));
    if (iv_is_empty(nw) || nw.hi < *a || nw.lo > *b) return 0;
    if (nw.lo > *a) *a = nw.lo;
    if (nw.hi < *b) *b = nw.hi;
    return 1;
}

/* An enclosure of g over [a, b]: the ray polynomial's centred form for
   polynomial tapes, else affine forms in t (reduced affine arithmetic,
   Knoll et al. 2009) or plain intervals of the ray's box. Near a root the
   centred form's rounding bound (the coefficients carry the cancellation
   of the expansion) can outweigh its width; then the affine enclosure of
   the tape is taken too and both intersected, so tolerances down to
   1e-13 stay reachable. */
static fr_result_t fr__g_range(fr__ray_t *R, const fr_tape_t *tp, double a, double b, int plain, iv_t *out)
{
    iv_t pr = iv_entire();
    R->evals++;
    if (R->pc) {
        double share;
        pr = fr__poly_range(R, a, b, &share);
        if (!iv_contains(pr, 0.0) || share == 0) { *out = pr; return FR_OK; }
    }
#ifndef IV_NO_AFFINE
    if (!plain) {
        iv_affine_t T = iv_affine_ray_param(a, b), P[3], res;
        fr_result_t e;
        int k;
        for (k = 0; k < 3; k++) P[k] = iv_affine_add_d(iv_affine_mul_d(T, R->d[k]), R->o[k]);
        e = fr__eval_affine(tp, P, R->eval, &res);
        if (e == FR_OK) {
            iv_t x = iv_intersect(iv_from_affine(res), pr); /* both enclose g */
            *out = iv_is_empty(x) ? iv_from_affine(res) : x;
        }
        return e;
    }
#endif
    {
        iv_t box[3];
        (void)plain;
        fr__ray_box(R, a, b, box);
        return fr__eval_interval(tp, box, R->eval, out);
    }
}

/* Leftmost-first bisection on t with an explicit stack (paper §4.1.3: no
   recursion). A segment whose enclosure excludes 0 (or is empty: f is NaN
   throughout) holds no root and is dropped; the first segment no wider
   than tol whose enclosure contains 0 is the hit. Pruned tapes (Keeter
   2020) are made every FR__PRUNE_EVERY levels and reused by the segment's
   descendants, which depth-first order keeps alive. */
/* What a test on a segment of fr__trace_interval decides. */
#define FR__SEG_GO_ON 0  /* nothing: the next tests decide */
#define FR__SEG_DROP 1   /* no root in it */
#define FR__SEG_ANSWER 2 /* *found, *t_hit, *t_err hold the answer */

/* The pruned tape of segment s's level (every FR__PRUNE_EVERY levels, up to
   FR__PRUNE_LEVELS), from the level above over s's box; the level above's
   when pruning fails. */
static void fr__prune_segment(fr__ray_t *R, const fr__seg_t *s, fr_tape_t *tapes, fr_instr_t *bufs)
{
    int lvl = s->depth / FR__PRUNE_EVERY;
    iv_t box[3];
    if (s->depth % FR__PRUNE_EVERY != 0 || s->depth == 0 || lvl >= FR__PRUNE_LEVELS) return;
    fr__ray_box(R, s->a, s->b, box);
    R->evals++;
    if (fr__prune_ex(&tapes[lvl - 1], box, FR_PRUNE_SIGN, R->eval, bufs + (size_t)lvl * R->tape->n_code, R->tape->n_code,
                    &tapes[lvl], NULL) != FR_OK)
        tapes[lvl] = tapes[lvl - 1];
}

/* A polynomial tape: where the centred form of g' (*dg) excludes 0, g is
   strictly monotone on the segment, so it holds at most one root, and the
   first one, as every segment left of it is excluded (depth-first, left
   first). A sign change at the ends then goes straight to regula falsi (to
   tol, bracketed); no sign change, with the ends' enclosures of one strict
   sign, proves there is none. Either saves the bisection levels down to
   tl. *ga, *gb get g at the ends when it was evaluated (*have_ends). */
static int fr__monotone_segment(fr__ray_t *R, const fr__seg_t *s, iv_t *dg, double *ga, double *gb, int *have_ends, int *found,
                                double *t_hit, double *t_err)
{
    double share;
    iv_t ea, eb;
    *dg = fr__poly_range_of(R, R->dc, R->dm, R->pdeg - 1, R->mdeg - 1, R->drho, R->dgam, s->a, s->b, &share);
    R->evals++;
    if (iv_is_empty(*dg) || iv_contains(*dg, 0.0)) return FR__SEG_GO_ON;
    *ga = fr__g(R, s->a);
    *gb = fr__g(R, s->b);
    *have_ends = 1;
    if (*ga == 0 || *gb == 0 || fr__opposite(*ga, *gb)) {
        *found = 1;
        *t_err = 0.5 * R->tol;
        if (*ga == 0) *t_hit = s->a;
        else if (*gb == 0) *t_hit = s->b;
        else if (R->any_hit) { *t_hit = 0.5 * (s->a + s->b); *t_err = 0.5 * (s->b - s->a); }
        else *t_hit = fr__refine(R, FR_REFINE_ILLINOIS, s->a, s->b, *ga, *gb, t_err);
        return FR__SEG_ANSWER;
    }
    ea = fr__poly_range(R, s->a, s->a, &share);
    eb = fr__poly_range(R, s->b, s->b, &share);
    R->evals += 2;
    return (ea.lo > 0 && eb.lo > 0) || (ea.hi < 0 && eb.hi < 0) ? FR__SEG_DROP : FR__SEG_GO_ON;
}

/* A segment no wider than tl (or any segment, for any-hit): a sign change
   at the ends proves a root inside. Without one the enclosure may just be
   loose (a near miss), so such a segment is bisected FR__TOUCH_SCALE
   further: a near miss is then excluded, a feature thinner than tl shows
   its sign change, and what survives is reported as a touch. Every segment
   left of this one is excluded (depth-first, left first), so a sign change
   here brackets the first root, or with several roots inside the segment
   one of them. Returns 1 with the answer, 0 to bisect on. */
static int fr__leaf_segment(fr__ray_t *R, const fr__seg_t *s, double tl, int have_ends, double ga, double gb, int *found,
                            double *t_hit, double *t_err)
{
    int change;
    if (!have_ends) { ga = fr__g(R, s->a); gb = fr__g(R, s->b); }
    change = ga == 0 || gb == 0 || fr__opposite(ga, gb);
    if (!change && !(s->b - s->a <= tl && (s->b - s->a <= tl * FR__TOUCH_SCALE || s->depth >= FR__TRACE_MAX_DEPTH))) return 0;
    *found = 1;
    *t_hit = ga == 0 ? s->a : gb == 0 && !fr__opposite(ga, gb) ? s->b : 0.5 * (s->a + s->b);
    *t_err = 0.5 * (s->b - s->a);
    if (change && !R->any_hit && ga != 0 && gb != 0 && s->b - s->a > 2.0 * R->tol) /* footprint leaf */
        *t_hit = fr__refine(R, FR_REFINE_ILLINOIS, s->a, s->b, ga, gb, t_err);
    return 1;
}

static fr_result_t fr__trace_interval(fr__ray_t *R, int plain, int prune, fr_instr_t *bufs, int *found,
                                      double *t_hit, double *t_err)
{
    fr__seg_t stack[FR__TRACE_MAX_DEPTH + 2];
    fr_tape_t tapes[FR__PRUNE_LEVELS];
    int sp = 0;
    unsigned int it;
    tapes[0] = *R->tape;
    stack[sp].a = R->t0; stack[sp].b = R->t1; stack[sp].depth = 0; sp++;
    *found = 0;
    for (it = 0; sp > 0 && it < R->max_iters; it++) {
        fr__seg_t s = stack[--sp];
        int lvl = s.depth / FR__PRUNE_EVERY;
        const fr_tape_t *tp;
        iv_t range, dg;
        fr_result_t e;
        double tl, ga = 0.0, gb = 0.0, m;
        int have_ends = 0; /* ga, gb hold g at the segment's ends */
        R->iters++;
        if (prune) fr__prune_segment(R, &s, tapes, bufs);
        tp = prune ? &tapes[lvl < FR__PRUNE_LEVELS ? lvl : FR__PRUNE_LEVELS - 1] : R->tape;
        e = fr__g_range(R, tp, s.a, s.b, plain, &range);
        if (e != FR_OK) return e;
        if (iv_is_empty(range) || !iv_contains(range, 0.0)) continue;
        /* tl: where bisection ends; tol, or the pixel footprint at s.b */
        tl = R->tol + R->footprint * fabs(s.b);
        dg = iv_entire();
        if (R->mono && s.b - s.a > tl) {
            int d = fr__monotone_segment(R, &s, &dg, &ga, &gb, &have_ends, found, t_hit, t_err);
            if (d == FR__SEG_ANSWER) return FR_OK;
            if (d == FR__SEG_DROP) continue;
        }
        if (R->newton && s.b - s.a > tl) {
            /* interval Newton: drop the segment or narrow it; a segment
               that shrank by half or more is tried again as it is */
            double na = s.a, nb = s.b;
            if (!fr__newton_narrow(R, dg, &na, &nb)) continue;
            if (nb - na <= 0.5 * (s.b - s.a) && s.depth < FR__TRACE_MAX_DEPTH) {
                stack[sp].a = na; stack[sp].b = nb; stack[sp].depth = s.depth + 1; sp++;
                continue;
            }
        }
        if ((s.b - s.a <= tl || R->any_hit) && fr__leaf_segment(R, &s, tl, have_ends, ga, gb, found, t_hit, t_err)) return FR_OK;
        if (s.depth >= FR__TRACE_MAX_DEPTH) { *found = 1; *t_hit = 0.5 * (s.a + s.b); *t_err = 0.5 * (s.b - s.a); return FR_OK; }
        m = 0.5 * (s.a + s.b);
        if (!(m > s.a && m < s.b)) { /* adjacent doubles: as narrow as t can be */
            *found = 1; *t_hit = s.a; *t_err = s.b - s.a;
            return FR_OK;
        }
        stack[sp].a = m; stack[sp].b = s.b; stack[sp].depth = s.depth + 1; sp++;
        stack[sp].a = s.a; stack[sp].b = m; stack[sp].depth = s.depth + 1; sp++;
    }
    /* segments left: everything before the top one is proven root-free,
       the stack holds the rest in order (the bottom one ends last) */
    if (sp > 0) fr__capped(R, stack[sp - 1].a, stack[0].b);
    return FR_OK;
}
#endif

#ifndef FR_NO_INTERVAL
/* Octree depth of fr_bound_box: default and cap (the explicit stack holds
   7 siblings per level). */
#define FR__BOUND_DEPTH 6
#define FR__BOUND_MAX_DEPTH 10
/* An enclosure of a function over a cell (fr__box_search). */
typedef fr_result_t (*fr__cell_fn)(const void *ctx, const iv_t box[3], iv_t *r);

/* The bounding box of the octree cells of [lo, hi] at depth `depth` whose
   enclosure may hold the solid (keep_zero 0: r.hi >= 0) or the surface
   (keep_zero 1: r.lo <= 0 <= r.hi); cells inside the box found so far are
   skipped. Nothing kept gives out_lo > out_hi. */
static fr_result_t fr__box_search(fr__cell_fn fn, const void *ctx, int keep_zero, const double lo[3], const double hi[3],
                                  int depth, double out_lo[3], double out_hi[3])
{
    struct { double lo[3], hi[3]; int depth; } stack[7 * FR__BOUND_MAX_DEPTH + 1];
    int sp, k;
    for (k = 0; k < 3; k++) {
        stack[0].lo[k] = lo[k]; stack[0].hi[k] = hi[k];
        out_lo[k] = HUGE_VAL; out_hi[k] = -HUGE_VAL;
    }
    stack[0].depth = 0;
    sp = 1;
    while (sp > 0) {
        iv_t box[3], r;
        int inside = 1, c;
        sp--;
        for (k = 0; k < 3; k++) {
            box[k] = iv_make(stack[sp].lo[k], stack[sp].hi[k]);
            inside &= stack[sp].lo[k] >= out_lo[k] && stack[sp].hi[k] <= out_hi[k];
        }
        if (inside) continue; /* cannot grow the box */
        if (fn(ctx, box, &r) != FR_OK) return FR_ERR_NO_INTERVAL;
        if (iv_is_empty(r) || r.hi < 0 || (keep_zero && r.lo > 0)) continue; /* nothing here (or f is NaN throughout) */
        if (stack[sp].depth >= depth) {
            for (k = 0; k < 3; k++) {
                if (stack[sp].lo[k] < out_lo[k]) out_lo[k] = stack[sp].lo[k];
                if (stack[sp].hi[k] > out_hi[k]) out_hi[k] = stack[sp].hi[k];
            }
            continue;
        }
        { /* replace the cell by its 8 children */
            double l[3], m[3], h[3];
            int d = stack[sp].depth + 1;
            for (k = 0; k < 3; k++) {
                l[k] = stack[sp].lo[k]; h[k] = stack[sp].hi[k]; m[k] = 0.5 * l[k] + 0.5 * h[k];
            }
            for (c = 0; c < 8; c++, sp++)
                for (k = 0; k < 3; k++) {
                    stack[sp].lo[k] = (c >> k) & 1 ? m[k] : l[k];
                    stack[sp].hi[k] = (c >> k) & 1 ? h[k] : m[k];
                    stack[sp].depth = d;
                }
        }
    }
    return FR_OK;
}

typedef struct fr__tape_cell_t {
    const fr_tape_t *tape;
    void *scratch;
} fr__tape_cell_t;
static fr_result_t fr__tape_cell(const void *ctx, const iv_t box[3], iv_t *r)
{
    const fr__tape_cell_t *c = (const fr__tape_cell_t *)ctx;
    return fr__eval_interval(c->tape, box, c->scratch, r);
}

static FR__NOINLINE fr_result_t fr__bound_box(const fr_tape_t *t, const double lo[3], const double hi[3], int depth, void *scratch,
                                double out_lo[3], double out_hi[3])
{
    fr__tape_cell_t c;
    int k;
    if (!t || !lo || !hi || !scratch || !out_lo || !out_hi || t->n_code == 0 || depth < 0) return FR_ERR_INVALID_ARG;
    if (t->flags & FR_TAPE_NO_INTERVAL) return FR_ERR_NO_INTERVAL;
    for (k = 0; k < 3; k++)
        if (!(lo[k] - lo[k] == 0) || !(hi[k] - hi[k] == 0) || !(lo[k] <= hi[k])) return FR_ERR_INVALID_ARG;
    if (depth == 0) depth = FR__BOUND_DEPTH;
    if (depth > FR__BOUND_MAX_DEPTH) depth = FR__BOUND_MAX_DEPTH;
    c.tape = t;
    c.scratch = scratch;
    return fr__box_search(fr__tape_cell, &c, 0, lo, hi, depth, out_lo, out_hi);
}

FR_DEF fr_result_t fr_bound_box(const fr_tape_t *t, const double lo[3], const double hi[3], int depth, void *scratch,
                                double out_lo[3], double out_hi[3])
{
    FR__IN_FP_ENV(fr_result_t, fr__bound_box(t, lo, hi, depth, scratch, out_lo, out_hi));
}
#endif

/* ---------------------------------------------------------------- analytic */

/* Expand every slot of g in powers of (t - ts), ts the segment's point
   nearest the coordinate origin, not about o: with o at 1e6 and the model
   near 0, coefficients about o would carry 1e12-sized terms whose rounding
   moves the roots by 1e-5, while o + t d itself is known to ulp(1e6) =
   1e-10. Returns ts. */
static double fr__analytic_expand(const fr__ray_t *R, const fr__trace_mem_t *mem, int with_mag)
{
    double ts, ob[3];
    int k;
    const fr_prepared_t *P = R->prep && R->prep->kind == FR_PREPARED_POLY ? R->prep : NULL;
    ts = -(R->o[0] * R->d[0] + R->o[1] * R->d[1] + R->o[2] * R->d[2]) /
         (R->d[0] * R->d[0] + R->d[1] * R->d[1] + R->d[2] * R->d[2]);
    if (!(ts >= R->t0)) ts = R->t0;
    if (!(ts <= R->t1)) ts = R->t1;
    if (!(ts - ts == 0)) ts = 0; /* unbounded segment */
    for (k = 0; k < 3; k++) ob[k] = R->o[k] + ts * R->d[k];
    if (P) {
        /* the prepared program: only the shape's slots, fixed degrees, both
           runs in one pass; an overflow on this ray takes the full runs */
        fr__tp_t *prog;
        unsigned int out = R->tape->outputs[0];
        int dg;
        fr__prep_layout(P->n_leaves, P->n_nodes, P->n_prog, NULL, NULL, &prog, P->mem);
        dg = prog[P->n_prog - 1].dc;
        fr__prog_run(R->tape, prog, P->n_prog, ob, R->d, mem->taylor, with_mag ? mem->taylor_mag : NULL);
        mem->deg[out] = fr__checked_degree(mem->taylor + (size_t)out * FR__TAYLOR_N, dg, FR__TRACE_MIN_COEF);
        if (with_mag) mem->deg_mag[out] = fr__checked_degree(mem->taylor_mag + (size_t)out * FR__TAYLOR_N, dg, FR__TRACE_MIN_COEF);
        if (mem->deg[out] >= 0 && (!with_mag || mem->deg_mag[out] >= 0)) return ts;
    }
    fr__taylor_run(R->tape, ob, R->d, mem->taylor, mem->deg, NULL);
    {
        unsigned int out = R->tape->outputs[0];
        mem->deg[out] = fr__checked_degree(mem->taylor + (size_t)out * FR__TAYLOR_N, mem->deg[out], FR__TRACE_MIN_COEF);
        if (with_mag && mem->deg[out] >= 0) {
            fr__taylor_run(R->tape, ob, R->d, mem->taylor_mag, mem->deg_mag, mem->taylor);
            mem->deg_mag[out] = fr__checked_degree(mem->taylor_mag + (size_t)out * FR__TAYLOR_N, mem->deg_mag[out], FR__TRACE_MIN_COEF);
            if (mem->deg_mag[out] < 0) mem->deg[out] = -1;
        }
    }
    return ts;
}

/* Mark the slots the shape needs as a CSG tree: min/max/R-function/negation
   nodes down to polynomial leaves (deg >= 0, from fr__analytic_expand).
   mem->list receives them ascending; returns their count, or -1 when the
   shape is not such a tree (some needed node is neither). */
static int fr__csg_mark(const fr_tape_t *t, const fr__trace_mem_t *mem)
{
    /* one backward pass from the output (operands precede their users),
       listing needed slots descending, then the list reversed: it runs per
       ray, and a third pass over the tape was a third of its cost */
    unsigned int i, out = t->outputs[0];
    int cnt = 0, j;
    for (i = 0; i < out; i++) mem->need[i] = 0;
    mem->need[out] = 1;
    for (i = out + 1; i-- > 0;) {
        const fr_instr_t *in = &t->code[i];
        if (!mem->need[i]) continue;
        mem->list[cnt++] = i;
        if (mem->deg[i] >= 0) { /* a leaf: it must not have overflowed on this ray */
            if (fr__checked_degree(mem->taylor + (size_t)i * FR__TAYLOR_N, mem->deg[i], FR__TRACE_MIN_COEF) < 0) return -1;
            continue;
        }
        switch ((fr_op_t)in->op) {
        case FR_OP_MIN: case FR_OP_MAX: case FR_OP_RUNI: case FR_OP_RINT:
            mem->need[in->a] = 1; mem->need[in->b] = 1; break;
        case FR_OP_NEG: mem->need[in->a] = 1; break;
        default: return -1;
        }
    }
    for (j = 0; j < cnt / 2; j++) {
        unsigned int x = mem->list[j];
        mem->list[j] = mem->list[cnt - 1 - j];
        mem->list[cnt - 1 - j] = x;
    }
    return cnt;
}


/* Analytic CSG classification (paper §3.1.1, "select the root ... placed
   on the surface of the CSG solid"), shared by the prepared and the plain
   path: leaves' signs, crossings, and a walk over the sorted crossings. */

static int fr__sgn(double x) { return x > 0 ? 1 : x < 0 ? -1 : 0; }

/* A leaf's crossing roots, general degree: fr_solve_poly on [s0, s1] (s = t
   - ts), each root a crossing where the leaf's sign differs in the gaps
   either side (Horner at the gaps' midpoints, so a double root is a touch);
   roots at s0 belong to the part before the segment. cand receives ts + s
   of the crossings, *sg the sign just after s0. -1: invalid coefficients. */
static int fr__poly_leaf(const double *c, int deg, double s0, double s1, double ts, int culled, double *cand, int *sg)
{
    double r[FR_POLY_MAX_DEGREE], x, y;
    int nr, j, m = 0, prev, first = 0, k;
    if (culled || deg <= 0) {
        x = 0.5 * s0 + 0.5 * s1;
        for (y = c[deg > 0 ? deg : 0], k = deg; k-- > 0;) y = y * x + c[k];
        *sg = fr__sgn(y);
        return 0;
    }
    nr = fr__solve_poly(c, deg, s0, s1, r);
    if (nr < 0) return -1;
    while (first < nr && r[first] <= s0) first++;
    prev = 0;
    for (j = first - 1; j < nr; j++) {
        double a = j < first ? s0 : r[j], b = j + 1 < nr ? r[j + 1] : s1;
        int g;
        x = 0.5 * a + 0.5 * b;
        for (y = c[deg], k = deg; k-- > 0;) y = y * x + c[k];
        g = fr__sgn(y);
        if (g == 0 && j >= first && j + 1 == nr) {
            /* the last root at s1 (or within rounding of it): its gap is
               empty and its midpoint the root. Just beyond it, 2^-20 of
               the gap before away, a simple root's sign has turned and a
               touch's has not (the prepared path takes such a root too) */
            x = a + (a - (j > first ? r[j - 1] : s0)) * 0x1p-20;
            for (y = c[deg], k = deg; k-- > 0;) y = y * x + c[k];
            g = fr__sgn(y);
        }
        if (j < first) *sg = prev = g;
        else {
            if (g != 0 && prev != 0 && g != prev) cand[m++] = ts + r[j];
            if (g != 0) prev = g;
        }
    }
    return m;
}

/* The sign of the shape from the leaves' signs v[0, nl): min, max and
   negation over signs, as over values (an R-function has the sign of min or
   max of its operands); node values go to v[nl...]. */
static FR__HOT_INLINE int fr__csg_sign(const fr__csg_node_t *nd, unsigned int nn, unsigned int nl, signed char *v,
                                       unsigned long long force)
{
    signed char *w = v + nl;
    unsigned int j;
    for (j = 0; j < nn; j++) {
        int a = v[nd[j].a], b = v[nd[j].b], mn = a < b ? a : b, mx = a < b ? b : a;
        w[j] = (signed char)(nd[j].op == FR__CSG_MAX ? mx : nd[j].op == FR__CSG_MIN ? mn : -a);
        if (force & nd[j].bit) w[j] = -1;
    }
    return nn ? w[nn - 1] : v[0];
}

/* The same over the tape's own slots (fr__csg_mark's list, ascending):
   leaves (deg >= 0) hold their signs in v[slot]. */
static int fr__csg_sign_tape(const fr_tape_t *t, const unsigned int *list, int cnt, const int *deg, signed char *v)
{
    int j;
    for (j = 0; j < cnt; j++) {
        unsigned int i = list[j];
        const fr_instr_t *in = &t->code[i];
        int a, b;
        if (deg[i] >= 0) continue;
        a = v[in->a];
        b = in->op == FR_OP_NEG ? 0 : v[in->b];
        v[i] = (signed char)(in->op == FR_OP_NEG ? -a : in->op == FR_OP_MIN || in->op == FR_OP_RINT ? (a < b ? a : b)
                                                                                                  : (a < b ? b : a));
    }
    return v[t->outputs[0]];
}

/* The tree a walk evaluates: a prepared model's nodes, or the tape's slots. */
typedef struct fr__csg_walk_t {
    const fr__csg_node_t *nodes; /* prepared: nn nodes over nl leaves, force as fr__csg_sign */
    unsigned int nn, nl;
    unsigned long long force;
    const fr_tape_t *tape;       /* plain: fr__csg_mark's list of cnt slots, with the Taylor degrees */
    const unsigned int *list;
    int cnt;
    const int *deg;
} fr__csg_walk_t;

static FR__HOT_INLINE int fr__walk_sign(const fr__csg_walk_t *W, signed char *v)
{
    return W->nodes ? fr__csg_sign(W->nodes, W->nn, W->nl, v, W->force) : fr__csg_sign_tape(W->tape, W->list, W->cnt, W->deg, v);
}

/* Sort the nc crossings cand (t) with their leaves cl, then find the first
   where the shape's sign differs between just before and just after it,
   within FR__CSG_SIGN_ULPS of the point's scale (near-coincident surfaces
   count together): vlo and vhi start as the leaves' signs after t0; a
   crossing flips its leaf's sign in vhi once it is within the bracket's
   end and in vlo once it is before the bracket's start, and the tree is
   re-evaluated only where a leaf changed -- no evaluation of g near a
   root, where rounding could hide a grazing ray's sign change. Returns the
   crossing's index or -1, with the shape's signs before (glo) and after
   (ghi) and the bracket's half-width. */
static FR__HOT_INLINE int fr__csg_walk(fr__ray_t *R, const fr__csg_walk_t *W, double *cand, unsigned int *cl, int nc, signed char *vlo,
                        signed char *vhi, int *glo, int *ghi, double *dt_out)
{
    int k, plo = 0, phi = 0;
    double oscale;
    for (k = 1; k < nc; k++) { /* insertion sort: few candidates */
        double x = cand[k];
        unsigned int y = cl[k];
        int i = k;
        while (i > 0 && cand[i - 1] > x) { cand[i] = cand[i - 1]; cl[i] = cl[i - 1]; i--; }
        cand[i] = x;
        cl[i] = y;
    }
    if (nc == 0) return -1;
    *glo = *ghi = fr__walk_sign(W, vlo);
    oscale = (fabs(R->o[0]) + fabs(R->o[1]) + fabs(R->o[2])) / (fabs(R->d[0]) + fabs(R->d[1]) + fabs(R->d[2]));
    for (k = 0; k < nc; k++) {
        double tc = cand[k], dt = FR__CSG_SIGN_ULPS * FR__U * (fabs(tc) + oscale);
        int mlo = plo, mhi = phi;
        while (phi < nc && cand[phi] <= tc + dt) { vhi[cl[phi]] = (signed char)-vhi[cl[phi]]; phi++; }
        while (plo < nc && cand[plo] < tc - dt) { vlo[cl[plo]] = (signed char)-vlo[cl[plo]]; plo++; }
        if (plo != mlo) *glo = fr__walk_sign(W, vlo);
        if (phi != mhi) *ghi = fr__walk_sign(W, vhi);
        R->iters++;
        if (*glo * *ghi < 0) { *dt_out = dt; return k; }
    }
    return -1;
}

/* The paper's analytic method. A polynomial tape: the roots of g. Otherwise
   the shape must be min/max/R-function/negation nodes over polynomial
   leaves; the zero set of such a node lies in the union of its operands'
   zero sets, so the hit is among the leaf roots: sorted, the first where f
   changes sign (§3.1.1, "select the root ... placed on the surface of the
   CSG solid"). ts: the expansion point of fr__analytic_expand, already run
   on mem; cnt: fr__csg_mark's count if it ran, else -2. */
static fr_result_t fr__trace_analytic(fr__ray_t *R, const fr__trace_mem_t *mem, double ts, int cnt, int *found,
                                      double *t_hit, double *t_err)
{
    const fr_tape_t *t = R->tape;
    unsigned int out = t->outputs[0];
    int nc = 0, k, j;
    double *cand = mem->cand, s0 = R->t0 - ts, s1 = R->t1 - ts;
    *found = 0;
    if (mem->deg[out] >= 0) { /* a polynomial tape; CSG trees scale their own (fr__csg_walk) */
        double r[FR_POLY_MAX_DEGREE], oscale = (fabs(R->o[0]) + fabs(R->o[1]) + fabs(R->o[2])) /
                                               (fabs(R->d[0]) + fabs(R->d[1]) + fabs(R->d[2]));
        int nr = fr__solve_poly(mem->taylor + (size_t)out * FR__TAYLOR_N, mem->deg[out], s0, s1, r);
        R->iters++;
        if (nr > 0) { *found = 1; *t_hit = ts + r[0]; *t_err = 4.0 * FR__U * (fabs(*t_hit) + oscale); }
        return FR_OK;
    }
    if (cnt == -2) cnt = fr__csg_mark(t, mem);
    if (cnt < 0) return FR_ERR_NOT_POLYNOMIAL;
    {
        signed char *vlo = mem->sgn, *vhi = mem->sgn + t->n_code;
        fr__csg_walk_t W;
        int glo, ghi, kh;
        double dt;
        for (j = 0; j < cnt; j++) { /* the polynomial leaves: their crossings and signs */
            unsigned int i = mem->list[j];
            int m, sg = 0;
            if (mem->deg[i] < 0) continue;
            m = fr__poly_leaf(mem->taylor + (size_t)i * FR__TAYLOR_N, mem->deg[i], s0, s1, ts, 0, cand + nc, &sg);
            R->iters++;
            if (m < 0) return FR_ERR_NOT_POLYNOMIAL;
            for (k = 0; k < m; k++) mem->cleaf[nc + k] = i;
            nc += m;
            vlo[i] = vhi[i] = (signed char)sg;
        }
        memset(&W, 0, sizeof W);
        W.tape = t; W.list = mem->list; W.cnt = cnt; W.deg = mem->deg;
        kh = fr__csg_walk(R, &W, cand, mem->cleaf, nc, vlo, vhi, &glo, &ghi, &dt);
        if (kh >= 0) { *found = 1; *t_hit = cand[kh]; *t_err = dt; }
        R->evals += (unsigned long long)cnt;
    }
    return FR_OK;
}

/* ---------------------------------------------------------------- normals and the entry point */

static void fr__normal(fr__ray_t *R, const fr_trace_desc_t *desc, const double p[3], double nrm[3])
{
    double g[3] = {0, 0, 0}, v, len;
    int k;
    if (desc->normal == FR_NORMAL_NONE) { nrm[0] = nrm[1] = nrm[2] = 0; return; }
    R->evals++;
    if (desc->normal != FR_NORMAL_AD || fr_eval_grad(R->tape, p, R->eval, &v, g) != FR_OK) {
        /* central differences, also when a callback has no gradient */
        double scale = fabs(p[0]) + fabs(p[1]) + fabs(p[2]), h;
        h = (desc->fd_step > 0 ? desc->fd_step : FR__FD_STEP) * (scale > 1 ? scale : 1);
        for (k = 0; k < 3; k++) {
            double q[3];
            q[0] = p[0]; q[1] = p[1]; q[2] = p[2];
            q[k] = p[k] + h; v = fr_eval(R->tape, q, R->eval);
            q[k] = p[k] - h; g[k] = (v - fr_eval(R->tape, q, R->eval)) / (2.0 * h);
            R->evals += 2;
        }
    }
    len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    for (k = 0; k < 3; k++) nrm[k] = len > 0 && len == len ? -g[k] / len : 0.0;
}

/* The AD normal of a prepared polynomial (FR_PREPARED_POLY) at p: value
   and gradient per slot (4 doubles in V) by the program's kernels, the
   derivative rules of fr_eval_grad on fewer and straighter cases (a fourth
   of the tangle cube's interval time went to the tape's AD). Returns 0
   for a program it cannot take (the caller then uses fr__normal). */
static int fr__prog_normal(const fr_tape_t *t, const fr_prepared_t *P, const double p[3], double *V, double nrm[3])
{
    fr__tp_t *prog;
    unsigned int j, out = t->outputs[0];
    int k;
    double len;
    fr__prep_layout(P->n_leaves, P->n_nodes, P->n_prog, NULL, NULL, &prog, P->mem);
    for (j = 0; j < P->n_prog; j++) {
        const fr__tp_t *pi = &prog[j];
        const fr_instr_t *in = &t->code[pi->slot];
        double *c = V + 4 * (size_t)pi->slot;
        const double *A = V + 4 * (size_t)pi->a, *B = V + 4 * (size_t)pi->b;
        double f = 0;
        switch (pi->kernel) {
        case FR__K_CONST: c[0] = in->k; c[1] = c[2] = c[3] = 0; continue;
        case FR__K_VAR: {
            int ax = (int)in->op - (int)FR_OP_VAR_X;
            c[0] = p[ax]; c[1] = c[2] = c[3] = 0; c[1 + ax] = 1;
            continue;
        }
        case FR__K_NEG: for (k = 0; k < 4; k++) c[k] = -A[k]; continue;
        case FR__K_ADD: for (k = 0; k < 4; k++) c[k] = A[k] + B[k]; continue;
        case FR__K_SUB: for (k = 0; k < 4; k++) c[k] = A[k] - B[k]; continue;
        case FR__K_MULK: for (k = 0; k < 4; k++) c[k] = A[k] * B[0]; continue;
        case FR__K_KMUL: for (k = 0; k < 4; k++) c[k] = A[0] * B[k]; continue;
        case FR__K_SQR1: case FR__K_SQR2: f = 2.0 * A[0]; c[0] = A[0] * A[0]; break;
        case FR__K_POW4: { double a2 = A[0] * A[0]; f = 4.0 * (a2 * A[0]); c[0] = a2 * a2; break; }
        default:
            switch ((fr_op_t)in->op) {
            case FR_OP_MUL: c[0] = A[0] * B[0]; for (k = 1; k < 4; k++) c[k] = A[k] * B[0] + A[0] * B[k]; continue;
            case FR_OP_SQR: f = 2.0 * A[0]; c[0] = A[0] * A[0]; break;
            case FR_OP_POWI: {
                int n = (int)in->k;
                c[0] = fr__powi(A[0], n);
                f = n == 0 ? 0.0 : in->k * fr__powi(A[0], n - 1);
                break;
            }
            case FR_OP_DIV: c[0] = A[0] / B[0]; f = 1.0 / B[0]; break; /* B is a constant */
            default:
                if (pi->dc != 0 || !fr__tpoly_const_op(in, A[0], B[0], &c[0])) return 0;
                c[1] = c[2] = c[3] = 0;
                continue;
            }
            break;
        }
        for (k = 1; k < 4; k++) c[k] = f * A[k]; /* the chain rule of a unary step */
    }
    len = sqrt(V[4 * (size_t)out + 1] * V[4 * (size_t)out + 1] + V[4 * (size_t)out + 2] * V[4 * (size_t)out + 2] +
               V[4 * (size_t)out + 3] * V[4 * (size_t)out + 3]);
    for (k = 0; k < 3; k++) nrm[k] = len > 0 && len == len ? -V[4 * (size_t)out + 1 + (size_t)k] / len : 0.0;
    return 1;
}

/* Clip [R->t0, R->t1] to the box b (lo x y z, hi x y z) by the slab test;
   0 if nothing is left. The box is padded by 2^-20 of its size plus the
   rounding of o and of the slab divisions, so a surface on the box's face
   is never clipped away. */
#define FR__BOX_PAD 9.5367431640625e-07 /* 2^-20 */
static int fr__clip_box(fr__ray_t *R, const double *b)
{
    double a = R->t0, z = R->t1;
    int k;
    for (k = 0; k < 3; k++) {
        double pad = FR__BOX_PAD * (b[k + 3] - b[k]) + 8.0 * FR__U * (fabs(R->o[k]) + fabs(b[k]) + fabs(b[k + 3]));
        double lo = b[k] - pad, hi = b[k + 3] + pad, ta, tb, inv;
        if (!(lo <= hi)) return 0; /* empty or NaN box */
        if (R->d[k] == 0) {
            if (R->o[k] < lo || R->o[k] > hi) return 0;
            continue;
        }
        inv = 1.0 / R->d[k];
        ta = (lo - R->o[k]) * inv;
        tb = (hi - R->o[k]) * inv;
        if (ta > tb) { double x = ta; ta = tb; tb = x; }
        ta -= 4.0 * FR__U * fabs(ta); /* the reciprocal's and products' rounding, outward */
        tb += 4.0 * FR__U * fabs(tb);
        if (ta > a) a = ta;
        if (tb < z) z = tb;
    }
    if (!(a <= z)) return 0;
    R->t0 = a; R->t1 = z;
    return 1;
}

/* ---------------------------------------------------------------- prepared models */

/* The reciprocal directions and o's rounding pad in t for slab tests
   (fr__slab_meets), computed once per ray. */
static void fr__ray_inv(fr__ray_t *R)
{
    int k;
    if (R->have_inv) return;
    R->tpad = 0.0;
    for (k = 0; k < 3; k++) {
        double op = 8.0 * FR__U * fabs(R->o[k]);
        R->inv[k] = R->d[k] != 0 ? 1.0 / R->d[k] : 0.0;
        if (op * fabs(R->inv[k]) > R->tpad) R->tpad = op * fabs(R->inv[k]);
    }
    R->have_inv = 1;
}

/* fr__clip_box with a box padded beforehand (fr__box_pad_set): only the
   ray's own rounding (fr__ray_inv's pad) is added, to the box's bounds in t. */
static int fr__clip_padded(fr__ray_t *R, const double *b)
{
    double A = -HUGE_VAL, Z = HUGE_VAL;
    int k;
    fr__ray_inv(R);
    for (k = 0; k < 3; k++) {
        double ta, tb;
        if (R->d[k] == 0) {
            double op = 8.0 * FR__U * fabs(R->o[k]);
            if (!(R->o[k] >= b[k] - op && R->o[k] <= b[k + 3] + op)) return 0;
            continue;
        }
        ta = (b[k] - R->o[k]) * R->inv[k];
        tb = (b[k + 3] - R->o[k]) * R->inv[k];
        if (ta > tb) { double x = ta; ta = tb; tb = x; }
        if (ta > A) A = ta;
        if (tb < Z) Z = tb;
    }
    A -= 4.0 * FR__U * fabs(A) + R->tpad;
    Z += 4.0 * FR__U * fabs(Z) + R->tpad;
    if (A < R->t0) A = R->t0;
    if (Z > R->t1) Z = R->t1;
    if (!(A <= Z)) return 0;
    R->t0 = A;
    R->t1 = Z;
    return 1;
}

/* Leaf zero-set boxes: octree depth, and the padding of the search box
   beyond the prepared box (twice fr__clip_box's, so the clipped segments
   of every ray lie inside it). */
#define FR__LEAF_BOX_DEPTH 6
#define FR__LEAF_CULL_SHARE 0.25
/* Quadric leaves use the quadratic formula while their largest coefficient
   on the ray lies in [2^-300, 2^300] (no overflow or underflow in Kahan's
   discriminant), else fr_solve_poly. */
#define FR__QUAD_BIG 2.037035976334486e90     /* 2^300 */
#define FR__QUAD_SMALL 4.9090934652977266e-91 /* 2^-300 */


/* The slots of root's subtree in ascending order (operands precede their
   users), into out; returns their count. stamp (n entries, left as they
   are between calls) marks visits with tag, which must differ from every
   earlier call's; stack holds n entries. */
static unsigned int fr__subtree(const fr_tape_t *t, unsigned int root, unsigned int tag, unsigned int *stamp,
                                unsigned int *stack, unsigned int *out)
{
    unsigned int sp = 0, m = 0;
    stack[sp++] = root;
    stamp[root] = tag;
    while (sp > 0) {
        unsigned int x = stack[--sp], op[3], k;
        const fr_instr_t *in = &t->code[x];
        int ar = fr__arity(in->op);
        out[m++] = x;
        op[0] = in->a; op[1] = in->b; op[2] = in->c;
        for (k = 0; k < (unsigned int)ar; k++)
            if (stamp[op[k]] != tag) { stamp[op[k]] = tag; stack[sp++] = op[k]; }
    }
    { /* ascending: Shell sort (Ciura's gaps; no libc qsort, which a user FR_MALLOC leaves undeclared) */
        static const unsigned int gaps[8] = {701, 301, 132, 57, 23, 10, 4, 1};
        unsigned int gi, i, j;
        for (gi = 0; gi < 8; gi++) {
            unsigned int h = gaps[gi];
            for (i = h; i < m; i++) {
                unsigned int v = out[i];
                for (j = i; j >= h && out[j - h] > v; j -= h) out[j] = out[j - h];
                out[j] = v;
            }
        }
    }
    return m;
}

/* The quadric (degree <= 2) monomial forms of the slots in list
   (ascending; the last is the leaf) in powers of q = p - e: W holds 10 doubles
   per slot, [1, X, Y, Z, XX, XY, XZ, YY, YZ, ZZ]; slots of generic degree
   outside [0, 2] get NaN. Returns 1 if the leaf came out finite. */
static int fr__quadric_forms(const fr_tape_t *t, const int *gdeg, const unsigned int *list, unsigned int cnt,
                             const double e[3], double *W)
{
    unsigned int j, last = list[cnt - 1];
    int k;
    for (j = 0; j < cnt; j++) {
        unsigned int i = list[j];
        const fr_instr_t *in = &t->code[i];
        double *c = W + 10 * (size_t)i, r[10];
        const double *a = W + 10 * (size_t)in->a, *b = W + 10 * (size_t)in->b;
        for (k = 0; k < 10; k++) r[k] = 0.0;
        if (gdeg[i] < 0 || gdeg[i] > 2) {
            r[0] = NAN;
        } else {
            switch ((fr_op_t)in->op) {
        case FR_OP_CONST: r[0] = in->k; break;
        case FR_OP_VAR_X: case FR_OP_VAR_Y: case FR_OP_VAR_Z: {
            int ax = (int)in->op - (int)FR_OP_VAR_X;
            r[0] = e[ax]; r[1 + ax] = 1.0;
            break;
        }
        case FR_OP_NEG: for (k = 0; k < 10; k++) r[k] = -a[k]; break;
        case FR_OP_ADD: for (k = 0; k < 10; k++) r[k] = a[k] + b[k]; break;
        case FR_OP_SUB: for (k = 0; k < 10; k++) r[k] = a[k] - b[k]; break;
        case FR_OP_SQR: case FR_OP_MUL: case FR_OP_POWI: {
            /* products of total degree <= 2 (gdeg says so): constant times
               anything, or linear times linear */
            const double *y = in->op == FR_OP_MUL ? b : a;
            int n = in->op == FR_OP_POWI ? (int)in->k : 2;
            if (n == 0) { r[0] = 1.0; break; }
            if (n == 1) { for (k = 0; k < 10; k++) r[k] = a[k]; break; }
            if (in->op == FR_OP_POWI && gdeg[in->a] == 0) { r[0] = fr__powi(a[0], n); break; }
            if (n != 2) { r[0] = NAN; break; }
            r[0] = a[0] * y[0];
            for (k = 1; k < 10; k++) r[k] = a[0] * y[k] + a[k] * y[0];
            r[4] += a[1] * y[1]; r[5] += a[1] * y[2] + a[2] * y[1]; r[6] += a[1] * y[3] + a[3] * y[1];
            r[7] += a[2] * y[2]; r[8] += a[2] * y[3] + a[3] * y[2]; r[9] += a[3] * y[3];
            break;
        }
        case FR_OP_DIV: for (k = 0; k < 10; k++) r[k] = b[0] != 0 ? a[k] / b[0] : NAN; break;
        default:
            if (!fr__tpoly_const_op(in, a[0], b[0], &r[0])) r[0] = NAN;
            break;
            }
        }
        for (k = 0; k < 10; k++) c[k] = r[k];
    }
    for (k = 0; k < 10; k++) if (!(W[10 * (size_t)last + (size_t)k] - W[10 * (size_t)last + (size_t)k] == 0)) return 0;
    return 1;
}

/* The leaf's form from W's slot: k, b, A's diagonal, A's off-diagonal. */
static void fr__quadric_store(fr__leaf_t *L, const double *w)
{
    L->q[0] = w[0]; L->q[1] = w[1]; L->q[2] = w[2]; L->q[3] = w[3];
    L->q[4] = w[4]; L->q[5] = w[7]; L->q[6] = w[9];
    L->q[7] = 0.5 * w[5]; L->q[8] = 0.5 * w[6]; L->q[9] = 0.5 * w[8];
    /* planes and axis-aligned quadrics (the library's spheres, cylinders,
       cones, ellipsoids) skip the products by zeros */
    L->shape = L->q[7] != 0 || L->q[8] != 0 || L->q[9] != 0 ? FR__LEAF_FULL
             : L->q[4] != 0 || L->q[5] != 0 || L->q[6] != 0 ? FR__LEAF_DIAGONAL : FR__LEAF_LINEAR;
}

#ifndef FR_NO_INTERVAL
/* A quadric leaf's form over a cell, in intervals (rigorous for the form). */
static fr_result_t fr__quadric_cell(const void *ctx, const iv_t box[3], iv_t *r)
{
    const fr__leaf_t *L = (const fr__leaf_t *)ctx;
    iv_t X[3], f = iv_point(L->q[0]);
    int k;
    for (k = 0; k < 3; k++) X[k] = iv_sub(box[k], iv_point(L->e[k]));
    for (k = 0; k < 3; k++) {
        f = iv_add(f, iv_mul_d(X[k], L->q[1 + k]));
        f = iv_add(f, iv_mul_d(iv_sqr(X[k]), L->q[4 + k]));
    }
    f = iv_add(f, iv_mul_d(iv_mul(X[0], X[1]), 2.0 * L->q[7]));
    f = iv_add(f, iv_mul_d(iv_mul(X[0], X[2]), 2.0 * L->q[8]));
    f = iv_add(f, iv_mul_d(iv_mul(X[1], X[2]), 2.0 * L->q[9]));
    *r = f;
    return FR_OK;
}
#endif

/* The search box of leaf zero sets: the prepared box, padded. */
static void fr__leaf_search_box(const double *box, double lo[3], double hi[3])
{
    int k;
    for (k = 0; k < 3; k++) {
        double pad = 2.0 * (FR__BOX_PAD * (box[k + 3] - box[k]) + 8.0 * FR__U * (fabs(box[k]) + fabs(box[k + 3])));
        lo[k] = box[k] - pad;
        hi[k] = box[k + 3] + pad;
    }
}

/* A leaf's zero-set box, padded as fr__clip_box pads (fr__slab_meets adds
   the ray's own rounding); an empty box stays empty. */
/* out = [lo, hi] padded as fr__clip_box pads a box (fr__slab_meets and
   fr__clip_padded add the ray's own rounding); an empty box stays empty.
   Returns its volume's share of the model box's. */
static double fr__box_pad_set(const double lo[3], const double hi[3], const double *model, double *out)
{
    double v = 1.0, vm = 1.0;
    int k;
    for (k = 0; k < 3; k++) {
        double pad = lo[k] <= hi[k] ? FR__BOX_PAD * (hi[k] - lo[k]) + 8.0 * FR__U * (fabs(lo[k]) + fabs(hi[k])) : 0.0;
        out[k] = lo[k] - pad;
        out[k + 3] = hi[k] + pad;
        v *= lo[k] <= hi[k] ? hi[k] - lo[k] : 0.0;
        vm *= model[k + 3] - model[k];
    }
    return vm > 0 ? v / vm : 1.0;
}

/* A slab test costs about half a quadric leaf, and a plane less than the
   test: quadric leaves and CSG nodes are culled only when their box is at
   most FR__LEAF_CULL_SHARE of the model's (rays through the model then
   miss it often), other leaves always. */
#ifndef FR_NO_INTERVAL
static void fr__leaf_box_set(fr__leaf_t *lf, const double lo[3], const double hi[3], const double *model)
{
    double share = fr__box_pad_set(lo, hi, model, lf->box);
    lf->boxed = !lf->quadric || (lf->shape != FR__LEAF_LINEAR && share <= FR__LEAF_CULL_SHARE);
}
#endif

#ifndef FR_NO_INTERVAL
/* The box of slot `slot`'s zero set (keep_zero 1) or solid (0) inside [lo,
   hi], by fr__box_search on its sub-tape compacted into work (live, newidx,
   rep, code, then interval scratch; fr_prepare sizes it). 0 if the tape has
   no interval evaluation. */
static int fr__subtape_box(const fr_tape_t *t, unsigned int slot, int keep_zero, const double lo[3], const double hi[3],
                           unsigned char *work, double out_lo[3], double out_hi[3])
{
    size_t n = t->n_code;
    unsigned char *live = work;
    unsigned int *newidx = (unsigned int *)(void *)(work + fr__align8(n)), *rep = newidx + n, m, i;
    fr_instr_t *code = (fr_instr_t *)(void *)(work + fr__align8(n) + fr__align8(2 * n * sizeof(unsigned int)));
    fr_tape_t sub = *t;
    fr__tape_cell_t cell;
    if (t->flags & FR_TAPE_NO_INTERVAL) return 0;
    for (i = 0; i < n; i++) rep[i] = i;
    m = fr__compact(t->code, (unsigned int)n, rep, &slot, 1, live, newidx, code, &sub.outputs[0]);
    sub.code = code;
    sub.n_code = m;
    sub.n_outputs = 1;
    cell.tape = &sub;
    cell.scratch = (unsigned char *)code + fr__align8(n * sizeof(fr_instr_t));
    return fr__box_search(fr__tape_cell, &cell, keep_zero, lo, hi, FR__LEAF_BOX_DEPTH, out_lo, out_hi) == FR_OK;
}
#endif

/* The leaves' forms and boxes. Quadrics: the form about the search box's
   centre gives a first zero-set box, then the form about that box's
   centre (the leaf's own middle: no cancellation of far-off terms) and
   the final box from it. Other leaves: the box of their sub-tape's zero
   set (compacted with the work area). */
static fr_result_t fr__prepare_leaves(const fr_tape_t *t, const int *gdeg, const double *box, fr__leaf_t *L,
                                      unsigned int nl, unsigned char *work)
{
    size_t n = t->n_code;
    double *W = (double *)(void *)work;
    unsigned int *stamp = (unsigned int *)(void *)(work + 10 * n * sizeof(double)), *stack = stamp + n, *sub = stack + n;
    double lo[3], hi[3], c[3];
    unsigned int j;
    int k;
    for (j = 0; j < n; j++) stamp[j] = 0;
    fr__leaf_search_box(box, lo, hi);
    for (k = 0; k < 3; k++) c[k] = 0.5 * lo[k] + 0.5 * hi[k];
    for (j = 0; j < nl; j++) {
        fr__leaf_t *lf = &L[j];
        lf->boxed = 0;
        unsigned int ns = lf->degree <= 2 ? fr__subtree(t, lf->slot, j + 1, stamp, stack, sub) : 0;
        if (lf->degree <= 2 && fr__quadric_forms(t, gdeg, sub, ns, c, W)) {
            lf->quadric = 1;
            for (k = 0; k < 3; k++) lf->e[k] = c[k];
            fr__quadric_store(lf, W + 10 * (size_t)lf->slot);
#ifndef FR_NO_INTERVAL
            {
                double blo[3], bhi[3], e2[3];
                if (fr__box_search(fr__quadric_cell, lf, 1, lo, hi, FR__LEAF_BOX_DEPTH, blo, bhi) != FR_OK) continue;
                if (blo[0] <= bhi[0]) {
                    for (k = 0; k < 3; k++) e2[k] = 0.5 * blo[k] + 0.5 * bhi[k];
                    if (!fr__quadric_forms(t, gdeg, sub, ns, e2, W)) continue;
                    for (k = 0; k < 3; k++) lf->e[k] = e2[k];
                    fr__quadric_store(lf, W + 10 * (size_t)lf->slot);
                    if (fr__box_search(fr__quadric_cell, lf, 1, lo, hi, FR__LEAF_BOX_DEPTH, blo, bhi) != FR_OK) continue;
                }
                fr__leaf_box_set(lf, blo, bhi, box);
            }
#endif
            continue;
        }
        lf->quadric = 0;
#ifndef FR_NO_INTERVAL
        {
            double blo[3], bhi[3];
            if (fr__subtape_box(t, lf->slot, 1, lo, hi, work, blo, bhi)) fr__leaf_box_set(lf, blo, bhi, box);
        }
#endif
    }
    (void)n;
    return FR_OK;
}

/* fr__leaf_t.decides and needs: a leaf of one sign throughout settles
   every node up a chain of single users as long as each node's other
   operand cannot undo it: an intersection (min) of a negative operand is
   negative, a union (max) of a positive one positive, negation flips; a
   union of a negative operand needs the other operand negative too, which
   a boxed node the ray misses is (its bit joins needs). Reaching the shape
   settles its sign: no crossing can change it. work: nl + nn unsigned ints. */
static void fr__prepare_decides(fr__leaf_t *L, unsigned int nl, const fr__csg_node_t *N, unsigned int nn,
                                unsigned int *work)
{
    unsigned int *user = work, i, j;
    int s0;
    for (i = 0; i < nl + nn; i++) user[i] = ~0u; /* the one user, ~0u none, ~1u several */
    for (i = 0; i < nn; i++) {
        unsigned int ops[2], k, no = N[i].op == FR__CSG_NEG ? 1u : 2u;
        ops[0] = N[i].a; ops[1] = N[i].b;
        for (k = 0; k < no; k++) user[ops[k]] = user[ops[k]] == ~0u ? nl + i : ~1u;
    }
    for (j = 0; j < nl; j++)
        for (s0 = 0; s0 < 2; s0++) {
            unsigned int cur = j;
            int sg = 2 * s0 - 1, ok = 1;
            unsigned long long need = 0;
            while (ok && cur != nl + nn - 1) {
                unsigned int p = user[cur], other;
                if (p >= nl + nn) { ok = 0; break; } /* no single user */
                other = N[p - nl].a == cur ? N[p - nl].b : N[p - nl].a;
                if (N[p - nl].op == FR__CSG_NEG) sg = -sg;
                else if (N[p - nl].op == FR__CSG_MIN) ok = sg < 0;
                else if (sg < 0) { /* a union: the other operand must be a missed box */
                    ok = other >= nl && N[other - nl].bit != 0;
                    if (ok) need |= N[other - nl].bit;
                }
                cur = p;
            }
            L[j].decides[s0] = ok;
            L[j].needs[s0] = need;
        }
}

#ifndef FR_NO_INTERVAL
/* The masks of the boxed nodes (fr__csg_node_t.bit, leaf_mask,
   node_mask): what a ray that misses a node's box may skip is what only
   that node reaches, that is what the shape reaches from below it but not
   along paths avoiding it (a leaf or node shared with the rest of the tree
   is still needed there). Boxed nodes beyond the 64th lose their box.
   work: 2 (nl + nn) bytes. */
static void fr__prepare_masks(fr__csg_node_t *N, unsigned int nn, unsigned int nl, unsigned char *work)
{
    unsigned char *avoid = work, *below = work + nl + nn;
    unsigned int i, x, nb = 0;
    for (i = nn; i-- > 0;) {
        if (!N[i].boxed) continue;
        if (nb == 64) { N[i].boxed = 0; continue; }
        N[i].bit = 1ull << nb++;
    }
    for (i = 0; i < nn; i++) {
        if (!N[i].bit) continue;
        memset(work, 0, 2 * (size_t)(nl + nn));
        if (i != nn - 1) avoid[nl + nn - 1] = 1;
        below[nl + i] = 1;
        for (x = nn; x-- > 0;) { /* operands precede their users */
            if (avoid[nl + x] && x != i) {
                avoid[N[x].a] = 1;
                if (N[x].op != FR__CSG_NEG) avoid[N[x].b] = 1;
            }
            if (below[nl + x]) {
                below[N[x].a] = 1;
                if (N[x].op != FR__CSG_NEG) below[N[x].b] = 1;
            }
        }
        for (x = 0; x < nl && nl <= 64; x++)
            if (below[x] && !avoid[x]) N[i].leaf_mask |= 1ull << x;
        for (x = 0; x < nn; x++)
            if (x != i && N[x].bit && below[nl + x] && !avoid[nl + x]) N[i].node_mask |= N[x].bit;
    }
}

/* The nodes' solid boxes, for nodes small enough to cull (fr__leaf_box_set). */
static void fr__prepare_nodes(const fr_tape_t *t, const double *box, fr__csg_node_t *N, unsigned int nn,
                              unsigned char *work)
{
    double lo[3], hi[3];
    unsigned int j;
    fr__leaf_search_box(box, lo, hi);
    for (j = 0; j < nn; j++) {
        double blo[3], bhi[3];
        N[j].boxed = 0;
        if (N[j].op == FR__CSG_NEG || !fr__subtape_box(t, N[j].slot, 0, lo, hi, work, blo, bhi)) continue;
        N[j].boxed = fr__box_pad_set(blo, bhi, box, N[j].box) <= FR__LEAF_CULL_SHARE;
    }
}
#endif

/* fr_prepare's scratch: generic degrees, marks, indices; then 10 doubles
   per slot for quadric forms, or a compacted sub-tape with its interval
   scratch. */
static size_t fr__prepare_work_bytes(const fr_tape_t *t)
{
    size_t n = t->n_code, bytes = fr__align8(n * sizeof(int)) + 2 * fr__align8(n) + fr__align8(n * sizeof(unsigned int));
    size_t a = 10 * n * sizeof(double) + 3 * n * sizeof(unsigned int), b = fr__align8(n) + fr__align8(2 * n * sizeof(unsigned int)) +
                                             fr__align8(n * sizeof(fr_instr_t)) + fr__eval_scratch_max(t);
    return bytes + (a > b ? a : b);
}

/* The kind of prepared model the tape allows, from the shape slot `outs`
   down: a polynomial in the coordinates (FR_PREPARED_POLY), a CSG tree of
   polynomial leaves under min, max, R-functions and negation
   (FR_PREPARED_CSG), or neither. need[i]: 1 for a slot the analysis
   reaches, 2 for one in the Taylor program too (gdeg: generic degrees). */
static fr_prepared_kind_t fr__prepare_kind(const fr_tape_t *t, const int *gdeg, unsigned int outs, unsigned char *need)
{
    fr_prepared_kind_t kind = gdeg[outs] >= 0 ? FR_PREPARED_POLY : FR_PREPARED_CSG;
    unsigned int i;
    memset(need, 0, t->n_code);
    need[outs] = 1;
    for (i = outs + 1; i-- > 0;) {
        const fr_instr_t *in = &t->code[i];
        if (!need[i]) continue;
        if (gdeg[i] >= 0) { /* a polynomial slot: in the program, with its operands */
            int ar = fr__arity(in->op);
            if (kind == FR_PREPARED_POLY || need[i] == 2) {
                need[i] = 2;
                if (ar >= 1) need[in->a] = 2;
                if (ar >= 2) need[in->b] = 2;
            }
            continue;
        }
        switch ((fr_op_t)in->op) { /* a CSG node */
        case FR_OP_MIN: case FR_OP_MAX: case FR_OP_RUNI: case FR_OP_RINT:
            if (!need[in->b]) need[in->b] = 1;
            /* fallthrough */
        case FR_OP_NEG:
            if (!need[in->a]) need[in->a] = 1;
            break;
        default: return FR_PREPARED_NONE;
        }
    }
    return kind;
}

/* The CSG tree's leaves (polynomial slots) and nodes in slot order, their
   operands as tree indices (idx: per slot, its leaf or nl + its node). */
static void fr__prepare_tree(const fr_tape_t *t, const int *gdeg, const unsigned char *need, unsigned int outs, unsigned int nl,
                             unsigned int *idx, fr__leaf_t *L, fr__csg_node_t *N)
{
    unsigned int i, jl = 0, jn = 0;
    for (i = 0; i <= outs; i++) {
        const fr_instr_t *in = &t->code[i];
        if (!need[i]) continue;
        if (gdeg[i] >= 0) {
            memset(&L[jl], 0, sizeof L[jl]);
            L[jl].slot = i;
            L[jl].degree = gdeg[i];
            jl++;
            continue;
        }
        N[jn].op = in->op == FR_OP_NEG ? FR__CSG_NEG : in->op == FR_OP_MIN || in->op == FR_OP_RINT ? FR__CSG_MIN : FR__CSG_MAX;
        N[jn].a = idx[in->a];
        N[jn].b = in->op == FR_OP_NEG ? 0 : idx[in->b];
        N[jn].slot = i;
        N[jn].boxed = 0;
        N[jn].bit = N[jn].leaf_mask = N[jn].node_mask = 0;
        idx[i] = nl + jn;
        jn++;
    }
}

/* The CSG model's leaves (quadric forms, boxes) and nodes (boxes, masks,
   what each leaf decides), then the non-quadric leaves' subtrees marked
   for the program (need 2). w: the scratch past need and idx. */
static void fr__prepare_csg(const fr_tape_t *t, const int *gdeg, unsigned int outs, fr_prepared_t *out, fr__leaf_t *L,
                            fr__csg_node_t *N, unsigned char *need, unsigned char *w)
{
    unsigned int i, j, nl = out->n_leaves, nn = out->n_nodes;
    if (out->has_box) {
        fr__prepare_leaves(t, gdeg, out->box, L, nl, w);
#ifndef FR_NO_INTERVAL
        fr__prepare_nodes(t, out->box, N, nn, w);
        fr__prepare_masks(N, nn, nl, w);
        for (j = 0; j < nn; j++) ((fr__prep_head_t *)out->mem)->n_boxed_nodes += N[j].bit != 0;
#endif
    }
    fr__prepare_decides(L, nl, N, nn, (unsigned int *)(void *)w);
    for (j = 0; j < nl; j++) {
        if (L[j].quadric) { out->n_quadrics++; continue; }
        need[L[j].slot] = 2;
    }
    for (i = outs + 1; i-- > 0;) {
        const fr_instr_t *in = &t->code[i];
        int ar;
        if (need[i] != 2) continue;
        ar = fr__arity(in->op);
        if (ar >= 1) need[in->a] = 2;
        if (ar >= 2) need[in->b] = 2;
    }
}

/* The Taylor program: each slot marked 2, in slot order, with its kernel
   for the operands' degrees. Returns its length. */
static unsigned int fr__prepare_program(const fr_tape_t *t, const int *gdeg, const unsigned char *need, unsigned int outs,
                                        fr__tp_t *P)
{
    unsigned int i, np = 0;
    for (i = 0; i <= outs; i++) {
        const fr_instr_t *in = &t->code[i];
        if (need[i] != 2) continue;
        P[np].slot = i;
        P[np].dc = (unsigned char)gdeg[i];
        P[np].da = (unsigned char)(fr__arity(in->op) >= 1 && gdeg[in->a] > 0 ? gdeg[in->a] : 0);
        P[np].db = (unsigned char)(fr__arity(in->op) >= 2 && gdeg[in->b] > 0 ? gdeg[in->b] : 0);
        P[np].kernel = fr__prog_kernel(in, P[np].da, P[np].db);
        P[np].a = fr__arity(in->op) >= 1 ? in->a : 0;
        P[np].b = fr__arity(in->op) >= 2 ? in->b : 0;
        P[np].oc = i * FR__TAYLOR_N;
        P[np].oa = P[np].a * FR__TAYLOR_N;
        P[np].ob = P[np].b * FR__TAYLOR_N;
        np++;
    }
    return np;
}

static FR__NOINLINE fr_result_t fr__prepare(const fr_tape_t *t, const double *bounds, fr_prepared_t *out)
{
    size_t n;
    unsigned char *work, *need;
    int *gdeg;
    unsigned int *idx, i, outs, nl = 0, nn = 0, np = 0;
    fr__leaf_t *L;
    fr__csg_node_t *N;
    fr__tp_t *P;
    int k;
    if (!t || !out || t->n_code == 0) return FR_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    out->tape = t;
    out->alloc_ctx = t->alloc_ctx;
    if (bounds) {
        for (k = 0; k < 3; k++)
            if (!(bounds[k] - bounds[k] == 0) || !(bounds[k + 3] - bounds[k + 3] == 0) || !(bounds[k] <= bounds[k + 3]))
                return FR_ERR_INVALID_ARG;
        for (k = 0; k < 6; k++) out->box[k] = bounds[k];
        out->has_box = 1;
    }
    n = t->n_code;
    work = (unsigned char *)FR_MALLOC(fr__prepare_work_bytes(t), t->alloc_ctx);
    if (!work) return FR_ERR_OUT_OF_MEMORY;
    gdeg = (int *)(void *)work;
    need = work + fr__align8(n * sizeof(int));
    idx = (unsigned int *)(void *)(need + 2 * fr__align8(n));
    for (i = 0; i < n; i++) {
        const fr_instr_t *in = &t->code[i];
        gdeg[i] = fr__tpoly_degree(in, i > 0 ? gdeg[in->a] : -1, i > 0 ? gdeg[in->b] : -1, 1);
    }
    outs = t->outputs[0];
    out->kind = fr__prepare_kind(t, gdeg, outs, need);
    if (out->kind == FR_PREPARED_NONE) { FR_FREE(work, t->alloc_ctx); return FR_OK; }
    /* leaves and nodes of the CSG tree; leaves that are not quadrics, or all
       of them without a box, join the program (fr__prepare_csg) */
    if (out->kind == FR_PREPARED_CSG)
        for (i = 0; i <= outs; i++) {
            if (!need[i]) continue;
            if (gdeg[i] >= 0) idx[i] = nl++;
            else nn++;
        }
    for (i = 0; i <= outs; i++) if (need[i] == 2) np++;
    {
        size_t bytes = fr__prep_layout(nl, nn, np + (unsigned int)n, NULL, NULL, NULL, NULL);
        out->mem = FR_MALLOC(bytes, t->alloc_ctx);
        if (!out->mem) { FR_FREE(work, t->alloc_ctx); memset(out, 0, sizeof *out); return FR_ERR_OUT_OF_MEMORY; }
        memset(out->mem, 0, sizeof(fr__prep_head_t));
    }
    fr__prep_layout(nl, nn, np + (unsigned int)n, &L, &N, &P, out->mem);
    if (out->has_box) {
        fr__prep_head_t *h = (fr__prep_head_t *)out->mem;
        fr__box_pad_set(out->box, out->box + 3, out->box, h->box);
    }
    if (out->kind == FR_PREPARED_CSG) {
        fr__prepare_tree(t, gdeg, need, outs, nl, idx, L, N);
        out->n_leaves = nl;
        out->n_nodes = nn;
        fr__prepare_csg(t, gdeg, outs, out, L, N, need, need + 2 * fr__align8(n) + fr__align8(n * sizeof(unsigned int)));
    }
    out->n_prog = fr__prepare_program(t, gdeg, need, outs, P);
    FR_FREE(work, t->alloc_ctx);
    return FR_OK;
}

FR_DEF fr_result_t fr_prepare(const fr_tape_t *t, const double *bounds, fr_prepared_t *out)
{
    FR__IN_FP_ENV(fr_result_t, fr__prepare(t, bounds, out));
}

FR_DEF void fr_prepared_free(fr_prepared_t *p)
{
    if (!p) return;
    if (p->mem) FR_FREE(p->mem, p->alloc_ctx);
    memset(p, 0, sizeof *p);
}

/* Does o + t d, t in [a, z], meet the box b (padded at fr_prepare as
   fr__clip_box pads)? The slab test of fr__clip_box with the clip's
   reciprocals (fr__ray_inv); the products' rounding (4u relative,
   monotone in t) and o's (R->tpad) are applied once to the final bounds. */
static int fr__slab_meets(const fr__ray_t *R, const double *b, double a, double z)
{
    int k;
    for (k = 0; k < 3; k++) {
        double lo = b[k] - R->o[k], hi = b[k + 3] - R->o[k], ta, tb;
        if (R->d[k] == 0) {
            double opad = 8.0 * FR__U * fabs(R->o[k]);
            if (!(lo <= opad && hi >= -opad)) return 0;
            continue;
        }
        ta = lo * R->inv[k];
        tb = hi * R->inv[k];
        if (ta > tb) { double x = ta; ta = tb; tb = x; }
        if (ta > a) a = ta;
        if (tb < z) z = tb;
    }
    return a - 4.0 * FR__U * fabs(a) - R->tpad <= z + 4.0 * FR__U * fabs(z) + R->tpad;
}


/* A quadric leaf on the ray: g(ts + s) = c0 + c1 s + c2 s^2 with ts the
   ray's point nearest the leaf's centre e, from the leaf's monomial form
   (a few dozen flops instead of a Taylor run over its subtree). Its roots
   by the quadratic formula, the discriminant by Kahan's fma scheme (exact
   up to the final roundings, so the roots are within a few ulps of those of
   the double coefficients, the cancelling one taken as c0 / h); D <= 0 is
   no crossing (a double root only touches). Returns the crossings in (t0,
   t1] into cand and the sign just after t0 into *sg (from the roots and the
   leading coefficient, so it agrees with them), as fr__poly_leaf; -1 on
   overflow. A leaf whose box the segment misses only needs its sign.
   Coefficients beyond [2^-300, 2^300] go to fr__poly_leaf. (Four leaves
   side by side in a vector were slower: libm's sqrt keeps gcc from
   vectorising, and node culling leaves about half the cup's leaves.) */
static int fr__quadric_leaf(const fr__leaf_t *L, const fr__ray_t *R, double inv_dd, int culled, double *cand, int *sg)
{
    const double *q = L->q, *d = R->d;
    double oe[3], q0[3], u[3], v[3], c[3], r[2], ts, s0, s1, m, lead;
    int k, n, after = 0, cnt = 0;
    for (k = 0; k < 3; k++) oe[k] = R->o[k] - L->e[k];
    if (L->shape == FR__LEAF_LINEAR) {
        /* a plane: g(t) = c0 + c1 t about t = 0, its root t = -c0 / c1 as
           well conditioned as o + t d itself */
        c[0] = q[0] + (q[1] * oe[0] + q[2] * oe[1] + q[3] * oe[2]);
        c[1] = q[1] * d[0] + q[2] * d[1] + q[3] * d[2];
        if (culled || c[1] == 0) { *sg = fr__sgn(c[0] + c[1] * R->t0); return 0; }
        r[0] = -c[0] / c[1];
        if (!(r[0] - r[0] == 0)) return -1;
        *sg = r[0] > R->t0 ? -fr__sgn(c[1]) : fr__sgn(c[1]);
        if (r[0] > R->t0 && r[0] <= R->t1) { cand[0] = r[0]; return 1; }
        return 0;
    }
    ts = -(oe[0] * d[0] + oe[1] * d[1] + oe[2] * d[2]) * inv_dd;
    if (!(ts >= R->t0)) ts = R->t0;
    if (!(ts <= R->t1)) ts = R->t1;
    for (k = 0; k < 3; k++) q0[k] = oe[k] + ts * d[k];
    if (L->shape == FR__LEAF_DIAGONAL) {
        for (k = 0; k < 3; k++) { v[k] = q[4 + k] * q0[k]; u[k] = q[4 + k] * d[k]; }
    } else {
        v[0] = q[4] * q0[0] + q[7] * q0[1] + q[8] * q0[2];
        v[1] = q[7] * q0[0] + q[5] * q0[1] + q[9] * q0[2];
        v[2] = q[8] * q0[0] + q[9] * q0[1] + q[6] * q0[2];
        u[0] = q[4] * d[0] + q[7] * d[1] + q[8] * d[2];
        u[1] = q[7] * d[0] + q[5] * d[1] + q[9] * d[2];
        u[2] = q[8] * d[0] + q[9] * d[1] + q[6] * d[2];
    }
    c[0] = q[0] + (q0[0] * (q[1] + v[0]) + q0[1] * (q[2] + v[1]) + q0[2] * (q[3] + v[2]));
    if (culled) { *sg = fr__sgn(c[0]); return 0; }
    c[2] = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    c[1] = (q[1] * d[0] + q[2] * d[1] + q[3] * d[2]) + 2.0 * (q0[0] * u[0] + q0[1] * u[1] + q0[2] * u[2]);
    s0 = R->t0 - ts;
    s1 = R->t1 - ts;
    m = fabs(c[0]) > fabs(c[1]) ? fabs(c[0]) : fabs(c[1]);
    if (fabs(c[2]) > m) m = fabs(c[2]);
    if (!(m - m == 0)) return -1;
    if (m == 0) { *sg = 0; return 0; }
    if (!(m < FR__QUAD_BIG && m > FR__QUAD_SMALL)) return fr__poly_leaf(c, fr__tpoly_trim(c, 2), s0, s1, ts, 0, cand, sg);
    {
        /* Most leaves have no root in the segment. That is certain, with no
           square root or division, when g(s0) and g(s1) share a sign by
           more than 8x their Horner error and either g' keeps its sign
           over the segment (no vertex inside) or the ends' sign is the
           opposite of c2's (the vertex, where g has the sign of -c2 if
           there are two roots, is then beyond both roots' reach). Roots
           computed below are within ulps of the true ones, so they would
           lie outside the segment as well. */
        double g0 = c[0] + s0 * (c[1] + s0 * c[2]), g1 = c[0] + s1 * (c[1] + s1 * c[2]);
        double e0 = 8.0 * 4.0 * FR__U * (fabs(c[0]) + fabs(s0) * (fabs(c[1]) + fabs(s0) * fabs(c[2])));
        double e1 = 8.0 * 4.0 * FR__U * (fabs(c[0]) + fabs(s1) * (fabs(c[1]) + fabs(s1) * fabs(c[2])));
        if ((g0 > e0 && g1 > e1) || (g0 < -e0 && g1 < -e1)) {
            double p0 = c[1] + 2.0 * c[2] * s0, p1 = c[1] + 2.0 * c[2] * s1;
            if ((p0 > 0 && p1 > 0) || (p0 < 0 && p1 < 0) || (g0 > 0) != (c[2] > 0)) { *sg = fr__sgn(g0); return 0; }
        }
    }
    if (c[2] == 0) {
        if (c[1] == 0) { *sg = fr__sgn(c[0]); return 0; }
        r[0] = -c[0] / c[1];
        n = 1;
        lead = c[1];
    } else {
        double p = c[1] * c[1], dp = fma(c[1], c[1], -p), c4 = 4.0 * c[2], qq = c4 * c[0], dq = fma(c4, c[0], -qq);
        double D = (p - qq) + (dp - dq), h;
        lead = c[2];
        if (!(D > 0)) { *sg = fr__sgn(lead); return 0; }
        h = -0.5 * (c[1] + copysign(sqrt(D), c[1]));
        r[0] = h / c[2];
        r[1] = c[0] / h;
        if (r[0] > r[1]) { double x = r[0]; r[0] = r[1]; r[1] = x; }
        n = 2;
    }
    for (k = 0; k < n; k++) after += r[k] > s0;
    *sg = (after & 1) ? -fr__sgn(lead) : fr__sgn(lead);
    for (k = 0; k < n; k++)
        if (r[k] > s0 && r[k] <= s1) cand[cnt++] = ts + r[k];
    return cnt;
}


/* Nodes whose solid box the segment misses are outside (-1) throughout:
   their bits into *force; the leaves and boxed nodes only they reach need
   no work (their bits into *skip, and nodes into a mask of their own:
   top-down from the shape, so a node inside a missed one is not even
   tested). */
static void fr__prep_cull_nodes(fr__ray_t *R, const fr__csg_node_t *N, unsigned int nn, unsigned long long *force,
                                unsigned long long *skip)
{
    unsigned long long gone = 0;
    unsigned int i;
    fr__ray_inv(R);
    for (i = nn; i-- > 0;) {
        if (!N[i].bit || (gone & N[i].bit)) continue;
        if (!fr__slab_meets(R, N[i].box, R->t0, R->t1)) {
            *force |= N[i].bit;
            *skip |= N[i].leaf_mask;
            gone |= N[i].node_mask;
        }
    }
}

/* ANALYTIC on a prepared CSG model (paper §3.1.1): every leaf's crossings
   of the segment, sorted; a candidate is the hit where the shape's sign
   differs between just before and just after it -- within the same
   FR__CSG_SIGN_ULPS bracket as fr__trace_analytic -- found by flipping the
   sign of each crossing's leaf (v_lo: crossings before the bracket, v_hi:
   up to its end) and evaluating the boolean tree. *leaf and *orient give
   the normal: the hit leaf's gradient, times -1 where the shape's sign
   rises with the leaf's, +1 where it falls (0: unknown, use AD). Returns
   FR_ERR_NOT_POLYNOMIAL when a leaf overflows on this ray (the caller then
   traces without the prepared model). */
static fr_result_t fr__trace_prepared_csg(fr__ray_t *R, const fr__trace_mem_t *mem, int *found, double *t_hit,
                                          double *t_err, unsigned int *leaf, int *orient)
{
    const fr_prepared_t *Pp = R->prep;
    const fr_tape_t *t = R->tape;
    fr__leaf_t *L;
    fr__csg_node_t *N;
    fr__tp_t *prog;
    unsigned int nl = Pp->n_leaves, nn = Pp->n_nodes, j;
    double *cand = mem->cand, dd, inv_dd, ts = 0;
    unsigned int *cl = mem->cleaf;
    signed char *vlo = mem->sgn, *vhi = mem->sgn + nl + nn;
    int nc = 0, k;
    unsigned long long force = 0, skip = 0;
    fr__prep_layout(nl, nn, Pp->n_prog, &L, &N, &prog, Pp->mem);
    *found = 0;
    *orient = 0;
    dd = R->d[0] * R->d[0] + R->d[1] * R->d[1] + R->d[2] * R->d[2];
    inv_dd = 1.0 / dd;
    if (((const fr__prep_head_t *)Pp->mem)->n_boxed_nodes) fr__prep_cull_nodes(R, N, nn, &force, &skip);
    if (Pp->n_prog) { /* the Taylor program of the leaves that are not quadrics */
        double ob[3];
        ts = -(R->o[0] * R->d[0] + R->o[1] * R->d[1] + R->o[2] * R->d[2]) * inv_dd;
        if (!(ts >= R->t0)) ts = R->t0;
        if (!(ts <= R->t1)) ts = R->t1;
        for (k = 0; k < 3; k++) ob[k] = R->o[k] + ts * R->d[k];
        fr__prog_run(t, prog, Pp->n_prog, ob, R->d, mem->taylor, NULL);
    }
    for (j = 0; j < nl; j++) {
        const fr__leaf_t *lf = &L[j];
        int culled = 0, sg = 0, m;
        if (skip && j < 64 && ((skip >> j) & 1u)) { vlo[j] = vhi[j] = 0; continue; } /* only missed nodes use it */
        if (lf->boxed) {
            fr__ray_inv(R);
            culled = !fr__slab_meets(R, lf->box, R->t0, R->t1);
        }
        if (lf->quadric) m = fr__quadric_leaf(lf, R, inv_dd, culled, cand + nc, &sg);
        else {
            const double *c = mem->taylor + (size_t)lf->slot * FR__TAYLOR_N;
            int dg = fr__checked_degree(c, lf->degree, FR__TRACE_MIN_COEF);
            m = dg < 0 ? -1 : fr__poly_leaf(c, dg, R->t0 - ts, R->t1 - ts, ts, culled, cand + nc, &sg);
        }
        if (m < 0) return FR_ERR_NOT_POLYNOMIAL;
        if (!culled) R->iters++;
        if (m == 0 && sg != 0 && lf->decides[sg > 0] && (force & lf->needs[sg > 0]) == lf->needs[sg > 0]) {
            R->evals += j + 1; /* the shape keeps one sign: no crossing can be the hit */
            return FR_OK;
        }
        for (k = 0; k < m; k++) cl[nc + k] = j;
        nc += m;
        vlo[j] = vhi[j] = (signed char)sg;
    }
    R->evals += nl;
    {
        fr__csg_walk_t W;
        int glo, ghi, kh;
        double dt;
        memset(&W, 0, sizeof W);
        W.nodes = N; W.nn = nn; W.nl = nl; W.force = force;
        kh = fr__csg_walk(R, &W, cand, cl, nc, vlo, vhi, &glo, &ghi, &dt);
        if (kh >= 0) {
            unsigned int lf = cl[kh];
            *found = 1;
            *t_hit = cand[kh];
            *t_err = dt;
            *leaf = lf;
            if (L[lf].quadric && vlo[lf] * vhi[lf] < 0) *orient = (vhi[lf] > vlo[lf]) == (ghi > glo) ? -1 : 1;
        }
    }
    return FR_OK;
}

/* The normal of a prepared quadric leaf at p: orient times its gradient
   b + 2 A (p - e), unit; 0 if it vanishes. */
static int fr__quadric_normal(const fr__leaf_t *L, int orient, const double p[3], double nrm[3])
{
    const double *q = L->q;
    double x = p[0] - L->e[0], y = p[1] - L->e[1], z = p[2] - L->e[2], g[3], len;
    int k;
    g[0] = q[1] + 2.0 * (q[4] * x + q[7] * y + q[8] * z);
    g[1] = q[2] + 2.0 * (q[7] * x + q[5] * y + q[9] * z);
    g[2] = q[3] + 2.0 * (q[8] * x + q[9] * y + q[6] * z);
    len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (!(len > 0 && len < HUGE_VAL)) return 0;
    for (k = 0; k < 3; k++) nrm[k] = orient * g[k] / len;
    return 1;
}

/* The |grad f| bound the marching methods use: desc's, else the tape's. */
static double fr__trace_lipschitz(const fr_tape_t *t, const fr_trace_desc_t *desc)
{
    return desc->lipschitz > 0 ? desc->lipschitz : t->lipschitz;
}

/* fr_trace's arguments: FR_OK when they make a ray query (a NULL desc
   stands for the zero one), else FR_ERR_INVALID_ARG. */
static fr_result_t fr__trace_args(const double o[3], const double d[3], double t0, double t1, const fr_trace_desc_t *desc)
{
    /* x - x is 0 for finite x, NaN for infinities and NaN: one test for all six */
    if (!((o[0] - o[0]) + (o[1] - o[1]) + (o[2] - o[2]) + (d[0] - d[0]) + (d[1] - d[1]) + (d[2] - d[2]) == 0))
        return FR_ERR_INVALID_ARG;
    if (!(t0 <= t1) || (d[0] == 0 && d[1] == 0 && d[2] == 0) || (unsigned int)desc->method >= (unsigned int)FR_METHOD_COUNT_)
        return FR_ERR_INVALID_ARG;
    return FR_OK;
}

/* Clips R's segment to the solid's box: desc->bounds, the prepared model's
   box, or the prepared model's padded box when it is the same box (or the
   only one). 0 when the ray misses the box: rays that miss cost only this. */
static int fr__trace_clip(fr__ray_t *R, const fr_trace_desc_t *desc)
{
    const double *b = desc->bounds;
    if (R->prep && R->prep->has_box &&
        (!b || (b[0] == R->prep->box[0] && b[1] == R->prep->box[1] && b[2] == R->prep->box[2] && b[3] == R->prep->box[3] &&
                b[4] == R->prep->box[4] && b[5] == R->prep->box[5])))
        return fr__clip_padded(R, ((const fr__prep_head_t *)R->prep->mem)->box);
    if (b && !fr__clip_box(R, b)) return 0;
    return !(R->prep && R->prep->has_box && !fr__clip_box(R, R->prep->box));
}

/* R's iteration cap, t tolerance (desc->tol, see fr_trace_desc_t),
   footprint and the rest of its state, for every method but the prepared
   CSG path. */
static void fr__trace_settings(fr__ray_t *R, const fr_trace_desc_t *desc, double t0, double t1)
{
    /* an infinite end counts as 0 here: the finite one sets the scale */
    double a0 = fabs(t0) < HUGE_VAL ? fabs(t0) : 0.0, a1 = fabs(t1) < HUGE_VAL ? fabs(t1) : 0.0;
    R->max_iters = desc->max_iters ? desc->max_iters : FR__TRACE_MAX_ITERS;
    if (desc->tol > 0) R->tol = desc->tol;
    else if (desc->tol < 0) R->tol = 4.0 * FR__U * (a0 > a1 ? a0 : a1);
    else R->tol = FR__TRACE_TOL_REL * (t1 - t0 < HUGE_VAL ? t1 - t0 : 1.0 + (t0 > -HUGE_VAL ? a0 : a1));
    if (!(R->tol > 0)) R->tol = FR__U;
    R->footprint = desc->footprint > 0 && desc->footprint < HUGE_VAL ? desc->footprint : 0.0;
    R->pc = R->pm = NULL;
    R->pdeg = R->mdeg = -1;
    R->ts = R->rho = R->drho = 0.0;
    R->newton = R->mono = 0;
    R->gam = R->dgam = 0.0;
    R->any_hit = desc->any_hit;
}

#ifndef FR_NO_INTERVAL
/* INTERVAL on a polynomial tape: the ray polynomial g(ts + s) with its
   rounding bounds (the centred form of g, fr__poly_range) and, for degree
   1 and up, g' for the monotone hand-over and interval Newton. Leaves
   R->pc NULL when the tape is not a polynomial in t or too long for the
   bound to stay useful. */
static void fr__interval_poly_form(fr__ray_t *R, fr__trace_mem_t *mem, const fr_trace_desc_t *desc)
{
    const fr_tape_t *t = R->tape;
    double nr = 160.0 * (double)t->n_code; /* roundings per coefficient, see fr__poly_range */
    unsigned int out = t->outputs[0];
    int k;
    if (!(nr * FR__U < 1e-3)) return;
    R->ts = fr__analytic_expand(R, mem, 1);
    if (mem->deg[out] < 0) return;
    R->pc = mem->taylor + (size_t)out * FR__TAYLOR_N;
    R->pm = mem->taylor_mag + (size_t)out * FR__TAYLOR_N;
    R->pdeg = mem->deg[out];
    R->mdeg = mem->deg_mag[out];
    R->rho = 2.0 * fr__gamma(nr);
    if (R->mdeg < R->pdeg) R->pc = NULL; /* cannot happen; stay safe */
    if (R->pc) R->gam = fr__gamma(2.0 * R->mdeg + 2.0);
    if (R->pc && R->mdeg >= 1) {
        /* g' = sum (k+1) c_{k+1} s^k; the products by k+1 round once more */
        for (k = 0; k < R->mdeg; k++) {
            R->dc[k] = k + 1 <= R->pdeg ? (double)(k + 1) * R->pc[k + 1] : 0.0;
            R->dm[k] = (double)(k + 1) * R->pm[k + 1];
        }
        R->drho = R->rho + 4.0 * FR__U;
        R->dgam = fr__gamma(2.0 * (R->mdeg - 1) + 2.0);
        R->newton = desc->interval_newton;
        R->mono = 1;
    }
}
#endif

/* The hit record of ray (o, d) traced as R: the point o + t d and, on a
   hit, the normal (the prepared model's closed forms where they apply,
   else desc->normal's mode); leaf and orient name the prepared CSG leaf
   hit (orient 0: none). */
static void fr__trace_answer(fr__ray_t *R, const fr__trace_mem_t *mem, const fr_trace_desc_t *desc, const double o[3],
                             const double d[3], fr_method_t m, int found, double t_hit, double t_err, unsigned int leaf,
                             int orient, fr_hit_t *hit)
{
    int k;
    hit->hit = found;
    hit->method = m;
    hit->t = found ? t_hit : 0.0;
    hit->t_err = found ? t_err : 0.0;
    for (k = 0; k < 3; k++) { hit->point[k] = found ? o[k] + t_hit * d[k] : 0.0; hit->normal[k] = 0.0; }
    if (found) {
        fr__leaf_t *lv = NULL;
        if (orient) fr__prep_layout(R->prep->n_leaves, R->prep->n_nodes, R->prep->n_prog, &lv, NULL, NULL, R->prep->mem);
        if (orient && desc->normal == FR_NORMAL_AD && fr__quadric_normal(&lv[leaf], orient, hit->point, hit->normal))
            R->evals++;
        else if (R->prep && R->prep->kind == FR_PREPARED_POLY && desc->normal == FR_NORMAL_AD &&
                 fr__prog_normal(R->tape, R->prep, hit->point, (double *)mem->eval, hit->normal))
            R->evals++;
        else
            fr__normal(R, desc, hit->point, hit->normal);
    }
    hit->evals = R->evals;
    hit->iterations = R->iters;
}

/* FR_METHOD_AUTO resolved: analytic if every shape path ends in
   polynomial leaves (*cnt: fr__csg_mark's count, -2 for a polynomial
   shape), else intervals on a finite segment where the tape has them,
   else stepping. */
static fr_method_t fr__auto_method(const fr__ray_t *R, const fr__trace_mem_t *mem, int *cnt)
{
    const fr_tape_t *t = R->tape;
    fr_method_t m;
    *cnt = mem->deg[t->outputs[0]] >= 0 ? -2 : fr__csg_mark(t, mem);
    m = *cnt == -1 ? FR_METHOD_STEP : FR_METHOD_ANALYTIC;
#ifndef FR_NO_INTERVAL
    if (m == FR_METHOD_STEP && !(t->flags & FR_TAPE_NO_INTERVAL) && R->t1 - R->t0 < HUGE_VAL) m = FR_METHOD_INTERVAL;
#endif
    return m;
}

/* The first root along R by method m (resolved), with what each method
   needs checked: a gradient for Newton steps, a step length or Lipschitz
   bound (or a finite segment, stepped in 256) for stepping, intervals and
   a finite segment for INTERVAL, a Lipschitz bound for sphere tracing. */
static fr_result_t fr__trace_method(fr__ray_t *R, fr__trace_mem_t *mem, const fr_trace_desc_t *desc, fr_method_t m,
                                    double ts, int cnt, int *found, double *t_hit, double *t_err)
{
    const fr_tape_t *t = R->tape;
    double step = desc->step, L = fr__trace_lipschitz(t, desc);
    switch (m) {
    case FR_METHOD_ANALYTIC:
        return fr__trace_analytic(R, mem, ts, cnt, found, t_hit, t_err);
    case FR_METHOD_STEP:
        if (desc->refine == FR_REFINE_NEWTON && (t->flags & FR_TAPE_NO_GRADIENT)) return FR_ERR_NO_GRADIENT;
        if (step <= 0 && !(L > 0 && L < HUGE_VAL)) {
            if (!(R->t1 - R->t0 < HUGE_VAL)) return FR_ERR_INVALID_ARG;
            step = (R->t1 - R->t0) / 256.0;
        }
        *found = fr__trace_step(R, step, desc->refine, L, t_hit, t_err);
        return FR_OK;
    case FR_METHOD_INTERVAL:
#ifndef FR_NO_INTERVAL
        if (t->flags & FR_TAPE_NO_INTERVAL) return FR_ERR_NO_INTERVAL;
        if (!(R->t1 - R->t0 < HUGE_VAL)) return FR_ERR_INVALID_ARG;
        if (!desc->plain_intervals && !desc->no_poly_range) fr__interval_poly_form(R, mem, desc);
        return fr__trace_interval(R, desc->plain_intervals, !desc->no_prune && !R->pc, mem->prune, found, t_hit, t_err);
#else
        return FR_ERR_NO_INTERVAL;
#endif
    case FR_METHOD_SPHERE:
        if (!(L > 0 && L < HUGE_VAL)) return FR_ERR_NO_LIPSCHITZ;
        *found = fr__trace_sphere(R, L, desc->over_relax > 0 ? desc->over_relax : FR__SPHERE_OMEGA, t_hit, t_err);
        return FR_OK;
    default:
        return FR_ERR_INVALID_ARG;
    }
}

/* fr_trace's body; desc is never NULL (fr_trace stands the defaults in). */
static FR__NOINLINE fr_result_t fr__trace(const fr_tape_t *t, const double o[3], const double d[3], double t0, double t1,
                            const fr_trace_desc_t *desc, void *scratch, fr_hit_t *hit)
{
    fr__trace_mem_t mem;
    fr__ray_t R;
    fr_method_t m;
    fr_result_t e = FR_OK;
    double t_hit = 0, t_err = 0, ts = 0;
    int found = 0, k, cnt = -2, orient = 0;
    unsigned int leaf = 0;
    if (!t || !o || !d || !scratch || !hit || t->n_code == 0) return FR_ERR_INVALID_ARG;
    if ((e = fr__trace_args(o, d, t0, t1, desc)) != FR_OK) return e;
    if (desc->method == FR_METHOD_SPHERE && !(fr__trace_lipschitz(t, desc) > 0 && fr__trace_lipschitz(t, desc) < HUGE_VAL))
        return FR_ERR_NO_LIPSCHITZ; /* whatever the ray: also one that misses the bounds */
    hit->hit = 0;
    hit->method = m = desc->method;
    hit->t = hit->t_err = 0.0;
    for (k = 0; k < 3; k++) hit->point[k] = hit->normal[k] = 0.0;
    hit->evals = hit->iterations = 0;
    for (k = 0; k < 3; k++) { R.o[k] = o[k]; R.d[k] = d[k]; }
    R.t0 = t0; R.t1 = t1;
    R.have_inv = 0;
    R.prep = desc->prepared && desc->prepared->tape == t && desc->prepared->kind != FR_PREPARED_NONE ? desc->prepared : NULL;
    if (!fr__trace_clip(&R, desc)) return FR_OK;
    fr__trace_layout(t, scratch, &mem);
    R.tape = t;
    R.eval = mem.eval;
    R.evals = R.iters = 0;
    R.capped = 0;
    /* the prepared CSG path needs none of the set-up below */
    if (R.prep && R.prep->kind == FR_PREPARED_CSG && (m == FR_METHOD_AUTO || m == FR_METHOD_ANALYTIC)) {
        e = fr__trace_prepared_csg(&R, &mem, &found, &t_hit, &t_err, &leaf, &orient);
        if (e == FR_OK) { m = FR_METHOD_ANALYTIC; goto done; }
        /* a leaf overflowed on this ray: trace it without the prepared model */
        e = FR_OK;
        found = 0;
        orient = 0;
    }
    fr__trace_settings(&R, desc, t0, t1);
    R.prep = R.prep && R.prep->kind == FR_PREPARED_POLY ? R.prep : NULL;
    if (m == FR_METHOD_AUTO || m == FR_METHOD_ANALYTIC) ts = fr__analytic_expand(&R, &mem, 0);
    if (m == FR_METHOD_AUTO) m = fr__auto_method(&R, &mem, &cnt);
    e = fr__trace_method(&R, &mem, desc, m, ts, cnt, &found, &t_hit, &t_err);
done:
    if (e != FR_OK) return e;
    fr__trace_answer(&R, &mem, desc, o, d, m, found, t_hit, t_err, leaf, orient, hit);
    if (!found && R.capped) { /* not a miss: the rest of the segment is unknown */
        hit->t = 0.5 * R.undecided_lo + 0.5 * R.undecided_hi;
        hit->t_err = 0.5 * R.undecided_hi - 0.5 * R.undecided_lo;
        return FR_ERR_ITERATIONS;
    }
    return FR_OK;
}

/* Directions whose largest component lies outside [1/FR__DIR_UNIT_RANGE,
   FR__DIR_UNIT_RANGE] are traced as d 2^k with t in units of 2^-k (k puts
   the largest component in [1, 2)): exact scalings, the same ray and the
   same points, but the ray polynomial's coefficients (|d|^j up to degree
   FR_POLY_MAX_DEGREE) neither overflow nor underflow -- to subnormals, or
   to 0, which would lower the degree unseen -- and the marching steps'
   |d| neither. The t-valued settings (tol, step) go with t. Directions
   inside the range are traced as given, bit for bit as before. */
#define FR__DIR_UNIT_RANGE 65536.0
static fr_result_t fr__trace_any_length(const fr_tape_t *t, const double o[3], const double d[3], double t0, double t1,
                                        const fr_trace_desc_t *desc_in, void *scratch, fr_hit_t *hit)
{
    fr_trace_desc_t D;
    double ds[3], m;
    int k, ex;
    if (!d || !hit) return fr__trace(t, o, d, t0, t1, desc_in, scratch, hit);
    m = fabs(d[0]);
    if (fabs(d[1]) > m) m = fabs(d[1]);
    if (fabs(d[2]) > m) m = fabs(d[2]);
    if (!(m > 0 && m < HUGE_VAL) || (m >= 1 / FR__DIR_UNIT_RANGE && m <= FR__DIR_UNIT_RANGE))
        return fr__trace(t, o, d, t0, t1, desc_in, scratch, hit);
    (void)frexp(m, &ex);
    for (k = 0; k < 3; k++) ds[k] = ldexp(d[k], 1 - ex);
    D = *desc_in;
    if (D.tol > 0) D.tol = ldexp(D.tol, ex - 1);
    if (D.step > 0) D.step = ldexp(D.step, ex - 1);
    {
        fr_result_t e = fr__trace(t, o, ds, ldexp(t0, ex - 1), ldexp(t1, ex - 1), &D, scratch, hit);
        if (e == FR_OK || e == FR_ERR_ITERATIONS) { /* other errors leave *hit as fr__trace left it */
            hit->t = ldexp(hit->t, 1 - ex);
            hit->t_err = ldexp(hit->t_err, 1 - ex);
        }
        return e;
    }
}

FR_DEF fr_result_t fr_trace(const fr_tape_t *t, const double o[3], const double d[3], double t0, double t1,
                            const fr_trace_desc_t *desc_in, void *scratch, fr_hit_t *hit)
{
    fr_trace_desc_t zero_desc;
    if (!desc_in) { /* the defaults: the one place a NULL desc is read */
        memset(&zero_desc, 0, sizeof zero_desc);
        desc_in = &zero_desc;
    }
    FR__IN_FP_ENV(fr_result_t, fr__trace_any_length(t, o, d, t0, t1, desc_in, scratch, hit));
}

/* ==== [end section: trace] ==== */


#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_FR_IMPLEMENTATION_DONE */
#endif /* FR_IMPLEMENTATION */

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
