/* lamina repair MODEL -o OUT: the mesh as loading repairs it, written out
 * (cli_repair.c). */
#ifndef LAM_CLI_REPAIR_H
#define LAM_CLI_REPAIR_H

int cmd_repair(int argc, char **argv);

#endif
