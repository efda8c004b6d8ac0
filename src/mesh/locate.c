/*
 * Point location on unstructured grids: uniform bins over the bounding box, each listing the cells
 * whose bounding boxes overlap it (bin side about the mean cell size, so a bin lists a handful of
 * cells), plus the edge neighbours of every cell for a short walk from a hint cell (a particle
 * moves little in a step, so its previous cell or a neighbour usually contains it).
 *
 * The inside test takes edges as inside with a tolerance of 1e-12 of the cell's squared size, so a
 * point on an edge shared by two cells may be given to either; a point outside every cell gives -1.
 */
#include "pmech/error.h"

#include "mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define WALK_STEPS 8

typedef struct locator {
    double lo[2], inv_bin[2];
    int nb[2];
    int32_t *start;  /* nb[0]*nb[1] + 1 */
    int32_t *cells;  /* cells listed by bin */
    int32_t *nbr;    /* nodes_per_cell per cell: neighbour across edge k (k -> k+1), -1 at the boundary */
    double *tol;     /* per cell: inside tolerance (1e-12 * squared diameter) */
} locator;

void pm_grid_locator_free(void *loc)
{
    locator *L = loc;
    if (!L)
        return;
    free(L->start);
    free(L->cells);
    free(L->nbr);
    free(L->tol);
    free(L);
}

/* Signed area of (a, b, p) times two. */
static inline double orient(const double *a, const double *b, const double *p)
{
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

static inline int contains_tol(const pm_grid *g, int32_t c, const double xp[2], double tol)
{
    const int npc = g->nodes_per_cell;
    const int32_t *v = g->conn + (size_t)npc * c;
    for (int k = 0; k < npc; k++)
        if (orient(g->x + 2 * v[k], g->x + 2 * v[(k + 1) % npc], xp) < -tol)
            return 0;
    return 1;
}

int pm_grid_cell_contains(const pm_grid *g, int32_t c, const double xp[2])
{
    const locator *L = g->locator;
    return contains_tol(g, c, xp, L ? L->tol[c] : 0.0);
}

typedef struct edge_rec {
    int32_t a, b, cell, k;
} edge_rec;

static int edge_cmp(const void *x, const void *y)
{
    const edge_rec *e = x, *f = y;
    if (e->a != f->a)
        return e->a < f->a ? -1 : 1;
    if (e->b != f->b)
        return e->b < f->b ? -1 : 1;
    return (e->cell > f->cell) - (e->cell < f->cell);
}

static void cell_box(const pm_grid *g, size_t c, double lo[2], double hi[2])
{
    const int npc = g->nodes_per_cell;
    const int32_t *v = g->conn + (size_t)npc * c;
    lo[0] = hi[0] = g->x[2 * v[0]];
    lo[1] = hi[1] = g->x[2 * v[0] + 1];
    for (int k = 1; k < npc; k++)
        for (int d = 0; d < 2; d++) {
            lo[d] = fmin(lo[d], g->x[2 * v[k] + d]);
            hi[d] = fmax(hi[d], g->x[2 * v[k] + d]);
        }
}

static void bin_range(const locator *L, const double lo[2], const double hi[2], int b0[2], int b1[2])
{
    for (int d = 0; d < 2; d++) {
        double f0 = (lo[d] - L->lo[d]) * L->inv_bin[d], f1 = (hi[d] - L->lo[d]) * L->inv_bin[d];
        int i0 = (int)floor(f0), i1 = (int)floor(f1);
        b0[d] = i0 < 0 ? 0 : (i0 >= L->nb[d] ? L->nb[d] - 1 : i0);
        b1[d] = i1 < 0 ? 0 : (i1 >= L->nb[d] ? L->nb[d] - 1 : i1);
    }
}

int pm_grid_locator_build(pm_grid *g)
{
    pm_grid_locator_free(g->locator);
    g->locator = NULL;
    locator *L = calloc(1, sizeof *L);
    if (!L)
        return pm_error_set(PM_ENOMEM, "out of memory for the point locator");
    g->locator = L;
    const size_t nc = g->n_cells;
    const int npc = g->nodes_per_cell;
    /* bins of about the mean cell size, at most ~2 bins per cell */
    double W = g->hi[0] - g->lo[0], H = g->hi[1] - g->lo[1];
    double area = fmax(W * H, 1e-300);
    double side = sqrt(area / (double)(nc ? nc : 1));
    for (int d = 0; d < 2; d++) {
        double ext = d ? H : W;
        double nb = ceil(ext / side);
        if (nb < 1)
            nb = 1;
        if (nb > 4096)
            nb = 4096;
        L->nb[d] = (int)nb;
        L->lo[d] = d ? g->lo[1] : g->lo[0];
        L->inv_bin[d] = ext > 0 ? L->nb[d] / ext : 0.0;
    }
    const size_t nbins = (size_t)L->nb[0] * (size_t)L->nb[1];
    L->start = calloc(nbins + 1, sizeof(int32_t));
    L->tol = malloc((nc ? nc : 1) * sizeof(double));
    L->nbr = malloc((nc ? nc : 1) * (size_t)npc * sizeof(int32_t));
    if (!L->start || !L->tol || !L->nbr)
        return pm_error_set(PM_ENOMEM, "out of memory for the point locator");
    size_t total = 0;
    for (size_t c = 0; c < nc; c++) {
        double lo[2], hi[2];
        int b0[2], b1[2];
        cell_box(g, c, lo, hi);
        double diam2 = (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]);
        L->tol[c] = 1e-12 * diam2;
        bin_range(L, lo, hi, b0, b1);
        for (int j = b0[1]; j <= b1[1]; j++)
            for (int i = b0[0]; i <= b1[0]; i++)
                L->start[(size_t)j * L->nb[0] + i + 1]++;
        total += (size_t)(b1[0] - b0[0] + 1) * (size_t)(b1[1] - b0[1] + 1);
    }
    if (total > INT32_MAX)
        return pm_error_set(PM_ENOMEM, "point locator too large");
    for (size_t b = 0; b < nbins; b++)
        L->start[b + 1] += L->start[b];
    L->cells = malloc((total ? total : 1) * sizeof(int32_t));
    int32_t *fill = malloc(nbins * sizeof(int32_t));
    if (!L->cells || !fill) {
        free(fill);
        return pm_error_set(PM_ENOMEM, "out of memory for the point locator");
    }
    memcpy(fill, L->start, nbins * sizeof(int32_t));
    for (size_t c = 0; c < nc; c++) {
        double lo[2], hi[2];
        int b0[2], b1[2];
        cell_box(g, c, lo, hi);
        bin_range(L, lo, hi, b0, b1);
        for (int j = b0[1]; j <= b1[1]; j++)
            for (int i = b0[0]; i <= b1[0]; i++)
                L->cells[fill[(size_t)j * L->nb[0] + i]++] = (int32_t)c;
    }
    free(fill);
    /* edge neighbours: sort the edges by their vertex pair, matching pairs are neighbours */
    const size_t ne = nc * (size_t)npc;
    edge_rec *e = malloc((ne ? ne : 1) * sizeof *e);
    if (!e)
        return pm_error_set(PM_ENOMEM, "out of memory for the point locator");
    for (size_t c = 0; c < nc; c++)
        for (int k = 0; k < npc; k++) {
            int32_t a = g->conn[(size_t)npc * c + k], b = g->conn[(size_t)npc * c + (k + 1) % npc];
            edge_rec *r = &e[(size_t)npc * c + k];
            r->a = a < b ? a : b;
            r->b = a < b ? b : a;
            r->cell = (int32_t)c;
            r->k = k;
        }
    qsort(e, ne, sizeof *e, edge_cmp);
    for (size_t i = 0; i < ne; i++)
        L->nbr[(size_t)npc * e[i].cell + e[i].k] = -1;
    for (size_t i = 0; i + 1 < ne; i++)
        if (e[i].a == e[i + 1].a && e[i].b == e[i + 1].b) {
            L->nbr[(size_t)npc * e[i].cell + e[i].k] = e[i + 1].cell;
            L->nbr[(size_t)npc * e[i + 1].cell + e[i + 1].k] = e[i].cell;
            i++;
        }
    free(e);
    return PM_OK;
}

int32_t pm_grid_locator_find(const pm_grid *g, const double xp[2], int32_t hint)
{
    const locator *L = g->locator;
    if (!(xp[0] >= g->lo[0] && xp[0] <= g->hi[0] && xp[1] >= g->lo[1] && xp[1] <= g->hi[1])) {
        /* the tolerance may admit points a hair outside the box; check the bins' edge cells */
        double tx = 1e-9 * (g->hi[0] - g->lo[0]), ty = 1e-9 * (g->hi[1] - g->lo[1]);
        if (!(xp[0] >= g->lo[0] - tx && xp[0] <= g->hi[0] + tx && xp[1] >= g->lo[1] - ty && xp[1] <= g->hi[1] + ty))
            return -1; /* also rejects NaN */
    }
    const int npc = g->nodes_per_cell;
    /* walk from the hint: cross the edge the point lies furthest outside of */
    if (hint >= 0 && (size_t)hint < g->n_cells) {
        int32_t c = hint;
        for (int step = 0; step < WALK_STEPS && c >= 0; step++) {
            const int32_t *v = g->conn + (size_t)npc * c;
            int worst = -1;
            double wv = -L->tol[c];
            for (int k = 0; k < npc; k++) {
                const double *a = g->x + 2 * v[k], *b = g->x + 2 * v[(k + 1) % npc];
                double o = orient(a, b, xp);
                if (o < wv) {
                    wv = o;
                    worst = k;
                }
            }
            if (worst < 0)
                return c;
            c = L->nbr[(size_t)npc * c + worst];
        }
    }
    int bx = (int)((xp[0] - L->lo[0]) * L->inv_bin[0]), by = (int)((xp[1] - L->lo[1]) * L->inv_bin[1]);
    bx = bx < 0 ? 0 : (bx >= L->nb[0] ? L->nb[0] - 1 : bx);
    by = by < 0 ? 0 : (by >= L->nb[1] ? L->nb[1] - 1 : by);
    const size_t b = (size_t)by * L->nb[0] + bx;
    for (int32_t k = L->start[b]; k < L->start[b + 1]; k++) {
        int32_t c = L->cells[k];
        if (contains_tol(g, c, xp, L->tol[c]))
            return c;
    }
    return -1;
}
