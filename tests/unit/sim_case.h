/* A simulation set up from case text held in memory, for unit tests that need a whole pm_sim
 * (tests/unit/test_contact.c, test_gmsh_walls.c, test_gmm_spacing.c, test_lattice.c). Include after cmocka.h. */
#ifndef PMECH_TEST_SIM_CASE_H
#define PMECH_TEST_SIM_CASE_H

#include <stdio.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"

/* The path of @p rel (relative to the repository's root) in @p out: the root is where this header's
 * tests/unit/ folder is. */
static inline void sc_repo_path(const char *rel, char *out, size_t n)
{
    const char *f = __FILE__, *cut = strstr(f, "tests/unit/");
    snprintf(out, n, "%.*s%s", (int)(cut ? cut - f : 0), f, rel);
}

/* The simulation of case @p text, loaded into @p c as if read from file @p name (relative paths in the
 * text resolve against its folder). Fails the test with the loader's or set-up's message unless both
 * succeed. */
static inline pm_sim *sc_sim_of(const char *text, const char *name, pm_case *c)
{
    if (pm_case_load_buffer(text, strlen(text), name, c) != PM_OK)
        fail_msg("%s", pm_error_message());
    pm_sim *s = NULL;
    if (pm_sim_create(c, &s, 1) != PM_OK)
        fail_msg("%s", pm_error_message());
    return s;
}

#endif
