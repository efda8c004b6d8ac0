/* `pmech render`: every frame of a run redrawn with one colour range (pm_render_dir), and an
 * animation of the pictures. Frames are read twice, once for the range and once to draw, so that
 * memory holds one frame at a time whatever the run's length. */
#include "pmech/render.h"

#include "io/animate.h"
#include "io/output.h"
#include "pmech/error.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PATH_LEN 4096

/* What run.json says about how to draw the run: its title and whether it was axisymmetric. */
static void run_info(const char *dir, char *title, size_t cap, int *axisymmetric)
{
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s/run.json", dir);
    title[0] = '\0';
    *axisymmetric = 0;
    json_t *root = json_load_file(path, 0, NULL);
    if (!root)
        return;
    const char *t = json_string_value(json_object_get(root, "title"));
    const char *f = json_string_value(json_object_get(root, "formulation"));
    if (t)
        snprintf(title, cap, "%s", t);
    *axisymmetric = f && !strcmp(f, "axisymmetric");
    json_decref(root);
}

/* The bounding box of grid.vtu; 0 when there is no readable grid. */
static int grid_box(const char *dir, double lo[2], double hi[2])
{
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s/grid.vtu", dir);
    pm_frame *g = NULL;
    if (pm_frame_read(path, &g) != PM_OK) {
        pm_error_clear();
        return 0;
    }
    const double *x = pm_frame_points(g);
    lo[0] = lo[1] = INFINITY;
    hi[0] = hi[1] = -INFINITY;
    for (size_t i = 0; i < pm_frame_n_points(g); i++)
        for (int d = 0; d < 2; d++) {
            lo[d] = fmin(lo[d], x[3 * i + d]);
            hi[d] = fmax(hi[d], x[3 * i + d]);
        }
    pm_frame_free(g);
    return hi[0] > lo[0] && hi[1] > lo[1];
}

/* Pass 1: the field's range over all frames, and the particles' bounding box. */
static int scan(const pm_series *s, const char *field, double range[2], double lo[2], double hi[2], int *category)
{
    range[0] = lo[0] = lo[1] = INFINITY;
    range[1] = hi[0] = hi[1] = -INFINITY;
    double *v = NULL;
    size_t cap = 0;
    int rc = PM_OK;
    for (size_t k = 0; !rc && k < s->n; k++) {
        pm_frame *f = NULL;
        rc = pm_frame_read(s->file[k], &f);
        const size_t n = rc ? 0 : pm_frame_n_points(f);
        if (!rc && n > cap) {
            free(v);
            cap = n;
            v = malloc(cap * sizeof *v);
            if (!v)
                rc = pm_error_set(PM_ENOMEM, "out of memory reading %s", s->file[k]);
        }
        if (!rc)
            rc = pm_frame_field(f, field, v, NULL, category);
        for (size_t i = 0; !rc && i < n; i++) {
            if (isfinite(v[i])) {
                range[0] = fmin(range[0], v[i]);
                range[1] = fmax(range[1], v[i]);
            }
            for (int d = 0; d < 2; d++) {
                lo[d] = fmin(lo[d], pm_frame_points(f)[3 * i + d]);
                hi[d] = fmax(hi[d], pm_frame_points(f)[3 * i + d]);
            }
        }
        pm_frame_free(f);
    }
    free(v);
    return rc;
}

int pm_render_dir(const char *dir, const pm_render_dir_opts *o, size_t *n_written)
{
    if (n_written)
        *n_written = 0;
    if (!o->field || !o->field[0])
        return pm_error_set(PM_EINPUT, "render %s: no field given", dir);
    const char *out_dir = o->out_dir ? o->out_dir : dir;
    pm_series s;
    pm_check(pm_series_read(dir, &s));
    if (o->out_dir && pm_mkdir_p(o->out_dir) != PM_OK) {
        pm_series_free(&s);
        return PM_EIO;
    }
    if (s.n == 0) {
        pm_series_free(&s);
        return pm_error_set(PM_EINPUT, "render %s: particles.pvd lists no frame", dir);
    }
    double range[2], plo[2], phi[2], lo[2], hi[2];
    int category = 0;
    int rc = scan(&s, o->field, range, plo, phi, &category);
    if (!rc && !grid_box(dir, lo, hi)) {
        /* no grid: the particles' box with a margin of 5 % */
        for (int d = 0; d < 2; d++) {
            const double m = 0.05 * fmax(phi[d] - plo[d], 1e-9);
            lo[d] = plo[d] - m;
            hi[d] = phi[d] + m;
        }
    }
    if (o->range) {
        range[0] = o->range[0];
        range[1] = o->range[1];
    } else if (!(range[0] <= range[1])) {
        range[0] = range[1] = 0;
    }
    if (!o->range && !(range[1] > range[0])) {
        const double d = range[0] != 0 ? 0.01 * fabs(range[0]) : 1.0;
        range[0] -= d;
        range[1] += d;
    }
    char title[256], stem[128], path[PATH_LEN];
    int axisymmetric;
    run_info(dir, title, sizeof title, &axisymmetric);
    snprintf(stem, sizeof stem, "%s", o->field);
    for (char *c = stem; *c; c++)
        if (*c == '.' || *c == '/')
            *c = '_';
    pm_render_opts ro = {.width = o->width, .range = category ? NULL : range, .title = title,
                         .show_time = 1, .axisymmetric = axisymmetric};
    for (size_t k = 0; !rc && k < s.n; k++) {
        pm_frame *f = NULL;
        rc = pm_frame_read(s.file[k], &f);
        if (rc)
            break;
        ro.time = isfinite(pm_frame_time(f)) ? pm_frame_time(f) : s.time[k];
        snprintf(path, sizeof path, "%s/%s_%06zu.png", out_dir, stem, k);
        rc = pm_render_frame(path, f, lo, hi, o->field, &ro);
        pm_frame_free(f);
        if (!rc && n_written)
            (*n_written)++;
        if (!rc && !o->quiet)
            fprintf(stderr, "\rpmech render: %s (%zu of %zu)", path, k + 1, s.n);
    }
    if (!o->quiet)
        fputc('\n', stderr);
    if (!rc && o->animation) {
        char pattern[PATH_LEN];
        snprintf(pattern, sizeof pattern, "%s/%s_%%06d.png", out_dir, stem);
        rc = pm_animate(pattern, o->fps > 0 ? o->fps : 10, o->animation);
    }
    pm_series_free(&s);
    return rc;
}
