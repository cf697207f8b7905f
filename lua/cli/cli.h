/* Shared pieces of the `lamina` command line: exit codes, messages, JSON. */
#ifndef LAM_CLI_H
#define LAM_CLI_H

#include <stdio.h>

#include "error.h"

enum { EXIT_OK = 0, EXIT_INPUT = 1, EXIT_USAGE = 2, EXIT_CHECK = 3 };

/* Print "lamina: <formatted error>" to stderr and return EXIT_INPUT. */
int cli_fail(const lam_error *err);

/* Print "lamina <cmd>: <msg>" and a hint to stderr; return EXIT_USAGE. */
int cli_usage(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Write s as a JSON string literal (with quotes). */
void cli_json_string(FILE *f, const char *s);

/* Write a double as JSON (shortest round-trip form; non-finite as null). */
void cli_json_number(FILE *f, double x);

/* Format a double for people: shortest form that reads back exactly. */
const char *cli_num(char *buf, size_t size, double x);

/* Load the model a command names: a file, or standard input for "-" (its
 * messages then name it "<stdin>"), read with `threads` threads (-j; 0:
 * LAMINA_THREADS, else the online processors). */


/* A failure of a command: a usage error (LAM_EUSAGE: options that cannot
 * go together, an output that would replace an input) as cli_usage says
 * it (exit 2), anything else as cli_fail (exit 1). */
int cli_fail_cmd(const char *cmd, const lam_error *err);

/* The writer of an output option `opt` ("-o"): the file `path` (atomic,
 * lam_writer_file) or standard output for "-". A file or standard output
 * that is a file the command read is refused (LAM_EUSAGE, the message
 * naming the option: writer.h). */
struct lam_writer;
int cli_writer(const char *opt, const char *path, struct lam_writer **w, lam_error *err);

/* The same refusal up front (lam_writer_check), for an output written at
 * the end of a run: after the inputs are read, before the work. NULL and
 * "-" pass. */
int cli_output_check(const char *opt, const char *path, lam_error *err);

/* The same for standard output, for a command that prints its report
 * there: LAM_EUSAGE when it was sent (> or >>) to a file the command read. */
int cli_stdout_check(lam_error *err);

/* Write svg to an output option's path (cli_writer): whole or not at all,
 * and at most max_output bytes (--max-output; 0: LAM_DEFAULT_MAX_OUTPUT). */
struct lam_svg;
int cli_save_svg(const struct lam_svg *svg, const char *path, unsigned long long max_output, lam_error *err);

int cmd_info(int argc, char **argv);
int cmd_join(int argc, char **argv);
int cmd_slice(int argc, char **argv);
int cmd_validate(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_machines(int argc, char **argv);

#endif
