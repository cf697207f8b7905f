/* Fatal signals: see cli_signal.h. */
#include "cli_signal.h"

#include <signal.h>
#include <string.h>

#include "writer.h"

void cli_fatal_signal(int sig)
{
    lam_writer_unlink_temps();
    signal(sig, SIG_DFL);
    raise(sig); /* held until this handler returns, then the default action */
}

/* Interrupts and hang-ups remove the temporary files of outputs being
 * written, then end the process by the same signal (exit status 128 + N
 * in a shell). A signal ignored when lamina started (nohup) stays ignored. */
void cli_signals_setup(void)
{
    static const int sigs[] = { SIGINT, SIGTERM, SIGHUP, SIGPIPE };
    for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) {
        struct sigaction sa, old;
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = cli_fatal_signal;
        sigfillset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}
