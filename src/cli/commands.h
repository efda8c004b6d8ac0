/* Sub-commands of the pmech program; each returns the process exit code (0, 1 or 2). */
#ifndef PMECH_CLI_COMMANDS_H
#define PMECH_CLI_COMMANDS_H

/** `pmech run CASE.json [-o DIR] [--quiet] [--threads N]` */
int pm_cmd_run(int argc, char **argv);

/** `pmech material DRIVER.json [-o OUT.csv]` */
int pm_cmd_material(int argc, char **argv);

#endif
