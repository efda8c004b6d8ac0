/* Setting up a simulation from a case: grid, approximation, particles, nodal arrays; its boundary
 * conditions (boundary.c) and contact surfaces (src/contact). */
#include "sim_internal.h"
#include "mesh/density.h"
#include "pmech/error.h"
#include "solver/implicit.h"

#include "boundary.h"
#include "contact/contact.h"
#include "solver/loads.h"
#include "contact/multibody.h"
#include "flow.h"
#include "core/seed.h"
#include "fbar.h"
#include "xpic.h"
#include "meshfree_internal.h"
#include "point_update.h"
#include "scatter.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int build_grid(const pm_case *c, pm_grid *g)
{
    if (c->grid.type == PM_GRID_GMSH) {
        int rc = pm_grid_gmsh_read(g, c->grid.file);
        if (rc)
            return pm_error_prefix(rc, "%s: grid.file: ", c->file);
        if (c->formulation == PM_AXISYMMETRIC && g->lo[0] < -1e-9 * g->h_min)
            return pm_error_set(PM_EINPUT,
                                "%s: grid.file: in an axisymmetric run x is the radius, so the mesh must lie in "
                                "x >= 0; its nodes reach x = %g",
                                c->file, g->lo[0]);
        /* MPM only: the meshfree methods take their nodal spacing from the mesh as given */
        if (c->grid.lattice && c->method == PM_METHOD_MPM && (rc = pm_grid_adopt_lattice(g)) < 0)
            return pm_error_prefix(rc, "%s: grid.file: ", c->file);
        return PM_OK;
    }
    if (c->grid.type != PM_GRID_RECTANGLE)
        return pm_error_set(PM_EINPUT, "%s: grid.type: only 'rectangle' and 'gmsh' grids are available", c->file);
    if (c->formulation == PM_AXISYMMETRIC && c->grid.origin[0] < 0)
        return pm_error_set(PM_EINPUT,
                            "%s: grid.origin: in an axisymmetric run x is the radius, so the grid must lie in "
                            "x >= 0; got origin x = %g",
                            c->file, c->grid.origin[0]);
    int rc = pm_grid_rectangle(g, c->grid.origin, c->grid.size, c->grid.cells, (pm_element)c->grid.element);
    if (rc)
        return pm_error_prefix(rc, "%s: grid: ", c->file);
    return PM_OK;
}

/* PMECH_SCATTER picks the strategy so that both can be measured and compared on the same build. A
 * misspelt value is an error rather than the default: a measurement would otherwise silently time
 * the other strategy. Unset or empty means "colour". */
static int scatter_strategy(pm_scatter *out)
{
    const char *e = getenv("PMECH_SCATTER");
    *out = PM_SCATTER_COLOUR;
    if (!e || !*e || strcmp(e, "colour") == 0)
        return PM_OK;
    if (strcmp(e, "buffers") == 0) {
        *out = PM_SCATTER_BUFFERS;
        return PM_OK;
    }
    return pm_error_set(PM_EINPUT, "environment variable PMECH_SCATTER=\"%s\": allowed values are \"colour\" and "
                        "\"buffers\"", e);
}

/* Per-thread copies of the nodal arrays only where a scatter may need them: colouring needs none. */
static int alloc_nodal(pm_nodal *nd, size_t nn, int n_threads, int need_buffers)
{
    nd->mass = calloc(nn, sizeof(double));
    nd->mom = calloc(PM_DIM * nn, sizeof(double));
    nd->vel = calloc(PM_DIM * nn, sizeof(double));
    nd->vel_new = calloc(PM_DIM * nn, sizeof(double));
    nd->force = calloc(PM_DIM * nn, sizeof(double));
    nd->acc = calloc(PM_DIM * nn, sizeof(double));
    nd->vel_strain = calloc(PM_DIM * nn, sizeof(double));
    nd->fixed = calloc(nn, 1);
    nd->vfix = calloc(PM_DIM * nn, sizeof(double));
    nd->n_all = nn;
    nd->n_threads = n_threads < 1 ? 1 : n_threads;
    if (nd->n_threads > 1 && need_buffers)
        nd->scratch = calloc((size_t)(nd->n_threads - 1) * PM_SCATTER_WIDTH * nn, sizeof(double));
    if (!nd->mass || !nd->mom || !nd->vel || !nd->vel_new || !nd->force || !nd->acc || !nd->vel_strain || !nd->fixed ||
        !nd->vfix || (nd->n_threads > 1 && need_buffers && !nd->scratch))
        return pm_error_set(PM_ENOMEM, "cannot allocate nodal arrays for %zu nodes", nn);
    return PM_OK;
}

static void free_nodal(pm_nodal *nd)
{
    free(nd->mass);
    free(nd->mom);
    free(nd->vel);
    free(nd->vel_new);
    free(nd->force);
    free(nd->acc);
    free(nd->vel_strain);
    free(nd->fixed);
    free(nd->vfix);
    free(nd->scratch);
    free(nd->timed);
    memset(nd, 0, sizeof *nd);
}

static size_t max_state(const pm_case *c)
{
    size_t n = 0;
    for (size_t m = 0; m < c->n_materials; m++)
        if (c->materials[m].ops->n_state > n)
            n = c->materials[m].ops->n_state;
    return n;
}

int pm_sim_create(const pm_case *c, pm_sim **out, int n_threads)
{
    *out = NULL;
    pm_sim *s = calloc(1, sizeof *s);
    if (!s)
        return pm_error_set(PM_ENOMEM, "out of memory");
    s->c = c;
    int rc = build_grid(c, &s->grid);
    if (rc)
        goto fail;
    const int meshfree = c->method != PM_METHOD_MPM;
    if (!meshfree) {
        pm_approx_opts aopts = {.lme_gamma = c->lme_gamma, .support_radius = c->support_radius};
        rc = pm_approx_create_opts(c->shape_function, &s->grid, &aopts, &s->approx);
        if (rc) {
            pm_error_prefix(rc, "%s: shape_function: ", c->file);
            goto fail;
        }
        s->approx->n_threads = n_threads < 1 ? 1 : n_threads;
        s->approx->fast_linear_quad = s->approx->ops->linear_quad_fast && s->grid.structured &&
                                      s->grid.element == PM_QUAD4;
        if ((rc = pm_multibody_create(c, s->grid.n_nodes, &s->mb)) != 0)
            goto fail;
        /* the inline linear-quad passes number a cell's nodes themselves, in one field */
        if (s->mb)
            s->approx->fast_linear_quad = 0;
    }
    if ((rc = scatter_strategy(&s->scatter)) != 0)
        goto fail;
    if (meshfree || !s->approx->fast_linear_quad)
        s->scatter = PM_SCATTER_BUFFERS; /* the row blocks need a structured grid's rows and 2 x 2 stencils */
    s->blocks = malloc((2 * (size_t)(n_threads < 1 ? 1 : n_threads) + 1) * sizeof(size_t));
    size_t *per_body = calloc(c->n_bodies ? c->n_bodies : 1, sizeof(size_t)), total = 0;
    if (!per_body) {
        rc = pm_error_set(PM_ENOMEM, "out of memory");
        goto fail;
    }
    rc = pm_seed_count(c, &s->grid, per_body, &total);
    free(per_body);
    size_t room = 0; /* for what the sources release */
    if (rc || (rc = pm_flow_create(c, &s->grid, max_state(c), &s->flow, &room)) != 0)
        goto fail;
    if ((rc = pm_particles_alloc_capacity(&s->p, total, total + room, max_state(c))) != 0 ||
        (c->analysis.transfer == PM_TRANSFER_APIC && (rc = pm_particles_enable_affine(&s->p)) != 0) ||
        (rc = pm_seed_fill(c, &s->grid, &s->p)) != 0 || (meshfree && (rc = pm_mf_create(s, n_threads)) != 0) ||
        (rc = alloc_nodal(&s->nd, s->grid.n_nodes * (s->mb ? (size_t)s->mb->n_fields : 1), n_threads,
                          s->scatter == PM_SCATTER_BUFFERS)) != 0 ||
        (rc = pm_bc_setup(c, &s->grid, &s->nd)) != 0 ||
        (rc = pm_contact_create(c, &s->grid, pm_sim_frame_grid(s), &s->contact)) != 0 ||
        /* one field: the friction sides (MPM) and walls (GMM) act where the material touches them
         * (src/contact/friction.c); RKPM's walls act node by node (pm_contact_takes_points says why) */
        (!s->mb && c->method != PM_METHOD_RKPM &&
         (rc = pm_contact_points_reserve(s->contact, &s->grid, s->p.cap)) != 0) ||
        (s->mb && (rc = pm_multibody_attach_surfaces(s->mb, pm_contact_n_surfaces(s->contact))) != 0) ||
        (rc = pm_fbar_create(s)) != 0 || (rc = pm_xpic_create(s)) != 0 ||
        (meshfree && (rc = pm_mf_setup_conditions(s)) != 0))
        goto fail;
    if (s->mb)
        pm_multibody_copy_conditions(s->mb, &s->nd);
    /* meshfree points are not binned by cell, and RKPM's particles are its nodes: never reordered */
    s->sort_interval = meshfree ? 0 : 50;
    s->perm = malloc((s->p.cap ? s->p.cap : 1) * sizeof(uint32_t));
    s->bucket = malloc((s->grid.n_cells + 1) * sizeof(uint32_t));
    s->scratch = malloc((s->p.cap ? s->p.cap : 1) * sizeof(double));
    s->iscratch = malloc((s->p.cap ? s->p.cap : 1) * sizeof(int32_t));
    if (!s->perm || !s->bucket || !s->scratch || !s->iscratch || !s->blocks) {
        rc = pm_error_set(PM_ENOMEM, "out of memory for the particle sort workspace");
        goto fail;
    }
    if (c->analysis.density_from_positions) {
        s->rho_node = malloc(s->grid.n_nodes * sizeof(double));
        s->rho_p = malloc((s->p.cap ? s->p.cap : 1) * sizeof(double));
        s->rho_work = malloc((s->grid.n_nodes + s->grid.n_cells) * sizeof(double));
        if (!s->rho_node || !s->rho_p || !s->rho_work) {
            rc = pm_error_set(PM_ENOMEM, "out of memory for the density from positions");
            goto fail;
        }
    }
    rc = s->approx->ops->connect(s->approx, &s->p);
    if (rc) {
        pm_error_prefix(PM_EINPUT, "%s: at t = 0: ", c->file);
        rc = PM_EINPUT;
        goto fail;
    }
    if ((rc = pm_flow_start(s)) != 0 || (rc = pm_loads_create(s, &s->loads)) != 0)
        goto fail;
    s->dt_next = c->analysis.dt > 0 ? c->analysis.dt : pm_sim_stable_dt(s);
    *out = s;
    return PM_OK;
fail:
    pm_sim_destroy(s);
    return rc;
}

void pm_sim_destroy(pm_sim *s)
{
    if (!s)
        return;
    pm_implicit_free(s);
    pm_fbar_destroy(s);
    free(s->xpic);
    pm_approx_destroy(s->approx);
    pm_mf_destroy(s);
    pm_particles_free(&s->p);
    free(s->perm);
    free(s->bucket);
    free(s->blocks);
    free(s->rho_node);
    free(s->rho_p);
    free(s->rho_work);
    free(s->scratch);
    free(s->iscratch);
    free_nodal(&s->nd);
    pm_contact_destroy(s->contact);
    pm_multibody_destroy(s->mb);
    pm_flow_destroy(s->flow);
    pm_loads_destroy(s->loads);
    pm_grid_free(&s->grid);
    free(s);
}

const pm_grid *pm_sim_frame_grid(const pm_sim *s)
{
    return s->mf ? &s->mf->background : &s->grid;
}

const pm_particles *pm_sim_particles(const pm_sim *s)
{
    return &s->p;
}

const pm_grid *pm_sim_grid(const pm_sim *s)
{
    return &s->grid;
}

double pm_sim_time(const pm_sim *s)
{
    return s->t;
}

long pm_sim_steps(const pm_sim *s)
{
    return s->step;
}

int pm_sim_advance(pm_sim *s, double dt)
{
    return s->c->analysis.type == PM_ANALYSIS_EXPLICIT ? pm_explicit_step(s, dt)
                                                        : pm_implicit_step(s, dt, NULL, NULL);
}

void pm_sim_gravity(const pm_sim *s, double t, double g[2])
{
    const double *g0 = s->c->analysis.gravity;
    double tr = s->c->analysis.gravity_ramp_time, f = 1.0;
    if (s->c->analysis.type == PM_ANALYSIS_QUASI_STATIC)
        f = fmin(1.0, t / s->c->analysis.end_time); /* the load grows with the pseudo-time */
    else if (tr > 0 && t < tr)
        f = 0.5 * (1.0 - cos(M_PI * t / tr));
    g[0] = f * g0[0];
    g[1] = f * g0[1];
}

double pm_sim_stable_dt(const pm_sim *s)
{
    const pm_particles *p = &s->p;
    double cmax = 0, vmax = 0;
    for (size_t i = 0; i < p->n; i++) {
        const pm_material *m = &s->c->materials[p->material[i]];
        double rho = p->mass[i] / p->vol[i];
        double c = pm_material_signal_speed(m, p->state + p->n_state * i, rho, s->grid.h_min);
        double v = hypot(p->v[2 * i], p->v[2 * i + 1]);
        cmax = fmax(cmax, c);
        vmax = fmax(vmax, v);
    }
    if (s->flow)
        return pm_flow_stable_dt(s, cmax + vmax);
    return s->c->analysis.cfl * s->grid.h_min / (cmax + vmax);
}

void pm_sim_energy(const pm_sim *s, double *kinetic, double *strain, double *gravity)
{
    const pm_particles *p = &s->p;
    double g[2], ke = 0, se = 0, ge = 0;
    pm_sim_gravity(s, s->t, g);
#pragma omp parallel for schedule(static) reduction(+ : ke, se, ge) num_threads(s->nd.n_threads)
    for (size_t i = 0; i < p->n; i++) {
        const double *v = p->v + PM_DIM * i, *x = p->x + PM_DIM * i, *x0 = p->x0 + PM_DIM * i;
        double v2 = 0, gx = 0;
        for (int d = 0; d < PM_DIM; d++) {
            v2 += v[d] * v[d];
            gx += g[d] * (x[d] - x0[d]);
        }
        ke += 0.5 * p->mass[i] * v2;
        ge -= p->mass[i] * gx;
        const pm_material *m = &s->c->materials[p->material[i]];
        const double w = pm_point_strain_energy(m, p->F + PM_NF * i, p->stress + PM_NS * i, p->state + p->n_state * i);
        se += w * p->vol0[i];
    }
    *kinetic = ke;
    *strain = se;
    *gravity = ge;
}

void pm_sim_sort_particles(pm_sim *s)
{
    pm_particles *p = &s->p;
    const size_t nc = s->grid.n_cells;
    uint32_t *b = s->bucket;
    memset(b, 0, (nc + 1) * sizeof(uint32_t));
    for (size_t i = 0; i < p->n; i++)
        b[p->cell[i] + 1]++;
    for (size_t c = 0; c < nc; c++)
        b[c + 1] += b[c];
    int sorted = 1;
    for (size_t i = 0; i < p->n; i++) {
        uint32_t at = b[p->cell[i]]++;
        s->perm[at] = (uint32_t)i;
        sorted &= at == i;
    }
    if (!sorted)
        pm_particles_permute(p, s->perm, s->scratch, s->iscratch);
}

/* The density by which a point is judged apart (analysis.apart_measure): its own, or with "cell" the
 * densest node of its cell, so that a point the deposit's free surface or the points' bunching leaves
 * in a thin part of a cell is not read apart while a node of its cell is packed. */
static double apart_density(const pm_sim *s, size_t i)
{
    if (!s->c->analysis.apart_from_cell)
        return s->rho_p[i];
    const pm_grid *g = &s->grid;
    const int32_t *node = g->conn + (size_t)g->nodes_per_cell * (size_t)s->p.cell[i];
    double r = 0;
    for (int k = 0; k < g->nodes_per_cell; k++)
        r = fmax(r, s->rho_node[node[k]]);
    return r;
}

int pm_sim_volumes_from_positions(pm_sim *s)
{
    pm_particles *p = &s->p;
    pm_check(pm_density_from_positions(&s->grid, p, s->c->formulation == PM_AXISYMMETRIC, -1, s->rho_node, s->rho_p,
                                       s->rho_work));
    for (size_t i = 0; i < p->n; i++) {
        if (!(s->rho_p[i] > 0))
            continue;
        p->vol[i] = p->mass[i] / s->rho_p[i];
        const pm_material *m = &s->c->materials[p->material[i]];
        if (m->ops->density_state)
            m->ops->density_state(m, apart_density(s, i) / m->density, p->state + p->n_state * i);
    }
    return PM_OK;
}
