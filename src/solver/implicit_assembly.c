/*
 * Implicit solver, the start of a step and the assembly: nodal mass, velocity and acceleration
 * projected from the particles (seed 000 Algorithm 1, initial phase), the unknowns, the sparse
 * pattern from the particles' stencils, and the residual and tangent of the UL-FEM phase:
 *   r = f_ext - f_int - M a,    K = sum_p V_p (B^T D B + G^T sigma G) + M / (beta dt^2).
 */
#include "implicit_internal.h"
#include "meshfree_internal.h"

#include "contact/contact.h"

#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/*
 * Quasi-static stabilisation. Without inertia nothing holds a node whose particles give it no
 * stiffness of its own, and a particle that has just crossed into a new cell makes exactly such
 * nodes: its far nodes carry a sliver of support, and with one particle the cell has a zero-strain
 * (rotation-like) mode whose only stiffness is the geometric one, of either sign. Newton then
 * stalls or wanders. Two deliberate measures:
 *  - weak nodes (touched by a single particle, or with support sum V_p N_I below PM_WEAK_SUPPORT
 *    of the volume of the particles they touch, where a node inside full cells has about 1/4 of it)
 *    are tied by a spring of stiffness PM_WEAK_SPRING * M * (volume of the particles they touch) / h^2
 *    (M the largest P-wave modulus), in residual and tangent, to the affine extrapolation of the
 *    increments of the particles touching them (weak_springs()). It used to tie them to their
 *    start-of-step position, which resists the motion itself: the spring force grew with the load
 *    step's displacement and stayed in the converged state (bspline2 cantilever in one load step 20 %
 *    too stiff, the answer depending on the step count). Against the affine extrapolation it resists
 *    only the nodal mode the particles do not see, and its force vanishes for any locally affine
 *    increment (translation, finite rotation, uniform strain);
 *  - every node gets PM_QS_SPRING times that stiffness scale in the tangent only (no effect on the
 *    converged state), so the tangent is never exactly singular.
 * Iterations where the tangent still misleads add a larger tangent-only spring of the same shape for
 * that iteration (implicit.c).
 */
#define PM_QS_SPRING 1e-10
#define PM_WEAK_SUPPORT 0.025
#define PM_WEAK_SPRING 1e-6

static void *grow(void *ptr, size_t count, size_t size)
{
    return realloc(ptr, (count ? count : 1) * size);
}

double pm_implicit_mass_floor(const pm_sim *s)
{
    return s->p.n ? 1e-12 * s->p.mass[0] : 0.0;
}

int pm_implicit_ws_alloc(pm_sim *s)
{
    pm_implicit_ws *w = calloc(1, sizeof *w);
    if (!w)
        return pm_error_set(PM_ENOMEM, "out of memory for the implicit solver");
    s->implicit = w;
    const size_t n = s->p.n, nn = s->grid.n_nodes, ns = s->p.n_state;
    w->n = n;
    w->nn = nn;
    w->st_cap = 4 * n;
    w->stress_n = malloc((PM_NS * n + 1) * sizeof(double));
    w->F_n = malloc((PM_NF * n + 1) * sizeof(double));
    w->state_n = malloc((ns * n + 1) * sizeof(double));
    w->vol_n = malloc((n + 1) * sizeof(double));
    w->x_n = malloc((2 * n + 1) * sizeof(double));
    w->eps_n = malloc((n + 1) * sizeof(double));
    w->n_rows = n + pm_mf_constraint_rows(s); /* meshfree constraint rows after the particles */
    w->st_off = malloc((w->n_rows + 1) * sizeof(int32_t));
    w->st_node = malloc(w->st_cap * sizeof(int32_t) + 1);
    w->st_N = malloc(w->st_cap * sizeof(double) + 1);
    w->st_dN = malloc(2 * w->st_cap * sizeof(double) + 1);
    w->np_idx = malloc(w->st_cap * sizeof(int32_t) + 1);
    w->dof = malloc(2 * nn * sizeof(int32_t));
    w->support = malloc(nn * sizeof(double));
    w->spring = calloc(nn, sizeof(double));
    w->touch = calloc(nn, sizeof(double));
    w->smax = calloc(nn, sizeof(double));
    w->anchor = calloc(nn, sizeof(double));
    w->np_off = malloc((nn + 1) * sizeof(int32_t));
    w->mark = malloc(nn * sizeof(int32_t));
    w->nbr = malloc(nn * sizeof(int32_t));
    double **v2[] = {&w->du, &w->vn, &w->an, &w->fint, &w->fext, &w->react, &w->res, &w->sol, &w->du_try, &w->res_base, &w->fscale};
    for (size_t k = 0; k < sizeof v2 / sizeof v2[0]; k++)
        *v2[k] = calloc(2 * nn, sizeof(double));
    if (!w->stress_n || !w->F_n || !w->state_n || !w->vol_n || !w->x_n || !w->eps_n || !w->st_off ||
        !w->st_node || !w->st_N || !w->st_dN || !w->np_idx || !w->dof || !w->support || !w->spring || !w->touch || !w->smax || !w->anchor ||
        !w->np_off || !w->mark || !w->nbr || !w->du || !w->vn || !w->an || !w->fint || !w->fext ||
        !w->react || !w->res || !w->sol || !w->du_try || !w->res_base || !w->fscale)
        return pm_error_set(PM_ENOMEM, "out of memory for the implicit solver (%zu particles, %zu nodes)", n, nn);
    pm_check(pm_sparse_solver_create(&w->solver));
    return PM_OK;
}

void pm_implicit_free(pm_sim *s)
{
    pm_implicit_ws *w = s->implicit;
    if (!w)
        return;
    void *arrays[] = {w->stress_n, w->F_n, w->state_n, w->vol_n, w->x_n, w->eps_n, w->st_off, w->st_node,
                      w->st_N, w->st_dN, w->np_idx, w->dof, w->support, w->spring, w->touch, w->smax, w->anchor, w->np_off, w->mark,
                      w->nbr, w->du, w->vn, w->an, w->fint, w->fext, w->react, w->res, w->sol, w->du_try, w->res_base, w->K_base, w->fscale};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    pm_csr_free(&w->K);
    pm_sparse_solver_destroy(w->solver);
    free(w);
    s->implicit = NULL;
}

/* Room for at least cap packed stencil entries. */
static int reserve_stencils(pm_implicit_ws *w, size_t cap)
{
    if (cap <= w->st_cap)
        return PM_OK;
    int32_t *nd = grow(w->st_node, cap, sizeof *nd);
    if (nd)
        w->st_node = nd;
    double *Nv = nd ? grow(w->st_N, cap, sizeof *Nv) : NULL;
    if (Nv)
        w->st_N = Nv;
    double *dv = Nv ? grow(w->st_dN, 2 * cap, sizeof *dv) : NULL;
    if (dv)
        w->st_dN = dv;
    int32_t *ix = dv ? grow(w->np_idx, cap, sizeof *ix) : NULL;
    if (!ix)
        return pm_error_set(PM_ENOMEM, "out of memory for particle stencils");
    w->np_idx = ix;
    w->st_cap = cap;
    return PM_OK;
}

/* Shape functions of every particle at its start-of-step position, packed (then the meshfree
 * constraint rows, which only shape the sparse pattern). */
static int store_stencils(pm_sim *s, pm_implicit_ws *w)
{
    size_t off = 0;
    pm_stencil st;
    for (size_t i = 0; i < w->n; i++) {
        if (s->approx->ops->eval(s->approx, &s->p, i, &st) != PM_OK)
            return pm_error_prefix(PM_ESIM, "step %ld: ", s->step + 1);
        /* wider stencils than the first guess (B-splines, LME, meshfree): grow once */
        if (off + (size_t)st.n > w->st_cap)
            pm_check(reserve_stencils(w, 2 * (off + (size_t)st.n) + (w->n_rows - i) * (size_t)st.n));
        w->st_off[i] = (int32_t)off;
        for (int k = 0; k < st.n; k++) {
            w->st_node[off + k] = st.node[k];
            w->st_N[off + k] = st.N[k];
            w->st_dN[2 * (off + k)] = st.dN[k][0];
            w->st_dN[2 * (off + k) + 1] = st.dN[k][1];
        }
        off += (size_t)st.n;
    }
    for (size_t r = w->n; r < w->n_rows; r++) {
        const int32_t *cols;
        const double *vals;
        const int m = pm_mf_constraint_stencil(s, r - w->n, &cols, &vals);
        w->st_off[r] = (int32_t)off;
        if (off + (size_t)m > w->st_cap)
            pm_check(reserve_stencils(w, 2 * (off + (size_t)m) + (w->n_rows - r) * PM_STENCIL_MAX));
        memcpy(w->st_node + off, cols, (size_t)m * sizeof *cols);
        memcpy(w->st_N + off, vals, (size_t)m * sizeof *vals);
        memset(w->st_dN + 2 * off, 0, 2 * (size_t)m * sizeof(double));
        off += (size_t)m;
    }
    w->st_off[w->n_rows] = (int32_t)off;
    return PM_OK;
}

/* Nodal mass, velocity, acceleration, support and external force; prescribed components. */
static void project(pm_sim *s, pm_implicit_ws *w)
{
    const pm_particles *p = &s->p;
    const size_t nn = w->nn;
    double *mass = s->nd.mass;
    double g[2];
    pm_sim_gravity(s, s->t + w->dt, g);
    memset(mass, 0, nn * sizeof(double));
    memset(w->support, 0, nn * sizeof(double));
    memset(w->touch, 0, nn * sizeof(double));
    memset(w->smax, 0, nn * sizeof(double));
    memset(w->vn, 0, 2 * nn * sizeof(double));
    memset(w->an, 0, 2 * nn * sizeof(double));
    memset(w->fext, 0, 2 * nn * sizeof(double));
    for (size_t i = 0; i < w->n; i++) {
        const double m = p->mass[i], V = p->vol[i];
        const double *v = p->v + 2 * i, *a = p->a + 2 * i, *sg = p->stress + PM_NS * i;
        const double sabs = fabs(sg[0]) + fabs(sg[1]) + fabs(sg[2]) + 2 * fabs(sg[3]);
        for (int32_t k = w->st_off[i]; k < w->st_off[i + 1]; k++) {
            const int32_t I = w->st_node[k];
            const double mN = m * w->st_N[k];
            mass[I] += mN;
            w->support[I] += V * w->st_N[k];
            w->touch[I] += V;
            w->smax[I] = fmax(w->smax[I], sabs);
            w->vn[2 * I] += mN * v[0];
            w->vn[2 * I + 1] += mN * v[1];
            w->an[2 * I] += mN * a[0];
            w->an[2 * I + 1] += mN * a[1];
            w->fext[2 * I] += mN * g[0];
            w->fext[2 * I + 1] += mN * g[1];
        }
    }
    const double floor = pm_implicit_mass_floor(s);
    for (size_t I = 0; I < nn; I++) {
        const int on = mass[I] > floor;
        for (int c = 0; c < 2; c++) {
            const size_t k = 2 * I + c;
            if (on) {
                w->vn[k] /= mass[I];
                w->an[k] /= mass[I];
            }
            if (w->quasi_static)
                w->vn[k] = w->an[k] = 0.0;
            if (s->nd.fixed[I] & (1u << c)) {
                /* a prescribed component moves with its velocity: no Newmark acceleration there */
                w->vn[k] = s->nd.vfix[k];
                w->an[k] = 0.0;
            }
        }
    }
    /* GMM and RKPM nodes keep their own velocity and acceleration from the last step (seed 000
     * Algorithm 2: the predictor uses the nodal values of the previous step, as in FEM) */
    if (s->mf && !w->quasi_static)
        pm_mf_nodal_history(s, w->vn, w->an);
}

/* Unknowns: the free components of nodes that carry material, numbered node by node. */
static void number_dofs(pm_sim *s, pm_implicit_ws *w)
{
    const double floor = pm_implicit_mass_floor(s);
    int nd = 0;
    for (size_t I = 0; I < w->nn; I++)
        for (int c = 0; c < 2; c++) {
            const size_t k = 2 * I + c;
            const int fixed = (s->nd.fixed[I] >> c) & 1u;
            w->du[k] = fixed ? s->nd.vfix[k] * w->dt : 0.0;
            w->dof[k] = (s->nd.mass[I] > floor && !fixed) ? nd++ : -1;
        }
    w->n_dof = nd;
}

static void stabilisation(pm_sim *s, pm_implicit_ws *w)
{
    double M = 0;
    for (size_t k = 0; k < s->c->n_materials; k++) {
        const pm_material *m = &s->c->materials[k];
        M = fmax(M, m->K + 4.0 * m->G / 3.0);
    }
    if (!(M > 0))
        M = 1.0; /* models without an elastic pair: scale by a unit modulus */
    const double h2 = s->grid.h_min * s->grid.h_min;
    for (size_t I = 0; I < w->nn; I++) {
        w->spring[I] = M * w->touch[I] / h2;
        const int few = w->np_off[I + 1] - w->np_off[I] < 2;
        const int weak = w->quasi_static && (few || w->support[I] < PM_WEAK_SUPPORT * w->touch[I]);
        w->anchor[I] = weak ? PM_WEAK_SPRING * w->spring[I] : 0.0;
    }
}

static void sort_ints(int32_t *a, int n)
{
    for (int i = 1; i < n; i++) {
        const int32_t v = a[i];
        int j = i - 1;
        while (j >= 0 && a[j] > v) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = v;
    }
}

/* Nodes sharing a particle with node I that have unknowns, sorted; returns their count. */
static int neighbours(const pm_implicit_ws *w, int32_t I)
{
    int cnt = 0;
    for (int32_t q = w->np_off[I]; q < w->np_off[I + 1]; q++) {
        const int32_t i = w->np_idx[q];
        for (int32_t k = w->st_off[i]; k < w->st_off[i + 1]; k++) {
            const int32_t J = w->st_node[k];
            if (w->mark[J] == I || (w->dof[2 * J] < 0 && w->dof[2 * J + 1] < 0))
                continue;
            w->mark[J] = I;
            w->nbr[cnt++] = J;
        }
    }
    sort_ints(w->nbr, cnt);
    return cnt;
}

/* CSR pattern of the unknowns: (I, c) couples with (J, d) when a particle's stencil holds I and J. */
static int build_pattern(pm_implicit_ws *w)
{
    const size_t nn = w->nn;
    memset(w->np_off, 0, (nn + 1) * sizeof(int32_t));
    const int32_t ntot = w->st_off[w->n_rows];
    for (int32_t k = 0; k < ntot; k++)
        w->np_off[w->st_node[k] + 1]++;
    for (size_t I = 0; I < nn; I++)
        w->np_off[I + 1] += w->np_off[I];
    for (size_t I = 0; I < nn; I++)
        w->mark[I] = w->np_off[I]; /* fill cursor */
    for (size_t i = 0; i < w->n_rows; i++)
        for (int32_t k = w->st_off[i]; k < w->st_off[i + 1]; k++)
            w->np_idx[w->mark[w->st_node[k]]++] = (int32_t)i;
    for (size_t I = 0; I < nn; I++)
        w->mark[I] = -1;
    size_t nnz = 0;
    for (size_t I = 0; I < nn; I++) {
        const int rows = (w->dof[2 * I] >= 0) + (w->dof[2 * I + 1] >= 0);
        if (!rows)
            continue;
        const int cnt = neighbours(w, (int32_t)I);
        size_t cols = 0;
        for (int q = 0; q < cnt; q++)
            cols += (size_t)((w->dof[2 * w->nbr[q]] >= 0) + (w->dof[2 * w->nbr[q] + 1] >= 0));
        nnz += (size_t)rows * cols;
    }
    if (nnz > (size_t)INT32_MAX)
        return pm_error_set(PM_ENOMEM, "the implicit system has %zu entries: too many for 32-bit indices", nnz);
    pm_check(pm_csr_reserve(&w->K, w->n_dof, nnz));
    for (size_t I = 0; I < nn; I++)
        w->mark[I] = -1;
    int pos = 0;
    for (size_t I = 0; I < nn; I++) {
        if (w->dof[2 * I] < 0 && w->dof[2 * I + 1] < 0)
            continue;
        const int cnt = neighbours(w, (int32_t)I);
        for (int c = 0; c < 2; c++) {
            const int row = w->dof[2 * I + c];
            if (row < 0)
                continue;
            w->K.rowptr[row] = pos;
            for (int q = 0; q < cnt; q++)
                for (int d = 0; d < 2; d++) {
                    const int col = w->dof[2 * w->nbr[q] + d];
                    if (col >= 0)
                        w->K.col[pos++] = col;
                }
        }
    }
    w->K.rowptr[w->n_dof] = pos;
    w->K.nnz = pos;
    return PM_OK;
}

int pm_implicit_setup_step(pm_sim *s, pm_implicit_ws *w)
{
    pm_particles *p = &s->p;
    memcpy(w->stress_n, p->stress, PM_NS * w->n * sizeof(double));
    memcpy(w->F_n, p->F, PM_NF * w->n * sizeof(double));
    memcpy(w->state_n, p->state, p->n_state * w->n * sizeof(double));
    memcpy(w->vol_n, p->vol, w->n * sizeof(double));
    memcpy(w->x_n, p->x, 2 * w->n * sizeof(double));
    memcpy(w->eps_n, p->eps_p, w->n * sizeof(double));
    pm_check(store_stencils(s, w));
    project(s, w);
    number_dofs(s, w);
    pm_check(build_pattern(w));
    stabilisation(s, w);
    pm_sparse_solver_new_pattern(w->solver);
    return PM_OK;
}

/* Add the 2x2 block k[c][d] of nodes (I, J) to the tangent. */
static void add_block(pm_implicit_ws *w, int32_t I, int32_t J, const double k[2][2])
{
    for (int c = 0; c < 2; c++) {
        const int row = w->dof[2 * I + c];
        if (row < 0)
            continue;
        for (int d = 0; d < 2; d++) {
            const int col = w->dof[2 * J + d];
            if (col < 0)
                continue;
            const int at = pm_csr_find(&w->K, row, col);
            if (at >= 0)
                w->K.val[at] += k[c][d];
        }
    }
}

/* f_int and (when want_K) B^T D B + G^T sigma G of one point. */
static void add_point(pm_implicit_ws *w, const int32_t *node, const pm_point_contrib *c, int want_K)
{
    const double V = c->V, *sg = c->sig, *D = c->D;
    for (int a = 0; a < c->n; a++) {
        const int32_t I = node[a];
        const double gx = c->g[a][0], gy = c->g[a][1], h = c->hoop[a];
        w->fint[2 * I] += V * (gx * sg[0] + gy * sg[3] + h * sg[2]);
        w->fint[2 * I + 1] += V * (gy * sg[1] + gx * sg[3]);
        w->fscale[2 * I] += V * (fabs(gx * sg[0]) + fabs(gy * sg[3]) + fabs(h * sg[2]));
        w->fscale[2 * I + 1] += V * (fabs(gy * sg[1]) + fabs(gx * sg[3]));
    }
    if (!want_K)
        return;
    /* D B_b for both columns of every node b: rows (xx, yy, zz, xy) */
    double DB[PM_STENCIL_MAX][2][4];
    for (int b = 0; b < c->n; b++) {
        const double gx = c->g[b][0], gy = c->g[b][1], h = c->hoop[b];
        for (int r = 0; r < 4; r++) {
            DB[b][0][r] = D[4 * r] * gx + D[4 * r + 2] * h + D[4 * r + 3] * gy;
            DB[b][1][r] = D[4 * r + 1] * gy + D[4 * r + 3] * gx;
        }
    }
    for (int a = 0; a < c->n; a++) {
        const double gx = c->g[a][0], gy = c->g[a][1], h = c->hoop[a];
        const double sgx = sg[0] * gx + sg[3] * gy, sgy = sg[3] * gx + sg[1] * gy;
        for (int b = 0; b < c->n; b++) {
            const double geo = V * (sgx * c->g[b][0] + sgy * c->g[b][1]);
            double k[2][2];
            for (int d = 0; d < 2; d++) {
                k[0][d] = V * (gx * DB[b][d][0] + h * DB[b][d][2] + gy * DB[b][d][3]);
                k[1][d] = V * (gy * DB[b][d][1] + gx * DB[b][d][3]);
            }
            k[0][0] += geo + V * sg[2] * h * c->hoop[b];
            k[1][1] += geo;
            add_block(w, node[a], node[b], k);
        }
    }
}

void pm_implicit_regularise(pm_implicit_ws *w, double lambda)
{
    for (size_t k = 0; k < 2 * w->nn; k++) {
        const int row = w->dof[k];
        if (row < 0)
            continue;
        const int at = pm_csr_find(&w->K, row, row);
        if (at >= 0)
            w->K.val[at] += lambda * w->spring[k / 2];
    }
}

/*
 * The weak-node springs (see the top of the file): for every particle p touching weak node I, the
 * energy 1/2 k_p |d_p|^2 with d_p = du_I - (u_p + H_p (x_I - x_p)), the node's increment against the
 * affine extrapolation of the particle's own increment (u_p = sum N_J du_J, H_p = sum du_J dN_J).
 * d_p is linear in du, d_p = sum_J a_J du_J with a_J = delta_IJ - N_J - dN_J . (x_I - x_p), and
 * vanishes for every affine increment field (translation, the increment of a finite rotation,
 * uniform strain), so the spring only resists what the particles cannot see: the motion of a node
 * relative to the material it hangs on.
 */
static void weak_springs(pm_sim *s, pm_implicit_ws *w, int want_K)
{
    const double *X = s->grid.x;
    for (size_t I = 0; I < w->nn; I++) {
        if (!(w->anchor[I] > 0))
            continue;
        for (int32_t q = w->np_off[I]; q < w->np_off[I + 1]; q++) {
            const int32_t i = w->np_idx[q];
            if ((size_t)i >= w->n)
                continue; /* meshfree constraint rows */
            const int32_t o0 = w->st_off[i], m = w->st_off[i + 1] - o0;
            const int32_t *node = w->st_node + o0;
            const double *N = w->st_N + o0, *dN = w->st_dN + 2 * (size_t)o0, *xp = w->x_n + 2 * i;
            const double kp = w->anchor[I] * w->vol_n[i] / w->touch[I];
            const double rx = X[2 * I] - xp[0], ry = X[2 * I + 1] - xp[1];
            double a[PM_STENCIL_MAX], d[2] = {0, 0};
            for (int k = 0; k < m; k++) {
                a[k] = (node[k] == (int32_t)I) - N[k] - dN[2 * k] * rx - dN[2 * k + 1] * ry;
                d[0] += a[k] * w->du[2 * node[k]];
                d[1] += a[k] * w->du[2 * node[k] + 1];
            }
            for (int k = 0; k < m; k++)
                for (int c = 0; c < 2; c++) {
                    const double f = kp * a[k] * d[c];
                    w->fint[2 * node[k] + c] += f;
                    w->fscale[2 * node[k] + c] += fabs(f);
                }
            if (!want_K)
                continue;
            for (int k = 0; k < m; k++)
                for (int l = 0; l < m; l++) {
                    const double kk = kp * a[k] * a[l];
                    const double blk[2][2] = {{kk, 0}, {0, kk}};
                    add_block(w, node[k], node[l], blk);
                }
        }
    }
}

int pm_implicit_evaluate(pm_sim *s, pm_implicit_ws *w, int want_K)
{
    const size_t nn = w->nn;
    memset(w->fint, 0, 2 * nn * sizeof(double));
    memset(w->fscale, 0, 2 * nn * sizeof(double));
    if (want_K)
        memset(w->K.val, 0, (size_t)w->K.nnz * sizeof(double));
    w->failed_particle = -1;
    pm_point_contrib c;
    for (size_t i = 0; i < w->n; i++) {
        if (pm_implicit_point(s, w, i, w->du, want_K, &c)) {
            w->failed_particle = (long)i;
            return 1;
        }
        add_point(w, w->st_node + w->st_off[i], &c, want_K);
    }
    weak_springs(s, w, want_K);
    pm_contact_implicit(s->contact, s->nd.mass, pm_implicit_mass_floor(s), w, want_K);
    const double *mass = s->nd.mass, dt = w->dt;
    const double c0 = w->quasi_static ? 0.0 : 4.0 / (dt * dt);
    const double kappa = w->quasi_static ? PM_QS_SPRING : 0.0;
    for (size_t I = 0; I < nn; I++)
        for (int d = 0; d < 2; d++) {
            const size_t k = 2 * I + d;
            /* Newmark, beta = 1/4: a_{n+1} = 4 / dt^2 (du - dt v_n) - a_n */
            const double acc = w->quasi_static ? 0.0 : c0 * (w->du[k] - dt * w->vn[k]) - w->an[k];
            const double r = w->fext[k] - w->fint[k] - mass[I] * acc;
            w->fscale[k] += fabs(mass[I] * acc) + fabs(w->fext[k]);
            const int row = w->dof[k];
            if (row >= 0) {
                w->res[row] = r;
                if (want_K) {
                    const int at = pm_csr_find(&w->K, row, row);
                    if (at >= 0)
                        w->K.val[at] += mass[I] * c0 + kappa * w->spring[I];
                }
            } else {
                w->react[k] = -r;
            }
        }
    if (s->mf && w->n_rows > w->n)
        pm_mf_penalty(s, w, want_K);
    return 0;
}
