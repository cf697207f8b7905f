#include "cli.h"

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
    if (x == 0) x = 0; /* no "-0" */
    double ax = fabs(x);
    if (ax >= 1e-4 && ax < 1e15) {
        /* plain decimals, as few as read back exactly */
        for (int dec = 0; dec <= 20; dec++) {
            snprintf(buf, size, "%.*f", dec, x);
            if (strtod(buf, NULL) == x) return buf;
        }
    }
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, x);
        if (strtod(buf, NULL) == x) return buf;
    }
    return buf;
}

void cli_json_number(FILE *f, double x)
{
    char buf[64];
    if (!isfinite(x)) fputs("null", f);
    else fputs(cli_num(buf, sizeof buf, x), f);
}
