/**
 * @file sparse.h (internal to src/, not installed)
 * @brief Sparse matrices in compressed-row storage and direct solves with SuiteSparse: CHOLMOD for
 *        symmetric positive definite systems, UMFPACK for everything else (and as the fallback when
 *        a Cholesky factorisation finds the matrix indefinite).
 *
 * The implicit solvers build the pattern once per step from the particles' stencils, then assemble
 * values and solve several times (Newton iterations) on the same pattern, so the solver keeps the
 * symbolic analysis until it is told the pattern changed.
 */
#ifndef PMECH_SPARSE_H
#define PMECH_SPARSE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A square sparse matrix in compressed-row storage with sorted column indices in every row. */
typedef struct pm_csr {
    int n;             /**< rows (= columns) */
    int nnz;           /**< stored entries */
    int *rowptr;       /**< n + 1 row starts */
    int *col;          /**< nnz column indices, ascending within a row */
    double *val;       /**< nnz values */
    size_t cap_n;      /**< allocated rows (capacity, so that steps rarely reallocate) */
    size_t cap_nnz;    /**< allocated entries */
} pm_csr;

/**
 * @brief Make room for @p n rows and @p nnz entries, keeping the capacity when it suffices.
 * @param A matrix (zeroed struct on first use)
 * @param n rows
 * @param nnz entries
 * @return PM_OK or PM_ENOMEM; the contents are undefined afterwards
 */
int pm_csr_reserve(pm_csr *A, int n, size_t nnz);

/** @brief Free a matrix's arrays and zero it. */
void pm_csr_free(pm_csr *A);

/**
 * @brief Index into A->val of entry (@p i, @p j), or -1 when it is not in the pattern.
 *        Binary search in row @p i.
 */
static inline int pm_csr_find(const pm_csr *A, int i, int j)
{
    int lo = A->rowptr[i], hi = A->rowptr[i + 1] - 1;
    while (lo <= hi) {
        const int mid = (lo + hi) >> 1, c = A->col[mid];
        if (c == j)
            return mid;
        if (c < j)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

/**
 * @brief Largest |a_ij - a_ji| relative to the largest |a_ij| (0 for a symmetric matrix).
 *        The pattern must be structurally symmetric.
 */
double pm_csr_asymmetry(const pm_csr *A);

/** @brief y = A x. */
void pm_csr_matvec(const pm_csr *A, const double *x, double *y);

/** Which factorisation a solve used. */
typedef enum { PM_SOLVER_CHOLMOD = 0, PM_SOLVER_UMFPACK = 1 } pm_solver_kind;

/** What a solve reports. */
typedef struct pm_solve_info {
    pm_solver_kind used;    /**< the factorisation that produced the solution */
    int fell_back;          /**< 1: CHOLMOD found the matrix not positive definite, UMFPACK solved it */
    double seconds;         /**< wall time of analysis + factorisation + solve */
} pm_solve_info;

typedef struct pm_sparse_solver pm_sparse_solver;

/**
 * @brief Create a direct solver.
 * @param out receives the solver; free with pm_sparse_solver_destroy()
 * @return PM_OK or PM_ENOMEM
 */
int pm_sparse_solver_create(pm_sparse_solver **out);

/** @brief Free a solver and its factorisations (NULL is fine). */
void pm_sparse_solver_destroy(pm_sparse_solver *s);

/**
 * @brief Forget the symbolic analysis: the next solve analyses the pattern anew. Call whenever
 *        the matrix's pattern changed.
 */
void pm_sparse_solver_new_pattern(pm_sparse_solver *s);

/**
 * @brief Solve A x = b.
 * @param s solver
 * @param A matrix with a structurally symmetric pattern
 * @param symmetric 1: A is symmetric, try CHOLMOD first (UMFPACK if it is not positive definite);
 *                  0: UMFPACK
 * @param b right-hand side (n)
 * @param x receives the solution (n; may not alias b)
 * @param info receives what was used (may be NULL)
 * @return PM_OK, PM_ESIM when the matrix is singular, PM_ENOMEM
 */
int pm_sparse_solve(pm_sparse_solver *s, const pm_csr *A, int symmetric, const double *b, double *x,
                    pm_solve_info *info);

#ifdef __cplusplus
}
#endif
#endif
