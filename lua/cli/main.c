/* The `lamina` executable: its command table (dispatch, --help) over one
 * command per file (cli_*.c). */
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "cli.h"
#include "cli_build.h"
#include "cli_lua.h"
#include "cli_repair.h"
#include "cli_signal.h"
#include "file.h"
#include "repl.h"
#include "version.h"
#include "writer.h"

#include <errno.h>
#include <stdint.h>
#include <stdio_ext.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

/* A run allocates and frees arrays of megabytes as it goes from the file
 * to the mesh, the edges and the layers. With glibc, big blocks come from
 * the heap and stay there, so freed memory is reused instead of handed back
 * to the kernel and faulted in afresh. Only for the commands that run once
 * and exit: an interactive session keeps the default, which gives memory
 * back between commands.
 *
 * The heap's first 64 MiB (address space: untouched, it costs no memory)
 * are asked for on transparent huge pages, as glibc's hugetlb tunable
 * would: a page fault costs about 12 us on the virtual machines we run on,
 * and a small run faults in every page of its model once. Measured (the
 * bench's sphere, -j 2): 3,900 -> 1,050 page faults, 0.129 -> about
 * 0.10 s; peak memory 22.4 -> 27 MB (a huge page is whole once touched);
 * the torus 40.7 -> 46 MB. Aligning the big arrays to huge pages as well
 * saved 20% more faults for 6 MB more. (Tried before without the heap's
 * arrays' own hints: slower after another big process had left memory to
 * compact; measured after a process touching 12 GB: no slower.) Bigger
 * models' arrays, past these 64 MiB, have their own hints (hugemem.h). */
static void heap_setup(void)
{
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD)
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    size_t n = (size_t)64 << 20;
    void *p = malloc(n);
#ifdef MADV_HUGEPAGE
    /* the whole pages of the block (the library's arrays hint themselves) */
    uintptr_t a = ((uintptr_t)p + 4095) & ~(uintptr_t)4095, z = ((uintptr_t)p + n) & ~(uintptr_t)4095;
    if (p && z > a) (void)madvise((void *)a, z - a, MADV_HUGEPAGE);
#endif
    free(p);
#endif
}

/* Standard output is closed at exit and checked, as GNU tools do it: a
 * report that could not be written (a full disk, /dev/full, a closed pipe
 * with SIGPIPE ignored) is an error, not exit 0. Runs at every exit (also
 * os.exit from Lua); _exit because exit is already under way. */
static void close_stdout(void)
{
    int pending = __fpending(stdout) != 0, earlier = ferror(stdout) != 0;
    errno = 0;
    int failed = fclose(stdout) != 0;
    if (earlier || (failed && (pending || errno != EBADF))) {
        int e = failed ? errno : 0;
        fprintf(stderr, "lamina: cannot write to standard output%s%s\n", e ? ": " : "", e ? strerror(e) : "");
        _exit(EXIT_INPUT);
    }
}

/* The commands: one table drives dispatch, `lamina --help` and the list of
 * man pages (the Makefile's MAN_CMDS reads the names of this table's
 * entries, one per line as `{ "NAME", `; man/genman.py checks that
 * --help lists the same ones and makes the bash completion from them).
 * A summary's "\n" continues it on the next line of --help. */
enum {
    CMD_LUA = 1,         /* Lua code runs: the library's default, no record of the inputs read */
    CMD_INTERACTIVE = 2, /* a session: glibc's heap as it is (heap_setup) */
};

typedef struct command {
    const char *name;    /* argv[1] */
    const char *args;    /* its synopsis after the name, for --help */
    const char *summary; /* for --help */
    int (*run)(int argc, char **argv);
    unsigned flags;      /* CMD_* */
} command;

static const command commands[] = {
    { "info", "MODEL [--json]", "model report: shells, cavities, volume, defects", cmd_info, 0 },
    { "repair", "MODEL -o FILE", "the mesh repaired (holes filled, facets\noriented) as STL or OBJ", cmd_repair,
      0 },
    { "slice", "MODEL [options]", "slice and plan; program to stdout or -o FILE", cmd_slice, 0 },
    { "build", "JOB.yaml [-o FILE]", "plan a build plate: parts placed, styles,\nseveral lasers (docs/builds.md)", cmd_build,
      0 },
    { "join", "PART... [-o FILE]", "the program of a run sliced in parts\n(lamina slice ... --layers A:B)", cmd_join,
      0 },
    { "validate", "MODEL [options]", "Embree check of every solid/hole label", cmd_validate, 0 },
    { "check", "MODEL -m MACHINE", "design-rule check (wall thickness, overhangs)", cmd_check, 0 },
    { "machines", "[--show NAME]", "list machine profiles / print one resolved", cmd_machines, 0 },
    { "run", "RECIPE.lua [ARGS...]", "run a Lua recipe (ARGS in `arg` and ...)", cmd_run, CMD_LUA },
    { "repl", "", "Lua prompt with lamina loaded (also plain\n`lamina` on a terminal)", cmd_repl,
      CMD_LUA | CMD_INTERACTIVE },
    { "-e", "CODE [-e CODE ...]", "run Lua code with lamina loaded", cmd_eval, CMD_LUA },
};

#define NCOMMANDS (sizeof commands / sizeof *commands)
#define HELP_COLUMN 28 /* the synopses' width: summaries start in one column */

static int help(void)
{
    printf("lamina " LAMINA_VERSION " - process planning for layered manufacturing\n\nusage:\n");
    for (size_t i = 0; i < NCOMMANDS; i++) {
        const command *c = &commands[i];
        char syn[64];
        snprintf(syn, sizeof syn, "%s%s%s", c->name, *c->args ? " " : "", c->args);
        printf("  lamina %-*s ", HELP_COLUMN, syn);
        for (const char *p = c->summary; *p; p++)
            if (*p == '\n') printf("\n%*s", 9 + HELP_COLUMN + 1, "");
            else putchar(*p);
        putchar('\n');
    }
    printf("  lamina --help | --version\n\n"
           "'lamina COMMAND --help' describes a command's options.\n"
           "Models: Unigrafix (.ug), STL (ASCII or binary), Wavefront OBJ.\n"
           "Exit codes: 0 success, 1 input or processing error, 2 usage error,\n"
           "3 the model was read but a check failed.\n");
    return EXIT_OK;
}

static int dispatch(int argc, char **argv);

int main(int argc, char **argv)
{
    atexit(close_stdout);
    cli_signals_setup();
    int rc = dispatch(argc, argv);
    lam_file_track(0);
    exit(rc);
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) return lua_main_default();
    const char *name = argv[1];
    const command *c = NULL;
    for (size_t i = 0; i < NCOMMANDS && !c; i++)
        if (strcmp(commands[i].name, name) == 0) c = &commands[i];
    unsigned flags = c ? c->flags : 0;
    if (!(flags & CMD_INTERACTIVE)) heap_setup();
    /* a command's outputs may not replace what it read (writer.h); Lua
     * (run, repl, -e) keeps the library's default: no record */
    if (!(flags & CMD_LUA)) lam_file_track(1);
    if (c) return c->run(argc - 1, argv + 1);
    if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0 || strcmp(name, "help") == 0) return help();
    if (strcmp(name, "--version") == 0) {
        printf("lamina " LAMINA_VERSION "\n");
        return EXIT_OK;
    }
    return cli_usage(NULL, "unknown command '%s'", name);
}
