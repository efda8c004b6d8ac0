/*
 * The XPIC(m) pass of the explicit MUSL step (design in xpic.h). Like APIC it runs through the
 * approximation's stencil for every grid kind; a run with another transfer never calls it.
 */
#include "xpic.h"
#include "explicit_internal.h"

#include "pmech/error.h"

#include <stdlib.h>

int pm_xpic_create(pm_sim *s)
{
    if (s->c->analysis.transfer != PM_TRANSFER_XPIC)
        return PM_OK;
    const size_t n = 2 * PM_DIM * s->nd.n_all;
    s->xpic = calloc(n, sizeof *s->xpic);
    if (!s->xpic)
        return pm_error_set(PM_ENOMEM, "cannot allocate XPIC's nodal work vectors (%zu bytes)", n * sizeof(double));
    return PM_OK;
}

/* A pass's nodal field and whether the particles keep its values as their velocity. */
typedef struct field_pass {
    const double *g;
    int set_velocity;
} field_pass;

/* Each particle's value of the nodal field, and its mass times that value back to the nodes. */
static void field_range(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *ctx, pm_range_out *out)
{
    (void)out;
    const field_pass *fp = ctx;
    const double *g = fp->g;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        pm_xp_stencil(s, i, &st); /* located by pm_xp_p2g, which reported any particle outside */
        double vp[PM_DIM] = {0};
        for (int k = 0; k < st.n; k++)
            for (int d = 0; d < PM_DIM; d++)
                vp[d] += st.N[k] * g[PM_DIM * (size_t)st.node[k] + d];
        if (fp->set_velocity)
            for (int d = 0; d < PM_DIM; d++)
                s->p.v[PM_DIM * i + d] = vp[d];
        const double m = s->p.mass[i];
        for (int k = 0; k < st.n; k++)
            for (int d = 0; d < PM_DIM; d++)
                b->mom[PM_DIM * (size_t)st.node[k] + d] += st.N[k] * m * vp[d];
    }
}

void pm_xpic_musl_project(pm_sim *s)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = nd->n_all, nv = PM_DIM * nn;
    double *t = s->xpic, *dv = s->xpic + nv; /* t = P^(r-1) v; dv = v* - v, summed term by term */
    const int m = s->c->analysis.xpic_order;
    const double mfloor = pm_xp_mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t j = 0; j < nv; j++) {
        t[j] = nd->vel[j];
        dv[j] = (m - 1) * nd->vel[j]; /* C(m, 1) v less the v of FLIP's increment: 0 for PIC */
    }
    double binom = m;
    for (int r = 2; r <= m; r++) {
        binom = binom * (m - r + 1) / r; /* C(m, r), exact: the product is C(m, r - 1) (m - r + 1) */
        const double c = r % 2 ? binom : -binom;
        const field_pass fp = {t, 0};
        pm_scatter_pass(s, field_range, &fp, PM_Z_MOM);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
        for (size_t n = 0; n < nn; n++) {
            const double mass = nd->mass[n];
            for (int d = 0; d < PM_DIM; d++) {
                const size_t j = PM_DIM * n + d;
                t[j] = mass > mfloor ? nd->mom[j] / mass : 0.0;
                dv[j] += c * t[j];
            }
        }
    }
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t j = 0; j < nv; j++)
        t[j] = nd->vel_new[j] + dv[j];
    const field_pass fp = {t, 1};
    pm_scatter_pass(s, field_range, &fp, PM_Z_MOM);
}
