/*
 * Which nodes touch which surface (contact.h): the candidates near every surface at time t, then the
 * gap of each from the material's surface, measured from the particles near the node, so a node acts
 * when the material reaches the surface and not when the node's cell does; and where the material
 * touches a node set, the points its nodal law acts at (friction.c).
 */
#include "contact/contact.h"

#include <math.h>
#include <string.h>

/* Place a moving obstacle at time t: its displacement is the integral of its velocity. */
static void place(pm_contact_surface *sf, double t)
{
    for (int d = 0; d < PM_DIM; d++) {
        sf->shift[d] = sf->motion ? pm_timefn_integral(&sf->motion[d], t) : 0.0;
        sf->vel[d] = sf->motion ? pm_timefn_value(&sf->motion[d], t) : 0.0;
    }
}

/* The box around a surface, widened by the reach: its points (a polyline, polygon), its disk, its
 * nodes (a node set); a straight meshfree wall is a slab across the whole frame. */
static void place_box(const pm_contact *ct, pm_contact_surface *sf, const pm_grid *g)
{
    for (int d = 0; d < PM_DIM; d++) {
        sf->box_lo[d] = INFINITY;
        sf->box_hi[d] = -INFINITY;
    }
    switch (sf->kind) {
    case PM_CONTACT_CIRCLE:
        for (int d = 0; d < PM_DIM; d++) {
            sf->box_lo[d] = sf->origin[d] + sf->shift[d] - sf->radius;
            sf->box_hi[d] = sf->origin[d] + sf->shift[d] + sf->radius;
        }
        break;
    case PM_CONTACT_POLYLINE:
    case PM_CONTACT_POLYGON:
    case PM_CONTACT_EDGES:
        for (size_t q = 0; q < sf->n_points; q++)
            for (int d = 0; d < PM_DIM; d++) {
                const double x = ct->points[PM_DIM * (sf->first_point + q) + d] + sf->shift[d];
                sf->box_lo[d] = fmin(sf->box_lo[d], x);
                sf->box_hi[d] = fmax(sf->box_hi[d], x);
            }
        break;
    case PM_CONTACT_NODE_SET:
        if (!g->x) { /* no node positions given: no box */
            for (int d = 0; d < PM_DIM; d++)
                sf->box_lo[d] = -INFINITY, sf->box_hi[d] = INFINITY;
            break;
        }
        for (size_t e = sf->first; e < sf->first + sf->n; e++)
            for (int d = 0; d < PM_DIM; d++) {
                const double x = g->x[PM_DIM * ct->node[e].node + d];
                sf->box_lo[d] = fmin(sf->box_lo[d], x);
                sf->box_hi[d] = fmax(sf->box_hi[d], x);
            }
        break;
    default:
        for (int d = 0; d < PM_DIM; d++) {
            sf->box_lo[d] = d == sf->axis ? sf->value : -INFINITY;
            sf->box_hi[d] = d == sf->axis ? sf->value : INFINITY;
        }
        break;
    }
    for (int d = 0; d < PM_DIM; d++) {
        sf->box_lo[d] -= ct->reach;
        sf->box_hi[d] += ct->reach;
    }
}

static inline int in_box(const pm_contact_surface *sf, const double *x)
{
    for (int d = 0; d < PM_DIM; d++)
        if (!(x[d] >= sf->box_lo[d] && x[d] <= sf->box_hi[d]))
            return 0;
    return 1;
}

/* Every node within reach of a surface that is not a node set (or inside it). */
static void near_nodes(pm_contact *ct, int32_t k, const pm_grid *g)
{
    const pm_contact_surface *sf = &ct->surface[k];
    for (size_t I = 0; I < g->n_nodes && ct->n_node < ct->cap; I++) {
        if (!in_box(sf, g->x + PM_DIM * I))
            continue;
        double n[PM_DIM];
        const double sd = pm_contact_distance(ct, sf, g->x + PM_DIM * I, n);
        if (sd > ct->reach)
            continue;
        pm_contact_node *cn = &ct->node[ct->n_node++];
        cn->node = (int32_t)I;
        cn->surface = k;
        for (int d = 0; d < PM_DIM; d++)
            cn->normal[d] = n[d];
        cn->mu = sf->mu;
        cn->gap = sd;
        cn->held = 0;
        cn->corner = 0;
        cn->own_row = 0;
    }
}

void pm_contact_detect(pm_contact *ct, const pm_grid *g, double t)
{
    if (!ct)
        return;
    ct->n_node = ct->n_fixed; /* node sets keep their nodes; they act where they carry mass */
    for (size_t e = 0; e < ct->n_fixed; e++) {
        ct->node[e].gap = 0.0;
        ct->node[e].held = 0;
    }
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        pm_contact_surface *sf = &ct->surface[k];
        place(sf, t);
        place_box(ct, sf, g);
        if (sf->kind != PM_CONTACT_NODE_SET && (sf->kind != PM_CONTACT_EDGES || sf->detected))
            near_nodes(ct, (int32_t)k, g);
    }
}

/* The particle's half-size: the radius of the circle of its area (its seeding box of half-sides hsize,
 * times det F). A box's corner would reach further along a slanted normal, but the corners of the boxes
 * along a slanted face stick out of the body seeded there; the circle does not. */
static inline double half_size(const pm_particles *p, size_t i)
{
#if PM_DIM != 2
#error "the particle's extent is written for the in-plane F"
#endif
    if (!p->hsize)
        return 0.0;
    const double *F = p->F + PM_NF * i, *h = p->hsize + PM_DIM * i;
    const double J = F[PM_FXX] * F[PM_FYY] - F[PM_FXY] * F[PM_FYX];
    return J > 0 ? sqrt(h[0] * h[1] * J) : 0.0;
}

/* A particle sets the gap of the contact nodes whose shape function at it is at least this fraction of
 * the largest one (a particle midway between two nodes sets both). */
static const double VOTE = 0.5;

/* The impulses particle i's point on surface k had in the last step, if it had one (else zero). Both
 * lists are in the same order, surface by surface and particle by particle, so one cursor runs through
 * the last one. A particle renumbered since (the periodic sort, sinks, sources) may take another's
 * impulses: they only start the sweeps, which converge from any start. */
static void last_impulses(pm_contact *ct, size_t k, size_t i, pm_contact_point *q)
{
    q->lam_n = 0.0;
    for (int d = 0; d < PM_DIM; d++)
        q->lam_t[d] = 0.0;
    if (ct->n_pt >= ct->pt_old) /* the new list reaches the old one: writing on would overwrite it */
        ct->n_pt_old = 0;
    const size_t end = ct->pt_old + ct->n_pt_old;
    size_t c = ct->pt_cursor;
    while (c < end && ct->pt[c].surface == (int32_t)k && ct->pt[c].particle < i)
        c++;
    ct->pt_cursor = c;
    if (c < end && ct->pt[c].surface == (int32_t)k && ct->pt[c].particle == i) {
        q->lam_n = ct->pt[c].lam_n;
        for (int d = 0; d < PM_DIM; d++)
            q->lam_t[d] = ct->pt[c].lam_t[d];
    }
}

/* A point where particle i's surface (its foot on the plane, gap above it) may touch node-set surface k:
 * between the entry e whose node moves the particle most and the neighbour of e on the foot's side. */
static void add_point(pm_contact *ct, size_t k, int32_t e, size_t i, double sd, const double n[PM_DIM],
                      double gap, const double *xp)
{
#if PM_DIM != 2
#error "a point lies between two nodes of a line"
#endif
    if (ct->n_pt >= ct->pt_cap) {
        ct->surface[k].points_lost = 1;
        return;
    }
    const double *xa = ct->node_x + PM_DIM * ct->node[e].node;
    const double foot[PM_DIM] = {xp[0] + sd * n[0], xp[1] + sd * n[1]};
    const double t[PM_DIM] = {-n[1], n[0]}, along = (foot[0] - xa[0]) * t[0] + (foot[1] - xa[1]) * t[1];
    int32_t b = -1;
    double s = 0.0;
    for (int side = 0; side < 2; side++) {
        const int32_t nb = ct->side_nbr[2 * e + side];
        if (nb < 0)
            continue;
        const double *xb = ct->node_x + PM_DIM * ct->node[nb].node;
        const double span = (xb[0] - xa[0]) * t[0] + (xb[1] - xa[1]) * t[1];
        if (span != 0 && along / span > 0) {
            b = nb;
            s = fmin(along / span, 1.0);
        }
    }
    pm_contact_point *q = &ct->pt[ct->n_pt];
    last_impulses(ct, k, i, q);
    ct->n_pt++;
    q->particle = q->index = i;
    q->surface = (int32_t)k;
    q->n = 2;
    for (int d = 0; d < PM_DIM; d++)
        q->normal[d] = ct->surface[k].normal[d];
    q->node[0] = ct->node[e].node;
    q->entry[0] = e;
    q->w[0] = 1.0 - s;
    q->node[1] = b >= 0 ? ct->node[b].node : -1;
    q->entry[1] = b;
    q->w[1] = b >= 0 ? s : 0.0;
    q->allow = gap > 0 ? gap : 0.0; /* divided by dt in the law */
    q->mass = 0.0;
}

/* A point where particle ip (stencil st, normal n into obstacle k, gap, mass mp) may touch an obstacle:
 * the particle itself, through those of its stencil's nodes that are the obstacle's candidates (slot),
 * so that the law holds the velocity that carries it and no node further than that velocity needs. */
static void add_touch(pm_contact *ct, size_t k, size_t ip, const pm_stencil *st, const double n[PM_DIM],
                      double gap, double mp)
{
    if (ct->n_pt >= ct->pt_cap) {
        ct->surface[k].points_lost = 1;
        return;
    }
    pm_contact_point *q = &ct->pt[ct->n_pt];
    last_impulses(ct, k, ip, q);
    q->particle = q->index = ip;
    int m = 0;
    for (int j = 0; j < st->n; j++) {
        const int32_t e = ct->slot[st->node[j]];
        if (e < 0 || !(st->N[j] > 0))
            continue;
        int at = m;
        if (m == PM_CONTACT_POINT_NODES) { /* a wide stencil: its largest shape functions */
            at = 0;
            for (int r = 1; r < m; r++)
                if (q->w[r] < q->w[at])
                    at = r;
            if (!(st->N[j] > q->w[at]))
                continue;
        } else {
            m++;
        }
        q->node[at] = st->node[j];
        q->entry[at] = e;
        q->w[at] = st->N[j];
    }
    double sum = 0.0;
    for (int i = 0; i < m; i++)
        sum += q->w[i];
    if (!(sum > 0))
        return;
    /* the candidates' share of a stencil reaching beyond them stands for the whole particle */
    for (int i = 0; i < m; i++)
        q->w[i] /= sum;
    q->n = m;
    q->surface = (int32_t)k;
    for (int d = 0; d < PM_DIM; d++)
        q->normal[d] = n[d];
    q->allow = gap > 0 ? gap : 0.0;
    q->mass = mp;
    ct->n_pt++;
}

/* The gaps of the entries [first, last) of surface k from the particles near it. */
static void surface_gaps(pm_contact *ct, size_t k, size_t first, size_t last, const pm_approx *a,
                         const pm_particles *p)
{
    pm_contact_surface *sf = &ct->surface[k];
    /* the nodal law of a node set or an obstacle acts where the material touches it, once points are
     * reserved */
    sf->points_lost = 0;
    const int points = ct->pt_cap > 0 && pm_contact_takes_points(sf);
    for (size_t e = first; e < last; e++) {
        ct->slot[ct->node[e].node] = (int32_t)e;
        ct->node[e].gap = INFINITY; /* no particle in the node's support: nothing to touch */
    }
    if (points) { /* this surface's points of the last step, if it had any, start at the first of them */
        size_t c = ct->pt_cursor;
        const size_t end = ct->pt_old + ct->n_pt_old;
        while (c < end && ct->pt[c].surface != (int32_t)k)
            c++;
        if (c < end)
            ct->pt_cursor = c;
    }
    pm_stencil st;
    for (size_t i = 0; i < p->n; i++) {
        if (!in_box(sf, p->x + PM_DIM * i))
            continue;
        double n[PM_DIM], sd;
        if (sf->kind == PM_CONTACT_EDGES) {
            /* a wall of many edges whose box may hold the whole body (a bin's outline): the distance to
             * every edge only for the particles whose stencil holds one of its nodes, the only ones that
             * set a gap below */
            if (pm_approx_eval(a, p, i, &st) != 0)
                continue;
            int near = 0;
            for (int j = 0; j < st.n && !near; j++)
                near = ct->slot[st.node[j]] >= 0 && st.N[j] > 0;
            if (!near)
                continue;
            sd = pm_contact_distance(ct, sf, p->x + PM_DIM * i, n);
            if (sd > ct->reach)
                continue;
        } else {
            sd = pm_contact_distance(ct, sf, p->x + PM_DIM * i, n);
            if (sd > ct->reach || pm_approx_eval(a, p, i, &st) != 0)
                continue;
        }
        /* the penalty law pushes on the particles' centres: its force grows from the first step on,
         * and a body seeded against the obstacle starts with no energy stored in it */
        const double gap = sf->law == PM_CONTACT_LAW_PENALTY_COULOMB && !ct->surface_gaps ? sd : sd - half_size(p, i);
        /* the particle moves mostly with its nearest contact nodes: it sets their gap only, so that a
         * node is not held by material at the far edge of its support (ahead of a rolling contact) */
        double wmax = 0.0;
        for (int j = 0; j < st.n; j++)
            if (ct->slot[st.node[j]] >= 0 && st.N[j] > wmax)
                wmax = st.N[j];
        int32_t e_max = -1;
        for (int j = 0; wmax > 0 && j < st.n; j++) {
            const int32_t e = ct->slot[st.node[j]];
            if (e >= 0 && st.N[j] == wmax && e_max < 0)
                e_max = e;
            if (e >= 0 && st.N[j] >= VOTE * wmax && gap < ct->node[e].gap) {
                ct->node[e].gap = gap;
                /* a tool's tip pushes the material along the face it lies off (seed 004 §5.3.2) */
                if (ct->node[e].corner)
                    for (int d = 0; d < PM_DIM; d++)
                        ct->node[e].normal[d] = n[d];
            }
        }
        if (points && gap <= 0.25 * ct->reach) {
            if (sf->kind != PM_CONTACT_NODE_SET)
                add_touch(ct, k, i, &st, n, gap, p->mass[i]);
            else if (e_max >= 0)
                add_point(ct, k, e_max, i, sd, n, gap, p->x + PM_DIM * i);
        }
    }
    /* a node held by both faces of a corner has two entries side by side, and the slot named the last */
    for (size_t e = last; e-- > first + 1;)
        if (ct->node[e - 1].node == ct->node[e].node)
            ct->node[e - 1].gap = ct->node[e].gap;
    for (size_t e = first; e < last; e++)
        ct->slot[ct->node[e].node] = -1;
}

void pm_contact_gaps(pm_contact *ct, const pm_approx *a, const pm_particles *p)
{
    if (!ct || !ct->slot)
        return;
    /* node sets hold their entries in creation order, the others in detection order: both by surface */
    size_t e = 0;
    /* the last step's points go to the end of the list, where the new ones find the impulses they start
     * from (friction.c); when the two lists might not fit side by side, every point starts from zero */
    const size_t old = ct->n_pt;
    ct->n_pt_old = 0;
    ct->pt_old = ct->pt_cap;
    if (old > 0 && 2 * old <= ct->pt_cap) {
        ct->pt_old = ct->pt_cap - old;
        memmove(ct->pt + ct->pt_old, ct->pt, old * sizeof *ct->pt);
        ct->n_pt_old = old;
    }
    ct->pt_cursor = ct->pt_old;
    ct->n_pt = 0;
    while (e < ct->n_node) {
        const int32_t k = ct->node[e].surface;
        size_t end = e;
        while (end < ct->n_node && ct->node[end].surface == k)
            end++;
        surface_gaps(ct, (size_t)k, e, end, a, p);
        e = end;
    }
}
