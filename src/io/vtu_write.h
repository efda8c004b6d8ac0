/**
 * @file vtu_write.h
 * @brief Internal to src/io: VTK XML UnstructuredGrid writer (binary appended raw data with
 *        UInt64 block headers) and the temporary-name-then-rename helpers every output file uses.
 */
#ifndef PMECH_IO_VTU_WRITE_H
#define PMECH_IO_VTU_WRITE_H

#include <stddef.h>
#include <stdio.h>

#include "pmech/grid.h"
#include "io/output.h"
#include "pmech/particles.h"

/** Element types of a DataArray. */
typedef enum { PM_VTU_F64 = 0, PM_VTU_I32 = 1, PM_VTU_I64 = 2, PM_VTU_U8 = 3 } pm_vtu_type;

/** One point-data array of a piece (its values are written later as an appended block). */
typedef struct pm_vtu_array {
    const char *name;              /**< Name attribute */
    pm_vtu_type type;              /**< element type */
    int ncomp;                     /**< NumberOfComponents */
    const char *const *comp_names; /**< ncomp ComponentNameK attributes, or NULL */
} pm_vtu_array;

/** The shape of one UnstructuredGrid piece. */
typedef struct pm_vtu_piece {
    size_t n_points;                /**< NumberOfPoints */
    size_t n_cells;                 /**< NumberOfCells */
    size_t conn_len;                /**< entries of the connectivity array */
    const pm_vtu_array *point_data; /**< point-data arrays */
    size_t n_point_data;            /**< their count */
} pm_vtu_piece;

/** Bytes of one element of @p t. */
size_t pm_vtu_type_size(pm_vtu_type t);

/**
 * @brief Write the XML part of a VTU file up to and including the `_` that starts the appended data.
 *
 * The caller must then write, with pm_vtu_write_block() and in this order: each point-data array
 * (n_points * ncomp elements), the points (Float64, 3 per point), the connectivity (Int64,
 * conn_len), the offsets (Int64, n_cells) and the types (UInt8, n_cells); then pm_vtu_write_footer().
 * @return PM_OK or PM_EIO (no path in the message: the caller prefixes it)
 */
int pm_vtu_write_header(FILE *f, const pm_vtu_piece *pc);

/** @brief Write one appended block: its UInt64 byte count, then @p bytes bytes of @p data. */
int pm_vtu_write_block(FILE *f, const void *data, size_t bytes);

/** @brief Close the AppendedData element and the document. */
int pm_vtu_write_footer(FILE *f);

/**
 * @brief Write the particles as VTK_VERTEX cells (z = 0) with displacement, velocity, stress
 *        (xx, yy, zz, xy), plastic_strain, material, body, mass and volume, atomically to @p path.
 * @param scratch suitably aligned workspace of at least 3 * max(n, 1) doubles (from malloc)
 * @return PM_OK or PM_EIO naming @p path
 */
int pm_vtu_write_particles(const char *path, const pm_particles *p, void *scratch);

/**
 * @brief Write the background grid (VTK_QUAD or VTK_TRIANGLE cells, or VTK_VERTEX for a grid
 *        without cells) atomically to @p path.
 * @return PM_OK, PM_ENOMEM or PM_EIO naming @p path
 */
int pm_vtu_write_grid(const char *path, const pm_grid *g);

/**
 * @brief Open "<path>.tmp" for writing (the name is stored in @p tmp).
 * @return the stream, or NULL with a PM_EIO message naming the file
 */
FILE *pm_atomic_fopen(const char *path, char *tmp, size_t tmp_size);

/**
 * @brief Finish a file opened with pm_atomic_fopen(): if @p ok, flush, close and rename it to
 *        @p path; otherwise (or if any of that fails) close and remove the temporary file.
 * @return PM_OK, or PM_EIO naming the path (an earlier message is kept when @p ok is 0)
 */
int pm_atomic_fclose(FILE *f, const char *tmp, const char *path, int ok);

/** What run.json records about one probe. */
typedef struct pm_probe_info {
    const char *name;             /**< probe name */
    long particle;                /**< followed particle at t = 0, or -1 for a body probe */
    const char *body;             /**< body name for a body probe, else NULL */
    const char *quantity;         /**< "position", "displacement", ... */
    double initial_position[2];   /**< the particle's position (body: centre of mass) at t = 0 */
} pm_probe_info;

/**
 * @brief Write run.json (pretty JSON, numbers round-trip) atomically to @p path.
 * @param frames particle frames written
 * @return PM_OK, PM_ENOMEM or PM_EIO naming @p path
 */
int pm_run_json_write(const char *path, const pm_run_summary *s, const pm_probe_info *probes,
                      size_t n_probes, size_t frames);

#endif
