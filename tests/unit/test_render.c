/*
 * Particle pictures (src/io/render.c), read back with cairo's PNG reader.
 *
 * Size: a 40-pixel margin all round and, for a field other than body, a 70-pixel colour bar; the
 * scale fits the grid's width into what is left, unless the height would pass twice the width.
 * Colours: the field's range over the particles maps onto the ramp, whose ends and middle are the
 * stops render.c defines (dark purple, teal, yellow, close to viridis); body pictures use the body
 * palette. A particle is a square of its half-size around its position, so the pixel at its centre
 * has its colour exactly, while a pixel where no particle is stays white.
 * Tolerance: 1 level of 255 per channel, cairo's rounding of a double colour to 8 bits; 4 levels
 * in the middle of the colour bar, whose 100 bands step by 0.01 in the ramp's parameter.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/error.h"
#include "pmech/render.h"

static const char *png = "test_render.png";

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

/* Whether pixel (x, y) has colour rgb (0..1) within tol levels of 255 per channel. */
static void expect_pixel(const picture *p, int x, int y, const double rgb[3], int tol)
{
    assert_true(x >= 0 && x < p->w && y >= 0 && y < p->h);
    const uint32_t v = *(const uint32_t *)(p->data + (size_t)y * (size_t)p->stride + 4 * (size_t)x);
    const int got[3] = {(int)(v >> 16 & 255), (int)(v >> 8 & 255), (int)(v & 255)};
    for (int c = 0; c < 3; c++) {
        const int want = (int)(rgb[c] * 255 + 0.5);
        if (abs(got[c] - want) > tol)
            fail_msg("pixel (%d, %d): got (%d, %d, %d), want (%d, %d, %d) within %d", x, y, got[0], got[1], got[2],
                     (int)(rgb[0] * 255 + 0.5), (int)(rgb[1] * 255 + 0.5), (int)(rgb[2] * 255 + 0.5), tol);
    }
}

static void grid(pm_grid *g, double lx, double ly)
{
    const double origin[PM_DIM] = {0, 0}, size[PM_DIM] = {lx, ly};
    const int cells[PM_DIM] = {2, 2};
    assert_int_equal(pm_grid_rectangle(g, origin, size, cells, PM_QUAD4), PM_OK);
}

/* n particles at y = 0.5, x = 0.5, 1.0, 1.5, ..., half-size 0.1, at rest, body i. */
static void particles(pm_particles *p, size_t n)
{
    assert_int_equal(pm_particles_alloc(p, n, 0), PM_OK);
    for (size_t i = 0; i < n; i++) {
        p->x[PM_DIM * i] = p->x0[PM_DIM * i] = 0.5 + 0.5 * (double)i;
        p->x[PM_DIM * i + 1] = p->x0[PM_DIM * i + 1] = 0.5;
        p->hsize[PM_DIM * i] = p->hsize[PM_DIM * i + 1] = 0.1;
        p->vol[i] = p->vol0[i] = 0.04;
        p->body[i] = (int32_t)i;
    }
}

static void size_follows_the_grid(void **state)
{
    (void)state;
    static const struct {
        double lx, ly;
        pm_field f;
        int w, h;
    } cases[] = {
        {2, 1, PM_FIELD_SPEED, 400, 205}, /* scale (400 - 80 - 70) / 2 = 125: 125 + 80 high */
        {2, 1, PM_FIELD_BODY, 400, 240},  /* no bar: (400 - 80) / 2 = 160 */
        {1, 10, PM_FIELD_BODY, 400, 880}, /* 320 * 10 > 800: scale 800 / 10 = 80, 800 + 80 high */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        pm_grid g;
        pm_particles p;
        grid(&g, cases[k].lx, cases[k].ly);
        particles(&p, 1);
        assert_int_equal(pm_render_particles(png, &g, &p, cases[k].f, cases[k].w, "size"), PM_OK);
        picture pic;
        open_picture(&pic);
        assert_int_equal(pic.w, cases[k].w);
        assert_int_equal(pic.h, cases[k].h);
        close_picture(&pic);
        pm_particles_free(&p);
        pm_grid_free(&g);
    }
}

/* Speeds 0, 2.5 and 5 on the grid [0, 2] x [0, 1] at width 400 (scale 125, height 205): the
 * particle at model (x, 0.5) is centred on pixel (40 + 125 x, 205 - 40 - 62.5). */
static void speed_colours_at_the_particles(void **state)
{
    (void)state;
    static const double lo[3] = {0.267, 0.005, 0.329}, mid[3] = {0.129, 0.569, 0.549}, hi[3] = {0.993, 0.906, 0.144},
                        white[3] = {1, 1, 1};
    pm_grid g;
    pm_particles p;
    grid(&g, 2, 1);
    particles(&p, 3);
    const double v1[PM_DIM] = {1.5, 2.0}, v2[PM_DIM] = {3.0, 4.0}; /* |v| = 2.5 and 5 */
    memcpy(p.v + PM_DIM * 1, v1, sizeof v1);
    memcpy(p.v + PM_DIM * 2, v2, sizeof v2);
    assert_int_equal(pm_render_particles(png, &g, &p, PM_FIELD_SPEED, 400, NULL), PM_OK);
    picture pic;
    open_picture(&pic);
    const int y = 205 - 40 - 62;
    expect_pixel(&pic, 40 + 62, y, lo, 1);   /* x = 0.5: the lowest speed */
    expect_pixel(&pic, 40 + 125, y, mid, 1); /* x = 1.0: halfway */
    expect_pixel(&pic, 40 + 187, y, hi, 1);  /* x = 1.5: the highest */
    /* 20 pixels above the particles (their half-size is 12.5) and left of them: empty */
    expect_pixel(&pic, 40 + 62, y - 25, white, 1);
    expect_pixel(&pic, 40 + 20, y, white, 1);
    expect_pixel(&pic, 10, 100, white, 1); /* the margin */
    /* the colour bar, 14 pixels wide from x = 400 - 70 + 10, spans the grid's height */
    expect_pixel(&pic, 400 - 70 + 17, 40 + 62, mid, 4);
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
    /* body pictures have no bar: scale 160, height 240; model (x, 0.5) -> (40 + 160 x, 120) */
    assert_int_equal(pm_render_particles(png, &g, &p, PM_FIELD_BODY, 400, NULL), PM_OK);
    picture pic;
    open_picture(&pic);
    expect_pixel(&pic, 40 + 80, 120, b0, 1);
    expect_pixel(&pic, 40 + 160, 120, b1, 1);
    close_picture(&pic);
    pm_particles_free(&p);
    pm_grid_free(&g);
}

static void unwritable_path_is_an_io_error(void **state)
{
    (void)state;
    pm_grid g;
    pm_particles p;
    grid(&g, 2, 1);
    particles(&p, 1);
    assert_int_equal(pm_render_particles("no/such/dir/x.png", &g, &p, PM_FIELD_BODY, 400, NULL), PM_EIO);
    assert_non_null(strstr(pm_error_message(), "no/such/dir/x.png"));
    pm_particles_free(&p);
    pm_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(size_follows_the_grid),
        cmocka_unit_test(speed_colours_at_the_particles),
        cmocka_unit_test(body_colours_from_the_palette),
        cmocka_unit_test(unwritable_path_is_an_io_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
