/* Node cloud and cell-list neighbour search: every query equals a brute-force scan of the nodes
 * (exactly: the same set, since both compare the same squared distance with r^2), on uniform and
 * clustered random clouds, for radii from a fraction of the spacing to a large part of the cloud,
 * for query points inside and outside the cloud's box; the skin rule (no rebuild while every node
 * moved at most the skin, a rebuild as soon as one moved more, correct answers in both cases,
 * also for nodes that left the box of the last build); the adaptive radius of seed 000 section
 * 5.3; a cloud put back from a stored state (positions, positions at the last build, cell side)
 * holding the very cell list of the cloud it was stored from; and the error paths. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shape/cloud.h"
#include "pmech/error.h"
#include "pmech/particles.h"

static double rnd(unsigned *seed) { return (double)rand_r(seed) / RAND_MAX; }

/* @p n points uniformly random in the box [lo, lo + size], each point's x drawn before its y; the caller
 * frees them. */
static double *random_points(size_t n, const double lo[PM_DIM], const double size[PM_DIM], unsigned *seed)
{
    double *x = malloc(PM_DIM * n * sizeof *x);
    assert_non_null(x);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < PM_DIM; d++)
            x[PM_DIM * i + d] = lo[d] + size[d] * rnd(seed);
    return x;
}

static int cmp_i32(const void *a, const void *b)
{
    const int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* Brute force: every node with |x_I - x|^2 < r^2, ascending. */
static int brute(const pm_cloud *c, const double x[2], double r, int32_t *out)
{
    int n = 0;
    for (size_t i = 0; i < c->n; i++) {
        const double dx = c->x[2 * i] - x[0], dy = c->x[2 * i + 1] - x[1];
        if (dx * dx + dy * dy < r * r)
            out[n++] = (int32_t)i;
    }
    return n;
}

/* Compare nq random queries with brute force; returns the number of nodes found in total. */
static long check_queries(const pm_cloud *c, int nq, double rmax, unsigned seed)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < c->n; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], c->x[2 * i + k]);
            hi[k] = fmax(hi[k], c->x[2 * i + k]);
        }
    int32_t *a = malloc(c->n * sizeof *a), *b = malloc(c->n * sizeof *b);
    double *d2 = malloc(c->n * sizeof *d2);
    assert_non_null(a);
    assert_non_null(b);
    assert_non_null(d2);
    long total = 0;
    for (int q = 0; q < nq; q++) {
        /* points up to 20 % outside the box, so the clamped border cells are exercised */
        const double x[2] = {lo[0] + (hi[0] - lo[0]) * (1.4 * rnd(&seed) - 0.2),
                             lo[1] + (hi[1] - lo[1]) * (1.4 * rnd(&seed) - 0.2)};
        const double r = rmax * rnd(&seed);
        int n;
        assert_int_equal(pm_cloud_query(c, x, r, (int)c->n, a, d2, &n), PM_OK);
        const int nb = brute(c, x, r, b);
        assert_int_equal(n, nb);
        for (int i = 0; i < n; i++) {
            const double dx = c->x[2 * a[i]] - x[0], dy = c->x[2 * a[i] + 1] - x[1];
            assert_true(d2[i] == dx * dx + dy * dy);
        }
        qsort(a, (size_t)n, sizeof *a, cmp_i32);
        assert_memory_equal(a, b, (size_t)n * sizeof *a);
        total += n;
    }
    free(a);
    free(b);
    free(d2);
    return total;
}

static void matches_brute_force(void **state)
{
    (void)state;
    unsigned seed = 11;
    const size_t n = 3000;
    const double lo[PM_DIM] = {-1, 5}, size[PM_DIM] = {3, 2}; /* uniform in a 3 x 2 box */
    double *x = random_points(n, lo, size, &seed);
    pm_cloud *c;
    assert_int_equal(pm_cloud_create(n, x, NULL, NULL, &c), PM_OK);
    printf("uniform: h %.4f, cell %.4f, %d x %d cells\n", c->h, c->cell, c->nc[0], c->nc[1]);
    long found = check_queries(c, 2000, 0.4, 3);
    printf("uniform: %ld nodes found in 2000 queries\n", found);
    assert_true(found > 2000); /* the comparison is not vacuous */
    pm_cloud_destroy(c);
    /* clustered: most nodes in a small blob plus a few far away (the cell side is enlarged so
     * the cell array stays proportional to the node count) */
    for (size_t i = 0; i < n; i++) {
        const double rr = 0.05 * sqrt(rnd(&seed)), t = 2 * M_PI * rnd(&seed);
        x[2 * i] = rr * cos(t);
        x[2 * i + 1] = rr * sin(t);
    }
    x[0] = 1e3;
    x[1] = -1e3;
    pm_cloud_opts o = {.h = NAN, .cell_size = 0.01, .skin = 0.001};
    assert_int_equal(pm_cloud_create(n, x, NULL, &o, &c), PM_OK);
    printf("clustered: cell %.4g, %d x %d cells for %zu nodes\n", c->cell, c->nc[0], c->nc[1], n);
    assert_true((double)c->nc[0] * c->nc[1] <= 4.0 * n + 64);
    check_queries(c, 500, 0.03, 5);
    const double far[2] = {1e3, -1e3};
    int32_t one[4];
    int nf;
    assert_int_equal(pm_cloud_query(c, far, 1.0, 4, one, NULL, &nf), PM_OK);
    assert_int_equal(nf, 1);
    assert_int_equal(one[0], 0);
    pm_cloud_destroy(c);
    free(x);
}

static void skin_rule(void **state)
{
    (void)state;
    unsigned seed = 17;
    const size_t n = 1500;
    const double lo[PM_DIM] = {0, 0}, size[PM_DIM] = {2, 1};
    double *x = random_points(n, lo, size, &seed), *vol = malloc(n * sizeof *vol);
    assert_non_null(vol);
    for (size_t i = 0; i < n; i++)
        vol[i] = 2.0 / n;
    pm_cloud *c;
    assert_int_equal(pm_cloud_create(n, x, vol, NULL, &c), PM_OK);
    /* h from the volumes: sqrt(2 / n) */
    assert_true(fabs(c->h - sqrt(2.0 / n)) < 1e-15);
    assert_true(fabs(c->skin - 0.25 * c->h) < 1e-15);
    assert_int_equal((int)c->n_builds, 1);
    int rebuilt = -1;
    /* each node moves by at most 0.9 skin, all drifting towards +x so some leave the box of the
     * build: no rebuild, and queries near the new edge must still find them */
    for (int step = 0; step < 3; step++) {
        for (size_t i = 0; i < n; i++) {
            const double t = 2 * M_PI * rnd(&seed), m = (0.3 * step + 0.3) * c->skin * rnd(&seed);
            c->x[2 * i] = x[2 * i] + (0.3 * step + 0.3) * c->skin * 0.5 + 0.5 * m * cos(t);
            c->x[2 * i + 1] = x[2 * i + 1] + 0.5 * m * sin(t);
        }
        assert_int_equal(pm_cloud_update(c, &rebuilt), PM_OK);
        assert_int_equal(rebuilt, 0);
        assert_true(c->last_move <= c->skin);
        assert_true(c->last_move >= 0.5 * (0.3 * step + 0.3) * c->skin);
        check_queries(c, 400, 0.2, 19 + step);
    }
    assert_int_equal((int)c->n_builds, 1);
    /* one node jumps further than the skin: rebuild */
    c->x[2 * 7] += 1.01 * c->skin + c->last_move;
    assert_int_equal(pm_cloud_update(c, &rebuilt), PM_OK);
    assert_int_equal(rebuilt, 1);
    assert_int_equal((int)c->n_builds, 2);
    assert_true(c->last_move == 0);
    check_queries(c, 400, 0.2, 23);
    /* a NaN position is reported, not binned */
    c->x[2 * 9 + 1] = NAN;
    assert_int_equal(pm_cloud_update(c, &rebuilt), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "node 9"));
    pm_cloud_destroy(c);
    free(x);
    free(vol);
}

static void adaptive_radius(void **state)
{
    (void)state;
    unsigned seed = 29;
    const size_t n = 800;
    const double lo[PM_DIM] = {0, 0}, size[PM_DIM] = {1, 1};
    double *x = random_points(n, lo, size, &seed);
    pm_cloud *c;
    assert_int_equal(pm_cloud_create(n, x, NULL, NULL, &c), PM_OK);
    int32_t idx[64], ref[800];
    double d2[64];
    int grown = 0;
    for (int q = 0; q < 500; q++) {
        const double p[2] = {1.2 * rnd(&seed) - 0.1, 1.2 * rnd(&seed) - 0.1};
        const double r0 = 0.5 * c->h;
        int nf;
        double r;
        assert_int_equal(pm_cloud_query_adaptive(c, p, r0, 6, 1.25, 64, idx, d2, &nf, &r), PM_OK);
        assert_true(nf >= 6 && nf <= 64);
        assert_int_equal(brute(c, p, r, ref), nf);
        /* the radius is the first of r0 * 1.25^k that holds 6 nodes */
        if (r > r0) {
            grown++;
            assert_true(brute(c, p, r / 1.25 * (1 + 1e-12), ref) < 6);
        }
    }
    assert_true(grown > 250); /* r0 = h / 2 rarely holds 6 nodes: the rule was exercised */
    /* asking for more nodes than the cloud has is an error, not an endless loop */
    int nf;
    double r;
    const double p[2] = {0.5, 0.5};
    assert_int_equal(pm_cloud_query_adaptive(c, p, 0.1, 900, 1.25, 1000, ref, NULL, &nf, &r), PM_ESIM);
    /* the true count is reported when the buffer is too small */
    assert_int_equal(pm_cloud_query(c, p, 2.0, 10, idx, NULL, &nf), PM_OK);
    assert_int_equal(nf, (int)n);
    /* sorting by distance (ties by index) */
    int m;
    assert_int_equal(pm_cloud_query(c, p, 0.15, 64, idx, d2, &m), PM_OK);
    assert_true(m > 10);
    pm_cloud_sort_by_distance(m, idx, d2);
    for (int i = 1; i < m; i++)
        assert_true(d2[i - 1] < d2[i] || (d2[i - 1] == d2[i] && idx[i - 1] < idx[i]));
    pm_cloud_destroy(c);
    free(x);
}

/* Nodes drift by at most 0.8 skin per move, a node far out once makes the rebuild enlarge the cell
 * side; then a second cloud, created from the starting positions as a restarted run creates it, is
 * given the first one's positions, positions at the last build and cell side: its cell list must be
 * the first one's bit for bit (bounds, offsets, node order, the positions the queries scan), so that
 * queries return the same nodes in the same order. Positions farther than the skin from the stored
 * build are refused. */
static void restore_gives_the_same_cell_list(void **state)
{
    (void)state;
    unsigned seed = 31;
    const size_t n = 1200;
    const double lo[PM_DIM] = {0, 0}, size[PM_DIM] = {2, 1};
    double *x0 = random_points(n, lo, size, &seed);
    pm_cloud *a, *b;
    assert_int_equal(pm_cloud_create(n, x0, NULL, NULL, &a), PM_OK);
    const double cell0 = a->cell;
    for (int step = 0; step < 40; step++) {
        for (size_t i = 0; i < n; i++) {
            const double t = 2 * M_PI * rnd(&seed);
            a->x[2 * i] += 0.8 * a->skin * cos(t);
            a->x[2 * i + 1] += 0.8 * a->skin * sin(t);
        }
        if (step == 20) /* far enough that the cells of the box would outnumber the nodes 4 to 1 */
            a->x[0] = 400.0;
        assert_int_equal(pm_cloud_update(a, NULL), PM_OK);
    }
    assert_true(a->n_builds > 10);
    assert_true(a->cell > cell0); /* enlarged at the far node's rebuild */
    assert_int_equal(pm_cloud_create(n, x0, NULL, NULL, &b), PM_OK);
    assert_int_equal(pm_cloud_restore(b, a->x, a->x_built, a->cell, a->n_builds), PM_OK);
    assert_true(b->cell == a->cell && b->n_builds == a->n_builds);
    assert_true(b->lo[0] == a->lo[0] && b->lo[1] == a->lo[1]);
    assert_true(b->nc[0] == a->nc[0] && b->nc[1] == a->nc[1]);
    assert_memory_equal(b->start, a->start, ((size_t)a->nc[0] * (size_t)a->nc[1] + 1) * sizeof *a->start);
    assert_memory_equal(b->order, a->order, n * sizeof *a->order);
    assert_memory_equal(b->x_built, a->x_built, 2 * n * sizeof *a->x_built);
    assert_memory_equal(b->x_sorted, a->x_sorted, 2 * n * sizeof *a->x_sorted);
    assert_memory_equal(b->x, a->x, 2 * n * sizeof *a->x);
    int32_t ia[256], ib[256];
    for (int q = 0; q < 200; q++) {
        const double p[2] = {2 * rnd(&seed), rnd(&seed)};
        int na, nb;
        assert_int_equal(pm_cloud_query(a, p, 3 * a->h, 256, ia, NULL, &na), PM_OK);
        assert_int_equal(pm_cloud_query(b, p, 3 * b->h, 256, ib, NULL, &nb), PM_OK);
        assert_int_equal(na, nb);
        assert_true(na <= 256);
        assert_memory_equal(ia, ib, (size_t)na * sizeof *ia);
    }
    /* a node 1.5 skin away from where it was built: not a state any update leaves */
    double *moved = malloc(2 * n * sizeof *moved);
    assert_non_null(moved);
    memcpy(moved, a->x_built, 2 * n * sizeof *moved);
    moved[2 * 5] += 1.5 * a->skin;
    assert_int_equal(pm_cloud_restore(b, moved, a->x_built, a->cell, a->n_builds), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "farther than the skin"));
    assert_int_equal(pm_cloud_restore(b, moved, a->x_built, 0.0, a->n_builds), PM_EINPUT);
    free(moved);
    pm_cloud_destroy(a);
    pm_cloud_destroy(b);
    free(x0);
}

static void bad_input(void **state)
{
    (void)state;
    pm_cloud *c;
    double x[4] = {0, 0, 1, NAN};
    assert_int_equal(pm_cloud_create(0, x, NULL, NULL, &c), PM_EINPUT);
    assert_null(c);
    assert_int_equal(pm_cloud_create(2, x, NULL, NULL, &c), PM_EINPUT);
    x[3] = 1;
    const double vol[2] = {1, -1};
    assert_int_equal(pm_cloud_create(2, x, vol, NULL, &c), PM_EINPUT);
    assert_int_equal(pm_cloud_create(2, x, NULL, NULL, &c), PM_OK);
    const double q[2] = {NAN, 0};
    int32_t idx[2];
    int nf;
    assert_int_equal(pm_cloud_query(c, q, 1.0, 2, idx, NULL, &nf), PM_EINPUT);
    pm_cloud_destroy(c);
    pm_cloud_destroy(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(matches_brute_force),
        cmocka_unit_test(skin_rule),
        cmocka_unit_test(adaptive_radius),
        cmocka_unit_test(restore_gives_the_same_cell_list),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
