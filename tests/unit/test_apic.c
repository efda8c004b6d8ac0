/*
 * APIC (analysis.transfer "apic"): a velocity field that is affine over the body, v = v0 + A (x - xc)
 * with rotation and shear in A, goes to the grid and back unchanged. With linear shape functions
 * sum N_I (x_I - x_p) = 0 and sum (x_I - x_p) (x) grad N_I = I, so every node with mass receives the
 * field's value at the node and the particles take v0 + A (x_p - xc) and C_p = A back, also in the
 * cells the body fills only in part. One step of 1e-4 s on a body with E = 1 Pa: the stress it builds
 * (E dt |A|, 3e-4 Pa) changes velocities by less than 1e-9 m/s, so the field must come back to 1e-8
 * of its size (measured: 4e-16 m/s, C_p within 8e-15 / s). PIC (flip 0) on the same body averages the
 * field over each node's particles and misses by a good part of |A| h (3 / s x 0.1 m) at the boundary
 * (measured 0.10 m/s), which the test also checks (at least 1e-2), so that the tolerance is one that a
 * transfer without the affine part fails. Momentum is conserved to round-off
 * as for the other transfers (the affine part adds sum_I N_I (x_I - x_p) = 0 to it). The loader refuses
 * APIC where it has no meaning (another scheme, a meshfree method, a PIC share), naming the key.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/material.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"
#include "transfer_case.h"

static const double A[4] = {0.5, -3.0, 3.0, -0.2}; /* xx, xy, yx, yy: spin 3 / s plus stretch and shear */
static const double V0[2] = {1.0, -0.5}, XC[2] = {0.5, 0.5}; /* XC: the disk's centre (tc_disk_case) */

static void make_case(pm_case *c, pm_transfer transfer, double flip, pm_material *mat, pm_case_body *body)
{
    /* its edge cuts cells at every fraction */
    tc_disk_case(c, mat, body, "apic.json", PM_SCHEME_MUSL, PM_QUAD4, 10, 1.0, 0.31);
    c->analysis.transfer = transfer;
    c->analysis.pic = 1.0 - flip;
}

static void affine(const double *x, double v[2])
{
    const double dx = x[0] - XC[0], dy = x[1] - XC[1];
    v[0] = V0[0] + A[0] * dx + A[1] * dy;
    v[1] = V0[1] + A[2] * dx + A[3] * dy;
}

/* One step from the affine field; returns the largest |v_p - field(x_p at the start)| and, with
 * APIC, the largest |C_p - A| into *cerr. Checks momentum on the way. */
static double one_step(pm_transfer transfer, double flip, double *cerr)
{
    pm_case c;
    pm_material mat;
    pm_case_body body;
    make_case(&c, transfer, flip, &mat, &body);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(&c, &s, 1), 0);
    /* the affine matrices exist in APIC runs only */
    assert_int_equal(s->p.n_affine, transfer == PM_TRANSFER_APIC ? 4 : 0);
    const size_t n = s->p.n;
    assert_true(n > 80);
    double x0[2 * 400], p0[2] = {0, 0};
    assert_true(n <= 400);
    for (size_t i = 0; i < n; i++) {
        affine(s->p.x + 2 * i, s->p.v + 2 * i);
        if (transfer == PM_TRANSFER_APIC) /* other transfers allocate no affine matrices */
            for (int j = 0; j < 4; j++)
                s->p.C[4 * i + j] = A[j];
        x0[2 * i] = s->p.x[2 * i];
        x0[2 * i + 1] = s->p.x[2 * i + 1];
        p0[0] += s->p.mass[i] * s->p.v[2 * i];
        p0[1] += s->p.mass[i] * s->p.v[2 * i + 1];
    }
    assert_int_equal(pm_explicit_step(s, 1e-4), 0);
    double err = 0, pe = 0, p1[2] = {0, 0};
    *cerr = 0;
    for (size_t i = 0; i < n; i++) {
        double v[2];
        affine(x0 + 2 * i, v);
        for (int d = 0; d < 2; d++) {
            err = fmax(err, fabs(s->p.v[2 * i + d] - v[d]));
            p1[d] += s->p.mass[i] * s->p.v[2 * i + d];
        }
        for (int j = 0; j < (int)s->p.n_affine; j++)
            *cerr = fmax(*cerr, fabs(s->p.C[4 * i + j] - A[j]));
    }
    for (int d = 0; d < 2; d++)
        pe = fmax(pe, fabs(p1[d] - p0[d]) / (fabs(p0[0]) + fabs(p0[1])));
    assert_true(pe <= 1e-12);
    pm_sim_destroy(s);
    return err;
}

static void apic_keeps_affine_field(void **st)
{
    (void)st;
    double cerr;
    const double err = one_step(PM_TRANSFER_APIC, 1.0, &cerr);
    assert_true(err <= 1e-8);  /* |v| and |A| h are of order 1 and 0.3 m/s */
    assert_true(cerr <= 1e-7); /* |A| is of order 3 / s */
}

static void pic_loses_it(void **st)
{
    (void)st;
    double cerr;
    const double err = one_step(PM_TRANSFER_FLIP, 0.0, &cerr);
    assert_true(err >= 1e-2);
}

/* tc_load's case, which must load with the transfer `extra` names when the loader takes it. */
static int load(const char *method, const char *extra)
{
    pm_case c;
    const int rc = tc_load(method, extra, &c);
    if (rc == PM_OK)
        assert_int_equal(c.analysis.transfer, strstr(extra, "apic") ? PM_TRANSFER_APIC : PM_TRANSFER_FLIP);
    pm_case_free(&c);
    return rc;
}

static void loader_checks(void **st)
{
    (void)st;
    assert_int_equal(load("mpm", ""), PM_OK);
    assert_int_equal(load("mpm", ", \"transfer\": \"apic\""), PM_OK);
    assert_int_equal(load("mpm", ", \"transfer\": \"apic\", \"scheme\": \"musl\", \"flip\": 1"), PM_OK);
    tc_refused("mpm", ", \"transfer\": \"apic\", \"scheme\": \"usl\"", "analysis.transfer");
    tc_refused("gmm", ", \"transfer\": \"apic\"", "analysis.transfer");
    tc_refused("mpm", ", \"transfer\": \"apic\", \"flip\": 0.9", "analysis.flip");
    tc_refused("mpm", ", \"transfer\": \"tpic\"", "analysis.transfer");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(apic_keeps_affine_field),
        cmocka_unit_test(pic_loses_it),
        cmocka_unit_test(loader_checks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
