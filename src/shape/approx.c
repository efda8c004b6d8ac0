/* Registry of approximations: adding one is one file and one line in `kinds`. */
#include "pmech/approx.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const pm_approx_ops pm_approx_linear_ops;
extern const pm_approx_ops pm_approx_gimp_ops;
extern const pm_approx_ops pm_approx_bspline2_ops;
extern const pm_approx_ops pm_approx_lme_ops;

static const pm_approx_ops *const kinds[] = {&pm_approx_linear_ops, &pm_approx_gimp_ops, &pm_approx_bspline2_ops,
                                             &pm_approx_lme_ops};
static const char *const names[] = {"linear", "gimp", "bspline2", "lme", NULL};

const char *const *pm_approx_names(void) { return names; }

int pm_approx_create_opts(const char *name, const pm_grid *g, const pm_approx_opts *opts, pm_approx **out)
{
    *out = NULL;
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        if (strcmp(kinds[k]->name, name) != 0)
            continue;
        pm_approx *a = calloc(1, sizeof *a);
        if (!a)
            return pm_error_set(PM_ENOMEM, "out of memory");
        a->ops = kinds[k];
        a->grid = g;
        a->n_threads = 1;
        a->opts.lme_gamma = NAN;
        a->opts.support_radius = NAN;
        if (opts)
            a->opts = *opts;
        if (a->ops->init) {
            int rc = a->ops->init(a);
            if (rc) {
                pm_approx_destroy(a);
                return rc;
            }
        }
        *out = a;
        return PM_OK;
    }
    char list[256] = "";
    for (size_t k = 0; names[k]; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", names[k]);
    return pm_error_set(PM_EINPUT, "shape_function '%s' is not available; available: %s", name, list);
}

int pm_approx_create(const char *name, const pm_grid *g, pm_approx **out)
{
    return pm_approx_create_opts(name, g, NULL, out);
}

void pm_approx_destroy(pm_approx *a)
{
    if (!a)
        return;
    if (a->ops->destroy)
        a->ops->destroy(a);
    free(a);
}
