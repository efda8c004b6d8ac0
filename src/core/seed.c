#include "seed.h"

#include "pmech/error.h"

#include <math.h>
#include <string.h>

/* Gauss-Legendre abscissae and weights on [-1, 1] for n = 1..6 (weights sum to 2). */
static const double gl_x[6][6] = {
    {0},
    {-0.5773502691896257645, 0.5773502691896257645},
    {-0.7745966692414833770, 0, 0.7745966692414833770},
    {-0.8611363115940525752, -0.3399810435848562648, 0.3399810435848562648, 0.8611363115940525752},
    {-0.9061798459386639928, -0.5384693101056830910, 0, 0.5384693101056830910, 0.9061798459386639928},
    {-0.9324695142031520279, -0.6612093864662645137, -0.2386191860831969086, 0.2386191860831969086,
     0.6612093864662645137, 0.9324695142031520279}};
static const double gl_w[6][6] = {
    {2},
    {1, 1},
    {0.5555555555555555556, 0.8888888888888888889, 0.5555555555555555556},
    {0.3478548451374538574, 0.6521451548625461426, 0.6521451548625461426, 0.3478548451374538574},
    {0.2369268850561890875, 0.4786286704993664680, 0.5688888888888888889, 0.4786286704993664680,
     0.2369268850561890875},
    {0.1713244923791703450, 0.3607615730481386076, 0.4679139345726910473, 0.4679139345726910473,
     0.3607615730481386076, 0.1713244923791703450}};

/* Symmetric triangle rules in barycentric coordinates (weights sum to 1). */
static const double tri6_a = 0.445948490915965, tri6_b = 0.091576213509771;
static const double tri6_wa = 0.223381589678011, tri6_wb = 0.109951743655322;

int pm_shape_contains(const pm_shape *s, const double x[2])
{
    switch (s->type) {
    case PM_SHAPE_RECTANGLE:
        return x[0] >= s->min[0] && x[0] <= s->max[0] && x[1] >= s->min[1] && x[1] <= s->max[1];
    case PM_SHAPE_CIRCLE: {
        double dx = x[0] - s->center[0], dy = x[1] - s->center[1];
        return dx * dx + dy * dy <= s->radius * s->radius;
    }
    case PM_SHAPE_POLYGON: {
        int in = 0;
        for (size_t i = 0, j = s->n_points - 1; i < s->n_points; j = i++) {
            const double *a = s->points + 2 * i, *b = s->points + 2 * j;
            if ((a[1] > x[1]) != (b[1] > x[1]) &&
                x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0])
                in = !in;
        }
        return in;
    }
    default:
        return 0;
    }
}

/* The quadrature points of one cell: physical positions, area weights and half-sizes. */
typedef struct cell_points {
    int n;
    double x[36][2];
    double w[36];
    double hs[36][2];
} cell_points;

static int ppc_of(const pm_case_body *b, const pm_grid *g)
{
    if (b->particles_per_cell > 0)
        return b->particles_per_cell;
    return g->element == PM_QUAD4 ? 2 : 3;
}

/* Gauss points of a general (unstructured, convex) quad: isoparametric map, weight w_i w_j det J. */
static void iso_quad_points(const pm_grid *g, size_t cell, int n, cell_points *cp)
{
    const int32_t *q = g->conn + 4 * cell;
    static const double XI[4] = {-1, 1, 1, -1}, ETA[4] = {-1, -1, 1, 1};
    cp->n = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const double xi = gl_x[n - 1][i], eta = gl_x[n - 1][j];
            double x = 0, y = 0, J[4] = {0, 0, 0, 0};
            for (int k = 0; k < 4; k++) {
                const double *v = g->x + 2 * q[k];
                double N = 0.25 * (1 + XI[k] * xi) * (1 + ETA[k] * eta);
                double dxi = 0.25 * XI[k] * (1 + ETA[k] * eta), deta = 0.25 * ETA[k] * (1 + XI[k] * xi);
                x += N * v[0];
                y += N * v[1];
                J[0] += dxi * v[0];
                J[1] += deta * v[0];
                J[2] += dxi * v[1];
                J[3] += deta * v[1];
            }
            int k = cp->n++;
            cp->x[k][0] = x;
            cp->x[k][1] = y;
            cp->w[k] = gl_w[n - 1][i] * gl_w[n - 1][j] * fabs(J[0] * J[3] - J[1] * J[2]);
            cp->hs[k][0] = cp->hs[k][1] = 0.5 * sqrt(cp->w[k]);
        }
}

/* uniform: the centres of n x n equal sub-squares (RKPM, whose particles are its nodes and whose
 * smoothed gradients need point-centred cells that tile the body), else Gauss points. */
static void quad_points(const pm_grid *g, size_t cell, int n, int uniform, cell_points *cp)
{
    if (!g->structured) {
        iso_quad_points(g, cell, n, cp);
        return;
    }
    const int32_t *q = g->conn + 4 * cell;
    const double *a = g->x + 2 * q[0], *c = g->x + 2 * q[2];
    double hx = c[0] - a[0], hy = c[1] - a[1];
    cp->n = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int k = cp->n++;
            cp->x[k][0] = a[0] + (uniform ? (i + 0.5) / n : 0.5 * (1 + gl_x[n - 1][i])) * hx;
            cp->x[k][1] = a[1] + (uniform ? (j + 0.5) / n : 0.5 * (1 + gl_x[n - 1][j])) * hy;
            cp->w[k] = uniform ? hx * hy / (n * n) : 0.25 * gl_w[n - 1][i] * gl_w[n - 1][j] * hx * hy;
            cp->hs[k][0] = 0.5 * hx / n;
            cp->hs[k][1] = 0.5 * hy / n;
        }
}

static void tri_points(const pm_grid *g, size_t cell, int n, cell_points *cp)
{
    const int32_t *t = g->conn + 3 * cell;
    const double *p0 = g->x + 2 * t[0], *p1 = g->x + 2 * t[1], *p2 = g->x + 2 * t[2];
    double area = 0.5 * fabs((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]));
    double bary[6][3], w[6];
    int m = 0;
    if (n == 1) {
        bary[0][0] = bary[0][1] = bary[0][2] = 1.0 / 3; w[0] = 1; m = 1;
    } else if (n == 3) {
        for (int k = 0; k < 3; k++) {
            for (int l = 0; l < 3; l++)
                bary[k][l] = l == k ? 2.0 / 3 : 1.0 / 6;
            w[k] = 1.0 / 3;
        }
        m = 3;
    } else {
        for (int k = 0; k < 3; k++) {
            for (int l = 0; l < 3; l++) {
                bary[k][l] = l == k ? 1 - 2 * tri6_a : tri6_a;
                bary[k + 3][l] = l == k ? 1 - 2 * tri6_b : tri6_b;
            }
            w[k] = tri6_wa;
            w[k + 3] = tri6_wb;
        }
        m = 6;
    }
    double hs = 0.5 * sqrt(area / m);
    cp->n = m;
    for (int k = 0; k < m; k++) {
        cp->x[k][0] = bary[k][0] * p0[0] + bary[k][1] * p1[0] + bary[k][2] * p2[0];
        cp->x[k][1] = bary[k][0] * p0[1] + bary[k][1] * p1[1] + bary[k][2] * p2[1];
        cp->w[k] = w[k] * area;
        cp->hs[k][0] = cp->hs[k][1] = hs;
    }
}

static void cell_quadrature(const pm_grid *g, size_t cell, int n, int uniform, cell_points *cp)
{
    if (g->element == PM_QUAD4)
        quad_points(g, cell, n, uniform, cp);
    else
        tri_points(g, cell, n, cp);
}

/* Quick reject: the body's bounding box against the cell's. */
static void shape_box(const pm_shape *s, double lo[2], double hi[2])
{
    switch (s->type) {
    case PM_SHAPE_RECTANGLE:
        memcpy(lo, s->min, sizeof(double) * 2);
        memcpy(hi, s->max, sizeof(double) * 2);
        return;
    case PM_SHAPE_CIRCLE:
        for (int d = 0; d < 2; d++) {
            lo[d] = s->center[d] - s->radius;
            hi[d] = s->center[d] + s->radius;
        }
        return;
    case PM_SHAPE_POLYGON:
        lo[0] = hi[0] = s->points[0];
        lo[1] = hi[1] = s->points[1];
        for (size_t i = 1; i < s->n_points; i++)
            for (int d = 0; d < 2; d++) {
                lo[d] = fmin(lo[d], s->points[2 * i + d]);
                hi[d] = fmax(hi[d], s->points[2 * i + d]);
            }
        return;
    default:
        lo[0] = lo[1] = -INFINITY;
        hi[0] = hi[1] = INFINITY;
    }
}

static int cell_may_touch(const pm_grid *g, size_t cell, const double lo[2], const double hi[2])
{
    const int32_t *c = g->conn + (size_t)g->nodes_per_cell * cell;
    double clo[2] = {INFINITY, INFINITY}, chi[2] = {-INFINITY, -INFINITY};
    for (int k = 0; k < g->nodes_per_cell; k++)
        for (int d = 0; d < 2; d++) {
            clo[d] = fmin(clo[d], g->x[2 * c[k] + d]);
            chi[d] = fmax(chi[d], g->x[2 * c[k] + d]);
        }
    return clo[0] <= hi[0] && chi[0] >= lo[0] && clo[1] <= hi[1] && chi[1] >= lo[1];
}

/*
 * A particle's half-size reaches no further than a circle's rim. A circle cuts the cells at every
 * angle, so the seeding half-sizes of its outermost points (their share of the cell) overshoot the rim
 * by different amounts: seen from the particles, as contact sees a body (its gap is the centre's
 * distance minus the half-size), a disk of R = 0.5 m on h = R/8 reached 0.502 m below its centre and
 * up to 0.512 m in other directions, a polygon that climbed onto its own corners as it rolled (8 mm
 * in 0.3 s, 9 % of the energy it released) and lost 14 % of its acceleration. A point at depth d
 * below the rim gets half-sizes of at most d, so the body's extent ends at the rim in every direction.
 * Straight faces (rectangles, polygons) keep the seeding half-sizes: along a face they overshoot by
 * one amount, so the face stays straight.
 */
static void trim_to_circle(const pm_shape *s, const double x[2], double hs[2])
{
    if (s->type != PM_SHAPE_CIRCLE)
        return;
    const double depth = s->radius - hypot(x[0] - s->center[0], x[1] - s->center[1]);
    for (int d = 0; d < 2; d++)
        hs[d] = fmin(hs[d], depth);
}

/* Visit every quadrature point of a body inside its shape; fill particles (body index b) when p != NULL. */
static size_t seed_body(const pm_case *c, const pm_case_body *body, int32_t b, const pm_grid *g, pm_particles *p,
                        size_t first)
{
    int n = ppc_of(body, g);
    double lo[2], hi[2];
    shape_box(&body->shape, lo, hi);
    cell_points cp;
    size_t k = first;
    /* gmsh_group: every quadrature point of the group's cells */
    const pm_cell_set *group = NULL;
    if (body->shape.type == PM_SHAPE_GMSH_GROUP && !(group = pm_grid_find_cell_set(g, body->shape.group)))
        return 0;
    const size_t n_visit = group ? group->n : g->n_cells;
    for (size_t iv = 0; iv < n_visit; iv++) {
        const size_t cell = group ? (size_t)group->cells[iv] : iv;
        if (!group && !cell_may_touch(g, cell, lo, hi))
            continue;
        cell_quadrature(g, cell, n, c->method == PM_METHOD_RKPM, &cp);
        for (int q = 0; q < cp.n; q++) {
            if (!group && !pm_shape_contains(&body->shape, cp.x[q]))
                continue;
            if (p) {
                const pm_material *m = &c->materials[body->material];
                double r = c->formulation == PM_AXISYMMETRIC ? cp.x[q][0] : 1.0;
                p->x[2 * k] = p->x0[2 * k] = cp.x[q][0];
                p->x[2 * k + 1] = p->x0[2 * k + 1] = cp.x[q][1];
                p->v[2 * k] = body->velocity[0];
                p->v[2 * k + 1] = body->velocity[1];
                /* before its first step a point moves with the velocity it is given */
                for (int d = 0; d < PM_DIM; d++)
                    p->v_grid[PM_DIM * k + d] = body->velocity[d];
                p->vol[k] = p->vol0[k] = cp.w[q] * r;
                p->mass[k] = m->density * p->vol[k];
                p->hsize[2 * k] = cp.hs[q][0];
                p->hsize[2 * k + 1] = cp.hs[q][1];
                trim_to_circle(&body->shape, cp.x[q], p->hsize + 2 * k);
                double *F = p->F + PM_NF * k;
                F[PM_FXX] = F[PM_FYY] = F[PM_FZZ] = 1.0;
                p->material[k] = body->material;
                p->body[k] = b;
                p->cell[k] = (int32_t)cell;
            }
            k++;
        }
    }
    return k - first;
}

int pm_seed_count(const pm_case *c, const pm_grid *g, size_t *per_body, size_t *total)
{
    *total = 0;
    for (size_t b = 0; b < c->n_bodies; b++) {
        per_body[b] = seed_body(c, &c->bodies[b], (int32_t)b, g, NULL, 0);
        if (per_body[b] == 0 && c->bodies[b].shape.type == PM_SHAPE_GMSH_GROUP)
            return pm_error_set(PM_EINPUT, "%s: bodies[%zu].shape.name: the mesh has no 2-D physical group '%s'",
                                c->file, b, c->bodies[b].shape.group);
        if (per_body[b] == 0)
            return pm_error_set(PM_EINPUT,
                                "%s: bodies[%zu] ('%s') yields no particle: no quadrature point of the "
                                "grid lies inside its shape; refine the grid, raise particles_per_cell, "
                                "or check the shape's coordinates",
                                c->file, b, c->bodies[b].name);
        *total += per_body[b];
    }
    return PM_OK;
}

static void initial_stress(const pm_case *c, const pm_case_body *b, const double x[2], double s[4])
{
    memset(s, 0, 4 * sizeof(double));
    if (b->stress0 == PM_STRESS0_CONSTANT) {
        memcpy(s, b->stress0_value, 4 * sizeof(double));
    } else if (b->stress0 == PM_STRESS0_GEOSTATIC) {
        /* vertical stress from the weight of the overburden, gravity along -y */
        double rho = c->materials[b->material].density;
        double depth = fmax(b->surface_y - x[1], 0.0);
        double syy = -rho * fabs(c->analysis.gravity[1]) * depth;
        s[PM_SYY] = syy;
        s[PM_SXX] = s[PM_SZZ] = b->k0 * syy;
    }
}

/* Initial stress and material state of particles [first, first + n) of one body. */
static void init_stress(const pm_case *c, const pm_case_body *b, pm_particles *p, size_t first, size_t n)
{
    const pm_material *m = &c->materials[b->material];
    for (size_t i = first; i < first + n; i++) {
        double *s = p->stress + PM_NS * i;
        initial_stress(c, b, p->x + PM_DIM * i, s);
        if (m->ops->init_state && p->n_state) {
            double s6[6] = {s[PM_SXX], s[PM_SYY], s[PM_SZZ], s[PM_SXY], 0, 0};
            m->ops->init_state(m, s6, p->state + p->n_state * i);
        }
    }
}

int pm_seed_fill(const pm_case *c, const pm_grid *g, pm_particles *p)
{
    size_t k = 0;
    for (size_t b = 0; b < c->n_bodies; b++) {
        const size_t n = seed_body(c, &c->bodies[b], (int32_t)b, g, p, k);
        init_stress(c, &c->bodies[b], p, k, n);
        k += n;
    }
    if (k != p->n)
        return pm_error_set(PM_EINTERNAL, "seeding produced %zu particles, %zu expected", k, p->n);
    return PM_OK;
}

size_t pm_seed_body_count(const pm_case *c, const pm_case_body *b, const pm_grid *g)
{
    return seed_body(c, b, 0, g, NULL, 0);
}

size_t pm_seed_body_fill(const pm_case *c, const pm_case_body *b, int32_t index, const pm_grid *g, pm_particles *p,
                         size_t first)
{
    const size_t n = seed_body(c, b, index, g, p, first);
    init_stress(c, b, p, first, n);
    return n;
}
