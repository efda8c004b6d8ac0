/*
 * The Gmsh reader and the driver-file loader take a path: a fuzz target hands them its bytes through
 * an anonymous in-memory file (memfd) named by /proc/self/fd/N, so no disk file is written per input.
 */
#ifndef PMECH_FUZZ_MEMFILE_H
#define PMECH_FUZZ_MEMFILE_H

#include <stddef.h>

/**
 * Replace the contents of the process's one in-memory file with @p size bytes of @p data.
 * @return its path (valid for the whole process), or NULL when the file cannot be made or written
 */
const char *fuzz_memfile(const void *data, size_t size);

#endif
