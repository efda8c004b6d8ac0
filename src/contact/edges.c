/*
 * Walls on the boundary of a Gmsh mesh (contact.h, PM_CONTACT_EDGES): a 1-D physical group whose line
 * elements the reader kept, each turned so that its element lies on its left. Every node of the group
 * touches the wall from t = 0 on, as a node set's do, but with the normal of its own edges, so that a
 * curved or cornered boundary at any orientation acts along its true outward normal; the wall's shape for
 * the gaps from the material (geometry.c) and for the traction profile (profile.c) is its edges.
 *
 * GMM and RKPM have no nodes on the mesh's boundary once their node cloud moves with the material: there
 * the same edges make a fixed rigid wall whose contact nodes every detection finds again (the nodes within
 * reach of the edges, as for a polyline obstacle), each with the normal of the face it lies off.
 */
#include "contact/contact.h"

#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if PM_DIM != 2
#error "a mesh edge's outward normal is its direction turned a quarter in the plane"
#endif

/* Unit outward normal of edge q (the element on its left, so the outside on its right); its length. */
static double edge_normal(const pm_grid *g, const int32_t *e, size_t q, double n[2])
{
    const double *a = g->x + 2 * e[2 * q], *b = g->x + 2 * e[2 * q + 1];
    const double t[2] = {b[0] - a[0], b[1] - a[1]}, len = hypot(t[0], t[1]);
    n[0] = t[1] / len;
    n[1] = -t[0] / len;
    return len;
}

enum { NODE_NONE, NODE_ONE, NODE_TWO, NODE_TIP };

/* What a node of the wall is, from the edges that end (qi) and start (qo) there: NODE_ONE with one
 * normal (one edge, or two that turn by less than the corner angle), NODE_TWO with one per edge (the
 * domain turns inwards: both faces hold the node), NODE_TIP (it turns outwards: the material near the
 * node lies off one face or the other), NODE_NONE (no edge). */
static int classify(const pm_grid *g, const int32_t *e, int32_t qi, int32_t qo, double n1[2], double n2[2])
{
    if (qi < 0 && qo < 0)
        return NODE_NONE;
    if (qi < 0 || qo < 0) {
        edge_normal(g, e, (size_t)(qi < 0 ? qo : qi), n1);
        return NODE_ONE;
    }
    const double L1 = edge_normal(g, e, (size_t)qi, n1), L2 = edge_normal(g, e, (size_t)qo, n2);
    /* weights 1 / L: the two chords of a circle then balance exactly along the radius */
    double m[2] = {n1[0] / L1 + n2[0] / L2, n1[1] / L1 + n2[1] / L2};
    const double len = hypot(m[0], m[1]);
    const int corner = n1[0] * n2[0] + n1[1] * n2[1] < cos(PM_CONTACT_CORNER_DEG * M_PI / 180.0);
    if (!corner) {
        n1[0] = m[0] / len, n1[1] = m[1] / len;
        return NODE_ONE;
    }
    /* the edges' directions are the normals turned back a quarter: (-n_y, n_x) */
    const double turn = (-n1[1]) * n2[0] - n1[0] * (-n2[1]);
    if (turn > 0)
        return NODE_TWO;
    if (len > 1e-12 * (1 / L1 + 1 / L2)) /* the tip's first normal until the material chooses a face */
        n1[0] = m[0] / len, n1[1] = m[1] / len;
    return NODE_TIP;
}

/* An entry of wall k at node; @p second: the node's second face at an inward corner, which keeps its own
 * force history in implicit runs. */
static void push(pm_contact *ct, int32_t node, int32_t k, const double n[2], double mu, int corner, int second)
{
    pm_contact_node *cn = &ct->node[ct->n_fixed++];
    memset(cn, 0, sizeof *cn);
    cn->node = node;
    cn->surface = k;
    cn->normal[0] = n[0], cn->normal[1] = n[1];
    cn->mu = mu;
    cn->corner = corner;
    if (second)
        cn->own_row = (int32_t)++ct->n_own_rows;
}

/* A new wall surface of the edges of @p set (nodes of @p g) with room for @p entries more entries: its
 * edges, two points each, appended to pm_contact::points. @return its index, or a negative status */
static int edge_surface(pm_contact *ct, const pm_grid *g, const pm_node_set *set, size_t entries, double mu,
                        pm_contact_law law, long bc, pm_contact_surface **out)
{
    const size_t ne = set->n_edges;
    const int32_t *e = set->edges;
    double *pts = realloc(ct->points, PM_DIM * (ct->n_points + 2 * ne + 1) * sizeof *pts);
    if (!pts)
        return pm_error_set(PM_ENOMEM, "out of memory for the wall '%s'", set->name);
    ct->points = pts;
    pm_contact_surface *sf = NULL;
    const int k = pm_contact_add_surface(ct, entries, &sf);
    if (k < 0)
        return k;
    sf->kind = PM_CONTACT_EDGES;
    sf->law = law;
    sf->mu = mu;
    sf->bc = bc;
    sf->axis = -1;
    sf->side = 1.0;
    sf->sharp = 1;
    for (int d = 0; d < PM_DIM; d++) {
        sf->normal[d] = set->normal[d];
        sf->origin[d] = g->x[PM_DIM * e[0] + d];
    }
    sf->first_point = ct->n_points;
    sf->n_points = 2 * ne;
    for (size_t q = 0; q < 2 * ne; q++)
        for (int d = 0; d < PM_DIM; d++)
            ct->points[PM_DIM * (ct->n_points + q) + d] = g->x[PM_DIM * e[q] + d];
    ct->n_points += 2 * ne;
    *out = sf;
    return k;
}

int pm_contact_add_edge_wall(pm_contact *ct, const pm_grid *frame, const pm_node_set *set, double mu,
                             pm_contact_law law, long bc)
{
    pm_contact_surface *sf = NULL;
    /* room for every node: the list never grows in a step */
    const int k = edge_surface(ct, frame, set, ct->n_nodes, mu, law, bc, &sf);
    if (k >= 0)
        sf->detected = 1;
    return k;
}

int pm_contact_add_edge_set(pm_contact *ct, const pm_grid *g, const pm_node_set *set, double mu,
                            pm_contact_law law, long bc)
{
    const int32_t *e = set->edges;
    int32_t *in = malloc((g->n_nodes + 1) * sizeof *in), *out = malloc((g->n_nodes + 1) * sizeof *out);
    if (!in || !out) {
        free(in), free(out);
        return pm_error_set(PM_ENOMEM, "out of memory for the wall '%s'", set->name);
    }
    for (size_t n = 0; n < g->n_nodes; n++)
        in[n] = out[n] = -1;
    for (size_t q = 0; q < set->n_edges; q++) {
        if (out[e[2 * q]] < 0)
            out[e[2 * q]] = (int32_t)q;
        if (in[e[2 * q + 1]] < 0)
            in[e[2 * q + 1]] = (int32_t)q;
    }
    size_t count = 0;
    double n1[2], n2[2];
    for (size_t i = 0; i < set->n; i++) {
        const int c = classify(g, e, in[set->nodes[i]], out[set->nodes[i]], n1, n2);
        count += c == NODE_TWO ? 2 : c == NODE_NONE ? 0 : 1;
    }
    pm_contact_surface *sf = NULL;
    const int k = edge_surface(ct, g, set, count, mu, law, bc, &sf);
    if (k < 0) {
        free(in), free(out);
        return k;
    }
    sf->first = ct->n_fixed;
    sf->n = count;
    for (size_t i = 0; i < set->n; i++) {
        const int32_t node = set->nodes[i];
        const int c = classify(g, e, in[node], out[node], n1, n2);
        if (c == NODE_NONE)
            continue;
        push(ct, node, k, n1, mu, c == NODE_TIP, 0);
        /* both faces of an inward corner hold the node: the entries stay side by side (detect.c) */
        if (c == NODE_TWO)
            push(ct, node, k, n2, mu, 0, 1);
    }
    ct->n_node = ct->n_fixed;
    free(in), free(out);
    return k;
}
