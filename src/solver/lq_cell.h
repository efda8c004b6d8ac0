/*
 * The structured linear quad4 grid of the explicit fast path: cell, node numbers and shape functions
 * of a particle with the grid's constants hoisted out of the particle loops (explicit_passes.c).
 */
#ifndef PMECH_LQ_CELL_H
#define PMECH_LQ_CELL_H

#include "pmech/grid.h"
#include "pmech/particles.h"

#include <stdint.h>

#if PM_DIM != 2
#error "the linear quad4 cell is a 2-D cell"
#endif

/*
 * The structured linear quad4 grid with its constants hoisted out of the particle loops. The cell's
 * row comes from a multiplication by 1 / nx, not an integer division: the division alone costs as
 * much as the rest of the shape functions. The product can be one off next to exact multiples,
 * hence the two corrections. Values are those of pm_linear_quad_eval() bit for bit.
 */
typedef struct lq_grid {
    double ox, oy, ihx, ihy, inx;
    int32_t nx;
} lq_grid;

static inline lq_grid lq_of(const pm_grid *g)
{
    lq_grid q = {g->origin[0], g->origin[1], 1.0 / g->h[0], 1.0 / g->h[1], 1.0 / g->cells[0], g->cells[0]};
    return q;
}

static inline void lq_cell(const lq_grid *q, int32_t cell, int32_t *cx, int32_t *cy)
{
    int64_t y = (int64_t)((double)cell * q->inx);
    y -= y * q->nx > cell;
    y += (y + 1) * q->nx <= cell;
    *cy = (int32_t)y;
    *cx = cell - (int32_t)y * q->nx;
}

/* The four nodes of a cell, counter-clockwise from the lower left. */
static inline void lq_nodes(const lq_grid *q, int32_t cx, int32_t cy, int32_t node[4])
{
    const int32_t n0 = cy * (q->nx + 1) + cx;
    node[0] = n0; node[1] = n0 + 1; node[2] = n0 + q->nx + 2; node[3] = n0 + q->nx + 1;
}

static inline void lq_N(const lq_grid *q, const double xp[PM_DIM], int32_t cx, int32_t cy, double N[4], double *xi_,
                        double *eta_)
{
    const double xi = (xp[0] - q->ox) * q->ihx - cx;
    const double eta = (xp[1] - q->oy) * q->ihy - cy;
    N[0] = (1 - xi) * (1 - eta); N[1] = xi * (1 - eta); N[2] = xi * eta; N[3] = (1 - xi) * eta;
    *xi_ = xi;
    *eta_ = eta;
}

static inline void lq_eval(const lq_grid *q, const double xp[PM_DIM], int32_t cx, int32_t cy, double N[4],
                           double dN[4][PM_DIM])
{
    double xi, eta;
    lq_N(q, xp, cx, cy, N, &xi, &eta);
    dN[0][0] = -(1 - eta) * q->ihx; dN[0][1] = -(1 - xi) * q->ihy;
    dN[1][0] = (1 - eta) * q->ihx;  dN[1][1] = -xi * q->ihy;
    dN[2][0] = eta * q->ihx;        dN[2][1] = xi * q->ihy;
    dN[3][0] = -eta * q->ihx;       dN[3][1] = (1 - xi) * q->ihy;
}

#endif
