/* The particle container (src/core/particles.c): room allocated beyond the count, copies of whole
 * particles between containers, removal that keeps the order, and ids that follow every move. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "pmech/particles.h"

/* Give particle i of p values that tell it apart in every field. */
static void stamp(pm_particles *p, size_t i, double v)
{
    for (int d = 0; d < PM_DIM; d++) {
        p->x[PM_DIM * i + d] = v + d;
        p->x0[PM_DIM * i + d] = v + 10 + d;
        p->v[PM_DIM * i + d] = v + 20 + d;
        p->a[PM_DIM * i + d] = v + 30 + d;
        p->hsize[PM_DIM * i + d] = v + 40 + d;
    }
    p->mass[i] = v + 50;
    p->vol[i] = v + 51;
    p->vol0[i] = v + 52;
    p->eps_p[i] = v + 53;
    for (int k = 0; k < PM_NF; k++)
        p->F[PM_NF * i + k] = v + 60 + k;
    for (int k = 0; k < PM_NS; k++)
        p->stress[PM_NS * i + k] = v + 70 + k;
    for (size_t k = 0; k < p->n_state; k++)
        p->state[p->n_state * i + k] = v + 80 + (double)k;
    p->material[i] = (int32_t)v + 1;
    p->body[i] = (int32_t)v + 2;
    p->cell[i] = (int32_t)v + 3;
}

/* Whether particle i of p carries the stamp v (the id aside). */
static int has_stamp(const pm_particles *p, size_t i, double v)
{
    int ok = 1;
    for (int d = 0; d < PM_DIM; d++)
        ok &= p->x[PM_DIM * i + d] == v + d && p->x0[PM_DIM * i + d] == v + 10 + d &&
              p->v[PM_DIM * i + d] == v + 20 + d && p->a[PM_DIM * i + d] == v + 30 + d &&
              p->hsize[PM_DIM * i + d] == v + 40 + d;
    ok &= p->mass[i] == v + 50 && p->vol[i] == v + 51 && p->vol0[i] == v + 52 && p->eps_p[i] == v + 53;
    for (int k = 0; k < PM_NF; k++)
        ok &= p->F[PM_NF * i + k] == v + 60 + k;
    for (int k = 0; k < PM_NS; k++)
        ok &= p->stress[PM_NS * i + k] == v + 70 + k;
    for (size_t k = 0; k < p->n_state; k++)
        ok &= p->state[p->n_state * i + k] == v + 80 + (double)k;
    ok &= p->material[i] == (int32_t)v + 1 && p->body[i] == (int32_t)v + 2 && p->cell[i] == (int32_t)v + 3;
    return ok;
}

static void capacity_and_ids(void **state)
{
    (void)state;
    pm_particles p;
    assert_int_equal(pm_particles_alloc_capacity(&p, 3, 10, 2), 0);
    assert_int_equal(p.n, 3);
    assert_int_equal(p.cap, 10);
    for (size_t i = 0; i < 3; i++)
        assert_int_equal(p.id[i], (int32_t)i);
    /* the room beyond n is there and zeroed */
    for (size_t i = 3; i < 10; i++)
        assert_true(p.mass[i] == 0 && p.state[2 * i + 1] == 0 && p.id[i] == 0);
    pm_particles_free(&p);
    assert_int_equal(pm_particles_alloc(&p, 4, 0), 0);
    assert_int_equal(p.cap, 4);
    pm_particles_free(&p);
}

static void copy_appends_whole_particles(void **state)
{
    (void)state;
    pm_particles p, q;
    assert_int_equal(pm_particles_alloc_capacity(&p, 2, 6, 3), 0);
    assert_int_equal(pm_particles_alloc(&q, 3, 3), 0);
    for (size_t i = 0; i < 2; i++)
        stamp(&p, i, 100.0 * (double)i);
    for (size_t i = 0; i < 3; i++) {
        stamp(&q, i, 1000.0 + 100.0 * (double)i);
        q.id[i] = 77;
    }
    double *x = p.x;
    pm_particles_copy(&p, p.n, &q, 1, 2);
    p.n += 2;
    assert_ptr_equal(p.x, x);
    assert_true(has_stamp(&p, 0, 0) && has_stamp(&p, 1, 100));
    assert_true(has_stamp(&p, 2, 1100) && has_stamp(&p, 3, 1200));
    assert_int_equal(p.id[2], 77);
    pm_particles_free(&p);
    pm_particles_free(&q);
}

static void remove_keeps_order_of_the_rest(void **state)
{
    (void)state;
    pm_particles p;
    assert_int_equal(pm_particles_alloc(&p, 7, 1), 0);
    for (size_t i = 0; i < 7; i++)
        stamp(&p, i, 100.0 * (double)i);
    const uint8_t none[7] = {0};
    assert_int_equal(pm_particles_remove(&p, none), 0);
    assert_int_equal(p.n, 7);
    const uint8_t drop[7] = {0, 1, 0, 0, 3, 1, 0};
    assert_int_equal(pm_particles_remove(&p, drop), 3);
    assert_int_equal(p.n, 4);
    const int kept[4] = {0, 2, 3, 6};
    for (size_t i = 0; i < 4; i++) {
        assert_true(has_stamp(&p, i, 100.0 * kept[i]));
        assert_int_equal(p.id[i], kept[i]);
    }
    const uint8_t all[4] = {1, 1, 1, 1};
    assert_int_equal(pm_particles_remove(&p, all), 4);
    assert_int_equal(p.n, 0);
    pm_particles_free(&p);
}

static void permute_moves_ids(void **state)
{
    (void)state;
    pm_particles p;
    assert_int_equal(pm_particles_alloc(&p, 4, 0), 0);
    for (size_t i = 0; i < 4; i++)
        stamp(&p, i, 100.0 * (double)i);
    const uint32_t perm[4] = {3, 1, 0, 2};
    double scratch[4];
    int32_t iscratch[4];
    pm_particles_permute(&p, perm, scratch, iscratch);
    for (size_t i = 0; i < 4; i++) {
        assert_true(has_stamp(&p, i, 100.0 * perm[i]));
        assert_int_equal(p.id[i], (int32_t)perm[i]);
    }
    pm_particles_free(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(capacity_and_ids),
        cmocka_unit_test(copy_appends_whole_particles),
        cmocka_unit_test(remove_keeps_order_of_the_rest),
        cmocka_unit_test(permute_moves_ids),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
