/**
 * @file frame.h
 * @brief Reading back what a run wrote: the list of frames in particles.pvd (or grid.pvd) and each
 *        frame's points and named arrays, as doubles. For post-processing in C (and through the
 *        Python package) and for `pmech render`, which redraws pictures from frames.
 *
 * The reader takes the VTK XML UnstructuredGrid files pmech writes (raw appended data, UInt32 or
 * UInt64 block headers, Float64/Float32/Int32/Int64/UInt8 arrays, uncompressed) and refuses others
 * with a message naming the file.
 */
#ifndef PMECH_FRAME_H
#define PMECH_FRAME_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** One frame read back (opaque). */
typedef struct pm_frame pm_frame;

/**
 * @brief Read a frame file (particles_NNNNNN.vtu, grid.vtu, grid_NNNNNN.vtu).
 * @param path the file
 * @param out receives the frame; free with pm_frame_free()
 * @return PM_OK; PM_EIO (cannot read); PM_EINPUT (not a VTU file pmech can read: the message says why)
 */
int pm_frame_read(const char *path, pm_frame **out);

/** @brief Free a frame (NULL is fine). */
void pm_frame_free(pm_frame *f);

/** @brief Number of points (particles, or grid nodes). */
size_t pm_frame_n_points(const pm_frame *f);

/** @brief Simulated time of the frame (its TimeValue field), or NaN when the file does not say. */
double pm_frame_time(const pm_frame *f);

/** @brief Point coordinates, 3 per point (z = 0 in 2-D), valid until pm_frame_free(). */
const double *pm_frame_points(const pm_frame *f);

/** @brief Number of point arrays. */
size_t pm_frame_n_arrays(const pm_frame *f);

/**
 * @brief Name and width of point array @p k.
 * @param f the frame
 * @param k index below pm_frame_n_arrays()
 * @param ncomp if not NULL, receives the number of components
 * @return the name, or NULL when @p k is out of range
 */
const char *pm_frame_array_name(const pm_frame *f, size_t k, int *ncomp);

/**
 * @brief The values of a point array, converted to doubles: ncomp per point, point-major.
 * @param f the frame
 * @param name array name ("velocity", "stress", "pressure", ...)
 * @param ncomp if not NULL, receives the number of components
 * @return the values, valid until pm_frame_free(), or NULL when the frame has no such array
 */
const double *pm_frame_array(const pm_frame *f, const char *name, int *ncomp);

/** The frames of a run, in time order, as listed in a .pvd collection. */
typedef struct pm_series {
    size_t n;       /**< number of frames */
    double *time;   /**< time of each frame */
    char **file;    /**< path of each frame file (the collection's directory joined with its name) */
} pm_series;

/**
 * @brief Read a ParaView collection (.pvd): the frames it lists.
 * @param path the .pvd file (a directory is taken as DIR/particles.pvd)
 * @param s receives the list; free with pm_series_free() (also after a failure)
 * @return PM_OK, PM_EIO (cannot read), PM_EINPUT (not a collection), PM_ENOMEM
 */
int pm_series_read(const char *path, pm_series *s);

/** @brief Free a frame list and zero it. Safe on a zeroed struct. */
void pm_series_free(pm_series *s);

#ifdef __cplusplus
}
#endif
#endif
