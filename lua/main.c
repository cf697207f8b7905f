/* The `lamina` executable: dispatch to one command per file (cli_*.c). */
#include "cli.h"
#include "cli_lua.h"
#include "version.h"

#include <string.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

/* A run allocates and frees arrays of megabytes as it goes from the file
 * to the mesh, the edges and the layers. With glibc, big blocks come from
 * the heap and stay there, so freed memory is reused instead of handed back
 * to the kernel and faulted in afresh. Only for the commands that run once
 * and exit: an interactive session keeps the default, which gives memory
 * back between commands. (Transparent huge pages for the heap
 * were tried too: a fifth faster alone, but twice as slow when the kernel
 * had to compact memory for them first, as after another big process.) */
static void heap_setup(void)
{
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD)
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

static int help(void)
{
    printf("lamina " LAMINA_VERSION " - process planning for layered manufacturing\n\n"
           "usage:\n"
           "  lamina info MODEL [--json]          model report: shells, cavities, volume, defects\n"
           "  lamina slice MODEL [options]        slice and plan; program to stdout or -o FILE\n"
           "  lamina validate MODEL [options]     Embree check of every solid/hole label\n"
           "  lamina check MODEL -m MACHINE       design-rule check (wall thickness, overhangs)\n"
           "  lamina machines [--show NAME]       list machine profiles / print one resolved\n"
           "  lamina run RECIPE.lua [ARGS...]     run a Lua recipe (ARGS in `arg` and ...)\n"
           "  lamina repl                         Lua prompt with lamina loaded (also plain\n"
           "                                      `lamina` on a terminal)\n"
           "  lamina -e CODE [-e CODE ...]        run Lua code with lamina loaded\n"
           "  lamina --help | --version\n\n"
           "'lamina COMMAND --help' describes a command's options.\n"
           "Models: Unigrafix (.ug), STL (ASCII or binary), Wavefront OBJ.\n"
           "Exit codes: 0 success, 1 input or processing error, 2 usage error,\n"
           "3 the model was read but a check failed.\n");
    return EXIT_OK;
}

int main(int argc, char **argv)
{
    if (argc < 2) return lua_main_default();
    const char *cmd = argv[1];
    if (strcmp(cmd, "repl") != 0) heap_setup();
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) return help();
    if (strcmp(cmd, "--version") == 0) {
        printf("lamina " LAMINA_VERSION "\n");
        return EXIT_OK;
    }
    if (strcmp(cmd, "info") == 0) return cmd_info(argc - 1, argv + 1);
    if (strcmp(cmd, "slice") == 0) return cmd_slice(argc - 1, argv + 1);
    if (strcmp(cmd, "validate") == 0) return cmd_validate(argc - 1, argv + 1);
    if (strcmp(cmd, "check") == 0) return cmd_check(argc - 1, argv + 1);
    if (strcmp(cmd, "machines") == 0) return cmd_machines(argc - 1, argv + 1);
    if (strcmp(cmd, "run") == 0) return cmd_run(argc - 1, argv + 1);
    if (strcmp(cmd, "repl") == 0) return cmd_repl(argc - 1, argv + 1);
    if (strcmp(cmd, "-e") == 0) return cmd_eval(argc - 1, argv + 1);
    return cli_usage(NULL, "unknown command '%s'", cmd);
}
