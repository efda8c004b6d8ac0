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
    const double *mass = s->nd.mass;
    double *sum = NULL;
    if (s->mb) { /* body fields: the grid shows their total mass and centre-of-mass velocity */
        sum = calloc((1 + PM_DIM) * (n ? n : 1), sizeof *sum);
        if (!sum) {
            free(contact);
            return pm_error_set(PM_ENOMEM, "out of memory writing a grid frame of %zu nodes", n);
        }
        for (size_t e = 0; e < s->nd.n_all; e++) {
            const size_t g = e % n;
            sum[g] += s->nd.mass[e];
            for (int d = 0; d < PM_DIM; d++)
                sum[n + PM_DIM * g + d] += s->nd.mass[e] * v[PM_DIM * e + d];
        }
        for (size_t g = 0; g < n; g++)
            for (int d = 0; d < PM_DIM; d++)
                sum[n + PM_DIM * g + d] = sum[g] > 0 ? sum[n + PM_DIM * g + d] / sum[g] : 0.0;
        mass = sum;
        v = sum + n;
    }
    /* before the first step the nodes have carried nothing yet */
    const int stepped = s->step > 0;
    const pm_vtu_grid_fields gf = {stepped ? mass : NULL, explicit_run && stepped ? v : NULL, s->nd.fixed, contact,
                                   &s->t};
    const int rc = pm_output_grid_frame(out, &s->grid, &gf);
    free(contact);
    free(sum);
    return rc;
}
