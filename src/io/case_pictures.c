/* The picture options of `output`: a fixed colour range and the width. */
#include "io/case_internal.h"
#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>

int pm_case_parse_picture_options(pm_case *c, const jr_ctx *cx, json_t *o)
{
    const double none[2] = {NAN, NAN};
    pm_check(jr_vec2(cx, o, "picture_range", 0, none, c->output.picture_range));
    const double *r = c->output.picture_range;
    if (json_object_get(o, "picture_range") && !(r[1] > r[0])) {
        char got[128];
        snprintf(got, sizeof got, "[%g, %g]; allowed: [lo, hi] with lo < hi", r[0], r[1]);
        return pm_case_fail(c->file, "output.picture_range", "got ", got);
    }
    long w;
    pm_check(jr_int(cx, o, "picture_width", 0, 800, 200, 8000, &w));
    c->output.picture_width = (int)w;
    return PM_OK;
}
