/* The `lamina` executable: dispatch to one command per file (cli_*.c). */
#include "cli.h"

#include <string.h>

#define LAMINA_VERSION "0.1.0"

static int help(void)
{
    printf("lamina " LAMINA_VERSION " - process planning for layered manufacturing\n\n"
           "usage:\n"
           "  lamina info MODEL [--json]     model report: shells, cavities, volume, defects\n"
           "  lamina slice MODEL [options]   slice; SLS contours to stdout or -o FILE, --svg preview\n"
           "  lamina machines [--show NAME]  list machine profiles / print one as resolved YAML\n"
           "  lamina --help | --version\n\n"
           "'lamina COMMAND --help' describes a command's options.\n"
           "Models: Unigrafix (.ug), STL (ASCII or binary), Wavefront OBJ.\n"
           "Exit codes: 0 success, 1 input or processing error, 2 usage error,\n"
           "3 the model was read but a check failed.\n");
    return EXIT_OK;
}

int main(int argc, char **argv)
{
    if (argc < 2) return cli_usage(NULL, "no command given");
    const char *cmd = argv[1];
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
    return cli_usage(NULL, "unknown command '%s'", cmd);
}
