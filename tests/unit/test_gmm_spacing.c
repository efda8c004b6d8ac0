/* The nodal spacing h of a GMM node cloud made from a grid, which seed 000's MLS support
 * r = 1.5 sqrt(2 h^2) scales with: the cell side of a structured grid (quads, or quads cut into
 * triangles), and on an unstructured mesh the square root of the area per node of the cells holding
 * particles, not the cells' smallest altitude, which stays the time step's length. Each case's mesh has
 * a known spacing, and its smallest altitude differs from it, so that a cloud sized by the altitude
 * fails. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"
#include "shape/meshfree.h"
#include "solver/meshfree_internal.h"
#include "sim_case.h"

/* A GMM simulation of a block (@p shape, JSON) on @p grid (JSON), loaded as if from @p case_path. */
static pm_sim *gmm_sim(const char *case_path, const char *grid, const char *shape, pm_case *c)
{
    char text[2048];
    snprintf(text, sizeof text,
             "{ \"dimension\": 2, \"method\": \"gmm\","
             "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.01, \"gravity\": [0, -9.81] },"
             "  \"grid\": %s,"
             "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,"
             "                   \"youngs_modulus\": 1.0e7, \"poisson_ratio\": 0.3 } ],"
             "  \"bodies\": [ { \"name\": \"b\", \"material\": \"m\", \"shape\": %s } ] }",
             grid, shape);
    pm_sim *s = sc_sim_of(text, case_path, c);
    assert_non_null(s->mf);
    return s;
}

/* The cloud's h and the MLS radius 1.5 sqrt(2) h against the spacing @p h, to round-off (the areas
 * are sums of products of coordinates of order 0.1 m). */
static void check_spacing(pm_sim *s, double h, const char *what)
{
    const double got = s->mf->cloud->h, r0 = pm_meshfree_radius(s->approx);
    printf("%s: spacing %.9g (expected %.9g), smallest cell size %.9g, MLS radius %.9g\n", what, got, h,
           s->mf->background.h_min, r0);
    assert_true(fabs(got - h) < 1e-12 * h);
    assert_true(fabs(r0 - 1.5 * sqrt(2.0) * h) < 1e-12 * h);
    /* the time step still follows the smallest cell, which a graded mesh's finest cells need */
    assert_true(s->grid.h_min == s->mf->background.h_min);
}

/* The triangles of the Gmsh incline (tests/verification/cases/make_gmsh_incline.py): columns 0.01 apart,
 * rows 0.01 apart along x = const, so each parallelogram of 1e-4 m^2 is two triangles and the spacing is
 * 0.01; the smallest altitude, across the longer diagonal, is 0.0056. */
static void gmsh_triangles(void **state)
{
    (void)state;
    char path[1024];
    sc_repo_path("tests/verification/cases/gmsh_incline.json", path, sizeof path);
    pm_case c;
    pm_sim *s = gmm_sim(path, "{ \"type\": \"gmsh\", \"file\": \"gmsh_incline25.msh\" }",
                        "{ \"type\": \"rectangle\", \"min\": [0.2, 0.33], \"max\": [0.3, 0.4] }", &c);
    assert_true(s->mf->background.h_min < 0.6 * 0.01);
    check_spacing(s, 0.01, "gmsh_incline25.msh");
    pm_sim_destroy(s);
    pm_case_free(&c);
}

/* A Gmsh mesh of 10 x 10 quads of 0.02 m x 0.005 m: area per node 1e-4 m^2, spacing 0.01, while the
 * smallest cell size (area over the longest side) is 0.005. */
static void gmsh_quads(void **state)
{
    (void)state;
    enum { NX = 10, NY = 10 };
    const double dx = 0.02, dy = 0.005;
    char mesh[] = "/tmp/pmech_test_gmm_spacing_XXXXXX";
    const int fd = mkstemp(mesh);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    assert_non_null(f);
    const int nn = (NX + 1) * (NY + 1);
    fprintf(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"block\"\n$EndPhysicalNames\n"
               "$Entities\n0 0 1 0\n1 0 0 0 %g %g 0 1 1 0\n$EndEntities\n$Nodes\n1 %d 1 %d\n2 1 0 %d\n",
            NX * dx, NY * dy, nn, nn, nn);
    for (int k = 1; k <= nn; k++)
        fprintf(f, "%d\n", k);
    for (int j = 0; j <= NY; j++)
        for (int i = 0; i <= NX; i++)
            fprintf(f, "%.17g %.17g 0\n", i * dx, j * dy);
    fprintf(f, "$EndNodes\n$Elements\n1 %d 1 %d\n2 1 3 %d\n", NX * NY, NX * NY, NX * NY);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            const int a = j * (NX + 1) + i + 1;
            fprintf(f, "%d %d %d %d %d\n", j * NX + i + 1, a, a + 1, a + NX + 2, a + NX + 1);
        }
    fprintf(f, "$EndElements\n");
    fclose(f);
    char grid[256];
    snprintf(grid, sizeof grid, "{ \"type\": \"gmsh\", \"file\": \"%s\" }", mesh);
    pm_case c;
    pm_sim *s = gmm_sim("/tmp/gmm_spacing.json", grid, "{ \"type\": \"rectangle\", \"min\": [0.05, 0.01], "
                                                      "\"max\": [0.15, 0.04] }", &c);
    remove(mesh);
    assert_true(fabs(s->mf->background.h_min - dy) < 1e-12);
    check_spacing(s, 0.01, "Gmsh quads 0.02 x 0.005");
    pm_sim_destroy(s);
    pm_case_free(&c);
}

/* Structured grids keep their cell side, quads and triangles alike. */
static void structured(void **state)
{
    (void)state;
    const char *elements[] = {"quad4", "tri3"};
    for (int k = 0; k < 2; k++) {
        char grid[256];
        snprintf(grid, sizeof grid, "{ \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [0.2, 0.1], "
                 "\"cells\": [20, 10], \"element\": \"%s\" }", elements[k]);
        pm_case c;
        pm_sim *s = gmm_sim("/tmp/gmm_spacing.json", grid, "{ \"type\": \"rectangle\", \"min\": [0.05, 0.0], "
                                                          "\"max\": [0.15, 0.04] }", &c);
        check_spacing(s, 0.01, elements[k]);
        pm_sim_destroy(s);
        pm_case_free(&c);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gmsh_triangles),
        cmocka_unit_test(gmsh_quads),
        cmocka_unit_test(structured),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
