/* tests/test_rounded_parallel.c — rounded_edges.h's build on the host's
   threads (re_scene_desc_t.parallel, THREADS in the header), objects
   spread over tasks and one object's steps split into tasks: the scene
   is the serial build's byte for byte, whatever the task count and the
   order the host runs them in; reports are the same per object; a failure
   names the same object, element and message as on one thread; the sizes
   agree; the objects are spread evenly; a failing allocator leaves no
   leak. The allocator hook (test_count_alloc.h) fills every block with
   one byte pattern (so block bytes compare with memcmp) and is called
   from the tasks' threads. */
#include "test_count_alloc.h"

#define RE_MALLOC(sz, ctx) ta_malloc((sz), (ctx))
#define RE_FREE(p, ctx) ta_free((p), (ctx))
/* The kd-tree's node capacity, when not 0 (one_object_kd_near_capacity):
   a tree built on threads then runs into it and is built again on one
   thread. */
static unsigned tp_node_cap;
#define RE__KD_NODE_CAP(refs) (tp_node_cap ? tp_node_cap : 2u * (refs))
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"

/* ---- hosts ---------------------------------------------------------------- */

typedef struct tp_host_t {
    int reverse;     /* run the tasks one after another, last first */
    unsigned count;  /* the count the build asked for */
    int skip;        /* a broken host: never runs task skip - 1 */
} tp_host_t;

typedef struct tp_call_t {
    re_task_fn task;
    void *ctx;
    unsigned i;
} tp_call_t;

static void *tp_thread(void *p)
{
    tp_call_t *c = (tp_call_t *)p;
    c->task(c->ctx, c->i);
    return NULL;
}

/* One thread per task (or all on this thread, last first). */
static void tp_parallel(void *user, unsigned count, re_task_fn task, void *task_ctx)
{
    tp_host_t *h = (tp_host_t *)user;
    pthread_t th[RE_MAX_BUILD_TASKS];
    tp_call_t call[RE_MAX_BUILD_TASKS];
    unsigned i;
    h->count = count;
    if (h->reverse) {
        for (i = count; i-- > 0;)
            if ((int)i + 1 != h->skip) task(task_ctx, i);
        return;
    }
    for (i = 0; i < count; i++) {
        call[i].task = task, call[i].ctx = task_ctx, call[i].i = i;
        pthread_create(&th[i], NULL, tp_thread, &call[i]);
    }
    for (i = 0; i < count; i++) pthread_join(th[i], NULL);
}

/* ---- reports, collected under a lock -------------------------------------- */

typedef struct tp_rep_t {
    int kind;
    unsigned object;
    long long e1, e2;
    double value;
    char msg[96];
} tp_rep_t;

typedef struct tp_reps_t {
    pthread_mutex_t mu;
    tp_rep_t r[4096];
    int n;
} tp_reps_t;

static void tp_report(void *u, const re_report_t *r)
{
    tp_reps_t *R = (tp_reps_t *)u;
    pthread_mutex_lock(&R->mu);
    if (R->n < 4096) {
        tp_rep_t *x = &R->r[R->n++];
        memset(x, 0, sizeof *x);
        x->kind = (int)r->kind, x->object = r->object, x->e1 = r->element, x->e2 = r->element2, x->value = r->value;
        snprintf(x->msg, sizeof x->msg, "%s", r->message);
    }
    pthread_mutex_unlock(&R->mu);
}

/* ---- the scene: objects of unequal size and kind --------------------------- */

#define TP_OBJECTS 14
typedef struct tp_scene_t {
    tm_mesh_t m[TP_OBJECTS];
    re_mesh_t mesh[TP_OBJECTS];
} tp_scene_t;

static tm_poly_t tp_poly; /* tm_random_hull's planes (unused here) */

static void tp_scene(tp_scene_t *S)
{
    t_rng_t rng = {2026};
    double lo[3] = {-0.5, -0.3, -0.2}, hi[3] = {0.5, 0.3, 0.2};
    int i;
    memset(S, 0, sizeof *S);
    for (i = 0; i < TP_OBJECTS; i++) {
        tm_mesh_t *m = &S->m[i];
        double r = 0.03;
        switch (i % 5) {
        case 0: tm_icosphere(m, 1 + i % 3, 1.0), r = 0.01; break;
        case 1: tm_random_hull(&rng, 10 + 4 * (i % 4), 0.8, 1.2, m, &tp_poly); break;
        case 2:
            tm_box(m, lo, hi), r = i == 7 ? 0.5 : 0.05; /* object 7: radius clamped, reported */
            if (i == 12) { /* a second box sharing the first one's corner: split per solid (construction step 2a) */
                double hi2[3] = {2 * hi[0] - lo[0], 2 * hi[1] - lo[1], 2 * hi[2] - lo[2]};
                unsigned b = m->nv, i0 = m->ni, j;
                tm_box(m, hi, hi2);
                for (j = i0; j < m->ni; j++)
                    if (m->idx[j] == b) m->idx[j] = 7;
            }
            break;
        case 3: /* an open box (no top): boundary edges and mixed vertices, reported */
            tm_box(m, lo, hi), m->ni -= 6;
            break;
        default: tm_icosphere(m, 3, 0.5), r = 0.004; break;
        }
        memset(&S->mesh[i], 0, sizeof S->mesh[i]);
        S->mesh[i].positions = m->v, S->mesh[i].vertex_count = m->nv;
        S->mesh[i].indices = m->idx, S->mesh[i].index_count = m->ni, S->mesh[i].radius = r;
    }
}

static void tp_scene_free(tp_scene_t *S)
{
    int i;
    for (i = 0; i < TP_OBJECTS; i++) tm_free(&S->m[i]);
}

static re_scene_desc_t tp_desc(const re_mesh_t *mesh, unsigned n, tp_host_t *host, unsigned threads, ta_alloc_t *al)
{
    re_scene_desc_t d;
    memset(&d, 0, sizeof d);
    d.objects = mesh, d.object_count = n, d.alloc_ctx = al;
    if (host) d.parallel = tp_parallel, d.parallel_user = host, d.threads = threads;
    return d;
}


/* The same stats; object by object, the same block bytes (every block
   starts as 0xA5, so unwritten padding compares too), and the same answers
   to the same rays. */
static void tp_same_scene(const re_scene_t *a, const re_scene_t *b, const tp_scene_t *S, unsigned long long seed)
{
    unsigned o, n_blocks = 0, n_answers = 0;
    t_rng_t rng;
    rng.s = seed;
    if (!T_CHECK(a && b) || !T_INT_EQ(a->n_objects, b->n_objects)) return;
    T_INT_EQ(memcmp(&a->stats, &b->stats, sizeof a->stats), 0);
    for (o = 0; o < a->n_objects; o++) {
        const re__object_t *x = &a->objects[o], *y = &b->objects[o];
        const tm_mesh_t *m = &S->m[o];
        int q;
        if (!T_INT_EQ(x->bytes, y->bytes)) continue;
        n_blocks += x->bytes == 0 || memcmp(x->block, y->block, x->bytes) == 0;
        for (q = 0; q < 200; q++) {
            unsigned t = (unsigned)(t_rng_u64(&rng) % (m->ni / 3)), k;
            double u = t_rng_unit(&rng) * 0.5, v = t_rng_unit(&rng) * 0.5, p[3], d[3], org[3];
            const double *A = m->v + 3 * m->idx[3 * t], *B = m->v + 3 * m->idx[3 * t + 1], *C = m->v + 3 * m->idx[3 * t + 2];
            re_hit_t h1, h2;
            for (k = 0; k < 3; k++) p[k] = A[k] + u * (B[k] - A[k]) + v * (C[k] - A[k]), d[k] = t_rng_range(&rng, -1, 1) - 0.5 * p[k];
            for (k = 0; k < 3; k++) org[k] = p[k] - d[k];
            re_query(a, org, d, o, t, 1.0, &h1);
            re_query(b, org, d, o, t, 1.0, &h2);
            n_answers += h1.kind == h2.kind && h1.t == h2.t && !memcmp(h1.normal, h2.normal, sizeof h1.normal) &&
                         h1.feature == h2.feature && h1.feature_index == h2.feature_index;
        }
    }
    T_INT_EQ(n_blocks, a->n_objects);
    T_INT_EQ(n_answers, 200 * a->n_objects);
}

/* 2, 3, 8 and 100 tasks on threads, and 5 run last first on one thread: the
   serial scene byte for byte. More tasks than objects count as one per
   object. */
static void parallel_build_equals_serial(void)
{
    static tp_scene_t S;
    re_scene_desc_t d;
    re_scene_t *s0 = NULL;
    re_diag_t dg;
    static const unsigned threads[] = {2, 3, 8, 100, 5};
    unsigned k;
    tp_scene(&S);
    d = tp_desc(S.mesh, TP_OBJECTS, NULL, 0, NULL);
    if (!T_INT_EQ(re_build(&d, &s0, &dg), RE_OK)) { tp_scene_free(&S); return; }
    T_GT(s0->stats.rounded_edges, 1000);
    T_INT_EQ(re_sphere_count(s0, 12), 16); /* both boxes of object 12, split at their common corner */
    for (k = 0; k < sizeof threads / sizeof *threads; k++) {
        tp_host_t host = {0, 0, 0};
        ta_alloc_t *al = ta_alloc_new(0);
        re_scene_t *s1 = NULL;
        host.reverse = k == 4;
        d = tp_desc(S.mesh, TP_OBJECTS, &host, threads[k], al);
        T_INT_EQ(re_build(&d, &s1, &dg), RE_OK);
        T_INT_EQ(host.count, threads[k] < TP_OBJECTS ? threads[k] : TP_OBJECTS);
        tp_same_scene(s0, s1, &S, 40 + k);
        re_free(s1);
        T_INT_EQ(al->live, 0);
        ta_alloc_delete(al);
    }
    /* threads 0 or 1, or no parallel hook: the calling thread */
    {
        tp_host_t host = {0, 0, 0};
        re_scene_t *s1 = NULL;
        d = tp_desc(S.mesh, TP_OBJECTS, &host, 1, NULL);
        T_INT_EQ(re_build(&d, &s1, &dg), RE_OK);
        T_INT_EQ(host.count, 0);
        tp_same_scene(s0, s1, &S, 50);
        re_free(s1);
    }
    re_free(s0);
    tp_scene_free(&S);
}

/* The same reports per object, in the same order within an object (the
   objects' reports interleave across threads). */
static void parallel_reports_match_serial(void)
{
    static tp_scene_t S;
    static tp_reps_t R0, R1;
    re_scene_desc_t d;
    re_scene_t *s = NULL;
    re_diag_t dg;
    int i, n_same = 0;
    unsigned objects_reported[TP_OBJECTS] = {0}, n_objects = 0;
    tp_host_t host = {0, 0, 0};
    tp_scene(&S);
    pthread_mutex_init(&R0.mu, NULL), pthread_mutex_init(&R1.mu, NULL);
    R0.n = R1.n = 0;
    d = tp_desc(S.mesh, TP_OBJECTS, NULL, 0, NULL);
    d.report = tp_report, d.report_user = &R0;
    T_INT_EQ(re_build(&d, &s, &dg), RE_OK);
    re_free(s), s = NULL;
    d = tp_desc(S.mesh, TP_OBJECTS, &host, 4, NULL);
    d.report = tp_report, d.report_user = &R1;
    T_INT_EQ(re_build(&d, &s, &dg), RE_OK);
    re_free(s);
    T_GT(R0.n, 20);
    T_LT(R0.n, 4096);
    if (T_INT_EQ(R1.n, R0.n)) {
        /* the serial reports come object by object; the parallel ones
           picked out object by object must give the same sequence */
        static tp_rep_t sorted[4096];
        int o, n = 0;
        for (o = 0; o < TP_OBJECTS; o++)
            for (i = 0; i < R1.n; i++)
                if (R1.r[i].object == (unsigned)o) sorted[n++] = R1.r[i];
        for (i = 0; i < R0.n; i++) {
            n_same += !memcmp(&sorted[i], &R0.r[i], sizeof sorted[i]);
            if (i > 0 && R0.r[i - 1].object > R0.r[i].object) T_FAIL("serial report %d: object %u after %u", i, R0.r[i].object, R0.r[i - 1].object);
        }
        T_INT_EQ(n_same, R0.n);
    }
    for (i = 0; i < R0.n; i++) n_objects += !objects_reported[R0.r[i].object]++;
    T_GE(n_objects, 4); /* open boxes, the clamped box */
    tp_scene_free(&S);
}

/* Two bad objects (5: a NaN vertex, 11: an index out of range): every task
   count reports object 5 with the serial build's element and message, and
   leaves no block behind. */
static void parallel_failure_names_lowest_object(void)
{
    static tp_scene_t S;
    re_scene_desc_t d;
    re_scene_t *s = NULL;
    re_diag_t d0, d1;
    re_result_t r0;
    unsigned k;
    tp_scene(&S);
    S.m[5].v[3 * 2 + 1] = NAN;
    S.m[11].idx[7] = S.m[11].nv + 3;
    d = tp_desc(S.mesh, TP_OBJECTS, NULL, 0, NULL);
    r0 = re_build(&d, &s, &d0);
    T_INT_EQ(r0, RE_ERR_NAN_VERTEX);
    T_INT_EQ(d0.object, 5);
    T_INT_EQ(d0.element, 2);
    for (k = 2; k <= 6; k += 2) {
        tp_host_t host = {0, 0, 0};
        ta_alloc_t *al = ta_alloc_new(0);
        re_sizes_t sz;
        host.reverse = k == 6;
        d = tp_desc(S.mesh, TP_OBJECTS, &host, k, al);
        memset(&d1, 0, sizeof d1);
        T_INT_EQ(re_build(&d, &s, &d1), r0);
        T_CHECK(s == NULL);
        T_INT_EQ(d1.result, d0.result);
        T_INT_EQ(d1.object, d0.object);
        T_INT_EQ(d1.element, d0.element);
        T_INT_EQ(strcmp(d1.message, d0.message), 0);
        memset(&d1, 0, sizeof d1);
        T_INT_EQ(re_build_sizes(&d, &sz, &d1), r0);
        T_INT_EQ(d1.object, 5);
        T_INT_EQ(al->live, 0);
        ta_alloc_delete(al);
    }
    tp_scene_free(&S);
}

/* A host parallel-for that returns without running task 1 of 3 fails the
   build of S's first n objects and the size query by name, and leaves
   nothing allocated. */
static void tp_skipped_task_fails(const tp_scene_t *S, unsigned n)
{
    re_scene_desc_t d;
    re_scene_t *s = NULL;
    re_sizes_t sz;
    re_diag_t dg;
    tp_host_t host = {1, 0, 2};
    ta_alloc_t *al = ta_alloc_new(0);
    d = tp_desc(S->mesh, n, &host, 3, al);
    T_INT_EQ(re_build(&d, &s, &dg), RE_ERR_INVALID_ARG);
    T_CHECK(s == NULL);
    T_CHECK(strstr(dg.message, "without running task 1 of 3") != NULL);
    T_INT_EQ(re_build_sizes(&d, &sz, &dg), RE_ERR_INVALID_ARG);
    T_INT_EQ(dg.result, RE_ERR_INVALID_ARG);
    T_INT_EQ(al->live, 0);
    ta_alloc_delete(al);
}

/* Objects spread over the tasks. */
static void parallel_skipped_task_fails(void)
{
    static tp_scene_t S;
    tp_scene(&S);
    tp_skipped_task_fails(&S, TP_OBJECTS);
    tp_scene_free(&S);
}

/* re_build_sizes() on threads gives the serial sizes, and re_build_into()
   with them the same scene. */
static void parallel_sizes_equal_serial(void)
{
    static tp_scene_t S;
    re_scene_desc_t d;
    re_sizes_t z0, z1;
    re_scene_t *s0 = NULL, *s1 = NULL;
    re_diag_t dg;
    tp_host_t host = {0, 0, 0};
    void *mem, *scratch;
    tp_scene(&S);
    d = tp_desc(S.mesh, TP_OBJECTS, NULL, 0, NULL);
    T_INT_EQ(re_build_sizes(&d, &z0, &dg), RE_OK);
    T_INT_EQ(re_build(&d, &s0, &dg), RE_OK);
    d = tp_desc(S.mesh, TP_OBJECTS, &host, 3, NULL);
    T_INT_EQ(re_build_sizes(&d, &z1, &dg), RE_OK);
    T_INT_EQ(host.count, 3);
    T_INT_EQ(z1.scene_bytes, z0.scene_bytes);
    T_INT_EQ(z1.scratch_bytes, z0.scratch_bytes);
    if (s0) T_INT_EQ(z0.scene_bytes, s0->stats.bytes);
    mem = calloc(1, z1.scene_bytes + 16), scratch = malloc(z1.scratch_bytes);
    if (T_CHECK(mem && scratch)) {
        T_INT_EQ(re_build_into(&d, mem, z1.scene_bytes, scratch, z1.scratch_bytes, &s1, &dg), RE_OK);
        if (s0 && s1) {
            unsigned o, n_same = 0;
            for (o = 0; o < TP_OBJECTS; o++) n_same += s0->objects[o].bytes == s1->objects[o].bytes;
            T_INT_EQ(n_same, TP_OBJECTS);
            T_INT_EQ(memcmp(&s0->stats, &s1->stats, sizeof s0->stats), 0);
        }
    }
    free(mem), free(scratch);
    re_free(s0);
    tp_scene_free(&S);
}

/* The assignment: five equal objects on two tasks go 3 and 2; one large
   object and many small ones put the large one alone; the heaviest task
   carries at most 4/3 of the best split plus one object (the greedy
   largest-first bound) on random sizes. */
static void parallel_tasks_share_the_objects_evenly(void)
{
    static re_mesh_t mesh[300];
    unsigned char owner[300];
    unsigned long long load[RE_MAX_BUILD_TASKS];
    re_scene_desc_t d;
    t_rng_t rng = {9};
    unsigned i, w, it, n_bound = 0;
    memset(mesh, 0, sizeof mesh);
    memset(&d, 0, sizeof d);
    d.objects = mesh;
    for (i = 0; i < 5; i++) mesh[i].index_count = 61440;
    d.object_count = 5;
    if (T_INT_EQ(re__assign_tasks(&d, 2, owner), RE_OK)) {
        unsigned n0 = 0;
        for (i = 0; i < 5; i++) n0 += owner[i] == 0;
        T_INT_EQ(n0, 3);
        T_INT_EQ(owner[0], 0), T_INT_EQ(owner[1], 1);
    }
    mesh[0].index_count = 300000;
    for (i = 1; i < 200; i++) mesh[i].index_count = 36;
    d.object_count = 200;
    if (T_INT_EQ(re__assign_tasks(&d, 4, owner), RE_OK)) {
        unsigned n_with0 = 0;
        for (i = 1; i < 200; i++) n_with0 += owner[i] == owner[0];
        T_INT_EQ(n_with0, 0);
    }
    for (it = 0; it < 200; it++) {
        unsigned k = 2 + (unsigned)(t_rng_u64(&rng) % 7), n = 1 + (unsigned)(t_rng_u64(&rng) % 300);
        unsigned long long sum = 0, big = 0, worst = 0;
        d.object_count = n;
        for (i = 0; i < n; i++) {
            mesh[i].index_count = 3 * (unsigned)(1 + t_rng_u64(&rng) % (it % 2 ? 20000 : 50));
            sum += mesh[i].index_count + 1u;
            if (mesh[i].index_count + 1u > big) big = mesh[i].index_count + 1u;
        }
        if (!T_INT_EQ(re__assign_tasks(&d, k, owner), RE_OK)) break;
        memset(load, 0, sizeof load);
        for (i = 0; i < n; i++) {
            if (owner[i] >= k) T_FAIL("object %u given to task %u of %u", i, owner[i], k);
            else load[owner[i]] += mesh[i].index_count + 1u;
        }
        for (w = 0; w < k; w++) worst = load[w] > worst ? load[w] : worst;
        /* greedy largest-first: worst <= sum / k + the largest object, and
           never worse than the largest object alone when there are fewer objects than tasks */
        n_bound += worst <= sum / k + big && (n > k || worst == big);
    }
    T_INT_EQ(n_bound, 200);
}

/* Every allocation of a build of S's first n objects on 3 threads, and of
   its size query, failing in turn: out of memory, a diagnostic that says
   so, nothing left allocated. Returns how many allocations there were. */
static long tp_each_allocation_fails(const tp_scene_t *S, unsigned n)
{
    re_scene_desc_t d;
    long at, n_calls, n_oom = 0;
    ta_alloc_t *count = ta_alloc_new(0);
    re_scene_t *s = NULL;
    re_diag_t dg;
    tp_host_t host = {0, 0, 0};
    d = tp_desc(S->mesh, n, &host, 3, count);
    T_INT_EQ(re_build(&d, &s, &dg), RE_OK);
    re_free(s), s = NULL;
    n_calls = count->calls;
    ta_alloc_delete(count);
    for (at = 1; at <= n_calls; at++) {
        ta_alloc_t *al = ta_alloc_new(at);
        re_sizes_t sz;
        re_result_t rc;
        d = tp_desc(S->mesh, n, &host, 3, al);
        rc = re_build(&d, &s, &dg);
        if (rc == RE_ERR_OUT_OF_MEMORY) n_oom += s == NULL && dg.result == RE_ERR_OUT_OF_MEMORY && strstr(dg.message, "out of memory") != NULL;
        else {
            re_free(s);
            T_FAIL("allocation %ld failing: %s", at, re_result_string(rc));
        }
        s = NULL;
        rc = re_build_sizes(&d, &sz, &dg);
        T_CHECK(rc == RE_OK || rc == RE_ERR_OUT_OF_MEMORY);
        if (al->live) T_FAIL("allocation %ld failing: %ld blocks left", at, al->live);
        ta_alloc_delete(al);
    }
    T_INT_EQ(n_oom, n_calls);
    return n_calls;
}

/* Six objects on three tasks. */
static void parallel_out_of_memory_leaves_nothing(void)
{
    static tp_scene_t S;
    tp_scene(&S);
    T_GT(tp_each_allocation_fails(&S, 6), 6);
    tp_scene_free(&S);
}

/* ---- one object split into tasks (THREADS) --------------------------------- */

/* One object with work enough to split: an icosphere of `level` (its
   corners, radii and kd-tree go to tasks), then, later in vertex order so
   in the last span of corners, two boxes sharing a corner (step 4 stops
   inside a task and runs again after step 2a), an open box (mixed
   vertices, reported) and a slab thinner than 2r (clamped, reported). */
static void tp_big(tp_scene_t *S, int level)
{
    tm_mesh_t *m = &S->m[0];
    double lo[3] = {2, -0.5, -0.5}, hi[3] = {3, 0.5, 0.5}, lo2[3] = {-3, -0.5, -0.5}, hi2[3] = {-2, 0.5, 0.5};
    double lo3[3] = {-1, -3, 0}, hi3[3] = {1, -2, 0.006};
    unsigned b, i0, j;
    memset(S, 0, sizeof *S);
    tm_icosphere(m, level, 1.0);
    b = m->nv;
    tm_box(m, lo, hi);
    i0 = m->ni;
    tm_box(m, hi, (double[3]){4, 1.5, 1.5});
    for (j = i0; j < m->ni; j++)
        if (m->idx[j] == b + 8) m->idx[j] = b + 7; /* the second box's low corner is the first one's high corner */
    tm_box(m, lo2, hi2), m->ni -= 6;
    tm_box(m, lo3, hi3);
    memset(&S->mesh[0], 0, sizeof S->mesh[0]);
    S->mesh[0].positions = m->v, S->mesh[0].vertex_count = m->nv;
    S->mesh[0].indices = m->idx, S->mesh[0].index_count = m->ni, S->mesh[0].radius = 0.004;
}

/* Levels 4 and 5, each on 2, 3, 8 and 100 tasks on threads and 5 run last
   first on one thread: the serial scene byte for byte, its reports in its
   order, its sizes. */
static void one_object_split_equals_serial(void)
{
    static tp_scene_t S;
    static tp_reps_t R0, R1;
    static const unsigned threads[] = {2, 3, 8, 100, 5};
    int level;
    pthread_mutex_init(&R0.mu, NULL), pthread_mutex_init(&R1.mu, NULL);
    for (level = 4; level <= 5; level++) {
        re_scene_desc_t d;
        re_scene_t *s0 = NULL;
        re_sizes_t z0;
        re_diag_t dg;
        unsigned k;
        tp_big(&S, level);
        R0.n = 0;
        d = tp_desc(S.mesh, 1, NULL, 0, NULL);
        d.report = tp_report, d.report_user = &R0;
        if (!T_INT_EQ(re_build(&d, &s0, &dg), RE_OK)) { tp_scene_free(&S); return; }
        d.report = NULL;
        T_INT_EQ(re_build_sizes(&d, &z0, &dg), RE_OK);
        T_GT(s0->stats.rounded_corners, 2500);
        T_GT(s0->stats.mixed_vertices, 0);
        T_GT(s0->stats.clamped, 0);
        T_GT(R0.n, 4);
        for (k = 0; k < sizeof threads / sizeof *threads; k++) {
            tp_host_t host = {0, 0, 0};
            ta_alloc_t *al = ta_alloc_new(0);
            re_scene_t *s1 = NULL;
            re_sizes_t z1;
            int i, n_same = 0;
            host.reverse = k == 4;
            R1.n = 0;
            d = tp_desc(S.mesh, 1, &host, threads[k], al);
            d.report = tp_report, d.report_user = &R1;
            T_INT_EQ(re_build(&d, &s1, &dg), RE_OK);
            T_GE(host.count, 2); /* split */
            tp_same_scene(s0, s1, &S, 60 + k);
            if (T_INT_EQ(R1.n, R0.n))
                for (i = 0; i < R0.n; i++) n_same += !memcmp(&R1.r[i], &R0.r[i], sizeof R0.r[i]);
            T_INT_EQ(n_same, R0.n);
            T_INT_EQ(re_build_sizes(&d, &z1, &dg), RE_OK);
            T_INT_EQ(z1.scene_bytes, z0.scene_bytes);
            T_INT_EQ(z1.scratch_bytes, z0.scratch_bytes);
            re_free(s1);
            T_INT_EQ(al->live, 0);
            ta_alloc_delete(al);
        }
        re_free(s0);
        tp_scene_free(&S);
    }
}

/* A split step of one object. */
static void one_object_skipped_task_fails(void)
{
    static tp_scene_t S;
    tp_big(&S, 4);
    tp_skipped_task_fails(&S, 1);
    tp_scene_free(&S);
}

/* One object whose steps split in three. */
static void one_object_out_of_memory_leaves_nothing(void)
{
    static tp_scene_t S;
    tp_big(&S, 4);
    T_GE(tp_each_allocation_fails(&S, 1), 5); /* scratch, the spans' fans, the plane marks, the kd-tree's right half, the block */
    tp_scene_free(&S);
}

/* The kd-tree's node capacity just above the tree's size and a little
   below it (cells left leaves where it runs out, or no room for the
   pending right children: the build fails): the halves built on threads
   then need more nodes than the capacity allows together, and the tree is
   built again on one thread. The serial result each time: the same scene,
   or the same failure. */
static void one_object_kd_near_capacity(void)
{
    static tp_scene_t S;
    static const int below[] = {2, 0, -1, -2, -3, -4, -5, -6, -7, -8, -9, -10, -12, -13, -20};
    re_scene_desc_t d;
    re_scene_t *s0 = NULL;
    re_diag_t d0;
    unsigned long long N;
    unsigned k, n_cut = 0, n_fit = 0, n_fail = 0;
    tp_big(&S, 4);
    tp_node_cap = 0;
    d = tp_desc(S.mesh, 1, NULL, 0, NULL);
    if (!T_INT_EQ(re_build(&d, &s0, &d0), RE_OK)) goto done;
    N = s0->stats.kd_nodes;
    re_free(s0), s0 = NULL;
    for (k = 0; k < sizeof below / sizeof *below; k++) {
        re_result_t r0;
        int j;
        tp_node_cap = (unsigned)((long long)N + below[k]);
        r0 = re_build(&d, &s0, &d0);
        if (r0 == RE_OK) n_fit++, n_cut += s0->stats.kd_nodes < N;
        else n_fail += r0 == RE_ERR_TOO_LARGE && strstr(d0.message, "node capacity") != NULL;
        for (j = 0; j < 2; j++) {
            tp_host_t host = {j, 0, 0};
            re_scene_desc_t dp = tp_desc(S.mesh, 1, &host, 2 + (unsigned)j, NULL);
            re_scene_t *s1 = NULL;
            re_diag_t d1;
            if (!T_INT_EQ(re_build(&dp, &s1, &d1), r0)) {
                re_free(s1);
                continue;
            }
            if (r0 == RE_OK) tp_same_scene(s0, s1, &S, 80 + k);
            else T_INT_EQ(strcmp(d1.message, d0.message), 0);
            T_INT_EQ(host.count, 2); /* the last step split: the kd-tree, in two */
            re_free(s1);
        }
        re_free(s0), s0 = NULL;
    }
    T_GE(n_fit, 6);
    T_GE(n_cut, 4); /* trees the capacity cut, built alike */
    T_GE(n_fail, 1); /* a capacity where the serial tree cannot end */
done:
    tp_node_cap = 0;
    re_free(s0);
    tp_scene_free(&S);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(parallel_build_equals_serial),
        T_CASE(parallel_reports_match_serial),
        T_CASE(parallel_failure_names_lowest_object),
        T_CASE(parallel_skipped_task_fails),
        T_CASE(parallel_sizes_equal_serial),
        T_CASE(parallel_tasks_share_the_objects_evenly),
        T_CASE(parallel_out_of_memory_leaves_nothing),
        T_CASE(one_object_split_equals_serial),
        T_CASE(one_object_kd_near_capacity),
        T_CASE(one_object_skipped_task_fails),
        T_CASE(one_object_out_of_memory_leaves_nothing),
    };
    return T_RUN(argc, argv, cases);
}
