/* grid of a case, and the refusal of counts that cannot be allocated. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"
#include "pmech/grid.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const grid_types[] = {"rectangle", "gmsh", NULL};
static const char *const elements[] = {"quad4", "tri3", NULL};

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

int pm_case_parse_grid(pm_case *c, json_t *g)
{
    jr_ctx cx = {c->file, "grid"};
    pm_check(jr_expect_object(&cx, "", g));
    int v;
    pm_check(jr_enum(&cx, g, "type", JR_REQUIRED, grid_types, 0, &v));
    c->grid.type = (pm_grid_type)v;
    if (c->grid.type == PM_GRID_GMSH) {
        pm_check(jr_only_keys(&cx, g, pm_case_keys(PM_KEYS_GRID_GMSH)));
        char rel[PM_PATH_MAX];
        pm_check(jr_string(&cx, g, "file", JR_REQUIRED, NULL, rel, sizeof rel));
        if (rel[0] == '/')
            snprintf(c->grid.file, sizeof c->grid.file, "%s", rel);
        else if ((size_t)snprintf(c->grid.file, sizeof c->grid.file, "%s/%s", c->dir, rel) >= sizeof c->grid.file)
            return pm_case_fail(c->file, "grid.file", "path too long", NULL);
        if (!file_exists(c->grid.file))
            return pm_error_set(PM_EINPUT, "%s: grid.file: mesh file \"%s\" not found (resolved against the case's "
                                "directory)", c->file, c->grid.file);
        pm_check(jr_bool(&cx, g, "lattice", 0, 1, &c->grid.lattice));
        return PM_OK;
    }
    pm_check(jr_only_keys(&cx, g, pm_case_keys(PM_KEYS_GRID_RECTANGLE)));
    const double zero[PM_DIM] = {0, 0};
    pm_check(jr_vec2(&cx, g, "origin", 0, zero, c->grid.origin));
    pm_check(jr_vec2(&cx, g, "size", JR_REQUIRED, NULL, c->grid.size));
    for (int d = 0; d < PM_DIM; d++)
        if (!(c->grid.size[d] > 0))
            return pm_error_set(PM_EINPUT, "%s: grid.size: got [%g, %g]; allowed: two lengths > 0", c->file,
                                c->grid.size[0], c->grid.size[1]);
    json_t *cells = json_object_get(g, "cells");
    if (!cells)
        return pm_case_fail(c->file, "grid.cells", "required key is missing", NULL);
    if (!json_is_array(cells) || json_array_size(cells) != PM_DIM || !json_is_integer(json_array_get(cells, 0)) ||
        !json_is_integer(json_array_get(cells, 1)))
        return pm_error_set(PM_EINPUT, "%s: grid.cells: expected a list of two whole numbers, got %s", c->file,
                            jr_text(cells));
    for (int d = 0; d < PM_DIM; d++) {
        json_int_t n = json_integer_value(json_array_get(cells, d));
        if (n < 1 || n > 100000000)
            return pm_error_set(PM_EINPUT, "%s: grid.cells[%d]: got %lld; allowed: 1 to 100000000", c->file, d,
                                (long long)n);
        c->grid.cells[d] = (int)n;
    }
    for (int d = 0; d < PM_DIM; d++) {
        /* a double holds a coordinate to 2.2e-16 of its size: far from 0 a small cell has no room left */
        const double h = c->grid.size[d] / c->grid.cells[d];
        const double far = fmax(fabs(c->grid.origin[d]), fabs(c->grid.origin[d] + c->grid.size[d]));
        if (!(far / h <= PM_COORD_PER_CELL_MAX))
            return pm_error_set(PM_EINPUT,
                                "%s: grid.origin: coordinates up to %g with cells of %g m: a double resolves %.2g of a "
                                "cell there, too coarse for shape functions (allowed: |coordinate| / cell below %g); "
                                "move the origin near 0",
                                c->file, far, h, far * 2.2e-16 / h, PM_COORD_PER_CELL_MAX);
    }
    pm_check(jr_enum(&cx, g, "element", 0, elements, PM_QUAD4, &v));
    c->grid.element = v;
    return PM_OK;
}

/* At most the particles of a body filling its shape's bounding box. */
static double box_particles(const pm_case *c, const pm_case_body *body, double cell_area)
{
    double lo[PM_DIM], hi[PM_DIM];
    pm_case_shape_box(&body->shape, lo, hi);
    const int n = body->particles_per_cell;
    const double per_cell = c->grid.element == PM_QUAD4 ? (double)(n ? n : 2) * (n ? n : 2) : 2.0 * (n ? n : 3);
    return (hi[0] - lo[0]) * (hi[1] - lo[1]) / cell_area * per_cell;
}

void pm_case_estimate_sizes(const pm_case *c, double *particles, double *nodes)
{
    *particles = *nodes = 0;
    if (c->grid.type != PM_GRID_RECTANGLE)
        return;
    const double cells = (double)c->grid.cells[0] * (double)c->grid.cells[1];
    const double cell_area = c->grid.size[0] * c->grid.size[1] / cells;
    for (size_t b = 0; b < c->n_bodies; b++)
        *particles += box_particles(c, &c->bodies[b], cell_area);
    for (size_t k = 0; k < c->n_sources; k++) /* room for every release is allocated at the start */
        *particles += box_particles(c, &c->sources[k].body, cell_area) * (double)pm_case_source_releases(c, k);
    *nodes = (double)(c->grid.cells[0] + 1) * (double)(c->grid.cells[1] + 1);
}

int pm_case_check_sizes(const pm_case *c)
{
    if (c->grid.type != PM_GRID_RECTANGLE)
        return PM_OK;
    double particles, nodes;
    pm_case_estimate_sizes(c, &particles, &nodes);
    const double bytes = particles * 220.0 + nodes * 120.0;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const double mem = pages > 0 && page > 0 ? (double)pages * (double)page : 1e12;
    if (particles > (double)INT32_MAX || nodes > (double)INT32_MAX || bytes > mem)
        return pm_error_set(PM_EINPUT,
                            "%s: grid.cells: about %.3g particles and %.3g grid nodes would need %.3g GB of memory; "
                            "this machine has %.3g GB (and at most %d of each fit); use fewer cells or particles",
                            c->file, particles, nodes, bytes / 1e9, mem / 1e9, INT32_MAX);
    return PM_OK;
}
