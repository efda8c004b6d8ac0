/**
 * @file grid.h
 * @brief The background grid of MPM: nodes, cells, named boundary node sets and point location.
 */
#ifndef PMECH_GRID_H
#define PMECH_GRID_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Cell types. */
typedef enum pm_element { PM_QUAD4 = 0, PM_TRI3 = 1 } pm_element;

/** A named set of grid nodes with the outward normal of that boundary (zero if not a straight side). */
typedef struct pm_node_set {
    char name[64];     /**< "x_min", "x_max", "y_min", "y_max", or a mesh physical group */
    size_t n;          /**< number of nodes */
    int32_t *nodes;    /**< node indices */
    double normal[2];  /**< outward unit normal */
} pm_node_set;

/** A background grid. Structured rectangle grids keep their spacing for O(1) point location. */
typedef struct pm_grid {
    pm_element element;      /**< cell type */
    int nodes_per_cell;      /**< 4 (quad4) or 3 (tri3) */
    size_t n_nodes;          /**< number of nodes */
    size_t n_cells;          /**< number of cells */
    double *x;               /**< node coordinates, 2 per node */
    int32_t *conn;           /**< cell connectivity, nodes_per_cell per cell, counter-clockwise */
    double lo[2], hi[2];     /**< bounding box */
    double h_min;            /**< smallest cell size (for the CFL condition) */
    int structured;          /**< 1 for a `rectangle` grid */
    double origin[2];        /**< structured: lower-left corner */
    double h[2];             /**< structured: cell size */
    int cells[2];            /**< structured: cells along x and y */
    size_t n_sets;           /**< named node sets */
    pm_node_set *sets;       /**< the sets (x_min, x_max, y_min, y_max at least) */
} pm_grid;

/**
 * @brief Build a structured rectangle grid.
 * @param g grid to fill
 * @param origin lower-left corner
 * @param size extent along x and y (> 0)
 * @param cells cells along x and y (>= 1)
 * @param element PM_QUAD4, or PM_TRI3 (each quad split along its lower-left to upper-right diagonal)
 * @return PM_OK, PM_EINPUT for nonsensical sizes, PM_ENOMEM
 */
int pm_grid_rectangle(pm_grid *g, const double origin[2], const double size[2],
                      const int cells[2], pm_element element);

/** @brief Free a grid and zero it. Safe on a zeroed struct. */
void pm_grid_free(pm_grid *g);

/**
 * @brief Find the cell containing point @p xp.
 * @param g grid
 * @param xp point
 * @return cell index, or -1 if the point is outside the grid
 */
int32_t pm_grid_locate(const pm_grid *g, const double xp[2]);

/** @brief The node set called @p name, or NULL. */
const pm_node_set *pm_grid_find_set(const pm_grid *g, const char *name);

/**
 * @brief Add a node set of all nodes with coordinate @p axis (0 = x, 1 = y) equal to @p value
 *        (within 1e-9 of the cell size).
 * @param g grid
 * @param name name of the new set
 * @param axis 0 or 1
 * @param value coordinate
 * @param normal outward normal to record (may be NULL: zero)
 * @return index of the set, or a negative status (no node on that line gives PM_EINPUT)
 */
int pm_grid_add_line_set(pm_grid *g, const char *name, int axis, double value, const double normal[2]);

#ifdef __cplusplus
}
#endif
#endif
