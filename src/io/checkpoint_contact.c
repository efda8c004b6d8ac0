/* Checkpoint pieces of the contact surfaces that only explicit runs with friction sides or wall profiles
 * carry (checkpoint_contact.h): the touching points' impulses and the wall profiles' impulses. */
#include "io/checkpoint_contact.h"

#include "pmech/error.h"

#include <stdlib.h>

/* Columns of a touching point's row: surface, particle, normal impulse, tangential impulse. */
enum { POINT_COLS = 3 + PM_DIM };

/* Columns of a wall profile's row: surface, node, the 1 + PM_DIM values of its node impulse. */
enum { PROFILE_COLS = 3 + PM_DIM };

static int put_double(const ck_file *f, hid_t g, const char *name, double v)
{
    return ck_attr_write(f, g, name, CK_DOUBLE, &v);
}

static int get_double(const ck_file *f, hid_t g, const char *name, double *v)
{
    return ck_attr_read(f, g, name, CK_DOUBLE, v);
}

/* Explicit friction sides start each step's sweeps from the impulses of the last step's touching points
 * (src/contact/friction.c): each point's surface, particle and impulses, and the step they were found for. */
int pm_ck_write_points(const ck_file *f, hid_t g, const pm_contact *ct)
{
    double *a = malloc((ct->n_pt ? ct->n_pt : 1) * POINT_COLS * sizeof *a);
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    for (size_t q = 0; q < ct->n_pt; q++) {
        const pm_contact_point *pt = &ct->pt[q];
        double *row = a + q * POINT_COLS;
        row[0] = pt->surface;
        row[1] = (double)pt->particle;
        row[2] = pt->lam_n;
        for (int d = 0; d < PM_DIM; d++)
            row[3 + d] = pt->lam_t[d];
    }
    int rc = ck_write(f, g, "points", CK_DOUBLE, a, ct->n_pt, POINT_COLS);
    free(a);
    return rc ? rc : put_double(f, g, "points_dt", ct->pt_dt);
}

/* Whether a node's profile row (1 + PM_DIM values) holds anything. */
static int has_impulse(const double *J)
{
    int any = 0;
    for (int d = 0; d <= PM_DIM; d++)
        any |= J[d] != 0;
    return any;
}

/* The wall profiles' impulses since their last frame (pm_contact_surface::node_impulse): one row per
 * node that has one, (surface, node, the 1 + PM_DIM values), so that a profile spanning the stop is the
 * uninterrupted run's. */
int pm_ck_write_profile_impulses(const ck_file *f, hid_t g, const pm_contact *ct)
{
    size_t rows = 0;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        for (size_t n = 0; ct->surface[k].node_impulse && n < ct->n_nodes; n++) {
            rows += has_impulse(ct->surface[k].node_impulse + (size_t)(1 + PM_DIM) * n);
        }
    double *a = malloc((rows ? rows : 1) * PROFILE_COLS * sizeof *a);
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    size_t q = 0;
    for (size_t k = 0; k < ct->n_surfaces; k++)
        for (size_t n = 0; ct->surface[k].node_impulse && n < ct->n_nodes; n++) {
            const double *J = ct->surface[k].node_impulse + (size_t)(1 + PM_DIM) * n;
            if (!has_impulse(J))
                continue;
            double *row = a + q++ * PROFILE_COLS;
            row[0] = (double)k;
            row[1] = (double)n;
            for (int d = 0; d <= PM_DIM; d++)
                row[2 + d] = J[d];
        }
    const int rc = ck_write(f, g, "profile_impulse", CK_DOUBLE, a, rows, PROFILE_COLS);
    free(a);
    return rc;
}

/* The last step's touching points, whose impulses the next step's sweeps start from (checkpoint_write.c);
 * a checkpoint without them (written before they were kept) starts those sweeps from zero. */
int pm_ck_read_points(const ck_file *f, const char *path, hid_t g, pm_contact *ct)
{
    size_t rows = 0;
    if (H5Lexists(g, "points", H5P_DEFAULT) <= 0 || ck_rows(f, g, "points", &rows) || rows == 0)
        return PM_OK;
    if (rows > ct->pt_cap)
        return pm_error_set(PM_EINPUT, "%s: %zu contact points where this case holds %zu", path, rows, ct->pt_cap);
    double *a = malloc(rows * POINT_COLS * sizeof *a);
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    int rc = ck_read(f, g, "points", CK_DOUBLE, a, rows, POINT_COLS);
    if (!rc)
        rc = get_double(f, g, "points_dt", &ct->pt_dt);
    for (size_t q = 0; !rc && q < rows; q++) {
        pm_contact_point *pt = &ct->pt[q];
        const double *row = a + q * POINT_COLS;
        pt->surface = (int32_t)row[0];
        pt->particle = (size_t)row[1];
        pt->lam_n = row[2];
        for (int d = 0; d < PM_DIM; d++)
            pt->lam_t[d] = row[3 + d];
    }
    free(a);
    if (!rc)
        ct->n_pt = rows;
    return rc;
}

/* The wall profiles' impulses since their last frame (checkpoint_write.c); a checkpoint written before
 * they were kept has none, and the profile spanning the stop then starts at it. */
int pm_ck_read_profile_impulses(const ck_file *f, const char *path, hid_t g, pm_contact *ct)
{
    size_t rows = 0;
    if (H5Lexists(g, "profile_impulse", H5P_DEFAULT) <= 0 || ck_rows(f, g, "profile_impulse", &rows) ||
        rows == 0)
        return PM_OK;
    if (rows > ct->n_surfaces * ct->n_nodes)
        return pm_error_set(PM_EINPUT, "%s: %zu wall profile rows where this case holds %zu", path, rows,
                            ct->n_surfaces * ct->n_nodes);
    double *a = malloc(rows * PROFILE_COLS * sizeof *a);
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    int rc = ck_read(f, g, "profile_impulse", CK_DOUBLE, a, rows, PROFILE_COLS);
    for (size_t q = 0; !rc && q < rows; q++) {
        const double *row = a + q * PROFILE_COLS;
        const double k = row[0], n = row[1];
        if (!(k >= 0 && k < (double)ct->n_surfaces && n >= 0 && n < (double)ct->n_nodes) ||
            !ct->surface[(size_t)k].node_impulse) {
            rc = pm_error_set(PM_EINPUT, "%s: wall profile row %zu names surface %g, node %g, not of this case",
                              path, q, k, n);
            break;
        }
        double *J = ct->surface[(size_t)k].node_impulse + (size_t)(1 + PM_DIM) * (size_t)n;
        for (int d = 0; d <= PM_DIM; d++)
            J[d] = row[2 + d];
    }
    free(a);
    return rc;
}
