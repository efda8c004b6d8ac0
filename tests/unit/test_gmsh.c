/* Gmsh MSH 4.1 reader: the example mesh (nodes, triangles, physical groups as node and cell sets,
 * outward normals of straight groups), quads, mixed meshes (quads split), and a message naming
 * file:line for each class of bad file. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/error.h"
#include "pmech/grid.h"

/* The repository root from this file's path (CMake passes absolute source paths). */
static void repo_path(const char *rel, char *out, size_t n)
{
    const char *f = __FILE__, *cut = strstr(f, "tests/unit/");
    snprintf(out, n, "%.*s%s", (int)(cut ? cut - f : 0), f, rel);
}

static void example_mesh(void **state)
{
    (void)state;
    char path[1024];
    repo_path("examples/gmsh_bar/bar.msh", path, sizeof path);
    pm_grid g;
    int rc = pm_grid_gmsh_read(&g, path);
    if (rc)
        fprintf(stderr, "%s\n", pm_error_message());
    assert_int_equal(rc, 0);
    assert_int_equal(g.element, PM_TRI3);
    assert_int_equal(g.n_nodes, 111 * 5);
    assert_int_equal(g.n_cells, 110 * 4 * 2);
    assert_false(g.structured);
    const pm_cell_set *bar = pm_grid_find_cell_set(&g, "bar"), *air = pm_grid_find_cell_set(&g, "air");
    assert_non_null(bar);
    assert_non_null(air);
    assert_int_equal(bar->n, 100 * 4 * 2);
    assert_int_equal(air->n, 10 * 4 * 2);
    const pm_node_set *fe = pm_grid_find_set(&g, "fixed_end"), *bot = pm_grid_find_set(&g, "bottom");
    const pm_node_set *top = pm_grid_find_set(&g, "top"), *free_end = pm_grid_find_set(&g, "free_end");
    assert_non_null(fe);
    assert_non_null(bot);
    assert_non_null(top);
    assert_non_null(free_end);
    assert_int_equal(fe->n, 5);
    assert_int_equal(bot->n, 111);
    for (size_t i = 0; i < fe->n; i++)
        assert_true(fabs(g.x[2 * fe->nodes[i]] - 1.0) < 1e-12);
    assert_true(fabs(fe->normal[0] - 1) < 1e-12 && fabs(fe->normal[1]) < 1e-12);
    assert_true(fabs(bot->normal[1] + 1) < 1e-12 && fabs(bot->normal[0]) < 1e-12);
    assert_true(fabs(top->normal[1] - 1) < 1e-12);
    /* an interior line: the normal points out of whichever cell was found first; it is a unit vector */
    assert_true(fabs(hypot(free_end->normal[0], free_end->normal[1]) - 1) < 1e-12);
    /* the bounding-box sides are there too */
    assert_non_null(pm_grid_find_set(&g, "x_max"));
    double x[2] = {0.5, 0.02};
    int32_t c = pm_grid_locate(&g, x);
    assert_true(c >= 0);
    int in_bar = 0;
    for (size_t i = 0; i < bar->n; i++)
        in_bar |= bar->cells[i] == c;
    assert_true(in_bar);
    pm_grid_free(&g);
}

static const char *head = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                          "$PhysicalNames\n2\n1 1 \"left\"\n2 2 \"block\"\n$EndPhysicalNames\n"
                          "$Entities\n0 1 1 0\n"
                          "1 0 0 0 0 1 0 1 1 0\n"
                          "1 0 0 0 2 1 0 1 2 0\n"
                          "$EndEntities\n";

static int read_text(const char *text, pm_grid *g)
{
    char path[] = "/tmp/pmech_test_gmsh_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs(text, f);
    fclose(f);
    int rc = pm_grid_gmsh_read(g, path);
    remove(path);
    return rc;
}

/* Two unit squares side by side as quads; "left" is the line x = 0. */
static const char *quads = "$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n"
                           "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n$EndNodes\n"
                           "$Elements\n2 3 1 3\n1 1 1 1\n1 4 1\n2 1 3 2\n2 1 2 5 4\n3 5 6 3 2\n$EndElements\n";

static void quad_mesh(void **state)
{
    (void)state;
    char text[2048];
    snprintf(text, sizeof text, "%s%s", head, quads);
    pm_grid g;
    int rc = read_text(text, &g);
    if (rc)
        fprintf(stderr, "%s\n", pm_error_message());
    assert_int_equal(rc, 0);
    assert_int_equal(g.element, PM_QUAD4);
    assert_int_equal(g.n_cells, 2);
    const pm_node_set *left = pm_grid_find_set(&g, "left");
    assert_non_null(left);
    assert_int_equal(left->n, 2);
    assert_true(fabs(left->normal[0] + 1) < 1e-12);
    const pm_cell_set *b = pm_grid_find_cell_set(&g, "block");
    assert_non_null(b);
    assert_int_equal(b->n, 2);
    /* the second quad was given clockwise: it is reoriented counter-clockwise */
    const int32_t *q = g.conn + 4;
    double s = 0;
    for (int k = 0; k < 4; k++) {
        const double *p0 = g.x + 2 * q[k], *p1 = g.x + 2 * q[(k + 1) % 4];
        s += p0[0] * p1[1] - p1[0] * p0[1];
    }
    assert_true(s > 0);
    double x[2] = {1.5, 0.25};
    assert_int_equal(pm_grid_locate(&g, x), 1);
    pm_grid_free(&g);
}

static void mixed_mesh_splits_quads(void **state)
{
    (void)state;
    char text[2048];
    snprintf(text, sizeof text, "%s%s", head,
             "$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n"
             "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n$EndNodes\n"
             "$Elements\n2 3 1 3\n2 1 3 1\n1 1 2 5 4\n2 1 2 2\n2 2 3 6\n3 2 6 5\n$EndElements\n");
    pm_grid g;
    assert_int_equal(read_text(text, &g), 0);
    assert_int_equal(g.element, PM_TRI3);
    assert_int_equal(g.n_cells, 4);
    assert_int_equal(pm_grid_find_cell_set(&g, "block")->n, 4);
    pm_grid_free(&g);
}

static void bad_files(void **state)
{
    (void)state;
    struct {
        const char *text, *expect;
    } cases[] = {
        {"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", "MSH version 2.2 is not supported"},
        {"$MeshFormat\n4.1 1 8\n$EndMeshFormat\n", "binary MSH files are not supported"},
        {"hello\n", "not a Gmsh MSH file"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 0\n$EndNodes\n"
         "$Elements\n1 1 1 1\n2 1 9 1\n1 1 1 1 1 1 1 1 1 1\n$EndElements\n",
         "element type 9 is not supported"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
         "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 7\n$EndElements\n",
         ":17: element refers to an undefined node"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 x\n0 1 0\n$EndNodes\n",
         ":11: expected a number"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 1 0\n$EndNodes\n$Elements\n0 0 1 0\n$EndElements\n",
         "no triangles or quads"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n2 0 0\n$EndNodes\n"
         "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n",
         "degenerate"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n", "expected an integer"},
        /* counts and tags the rest of the file cannot back are refused before they allocate */
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 90000000 1 90000000\n2 1 0 1\n1\n0 0 0\n$EndNodes\n",
         "number of nodes 90000000: the"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 300000000\n2 1 0 1\n300000000\n0 0 0\n$EndNodes\n",
         "node tags up to 300000000 for 1 nodes"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 3000000000\n", "node tags out of range"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n90000000 0 0 0\n$EndEntities\n",
         "number of entities 90000000"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
         "$Elements\n1 90000000 1 90000000\n2 1 2 1\n1 1 2 3\n$EndElements\n",
         "number of elements 90000000"},
        /* meshes that used to build a wrong grid: the elements are named by their tags */
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
         "$Elements\n1 2 1 8\n2 1 2 2\n7 1 2 3\n8 2 3 1\n$EndElements\n",
         "elements 7 and 8 have the same nodes"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n1 0.5 0\n"
         "$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 2 1 4\n$EndElements\n",
         "elements 1 and 2 overlap"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n2 0 0\n0 1 0\n1 2 0\n"
         "$EndNodes\n$Elements\n1 1 5 5\n2 1 3 1\n5 1 2 3 4\n$EndElements\n",
         "element 5 (a quad) is inverted"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n"
         "0 0 0\n1 0 0\n0 1 0\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
         "$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 4 5 6\n$EndElements\n",
         "nodes 1 and 4 are both at (0, 0)"},
        {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
         "$Elements\n1 1 1 1\n2 1 2 1\n4 1 2 2\n$EndElements\n",
         "element 4 lists node 2 twice"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        pm_grid g;
        int rc = read_text(cases[i].text, &g);
        printf("bad file %zu: %s\n", i, pm_error_message());
        assert_int_equal(rc, PM_EINPUT);
        assert_non_null(strstr(pm_error_message(), cases[i].expect));
    }
    pm_grid g;
    assert_int_equal(pm_grid_gmsh_read(&g, "/nonexistent/x.msh"), PM_EIO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(example_mesh),
        cmocka_unit_test(quad_mesh),
        cmocka_unit_test(mixed_mesh_splits_quads),
        cmocka_unit_test(bad_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
