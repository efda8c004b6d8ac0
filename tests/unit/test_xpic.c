/*
 * XPIC(m) (analysis.transfer "xpic", analysis.xpic_order m; Hammerquist and Nairn 2017) against its
 * definition, V_new = V + S (v+ - v) - (I - S S+)^m V, with S the bilinear interpolation from the
 * nodes to the particles and S+ the mass-weighted projection back.
 *
 * - m = 1 is PIC: three steps under gravity from a scattered velocity field agree with `flip` 0 to
 *   1e-12 of the velocities (measured: bitwise), positions to 1e-12 m.
 * - One step without forces (zero stress, zero gravity, so v+ = v): the particles' velocities equal
 *   the reference computed here in the particles' space, (I - S S+) applied m times to V with dense
 *   matrices built from the shape functions written out, a different route from the solver's series
 *   of nodal passes. Tolerance 1e-12 of the field (round-off of a few hundred additions, each term
 *   below 10 times the field for m = 5; measured 2e-15 to 4e-15 m/s); m = 1, 2 and 5. A wrong sign or
 *   coefficient of one term of the series errs by that term, C(m, r) P^(r-1) v, of the field's size.
 * - Dissipation: S S+ is self-adjoint in the particles' mass inner product with eigenvalues in [0, 1],
 *   so each mode keeps 1 - (1 - l)^m of itself, PIC's l at most, FLIP's 1 at least: the kinetic
 *   energy after the step lies between PIC's and FLIP's and grows with m.
 * - A uniform velocity goes through unchanged: to 1e-14 of it for m = 1 and 5, 1e-10 for m = 20
 *   (measured 2e-11: the alternating sums of C(20, r) reach 1.8e5 times the field).
 * The loader takes xpic_order from 1 to 20 (default 5), refuses other values and the key without
 * transfer "xpic", and refuses "xpic" with another scheme, a meshfree method or a PIC share.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/material.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"
#include "transfer_case.h"

#define CELLS 10
#define NODES ((CELLS + 1) * (CELLS + 1))
#define MAXP 400

static void make_case(pm_case *c, pm_transfer transfer, int order, double flip, double gravity, pm_material *mat,
                      pm_case_body *body)
{
    /* its edge cuts cells at every fraction: nodes with little mass */
    tc_disk_case(c, mat, body, "xpic.json", PM_SCHEME_MUSL, PM_QUAD4, CELLS, 1e4, 0.31);
    c->analysis.transfer = transfer;
    c->analysis.xpic_order = order;
    c->analysis.pic = 1.0 - flip;
    c->analysis.gravity[1] = -gravity;
}

/* A velocity field with a smooth part and a part that changes sign from particle to particle. */
static void scattered(size_t i, const double *x, double v[2])
{
    const double noise = ((i * 7919u) % 13u) / 6.0 - 1.0;
    v[0] = 1.0 + 0.5 * sin(6.0 * x[1]) + 0.3 * noise;
    v[1] = -0.5 + 0.4 * cos(5.0 * x[0]) - 0.2 * noise;
}

/* A simulation of the disk with the scattered velocities, or (uniform) (1, -0.5) everywhere. */
static pm_sim *start(pm_case *c, pm_material *mat, pm_case_body *body, pm_transfer transfer, int order, double flip,
                     double gravity, int uniform)
{
    make_case(c, transfer, order, flip, gravity, mat, body);
    pm_sim *s = NULL;
    assert_int_equal(pm_sim_create(c, &s, 1), 0);
    assert_true(s->p.n > 80 && s->p.n <= MAXP);
    assert_int_equal(s->p.n_affine, 0); /* only APIC allocates affine matrices */
    for (size_t i = 0; i < s->p.n; i++) {
        if (uniform) {
            s->p.v[2 * i] = 1.0;
            s->p.v[2 * i + 1] = -0.5;
        } else {
            scattered(i, s->p.x + 2 * i, s->p.v + 2 * i);
        }
    }
    return s;
}

static double max_abs(const double *a, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i]));
    return m;
}

static void xpic_1_is_pic(void **st)
{
    (void)st;
    pm_case c[2];
    pm_material mat[2];
    pm_case_body body[2];
    pm_sim *x = start(&c[0], &mat[0], &body[0], PM_TRANSFER_XPIC, 1, 1.0, 9.81, 0);
    pm_sim *p = start(&c[1], &mat[1], &body[1], PM_TRANSFER_FLIP, 5, 0.0, 9.81, 0);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(pm_explicit_step(x, 1e-3), 0);
        assert_int_equal(pm_explicit_step(p, 1e-3), 0);
    }
    const size_t n = x->p.n;
    double dv = 0, dx = 0;
    for (size_t i = 0; i < 2 * n; i++) {
        dv = fmax(dv, fabs(x->p.v[i] - p->p.v[i]));
        dx = fmax(dx, fabs(x->p.x[i] - p->p.x[i]));
    }
    const double vmax = max_abs(p->p.v, 2 * n);
    printf("XPIC(1) against PIC after 3 steps: velocities within %.2e m/s (of %.2f), positions %.2e m\n", dv, vmax,
           dx);
    assert_true(dv <= 1e-12 * vmax);
    assert_true(dx <= 1e-12);
    pm_sim_destroy(x);
    pm_sim_destroy(p);
}

/* The reference: S (n x NODES) from the bilinear shape functions written out, masses, then
 * V - (I - S S+)^m V in the particles' space. */
static void reference(const pm_sim *s, const double *V, int m, double *out)
{
    const size_t n = s->p.n;
    const double h = 1.0 / CELLS;
    static double S[MAXP][NODES];
    double mi[NODES] = {0};
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < NODES; a++) {
            const double dx = fabs(s->p.x[2 * i] - (a % (CELLS + 1)) * h) / h;
            const double dy = fabs(s->p.x[2 * i + 1] - (a / (CELLS + 1)) * h) / h;
            S[i][a] = dx < 1 && dy < 1 ? (1 - dx) * (1 - dy) : 0.0;
            mi[a] += S[i][a] * s->p.mass[i];
        }
    static double W[2 * MAXP];
    memcpy(W, V, 2 * n * sizeof *W);
    for (int r = 0; r < m; r++) {
        double g[2 * NODES] = {0};
        for (size_t i = 0; i < n; i++)
            for (int a = 0; a < NODES; a++)
                for (int d = 0; d < 2; d++)
                    g[2 * a + d] += S[i][a] * s->p.mass[i] * W[2 * i + d];
        for (int a = 0; a < NODES; a++)
            for (int d = 0; d < 2; d++)
                g[2 * a + d] = mi[a] > 0 ? g[2 * a + d] / mi[a] : 0.0;
        for (size_t i = 0; i < n; i++)
            for (int d = 0; d < 2; d++) {
                double q = 0;
                for (int a = 0; a < NODES; a++)
                    q += S[i][a] * g[2 * a + d];
                W[2 * i + d] -= q;
            }
    }
    for (size_t i = 0; i < 2 * n; i++)
        out[i] = V[i] - W[i];
}

static double kinetic(const pm_sim *s)
{
    double e = 0;
    for (size_t i = 0; i < s->p.n; i++)
        e += 0.5 * s->p.mass[i] * (s->p.v[2 * i] * s->p.v[2 * i] + s->p.v[2 * i + 1] * s->p.v[2 * i + 1]);
    return e;
}

/* One force-free step with transfer `tr` of order m (flip: the FLIP share); returns the kinetic
 * energy after it and, with XPIC, the largest difference from the reference into *err. */
static double force_free_step(pm_transfer tr, int m, double flip, double *err)
{
    pm_case c;
    pm_material mat;
    pm_case_body body;
    pm_sim *s = start(&c, &mat, &body, tr, m, flip, 0.0, 0);
    const size_t n = s->p.n;
    static double V[2 * MAXP], want[2 * MAXP];
    memcpy(V, s->p.v, 2 * n * sizeof *V);
    if (tr == PM_TRANSFER_XPIC)
        reference(s, V, m, want);
    assert_int_equal(pm_explicit_step(s, 1e-4), 0);
    *err = 0;
    if (tr == PM_TRANSFER_XPIC)
        for (size_t i = 0; i < 2 * n; i++)
            *err = fmax(*err, fabs(s->p.v[i] - want[i]));
    const double e = kinetic(s);
    pm_sim_destroy(s);
    return e;
}

static void xpic_matches_definition(void **st)
{
    (void)st;
    double err, e[4];
    const int orders[3] = {1, 2, 5};
    const double e_flip = force_free_step(PM_TRANSFER_FLIP, 5, 1.0, &err);
    e[0] = force_free_step(PM_TRANSFER_FLIP, 5, 0.0, &err);
    for (int k = 0; k < 3; k++) {
        e[k + 1] = force_free_step(PM_TRANSFER_XPIC, orders[k], 1.0, &err);
        printf("XPIC(%d): largest difference from the reference %.2e m/s; kinetic energy %.6f J\n", orders[k], err,
               e[k + 1]);
        assert_true(err <= 1e-12 * 1.6); /* the field's largest component is about 1.6 m/s */
    }
    printf("kinetic energy: PIC %.6f J, FLIP %.6f J\n", e[0], e_flip);
    assert_true(fabs(e[1] - e[0]) <= 1e-12 * e[0]); /* m = 1 is PIC */
    assert_true(e[1] < e[2] && e[2] < e[3] && e[3] < e_flip);
}

static void uniform_passes(void **st)
{
    (void)st;
    const int orders[3] = {1, 5, 20};
    for (int k = 0; k < 3; k++) {
        const int m = orders[k];
        pm_case c;
        pm_material mat;
        pm_case_body body;
        pm_sim *s = start(&c, &mat, &body, PM_TRANSFER_XPIC, m, 1.0, 0.0, 1);
        assert_int_equal(pm_explicit_step(s, 1e-4), 0);
        double err = 0;
        for (size_t i = 0; i < s->p.n; i++)
            err = fmax(err, fmax(fabs(s->p.v[2 * i] - 1.0), fabs(s->p.v[2 * i + 1] + 0.5)));
        printf("XPIC(%d): uniform field back within %.2e m/s\n", m, err);
        /* the alternating sum of C(20, r) reaches 1.8e5 times the field: round-off of 1e-16 each */
        assert_true(err <= (m > 5 ? 1e-10 : 1e-14));
        pm_sim_destroy(s);
    }
}

/* tc_load's case; the XPIC order it loads with into *order (0 for another transfer). */
static int load(const char *method, const char *extra, int *order)
{
    pm_case c;
    const int rc = tc_load(method, extra, &c);
    if (rc == PM_OK)
        *order = c.analysis.transfer == PM_TRANSFER_XPIC ? c.analysis.xpic_order : 0;
    pm_case_free(&c);
    return rc;
}

static void loader_checks(void **st)
{
    (void)st;
    int order;
    assert_int_equal(load("mpm", ", \"transfer\": \"xpic\"", &order), PM_OK);
    assert_int_equal(order, 5);
    assert_int_equal(load("mpm", ", \"transfer\": \"xpic\", \"xpic_order\": 1", &order), PM_OK);
    assert_int_equal(order, 1);
    assert_int_equal(load("mpm", ", \"transfer\": \"xpic\", \"xpic_order\": 20, \"flip\": 1", &order), PM_OK);
    assert_int_equal(order, 20);
    tc_refused("mpm", ", \"transfer\": \"xpic\", \"xpic_order\": 0", "analysis.xpic_order: got 0; allowed: a whole "
                                                                   "number from 1 to 20");
    tc_refused("mpm", ", \"transfer\": \"xpic\", \"xpic_order\": 21", "analysis.xpic_order");
    tc_refused("mpm", ", \"transfer\": \"xpic\", \"xpic_order\": 2.5", "analysis.xpic_order");
    tc_refused("mpm", ", \"xpic_order\": 3", "analysis.xpic_order");
    tc_refused("mpm", ", \"transfer\": \"xpic\", \"scheme\": \"usl\"", "analysis.transfer");
    tc_refused("gmm", ", \"transfer\": \"xpic\"", "analysis.transfer");
    tc_refused("mpm", ", \"transfer\": \"xpic\", \"flip\": 0.9", "analysis.flip");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(xpic_1_is_pic),
        cmocka_unit_test(xpic_matches_definition),
        cmocka_unit_test(uniform_passes),
        cmocka_unit_test(loader_checks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
