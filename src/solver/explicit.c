/*
 * Explicit MPM time step: USF, USL, MUSL (Sulsky et al.; seed 004 section 3.5) and the explicit
 * Newmark predictor-corrector (seed 003 section 2.2, gamma = 1/2).
 *
 * Every particle pass evaluates shape functions at the positions of the start of the step (the
 * grid is the undeformed one during the step), so positions are moved in the last pass.
 * Parallel scatters never let two threads add into one node: either the particles, sorted by cell,
 * are cut into row blocks of two colours that scatter colour by colour straight into the nodal
 * arrays, or every thread scatters into its own copy of them, summed afterwards (pm_scatter). Either
 * way the result depends on the thread count only by round-off.
 */
#include "pmech/sim.h"
#include "pmech/error.h"
#include "contact/contact.h"
#include "meshfree_internal.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

/*
 * The linear quad4 particle loops work on four nodes at a time: on x86-64 an AVX2 copy of them is
 * built beside the baseline one and chosen at load time where the processor has AVX2 (8 % fewer
 * instructions per particle-step). AVX2 alone has no fused multiply-add and C11 mode contracts
 * nothing, so both copies compute bit for bit the same results.
 */
#define PM_HOT
#if defined(__x86_64__) && defined(__linux__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#undef PM_HOT
#define PM_HOT __attribute__((target_clones("avx2", "default")))
#endif
#endif

/*
 * The structured linear quad4 grid with its constants hoisted out of the particle loops. The cell's
 * row comes from a multiplication by 1 / nx, not an integer division: the division alone costs as
 * much as the rest of the shape functions. The product can be one off next to exact multiples,
 * hence the two corrections. Values are those of pm_linear_quad_eval() bit for bit.
 */
typedef struct lq_grid {
    double ox, oy, ihx, ihy, inx;
    int32_t nx;
} lq_grid;

static inline lq_grid lq_of(const pm_grid *g)
{
    lq_grid q = {g->origin[0], g->origin[1], 1.0 / g->h[0], 1.0 / g->h[1], 1.0 / g->cells[0], g->cells[0]};
    return q;
}

static inline void lq_cell(const lq_grid *q, int32_t cell, int32_t *cx, int32_t *cy)
{
    int64_t y = (int64_t)((double)cell * q->inx);
    y -= y * q->nx > cell;
    y += (y + 1) * q->nx <= cell;
    *cy = (int32_t)y;
    *cx = cell - (int32_t)y * q->nx;
}

/* Lower-left node of a cell; the others are +1, +nx+2, +nx+1 (counter-clockwise). */
static inline int32_t lq_node0(const lq_grid *q, int32_t cx, int32_t cy) { return cy * (q->nx + 1) + cx; }

static inline void lq_N(const lq_grid *q, const double xp[2], int32_t cx, int32_t cy, double N[4], double *xi_,
                        double *eta_)
{
    const double xi = (xp[0] - q->ox) * q->ihx - cx;
    const double eta = (xp[1] - q->oy) * q->ihy - cy;
    N[0] = (1 - xi) * (1 - eta); N[1] = xi * (1 - eta); N[2] = xi * eta; N[3] = (1 - xi) * eta;
    *xi_ = xi;
    *eta_ = eta;
}

static inline void lq_eval(const lq_grid *q, const double xp[2], int32_t cx, int32_t cy, double N[4],
                           double dN[4][2])
{
    double xi, eta;
    lq_N(q, xp, cx, cy, N, &xi, &eta);
    dN[0][0] = -(1 - eta) * q->ihx; dN[0][1] = -(1 - xi) * q->ihy;
    dN[1][0] = (1 - eta) * q->ihx;  dN[1][1] = -xi * q->ihy;
    dN[2][0] = eta * q->ihx;        dN[2][1] = xi * q->ihy;
    dN[3][0] = -eta * q->ihx;       dN[3][1] = (1 - xi) * q->ihy;
}

/* Shape functions of particle i through the approximation's interface (the structured linear quad4
 * case inline). */
static inline int stencil_at(const pm_sim *s, size_t i, pm_stencil *st)
{
    if (s->approx->fast_linear_quad) {
        const lq_grid q = lq_of(&s->grid);
        int32_t cx, cy;
        lq_cell(&q, s->p.cell[i], &cx, &cy);
        const int32_t n0 = lq_node0(&q, cx, cy);
        st->n = 4;
        st->node[0] = n0; st->node[1] = n0 + 1; st->node[2] = n0 + q.nx + 2; st->node[3] = n0 + q.nx + 1;
        lq_eval(&q, s->p.x + 2 * i, cx, cy, st->N, st->dN);
        return PM_OK;
    }
    return s->approx->ops->eval(s->approx, &s->p, i, st);
}

/* The nodal buffers a thread scatters into: thread 0 (and every thread of a colour scatter) uses
 * the real arrays. */
typedef struct scatter_buf {
    double *mass, *mom, *force;
} scatter_buf;

static scatter_buf thread_buf(const pm_sim *s, int tid)
{
    size_t nn = s->grid.n_nodes;
    scatter_buf b;
    if (tid == 0 || s->scatter == PM_SCATTER_COLOUR) {
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

enum { Z_MASS = 1, Z_MOM = 2, Z_FORCE = 4 };

static void zero_buf(scatter_buf b, size_t nn, unsigned what)
{
    if (what & Z_MASS)
        memset(b.mass, 0, nn * sizeof(double));
    if (what & Z_MOM)
        memset(b.mom, 0, 2 * nn * sizeof(double));
    if (what & Z_FORCE)
        memset(b.force, 0, 2 * nn * sizeof(double));
}

/* Sum the other threads' buffers into the real arrays (called inside a parallel region). */
static void reduce_bufs(const pm_sim *s, int nt, unsigned what)
{
    size_t nn = s->grid.n_nodes;
    for (int t = 1; t < nt; t++) {
        scatter_buf b = thread_buf(s, t);
#pragma omp for schedule(static)
        for (size_t n = 0; n < nn; n++) {
            if (what & Z_MASS)
                s->nd.mass[n] += b.mass[n];
            if (what & Z_MOM) {
                s->nd.mom[2 * n] += b.mom[2 * n];
                s->nd.mom[2 * n + 1] += b.mom[2 * n + 1];
            }
            if (what & Z_FORCE) {
                s->nd.force[2 * n] += b.force[2 * n];
                s->nd.force[2 * n + 1] += b.force[2 * n + 1];
            }
        }
    }
}

/* What a scatter over a range of particles reports: the first failed particle, the largest wave speed. */
typedef struct range_out {
    long bad;
    double wave;
} range_out;

typedef void (*range_fn)(pm_sim *s, size_t lo, size_t hi, const scatter_buf *b, const void *ctx, range_out *out);

/*
 * Run a scatter pass: fn over every particle, each call writing into buffer b. Buffers: each thread
 * takes a contiguous range into its own copy, summed after. Colour: the row blocks of one colour
 * share no node, so they scatter at once into the real arrays, one colour after the other; when
 * they do share one (blocks_ok = 0), one thread scatters everything.
 */
static range_out scatter_pass(pm_sim *s, range_fn fn, const void *ctx, unsigned zero)
{
    long bad = LONG_MAX;
    double wave = 0;
    const size_t n = s->p.n, nn = s->grid.n_nodes;
#pragma omp parallel num_threads(s->nd.n_threads) reduction(min : bad) reduction(max : wave)
    {
        const int tid = omp_get_thread_num(), used = omp_get_num_threads();
        range_out o = {LONG_MAX, 0};
        if (s->scatter == PM_SCATTER_COLOUR && used > 1) {
            scatter_buf b = thread_buf(s, 0);
#pragma omp for schedule(static)
            for (size_t k = 0; k < nn; k++) {
                if (zero & Z_MASS)
                    b.mass[k] = 0;
                if (zero & Z_MOM)
                    b.mom[2 * k] = b.mom[2 * k + 1] = 0;
                if (zero & Z_FORCE)
                    b.force[2 * k] = b.force[2 * k + 1] = 0;
            }
            if (s->blocks_ok) {
                const int nb = s->n_blocks;
                for (int c = 0; c < 2; c++) {
                    for (int k = 2 * tid + c; k < nb; k += 2 * used)
                        fn(s, s->blocks[k], s->blocks[k + 1], &b, ctx, &o);
#pragma omp barrier
                }
            } else {
#pragma omp single
                fn(s, 0, n, &b, ctx, &o);
            }
        } else {
            scatter_buf b = thread_buf(s, tid);
            zero_buf(b, nn, zero);
            if (used > 1) {
#pragma omp barrier
            }
            fn(s, n * (size_t)tid / (size_t)used, n * (size_t)(tid + 1) / (size_t)used, &b, ctx, &o);
            if (used > 1) {
#pragma omp barrier
                reduce_bufs(s, used, zero);
            }
        }
        bad = o.bad;
        wave = o.wave;
    }
    range_out r = {bad, wave};
    return r;
}

/*
 * Colour scatter: cut the particles (just sorted by cell) into 2 x threads blocks of whole cell
 * rows with about equal counts. Block k then covers rows strictly below those of block k + 1, so
 * blocks k and k + 2 are a whole block apart.
 */
static void cut_blocks(pm_sim *s)
{
    const pm_particles *p = &s->p;
    const int nb = 2 * s->nd.n_threads;
    const int32_t nx = s->grid.cells[0];
    s->blocks[0] = 0;
    for (int k = 1; k < nb; k++) {
        size_t at = p->n * (size_t)k / (size_t)nb, lo = s->blocks[k - 1], hi = at;
        if (at < p->n) {
            const int32_t first = p->cell[at] / nx * nx; /* first cell of the row of particle `at` */
            while (lo < hi) {                           /* first particle in that row or above */
                const size_t mid = lo + (hi - lo) / 2;
                if (p->cell[mid] < first)
                    lo = mid + 1;
                else
                    hi = mid;
            }
        } else {
            lo = p->n;
        }
        s->blocks[k] = lo;
    }
    s->blocks[nb] = p->n;
    s->n_blocks = nb;
}

/*
 * Particles move between sorts: check with this step's cells that no two blocks of one colour touch
 * a common node row (a block in rows r0..r1 touches node rows r0..r1 + 1).
 */
static int blocks_disjoint(const pm_sim *s)
{
    enum { MAXB = 256 }; /* row ranges on the stack; beyond 128 threads one thread scatters */
    const int nb = s->n_blocks;
    if (nb <= 2 || nb > MAXB)
        return nb == 2 ? 1 : 0;
    int32_t lo[MAXB], hi[MAXB];
    const int32_t *cell = s->p.cell;
#pragma omp parallel for schedule(static, 1) num_threads(s->nd.n_threads)
    for (int k = 0; k < nb; k++) {
        int32_t a = INT32_MAX, b = -1;
        for (size_t i = s->blocks[k]; i < s->blocks[k + 1]; i++) {
            a = cell[i] < a ? cell[i] : a;
            b = cell[i] > b ? cell[i] : b;
        }
        lo[k] = b < 0 ? -1 : a / s->grid.cells[0];
        hi[k] = b < 0 ? -1 : b / s->grid.cells[0];
    }
    for (int j = 0; j < nb; j++)
        for (int k = j + 2; k < nb; k += 2)
            if (hi[j] >= 0 && hi[k] >= 0 && !(hi[j] + 1 < lo[k] || hi[k] + 1 < lo[j]))
                return 0;
    return 1;
}

/* Before a step's scatters: blocks cut for the current order, and whether they may scatter at once. */
static void prepare_colour(pm_sim *s, int sorted)
{
    if (s->scatter != PM_SCATTER_COLOUR || s->nd.n_threads < 2)
        return;
    if (sorted || s->n_blocks != 2 * s->nd.n_threads || s->blocks[s->n_blocks] != s->p.n)
        cut_blocks(s);
    s->blocks_ok = blocks_disjoint(s);
    if (!s->blocks_ok && s->sort_interval > 0 && s->grid.n_cells < UINT32_MAX) {
        pm_sim_sort_particles(s); /* particles drifted across a whole block: sort before the usual time */
        cut_blocks(s);
        s->blocks_ok = blocks_disjoint(s);
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
static inline int update_stress_L(pm_sim *s, size_t i, const double L[4], double vr, double dt, double *wave)
{
    pm_particles *p = &s->p;
    const pm_formulation form = s->c->formulation;
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

static inline int update_stress(pm_sim *s, size_t i, const pm_stencil *st, const double *nv, double dt,
                                double *wave)
{
    double L[4] = {0, 0, 0, 0}, vr = 0;
    for (int k = 0; k < st->n; k++) {
        const double *v = nv + 2 * st->node[k];
        L[0] += v[0] * st->dN[k][0];
        L[1] += v[0] * st->dN[k][1];
        L[2] += v[1] * st->dN[k][0];
        L[3] += v[1] * st->dN[k][1];
        vr += v[0] * st->N[k];
    }
    return update_stress_L(s, i, L, vr, dt, wave);
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
        /* here rather than in a loop of its own: the velocities are still in registers */
        a[0] = (vn[0] - v[0]) / dt;
        a[1] = (vn[1] - v[1]) / dt;
    }
    pm_contact_apply(s->contact, pm_contact_field_of(nd, nd->vel_new, mfloor), dt, dt);
    if (s->mf && s->mf->transform)
        pm_mf_impose_update(s, dt, constrain_start);
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
    pm_contact_project_normal(s->contact, pm_contact_field_of(nd, out, mfloor));
    if (s->mf && s->mf->transform)
        pm_mf_impose(s, out, 0);
}

/* Pass 1 of every scheme: mass, momentum (of v + shift * a) and optionally forces to the grid. */
typedef struct p2g_ctx {
    double shift;
    int with_force;
    double g[2];
} p2g_ctx;

static void p2g_range(pm_sim *s, size_t lo, size_t hi, const scatter_buf *b, const void *vc, range_out *out)
{
    const p2g_ctx *c = vc;
    const pm_particles *p = &s->p;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        if (stencil_at(s, i, &st) != PM_OK) {
            out->bad = (long)i < out->bad ? (long)i : out->bad;
            continue;
        }
        const double m = p->mass[i];
        const double vx = p->v[2 * i] + c->shift * p->a[2 * i];
        const double vy = p->v[2 * i + 1] + c->shift * p->a[2 * i + 1];
        for (int k = 0; k < st.n; k++) {
            const int32_t n = st.node[k];
            const double w = st.N[k] * m;
            b->mass[n] += w;
            b->mom[2 * n] += w * vx;
            b->mom[2 * n + 1] += w * vy;
        }
        if (c->with_force)
            scatter_force(s, i, &st, c->g, b->force);
    }
}

/* Per-cell sums of the linear quad4 scatters, added to the four nodes when the next particle is in
 * another cell: particles sorted by cell come in runs of about particles-per-cell, so the nodal
 * arrays are read and written once per run instead of once per particle. */
typedef struct cell_sums {
    double m[4], mx[4], my[4], fx[4], fy[4];
} cell_sums;

static inline void add_cell_sums(const scatter_buf *b, int32_t n0, int32_t nx, const cell_sums *a, unsigned what)
{
    const int32_t node[4] = {n0, n0 + 1, n0 + nx + 2, n0 + nx + 1};
    for (int k = 0; k < 4; k++) {
        const int32_t n = node[k];
        if (what & Z_MASS)
            b->mass[n] += a->m[k];
        if (what & Z_MOM) {
            b->mom[2 * n] += a->mx[k];
            b->mom[2 * n + 1] += a->my[k];
        }
        if (what & Z_FORCE) {
            b->force[2 * n] += a->fx[k];
            b->force[2 * n + 1] += a->fy[k];
        }
    }
}

PM_HOT static void p2g_range_lq(pm_sim *s, size_t lo, size_t hi, const scatter_buf *b, const void *vc, range_out *out)
{
    (void)out;
    const p2g_ctx *c = vc;
    const pm_particles *p = &s->p;
    const lq_grid q = lq_of(&s->grid);
    const double *restrict x = p->x, *restrict v = p->v, *restrict acc = p->a, *restrict mass = p->mass;
    const double *restrict vol = p->vol, *restrict sig = p->stress;
    const int32_t *restrict cell = p->cell;
    const int axi = s->c->formulation == PM_AXISYMMETRIC, shifted = c->shift != 0.0;
    const unsigned what = Z_MASS | Z_MOM | (c->with_force ? Z_FORCE : 0u);
    const double shift = c->shift, g0 = c->g[0], g1 = c->g[1];
    cell_sums a;
    memset(&a, 0, sizeof a);
    int32_t cur = -1, cx = 0, cy = 0;
    for (size_t i = lo; i < hi; i++) {
        if (cell[i] != cur) {
            if (cur >= 0)
                add_cell_sums(b, lq_node0(&q, cx, cy), q.nx, &a, what);
            memset(&a, 0, sizeof a);
            cur = cell[i];
            lq_cell(&q, cur, &cx, &cy);
        }
        double N[4], dN[4][2];
        lq_eval(&q, x + 2 * i, cx, cy, N, dN);
        const double m = mass[i];
        /* momentum of v, not v + 0 * a: the schemes without a shift need not read a at all */
        const double vx = shifted ? v[2 * i] + shift * acc[2 * i] : v[2 * i];
        const double vy = shifted ? v[2 * i + 1] + shift * acc[2 * i + 1] : v[2 * i + 1];
        for (int k = 0; k < 4; k++) {
            const double w = N[k] * m;
            a.m[k] += w;
            a.mx[k] += w * vx;
            a.my[k] += w * vy;
        }
        if (what & Z_FORCE) {
            const double *sg = sig + PM_NS * i;
            const double V = vol[i], sxx = sg[PM_SXX], syy = sg[PM_SYY], sxy = sg[PM_SXY];
            const double hoop = axi ? sg[PM_SZZ] / x[2 * i] : 0.0;
            for (int k = 0; k < 4; k++) {
                double tx = sxx * dN[k][0] + sxy * dN[k][1];
                if (axi)
                    tx += hoop * N[k];
                a.fx[k] += -V * tx + N[k] * m * g0;
                a.fy[k] += -V * (sxy * dN[k][0] + syy * dN[k][1]) + N[k] * m * g1;
            }
        }
    }
    if (cur >= 0)
        add_cell_sums(b, lq_node0(&q, cx, cy), q.nx, &a, what);
}

static long p2g(pm_sim *s, double mom_shift, int with_force, const double g[2])
{
    const p2g_ctx c = {mom_shift, with_force, {g[0], g[1]}};
    return scatter_pass(s, s->approx->fast_linear_quad ? p2g_range_lq : p2g_range, &c, Z_MASS | Z_MOM | Z_FORCE).bad;
}

/* MUSL: particle velocities from nodal accelerations, then their momentum back to the grid. */
static void musl_range(pm_sim *s, size_t lo, size_t hi, const scatter_buf *b, const void *vc, range_out *out)
{
    (void)out;
    const double dt = *(const double *)vc;
    pm_particles *p = &s->p;
    const double *acc = s->nd.acc;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        stencil_at(s, i, &st);
        double ax = 0, ay = 0;
        for (int k = 0; k < st.n; k++) {
            ax += st.N[k] * acc[2 * st.node[k]];
            ay += st.N[k] * acc[2 * st.node[k] + 1];
        }
        double *v = p->v + 2 * i;
        v[0] += dt * ax;
        v[1] += dt * ay;
        const double m = p->mass[i];
        for (int k = 0; k < st.n; k++) {
            const int32_t n = st.node[k];
            b->mom[2 * n] += st.N[k] * m * v[0];
            b->mom[2 * n + 1] += st.N[k] * m * v[1];
        }
    }
}

PM_HOT static void musl_range_lq(pm_sim *s, size_t lo, size_t hi, const scatter_buf *b, const void *vc, range_out *out)
{
    (void)out;
    const double dt = *(const double *)vc;
    pm_particles *p = &s->p;
    const lq_grid q = lq_of(&s->grid);
    const double *restrict x = p->x, *restrict mass = p->mass, *restrict nacc = s->nd.acc;
    double *restrict v = p->v;
    const int32_t *restrict cell = p->cell;
    cell_sums a;
    memset(&a, 0, sizeof a);
    double gx[4] = {0, 0, 0, 0}, gy[4] = {0, 0, 0, 0};
    int32_t cur = -1, cx = 0, cy = 0;
    for (size_t i = lo; i < hi; i++) {
        if (cell[i] != cur) {
            if (cur >= 0)
                add_cell_sums(b, lq_node0(&q, cx, cy), q.nx, &a, Z_MOM);
            memset(&a, 0, sizeof a);
            cur = cell[i];
            lq_cell(&q, cur, &cx, &cy);
            const int32_t n0 = lq_node0(&q, cx, cy), node[4] = {n0, n0 + 1, n0 + q.nx + 2, n0 + q.nx + 1};
            for (int k = 0; k < 4; k++) {
                gx[k] = nacc[2 * node[k]];
                gy[k] = nacc[2 * node[k] + 1];
            }
        }
        double N[4], xi, eta;
        lq_N(&q, x + 2 * i, cx, cy, N, &xi, &eta);
        double ax = 0, ay = 0;
        for (int k = 0; k < 4; k++) {
            ax += N[k] * gx[k];
            ay += N[k] * gy[k];
        }
        const double vx = v[2 * i] + dt * ax, vy = v[2 * i + 1] + dt * ay;
        v[2 * i] = vx;
        v[2 * i + 1] = vy;
        const double m = mass[i];
        for (int k = 0; k < 4; k++) {
            a.mx[k] += N[k] * m * vx;
            a.my[k] += N[k] * m * vy;
        }
    }
    if (cur >= 0)
        add_cell_sums(b, lq_node0(&q, cx, cy), q.nx, &a, Z_MOM);
}

/* USL and MUSL, last pass: strain rate from `vs`, stress, velocity (USL) and position from the
 * end-of-step nodal velocity. The linear quad4 case reads the four nodes once per run of
 * particles in one cell. */
PM_HOT static void usl_finish_lq(pm_sim *s, size_t lo, size_t hi, double dt, int musl, const double *vs, range_out *o)
{
    pm_particles *p = &s->p;
    const lq_grid q = lq_of(&s->grid);
    const double *restrict nvn = s->nd.vel_new, *restrict nacc = s->nd.acc;
    const int32_t *restrict cell = p->cell;
    const int axi = s->c->formulation == PM_AXISYMMETRIC;
    double sv[4][2] = {{0}}, ev[4][2] = {{0}}, ea[4][2] = {{0}};
    int32_t cur = -1, cx = 0, cy = 0;
    for (size_t i = lo; i < hi; i++) {
        if (cell[i] != cur) {
            cur = cell[i];
            lq_cell(&q, cur, &cx, &cy);
            const int32_t n0 = lq_node0(&q, cx, cy), node[4] = {n0, n0 + 1, n0 + q.nx + 2, n0 + q.nx + 1};
            for (int k = 0; k < 4; k++)
                for (int d = 0; d < 2; d++) {
                    sv[k][d] = vs[2 * node[k] + d];
                    ev[k][d] = nvn[2 * node[k] + d];
                    ea[k][d] = musl ? 0.0 : nacc[2 * node[k] + d];
                }
        }
        double N[4], dN[4][2];
        lq_eval(&q, p->x + 2 * i, cx, cy, N, dN);
        double vg[2] = {0, 0};
        for (int k = 0; k < 4; k++) {
            vg[0] += N[k] * ev[k][0];
            vg[1] += N[k] * ev[k][1];
        }
        if (!musl) {
            double ag[2] = {0, 0};
            for (int k = 0; k < 4; k++) {
                ag[0] += N[k] * ea[k][0];
                ag[1] += N[k] * ea[k][1];
            }
            p->v[2 * i] += dt * ag[0];
            p->v[2 * i + 1] += dt * ag[1];
        }
        double L[4] = {0, 0, 0, 0}, vr = 0;
        for (int k = 0; k < 4; k++) {
            L[0] += sv[k][0] * dN[k][0];
            L[1] += sv[k][0] * dN[k][1];
            L[2] += sv[k][1] * dN[k][0];
            L[3] += sv[k][1] * dN[k][1];
        }
        if (axi) /* the hoop rate v_r / r needs the radial velocity */
            for (int k = 0; k < 4; k++)
                vr += sv[k][0] * N[k];
        double w = 0;
        if (update_stress_L(s, i, L, vr, dt, &w)) {
            o->bad = (long)i < o->bad ? (long)i : o->bad;
            continue;
        }
        o->wave = w > o->wave ? w : o->wave;
        p->x[2 * i] += dt * vg[0];
        p->x[2 * i + 1] += dt * vg[1];
    }
}

static void usl_finish(pm_sim *s, size_t lo, size_t hi, double dt, int musl, const double *vs, range_out *o)
{
    pm_particles *p = &s->p;
    const pm_nodal *nd = &s->nd;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        stencil_at(s, i, &st);
        double vg[2], ag[2];
        gather(&st, nd->vel_new, nd->acc, vg, ag);
        if (!musl) {
            p->v[2 * i] += dt * ag[0];
            p->v[2 * i + 1] += dt * ag[1];
        }
        double w = 0;
        if (update_stress(s, i, &st, vs, dt, &w)) {
            o->bad = (long)i < o->bad ? (long)i : o->bad;
            continue;
        }
        o->wave = w > o->wave ? w : o->wave;
        p->x[2 * i] += dt * vg[0];
        p->x[2 * i + 1] += dt * vg[1];
    }
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
    double g[2];
    pm_sim_gravity(s, s->t, g);
    long bad = p2g(s, 0.0, 1, g);
    if (bad != LONG_MAX)
        return fail_particle(s, bad, "is outside the grid");
    grid_update(s, dt, 1);
    pm_nodal *nd = &s->nd;
    const int lq = s->approx->fast_linear_quad;
    if (musl) {
        scatter_pass(s, lq ? musl_range_lq : musl_range, &dt, Z_MOM);
        /* nd->vel now holds the re-projected velocity used for the strain rate */
        grid_velocity_from_momentum(s, nd->vel);
    }
    const double *vs = musl ? nd->vel : nd->vel_new;
    double wave = 0;
    long failed = LONG_MAX;
    const size_t n = s->p.n;
#pragma omp parallel num_threads(nd->n_threads) reduction(min : failed) reduction(max : wave)
    {
        const size_t tid = (size_t)omp_get_thread_num(), used = (size_t)omp_get_num_threads();
        range_out o = {LONG_MAX, 0};
        if (lq)
            usl_finish_lq(s, n * tid / used, n * (tid + 1) / used, dt, musl, vs, &o);
        else
            usl_finish(s, n * tid / used, n * (tid + 1) / used, dt, musl, vs, &o);
        failed = o.bad;
        wave = o.wave;
    }
    s->max_wave = wave;
    if (failed != LONG_MAX)
        return fail_particle(s, failed, failure_text(s, failed));
    return PM_OK;
}

/* Forces and stress of the predictor-corrector and USF share this pass: strain from nodal velocity
 * `nv`, new stress, then its internal force scattered. */
typedef struct stress_force_ctx {
    double dt;
    const double *nv;
    double g[2];
} stress_force_ctx;

static void stress_force_range(pm_sim *s, size_t lo, size_t hi, const scatter_buf *b, const void *vc, range_out *o)
{
    const stress_force_ctx *c = vc;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        stencil_at(s, i, &st);
        double w = 0;
        if (update_stress(s, i, &st, c->nv, c->dt, &w)) {
            o->bad = (long)i < o->bad ? (long)i : o->bad;
            continue;
        }
        o->wave = w > o->wave ? w : o->wave;
        scatter_force(s, i, &st, c->g, b->force);
    }
}

static long stress_and_force(pm_sim *s, double dt, const double *nv, const double g[2])
{
    const stress_force_ctx c = {dt, nv, {g[0], g[1]}};
    range_out r = scatter_pass(s, stress_force_range, &c, Z_FORCE);
    s->max_wave = r.wave;
    return r.bad;
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
    pm_contact_apply(s->contact, pm_contact_field_of(nd, nd->vel_new, mfloor), dt, gamma * dt);
    if (s->mf && s->mf->transform)
        pm_mf_impose(s, nd->acc, 1);
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
    const int sort = s->sort_interval > 0 && s->step % s->sort_interval == 0 && s->grid.n_cells < UINT32_MAX;
    if (sort)
        pm_sim_sort_particles(s);
    prepare_colour(s, sort);
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
    if (s->mf) /* the particles moved with the predicted velocity in the predictor-corrector */
        return pm_mf_after_explicit(s, dt, s->c->analysis.scheme == PM_SCHEME_NEWMARK_PC ? s->nd.vel : s->nd.vel_new);
    return PM_OK;
}
