/*
 * The APIC passes of the explicit MUSL step (design in apic.h). They run through the approximation's
 * stencil for every grid kind, so the linear quad4 grid takes the general path here; a run with
 * another transfer never calls them.
 */
#include "apic.h"
#include "explicit_internal.h"

/* Add particle i's momentum, of velocity vp and affine matrix Cp, to the nodes of its stencil. Node
 * numbers of body fields (contact/multibody.h) are those of the grid's node plus the field's offset,
 * hence the remainder for the node's position. */
static inline void scatter_affine(const pm_sim *s, size_t i, const pm_stencil *st, const double vp[PM_DIM],
                                  const double Cp[PM_DIM * PM_DIM], const pm_scatter_buf *b)
{
    const double *xp = s->p.x + PM_DIM * i, m = s->p.mass[i];
    const size_t nn = s->grid.n_nodes;
    for (int k = 0; k < st->n; k++) {
        const size_t n = (size_t)st->node[k];
        const double *xi = s->grid.x + PM_DIM * (n % nn);
        double r[PM_DIM];
        for (int d = 0; d < PM_DIM; d++)
            r[d] = xi[d] - xp[d];
        const double w = st->N[k] * m;
        for (int a = 0; a < PM_DIM; a++) {
            double va = vp[a];
            for (int c = 0; c < PM_DIM; c++)
                va += Cp[PM_DIM * a + c] * r[c];
            b->mom[PM_DIM * n + a] += w * va;
        }
    }
}

static void p2g_range(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *ctx, pm_range_out *out)
{
    (void)ctx;
    (void)out;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        pm_xp_stencil(s, i, &st); /* located by pm_xp_p2g, which reported any particle outside */
        scatter_affine(s, i, &st, s->p.v + PM_DIM * i, s->p.C + PM_DIM * PM_DIM * i, b);
    }
}

void pm_apic_p2g_momentum(pm_sim *s)
{
    pm_scatter_pass(s, p2g_range, NULL, PM_Z_MOM);
}

static void project_range(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *ctx,
                          pm_range_out *out)
{
    (void)ctx;
    (void)out;
    const double *vn = s->nd.vel_new;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        pm_xp_stencil(s, i, &st);
        double vp[PM_DIM] = {0}, Cp[PM_DIM * PM_DIM] = {0};
        for (int k = 0; k < st.n; k++) {
            const double *v = vn + PM_DIM * st.node[k];
            for (int a = 0; a < PM_DIM; a++) {
                vp[a] += st.N[k] * v[a];
                for (int c = 0; c < PM_DIM; c++)
                    Cp[PM_DIM * a + c] += v[a] * st.dN[k][c];
            }
        }
        for (int a = 0; a < PM_DIM; a++)
            s->p.v[PM_DIM * i + a] = vp[a];
        for (int j = 0; j < PM_DIM * PM_DIM; j++)
            s->p.C[PM_DIM * PM_DIM * i + j] = Cp[j];
        scatter_affine(s, i, &st, vp, Cp, b);
    }
}

void pm_apic_musl_project(pm_sim *s)
{
    pm_scatter_pass(s, project_range, NULL, PM_Z_MOM);
}
