/*
 * Direct sparse solves through SuiteSparse. The matrices are assembled in CSR with a structurally
 * symmetric pattern; read as CSC the same arrays are A^T, which is A itself for CHOLMOD (symmetric,
 * upper part used) and is solved transposed by UMFPACK.
 *
 * CHOLMOD is asked for a supernodal (always LL^T) factorisation so that an indefinite tangent (the
 * geometric stiffness of compressed material can make it so) is reported as not positive definite
 * rather than factorised without pivoting; the solve then falls back to UMFPACK.
 */
#include "linalg/sparse.h"
#include "pmech/error.h"
#include "io/progress.h"

#include <cholmod.h>
#include <stdlib.h>
#include <string.h>
#include <umfpack.h>

struct pm_sparse_solver {
    cholmod_common cc;
    cholmod_factor *L;       /* CHOLMOD symbolic + numeric factor (NULL: analyse first) */
    void *symbolic;          /* UMFPACK symbolic analysis (NULL: analyse first) */
    int cholmod_failed;      /* the current pattern's matrix was not positive definite once */
    double control[UMFPACK_CONTROL];
};

int pm_sparse_solver_create(pm_sparse_solver **out)
{
    pm_sparse_solver *s = calloc(1, sizeof *s);
    if (!s)
        return pm_error_set(PM_ENOMEM, "out of memory for the sparse solver");
    cholmod_start(&s->cc);
    s->cc.print = 0;
    s->cc.supernodal = CHOLMOD_SUPERNODAL;
    s->cc.quick_return_if_not_posdef = 1;
    umfpack_di_defaults(s->control);
    *out = s;
    return PM_OK;
}

void pm_sparse_solver_new_pattern(pm_sparse_solver *s)
{
    if (s->L)
        cholmod_free_factor(&s->L, &s->cc);
    if (s->symbolic)
        umfpack_di_free_symbolic(&s->symbolic);
    s->cholmod_failed = 0;
}

void pm_sparse_solver_destroy(pm_sparse_solver *s)
{
    if (!s)
        return;
    pm_sparse_solver_new_pattern(s);
    cholmod_finish(&s->cc);
    free(s);
}

/* The CSR arrays seen by CHOLMOD as a symmetric matrix, without copying. */
static cholmod_sparse wrap(const pm_csr *A)
{
    cholmod_sparse m;
    memset(&m, 0, sizeof m);
    m.nrow = m.ncol = (size_t)A->n;
    m.nzmax = (size_t)A->nnz;
    m.p = A->rowptr;
    m.i = A->col;
    m.x = A->val;
    m.stype = 1;
    m.itype = CHOLMOD_INT;
    m.xtype = CHOLMOD_REAL;
    m.dtype = CHOLMOD_DOUBLE;
    m.sorted = 1;
    m.packed = 1;
    return m;
}

/* 0: solved; 1: not positive definite (caller falls back); negative: error. */
static int solve_cholmod(pm_sparse_solver *s, const pm_csr *A, const double *b, double *x)
{
    cholmod_sparse m = wrap(A);
    if (!s->L) {
        s->L = cholmod_analyze(&m, &s->cc);
        if (!s->L)
            return pm_error_set(PM_ENOMEM, "CHOLMOD could not analyse a %d x %d matrix (status %d)", A->n, A->n,
                                s->cc.status);
    }
    if (!cholmod_factorize(&m, s->L, &s->cc) && s->cc.status < 0)
        return pm_error_set(PM_ENOMEM, "CHOLMOD factorisation failed (status %d)", s->cc.status);
    if (s->cc.status == CHOLMOD_NOT_POSDEF)
        return 1;
    cholmod_dense rhs;
    memset(&rhs, 0, sizeof rhs);
    rhs.nrow = (size_t)A->n;
    rhs.ncol = 1;
    rhs.nzmax = rhs.d = (size_t)A->n;
    rhs.x = (void *)b;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    cholmod_dense *sol = cholmod_solve(CHOLMOD_A, s->L, &rhs, &s->cc);
    if (!sol)
        return pm_error_set(PM_ENOMEM, "CHOLMOD solve failed (status %d)", s->cc.status);
    memcpy(x, sol->x, (size_t)A->n * sizeof(double));
    cholmod_free_dense(&sol, &s->cc);
    return 0;
}

static int solve_umfpack(pm_sparse_solver *s, const pm_csr *A, const double *b, double *x)
{
    double info[UMFPACK_INFO];
    int st;
    if (!s->symbolic) {
        st = umfpack_di_symbolic(A->n, A->n, A->rowptr, A->col, A->val, &s->symbolic, s->control, info);
        if (st != UMFPACK_OK)
            return pm_error_set(st == UMFPACK_ERROR_out_of_memory ? PM_ENOMEM : PM_EINTERNAL,
                                "UMFPACK could not analyse a %d x %d matrix (status %d)", A->n, A->n, st);
    }
    void *numeric = NULL;
    st = umfpack_di_numeric(A->rowptr, A->col, A->val, s->symbolic, &numeric, s->control, info);
    if (st == UMFPACK_WARNING_singular_matrix) {
        umfpack_di_free_numeric(&numeric);
        return pm_error_set(PM_ESIM, "the tangent matrix is singular (UMFPACK): part of the body is not held");
    }
    if (st != UMFPACK_OK) {
        umfpack_di_free_numeric(&numeric);
        return pm_error_set(st == UMFPACK_ERROR_out_of_memory ? PM_ENOMEM : PM_EINTERNAL,
                            "UMFPACK factorisation failed (status %d)", st);
    }
    /* the CSR arrays read as CSC are A^T: solve (A^T)^T x = b */
    st = umfpack_di_solve(UMFPACK_At, A->rowptr, A->col, A->val, x, b, numeric, s->control, info);
    umfpack_di_free_numeric(&numeric);
    if (st != UMFPACK_OK)
        return pm_error_set(PM_ESIM, "UMFPACK solve failed (status %d)", st);
    return PM_OK;
}

int pm_sparse_solve(pm_sparse_solver *s, const pm_csr *A, int symmetric, const double *b, double *x,
                    pm_solve_info *info)
{
    const double w0 = pm_wall_seconds();
    pm_solve_info inf = {PM_SOLVER_UMFPACK, 0, 0};
    int rc;
    if (symmetric && !s->cholmod_failed) {
        rc = solve_cholmod(s, A, b, x);
        if (rc < 0)
            return rc;
        if (rc == 0) {
            inf.used = PM_SOLVER_CHOLMOD;
        } else {
            /* indefinite: keep to UMFPACK for the rest of this pattern (the next iterations see
             * nearly the same matrix) */
            s->cholmod_failed = 1;
            inf.fell_back = 1;
            rc = solve_umfpack(s, A, b, x);
        }
    } else {
        rc = solve_umfpack(s, A, b, x);
    }
    inf.seconds = pm_wall_seconds() - w0;
    if (info)
        *info = inf;
    return rc;
}
