/* Particle pictures with cairo: each particle a square of its own size, coloured by a field. */
#include "pmech/render.h"
#include "pmech/error.h"

#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const field_names[] = {"body", "speed", "pressure", "plastic_strain", "syy", "displacement"};

int pm_field_from_name(const char *name)
{
    for (int k = 0; k < (int)(sizeof field_names / sizeof field_names[0]); k++)
        if (!strcmp(name, field_names[k]))
            return k;
    return -1;
}

const char *pm_field_name(pm_field f) { return field_names[f]; }

static double field_value(const pm_particles *p, size_t i, pm_field f)
{
    const double *s = p->stress + PM_NS * i;
    switch (f) {
    case PM_FIELD_BODY: return p->body[i];
    case PM_FIELD_SPEED: return hypot(p->v[2 * i], p->v[2 * i + 1]);
    case PM_FIELD_PRESSURE: return -(s[PM_SXX] + s[PM_SYY] + s[PM_SZZ]) / 3.0;
    case PM_FIELD_PLASTIC_STRAIN: return p->eps_p[i];
    case PM_FIELD_SYY: return s[PM_SYY];
    default: return hypot(p->x[2 * i] - p->x0[2 * i], p->x[2 * i + 1] - p->x0[2 * i + 1]);
    }
}

/* A perceptually ordered blue-green-yellow ramp (close to viridis), t in [0, 1]. */
static void ramp(double t, double rgb[3])
{
    static const double stops[5][3] = {
        {0.267, 0.005, 0.329}, {0.231, 0.322, 0.545}, {0.129, 0.569, 0.549}, {0.369, 0.788, 0.384}, {0.993, 0.906, 0.144}};
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double x = t * 4;
    int k = (int)x;
    if (k >= 4)
        k = 3;
    double u = x - k;
    for (int c = 0; c < 3; c++)
        rgb[c] = stops[k][c] * (1 - u) + stops[k + 1][c] * u;
}

static void body_colour(int b, double rgb[3])
{
    static const double pal[6][3] = {{0.85, 0.37, 0.01}, {0.46, 0.44, 0.70}, {0.11, 0.62, 0.47},
                                     {0.91, 0.16, 0.54}, {0.40, 0.65, 0.12}, {0.90, 0.67, 0.01}};
    memcpy(rgb, pal[(b % 6 + 6) % 6], sizeof pal[0]);
}

int pm_render_particles(const char *path, const pm_grid *g, const pm_particles *p, pm_field field, int width,
                        const char *title)
{
    const double margin = 40, bar = field == PM_FIELD_BODY ? 0 : 70;
    const double wx = g->hi[0] - g->lo[0], wy = g->hi[1] - g->lo[1];
    double scale = (width - 2 * margin - bar) / wx;
    if (wy * scale > 2.0 * width)
        scale = 2.0 * width / wy;
    const int W = width, H = (int)(wy * scale + 2 * margin);
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    /* y up: model (x, y) -> pixel (margin + (x - lo) s, H - margin - (y - lo) s) */
#define PX(x) (margin + ((x) - g->lo[0]) * scale)
#define PY(y) (H - margin - ((y) - g->lo[1]) * scale)
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, PX(g->lo[0]), PY(g->hi[1]), wx * scale, wy * scale);
    cairo_stroke(cr);
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        double v = field_value(p, i, field);
        if (isfinite(v)) {
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
    }
    if (!(lo <= hi)) /* no particle (yet or any more, with sources and sinks): an empty frame of 0..1 */
        lo = 0;
    if (!(hi > lo)) {
        hi = lo + 1;
    }
    for (size_t i = 0; i < p->n; i++) {
        double rgb[3];
        if (field == PM_FIELD_BODY)
            body_colour(p->body[i], rgb);
        else
            ramp((field_value(p, i, field) - lo) / (hi - lo), rgb);
        /* the particle's current extent: initial half-size stretched by the area change */
        const double J = p->vol0[i] > 0 ? sqrt(p->vol[i] / p->vol0[i]) : 1;
        const double hx = fmax(p->hsize[2 * i] * J * scale, 0.75), hy = fmax(p->hsize[2 * i + 1] * J * scale, 0.75);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        cairo_rectangle(cr, PX(p->x[2 * i]) - hx, PY(p->x[2 * i + 1]) - hy, 2 * hx, 2 * hy);
        cairo_fill(cr);
    }
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 13);
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (title) {
        cairo_move_to(cr, margin, 24);
        cairo_show_text(cr, title);
    }
    if (field != PM_FIELD_BODY) {
        /* colour bar with its range */
        const double bx = W - bar + 10, by = margin, bh = H - 2 * margin;
        for (int k = 0; k < 100; k++) {
            double rgb[3];
            ramp(k / 99.0, rgb);
            cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
            cairo_rectangle(cr, bx, by + bh * (1 - (k + 1) / 100.0), 14, bh / 100.0 + 0.5);
            cairo_fill(cr);
        }
        char txt[64];
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_font_size(cr, 10);
        snprintf(txt, sizeof txt, "%.3g", hi);
        cairo_move_to(cr, bx - 4, by - 6);
        cairo_show_text(cr, txt);
        snprintf(txt, sizeof txt, "%.3g", lo);
        cairo_move_to(cr, bx - 4, by + bh + 14);
        cairo_show_text(cr, txt);
        cairo_move_to(cr, bx - 4, by + bh + 28);
        cairo_show_text(cr, field_names[field]);
    }
#undef PX
#undef PY
    cairo_destroy(cr);
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    cairo_status_t st = cairo_surface_write_to_png(surf, tmp);
    cairo_surface_destroy(surf);
    if (st != CAIRO_STATUS_SUCCESS || rename(tmp, path) != 0) {
        remove(tmp);
        return pm_error_set(PM_EIO, "cannot write picture %s: %s", path,
                            st != CAIRO_STATUS_SUCCESS ? cairo_status_to_string(st) : strerror(errno));
    }
    return PM_OK;
}
