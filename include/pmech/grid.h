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
    size_t n_edges;    /**< a Gmsh 1-D group on the mesh's boundary: its line elements (0 for other sets) */
    int32_t *edges;    /**< 2 node indices per edge, each edge turned so that the element owning it lies on
                            its left (the outward normal is its direction turned clockwise), the edges in
                            chains: where one edge ends the next one starts, when the group allows it */
} pm_node_set;

/** A named set of cells: a 2-D physical group of a Gmsh mesh (for `gmsh_group` body shapes). */
typedef struct pm_cell_set {
    char name[64];     /**< physical group name */
    size_t n;          /**< number of cells */
    int32_t *cells;    /**< cell indices */
} pm_cell_set;

/** Largest |coordinate| / cell size a grid accepts: a double holds a coordinate to 2.2e-16 of its size,
 *  so beyond this a point's place in its cell is known to worse than 2.2e-7 of the cell. */
#define PM_COORD_PER_CELL_MAX 1e9

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
    size_t n_cell_sets;      /**< named cell sets (Gmsh 2-D physical groups) */
    pm_cell_set *cell_sets;  /**< the cell sets */
    void *locator;           /**< unstructured grids: private point-location index (bins + neighbours) */
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

/**
 * @brief Find the cell containing @p xp, starting from cell @p hint (e.g. the particle's cell at
 *        the previous step). Unstructured grids check the hint and walk across edges towards the
 *        point for a few steps before falling back to the bins; structured grids ignore the hint.
 * @param g grid
 * @param xp point
 * @param hint a cell index, or -1
 * @return cell index, or -1 if the point is outside the grid
 */
int32_t pm_grid_locate_from(const pm_grid *g, const double xp[2], int32_t hint);

/**
 * @brief Build an unstructured grid from nodes and cells (copied). Cells are reoriented
 *        counter-clockwise; the bounding box, h_min and the point locator are computed. The grid has
 *        the node sets x_min, x_max, y_min, y_max of the nodes on its bounding box sides (those
 *        that have nodes).
 * @param g grid to fill
 * @param n_nodes number of nodes
 * @param x node coordinates (2 per node)
 * @param n_cells number of cells
 * @param conn connectivity (3 or 4 node indices per cell)
 * @param element PM_TRI3 or PM_QUAD4
 * @return PM_OK, PM_EINPUT (node index out of range, degenerate cell), PM_ENOMEM
 */
int pm_grid_unstructured(pm_grid *g, size_t n_nodes, const double *x, size_t n_cells, const int32_t *conn,
                         pm_element element);

/**
 * @brief Read a Gmsh mesh (MSH 4.1 ASCII) into an unstructured grid: 3-node triangles and
 *        4-node quads (a mesh with both has its quads split into two triangles). Every 1-D (and 0-D)
 *        physical group becomes a node set with the group's name (outward normal recorded when its
 *        nodes lie on one straight line; its line elements kept as pm_node_set::edges when every one
 *        of them lies on the mesh's boundary, i.e. belongs to one element), every 2-D physical group a
 *        cell set. Nodes used by no
 *        2-D element are dropped.
 * @param g grid to fill
 * @param path the .msh file
 * @return PM_OK, PM_EIO (cannot read), PM_EINPUT (message names path:line), PM_ENOMEM
 */
int pm_grid_gmsh_read(pm_grid *g, const char *path);

/**
 * @brief Make an unstructured quad4 grid that is a lattice (equal axis-aligned cells filling its
 *        bounding box, as a transfinite Gmsh rectangle) the structured grid of those cells: nodes and
 *        cells renumbered to the `rectangle` grid's order and coordinates, node sets (with their
 *        edges) and cell sets renumbered with them, the point locator dropped. Any other grid is left
 *        as it is.
 * @param g grid
 * @return 1 if renumbered, 0 if not a lattice (unchanged), PM_ENOMEM (unchanged)
 */
int pm_grid_adopt_lattice(pm_grid *g);

/**
 * @brief Add a named node set (nodes copied).
 * @return index of the set, or a negative status
 */
int pm_grid_add_node_set(pm_grid *g, const char *name, size_t n, const int32_t *nodes, const double normal[2]);

/** @brief The cell set called @p name, or NULL. */
const pm_cell_set *pm_grid_find_cell_set(const pm_grid *g, const char *name);

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

/**
 * @brief Which side of the grid's bounding box a boundary name means.
 * @param name a boundary name ("x_min", "x_max", "y_min", "y_max", ...)
 * @param axis receives the side's axis (0 = x, 1 = y) when it is a side
 * @param hi receives 1 for the upper side (x_max, y_max), 0 for the lower
 * @return 1 if @p name names a side, 0 otherwise (a mesh group or a line)
 */
int pm_grid_side_of(const char *name, int *axis, int *hi);

#ifdef __cplusplus
}
#endif
#endif
