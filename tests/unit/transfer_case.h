/* Cases shared by the particle-grid transfer tests (tests/unit/test_transfer.c, test_apic.c,
 * test_xpic.c): an elastic disk on a square grid built in memory, and a small case file given to the
 * loader. Include after cmocka.h. */
#ifndef PMECH_TEST_TRANSFER_CASE_H
#define PMECH_TEST_TRANSFER_CASE_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/material.h"

/*
 * An explicit run of scheme @p scheme with linear shape functions (CFL 0.2, end time 1 s) on a grid of
 * @p cells x @p cells elements @p el over the unit square: a disk "disk" of radius @p radius centred
 * at (0.5, 0.5), of linear-elastic material "m" (density 1000 kg/m^3, Young's modulus @p youngs,
 * Poisson's ratio 0.3). @p c, @p mat and @p body are cleared first, so the transfer is FLIP without a
 * PIC share and there is no gravity; @p c points at @p mat and @p body, which must outlive it.
 */
static inline void tc_disk_case(pm_case *c, pm_material *mat, pm_case_body *body, const char *file,
                                pm_scheme scheme, pm_element el, int cells, double youngs, double radius)
{
    memset(c, 0, sizeof *c);
    snprintf(c->file, sizeof c->file, "%s", file);
    strcpy(c->shape_function, "linear");
    c->dimension = PM_DIM;
    c->analysis.type = PM_ANALYSIS_EXPLICIT;
    c->analysis.scheme = scheme;
    c->analysis.end_time = 1;
    c->analysis.cfl = 0.2;
    c->grid.type = PM_GRID_RECTANGLE;
    for (int d = 0; d < PM_DIM; d++) {
        c->grid.size[d] = 1.0;
        c->grid.cells[d] = cells;
    }
    c->grid.element = el;
    memset(mat, 0, sizeof *mat);
    mat->ops = pm_material_find("linear_elastic");
    assert_non_null(mat->ops);
    strcpy(mat->name, "m");
    mat->density = 1000;
    assert_int_equal(pm_material_set_elastic(mat, youngs, 0.3, NAN, NAN), 0);
    c->materials = mat;
    c->n_materials = 1;
    memset(body, 0, sizeof *body);
    strcpy(body->name, "disk");
    body->shape.type = PM_SHAPE_CIRCLE;
    for (int d = 0; d < PM_DIM; d++)
        body->shape.center[d] = 0.5;
    body->shape.radius = radius;
    c->bodies = body;
    c->n_bodies = 1;
}

/*
 * Load a small explicit case on method @p method (an elastic block on a 4 x 4 grid) whose analysis
 * object ends with @p extra (", \"key\": value" pairs) into @p c. Returns the loader's status; the
 * caller frees @p c with pm_case_free whatever it is.
 */
static inline int tc_load(const char *method, const char *extra, pm_case *c)
{
    char buf[2048];
    snprintf(buf, sizeof buf,
             "{ \"dimension\": 2, \"method\": \"%s\",\n"
             "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.01%s },\n"
             "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [4, 4] },\n"
             "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
             "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
             "  \"bodies\": [ { \"material\": \"m\",\n"
             "                \"shape\": { \"type\": \"rectangle\", \"min\": [0, 0], \"max\": [1, 0.5] } } ] }\n",
             method, extra);
    return pm_case_load_buffer(buf, strlen(buf), "case.json", c);
}

/* The case of tc_load refused as bad input, with a message that names @p key. */
static inline void tc_refused(const char *method, const char *extra, const char *key)
{
    pm_case c;
    const int rc = tc_load(method, extra, &c);
    pm_case_free(&c);
    assert_int_equal(rc, PM_EINPUT);
    if (!strstr(pm_error_message(), key))
        fail_msg("message \"%s\" lacks \"%s\"", pm_error_message(), key);
}

#endif
