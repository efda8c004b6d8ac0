/*
 * Fuzz target of the case loader and the simulation set-up: any bytes either load as a case or give an
 * input error; a case that loads is then built by pm_sim_create (grid, shape functions, seeding,
 * boundary conditions, contact, sources), which may refuse it but must never crash, leak or reach
 * undefined behaviour.
 *
 * The loader already refuses a case whose estimated particles and nodes exceed the machine's memory;
 * the fuzzer keeps to a far smaller budget so that one input takes milliseconds, not minutes.
 * Relative file names (grid.file of a Gmsh grid) resolve against the examples' gmsh_bar directory
 * (FUZZ_CASE_NAME, set by the build), so a seed can name its mesh "bar.msh".
 * A built simulation of at most FUZZ_STEP_PARTICLES particles (FUZZ_STEP_POINTS_COSTLY for GMM, RKPM and
 * implicit analyses) then takes a few steps (pm_sim_advance: the explicit passes, or Newton with its step
 * cuts, contact, obstacles, loads, sources and sinks), with the Newton iterations and step cuts capped so
 * that one step stays short; a step may fail (PM_ESIM), as a diverging case must, but not crash.
 * With FUZZ_VERBOSE=1 in the environment each input's outcome is printed (to see how far the seeds reach).
 */
#include <stddef.h>
#include <stdint.h>

#include "io/case_internal.h"
#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef FUZZ_CASE_NAME
#define FUZZ_CASE_NAME "fuzz/case.json"
#endif

/* particles and grid nodes a fuzz input may ask for (larger cases only load): set-up takes tens of
 * milliseconds at the limits under the sanitizers, GMM and RKPM (neighbour searches, moment matrices
 * per point) about ten times as long per point as MPM */
#define FUZZ_MAX_PARTICLES 20000.0
#define FUZZ_MAX_MESHFREE_POINTS 2000.0
#define FUZZ_MAX_NODES 40000.0
/* steps taken by a built simulation this small: explicit MPM, or GMM, RKPM, implicit and quasi-static
 * (one Newton solve each, of at most FUZZ_NEWTON_ITERATIONS iterations and FUZZ_STEP_CUTS cuts), whose
 * step costs far more per point (an RKPM slope of 1800 points took over 30 s for one Newton step) */
#define FUZZ_STEP_PARTICLES 2000
#define FUZZ_STEP_POINTS_COSTLY 200
#define FUZZ_EXPLICIT_STEPS 3
#define FUZZ_IMPLICIT_STEPS 1
#define FUZZ_NEWTON_ITERATIONS 8
#define FUZZ_STEP_CUTS 2

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A few steps of the size a run would take (src/solver/run.c): quasi-static increments of
 * end_time / load_steps, the fixed dt, or the stable step. Returns 1 when they all succeeded. */
static int take_steps(pm_sim *s, const pm_case *c)
{
    const int explicit_run = c->analysis.type == PM_ANALYSIS_EXPLICIT;
    const size_t max_points = explicit_run && c->method == PM_METHOD_MPM ? FUZZ_STEP_PARTICLES : FUZZ_STEP_POINTS_COSTLY;
    if (pm_sim_particles(s)->n > max_points)
        return 0;
    for (int k = 0; k < (explicit_run ? FUZZ_EXPLICIT_STEPS : FUZZ_IMPLICIT_STEPS); k++) {
        const double dt = c->analysis.type == PM_ANALYSIS_QUASI_STATIC ? c->analysis.end_time / c->analysis.load_steps
                          : c->analysis.dt > 0                        ? c->analysis.dt
                                                                      : pm_sim_stable_dt(s);
        if (!(dt > 0) || !isfinite(dt) || pm_sim_advance(s, dt) != 0)
            return 0;
    }
    return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int verbose = -1;
    if (verbose < 0)
        verbose = getenv("FUZZ_VERBOSE") && atoi(getenv("FUZZ_VERBOSE")) > 0;
    const char *outcome = "refused by the loader";
    pm_case c;
    if (pm_case_load_buffer((const char *)data, size, FUZZ_CASE_NAME, &c) == 0) {
        double particles, nodes;
        pm_case_estimate_sizes(&c, &particles, &nodes);
        pm_sim *s = NULL;
        const double max_particles = c.method == PM_METHOD_MPM ? FUZZ_MAX_PARTICLES : FUZZ_MAX_MESHFREE_POINTS;
        outcome = "loaded, larger than the fuzzing budget";
        if (c.analysis.newton.max_iterations > FUZZ_NEWTON_ITERATIONS)
            c.analysis.newton.max_iterations = FUZZ_NEWTON_ITERATIONS;
        if (c.analysis.newton.max_step_cuts > FUZZ_STEP_CUTS)
            c.analysis.newton.max_step_cuts = FUZZ_STEP_CUTS;
        if (particles <= max_particles && nodes <= FUZZ_MAX_NODES) {
            outcome = "refused by pm_sim_create";
            if (pm_sim_create(&c, &s, 1) == 0)
                outcome = take_steps(s, &c) ? "simulation built and stepped" : "simulation built";
            pm_sim_destroy(s);
        }
    }
    if (verbose)
        printf("fuzz case_sim: %zu bytes: %s%s%s\n", size, outcome, outcome[0] == 'r' ? ": " : "",
               outcome[0] == 'r' ? pm_error_message() : "");
    pm_case_free(&c);
    return 0;
}
