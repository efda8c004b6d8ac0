/*
 * Parallel scatters of particle passes into the nodal arrays (src/solver/scatter.c). No two threads
 * ever add into one node: either the particles, sorted by cell, are cut into row blocks of two
 * colours that scatter colour by colour straight into the nodal arrays, or every thread scatters
 * into its own copy of them, summed afterwards. Either way the result depends on the thread count
 * only by round-off.
 */
#ifndef PMECH_SCATTER_H
#define PMECH_SCATTER_H

#include "solver/sim_internal.h"

#include <stddef.h>

/* Doubles per node of a thread's private copy: mass, momentum and force. */
#define PM_SCATTER_WIDTH (1 + 2 * PM_DIM)

/* The nodal arrays a pass scatters into: the real ones, or a thread's private copy. */
typedef struct pm_scatter_buf {
    double *mass, *mom, *force;
} pm_scatter_buf;

/* Which nodal arrays a pass writes: they are zeroed before it and summed over the copies after. */
enum { PM_Z_MASS = 1, PM_Z_MOM = 2, PM_Z_FORCE = 4 };

/* What a pass over a range of particles reports: the first failed particle (LONG_MAX: none) and the
 * largest wave speed. */
typedef struct pm_range_out {
    long bad;
    double wave;
} pm_range_out;

/* A pass over particles [lo, hi), adding into b; ctx is the pass's own parameters. It lowers
 * out->bad and raises out->wave, never resets them. */
typedef void (*pm_range_fn)(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *ctx,
                            pm_range_out *out);

/* Run fn over every particle in parallel with s->nd.n_threads threads, the arrays named in `zero`
 * (PM_Z_* bits) zeroed first; returns the reports of all ranges combined. */
pm_range_out pm_scatter_pass(pm_sim *s, pm_range_fn fn, const void *ctx, unsigned zero);

/* Before a step's scatters (colour scatter only): cut the blocks again when the particles were just
 * sorted (`sorted`) or their count changed, and find whether blocks of one colour share no node;
 * sort early if the particles drifted too far for that. */
void pm_scatter_prepare(pm_sim *s, int sorted);

#endif
