/* Pictures of a run with one colour range (run_pictures.h). */
#include "io/run_pictures.h"

#include "pmech/error.h"
#include "pmech/frame.h"
#include "pmech/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct pm_run_pictures {
    char dir[PM_PATH_MAX];
    char title[256];
    pm_field field;
    int width, axisymmetric, fixed, category;
    double lo[2], hi[2];   /* the region shown */
    double range[2];       /* fixed, or the union of all frames so far */
    double (*used)[2];     /* the range each frame was drawn with */
    size_t n_used, cap;
};

int pm_run_pictures_open(pm_run_pictures **out, const pm_case *c, const char *dir, const pm_grid *g)
{
    *out = NULL;
    const int f = pm_field_from_name(c->output.pictures);
    if (!c->output.pictures[0] || f < 0)
        return PM_OK;
    pm_run_pictures *rp = calloc(1, sizeof *rp);
    if (!rp)
        return pm_error_set(PM_ENOMEM, "out of memory for the pictures of the run");
    snprintf(rp->dir, sizeof rp->dir, "%s", dir);
    snprintf(rp->title, sizeof rp->title, "%s", c->title);
    rp->field = (pm_field)f;
    rp->width = c->output.picture_width > 0 ? c->output.picture_width : 800;
    rp->axisymmetric = c->formulation == PM_AXISYMMETRIC;
    rp->category = rp->field == PM_FIELD_BODY || rp->field == PM_FIELD_MATERIAL;
    rp->fixed = !isnan(c->output.picture_range[0]);
    rp->range[0] = rp->fixed ? c->output.picture_range[0] : INFINITY;
    rp->range[1] = rp->fixed ? c->output.picture_range[1] : -INFINITY;
    memcpy(rp->lo, g->lo, sizeof rp->lo);
    memcpy(rp->hi, g->hi, sizeof rp->hi);
    *out = rp;
    return PM_OK;
}

/* The range the pictures show: the union so far, a single value widened around itself. */
static void shown_range(const pm_run_pictures *rp, double r[2])
{
    r[0] = rp->range[0];
    r[1] = rp->range[1];
    if (!(r[0] <= r[1]))
        r[0] = r[1] = 0;
    if (!(r[1] > r[0])) {
        const double d = r[0] != 0 ? 0.01 * fabs(r[0]) : 1.0;
        r[0] -= d;
        r[1] += d;
    }
}

static void picture_path(const pm_run_pictures *rp, size_t frame, char *path, size_t cap)
{
    snprintf(path, cap, "%s/particles_%06zu.png", rp->dir, frame);
}

int pm_run_pictures_frame(pm_run_pictures *rp, size_t frame, double t, const pm_particles *p)
{
    if (!rp)
        return PM_OK;
    if (frame >= rp->cap) {
        const size_t cap = rp->cap ? 2 * rp->cap : 64;
        double(*u)[2] = realloc(rp->used, cap * sizeof *u);
        if (!u)
            return pm_error_set(PM_ENOMEM, "out of memory for the pictures of the run");
        rp->used = u;
        rp->cap = cap;
    }
    double r[2];
    if (!rp->category && !rp->fixed && pm_field_range(p, rp->field, r) == PM_OK) {
        rp->range[0] = fmin(rp->range[0], r[0]);
        rp->range[1] = fmax(rp->range[1], r[1]);
    }
    pm_error_clear();
    shown_range(rp, r);
    pm_grid box;
    memset(&box, 0, sizeof box);
    memcpy(box.lo, rp->lo, sizeof box.lo);
    memcpy(box.hi, rp->hi, sizeof box.hi);
    const pm_render_opts o = {.width = rp->width, .range = rp->category ? NULL : r, .title = rp->title,
                              .show_time = 1, .time = t, .axisymmetric = rp->axisymmetric};
    char path[PM_PATH_MAX + 64];
    picture_path(rp, frame, path, sizeof path);
    pm_check(pm_render_field(path, &box, p, rp->field, &o));
    rp->used[frame][0] = r[0];
    rp->used[frame][1] = r[1];
    if (frame + 1 > rp->n_used)
        rp->n_used = frame + 1;
    return PM_OK;
}

int pm_run_pictures_close(pm_run_pictures *rp)
{
    if (!rp)
        return PM_OK;
    int rc = PM_OK;
    double r[2];
    shown_range(rp, r);
    const pm_render_opts o = {.width = rp->width, .range = r, .title = rp->title, .show_time = 1,
                              .axisymmetric = rp->axisymmetric};
    for (size_t k = 0; !rp->category && k < rp->n_used; k++) {
        if (rp->used[k][0] == r[0] && rp->used[k][1] == r[1])
            continue;
        char vtu[PM_PATH_MAX + 64], png[PM_PATH_MAX + 64];
        snprintf(vtu, sizeof vtu, "%s/particles_%06zu.vtu", rp->dir, k);
        picture_path(rp, k, png, sizeof png);
        pm_frame *f = NULL;
        int r1 = pm_frame_read(vtu, &f);
        if (!r1) {
            pm_render_opts ok = o;
            ok.time = pm_frame_time(f);
            r1 = pm_render_frame(png, f, rp->lo, rp->hi, pm_field_name(rp->field), &ok);
        }
        pm_frame_free(f);
        if (r1 && !rc)
            rc = r1;
    }
    free(rp->used);
    free(rp);
    return rc;
}

size_t pm_run_pictures_state(const pm_run_pictures *rp, double range[2], const double (**used)[2])
{
    if (!rp)
        return 0;
    range[0] = rp->range[0];
    range[1] = rp->range[1];
    *used = (const double(*)[2])rp->used;
    return rp->n_used;
}

int pm_run_pictures_restore(pm_run_pictures *rp, const double range[2], const double (*used)[2], size_t n)
{
    if (!rp)
        return PM_OK;
    if (n > rp->cap) {
        double(*u)[2] = realloc(rp->used, n * sizeof *u);
        if (!u)
            return pm_error_set(PM_ENOMEM, "out of memory for the ranges of %zu pictures", n);
        rp->used = u;
        rp->cap = n;
    }
    if (n)
        memcpy(rp->used, used, n * sizeof *used);
    rp->n_used = n;
    rp->range[0] = range[0];
    rp->range[1] = range[1];
    return PM_OK;
}
