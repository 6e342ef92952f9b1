/* ex_timer.c — see ex_timer.h */
#include "ex_timer.h"

#include <stdio.h>
#include <time.h>

double ex_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void ex_timer_start(ex_timer_t *tm) { tm->start = tm->last = ex_now(); }

double ex_timer_phase(ex_timer_t *tm, const char *phase)
{
    double now = ex_now(), dt = now - tm->last;
    tm->last = now;
    printf("  %s: %.3f s\n", phase, dt);
    fflush(stdout);
    return dt;
}

double ex_timer_total(const ex_timer_t *tm) { return ex_now() - tm->start; }

void ex_report_written(const char *path, double seconds)
{
    printf("wrote %s (%.2f s)\n", path, seconds);
    fflush(stdout);
}
