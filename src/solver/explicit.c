/*
 * Explicit MPM time step: USF, USL, MUSL (Sulsky et al.; seed 004 section 3.5) and the explicit
 * Newmark predictor-corrector (seed 003 section 2.2, gamma = 1/2).
 *
 * Every particle pass evaluates shape functions at the positions of the start of the step (the
 * grid is the undeformed one during the step), so positions are moved in the last pass.
 * Scatters run in parallel into per-thread nodal buffers that are summed afterwards, so no two
 * threads write the same memory and the result depends on the thread count only by round-off.
 */
#include "pmech/sim.h"
#include "pmech/error.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

/* Shape functions of particle i; the structured linear quad4 case is inlined. */
static inline int stencil_at(const pm_sim *s, size_t i, pm_stencil *st)
{
    if (s->approx->fast_linear_quad) {
        double dN[8];
        st->n = 4;
        pm_linear_quad_eval(&s->grid, s->p.x + 2 * i, s->p.cell[i], st->node, st->N, dN);
        for (int k = 0; k < 4; k++) {
            st->dN[k][0] = dN[2 * k];
            st->dN[k][1] = dN[2 * k + 1];
        }
        return PM_OK;
    }
    return s->approx->ops->eval(s->approx, &s->p, i, st);
}

/* The nodal buffers a thread scatters into: thread 0 uses the real arrays. */
typedef struct scatter_buf {
    double *mass, *mom, *force;
} scatter_buf;

static scatter_buf thread_buf(const pm_sim *s, int tid)
{
    size_t nn = s->grid.n_nodes;
    scatter_buf b;
    if (tid == 0) {
        b.mass = s->nd.mass;
        b.mom = s->nd.mom;
        b.force = s->nd.force;
    } else {
        double *base = s->nd.scratch + (size_t)(tid - 1) * 5 * nn;
        b.mass = base;
        b.mom = base + nn;
        b.force = base + 3 * nn;
    }
    return b;
}

static void zero_buf(scatter_buf b, size_t nn, int with_mass, int with_force)
{
    if (with_mass)
        memset(b.mass, 0, nn * sizeof(double));
    memset(b.mom, 0, 2 * nn * sizeof(double));
    if (with_force)
        memset(b.force, 0, 2 * nn * sizeof(double));
}

/* Sum the other threads' buffers into the real arrays (called inside a parallel region). */
static void reduce_bufs(const pm_sim *s, int nt, int with_mass, int with_force)
{
    size_t nn = s->grid.n_nodes;
    for (int t = 1; t < nt; t++) {
        scatter_buf b = thread_buf(s, t);
#pragma omp for schedule(static)
        for (size_t n = 0; n < nn; n++) {
            if (with_mass)
                s->nd.mass[n] += b.mass[n];
            s->nd.mom[2 * n] += b.mom[2 * n];
            s->nd.mom[2 * n + 1] += b.mom[2 * n + 1];
            if (with_force) {
                s->nd.force[2 * n] += b.force[2 * n];
                s->nd.force[2 * n + 1] += b.force[2 * n + 1];
            }
        }
    }
}

/* Internal force of particle i on the nodes of its stencil, plus its weight. In axisymmetric runs
 * (x = r) the hoop stress adds -V sigma_tt N / r to the radial force (seed 004 eq. 4). */
static inline void scatter_force(const pm_sim *s, size_t i, const pm_stencil *st, const double g[2],
                                 double *force)
{
    const double *sg = s->p.stress + PM_NS * i;
    const double V = s->p.vol[i], m = s->p.mass[i];
    const double hoop = s->c->formulation == PM_AXISYMMETRIC ? sg[PM_SZZ] / s->p.x[2 * i] : 0.0;
    for (int k = 0; k < st->n; k++) {
        const int32_t n = st->node[k];
        const double dx = st->dN[k][0], dy = st->dN[k][1], N = st->N[k];
        force[2 * n] += -V * (sg[PM_SXX] * dx + sg[PM_SXY] * dy + hoop * N) + N * m * g[0];
        force[2 * n + 1] += -V * (sg[PM_SXY] * dx + sg[PM_SYY] * dy) + N * m * g[1];
    }
}

/* Plane stress: find the out-of-plane stretch increment that makes sigma_zz vanish, by Newton
 * iterations on the material's own update (its tangent gives the slope). The state is restored
 * before each retry so that the accepted update is a single step of the model. */
static int plane_stress_update(const pm_material *m, pm_material_step *in, double *state, size_t n_state,
                               double s6[6], double Fzz_old)
{
    double st0[PM_MAT_MAX_STATE], s0[6], T[36];
    memcpy(st0, state, n_state * sizeof(double));
    memcpy(s0, s6, sizeof s0);
    double dz = 1.0;
    for (int it = 0; it < 12; it++) {
        memcpy(state, st0, n_state * sizeof(double));
        memcpy(s6, s0, sizeof s0);
        in->F_incr[8] = dz;
        in->F_new[8] = dz * Fzz_old;
        if (m->ops->update(m, in, state, s6, T) != PM_OK)
            return 1;
        const double scale = fabs(s6[0]) + fabs(s6[1]) + fabs(s6[3]) + 1e-300;
        if (fabs(s6[2]) <= 1e-12 * scale || !(T[14] > 0))
            break;
        dz -= s6[2] / T[14];
        if (!(dz > 0))
            return 1;
    }
    s6[2] = 0.0;
    return 0;
}

/*
 * Velocity gradient from nodal velocities, then the material's stress update, volume from det F,
 * and the particle's wave speed. Returns 0, or 1 if the point failed (inverted, NaN, model failure).
 * The out-of-plane stretch: 1 (plane strain), from sigma_zz = 0 (plane stress), or the hoop rate
 * v_r / r (axisymmetric).
 */
static inline int update_stress(pm_sim *s, size_t i, const pm_stencil *st, const double *nv, double dt,
                                double *wave)
{
    pm_particles *p = &s->p;
    const pm_formulation form = s->c->formulation;
    double L[4] = {0, 0, 0, 0}, vr = 0;
    for (int k = 0; k < st->n; k++) {
        const double *v = nv + 2 * st->node[k];
        L[0] += v[0] * st->dN[k][0];
        L[1] += v[0] * st->dN[k][1];
        L[2] += v[1] * st->dN[k][0];
        L[3] += v[1] * st->dN[k][1];
        vr += v[0] * st->N[k];
    }
    double *F = p->F + PM_NF * i;
    pm_material_step in;
    const double a = 1 + dt * L[0], b = dt * L[1], c = dt * L[2], d = 1 + dt * L[3];
    const double dz = form == PM_AXISYMMETRIC ? 1 + dt * vr / p->x[2 * i] : 1.0;
    in.F_incr[0] = a; in.F_incr[1] = b; in.F_incr[2] = 0;
    in.F_incr[3] = c; in.F_incr[4] = d; in.F_incr[5] = 0;
    in.F_incr[6] = 0; in.F_incr[7] = 0; in.F_incr[8] = dz;
    in.F_old[0] = F[PM_FXX]; in.F_old[1] = F[PM_FXY]; in.F_old[2] = 0;
    in.F_old[3] = F[PM_FYX]; in.F_old[4] = F[PM_FYY]; in.F_old[5] = 0;
    in.F_old[6] = 0; in.F_old[7] = 0; in.F_old[8] = F[PM_FZZ];
    const double nxx = a * F[PM_FXX] + b * F[PM_FYX], nxy = a * F[PM_FXY] + b * F[PM_FYY];
    const double nyx = c * F[PM_FXX] + d * F[PM_FYX], nyy = c * F[PM_FXY] + d * F[PM_FYY];
    in.F_new[0] = nxx; in.F_new[1] = nxy; in.F_new[2] = 0;
    in.F_new[3] = nyx; in.F_new[4] = nyy; in.F_new[5] = 0;
    in.F_new[6] = 0; in.F_new[7] = 0; in.F_new[8] = dz * F[PM_FZZ];
    in.dt = dt;
    const double J2 = nxx * nyy - nxy * nyx;
    if (!(J2 > 0) || !(dz > 0))
        return 1;
    const pm_material *m = &s->c->materials[p->material[i]];
    double *sg = p->stress + PM_NS * i, *state = p->state + p->n_state * i;
    double s6[6] = {sg[PM_SXX], sg[PM_SYY], sg[PM_SZZ], sg[PM_SXY], 0, 0};
    if (form == PM_PLANE_STRESS) {
        if (plane_stress_update(m, &in, state, p->n_state, s6, F[PM_FZZ]))
            return 1;
    } else if (m->ops->update(m, &in, state, s6, NULL) != PM_OK) {
        return 1;
    }
    const double Fzz = in.F_new[8], J = J2 * Fzz;
    F[PM_FXX] = nxx; F[PM_FXY] = nxy; F[PM_FYX] = nyx; F[PM_FYY] = nyy; F[PM_FZZ] = Fzz;
    sg[PM_SXX] = s6[0]; sg[PM_SYY] = s6[1]; sg[PM_SZZ] = s6[2]; sg[PM_SXY] = s6[3];
    if (!isfinite(s6[0] + s6[1] + s6[2] + s6[3]) || !(J > 0))
        return 1;
    p->vol[i] = p->vol0[i] * J;
    if (m->ops->plastic_strain)
        p->eps_p[i] = m->ops->plastic_strain(m, state);
    if (s->c->analysis.dt > 0)
        return 0; /* fixed step: the wave speed is not needed */
    const double rho = p->mass[i] / p->vol[i];
    const double cw = m->ops->wave_speed ? m->ops->wave_speed(m, state, rho)
                                         : pm_material_elastic_wave_speed(m, state, rho);
    const double *v = p->v + 2 * i;
    *wave = cw + sqrt(v[0] * v[0] + v[1] * v[1]);
    return 0;
}

/* Interpolate a nodal velocity and acceleration to a particle. */
static inline void gather(const pm_stencil *st, const double *vel, const double *acc, double v[2], double a[2])
{
    v[0] = v[1] = a[0] = a[1] = 0;
    for (int k = 0; k < st->n; k++) {
        const int32_t n = st->node[k];
        v[0] += st->N[k] * vel[2 * n];
        v[1] += st->N[k] * vel[2 * n + 1];
        a[0] += st->N[k] * acc[2 * n];
        a[1] += st->N[k] * acc[2 * n + 1];
    }
}

/* Coulomb friction on a grid boundary (Bardenhagen et al. 2000): the approaching normal velocity is
 * removed and the tangential speed reduced by mu times that change, never reversed. */
static void apply_friction(const pm_friction_node *fn, double v[2])
{
    const double *nrm = fn->normal;
    const double vn = v[0] * nrm[0] + v[1] * nrm[1];
    if (vn <= 0)
        return; /* separating or sliding along: free */
    double vt[2] = {v[0] - vn * nrm[0], v[1] - vn * nrm[1]};
    const double speed = hypot(vt[0], vt[1]), cut = fn->mu * vn;
    const double keep = speed > cut ? 1.0 - cut / speed : 0.0;
    v[0] = keep * vt[0];
    v[1] = keep * vt[1];
}

/* Remove only the approaching normal velocity (no friction impulse): for velocities that are
 * re-projected within a step, where the frictional impulse has already been applied. */
static void apply_contact_normal(const pm_friction_node *fn, double v[2])
{
    const double vn = v[0] * fn->normal[0] + v[1] * fn->normal[1];
    if (vn > 0) {
        v[0] -= vn * fn->normal[0];
        v[1] -= vn * fn->normal[1];
    }
}

static void constrain(const pm_nodal *nd, int32_t n, double v[2])
{
    if (nd->fixed[n] & 1u)
        v[0] = nd->vfix[2 * n];
    if (nd->fixed[n] & 2u)
        v[1] = nd->vfix[2 * n + 1];
}

/* Smallest nodal mass treated as carrying material: guards divisions by round-off masses. */
static double mass_floor(const pm_sim *s)
{
    return s->p.n ? 1e-12 * s->p.mass[0] : 0.0;
}

/*
 * Nodal velocities from momentum (constrained), accelerations from forces with local damping,
 * constraints and friction applied to the end-of-step velocity; acc = (v_new - v) / dt so that the
 * particles receive the reaction impulses too.
 */
static void grid_update(pm_sim *s, double dt, int constrain_start)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = s->grid.n_nodes;
    const double alpha = s->c->analysis.damping, mfloor = mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        double *v = nd->vel + 2 * n, *vn = nd->vel_new + 2 * n, *a = nd->acc + 2 * n;
        const double m = nd->mass[n];
        if (!(m > mfloor)) {
            v[0] = v[1] = vn[0] = vn[1] = a[0] = a[1] = 0;
            continue;
        }
        v[0] = nd->mom[2 * n] / m;
        v[1] = nd->mom[2 * n + 1] / m;
        double f[2] = {nd->force[2 * n], nd->force[2 * n + 1]};
        if (alpha > 0)
            for (int d = 0; d < 2; d++)
                f[d] -= alpha * fabs(f[d]) * (v[d] > 0 ? 1.0 : v[d] < 0 ? -1.0 : 0.0);
        vn[0] = v[0] + dt * f[0] / m;
        vn[1] = v[1] + dt * f[1] / m;
        if (constrain_start)
            constrain(nd, (int32_t)n, v);
        constrain(nd, (int32_t)n, vn);
    }
    for (size_t k = 0; k < nd->n_friction; k++) {
        const pm_friction_node *fn = &nd->friction[k];
        if (nd->mass[fn->node] > mfloor) {
            apply_friction(fn, nd->vel_new + 2 * fn->node);
            constrain(nd, fn->node, nd->vel_new + 2 * fn->node);
        }
    }
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < 2 * nn; n++)
        nd->acc[n] = (nd->vel_new[n] - nd->vel[n]) / dt;
}

/* Velocities re-projected from particle momentum (MUSL) or P2G momentum (USF start) with constraints. */
static void grid_velocity_from_momentum(pm_sim *s, double *out)
{
    pm_nodal *nd = &s->nd;
    const size_t nn = s->grid.n_nodes;
    const double mfloor = mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        double *v = out + 2 * n;
        const double m = nd->mass[n];
        if (!(m > mfloor)) {
            v[0] = v[1] = 0;
            continue;
        }
        v[0] = nd->mom[2 * n] / m;
        v[1] = nd->mom[2 * n + 1] / m;
        constrain(nd, (int32_t)n, v);
    }
    for (size_t k = 0; k < nd->n_friction; k++) {
        const pm_friction_node *fn = &nd->friction[k];
        apply_contact_normal(fn, out + 2 * fn->node);
        constrain(nd, fn->node, out + 2 * fn->node);
    }
}

/* Pass 1 of every scheme: mass, momentum (of v + shift * a) and optionally forces to the grid. */
static long p2g(pm_sim *s, double mom_shift, int with_force, const double g[2])
{
    pm_particles *p = &s->p;
    long bad = LONG_MAX;
    // cppcheck-suppress variableScope ; shared by the threads of the region below
    int used = 1;
#pragma omp parallel num_threads(s->nd.n_threads) reduction(min : bad)
    {
        const int tid = omp_get_thread_num();
#pragma omp single
        used = omp_get_num_threads();
        scatter_buf b = thread_buf(s, tid);
        zero_buf(b, s->grid.n_nodes, 1, 1);
#pragma omp barrier
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            if (stencil_at(s, i, &st) != PM_OK) {
                bad = (long)i < bad ? (long)i : bad;
                continue;
            }
            const double m = p->mass[i];
            const double vx = p->v[2 * i] + mom_shift * p->a[2 * i];
            const double vy = p->v[2 * i + 1] + mom_shift * p->a[2 * i + 1];
            for (int k = 0; k < st.n; k++) {
                const int32_t n = st.node[k];
                const double w = st.N[k] * m;
                b.mass[n] += w;
                b.mom[2 * n] += w * vx;
                b.mom[2 * n + 1] += w * vy;
            }
            if (with_force)
                scatter_force(s, i, &st, g, b.force);
        }
        reduce_bufs(s, used, 1, 1);
    }
    return bad;
}

static int fail_particle(const pm_sim *s, long i, const char *what)
{
    const double *x = s->p.x + 2 * i;
    return pm_error_set(PM_ESIM, "step %ld (t = %.6g s): particle %ld at (%.6g, %.6g) %s", s->step + 1, s->t, i,
                        x[0], x[1], what);
}

static const char *failure_text(const pm_sim *s, long i)
{
    const double *F = s->p.F + PM_NF * i;
    double J = (F[PM_FXX] * F[PM_FYY] - F[PM_FXY] * F[PM_FYX]) * F[PM_FZZ];
    return J > 0 && isfinite(J) ? "failed: its stress or velocity is not finite (the run diverged; try a "
                                  "smaller dt or cfl)"
                                : "inverted (det F <= 0): the run diverged; try a smaller dt or cfl";
}

/* USL and MUSL: forces from the stress at the start, then (MUSL) velocities re-projected. */
static int step_usl_musl(pm_sim *s, double dt, int musl)
{
    pm_particles *p = &s->p;
    double g[2];
    pm_sim_gravity(s, s->t, g);
    long bad = p2g(s, 0.0, 1, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    grid_update(s, dt, 1);
    pm_nodal *nd = &s->nd;
    // cppcheck-suppress variableScope ; shared by the threads of the region below
    int used = 1;
    if (musl) {
        /* particle velocities from nodal accelerations, then their momentum back to the grid */
#pragma omp parallel num_threads(nd->n_threads)
        {
            const int tid = omp_get_thread_num();
#pragma omp single
            used = omp_get_num_threads();
            scatter_buf b = thread_buf(s, tid);
            zero_buf(b, s->grid.n_nodes, 0, 0);
#pragma omp barrier
            pm_stencil st;
#pragma omp for schedule(static)
            for (size_t i = 0; i < p->n; i++) {
                stencil_at(s, i, &st);
                double ax = 0, ay = 0;
                for (int k = 0; k < st.n; k++) {
                    ax += st.N[k] * nd->acc[2 * st.node[k]];
                    ay += st.N[k] * nd->acc[2 * st.node[k] + 1];
                }
                double *v = p->v + 2 * i;
                v[0] += dt * ax;
                v[1] += dt * ay;
                const double m = p->mass[i];
                for (int k = 0; k < st.n; k++) {
                    const int32_t n = st.node[k];
                    // cppcheck-suppress unreadVariable ; b.mom points into the nodal arrays
                    b.mom[2 * n] += st.N[k] * m * v[0];
                    // cppcheck-suppress unreadVariable
                    b.mom[2 * n + 1] += st.N[k] * m * v[1];
                }
            }
            reduce_bufs(s, used, 0, 0);
        }
        /* nd->vel now holds the re-projected velocity used for the strain rate */
        grid_velocity_from_momentum(s, nd->vel);
    }
    const double *vstrain = musl ? nd->vel : nd->vel_new;
    double wave = 0;
    bad = LONG_MAX;
#pragma omp parallel num_threads(nd->n_threads) reduction(min : bad) reduction(max : wave)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            stencil_at(s, i, &st);
            double vg[2], ag[2];
            gather(&st, nd->vel_new, nd->acc, vg, ag);
            if (!musl) {
                p->v[2 * i] += dt * ag[0];
                p->v[2 * i + 1] += dt * ag[1];
            }
            double w = 0;
            if (update_stress(s, i, &st, vstrain, dt, &w)) {
                bad = (long)i < bad ? (long)i : bad;
                continue;
            }
            wave = w > wave ? w : wave;
            p->x[2 * i] += dt * vg[0];
            p->x[2 * i + 1] += dt * vg[1];
        }
    }
    s->max_wave = wave;
    if (bad != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    return PM_OK;
}

/* Forces and stress of the predictor-corrector and USF share this pass: strain from nodal velocity
 * `nv`, new stress, then its internal force scattered. */
static long stress_and_force(pm_sim *s, double dt, const double *nv, const double g[2])
{
    pm_particles *p = &s->p;
    pm_nodal *nd = &s->nd;
    double wave = 0;
    // cppcheck-suppress variableScope ; shared by the threads of the region below
    int used = 1;
    long bad = LONG_MAX;
#pragma omp parallel num_threads(nd->n_threads) reduction(min : bad) reduction(max : wave)
    {
        const int tid = omp_get_thread_num();
#pragma omp single
        used = omp_get_num_threads();
        scatter_buf b = thread_buf(s, tid);
        memset(b.force, 0, 2 * s->grid.n_nodes * sizeof(double));
#pragma omp barrier
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            stencil_at(s, i, &st);
            double w = 0;
            if (update_stress(s, i, &st, nv, dt, &w)) {
                bad = (long)i < bad ? (long)i : bad;
                continue;
            }
            wave = w > wave ? w : wave;
            scatter_force(s, i, &st, g, b.force);
        }
        for (int t = 1; t < used; t++) {
            scatter_buf o = thread_buf(s, t);
#pragma omp for schedule(static)
            for (size_t n = 0; n < 2 * s->grid.n_nodes; n++)
                nd->force[n] += o.force[n];
        }
    }
    s->max_wave = wave;
    return bad;
}

/* USF: stress first from the projected velocity, then forces from the new stress. */
static int step_usf(pm_sim *s, double dt)
{
    pm_particles *p = &s->p;
    pm_nodal *nd = &s->nd;
    double g[2];
    pm_sim_gravity(s, s->t, g);
    long bad = p2g(s, 0.0, 0, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    grid_velocity_from_momentum(s, nd->vel);
    bad = stress_and_force(s, dt, nd->vel, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    grid_update(s, dt, 1);
#pragma omp parallel num_threads(nd->n_threads)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            stencil_at(s, i, &st);
            double v[2], a[2];
            gather(&st, nd->vel_new, nd->acc, v, a);
            p->v[2 * i] += dt * a[0];
            p->v[2 * i + 1] += dt * a[1];
            p->x[2 * i] += dt * v[0];
            p->x[2 * i + 1] += dt * v[1];
        }
    }
    return PM_OK;
}

/*
 * Explicit Newmark predictor-corrector (seed 003, Algorithm of section 2.2, gamma = 1/2):
 * predicted nodal velocity from v_p + (1 - gamma) dt a_p, strain from it, forces from the new
 * stress, corrector v = v_pred + gamma dt a; particles: a_p = N a, v_p += dt ((1-gamma) a_p_old +
 * gamma a_p), x_p += dt N v_pred (= dt v + dt^2/2 a, the central-difference position).
 */
static int step_newmark_pc(pm_sim *s, double dt)
{
    const double gamma = 0.5;
    pm_particles *p = &s->p;
    pm_nodal *nd = &s->nd;
    double g[2];
    pm_sim_gravity(s, s->t + dt, g);
    long bad = p2g(s, (1 - gamma) * dt, 0, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    grid_velocity_from_momentum(s, nd->vel);
    bad = stress_and_force(s, dt, nd->vel, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, failure_text(s, bad));
    const size_t nn = s->grid.n_nodes;
    const double alpha = s->c->analysis.damping, mfloor = mass_floor(s);
#pragma omp parallel for schedule(static) num_threads(nd->n_threads)
    for (size_t n = 0; n < nn; n++) {
        const double m = nd->mass[n];
        double *a = nd->acc + 2 * n, *v = nd->vel + 2 * n, *vn = nd->vel_new + 2 * n;
        if (!(m > mfloor)) {
            a[0] = a[1] = vn[0] = vn[1] = 0;
            continue;
        }
        for (int d = 0; d < 2; d++) {
            double f = nd->force[2 * n + d];
            if (alpha > 0)
                f -= alpha * fabs(f) * (v[d] > 0 ? 1.0 : v[d] < 0 ? -1.0 : 0.0);
            /* prescribed components: acceleration zero, the force is the reaction */
            a[d] = (nd->fixed[n] & (1u << d)) ? 0.0 : f / m;
            vn[d] = v[d] + gamma * dt * a[d];
        }
    }
    for (size_t k = 0; k < nd->n_friction; k++) {
        const pm_friction_node *fn = &nd->friction[k];
        const int32_t n = fn->node;
        if (!(nd->mass[n] > mfloor))
            continue;
        apply_friction(fn, nd->vel_new + 2 * n);
        constrain(nd, n, nd->vel_new + 2 * n);
        for (int d = 0; d < 2; d++)
            nd->acc[2 * n + d] = (nd->vel_new[2 * n + d] - nd->vel[2 * n + d]) / (gamma * dt);
    }
#pragma omp parallel num_threads(nd->n_threads)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            stencil_at(s, i, &st);
            double vg[2], ag[2];
            gather(&st, nd->vel, nd->acc, vg, ag);
            double *v = p->v + 2 * i, *a = p->a + 2 * i;
            v[0] += dt * ((1 - gamma) * a[0] + gamma * ag[0]);
            v[1] += dt * ((1 - gamma) * a[1] + gamma * ag[1]);
            a[0] = ag[0];
            a[1] = ag[1];
            p->x[2 * i] += dt * vg[0];
            p->x[2 * i + 1] += dt * vg[1];
        }
    }
    return PM_OK;
}

int pm_sim_update_stresses(pm_sim *s, const double *nodal_v, double dt)
{
    pm_check(s->approx->ops->connect(s->approx, &s->p));
    long bad = LONG_MAX;
    double wave = 0;
#pragma omp parallel num_threads(s->nd.n_threads) reduction(min : bad) reduction(max : wave)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < s->p.n; i++) {
            double w = 0;
            if (stencil_at(s, i, &st) != PM_OK || update_stress(s, i, &st, nodal_v, dt, &w))
                bad = (long)i < bad ? (long)i : bad;
            wave = w > wave ? w : wave;
        }
    }
    s->max_wave = wave;
    return bad == LONG_MAX ? PM_OK : fail_particle(s, bad, failure_text(s, bad));
}

int pm_explicit_step(pm_sim *s, double dt)
{
    int rc = s->approx->ops->connect(s->approx, &s->p);
    if (rc)
        return pm_error_prefix(PM_ESIM, "step %ld (t = %.6g s): ", s->step + 1, s->t);
    pm_sim_update_constraints(s);
    if (s->rho_p && (rc = pm_sim_volumes_from_positions(s)) != PM_OK)
        return pm_error_prefix(PM_ESIM, "step %ld (t = %.6g s): ", s->step + 1, s->t);
    /* particles drift apart in memory as they move; a periodic sort keeps the scatters local */
    if (s->sort_interval > 0 && s->step % s->sort_interval == 0 && s->grid.n_cells < UINT32_MAX)
        pm_sim_sort_particles(s);
    switch (s->c->analysis.scheme) {
    case PM_SCHEME_USF: rc = step_usf(s, dt); break;
    case PM_SCHEME_USL: rc = step_usl_musl(s, dt, 0); break;
    case PM_SCHEME_NEWMARK_PC: rc = step_newmark_pc(s, dt); break;
    default: rc = step_usl_musl(s, dt, 1); break;
    }
    if (rc)
        return rc;
    s->t += dt;
    s->step++;
    return PM_OK;
}
