/*
 * Particle pictures (picture.h). Top to bottom: the title with the time, the model region with its
 * y axis on the left and x axis below (ticks in metres), then a horizontal colour bar as wide as the
 * picture allows, with its tick labels and the field's name and unit under it. A horizontal bar keeps
 * its label readable whatever the domain's aspect: a wide slope and a tall silo get the same bar. Every
 * text is measured with cairo before it is placed, and a text wider than the picture is drawn smaller
 * instead of being cut.
 *
 * Particles are drawn as the parallelograms their initial half-sizes span after the in-plane
 * deformation gradient (in axisymmetric runs: their area in the r-z plane; see COVER for the margin),
 * without antialiasing so
 * that neighbouring particles meet without seams and a particle's centre pixel has its exact colour.
 * A parallelogram more than ASPECT_MAX times longer than wide is drawn with that aspect instead, with
 * its area and its axes' directions kept, and one more than AREA_MAX times its initial area is drawn
 * with that area (ASPECT_MAX).
 */
#include "io/picture.h"

#include "io/plot.h"
#include "pmech/error.h"
#include "pmech/particles.h"

#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define TICKS_MAX 40

/* Particles are drawn 16 % larger than their half-sizes: MPM seeds them at Gauss points, whose spacing
 * inside a cell (h / sqrt 3 for 2 x 2 points, 0.387 h for 3 x 3) exceeds twice their half-size (h / 2,
 * h / 3), so true sizes would leave a seam in every cell; 1.16 closes both, while particles that really
 * separate (cracks, run-out) still show their gaps. */
#define COVER 1.16

/* Points sheared along a wall or a tool reach shear strains of tens (a silo insert's cone: 1 m/s across a
 * 20 mm cell for a second), and the parallelogram of their initial square then reaches metres across the
 * picture, through material that is not theirs and above the free surface. A point stands for the
 * material within about a cell of it, so its drawn shape is kept within an aspect of 4 (a shear of 1.5
 * stays as it is), its area unchanged, so that the picture still shows where points crowd or spread. */
#define ASPECT_MAX 4.0

/* Likewise a point whose volume has grown many times (det F of tens where points separate under a silo
 * insert or at a run-out's front) is drawn at most 4 times its initial area: larger, it covers empty
 * space and the points around it; at 4 times it still shows the gap it stands in. */
#define AREA_MAX 4.0

/* Scales the 2 x 2 map with columns a and b (the parallelogram's half-axes) to an aspect of at most
 * ASPECT_MAX and an area of at most AREA_MAX times area0 (the undeformed map's): with
 * M = U diag(s1, s2) V^T, s1 >= |s2|, the singular values become sqrt(A r) and sqrt(A / r), r the capped
 * aspect, A the capped area, and U, V stay. */
static void cap_shape(double a[2], double b[2], double area0)
{
    const double e = 0.5 * (a[0] + b[1]), f = 0.5 * (a[0] - b[1]);
    const double g = 0.5 * (a[1] + b[0]), h = 0.5 * (a[1] - b[0]);
    const double q = hypot(e, h), r = hypot(f, g);
    const double s1 = q + r, s2 = q - r; /* s2 < 0: the map reflects */
    const double area_drawn = s1 * fabs(s2), area = fmin(area_drawn, AREA_MAX * area0);
    if (!(fabs(s2) * ASPECT_MAX < s1) && !(area < area_drawn))
        return;
    const double aspect = fmin(s1 / fabs(s2), ASPECT_MAX);
    const double t1 = sqrt(area * aspect), t2 = copysign(sqrt(area / aspect), s2);
    /* M = R(phi) diag(s1, s2) R(theta) with these angles (the closed form of a 2 x 2 SVD) */
    const double a1 = atan2(g, f), a2 = atan2(h, e);
    const double th = 0.5 * (a2 - a1), ph = 0.5 * (a2 + a1);
    const double cp = cos(ph), sp = sin(ph), ct = cos(th), st = sin(th);
    /* R(phi) diag(t1, t2) R(theta), R(x) = [[cos x, -sin x], [sin x, cos x]] */
    const double m00 = cp * t1 * ct - sp * t2 * st, m01 = -cp * t1 * st - sp * t2 * ct;
    const double m10 = sp * t1 * ct + cp * t2 * st, m11 = -sp * t1 * st + cp * t2 * ct;
    a[0] = m00;
    a[1] = m10;
    b[0] = m01;
    b[1] = m11;
}

void pm_picture_ramp(double t, double rgb[3])
{
    static const double stops[5][3] = {{0.267, 0.005, 0.329},
                                       {0.231, 0.322, 0.545},
                                       {0.129, 0.569, 0.549},
                                       {0.369, 0.788, 0.384},
                                       {0.993, 0.906, 0.144}};
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    const double x = t * 4;
    int k = (int)x;
    if (k >= 4)
        k = 3;
    const double u = x - k;
    for (int c = 0; c < 3; c++)
        rgb[c] = stops[k][c] * (1 - u) + stops[k + 1][c] * u;
}

void pm_picture_category_colour(int k, double rgb[3])
{
    static const double pal[6][3] = {{0.85, 0.37, 0.01}, {0.46, 0.44, 0.70}, {0.11, 0.62, 0.47},
                                     {0.91, 0.16, 0.54}, {0.40, 0.65, 0.12}, {0.90, 0.67, 0.01}};
    memcpy(rgb, pal[(k % 6 + 6) % 6], sizeof pal[0]);
}

double pm_picture_unit_scale(const char *unit, double max_abs, char *shown, size_t cap)
{
    if (!unit || strcmp(unit, "Pa") != 0) {
        snprintf(shown, cap, "%s", unit ? unit : "");
        return 1;
    }
    static const struct {
        double at;
        const char *name;
    } pre[] = {{1e9, "GPa"}, {1e6, "MPa"}, {1e3, "kPa"}};
    for (size_t k = 0; k < sizeof pre / sizeof pre[0]; k++)
        if (max_abs >= pre[k].at) {
            snprintf(shown, cap, "%s", pre[k].name);
            return 1 / pre[k].at;
        }
    snprintf(shown, cap, "Pa");
    return 1;
}

/* Ticks of [lo, hi] with about n intervals: whole multiples of the step inside the range. */
static int ticks(double lo, double hi, int n, double *t, double *step)
{
    if (n < 1)
        n = 1;
    *step = pm_plot_nice_step(lo, hi, n);
    int k = 0;
    const double first = ceil(lo / *step - 1e-9) * *step;
    for (double v = first; v <= hi + 1e-9 * *step && k < TICKS_MAX; v = first + k * *step)
        t[k++] = fabs(v) < 1e-12 * *step ? 0.0 : v;
    return k;
}

static double text_width(cairo_t *cr, const char *s)
{
    cairo_text_extents_t te;
    cairo_text_extents(cr, s, &te);
    return te.x_advance;
}

/* The widest tick label of [lo, hi] cut into about n intervals. */
static double widest_tick(cairo_t *cr, double lo, double hi, int n, double factor)
{
    double t[TICKS_MAX], step, w = 0;
    const int k = ticks(lo * factor, hi * factor, n, t, &step);
    char buf[64];
    for (int i = 0; i < k; i++) {
        pm_plot_format_tick(t[i], step, buf, sizeof buf);
        w = fmax(w, text_width(cr, buf));
    }
    return w;
}

static int has_title(const pm_picture *pic) { return (pic->title && pic->title[0]) || isfinite(pic->time); }

/* The layout, measured with the font of @p cr. */
static int layout(cairo_t *cr, const pm_picture *pic, pm_picture_layout *L)
{
    const double wx = pic->hi[0] - pic->lo[0], wy = pic->hi[1] - pic->lo[1];
    if (!(wx > 0) || !(wy > 0) || !isfinite(wx) || !isfinite(wy))
        return pm_error_set(PM_EINPUT, "picture: the region shown has no area ([%g, %g] x [%g, %g])", pic->lo[0],
                            pic->hi[0], pic->lo[1], pic->hi[1]);
    if (pic->width < 200 || pic->width > 20000)
        return pm_error_set(PM_EINPUT, "picture: width %d pixels; allowed: 200 to 20000", pic->width);
    memset(L, 0, sizeof *L);
    const double W = pic->width;
    const double fs = fmin(fmax(W / 60.0, 11.0), 18.0), pad = 0.6 * fs;
    L->width = pic->width;
    L->font = fs;
    L->has_bar = pic->value != NULL;
    cairo_set_font_size(cr, fs);
    /* left: the rotated axis name, the widest y tick label, the tick */
    const double left = pad + fs + pad + widest_tick(cr, pic->lo[1], pic->hi[1], 8, 1) + 0.5 * fs;
    /* right: half of the widest x tick label, which may sit at the right edge */
    const double right = pad + fmax(0.5 * widest_tick(cr, pic->lo[0], pic->hi[0], 10, 1), pad);
    const double top = has_title(pic) ? pad + 1.5 * fs + pad : pad + 0.5 * fs;
    L->plot_x = left;
    L->plot_y = top;
    double avail = W - left - right;
    if (avail < 50)
        return pm_error_set(PM_EINPUT, "picture: width %d pixels leaves no room for the model region", pic->width);
    L->scale = avail / wx;
    if (wy * L->scale > 2 * W) /* a tall domain: at most twice as high as wide */
        L->scale = 2 * W / wy;
    L->plot_w = wx * L->scale;
    L->plot_h = wy * L->scale;
    /* under the region: ticks, tick labels, the axis name */
    double y = top + L->plot_h + 0.4 * fs + 0.3 * fs + fs + pad + fs + pad;
    if (L->has_bar) {
        L->bar_x = left;
        L->bar_w = avail;
        L->bar_y = y;
        L->bar_h = fmax(12.0, 1.1 * fs);
        y += L->bar_h + 0.3 * fs + 0.3 * fs + fs + pad + fs + pad;
    }
    L->height = (int)ceil(y);
    return PM_OK;
}

int pm_picture_layout_of(const pm_picture *pic, pm_picture_layout *lay)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t *cr = cairo_create(s);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    const int rc = layout(cr, pic, lay);
    cairo_destroy(cr);
    cairo_surface_destroy(s);
    return rc;
}

/* Show text with its left edge at x and its baseline at y, smaller if it would pass max_w. */
static void show_fit(cairo_t *cr, const char *s, double x, double y, double max_w, double fs)
{
    const double w = text_width(cr, s);
    if (w > max_w && w > 0)
        cairo_set_font_size(cr, fs * max_w / w);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s);
    cairo_set_font_size(cr, fs);
}

static void draw_particles(cairo_t *cr, const pm_picture *pic, const pm_picture_layout *L)
{
    const double s = L->scale;
    cairo_save(cr);
    cairo_rectangle(cr, L->plot_x, L->plot_y, L->plot_w, L->plot_h);
    cairo_clip(cr);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    for (size_t i = 0; i < pic->n; i++) {
        const double *xi = pic->x + (size_t)pic->x_stride * i;
        double rgb[3] = {0.6, 0.6, 0.6};
        if (pic->value) {
            const double v = pic->value[i];
            if (isfinite(v))
                pm_picture_ramp((v - pic->range[0]) / (pic->range[1] - pic->range[0]), rgb);
        } else if (pic->category) {
            pm_picture_category_colour((int)pic->category[i], rgb);
        }
        const double cx = L->plot_x + (xi[0] - pic->lo[0]) * s, cy = L->plot_y + L->plot_h - (xi[1] - pic->lo[1]) * s;
        const double hx = pic->hsize ? COVER * pic->hsize[PM_DIM * i] : 0;
        const double hy = pic->hsize ? COVER * pic->hsize[PM_DIM * i + 1] : 0;
        const double *F = pic->F ? pic->F + PM_NF * i : NULL;
        /* half-axes in pixels (y down): F (hx, 0) and F (0, hy) */
        double a[2] = {hx * s, 0}, b[2] = {0, -hy * s};
        if (F) {
            a[0] = F[PM_FXX] * hx * s;
            a[1] = -F[PM_FYX] * hx * s;
            b[0] = F[PM_FXY] * hy * s;
            b[1] = -F[PM_FYY] * hy * s;
            cap_shape(a, b, hx * hy * s * s);
        }
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        if (hypot(a[0], a[1]) < 0.75 || hypot(b[0], b[1]) < 0.75 || !isfinite(a[0] + a[1] + b[0] + b[1])) {
            cairo_rectangle(cr, cx - 0.75, cy - 0.75, 1.5, 1.5); /* never smaller than a pixel */
        } else {
            cairo_move_to(cr, cx + a[0] + b[0], cy + a[1] + b[1]);
            cairo_line_to(cr, cx - a[0] + b[0], cy - a[1] + b[1]);
            cairo_line_to(cr, cx - a[0] - b[0], cy - a[1] - b[1]);
            cairo_line_to(cr, cx + a[0] - b[0], cy + a[1] - b[1]);
            cairo_close_path(cr);
        }
        cairo_fill(cr);
    }
    cairo_restore(cr);
}

static void draw_axes(cairo_t *cr, const pm_picture *pic, const pm_picture_layout *L)
{
    const double fs = L->font, pad = 0.6 * fs, x0 = L->plot_x, y0 = L->plot_y, w = L->plot_w, h = L->plot_h;
    char buf[64];
    double t[TICKS_MAX], step;
    cairo_set_line_width(cr, 1.0);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, floor(x0) + 0.5, floor(y0) + 0.5, floor(w), floor(h));
    cairo_stroke(cr);
    /* x ticks: as many as fit with a gap of two font sizes between labels */
    const double lw = widest_tick(cr, pic->lo[0], pic->hi[0], 10, 1) + 2 * fs;
    int nt = ticks(pic->lo[0], pic->hi[0], (int)fmax(1, fmin(10, w / lw)), t, &step);
    for (int i = 0; i < nt; i++) {
        const double px = floor(x0 + (t[i] - pic->lo[0]) * L->scale) + 0.5;
        cairo_move_to(cr, px, y0 + h);
        cairo_line_to(cr, px, y0 + h + 0.4 * fs);
        cairo_stroke(cr);
        pm_plot_format_tick(t[i], step, buf, sizeof buf);
        cairo_move_to(cr, px - 0.5 * text_width(cr, buf), y0 + h + 0.7 * fs + fs * 0.8);
        cairo_show_text(cr, buf);
    }
    /* y ticks, labels at least 1.5 font sizes apart */
    nt = ticks(pic->lo[1], pic->hi[1], (int)fmax(1, fmin(8, h / (2.0 * fs))), t, &step);
    double last = INFINITY;
    for (int i = 0; i < nt; i++) {
        const double py = floor(y0 + h - (t[i] - pic->lo[1]) * L->scale) + 0.5;
        cairo_move_to(cr, x0 - 0.4 * fs, py);
        cairo_line_to(cr, x0, py);
        cairo_stroke(cr);
        if (fabs(last - py) < 1.5 * fs)
            continue;
        last = py;
        pm_plot_format_tick(t[i], step, buf, sizeof buf);
        cairo_move_to(cr, x0 - 0.5 * fs - text_width(cr, buf), py + 0.35 * fs);
        cairo_show_text(cr, buf);
    }
    /* axis names */
    const char *xn = pic->axisymmetric ? "r [m]" : "x [m]", *yn = pic->axisymmetric ? "z [m]" : "y [m]";
    cairo_move_to(cr, x0 + 0.5 * w - 0.5 * text_width(cr, xn), y0 + h + 0.7 * fs + fs + pad + 0.8 * fs);
    cairo_show_text(cr, xn);
    cairo_save(cr);
    cairo_move_to(cr, pad + 0.8 * fs, y0 + 0.5 * h + 0.5 * text_width(cr, yn));
    cairo_rotate(cr, -M_PI / 2);
    cairo_show_text(cr, yn);
    cairo_restore(cr);
}

static void draw_bar(cairo_t *cr, const pm_picture *pic, const pm_picture_layout *L)
{
    const double fs = L->font, pad = 0.6 * fs, bx = L->bar_x, by = L->bar_y, bw = L->bar_w, bh = L->bar_h;
    const int bands = 256;
    for (int k = 0; k < bands; k++) {
        double rgb[3];
        pm_picture_ramp((k + 0.5) / bands, rgb);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        cairo_rectangle(cr, bx + bw * k / bands, by, bw / bands + 0.5, bh);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, floor(bx) + 0.5, floor(by) + 0.5, floor(bw), floor(bh));
    cairo_stroke(cr);
    char unit[16], buf[64], label[256];
    const double lo = pic->range[0], hi = pic->range[1];
    const double f = pm_picture_unit_scale(pic->unit, fmax(fabs(lo), fabs(hi)), unit, sizeof unit);
    const double lw = widest_tick(cr, lo, hi, 8, f) + 2 * fs;
    double t[TICKS_MAX], step;
    const int nt = ticks(lo * f, hi * f, (int)fmax(1, fmin(8, bw / lw)), t, &step);
    for (int i = 0; i < nt; i++) {
        const double px = floor(bx + (t[i] / f - lo) / (hi - lo) * bw) + 0.5;
        cairo_move_to(cr, px, by + bh);
        cairo_line_to(cr, px, by + bh + 0.3 * fs);
        cairo_stroke(cr);
        pm_plot_format_tick(t[i], step, buf, sizeof buf);
        const double tw = text_width(cr, buf);
        /* keep the end labels inside the picture */
        const double lx = fmin(fmax(px - 0.5 * tw, 1.0), L->width - 1.0 - tw);
        cairo_move_to(cr, lx, by + bh + 0.6 * fs + 0.8 * fs);
        cairo_show_text(cr, buf);
    }
    if (unit[0])
        snprintf(label, sizeof label, "%s [%s]", pic->field ? pic->field : "", unit);
    else
        snprintf(label, sizeof label, "%s", pic->field ? pic->field : "");
    const double max_w = L->width - 2 * pad, w = fmin(text_width(cr, label), max_w);
    show_fit(cr, label, fmax(pad, bx + 0.5 * bw - 0.5 * w), by + bh + 0.6 * fs + fs + pad + 0.8 * fs, max_w, fs);
}

int pm_picture_write(const char *png, const pm_picture *pic)
{
    if (pic->value && !(pic->range[1] > pic->range[0]))
        return pm_error_set(PM_EINPUT, "picture %s: colour range [%g, %g] is empty", png, pic->range[0], pic->range[1]);
    cairo_surface_t *probe = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t *pc = cairo_create(probe);
    cairo_select_font_face(pc, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    pm_picture_layout L;
    int rc = layout(pc, pic, &L);
    cairo_destroy(pc);
    cairo_surface_destroy(probe);
    if (rc)
        return pm_error_prefix(rc, "picture %s: ", png);
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, L.width, L.height);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, L.font);
    draw_particles(cr, pic, &L);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_axes(cr, pic, &L);
    if (L.has_bar)
        draw_bar(cr, pic, &L);
    if (has_title(pic)) {
        char title[512];
        if (isfinite(pic->time))
            snprintf(title, sizeof title, "%s%st = %.4g s", pic->title ? pic->title : "",
                     pic->title && pic->title[0] ? "   " : "", pic->time);
        else
            snprintf(title, sizeof title, "%s", pic->title);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_font_size(cr, 1.15 * L.font);
        show_fit(cr, title, 0.6 * L.font, 0.6 * L.font + 1.1 * L.font, L.width - 1.2 * L.font, 1.15 * L.font);
    }
    cairo_destroy(cr);
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", png);
    const cairo_status_t st = cairo_surface_write_to_png(surf, tmp);
    cairo_surface_destroy(surf);
    if (st != CAIRO_STATUS_SUCCESS || rename(tmp, png) != 0) {
        const int err = errno;
        remove(tmp);
        return pm_error_set(PM_EIO, "cannot write picture %s: %s", png,
                            st != CAIRO_STATUS_SUCCESS ? cairo_status_to_string(st) : strerror(err));
    }
    return PM_OK;
}
