/* `pmech run`: load a case, run it, report where the results are. */
#include "cli/commands.h"

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int bad_usage(const char *what)
{
    fprintf(stderr, "pmech run: %s\nusage: pmech run CASE.json [-o DIR] [--quiet] [--verbose] [--threads N]\n", what);
    return 2;
}

int pm_cmd_run(int argc, char **argv)
{
    const char *case_file = NULL;
    pm_run_opts o = {.out_dir = NULL, .quiet = 0, .threads = 0, .write_output = 1};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
            if (++i >= argc)
                return bad_usage("-o needs a directory");
            o.out_dir = argv[i];
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
    pm_case c;
    int rc = pm_case_load(case_file, &c);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        pm_case_free(&c);
        return pm_exit_code(rc);
    }
    const char *dir = o.out_dir ? o.out_dir : c.output.directory;
    rc = pm_run(&c, &o, NULL);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        if (rc != PM_EINPUT)
            fprintf(stderr, "pmech: results written so far are in %s/\n", dir);
    } else if (!o.quiet) {
        fprintf(stderr, "pmech: results in %s/ (open %s/particles.pvd in ParaView)\n", dir, dir);
    }
    pm_case_free(&c);
    return pm_exit_code(rc);
}
