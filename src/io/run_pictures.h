/**
 * @file run_pictures.h (internal to src/, not installed)
 * @brief The pictures of a run (`output.pictures`): one per frame, all with one colour range. With
 *        `output.picture_range` that range is fixed from the start; otherwise each frame is drawn, as it
 *        is written, with the range of all frames so far (so a long run can be watched), and when the
 *        run ends the frames drawn with a narrower range than the whole run's are redrawn from their
 *        VTU files.
 */
#ifndef PMECH_IO_RUN_PICTURES_H
#define PMECH_IO_RUN_PICTURES_H

#include <stddef.h>

#include "pmech/case.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

typedef struct pm_run_pictures pm_run_pictures;

/**
 * @brief Start the pictures of a run (nothing to do when the case asks for none: *rp stays NULL).
 * @param rp receives the state
 * @param c the case (its output.pictures, picture_range, picture_width, title, formulation)
 * @param dir the output directory
 * @param g the grid whose bounding box frames the pictures
 * @return PM_OK, PM_ENOMEM
 */
int pm_run_pictures_open(pm_run_pictures **rp, const pm_case *c, const char *dir, const pm_grid *g);

/**
 * @brief Draw frame @p frame (particles_NNNNNN.png beside particles_NNNNNN.vtu). NULL @p rp: nothing.
 * @return PM_OK, PM_ENOMEM, PM_EIO
 */
int pm_run_pictures_frame(pm_run_pictures *rp, size_t frame, double t, const pm_particles *p);

/**
 * @brief Redraw, from their frames, the pictures drawn with another range than the whole run's, then
 *        free @p rp (NULL is fine).
 * @return PM_OK, or the first error (every picture is still attempted)
 */
int pm_run_pictures_close(pm_run_pictures *rp);

/**
 * @brief The colour range so far and the range each picture was drawn with (a checkpoint keeps them).
 * @param used receives the per-picture ranges (owned by @p rp)
 * @return the number of pictures drawn; 0 for NULL @p rp
 */
size_t pm_run_pictures_state(const pm_run_pictures *rp, double range[2], const double (**used)[2]);

/**
 * @brief Put back what pm_run_pictures_state() gave (a run continued from a checkpoint). NULL @p rp:
 *        nothing.
 * @return PM_OK, PM_ENOMEM
 */
int pm_run_pictures_restore(pm_run_pictures *rp, const double range[2], const double (*used)[2], size_t n);

#endif
