/*
 * What the meshfree kinds on a node cloud share (not public): their private data, the candidate
 * lists that answer a point's first neighbour query, and the evaluations of the two families,
 * linear-moment (mls, rk_cubic: mls_rk.c) and max-ent (lme: lme_cloud.c). The approximation
 * around them (cache, connect, options) is meshfree.c.
 */
#ifndef PMECH_MESHFREE_SHAPE_H
#define PMECH_MESHFREE_SHAPE_H

#include "shape/meshfree.h"

#include "shape_internal.h"

#include <math.h>

/* Most steps of the adaptive growth of a support. */
#define MF_MAX_GROWTH 60

typedef enum mf_kind { MF_MLS, MF_LME, MF_RK } mf_kind;

/* Candidate lists, one per point that is evaluated again and again (the solver's material points,
 * the cloud's nodes): the nodes near where the list was made, which answer the point's first query
 * while they are sure to hold every node of its support (lists_get()). */
typedef struct mf_lists {
    size_t n, slot;    /* lists, entries per list */
    int32_t *node;     /* slot per list */
    int *len;          /* -1: none */
    double *x;         /* PM_DIM per list: where it was made */
    size_t *build;     /* the cloud's n_builds when it was made */
} mf_lists;

/* Stencils of the points as of the last connect(), so that the several passes of a step evaluate
 * each point once: slot entries per point, the position they were computed at as the key. LME also
 * keeps each point's lambda, the start of its next Newton solve. */
typedef struct mf_cache {
    size_t n, slot;    /* points, entries per point */
    int *len;          /* nodes per point; -1: not cached (evaluate afresh) */
    double *key;       /* PM_DIM per point (NAN: never evaluated) */
    int32_t *node;     /* slot per point */
    double *N, *dN;    /* slot, PM_DIM slot per point */
    double *lam;       /* LME: PM_DIM per point, lambda at key (0, 0: none) */
    mf_lists lists;    /* one per point */
} mf_cache;

/* The private data of a cloud kind: the kind's family, its cloud, the tuning after defaults (beta
 * from gamma and the cloud's h) and the per-point state that connect() keeps. */
typedef struct mf_data {
    mf_kind kind;
    pm_cloud *cloud;
    double r0, growth, cond_tol, gamma, beta;
    int min_nodes, max_extra, tensor, smooth, axisym;
    mf_cache cache;
    /* pm_meshfree_eval_node(): per cloud node, its candidate list and (LME) last lambda */
    mf_lists node_lists;
    double *node_lam;
} mf_data;

/* A point's candidate list: the nodes that were within some radius R_L of a nearby position (see
 * cache_fill()). NULL where the cell list is to be searched instead. */
typedef struct mf_list {
    const int32_t *node;
    int n;
} mf_list;

/* The nodes of a candidate list within r of x, with their offsets x - x_I and squared distances:
 * what pm_cloud_gather() gives, in the same order (the list is a cell-list query of the same build),
 * without visiting cells or testing the nodes outside R_L. */
static inline int list_gather(const pm_cloud *c, const mf_list *L, const double x[2], double r,
                              int32_t *restrict idx, double (*restrict d)[2], double *restrict q)
{
    const double r2 = r * r, x0 = x[0], x1 = x[1];
    const double *restrict xc = c->x;
    int n = 0;
    for (int k = 0; k < L->n; k++) {
        const int32_t j = L->node[k];
        const double dx = x0 - xc[PM_DIM * (size_t)j], dy = x1 - xc[PM_DIM * (size_t)j + 1];
        const double qq = dx * dx + dy * dy;
        idx[n] = j;
        d[n][0] = dx;
        d[n][1] = dy;
        q[n] = qq;
        n += qq < r2;
    }
    return n;
}

/* The query radius of the first (not grown) support: the tensor kernel's square of half-side r0
 * lies within the circle of radius r0 sqrt 2. */
static inline double first_radius(const mf_data *md)
{
    return md->tensor ? md->r0 * sqrt(2.0) : md->r0;
}

/**
 * MLS or RK (by md->kind) at x: the support grows from md->r0 until it holds min_nodes nodes and
 * the moment matrix is well conditioned. L: a candidate list for the first support, or NULL.
 * Returns PM_OK or PM_ESIM.
 */
int pm_mf_moment_eval(const mf_data *md, const double x[2], const mf_list *L, pm_stencil *s);

/**
 * LME at x. lam: in, the starting lambda (0, 0 for none); out, the solution. L: a candidate list
 * for the first support, or NULL. Returns PM_OK or PM_ESIM.
 */
int pm_mf_lme_eval(const mf_data *md, const double x[2], double lam[2], const mf_list *L, pm_stencil *s);

#endif
