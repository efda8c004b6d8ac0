/**
 * @file checkpoint_meshfree.h (internal to src/io)
 * @brief The group /meshfree of a checkpoint (GMM and RKPM runs; layout in docs/checkpoint.md): the node
 *        cloud, its cell list's build, the approximation's kept state and the implicit nodal history.
 */
#ifndef PMECH_IO_CHECKPOINT_MESHFREE_H
#define PMECH_IO_CHECKPOINT_MESHFREE_H

#include "io/checkpoint_h5.h"
#include "solver/sim_internal.h"

/**
 * @brief Write the meshfree state of @p s into the open group @p g.
 * @return PM_OK, PM_EIO naming the dataset, PM_ENOMEM
 */
int pm_ck_write_meshfree(const ck_file *f, hid_t g, const pm_sim *s);

/**
 * @brief Put the meshfree state stored in group @p g into @p s, after its particles and nodal arrays: the
 *        cloud as it was (positions, the build of its cell list, volumes), the approximation's kept
 *        state, the implicit nodal history, and the boundary rows evaluated at the restored nodes.
 * @return PM_OK, PM_EINPUT when the stored cloud does not fit this case's (another node count or kind)
 */
int pm_ck_read_meshfree(const ck_file *f, hid_t g, pm_sim *s);

#endif
