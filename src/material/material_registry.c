/* The list of constitutive models: adding a model is one file plus one line here. */
#include "material/material_internal.h"

#include <stddef.h>
#include <string.h>

static const pm_material_ops *const registry[] = {
    &pm_linear_elastic_ops,
    &pm_neo_hookean_ops,
    &pm_von_mises_ops,
    &pm_mohr_coulomb_ops,
    &pm_drucker_prager_ops,
    &pm_viscoplastic_dp_ops,
    &pm_granular_ops,
};

#define N_MODELS (sizeof registry / sizeof registry[0])

static const char *const names[N_MODELS + 1] = {
    "linear_elastic",
    "neo_hookean",
    "von_mises",
    "mohr_coulomb",
    "drucker_prager",
    "viscoplastic_drucker_prager",
    "granular",
    NULL,
};

const pm_material_ops *pm_material_find(const char *name)
{
    if (!name)
        return NULL;
    for (size_t i = 0; i < N_MODELS; i++)
        if (!strcmp(registry[i]->name, name))
            return registry[i];
    return NULL;
}

const char *const *pm_material_names(void) { return names; }
