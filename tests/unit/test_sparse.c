/*
 * Sparse matrices and direct solves (src/linalg): systems whose solution is known exactly, solved by
 * each path pm_sparse_solve offers (CHOLMOD for SPD, UMFPACK for unsymmetric, UMFPACK after CHOLMOD
 * finds a symmetric matrix indefinite), element-by-element assembly summing into a shared entry,
 * and singular matrices reported as PM_ESIM.
 *
 * Tolerances: the solutions are exact in exact arithmetic, so what remains is round-off, bounded by
 * about cond(A) * eps * |x|. The 1-D Laplacian of n = 99 unknowns has cond = 4 / (pi h)^2 ~ 4e3,
 * so 1e-10 relative leaves two orders of margin without hiding a wrong solve (which errs by O(1)).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/error.h"
#include "linalg/sparse.h"

#define N 99 /* unknowns of the 1-D problems: h = 1 / (N + 1) */

/* A from a dense row-major n x n array: every nonzero entry and the whole diagonal are stored. */
static void from_dense(pm_csr *A, int n, const double *dense)
{
    size_t nnz = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            nnz += dense[i * n + j] != 0 || i == j;
    assert_int_equal(pm_csr_reserve(A, n, nnz), PM_OK);
    int pos = 0;
    for (int i = 0; i < n; i++) {
        A->rowptr[i] = pos;
        for (int j = 0; j < n; j++)
            if (dense[i * n + j] != 0 || i == j) {
                A->col[pos] = j;
                A->val[pos++] = dense[i * n + j];
            }
    }
    A->rowptr[n] = pos;
    A->nnz = pos;
}

/* The tridiagonal pattern of n unknowns, values zero. */
static void tridiagonal_pattern(pm_csr *A, int n)
{
    assert_int_equal(pm_csr_reserve(A, n, (size_t)(3 * n - 2)), PM_OK);
    int pos = 0;
    for (int i = 0; i < n; i++) {
        A->rowptr[i] = pos;
        for (int j = i - 1; j <= i + 1; j++)
            if (j >= 0 && j < n) {
                A->col[pos] = j;
                A->val[pos++] = 0;
            }
    }
    A->rowptr[n] = pos;
    A->nnz = pos;
}

/*
 * -u'' = 1 on (0, 1), u(0) = u(1) = 0, by linear elements: each element [x_e, x_e+1] adds
 * [1 -1; -1 1] / h to its two nodes (the boundary nodes are not unknowns), and b_i = h. The
 * three-point stencil differentiates quadratics exactly, so the discrete solution is the exact
 * u = x (1 - x) / 2 at the nodes.
 */
static void assemble_laplacian(pm_csr *A, double *b)
{
    const double h = 1.0 / (N + 1);
    tridiagonal_pattern(A, N);
    for (int e = 0; e <= N; e++) { /* element e joins nodes e and e + 1; unknown i is node i + 1 */
        const int dof[2] = {e - 1, e};
        const double ke[2][2] = {{1 / h, -1 / h}, {-1 / h, 1 / h}};
        for (int a = 0; a < 2; a++)
            for (int c = 0; c < 2; c++) {
                if (dof[a] < 0 || dof[a] >= N || dof[c] < 0 || dof[c] >= N)
                    continue;
                const int at = pm_csr_find(A, dof[a], dof[c]);
                assert_true(at >= 0);
                A->val[at] += ke[a][c];
            }
    }
    for (int i = 0; i < N; i++)
        b[i] = h;
}

static double max_rel_error(const double *x, const double *exact, int n)
{
    double e = 0, m = 0;
    for (int i = 0; i < n; i++) {
        e = fmax(e, fabs(x[i] - exact[i]));
        m = fmax(m, fabs(exact[i]));
    }
    return e / m;
}

static double rel_residual(const pm_csr *A, const double *x, const double *b)
{
    double r[N], rn = 0, bn = 0;
    assert_true(A->n <= N);
    pm_csr_matvec(A, x, r);
    for (int i = 0; i < A->n; i++) {
        rn = fmax(rn, fabs(r[i] - b[i]));
        bn = fmax(bn, fabs(b[i]));
    }
    return rn / bn;
}

/* Two elements share every interior node: its diagonal entry is the sum of both, 2 / h. */
static void assembly_sums_shared_entries(void **state)
{
    (void)state;
    pm_csr A = {0};
    double b[N];
    assemble_laplacian(&A, b);
    const double h = 1.0 / (N + 1);
    assert_int_equal(A.nnz, 3 * N - 2);
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            const int at = pm_csr_find(&A, i, j);
            if (abs(i - j) > 1) {
                assert_int_equal(at, -1);
                continue;
            }
            assert_true(at >= 0);
            const double want = i == j ? 2 / h : -1 / h;
            assert_true(fabs(A.val[at] - want) <= 1e-12 * fabs(want)); /* sums of two exact doubles */
        }
    assert_true(pm_csr_asymmetry(&A) == 0.0);
    pm_csr_free(&A);
}

static void spd_laplacian_by_cholmod_and_umfpack(void **state)
{
    (void)state;
    pm_csr A = {0};
    double b[N], x[N], exact[N];
    assemble_laplacian(&A, b);
    const double h = 1.0 / (N + 1);
    for (int i = 0; i < N; i++) {
        const double xi = (i + 1) * h;
        exact[i] = xi * (1 - xi) / 2;
    }
    pm_sparse_solver *s;
    assert_int_equal(pm_sparse_solver_create(&s), PM_OK);
    for (int symmetric = 1; symmetric >= 0; symmetric--) {
        pm_solve_info info;
        memset(x, 0, sizeof x);
        assert_int_equal(pm_sparse_solve(s, &A, symmetric, b, x, &info), PM_OK);
        assert_int_equal(info.used, symmetric ? PM_SOLVER_CHOLMOD : PM_SOLVER_UMFPACK);
        assert_int_equal(info.fell_back, 0);
        assert_true(max_rel_error(x, exact, N) < 1e-10);
        assert_true(rel_residual(&A, x, b) < 1e-10);
    }
    /* same pattern, values doubled (the kept analysis is reused): the solution halves */
    for (int k = 0; k < A.nnz; k++)
        A.val[k] *= 2;
    for (int i = 0; i < N; i++)
        exact[i] /= 2;
    assert_int_equal(pm_sparse_solve(s, &A, 1, b, x, NULL), PM_OK);
    assert_true(max_rel_error(x, exact, N) < 1e-10);
    pm_sparse_solver_destroy(s);
    pm_csr_free(&A);
}

/*
 * Central differences of -u'' + c u' (a tridiagonal matrix with 2 on the diagonal, -1 - p below and
 * -1 + p above, p = c h / 2 = 0.3) against a manufactured x; b is computed from the stencil here, not
 * by pm_csr_matvec, so both are checked.
 */
static void unsymmetric_by_umfpack(void **state)
{
    (void)state;
    const double p = 0.3;
    static double dense[N * N];
    double x[N], exact[N], b[N];
    memset(dense, 0, sizeof dense);
    for (int i = 0; i < N; i++) {
        exact[i] = sin(0.1 * i) + (double)i / N;
        dense[i * N + i] = 2;
        if (i > 0)
            dense[i * N + i - 1] = -1 - p;
        if (i + 1 < N)
            dense[i * N + i + 1] = -1 + p;
    }
    for (int i = 0; i < N; i++)
        b[i] = 2 * exact[i] + (i > 0 ? (-1 - p) * exact[i - 1] : 0) + (i + 1 < N ? (-1 + p) * exact[i + 1] : 0);
    pm_csr A = {0};
    from_dense(&A, N, dense);
    /* |a_ij - a_ji| = 2p on every off-diagonal pair; the largest entry is the diagonal's 2 */
    assert_true(fabs(pm_csr_asymmetry(&A) - 2 * p / 2) < 1e-15);
    double y[N];
    pm_csr_matvec(&A, exact, y);
    assert_true(max_rel_error(y, b, N) < 1e-15);
    pm_sparse_solver *s;
    assert_int_equal(pm_sparse_solver_create(&s), PM_OK);
    pm_solve_info info;
    assert_int_equal(pm_sparse_solve(s, &A, 0, b, x, &info), PM_OK);
    assert_int_equal(info.used, PM_SOLVER_UMFPACK);
    /* cond of this diagonally dominant matrix is of the Laplacian's order: same margin */
    assert_true(max_rel_error(x, exact, N) < 1e-10);
    assert_true(rel_residual(&A, x, b) < 1e-10);
    pm_sparse_solver_destroy(s);
    pm_csr_free(&A);
}

/* [[1, 2], [2, 1]] has eigenvalues 3 and -1: CHOLMOD refuses it, UMFPACK solves it; x = (1, -2). */
static void indefinite_symmetric_falls_back(void **state)
{
    (void)state;
    const double dense[4] = {1, 2, 2, 1}, exact[2] = {1, -2}, b[2] = {-3, 0};
    pm_csr A = {0};
    from_dense(&A, 2, dense);
    pm_sparse_solver *s;
    assert_int_equal(pm_sparse_solver_create(&s), PM_OK);
    double x[2];
    pm_solve_info info;
    assert_int_equal(pm_sparse_solve(s, &A, 1, b, x, &info), PM_OK);
    assert_int_equal(info.used, PM_SOLVER_UMFPACK);
    assert_int_equal(info.fell_back, 1);
    assert_true(max_rel_error(x, exact, 2) < 1e-14); /* 2 x 2 with cond 3: a few ulps */
    pm_sparse_solver_destroy(s);
    pm_csr_free(&A);
}

static void expect_singular(const double *dense, int n, int symmetric)
{
    pm_csr A = {0};
    from_dense(&A, n, dense);
    pm_sparse_solver *s;
    assert_int_equal(pm_sparse_solver_create(&s), PM_OK);
    double b[3] = {1, 1, 1}, x[3];
    assert_int_equal(pm_sparse_solve(s, &A, symmetric, b, x, NULL), PM_ESIM);
    assert_non_null(strstr(pm_error_message(), "singular"));
    pm_sparse_solver_destroy(s);
    pm_csr_free(&A);
}

/* Rank-deficient matrices give PM_ESIM and a message, on either path. */
static void singular_is_an_error(void **state)
{
    (void)state;
    const double ones[4] = {1, 1, 1, 1};               /* rank 1 */
    const double free_body[4] = {1, -1, -1, 1};        /* a spring held nowhere: PSD, rank 1 */
    const double zero_row[9] = {2, 0, 1, 0, 0, 0, 1, 0, 2}; /* an unknown nothing holds */
    expect_singular(ones, 2, 0);
    expect_singular(free_body, 2, 1);
    expect_singular(zero_row, 3, 0);
    expect_singular(zero_row, 3, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(assembly_sums_shared_entries),
        cmocka_unit_test(spd_laplacian_by_cholmod_and_umfpack),
        cmocka_unit_test(unsymmetric_by_umfpack),
        cmocka_unit_test(indefinite_symmetric_falls_back),
        cmocka_unit_test(singular_is_an_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
