/*
 * The elastic block of verify_incline (0.2 m x 0.06 m, E = 1e7 Pa, nu = 0.3, density 1000, 2 x 2 points
 * per cell, MUSL at CFL 0.3) sliding with Coulomb friction mu = 0.3 on the y_min friction side of a quad
 * grid, gravity tilted by 25 degrees, on cells of h = 0.005 m: twice as fine as the incline tests. On
 * this grid the nodal Coulomb law at the touching points threw the block's front corner off the floor
 * at 0.038 s (+33 to +52 % at 0.1 s, the block bouncing 10-15 mm high): when the front column of points
 * crossed into the next cell, the node ahead carried 1e-3 of a point's mass, its end-of-step velocity was
 * tens of m/s (its force does not shrink with its mass), and the law read it with the point's full weight
 * and wrote its normal part back into the velocities the strains are taken from. Such a node now weighs
 * in by its mass over the particle's (friction.c; docs/verification-notes.md).
 *
 * Judged, with why:
 *  - the mean velocity along the slope at 0.1 s and 0.2 s against the rigid block's g (sin - mu cos) t
 *    within 2 % (issue 14's tolerance; the elastic block rings a little as it settles; frictionless is
 *    +180 %, and the thrown block +33 to +52 % at 0.1 s);
 *  - the energy the run makes: the block's kinetic, strain and gravitational energy minus their start,
 *    plus the work a rigid block's friction does over the same travel (mu W cos(theta) times the centre
 *    of mass's travel), is zero for the rigid answer, and a Coulomb law can only take energy out. Its
 *    largest value over the run must stay below 5 % of that friction work at the end: the elastic block
 *    rings on its side (strain energy 0.009 J at 0.1-0.2 s, forty times its static one, and about as
 *    much kinetic), energy a rigid block has not; its rise (below) lifts its weight by 0.02 J, 2 % of
 *    the friction work; and friction under a ringing bottom does a little less work than under a rigid
 *    one. Measured 4.2 %; the thrown block made 298 times the friction work; a block 5 % short
 *    of friction is also 9 % fast;
 *  - the rise of the centre of mass off the floor, largest over the run, below half a point spacing
 *    (0.25 h = 1.25 mm): the block stays on the floor (the thrown block rose 15 mm).
 * Expected to fail, and reported instead of judged: that rise below 0.01 h. The points' circles reach
 * 0.039 h = 0.19 mm past the floor as seeded (Gauss positions); the law lets a point approach only down
 * to a gap of zero and never pushes, so each time the ringing bottom lifts it cannot come back all the
 * way, and the block climbs by that overlap and stays there (measured 0.038 h). A point that
 * kept the overlap it first touched with, and could come back to it, removed the rise (0.0037 h) but
 * moved a silo's wall pressure out of its test's band (docs/verification-notes.md). The test exits 1
 * when the rise is below 0.01 h, so that the check is then judged.
 * MUSL is the scheme the incline tests use. The same block with USL is judged by the same three
 * criteria (velocity at 0.1 and 0.2 s within 2 %, energy made below 5 %, rise below 0.25 h): its strains
 * take the end-of-step nodal velocities, and the block diverged at 0.037 s when its front column of
 * points crossed x = 0.300 m (the node ahead at 2e-6 of a point's mass, 63 m/s, a strain of 0.16 in a
 * step at the front point); a node that light now gives USL's strain rate only part of its increment
 * (src/solver/explicit_grid.c).
 *
 * GMM (MLS) on the same grid (its nodes the grid's, moving with the material, the side a rigid wall), to
 * 0.2 s, judged as MPM is: velocity within 2 % at 0.1 s and 0.2 s, energy made below 5 % of the friction
 * work, rise below 0.25 h. Its wall acted node by node on the cloud's nodes until it acted at the touching
 * particles (src/contact/contact.h, pm_contact_takes_points): the bottom row of nodes then carried a wave
 * along the floor whose amplitude exceeded the sliding speed (0.02-0.16 m/s about 0.075 at 0.05 s), part
 * of the row stuck, slid backwards or lifted off while the rest slid, and the floor's friction fell to
 * 0.27-0.28 of its normal force: +6.1 % at 0.1 s, which fails the 2 %. Measured now: +0.17 % at 0.1 s,
 * +0.58 % at 0.2 s, the friction 0.300 of the normal force after 0.01 s, energy made 3.2 % of the
 * friction work, rise 0.039 h (the seeded overlap climbed out of, as MPM's).
 *
 * Small variant (PMECH_VERIFY_SMALL, for sanitizer builds): GMM to 0.1 s only, judged the same way at
 * 0.1 s (measured +0.17 %, energy made 2.8 % of the friction work by then, rise 0.01 h; node by node
 * +6.1 %, which still fails). The full test takes 40 s of CPU in the release build, three quarters of it
 * GMM's (26 s small).
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double G = 9.81, MU = 0.3, DEG = 25.0, H = 0.005;
static const char *B = "incline_fine";

/* What one run did, measured after every step. */
typedef struct fine_run {
    double th, mass, e0, x0[PM_DIM];
    double v_at[2];     /* mean velocity along the floor at 0.1 s and at the end */
    double travel;      /* the centre of mass's travel along the floor at the end */
    double rise;        /* largest rise of the centre of mass off the floor */
    double made;        /* largest energy made: E - E0 + mu W cos(theta) travel */
    double secs;
    int ok;
} fine_run;

static int each(pm_sim *s, void *ctx)
{
    fine_run *r = ctx;
    double v[PM_DIM], x[PM_DIM], k, u, g;
    vu_body_mean(s, 0, v, x);
    pm_sim_energy(s, &k, &u, &g);
    const double travel = x[0] - r->x0[0];
    r->rise = fmax(r->rise, x[1] - r->x0[1]);
    r->made = fmax(r->made, k + u + g - r->e0 + MU * r->mass * G * cos(r->th) * travel);
    if (s->t <= 0.1 + 1e-12)
        r->v_at[0] = v[0];
    r->v_at[1] = v[0];
    r->travel = travel;
    return 1;
}

static fine_run run(const char *method, const char *scheme, double t_end)
{
    fine_run r = {.th = DEG * M_PI / 180.0};
    char text[2048], how[96] = "";
    if (strcmp(method, "mpm"))
        snprintf(how, sizeof how, "\"method\": \"%s\", \"shape_function\": \"mls\",", method);
    snprintf(text, sizeof text,
             "{ \"dimension\": 2, %s \"analysis\": { \"type\": \"explicit\", \"scheme\": \"%s\", \"end_time\": %g,"
             "  \"cfl\": 0.3, \"gravity\": [%.12g, %.12g] },"
             "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, 0], \"size\": [0.5, 0.2], \"cells\": [%d, %d],"
             "             \"element\": \"quad4\" },"
             "  \"materials\": [ { \"name\": \"block\", \"model\": \"linear_elastic\", \"density\": 1000,"
             "                   \"youngs_modulus\": 1.0e7, \"poisson_ratio\": 0.3 } ],"
             "  \"bodies\": [ { \"name\": \"block\", \"material\": \"block\", \"particles_per_cell\": 2,"
             "    \"shape\": { \"type\": \"rectangle\", \"min\": [0.1, 0.0], \"max\": [0.3, 0.06] } } ],"
             "  \"boundary_conditions\": [ { \"type\": \"friction\", \"boundary\": \"y_min\", \"coefficient\": %g } ] }",
             how, scheme, t_end, G * sin(r.th), -G * cos(r.th), (int)lround(0.5 / H), (int)lround(0.2 / H), MU);
    pm_case c;
    if (pm_case_load_buffer(text, strlen(text), "incline_fine.json", &c) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(2);
    }
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    for (size_t i = 0; i < s->p.n; i++)
        r.mass += s->p.mass[i];
    double v[PM_DIM], k, u, g;
    vu_body_mean(s, 0, v, r.x0);
    pm_sim_energy(s, &k, &u, &g);
    r.e0 = k + u + g;
    r.ok = vu_run_each(s, t_end, each, &r);
    if (!r.ok)
        fprintf(stderr, "%s, %s: stopped at t = %g s\n", method, scheme, s->t);
    r.secs = vu_now() - t0;
    pm_sim_destroy(s);
    pm_case_free(&c);
    return r;
}

/* The checks every run gets: the velocity along the floor at the first @p n_ends of 0.1 and 0.2 s against
 * g (sin - mu cos) t = @p a t (2 %), the largest energy the run made against the rigid block's friction
 * work (5 %), and the largest rise off the floor (0.25 h). @p vel and @p who head the rows' names, @p when
 * says when the friction work is taken. Returns 1 if all pass. */
static int judge(const fine_run *r, const char *vel, const char *who, const char *when, int n_ends, double a)
{
    static const double ends[2] = {0.1, 0.2};
    char q[160];
    int ok = r->ok;
    for (int k = 0; k < n_ends; k++) {
        snprintf(q, sizeof q, "%s: velocity along the floor at %g s (m/s)", vel, ends[k]);
        ok &= vu_report(B, q, r->v_at[k], a * ends[k], r->v_at[k] / (a * ends[k]) - 1, 0.02, r->secs);
    }
    const double work = MU * r->mass * G * cos(r->th) * r->travel;
    snprintf(q, sizeof q, "%s: largest energy made over the run / rigid friction work %s", who, when);
    ok &= vu_report(B, q, r->made / work, 0, r->made / work, 0.05, r->secs);
    snprintf(q, sizeof q, "%s: largest rise of the centre of mass off the floor / h", who);
    ok &= vu_report(B, q, r->rise / H, 0, r->rise / H, 0.25, r->secs);
    return ok;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    const double a = G * (sin(DEG * M_PI / 180.0) - MU * cos(DEG * M_PI / 180.0));
    const fine_run m = run("mpm", "musl", 0.2);
    int ok = judge(&m, "MPM, h = 0.005 m, 25 deg, mu 0.3", "MPM", "at 0.2 s", 2, a);
    vu_report(B, "MPM: the same rise / h, expected to fail 0.01 h (the seeded overlap climbed out of, 0.039 h)",
              m.rise / H, 0, m.rise / H, -1, m.secs);
    if (m.rise / H <= 0.01) {
        printf("the block's rise is now below 0.01 h: judge it instead of expecting it to fail\n");
        ok = 0;
    }
    const fine_run u = run("mpm", "usl", 0.2);
    ok &= judge(&u, "MPM, usl", "MPM, usl", "at 0.2 s", 2, a);
    /* the small variant stops GMM at 0.1 s (see the top) */
    const int n_gmm = vu_small() ? 1 : 2;
    const fine_run f = run("gmm", "musl", n_gmm == 1 ? 0.1 : 0.2);
    ok &= judge(&f, "GMM-MLS, h = 0.005 m, 25 deg, mu 0.3", "GMM-MLS", "at the end", n_gmm, a);
    return ok ? 0 : 1;
}
