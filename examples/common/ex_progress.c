/* ex_progress.c — see ex_progress.h */
#include "ex_progress.h"

#include <stdio.h>
#include <unistd.h>

#include "ex_timer.h"

#define EX__PROGRESS_DELAY 1.0      /* seconds of silence before the first draw */
#define EX__PROGRESS_TTY_PERIOD 0.1 /* redraw period on a terminal */
#define EX__PROGRESS_LOG_PERIOD 5.0 /* line period when stderr is a file */
#define EX__PROGRESS_WIDTH 30

void ex_progress_begin(ex_progress_t *p, const char *label, long long total)
{
    p->label = label ? label : "progress";
    p->total = total > 0 ? total : 1;
    p->start = ex_now();
    p->last_draw = p->start;
    p->drawn = 0;
    p->tty = isatty(2);
}

static void ex__progress_draw(const ex_progress_t *p, long long done, double now)
{
    double f = (double)done / (double)p->total;
    int i, fill;
    if (f > 1) f = 1;
    if (!p->tty) {
        if (f > 0.02 && f < 1)
            fprintf(stderr, "%s: %3.0f%% (%.1f s, ~%.0f s left)\n", p->label, 100 * f, now - p->start,
                    (now - p->start) * (1 - f) / f);
        else
            fprintf(stderr, "%s: %3.0f%% (%.1f s)\n", p->label, 100 * f, now - p->start);
        return;
    }
    fill = (int)(f * EX__PROGRESS_WIDTH);
    fprintf(stderr, "\r%s [", p->label);
    for (i = 0; i < EX__PROGRESS_WIDTH; i++) fputc(i < fill ? '#' : '.', stderr);
    fprintf(stderr, "] %3.0f%%  %.1f s", 100 * f, now - p->start);
    if (f > 0.02 && f < 1) fprintf(stderr, ", ~%.0f s left   ", (now - p->start) * (1 - f) / f);
    else fprintf(stderr, "              ");
    fflush(stderr);
}

void ex_progress_update(ex_progress_t *p, long long done)
{
    double now = ex_now();
    double period = p->tty ? EX__PROGRESS_TTY_PERIOD : EX__PROGRESS_LOG_PERIOD;
    if (now - p->start < EX__PROGRESS_DELAY) return;
    if (p->drawn && now - p->last_draw < period) return;
    ex__progress_draw(p, done, now);
    p->drawn = 1;
    p->last_draw = now;
}

void ex_progress_end(ex_progress_t *p)
{
    if (!p->drawn) return;
    ex__progress_draw(p, p->total, ex_now());
    if (p->tty) fputc('\n', stderr);
    fflush(stderr);
}
