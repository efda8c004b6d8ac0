/*
 * Particle pictures (src/io/picture.c, src/io/render.c), read back with cairo's PNG reader.
 *
 * Size: the picture is as wide as asked; the model region keeps the domain's aspect (one scale in x and
 * y) and fills the width left by the axes, unless it would be more than twice as high as the picture is
 * wide. Positions: the layout gives the pixel of a model point; the pixel at a particle's centre has its
 * colour exactly, a pixel beyond its deformed area is white; a point sheared past an aspect of 4 or
 * grown past 4 times its area is drawn capped to them (picture.c).
 * Colours: the ramp's ends and middle are the stops picture.c defines (dark purple, teal, yellow, close
 * to viridis); body pictures use the body palette. Tolerance: 1 level of 255 per channel, cairo's
 * rounding of a double colour to 8 bits.
 * Text: the colour bar's label is measured with cairo at the picture's font size; the dark pixels of its
 * row must span that width (within 3 pixels of glyph side bearings) and stay inside the picture, with
 * white columns at both edges: the label is neither cut nor clipped, even on a 100 x 1 domain drawn 300
 * pixels wide.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/picture.h"
#include "pmech/error.h"
#include "pmech/render.h"

static const char *png = "test_render.png";
static const double white[3] = {1, 1, 1};

typedef struct picture {
    cairo_surface_t *s;
    int w, h, stride;
    const unsigned char *data;
} picture;

static void open_picture(picture *p)
{
    p->s = cairo_image_surface_create_from_png(png);
    assert_int_equal(cairo_surface_status(p->s), CAIRO_STATUS_SUCCESS);
    p->w = cairo_image_surface_get_width(p->s);
    p->h = cairo_image_surface_get_height(p->s);
    p->stride = cairo_image_surface_get_stride(p->s);
    p->data = cairo_image_surface_get_data(p->s);
}

static void close_picture(picture *p)
{
    cairo_surface_destroy(p->s);
    remove(png);
}

static void pixel(const picture *p, int x, int y, int rgb[3])
{
    assert_true(x >= 0 && x < p->w && y >= 0 && y < p->h);
    const uint32_t v = *(const uint32_t *)(p->data + (size_t)y * (size_t)p->stride + 4 * (size_t)x);
    rgb[0] = (int)(v >> 16 & 255);
    rgb[1] = (int)(v >> 8 & 255);
    rgb[2] = (int)(v & 255);
}

/* Whether pixel (x, y) has colour rgb (0..1) within tol levels of 255 per channel. */
static void expect_pixel(const picture *p, int x, int y, const double rgb[3], int tol)
{
    int got[3];
    pixel(p, x, y, got);
    for (int c = 0; c < 3; c++) {
        const int want = (int)(rgb[c] * 255 + 0.5);
        if (abs(got[c] - want) > tol)
            fail_msg("pixel (%d, %d): got (%d, %d, %d), want (%d, %d, %d) within %d", x, y, got[0], got[1], got[2],
                     (int)(rgb[0] * 255 + 0.5), (int)(rgb[1] * 255 + 0.5), (int)(rgb[2] * 255 + 0.5), tol);
    }
}

static int dark(const picture *p, int x, int y)
{
    int c[3];
    pixel(p, x, y, c);
    return c[0] + c[1] + c[2] < 3 * 160;
}

static void grid(pm_grid *g, double lx, double ly)
{
    const double origin[PM_DIM] = {0, 0}, size[PM_DIM] = {lx, ly};
    const int cells[PM_DIM] = {2, 2};
    assert_int_equal(pm_grid_rectangle(g, origin, size, cells, PM_QUAD4), PM_OK);
}

/* n particles at y = 0.5, x = 0.5, 1.0, 1.5, ..., half-size 0.1, undeformed, at rest, body i. */
static void particles(pm_particles *p, size_t n)
{
    assert_int_equal(pm_particles_alloc(p, n, 0), PM_OK);
    for (size_t i = 0; i < n; i++) {
        p->x[PM_DIM * i] = p->x0[PM_DIM * i] = 0.5 + 0.5 * (double)i;
        p->x[PM_DIM * i + 1] = p->x0[PM_DIM * i + 1] = 0.5;
        p->hsize[PM_DIM * i] = p->hsize[PM_DIM * i + 1] = 0.1;
        p->F[PM_NF * i + PM_FXX] = p->F[PM_NF * i + PM_FYY] = p->F[PM_NF * i + PM_FZZ] = 1;
        p->vol[i] = p->vol0[i] = 0.04;
        p->body[i] = (int32_t)i;
    }
}

/* The layout pm_render_field uses for this grid, field and width. */
static pm_picture_layout layout_for(const pm_grid *g, int category, int width)
{
    pm_picture pic;
    memset(&pic, 0, sizeof pic);
    static const double v = 0;
    pic.value = category ? NULL : &v;
    pic.range[1] = 1;
    memcpy(pic.lo, g->lo, sizeof pic.lo);
    memcpy(pic.hi, g->hi, sizeof pic.hi);
    pic.time = NAN;
    pic.width = width;
    pm_picture_layout L;
    assert_int_equal(pm_picture_layout_of(&pic, &L), PM_OK);
    return L;
}

/* The pixel of model point (x, y). */
static void to_pixel(const pm_picture_layout *L, const pm_grid *g, double x, double y, int *px, int *py)
{
    *px = (int)floor(L->plot_x + (x - g->lo[0]) * L->scale);
    *py = (int)floor(L->plot_y + L->plot_h - (y - g->lo[1]) * L->scale);
}

static void size_follows_the_grid(void **state)
{
    (void)state;
    static const struct {
        double lx, ly;
        pm_field f;
        int w;
    } cases[] = {{2, 1, PM_FIELD_SPEED, 400}, {2, 1, PM_FIELD_BODY, 400}, {1, 10, PM_FIELD_BODY, 400},
                 {100, 1, PM_FIELD_PRESSURE, 300}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        pm_grid g;
        pm_particles p;
        grid(&g, cases[k].lx, cases[k].ly);
        particles(&p, 1);
        const pm_render_opts o = {.width = cases[k].w};
        assert_int_equal(pm_render_field(png, &g, &p, cases[k].f, &o), PM_OK);
        const pm_picture_layout L = layout_for(&g, cases[k].f == PM_FIELD_BODY, cases[k].w);
        picture pic;
        open_picture(&pic);
        assert_int_equal(pic.w, cases[k].w);
        assert_int_equal(pic.h, L.height);
        /* one scale along x and y; the region inside the picture */
        assert_true(fabs(L.plot_w / L.plot_h - cases[k].lx / cases[k].ly) < 1e-9 * cases[k].lx / cases[k].ly);
        assert_true(L.plot_x > 0 && L.plot_x + L.plot_w < pic.w && L.plot_y > 0 && L.plot_y + L.plot_h < pic.h);
        if (cases[k].ly > 2 * cases[k].lx) /* tall: twice the width */
            assert_true(fabs(L.plot_h - 2.0 * cases[k].w) < 1e-9);
        close_picture(&pic);
        pm_particles_free(&p);
        pm_grid_free(&g);
    }
}

/* Speeds 0, 2.5 and 5 on the grid [0, 2] x [0, 1]: the lowest, middle and highest colour of the ramp. */
static void speed_colours_at_the_particles(void **state)
{
    (void)state;
    static const double lo[3] = {0.267, 0.005, 0.329}, mid[3] = {0.129, 0.569, 0.549}, hi[3] = {0.993, 0.906, 0.144};
    pm_grid g;
    pm_particles p;
    grid(&g, 2, 1);
    particles(&p, 3);
    const double v1[PM_DIM] = {1.5, 2.0}, v2[PM_DIM] = {3.0, 4.0}; /* |v| = 2.5 and 5 */
    memcpy(p.v + PM_DIM * 1, v1, sizeof v1);
    memcpy(p.v + PM_DIM * 2, v2, sizeof v2);
    const pm_render_opts o = {.width = 400};
    assert_int_equal(pm_render_field(png, &g, &p, PM_FIELD_SPEED, &o), PM_OK);
    const pm_picture_layout L = layout_for(&g, 0, 400);
    picture pic;
    open_picture(&pic);
    int x, y;
    to_pixel(&L, &g, 0.5, 0.5, &x, &y);
    expect_pixel(&pic, x, y, lo, 1);
    to_pixel(&L, &g, 1.0, 0.5, &x, &y);
    expect_pixel(&pic, x, y, mid, 1);
    to_pixel(&L, &g, 1.5, 0.5, &x, &y);
    expect_pixel(&pic, x, y, hi, 1);
    /* 0.15 m above a particle (its half-size is 0.1) and between two: empty */
    to_pixel(&L, &g, 0.5, 0.65, &x, &y);
    expect_pixel(&pic, x, y, white, 1);
    to_pixel(&L, &g, 0.75, 0.5, &x, &y);
    expect_pixel(&pic, x, y, white, 1);
    /* the colour bar runs from the lowest colour on the left to the highest on the right (256 bands:
     * within 4 levels of the ramp at the pixel's centre) */
    const int bx[3] = {(int)L.bar_x + 2, (int)(L.bar_x + L.bar_w / 2), (int)(L.bar_x + L.bar_w) - 3};
    for (int k = 0; k < 3; k++) {
        double want[3];
        pm_picture_ramp((bx[k] + 0.5 - L.bar_x) / L.bar_w, want);
        expect_pixel(&pic, bx[k], (int)(L.bar_y + L.bar_h / 2), want, 4);
    }
    /* an x tick at x = 1 m: a dark mark just under the region */
    to_pixel(&L, &g, 1.0, 0, &x, &y);
    assert_true(dark(&pic, x, y + 3));
    close_picture(&pic);
    /* a fixed range: speed 2.5 at the bottom of [2.5, 10] is the lowest colour */
    const double range[2] = {2.5, 10};
    const pm_render_opts fixed = {.width = 400, .range = range};
    assert_int_equal(pm_render_field(png, &g, &p, PM_FIELD_SPEED, &fixed), PM_OK);
    open_picture(&pic);
    to_pixel(&L, &g, 1.0, 0.5, &x, &y);
    expect_pixel(&pic, x, y, lo, 1);
    close_picture(&pic);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

/* The colour of body 0 in the body palette. */
static const double body0[3] = {0.85, 0.37, 0.01};

/* Draws one point of body 0 at (1.0, 0.5) on a 2 x 1 m grid, 600 pixels wide, with half-size h and the
 * in-plane F (fxx, fxy; 0, fyy), and opens the picture with its layout. */
static void draw_one_point(double h, double fxx, double fxy, double fyy, pm_grid *g, picture *pic,
                           pm_picture_layout *L)
{
    pm_particles p;
    grid(g, 2, 1);
    particles(&p, 1);
    p.x[0] = 1.0;
    p.hsize[0] = p.hsize[1] = h;
    p.F[PM_FXX] = fxx;
    p.F[PM_FXY] = fxy;
    p.F[PM_FYY] = fyy;
    assert_int_equal(pm_render_field(png, g, &p, PM_FIELD_BODY, &(pm_render_opts){.width = 600}), PM_OK);
    pm_particles_free(&p);
    *L = layout_for(g, 1, 600);
    open_picture(pic);
}

/* Whether the pixel of model point (x, y) has colour rgb. */
static void expect_at(const picture *pic, const pm_picture_layout *L, const pm_grid *g, double x, double y,
                      const double rgb[3])
{
    int px, py;
    to_pixel(L, g, x, y, &px, &py);
    expect_pixel(pic, px, py, rgb, 1);
}

/* A particle sheared by F = [1 1; 0 1] covers the parallelogram its half-sizes span, not its square. */
static void particles_are_drawn_as_their_deformed_area(void **state)
{
    (void)state;
    pm_grid g;
    picture pic;
    pm_picture_layout L;
    draw_one_point(0.2, 1, 1, 1, &g, &pic, &L);
    /* the corner (+0.2 + 0.2, +0.2) of the parallelogram is covered, the square's (-0.18, +0.18) is not */
    expect_at(&pic, &L, &g, 1.0 + 0.35, 0.5 + 0.18, body0);
    expect_at(&pic, &L, &g, 1.0 - 0.18, 0.5 + 0.18, white);
    close_picture(&pic);
    pm_grid_free(&g);
}

/* A point sheared far (F_xy = 5: an aspect of 27) is drawn with an aspect of 4, its area kept: the
 * parallelogram of its square would reach (1.5, 0.6), half a metre from its centre; the capped shape
 * reaches 0.24 m along its long axis. Its coloured pixels make its area (4 (1.16 h)^2 det F) within 8 %:
 * the edge pixels of a shape 0.47 m by 0.12 m at 250 pixels per metre are about 5 % of its area. */
static void sheared_particles_keep_an_aspect_of_four(void **state)
{
    (void)state;
    pm_grid g;
    picture pic;
    pm_picture_layout L;
    draw_one_point(0.1, 1, 5, 1, &g, &pic, &L);
    expect_at(&pic, &L, &g, 1.0, 0.5, body0);
    expect_at(&pic, &L, &g, 1.5, 0.6, white);
    long coloured = 0;
    for (int j = 0; j < pic.h; j++)
        for (int i = 0; i < pic.w; i++) {
            int c[3], same = 1;
            pixel(&pic, i, j, c);
            for (int k = 0; k < 3; k++)
                same &= abs(c[k] - (int)lround(255 * body0[k])) <= 1;
            coloured += same;
        }
    const double side = 2 * 1.16 * 0.1 * L.scale;
    assert_true(fabs((double)coloured / (side * side) - 1) < 0.08);
    close_picture(&pic);
    pm_grid_free(&g);
}

/* A point grown to 16 times its area (F = 4 I) is drawn at 4 times it: its half-width 2 x 1.16 x 0.1 m,
 * so (1.3, 0.5), inside the uncapped 0.46 m, is white, and (1.2, 0.5) is coloured. */
static void swollen_particles_are_drawn_at_four_times_their_area(void **state)
{
    (void)state;
    pm_grid g;
    picture pic;
    pm_picture_layout L;
    draw_one_point(0.1, 4, 0, 4, &g, &pic, &L);
    expect_at(&pic, &L, &g, 1.2, 0.5, body0);
    expect_at(&pic, &L, &g, 1.3, 0.5, white);
    close_picture(&pic);
    pm_grid_free(&g);
}

/* Axisymmetric particles far from the axis are drawn their size in the r-z plane: a particle of
 * half-size 0.1 at r = 9 (volume per radian 0.36) covers 0.2 m, not sqrt(0.36) = 0.6 m. */
static void axisymmetric_particles_have_their_rz_size(void **state)
{
    (void)state;
    static const double b0[3] = {0.85, 0.37, 0.01};
    pm_grid g;
    pm_particles p;
    grid(&g, 10, 2);
    particles(&p, 1);
    p.x[0] = p.x0[0] = 9.0;
    p.x[1] = p.x0[1] = 1.0;
    p.vol[0] = p.vol0[0] = 0.04 * 9.0;
    const pm_render_opts o = {.width = 800, .axisymmetric = 1};
    assert_int_equal(pm_render_field(png, &g, &p, PM_FIELD_BODY, &o), PM_OK);
    const pm_picture_layout L = layout_for(&g, 1, 800);
    picture pic;
    open_picture(&pic);
    int x, y;
    to_pixel(&L, &g, 9.08, 1.0, &x, &y);
    expect_pixel(&pic, x, y, b0, 1);
    to_pixel(&L, &g, 9.15, 1.0, &x, &y);
    expect_pixel(&pic, x, y, white, 1);
    close_picture(&pic);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

static void body_colours_from_the_palette(void **state)
{
    (void)state;
    static const double b0[3] = {0.85, 0.37, 0.01}, b1[3] = {0.46, 0.44, 0.70};
    pm_grid g;
    pm_particles p;
    grid(&g, 2, 1);
    particles(&p, 2);
    assert_int_equal(pm_render_particles(png, &g, &p, PM_FIELD_BODY, 400, NULL), PM_OK);
    const pm_picture_layout L = layout_for(&g, 1, 400);
    picture pic;
    open_picture(&pic);
    int x, y;
    to_pixel(&L, &g, 0.5, 0.5, &x, &y);
    expect_pixel(&pic, x, y, b0, 1);
    to_pixel(&L, &g, 1.0, 0.5, &x, &y);
    expect_pixel(&pic, x, y, b1, 1);
    close_picture(&pic);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

/* The columns of row band [y0, y1) that hold dark pixels: first and last. */
static int dark_span(const picture *pic, int y0, int y1, int *first, int *last)
{
    *first = pic->w;
    *last = -1;
    for (int y = y0; y < y1; y++)
        for (int x = 0; x < pic->w; x++)
            if (dark(pic, x, y)) {
                if (x < *first)
                    *first = x;
                if (x > *last)
                    *last = x;
            }
    return *last >= 0;
}

/* The bar label "deviatoric_strain [-]" and a stress label in kPa, on a 100 x 1 domain 300 pixels wide. */
static void colour_bar_label_is_whole(void **state)
{
    (void)state;
    static const struct {
        pm_field f;
        double value;
        const char *label;
    } cases[] = {{PM_FIELD_DEVIATORIC_STRAIN, 0, "deviatoric_strain [-]"}, {PM_FIELD_SYY, -2.5e4, "syy [kPa]"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        pm_grid g;
        pm_particles p;
        grid(&g, 100, 1);
        particles(&p, 2);
        p.F[PM_FXX] = 1.5; /* some deviatoric strain for the first particle */
        p.stress[PM_SYY] = cases[k].value;
        assert_int_equal(pm_render_field(png, &g, &p, cases[k].f, &(pm_render_opts){.width = 300}), PM_OK);
        const pm_picture_layout L = layout_for(&g, 0, 300);
        picture pic;
        open_picture(&pic);
        /* the label's row: below the bar's tick labels, to the bottom of the picture */
        const int y0 = (int)(L.bar_y + L.bar_h + 0.6 * L.font + 1.0 * L.font + 2), y1 = pic.h;
        int first, last;
        assert_true(dark_span(&pic, y0, y1, &first, &last));
        cairo_t *cr = cairo_create(pic.s);
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, L.font);
        cairo_text_extents_t te;
        cairo_text_extents(cr, cases[k].label, &te);
        cairo_destroy(cr);
        if (fabs((last - first + 1) - te.width) > 3)
            fail_msg("%s: dark span %d..%d (%d px), the label measures %.1f px", cases[k].label, first, last,
                     last - first + 1, te.width);
        assert_true(first > 0 && last < pic.w - 1);
        /* and every tick label of the bar inside the picture */
        const int t0 = (int)(L.bar_y + L.bar_h + 1), t1 = y0 - 1;
        assert_true(dark_span(&pic, t0, t1, &first, &last));
        assert_true(first > 0 && last < pic.w - 1);
        close_picture(&pic);
        pm_particles_free(&p);
        pm_grid_free(&g);
    }
}

static void stress_units_get_a_prefix(void **state)
{
    (void)state;
    char u[16];
    assert_true(pm_picture_unit_scale("Pa", 999, u, sizeof u) == 1 && !strcmp(u, "Pa"));
    assert_true(pm_picture_unit_scale("Pa", 2.5e4, u, sizeof u) == 1e-3 && !strcmp(u, "kPa"));
    assert_true(pm_picture_unit_scale("Pa", 3e7, u, sizeof u) == 1e-6 && !strcmp(u, "MPa"));
    assert_true(pm_picture_unit_scale("m/s", 3e7, u, sizeof u) == 1 && !strcmp(u, "m/s"));
}

static void bad_input_is_refused(void **state)
{
    (void)state;
    pm_grid g;
    pm_particles p;
    grid(&g, 2, 1);
    particles(&p, 1);
    assert_int_equal(pm_render_particles("no/such/dir/x.png", &g, &p, PM_FIELD_BODY, 400, NULL), PM_EIO);
    assert_non_null(strstr(pm_error_message(), "no/such/dir/x.png"));
    assert_int_equal(pm_render_particles(png, &g, &p, PM_FIELD_BODY, 100, NULL), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "width 100"));
    const double bad[2] = {1, 1};
    assert_int_equal(pm_render_field(png, &g, &p, PM_FIELD_SPEED, &(pm_render_opts){.range = bad}), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "range"));
    pm_particles_free(&p);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(size_follows_the_grid),
        cmocka_unit_test(speed_colours_at_the_particles),
        cmocka_unit_test(particles_are_drawn_as_their_deformed_area),
        cmocka_unit_test(sheared_particles_keep_an_aspect_of_four),
        cmocka_unit_test(swollen_particles_are_drawn_at_four_times_their_area),
        cmocka_unit_test(axisymmetric_particles_have_their_rz_size),
        cmocka_unit_test(body_colours_from_the_palette),
        cmocka_unit_test(colour_bar_label_is_whole),
        cmocka_unit_test(stress_units_get_a_prefix),
        cmocka_unit_test(bad_input_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
