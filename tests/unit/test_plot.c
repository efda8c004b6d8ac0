/* The cairo line-plot helper: writes a PNG of the requested size with the curves drawn, reads
 * CSV columns by name, and reports missing columns and unwritable files. */
#define _GNU_SOURCE /* dlsym(RTLD_DEFAULT) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cairo.h>
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/plot.h"
#include "pmech/error.h"

/* Count pixels close to colour c in a PNG. */
static long count_colour(const char *png, const double c[3], int *w, int *h)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(png);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    *w = cairo_image_surface_get_width(s);
    *h = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char *d = cairo_image_surface_get_data(s);
    long n = 0;
    for (int y = 0; y < *h; y++)
        for (int x = 0; x < *w; x++) {
            const uint32_t px = *(const uint32_t *)(d + (size_t)y * stride + 4 * (size_t)x);
            const int r = (px >> 16) & 255, g = (px >> 8) & 255, b = px & 255;
            if (abs(r - (int)(255 * c[0])) < 20 && abs(g - (int)(255 * c[1])) < 20 && abs(b - (int)(255 * c[2])) < 20)
                n++;
        }
    cairo_surface_destroy(s);
    return n;
}

static void plot_arrays(void **unused)
{
    (void)unused;
    double x[50], y[50], z[2] = {0, 49}, r[2] = {0.5, 0.5};
    for (int i = 0; i < 50; i++) {
        x[i] = i;
        y[i] = sin(i / 8.0);
    }
    pm_plot_series s[2];
    memset(s, 0, sizeof s);
    s[0] = (pm_plot_series){x, y, 50, "sin", {0.8, 0.1, 0.1}, 0, 0};
    s[1] = (pm_plot_series){z, r, 2, "reference", {0.1, 0.1, 0.8}, 1, 0};
    const pm_plot_opts o = {"a title", "x label", "y label", 640, 480, 1, 0};
    assert_int_equal(pm_plot_lines("test_plot_arrays.png", s, 2, &o), PM_OK);
    int w, h;
    const double red[3] = {0.8, 0.1, 0.1}, blue[3] = {0.1, 0.1, 0.8}, black[3] = {0, 0, 0};
    assert_true(count_colour("test_plot_arrays.png", red, &w, &h) > 300);
    assert_int_equal(w, 640);
    assert_int_equal(h, 480);
    assert_true(count_colour("test_plot_arrays.png", blue, &w, &h) > 100);
    assert_true(count_colour("test_plot_arrays.png", black, &w, &h) > 1000); /* axes and text */
    /* nothing finite to plot */
    double nan1 = NAN;
    pm_plot_series bad = {&nan1, &nan1, 1, NULL, {0, 0, 0}, 0, 0};
    assert_int_equal(pm_plot_lines("test_plot_bad.png", &bad, 1, NULL), PM_EINPUT);
    assert_int_equal(pm_plot_lines("/nonexistent-dir/x.png", s, 1, NULL), PM_EIO);
}

static void plot_csv_columns(void **unused)
{
    (void)unused;
    FILE *f = fopen("test_plot.csv", "w");
    assert_non_null(f);
    fprintf(f, "step,eyy,q\n");
    for (int i = 0; i <= 400; i++) /* more rows than the reader's first buffer */
        fprintf(f, "%d,%g,%g\n", i, -i * 1e-4, 1e5 * (1 - exp(-i / 50.0)));
    fclose(f);
    const char *cols[] = {"q"};
    const pm_plot_opts o = {NULL, "axial strain (%)", "q (kPa)", 0, 0, 1, 2};
    assert_int_equal(pm_plot_csv("test_plot.csv", "eyy", -100, cols, 1e-3, 1, "test_plot_csv.png", &o), PM_OK);
    int w, h;
    const double blue[3] = {0.12, 0.47, 0.71};
    assert_true(count_colour("test_plot_csv.png", blue, &w, &h) > 300);
    assert_int_equal(w, 800);
    const char *missing[] = {"p"};
    assert_int_equal(pm_plot_csv("test_plot.csv", "eyy", 1, missing, 1, 1, "x.png", NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "'p'"));
    assert_int_equal(pm_plot_csv("no_such.csv", "eyy", 1, cols, 1, 1, "x.png", NULL), PM_EIO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plot_arrays),
        cmocka_unit_test(plot_csv_columns),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    /* release cairo's and fontconfig's process-wide font caches so that LeakSanitizer sees only
     * real leaks (fontconfig is loaded by cairo, hence looked up at run time) */
    cairo_debug_reset_static_data();
    void (*fc_fini)(void) = (void (*)(void))dlsym(RTLD_DEFAULT, "FcFini");
    if (fc_fini)
        fc_fini();
    return rc;
}
