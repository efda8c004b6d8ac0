/* Internal to src/io: one material object of a case or driver file to pm_material. */
#ifndef PMECH_IO_MATERIAL_READ_H
#define PMECH_IO_MATERIAL_READ_H

#include <jansson.h>

#include "pmech/material.h"

/**
 * Read a material object at key path @p path of @p file: `model`, `density`, the elastic pair (when
 * the model takes one) and the model's parameters, with range checks from its pm_param_spec table,
 * then the model's own cross-checks (ops->init). @p need_name: `name` is required (case files) or
 * optional (driver files). Returns PM_OK or PM_EINPUT naming the key path.
 */
int pm_read_material(const char *file, const char *path, json_t *obj, int need_name, pm_material *m);

#endif
