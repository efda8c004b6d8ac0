/* OpenMP threads that wait for work sleep instead of spinning, unless the user chose otherwise.
 *
 * On a machine busy with other programs, spinning threads hold cores that the other programs (and this
 * run's own preempted threads) need, and a 2-thread run became several times slower than one thread
 * (docs/performance.md). The policy must be in the environment before the OpenMP runtime reads it,
 * which libgomp does in its library constructor, before main() runs; a function in the program's
 * .preinit_array runs before any library constructor (ELF: pre-initialisation functions of the
 * executable come first), so it sets the default there. A value already set (OMP_WAIT_POLICY=active)
 * is kept. */
#include <stdlib.h>

static void passive_wait(int argc, char **argv, char **envp)
{
    (void)argc;
    (void)argv;
    (void)envp;
    setenv("OMP_WAIT_POLICY", "passive", 0);
}

__attribute__((section(".preinit_array"), used)) static void (*const pm_preinit_wait_policy)(int, char **,
                                                                                            char **) = passive_wait;
