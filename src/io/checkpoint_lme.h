/**
 * @file checkpoint_lme.h (internal to src/io)
 * @brief The group /lme of a checkpoint (method mpm with shape_function lme; layout in docs/checkpoint.md):
 *        each particle slot's kept stencil, position and lambda (shape/lme_state.h).
 */
#ifndef PMECH_IO_CHECKPOINT_LME_H
#define PMECH_IO_CHECKPOINT_LME_H

#include "io/checkpoint_h5.h"
#include "pmech/approx.h"

/**
 * @brief Write the per-slot cache of @p a (the grid kind lme) into the open group @p g.
 * @return PM_OK, PM_EIO naming the dataset, PM_ENOMEM
 */
int pm_ck_write_lme(const ck_file *f, hid_t g, const pm_approx *a);

/**
 * @brief Put the cache stored in group @p g back into @p a, whose slots were sized by its first connect()
 *        exactly as the stored run's were.
 * @return PM_OK, PM_EINPUT when the stored slots do not fit (another count or width) or a stored stencil
 *         is longer than a slot
 */
int pm_ck_read_lme(const ck_file *f, hid_t g, pm_approx *a);

#endif
