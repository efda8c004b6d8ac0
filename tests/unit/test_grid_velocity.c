/*
 * The velocity each point's position moved with over the last step (pm_particles::v_grid), against
 * what the point did:
 *
 * - a block in uniform translation, no gravity and no condition: every scheme, GMM, RKPM and the
 *   implicit solver move it rigidly, and v_grid equals both the block's velocity and (x_new - x_old)/dt.
 *   Tolerance 1e-9 m/s against a velocity of order 1 m/s: (x_new - x_old)/dt loses about
 *   eps |x| / dt = 2e-16 * 1 / 1e-4 = 2e-12 m/s to the cancellation of x_new - x_old, and the implicit
 *   solver's converged displacement carries its Newton tolerance's residue on top (a free block has no
 *   stress, so that residue is round-off as well). A v_grid left at zero or at a stale value is off by
 *   the whole velocity.
 * - the hidden velocity of FLIP: a block at rest on a fixed floor whose points come in coincident pairs
 *   with opposite velocities +-1 m/s (equal masses: every node's momentum is zero), one MUSL step. The
 *   grid sees no motion, so the points do not move and v_grid is zero, while the points' own velocities
 *   keep the pattern. Tolerance 1e-12 m/s: the nodal momentum is a sum of products m N v that cancel
 *   pair by pair, leaving round-off of the 1 m/s terms (1e-16 relative, a few terms per node).
 * - sources and sinks: a block falling onto a fixed floor through an outlet, with portions released
 *   above it; after every step each particle that was there before has v_grid = (x_new - x_old)/dt
 *   (followed by its id through the sorts and the outlet's compactions) and each one released in the
 *   step has the velocity it was released with. The velocities differ from point to point (the floor
 *   stops some, the outlet lets others fall), checked to exceed 0.1 m/s of spread, so that a field
 *   shifted by one point in a compaction would fail. Tolerance 1e-10 m/s: positions of order 1 m,
 *   dt 1e-3 s, cancellation 2e-13 m/s.
 */
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

static pm_sim *make(const char *text, pm_case *c)
{
    if (pm_case_load_buffer(text, strlen(text), "case.json", c) != PM_OK)
        fail_msg("case: %s", pm_error_message());
    pm_sim *s = NULL;
    if (pm_sim_create(c, &s, 1) != PM_OK)
        fail_msg("sim: %s", pm_error_message());
    return s;
}

static const double VT[PM_DIM] = {0.3, -0.2};

/* A 0.4 x 0.2 m elastic block in the middle of a 1 x 1 m grid of 10 x 10 cells, moving at VT. */
static void translation(const char *method, const char *type, const char *scheme)
{
    char text[2048];
    snprintf(text, sizeof text,
             "{ \"dimension\": 2, \"method\": \"%s\",\n"
             "  \"analysis\": { \"type\": \"%s\", %s \"end_time\": 0.01, \"dt\": 1e-4 },\n"
             "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [10, 10] },\n"
             "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
             "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
             "  \"bodies\": [ { \"material\": \"m\", \"velocity\": [%.17g, %.17g],\n"
             "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.3, 0.4], \"max\": [0.7, 0.6] } } ] }\n",
             method, type, scheme, VT[0], VT[1]);
    pm_case c;
    pm_sim *s = make(text, &c);
    pm_particles *p = &s->p;
    const size_t n = p->n;
    assert_true(n > 0);
    double *x_old = malloc(PM_DIM * n * sizeof *x_old);
    assert_non_null(x_old);
    const double dt = 1e-4;
    for (int step = 0; step < 5; step++) {
        memcpy(x_old, p->x, PM_DIM * n * sizeof *x_old);
        for (size_t i = 0; i < PM_DIM * n; i++) /* stale: the seed gives the block's velocity already */
            p->v_grid[i] = NAN;
        if (pm_sim_advance(s, dt) != PM_OK)
            fail_msg("%s %s %s: %s", method, type, scheme, pm_error_message());
        for (size_t i = 0; i < n; i++)
            for (int d = 0; d < PM_DIM; d++) {
                const double vg = p->v_grid[PM_DIM * i + d];
                const double moved = (p->x[PM_DIM * i + d] - x_old[PM_DIM * i + d]) / dt;
                if (!(fabs(vg - VT[d]) <= 1e-9 && fabs(vg - moved) <= 1e-9))
                    fail_msg("%s %s %s, step %d, point %zu, component %d: v_grid %.17g, moved %.17g, block %.17g",
                             method, type, scheme, step, i, d, vg, moved, VT[d]);
            }
    }
    free(x_old);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

static void translation_explicit_schemes(void **state)
{
    (void)state;
    const char *schemes[] = {"\"scheme\": \"musl\",", "\"scheme\": \"usl\",", "\"scheme\": \"usf\",",
                             "\"scheme\": \"newmark_pc\","};
    for (size_t k = 0; k < sizeof schemes / sizeof schemes[0]; k++)
        translation("mpm", "explicit", schemes[k]);
}

static void translation_meshfree(void **state)
{
    (void)state;
    translation("gmm", "explicit", "");
    translation("rkpm", "explicit", "");
    translation("gmm", "implicit", "");
}

static void translation_implicit(void **state)
{
    (void)state;
    translation("mpm", "implicit", "");
}

/* Coincident pairs with opposite velocities: no momentum on any node, so nothing moves. */
static void hidden_velocity_moves_nothing(void **state)
{
    (void)state;
    const char *text =
        "{ \"dimension\": 2,\n"
        "  \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": 0.01, \"dt\": 1e-4 },\n"
        "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [10, 10] },\n"
        "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
        "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
        "  \"bodies\": [ { \"material\": \"m\",\n"
        "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.2, 0], \"max\": [0.8, 0.4] } } ],\n"
        "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"x\", \"y\"] } ] }\n";
    pm_case c;
    pm_sim *s = make(text, &c);
    pm_particles *p = &s->p;
    const size_t n = p->n;
    assert_true(n >= 2 && n % 2 == 0);
    const double V = 1.0;
    for (size_t i = 0; i < n; i += 2) {
        assert_true(p->mass[i] == p->mass[i + 1]);
        for (int d = 0; d < PM_DIM; d++) {
            p->x[PM_DIM * (i + 1) + d] = p->x[PM_DIM * i + d];
            const double v = d == 0 ? V : -0.5 * V; /* a pair moves apart along a slanted line */
            p->v[PM_DIM * i + d] = v;
            p->v[PM_DIM * (i + 1) + d] = -v;
            /* a stale value, so that a v_grid the step leaves alone fails */
            p->v_grid[PM_DIM * i + d] = p->v_grid[PM_DIM * (i + 1) + d] = v;
        }
    }
    double *x_old = malloc(PM_DIM * n * sizeof *x_old);
    assert_non_null(x_old);
    memcpy(x_old, p->x, PM_DIM * n * sizeof *x_old);
    assert_int_equal(pm_sim_advance(s, 1e-4), PM_OK);
    for (size_t i = 0; i < n; i++) {
        const double sign = i % 2 ? -1.0 : 1.0;
        for (int d = 0; d < PM_DIM; d++) {
            const double v = sign * (d == 0 ? V : -0.5 * V);
            if (!(fabs(p->v_grid[PM_DIM * i + d]) <= 1e-12))
                fail_msg("point %zu, component %d: v_grid %.3g, expected 0", i, d, p->v_grid[PM_DIM * i + d]);
            if (!(fabs(p->v[PM_DIM * i + d] - v) <= 1e-12))
                fail_msg("point %zu, component %d: v %.17g, expected the pattern's %g", i, d, p->v[PM_DIM * i + d], v);
            assert_true(fabs(p->x[PM_DIM * i + d] - x_old[PM_DIM * i + d]) <= 1e-12 * 1e-4);
        }
    }
    free(x_old);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

/* Sources append points and the outlet removes them; v_grid follows each point by its id. */
static void sources_and_sinks_keep_it_with_its_point(void **state)
{
    (void)state;
    const char *text =
        "{ \"dimension\": 2,\n"
        "  \"analysis\": { \"type\": \"explicit\", \"end_time\": 0.3, \"dt\": 1e-3, \"gravity\": [0, -9.81] },\n"
        "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [10, 10] },\n"
        "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
        "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ],\n"
        "  \"bodies\": [ { \"material\": \"m\", \"velocity\": [0, -1],\n"
        "                \"shape\": { \"type\": \"rectangle\", \"min\": [0.1, 0.2], \"max\": [0.9, 0.4] } } ],\n"
        "  \"sources\": [ { \"name\": \"hopper\", \"material\": \"m\", \"velocity\": [0.3, -1], \"period\": 0.03,\n"
        "                  \"until\": 0.2, \"shape\": { \"type\": \"rectangle\", \"min\": [0.1, 0.8], \"max\": [0.3, 0.9] } } ],\n"
        "  \"sinks\": [ { \"type\": \"outlet\", \"boundary\": { \"y\": 0.1, \"to\": 0.4, \"normal\": [0, -1] } } ],\n"
        "  \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", \"directions\": [\"x\", \"y\"] } ] }\n";
    pm_case c;
    pm_sim *s = make(text, &c);
    pm_particles *p = &s->p;
    const size_t cap = p->cap;
    /* ids are never reused and count up from 0, so cap bounds them */
    double *x_old = malloc(PM_DIM * cap * sizeof *x_old);
    unsigned char *had = calloc(cap, 1);
    assert_non_null(x_old);
    assert_non_null(had);
    const double dt = 1e-3, release_v[PM_DIM] = {0.3, -1};
    size_t appended = 0, removed = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (int step = 0; step < 250; step++) {
        memset(had, 0, cap);
        for (size_t i = 0; i < p->n; i++) {
            const size_t id = (size_t)p->id[i];
            assert_true(id < cap);
            had[id] = 1;
            memcpy(x_old + PM_DIM * id, p->x + PM_DIM * i, PM_DIM * sizeof *x_old);
            for (int d = 0; d < PM_DIM; d++) /* stale, so that only what the step writes passes */
                p->v_grid[PM_DIM * i + d] = NAN;
        }
        const size_t n_before = p->n;
        if (pm_sim_advance(s, dt) != PM_OK)
            fail_msg("step %d: %s", step, pm_error_message());
        size_t kept = 0;
        for (size_t i = 0; i < p->n; i++) {
            const size_t id = (size_t)p->id[i];
            assert_true(id < cap);
            for (int d = 0; d < PM_DIM; d++) {
                const double vg = p->v_grid[PM_DIM * i + d];
                const double want = had[id] ? (p->x[PM_DIM * i + d] - x_old[PM_DIM * id + d]) / dt : release_v[d];
                if (!(fabs(vg - want) <= 1e-10))
                    fail_msg("step %d, point %zu (id %zu, %s): v_grid %.17g, expected %.17g", step, i, id,
                             had[id] ? "moved" : "released", vg, want);
            }
            kept += had[id];
            lo = fmin(lo, p->v_grid[PM_DIM * i + 1]);
            hi = fmax(hi, p->v_grid[PM_DIM * i + 1]);
        }
        appended += p->n - kept;
        removed += n_before - kept;
    }
    assert_true(appended > 0);
    assert_true(removed > 0);
    assert_true(hi - lo > 0.1);
    free(had);
    free(x_old);
    pm_sim_destroy(s);
    pm_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(translation_explicit_schemes),
        cmocka_unit_test(translation_meshfree),
        cmocka_unit_test(translation_implicit),
        cmocka_unit_test(hidden_velocity_moves_nothing),
        cmocka_unit_test(sources_and_sinks_keep_it_with_its_point),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
