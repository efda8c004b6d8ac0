#include "pmech/particles.h"
#include "pmech/error.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/*
 * The particle fields, one row each: where the pointer sits in pm_particles, its element size and
 * its width. Allocation, freeing, byte counts and permutation all walk this table, so adding a field
 * is one row (and packing particles for distributed runs will walk it too).
 */
typedef struct field_row {
    const char *name;  /* as files that store every field call it (checkpoints) */
    size_t offset;     /* of the array pointer inside pm_particles */
    size_t elem;       /* bytes of one entry */
    size_t width;      /* entries per particle; 0: n_state; AFFINE: n_affine */
} field_row;

/* The width of APIC's affine matrix: PM_DIM x PM_DIM once pm_particles_enable_affine() ran, else 0, so
 * that runs with other transfers neither allocate nor sort, copy or store it. */
#define AFFINE ((size_t)-1)

#define FIELD(member, type, w) { #member, offsetof(pm_particles, member), sizeof(type), (w) }
static const field_row fields[] = {
    FIELD(x, double, PM_DIM),      FIELD(x0, double, PM_DIM),   FIELD(v, double, PM_DIM),
    FIELD(a, double, PM_DIM),      FIELD(v_grid, double, PM_DIM), FIELD(mass, double, 1),   FIELD(vol, double, 1),
    FIELD(vol0, double, 1),        FIELD(F, double, PM_NF),     FIELD(stress, double, PM_NS),
    FIELD(eps_p, double, 1),       FIELD(state, double, 0),     FIELD(hsize, double, PM_DIM),
    FIELD(C, double, AFFINE),
    FIELD(material, int32_t, 1),   FIELD(body, int32_t, 1),     FIELD(cell, int32_t, 1),
    FIELD(id, int32_t, 1),
};
#undef FIELD
#define N_FIELDS (sizeof fields / sizeof fields[0])

static void **field_ptr(pm_particles *p, size_t k)
{
    return (void **)((char *)p + fields[k].offset);
}

static size_t field_width(const pm_particles *p, size_t k)
{
    if (fields[k].width == AFFINE)
        return p->n_affine;
    return fields[k].width ? fields[k].width : p->n_state;
}

size_t pm_particles_field_count(void)
{
    return N_FIELDS;
}

void pm_particles_field_get(const pm_particles *p, size_t k, pm_particle_field *f)
{
    f->name = fields[k].name;
    f->data = *(void *const *)((const char *)p + fields[k].offset);
    f->elem = fields[k].elem;
    f->width = field_width(p, k);
    f->is_int = fields[k].elem == sizeof(int32_t);
}

size_t pm_particles_bytes_per_particle(size_t n_state)
{
    size_t b = 0;
    for (size_t k = 0; k < N_FIELDS; k++)
        if (fields[k].width != AFFINE)
            b += fields[k].elem * (fields[k].width ? fields[k].width : n_state);
    return b;
}

int pm_particles_alloc_capacity(pm_particles *p, size_t n, size_t cap, size_t n_state)
{
    memset(p, 0, sizeof *p);
    if (cap < n)
        cap = n;
    p->n = n;
    p->cap = cap;
    p->n_state = n_state;
    size_t cnt = cap ? cap : 1;
    for (size_t k = 0; k < N_FIELDS; k++) {
        const size_t w = field_width(p, k);
        void **arr = field_ptr(p, k);
        /* an empty affine field still gets one entry: a valid pointer for the generic walks */
        *arr = calloc(fields[k].width == AFFINE ? 1 : cnt * (w ? w : 1), fields[k].elem);
        if (!*arr)
            goto fail;
    }
    for (size_t i = 0; i < n; i++)
        p->id[i] = (int32_t)i;
    return PM_OK;
fail:
    pm_particles_free(p);
    return pm_error_set(PM_ENOMEM, "cannot allocate %zu particles (%zu bytes)", cap,
                        cap * pm_particles_bytes_per_particle(n_state));
}

int pm_particles_alloc(pm_particles *p, size_t n, size_t n_state)
{
    return pm_particles_alloc_capacity(p, n, n, n_state);
}

int pm_particles_enable_affine(pm_particles *p)
{
    const size_t w = PM_DIM * PM_DIM, cnt = p->cap ? p->cap : 1;
    if (p->n_affine == w)
        return PM_OK;
    double *C = calloc(cnt * w, sizeof *C);
    if (!C)
        return pm_error_set(PM_ENOMEM, "cannot allocate the affine matrices of %zu particles (%zu bytes)", cnt,
                            cnt * w * sizeof *C);
    free(p->C);
    p->C = C;
    p->n_affine = w;
    return PM_OK;
}

void pm_particles_copy(pm_particles *dst, size_t at, const pm_particles *src, size_t from, size_t count)
{
    for (size_t k = 0; k < N_FIELDS; k++) {
        const size_t row = fields[k].elem * field_width(dst, k);
        if (row == 0 || count == 0)
            continue;
        char *d = *field_ptr(dst, k);
        if (field_width(src, k) != field_width(dst, k)) { /* only the affine field: a source has none */
            memset(d + at * row, 0, count * row);
            continue;
        }
        const char *s = *(void *const *)((const char *)src + fields[k].offset);
        memcpy(d + at * row, s + from * row, count * row);
    }
}

/* Stable compaction, field by field, moving each run of kept particles with one memmove (sinks remove
 * a few particles at a time, so the runs are long); everything before the first dropped particle stays
 * put. */
size_t pm_particles_remove(pm_particles *p, const uint8_t *drop)
{
    size_t first = 0;
    while (first < p->n && !drop[first])
        first++;
    if (first == p->n)
        return 0;
    size_t kept = first;
    for (size_t k = 0; k < N_FIELDS; k++) {
        const size_t row = fields[k].elem * field_width(p, k);
        char *a = *field_ptr(p, k);
        size_t to = first, i = first;
        while (i < p->n) {
            while (i < p->n && drop[i])
                i++;
            const size_t start = i;
            while (i < p->n && !drop[i])
                i++;
            if (row && i > start)
                memmove(a + to * row, a + start * row, (i - start) * row);
            to += i - start;
        }
        kept = to;
    }
    const size_t removed = p->n - kept;
    p->n = kept;
    return removed;
}

void pm_particles_free(pm_particles *p)
{
    for (size_t k = 0; k < N_FIELDS; k++)
        free(*field_ptr(p, k));
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

static void permute_ints(int32_t *a, size_t w, size_t n, const uint32_t *perm, int32_t *scratch)
{
    for (size_t c = 0; c < w; c++) {
        for (size_t i = 0; i < n; i++)
            scratch[i] = a[(size_t)perm[i] * w + c];
        for (size_t i = 0; i < n; i++)
            a[i * w + c] = scratch[i];
    }
}

int pm_particles_permute(pm_particles *p, const uint32_t *perm, double *scratch, int32_t *iscratch)
{
    for (size_t k = 0; k < N_FIELDS; k++) {
        const size_t w = field_width(p, k);
        void *arr = *field_ptr(p, k);
        if (fields[k].elem == sizeof(double))
            permute_doubles(arr, w, p->n, perm, scratch);
        else
            permute_ints(arr, w, p->n, perm, iscratch);
    }
    return PM_OK;
}
