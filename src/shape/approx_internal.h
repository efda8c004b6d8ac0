/**
 * @file approx_internal.h
 * @brief Inside of an approximation (the solvers' and the kinds', not the library user's): the
 *        state behind the opaque pm_approx and the inline linear quad4 functions of the hot loops.
 */
#ifndef PMECH_APPROX_INTERNAL_H
#define PMECH_APPROX_INTERNAL_H

#include "pmech/approx.h"

/** An approximation bound to a grid (or node cloud). */
struct pm_approx {
    const pm_approx_ops *ops;  /**< the kind */
    const pm_grid *grid;       /**< nodes it interpolates from */
    int fast_linear_quad;      /**< 1: linear quad4 on a structured grid; solvers may inline it */
    int n_threads;             /**< OpenMP threads for connect (set by the owner; 1 by default) */
    void *data;                /**< private data of the kind */
    pm_approx_opts opts;       /**< tuning keys given at creation */
};

/**
 * @brief Linear shape functions of a structured quad4 cell, inline for the solvers' hot loops.
 * @param g structured grid
 * @param xp point
 * @param cell cell containing xp
 * @param node receives the 4 node indices (counter-clockwise from lower-left)
 * @param N receives the 4 values
 * @param dN receives the 4 gradients, (d/dx, d/dy) interleaved
 */
static inline void pm_linear_quad_eval(const pm_grid *g, const double xp[2], int32_t cell,
                                       int32_t node[4], double N[4], double dN[8])
{
    const int nx = g->cells[0];
    const int cx = cell % nx, cy = cell / nx;
    const double ihx = 1.0 / g->h[0], ihy = 1.0 / g->h[1];
    const double xi = (xp[0] - g->origin[0]) * ihx - cx;
    const double eta = (xp[1] - g->origin[1]) * ihy - cy;
    const int32_t n0 = cy * (nx + 1) + cx;
    node[0] = n0; node[1] = n0 + 1; node[2] = n0 + nx + 2; node[3] = n0 + nx + 1;
    N[0] = (1 - xi) * (1 - eta); N[1] = xi * (1 - eta); N[2] = xi * eta; N[3] = (1 - xi) * eta;
    dN[0] = -(1 - eta) * ihx; dN[1] = -(1 - xi) * ihy;
    dN[2] = (1 - eta) * ihx;  dN[3] = -xi * ihy;
    dN[4] = eta * ihx;        dN[5] = xi * ihy;
    dN[6] = -eta * ihx;       dN[7] = (1 - xi) * ihy;
}

#endif
