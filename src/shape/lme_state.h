/**
 * @file lme_state.h (internal to src/, not installed)
 * @brief What the grid kind `lme` keeps per particle slot from one evaluation to the next (lme.c): the
 *        last stencil and the position and lambda it belongs to. A stencil evaluated at a bit-identical
 *        position is returned as kept, and any other position starts Newton from a prediction made of
 *        the kept values, so a run continued from a checkpoint needs them back to continue bitwise.
 */
#ifndef PMECH_LME_STATE_H
#define PMECH_LME_STATE_H

#include "pmech/approx.h"

#include <stddef.h>
#include <stdint.h>

/** The per-slot cache of an `lme` grid approximation, as pointers into it. */
typedef struct pm_lme_state {
    size_t cap;      /**< slots (one per particle the arrays can hold) */
    size_t n_nodes;  /**< nodes of the grid the stencils name */
    int width;       /**< nodes a slot can hold */
    double *xs;      /**< 2 per slot: where the kept lambda was found (NaN: nothing kept) */
    double *lam;     /**< 2 per slot: that lambda */
    int *n;          /**< per slot: nodes of the kept stencil (0: the lambda only) */
    int32_t *node;   /**< width per slot: the kept stencil's nodes */
    double *N;       /**< width per slot: its values */
    double (*dN)[2]; /**< width per slot: its gradients */
} pm_lme_state;

/**
 * @brief The cache of @p a, an approximation of the grid kind `lme` (valid until it is destroyed; a
 *        connect() with more particles than slots replaces it).
 * @param a the approximation
 * @param st receives the pointers
 * @return PM_OK, or PM_EINPUT when @p a is of another kind
 */
int pm_lme_state_get(const pm_approx *a, pm_lme_state *st);

#endif
