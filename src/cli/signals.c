/*
 * SIGINT and SIGTERM during `pmech run`: the first asks the run to stop after the step in progress (it
 * then closes its files and writes run.json); a second one ends the process at once. Every output file
 * is whole at any moment (frames and run.json are renamed into place, CSV lines are written whole), so
 * what is on disk stays readable either way.
 */
#include "cli/commands.h"

#include <signal.h>
#include <string.h>
#include <unistd.h>

static volatile sig_atomic_t pending;

static void on_signal(int sig)
{
    if (pending)
        _exit(128 + sig);
    pending = sig;
}

const volatile sig_atomic_t *pm_cli_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART; /* the step in progress finishes its writes */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    return &pending;
}
