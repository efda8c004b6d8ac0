/* Runs with flat arguments, for bindings (the Python package) that call the library through a foreign
 * function interface and must not depend on the layout of option structs that grow. */
#include "pmech/error.h"
#include "pmech/sim.h"
#include "pmech/strength_reduction.h"

#include <stdlib.h>

int pm_run_to(const pm_case *c, const char *out_dir, int threads, int quiet, pm_run_stats *stats)
{
    pm_run_opts o = {.out_dir = out_dir, .quiet = quiet, .threads = threads, .write_output = 1, .stats = stats};
    return pm_run(c, &o, NULL);
}

int pm_strength_reduction_to(const pm_case *c, const char *out_dir, int threads, int quiet, double *fos, double *lo,
                             double *hi)
{
    pm_run_opts o = {.out_dir = out_dir && out_dir[0] ? out_dir : NULL, .quiet = quiet, .threads = threads,
                     .write_output = !(out_dir && !out_dir[0])};
    pm_srf_result *r = malloc(sizeof *r);
    if (!r)
        return pm_error_set(PM_ENOMEM, "out of memory for a strength reduction");
    const int rc = pm_strength_reduction(c, &o, r);
    if (!rc) {
        *fos = r->fos;
        *lo = r->lo;
        *hi = r->hi;
    }
    free(r);
    return rc;
}
