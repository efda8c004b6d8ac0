/* The contact laws on nodal velocities and their application in explicit steps (contact.h). */
#include "contact/contact.h"

#include <math.h>
#include <string.h>

/* a . b in the order a[0] b[0] + a[1] b[1] + ... (no leading 0 +, which could flip a zero's sign) */
static inline double dot(const double *a, const double *b)
{
    double s = a[0] * b[0];
    for (int d = 1; d < PM_DIM; d++)
        s += a[d] * b[d];
    return s;
}

static inline double norm(const double *a)
{
#if PM_DIM == 2
    return hypot(a[0], a[1]);
#else
    return sqrt(dot(a, a));
#endif
}

int pm_contact_nodal_coulomb(const double normal[PM_DIM], double mu, double v[PM_DIM])
{
    const double vn = dot(v, normal);
    if (vn <= 0)
        return 0; /* separating or sliding along: free */
    double vt[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        vt[d] = v[d] - vn * normal[d];
    const double speed = norm(vt), cut = mu * vn;
    const double keep = speed > cut ? 1.0 - cut / speed : 0.0;
    for (int d = 0; d < PM_DIM; d++)
        v[d] = keep * vt[d];
    return 1;
}

/* Normal velocity cut by dvn > 0, the tangential speed by up to mu dvn (never reversed). */
static void cut_slip(const double normal[PM_DIM], double mu, double vn, double dvn, double v[PM_DIM])
{
    double vt[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        vt[d] = v[d] - vn * normal[d];
    const double speed = norm(vt), c = mu * dvn;
    const double keep = speed > c ? 1.0 - c / speed : 0.0;
    for (int d = 0; d < PM_DIM; d++)
        v[d] = keep * vt[d] + (vn - dvn) * normal[d];
}

int pm_contact_nodal_coulomb_gap(const double normal[PM_DIM], double mu, double allowed, double v[PM_DIM])
{
    const double vn = dot(v, normal);
    if (!(vn > allowed))
        return 0; /* separating, or closing no more than the gap in this step */
    cut_slip(normal, mu, vn, vn - allowed, v);
    return 1;
}

int pm_contact_penalty_coulomb(const double normal[PM_DIM], double mu, double push, double v[PM_DIM])
{
    if (!(push > 0))
        return 0;
    cut_slip(normal, mu, dot(v, normal), push, v);
    return 1;
}

int pm_contact_normal_only(const double normal[PM_DIM], double v[PM_DIM])
{
    const double vn = dot(v, normal);
    if (!(vn > 0))
        return 0;
    for (int d = 0; d < PM_DIM; d++)
        v[d] -= vn * normal[d];
    return 1;
}

/* The node's prescribed components win over the contact law. */
static inline void constrain(const pm_contact_field *f, int32_t n, double v[PM_DIM])
{
    for (int d = 0; d < PM_DIM; d++)
        if (f->fixed[n] & (1u << d))
            v[d] = f->vfix[PM_DIM * n + d];
}

/* The impulse the law gave one node, as a force on the material, into its surface's resultant. */
static void add_force(pm_contact_surface *sf, const pm_contact_node *cn, double m, const double before[PM_DIM],
                      const double after[PM_DIM], double dt)
{
    double dv[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        dv[d] = after[d] - before[d];
    const double dvn = dot(dv, cn->normal);
    sf->f.normal -= m * dvn / dt;
    sf->impulse.normal -= m * dvn;
    for (int d = 0; d < PM_DIM; d++) {
        sf->f.force[d] += m * dv[d] / dt;
        sf->f.tangent[d] += m * (dv[d] - dvn * cn->normal[d]) / dt;
        sf->impulse.force[d] += m * dv[d];
        sf->impulse.tangent[d] += m * (dv[d] - dvn * cn->normal[d]);
    }
    double *J = sf->node_impulse + (size_t)(1 + PM_DIM) * (size_t)cn->node;
    J[0] -= m * dvn;
    for (int d = 0; d < PM_DIM; d++)
        J[1 + d] += m * (dv[d] - dvn * cn->normal[d]);
}

void pm_contact_apply(pm_contact *ct, pm_contact_field f, double dt, double dt_acc)
{
    if (!ct)
        return;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        memset(&ct->surface[k].f, 0, sizeof ct->surface[k].f);
    for (size_t k = 0; k < ct->n_node; k++) {
        pm_contact_node *cn = &ct->node[k];
        const int32_t n = cn->node;
        cn->held = 0;
        if (!(f.mass[n] > f.mass_floor))
            continue;
        pm_contact_surface *sf = &ct->surface[cn->surface];
        double *v = f.v + PM_DIM * n, before[PM_DIM];
        memcpy(before, v, sizeof before);
        int acted = 0;
        if (sf->motion) { /* the laws act on the velocity relative to a moving obstacle */
            for (int d = 0; d < PM_DIM; d++)
                v[d] -= sf->vel[d];
        }
        switch (sf->law) {
        case PM_CONTACT_LAW_NODAL_COULOMB:
            /* a node set's old arithmetic, bit for bit, where the material touches it */
            acted = cn->gap > 0 ? pm_contact_nodal_coulomb_gap(cn->normal, cn->mu, cn->gap / dt, v)
                                : pm_contact_nodal_coulomb(cn->normal, cn->mu, v);
            break;
        case PM_CONTACT_LAW_PENALTY_COULOMB:
            acted = cn->gap < 0 && pm_contact_penalty_coulomb(cn->normal, cn->mu, -sf->stiffness * cn->gap * dt_acc, v);
            break;
        }
        if (sf->motion) {
            for (int d = 0; d < PM_DIM; d++)
                v[d] += sf->vel[d];
        }
        cn->held = acted && sf->law == PM_CONTACT_LAW_NODAL_COULOMB;
        if (cn->held)
            cn->vn_held = dot(v, cn->normal) - (sf->motion ? dot(sf->vel, cn->normal) : 0.0);
        if (acted)
            add_force(sf, cn, f.mass[n], before, v, dt);
        constrain(&f, n, v);
        for (int d = 0; d < PM_DIM; d++)
            f.acc[PM_DIM * n + d] = (v[d] - f.v0[PM_DIM * n + d]) / dt_acc;
    }
}

void pm_contact_project_normal(const pm_contact *ct, pm_contact_field f)
{
    if (!ct)
        return;
    for (size_t k = 0; k < ct->n_node; k++) {
        const pm_contact_node *cn = &ct->node[k];
        const pm_contact_surface *sf = &ct->surface[cn->surface];
        /* only where the material touches; a penalty surface acts by its force alone */
        if ((cn->gap > 0 && !cn->held) || sf->law == PM_CONTACT_LAW_PENALTY_COULOMB)
            continue;
        double *v = f.v + PM_DIM * cn->node;
        for (int d = 0; sf->motion && d < PM_DIM; d++)
            v[d] -= sf->vel[d];
        /* A node the law held in this step keeps the normal velocity the law left it: the particles
         * moved with that one. Removing only an approaching normal velocity here, and keeping a
         * separating one, turned every fluctuation of the mapped velocity (friction's stick and slip
         * feed them) into a strain away from the wall that no particle's motion had: a ratchet that
         * compressed a bin's fill sideways and raised its wall pressure 17-55 % above Janssen's. */
        if (cn->held) {
            const double dvn = dot(v, cn->normal) - cn->vn_held;
            for (int d = 0; d < PM_DIM; d++)
                v[d] -= dvn * cn->normal[d];
        } else {
            pm_contact_normal_only(cn->normal, v);
        }
        for (int d = 0; sf->motion && d < PM_DIM; d++)
            v[d] += sf->vel[d];
        constrain(&f, cn->node, v);
    }
}
