/* contact_forces.csv: the force between every listed pair of contact groups over time (multibody.h).
 * Each row is written whole and flushed, so the file stays valid if a run stops. */
#include "contact/multibody.h"

#include "pmech/error.h"

#include <errno.h>
#include <string.h>

int pm_multibody_log_open(pm_multibody *mb, const pm_case *c, const char *dir)
{
    char path[PM_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/contact_forces.csv", dir);
    mb->log = fopen(path, "w");
    if (!mb->log)
        return pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(errno));
    fputs("time,first,second", mb->log);
    for (int d = 0; d < PM_DIM; d++)
        fprintf(mb->log, ",f%c", "xyz"[d]);
    fputc('\n', mb->log);
    memset(mb->pair_impulse, 0, PM_DIM * (size_t)mb->n_fields * (size_t)mb->n_fields * sizeof(double));
    mb->impulse_time = 0;
    return pm_multibody_log_row(mb, c, 0.0);
}

void pm_multibody_log_step(pm_multibody *mb, double dt)
{
    const size_t nf = (size_t)mb->n_fields;
    for (size_t k = 0; k < PM_DIM * nf * nf; k++)
        mb->pair_impulse[k] += mb->pair_force[k] * dt;
    mb->impulse_time += dt;
}

/* Where the force on field a from field b went: a acts against its heaviest neighbour, so at a node
 * the impulse of a pair may be booked on either side; the force on a from b is the mean of what a
 * received from b and minus what b received from a. */
int pm_multibody_log_row(pm_multibody *mb, const pm_case *c, double t)
{
    if (!mb->log)
        return PM_OK;
    const size_t nf = (size_t)mb->n_fields;
    const double span = mb->impulse_time > 0 ? mb->impulse_time : 1.0;
    for (size_t k = 0; k < c->n_contact_pairs; k++) {
        const pm_case_contact_pair *pr = &c->contact_pairs[k];
        size_t a = nf, b = nf;
        for (size_t f = 0; f < nf; f++) {
            if (!strcmp(mb->name[f], pr->group[0]))
                a = f;
            if (!strcmp(mb->name[f], pr->group[1]))
                b = f;
        }
        if (a == nf || b == nf)
            continue;
        const double *on_a = mb->pair_impulse + PM_DIM * (a * nf + b), *on_b = mb->pair_impulse + PM_DIM * (b * nf + a);
        fprintf(mb->log, "%.17g,%s,%s", t, pr->group[0], pr->group[1]);
        for (int d = 0; d < PM_DIM; d++)
            fprintf(mb->log, ",%.17g", 0.5 * (on_a[d] - on_b[d]) / span);
        fputc('\n', mb->log);
    }
    memset(mb->pair_impulse, 0, PM_DIM * nf * nf * sizeof(double));
    mb->impulse_time = 0;
    return fflush(mb->log) == 0 && !ferror(mb->log) ? PM_OK : pm_error_set(PM_EIO, "contact_forces.csv: write failed");
}

int pm_multibody_log_close(pm_multibody *mb)
{
    if (!mb || !mb->log)
        return PM_OK;
    const int bad = fclose(mb->log) != 0;
    mb->log = NULL;
    return bad ? pm_error_set(PM_EIO, "contact_forces.csv: write failed") : PM_OK;
}
