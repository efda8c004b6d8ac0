/* The parallel scatter machinery of the particle passes (see scatter.h). */
#include "scatter.h"

#include <limits.h>
#include <omp.h>
#include <string.h>

/* The nodal buffers a thread scatters into: thread 0 (and every thread of a colour scatter) uses
 * the real arrays. */
static pm_scatter_buf thread_buf(const pm_sim *s, int tid)
{
    size_t nn = s->nd.n_all;
    pm_scatter_buf b;
    if (tid == 0 || s->scatter == PM_SCATTER_COLOUR) {
        b.mass = s->nd.mass;
        b.mom = s->nd.mom;
        b.force = s->nd.force;
    } else {
        double *base = s->nd.scratch + (size_t)(tid - 1) * PM_SCATTER_WIDTH * nn;
        b.mass = base;
        b.mom = base + nn;
        b.force = base + (1 + PM_DIM) * nn;
    }
    return b;
}

static void zero_buf(pm_scatter_buf b, size_t nn, unsigned what)
{
    if (what & PM_Z_MASS)
        memset(b.mass, 0, nn * sizeof(double));
    if (what & PM_Z_MOM)
        memset(b.mom, 0, PM_DIM * nn * sizeof(double));
    if (what & PM_Z_FORCE)
        memset(b.force, 0, PM_DIM * nn * sizeof(double));
}

/* Sum the other threads' buffers into the real arrays (called inside a parallel region). */
static void reduce_bufs(const pm_sim *s, int nt, unsigned what)
{
    size_t nn = s->nd.n_all;
    for (int t = 1; t < nt; t++) {
        pm_scatter_buf b = thread_buf(s, t);
#pragma omp for schedule(static)
        for (size_t n = 0; n < nn; n++) {
            if (what & PM_Z_MASS)
                s->nd.mass[n] += b.mass[n];
            for (int d = 0; d < PM_DIM; d++) {
                if (what & PM_Z_MOM)
                    s->nd.mom[PM_DIM * n + d] += b.mom[PM_DIM * n + d];
                if (what & PM_Z_FORCE)
                    s->nd.force[PM_DIM * n + d] += b.force[PM_DIM * n + d];
            }
        }
    }
}

/*
 * Run a scatter pass: fn over every particle, each call writing into buffer b. Buffers: each thread
 * takes a contiguous range into its own copy, summed after. Colour: the row blocks of one colour
 * share no node, so they scatter at once into the real arrays, one colour after the other; when
 * they do share one (blocks_ok = 0), one thread scatters everything.
 */
pm_range_out pm_scatter_pass(pm_sim *s, pm_range_fn fn, const void *ctx, unsigned zero)
{
    long bad = LONG_MAX;
    double wave = 0;
    const size_t n = s->p.n, nn = s->nd.n_all;
#pragma omp parallel num_threads(s->nd.n_threads) reduction(min : bad) reduction(max : wave)
    {
        const int tid = omp_get_thread_num(), used = omp_get_num_threads();
        pm_range_out o = {LONG_MAX, 0};
        if (s->scatter == PM_SCATTER_COLOUR && used > 1) {
            pm_scatter_buf b = thread_buf(s, 0);
#pragma omp for schedule(static)
            for (size_t k = 0; k < nn; k++) {
                if (zero & PM_Z_MASS)
                    b.mass[k] = 0;
                for (int d = 0; d < PM_DIM; d++) {
                    if (zero & PM_Z_MOM)
                        b.mom[PM_DIM * k + d] = 0;
                    if (zero & PM_Z_FORCE)
                        b.force[PM_DIM * k + d] = 0;
                }
            }
            if (s->blocks_ok) {
                const int nb = s->n_blocks;
                for (int c = 0; c < 2; c++) {
                    for (int k = 2 * tid + c; k < nb; k += 2 * used)
                        fn(s, s->blocks[k], s->blocks[k + 1], &b, ctx, &o);
#pragma omp barrier
                }
            } else {
#pragma omp single
                fn(s, 0, n, &b, ctx, &o);
            }
        } else {
            pm_scatter_buf b = thread_buf(s, tid);
            zero_buf(b, nn, zero);
            if (used > 1) {
#pragma omp barrier
            }
            fn(s, n * (size_t)tid / (size_t)used, n * (size_t)(tid + 1) / (size_t)used, &b, ctx, &o);
            if (used > 1) {
#pragma omp barrier
                reduce_bufs(s, used, zero);
            }
        }
        bad = o.bad;
        wave = o.wave;
    }
    pm_range_out r = {bad, wave};
    return r;
}

/*
 * Colour scatter: cut the particles (just sorted by cell) into 2 x threads blocks of whole cell
 * rows with about equal counts. Block k then covers rows strictly below those of block k + 1, so
 * blocks k and k + 2 are a whole block apart.
 */
static void cut_blocks(pm_sim *s)
{
    const pm_particles *p = &s->p;
    const int nb = 2 * s->nd.n_threads;
    const int32_t nx = s->grid.cells[0];
    s->blocks[0] = 0;
    for (int k = 1; k < nb; k++) {
        size_t at = p->n * (size_t)k / (size_t)nb, lo = s->blocks[k - 1], hi = at;
        if (at < p->n) {
            const int32_t first = p->cell[at] / nx * nx; /* first cell of the row of particle `at` */
            while (lo < hi) {                           /* first particle in that row or above */
                const size_t mid = lo + (hi - lo) / 2;
                if (p->cell[mid] < first)
                    lo = mid + 1;
                else
                    hi = mid;
            }
        } else {
            lo = p->n;
        }
        s->blocks[k] = lo;
    }
    s->blocks[nb] = p->n;
    s->n_blocks = nb;
}

/*
 * Particles move between sorts: check with this step's cells that no two blocks of one colour touch
 * a common node row (a block in rows r0..r1 touches node rows r0..r1 + 1).
 */
static int blocks_disjoint(const pm_sim *s)
{
    enum { MAXB = 256 }; /* row ranges on the stack; beyond 128 threads one thread scatters */
    const int nb = s->n_blocks;
    if (nb <= 2 || nb > MAXB)
        return nb == 2 ? 1 : 0;
    int32_t lo[MAXB], hi[MAXB];
    const int32_t *cell = s->p.cell;
#pragma omp parallel for schedule(static, 1) num_threads(s->nd.n_threads)
    for (int k = 0; k < nb; k++) {
        int32_t a = INT32_MAX, b = -1;
        for (size_t i = s->blocks[k]; i < s->blocks[k + 1]; i++) {
            a = cell[i] < a ? cell[i] : a;
            b = cell[i] > b ? cell[i] : b;
        }
        lo[k] = b < 0 ? -1 : a / s->grid.cells[0];
        hi[k] = b < 0 ? -1 : b / s->grid.cells[0];
    }
    for (int j = 0; j < nb; j++)
        for (int k = j + 2; k < nb; k += 2)
            if (hi[j] >= 0 && hi[k] >= 0 && !(hi[j] + 1 < lo[k] || hi[k] + 1 < lo[j]))
                return 0;
    return 1;
}

/* Before a step's scatters: blocks cut for the current order, and whether they may scatter at once. */
void pm_scatter_prepare(pm_sim *s, int sorted)
{
    if (s->scatter != PM_SCATTER_COLOUR || s->nd.n_threads < 2)
        return;
    if (sorted || s->n_blocks != 2 * s->nd.n_threads || s->blocks[s->n_blocks] != s->p.n)
        cut_blocks(s);
    s->blocks_ok = blocks_disjoint(s);
    if (!s->blocks_ok && s->sort_interval > 0 && s->grid.n_cells < UINT32_MAX) {
        pm_sim_sort_particles(s); /* particles drifted across a whole block: sort before the usual time */
        cut_blocks(s);
        s->blocks_ok = blocks_disjoint(s);
    }
}
