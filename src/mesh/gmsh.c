/*
 * Gmsh meshes to grids: the parsed file (gmsh_read.c) becomes an unstructured grid of one element
 * kind (a mesh of triangles and quads becomes all triangles, each quad split in two), its 2-D physical
 * groups cell sets, its 1-D and 0-D groups node sets with the outward normal of a straight one, and a
 * 1-D group on the mesh's boundary keeps its line elements, turned to have their element on the left
 * and put in chains, so that a wall on it can take its normals and its shape from them.
 */
#include "mesh/gmsh_internal.h"
#include "mesh/mesh_internal.h"

#include "pmech/error.h"
#include "pmech/grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const pm_msh_entity *find_entity(const pm_msh *m, int dim, int tag)
{
    for (size_t i = 0; i < m->n_ent; i++)
        if (m->ent[i].dim == dim && m->ent[i].tag == tag)
            return &m->ent[i];
    return NULL;
}

static void phys_label(const pm_msh *m, int dim, int tag, char out[64])
{
    for (size_t i = 0; i < m->n_names; i++)
        if (m->names[i].dim == dim && m->names[i].tag == tag) {
            snprintf(out, 64, "%s", m->names[i].name);
            return;
        }
    snprintf(out, 64, "%d", tag);
}

/* Outward normal of a node set when its nodes lie on one straight line (else zero). */
static void line_normal(const pm_grid *g, const int32_t *nodes, size_t n, int32_t ea, int32_t eb, double nrm[PM_DIM])
{
    nrm[0] = nrm[1] = 0;
    if (n < 2)
        return;
    /* direction from the farthest pair found from node 0 */
    const double *p0 = g->x + PM_DIM * nodes[0];
    size_t far = 0;
    double dmax = 0;
    for (size_t i = 1; i < n; i++) {
        const double *p = g->x + PM_DIM * nodes[i];
        double d = hypot(p[0] - p0[0], p[1] - p0[1]);
        if (d > dmax) {
            dmax = d;
            far = i;
        }
    }
    if (dmax <= 0)
        return;
    const double *p1 = g->x + PM_DIM * nodes[far];
    double t[PM_DIM] = {(p1[0] - p0[0]) / dmax, (p1[1] - p0[1]) / dmax};
    for (size_t i = 0; i < n; i++) {
        const double *p = g->x + PM_DIM * nodes[i];
        if (fabs((p[0] - p0[0]) * t[1] - (p[1] - p0[1]) * t[0]) > 1e-9 * dmax)
            return; /* not straight */
    }
    double cand[PM_DIM] = {t[1], -t[0]};
    /* orient away from a cell that has edge (ea, eb) */
    const int npc = g->nodes_per_cell;
    for (size_t c = 0; c < g->n_cells; c++) {
        const int32_t *v = g->conn + (size_t)npc * c;
        int has_a = 0, has_b = 0;
        double cx = 0, cy = 0;
        for (int k = 0; k < npc; k++) {
            has_a |= v[k] == ea;
            has_b |= v[k] == eb;
            cx += g->x[PM_DIM * v[k]] / npc;
            cy += g->x[PM_DIM * v[k] + 1] / npc;
        }
        if (has_a && has_b) {
            double mx = 0.5 * (g->x[PM_DIM * ea] + g->x[PM_DIM * eb]);
            double my = 0.5 * (g->x[PM_DIM * ea + 1] + g->x[PM_DIM * eb + 1]);
            double s = cand[0] * (mx - cx) + cand[1] * (my - cy);
            nrm[0] = s >= 0 ? cand[0] : -cand[0];
            nrm[1] = s >= 0 ? cand[1] : -cand[1];
            return;
        }
    }
}

/* The cells around every node (compressed rows): which element owns an edge of a 1-D group. */
typedef struct node_cells {
    int32_t *start; /* n_nodes + 1 */
    int32_t *cell;
} node_cells;

static int node_cells_build(const pm_grid *g, node_cells *nc)
{
    const int npc = g->nodes_per_cell;
    nc->start = calloc(g->n_nodes + 1, sizeof *nc->start);
    nc->cell = malloc(((size_t)npc * g->n_cells + 1) * sizeof *nc->cell);
    if (!nc->start || !nc->cell)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t k = 0; k < (size_t)npc * g->n_cells; k++)
        nc->start[g->conn[k] + 1]++;
    for (size_t n = 0; n < g->n_nodes; n++)
        nc->start[n + 1] += nc->start[n];
    int32_t *fill = malloc((g->n_nodes + 1) * sizeof *fill);
    if (!fill)
        return pm_error_set(PM_ENOMEM, "out of memory");
    memcpy(fill, nc->start, g->n_nodes * sizeof *fill);
    for (size_t c = 0; c < g->n_cells; c++)
        for (int k = 0; k < npc; k++)
            nc->cell[fill[g->conn[(size_t)npc * c + k]]++] = (int32_t)c;
    free(fill);
    return PM_OK;
}

/* Turn every edge (a, b) of a group so that the one element owning it lies on its left (the grid's
 * cells run counter-clockwise, so the owner lists b right after a), then put the edges in chains.
 * Returns 0 when an edge has no owner or two (a line inside the mesh has no outward side). */
static int orient_edges(const pm_grid *g, const node_cells *nc, int32_t *e, size_t ne, int32_t *next_of)
{
    const int npc = g->nodes_per_cell;
    for (size_t q = 0; q < ne; q++) {
        const int32_t a = e[2 * q], b = e[2 * q + 1];
        int owners = 0, flip = 0;
        for (int32_t i = nc->start[a]; i < nc->start[a + 1]; i++) {
            const int32_t *v = g->conn + (size_t)npc * (size_t)nc->cell[i];
            for (int k = 0; k < npc; k++) {
                const int32_t p = v[k], r = v[(k + 1) % npc];
                if (p == a && r == b)
                    owners++;
                else if (p == b && r == a)
                    owners++, flip = 1;
            }
        }
        if (owners != 1)
            return 0;
        if (flip)
            e[2 * q] = b, e[2 * q + 1] = a;
    }
    /* chains: start at the edges nothing leads into (open ends), then whatever closed loops are left;
     * each node leads on to the edge that starts there */
    int32_t *tmp = malloc((2 * ne + 1) * sizeof *tmp);
    uint8_t *done = calloc(ne + 1, 1);
    uint8_t *led = calloc(g->n_nodes + 1, 1);
    if (!tmp || !done || !led) {
        free(tmp), free(done), free(led);
        return -1;
    }
    for (size_t q = 0; q < ne; q++) {
        next_of[e[2 * q]] = (int32_t)q;
        led[e[2 * q + 1]] = 1;
    }
    size_t out = 0;
    for (int pass = 0; pass < 2; pass++)
        for (size_t q0 = 0; q0 < ne; q0++) {
            if (done[q0] || (pass == 0 && led[e[2 * q0]]))
                continue;
            for (int32_t q = (int32_t)q0; q >= 0 && !done[q]; q = next_of[e[2 * q + 1]]) {
                done[q] = 1;
                tmp[2 * out] = e[2 * q], tmp[2 * out + 1] = e[2 * q + 1];
                out++;
            }
        }
    memcpy(e, tmp, 2 * ne * sizeof *e);
    for (size_t q = 0; q < ne; q++)
        next_of[e[2 * q]] = -1;
    free(tmp), free(done), free(led);
    return 1;
}

/* Build the grid from the parsed file. */
static int build(pm_grid *g, const pm_msh *m, const char *path)
{
    const size_t n2d = m->n_tri + m->n_quad;
    if (n2d == 0)
        return pm_error_set(PM_EINPUT, "%s: the mesh has no triangles or quads (mesh it in 2-D: gmsh -2)", path);
    const int mixed = m->n_tri && m->n_quad;
    const pm_element el = m->n_quad && !mixed ? PM_QUAD4 : PM_TRI3;
    const int npc = el == PM_QUAD4 ? 4 : 3;
    const size_t ncells = m->n_tri + (mixed ? 2 : 1) * m->n_quad;
    int32_t *conn = malloc(ncells * (size_t)npc * sizeof(int32_t));
    long *used = malloc(m->n_nodes * sizeof(long)); /* node index -> compact index */
    double *xy = malloc(PM_DIM * m->n_nodes * sizeof(double));
    int32_t *cell_of = malloc(n2d * sizeof(int32_t)); /* first cell of each 2-D element */
    int rc = PM_OK;
    if (!conn || !used || !xy || !cell_of) {
        rc = pm_error_set(PM_ENOMEM, "out of memory reading %s", path);
        goto done;
    }
    for (size_t i = 0; i < m->n_nodes; i++)
        used[i] = -1;
    size_t nn = 0, c = 0;
#define NODE(tag) (used[m->tag_index[tag]] >= 0 ? used[m->tag_index[tag]] \
                   : (xy[PM_DIM * nn] = m->xy[PM_DIM * m->tag_index[tag]],                     \
                      xy[PM_DIM * nn + 1] = m->xy[PM_DIM * m->tag_index[tag] + 1],              \
                      used[m->tag_index[tag]] = (long)nn++))
    for (size_t e = 0; e < m->n_tri; e++) {
        cell_of[e] = (int32_t)c;
        for (int k = 0; k < 3; k++)
            conn[3 * c + k] = (int32_t)NODE(m->tri[3 * e + k]);
        c++;
    }
    for (size_t e = 0; e < m->n_quad; e++) {
        int32_t q[4];
        for (int k = 0; k < 4; k++)
            q[k] = (int32_t)NODE(m->quad[4 * e + k]);
        cell_of[m->n_tri + e] = (int32_t)c;
        if (!mixed) {
            memcpy(conn + 4 * c, q, sizeof q);
            c++;
        } else {
            int32_t t1[3] = {q[0], q[1], q[2]}, t2[3] = {q[0], q[2], q[3]};
            memcpy(conn + 3 * c, t1, sizeof t1);
            memcpy(conn + 3 * (c + 1), t2, sizeof t2);
            c += 2;
        }
    }
#undef NODE
    rc = pm_grid_unstructured(g, nn, xy, ncells, conn, el);
    if (rc) {
        pm_error_prefix(rc, "%s: ", path);
        goto done;
    }
    /* 2-D physical groups -> cell sets */
    for (size_t ie = 0; ie < m->n_ent && !rc; ie++) {
        const pm_msh_entity *en = &m->ent[ie];
        if (en->dim != 2)
            continue;
        for (int q = 0; q < en->n_phys && !rc; q++) {
            char name[64];
            phys_label(m, 2, en->phys[q], name);
            pm_cell_set *set = NULL;
            for (size_t s = 0; s < g->n_cell_sets; s++)
                if (strcmp(g->cell_sets[s].name, name) == 0)
                    set = &g->cell_sets[s];
            if (!set) {
                pm_cell_set *cs = realloc(g->cell_sets, (g->n_cell_sets + 1) * sizeof *cs);
                if (!cs) {
                    rc = pm_error_set(PM_ENOMEM, "out of memory");
                    break;
                }
                g->cell_sets = cs;
                set = &g->cell_sets[g->n_cell_sets++];
                memset(set, 0, sizeof *set);
                snprintf(set->name, sizeof set->name, "%s", name);
            }
            size_t add = 0;
            for (size_t e = 0; e < n2d; e++) {
                int ent = e < m->n_tri ? m->tri_ent[e] : m->quad_ent[e - m->n_tri];
                if (ent == en->tag)
                    add += (e >= m->n_tri && mixed) ? 2 : 1;
            }
            int32_t *cells = realloc(set->cells, (set->n + add + 1) * sizeof(int32_t));
            if (!cells) {
                rc = pm_error_set(PM_ENOMEM, "out of memory");
                break;
            }
            set->cells = cells;
            for (size_t e = 0; e < n2d; e++) {
                int ent = e < m->n_tri ? m->tri_ent[e] : m->quad_ent[e - m->n_tri];
                if (ent != en->tag)
                    continue;
                set->cells[set->n++] = cell_of[e];
                if (e >= m->n_tri && mixed)
                    set->cells[set->n++] = cell_of[e] + 1;
            }
        }
    }
    /* 1-D and 0-D physical groups -> node sets */
    node_cells nc = {NULL, NULL};
    int32_t *next_of = NULL;
    if (m->n_line && !rc) {
        rc = node_cells_build(g, &nc);
        next_of = malloc((g->n_nodes + 1) * sizeof *next_of);
        if (!rc && !next_of)
            rc = pm_error_set(PM_ENOMEM, "out of memory");
        for (size_t n = 0; !rc && n < g->n_nodes; n++)
            next_of[n] = -1;
    }
    for (int dim = 1; dim >= 0 && !rc; dim--) {
        /* every distinct (dim, physical tag) */
        for (size_t ie = 0; ie < m->n_ent && !rc; ie++) {
            const pm_msh_entity *en = &m->ent[ie];
            if (en->dim != dim)
                continue;
            for (int q = 0; q < en->n_phys && !rc; q++) {
                const int ptag = en->phys[q];
                /* handle each physical group once: at its first entity */
                int seen = 0;
                for (size_t je = 0; je < ie && !seen; je++)
                    if (m->ent[je].dim == dim)
                        for (int k = 0; k < m->ent[je].n_phys; k++)
                            seen |= m->ent[je].phys[k] == ptag;
                if (seen)
                    continue;
                const size_t ne = dim == 1 ? m->n_line : m->n_pt;
                const long *vv = dim == 1 ? m->line : m->pt;
                const int *ents = dim == 1 ? m->line_ent : m->pt_ent;
                const int npe = dim == 1 ? 2 : 1;
                int32_t *nodes = malloc((ne * (size_t)npe + 1) * sizeof(int32_t));
                int32_t *pairs = malloc((ne * (size_t)npe + 1) * sizeof(int32_t));
                if (!nodes || !pairs) {
                    free(nodes), free(pairs);
                    rc = pm_error_set(PM_ENOMEM, "out of memory");
                    break;
                }
                size_t cnt = 0, npairs = 0;
                int32_t ea = -1, eb = -1;
                for (size_t e = 0; e < ne; e++) {
                    const pm_msh_entity *ee = find_entity(m, dim, ents[e]);
                    int in = 0;
                    for (int k = 0; ee && k < ee->n_phys; k++)
                        in |= ee->phys[k] == ptag;
                    if (!in)
                        continue;
                    int ok = 1;
                    int32_t loc[2] = {-1, -1};
                    for (int k = 0; k < npe; k++) {
                        long u = used[m->tag_index[vv[(size_t)npe * e + k]]];
                        if (u < 0)
                            ok = 0; /* a node no cell uses */
                        else
                            nodes[cnt++] = loc[k] = (int32_t)u;
                    }
                    if (dim == 1 && ok && ea < 0) {
                        ea = loc[0];
                        eb = loc[1];
                    }
                    if (dim == 1 && ok && loc[0] != loc[1]) {
                        pairs[2 * npairs] = loc[0];
                        pairs[2 * npairs + 1] = loc[1];
                        npairs++;
                    }
                }
                qsort(nodes, cnt, sizeof(int32_t), pm_mesh_cmp_i32);
                size_t u = 0;
                for (size_t i = 0; i < cnt; i++)
                    if (u == 0 || nodes[i] != nodes[u - 1])
                        nodes[u++] = nodes[i];
                double nrm[PM_DIM] = {0, 0};
                if (dim == 1 && ea >= 0)
                    line_normal(g, nodes, u, ea, eb, nrm);
                char name[64];
                phys_label(m, dim, ptag, name);
                int k = pm_grid_add_node_set(g, name, u, nodes, nrm);
                free(nodes);
                if (k < 0)
                    rc = k;
                const int on_boundary = k >= 0 && npairs ? orient_edges(g, &nc, pairs, npairs, next_of) : 0;
                if (on_boundary < 0)
                    rc = pm_error_set(PM_ENOMEM, "out of memory");
                if (on_boundary > 0) {
                    g->sets[k].edges = pairs;
                    g->sets[k].n_edges = npairs;
                    pairs = NULL;
                }
                free(pairs);
            }
        }
    }
    free(nc.start);
    free(nc.cell);
    free(next_of);
    if (rc)
        pm_grid_free(g);
done:
    free(conn);
    free(used);
    free(xy);
    free(cell_of);
    return rc;
}

int pm_grid_gmsh_read(pm_grid *g, const char *path)
{
    memset(g, 0, sizeof *g);
    pm_msh m;
    int rc = pm_msh_parse(path, &m);
    if (!rc)
        rc = pm_msh_check_elements(&m, path);
    if (!rc)
        rc = build(g, &m, path);
    pm_msh_free(&m);
    return rc;
}
