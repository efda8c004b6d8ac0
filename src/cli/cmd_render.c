/* `pmech render`: redraw the pictures of a finished (or stopped) run from its frames, coloured by any
 * field, with one colour range, and optionally an animation of them. */
#include "cli/commands.h"

#include "pmech/error.h"
#include "pmech/render.h"

#include <stdlib.h>
#include <string.h>

#define RENDER_USAGE "pmech render DIR --field F [--range LO HI] [--width PX] [-o OUTDIR] [--animation FILE] [--fps N]\n"

void pm_cmd_render_usage(FILE *f)
{
    fprintf(f, "usage: " RENDER_USAGE
               "  Draw every frame of the run in DIR (its particles.pvd) coloured by field F, as\n"
               "  OUTDIR/F_NNNNNN.png, all with one colour range, without running anything again.\n"
               "  -f, --field F        body, material, speed, grid_speed, displacement, pressure, q, sxx, syy,\n"
               "                       szz, sxy, plastic_strain, volumetric_strain, deviatoric_strain; any array of\n"
               "                       the frames (mass, volume); a vector's magnitude (velocity); or one\n"
               "                       component as ARRAY.C (velocity.y, stress.xy)\n"
               "  --range LO HI        fixed colour range in the field's SI unit (default: the smallest to\n"
               "                       the largest value over all frames)\n"
               "  --width PX           picture width in pixels, 200 to 8000 (default 800)\n"
               "  -o, --output OUTDIR  where the pictures go (default DIR)\n"
               "  --animation FILE     also make FILE.gif or FILE.mp4 of the pictures (needs ffmpeg)\n"
               "  --fps N              frames per second of the animation (default 10)\n"
               "  -q, --quiet          no progress line\n"
               "  -h, --help           this text\n");
}

static int bad_usage(const char *what)
{
    fprintf(stderr, "pmech render: %s\nusage: " RENDER_USAGE "(pmech render --help)\n", what);
    return 2;
}

/* A number argument; 0 and a message when it is not one. */
static int number(const char *s, double *v)
{
    char *end = NULL;
    *v = strtod(s, &end);
    return end != s && *end == '\0';
}

int pm_cmd_render(int argc, char **argv)
{
    const char *dir = NULL;
    double range[2], width = 0;
    pm_render_dir_opts o = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const int more = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            pm_cmd_render_usage(stdout);
            return 0;
        } else if (!strcmp(a, "-f") || !strcmp(a, "--field")) {
            if (!more)
                return bad_usage("--field needs a field name");
            o.field = argv[++i];
        } else if (!strcmp(a, "--range")) {
            if (i + 2 >= argc || !number(argv[i + 1], &range[0]) || !number(argv[i + 2], &range[1]) ||
                !(range[1] > range[0]))
                return bad_usage("--range takes two numbers LO HI with LO < HI");
            o.range = range;
            i += 2;
        } else if (!strcmp(a, "--width")) {
            if (!more || !number(argv[i + 1], &width) || width != (int)width || width < 200 || width > 8000)
                return bad_usage("--width takes a whole number of pixels from 200 to 8000");
            o.width = (int)width;
            i++;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!more)
                return bad_usage("-o needs a directory");
            o.out_dir = argv[++i];
        } else if (!strcmp(a, "--animation")) {
            if (!more)
                return bad_usage("--animation needs a file name ending in .gif or .mp4");
            o.animation = argv[++i];
        } else if (!strcmp(a, "--fps")) {
            if (!more || !number(argv[i + 1], &o.fps) || !(o.fps > 0 && o.fps <= 120))
                return bad_usage("--fps takes a number of frames per second in (0, 120]");
            i++;
        } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
            o.quiet = 1;
        } else if (a[0] == '-') {
            char msg[256];
            snprintf(msg, sizeof msg, "unknown option '%s'", a);
            return bad_usage(msg);
        } else if (!dir) {
            dir = a;
        } else {
            return bad_usage("only one run directory may be given");
        }
    }
    if (!dir)
        return bad_usage("no run directory given");
    if (!o.field)
        return bad_usage("no --field given");
    /* a directory without frames is a wrong argument (exit 2), not a failure to write (exit 1) */
    pm_series s;
    int rc = pm_series_read(dir, &s);
    pm_series_free(&s);
    if (rc) {
        fprintf(stderr, "pmech: %s (is '%s' the output directory of a run?)\n", pm_error_message(), dir);
        return 2;
    }
    size_t n = 0;
    rc = pm_render_dir(dir, &o, &n);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        return pm_exit_code(rc);
    }
    if (!o.quiet) {
        fprintf(stderr, "pmech: %zu pictures of %s in %s/", n, o.field, o.out_dir ? o.out_dir : dir);
        if (o.animation)
            fprintf(stderr, ", animation %s", o.animation);
        fputc('\n', stderr);
    }
    return 0;
}
