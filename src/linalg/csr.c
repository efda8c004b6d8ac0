/* Compressed-row matrices: storage with kept capacity, symmetry measure, product. */
#include "linalg/sparse.h"
#include "pmech/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pm_csr_reserve(pm_csr *A, int n, size_t nnz)
{
    if (n < 0)
        return pm_error_set(PM_EINTERNAL, "sparse matrix with %d rows", n);
    if ((size_t)n + 1 > A->cap_n) {
        size_t cap = (size_t)n + 1 + (size_t)n / 4;
        int *r = realloc(A->rowptr, cap * sizeof *r);
        if (!r)
            return pm_error_set(PM_ENOMEM, "out of memory for a sparse matrix of %d rows", n);
        A->rowptr = r;
        A->cap_n = cap;
    }
    if (nnz > A->cap_nnz) {
        size_t cap = nnz + nnz / 4;
        int *c = realloc(A->col, cap * sizeof *c);
        if (c)
            A->col = c;
        double *v = c ? realloc(A->val, cap * sizeof *v) : NULL;
        if (!c || !v)
            return pm_error_set(PM_ENOMEM, "out of memory for a sparse matrix of %zu entries", nnz);
        A->val = v;
        A->cap_nnz = cap;
    }
    A->n = n;
    return PM_OK;
}

void pm_csr_free(pm_csr *A)
{
    free(A->rowptr);
    free(A->col);
    free(A->val);
    memset(A, 0, sizeof *A);
}

double pm_csr_asymmetry(const pm_csr *A)
{
    double amax = 0, dmax = 0;
    for (int i = 0; i < A->n; i++)
        for (int k = A->rowptr[i]; k < A->rowptr[i + 1]; k++) {
            const int j = A->col[k];
            amax = fmax(amax, fabs(A->val[k]));
            if (j <= i)
                continue;
            const int kt = pm_csr_find(A, j, i);
            const double aji = kt >= 0 ? A->val[kt] : 0.0;
            dmax = fmax(dmax, fabs(A->val[k] - aji));
        }
    return amax > 0 ? dmax / amax : 0.0;
}

void pm_csr_matvec(const pm_csr *A, const double *x, double *y)
{
    for (int i = 0; i < A->n; i++) {
        double s = 0;
        for (int k = A->rowptr[i]; k < A->rowptr[i + 1]; k++)
            s += A->val[k] * x[A->col[k]];
        y[i] = s;
    }
}
