/* OpenMP threads that wait for work sleep instead of spinning, unless the user chose otherwise.
 *
 * On a machine busy with other programs, spinning threads hold cores that the other programs (and this
 * run's own preempted threads) need: a 2-thread run measured several times slower than one thread, and
 * faster than one thread once its waiting threads slept (docs/performance.md). The OpenMP runtime reads
 * the policy once, in its library constructor, before main() runs and before anything main() could
 * set; so `pmech run` sets OMP_WAIT_POLICY=passive and starts itself again, once, when the user has set
 * neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT. Under valgrind (its preload library in LD_PRELOAD) it does
 * not, since the new process would run without the tool. */
#include "cli/commands.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void pm_cli_passive_wait(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return;
    const char *pre = getenv("LD_PRELOAD");
    if (pre && strstr(pre, "vgpreload"))
        return;
    if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0)
        return;
    execv("/proc/self/exe", argv);
    /* the exec failed: run on with the runtime's default policy (it read the environment already) */
}
