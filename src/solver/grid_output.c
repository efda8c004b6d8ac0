/* Grid frames: what the nodes carried at the end of the last step. */
#include "solver/grid_output.h"

#include "contact/contact.h"
#include "io/vtu_write.h"
#include "pmech/error.h"

#include <stdlib.h>

int pm_sim_grid_frame(pm_output *out, const pm_sim *s)
{
    const size_t n = s->grid.n_nodes;
    int32_t *contact = calloc(n ? n : 1, sizeof *contact);
    if (!contact)
        return pm_error_set(PM_ENOMEM, "out of memory writing a grid frame of %zu nodes", n);
    /* 1 + the surface each node touches (pm_contact_detect found them at the start of the last step) */
    for (size_t k = 0; s->contact && k < s->contact->n_node; k++) {
        const pm_contact_node *cn = &s->contact->node[k];
        if (cn->node >= 0 && (size_t)cn->node < n)
            contact[cn->node] = cn->surface + 1;
    }
    const int explicit_run = s->c->analysis.type == PM_ANALYSIS_EXPLICIT;
    const double *v = s->c->analysis.scheme == PM_SCHEME_NEWMARK_PC ? s->nd.vel : s->nd.vel_new;
    /* before the first step the nodes have carried nothing yet */
    const int stepped = s->step > 0;
    const pm_vtu_grid_fields gf = {stepped ? s->nd.mass : NULL, explicit_run && stepped ? v : NULL, s->nd.fixed, contact,
                                   &s->t};
    const int rc = pm_output_grid_frame(out, &s->grid, &gf);
    free(contact);
    return rc;
}
