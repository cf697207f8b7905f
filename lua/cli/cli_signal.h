/* Fatal signals of the `lamina` executable: an interrupt or a hang-up
 * removes the temporary files of the outputs being written, then ends
 * the process by the same signal (main.c sets it up, cli_lua.c ends a
 * recipe by it). */
#ifndef LAM_CLI_SIGNAL_H
#define LAM_CLI_SIGNAL_H

/* The handler of SIGINT, SIGTERM, SIGHUP and SIGPIPE: remove the
 * temporary files of outputs being written and end by the same signal.
 * Async-signal-safe. */
void cli_fatal_signal(int sig);

/* Install cli_fatal_signal for those signals (exit status 128 + N in a
 * shell); a signal ignored when lamina started (nohup) stays ignored. */
void cli_signals_setup(void);

#endif
