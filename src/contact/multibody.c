/* Body fields of a multi-body run: set-up from the case, and each step's shared nodes, normals and
 * fronts (multibody.h). */
#include "contact/multibody.h"

#include "pmech/error.h"
#include "solver/explicit_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const pm_case_body *body_of(const pm_case *c, size_t b)
{
    return b < c->n_bodies ? &c->bodies[b] : &c->sources[b - c->n_bodies].body;
}

static int field_named(const pm_multibody *mb, const char *name)
{
    for (int f = 0; f < mb->n_fields; f++)
        if (!strcmp(mb->name[f], name))
            return f;
    return -1;
}

/* One field per distinct contact group, in the order the bodies and sources first name them. */
static void assign_fields(pm_multibody *mb, const pm_case *c)
{
    for (size_t b = 0; b < mb->n_bodies; b++) {
        const char *g = body_of(c, b)->contact_group;
        int f = field_named(mb, g);
        if (f < 0) {
            f = mb->n_fields++;
            mb->name[f] = g;
        }
        mb->field_of_body[b] = f;
    }
}

static void set_laws(pm_multibody *mb, const pm_case *c)
{
    const size_t nf = (size_t)mb->n_fields;
    for (size_t k = 0; k < nf * nf; k++) {
        mb->law[k] = PM_PAIR_NO_SLIP;
        mb->mu[k] = INFINITY;
        mb->extent[k] = 0;
    }
    for (size_t k = 0; k < c->n_contact_pairs; k++) {
        const pm_case_contact_pair *pr = &c->contact_pairs[k];
        const int a = field_named(mb, pr->group[0]), b = field_named(mb, pr->group[1]);
        if (a < 0 || b < 0)
            continue; /* the case loader checked the names */
        const double mu = pr->law == PM_PAIR_COULOMB ? pr->friction : pr->law == PM_PAIR_FRICTIONLESS ? 0.0 : INFINITY;
        const size_t ab = (size_t)a * nf + (size_t)b, ba = (size_t)b * nf + (size_t)a;
        mb->law[ab] = mb->law[ba] = (uint8_t)pr->law;
        mb->mu[ab] = mb->mu[ba] = mu;
        mb->extent[ab] = mb->extent[ba] = (uint8_t)(pr->law != PM_PAIR_NO_SLIP && pr->extent_check);
        mb->any_extent |= mb->extent[ab];
    }
}

int pm_multibody_create(const pm_case *c, size_t n_nodes, pm_multibody **out)
{
    *out = NULL;
    if (!c->n_contact_pairs)
        return PM_OK;
    pm_multibody *mb = calloc(1, sizeof *mb);
    if (!mb)
        return pm_error_set(PM_ENOMEM, "out of memory for the body fields");
    mb->n_nodes = n_nodes;
    mb->n_bodies = c->n_bodies + c->n_sources;
    const size_t nb = mb->n_bodies ? mb->n_bodies : 1;
    mb->field_of_body = calloc(nb, sizeof *mb->field_of_body);
    mb->offset_of_body = calloc(nb, sizeof *mb->offset_of_body);
    mb->name = calloc(nb, sizeof *mb->name);
    if (!mb->field_of_body || !mb->offset_of_body || !mb->name) {
        pm_multibody_destroy(mb);
        return pm_error_set(PM_ENOMEM, "out of memory for the body fields");
    }
    assign_fields(mb, c);
    const size_t nf = (size_t)mb->n_fields, all = nf * n_nodes;
    if (all >= (size_t)INT32_MAX) {
        pm_multibody_destroy(mb);
        return pm_error_set(PM_EINPUT,
                            "%s: contact_pairs: %zu contact groups x %zu grid nodes exceed the %d node entries a "
                            "stencil can number; use fewer contact groups (bodies sharing a contact_group share a "
                            "field) or a coarser grid",
                            c->file, nf, n_nodes, INT32_MAX);
    }
    for (size_t b = 0; b < mb->n_bodies; b++)
        mb->offset_of_body[b] = (int32_t)((size_t)mb->field_of_body[b] * n_nodes);
    mb->law = calloc(nf * nf, 1);
    mb->mu = calloc(nf * nf, sizeof *mb->mu);
    mb->extent = calloc(nf * nf, 1);
    mb->pair_force = calloc(PM_DIM * nf * nf, sizeof *mb->pair_force);
    mb->pair_impulse = calloc(PM_DIM * nf * nf, sizeof *mb->pair_impulse);
    mb->shared = calloc(n_nodes ? n_nodes : 1, 1);
    mb->list = calloc(n_nodes ? n_nodes : 1, sizeof *mb->list);
    mb->grad = calloc(PM_DIM * (all ? all : 1), sizeof *mb->grad);
    mb->normal = calloc(PM_DIM * (all ? all : 1), sizeof *mb->normal);
    mb->front = calloc(all ? all : 1, sizeof *mb->front);
    mb->vol = calloc(all ? all : 1, sizeof *mb->vol);
    if (!mb->law || !mb->mu || !mb->extent || !mb->pair_force || !mb->pair_impulse || !mb->shared || !mb->list ||
        !mb->grad || !mb->normal || !mb->front || !mb->vol) {
        pm_multibody_destroy(mb);
        return pm_error_set(PM_ENOMEM, "out of memory for %zu body fields of %zu nodes", nf, n_nodes);
    }
    set_laws(mb, c);
    *out = mb;
    return PM_OK;
}

void pm_multibody_destroy(pm_multibody *mb)
{
    if (!mb)
        return;
    if (mb->log)
        fclose(mb->log);
    free(mb->field_of_body);
    free(mb->offset_of_body);
    free(mb->name);
    free(mb->law);
    free(mb->mu);
    free(mb->extent);
    free(mb->pair_force);
    free(mb->pair_impulse);
    free(mb->shared);
    free(mb->list);
    free(mb->grad);
    free(mb->normal);
    free(mb->front);
    free(mb->vol);
    free(mb->surface_sum);
    free(mb);
}

void pm_multibody_copy_conditions(const pm_multibody *mb, pm_nodal *nd)
{
    const size_t nn = mb->n_nodes;
    for (int f = 1; f < mb->n_fields; f++) {
        memcpy(nd->fixed + (size_t)f * nn, nd->fixed, nn);
        memcpy(nd->vfix + (size_t)f * nn * PM_DIM, nd->vfix, PM_DIM * nn * sizeof(double));
    }
}

int pm_multibody_attach_surfaces(pm_multibody *mb, size_t n_surfaces)
{
    mb->n_surfaces = n_surfaces;
    mb->surface_sum = calloc(n_surfaces ? n_surfaces : 1, sizeof *mb->surface_sum);
    return mb->surface_sum ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory for the contact surfaces' forces");
}

/* The shared nodes of this step: two fields or more carry mass there. */
static void find_shared(pm_multibody *mb, const double *mass, double floor)
{
    const size_t nn = mb->n_nodes;
    mb->n_list = 0;
    for (size_t n = 0; n < nn; n++) {
        int carrying = 0;
        for (int f = 0; f < mb->n_fields && carrying < 2; f++)
            carrying += mass[(size_t)f * nn + n] > floor;
        mb->shared[n] = carrying >= 2;
        if (carrying >= 2)
            mb->list[mb->n_list++] = (int32_t)n;
    }
}

/* Volumes and volume gradients of every field at the shared nodes (one pass over the particles). */
static void volume_gradients(pm_multibody *mb, const pm_sim *s)
{
    const size_t nn = mb->n_nodes;
    for (size_t k = 0; k < mb->n_list; k++)
        for (int f = 0; f < mb->n_fields; f++)
        {
            const size_t e = (size_t)f * nn + (size_t)mb->list[k];
            mb->vol[e] = 0;
            for (int d = 0; d < PM_DIM; d++)
                mb->grad[PM_DIM * e + d] = 0;
        }
    const pm_particles *p = &s->p;
    pm_stencil st;
    for (size_t i = 0; i < p->n; i++) {
        if (pm_xp_stencil(s, i, &st) != PM_OK)
            continue;
        const size_t off = (size_t)mb->offset_of_body[p->body[i]];
        for (int k = 0; k < st.n; k++) {
            const size_t e = (size_t)st.node[k];
            if (!mb->shared[e - off])
                continue;
            mb->vol[e] += p->vol[i] * st.N[k];
            for (int d = 0; d < PM_DIM; d++)
                mb->grad[PM_DIM * e + d] += p->vol[i] * st.dN[k][d];
        }
    }
}

/* The field other than a with the most volume at grid node n (-1: none carries mass). */
static int fullest_other(const pm_multibody *mb, const double *mass, double floor, size_t n, int a)
{
    int best = -1;
    for (int f = 0; f < mb->n_fields; f++) {
        const size_t e = (size_t)f * mb->n_nodes + n;
        if (f != a && mass[e] > floor && (best < 0 || mb->vol[e] > mb->vol[(size_t)best * mb->n_nodes + n]))
            best = f;
    }
    return best;
}

/* Outward normal of every carrying field at the shared nodes: the volume gradient of the field
 * that fills more of the node's support, a's own or its fullest neighbour's reversed (sum_p V_p
 * grad N_I(x_p) points from a body's particles to the node: out of the body). Ties go to the lower
 * field, so two fields always get opposite normals. A component a condition prescribes at the node
 * is left out: there the gradient only sees the grid's edge (a body against a roller side leans
 * out of the side), and contact cannot act along it anyway. */
static void normals(pm_multibody *mb, const double *mass, const uint8_t *fixed, double floor)
{
    const size_t nn = mb->n_nodes;
    for (size_t k = 0; k < mb->n_list; k++) {
        const size_t n = (size_t)mb->list[k];
        for (int a = 0; a < mb->n_fields; a++) {
            const size_t e = (size_t)a * nn + n;
            double *nv = mb->normal + PM_DIM * e;
            mb->front[e] = -INFINITY;
            const int b = mass[e] > floor ? fullest_other(mb, mass, floor, n, a) : -1;
            if (b < 0) {
                for (int d = 0; d < PM_DIM; d++)
                    nv[d] = 0;
                continue;
            }
            const size_t eb = (size_t)b * nn + n;
            const int own = mb->vol[e] > mb->vol[eb] || (mb->vol[e] == mb->vol[eb] && a < b);
            const double *gr = mb->grad + PM_DIM * (own ? e : eb), sign = own ? 1.0 : -1.0;
            double len2 = 0, g[PM_DIM];
            for (int d = 0; d < PM_DIM; d++) {
                g[d] = (fixed[n] & (1u << d)) ? 0.0 : gr[d];
                len2 += g[d] * g[d];
            }
            const double len = sqrt(len2);
            for (int d = 0; d < PM_DIM; d++)
                nv[d] = len > 0 ? sign * g[d] / len : 0.0;
        }
    }
}

/* How far particle i's domain, the parallelogram F [-h, h] about x_p, reaches along unit n. */
static double reach(const pm_particles *p, size_t i, const double n[PM_DIM])
{
#if PM_DIM != 2
#error "the particle domain's reach is written for the 2-D deformation gradient"
#endif
    const double *F = p->F + PM_NF * i, *h = p->hsize + PM_DIM * i, *x = p->x + PM_DIM * i;
    const double ftn0 = F[PM_FXX] * n[0] + F[PM_FYX] * n[1], ftn1 = F[PM_FXY] * n[0] + F[PM_FYY] * n[1];
    return x[0] * n[0] + x[1] * n[1] + fabs(ftn0) * h[0] + fabs(ftn1) * h[1];
}

/* Every field's front at the shared nodes: the largest reach of its particles there. */
static void fronts(pm_multibody *mb, const pm_sim *s)
{
    const pm_particles *p = &s->p;
    pm_stencil st;
    for (size_t i = 0; i < p->n; i++) {
        if (pm_xp_stencil(s, i, &st) != PM_OK)
            continue;
        const size_t off = (size_t)mb->offset_of_body[p->body[i]];
        for (int k = 0; k < st.n; k++) {
            const size_t e = (size_t)st.node[k];
            if (!mb->shared[e - off] || !(st.N[k] > 0))
                continue;
            const double r = reach(p, i, mb->normal + PM_DIM * e);
            if (r > mb->front[e])
                mb->front[e] = r;
        }
    }
}

void pm_multibody_prepare(pm_sim *s)
{
    pm_multibody *mb = s->mb;
    const double floor = pm_xp_mass_floor(s);
    find_shared(mb, s->nd.mass, floor);
    if (!mb->n_list)
        return;
    volume_gradients(mb, s);
    normals(mb, s->nd.mass, s->nd.fixed, floor);
    if (mb->any_extent)
        fronts(mb, s);
}
