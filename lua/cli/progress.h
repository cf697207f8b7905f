/* How much a command says, and its progress line on a terminal.
 *
 * -q (quiet): no progress line and no notes (closed gaps, dropped loops,
 * the build-time line); warnings and errors still print. -v (verbose):
 * every per-layer note instead of the first 20 and a summary, and the time
 * each stage took. The progress line ("lamina: slicing part.stl: layer
 * 1200 of 10000 (12%), 850 layers/s, 10 s left") goes to standard error
 * only when it is a terminal and -q is not given; it is redrawn in place
 * (\r) at most every 0.2 s of the monotonic clock, first after 0.5 s (a
 * short run shows none), cut to the terminal's width, and erased before
 * any other message and at the end. LAMINA_PROGRESS_INTERVAL=SECONDS sets
 * the least time between redraws; 0 draws at every layer from the first
 * (the tests use it). Nor is there a line when the command's data (a
 * program, JSON) goes to standard output on a terminal: it would land in
 * the middle of it. One line per process: the commands run on one
 * thread. */
#ifndef LAM_CLI_PROGRESS_H
#define LAM_CLI_PROGRESS_H

#include <stddef.h>

typedef struct cli_progress {
    int level;            /* -1 quiet, 0 normal, 1 verbose */
    int tty;              /* standard error is a terminal */
    char what[160];       /* "slicing part.stl" */
    size_t total, done;
    double start, due;    /* monotonic seconds: the run's start, the next redraw */
    double interval, delay;
    double stage;         /* when the stage being timed (-v) began */
    size_t shown;         /* characters of the line on the screen; 0: none */
    int hidden;           /* erased for a message: redraw at the next step */
} cli_progress;

/* Set p up for a command run with level -1 (-q), 0 or 1 (-v);
 * stdout_data: the command writes its data to standard output (no line
 * when that is a terminal). Starts the first stage's clock; draws
 * nothing. */
void cli_progress_init(cli_progress *p, int level, int stdout_data);

/* A run of `total` layers begins: `verb` it does to model `path`
 * ("slicing", "parts/part.stl"; the line names the file without its
 * folders). */
void cli_progress_begin(cli_progress *p, const char *verb, const char *path, size_t total);

/* `done` layers of the total are done: redraw the line when it is due. */
void cli_progress_step(cli_progress *p, size_t done);

/* Erase the line, if one is shown, before printing anything else to the
 * terminal; the next step draws it again. */
void cli_progress_hide(cli_progress *p);

/* The run is over: erase the line for good; with -v say how long the
 * layers took. */
void cli_progress_end(cli_progress *p);

/* With -v: "lamina: <stage>: 0.123 s", the time since the last stage (or
 * init) ended; then the next stage's clock starts. */
void cli_progress_stage(cli_progress *p, const char *stage);

/* How many notes of one kind (one a layer) to print before summarising:
 * 0 with -q, 20, or all with -v. */
size_t cli_progress_notes(const cli_progress *p);

#endif
