/* Line plots to PNG with cairo: axes, 1-2-5 ticks, labels, legend (see plot.h). */
#include "io/plot.h"

#include "pmech/error.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double palette[6][3] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17},
                                     {1.00, 0.50, 0.05}, {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29}};

double pm_plot_nice_step(double lo, double hi, int n)
{
    const double raw = (hi - lo) / n;
    const double p = pow(10.0, floor(log10(raw)));
    const double f = raw / p;
    return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

/* Widen [lo, hi] to whole ticks; a degenerate range gets a unit-sized window. */
static void nice_range(double *lo, double *hi, double *step)
{
    if (!(*hi > *lo)) {
        const double d = *lo != 0 ? fabs(*lo) * 0.1 : 1.0;
        *lo -= d;
        *hi += d;
    }
    *step = pm_plot_nice_step(*lo, *hi, 6);
    *lo = floor(*lo / *step + 1e-9) * *step;
    *hi = ceil(*hi / *step - 1e-9) * *step;
}

void pm_plot_format_tick(double v, double step, char *buf, size_t n)
{
    if (fabs(v) < 1e-12 * step)
        v = 0;
    const double a = fmax(fabs(v), step);
    if (a >= 1e5 || a < 1e-3)
        snprintf(buf, n, "%.3g", v);
    else {
        int dec = step >= 1 ? 0 : (int)ceil(-log10(step) - 1e-9);
        snprintf(buf, n, "%.*f", dec, v);
    }
}

int pm_plot_lines(const char *png, const pm_plot_series *s, size_t ns, const pm_plot_opts *o)
{
    pm_plot_opts def = {0};
    if (!o)
        o = &def;
    const int W = o->width > 0 ? o->width : 800, H = o->height > 0 ? o->height : 560;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (size_t k = 0; k < ns; k++)
        for (size_t i = 0; i < s[k].n; i++) {
            if (!isfinite(s[k].x[i]) || !isfinite(s[k].y[i]))
                continue;
            x0 = fmin(x0, s[k].x[i]);
            x1 = fmax(x1, s[k].x[i]);
            y0 = fmin(y0, s[k].y[i]);
            y1 = fmax(y1, s[k].y[i]);
        }
    if (!(x0 <= x1))
        return pm_error_set(PM_EINPUT, "plot %s: no finite data point", png);
    if (o->y_from_zero) {
        y0 = fmin(y0, 0);
        y1 = fmax(y1, 0);
    }
    double xs, ys;
    nice_range(&x0, &x1, &xs);
    nice_range(&y0, &y1, &ys);

    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    const double fs = H / 40.0 > 11 ? H / 40.0 : 11;
    cairo_set_font_size(cr, fs);
    /* plot area */
    const double L = 5.5 * fs, R = W - 1.5 * fs, T = (o->title ? 3.0 : 1.5) * fs, B = H - 4.0 * fs;
    const double sx = (R - L) / (x1 - x0), sy = (B - T) / (y1 - y0);
#define PX(v) (L + ((v) - x0) * sx)
#define PY(v) (B - ((v) - y0) * sy)
    cairo_text_extents_t te;
    char buf[64];
    /* grid and ticks */
    cairo_set_line_width(cr, 1.0);
    for (double v = x0; v <= x1 + 0.5 * xs; v += xs) {
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        cairo_move_to(cr, floor(PX(v)) + 0.5, T);
        cairo_line_to(cr, floor(PX(v)) + 0.5, B);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, floor(PX(v)) + 0.5, B);
        cairo_line_to(cr, floor(PX(v)) + 0.5, B + 0.4 * fs);
        cairo_stroke(cr);
        pm_plot_format_tick(v, xs, buf, sizeof buf);
        cairo_text_extents(cr, buf, &te);
        cairo_move_to(cr, PX(v) - te.width / 2 - te.x_bearing, B + 0.6 * fs + te.height);
        cairo_show_text(cr, buf);
    }
    for (double v = y0; v <= y1 + 0.5 * ys; v += ys) {
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        cairo_move_to(cr, L, floor(PY(v)) + 0.5);
        cairo_line_to(cr, R, floor(PY(v)) + 0.5);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, L - 0.4 * fs, floor(PY(v)) + 0.5);
        cairo_line_to(cr, L, floor(PY(v)) + 0.5);
        cairo_stroke(cr);
        pm_plot_format_tick(v, ys, buf, sizeof buf);
        cairo_text_extents(cr, buf, &te);
        cairo_move_to(cr, L - 0.6 * fs - te.width - te.x_bearing, PY(v) + te.height / 2);
        cairo_show_text(cr, buf);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, floor(L) + 0.5, floor(T) + 0.5, floor(R - L), floor(B - T));
    cairo_stroke(cr);
    /* labels */
    if (o->xlabel) {
        cairo_text_extents(cr, o->xlabel, &te);
        cairo_move_to(cr, (L + R) / 2 - te.width / 2 - te.x_bearing, H - 0.8 * fs);
        cairo_show_text(cr, o->xlabel);
    }
    if (o->ylabel) {
        cairo_text_extents(cr, o->ylabel, &te);
        cairo_save(cr);
        cairo_move_to(cr, 1.4 * fs, (T + B) / 2 + te.width / 2);
        cairo_rotate(cr, -M_PI / 2);
        cairo_show_text(cr, o->ylabel);
        cairo_restore(cr);
    }
    if (o->title) {
        cairo_set_font_size(cr, 1.2 * fs);
        cairo_text_extents(cr, o->title, &te);
        cairo_move_to(cr, (L + R) / 2 - te.width / 2 - te.x_bearing, 1.9 * fs);
        cairo_show_text(cr, o->title);
        cairo_set_font_size(cr, fs);
    }
    /* curves, clipped to the plot area */
    cairo_save(cr);
    cairo_rectangle(cr, L, T, R - L, B - T);
    cairo_clip(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (size_t k = 0; k < ns; k++) {
        const double *c = s[k].rgb;
        if (c[0] == 0 && c[1] == 0 && c[2] == 0)
            c = palette[k % 6];
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_set_line_width(cr, 2.0);
        const double dash[] = {8.0, 5.0};
        cairo_set_dash(cr, dash, s[k].dashed ? 2 : 0, 0);
        int pen = 0;
        for (size_t i = 0; i < s[k].n; i++) {
            if (!isfinite(s[k].x[i]) || !isfinite(s[k].y[i])) {
                pen = 0;
                continue;
            }
            if (pen)
                cairo_line_to(cr, PX(s[k].x[i]), PY(s[k].y[i]));
            else
                cairo_move_to(cr, PX(s[k].x[i]), PY(s[k].y[i]));
            pen = 1;
        }
        cairo_stroke(cr);
        cairo_set_dash(cr, dash, 0, 0);
        if (s[k].markers)
            for (size_t i = 0; i < s[k].n; i++)
                if (isfinite(s[k].x[i]) && isfinite(s[k].y[i])) {
                    cairo_arc(cr, PX(s[k].x[i]), PY(s[k].y[i]), 3.0, 0, 2 * M_PI);
                    cairo_fill(cr);
                }
    }
    cairo_restore(cr);
    /* legend inside the plot, in the corner chosen by o->legend, on a white box */
    size_t nl = 0;
    double lw = 0;
    for (size_t k = 0; k < ns; k++)
        if (s[k].label && s[k].label[0]) {
            cairo_text_extents(cr, s[k].label, &te);
            lw = fmax(lw, te.x_advance);
            nl++;
        }
    if (nl) {
        const double bw = lw + 4.3 * fs, bh = 1.4 * fs * nl + 0.6 * fs;
        const int right = o->legend == 1 || o->legend == 2, bottom = o->legend == 2 || o->legend == 3;
        const double bx = right ? R - bw - 0.5 * fs : L + 0.5 * fs;
        const double by = bottom ? B - bh - 0.5 * fs : T + 0.5 * fs;
        cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
        cairo_rectangle(cr, bx, by, bw, bh);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
        cairo_set_line_width(cr, 1.0);
        cairo_stroke(cr);
        double ly = by + 1.3 * fs;
        for (size_t k = 0; k < ns; k++) {
            if (!s[k].label || !s[k].label[0])
                continue;
            const double *c = s[k].rgb;
            if (c[0] == 0 && c[1] == 0 && c[2] == 0)
                c = palette[k % 6];
            cairo_set_source_rgb(cr, c[0], c[1], c[2]);
            const double dash[] = {8.0, 5.0};
            cairo_set_dash(cr, dash, s[k].dashed ? 2 : 0, 0);
            cairo_set_line_width(cr, 2.0);
            cairo_move_to(cr, bx + 0.5 * fs, ly - 0.35 * fs);
            cairo_line_to(cr, bx + 3.0 * fs, ly - 0.35 * fs);
            cairo_stroke(cr);
            cairo_set_dash(cr, dash, 0, 0);
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_move_to(cr, bx + 3.5 * fs, ly);
            cairo_show_text(cr, s[k].label);
            ly += 1.4 * fs;
        }
    }
#undef PX
#undef PY
    cairo_destroy(cr);
    const cairo_status_t st = cairo_surface_write_to_png(surf, png);
    cairo_surface_destroy(surf);
    if (st != CAIRO_STATUS_SUCCESS)
        return pm_error_set(PM_EIO, "cannot write PNG '%s': %s", png, cairo_status_to_string(st));
    return PM_OK;
}

/* Index of column @p name in a comma-separated header line, or -1. */
static int column_index(const char *header, const char *name)
{
    int idx = 0;
    const size_t n = strlen(name);
    for (const char *p = header;; idx++) {
        const char *e = p + strcspn(p, ",\r\n");
        if ((size_t)(e - p) == n && !strncmp(p, name, n))
            return idx;
        if (*e != ',')
            return -1;
        p = e + 1;
    }
}

int pm_plot_csv(const char *csv, const char *xcol, double xscale, const char *const *ycols,
                double yscale, size_t ny, const char *png, const pm_plot_opts *o)
{
    if (ny < 1 || ny > 8)
        return pm_error_set(PM_EINPUT, "plot %s: between 1 and 8 y columns", png);
    FILE *f = fopen(csv, "r");
    if (!f)
        return pm_error_set(PM_EIO, "cannot read '%s'", csv);
    char line[8192];
    if (!fgets(line, sizeof line, f)) {
        fclose(f);
        return pm_error_set(PM_EINPUT, "%s: empty file", csv);
    }
    int ix = column_index(line, xcol), iy[8], imax = ix;
    if (ix < 0) {
        fclose(f);
        return pm_error_set(PM_EINPUT, "%s: no column '%s'", csv, xcol);
    }
    for (size_t k = 0; k < ny; k++) {
        iy[k] = column_index(line, ycols[k]);
        if (iy[k] < 0) {
            fclose(f);
            return pm_error_set(PM_EINPUT, "%s: no column '%s'", csv, ycols[k]);
        }
        if (iy[k] > imax)
            imax = iy[k];
    }
    size_t n = 0, cap = 256;
    double *x = malloc(cap * sizeof *x), *y = malloc(cap * ny * sizeof *y);
    double *vals = malloc(((size_t)imax + 1) * sizeof *vals);
    int rc = PM_OK;
    if (!x || !y || !vals)
        rc = pm_error_set(PM_ENOMEM, "plot: out of memory");
    while (rc == PM_OK && fgets(line, sizeof line, f)) {
        char *p = line;
        int ok = 1;
        for (int c = 0; c <= imax; c++) {
            char *end;
            vals[c] = strtod(p, &end);
            if (end == p) {
                ok = 0;
                break;
            }
            p = end;
            if (c < imax) {
                if (*p != ',') {
                    ok = 0;
                    break;
                }
                p++;
            }
        }
        if (!ok)
            continue;
        if (n == cap) {
            cap *= 2;
            double *nx = realloc(x, cap * sizeof *x);
            if (nx)
                x = nx;
            double *nyv = nx ? realloc(y, cap * ny * sizeof *y) : NULL;
            if (nyv)
                y = nyv;
            if (!nx || !nyv) {
                rc = pm_error_set(PM_ENOMEM, "plot: out of memory");
                break;
            }
        }
        x[n] = xscale * vals[ix];
        for (size_t k = 0; k < ny; k++)
            y[n * ny + k] = yscale * vals[iy[k]];
        n++;
    }
    fclose(f);
    if (rc == PM_OK && n == 0)
        rc = pm_error_set(PM_EINPUT, "%s: no data rows", csv);
    double *yy = rc == PM_OK ? malloc(n * ny * sizeof *yy) : NULL;
    if (rc == PM_OK && !yy)
        rc = pm_error_set(PM_ENOMEM, "plot: out of memory");
    if (rc == PM_OK) {
        pm_plot_series s[8];
        memset(s, 0, sizeof s);
        for (size_t k = 0; k < ny; k++) {
            for (size_t i = 0; i < n; i++)
                yy[k * n + i] = y[i * ny + k];
            s[k].x = x;
            s[k].y = yy + k * n;
            s[k].n = n;
            s[k].label = ycols[k];
        }
        rc = pm_plot_lines(png, s, ny, o);
    }
    free(yy);
    free(x);
    free(y);
    free(vals);
    return rc;
}
