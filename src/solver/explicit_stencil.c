/* A particle's stencil for the passes that take it through the approximation's interface; with
 * body fields, numbered in the particle's own field (contact/multibody.h). */
#include "explicit_internal.h"

#include "contact/multibody.h"

int pm_xp_stencil(const pm_sim *s, size_t i, pm_stencil *st)
{
    const int rc = s->approx->ops->eval(s->approx, &s->p, i, st);
    if (s->mb) {
        const int32_t off = s->mb->offset_of_body[s->p.body[i]];
        for (int k = 0; k < st->n; k++)
            st->node[k] += off;
    }
    return rc;
}
