/* Point location on unstructured grids (internal to src/mesh). */
#ifndef PMECH_MESH_INTERNAL_H
#define PMECH_MESH_INTERNAL_H

#include "pmech/grid.h"

/** Build g->locator (bins of cells + edge neighbours). Returns PM_OK or PM_ENOMEM. */
int pm_grid_locator_build(pm_grid *g);

/** Free a locator (NULL is fine). */
void pm_grid_locator_free(void *loc);

/** The cell of g containing xp, starting from @p hint (-1: none); -1 if outside. */
int32_t pm_grid_locator_find(const pm_grid *g, const double xp[2], int32_t hint);

/** qsort order of int32_t values (node and cell indices). */
int pm_mesh_cmp_i32(const void *a, const void *b);

/** 1 if xp lies in cell c of g (edges included, with a round-off tolerance); cells are convex. */
int pm_grid_cell_contains(const pm_grid *g, int32_t c, const double xp[2]);

#endif
