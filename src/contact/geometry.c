/*
 * Where a surface is: the signed distance of a point to a plane, a polyline, a polygon, a circle or
 * a Gmsh wall's edges placed at its position of the last detection, and the unit normal pointing into it (contact.h).
 */
#include "contact/contact.h"
#include "contact/segment.h"

#include <math.h>

static inline double dot2(const double *a, const double *b)
{
    double s = a[0] * b[0];
    for (int d = 1; d < PM_DIM; d++)
        s += a[d] * b[d];
    return s;
}

static double plane(const pm_contact_surface *sf, const double x[PM_DIM], double n[PM_DIM])
{
    double r[PM_DIM];
    for (int d = 0; d < PM_DIM; d++) {
        r[d] = sf->origin[d] + sf->shift[d] - x[d];
        n[d] = sf->normal[d];
    }
    return dot2(r, sf->normal);
}

static double circle(const pm_contact_surface *sf, const double x[PM_DIM], double n[PM_DIM])
{
    double r[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        r[d] = sf->origin[d] + sf->shift[d] - x[d];
    const double len = sqrt(dot2(r, r));
    for (int d = 0; d < PM_DIM; d++)
        n[d] = len > 0 ? r[d] / len : (d == PM_DIM - 1 ? -1.0 : 0.0);
    return len - sf->radius;
}

/* Segments of a polyline or polygon: the nearest one decides. The material-side normal of segment
 * a -> b is side times its left normal (-e_y, e_x). Outside a corner shared by two segments every
 * point is nearest the corner itself: a round corner pushes along the direction to it, a sharp one
 * along the normal of the face the point lies squarely off, so that material on either side of a
 * tool's tip follows its own face (seed 004 §5.3.2 gives the tip two nodes, one per face). */
static double chain(const pm_contact *ct, const pm_contact_surface *sf, const double x[PM_DIM], double n[PM_DIM])
{
#if PM_DIM != 2
#error "polylines and polygons are 2-D: their normals are the segments' in-plane normals"
#endif
    const double *pts = ct->points + PM_DIM * sf->first_point;
    /* a Gmsh wall's edges are pairs of points, every end a corner (or a smooth joint, which the sharp
     * rule gives the same distance) */
    const int pairs = sf->kind == PM_CONTACT_EDGES;
    const size_t np = sf->n_points, nseg = pairs ? np / 2 : sf->kind == PM_CONTACT_POLYGON ? np : np - 1;
    double best = INFINITY, best_depth = 0, q_best[2] = {0, 0}, m_best[2] = {0, 1};
    int inside = 0, at_corner = 0;
    for (size_t k = 0; k < nseg; k++) {
        const double *a0 = pts + 2 * (pairs ? 2 * k : k), *b0 = pairs ? a0 + 2 : pts + 2 * ((k + 1) % np);
        const double a[2] = {a0[0] + sf->shift[0], a0[1] + sf->shift[1]};
        const double b[2] = {b0[0] + sf->shift[0], b0[1] + sf->shift[1]};
        double q[2], dist;
        const double s = pm_segment_nearest(a, b, x, q, &dist);
        const double e[2] = {b[0] - a[0], b[1] - a[1]}, r[2] = {x[0] - a[0], x[1] - a[1]}, len = sqrt(dot2(e, e));
        const double m[2] = {-sf->side * e[1] / len, sf->side * e[0] / len};
        const double depth = fabs(dot2(r, m));
        /* a shared end point is as near on both segments: the one the point lies squarely off decides */
        if (dist < best * (1 - 1e-12) || (dist <= best * (1 + 1e-12) && depth > best_depth)) {
            best = dist;
            best_depth = depth;
            q_best[0] = q[0], q_best[1] = q[1];
            m_best[0] = m[0], m_best[1] = m[1];
            /* a polyline's two free ends are no corners */
            at_corner = (s <= 0 && (pairs || sf->kind == PM_CONTACT_POLYGON || k > 0)) ||
                        (s >= 1 && (pairs || sf->kind == PM_CONTACT_POLYGON || k + 1 < nseg));
        }
        /* even-odd rule for the polygon's inside */
        if (sf->kind == PM_CONTACT_POLYGON && ((a[1] > x[1]) != (b[1] > x[1])) &&
            x[0] < a[0] + (x[1] - a[1]) * e[0] / e[1])
            inside = !inside;
    }
    double sgn;
    if (sf->kind == PM_CONTACT_POLYGON) {
        sgn = inside ? -1.0 : 1.0;
    } else {
        const double w[2] = {x[0] - q_best[0], x[1] - q_best[1]};
        sgn = dot2(w, m_best) >= 0 ? 1.0 : -1.0;
    }
    if (sf->sharp && at_corner && sgn > 0) {
        n[0] = -m_best[0], n[1] = -m_best[1];
    } else if (best > 1e-12 * (1 + fabs(x[0]) + fabs(x[1]))) {
        /* towards the nearest point from the material's side, deeper in from inside */
        for (int d = 0; d < 2; d++)
            n[d] = sgn * (q_best[d] - x[d]) / best;
    } else {
        n[0] = -m_best[0], n[1] = -m_best[1];
    }
    return sgn * best;
}

double pm_contact_distance(const pm_contact *ct, const pm_contact_surface *sf, const double x[PM_DIM],
                           double n[PM_DIM])
{
    switch (sf->kind) {
    case PM_CONTACT_CIRCLE: return circle(sf, x, n);
    case PM_CONTACT_POLYLINE:
    case PM_CONTACT_POLYGON:
    case PM_CONTACT_EDGES: return chain(ct, sf, x, n);
    default: return plane(sf, x, n);
    }
}
