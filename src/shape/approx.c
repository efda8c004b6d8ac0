/* Registry of approximations: adding one is one file and one line in `kinds`. */
#include "pmech/approx.h"
#include "pmech/error.h"

#include <stdlib.h>
#include <string.h>

extern const pm_approx_ops pm_approx_linear_ops;

static const pm_approx_ops *const kinds[] = {&pm_approx_linear_ops};
static const char *const names[] = {"linear", NULL};

const char *const *pm_approx_names(void) { return names; }

int pm_approx_create(const char *name, const pm_grid *g, pm_approx **out)
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
        *out = a;
        return PM_OK;
    }
    return pm_error_set(PM_EINPUT, "shape_function '%s' is not available; available: linear", name);
}

void pm_approx_destroy(pm_approx *a)
{
    if (!a)
        return;
    if (a->ops->destroy)
        a->ops->destroy(a);
    free(a);
}
