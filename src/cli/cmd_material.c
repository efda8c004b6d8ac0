/* `pmech material`: drive one material point along a path and write its response as CSV. */
#include "cli/commands.h"

#include "pmech/case.h"
#include "pmech/driver.h"
#include "pmech/error.h"

#include <stdio.h>
#include <string.h>

void pm_cmd_material_usage(FILE *f)
{
    fprintf(f, "usage: pmech material DRIVER.json [-o OUT.csv]\n"
               "  Drive one material point along the driver file's path (docs/materials.md) and write CSV\n"
               "  with the columns\n  %s\n"
               "  -o, --output OUT.csv  write to OUT.csv instead of standard output\n"
               "  -h, --help            this text\n",
            PM_DRIVER_CSV_HEADER);
}

static int bad_usage(const char *what)
{
    fprintf(stderr, "pmech material: %s\nusage: pmech material DRIVER.json [-o OUT.csv]\n", what);
    return 2;
}

int pm_cmd_material(int argc, char **argv)
{
    const char *file = NULL, *out = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--output")) {
            if (++i >= argc)
                return bad_usage("-o needs a file name");
            out = argv[i];
        } else if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
            pm_cmd_material_usage(stdout);
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            char msg[256];
            snprintf(msg, sizeof msg, "unknown option '%s'", argv[i]);
            return bad_usage(msg);
        } else if (!file) {
            file = argv[i];
        } else {
            return bad_usage("only one driver file may be given");
        }
    }
    if (!file)
        return bad_usage("no driver file given");
    pm_driver d;
    memset(&d, 0, sizeof d);
    int rc = pm_driver_load(file, &d);
    if (rc) {
        fprintf(stderr, "pmech: %s\n", pm_error_message());
        pm_driver_free(&d);
        return pm_exit_code(rc);
    }
    FILE *f = stdout;
    if (out) {
        f = fopen(out, "w");
        if (!f) {
            fprintf(stderr, "pmech: cannot write '%s'\n", out);
            pm_driver_free(&d);
            return 1;
        }
    }
    rc = pm_driver_run(&d, f);
    int wrc = 0;
    if (out)
        wrc = fclose(f);
    else
        wrc = fflush(f);
    if (rc)
        fprintf(stderr, "pmech: %s\n", pm_error_message());
    else if (wrc) {
        fprintf(stderr, "pmech: error writing '%s'\n", out ? out : "stdout");
        rc = PM_EIO;
    }
    pm_driver_free(&d);
    return pm_exit_code(rc);
}
