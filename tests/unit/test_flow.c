/* Sources and sinks in a running simulation (src/solver/inject.c, remove.c): what is released, when,
 * where it goes in memory, what the sinks take and what they leave. Every expected count follows
 * from the geometry (cells x points per cell) and the schedule, not from an earlier run. */
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
#include "solver/flow.h"
#include "solver/sim_internal.h"

/* A 1 x 1 grid of 10 x 10 cells (2 x 2 points per cell: 4 per cell); %s: end_time, the dt key (or
 * nothing: automatic), gravity y, then the rest of the case (bodies, sources, sinks, conditions), which
 * starts with a comma. */
static const char *tmpl =
    "{ \"dimension\": 2,\n"
    "  \"analysis\": { \"type\": \"explicit\", \"end_time\": %g, %s \"gravity\": [0, %g] },\n"
    "  \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [10, 10] },\n"
    "  \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1000,\n"
    "                   \"youngs_modulus\": 1e6, \"poisson_ratio\": 0.3 } ]\n"
    "  %s }\n";

static pm_case cs;

static void fill(char *buf, size_t cap, double end, double dt, double gy, const char *rest)
{
    char dts[64] = "";
    if (dt > 0)
        snprintf(dts, sizeof dts, "\"dt\": %g,", dt);
    snprintf(buf, cap, tmpl, end, dts, gy, rest);
}

static pm_sim *make(double end, double dt, double gy, const char *rest)
{
    char buf[8192];
    fill(buf, sizeof buf, end, dt, gy, rest);
    if (pm_case_load_buffer(buf, strlen(buf), "case.json", &cs) != PM_OK)
        fail_msg("case: %s", pm_error_message());
    pm_sim *s = NULL;
    if (pm_sim_create(&cs, &s, 1) != PM_OK)
        fail_msg("sim: %s", pm_error_message());
    return s;
}

static void done(pm_sim *s)
{
    pm_sim_destroy(s);
    pm_case_free(&cs);
}

static int run_to(pm_sim *s, double t)
{
    while (pm_sim_time(s) < t - 1e-12) {
        int rc = pm_sim_advance(s, cs.analysis.dt);
        if (rc)
            return rc;
    }
    return PM_OK;
}

/* A portion released at t = 0 is the body with the same keys: the same run to the last bit. */
static void release_at_zero_is_the_body(void **state)
{
    (void)state;
    const char *shape = "\"material\": \"m\", \"velocity\": [0.5, -0.2], \"initial_stress\": [-100, -200, -50, 10], "
                        "\"shape\": { \"type\": \"polygon\", \"points\": [[0.2, 0.2], [0.7, 0.3], [0.4, 0.8]] }";
    char rest[1024];
    snprintf(rest, sizeof rest, ", \"sources\": [ { %s, \"times\": [0] } ]", shape);
    pm_sim *a = make(0.02, 1e-4, -9.81, rest);
    pm_case ca = cs;
    memset(&cs, 0, sizeof cs);
    snprintf(rest, sizeof rest, ", \"bodies\": [ { %s } ]", shape);
    pm_sim *b = make(0.02, 1e-4, -9.81, rest);
    const pm_particles *pa = pm_sim_particles(a), *pb = pm_sim_particles(b);
    assert_true(pa->n > 0);
    assert_int_equal(pa->n, pb->n);
    assert_int_equal(pa->cap, pa->n);
    for (int k = 0; k < 100; k++) {
        assert_int_equal(pm_sim_advance(a, 1e-4), PM_OK);
        assert_int_equal(pm_sim_advance(b, 1e-4), PM_OK);
    }
    assert_memory_equal(pa->x, pb->x, PM_DIM * pa->n * sizeof(double));
    assert_memory_equal(pa->v, pb->v, PM_DIM * pa->n * sizeof(double));
    assert_memory_equal(pa->stress, pb->stress, PM_NS * pa->n * sizeof(double));
    assert_memory_equal(pa->id, pb->id, pa->n * sizeof(int32_t));
    done(b);
    cs = ca;
    done(a);
}

/* Portions of 2 x 1 cells (8 points) every 0.05 s from 0 to 0.2: five releases, room for all of them
 * allocated at the start, ids never reused, the arrays never moved. */
static void periodic_releases_append_in_place(void **state)
{
    (void)state;
    pm_sim *s = make(0.3, 1e-3, -9.81,
                     ", \"sources\": [ { \"name\": \"hopper\", \"material\": \"m\", \"period\": 0.05, \"until\": 0.2,"
                     " \"shape\": { \"type\": \"rectangle\", \"min\": [0.4, 0.8], \"max\": [0.6, 0.9] } } ]");
    const pm_particles *p = pm_sim_particles(s);
    assert_int_equal(p->cap, 5 * 8);
    assert_int_equal(p->n, 8); /* the release at t = 0 is made at set-up */
    const double *x = p->x;
    const int32_t *id = p->id;
    size_t prev = p->n;
    for (int k = 1; k <= 300; k++) {
        assert_int_equal(pm_sim_advance(s, 1e-3), PM_OK);
        const double t = pm_sim_time(s);
        /* a release is due at j * 0.05 and made at the end of the step that reaches it */
        const size_t want = 8 * (size_t)fmin(5, floor(t / 0.05 + 1e-6) + 1);
        if (p->n != want)
            fail_msg("t = %g: %zu particles, expected %zu", t, p->n, want);
        if (p->n != prev) {
            const pm_source_run *r = &s->flow->src[0];
            assert_int_equal(r->event, PM_RELEASE_DONE);
            assert_true(fabs(r->event_time - t) < 1e-15);
            prev = p->n;
        }
    }
    assert_ptr_equal(p->x, x);
    assert_ptr_equal(p->id, id);
    int seen[40] = {0};
    for (size_t i = 0; i < p->n; i++) {
        assert_true(p->id[i] >= 0 && p->id[i] < 40);
        assert_int_equal(seen[p->id[i]]++, 0);
        assert_int_equal(p->body[i], 0); /* no bodies: the source's index is 0 + 0 */
    }
    pm_flow_totals t;
    pm_flow_totals_of(s, &t);
    assert_int_equal(t.released, 40);
    /* mass = density x area: 5 portions of 0.2 x 0.1 m */
    assert_true(fabs(t.released_mass - 5 * 1000 * 0.02) < 1e-10);
    done(s);
}

/* A portion that does not move keeps its region occupied: with only_when_free the later releases are
 * skipped (and marked so for the log); without it they would pile up. */
static void only_when_free_skips_occupied_region(void **state)
{
    (void)state;
    pm_sim *s = make(0.1, 1e-3, 0,
                     ", \"sources\": [ { \"material\": \"m\", \"period\": 0.02, \"only_when_free\": true,"
                     " \"shape\": { \"type\": \"rectangle\", \"min\": [0.4, 0.4], \"max\": [0.6, 0.5] } } ]");
    int skipped = 0;
    for (int k = 0; k < 100; k++) {
        assert_int_equal(pm_sim_advance(s, 1e-3), PM_OK);
        skipped += s->flow->src[0].event == PM_RELEASE_SKIPPED;
    }
    assert_int_equal(pm_sim_particles(s)->n, 8);
    assert_int_equal(skipped, 5); /* 0.02, 0.04, 0.06, 0.08, 0.1 */
    done(s);
    /* moving away at 5 m/s, the portion leaves its region within 0.02 s: every release is made */
    s = make(0.1, 1e-3, 0,
             ", \"sources\": [ { \"material\": \"m\", \"period\": 0.02, \"only_when_free\": true, \"velocity\": [0, -5],"
             " \"shape\": { \"type\": \"rectangle\", \"min\": [0.4, 0.9], \"max\": [0.6, 1.0] } } ],"
             " \"sinks\": [ { \"type\": \"outside_grid\" } ]");
    size_t released = 0;
    for (int k = 0; k < 100; k++) {
        assert_int_equal(pm_sim_advance(s, 1e-3), PM_OK);
        released += s->flow->src[0].event == PM_RELEASE_DONE;
    }
    assert_int_equal(released, 5);
    done(s);
}

static void two_releases_in_one_step_stop_the_run(void **state)
{
    (void)state;
    pm_sim *s = make(0.1, 1e-2, 0,
                     ", \"sources\": [ { \"name\": \"fast\", \"material\": \"m\", \"period\": 0.004, \"shape\": "
                     "{ \"type\": \"rectangle\", \"min\": [0.4, 0.4], \"max\": [0.6, 0.5] } } ]");
    assert_int_equal(pm_sim_advance(s, 1e-2), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "step 1 (t = 0.01 s): sources[0] ('fast'): 2 releases fell due within "
                                               "one step"));
    done(s);
}

static void overlapping_sources_refused(void **state)
{
    (void)state;
    char buf[4096];
    fill(buf, sizeof buf, 1.0, 1e-3, 0.0,
             ", \"sources\": [ { \"material\": \"m\", \"times\": [0], \"shape\": { \"type\": \"rectangle\", "
             "\"min\": [0.1, 0.1], \"max\": [0.5, 0.5] } }, { \"material\": \"m\", \"times\": [0.5], \"shape\": "
             "{ \"type\": \"circle\", \"center\": [0.5, 0.5], \"radius\": 0.1 } } ]");
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &cs), PM_OK);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&cs, &s, 1), PM_EINPUT);
    assert_null(s);
    assert_non_null(strstr(pm_error_message(), "case.json: sources[1].shape: overlaps sources[0].shape"));
    pm_case_free(&cs);
    /* touching along an edge is not overlapping */
    fill(buf, sizeof buf, 0.1, 1e-3, 0.0,
             ", \"sources\": [ { \"material\": \"m\", \"times\": [0], \"shape\": { \"type\": \"rectangle\", "
             "\"min\": [0.1, 0.1], \"max\": [0.5, 0.5] } }, { \"material\": \"m\", \"times\": [0], \"shape\": "
             "{ \"type\": \"rectangle\", \"min\": [0.5, 0.1], \"max\": [0.9, 0.5] } } ]");
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &cs), PM_OK);
    assert_int_equal(pm_sim_create(&cs, &s, 1), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 2 * 16 * 4);
    done(s);
}

/* A block 0.4 wide (x 0.3..0.7, 8 point columns 0.05 apart) moving down at 1 m/s through an outlet on
 * y = 0.5 from x = 0.3 to 0.5: the 4 point columns left of 0.5 are removed as they cross, the others
 * pass. Nothing else acts (no gravity, a rigid-body motion has no stress). */
static void outlet_takes_what_crosses_it(void **state)
{
    (void)state;
    pm_sim *s = make(0.3, 1e-3, 0,
                     ", \"bodies\": [ { \"material\": \"m\", \"velocity\": [0, -1], \"shape\": { \"type\": \"rectangle\","
                     " \"min\": [0.3, 0.6], \"max\": [0.7, 0.8] } } ],"
                     " \"sinks\": [ { \"type\": \"outlet\", \"boundary\": { \"y\": 0.5, \"from\": 0.3, \"to\": 0.5,"
                     " \"normal\": [0, -1] } } ]");
    const pm_particles *p = pm_sim_particles(s);
    assert_int_equal(p->n, 8 * 4);
    assert_int_equal(run_to(s, 0.3), PM_OK); /* the block's top reaches 0.5 at t = 0.3 */
    assert_int_equal(p->n, 4 * 4);
    for (size_t i = 0; i < p->n; i++)
        assert_true(p->x[PM_DIM * i] > 0.5);
    pm_flow_totals t;
    pm_flow_totals_of(s, &t);
    assert_int_equal(t.removed, 16);
    assert_true(fabs(t.removed_mass - 1000 * 0.2 * 0.2) < 1e-12);
    done(s);
    /* the same block moving up through an outlet that removes downward crossings passes whole */
    s = make(0.3, 1e-3, 0,
             ", \"bodies\": [ { \"material\": \"m\", \"velocity\": [0, 1], \"shape\": { \"type\": \"rectangle\","
             " \"min\": [0.3, 0.2], \"max\": [0.7, 0.4] } } ],"
             " \"sinks\": [ { \"type\": \"outlet\", \"boundary\": { \"y\": 0.5, \"normal\": [0, -1] } } ]");
    assert_int_equal(run_to(s, 0.3), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 32);
    done(s);
    /* without a normal, either direction removes */
    s = make(0.3, 1e-3, 0,
             ", \"bodies\": [ { \"material\": \"m\", \"velocity\": [0, 1], \"shape\": { \"type\": \"rectangle\","
             " \"min\": [0.3, 0.2], \"max\": [0.7, 0.4] } } ],"
             " \"sinks\": [ { \"type\": \"outlet\", \"boundary\": { \"y\": 0.5 } } ]");
    assert_int_equal(run_to(s, 0.3), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 0);
    done(s);
}

/* Leaving the grid stops the run unless a sink takes the particles; a region takes what lies in it. */
static void grid_exit_and_region(void **state)
{
    (void)state;
    const char *body = ", \"bodies\": [ { \"material\": \"m\", \"velocity\": [-2, 0], \"shape\": { \"type\": "
                       "\"rectangle\", \"min\": [0.1, 0.4], \"max\": [0.3, 0.6] } } ]";
    pm_sim *s = make(0.3, 1e-3, 0, body);
    assert_int_equal(run_to(s, 0.3), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "left the grid"));
    done(s);
    char rest[1024];
    snprintf(rest, sizeof rest, "%s, \"sinks\": [ { \"type\": \"outside_grid\", \"name\": \"edge\" } ]", body);
    s = make(0.3, 1e-3, 0, rest);
    assert_int_equal(run_to(s, 0.3), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 0);
    assert_int_equal(s->flow->snk[0].removed, 16);
    done(s);
    /* a region in the block's path takes it before the grid's edge is reached; the first sink listed
     * that takes a particle counts it */
    snprintf(rest, sizeof rest,
             "%s, \"sinks\": [ { \"type\": \"region\", \"shape\": { \"type\": \"rectangle\", \"min\": [0, 0], "
             "\"max\": [0.05, 1] } }, { \"type\": \"outside_grid\" } ]",
             body);
    s = make(0.3, 1e-3, 0, rest);
    assert_int_equal(run_to(s, 0.3), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 0);
    assert_int_equal(s->flow->snk[0].removed, 16);
    assert_int_equal(s->flow->snk[1].removed, 0);
    done(s);
    /* an outlet on a grid side removes what leaves through it outwards */
    snprintf(rest, sizeof rest, "%s, \"sinks\": [ { \"type\": \"outlet\", \"boundary\": \"x_min\" } ]", body);
    s = make(0.3, 1e-3, 0, rest);
    assert_true(s->flow->snk[0].axis == 0 && s->flow->snk[0].value == 0 && s->flow->snk[0].normal[0] == -1);
    assert_int_equal(run_to(s, 0.3), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 0);
    done(s);
}

/* With nothing on the grid, a step waits for the next release; the release raises the stable step's
 * wave speed at once. */
static void empty_grid_waits_for_release(void **state)
{
    (void)state;
    pm_sim *s = make(1.0, 0, 0,
                     ", \"sources\": [ { \"material\": \"m\", \"times\": [0.25, 0.5], \"velocity\": [0, -3], "
                     "\"shape\": { \"type\": \"rectangle\", \"min\": [0.4, 0.4], \"max\": [0.6, 0.5] } } ],"
                     " \"sinks\": [ { \"type\": \"outside_grid\" } ]");
    assert_int_equal(pm_sim_particles(s)->n, 0);
    assert_true(fabs(pm_sim_stable_dt(s) - 0.25) < 1e-15);
    assert_int_equal(pm_sim_advance(s, pm_sim_stable_dt(s)), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 8);
    /* c = sqrt(M / rho), M = E (1 - nu) / ((1 + nu)(1 - 2 nu)); plus the 3 m/s of the release */
    const double c = sqrt(1e6 * 0.7 / (1.3 * 0.4) / 1000), want = 0.2 * 0.1 / (c + 3);
    assert_true(fabs(pm_sim_stable_dt(s) - want) < 1e-12 * want);
    done(s);
}

/* Work arrays sized per particle (the F-bar scales here) have room for every release: the released
 * particles are averaged like the others (run under ASan, an array sized for the start would be
 * overrun at the second release). */
static void per_particle_work_arrays_cover_releases(void **state)
{
    (void)state;
    char buf[4096];
    fill(buf, sizeof buf, 0.1, 1e-3, -9.81,
         ", \"sources\": [ { \"material\": \"m\", \"period\": 0.02, \"shape\": { \"type\": \"rectangle\", "
         "\"min\": [0.3, 0.8], \"max\": [0.7, 1.0] } } ], \"sinks\": [ { \"type\": \"outside_grid\" } ]");
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &cs), PM_OK);
    assert_int_equal(pm_case_set_string(&cs, "analysis.fbar", "cell"), PM_OK);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&cs, &s, 1), PM_OK);
    assert_int_equal(run_to(s, 0.1), PM_OK);
    assert_int_equal(pm_sim_particles(s)->n, 6 * 32);
    done(s);
}

/* Appends and removals with two threads: the coloured row blocks are cut again for the new count and
 * the appended particles sorted in, so the run matches the one-thread run to round-off (same counts,
 * the same particles, positions within 1e-12 m). */
static void two_threads_match_one(void **state)
{
    (void)state;
    const char *rest = ", \"bodies\": [ { \"material\": \"m\", \"shape\": { \"type\": \"rectangle\", "
                       "\"min\": [0, 0], \"max\": [1, 0.3] } } ], \"sources\": [ { \"material\": \"m\", "
                       "\"period\": 0.01, \"velocity\": [0, -2], \"shape\": { \"type\": \"rectangle\", "
                       "\"min\": [0.3, 0.8], \"max\": [0.7, 1.0] } } ], \"sinks\": [ { \"type\": \"region\", "
                       "\"shape\": { \"type\": \"rectangle\", \"min\": [0, 0.45], \"max\": [1, 0.5] } } ], "
                       "\"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\", "
                       "\"directions\": [\"x\", \"y\"] } ]";
    char buf[4096];
    fill(buf, sizeof buf, 0.2, 2e-4, -9.81, rest);
    pm_case c1, c2;
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &c1), PM_OK);
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &c2), PM_OK);
    pm_sim *a = NULL, *b = NULL;
    assert_int_equal(pm_sim_create(&c1, &a, 1), PM_OK);
    assert_int_equal(pm_sim_create(&c2, &b, 2), PM_OK);
    for (int k = 0; k < 1000; k++) {
        assert_int_equal(pm_sim_advance(a, 2e-4), PM_OK);
        assert_int_equal(pm_sim_advance(b, 2e-4), PM_OK);
    }
    const pm_particles *pa = pm_sim_particles(a), *pb = pm_sim_particles(b);
    pm_flow_totals ta, tb;
    pm_flow_totals_of(a, &ta);
    pm_flow_totals_of(b, &tb);
    assert_true(ta.released > 0 && ta.removed > 0); /* both happened */
    assert_int_equal(ta.removed, tb.removed);
    assert_int_equal(pa->n, pb->n);
    /* the two runs may sort at different steps (two threads sort early when the row blocks overlap):
     * particles are matched by id */
    const size_t ids = (size_t)a->flow->next_id;
    assert_int_equal(ids, (size_t)b->flow->next_id);
    long *where = malloc(ids * sizeof *where);
    assert_non_null(where);
    for (size_t k = 0; k < ids; k++)
        where[k] = -1;
    for (size_t i = 0; i < pb->n; i++)
        where[pb->id[i]] = (long)i;
    for (size_t i = 0; i < pa->n; i++) {
        const long j = where[pa->id[i]];
        assert_true(j >= 0);
        for (int d = 0; d < PM_DIM; d++)
            assert_true(fabs(pa->x[PM_DIM * i + d] - pb->x[PM_DIM * (size_t)j + d]) < 1e-12);
    }
    free(where);
    pm_sim_destroy(a);
    pm_sim_destroy(b);
    pm_case_free(&c1);
    pm_case_free(&c2);
}

/* A fixed condition with `until` is a gate: a block resting on the line y = 0.5 under gravity stays
 * there while the gate holds (an outlet sink on the same line takes nothing), and falls through it
 * freely once it is released at t = 0.1 (its top, 0.2 above the line, crosses it 0.2 s later at
 * g = 10). A gate that shares a held component with another condition is refused, as is a gate in
 * an implicit analysis (whose unknowns are numbered once). */
static void released_fixed_condition_opens_a_gate(void **state)
{
    (void)state;
    const char *gate = ", \"bodies\": [ { \"material\": \"m\", \"shape\": { \"type\": \"rectangle\","
                       " \"min\": [0.3, 0.5], \"max\": [0.7, 0.7] } } ],"
                       " \"sinks\": [ { \"type\": \"outlet\", \"boundary\": { \"y\": 0.5, \"normal\": [0, -1] } } ],"
                       " \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": { \"y\": 0.5 },"
                       " \"directions\": [\"y\"], \"until\": 0.1 } %s ]";
    char rest[1024];
    snprintf(rest, sizeof rest, gate, "");
    pm_sim *s = make(0.45, 1e-3, -10, rest);
    const pm_particles *p = pm_sim_particles(s);
    assert_int_equal(p->n, 8 * 4);
    assert_int_equal(run_to(s, 0.099), PM_OK);
    assert_int_equal(p->n, 32);
    assert_int_equal(run_to(s, 0.45), PM_OK);
    assert_int_equal(p->n, 0);
    done(s);
    /* sharing the node (0, 0.5) in y with a fixed side */
    snprintf(rest, sizeof rest, gate,
             ", { \"type\": \"fixed\", \"boundary\": \"x_min\", \"directions\": [\"x\", \"y\"] }");
    char buf[8192];
    fill(buf, sizeof buf, 0.45, 1e-3, -10, rest);
    assert_int_equal(pm_case_load_buffer(buf, strlen(buf), "case.json", &cs), PM_OK);
    s = NULL;
    assert_int_equal(pm_sim_create(&cs, &s, 1), PM_EINPUT);
    assert_null(s);
    assert_non_null(strstr(pm_error_message(), "boundary_conditions[0]: the node at (0, 0.5) is also held in y"));
    pm_case_free(&cs);
    const char *implicit = "{ \"dimension\": 2, \"analysis\": { \"type\": \"implicit\", \"end_time\": 1, \"dt\": 0.1 },"
                           " \"grid\": { \"type\": \"rectangle\", \"size\": [1, 1], \"cells\": [2, 2] },"
                           " \"materials\": [ { \"name\": \"m\", \"model\": \"linear_elastic\", \"density\": 1,"
                           " \"youngs_modulus\": 1, \"poisson_ratio\": 0 } ],"
                           " \"bodies\": [ { \"material\": \"m\", \"shape\": { \"type\": \"rectangle\","
                           " \"min\": [0, 0], \"max\": [1, 1] } } ],"
                           " \"boundary_conditions\": [ { \"type\": \"fixed\", \"boundary\": \"y_min\","
                           " \"directions\": [\"y\"], \"until\": 0.5 } ] }";
    assert_int_equal(pm_case_load_buffer(implicit, strlen(implicit), "case.json", &cs), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "case.json: boundary_conditions[0].until: a fixed condition can be "
                                               "released only in an 'explicit' analysis"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(release_at_zero_is_the_body),
        cmocka_unit_test(periodic_releases_append_in_place),
        cmocka_unit_test(only_when_free_skips_occupied_region),
        cmocka_unit_test(two_releases_in_one_step_stop_the_run),
        cmocka_unit_test(overlapping_sources_refused),
        cmocka_unit_test(outlet_takes_what_crosses_it),
        cmocka_unit_test(grid_exit_and_region),
        cmocka_unit_test(empty_grid_waits_for_release),
        cmocka_unit_test(per_particle_work_arrays_cover_releases),
        cmocka_unit_test(two_threads_match_one),
        cmocka_unit_test(released_fixed_condition_opens_a_gate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
