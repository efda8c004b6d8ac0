/*
 * Registry of approximations: adding a grid kind is one file and one line in `grid_kinds`, a
 * node-cloud kind one line in `cloud_kinds`. Every list of names, and which method takes which
 * name, is read off these two tables.
 */
#include "approx_internal.h"
#include "pmech/case.h"
#include "pmech/error.h"
#include "shape/meshfree.h"

#include "shape_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

_Static_assert(PM_APPROX_MPM == 1u << PM_METHOD_MPM && PM_APPROX_GMM == 1u << PM_METHOD_GMM &&
                   PM_APPROX_RKPM == 1u << PM_METHOD_RKPM,
               "approximation method bits follow pm_method");

extern const pm_approx_ops pm_approx_linear_ops;
extern const pm_approx_ops pm_approx_gimp_ops;
extern const pm_approx_ops pm_approx_bspline2_ops;
extern const pm_approx_ops pm_approx_lme_ops;

static const pm_approx_ops *const grid_kinds[] = {&pm_approx_linear_ops, &pm_approx_gimp_ops,
                                                  &pm_approx_bspline2_ops, &pm_approx_lme_ops};
#define N_GRID (sizeof grid_kinds / sizeof grid_kinds[0])

/* The first kind serving a method is its default, so mls comes before lme. */
static const pm_cloud_kind cloud_kinds[] = {
    {&pm_approx_mls_ops, pm_mf_init_mls},
    {&pm_approx_lme_cloud_ops, pm_mf_init_lme},
    {&pm_approx_rk_cubic_ops, pm_mf_init_rk},
};
#define N_CLOUD (sizeof cloud_kinds / sizeof cloud_kinds[0])

static const char *grid_names[N_GRID + 1];
static once_flag grid_names_once = ONCE_FLAG_INIT;

static void grid_names_fill(void)
{
    for (size_t k = 0; k < N_GRID; k++)
        grid_names[k] = grid_kinds[k]->name;
    grid_names[N_GRID] = NULL;
}

const char *const *pm_approx_names(void)
{
    call_once(&grid_names_once, grid_names_fill);
    return grid_names;
}

/* Kind k of the grid kinds followed by the cloud kinds. */
static const pm_approx_ops *kind_at(size_t k)
{
    return k < N_GRID ? grid_kinds[k] : cloud_kinds[k - N_GRID].ops;
}

/* Append name to the NULL-terminated out[0..n) unless it is there; returns the new count. */
static size_t add_name(const char **out, size_t n, size_t cap, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(out[i], name) == 0)
            return n;
    if (n + 1 >= cap)
        return n;
    out[n++] = name;
    out[n] = NULL;
    return n;
}

size_t pm_approx_all_names(const char **out, size_t cap)
{
    if (cap == 0)
        return 0;
    size_t n = 0;
    out[0] = NULL;
    for (size_t k = 0; k < N_GRID + N_CLOUD; k++)
        n = add_name(out, n, cap, kind_at(k)->name);
    return n;
}

/* The method's bit, 0 for a value outside pm_method. */
static unsigned method_bit(int method)
{
    return method >= 0 && method < 8 ? 1u << method : 0u;
}

size_t pm_approx_names_for_method(int method, const char **out, size_t cap)
{
    if (cap == 0)
        return 0;
    const unsigned bit = method_bit(method);
    size_t n = 0;
    out[0] = NULL;
    for (size_t k = 0; k < N_GRID + N_CLOUD; k++)
        if (kind_at(k)->methods & bit)
            n = add_name(out, n, cap, kind_at(k)->name);
    return n;
}

const pm_approx_ops *pm_approx_find(const char *name, int method)
{
    const unsigned bit = method_bit(method);
    for (size_t k = 0; name && k < N_GRID + N_CLOUD; k++)
        if ((kind_at(k)->methods & bit) && strcmp(kind_at(k)->name, name) == 0)
            return kind_at(k);
    return NULL;
}

int pm_approx_serves(const char *name, int method)
{
    return pm_approx_find(name, method) != NULL;
}

/* "a, b, c" of the names in ops tables [from, to) of kind_at(). */
static void name_list(size_t from, size_t to, char *list, size_t size)
{
    list[0] = '\0';
    for (size_t k = from; k < to; k++)
        snprintf(list + strlen(list), size - strlen(list), "%s%s", k > from ? ", " : "", kind_at(k)->name);
}

int pm_approx_create_opts(const char *name, const pm_grid *g, const pm_approx_opts *opts, pm_approx **out)
{
    *out = NULL;
    for (size_t k = 0; k < N_GRID; k++) {
        if (strcmp(grid_kinds[k]->name, name) != 0)
            continue;
        pm_approx *a = calloc(1, sizeof *a);
        if (!a)
            return pm_error_set(PM_ENOMEM, "out of memory");
        a->ops = grid_kinds[k];
        a->grid = g;
        a->n_threads = 1;
        a->opts.lme_gamma = NAN;
        a->opts.support_radius = NAN;
        if (opts)
            a->opts = *opts;
        if (a->ops->init) {
            int rc = a->ops->init(a);
            if (rc) {
                pm_approx_destroy(a);
                return rc;
            }
        }
        *out = a;
        return PM_OK;
    }
    char list[256];
    name_list(0, N_GRID, list, sizeof list);
    return pm_error_set(PM_EINPUT, "shape_function '%s' is not available; available: %s", name, list);
}

int pm_approx_create(const char *name, const pm_grid *g, pm_approx **out)
{
    return pm_approx_create_opts(name, g, NULL, out);
}

void pm_approx_destroy(pm_approx *a)
{
    if (!a)
        return;
    if (a->ops->destroy)
        a->ops->destroy(a);
    free(a);
}

int pm_approx_connect(pm_approx *a, pm_particles *p)
{
    return a->ops->connect(a, p);
}

int pm_approx_eval(const pm_approx *a, const pm_particles *p, size_t ip, pm_stencil *s)
{
    return a->ops->eval(a, p, ip, s);
}

const pm_approx_ops *pm_approx_kind(const pm_approx *a)
{
    return a->ops;
}

const pm_cloud_kind *pm_cloud_kind_of(const pm_approx_ops *ops)
{
    for (size_t k = 0; k < N_CLOUD; k++)
        if (cloud_kinds[k].ops == ops)
            return &cloud_kinds[k];
    return NULL;
}

int pm_approx_is_meshfree(const pm_approx *a)
{
    return a && pm_cloud_kind_of(a->ops) != NULL;
}

int pm_approx_create_cloud(const char *name, pm_cloud *cloud, const pm_meshfree_opts *opts, pm_approx **out)
{
    *out = NULL;
    const pm_cloud_kind *kind = NULL;
    for (size_t k = 0; k < N_CLOUD && !kind; k++)
        if (strcmp(cloud_kinds[k].ops->name, name) == 0)
            kind = &cloud_kinds[k];
    if (!kind) {
        char list[256];
        name_list(N_GRID, N_GRID + N_CLOUD, list, sizeof list);
        return pm_error_set(PM_EINPUT, "shape_function '%s' is not available on a node cloud; available: %s", name,
                            list);
    }
    if (!cloud)
        return pm_error_set(PM_EINPUT, "%s: no node cloud", name);
    pm_approx *a = calloc(1, sizeof *a);
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory");
    a->ops = kind->ops;
    a->grid = NULL;
    a->n_threads = 1;
    const int rc = kind->init(a, cloud, opts);
    if (rc) {
        free(a);
        return rc;
    }
    *out = a;
    return PM_OK;
}
