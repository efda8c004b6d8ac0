/*
 * Meshfree shape functions on a node cloud, all with a linear basis:
 *
 *   mls       seed 000 eqs. 50-58: N_I = p(x)^T M^-1(x) p(x_I) w_I(x), M = sum w_I p(x_I) p(x_I)^T,
 *             w_I the cubic spline (seed 002 eq. 40) of |x - x_I| / r.
 *   rk_cubic  seed 002 eqs. 1-14: Psi_I = C(x; x - x_I) Phi_a(x - x_I) Delta V_I with the correction
 *             C = H^T(x - x_I) M^-1 H(0), Phi_a the same cubic spline, radial or tensor product (eq. 11).
 *   lme       seed 000 eq. 61 / seed 003 eqs. 33-39: N_I = exp(-beta |d_I|^2 + lambda . d_I) / Z,
 *             Newton on lambda shared with the grid kind (pm_lme_newton() in lme.c).
 *
 * The two families are mls_rk.c (MLS and RK, one linear-moment construction with different weights)
 * and lme_cloud.c; this file is the approximation around them: the per-point candidate lists and
 * stencil cache, connect()/eval(), the smoothed gradients of nodal integration, and the options.
 *
 * The neighbours of a point are found afresh at each evaluation with the adaptive rule of seed 000
 * section 5.3: MLS/RK grow the radius until at least min_nodes nodes are inside and the moment
 * matrix is well conditioned; LME grows it until the nodes enclose the point, then adds the
 * next-nearest nodes one at a time while cond(J) exceeds its tolerance.
 */
#include "shape/meshfree.h"
#include "pmech/error.h"

#include "meshfree_shape.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MF_DEFAULT_DILATION 1.5
#define MF_DEFAULT_GROWTH 1.25
/* MLS: nodes that move with a flow are stretched apart along it and pressed together across it, so a
 * circular support can hold only one or two rows of nodes across the stretch; its moment matrix is
 * then nearly singular (gradients ten times their size, N down to -0.6) and the support must grow.
 * A regular or 0.3 h-jittered cloud gives 9-33. RK keeps the round-off bound: its volume-weighted
 * moments next to the edge of a particle cloud exceed 100 without being degenerate, and growing
 * them there changes the solution (the RKPM cantilever moves by 0.8 %). */
#define MF_DEFAULT_MLS_COND 1e2
#define MF_DEFAULT_MOMENT_COND 1e6
#define MF_DEFAULT_HESSIAN_COND 1e4
#define MF_DEFAULT_MIN_NODES 6
#define MF_DEFAULT_LME_MIN_NODES 3
#define MF_DEFAULT_LME_EXTRA 8
/* a widened stencil cache leaves room beyond the longest stencil, so that it is not widened again at
 * the next step (every widening restarts the LME lambdas) */
#define MF_SLOT_EXTRA 4

/* ---- the approximation --------------------------------------------------------------------- */

/* Margin of the candidate lists: a list made at x_L with radius R_L = r + 2 skin + delta holds every
 * node within r of any x with |x - x_L| <= delta as long as the cell list was not rebuilt, since
 * every node then moved at most 2 skin since the list was made (skin each side of its build). */
static double list_delta(const pm_cloud *c)
{
    return c->skin;
}

static double list_radius(const mf_data *md)
{
    return first_radius(md) + 2 * md->cloud->skin + list_delta(md->cloud);
}

static void lists_free(mf_lists *L)
{
    free(L->node);
    free(L->len);
    free(L->x);
    free(L->build);
    memset(L, 0, sizeof *L);
}

static int lists_alloc(mf_lists *L, const mf_data *md, size_t n)
{
    lists_free(L);
    const size_t n1 = n ? n : 1;
    /* room for 1.5 times the nodes of a list's disc in a cloud of spacing h (a denser spot makes
     * lists that do not fit: those points search the cell list) */
    const double rl = list_radius(md) / md->cloud->h;
    const double want = 1.5 * M_PI * rl * rl + 8;
    L->slot = want < 16 ? 16 : want > PM_SHAPE_CAND_MAX ? PM_SHAPE_CAND_MAX : (size_t)want;
    L->node = malloc(n1 * L->slot * sizeof *L->node);
    L->len = malloc(n1 * sizeof *L->len);
    L->x = malloc(PM_DIM * n1 * sizeof *L->x);
    L->build = malloc(n1 * sizeof *L->build);
    if (!L->node || !L->len || !L->x || !L->build) {
        lists_free(L);
        return pm_error_set(PM_ENOMEM, "out of memory for %zu candidate lists", n);
    }
    for (size_t i = 0; i < n; i++)
        L->len[i] = -1;
    L->n = n;
    return PM_OK;
}

/* List i for a point now at x: kept while x is within delta of where it was made and the cell list
 * was not rebuilt since, made anew otherwise (and then kept for the next calls). NULL when the
 * list does not fit its slot: the caller searches the cell list. */
static const mf_list *lists_get(const mf_data *md, const mf_lists *L, size_t i, const double x[2], mf_list *out)
{
    int32_t *node = L->node + i * L->slot;
    double *xl = L->x + PM_DIM * i;
    const double dx = x[0] - xl[0], dy = x[1] - xl[1], delta = list_delta(md->cloud);
    if (L->len[i] < 0 || L->build[i] != md->cloud->n_builds || !(dx * dx + dy * dy <= delta * delta)) {
        if (!isfinite(x[0]) || !isfinite(x[1]))
            return NULL;
        const int n = pm_cloud_gather(md->cloud, x, list_radius(md), (int)L->slot, node, NULL, NULL);
        L->len[i] = n <= (int)L->slot ? n : -1;
        L->build[i] = md->cloud->n_builds;
        xl[0] = x[0];
        xl[1] = x[1];
    }
    if (L->len[i] < 0)
        return NULL;
    out->node = node;
    out->n = L->len[i];
    return out;
}

static void cache_free(mf_cache *c)
{
    free(c->len);
    free(c->key);
    free(c->node);
    free(c->N);
    free(c->dN);
    free(c->lam);
    lists_free(&c->lists);
    memset(c, 0, sizeof *c);
}

static int cache_alloc(mf_cache *c, const mf_data *md, size_t n, size_t slot)
{
    cache_free(c);
    const size_t n1 = n ? n : 1;
    c->len = malloc(n1 * sizeof *c->len);
    c->key = malloc(PM_DIM * n1 * sizeof *c->key);
    c->node = malloc(n1 * slot * sizeof *c->node);
    c->N = malloc(n1 * slot * sizeof *c->N);
    c->dN = malloc(PM_DIM * n1 * slot * sizeof *c->dN);
    c->lam = calloc(PM_DIM * n1, sizeof *c->lam);
    if (!c->len || !c->key || !c->node || !c->N || !c->dN || !c->lam || lists_alloc(&c->lists, md, n)) {
        cache_free(c);
        return pm_error_set(PM_ENOMEM, "out of memory for %zu meshfree stencils", n);
    }
    for (size_t i = 0; i < PM_DIM * n; i++)
        c->key[i] = NAN;
    c->n = n;
    c->slot = slot;
    return PM_OK;
}

/* pm_meshfree_eval() for a known meshfree kind; lam as for pm_mf_lme_eval() (LME only), L a
 * candidate list for the first support or NULL. */
static int point_eval(const mf_data *md, const char *name, const double x[2], double lam[2], const mf_list *L,
                      pm_stencil *s)
{
    s->n = 0;
    if (!isfinite(x[0]) || !isfinite(x[1]))
        return pm_error_set(PM_ESIM, "%s: non-finite point (%g, %g)", name, x[0], x[1]);
    return md->kind == MF_LME ? pm_mf_lme_eval(md, x, lam, L, s) : pm_mf_moment_eval(md, x, L, s);
}

/*
 * Stabilised conforming nodal integration (Chen et al. 2001): when the integration points are the
 * nodes themselves (RKPM), point gradients leave spurious zero-energy modes and fail the linear
 * patch test. The gradient at a point is instead the average over its cell, a square of the
 * point's area centred on it: grad N_I = 1/A * boundary integral of N_I n, by two Gauss points on
 * each side. The cells of seeded particles tile the body, so the smoothed gradients integrate a
 * linear field exactly (the integration constraint that makes the patch test pass). Values N stay
 * those at the point.
 */
static int smoothed_eval(const pm_approx *a, const double x[2], double half, pm_stencil *s)
{
    pm_check(pm_meshfree_eval(a, x, s));
    for (int k = 0; k < s->n; k++)
        s->dN[k][0] = s->dN[k][1] = 0.0;
    static const double g = 0.57735026918962576; /* 1 / sqrt 3 */
    static const double nrm[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (int e = 0; e < 4; e++) {
        for (int q = 0; q < 2; q++) {
            const double t = (q ? g : -g) * half;
            const double xq[2] = {x[0] + nrm[e][0] * half - nrm[e][1] * t, x[1] + nrm[e][1] * half + nrm[e][0] * t};
            pm_stencil sq;
            pm_check(pm_meshfree_eval(a, xq, &sq));
            for (int k = 0; k < sq.n; k++) {
                int at = 0;
                while (at < s->n && s->node[at] != sq.node[k])
                    at++;
                if (at == s->n) {
                    if (s->n == PM_STENCIL_MAX)
                        return pm_error_set(PM_ESIM, "the smoothing cell at (%g, %g) touches more than %d nodes: "
                                            "reduce support_radius", x[0], x[1], PM_STENCIL_MAX);
                    s->node[at] = sq.node[k];
                    s->N[at] = 0.0;
                    s->dN[at][0] = s->dN[at][1] = 0.0;
                    s->n++;
                }
                /* each Gauss point weighs half a side: half; the area is (2 half)^2 */
                const double w = sq.N[k] * half / (4 * half * half);
                s->dN[at][0] += w * nrm[e][0];
                s->dN[at][1] += w * nrm[e][1];
            }
        }
    }
    return PM_OK;
}

/* Evaluate every point once into the cache. A stencil longer than the slot leaves the point
 * uncached and reports its length, so that the caller can widen the slot and try again. */
static int cache_fill(pm_approx *a, const pm_particles *p, long *bad, int *longest)
{
    const mf_data *md = a->data;
    const mf_cache *c = &md->cache;
    const int axisym = md->axisym;
    const double h_warm = md->cloud->h;
    long first_bad = LONG_MAX;
    int most = 0;
#pragma omp parallel for schedule(dynamic, 256) num_threads(a->n_threads) reduction(min : first_bad) \
    reduction(max : most)
    for (size_t i = 0; i < p->n; i++) {
        pm_stencil st;
        const double *x = p->x + PM_DIM * i;
        /* LME: start Newton from this slot's last lambda if the point it belongs to was near x (the
         * periodic sort of the particles may have given the slot to another one far away) */
        double *lam = c->lam + PM_DIM * i;
        if (!(fabs(x[0] - c->key[PM_DIM * i]) + fabs(x[1] - c->key[PM_DIM * i + 1]) < h_warm))
            lam[0] = lam[1] = 0;
        c->len[i] = -1;
        c->key[PM_DIM * i] = x[0];
        c->key[PM_DIM * i + 1] = x[1];
        /* the cell of a point: its area (per radian in axisymmetric runs the volume is r times it) */
        const double area = p->vol && p->vol[i] > 0 ? p->vol[i] / (axisym && x[0] > 0 ? x[0] : 1.0) : 0.0;
        int rc;
        if (md->smooth && area > 0)
            rc = smoothed_eval(a, x, 0.5 * sqrt(area), &st);
        else {
            mf_list buf;
            rc = point_eval(md, a->ops->name, x, lam, lists_get(md, &c->lists, i, x, &buf), &st);
        }
        if (rc != PM_OK) {
            lam[0] = lam[1] = 0;
            first_bad = (long)i < first_bad ? (long)i : first_bad;
            continue;
        }
        most = st.n > most ? st.n : most;
        if ((size_t)st.n > c->slot)
            continue;
        const size_t o = i * c->slot;
        memcpy(c->node + o, st.node, (size_t)st.n * sizeof *st.node);
        memcpy(c->N + o, st.N, (size_t)st.n * sizeof *st.N);
        memcpy(c->dN + PM_DIM * o, st.dN, PM_DIM * (size_t)st.n * sizeof(double));
        c->len[i] = st.n;
    }
    *bad = first_bad;
    *longest = most;
    return PM_OK;
}

/* Refresh the cell list, then the shape functions of every point at its current position. The
 * cache is sized on the first call and widened only when a stencil outgrows it. */
static int mf_connect(pm_approx *a, pm_particles *p)
{
    mf_data *md = a->data;
    pm_check(pm_cloud_update(md->cloud, NULL));
    if (!p || p->n == 0)
        return PM_OK;
    if (md->cache.n != p->n || md->cache.slot == 0)
        pm_check(cache_alloc(&md->cache, md, p->n, md->cache.slot ? md->cache.slot : 24));
    long bad;
    int longest;
    pm_check(cache_fill(a, p, &bad, &longest));
    if (bad == LONG_MAX && (size_t)longest > md->cache.slot) {
        pm_check(cache_alloc(&md->cache, md, p->n, (size_t)longest + MF_SLOT_EXTRA));
        pm_check(cache_fill(a, p, &bad, &longest));
    }
    if (bad != LONG_MAX) {
        pm_stencil st;
        int rc = pm_meshfree_eval(a, p->x + PM_DIM * bad, &st);
        return pm_error_prefix(rc ? rc : PM_ESIM, "particle %ld at (%g, %g): ", bad, p->x[PM_DIM * bad],
                               p->x[PM_DIM * bad + 1]);
    }
    return PM_OK;
}

static int mf_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    const mf_cache *c = &((const mf_data *)a->data)->cache;
    const double *x = p->x + PM_DIM * ip;
    if (ip < c->n && c->len[ip] >= 0 && c->key[PM_DIM * ip] == x[0] && c->key[PM_DIM * ip + 1] == x[1]) {
        const size_t o = ip * c->slot;
        s->n = c->len[ip];
        memcpy(s->node, c->node + o, (size_t)s->n * sizeof *s->node);
        memcpy(s->N, c->N + o, (size_t)s->n * sizeof *s->N);
        memcpy(s->dN, c->dN + PM_DIM * o, PM_DIM * (size_t)s->n * sizeof(double));
        return PM_OK;
    }
    int rc = pm_meshfree_eval(a, x, s);
    return rc ? pm_error_prefix(rc, "particle %zu: ", ip) : PM_OK;
}

static void mf_destroy(pm_approx *a)
{
    mf_data *md = a->data;
    if (md) {
        cache_free(&md->cache);
        lists_free(&md->node_lists);
        free(md->node_lam);
    }
    free(a->data);
    a->data = NULL;
}

/* The boundary transform is what makes mls and rk_cubic take prescribed values at the nodes; LME
 * has the Kronecker delta on the boundary of the cloud's hull already. */
const pm_approx_ops pm_approx_mls_ops = {.name = "mls", .methods = PM_APPROX_GMM, .interpolating = 0,
                                         .connect = mf_connect, .eval = mf_eval, .destroy = mf_destroy};
const pm_approx_ops pm_approx_lme_cloud_ops = {.name = "lme", .methods = PM_APPROX_GMM, .interpolating = 1,
                                               .connect = mf_connect, .eval = mf_eval, .destroy = mf_destroy};
const pm_approx_ops pm_approx_rk_cubic_ops = {.name = "rk_cubic", .methods = PM_APPROX_RKPM, .interpolating = 0,
                                              .connect = mf_connect, .eval = mf_eval, .destroy = mf_destroy};

pm_cloud *pm_meshfree_cloud(const pm_approx *a)
{
    return pm_approx_is_meshfree(a) ? ((const mf_data *)a->data)->cloud : NULL;
}

double pm_meshfree_radius(const pm_approx *a)
{
    return pm_approx_is_meshfree(a) ? ((const mf_data *)a->data)->r0 : NAN;
}

int pm_meshfree_eval(const pm_approx *a, const double x[2], pm_stencil *s)
{
    if (!pm_approx_is_meshfree(a))
        return pm_error_set(PM_EINPUT, "pm_meshfree_eval: '%s' is not a meshfree approximation",
                            a ? a->ops->name : "(null)");
    double lam[2] = {0, 0};
    return point_eval(a->data, a->ops->name, x, lam, NULL, s);
}

int pm_meshfree_eval_node(const pm_approx *a, size_t node, pm_stencil *s)
{
    if (!pm_approx_is_meshfree(a))
        return pm_error_set(PM_EINPUT, "pm_meshfree_eval_node: '%s' is not a meshfree approximation",
                            a ? a->ops->name : "(null)");
    const mf_data *md = a->data;
    if (node >= md->cloud->n)
        return pm_error_set(PM_EINPUT, "pm_meshfree_eval_node: node %zu of a cloud of %zu", node, md->cloud->n);
    const double x[2] = {md->cloud->x[PM_DIM * node], md->cloud->x[PM_DIM * node + 1]};
    double *lam = md->node_lam + PM_DIM * node;
    mf_list buf;
    const int rc = point_eval(md, a->ops->name, x, lam, lists_get(md, &md->node_lists, node, x, &buf), s);
    if (rc != PM_OK)
        lam[0] = lam[1] = 0;
    return rc;
}

int pm_meshfree_state_get(const pm_approx *a, pm_meshfree_state *st)
{
    if (!pm_approx_is_meshfree(a))
        return pm_error_set(PM_EINPUT, "pm_meshfree_state_get: '%s' is not a meshfree approximation",
                            a ? a->ops->name : "(null)");
    const mf_data *md = a->data;
    const int lme = md->kind == MF_LME;
    *st = (pm_meshfree_state){.n_points = md->cache.n, .slot = md->cache.slot, .n_nodes = md->cloud->n};
    if (lme) {
        st->key = md->cache.key;
        st->lam = md->cache.lam;
        st->node_lam = md->node_lam;
    }
    return PM_OK;
}

int pm_meshfree_state_resize(pm_approx *a, size_t n_points, size_t slot)
{
    if (!pm_approx_is_meshfree(a))
        return pm_error_set(PM_EINPUT, "pm_meshfree_state_resize: '%s' is not a meshfree approximation",
                            a ? a->ops->name : "(null)");
    mf_data *md = a->data;
    if (n_points == 0) {
        cache_free(&md->cache);
        return PM_OK;
    }
    if (slot < 1 || slot > PM_STENCIL_MAX + MF_SLOT_EXTRA)
        return pm_error_set(PM_EINPUT, "meshfree stencils of %zu entries (1 to %d)", slot,
                            PM_STENCIL_MAX + MF_SLOT_EXTRA);
    return cache_alloc(&md->cache, md, n_points, slot);
}

pm_meshfree_opts pm_meshfree_opts_default(void)
{
    return (pm_meshfree_opts){.support_radius = NAN, .dilation = NAN, .lme_gamma = NAN, .cond_tol = NAN,
                              .growth = NAN, .min_nodes = 0, .lme_max_extra = 0, .rk_tensor = 0,
                              .smoothing = 0, .axisymmetric = 0};
}

/* A set option must be a positive finite number; NAN means "default". */
static int opt_value(double v, double def, const char *what, double *out)
{
    if (isnan(v)) {
        *out = def;
        return PM_OK;
    }
    if (!(v > 0) || !isfinite(v))
        return pm_error_set(PM_EINPUT, "%s must be a positive number, not %g", what, v);
    *out = v;
    return PM_OK;
}

/* The set-up shared by the three kinds (pm_cloud_kind::init); the kind decides the defaults. */
static int mf_init(pm_approx *a, mf_kind kind, pm_cloud *cloud, const pm_meshfree_opts *opts)
{
    const char *name = a->ops->name;
    const pm_meshfree_opts o = opts ? *opts : pm_meshfree_opts_default();
    mf_data *md = calloc(1, sizeof *md);
    if (!md)
        return pm_error_set(PM_ENOMEM, "out of memory");
    md->kind = kind;
    md->cloud = cloud;
    const double h = cloud->h;
    double f = MF_DEFAULT_DILATION;
    int rc = opt_value(o.dilation, MF_DEFAULT_DILATION, "dilation", &f);
    if (!rc)
        rc = opt_value(o.lme_gamma, PM_LME_DEFAULT_GAMMA, "lme_gamma", &md->gamma);
    if (!rc)
        rc = opt_value(o.growth, MF_DEFAULT_GROWTH, "growth", &md->growth);
    if (!rc)
        rc = opt_value(o.cond_tol, kind == MF_LME ? MF_DEFAULT_HESSIAN_COND
                                       : kind == MF_MLS ? MF_DEFAULT_MLS_COND : MF_DEFAULT_MOMENT_COND,
                       "cond_tol",
                       &md->cond_tol);
    md->beta = md->gamma / (h * h);
    const double r_def = kind == MF_LME ? fmax(h * sqrt(-log(PM_LME_PRIOR_TOL) / md->gamma), sqrt(2.0) * h)
                                        : f * sqrt(2.0 * h * h);
    if (!rc)
        rc = opt_value(o.support_radius, r_def, "support_radius", &md->r0);
    md->min_nodes = o.min_nodes > 0 ? o.min_nodes : kind == MF_LME ? MF_DEFAULT_LME_MIN_NODES : MF_DEFAULT_MIN_NODES;
    md->max_extra = o.lme_max_extra > 0 ? o.lme_max_extra : MF_DEFAULT_LME_EXTRA;
    md->tensor = kind == MF_RK && o.rk_tensor;
    md->smooth = o.smoothing > 0 || (o.smoothing == 0 && kind == MF_RK);
    md->axisym = o.axisymmetric != 0;
    if (!rc && !(md->growth > 1))
        rc = pm_error_set(PM_EINPUT, "%s: growth must exceed 1, not %g", name, md->growth);
    if (!rc && (md->min_nodes < 3 || md->min_nodes > PM_STENCIL_MAX || o.min_nodes < 0))
        rc = pm_error_set(PM_EINPUT, "%s: min_nodes must be 3 to %d, not %d", name, PM_STENCIL_MAX, o.min_nodes);
    if (!rc && o.lme_max_extra < 0)
        rc = pm_error_set(PM_EINPUT, "%s: lme_max_extra must not be negative", name);
    if (!rc) {
        md->node_lam = calloc(PM_DIM * cloud->n, sizeof *md->node_lam);
        rc = md->node_lam ? lists_alloc(&md->node_lists, md, cloud->n) : pm_error_set(PM_ENOMEM, "out of memory");
    }
    if (rc) {
        lists_free(&md->node_lists);
        free(md->node_lam);
        free(md);
        return rc;
    }
    a->data = md;
    a->opts.lme_gamma = md->gamma;
    a->opts.support_radius = md->r0;
    return PM_OK;
}

int pm_mf_init_mls(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts)
{
    return mf_init(a, MF_MLS, cloud, opts);
}

int pm_mf_init_lme(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts)
{
    return mf_init(a, MF_LME, cloud, opts);
}

int pm_mf_init_rk(pm_approx *a, pm_cloud *cloud, const pm_meshfree_opts *opts)
{
    return mf_init(a, MF_RK, cloud, opts);
}
