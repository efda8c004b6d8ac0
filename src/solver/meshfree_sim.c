/*
 * GMM and RKPM as methods of the same solvers (ARCHITECTURE.md): the case's grid only creates the
 * nodes, then a node cloud takes its place as s->grid (nodes, no cells), the meshfree approximation
 * takes the place of the grid one, and the explicit and implicit steps run unchanged on it. What
 * differs is here:
 *  - the nodes move with the material after every step (GMM: with their own velocity or displacement;
 *    RKPM: they are the particles) instead of being reset;
 *  - a condition named by a grid side holds the nodes on that side at t = 0 (RKPM: the particles
 *    within half a particle spacing of it, the outermost layer), and they keep it as they move;
 *  - mls and rk_cubic do not interpolate, so a prescribed component is not a nodal value: the rows
 *    Lambda_JI = N_I(x_J) of those nodes (the Kronecker-delta transformation of seed 002 eqs. 15-21,
 *    restricted to them) make the interpolated value at x_J what is prescribed. Explicit steps solve
 *    for the boundary coefficients after every velocity update (pm_kd_impose); implicit steps add the
 *    constraint rows as a penalty (the multipoint-constraint form). lme interpolates on the hull of
 *    the nodes (weak Kronecker-delta property), so its nodes are constrained directly, as in MPM;
 *  - `friction` conditions (and fixed sides) are rigid walls of the contact module (src/contact)
 *    whose contact set is found before every step.
 */
#include "meshfree_internal.h"

#include "implicit_internal.h"
#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Penalty factor of the implicit constraint rows, relative to the stiffness scale of the node: the
 * constraint is then met to about 1e-5 of the displacement, far below the discretisation error,
 * while a direct solver still factors the tangent accurately. */
#define PM_MF_PENALTY 1e5

/* Area of cell c of an unstructured grid (its nodes counter-clockwise). */
static double cell_area(const pm_grid *g, size_t c)
{
#if PM_DIM != 2
#error "a cell's area is its polygon's in the plane"
#endif
    const int m = g->nodes_per_cell;
    const int32_t *v = g->conn + (size_t)m * c;
    double a2 = 0.0;
    for (int k = 0; k < m; k++) {
        const double *p = g->x + PM_DIM * v[k], *q = g->x + PM_DIM * v[(k + 1) % m];
        a2 += p[0] * q[1] - q[0] * p[1];
    }
    return 0.5 * fabs(a2);
}

/*
 * GMM: the nodes of every cell holding a particle; map[old] = new index or -1. *h_out: their nodal
 * spacing, the length seed 000's support r = f sqrt(2 h^2) scales with: a structured grid's cell side,
 * else the square root of the area per node of the cells holding particles. A triangulation has about
 * two triangles per node (six around each node, three nodes to each triangle: Euler's formula), a quad
 * mesh one quad, so that area is twice the mean triangle's or the mean quad's, and a structured grid cut
 * into triangles gets its cell side either way. The smallest altitude, what the time step is limited
 * by, is 0.56 of the spacing on the triangles of tests/verification/cases/gmsh_incline25.msh: it made
 * supports of 1.2 spacings, every one grown by the adaptive rule to 6-9 nodes, and a block's bottom row
 * of nodes shook against a frictional slope there (verify_gmsh_incline_meshfree).
 */
static int gmm_nodes(const pm_grid *g, const pm_particles *p, int32_t *map, size_t *n_out, double *h_out)
{
    memset(map, 0xff, g->n_nodes * sizeof *map);
    uint8_t *held = g->structured ? NULL : calloc(g->n_cells ? g->n_cells : 1, 1);
    if (!g->structured && !held)
        return pm_error_set(PM_ENOMEM, "out of memory");
    double area = 0.0;
    size_t cells = 0;
    for (size_t i = 0; i < p->n; i++) {
        int32_t cell = pm_grid_locate(g, p->x + 2 * i);
        if (cell < 0) {
            free(held);
            return pm_error_set(PM_EINPUT, "particle %zu at (%g, %g) lies outside the grid", i, p->x[2 * i],
                                p->x[2 * i + 1]);
        }
        for (int k = 0; k < g->nodes_per_cell; k++)
            map[g->conn[(size_t)g->nodes_per_cell * cell + k]] = 0;
        if (held && !held[cell]) {
            held[cell] = 1;
            area += cell_area(g, (size_t)cell);
            cells++;
        }
    }
    free(held);
    size_t n = 0;
    for (size_t I = 0; I < g->n_nodes; I++)
        if (map[I] == 0)
            map[I] = (int32_t)n++;
    *n_out = n;
    if (g->structured)
        *h_out = fmin(g->h[0], g->h[1]);
    else
        *h_out = sqrt((g->nodes_per_cell == 3 ? 2.0 : 1.0) * area / (double)(cells ? cells : 1));
    return PM_OK;
}

/* Node sets of the node grid: GMM maps the background's sets; RKPM takes the outermost particle layer
 * along each named side. */
static int node_sets(pm_sim *s, const int32_t *map)
{
    const pm_mf *mf = s->mf;
    const pm_grid *bg = &mf->background;
    int32_t *nodes = malloc((s->grid.n_nodes ? s->grid.n_nodes : 1) * sizeof *nodes);
    if (!nodes)
        return pm_error_set(PM_ENOMEM, "out of memory for node sets");
    int rc = PM_OK;
    for (size_t k = 0; k < bg->n_sets && !rc; k++) {
        const pm_node_set *set = &bg->sets[k];
        size_t n = 0;
        int axis, hi;
        if (mf->rkpm) {
            if (!pm_grid_side_of(set->name, &axis, &hi))
                continue; /* physical groups name grid nodes, which RKPM does not have */
            const double at = hi ? bg->hi[axis] : bg->lo[axis];
            const double tol = 0.5 * mf->cloud->h * (1 + 1e-6);
            for (size_t I = 0; I < s->grid.n_nodes; I++)
                if (fabs(s->grid.x[2 * I + axis] - at) <= tol)
                    nodes[n++] = (int32_t)I;
        } else {
            for (size_t q = 0; q < set->n; q++)
                if (map[set->nodes[q]] >= 0)
                    nodes[n++] = map[set->nodes[q]];
        }
        const int k_new = pm_grid_add_node_set(&s->grid, set->name, n, nodes, set->normal);
        rc = k_new < 0 ? k_new : PM_OK; /* it returns the new set's index */
    }
    free(nodes);
    return rc;
}

int pm_mf_create(pm_sim *s, int n_threads)
{
    const pm_case *c = s->c;
    pm_mf *mf = calloc(1, sizeof *mf);
    if (!mf)
        return pm_error_set(PM_ENOMEM, "out of memory");
    s->mf = mf;
    mf->background = s->grid;
    memset(&s->grid, 0, sizeof s->grid);
    mf->rkpm = c->method == PM_METHOD_RKPM;
    const pm_approx_ops *kind = pm_approx_find(c->shape_function, c->method);
    if (!kind)
        return pm_error_set(PM_EINPUT, "%s: shape_function '%s' does not serve this method", c->file, c->shape_function);
    mf->transform = !kind->interpolating;
    const pm_grid *bg = &mf->background;
    const pm_particles *p = &s->p;
    if (p->n == 0)
        return pm_error_set(PM_EINPUT, "%s: a meshfree run needs particles to make its nodes", c->file);
    int32_t *map = NULL;
    double *x = NULL;
    size_t n = 0;
    pm_cloud_opts co = {.h = NAN, .cell_size = NAN, .skin = NAN};
    int rc = PM_OK;
    if (mf->rkpm) {
        rc = pm_cloud_create(p->n, p->x, p->vol, &co, &mf->cloud);
    } else {
        map = malloc(bg->n_nodes * sizeof *map);
        if (!map)
            return pm_error_set(PM_ENOMEM, "out of memory");
        rc = gmm_nodes(bg, p, map, &n, &co.h);
        if (!rc && !(x = malloc(2 * n * sizeof *x)))
            rc = pm_error_set(PM_ENOMEM, "out of memory for %zu nodes", n);
        for (size_t I = 0; !rc && I < bg->n_nodes; I++)
            if (map[I] >= 0) {
                x[2 * map[I]] = bg->x[2 * I];
                x[2 * map[I] + 1] = bg->x[2 * I + 1];
            }
        if (!rc)
            rc = pm_cloud_create(n, x, NULL, &co, &mf->cloud);
        free(x);
    }
    if (rc) {
        free(map);
        return pm_error_prefix(rc, "%s: method: ", c->file);
    }
    pm_meshfree_opts o = pm_meshfree_opts_default();
    o.support_radius = c->support_radius;
    o.lme_gamma = c->lme_gamma;
    o.cond_tol = c->max_condition;
    o.axisymmetric = c->formulation == PM_AXISYMMETRIC;
    rc = pm_approx_create_cloud(c->shape_function, mf->cloud, &o, &s->approx);
    if (rc) {
        free(map);
        return pm_error_prefix(rc, "%s: shape_function: ", c->file);
    }
    s->approx->n_threads = n_threads < 1 ? 1 : n_threads;
    /* the node grid: cloud nodes, no cells; its x is the cloud's, so moving one moves both */
    pm_grid *g = &s->grid;
    g->element = bg->element;
    g->n_nodes = mf->cloud->n;
    g->x = mf->cloud->x;
    /* the step's length: GMM keeps the grid's smallest cell size (its spacing on a structured grid),
     * which a graded mesh's finest cells need, while its supports scale with the mean spacing */
    g->h_min = mf->rkpm ? mf->cloud->h : bg->h_min;
    for (int d = 0; d < 2; d++) {
        g->lo[d] = bg->lo[d];
        g->hi[d] = bg->hi[d];
    }
    rc = node_sets(s, map);
    free(map);
    if (rc)
        return rc;
    mf->vh = calloc(2 * g->n_nodes, sizeof(double));
    mf->ah = calloc(2 * g->n_nodes, sizeof(double));
    mf->g_nodes = calloc(2 * g->n_nodes, sizeof(double));
    if (!mf->vh || !mf->ah || !mf->g_nodes)
        return pm_error_set(PM_ENOMEM, "out of memory for %zu nodes", g->n_nodes);
    return PM_OK;
}

/* RKPM: a node held by a side condition lies up to half a particle spacing inside that side; its row
 * is evaluated on the side itself (the node projected onto it), so that the prescribed value holds at
 * the body's boundary and a uniform strain is the discrete solution of a patch. */
static int side_offsets(pm_sim *s, int comp)
{
    pm_mf *mf = s->mf;
    const size_t nb = pm_kd_size(mf->kd[comp]);
    double *off = calloc(2 * (nb ? nb : 1), sizeof(double));
    if (!off)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (size_t b = 0; b < s->c->n_bcs; b++) {
        const pm_case_bc *bc = &s->c->bcs[b];
        int axis, hi;
        if (bc->type == PM_BC_FRICTION || !(bc->dirs & (1u << comp)) || !pm_grid_side_of(bc->boundary, &axis, &hi))
            continue;
        const pm_node_set *set = pm_grid_find_set(&s->grid, bc->boundary);
        const double at = hi ? mf->background.hi[axis] : mf->background.lo[axis];
        for (size_t q = 0; set && q < set->n; q++)
            for (size_t j = 0; j < nb; j++)
                if (mf->kd_nodes[comp][j] == set->nodes[q])
                    off[2 * j + axis] = at - s->grid.x[2 * (size_t)set->nodes[q] + axis];
    }
    const int rc = pm_kd_set_offsets(mf->kd[comp], s->approx, off);
    free(off);
    return rc;
}

int pm_mf_setup_conditions(pm_sim *s)
{
    pm_mf *mf = s->mf;
    if (!mf->transform)
        return PM_OK;
    pm_nodal *nd = &s->nd;
    const size_t nn = s->grid.n_nodes;
    size_t most = 0;
    for (int c = 0; c < 2; c++) {
        size_t nb = 0;
        for (size_t I = 0; I < nn; I++)
            nb += (nd->fixed[I] >> c) & 1u;
        if (!nb)
            continue;
        mf->kd_nodes[c] = malloc(nb * sizeof(int32_t));
        if (!mf->kd_nodes[c])
            return pm_error_set(PM_ENOMEM, "out of memory");
        nb = 0;
        for (size_t I = 0; I < nn; I++)
            if ((nd->fixed[I] >> c) & 1u) {
                mf->kd_nodes[c][nb++] = (int32_t)I;
                nd->fixed[I] &= (uint8_t) ~(1u << c); /* the Lambda rows hold it now, not the nodal value */
            }
        int rc = pm_kd_create(s->approx, nb, mf->kd_nodes[c], &mf->kd[c]);
        if (!rc && mf->rkpm)
            rc = side_offsets(s, c);
        if (rc)
            return pm_error_prefix(rc, "%s: boundary_conditions: ", s->c->file);
        most = nb > most ? nb : most;
    }
    mf->g = malloc((most ? most : 1) * sizeof(double));
    return mf->g ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory");
}

void pm_mf_destroy(pm_sim *s)
{
    pm_mf *mf = s->mf;
    if (!mf)
        return;
    s->grid.x = NULL; /* the cloud's */
    for (int c = 0; c < 2; c++) {
        pm_kd_destroy(mf->kd[c]);
        free(mf->kd_nodes[c]);
    }
    free(mf->g);
    free(mf->vh);
    free(mf->ah);
    free(mf->g_nodes);
    pm_cloud_destroy(mf->cloud);
    pm_grid_free(&mf->background);
    free(mf);
    s->mf = NULL;
}

void pm_mf_impose(pm_sim *s, double *nodal, int what)
{
    pm_mf *mf = s->mf;
    for (int c = 0; c < 2; c++) {
        if (!mf->kd[c])
            continue;
        const size_t nb = pm_kd_size(mf->kd[c]);
        for (size_t j = 0; j < nb; j++)
            mf->g[j] = what == 0 ? s->nd.vfix[2 * (size_t)mf->kd_nodes[c][j] + c] : 0.0;
        if (pm_kd_impose(mf->kd[c], mf->g, 2, c, nodal) != PM_OK)
            mf->failed = 1;
    }
}

void pm_mf_impose_update(pm_sim *s, double dt)
{
    pm_mf *mf = s->mf;
    pm_nodal *nd = &s->nd;
    pm_mf_impose(s, nd->vel, 0);
    pm_mf_impose(s, nd->vel_new, 0);
    for (int c = 0; c < 2; c++) {
        if (!mf->kd[c])
            continue;
        const size_t nb = pm_kd_size(mf->kd[c]);
        for (size_t j = 0; j < nb; j++) {
            const size_t k = 2 * (size_t)mf->kd_nodes[c][j];
            for (int d = 0; d < 2; d++)
                nd->acc[k + d] = (nd->vel_new[k + d] - nd->vel[k + d]) / dt;
        }
    }
}

/* After the nodes moved: the cell list, RKPM's node volumes, the Lambda rows (the wall contacts are
 * found at the start of the next step, pm_sim_update_constraints). */
static int nodes_moved(pm_sim *s)
{
    pm_mf *mf = s->mf;
    if (mf->rkpm)
        memcpy(mf->cloud->vol, s->p.vol, s->p.n * sizeof(double));
    pm_check(pm_cloud_update(mf->cloud, NULL));
    for (int c = 0; c < 2; c++)
        if (mf->kd[c]) {
            int rc = pm_kd_update(mf->kd[c], s->approx);
            if (rc)
                return pm_error_prefix(PM_ESIM, "step %ld (t = %.6g s): boundary nodes: ", s->step, s->t);
        }
    if (mf->failed) {
        mf->failed = 0;
        return pm_error_set(PM_ESIM,
                            "step %ld (t = %.6g s): the prescribed boundary values could not be imposed on the "
                            "meshfree coefficients (the boundary rows are nearly singular)",
                            s->step, s->t);
    }
    return PM_OK;
}

int pm_mf_restored(pm_sim *s)
{
    pm_mf *mf = s->mf;
    for (int c = 0; c < 2; c++)
        if (mf->kd[c])
            pm_check(pm_kd_update(mf->kd[c], s->approx));
    return PM_OK;
}

/*
 * GMM nodes move with the material: by the interpolated field at their own position,
 * sum_J N_J(x_I) d_J, not by their coefficient d_I. The two differ by O(h^2 grad^2 u) for
 * non-interpolating functions, and moving by the coefficient would deform the cloud by a map other
 * than the particles', so the shape functions of the next step would see a strain the stresses do
 * not hold (measured on the bending cantilever: a residual at the start of each load step of the
 * order of the load increment itself).
 */
static void move_gmm_nodes(pm_sim *s, const double *d, double scale)
{
    pm_mf *mf = s->mf;
    const size_t nn = s->grid.n_nodes;
    double *dx = mf->g_nodes;
#pragma omp parallel for schedule(dynamic, 256) num_threads(s->nd.n_threads)
    for (size_t I = 0; I < nn; I++) {
        pm_stencil st;
        if (pm_meshfree_eval_node(s->approx, I, &st) != PM_OK) {
            /* LME at a vertex of the cloud's hull, where it interpolates: the coefficient is the value */
            dx[2 * I] = d[2 * I];
            dx[2 * I + 1] = d[2 * I + 1];
            continue;
        }
        dx[2 * I] = dx[2 * I + 1] = 0.0;
        for (int k = 0; k < st.n; k++) {
            dx[2 * I] += st.N[k] * d[2 * (size_t)st.node[k]];
            dx[2 * I + 1] += st.N[k] * d[2 * (size_t)st.node[k] + 1];
        }
    }
    for (size_t k = 0; k < 2 * nn; k++)
        mf->cloud->x[k] += scale * dx[k];
}

/* Points outside the case's grid stop the run as in MPM: the approximation would go on extrapolating
 * from a node cloud the grid's conditions and output no longer describe. */
static int points_inside(const pm_sim *s, long step)
{
    const pm_grid *bg = &s->mf->background;
    const pm_particles *p = &s->p;
    for (size_t i = 0; i < p->n; i++)
        for (int d = 0; d < PM_DIM; d++) {
            const double x = p->x[PM_DIM * i + d];
            if (!(x >= bg->lo[d] && x <= bg->hi[d]))
                return pm_error_set(PM_ESIM, "step %ld (t = %.6g s): particle %zu left the grid at (%.6g, %.6g)", step,
                                    s->t, i, p->x[PM_DIM * i], p->x[PM_DIM * i + 1]);
        }
    return PM_OK;
}

int pm_mf_after_explicit(pm_sim *s, double dt, const double *vel)
{
    pm_check(points_inside(s, s->step));
    pm_mf *mf = s->mf;
    if (mf->rkpm)
        memcpy(mf->cloud->x, s->p.x, 2 * s->p.n * sizeof(double));
    else
        move_gmm_nodes(s, vel, dt);
    return nodes_moved(s);
}

int pm_mf_after_implicit(pm_sim *s, const double *du, const double *v, const double *a)
{
    pm_check(points_inside(s, s->step + 1));
    pm_mf *mf = s->mf;
    if (mf->rkpm)
        memcpy(mf->cloud->x, s->p.x, 2 * s->p.n * sizeof(double));
    else
        move_gmm_nodes(s, du, 1.0);
    memcpy(mf->vh, v, 2 * s->grid.n_nodes * sizeof(double));
    memcpy(mf->ah, a, 2 * s->grid.n_nodes * sizeof(double));
    mf->history = 1;
    return nodes_moved(s);
}

void pm_mf_nodal_history(const pm_sim *s, double *vn, double *an)
{
    const pm_mf *mf = s->mf;
    if (!mf->history)
        return;
    for (size_t I = 0; I < s->grid.n_nodes; I++)
        for (int c = 0; c < 2; c++) {
            if (s->nd.fixed[I] & (1u << c))
                continue;
            vn[2 * I + c] = mf->vh[2 * I + c];
            an[2 * I + c] = mf->ah[2 * I + c];
        }
}

size_t pm_mf_constraint_rows(const pm_sim *s)
{
    if (!s->mf)
        return 0;
    return (s->mf->kd[0] ? pm_kd_size(s->mf->kd[0]) : 0) + (s->mf->kd[1] ? pm_kd_size(s->mf->kd[1]) : 0);
}

/* Constraint row r (the x rows first, then the y rows, the order pm_mf_penalty walks them): its
 * nodes and values; returns their number. */
int pm_mf_constraint_stencil(const pm_sim *s, size_t row, const int32_t **cols, const double **vals)
{
    const pm_mf *mf = s->mf;
    const size_t nx = mf->kd[0] ? pm_kd_size(mf->kd[0]) : 0;
    const pm_kd *kd = row < nx ? mf->kd[0] : mf->kd[1];
    int32_t node;
    return pm_kd_row(kd, row < nx ? row : row - nx, &node, cols, vals);
}

void pm_mf_penalty(pm_sim *s, pm_implicit_ws *w, int want_K)
{
    const pm_mf *mf = s->mf;
    size_t r = w->n;
    for (int c = 0; c < 2; c++) {
        if (!mf->kd[c])
            continue;
        const size_t nb = pm_kd_size(mf->kd[c]);
        for (size_t j = 0; j < nb; j++, r++) {
            int32_t J;
            const int32_t *cols;
            const double *vals;
            const int m = pm_kd_row(mf->kd[c], j, &J, &cols, &vals);
            const double alpha = PM_MF_PENALTY * (w->spring[J] > 0 ? w->spring[J] : 1.0);
            double e = -s->nd.vfix[2 * (size_t)J + c] * w->dt;
            for (int q = 0; q < m; q++)
                e += vals[q] * w->du[2 * (size_t)cols[q] + c];
            w->react[2 * (size_t)J + c] = -alpha * e;
            for (int a = 0; a < m; a++) {
                const int row = w->dof[2 * (size_t)cols[a] + c];
                if (row < 0)
                    continue;
                w->res[row] -= alpha * vals[a] * e;
                w->fscale[2 * (size_t)cols[a] + c] += fabs(alpha * vals[a] * e);
                if (!want_K)
                    continue;
                for (int b = 0; b < m; b++) {
                    const int col = w->dof[2 * (size_t)cols[b] + c];
                    const int at = col >= 0 ? pm_csr_find(&w->K, row, col) : -1;
                    if (at >= 0)
                        w->K.val[at] += alpha * vals[a] * vals[b];
                }
            }
        }
    }
}
