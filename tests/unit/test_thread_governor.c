/* The thread governor (src/solver/thread_governor.c) on synthetic step times: it moves to one thread
 * when one thread is faster (a busy machine), stays when the threads pay, comes back when the load goes,
 * and its trials of the losing count cost little over a long run. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "solver/thread_governor.h"

/* Run @p steps steps whose time is t1 on one thread and tn on more; returns the steps run on the slower. */
static long run(pm_thread_gov *g, pm_sim *s, long steps, double t1, double tn)
{
    long slow = 0;
    for (long k = 0; k < steps; k++) {
        pm_thread_gov_before(g, s);
        const int one = s->nd.n_threads == 1;
        slow += one ? t1 > tn : tn > t1;
        pm_thread_gov_after(g, one ? t1 : tn);
    }
    return slow;
}

static void setup(pm_thread_gov *g, pm_sim *s, int active)
{
    memset(s, 0, sizeof *s);
    s->nd.n_threads = 2;
    pm_thread_gov_init(g, s, active);
}

static void moves_to_one_thread_when_that_is_faster(void **state)
{
    (void)state;
    pm_thread_gov g;
    pm_sim s;
    setup(&g, &s, 1);
    run(&g, &s, 100, 1.0, 7.0); /* the busy machine of the report: two threads 7 times slower */
    assert_int_equal(g.cur, 1);
    /* over a long run the trials on two threads are a small part of the steps */
    const long slow = run(&g, &s, 20000, 1.0, 7.0);
    assert_int_equal(g.cur, 1);
    assert_true(slow < 20000 / 100);
    assert_int_equal(pm_thread_gov_main_count(&g), 1);
}

static void stays_when_threads_pay_and_returns_when_load_goes(void **state)
{
    (void)state;
    pm_thread_gov g;
    pm_sim s;
    setup(&g, &s, 1);
    long slow = run(&g, &s, 20000, 1.0, 0.55); /* an idle machine: two threads 1.8 times faster */
    assert_int_equal(g.cur, 2);
    assert_true(slow < 20000 / 100);
    run(&g, &s, 20000, 1.0, 3.0); /* another program starts */
    assert_int_equal(g.cur, 1);
    run(&g, &s, 20000, 1.0, 0.55); /* and stops */
    assert_int_equal(g.cur, 2);
    assert_int_equal(g.switches, 2);
}

static void ignores_small_differences(void **state)
{
    (void)state;
    pm_thread_gov g;
    pm_sim s;
    setup(&g, &s, 1);
    run(&g, &s, 5000, 1.0, 1.02); /* within 5 %: no change */
    assert_int_equal(g.cur, 2);
    assert_int_equal(g.switches, 0);
}

static void a_chosen_count_is_kept(void **state)
{
    (void)state;
    pm_thread_gov g;
    pm_sim s;
    setup(&g, &s, 0);
    run(&g, &s, 1000, 1.0, 7.0);
    assert_int_equal(s.nd.n_threads, 2);
    assert_int_equal(pm_thread_gov_main_count(&g), 2);
    s.nd.n_threads = 1;
    pm_thread_gov_init(&g, &s, 1); /* one thread given: nothing to choose */
    assert_int_equal(g.active, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(moves_to_one_thread_when_that_is_faster),
        cmocka_unit_test(stays_when_threads_pay_and_returns_when_load_goes),
        cmocka_unit_test(ignores_small_differences),
        cmocka_unit_test(a_chosen_count_is_kept),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
