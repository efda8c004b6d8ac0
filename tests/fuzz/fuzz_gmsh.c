/*
 * Fuzz target of the Gmsh reader: any bytes given as a .msh file either become an unstructured grid
 * (parse, element checks, grid build: pm_grid_gmsh_read) or an input error, never a crash, a leak,
 * undefined behaviour or an allocation the file's size does not justify (libFuzzer's -rss_limit_mb).
 * A grid read is then offered to pm_grid_adopt_lattice, as an `mpm` run does: a lattice it renumbers
 * must locate its own nodes' cells like any structured grid.
 */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_memfile.h"
#include "pmech/grid.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_memfile(data, size);
    if (!path)
        return 0;
    pm_grid g;
    if (pm_grid_gmsh_read(&g, path) != 0)
        return 0;
    if (pm_grid_adopt_lattice(&g) == 1) {
        for (size_t k = 0; k < g.n_nodes; k++)
            if (pm_grid_locate(&g, g.x + 2 * k) < 0)
                __builtin_trap(); /* a node of the grid outside it: the renumbering is wrong */
    }
    pm_grid_free(&g);
    return 0;
}
