#include "progress.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#define INTERVAL 0.2 /* seconds between redraws: five a second at most */
#define DELAY 0.5    /* before the first: a short run shows no line */
#define NOTES 20     /* notes of a kind before the summary */

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

void cli_progress_init(cli_progress *p, int level, int stdout_data)
{
    memset(p, 0, sizeof *p);
    p->level = level;
    p->tty = level >= 0 && isatty(STDERR_FILENO) && !(stdout_data && isatty(STDOUT_FILENO));
    p->interval = INTERVAL;
    p->delay = DELAY;
    const char *env = getenv("LAMINA_PROGRESS_INTERVAL");
    if (env && p->tty) {
        char *end;
        errno = 0;
        double x = strtod(env, &end);
        if (end == env || *end || errno || !(x >= 0) || x > 3600)
            fprintf(stderr, "lamina: LAMINA_PROGRESS_INTERVAL=%s is not a number of seconds from 0 to 3600; "
                            "using %g\n", env, INTERVAL);
        else p->interval = x, p->delay = x < DELAY ? x : DELAY;
    }
    p->stage = now();
}

void cli_progress_begin(cli_progress *p, const char *verb, const char *path, size_t total)
{
    /* the file's name without its folders: the counts after it should fit */
    const char *base = strrchr(path, '/');
    snprintf(p->what, sizeof p->what, "%s %s", verb, base && base[1] ? base + 1 : path);
    p->total = total;
    p->done = 0;
    p->start = now();
    p->due = p->start + p->delay;
}

/* "<1 s", "42 s", "3 min 05 s", "2 h 10 min" */
static void duration(char *buf, size_t size, double s)
{
    if (s < 1) snprintf(buf, size, "<1 s");
    else if (s < 60) snprintf(buf, size, "%.0f s", floor(s));
    else if (s < 3600) snprintf(buf, size, "%d min %02d s", (int)(s / 60), (int)fmod(s, 60));
    else if (s < 1e7) snprintf(buf, size, "%d h %02d min", (int)(s / 3600), (int)fmod(s / 60, 60));
    else snprintf(buf, size, "a long time");
}

/* The terminal's width, so the line never wraps (a wrapped line cannot
 * be redrawn with \r). */
static size_t columns(void)
{
    struct winsize ws;
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
    return 80;
}

static void draw(cli_progress *p, double t)
{
    char line[512], left[64];
    double elapsed = t - p->start;
    int n = snprintf(line, sizeof line, "lamina: %s: layer %zu of %zu (%.0f%%)", p->what, p->done, p->total,
                     p->total ? floor(100.0 * (double)p->done / (double)p->total) : 100.0);
    if (p->done && elapsed > 0 && n > 0 && (size_t)n < sizeof line) {
        double rate = (double)p->done / elapsed;
        duration(left, sizeof left, (double)(p->total - p->done) / rate);
        n += snprintf(line + n, sizeof line - (size_t)n, rate >= 100 ? ", %.0f layers/s, %s left" : ", %.3g layers/s, %s left",
                      rate, left);
    }
    size_t len = n < 0 ? 0 : (size_t)n >= sizeof line ? sizeof line - 1 : (size_t)n;
    size_t cols = columns();
    if (len > cols - 1) len = cols - 1;
    /* one write: \r, the line, blanks over the rest of a longer last one */
    char out[1100];
    size_t k = 0;
    out[k++] = '\r';
    memcpy(out + k, line, len);
    k += len;
    for (size_t i = len; i < p->shown && k < sizeof out; i++) out[k++] = ' ';
    fwrite(out, 1, k, stderr);
    fflush(stderr);
    p->shown = len > p->shown ? len : p->shown;
    p->hidden = 0;
}

void cli_progress_step(cli_progress *p, size_t done)
{
    p->done = done;
    if (!p->tty || !p->total) return;
    double t = now();
    if (t < p->due && !p->hidden) return;
    if (t < p->start + p->delay) return;
    draw(p, t);
    p->due = t + p->interval;
}

void cli_progress_hide(cli_progress *p)
{
    if (!p || !p->shown) return;
    char out[1100];
    size_t k = 0;
    out[k++] = '\r';
    for (size_t i = 0; i < p->shown && k + 1 < sizeof out; i++) out[k++] = ' ';
    out[k++] = '\r';
    fwrite(out, 1, k, stderr);
    fflush(stderr);
    p->shown = 0;
    p->hidden = 1;
}

void cli_progress_end(cli_progress *p)
{
    cli_progress_hide(p);
    p->hidden = 0;
    if (p->level > 0 && p->what[0]) {
        double s = now() - p->start;
        fprintf(stderr, "lamina: %s: %zu layer%s in %.3f s", p->what, p->done, p->done == 1 ? "" : "s", s);
        double rate = s > 0 ? (double)p->done / s : 0;
        if (rate > 0) fprintf(stderr, rate >= 100 ? " (%.0f layers/s)" : " (%.3g layers/s)", rate);
        fputc('\n', stderr);
    }
    p->what[0] = '\0';
    p->total = 0;
    p->stage = now();
}

void cli_progress_stage(cli_progress *p, const char *stage)
{
    double t = now();
    if (p->level > 0) {
        cli_progress_hide(p);
        fprintf(stderr, "lamina: %s: %.3f s\n", stage, t - p->stage);
    }
    p->stage = t;
}

size_t cli_progress_notes(const cli_progress *p)
{
    return p->level < 0 ? 0 : p->level > 0 ? SIZE_MAX : NOTES;
}
