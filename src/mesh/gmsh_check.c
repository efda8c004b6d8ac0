/*
 * Checks of a Gmsh mesh's 2-D elements before they become a grid. A mesh that lists an element twice,
 * folds over itself or has a flat element still builds a grid, and a run on it ends with exit 0 and a
 * wrong answer (twice the mass of the doubled elements, particles seeded in both layers); so such meshes
 * are refused here, naming the elements by their tags in the file.
 *
 * Overlap test: with every element turned counter-clockwise, the two elements that share an inner edge
 * walk it in opposite directions; two elements that walk it the same way lie on the same side of it,
 * i.e. overlap. A mesh copied onto itself with new node tags shares no edge with the original: it shows
 * as two nodes at one point.
 */
#include "mesh/gmsh_internal.h"

#include "pmech/error.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct edge {
    long lo, hi;   /* node tags, lo < hi */
    size_t elem;   /* 2-D element index: triangles first, then quads */
    int forward;   /* 1 when the counter-clockwise element walks lo -> hi */
} edge;

static int cmp_edge(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    if (x->lo != y->lo)
        return x->lo < y->lo ? -1 : 1;
    if (x->hi != y->hi)
        return x->hi < y->hi ? -1 : 1;
    return x->elem < y->elem ? -1 : x->elem > y->elem;
}

typedef struct node_at {
    double x, y;
    long tag;
} node_at;

static int cmp_node(const void *a, const void *b)
{
    const node_at *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    if (p->y != q->y)
        return p->y < q->y ? -1 : 1;
    return (p->tag > q->tag) - (p->tag < q->tag);
}

typedef struct elem_view {
    const pm_msh *m;
    size_t n_tri;
} elem_view;

static int elem_nodes(const elem_view *v, size_t e, const long **nodes)
{
    if (e < v->n_tri) {
        *nodes = v->m->tri + 3 * e;
        return 3;
    }
    *nodes = v->m->quad + 4 * (e - v->n_tri);
    return 4;
}

static long elem_tag(const elem_view *v, size_t e)
{
    return e < v->n_tri ? v->m->tri_tag[e] : v->m->quad_tag[e - v->n_tri];
}

static const double *node_xy(const pm_msh *m, long tag)
{
    return m->xy + PM_DIM * m->tag_index[tag];
}

/* Twice the signed area of the element and whether every corner turns the same way. */
static double elem_area2(const pm_msh *m, const long *nd, int n, int *convex)
{
    double a2 = 0;
    int pos = 0, neg = 0;
    for (int k = 0; k < n; k++) {
        const double *p = node_xy(m, nd[k]), *q = node_xy(m, nd[(k + 1) % n]), *r = node_xy(m, nd[(k + 2) % n]);
        a2 += p[0] * q[1] - q[0] * p[1];
        const double turn = (q[0] - p[0]) * (r[1] - q[1]) - (q[1] - p[1]) * (r[0] - q[0]);
        pos += turn > 0;
        neg += turn < 0;
    }
    *convex = !(pos && neg);
    return a2;
}

/* Size squared of the element's bounding box: the scale below which an area counts as zero. */
static double elem_scale2(const pm_msh *m, const long *nd, int n)
{
    double lo[PM_DIM], hi[PM_DIM];
    for (int d = 0; d < PM_DIM; d++) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
    }
    for (int k = 0; k < n; k++)
        for (int d = 0; d < PM_DIM; d++) {
            lo[d] = fmin(lo[d], node_xy(m, nd[k])[d]);
            hi[d] = fmax(hi[d], node_xy(m, nd[k])[d]);
        }
    double s2 = 0;
    for (int d = 0; d < PM_DIM; d++)
        s2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
    return s2;
}

static int same_nodes(const long *a, int na, const long *b, int nb)
{
    if (na != nb)
        return 0;
    for (int i = 0; i < na; i++) {
        int found = 0;
        for (int j = 0; j < nb; j++)
            found |= a[i] == b[j];
        if (!found)
            return 0;
    }
    return 1;
}

static int check_shapes(const elem_view *v, const char *path, size_t n2d, int *ccw)
{
    for (size_t e = 0; e < n2d; e++) {
        const long *nd;
        const int n = elem_nodes(v, e, &nd);
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++)
                if (nd[i] == nd[j])
                    return pm_error_set(PM_EINPUT, "%s: element %ld lists node %ld twice", path, elem_tag(v, e),
                                        nd[i]);
        int convex;
        const double a2 = elem_area2(v->m, nd, n, &convex);
        if (!(fabs(a2) > 1e-12 * elem_scale2(v->m, nd, n)))
            return pm_error_set(PM_EINPUT, "%s: element %ld is degenerate: its area is %g", path, elem_tag(v, e),
                                a2 / 2);
        if (!convex)
            return pm_error_set(PM_EINPUT,
                                "%s: element %ld (a quad) is inverted or not convex: its corners turn both ways",
                                path, elem_tag(v, e));
        ccw[e] = a2 > 0;
    }
    return PM_OK;
}

static int check_edges(const elem_view *v, const char *path, size_t n2d, const int *ccw, edge *ed)
{
    size_t ne = 0;
    for (size_t e = 0; e < n2d; e++) {
        const long *nd;
        const int n = elem_nodes(v, e, &nd);
        for (int k = 0; k < n; k++) {
            long a = nd[k], b = nd[(k + 1) % n];
            if (!ccw[e]) {
                const long t = a;
                a = b;
                b = t;
            }
            ed[ne++] = (edge){a < b ? a : b, a < b ? b : a, e, a < b};
        }
    }
    qsort(ed, ne, sizeof *ed, cmp_edge);
    for (size_t i = 0; i + 1 < ne; i++) {
        const edge *x = &ed[i], *y = &ed[i + 1];
        if (x->lo != y->lo || x->hi != y->hi)
            continue;
        const long *na, *nb;
        const int ka = elem_nodes(v, x->elem, &na), kb = elem_nodes(v, y->elem, &nb);
        if (same_nodes(na, ka, nb, kb))
            return pm_error_set(PM_EINPUT, "%s: elements %ld and %ld have the same nodes: the mesh lists one element "
                                "twice", path, elem_tag(v, x->elem), elem_tag(v, y->elem));
        if (x->forward == y->forward || (i + 2 < ne && ed[i + 2].lo == x->lo && ed[i + 2].hi == x->hi))
            return pm_error_set(PM_EINPUT, "%s: elements %ld and %ld overlap: both lie on the same side of the edge "
                                "between nodes %ld and %ld", path, elem_tag(v, x->elem), elem_tag(v, y->elem),
                                x->lo, x->hi);
    }
    return PM_OK;
}

static int check_coincident_nodes(const elem_view *v, const char *path, size_t n2d, node_at *na, edge *ed)
{
    /* both ends of every edge: each node an element uses, a few times over */
    size_t n = 0, ne = 0;
    for (size_t e = 0; e < n2d; e++) {
        const long *nd;
        ne += (size_t)elem_nodes(v, e, &nd);
    }
    for (size_t i = 0; i < ne; i++) {
        const long tags[2] = {ed[i].lo, ed[i].hi};
        for (int k = 0; k < 2; k++) {
            const double *p = node_xy(v->m, tags[k]);
            na[n++] = (node_at){p[0], p[1], tags[k]};
        }
    }
    qsort(na, n, sizeof *na, cmp_node);
    /* Two nodes of line elements may share a point: the two faces of a slit meet there (a tool's tip,
     * seed 004 §5.3.2, where material ahead of the tip parts along a cut), each node on its own side. A
     * mesh copied onto itself still shows at its inner nodes, which no line element has. */
    uint8_t *on_line = calloc((size_t)v->m->max_tag + 1, 1);
    if (!on_line)
        return pm_error_set(PM_ENOMEM, "out of memory checking %s", path);
    for (size_t i = 0; i < 2 * v->m->n_line; i++)
        on_line[v->m->line[i]] = 1;
    int rc = PM_OK;
    for (size_t i = 0; i + 1 < n && !rc; i++)
        if (na[i].x == na[i + 1].x && na[i].y == na[i + 1].y && na[i].tag != na[i + 1].tag &&
            !(on_line[na[i].tag] && on_line[na[i + 1].tag]))
            rc = pm_error_set(PM_EINPUT, "%s: nodes %ld and %ld are both at (%g, %g): the mesh overlaps itself or "
                              "is not connected there (only nodes of line elements, the two sides of a slit, may "
                              "share a point)", path, na[i].tag, na[i + 1].tag, na[i].x, na[i].y);
    free(on_line);
    return rc;
}

int pm_msh_check_elements(const pm_msh *m, const char *path)
{
    const size_t n2d = m->n_tri + m->n_quad;
    if (n2d == 0)
        return PM_OK;
    const elem_view v = {m, m->n_tri};
    const size_t n_edges = 3 * m->n_tri + 4 * m->n_quad;
    int *ccw = malloc(n2d * sizeof *ccw);
    edge *ed = malloc(n_edges * sizeof *ed);
    node_at *na = malloc(2 * n_edges * sizeof *na);
    int rc = ccw && ed && na ? PM_OK : pm_error_set(PM_ENOMEM, "%s: out of memory checking %zu elements", path, n2d);
    if (!rc)
        rc = check_shapes(&v, path, n2d, ccw);
    if (!rc)
        rc = check_edges(&v, path, n2d, ccw, ed);
    if (!rc)
        rc = check_coincident_nodes(&v, path, n2d, na, ed);
    free(ccw);
    free(ed);
    free(na);
    return rc;
}
