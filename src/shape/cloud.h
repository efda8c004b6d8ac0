/**
 * @file cloud.h (internal to src/, not installed)
 * @brief A cloud of nodes (GMM: Lagrangian nodes; RKPM: the particles themselves) and the
 *        uniform cell list that answers "which nodes lie within r of x".
 *
 * The cell list is built from the node positions at one moment (pm_cloud_rebuild()) and stays
 * valid while no node has moved more than the skin distance from where it was binned: a query of
 * radius r visits the cells within r + skin, then tests the positions. The owner moves nodes by
 * writing pm_cloud::x in place and calls pm_cloud_update(), which rebuilds only when the largest
 * displacement since the last build exceeds the skin, and otherwise copies the positions into the
 * cell order the queries scan: queries see the positions as of the last update or build, so every
 * move must be followed by an update before the next query. Queries never allocate: they write
 * into buffers the caller provides, and are safe to run from many threads at once (they only read
 * the cloud).
 */
#ifndef PMECH_CLOUD_H
#define PMECH_CLOUD_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Tuning of a cloud; NAN (or <= 0) picks the default given for each field. */
typedef struct pm_cloud_opts {
    double h;         /**< nodal spacing (m); default sqrt(mean volume) with volumes, else sqrt(box area / n) */
    double cell_size; /**< side of the cell-list squares (m); default 2.5 h (about an MLS radius plus the skin) */
    double skin;      /**< displacement that triggers a rebuild (m); default 0.25 h */
} pm_cloud_opts;

/** A node cloud with its cell list. Fields other than x and vol are read-only for users. */
typedef struct pm_cloud {
    size_t n;         /**< number of nodes */
    double *x;        /**< current positions, 2 per node (the owner may write them, then pm_cloud_update()) */
    double *vol;      /**< node volumes (RKPM quadrature weights Delta V_I); 1 when none were given */
    double h;         /**< nodal spacing used for defaults (m) */
    double cell;      /**< cell side (m) */
    double skin;      /**< rebuild threshold (m) */
    double lo[2];     /**< lower corner of the cell list */
    int nc[2];        /**< cells per direction */
    int32_t *start;   /**< nc[0] * nc[1] + 1 offsets into order */
    int32_t *order;   /**< node indices sorted by cell */
    double *x_built;  /**< positions at the last build, 2 per node */
    double *x_sorted; /**< positions as of the last update or build, in the order of @c order (what
                           queries scan: contiguous within a row of cells) */
    size_t cap_cells; /**< allocated length of start */
    size_t n_builds;  /**< number of builds so far (the first one included) */
    double last_move; /**< largest displacement since the last build, as of the last update */
} pm_cloud;

/**
 * @brief Create a cloud from node positions (copied) and build its cell list.
 * @param n number of nodes (> 0)
 * @param x positions, 2 per node
 * @param vol node volumes (NULL: all 1)
 * @param opts tuning (NULL: all defaults)
 * @param out receives the cloud; free with pm_cloud_destroy()
 * @return PM_OK, PM_EINPUT (no nodes, non-finite positions, negative volume), PM_ENOMEM
 */
int pm_cloud_create(size_t n, const double *x, const double *vol, const pm_cloud_opts *opts, pm_cloud **out);

/** @brief Free a cloud (NULL is fine). @param c the cloud */
void pm_cloud_destroy(pm_cloud *c);

/**
 * @brief Rebuild the cell list from the current positions (bounding box, counting sort).
 * @param c the cloud
 * @return PM_OK, PM_EINPUT for a non-finite position, PM_ENOMEM when the box grew and the
 *         cell array could not be enlarged
 */
int pm_cloud_rebuild(pm_cloud *c);

/**
 * @brief After the owner moved nodes: rebuild the cell list if some node moved more than the skin
 *        since the last build; otherwise record the largest displacement (pm_cloud::last_move) and
 *        hand the new positions to the queries (pm_cloud::x_sorted).
 * @param c the cloud
 * @param rebuilt receives 1 if the list was rebuilt, 0 if not (may be NULL)
 * @return PM_OK or the status of pm_cloud_rebuild()
 */
int pm_cloud_update(pm_cloud *c, int *rebuilt);

/**
 * @brief Put a cloud back into a state it had (a checkpoint): the positions @p x_built of its last
 *        build, binned with cell side @p cell, then the current positions @p x handed to the queries.
 *
 * The cell list's order (a stable counting sort by node index) is a function of the built positions
 * and the cell side alone, so the restored list, and with it the order of every neighbour list and
 * shape-function sum, is the one the cloud had; @p n_builds is the count it had (candidate lists are
 * tagged with it).
 * @param c the cloud, with as many nodes as the state
 * @param x current positions, 2 per node
 * @param x_built positions at the last build, 2 per node
 * @param cell cell side of the last build (m, > 0)
 * @param n_builds builds so far
 * @return PM_OK; PM_EINPUT for a non-finite position or cell side, or positions that moved farther
 *         than the skin since @p x_built (no cloud is left in that state after pm_cloud_update())
 */
int pm_cloud_restore(pm_cloud *c, const double *x, const double *x_built, double cell, size_t n_builds);

/**
 * @brief All nodes I with |x_I - x| < r (positions as of the last pm_cloud_update() or
 *        pm_cloud_rebuild()), in no particular order.
 *
 * Correct as long as no node moved more than the skin since the last build (pm_cloud_update()
 * keeps it so). Writes at most @p cap entries; *n_found is the true count, so a caller can tell
 * that its buffer was too small.
 * @param c the cloud
 * @param x query point
 * @param r radius (m)
 * @param cap capacity of @p idx and @p d2
 * @param idx receives node indices
 * @param d2 receives squared distances |x_I - x|^2 (may be NULL)
 * @param n_found receives the number of nodes within r (may exceed @p cap)
 * @return PM_OK, or PM_EINPUT for a non-finite point or radius
 */
int pm_cloud_query(const pm_cloud *c, const double x[2], double r, int cap, int32_t *idx, double *d2,
                   int *n_found);

/**
 * @brief The adaptive search of seed 000 section 5.3: start from radius @p r0 and multiply it by
 *        @p growth until at least @p min_count nodes lie within it.
 * @param c the cloud
 * @param x query point
 * @param r0 initial radius (> 0)
 * @param min_count nodes wanted (MLS: 6)
 * @param growth factor per step (> 1; 1.25 is a good choice)
 * @param cap capacity of @p idx and @p d2
 * @param idx receives node indices
 * @param d2 receives squared distances (may be NULL)
 * @param n_found receives the number of nodes within the final radius
 * @param r_used receives the final radius
 * @return PM_OK; PM_ESIM when the count jumps past @p cap in one growth step before reaching
 *         @p min_count, or the whole cloud has fewer than @p min_count nodes; PM_EINPUT for bad
 *         parameters or a non-finite point
 */
int pm_cloud_query_adaptive(const pm_cloud *c, const double x[2], double r0, int min_count, double growth,
                            int cap, int32_t *idx, double *d2, int *n_found, double *r_used);

/**
 * @brief Order a neighbour list by distance (ties by node index), in place; insertion sort, meant
 *        for the few dozen nodes of one stencil.
 * @param n entries
 * @param idx node indices
 * @param d2 squared distances
 */
void pm_cloud_sort_by_distance(int n, int32_t *idx, double *d2);

#ifdef __cplusplus
}
#endif
#endif
