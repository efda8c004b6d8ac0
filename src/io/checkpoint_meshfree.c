/*
 * The group /meshfree of a checkpoint (checkpoint_meshfree.h; layout in docs/checkpoint.md).
 *
 * A GMM or RKPM step reads, besides the particles and nodal arrays, the node cloud: its positions, and
 * the cell list that answers every neighbour search. The list is rebuilt only when a node has moved
 * farther than the skin since the last build, and the order in which it holds the nodes (a stable
 * counting sort of the built positions) is the order of every stencil and so of every shape-function
 * sum. That order is a function of the positions at the last build and the cell side alone, so those
 * two are stored and the list is rebuilt from them: no history beyond them is needed. LME adds each
 * point's and each node's last lambda (the next Newton solve starts from it, and a start elsewhere
 * converges to other last digits) and the size of the stencil cache (widening it restarts them).
 * Implicit GMM keeps each node's velocity and acceleration of the last step for the predictor.
 */
#include "io/checkpoint_meshfree.h"

#include "pmech/error.h"
#include "solver/meshfree_internal.h"

#include <stdlib.h>
#include <string.h>

static int put_long(const ck_file *f, hid_t g, const char *name, long v)
{
    const int64_t x = v;
    return ck_attr_write(f, g, name, CK_INT64, &x);
}

static int get_long(const ck_file *f, hid_t g, const char *name, long *v)
{
    int64_t x = 0;
    pm_check(ck_attr_read(f, g, name, CK_INT64, &x));
    *v = (long)x;
    return PM_OK;
}

int pm_ck_write_meshfree(const ck_file *f, hid_t g, const pm_sim *s)
{
    const pm_mf *mf = s->mf;
    const pm_cloud *c = mf->cloud;
    pm_meshfree_state st;
    pm_check(pm_meshfree_state_get(s->approx, &st));
    const int32_t history = mf->history;
    pm_check(ck_attr_write_string(f, g, "shape_function", s->approx->ops->name));
    pm_check(ck_attr_write(f, g, "cell", CK_DOUBLE, &c->cell));
    pm_check(put_long(f, g, "builds", (long)c->n_builds));
    pm_check(put_long(f, g, "cache_points", (long)st.n_points));
    pm_check(put_long(f, g, "cache_slot", (long)st.slot));
    pm_check(ck_attr_write(f, g, "history", CK_INT32, &history));
    pm_check(ck_write(f, g, "x", CK_DOUBLE, c->x, c->n, PM_DIM));
    pm_check(ck_write(f, g, "x_built", CK_DOUBLE, c->x_built, c->n, PM_DIM));
    pm_check(ck_write(f, g, "volume", CK_DOUBLE, c->vol, c->n, 1));
    const size_t nh = mf->history ? c->n : 0;
    pm_check(ck_write(f, g, "velocity_history", CK_DOUBLE, mf->vh, nh, PM_DIM));
    pm_check(ck_write(f, g, "acceleration_history", CK_DOUBLE, mf->ah, nh, PM_DIM));
    /* mls and rk_cubic keep no per-point state that changes a result: empty datasets */
    const size_t np = st.lam ? st.n_points : 0, nn = st.node_lam ? st.n_nodes : 0;
    pm_check(ck_write(f, g, "point_key", CK_DOUBLE, st.key, np, PM_DIM));
    pm_check(ck_write(f, g, "point_lambda", CK_DOUBLE, st.lam, np, PM_DIM));
    return ck_write(f, g, "node_lambda", CK_DOUBLE, st.node_lam, nn, PM_DIM);
}

static int read_cloud(const ck_file *f, hid_t g, pm_cloud *c)
{
    double cell = 0;
    long builds = 0;
    pm_check(ck_attr_read(f, g, "cell", CK_DOUBLE, &cell));
    pm_check(get_long(f, g, "builds", &builds));
    double *x = malloc(2 * c->n * PM_DIM * sizeof *x); /* the positions now, then at the last build */
    if (!x)
        return pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    double *built = x + c->n * PM_DIM;
    int rc = ck_read(f, g, "x", CK_DOUBLE, x, c->n, PM_DIM);
    if (!rc)
        rc = ck_read(f, g, "x_built", CK_DOUBLE, built, c->n, PM_DIM);
    if (!rc)
        rc = ck_read(f, g, "volume", CK_DOUBLE, c->vol, c->n, 1);
    if (!rc && builds < 1)
        rc = pm_error_set(PM_EINPUT, "%s: /meshfree: %ld builds of the cell list (at least 1)", f->path, builds);
    if (!rc && (rc = pm_cloud_restore(c, x, built, cell, (size_t)builds)) != PM_OK)
        pm_error_prefix(rc, "%s: /meshfree: ", f->path);
    free(x);
    return rc;
}

/* The stencil cache at its stored size, with LME's lambdas. */
static int read_approx(const ck_file *f, hid_t g, pm_approx *a, size_t cap)
{
    long points = 0, slot = 0;
    pm_check(get_long(f, g, "cache_points", &points));
    pm_check(get_long(f, g, "cache_slot", &slot));
    /* the cache has one entry per particle of the last connect(): never more than the arrays hold */
    if (points < 0 || (size_t)points > cap || slot < 0)
        return pm_error_set(PM_EINPUT, "%s: /meshfree: a stencil cache of %ld points does not fit this case's %zu "
                            "particles", f->path, points, cap);
    int rc = pm_meshfree_state_resize(a, (size_t)points, (size_t)slot);
    if (rc)
        return pm_error_prefix(rc, "%s: /meshfree: ", f->path);
    pm_meshfree_state st;
    pm_check(pm_meshfree_state_get(a, &st));
    const size_t np = st.lam ? st.n_points : 0, nn = st.node_lam ? st.n_nodes : 0;
    pm_check(ck_read(f, g, "point_key", CK_DOUBLE, st.key, np, PM_DIM));
    pm_check(ck_read(f, g, "point_lambda", CK_DOUBLE, st.lam, np, PM_DIM));
    return ck_read(f, g, "node_lambda", CK_DOUBLE, st.node_lam, nn, PM_DIM);
}

int pm_ck_read_meshfree(const ck_file *f, hid_t g, pm_sim *s)
{
    pm_mf *mf = s->mf;
    char kind[64];
    pm_check(ck_attr_read_string(f, g, "shape_function", kind, sizeof kind));
    if (strcmp(kind, s->approx->ops->name))
        return pm_error_set(PM_EINPUT, "%s: /meshfree holds a '%s' run, the case runs '%s'", f->path, kind,
                            s->approx->ops->name);
    int32_t history = 0;
    pm_check(ck_attr_read(f, g, "history", CK_INT32, &history));
    pm_check(read_cloud(f, g, mf->cloud));
    pm_check(read_approx(f, g, s->approx, s->p.cap));
    const size_t nh = history ? mf->cloud->n : 0;
    pm_check(ck_read(f, g, "velocity_history", CK_DOUBLE, mf->vh, nh, PM_DIM));
    pm_check(ck_read(f, g, "acceleration_history", CK_DOUBLE, mf->ah, nh, PM_DIM));
    mf->history = history != 0;
    const int rc = pm_mf_restored(s);
    return rc ? pm_error_prefix(rc, "%s: the boundary rows at the stored nodes: ", f->path) : PM_OK;
}
