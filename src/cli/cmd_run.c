/* `pmech run`: load a case, run it, report where the results are. */
#include "cli/commands.h"

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"
#include "pmech/strength_reduction.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RUN_USAGE "pmech run CASE.json [-o DIR] [--overwrite] [--restart DIR] [--quiet] [--verbose] [--threads N]\n"

void pm_cmd_run_usage(FILE *f)
{
    fprintf(f, "usage: " RUN_USAGE
               "  Run the case file CASE.json (keys: docs/input.md) to its end time.\n"
               "  -o, --output DIR  write results to DIR instead of the case's output.directory\n"
               "  --overwrite       replace the outputs of an earlier run in that directory (without it such a\n"
               "                    directory is refused and nothing in it is touched)\n"
               "  --restart DIR     continue the run whose checkpoint.h5 is in DIR (written at the end, on Ctrl-C or\n"
               "                    SIGTERM, and every output.checkpoint_interval): the results after its time are\n"
               "                    the same bytes as a run never stopped, with the same --threads (docs/checkpoint.md)\n"
               "  -q, --quiet       no progress line\n"
               "  -v, --verbose     implicit runs: print every Newton iteration instead of the progress line\n"
               "  --threads N       OpenMP threads (default: OMP_NUM_THREADS if set, else all cores, but one\n"
               "                    for runs of fewer than 5,000 particles)\n"
               "  -h, --help        this text\n"
               "  Outputs: particles.pvd (open in ParaView) with one particles_NNNNNN.vtu per frame, grid.vtu,\n"
               "  probes.csv, energy.csv, run.json, checkpoint.h5 (what --restart continues from); implicit runs\n"
               "  add newton.log and reactions.csv; a case with analysis.strength_reduction writes\n"
               "  strength_reduction.csv and one srf_<F>/ per trial.\n");
}

static int bad_usage(const char *what)
{
    fprintf(stderr, "pmech run: %s\nusage: " RUN_USAGE "(pmech run --help)\n", what);
    return 2;
}

static int help(void)
{
    pm_cmd_run_usage(stdout);
    return 0;
}

/* A case with analysis.strength_reduction is a search of many runs; the factor of safety is its result. */
static int run_strength_reduction(const pm_case *c, const pm_run_opts *o, const char *dir)
{
    /* the trials run quietly: the case's warnings are said once, here */
    char warnings[8][PM_WARNING_LEN];
    const size_t nw = o->quiet ? 0 : pm_case_warnings(c, warnings, 8);
    for (size_t k = 0; k < nw && k < 8; k++)
        fprintf(stderr, "pmech: warning: %s\n", warnings[k]);
    pm_srf_result *r = malloc(sizeof *r);
    if (!r) {
        fprintf(stderr, "pmech: out of memory\n");
        return PM_ENOMEM;
    }
    int rc = pm_strength_reduction(c, o, r);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        if (rc != PM_EINPUT)
            fprintf(stderr, "pmech: the trials run so far are in %s/strength_reduction.csv\n", dir);
    } else {
        printf("factor of safety %.4f (holds at %.4f, fails at %.4f)\n", r->fos, r->lo, r->hi);
        if (!o->quiet)
            fprintf(stderr, "pmech: trials in %s/strength_reduction.csv; the last that held in %s/srf_%.4f/, the "
                    "first that failed in %s/srf_%.4f/\n", dir, dir, r->lo, dir, r->hi);
    }
    free(r);
    return rc;
}

int pm_cmd_run(int argc, char **argv)
{
    const char *case_file = NULL;
    int overwrite = 0;
    pm_run_opts o = {.out_dir = NULL, .quiet = 0, .threads = 0, .write_output = 1};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help"))
            return help();
        if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
            if (++i >= argc)
                return bad_usage("-o needs a directory");
            if (!argv[i][0])
                return bad_usage("-o \"\": the output directory is empty (give a directory, e.g. -o .)");
            o.out_dir = argv[i];
        } else if (!strcmp(argv[i], "--restart")) {
            if (++i >= argc)
                return bad_usage("--restart needs the directory of the run to continue");
            if (!argv[i][0])
                return bad_usage("--restart \"\": the directory is empty (give the run's output directory)");
            o.restart = argv[i];
        } else if (!strcmp(argv[i], "--overwrite")) {
            overwrite = 1;
        } else if (!strcmp(argv[i], "--quiet") || !strcmp(argv[i], "-q")) {
            o.quiet = 1;
        } else if (!strcmp(argv[i], "--verbose") || !strcmp(argv[i], "-v")) {
            o.verbose = 1;
        } else if (!strcmp(argv[i], "--threads")) {
            char *end = NULL;
            if (++i >= argc)
                return bad_usage("--threads needs a number");
            long n = strtol(argv[i], &end, 10);
            if (*end || n < 1 || n > 4096)
                return bad_usage("--threads takes a whole number from 1 to 4096");
            o.threads = (int)n;
        } else if (argv[i][0] == '-') {
            char msg[256];
            snprintf(msg, sizeof msg, "unknown option '%s'", argv[i]);
            return bad_usage(msg);
        } else if (!case_file) {
            case_file = argv[i];
        } else {
            return bad_usage("only one case file may be given");
        }
    }
    if (!case_file)
        return bad_usage("no case file given");
    if (o.restart && o.out_dir && strcmp(o.restart, o.out_dir))
        return bad_usage("--restart DIR continues the run in DIR: -o cannot name another directory");
    if (o.restart && overwrite)
        return bad_usage("--restart keeps the run's outputs up to its checkpoint: --overwrite contradicts it");
    pm_case c;
    int rc = pm_case_load(case_file, &c);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        pm_case_free(&c);
        return pm_exit_code(rc);
    }
    const char *dir = o.restart ? o.restart : o.out_dir ? o.out_dir : c.output.directory;
    int lock_fd = -1;
    /* a restart continues the outputs found there */
    rc = pm_cli_claim_output(dir, overwrite || o.restart, &lock_fd);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        pm_case_free(&c);
        return pm_exit_code(rc);
    }
    o.interrupt = pm_cli_signals_install();
    if (c.analysis.strength_reduction.enabled && o.restart) {
        fprintf(stderr, "pmech: --restart: a strength reduction is a search of many runs; it cannot be continued "
                        "from a checkpoint (run it again)\n");
        pm_cli_release_output(lock_fd);
        pm_case_free(&c);
        return 2;
    }
    if (c.analysis.strength_reduction.enabled) {
        rc = run_strength_reduction(&c, &o, dir);
        pm_cli_release_output(lock_fd);
        pm_case_free(&c);
        return rc == PM_EINTR ? 128 + (int)*o.interrupt : pm_exit_code(rc);
    }
    pm_cli_signals_prepare(dir, case_file);
    rc = pm_run(&c, &o, NULL);
    pm_cli_signals_finished();
    pm_cli_release_output(lock_fd);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        if (rc != PM_EINPUT)
            fprintf(stderr, "pmech: results written so far are in %s/\n", dir);
    } else if (!o.quiet) {
        fprintf(stderr, "pmech: results in %s/ (open %s/particles.pvd in ParaView)\n", dir, dir);
    }
    pm_case_free(&c);
    return rc == PM_EINTR ? 128 + (int)*o.interrupt : pm_exit_code(rc);
}
