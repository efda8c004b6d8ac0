/*
 * Node cloud and uniform cell list for the meshfree approximations (GMM, RKPM).
 *
 * Nodes are binned by their positions at the last build (x_built). A node whose current position
 * is within r of the query point x was binned at most r + skin from x as long as it moved at most
 * skin since the build, so a query visits the cells that meet the disc of radius r + skin and tests
 * the positions of the last update (x_sorted: a copy in bin order, so that a row of cells is read
 * front to back). Bins are clamped to the border cells, which keeps nodes that left the box of the
 * last build findable (clamping is monotone, so a node's clamped cell is inside the clamped range
 * of any interval that contains its binned position).
 */
#include "shape/cloud.h"
#include "pmech/error.h"

#include "shape_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CLOUD_DEFAULT_CELL 2.5  /* x h */
#define CLOUD_DEFAULT_SKIN 0.25 /* x h */
/* A scattered cloud (a few nodes far away) would ask for a huge, nearly empty cell array: above
 * this many cells per node the cell side is enlarged instead. */
#define CLOUD_MAX_CELLS_PER_NODE 4
#define CLOUD_MAX_GROWTH_STEPS 200

static int cell_coord(const pm_cloud *c, double v, int k)
{
    double b = floor((v - c->lo[k]) / c->cell);
    if (!(b > 0)) /* also catches NaN */
        return 0;
    if (b > c->nc[k] - 1)
        return c->nc[k] - 1;
    return (int)b;
}

int pm_cloud_rebuild(pm_cloud *c)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < c->n; i++)
        for (int k = 0; k < 2; k++) {
            const double v = c->x[2 * i + k];
            if (!isfinite(v))
                return pm_error_set(PM_EINPUT, "cloud: node %zu has a non-finite position", i);
            lo[k] = fmin(lo[k], v);
            hi[k] = fmax(hi[k], v);
        }
    double cell = c->cell;
    size_t limit = CLOUD_MAX_CELLS_PER_NODE * c->n + 64;
    for (;;) {
        double n0 = floor((hi[0] - lo[0]) / cell) + 1, n1 = floor((hi[1] - lo[1]) / cell) + 1;
        if (n0 * n1 <= (double)limit) {
            c->nc[0] = (int)n0;
            c->nc[1] = (int)n1;
            break;
        }
        cell *= 1.5;
    }
    c->cell = cell;
    c->lo[0] = lo[0];
    c->lo[1] = lo[1];
    const size_t ncell = (size_t)c->nc[0] * (size_t)c->nc[1];
    if (ncell + 1 > c->cap_cells) {
        int32_t *s = realloc(c->start, (ncell + 1) * sizeof *s);
        if (!s)
            return pm_error_set(PM_ENOMEM, "cloud: out of memory for %zu cells", ncell);
        c->start = s;
        c->cap_cells = ncell + 1;
    }
    memset(c->start, 0, (ncell + 1) * sizeof *c->start);
    memcpy(c->x_built, c->x, 2 * c->n * sizeof *c->x);
    /* counting sort by cell */
    for (size_t i = 0; i < c->n; i++) {
        const int32_t b = cell_coord(c, c->x[2 * i + 1], 1) * c->nc[0] + cell_coord(c, c->x[2 * i], 0);
        c->start[b + 1]++;
    }
    for (size_t b = 0; b < ncell; b++)
        c->start[b + 1] += c->start[b];
    /* place the nodes advancing start[b] to the end of bin b, then shift it back by one bin: no
     * second offset array */
    int32_t *fill = c->start;
    for (size_t i = 0; i < c->n; i++) {
        const int32_t b = cell_coord(c, c->x[2 * i + 1], 1) * c->nc[0] + cell_coord(c, c->x[2 * i], 0);
        c->order[fill[b]++] = (int32_t)i;
    }
    for (size_t b = ncell; b > 0; b--)
        c->start[b] = c->start[b - 1];
    c->start[0] = 0;
    for (size_t k = 0; k < c->n; k++) {
        c->x_sorted[2 * k] = c->x[2 * (size_t)c->order[k]];
        c->x_sorted[2 * k + 1] = c->x[2 * (size_t)c->order[k] + 1];
    }
    c->n_builds++;
    c->last_move = 0;
    return PM_OK;
}

int pm_cloud_create(size_t n, const double *x, const double *vol, const pm_cloud_opts *opts, pm_cloud **out)
{
    *out = NULL;
    if (n == 0 || n > INT32_MAX)
        return pm_error_set(PM_EINPUT, "cloud: %zu nodes (need 1 to %d)", n, INT32_MAX);
    pm_cloud *c = calloc(1, sizeof *c);
    if (!c)
        return pm_error_set(PM_ENOMEM, "out of memory");
    c->n = n;
    c->x = malloc(2 * n * sizeof *c->x);
    c->x_built = malloc(2 * n * sizeof *c->x_built);
    c->vol = malloc(n * sizeof *c->vol);
    c->order = malloc(n * sizeof *c->order);
    c->x_sorted = malloc(2 * n * sizeof *c->x_sorted);
    if (!c->x || !c->x_built || !c->vol || !c->order || !c->x_sorted) {
        pm_cloud_destroy(c);
        return pm_error_set(PM_ENOMEM, "cloud: out of memory for %zu nodes", n);
    }
    memcpy(c->x, x, 2 * n * sizeof *x);
    double vsum = 0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++) {
        c->vol[i] = vol ? vol[i] : 1.0;
        if (!(c->vol[i] >= 0) || !isfinite(c->vol[i])) {
            pm_cloud_destroy(c);
            return pm_error_set(PM_EINPUT, "cloud: node %zu has volume %g", i, vol ? vol[i] : 1.0);
        }
        vsum += c->vol[i];
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], x[2 * i + k]);
            hi[k] = fmax(hi[k], x[2 * i + k]);
        }
    }
    const pm_cloud_opts o = opts ? *opts : (pm_cloud_opts){NAN, NAN, NAN};
    if (o.h > 0)
        c->h = o.h;
    else if (vol && vsum > 0)
        c->h = sqrt(vsum / (double)n);
    else
        c->h = sqrt((hi[0] - lo[0]) * (hi[1] - lo[1]) / (double)n);
    if (!(c->h > 0) || !isfinite(c->h)) /* one node, or all on a line: fall back to the box size */
        c->h = fmax(fmax(hi[0] - lo[0], hi[1] - lo[1]), 1.0) / sqrt((double)n);
    c->cell = o.cell_size > 0 ? o.cell_size : CLOUD_DEFAULT_CELL * c->h;
    c->skin = o.skin > 0 ? o.skin : CLOUD_DEFAULT_SKIN * c->h;
    if (!isfinite(c->cell) || !isfinite(c->skin)) {
        pm_cloud_destroy(c);
        return pm_error_set(PM_EINPUT, "cloud: non-finite cell size or skin");
    }
    int rc = pm_cloud_rebuild(c);
    if (rc) {
        pm_cloud_destroy(c);
        return rc;
    }
    *out = c;
    return PM_OK;
}

void pm_cloud_destroy(pm_cloud *c)
{
    if (!c)
        return;
    free(c->x);
    free(c->x_built);
    free(c->vol);
    free(c->order);
    free(c->x_sorted);
    free(c->start);
    free(c);
}

int pm_cloud_update(pm_cloud *c, int *rebuilt)
{
    double m2 = 0;
    int bad = 0;
    /* in cell order, so that the positions the queries scan are refreshed in the same pass */
    for (size_t k = 0; k < c->n; k++) {
        const size_t i = 2 * (size_t)c->order[k];
        const double x0 = c->x[i], x1 = c->x[i + 1];
        const double dx = x0 - c->x_built[i], dy = x1 - c->x_built[i + 1];
        const double d2 = dx * dx + dy * dy;
        m2 = d2 > m2 ? d2 : m2;
        bad |= !(d2 < INFINITY);
        c->x_sorted[2 * k] = x0;
        c->x_sorted[2 * k + 1] = x1;
    }
    c->last_move = bad ? NAN : sqrt(m2);
    /* a non-finite position must go to the rebuild too, which reports the node */
    const int need = bad || c->last_move > c->skin;
    if (rebuilt)
        *rebuilt = need;
    return need ? pm_cloud_rebuild(c) : PM_OK;
}

int pm_cloud_restore(pm_cloud *c, const double *x, const double *x_built, double cell, size_t n_builds)
{
    if (!(cell > 0) || !isfinite(cell))
        return pm_error_set(PM_EINPUT, "cloud: cell side %g", cell);
    /* the cell side of that build already fitted its positions: pm_cloud_rebuild() keeps it, so lo,
     * nc and the order come out as they were */
    c->cell = cell;
    memcpy(c->x, x_built, PM_DIM * c->n * sizeof *c->x);
    pm_check(pm_cloud_rebuild(c));
    memcpy(c->x, x, PM_DIM * c->n * sizeof *c->x);
    int rebuilt = 0;
    pm_check(pm_cloud_update(c, &rebuilt));
    c->n_builds = n_builds;
    if (rebuilt)
        return pm_error_set(PM_EINPUT, "cloud: a node moved farther than the skin %g since the stored build",
                            c->skin);
    return PM_OK;
}

/* cell_coord() with a multiplication by 1 / cell instead of a division (see scan()) */
static inline int cell_coord_mul(const pm_cloud *c, double v, int k, double inv)
{
    const double b = (v - c->lo[k]) * inv;
    if (!(b > 0))
        return 0;
    return b < c->nc[k] ? (int)b : c->nc[k] - 1;
}

/*
 * The scan shared by pm_cloud_query() and pm_cloud_gather(). Only the cells that meet the disc of
 * radius r + skin are visited: per row of cells, the x range is the disc's chord at the row's
 * nearest edge (the border rows reach to infinity, as the clamped bins do); with 2.5 h cells this
 * drops a tenth of the candidates of the full square. Row ranges use a multiplication where the
 * binning divides, and row edges are recomputed: either can round a few ulp of the coordinates
 * away from the binning, so the disc is widened by a margin far above that (1e-9 of the box).
 * Candidates are appended without a branch on the distance test (true for about a third of them,
 * so a branch would mispredict often) whenever the row cannot overflow cap; d (x - x_I) and d2
 * are optional.
 */
static inline int scan(const pm_cloud *c, const double x[2], double r, int cap, int32_t *restrict idx,
                       double (*restrict d)[2], double *restrict d2)
{
    const double box = c->cell * (1.0 + c->nc[0] + c->nc[1]) + fabs(c->lo[0]) + fabs(c->lo[1]);
    const double slack = 1e-9 * box, rr = r + c->skin + slack, r2 = r * r, x0 = x[0], x1 = x[1];
    const double inv = 1.0 / c->cell;
    const int iy0 = cell_coord_mul(c, x1 - rr, 1, inv), iy1 = cell_coord_mul(c, x1 + rr, 1, inv);
    const double *restrict xs = c->x_sorted;
    const int32_t *restrict order = c->order;
    int n = 0;
    for (int iy = iy0; iy <= iy1; iy++) {
        const double ylo = iy == 0 ? -INFINITY : c->lo[1] + iy * c->cell;
        const double yhi = iy == c->nc[1] - 1 ? INFINITY : c->lo[1] + (iy + 1) * c->cell;
        double dy = x1 < ylo ? ylo - x1 : x1 > yhi ? x1 - yhi : 0.0;
        dy = dy > slack ? dy - slack : 0.0;
        const double w = dy < rr ? sqrt(rr * rr - dy * dy) : 0.0;
        const int ix0 = cell_coord_mul(c, x0 - w, 0, inv), ix1 = cell_coord_mul(c, x0 + w, 0, inv);
        const int32_t *st = c->start + (size_t)iy * c->nc[0];
        const int32_t k0 = st[ix0], k1 = st[ix1 + 1]; /* cells of one row are contiguous */
        if (n + (k1 - k0) <= cap) {
            for (int32_t k = k0; k < k1; k++) {
                const int32_t j = order[k];
                const double dx = x0 - xs[2 * k], dyj = x1 - xs[2 * k + 1];
                const double q = dx * dx + dyj * dyj;
                idx[n] = j;
                if (d) {
                    d[n][0] = dx;
                    d[n][1] = dyj;
                }
                if (d2)
                    d2[n] = q;
                n += q < r2;
            }
        } else {
            for (int32_t k = k0; k < k1; k++) {
                const int32_t j = order[k];
                const double dx = x0 - xs[2 * k], dyj = x1 - xs[2 * k + 1];
                const double q = dx * dx + dyj * dyj;
                if (!(q < r2))
                    continue;
                if (n < cap) {
                    idx[n] = j;
                    if (d) {
                        d[n][0] = dx;
                        d[n][1] = dyj;
                    }
                    if (d2)
                        d2[n] = q;
                }
                n++;
            }
        }
    }
    return n;
}

int pm_cloud_query(const pm_cloud *c, const double x[2], double r, int cap, int32_t *idx, double *d2,
                   int *n_found)
{
    *n_found = 0;
    if (!isfinite(x[0]) || !isfinite(x[1]) || !(r >= 0) || !isfinite(r))
        return pm_error_set(PM_EINPUT, "cloud: query at (%g, %g) with radius %g", x[0], x[1], r);
    *n_found = d2 ? scan(c, x, r, cap, idx, NULL, d2) : scan(c, x, r, cap, idx, NULL, NULL);
    return PM_OK;
}

int pm_cloud_gather(const pm_cloud *c, const double x[2], double r, int cap, int32_t *idx, double (*d)[2],
                    double *d2)
{
    return scan(c, x, r, cap, idx, d, d2);
}

int pm_cloud_query_adaptive(const pm_cloud *c, const double x[2], double r0, int min_count, double growth,
                            int cap, int32_t *idx, double *d2, int *n_found, double *r_used)
{
    *n_found = 0;
    *r_used = r0;
    if (!(r0 > 0) || !(growth > 1) || min_count < 1 || cap < min_count)
        return pm_error_set(PM_EINPUT, "cloud: adaptive search with r0 %g, growth %g, min %d, capacity %d", r0,
                            growth, min_count, cap);
    if ((size_t)min_count > c->n)
        return pm_error_set(PM_ESIM, "cloud: %d nodes wanted around (%g, %g) but the cloud has %zu", min_count,
                            x[0], x[1], c->n);
    double r = r0;
    for (int step = 0; step < CLOUD_MAX_GROWTH_STEPS; step++, r *= growth) {
        int n;
        pm_check(pm_cloud_query(c, x, r, cap, idx, d2, &n));
        *n_found = n;
        *r_used = r;
        if (n > cap)
            return pm_error_set(PM_ESIM,
                                "cloud: around (%g, %g) the count jumped to %d (> %d) at radius %g before "
                                "reaching %d nodes",
                                x[0], x[1], n, cap, r, min_count);
        if (n >= min_count)
            return PM_OK;
    }
    return pm_error_set(PM_ESIM, "cloud: fewer than %d nodes within %g of (%g, %g)", min_count, r, x[0], x[1]);
}

void pm_cloud_sort_by_distance(int n, int32_t *idx, double *d2)
{
    for (int i = 1; i < n; i++) {
        const int32_t ki = idx[i];
        const double di = d2[i];
        int j = i - 1;
        while (j >= 0 && (d2[j] > di || (d2[j] == di && idx[j] > ki))) {
            idx[j + 1] = idx[j];
            d2[j + 1] = d2[j];
            j--;
        }
        idx[j + 1] = ki;
        d2[j + 1] = di;
    }
}
