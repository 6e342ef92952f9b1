/* ex_timer.h — wall-clock timing and the "what was written, how long" lines.

   ex_timer_t tm; ex_timer_start(&tm);
   build();   ex_timer_phase(&tm, "build BVH");     //  "  build BVH: 0.012 s"
   render();  ex_timer_phase(&tm, "render");
   ex_report_written(path, ex_timer_total(&tm));      //  "wrote out/x.png (1.84 s)"
   All lines go to stdout. */
#ifndef FILIGREE_EX_TIMER_H
#define FILIGREE_EX_TIMER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Seconds on a monotonic wall clock. */
double ex_now(void);

typedef struct ex_timer_t { double start, last; } ex_timer_t;

void ex_timer_start(ex_timer_t *tm);
/* Prints "  <phase>: <seconds> s" for the time since the previous phase (or
   the start) and returns those seconds. */
double ex_timer_phase(ex_timer_t *tm, const char *phase);
/* Seconds since ex_timer_start. */
double ex_timer_total(const ex_timer_t *tm);

/* Prints "wrote <path> (<seconds> s)". */
void ex_report_written(const char *path, double seconds);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_TIMER_H */
