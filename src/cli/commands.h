/* Sub-commands of the pmech program; each returns the process exit code (0, 1 or 2) and prints its full
 * usage with its _usage function, which `pmech --help` calls for every command so that the one text
 * lists every command and option. */
#ifndef PMECH_CLI_COMMANDS_H
#define PMECH_CLI_COMMANDS_H

#include <signal.h>
#include <stdio.h>

/** `pmech run CASE.json [-o DIR] [--quiet] [--verbose] [--threads N]` */
int pm_cmd_run(int argc, char **argv);
/** The usage and options of `pmech run`. */
void pm_cmd_run_usage(FILE *f);

/** `pmech material DRIVER.json [-o OUT.csv]` */
int pm_cmd_material(int argc, char **argv);
/** The usage and options of `pmech material`. */
void pm_cmd_material_usage(FILE *f);

/** `pmech render DIR --field F [...]` */
int pm_cmd_render(int argc, char **argv);
/** The usage and options of `pmech render`. */
void pm_cmd_render_usage(FILE *f);

/**
 * Make OpenMP's waiting threads sleep (OMP_WAIT_POLICY=passive) unless the user chose a policy: sets it
 * and starts the program again with @p argv (returns only when nothing was to be done, or exec failed).
 */
void pm_cli_passive_wait(char **argv);

/**
 * Claim @p dir for one run: create it, lock it against other pmech runs (DIR/.pmech.lock, held until
 * pm_cli_release_output or the end of the process) and refuse it when it holds an earlier run's outputs
 * unless @p overwrite. Returns PM_OK with *lock_fd set, or PM_EINPUT / PM_EIO with a message.
 */
int pm_cli_claim_output(const char *dir, int overwrite, int *lock_fd);
/**
 * Catch SIGINT and SIGTERM: the first is stored in the returned flag (pass it as pm_run_opts.interrupt
 * so the run stops after its current step); a second ends the process at once with 128 + the signal.
 */
const volatile sig_atomic_t *pm_cli_signals_install(void);

/**
 * Prepare the short run.json a second SIGINT or SIGTERM writes into @p dir before it ends the process
 * (exit status, which signal, case file), since the run cannot write its own then.
 */
void pm_cli_signals_prepare(const char *dir, const char *case_file);

/** The run wrote its own run.json: a second signal from now on only ends the process. */
void pm_cli_signals_finished(void);

/** Release the lock pm_cli_claim_output took (-1: nothing to release). */
void pm_cli_release_output(int lock_fd);

#endif
