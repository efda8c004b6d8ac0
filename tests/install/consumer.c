/*
 * A program outside the tree that uses the installed library through pmech.h and pkg-config: it loads
 * the case named on its command line, runs it without writing files and prints the time reached.
 */
#include <pmech/pmech.h>
#include <stdio.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: consumer CASE.json\n");
        return 2;
    }
    pm_case c;
    if (pm_case_load(argv[1], &c) != PM_OK) {
        fprintf(stderr, "consumer: %s\n", pm_error_message());
        pm_case_free(&c);
        return 2;
    }
    pm_run_stats stats = {0};
    pm_run_opts o = {.quiet = 1, .threads = 1, .write_output = 0, .stats = &stats};
    const int rc = pm_run(&c, &o, NULL);
    printf("%s: reached t = %g s in %ld steps\n", rc == PM_OK ? "ok" : pm_error_message(), stats.t, stats.steps);
    const int ok = rc == PM_OK && stats.t >= c.analysis.end_time * (1 - 1e-9);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
