/* The pmech program: dispatches to sub-commands. */
#include "cli/commands.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "pmech %s - particle solver for large-deformation solid mechanics (MPM, GMM, RKPM)\n"
            "\n"
            "usage:\n"
            "  pmech run CASE.json [-o DIR] [--quiet] [--verbose] [--threads N] (pmech run --help)\n"
            "      run a case file; outputs (ParaView particles.pvd, grid.vtu, probes.csv,\n"
            "      energy.csv, run.json; implicit runs add newton.log and reactions.csv) go to\n"
            "      DIR (default: the case's output.directory); --verbose prints every Newton\n"
            "      iteration of implicit runs instead of the progress line\n"
            "  pmech material DRIVER.json [-o OUT.csv]       (pmech material --help)\n"
            "      drive one material point along a stress/strain path and write CSV\n"
            "  pmech --help | --version\n"
            "\n"
            "exit codes: 0 success, 1 the simulation failed, 2 invalid input\n"
            "input reference: docs/input.md (installed: PREFIX/share/doc/pmech/input.md)\n",
            PMECH_VERSION);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("pmech %s\n", PMECH_VERSION);
        return 0;
    }
    if (!strcmp(argv[1], "run"))
        return pm_cmd_run(argc - 1, argv + 1);
    if (!strcmp(argv[1], "material"))
        return pm_cmd_material(argc - 1, argv + 1);
    fprintf(stderr, "pmech: unknown command '%s' (commands: run, material; see pmech --help)\n", argv[1]);
    return 2;
}
