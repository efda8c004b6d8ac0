/* A case on a Gmsh grid end to end: the example loads, the gmsh_group body fills exactly its
 * group's triangles (3 points each, volumes summing to the group's area), boundary groups fix the
 * right nodes, and a missing group or file is reported by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"

static void repo_path(const char *rel, char *out, size_t n)
{
    const char *f = __FILE__, *cut = strstr(f, "tests/unit/");
    snprintf(out, n, "%.*s%s", (int)(cut ? cut - f : 0), f, rel);
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    b[n] = 0;
    fclose(f);
    *len = (size_t)n;
    return b;
}

static void example_case_runs_setup(void **state)
{
    (void)state;
    char path[1024];
    repo_path("examples/gmsh_bar/case.json", path, sizeof path);
    pm_case c;
    int rc = pm_case_load(path, &c);
    if (rc)
        fprintf(stderr, "%s\n", pm_error_message());
    assert_int_equal(rc, 0);
    pm_sim *s;
    rc = pm_sim_create(&c, &s, 1);
    if (rc)
        fprintf(stderr, "%s\n", pm_error_message());
    assert_int_equal(rc, 0);
    assert_int_equal(s->p.n, 800 * 3);
    double vol = 0;
    for (size_t i = 0; i < s->p.n; i++) {
        assert_true(s->p.x[2 * i] > 0 && s->p.x[2 * i] < 1);
        vol += s->p.vol[i];
    }
    printf("gmsh_group 'bar': %zu particles, volume %.15g (area 0.04)\n", s->p.n, vol);
    assert_true(fabs(vol - 0.04) < 1e-12);
    /* fixed_end nodes are fixed in x, bottom and top in y */
    const pm_node_set *fe = pm_grid_find_set(&s->grid, "fixed_end");
    assert_non_null(fe);
    for (size_t i = 0; i < fe->n; i++)
        assert_true(s->nd.fixed[fe->nodes[i]] & 1u);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

static void missing_group_and_file(void **state)
{
    (void)state;
    char path[1024];
    repo_path("examples/gmsh_bar/case.json", path, sizeof path);
    size_t len;
    char *text = slurp(path, &len);
    char *at = strstr(text, "\"name\": \"bar\" }");
    assert_non_null(at);
    memcpy(at, "\"name\": \"baz\" }", 15);
    pm_case c;
    assert_int_equal(pm_case_load_buffer(text, len, path, &c), 0);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&c, &s, 1), PM_EINPUT);
    printf("%s\n", pm_error_message());
    assert_non_null(strstr(pm_error_message(), "no 2-D physical group 'baz'"));
    pm_case_free(&c);
    memcpy(at, "\"name\": \"bar\" }", 15);
    at = strstr(text, "bar.msh");
    assert_non_null(at);
    memcpy(at, "xyz.msh", 7);
    /* the loader may catch the missing file itself; otherwise the grid setup does */
    int rc = pm_case_load_buffer(text, len, path, &c);
    if (rc == 0)
        rc = pm_sim_create(&c, &s, 1);
    printf("%s\n", pm_error_message());
    assert_true(rc == PM_EIO || rc == PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "xyz.msh"));
    pm_case_free(&c);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(example_case_runs_setup),
        cmocka_unit_test(missing_group_and_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
