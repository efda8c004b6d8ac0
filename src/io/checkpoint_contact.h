/* Checkpoint datasets of the contact surfaces' explicit state (checkpoint_write.c, checkpoint_read.c). */
#ifndef PMECH_IO_CHECKPOINT_CONTACT_H
#define PMECH_IO_CHECKPOINT_CONTACT_H

#include "contact/contact.h"
#include "io/checkpoint_h5.h"

/** @brief Write the last step's touching points of @p ct (surface, particle, impulses) and the step they
 *         were found for into group @p g. @return PM_OK, PM_ENOMEM, PM_EIO */
int pm_ck_write_points(const ck_file *f, hid_t g, const pm_contact *ct);

/** @brief Write the wall profiles' node impulses gathered since their last frame (the non-zero rows) into
 *         group @p g. @return PM_OK, PM_ENOMEM, PM_EIO */
int pm_ck_write_profile_impulses(const ck_file *f, hid_t g, const pm_contact *ct);

/** @brief Read what pm_ck_write_points() wrote into @p ct (none in an older checkpoint: the sweeps then
 *         start from zero); @p path names the file in messages. @return PM_OK, PM_EINPUT, PM_ENOMEM, PM_EIO */
int pm_ck_read_points(const ck_file *f, const char *path, hid_t g, pm_contact *ct);

/** @brief Read what pm_ck_write_profile_impulses() wrote into @p ct, after the wall profiles were opened
 *         (which start them afresh). @return PM_OK, PM_EINPUT, PM_ENOMEM, PM_EIO */
int pm_ck_read_profile_impulses(const ck_file *f, const char *path, hid_t g, pm_contact *ct);

#endif
