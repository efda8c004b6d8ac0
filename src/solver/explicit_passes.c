/*
 * The particle passes of the explicit step. Each pass is written once, as an always-inline body with
 * a compile-time flag LQ, and instantiated twice: LQ = 1 for the structured linear quad4 grid, whose
 * stencil is computed inline and whose four nodes are read and written once per run of particles in
 * one cell (particles are sorted by cell), and LQ = 0 for any approximation through pm_stencil.
 *
 * Scatters in the LQ instances add per-cell sums to the nodes, the others add particle by particle:
 * the two orders round differently, and each instance keeps its own so that a run's results do not
 * depend on how its passes are written. Loops over vector components run to PM_DIM; they unroll to
 * the same code as the written-out 2-D ones.
 */
#include "explicit_internal.h"
#include "contact/multibody.h"
#include "fbar.h"
#include "lq_cell.h"
#include "point_update.h"

#include "pmech/error.h"

#include <limits.h>
#include <omp.h>
#include <string.h>

#if PM_DIM != 2
#error "the linear quad4 passes are written for 2-D grids"
#endif

/*
 * The LQ particle loops work on four nodes at a time: on x86-64 an AVX2 copy of them is built beside
 * the baseline one and chosen at load time where the processor has AVX2 (8 % fewer instructions per
 * particle-step). AVX2 alone has no fused multiply-add and C11 mode contracts nothing, so both copies
 * compute bit for bit the same results.
 */
#define PM_HOT
#if defined(__x86_64__) && defined(__linux__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#undef PM_HOT
#define PM_HOT __attribute__((target_clones("avx2", "default")))
#endif
#endif

/* Pass bodies: inlined into each instance so that the LQ flag folds away. */
#define PM_BODY static inline __attribute__((always_inline))

/* Shape functions of particle i through the approximation's interface (the linear quad4 case
 * inline, without the per-cell reuse of the LQ instances). */
static inline int stencil_at(const pm_sim *s, size_t i, pm_stencil *st)
{
    if (s->approx->fast_linear_quad) { /* never with body fields (pm_sim_create) */
        const lq_grid q = lq_of(&s->grid);
        int32_t cx, cy;
        lq_cell(&q, s->p.cell[i], &cx, &cy);
        st->n = 4;
        lq_nodes(&q, cx, cy, st->node);
        lq_eval(&q, s->p.x + PM_DIM * i, cx, cy, st->N, st->dN);
        return PM_OK;
    }
    if (s->mb) /* body fields: the nodes of the particle's own field */
        return pm_xp_stencil(s, i, st);
    return s->approx->ops->eval(s->approx, &s->p, i, st);
}

/*
 * Particle i's stress update over dt from its velocity gradient (lxx, lxy, lyx, lyy) and, in
 * axisymmetric runs, its radial velocity vr; its wave speed into *wave unless the step is fixed.
 * Returns 0, or 1 if the point failed. The gradient comes in registers: read back as an array, its
 * element-wise stores could not be forwarded to a paired load, which doubled this function's time.
 */
static inline int point_step(pm_sim *s, size_t i, double lxx, double lxy, double lyx, double lyy, double vr,
                             double dt, double *wave)
{
    pm_particles *p = &s->p;
    const pm_material *m = &s->c->materials[p->material[i]];
    double *F = p->F + PM_NF * i, *sg = p->stress + PM_NS * i, *state = p->state + p->n_state * i;
    const pm_point_from from = {F, sg, state, p->vol0[i], 0};
    const double H[4] = {dt * lxx, dt * lxy, dt * lyx, dt * lyy};
    if (pm_point_update(m, s->c->formulation, &from, H, dt * vr, p->x[PM_DIM * i], dt, p->n_state, F, sg, state,
                        &p->vol[i], &p->eps_p[i], NULL))
        return 1;
    if (s->c->analysis.dt > 0)
        return 0; /* fixed step: the wave speed is not needed */
    *wave = pm_point_wave_speed(m, state, p->mass[i], p->vol[i], s->grid.h_min, p->v + PM_DIM * i);
    return 0;
}

/* Velocity gradient L = sum_k v_k (x) dN_k (xx, xy, yx, yy) and the radial velocity sum_k N_k v_k,x of a
 * stencil from nodal velocities nv. */
static inline void velocity_gradient(const pm_stencil *st, const double *nv, double L[4], double *vr)
{
    for (int j = 0; j < 4; j++)
        L[j] = 0;
    *vr = 0;
    for (int k = 0; k < st->n; k++) {
        const double *v = nv + PM_DIM * st->node[k];
        for (int a = 0; a < PM_DIM; a++)
            for (int b = 0; b < PM_DIM; b++)
                L[PM_DIM * a + b] += v[a] * st->dN[k][b];
        *vr += v[0] * st->N[k];
    }
}

/* Internal force plus weight of a particle on one node (shape function N, gradient dN): -V sigma dN
 * + N m g, and in axisymmetric runs (x = r) the hoop stress's -V sigma_tt N / r on the radial
 * component (seed 004 eq. 4; hoop = sigma_tt / r, 0 otherwise). The stress is stored as xx, yy, zz,
 * xy, not as a matrix, so the 2-D rows of sigma dN are written out. */
static inline void node_force(const double *sg, double V, double m, const double g[PM_DIM], int axi, double hoop,
                              double N, const double dN[PM_DIM], double f[PM_DIM])
{
    double tx = sg[PM_SXX] * dN[0] + sg[PM_SXY] * dN[1];
    if (axi)
        tx += hoop * N;
    f[0] = -V * tx + N * m * g[0];
    f[1] = -V * (sg[PM_SXY] * dN[0] + sg[PM_SYY] * dN[1]) + N * m * g[1];
}

/* Per-cell sums of the LQ scatters, by node of the cell (innermost, so four nodes go in one vector). */
typedef struct cell_sums {
    double m[4], mom[PM_DIM][4], f[PM_DIM][4];
} cell_sums;

static inline void add_cell_sums(const pm_scatter_buf *b, const lq_grid *q, int32_t cx, int32_t cy, const cell_sums *a,
                                 unsigned what)
{
    int32_t node[4];
    lq_nodes(q, cx, cy, node);
    for (int k = 0; k < 4; k++) {
        const size_t n = (size_t)node[k];
        if (what & PM_Z_MASS)
            b->mass[n] += a->m[k];
        for (int d = 0; d < PM_DIM; d++) {
            if (what & PM_Z_MOM)
                b->mom[PM_DIM * n + d] += a->mom[d][k];
            if (what & PM_Z_FORCE)
                b->force[PM_DIM * n + d] += a->f[d][k];
        }
    }
}

/*
 * Inside a pass body: the stencil of the current particle, from the LQ cell (Nl, dNl) or from st.
 * With LQ a constant, each folds to a plain array access.
 */
#define SN(k) (LQ ? Nl[k] : st.N[k])
#define SDN(k, d) (LQ ? dNl[k][d] : st.dN[k][d])

/*
 * The LQ cell run: when particle i is in another cell than the one before, flush (a statement
 * adding the old run's sums, if any, to the nodes of cell cx, cy), then find the new cell and its
 * nodes (node[4]) and run `load` (a statement reading what the run needs from them). Only the cell
 * is carried from one particle to the next: kept as an array, the node numbers went through memory.
 */
#define LQ_ENTER_CELL(flush, load)                                                                     \
    do {                                                                                               \
        if (LQ && cell[i] != cur) {                                                                    \
            if (cur >= 0) {                                                                            \
                flush;                                                                                 \
            }                                                                                          \
            cur = cell[i];                                                                             \
            lq_cell(&q, cur, &cx, &cy);                                                                \
            int32_t node[4];                                                                           \
            lq_nodes(&q, cx, cy, node);                                                                \
            load;                                                                                      \
        }                                                                                              \
    } while (0)

/* Pass 1 of every scheme: mass, momentum (of v + shift * a) and optionally forces to the grid. */
typedef struct p2g_ctx {
    double shift;
    int with_force;
    double g[PM_DIM];
} p2g_ctx;

PM_BODY void p2g_body(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const p2g_ctx *c, pm_range_out *out,
                      const int LQ)
{
    const pm_particles *p = &s->p;
    const lq_grid q = lq_of(&s->grid);
    const double *restrict x = p->x, *restrict v = p->v, *restrict acc = p->a, *restrict mass = p->mass;
    const double *restrict vol = p->vol, *restrict sig = p->stress;
    const int32_t *restrict cell = p->cell;
    const int axi = s->c->formulation == PM_AXISYMMETRIC, shifted = c->shift != 0.0;
    const unsigned what = PM_Z_MASS | PM_Z_MOM | (c->with_force ? (unsigned)PM_Z_FORCE : 0u);
    const double shift = c->shift;
    double g[PM_DIM];
    for (int d = 0; d < PM_DIM; d++)
        g[d] = c->g[d];
    cell_sums a;
    memset(&a, 0, sizeof a);
    pm_stencil st;
    double Nl[4], dNl[4][PM_DIM];
    int32_t cur = -1, cx = 0, cy = 0;
    for (size_t i = lo; i < hi; i++) {
        if (LQ) {
            LQ_ENTER_CELL(add_cell_sums(b, &q, cx, cy, &a, what), memset(&a, 0, sizeof a));
            lq_eval(&q, x + PM_DIM * i, cx, cy, Nl, dNl);
        } else if (stencil_at(s, i, &st) != PM_OK) {
            out->bad = (long)i < out->bad ? (long)i : out->bad;
            continue;
        }
        const int nk = LQ ? 4 : st.n;
        const double m = mass[i];
        /* momentum of v, not v + 0 * a: the schemes without a shift need not read a at all */
        double vp[PM_DIM];
        for (int d = 0; d < PM_DIM; d++)
            vp[d] = shifted ? v[PM_DIM * i + d] + shift * acc[PM_DIM * i + d] : v[PM_DIM * i + d];
        if (LQ) {
            /* node innermost: the four nodes of the cell are one vector */
            double w[4];
            for (int k = 0; k < 4; k++) {
                w[k] = Nl[k] * m;
                a.m[k] += w[k];
            }
            for (int d = 0; d < PM_DIM; d++)
                for (int k = 0; k < 4; k++)
                    a.mom[d][k] += w[k] * vp[d];
        } else {
            for (int k = 0; k < nk; k++) {
                const int32_t n = st.node[k];
                const double w = st.N[k] * m;
                b->mass[n] += w;
                for (int d = 0; d < PM_DIM; d++)
                    b->mom[PM_DIM * n + d] += w * vp[d];
            }
        }
        if (what & PM_Z_FORCE) {
            double sg[PM_NS];
            for (int j = 0; j < PM_NS; j++)
                sg[j] = sig[PM_NS * i + j];
            const double V = vol[i], hoop = axi ? sg[PM_SZZ] / x[PM_DIM * i] : 0.0;
            for (int k = 0; k < nk; k++) {
                const double dN[PM_DIM] = {SDN(k, 0), SDN(k, 1)};
                double f[PM_DIM];
                node_force(sg, V, m, g, axi, hoop, SN(k), dN, f);
                for (int d = 0; d < PM_DIM; d++) {
                    if (LQ)
                        a.f[d][k] += f[d];
                    else
                        b->force[PM_DIM * st.node[k] + d] += f[d];
                }
            }
        }
    }
    if (LQ && cur >= 0)
        add_cell_sums(b, &q, cx, cy, &a, what);
}

static void p2g_range(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *c, pm_range_out *out)
{
    p2g_body(s, lo, hi, b, c, out, 0);
}

PM_HOT static void p2g_range_lq(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *c,
                                pm_range_out *out)
{
    p2g_body(s, lo, hi, b, c, out, 1);
}

long pm_xp_p2g(pm_sim *s, double mom_shift, int with_force, const double g[PM_DIM])
{
    p2g_ctx c = {mom_shift, with_force, {0}};
    for (int d = 0; d < PM_DIM; d++)
        c.g[d] = g[d];
    const long bad = pm_scatter_pass(s, s->approx->fast_linear_quad ? p2g_range_lq : p2g_range, &c,
                                     PM_Z_MASS | PM_Z_MOM | PM_Z_FORCE).bad;
    if (s->mb && bad == LONG_MAX) /* where the body fields meet, from this step's masses */
        pm_multibody_prepare(s);
    return bad;
}

/* MUSL: particle velocities from nodal accelerations, then their momentum back to the grid. */
PM_BODY void musl_body(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, double dt, const int LQ,
                        const int BLEND)
{
    pm_particles *p = &s->p;
    const lq_grid q = lq_of(&s->grid);
    const double *restrict x = p->x, *restrict mass = p->mass, *restrict nacc = s->nd.acc;
    const double *restrict nvn = s->nd.vel_new;
    double *restrict v = p->v;
    const int32_t *restrict cell = p->cell;
    /* the FLIP share of the velocity update; the rest is PIC, the end-of-step grid velocity */
    const double pic = s->c->analysis.pic, flip = 1.0 - pic;
    cell_sums a;
    memset(&a, 0, sizeof a);
    pm_stencil st;
    double Nl[4], ga[PM_DIM][4] = {{0}}, gv[PM_DIM][4] = {{0}};
    int32_t cur = -1, cx = 0, cy = 0;
    for (size_t i = lo; i < hi; i++) {
        if (LQ) {
            LQ_ENTER_CELL(add_cell_sums(b, &q, cx, cy, &a, PM_Z_MOM), {
                memset(&a, 0, sizeof a);
                for (int k = 0; k < 4; k++)
                    for (int d = 0; d < PM_DIM; d++) {
                        ga[d][k] = nacc[PM_DIM * (size_t)node[k] + d];
                        if (BLEND)
                            gv[d][k] = nvn[PM_DIM * (size_t)node[k] + d];
                    }
            });
            double xi, eta;
            lq_N(&q, x + PM_DIM * i, cx, cy, Nl, &xi, &eta);
        } else {
            stencil_at(s, i, &st);
        }
        const int nk = LQ ? 4 : st.n;
        double ap[PM_DIM] = {0}, vg[PM_DIM] = {0};
        for (int d = 0; d < PM_DIM; d++)
            for (int k = 0; k < nk; k++) {
                ap[d] += SN(k) * (LQ ? ga[d][k] : nacc[PM_DIM * st.node[k] + d]);
                if (BLEND)
                    vg[d] += SN(k) * (LQ ? gv[d][k] : nvn[PM_DIM * st.node[k] + d]);
            }
        double vp[PM_DIM];
        for (int d = 0; d < PM_DIM; d++)
            v[PM_DIM * i + d] = vp[d] =
                BLEND ? flip * (v[PM_DIM * i + d] + dt * ap[d]) + pic * vg[d] : v[PM_DIM * i + d] + dt * ap[d];
        const double m = mass[i];
        /* node innermost: the four nodes of an LQ cell are one vector */
        for (int d = 0; d < PM_DIM; d++)
            for (int k = 0; k < nk; k++) {
                if (LQ)
                    a.mom[d][k] += SN(k) * m * vp[d];
                else
                    b->mom[PM_DIM * st.node[k] + d] += SN(k) * m * vp[d];
            }
    }
    if (LQ && cur >= 0)
        add_cell_sums(b, &q, cx, cy, &a, PM_Z_MOM);
}

static void musl_range(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *dt, pm_range_out *out)
{
    (void)out;
    if (s->c->analysis.pic > 0)
        musl_body(s, lo, hi, b, *(const double *)dt, 0, 1);
    else
        musl_body(s, lo, hi, b, *(const double *)dt, 0, 0);
}

PM_HOT static void musl_range_lq(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *dt,
                                 pm_range_out *out)
{
    (void)out;
    musl_body(s, lo, hi, b, *(const double *)dt, 1, 0);
}

/* The PIC-blending copy of the LQ instance, so that the usual one gathers no nodal velocities. */
static void musl_range_lq_blend(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *dt,
                                pm_range_out *out)
{
    (void)out;
    musl_body(s, lo, hi, b, *(const double *)dt, 1, 1);
}

void pm_xp_musl_project(pm_sim *s, double dt)
{
    const int blend = s->c->analysis.pic > 0;
    pm_scatter_pass(s, s->approx->fast_linear_quad ? (blend ? musl_range_lq_blend : musl_range_lq) : musl_range, &dt,
                    PM_Z_MOM);
}

/* USL and MUSL, last pass (see pm_xp_usl_finish). The LQ instance reads the four nodes once per run
 * of particles in one cell. */
PM_BODY void usl_finish_body(pm_sim *s, size_t lo, size_t hi, double dt, int musl, const double *vs, pm_range_out *o,
                             const int LQ, const int FB)
{
    pm_particles *p = &s->p;
    const lq_grid q = lq_of(&s->grid);
    const double *restrict nvn = s->nd.vel_new, *restrict nacc = s->nd.acc;
    const int32_t *restrict cell = p->cell;
    const int axi = s->c->formulation == PM_AXISYMMETRIC;
    pm_stencil st;
    double Nl[4], dNl[4][PM_DIM], sv[4][PM_DIM] = {{0}}, ev[4][PM_DIM] = {{0}}, ea[4][PM_DIM] = {{0}};
    int32_t cur = -1, cx = 0, cy = 0;
    for (size_t i = lo; i < hi; i++) {
        if (LQ) {
            LQ_ENTER_CELL((void)0, {
                for (int k = 0; k < 4; k++)
                    for (int d = 0; d < PM_DIM; d++) {
                        sv[k][d] = vs[PM_DIM * (size_t)node[k] + d];
                        ev[k][d] = nvn[PM_DIM * (size_t)node[k] + d];
                        ea[k][d] = musl ? 0.0 : nacc[PM_DIM * (size_t)node[k] + d];
                    }
            });
            lq_eval(&q, p->x + PM_DIM * i, cx, cy, Nl, dNl);
        } else {
            stencil_at(s, i, &st);
        }
        const int nk = LQ ? 4 : st.n;
#define SV(k, d) (LQ ? sv[k][d] : vs[PM_DIM * st.node[k] + d])
        double vg[PM_DIM] = {0};
        for (int k = 0; k < nk; k++)
            for (int d = 0; d < PM_DIM; d++)
                vg[d] += SN(k) * (LQ ? ev[k][d] : nvn[PM_DIM * st.node[k] + d]);
        if (!musl) {
            double ag[PM_DIM] = {0};
            for (int k = 0; k < nk; k++)
                for (int d = 0; d < PM_DIM; d++)
                    ag[d] += SN(k) * (LQ ? ea[k][d] : nacc[PM_DIM * st.node[k] + d]);
            for (int d = 0; d < PM_DIM; d++)
                p->v[PM_DIM * i + d] += dt * ag[d];
        }
        double L[PM_DIM * PM_DIM] = {0}, vr = 0;
        for (int k = 0; k < nk; k++)
            for (int a = 0; a < PM_DIM; a++)
                for (int c = 0; c < PM_DIM; c++)
                    L[PM_DIM * a + c] += SV(k, a) * SDN(k, c);
        if (axi) /* the hoop rate v_r / r needs the radial velocity */
            for (int k = 0; k < nk; k++)
                vr += SV(k, 0) * SN(k);
#undef SV
        if (FB) /* F-bar: the step's volume change is its cell's */
            pm_fbar_scale_rate(s->fbar->alpha[i], axi, p->x[PM_DIM * i], dt, L, &vr);
        double w = 0;
        if (point_step(s, i, L[0], L[1], L[2], L[3], vr, dt, &w)) {
            o->bad = (long)i < o->bad ? (long)i : o->bad;
            continue;
        }
        o->wave = w > o->wave ? w : o->wave;
        for (int d = 0; d < PM_DIM; d++)
            p->x[PM_DIM * i + d] += dt * vg[d];
        memcpy(p->v_grid + PM_DIM * i, vg, sizeof vg); /* output only: what moved the point */
    }
}

static void usl_finish_range(pm_sim *s, size_t lo, size_t hi, double dt, int musl, const double *vs, pm_range_out *o)
{
    if (s->fbar)
        usl_finish_body(s, lo, hi, dt, musl, vs, o, 0, 1);
    else
        usl_finish_body(s, lo, hi, dt, musl, vs, o, 0, 0);
}

PM_HOT static void usl_finish_range_lq(pm_sim *s, size_t lo, size_t hi, double dt, int musl, const double *vs,
                                       pm_range_out *o)
{
    usl_finish_body(s, lo, hi, dt, musl, vs, o, 1, 0);
}

/* The F-bar copy of the LQ instance, so that the usual one carries no test for it. */
static void usl_finish_range_lq_fbar(pm_sim *s, size_t lo, size_t hi, double dt, int musl, const double *vs,
                                     pm_range_out *o)
{
    usl_finish_body(s, lo, hi, dt, musl, vs, o, 1, 1);
}

long pm_xp_usl_finish(pm_sim *s, double dt, int musl, const double *vs)
{
    const int lq = s->approx->fast_linear_quad;
    double wave = 0;
    long failed = LONG_MAX;
    const size_t n = s->p.n;
#pragma omp parallel num_threads(s->nd.n_threads) reduction(min : failed) reduction(max : wave)
    {
        const size_t tid = (size_t)omp_get_thread_num(), used = (size_t)omp_get_num_threads();
        pm_range_out o = {LONG_MAX, 0};
        if (lq && s->fbar)
            usl_finish_range_lq_fbar(s, n * tid / used, n * (tid + 1) / used, dt, musl, vs, &o);
        else if (lq)
            usl_finish_range_lq(s, n * tid / used, n * (tid + 1) / used, dt, musl, vs, &o);
        else
            usl_finish_range(s, n * tid / used, n * (tid + 1) / used, dt, musl, vs, &o);
        failed = o.bad;
        wave = o.wave;
    }
    s->max_wave = wave;
    return failed;
}

/* The passes below run through pm_stencil for every approximation (stencil_at computes the linear
 * quad4 one inline): their scatters add particle by particle. */

/* Stress of particle i from the nodal velocities nv over its stencil st. */
static inline int stencil_stress(pm_sim *s, size_t i, const pm_stencil *st, const double *nv, double dt,
                                 double *wave)
{
    double L[4], vr;
    velocity_gradient(st, nv, L, &vr);
    if (s->fbar)
        pm_fbar_scale_rate(s->fbar->alpha[i], s->c->formulation == PM_AXISYMMETRIC, s->p.x[PM_DIM * i], dt, L, &vr);
    return point_step(s, i, L[0], L[1], L[2], L[3], vr, dt, wave);
}

typedef struct stress_force_ctx {
    double dt;
    const double *nv;
    double g[PM_DIM];
} stress_force_ctx;

static void stress_force_range(pm_sim *s, size_t lo, size_t hi, const pm_scatter_buf *b, const void *vc,
                               pm_range_out *o)
{
    const stress_force_ctx *c = vc;
    const pm_particles *p = &s->p;
    const int axi = s->c->formulation == PM_AXISYMMETRIC;
    pm_stencil st;
    for (size_t i = lo; i < hi; i++) {
        stencil_at(s, i, &st);
        double w = 0;
        if (stencil_stress(s, i, &st, c->nv, c->dt, &w)) {
            o->bad = (long)i < o->bad ? (long)i : o->bad;
            continue;
        }
        o->wave = w > o->wave ? w : o->wave;
        const double *sg = p->stress + PM_NS * i, V = p->vol[i], m = p->mass[i];
        const double hoop = axi ? sg[PM_SZZ] / p->x[PM_DIM * i] : 0.0;
        for (int k = 0; k < st.n; k++) {
            double f[PM_DIM];
            node_force(sg, V, m, c->g, axi, hoop, st.N[k], st.dN[k], f);
            for (int d = 0; d < PM_DIM; d++)
                b->force[PM_DIM * st.node[k] + d] += f[d];
        }
    }
}

long pm_xp_stress_and_force(pm_sim *s, double dt, const double *nv, const double g[PM_DIM])
{
    stress_force_ctx c = {dt, nv, {0}};
    for (int d = 0; d < PM_DIM; d++)
        c.g[d] = g[d];
    pm_range_out r = pm_scatter_pass(s, stress_force_range, &c, PM_Z_FORCE);
    s->max_wave = r.wave;
    return r.bad;
}

/* Interpolate a nodal velocity and acceleration to a particle. */
static inline void gather(const pm_stencil *st, const double *vel, const double *acc, double v[PM_DIM],
                          double a[PM_DIM])
{
    for (int d = 0; d < PM_DIM; d++)
        v[d] = a[d] = 0;
    for (int k = 0; k < st->n; k++) {
        const int32_t n = st->node[k];
        for (int d = 0; d < PM_DIM; d++) {
            v[d] += st->N[k] * vel[PM_DIM * n + d];
            a[d] += st->N[k] * acc[PM_DIM * n + d];
        }
    }
}

void pm_xp_g2p_usf(pm_sim *s, double dt)
{
    pm_particles *p = &s->p;
    const pm_nodal *nd = &s->nd;
#pragma omp parallel num_threads(nd->n_threads)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            stencil_at(s, i, &st);
            double *v = p->v_grid + PM_DIM * i, a[PM_DIM]; /* kept: the velocity the point moves with */
            gather(&st, nd->vel_new, nd->acc, v, a);
            for (int d = 0; d < PM_DIM; d++) {
                p->v[PM_DIM * i + d] += dt * a[d];
                p->x[PM_DIM * i + d] += dt * v[d];
            }
        }
    }
}

void pm_xp_g2p_newmark(pm_sim *s, double dt, double gamma)
{
    pm_particles *p = &s->p;
    const pm_nodal *nd = &s->nd;
#pragma omp parallel num_threads(nd->n_threads)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < p->n; i++) {
            stencil_at(s, i, &st);
            double *vg = p->v_grid + PM_DIM * i, ag[PM_DIM]; /* kept: the velocity the point moves with */
            gather(&st, nd->vel, nd->acc, vg, ag);
            double *v = p->v + PM_DIM * i, *a = p->a + PM_DIM * i;
            for (int d = 0; d < PM_DIM; d++) {
                v[d] += dt * ((1 - gamma) * a[d] + gamma * ag[d]);
                a[d] = ag[d];
                p->x[PM_DIM * i + d] += dt * vg[d];
            }
        }
    }
}

long pm_xp_stress_only(pm_sim *s, const double *nodal_v, double dt)
{
    long bad = LONG_MAX;
    double wave = 0;
#pragma omp parallel num_threads(s->nd.n_threads) reduction(min : bad) reduction(max : wave)
    {
        pm_stencil st;
#pragma omp for schedule(static)
        for (size_t i = 0; i < s->p.n; i++) {
            double w = 0;
            if (stencil_at(s, i, &st) != PM_OK || stencil_stress(s, i, &st, nodal_v, dt, &w))
                bad = (long)i < bad ? (long)i : bad;
            wave = w > wave ? w : wave;
        }
    }
    s->max_wave = wave;
    return bad;
}
