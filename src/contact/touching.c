/*
 * What the law at the touching particles does to the particles themselves (contact.h,
 * pm_contact_particle_velocities).
 *
 * An obstacle acting at the particles holds the velocity each touching particle's stencil gives it, the
 * one it moves with. The FLIP update then adds to the particle's own velocity only the change of that
 * interpolated velocity, so whatever difference the particle's own velocity had from it before the law
 * held it survives: a grain that came to rest on the floor kept the downward velocity it landed with. Where
 * the floor cuts through a cell, the nodes below it carry mass from the touching particles alone, so the
 * next mapping gives them that kept velocity while the nodes above carry the deposit's: the particle's
 * velocity gradient stretches it away from the floor step after step while it stays where it is (the
 * law is satisfied: its interpolated velocity does not approach). A cohesionless point offers no
 * stress against that stretch; on a granular column's floor half a cell above a grid line points grew to
 * 4.7e5 times their volume. Giving the held particle the velocity it moves with removes the difference
 * and the stretch with it.
 */
#include "contact/contact.h"

void pm_contact_particle_velocities(const pm_contact *ct, const pm_approx *a, pm_particles *p, const double *v0,
                                    double shift)
{
    if (!ct)
        return;
    for (size_t q = 0; q < ct->n_pt; q++) {
        const pm_contact_point *pt = &ct->pt[q];
        const pm_contact_surface *sf = &ct->surface[pt->surface];
        /* a node set's points are feet between nodes on the surface: the law holds those nodes
         * themselves, and the FLIP update passes their change on in full */
        if (sf->kind == PM_CONTACT_NODE_SET || sf->points_lost || !(pt->lam_n > 0) || pt->particle >= p->n)
            continue;
        pm_stencil st;
        if (pm_approx_eval(a, p, pt->particle, &st) != 0)
            continue;
        double v[PM_DIM] = {0};
        for (int k = 0; k < st.n; k++)
            for (int d = 0; d < PM_DIM; d++)
                v[d] += st.N[k] * v0[PM_DIM * st.node[k] + d];
        double *vp = p->v + PM_DIM * pt->particle;
        const double *ap = shift > 0 ? p->a + PM_DIM * pt->particle : NULL;
        for (int d = 0; d < PM_DIM; d++)
            vp[d] = ap ? v[d] - shift * ap[d] : v[d];
    }
}
