/*
 * Fuzz target of the Gmsh reader: any bytes given as a .msh file either become an unstructured grid
 * (parse, element checks, grid build: pm_grid_gmsh_read) or an input error, never a crash, a leak,
 * undefined behaviour or an allocation the file's size does not justify (libFuzzer's -rss_limit_mb).
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
    if (pm_grid_gmsh_read(&g, path) == 0)
        pm_grid_free(&g);
    return 0;
}
