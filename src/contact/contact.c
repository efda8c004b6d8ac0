/* Contact surfaces from the case, their detection, their forces, and the implicit entry (contact.h). */
#include "contact/contact.h"

#include "pmech/error.h"
#include "solver/boundary.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pm_contact_new(size_t n_nodes, pm_contact **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return pm_error_set(PM_ENOMEM, "out of memory for the contact surfaces");
    (*out)->n_nodes = n_nodes;
    (*out)->slot = malloc((n_nodes ? n_nodes : 1) * sizeof *(*out)->slot);
    if (!(*out)->slot) {
        free(*out);
        *out = NULL;
        return pm_error_set(PM_ENOMEM, "out of memory for the contact surfaces");
    }
    for (size_t i = 0; i < n_nodes; i++)
        (*out)->slot[i] = -1;
    return PM_OK;
}

void pm_contact_destroy(pm_contact *ct)
{
    if (!ct)
        return;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        free(ct->surface[k].node_impulse);
    free(ct->surface);
    free(ct->node);
    free(ct->points);
    free(ct->slot);
    free(ct->held);
    free(ct->held_next);
    free(ct->pt);
    free(ct->side_nbr);
    free(ct->pt_impulse);
    free(ct->pt_renum);
    free(ct);
}

int pm_contact_add_surface(pm_contact *ct, size_t more_nodes, pm_contact_surface **out)
{
    pm_contact_surface *s = realloc(ct->surface, (ct->n_surfaces + 1) * sizeof *s);
    if (!s)
        return pm_error_set(PM_ENOMEM, "out of memory for the contact surfaces");
    ct->surface = s;
    if (more_nodes) {
        pm_contact_node *n = realloc(ct->node, (ct->cap + more_nodes) * sizeof *n);
        if (!n)
            return pm_error_set(PM_ENOMEM, "out of memory for friction nodes");
        ct->node = n;
        ct->cap += more_nodes;
    }
    double *J = calloc((size_t)(1 + PM_DIM) * (ct->n_nodes ? ct->n_nodes : 1), sizeof *J);
    if (!J)
        return pm_error_set(PM_ENOMEM, "out of memory for the contact surfaces");
    *out = &ct->surface[ct->n_surfaces];
    memset(*out, 0, sizeof **out);
    (*out)->node_impulse = J;
    (*out)->bc = (*out)->obstacle = -1;
    return (int)ct->n_surfaces++;
}

int pm_contact_add_node_set(pm_contact *ct, size_t n, const int32_t *nodes, const double normal[PM_DIM], double mu,
                            pm_contact_law law, long bc)
{
    pm_contact_surface *sf = NULL;
    const int k = pm_contact_add_surface(ct, n, &sf);
    if (k < 0)
        return k;
    sf->kind = PM_CONTACT_NODE_SET;
    sf->law = law;
    sf->mu = mu;
    sf->bc = bc;
    sf->axis = -1;
    for (int d = 0; d < PM_DIM; d++)
        sf->normal[d] = normal[d];
    /* node-set entries come first; the walls' entries after them are found again by every detection,
     * so n_node is cut back to the node sets' entries below */
    sf->first = ct->n_fixed;
    sf->n = n;
    for (size_t i = 0; i < n; i++) {
        pm_contact_node *cn = &ct->node[ct->n_fixed++];
        cn->node = nodes[i];
        cn->surface = k;
        for (int d = 0; d < PM_DIM; d++)
            cn->normal[d] = normal[d];
        cn->mu = mu;
        cn->gap = 0.0;
        cn->held = 0;
        cn->corner = 0;
    }
    ct->n_node = ct->n_fixed;
    return k;
}

int pm_contact_add_wall(pm_contact *ct, int axis, double value, const double normal[PM_DIM], double mu,
                        pm_contact_law law, long bc, int guard)
{
    pm_contact_surface *sf = NULL;
    const int k = pm_contact_add_surface(ct, ct->n_nodes, &sf); /* room for every node: the list never grows in a step */
    if (k < 0)
        return k;
    sf->kind = PM_CONTACT_WALL;
    sf->origin[axis] = value;
    sf->law = law;
    sf->mu = mu;
    sf->bc = bc;
    sf->guard = guard;
    sf->axis = axis;
    sf->value = value;
    for (int d = 0; d < PM_DIM; d++)
        sf->normal[d] = normal[d];
    return k;
}

/* A `fixed` condition on a grid side that holds the side's normal component: in MPM every grid node
 * on the side is held; meshfree nodes that reach the side later (material spreading over a base) are
 * stopped there by a guard wall that sticks when the tangent is held too and slides freely
 * otherwise; the nodes on it at t = 0 keep their condition as well. */
static int side_wall(const pm_case_bc *bc, int *axis, int *hi, double *mu)
{
    if (bc->type != PM_BC_FIXED || bc->line_axis >= 0 || !pm_grid_side_of(bc->boundary, axis, hi) ||
        !(bc->dirs & (1u << *axis)))
        return 0;
    *mu = (bc->dirs & (1u << (1 - *axis))) ? INFINITY : 0.0;
    return 1;
}

/* A Gmsh group's normal that is a grid axis' (to round-off): that axis' exact normal in n. Such a
 * group is a grid side or line drawn in the mesh, and takes their law (the material held at its touching
 * points, between nodes) rather than the node-by-node law of curved and inclined groups, so a case on a
 * mesh of a rectangle gives the numbers of the same case on the `rectangle` grid. */
static int axis_aligned(const double normal[PM_DIM], double n[PM_DIM])
{
    for (int d = 0; d < PM_DIM; d++) {
        if (fabs(fabs(normal[d]) - 1.0) > 1e-12)
            continue;
        for (int e = 0; e < PM_DIM; e++)
            n[e] = e == d ? (normal[d] > 0 ? 1.0 : -1.0) : 0.0;
        return 1;
    }
    return 0;
}

/* MPM: a friction condition holds the grid nodes of its side or line from t = 0 on. */
static int node_set_surfaces(pm_contact *ct, const pm_case *c, pm_grid *g)
{
    for (size_t b = 0; b < c->n_bcs; b++) {
        const pm_case_bc *bc = &c->bcs[b];
        if (bc->type != PM_BC_FRICTION)
            continue;
        const pm_node_set *set;
        pm_check(pm_bc_node_set(c, b, g, &set));
        double axis_normal[PM_DIM];
        const int straight = axis_aligned(set->normal, axis_normal);
        if (set->n_edges && !straight) { /* a Gmsh group on the mesh's boundary: the normals of its edges */
            const int k = pm_contact_add_edge_set(ct, g, set, bc->coefficient, PM_CONTACT_LAW_NODAL_COULOMB, (long)b);
            if (k < 0)
                return k;
            continue;
        }
        int given = 0;
        for (int d = 0; d < PM_DIM; d++)
            given |= set->normal[d] != 0;
        if (!given)
            return pm_error_set(PM_EINPUT,
                                "%s: boundary_conditions[%zu]: friction needs a grid side (x_min, x_max, "
                                "y_min, y_max) or a line with an outward \"normal\"",
                                c->file, b);
        const int k = pm_contact_add_node_set(ct, set->n, set->nodes, straight ? axis_normal : set->normal,
                                              bc->coefficient, PM_CONTACT_LAW_NODAL_COULOMB, (long)b);
        if (k < 0)
            return k;
        /* its plane, for the gaps of the material from it: through a node of the set */
        for (int d = 0; set->n && d < PM_DIM; d++)
            ct->surface[k].origin[d] = g->x[PM_DIM * set->nodes[0] + d];
    }
    return PM_OK;
}

/* gmm, rkpm: friction conditions, and fixed sides, as walls at the grid side or the given line. */
static int wall_surfaces(pm_contact *ct, const pm_case *c, const pm_grid *frame)
{
    for (size_t b = 0; b < c->n_bcs; b++) {
        const pm_case_bc *bc = &c->bcs[b];
        int axis, hi, k;
        double mu, normal[PM_DIM] = {0};
        if (side_wall(bc, &axis, &hi, &mu)) {
            normal[axis] = hi ? 1.0 : -1.0;
            k = pm_contact_add_wall(ct, axis, hi ? frame->hi[axis] : frame->lo[axis], normal, mu,
                                    PM_CONTACT_LAW_NODAL_COULOMB, (long)b, 1);
            if (k < 0)
                return k;
            continue;
        }
        if (bc->type != PM_BC_FRICTION)
            continue;
        double value;
        if (bc->line_axis >= 0) {
            axis = bc->line_axis;
            value = bc->line_value;
            for (int d = 0; d < PM_DIM; d++)
                normal[d] = bc->line_normal[d];
        } else if (pm_grid_side_of(bc->boundary, &axis, &hi)) {
            value = hi ? frame->hi[axis] : frame->lo[axis];
            normal[axis] = hi ? 1.0 : -1.0;
        } else {
            /* a Gmsh group on the mesh's boundary: a wall of its edges */
            const pm_node_set *set = pm_grid_find_set(frame, bc->boundary);
            if (set && set->n_edges) {
                k = pm_contact_add_edge_wall(ct, frame, set, bc->coefficient, PM_CONTACT_LAW_NODAL_COULOMB, (long)b);
                if (k < 0)
                    return k;
                continue;
            }
            return pm_error_set(PM_EINPUT,
                                "%s: boundary_conditions[%zu].boundary: with method gmm or rkpm, friction needs a "
                                "grid side (x_min, x_max, y_min, y_max), a line or a 1-D group on the boundary "
                                "of the Gmsh mesh, not '%s'",
                                c->file, b, bc->boundary);
        }
        if (normal[axis] == 0)
            return pm_error_set(PM_EINPUT,
                                "%s: boundary_conditions[%zu]: a friction line of a meshfree run needs a \"normal\" "
                                "along its axis",
                                c->file, b);
        k = pm_contact_add_wall(ct, axis, value, normal, bc->coefficient, PM_CONTACT_LAW_NODAL_COULOMB, (long)b, 0);
        if (k < 0)
            return k;
    }
    return PM_OK;
}


/* The largest P-wave speed of the case's materials at their reference state (penalty stiffness). */
static double wave_speed(const pm_case *c)
{
    double w = 0.0;
    for (size_t m = 0; m < c->n_materials; m++) {
        const double cm = pm_material_elastic_wave_speed(&c->materials[m], NULL, c->materials[m].density);
        if (isfinite(cm) && cm > w)
            w = cm;
    }
    return w;
}

int pm_contact_add_obstacle(pm_contact *ct, const pm_case *c, size_t k, double wave, double h)
{
    const pm_case_obstacle *ob = &c->obstacles[k];
    const size_t np = ob->type == PM_OBSTACLE_CIRCLE ? 0 : ob->n_points;
    double *pts = realloc(ct->points, PM_DIM * (ct->n_points + np + 1) * sizeof *pts);
    if (!pts)
        return pm_error_set(PM_ENOMEM, "out of memory for the obstacles");
    ct->points = pts;
    pm_contact_surface *sf = NULL;
    const int i = pm_contact_add_surface(ct, ct->n_nodes, &sf); /* room for every node: the list never grows in a step */
    if (i < 0)
        return i;
    sf->obstacle = (long)k;
    sf->law = ob->law == PM_OBSTACLE_PENALTY ? PM_CONTACT_LAW_PENALTY_COULOMB : PM_CONTACT_LAW_NODAL_COULOMB;
    sf->mu = ob->friction;
    sf->axis = -1;
    sf->motion = ob->velocity;
    sf->stiffness = ob->penalty_factor * (wave / h) * (wave / h);
    sf->at_particles = ob->at_particles;
    if (ob->type == PM_OBSTACLE_CIRCLE) {
        sf->kind = PM_CONTACT_CIRCLE;
        for (int d = 0; d < PM_DIM; d++)
            sf->origin[d] = ob->center[d];
        sf->radius = ob->radius;
        return i;
    }
    sf->kind = ob->type == PM_OBSTACLE_POLYGON ? PM_CONTACT_POLYGON : PM_CONTACT_POLYLINE;
    sf->first_point = ct->n_points;
    sf->n_points = np;
    memcpy(ct->points + PM_DIM * ct->n_points, ob->points, PM_DIM * np * sizeof *pts);
    ct->n_points += np;
    sf->sharp = ob->sharp_corners;
    if (sf->kind == PM_CONTACT_POLYLINE) {
        sf->side = ob->material_right ? -1.0 : 1.0;
    } else {
        double area2 = 0.0; /* twice the signed area: positive when counter-clockwise */
        for (size_t q = 0; q < np; q++) {
            const double *a = ob->points + PM_DIM * q, *b = ob->points + PM_DIM * ((q + 1) % np);
            area2 += a[0] * b[1] - a[1] * b[0];
        }
        sf->side = area2 > 0 ? -1.0 : 1.0;
    }
    return i;
}

static int obstacle_surfaces(pm_contact *ct, const pm_case *c, const pm_grid *frame)
{
    const double wave = wave_speed(c), h = frame->h_min;
    for (size_t k = 0; k < c->n_obstacles; k++) {
        const int i = pm_contact_add_obstacle(ct, c, k, wave, h);
        if (i < 0)
            return i;
    }
    return PM_OK;
}

int pm_contact_create(const pm_case *c, pm_grid *g, const pm_grid *frame, pm_contact **out)
{
    *out = NULL;
    pm_contact *ct;
    pm_check(pm_contact_new(g->n_nodes, &ct));
    /* a node or particle this close to a surface may take part: two cells cover the widest support of
     * the grid kinds (linear 1, uGIMP 1 + half a particle, B-spline 1.5 cells) */
    ct->reach = 2.0 * frame->h_min;
    const double wave = wave_speed(c);
    ct->penalty = (wave / frame->h_min) * (wave / frame->h_min);
    int rc = c->method == PM_METHOD_MPM ? node_set_surfaces(ct, c, g) : wall_surfaces(ct, c, frame);
    if (!rc)
        rc = obstacle_surfaces(ct, c, frame);
    if (rc) {
        pm_contact_destroy(ct);
        return rc;
    }
    pm_contact_detect(ct, g, 0.0);
    *out = ct;
    return PM_OK;
}

size_t pm_contact_n_surfaces(const pm_contact *ct)
{
    return ct ? ct->n_surfaces : 0;
}

int pm_contact_force_of(const pm_contact *ct, size_t k, pm_contact_force *out)
{
    if (!ct || k >= ct->n_surfaces)
        return pm_error_set(PM_EINPUT, "no contact surface %zu", k);
    *out = ct->surface[k].f;
    return PM_OK;
}

/* A node-set entry and its position along its surface, for ordering the entries. */
typedef struct side_key {
    double along;
    int32_t e;
} side_key;

static int by_along(const void *a, const void *b)
{
    const double x = ((const side_key *)a)->along, y = ((const side_key *)b)->along;
    return (x > y) - (x < y);
}

int pm_contact_points_reserve(pm_contact *ct, const pm_grid *g, size_t cap)
{
#if PM_DIM != 2
#error "a node set's neighbours are ordered along a line"
#endif
    if (!ct || !g->x)
        return PM_OK;
    /* a particle sets a point only within half a cell of a node set (detect.c): up to 18 per node of
     * the set at 6 x 6 points per cell, so the list follows the nodes rather than the particles; on an
     * obstacle, the particles with a gap within half a cell: a band about 0.6 of a cell deep at 6 x 6
     * points per cell, some 22 per cell of its length, and room for three times that (material heaped
     * against it, the round of a corner); a step that finds more lets the surface act node by node */
    size_t want = ct->n_fixed ? (cap < 32 * ct->n_fixed ? cap : 32 * ct->n_fixed) : 0, want_ob = 0;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        if (ct->surface[k].kind != PM_CONTACT_NODE_SET && pm_contact_takes_points(&ct->surface[k]))
            want_ob += 64 * ((size_t)ceil(pm_contact_length(ct, k, g) / g->h_min) + 8);
    want += want_ob < cap ? want_ob : cap;
    if (!want)
        return PM_OK;
    const size_t rows = ct->cap ? ct->cap : 1; /* every entry any surface may have in a step */
    ct->pt = malloc(want * sizeof *ct->pt);
    ct->side_nbr = malloc(2 * (ct->n_fixed ? ct->n_fixed : 1) * sizeof *ct->side_nbr);
    ct->pt_impulse = malloc(PM_CONTACT_PT_ROW * rows * sizeof *ct->pt_impulse);
    ct->pt_renum = malloc(want * sizeof *ct->pt_renum);
    side_key *key = malloc((ct->n_fixed ? ct->n_fixed : 1) * sizeof *key);
    if (!ct->pt || !ct->side_nbr || !ct->pt_impulse || !ct->pt_renum || !key) {
        free(key);
        return pm_error_set(PM_ENOMEM, "out of memory for the contact points");
    }
    for (size_t k = 0; k < ct->n_surfaces; k++) {
        const pm_contact_surface *sf = &ct->surface[k];
        if (sf->kind != PM_CONTACT_NODE_SET)
            continue;
        /* a node set lies on a straight side or line: its nodes in order along it are neighbours */
        const double t[PM_DIM] = {-sf->normal[1], sf->normal[0]};
        for (size_t i = 0; i < sf->n; i++) {
            const double *x = g->x + PM_DIM * ct->node[sf->first + i].node;
            key[i].along = x[0] * t[0] + x[1] * t[1];
            key[i].e = (int32_t)(sf->first + i);
        }
        qsort(key, sf->n, sizeof *key, by_along);
        for (size_t i = 0; i < sf->n; i++) {
            ct->side_nbr[2 * key[i].e] = i > 0 ? key[i - 1].e : -1;
            ct->side_nbr[2 * key[i].e + 1] = i + 1 < sf->n ? key[i + 1].e : -1;
        }
    }
    free(key);
    ct->pt_cap = want;
    ct->node_x = g->x;
    return PM_OK;
}

/* Points of one surface in the order pm_contact_gaps() makes and matches them in: by particle. */
static int by_particle(const void *a, const void *b)
{
    const size_t i = ((const pm_contact_point *)a)->particle, j = ((const pm_contact_point *)b)->particle;
    return (i > j) - (i < j);
}

void pm_contact_renumber(pm_contact *ct, const uint32_t *perm, size_t n)
{
    if (!ct || !ct->n_pt)
        return;
    /* each surface's points (one run of the list, in the order of the surfaces' entries) are in order of
     * their old particles: every new index finds its particle's point, if it has one, by bisection */
    for (size_t q = 0; q < ct->n_pt; q++)
        ct->pt_renum[q] = ct->pt[q].particle;
    for (size_t lo = 0, hi; lo < ct->n_pt; lo = hi) {
        for (hi = lo; hi < ct->n_pt && ct->pt[hi].surface == ct->pt[lo].surface; hi++)
            ;
        for (size_t j = 0; j < n; j++) {
            size_t a = lo, b = hi;
            while (a < b) {
                const size_t mid = a + (b - a) / 2;
                if (ct->pt[mid].particle < perm[j])
                    a = mid + 1;
                else
                    b = mid;
            }
            if (a < hi && ct->pt[a].particle == perm[j])
                ct->pt_renum[a] = j;
        }
    }
    for (size_t lo = 0, hi; lo < ct->n_pt; lo = hi) {
        for (hi = lo; hi < ct->n_pt && ct->pt[hi].surface == ct->pt[lo].surface; hi++)
            ct->pt[hi].particle = ct->pt_renum[hi];
        qsort(ct->pt + lo, hi - lo, sizeof *ct->pt, by_particle);
    }
}
