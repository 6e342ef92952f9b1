/* Latency of the vector instructions interval.h's pair path puts on a
   dependency chain, in cycles of this CPU: each instruction timed in a
   chain of ten copies (thread CPU time, best of 5 interleaved rounds),
   divided by a chain of 64-bit integer adds (1 cycle on every x86). The
   floors of docs/interval.md ("Why the latency goal is out of reach") are
   sums of these; bench_interval_ops measures the chains they bound.
   x86-64 only; the AVX-512 rows where the compiler targets them.
   Output: table on stdout, out/bench/interval_latency.csv. */
#include <immintrin.h>
#include <stdio.h>
#include <time.h>

enum { REPS = 20000000, ROUNDS = 5 };

static double cpu_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

#define TEN(s) s s s s s s s s s s
/* ns per instruction of a chain x = ins(x, y, z) */
#define VEC_CHAIN(fn, ins)                                                                      \
    static double fn(void)                                                                      \
    {                                                                                           \
        __m128d x = _mm_set_pd(1.0, 1.0), y = _mm_set_pd(1e-300, 1e-300), z = _mm_setzero_pd(); \
        volatile double keep;                                                                   \
        double t0 = cpu_ns();                                                                   \
        long i;                                                                                 \
        for (i = 0; i < REPS; i++) __asm__ volatile(TEN(ins "\n") : "+x"(x) : "x"(y), "x"(z));  \
        keep = _mm_cvtsd_f64(x);                                                                \
        (void)keep;                                                                             \
        return (cpu_ns() - t0) / (REPS * 10.0);                                                 \
    }

static double int_add(void)
{
    long x = 1, y = 3, i;
    volatile long keep;
    double t0 = cpu_ns();
    for (i = 0; i < REPS; i++) __asm__ volatile(TEN("add %1, %0\n") : "+r"(x) : "r"(y));
    keep = x;
    (void)keep;
    return (cpu_ns() - t0) / (REPS * 10.0);
}

VEC_CHAIN(addsd, "vaddsd %1, %0, %0")
VEC_CHAIN(addpd, "vaddpd %1, %0, %0")
VEC_CHAIN(mulpd, "vmulpd %1, %0, %0")
VEC_CHAIN(fmadd, "vfmadd231pd %1, %2, %0")
VEC_CHAIN(fmaddsub, "vfmaddsub231pd %1, %2, %0")
VEC_CHAIN(andpd, "vandpd %1, %0, %0")
VEC_CHAIN(xorpd, "vxorpd %1, %0, %0")
VEC_CHAIN(minpd, "vminpd %1, %0, %0")
VEC_CHAIN(unpcklpd, "vunpcklpd %1, %0, %0")
VEC_CHAIN(movddup, "vmovddup %0, %0")
VEC_CHAIN(vpermilpd, "vpermilpd $1, %0, %0")
VEC_CHAIN(blendvpd, "vblendvpd %0, %1, %0, %0")
VEC_CHAIN(vpaddq, "vpaddq %1, %0, %0")
#if defined(__AVX512VL__) && defined(__AVX512DQ__)
VEC_CHAIN(vrangepd, "vrangepd $2, %1, %0, %0")
VEC_CHAIN(vpmaxsq, "vpmaxsq %1, %0, %0")
#endif

typedef struct {
    const char *name;
    double (*fn)(void);
} probe_t;

int main(int argc, char **argv)
{
    static const probe_t probes[] = {
        {"add (int)", int_add}, {"vaddsd", addsd},       {"vaddpd", addpd},       {"vmulpd", mulpd},
        {"vfmadd", fmadd},      {"vfmaddsub", fmaddsub}, {"vandpd", andpd},       {"vxorpd", xorpd},
        {"vminpd", minpd},      {"vunpcklpd", unpcklpd}, {"vmovddup", movddup},   {"vpermilpd", vpermilpd},
        {"vblendvpd", blendvpd}, {"vpaddq", vpaddq},
#if defined(__AVX512VL__) && defined(__AVX512DQ__)
        {"vrangepd", vrangepd}, {"vpmaxsq", vpmaxsq},
#endif
    };
    enum { NP = sizeof probes / sizeof probes[0] };
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    char path[512];
    double best[NP];
    FILE *csv;
    int k, r;
    for (k = 0; k < NP; k++) best[k] = 1e30;
    for (r = 0; r < ROUNDS; r++) { /* interleaved: a slow spell hits every row */
        fprintf(stderr, "latency round %d of %d\n", r + 1, ROUNDS);
        for (k = 0; k < NP; k++) {
            double t = probes[k].fn();
            if (t < best[k]) best[k] = t;
        }
    }
    snprintf(path, sizeof path, "%s/interval_latency.csv", dir);
    csv = fopen(path, "w");
    if (!csv) {
        fprintf(stderr, "cannot write %s\n", path);
        return 1;
    }
    fprintf(csv, "instruction,ns,cycles\n");
    printf("latency of one instruction in a dependent chain (best of %d rounds; cycles: against the integer add, 1 cycle, "
           "here %.2f GHz)\n",
           ROUNDS, 1 / best[0]);
    printf("instruction      ns  cycles\n");
    for (k = 0; k < NP; k++) {
        printf("%-11s  %.4f  %6.2f\n", probes[k].name, best[k], best[k] / best[0]);
        fprintf(csv, "%s,%.5f,%.3f\n", probes[k].name, best[k], best[k] / best[0]);
    }
    fclose(csv);
    printf("wrote %s\n", path);
    return 0;
}
