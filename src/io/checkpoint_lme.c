/*
 * The group /lme of a checkpoint (checkpoint_lme.h; layout in docs/checkpoint.md). The grid kind lme
 * returns a kept stencil for a point evaluated again at a bit-identical position and starts Newton
 * elsewhere from a prediction made of the kept stencil and lambda: both decide the last digits of the
 * next step, so every slot's position, lambda and stencil is stored. Stencils are stored packed (only
 * the entries a slot uses, slot after slot), which keeps the file free of unused memory.
 */
#include "io/checkpoint_lme.h"

#include "pmech/error.h"
#include "shape/lme_state.h"

#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(int) == sizeof(int32_t), "stencil lengths are stored as 32-bit integers");

int pm_ck_write_lme(const ck_file *f, hid_t g, const pm_approx *a)
{
    pm_lme_state st;
    pm_check(pm_lme_state_get(a, &st));
    const int64_t slots = (int64_t)st.cap;
    const int32_t width = st.width;
    pm_check(ck_attr_write(f, g, "slots", CK_INT64, &slots));
    pm_check(ck_attr_write(f, g, "width", CK_INT32, &width));
    pm_check(ck_write(f, g, "position", CK_DOUBLE, st.xs, st.cap, PM_DIM));
    pm_check(ck_write(f, g, "lambda", CK_DOUBLE, st.lam, st.cap, PM_DIM));
    pm_check(ck_write(f, g, "stencil_length", CK_INT32, st.n, st.cap, 1));
    size_t total = 0;
    for (size_t i = 0; i < st.cap; i++)
        total += (size_t)st.n[i];
    int32_t *node = malloc((total ? total : 1) * sizeof *node);
    double *val = malloc((total ? total : 1) * (1 + PM_DIM) * sizeof *val);
    int rc = node && val ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    for (size_t i = 0, k = 0; !rc && i < st.cap; i++)
        for (int j = 0; j < st.n[i]; j++, k++) {
            const size_t o = i * (size_t)st.width + (size_t)j;
            node[k] = st.node[o];
            val[k] = st.N[o];
            for (int d = 0; d < PM_DIM; d++)
                val[total + PM_DIM * k + d] = st.dN[o][d];
        }
    if (!rc)
        rc = ck_write(f, g, "stencil_node", CK_INT32, node, total, 1);
    if (!rc)
        rc = ck_write(f, g, "stencil_N", CK_DOUBLE, val, total, 1);
    if (!rc)
        rc = ck_write(f, g, "stencil_dN", CK_DOUBLE, val + total, total, PM_DIM);
    free(node);
    free(val);
    return rc;
}

int pm_ck_read_lme(const ck_file *f, hid_t g, pm_approx *a)
{
    pm_lme_state st;
    pm_check(pm_lme_state_get(a, &st));
    int64_t slots = 0;
    int32_t width = 0;
    pm_check(ck_attr_read(f, g, "slots", CK_INT64, &slots));
    pm_check(ck_attr_read(f, g, "width", CK_INT32, &width));
    if (slots != (int64_t)st.cap || width != st.width)
        return pm_error_set(PM_EINPUT,
                            "%s: /lme holds %lld stencils of up to %d nodes; this case keeps %zu of up to %d",
                            f->path, (long long)slots, (int)width, st.cap, st.width);
    pm_check(ck_read(f, g, "position", CK_DOUBLE, st.xs, st.cap, PM_DIM));
    pm_check(ck_read(f, g, "lambda", CK_DOUBLE, st.lam, st.cap, PM_DIM));
    pm_check(ck_read(f, g, "stencil_length", CK_INT32, st.n, st.cap, 1));
    size_t total = 0;
    for (size_t i = 0; i < st.cap; i++) {
        if (st.n[i] < 0 || st.n[i] > st.width) {
            memset(st.n, 0, st.cap * sizeof *st.n); /* no kept stencil is used half read */
            return pm_error_set(PM_EINPUT, "%s: /lme/stencil_length: slot %zu holds %d nodes (0 to %d)", f->path, i,
                                st.n[i], st.width);
        }
        total += (size_t)st.n[i];
    }
    int32_t *node = malloc((total ? total : 1) * sizeof *node);
    double *val = malloc((total ? total : 1) * (1 + PM_DIM) * sizeof *val);
    int rc = node && val ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    if (!rc)
        rc = ck_read(f, g, "stencil_node", CK_INT32, node, total, 1);
    if (!rc)
        rc = ck_read(f, g, "stencil_N", CK_DOUBLE, val, total, 1);
    if (!rc)
        rc = ck_read(f, g, "stencil_dN", CK_DOUBLE, val + total, total, PM_DIM);
    for (size_t k = 0; !rc && k < total; k++)
        if (node[k] < 0 || (size_t)node[k] >= st.n_nodes)
            rc = pm_error_set(PM_EINPUT, "%s: /lme/stencil_node: entry %zu is node %d of a grid of %zu", f->path, k,
                              (int)node[k], st.n_nodes);
    for (size_t i = 0, k = 0; !rc && i < st.cap; i++)
        for (int j = 0; j < st.n[i]; j++, k++) {
            const size_t o = i * (size_t)st.width + (size_t)j;
            st.node[o] = node[k];
            st.N[o] = val[k];
            for (int d = 0; d < PM_DIM; d++)
                st.dN[o][d] = val[total + PM_DIM * k + d];
        }
    if (rc)
        memset(st.n, 0, st.cap * sizeof *st.n);
    free(node);
    free(val);
    return rc;
}
