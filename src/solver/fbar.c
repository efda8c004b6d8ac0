/* F-bar volumetric averaging over background cells (see fbar.h). */
#include "fbar.h"

#include "pmech/error.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int pm_fbar_create(pm_sim *s)
{
    if (s->c->analysis.fbar == PM_FBAR_NONE)
        return PM_OK;
    pm_fbar *f = calloc(1, sizeof *f);
    if (!f)
        return pm_error_set(PM_ENOMEM, "out of memory for the F-bar averaging");
    s->fbar = f;
    const size_t n = s->p.cap ? s->p.cap : 1; /* sources append particles up to the capacity */
    f->alpha = malloc(n * sizeof(double));
    f->det = malloc(n * sizeof(double));
    f->sum = malloc(2 * (s->grid.n_cells ? s->grid.n_cells : 1) * sizeof(double));
    if (!f->alpha || !f->det || !f->sum)
        return pm_error_set(PM_ENOMEM, "out of memory for the F-bar averaging (%zu particles, %zu cells)", s->p.n,
                            s->grid.n_cells);
    for (size_t i = 0; i < n; i++)
        f->alpha[i] = 1.0;
    return PM_OK;
}

void pm_fbar_destroy(pm_sim *s)
{
    if (!s->fbar)
        return;
    free(s->fbar->alpha);
    free(s->fbar->det);
    free(s->fbar->sum);
    free(s->fbar);
    s->fbar = NULL;
}

long pm_fbar_prepare(pm_sim *s, const double *nv, double dt)
{
    pm_fbar *f = s->fbar;
    const pm_particles *p = &s->p;
    const size_t n = p->n, nc = s->grid.n_cells;
    const int axi = s->c->formulation == PM_AXISYMMETRIC;
    long bad = LONG_MAX;
#pragma omp parallel for schedule(static) num_threads(s->nd.n_threads) reduction(min : bad)
    for (size_t i = 0; i < n; i++) {
        pm_stencil st;
        if (s->approx->ops->eval(s->approx, p, i, &st) != PM_OK) {
            bad = (long)i < bad ? (long)i : bad;
            f->det[i] = 1.0;
            continue;
        }
        double L[PM_DIM * PM_DIM] = {0}, vr = 0;
        for (int k = 0; k < st.n; k++) {
            const double *v = nv + PM_DIM * st.node[k];
            for (int a = 0; a < PM_DIM; a++)
                for (int b = 0; b < PM_DIM; b++)
                    L[PM_DIM * a + b] += v[a] * st.dN[k][b];
            vr += v[0] * st.N[k];
        }
        double J = (1 + dt * L[0]) * (1 + dt * L[3]) - dt * L[1] * dt * L[2];
        if (axi)
            J *= 1 + dt * vr / p->x[PM_DIM * i];
        if (!(J > 0))
            bad = (long)i < bad ? (long)i : bad;
        f->det[i] = J;
    }
    /* per-cell sums in particle order: a few adds per particle, not worth a parallel reduction */
    double *sv = f->sum, *sw = f->sum + nc;
    memset(f->sum, 0, 2 * nc * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        const int32_t c = p->cell[i];
        sv[c] += p->vol[i] * f->det[i];
        sw[c] += p->vol[i];
    }
    /* alpha^k = (J_cell / J)^(1 - s): the averaged volume ratio J_cell^(1 - s) J^s over the particle's own */
    const double inv_k = (axi ? 1.0 / 3.0 : 0.5) * (1.0 - s->c->analysis.fbar_own_share);
#pragma omp parallel for schedule(static) num_threads(s->nd.n_threads)
    for (size_t i = 0; i < n; i++) {
        const int32_t c = p->cell[i];
        const double J = f->det[i], Jc = sv[c] / sw[c];
        f->alpha[i] = J > 0 && Jc > 0 ? pow(Jc / J, inv_k) : 1.0;
    }
    return bad;
}
