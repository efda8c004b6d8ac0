/* Sub-commands of the pmech program; each returns the process exit code (0, 1 or 2) and prints its full
 * usage with its _usage function, which `pmech --help` calls for every command so that the one text
 * lists every command and option. */
#ifndef PMECH_CLI_COMMANDS_H
#define PMECH_CLI_COMMANDS_H

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

#endif
