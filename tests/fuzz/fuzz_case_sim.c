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
 */
#include <stddef.h>
#include <stdint.h>

#include "io/case_internal.h"
#include "pmech/case.h"
#include "pmech/sim.h"

#ifndef FUZZ_CASE_NAME
#define FUZZ_CASE_NAME "fuzz/case.json"
#endif

/* particles and grid nodes a fuzz input may ask for (larger cases only load): set-up takes tens of
 * milliseconds at the limits under the sanitizers, GMM and RKPM (neighbour searches, moment matrices
 * per point) about ten times as long per point as MPM */
#define FUZZ_MAX_PARTICLES 20000.0
#define FUZZ_MAX_MESHFREE_POINTS 2000.0
#define FUZZ_MAX_NODES 40000.0

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pm_case c;
    if (pm_case_load_buffer((const char *)data, size, FUZZ_CASE_NAME, &c) == 0) {
        double particles, nodes;
        pm_case_estimate_sizes(&c, &particles, &nodes);
        pm_sim *s = NULL;
        const double max_particles = c.method == PM_METHOD_MPM ? FUZZ_MAX_PARTICLES : FUZZ_MAX_MESHFREE_POINTS;
        if (particles <= max_particles && nodes <= FUZZ_MAX_NODES && pm_sim_create(&c, &s, 1) == 0)
            pm_sim_destroy(s);
    }
    pm_case_free(&c);
    return 0;
}
