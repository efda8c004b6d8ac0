/**
 * @file approx.h
 * @brief How a material point sees the nodes: connectivity and shape functions N_I(x_p) with
 *        gradients. MPM, GMM and RKPM differ only in the approximation plugged in here.
 */
#ifndef PMECH_APPROX_H
#define PMECH_APPROX_H

#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of nodes one point may be connected to. */
#define PM_STENCIL_MAX 64

/** The nodes a point talks to, their shape function values and gradients. */
typedef struct pm_stencil {
    int n;                           /**< number of nodes */
    int32_t node[PM_STENCIL_MAX];    /**< node indices */
    double N[PM_STENCIL_MAX];        /**< shape function values */
    double dN[PM_STENCIL_MAX][2];    /**< shape function gradients (d/dx, d/dy) */
} pm_stencil;

typedef struct pm_approx pm_approx;

/**
 * Methods an approximation serves, the bits of pm_approx_ops::methods: bit m stands for the
 * pm_method m of case.h (PM_METHOD_MPM = 0, GMM = 1, RKPM = 2), so `1u << c->method` tests a case.
 */
enum {
    PM_APPROX_MPM = 1u << 0,   /**< grid kinds, for `method: mpm` */
    PM_APPROX_GMM = 1u << 1,   /**< node-cloud kinds of the generalized meshfree method */
    PM_APPROX_RKPM = 1u << 2   /**< node-cloud kinds of the reproducing kernel particle method */
};

/** Operations of an approximation; one static table per kind. */
typedef struct pm_approx_ops {
    const char *name;  /**< the `shape_function` value, e.g. "linear" */
    unsigned methods;  /**< PM_APPROX_* bits of the methods that may use this kind */
    /**
     * 1: the functions take the nodal values at the nodes where essential conditions are imposed
     * (Kronecker delta there: linear; lme on the boundary of its hull), so those values can be set
     * directly; 0: they only approximate them (mls, rk_cubic, gimp, bspline2), and a meshfree
     * solver must transform the nodal unknowns to impose them.
     */
    int interpolating;
    /** 1: on a structured quad4 grid pm_linear_quad_eval() gives exactly this kind's functions. */
    int linear_quad_fast;
    /**
     * Rebuild connectivity for all points (MPM: locate the cell of each point into p->cell;
     * meshfree: neighbour search). Returns PM_OK or PM_ESIM naming a particle that left the grid.
     */
    int (*connect)(pm_approx *a, pm_particles *p);
    /** Fill N and dN/dx for point @p ip. Returns PM_OK or PM_ESIM. */
    int (*eval)(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s);
    /** Free private data (may be NULL). */
    void (*destroy)(pm_approx *a);
    /**
     * Check that the kind fits the grid and set up private data from pm_approx::opts (may be
     * NULL). Called once by pm_approx_create_opts(); returns PM_OK or PM_EINPUT/PM_ENOMEM.
     */
    int (*init)(pm_approx *a);
} pm_approx_ops;

/** Tuning keys of the case file that approximations read (INPUT.md `lme_gamma`, `support_radius`). */
typedef struct pm_approx_opts {
    double lme_gamma;       /**< LME: gamma = beta h^2; NAN = the default (1.8) */
    double support_radius;  /**< meshfree/LME support radius in metres; NAN = from the kind's tolerance */
} pm_approx_opts;

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
 * @brief Create the approximation called @p name on grid @p g.
 * @param name a `shape_function` value
 * @param g grid (must outlive the approximation)
 * @param out receives a new approximation; free with pm_approx_destroy()
 * @return PM_OK, PM_EINPUT for an unknown name or one that does not fit the grid
 */
int pm_approx_create(const char *name, const pm_grid *g, pm_approx **out);

/**
 * @brief Create the approximation called @p name on grid @p g with the case's tuning keys.
 * @param name a `shape_function` value
 * @param g grid (must outlive the approximation)
 * @param opts tuning keys (NULL: all defaults)
 * @param out receives a new approximation; free with pm_approx_destroy()
 * @return PM_OK, PM_EINPUT for an unknown name or one that does not fit the grid, PM_ENOMEM
 */
int pm_approx_create_opts(const char *name, const pm_grid *g, const pm_approx_opts *opts, pm_approx **out);

/** @brief Destroy an approximation (NULL is fine). */
void pm_approx_destroy(pm_approx *a);

/** @brief Names of the grid approximations (pm_approx_create()), NULL-terminated (for messages and "did you mean"). */
const char *const *pm_approx_names(void);

/**
 * @brief Every `shape_function` name, the grid kinds then the node-cloud kinds, each name once
 *        (lme is both): the values a case file may give.
 * @param out receives at most @p cap - 1 names and a terminating NULL
 * @param cap entries of @p out (>= 1)
 * @return the number of names written (without the NULL)
 */
size_t pm_approx_all_names(const char **out, size_t cap);

/**
 * @brief The `shape_function` names that method @p method serves, the method's default first
 *        (mpm: linear, gimp, bspline2, lme; gmm: mls, lme; rkpm: rk_cubic).
 * @param method a pm_method value (case.h)
 * @param out receives at most @p cap - 1 names and a terminating NULL
 * @param cap entries of @p out (>= 1)
 * @return the number of names written (without the NULL); 0 for an unknown method
 */
size_t pm_approx_names_for_method(int method, const char **out, size_t cap);

/**
 * @brief Whether the kind called @p name serves method @p method (on a grid for mpm, on a node
 *        cloud for gmm and rkpm).
 * @param name a `shape_function` value
 * @param method a pm_method value (case.h)
 * @return 1 or 0 (0 also for an unknown name or method)
 */
int pm_approx_serves(const char *name, int method);

/**
 * @brief The ops table of kind @p name as used by method @p method (the grid lme for mpm, the
 *        cloud lme for gmm), for asking its capabilities before anything is created.
 * @param name a `shape_function` value
 * @param method a pm_method value (case.h)
 * @return the table, or NULL when the method has no kind of that name
 */
const pm_approx_ops *pm_approx_find(const char *name, int method);

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

#ifdef __cplusplus
}
#endif
#endif
