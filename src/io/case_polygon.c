/*
 * A polygon shape must enclose an area and must not cross itself: the seeding's point-in-polygon test
 * still answers for a figure that does (even-odd rule), so a crossed or flat outline used to become a
 * body of another shape, or of one particle, without a word.
 */
#include "io/case_internal.h"

#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>

typedef struct seg {
    double lo_x, hi_x;
    size_t k; /* from point k to point k + 1 (mod n) */
} seg;

static int cmp_seg(const void *a, const void *b)
{
    const seg *s = a, *t = b;
    return (s->lo_x > t->lo_x) - (s->lo_x < t->lo_x);
}

static double orient(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int same_point(const double *a, const double *b)
{
    return a[0] == b[0] && a[1] == b[1];
}

/* c on segment ab, strictly between its ends, given that a, b, c are collinear. */
static int inside_segment(const double *a, const double *b, const double *c)
{
    return !same_point(c, a) && !same_point(c, b) && fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) &&
           fmin(a[1], b[1]) <= c[1] && c[1] <= fmax(a[1], b[1]);
}

/* Segments ab and cd cross, or one ends inside the other; meeting at a shared end point is allowed. */
static int segments_meet(const double *a, const double *b, const double *c, const double *d)
{
    const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
        return 1;
    return (o1 == 0 && inside_segment(a, b, c)) || (o2 == 0 && inside_segment(a, b, d)) ||
           (o3 == 0 && inside_segment(c, d, a)) || (o4 == 0 && inside_segment(c, d, b));
}

int pm_case_check_polygon(const pm_case *c, const char *path, const pm_shape *s)
{
    const size_t n = s->n_points;
    const double *p = s->points;
    double area2 = 0, lo[PM_DIM] = {INFINITY, INFINITY}, hi[PM_DIM] = {-INFINITY, -INFINITY};
    for (size_t k = 0; k < n; k++) {
        const double *a = p + PM_DIM * k, *b = p + PM_DIM * ((k + 1) % n);
        area2 += a[0] * b[1] - b[0] * a[1];
        for (int d = 0; d < PM_DIM; d++) {
            lo[d] = fmin(lo[d], a[d]);
            hi[d] = fmax(hi[d], a[d]);
        }
    }
    const double diag2 = (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]);
    /* all on one line (the farthest point from the first fixes the line): say so rather than "crossed" */
    size_t far = 0;
    double far2 = 0;
    for (size_t k = 1; k < n; k++) {
        const double dx = p[PM_DIM * k] - p[0], dy = p[PM_DIM * k + 1] - p[1];
        if (dx * dx + dy * dy > far2) {
            far2 = dx * dx + dy * dy;
            far = k;
        }
    }
    int on_line = 1;
    for (size_t k = 0; k < n && on_line; k++)
        on_line = fabs(orient(p, p + PM_DIM * far, p + PM_DIM * k)) <= 1e-12 * diag2;
    if (on_line)
        return pm_error_set(PM_EINPUT, "%s: %s: the %zu points lie on one line (or one point): they enclose no area",
                            c->file, path, n);
    seg *sg = malloc(n * sizeof *sg);
    if (!sg)
        return pm_error_set(PM_ENOMEM, "out of memory checking %s", path);
    size_t m = 0;
    for (size_t k = 0; k < n; k++) {
        const double *a = p + PM_DIM * k, *b = p + PM_DIM * ((k + 1) % n);
        if (!same_point(a, b)) /* a point repeated, e.g. the first again at the end, is no edge */
            sg[m++] = (seg){fmin(a[0], b[0]), fmax(a[0], b[0]), k};
    }
    /* sweep along x: only edges whose x ranges overlap can meet */
    qsort(sg, m, sizeof *sg, cmp_seg);
    int rc = PM_OK;
    for (size_t i = 0; i < m && !rc; i++)
        for (size_t j = i + 1; j < m && sg[j].lo_x <= sg[i].hi_x && !rc; j++) {
            const size_t ki = sg[i].k, kj = sg[j].k;
            const double *a = p + PM_DIM * ki, *b = p + PM_DIM * ((ki + 1) % n);
            const double *e = p + PM_DIM * kj, *f = p + PM_DIM * ((kj + 1) % n);
            if (segments_meet(a, b, e, f)) {
                const size_t k1 = ki < kj ? ki : kj, k2 = ki < kj ? kj : ki;
                rc = pm_error_set(PM_EINPUT,
                                  "%s: %s: the outline crosses itself: the edge from point %zu to %zu meets the edge "
                                  "from point %zu to %zu; list the points once around the outline",
                                  c->file, path, k1, (k1 + 1) % n, k2, (k2 + 1) % n);
            }
        }
    free(sg);
    if (!rc && !(fabs(area2) > 1e-12 * diag2))
        rc = pm_error_set(PM_EINPUT, "%s: %s: the outline of the %zu points encloses no area",
                          c->file, path, n);
    return rc;
}
