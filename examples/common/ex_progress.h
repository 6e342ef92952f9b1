/* ex_progress.h — a progress bar on stderr for anything longer than a second.

   Nothing is drawn during the first second, so quick jobs stay silent. On a
   terminal the bar redraws in place ("render [#######.....]  58%  3.1 s");
   when stderr is a file or pipe it prints a plain line every ~5 s instead.
   One thread drives a bar (the tile renderer does it from its main thread). */
#ifndef FILIGREE_EX_PROGRESS_H
#define FILIGREE_EX_PROGRESS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ex_progress_t {
    const char *label;
    long long total;
    double start, last_draw;
    int drawn;      /* 1 once something was printed */
    int tty;        /* stderr is a terminal */
} ex_progress_t;

void ex_progress_begin(ex_progress_t *p, const char *label, long long total);
/* `done` of `total` units finished; cheap to call often. */
void ex_progress_update(ex_progress_t *p, long long done);
/* Ends the bar (completes the line if one was drawn). */
void ex_progress_end(ex_progress_t *p);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_PROGRESS_H */
