#include "pmech/particles.h"
#include "pmech/error.h"

#include <stdlib.h>
#include <string.h>

/* Widths of the double arrays, in the order of the struct; kept in one table so that
 * allocation, byte counts and permutation cannot disagree. */
#define N_DOUBLE_ARRAYS 12

static double **double_array(pm_particles *p, int k, size_t *width)
{
    switch (k) {
    case 0: *width = 2; return &p->x;
    case 1: *width = 2; return &p->x0;
    case 2: *width = 2; return &p->v;
    case 3: *width = 2; return &p->a;
    case 4: *width = 1; return &p->mass;
    case 5: *width = 1; return &p->vol;
    case 6: *width = 1; return &p->vol0;
    case 7: *width = PM_NF; return &p->F;
    case 8: *width = PM_NS; return &p->stress;
    case 9: *width = 1; return &p->eps_p;
    case 10: *width = p->n_state; return &p->state;
    default: *width = 2; return &p->hsize;
    }
}

size_t pm_particles_bytes_per_particle(size_t n_state)
{
    return sizeof(double) * (2 + 2 + 2 + 2 + 1 + 1 + 1 + PM_NF + PM_NS + 1 + n_state + 2) +
           3 * sizeof(int32_t);
}

int pm_particles_alloc(pm_particles *p, size_t n, size_t n_state)
{
    memset(p, 0, sizeof *p);
    p->n = n;
    p->n_state = n_state;
    size_t cnt = n ? n : 1;
    for (int k = 0; k < N_DOUBLE_ARRAYS; k++) {
        size_t w;
        double **arr = double_array(p, k, &w);
        *arr = calloc(cnt * (w ? w : 1), sizeof(double));
        if (!*arr)
            goto fail;
    }
    p->material = calloc(cnt, sizeof(int32_t));
    p->body = calloc(cnt, sizeof(int32_t));
    p->cell = calloc(cnt, sizeof(int32_t));
    if (!p->material || !p->body || !p->cell)
        goto fail;
    return PM_OK;
fail:
    pm_particles_free(p);
    return pm_error_set(PM_ENOMEM, "cannot allocate %zu particles (%zu bytes)", n,
                        n * pm_particles_bytes_per_particle(n_state));
}

void pm_particles_free(pm_particles *p)
{
    for (int k = 0; k < N_DOUBLE_ARRAYS; k++) {
        size_t w;
        double **arr = double_array(p, k, &w);
        free(*arr);
    }
    free(p->material);
    free(p->body);
    free(p->cell);
    memset(p, 0, sizeof *p);
}

/* One component at a time, so the workspace is one double per particle whatever the width. */
static void permute_doubles(double *a, size_t w, size_t n, const uint32_t *perm, double *scratch)
{
    for (size_t c = 0; c < w; c++) {
        for (size_t i = 0; i < n; i++)
            scratch[i] = a[(size_t)perm[i] * w + c];
        for (size_t i = 0; i < n; i++)
            a[i * w + c] = scratch[i];
    }
}

static void permute_ints(int32_t *a, size_t n, const uint32_t *perm, int32_t *scratch)
{
    for (size_t i = 0; i < n; i++)
        scratch[i] = a[perm[i]];
    memcpy(a, scratch, n * sizeof(int32_t));
}

int pm_particles_permute(pm_particles *p, const uint32_t *perm, double *scratch, int32_t *iscratch)
{
    for (int k = 0; k < N_DOUBLE_ARRAYS; k++) {
        size_t w;
        double **arr = double_array(p, k, &w);
        if (w)
            permute_doubles(*arr, w, p->n, perm, scratch);
    }
    permute_ints(p->material, p->n, perm, iscratch);
    permute_ints(p->body, p->n, perm, iscratch);
    permute_ints(p->cell, p->n, perm, iscratch);
    return PM_OK;
}
