#include "cli.h"

#include "dialect.h"
#include "fmt.h"
#include "model.h"
#include "planner.h"
#include "pool.h"
#include "svg.h"
#include "writer.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int cli_fail(const lam_error *err)
{
    char buf[2048];
    fprintf(stderr, "lamina: %s\n", lam_error_format(err, buf, sizeof buf));
    return EXIT_INPUT;
}

int cli_usage(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "lamina%s%s: ", cmd ? " " : "", cmd ? cmd : "");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(try 'lamina%s%s --help')\n", cmd ? " " : "", cmd ? cmd : "");
    return EXIT_USAGE;
}

void cli_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        default:
            if (*p < 0x20) fprintf(f, "\\u%04x", *p);
            else fputc(*p, f);
        }
    }
    fputc('"', f);
}

const char *cli_num(char *buf, size_t size, double x)
{
    /* the one shortest round-trip printer (dialect.h) */
    char tmp[LAM_FMT_MAX];
    lam_dialect_number(tmp, x);
    snprintf(buf, size, "%s", tmp);
    return buf;
}

void cli_json_number(FILE *f, double x)
{
    char buf[64];
    if (!isfinite(x)) fputs("null", f);
    else fputs(cli_num(buf, sizeof buf, x), f);
}

int cli_fail_cmd(const char *cmd, const lam_error *err)
{
    return err->code == LAM_EUSAGE ? cli_usage(cmd, "%s", err->msg) : cli_fail(err);
}

/* "-o FILE is an input of this command ...": an output refused as an
 * input (writer.h) is named with its option. */
static int name_option(const char *opt, const char *path, int rc, lam_error *err)
{
    /* lam_error_set may take err's own message */
    if (rc == LAM_EUSAGE && err && strcmp(path, "-")) lam_error_set(err, rc, NULL, 0, 0, "%s %s", opt, err->msg);
    return rc;
}

int cli_writer(const char *opt, const char *path, lam_writer **w, lam_error *err)
{
    if (!strcmp(path, "-")) {
        int rc = cli_stdout_check(err);
        return rc ? rc : lam_writer_stream(stdout, "stdout", w, err);
    }
    return name_option(opt, path, lam_writer_file(path, w, err), err);
}

int cli_stdout_check(lam_error *err)
{
    return lam_writer_check_stream(stdout, "standard output", err);
}

int cli_output_check(const char *opt, const char *path, lam_error *err)
{
    return path && strcmp(path, "-") ? name_option(opt, path, lam_writer_check(path, err), err) : LAM_OK;
}

int cli_save_svg(const lam_svg *svg, const char *path, unsigned long long max_output, lam_error *err)
{
    lam_writer *w;
    int rc = cli_writer("--svg", path, &w, err);
    if (rc) return rc;
    lam_writer_set_limit(w, max_output ? max_output : LAM_DEFAULT_MAX_OUTPUT);
    lam_svg_write(svg, w);
    return lam_writer_commit(w, err);
}
