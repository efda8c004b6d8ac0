/* The pmech program: dispatches to sub-commands. `pmech --help` prints every command's own usage, so
 * it lists every command and option there is. */
#include "cli/commands.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f, "pmech %s - particle solver for large-deformation solid mechanics (MPM, GMM, RKPM)\n\n"
               "Commands (each also answers --help):\n\n",
            PMECH_VERSION);
    pm_cmd_run_usage(f);
    fputc('\n', f);
    pm_cmd_material_usage(f);
    fputc('\n', f);
    pm_cmd_render_usage(f);
    fprintf(f, "\n"
               "usage: pmech --help | --version\n"
               "\n"
               "Threads: --threads N, else OMP_NUM_THREADS, else all cores (one below 5,000 particles).\n"
               "Threads that wait yield their core (OMP_WAIT_POLICY=passive unless set), so a run on a busy\n"
               "machine does not fight other programs for cores (docs/performance.md).\n"
               "Exit codes: 0 success, 1 the simulation failed (outputs so far stay valid), 2 invalid input.\n"
               "Documentation: docs/ (installed: PREFIX/share/doc/pmech): input.md (every case key),\n"
               "tutorial.md (a first soil case), api.md (C and Python), materials.md, verification.md.\n");
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
    if (!strcmp(argv[1], "run")) {
        pm_cli_passive_wait(argv);
        return pm_cmd_run(argc - 1, argv + 1);
    }
    if (!strcmp(argv[1], "material"))
        return pm_cmd_material(argc - 1, argv + 1);
    if (!strcmp(argv[1], "render"))
        return pm_cmd_render(argc - 1, argv + 1);
    fprintf(stderr, "pmech: unknown command '%s' (commands: run, material, render; see pmech --help)\n", argv[1]);
    return 2;
}
