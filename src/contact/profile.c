/*
 * Traction profiles along the surfaces (contact.h): the impulses the law gave each node, summed since
 * the last reset, spread onto stations spaced about a cell apart along the wall, and divided by the
 * time and by each station's share of the wall's length.
 *
 * A node's impulse goes to the two stations either side of its position along the wall, in
 * proportion to its nearness (as a linear element along the wall would lump a traction onto its
 * nodes). A node that lies exactly on a station gives it everything, and one that falls on a cell's
 * edge by round-off splits its impulse instead of jumping from one station to the next: a grid-aligned
 * wall and a slanted one give the same kind of profile.
 */
#include "contact/contact.h"
#include "contact/segment.h"

#include "pmech/error.h"

#include <math.h>
#include <string.h>

#if PM_DIM != 2
#error "positions along a wall are arc lengths of 2-D curves"
#endif

static inline double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1];
}

/* The direction along a straight surface: its normal turned a quarter, pointing up or right. */
static void straight_tangent(const pm_contact_surface *sf, double t[PM_DIM])
{
    t[0] = -sf->normal[1];
    t[1] = sf->normal[0];
    if (t[0] < 0 || (t[0] == 0 && t[1] < 0))
        t[0] = -t[0], t[1] = -t[1];
}

/* Segments of a chain: a polyline's np - 1, a polygon's np (the last closes it), a Gmsh wall's edges
 * (pairs of points, in their chains: the arc length runs along each chain, one after the other). */
static size_t n_segments(const pm_contact_surface *sf)
{
    const size_t np = sf->n_points;
    return sf->kind == PM_CONTACT_EDGES ? np / 2 : sf->kind == PM_CONTACT_POLYGON ? np : np - 1;
}

static void segment(const pm_contact *ct, const pm_contact_surface *sf, size_t k, const double **a, const double **b)
{
    const double *pts = ct->points + PM_DIM * sf->first_point;
    if (sf->kind == PM_CONTACT_EDGES) {
        *a = pts + PM_DIM * 2 * k;
        *b = *a + PM_DIM;
    } else {
        *a = pts + PM_DIM * k;
        *b = pts + PM_DIM * ((k + 1) % sf->n_points);
    }
}

/* Polyline, polygon or Gmsh wall: the arc length of the point of the chain nearest to x, and the chain's unit
 * direction there. */
static double chain_position(const pm_contact *ct, const pm_contact_surface *sf, const double x[PM_DIM],
                             double t[PM_DIM])
{
    const size_t nseg = n_segments(sf);
    double best = INFINITY, at = 0, walked = 0;
    t[0] = 0, t[1] = 1;
    for (size_t k = 0; k < nseg; k++) {
        const double *a0, *b0;
        segment(ct, sf, k, &a0, &b0);
        const double a[2] = {a0[0] + sf->shift[0], a0[1] + sf->shift[1]};
        const double b[2] = {b0[0] + sf->shift[0], b0[1] + sf->shift[1]};
        const double e[2] = {b[0] - a[0], b[1] - a[1]}, len = sqrt(dot(e, e));
        double q[2], dist;
        const double u = pm_segment_nearest(a, b, x, q, &dist);
        /* a node on the end two segments share is as near both by round-off: the first one keeps it */
        if (dist + 1e-12 * len < best) {
            best = dist;
            at = walked + u * len;
            t[0] = e[0] / len, t[1] = e[1] / len;
        }
        walked += len;
    }
    return at;
}

/* The point of a chain at arc length s (its last point beyond the end). */
static void chain_point(const pm_contact *ct, const pm_contact_surface *sf, double s, double x[PM_DIM])
{
    const size_t nseg = n_segments(sf);
    for (size_t k = 0; k < nseg; k++) {
        const double *a, *b;
        segment(ct, sf, k, &a, &b);
        const double len = hypot(b[0] - a[0], b[1] - a[1]);
        if (s <= len || k + 1 == nseg) {
            const double u = len > 0 ? fmin(s / len, 1.0) : 0.0;
            for (int d = 0; d < PM_DIM; d++)
                x[d] = a[d] + u * (b[d] - a[d]) + sf->shift[d];
            return;
        }
        s -= len;
    }
}

double pm_contact_length(const pm_contact *ct, size_t k, const pm_grid *g)
{
    const pm_contact_surface *sf = &ct->surface[k];
    switch (sf->kind) {
    case PM_CONTACT_CIRCLE: return 2 * M_PI * sf->radius;
    case PM_CONTACT_POLYLINE:
    case PM_CONTACT_POLYGON:
    case PM_CONTACT_EDGES: {
        const size_t nseg = n_segments(sf);
        double L = 0;
        for (size_t q = 0; q < nseg; q++) {
            const double *a, *b;
            segment(ct, sf, q, &a, &b);
            L += hypot(b[0] - a[0], b[1] - a[1]);
        }
        return L;
    }
    case PM_CONTACT_NODE_SET: {
        double t[PM_DIM], lo = INFINITY, hi = -INFINITY;
        straight_tangent(sf, t);
        for (size_t e = sf->first; e < sf->first + sf->n; e++) {
            const double s = dot(g->x + PM_DIM * ct->node[e].node, t);
            lo = fmin(lo, s);
            hi = fmax(hi, s);
        }
        return hi > lo ? hi - lo : 0.0;
    }
    default: { /* a meshfree wall spans the grid's frame along its axis */
        const int along = 1 - sf->axis;
        return g->hi[along] - g->lo[along];
    }
    }
}

/* Where the wall's stations start: arc length 0 of a chain or a circle; the lowest node of a node set;
 * the frame's side for a meshfree wall. Returns the coordinate along t at arc length 0. */
static double straight_start(const pm_contact *ct, const pm_contact_surface *sf, const pm_grid *g, const double t[PM_DIM])
{
    if (sf->kind == PM_CONTACT_WALL)
        return g->lo[1 - sf->axis];
    double lo = INFINITY;
    for (size_t e = sf->first; e < sf->first + sf->n; e++)
        lo = fmin(lo, dot(g->x + PM_DIM * ct->node[e].node, t));
    return lo;
}

size_t pm_contact_profile_stations(const pm_contact *ct, size_t k, const pm_grid *g)
{
    const pm_contact_surface *sf = &ct->surface[k];
    const double L = pm_contact_length(ct, k, g);
    const size_t cells = L > 0 ? (size_t)fmax(1.0, round(L / g->h_min)) : 0;
    if (!cells)
        return 1;
    return sf->kind == PM_CONTACT_POLYGON || sf->kind == PM_CONTACT_CIRCLE ? cells : cells + 1;
}

int pm_contact_profile(const pm_contact *ct, size_t k, const pm_grid *g, double span, pm_contact_station *out,
                       size_t n_out)
{
    if (!ct || k >= ct->n_surfaces || n_out != pm_contact_profile_stations(ct, k, g) || !(span > 0))
        return pm_error_set(PM_EINPUT, "traction profile of surface %zu: bad request", k);
    const pm_contact_surface *sf = &ct->surface[k];
    const int closed = sf->kind == PM_CONTACT_POLYGON || sf->kind == PM_CONTACT_CIRCLE;
    const double L = pm_contact_length(ct, k, g);
    const size_t cells = closed ? n_out : n_out - 1;
    const double step = cells ? L / (double)cells : 1.0;
    memset(out, 0, n_out * sizeof *out);
    double t_line[PM_DIM] = {0, 0}, start = 0;
    const int straight = sf->kind == PM_CONTACT_NODE_SET || sf->kind == PM_CONTACT_WALL;
    if (straight) {
        straight_tangent(sf, t_line);
        start = straight_start(ct, sf, g, t_line);
    }
    for (size_t I = 0; I < g->n_nodes; I++) {
        const double *J = sf->node_impulse + (1 + PM_DIM) * I;
        if (J[0] == 0 && J[1] == 0 && J[2] == 0)
            continue;
        const double *x = g->x + PM_DIM * I;
        double s, t[PM_DIM] = {0, 0};
        if (straight) {
            s = dot(x, t_line) - start;
            t[0] = t_line[0], t[1] = t_line[1];
        } else if (sf->kind == PM_CONTACT_CIRCLE) {
            const double r[2] = {x[0] - sf->origin[0] - sf->shift[0], x[1] - sf->origin[1] - sf->shift[1]};
            double a = atan2(r[1], r[0]);
            if (a < 0)
                a += 2 * M_PI;
            s = a * sf->radius;
            t[0] = -sin(a), t[1] = cos(a);
        } else {
            s = chain_position(ct, sf, x, t);
        }
        /* the two stations either side, weighted by nearness */
        size_t a = 0, b = 0;
        double w1 = 0;
        if (closed) {
            double u = fmod(s / step, (double)cells);
            if (u < 0)
                u += (double)cells;
            const double j0 = floor(u);
            w1 = u - j0;
            a = (size_t)j0 % cells;
            b = (a + 1) % cells;
        } else if (cells) {
            const double u = fmin(fmax(s / step, 0.0), (double)cells), j0 = fmin(floor(u), (double)cells - 1);
            w1 = u - j0;
            a = (size_t)j0;
            b = a + 1;
        }
        const double tangential = dot(J + 1, t);
        out[a].normal += (1 - w1) * J[0];
        out[a].tangent += (1 - w1) * tangential;
        out[b].normal += w1 * J[0];
        out[b].tangent += w1 * tangential;
    }
    for (size_t j = 0; j < n_out; j++) {
        /* each station's share of the wall: a step, half of one at the ends of an open wall */
        const double share = closed || (j > 0 && j + 1 < n_out) ? step : (n_out > 1 ? 0.5 * step : 1.0);
        out[j].s = (double)j * step;
        out[j].normal /= span * share;
        out[j].tangent /= span * share;
        if (straight) {
            /* a point of its plane: a node set's first node, a wall's origin */
            const double *p0 = sf->kind == PM_CONTACT_NODE_SET && sf->n ? g->x + PM_DIM * ct->node[sf->first].node : NULL;
            for (int d = 0; d < PM_DIM; d++)
                out[j].x[d] = p0 ? p0[d] : sf->origin[d] + sf->shift[d];
            /* the point of the wall at this station: its plane's point, moved along the wall */
            const double along = start + out[j].s - dot(out[j].x, t_line);
            for (int d = 0; d < PM_DIM; d++)
                out[j].x[d] += along * t_line[d];
        } else if (sf->kind == PM_CONTACT_CIRCLE) {
            const double a = out[j].s / sf->radius;
            out[j].x[0] = sf->origin[0] + sf->shift[0] + sf->radius * cos(a);
            out[j].x[1] = sf->origin[1] + sf->shift[1] + sf->radius * sin(a);
        } else {
            chain_point(ct, sf, out[j].s, out[j].x);
        }
    }
    return PM_OK;
}

void pm_contact_profile_reset(pm_contact *ct)
{
    for (size_t k = 0; ct && k < ct->n_surfaces; k++)
        memset(ct->surface[k].node_impulse, 0, (size_t)(1 + PM_DIM) * (ct->n_nodes ? ct->n_nodes : 1) * sizeof(double));
}
