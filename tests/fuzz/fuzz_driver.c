/*
 * Fuzz target of `pmech material` driver files: any bytes either load as a driver (material and path)
 * or give an input error; a loaded driver short enough to run in a few milliseconds is also run, so
 * the material models see the parameters and paths the fuzzer makes. The run may fail (PM_ESIM)
 * but must never crash or reach undefined behaviour.
 */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_memfile.h"
#include "pmech/case.h"
#include "pmech/driver.h"

/* A run of more steps checks nothing new and would slow the fuzzer down. */
#define FUZZ_DRIVER_MAX_STEPS 200

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_memfile(data, size);
    if (!path)
        return 0;
    pm_driver d;
    if (pm_driver_load(path, &d) == 0 && d.steps >= 1 && d.steps <= FUZZ_DRIVER_MAX_STEPS)
        pm_driver_run(&d, NULL);
    pm_driver_free(&d);
    return 0;
}
