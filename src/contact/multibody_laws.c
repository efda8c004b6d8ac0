/* The pair laws at the nodes two body fields share, and the boundary surfaces acting on every field
 * (multibody.h). */
#include "contact/multibody.h"

#include "solver/explicit_internal.h"

#include <math.h>
#include <string.h>

/* The other field carrying the most mass at grid node n (-1: none). */
static int heaviest_other(const pm_multibody *mb, const double *mass, double floor, size_t n, int a)
{
    int best = -1;
    double mbest = floor;
    for (int f = 0; f < mb->n_fields; f++) {
        const double m = mass[(size_t)f * mb->n_nodes + n];
        if (f != a && m > mbest) {
            mbest = m;
            best = f;
        }
    }
    return best;
}

/* Centre-of-mass velocity of the fields at grid node n. */
static void centre_of_mass(const pm_multibody *mb, const double *mass, double floor, const double *v, size_t n,
                           double vcm[PM_DIM])
{
    double m = 0, mom[PM_DIM] = {0};
    for (int f = 0; f < mb->n_fields; f++) {
        const size_t e = (size_t)f * mb->n_nodes + n;
        if (!(mass[e] > floor))
            continue;
        m += mass[e];
        for (int d = 0; d < PM_DIM; d++)
            mom[d] += mass[e] * v[PM_DIM * e + d];
    }
    for (int d = 0; d < PM_DIM; d++)
        vcm[d] = mom[d] / m;
}

/* Whether fields a and b touch at grid node n under the pair's test (the approach is the law's). */
static int touching(const pm_multibody *mb, size_t ab, size_t n, int a, int b)
{
    if (!mb->extent[ab])
        return 1;
    const double fa = mb->front[(size_t)a * mb->n_nodes + n], fb = mb->front[(size_t)b * mb->n_nodes + n];
    return fa + fb >= 0;
}

static inline void constrain(const pm_nodal *nd, size_t e, double v[PM_DIM])
{
    for (int d = 0; d < PM_DIM; d++)
        if (nd->fixed[e] & (1u << d))
            v[d] = nd->vfix[PM_DIM * e + d];
}

/*
 * Field a's velocity va at shared node n against the centre of mass vcm: no_slip takes vcm (*stuck
 * set); the other laws act on va - vcm along a's normal when the fields touch (full: friction too;
 * else the approaching normal part only). Returns the partner field, or -1 when nothing acted.
 */
static int act(const pm_multibody *mb, const double *mass, double floor, size_t n, int a, const double vcm[PM_DIM],
               int full, double va[PM_DIM], int *stuck)
{
    *stuck = 0;
    const int b = heaviest_other(mb, mass, floor, n, a);
    if (b < 0)
        return -1;
    const size_t ab = (size_t)a * (size_t)mb->n_fields + (size_t)b, e = (size_t)a * mb->n_nodes + n;
    if (mb->law[ab] == PM_PAIR_NO_SLIP) {
        memcpy(va, vcm, PM_DIM * sizeof(double));
        *stuck = 1;
        return b;
    }
    const double *nrm = mb->normal + PM_DIM * e;
    if (!(nrm[0] != 0 || nrm[1] != 0) || !touching(mb, ab, n, a, b))
        return -1;
    double rel[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        rel[d] = va[d] - vcm[d];
    const int acted = full ? pm_contact_nodal_coulomb(nrm, mb->mu[ab], rel) : pm_contact_normal_only(nrm, rel);
    if (!acted)
        return -1;
    for (int d = 0; d < PM_DIM; d++)
        va[d] = vcm[d] + rel[d];
    return b;
}

/* The pair laws at every shared node, on velocities v (full: with friction and forces). A stuck
 * field's acceleration is that of the centre of mass, (vcm - vcm0) / dt_acc, as in a single field,
 * so that a no_slip pair moves its particles exactly as one field would. The pair force is the
 * velocity change over dt_acc too: that is the acceleration the law adds, which a scheme applying it
 * over part of the step (Newmark's gamma dt) carries over the whole step. */
static void pair_laws(pm_sim *s, double *v, int full, double dt_acc)
{
    pm_multibody *mb = s->mb;
    const pm_nodal *nd = &s->nd;
    const double floor = pm_xp_mass_floor(s);
    const size_t nn = mb->n_nodes;
    for (size_t k = 0; k < mb->n_list; k++) {
        const size_t n = (size_t)mb->list[k];
        double vcm[PM_DIM], vcm0[PM_DIM];
        centre_of_mass(mb, nd->mass, floor, v, n, vcm);
        if (full)
            centre_of_mass(mb, nd->mass, floor, nd->vel, n, vcm0);
        for (int a = 0; a < mb->n_fields; a++) {
            const size_t e = (size_t)a * nn + n;
            if (!(nd->mass[e] > floor))
                continue;
            double *va = v + PM_DIM * e, before[PM_DIM];
            memcpy(before, va, sizeof before);
            int stuck;
            const int b = act(mb, nd->mass, floor, n, a, vcm, full, va, &stuck);
            constrain(nd, e, va);
            if (!full)
                continue;
            const double *v0 = stuck ? vcm0 : nd->vel + PM_DIM * e;
            for (int d = 0; d < PM_DIM; d++)
                nd->acc[PM_DIM * e + d] = (va[d] - v0[d]) / dt_acc;
            if (b < 0)
                continue;
            double *f = mb->pair_force + PM_DIM * ((size_t)a * (size_t)mb->n_fields + (size_t)b);
            for (int d = 0; d < PM_DIM; d++)
                f[d] += nd->mass[e] * (va[d] - before[d]) / dt_acc;
        }
    }
}

/* The boundary surfaces on field f's part of the nodal arrays. */
static pm_contact_field field_view(const pm_sim *s, int f, double *v, double floor)
{
    const pm_nodal *nd = &s->nd;
    const size_t off = (size_t)f * s->mb->n_nodes;
    pm_contact_field cf = {nd->mass + off, nd->vel + PM_DIM * off, v + PM_DIM * off, nd->acc + PM_DIM * off,
                           nd->fixed + off, nd->vfix + PM_DIM * off, floor};
    return cf;
}

void pm_multibody_apply(pm_sim *s, double *v, double dt, double dt_acc)
{
    pm_multibody *mb = s->mb;
    const size_t nf = (size_t)mb->n_fields;
    memset(mb->pair_force, 0, PM_DIM * nf * nf * sizeof(double));
    pair_laws(s, v, 1, dt_acc);
    pm_contact *ct = s->contact;
    if (!ct || !ct->n_surfaces)
        return;
    const double floor = pm_xp_mass_floor(s);
    const size_t ns = ct->n_surfaces < mb->n_surfaces ? ct->n_surfaces : mb->n_surfaces;
    memset(mb->surface_sum, 0, ns * sizeof *mb->surface_sum);
    for (int f = 0; f < mb->n_fields; f++) {
        pm_contact_apply(ct, field_view(s, f, v, floor), dt, dt_acc);
        for (size_t k = 0; k < ns; k++) {
            const pm_contact_force *g = &ct->surface[k].f;
            pm_contact_force *sum = &mb->surface_sum[k];
            sum->normal += g->normal;
            for (int d = 0; d < PM_DIM; d++) {
                sum->force[d] += g->force[d];
                sum->tangent[d] += g->tangent[d];
            }
        }
    }
    for (size_t k = 0; k < ns; k++)
        ct->surface[k].f = mb->surface_sum[k];
}

void pm_multibody_project(pm_sim *s, double *v)
{
    pair_laws(s, v, 0, 0.0);
    if (!s->contact)
        return;
    const double floor = pm_xp_mass_floor(s);
    for (int f = 0; f < s->mb->n_fields; f++)
        pm_contact_project_normal(s->contact, field_view(s, f, v, floor));
}

double pm_multibody_strain_mass(const pm_sim *s, size_t e)
{
    const pm_multibody *mb = s->mb;
    const double *mass = s->nd.mass, floor = pm_xp_mass_floor(s);
    const size_t n = e % mb->n_nodes;
    const int a = (int)(e / mb->n_nodes), b = heaviest_other(mb, mass, floor, n, a);
    if (b < 0 || mb->law[(size_t)a * (size_t)mb->n_fields + (size_t)b] != PM_PAIR_NO_SLIP)
        return mass[e];
    double m = 0;
    for (int f = 0; f < mb->n_fields; f++) {
        const double mf = mass[(size_t)f * mb->n_nodes + n];
        m += mf > floor ? mf : 0.0;
    }
    return m;
}
