/*
 * The pictures of a run have one colour range (src/io/run_pictures.c), and `pmech render`
 * (pm_render_dir) redraws them from the frames.
 *
 * A block falls freely under g = 10 m/s^2: every particle has the speed g t (linear MPM moves a rigid
 * body exactly: the nodal velocity of a uniform field is that field, and v gains g dt per step), so each
 * picture is one colour. With one range for the run, [0, g T], the picture at time t shows the ramp at
 * t / T: the darkest colour at t = 0 and the brightest at T. A picture coloured over its own frame's
 * range would show the middle of the ramp for every uniform frame, and fails. A fixed picture_range
 * [0, 2 g T] puts the last frame at the middle. Tolerance: 2 levels of 255 (8-bit rounding of the
 * ramp, and t / T from the frame's time rounded to 17 digits).
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
#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/frame.h"
#include "pmech/render.h"
#include "pmech/sim.h"

#define G 10.0
#define T_END 0.2

static const char *case_text =
    "{ \"title\": \"fall\", \"dimension\": 2,\n"
    "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.2, \"gravity\": [0, -10], \"dt\": 1e-3 },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [10, 10] },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
    "  \"bodies\": [ { \"name\": \"block\", \"material\": \"m\",\n"
    "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.3, 0.5], \"max\": [0.7, 0.9] } } ],\n"
    "  \"output\": { \"directory\": \"run_pictures.out\", \"interval\": 0.05, \"pictures\": \"speed\" } }\n";

/* The colour of picture @p png at the block's centre in frame @p vtu. */
static void colour_at_block(const char *png, const char *vtu, const char *title, int rgb[3], double *t)
{
    pm_frame *f;
    assert_int_equal(pm_frame_read(vtu, &f), PM_OK);
    *t = pm_frame_time(f);
    double cx = 0, cy = 0;
    const size_t n = pm_frame_n_points(f);
    for (size_t i = 0; i < n; i++) {
        cx += pm_frame_points(f)[3 * i] / (double)n;
        cy += pm_frame_points(f)[3 * i + 1] / (double)n;
    }
    pm_frame_free(f);
    pm_picture pic;
    memset(&pic, 0, sizeof pic);
    static const double v = 0;
    pic.value = &v;
    pic.range[1] = 1;
    pic.hi[0] = pic.hi[1] = 1;
    pic.title = title;
    pic.time = *t;
    pic.width = 800;
    pm_picture_layout L;
    assert_int_equal(pm_picture_layout_of(&pic, &L), PM_OK);
    cairo_surface_t *s = cairo_image_surface_create_from_png(png);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    assert_int_equal(cairo_image_surface_get_height(s), L.height);
    /* the centre falls between four particles: look just beside it, inside one */
    const int x = (int)floor(L.plot_x + (cx + 0.01) * L.scale), y = (int)floor(L.plot_y + L.plot_h - (cy + 0.01) * L.scale);
    const uint32_t px = *(const uint32_t *)(cairo_image_surface_get_data(s) +
                                            (size_t)y * (size_t)cairo_image_surface_get_stride(s) + 4 * (size_t)x);
    rgb[0] = (int)(px >> 16 & 255);
    rgb[1] = (int)(px >> 8 & 255);
    rgb[2] = (int)(px & 255);
    cairo_surface_destroy(s);
}

static void expect_ramp(const int got[3], double u, const char *what)
{
    double want[3];
    pm_picture_ramp(u, want);
    for (int c = 0; c < 3; c++)
        if (abs(got[c] - (int)(want[c] * 255 + 0.5)) > 2)
            fail_msg("%s: colour (%d, %d, %d), want the ramp at %.3f (%d, %d, %d)", what, got[0], got[1], got[2], u,
                     (int)(want[0] * 255 + 0.5), (int)(want[1] * 255 + 0.5), (int)(want[2] * 255 + 0.5));
}

static void run(pm_case *c, const char *dir)
{
    pm_run_opts o = {.out_dir = dir, .quiet = 1, .threads = 1, .write_output = 1};
    if (pm_run(c, &o, NULL) != PM_OK)
        fail_msg("%s", pm_error_message());
}

static void one_range_for_the_run(void **state)
{
    (void)state;
    pm_case c;
    assert_int_equal(pm_case_load_buffer(case_text, strlen(case_text), "fall.json", &c), PM_OK);
    run(&c, "run_pictures.out");
    for (int k = 0; k <= 4; k++) {
        char png[64], vtu[64], what[64];
        snprintf(png, sizeof png, "run_pictures.out/particles_%06d.png", k);
        snprintf(vtu, sizeof vtu, "run_pictures.out/particles_%06d.vtu", k);
        int rgb[3];
        double t;
        colour_at_block(png, vtu, "fall", rgb, &t);
        snprintf(what, sizeof what, "frame %d (t = %g s)", k, t);
        expect_ramp(rgb, t / T_END, what);
    }
    /* a fixed range [0, 2 g T]: the last frame in the middle of the ramp */
    assert_int_equal(pm_case_set_json(&c, "output.picture_range", "[0, 4]"), PM_OK);
    run(&c, "run_pictures.out");
    int rgb[3];
    double t;
    colour_at_block("run_pictures.out/particles_000004.png", "run_pictures.out/particles_000004.vtu", "fall", rgb, &t);
    expect_ramp(rgb, 0.5, "last frame with picture_range [0, 4]");
    pm_case_free(&c);
}

/* pm_render_dir redraws any field over one range: velocity.y runs from 0 (t = 0, the top of its range,
 * the brightest colour) to -g T (the darkest). An unknown field is refused with the frame's arrays. */
static void render_redraws_from_frames(void **state)
{
    (void)state;
    pm_case c;
    assert_int_equal(pm_case_load_buffer(case_text, strlen(case_text), "fall.json", &c), PM_OK);
    run(&c, "run_pictures.out");
    pm_render_dir_opts o = {.field = "velocity.y", .quiet = 1};
    size_t n = 0;
    if (pm_render_dir("run_pictures.out", &o, &n) != PM_OK)
        fail_msg("%s", pm_error_message());
    assert_int_equal(n, 5);
    int rgb[3];
    double t;
    colour_at_block("run_pictures.out/velocity_y_000000.png", "run_pictures.out/particles_000000.vtu", "fall", rgb,
                    &t);
    expect_ramp(rgb, 1.0, "velocity.y at t = 0");
    colour_at_block("run_pictures.out/velocity_y_000004.png", "run_pictures.out/particles_000004.vtu", "fall", rgb,
                    &t);
    expect_ramp(rgb, 0.0, "velocity.y at the end");
    o.field = "velocity.w";
    assert_int_equal(pm_render_dir("run_pictures.out", &o, &n), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "velocity.w"));
    assert_non_null(strstr(pm_error_message(), "deviatoric_strain"));
    o.field = "speed";
    o.animation = "run_pictures.out/speed.gif";
    o.fps = 5;
    if (pm_render_dir("run_pictures.out", &o, &n) != PM_OK)
        fail_msg("%s", pm_error_message());
    FILE *f = fopen("run_pictures.out/speed.gif", "rb");
    assert_non_null(f);
    char magic[6] = {0};
    assert_int_equal(fread(magic, 1, 6, f), 6);
    fclose(f);
    assert_memory_equal(magic, "GIF89a", 6);
    o.animation = "run_pictures.out/speed.avi";
    assert_int_equal(pm_render_dir("run_pictures.out", &o, &n), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), ".gif or .mp4"));
    pm_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(one_range_for_the_run),
        cmocka_unit_test(render_redraws_from_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
