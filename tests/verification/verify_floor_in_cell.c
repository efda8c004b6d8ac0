/*
 * A cohesionless block slumping onto a rigid floor that cuts through a cell (an obstacle acting at the
 * touching particles, acts_at "particles", half a cell above a grid line), with FLIP: the points that
 * come to rest on the floor must stay the size they came to rest with.
 *
 * The block, 0.5 m x 0.25 m of the granular column's sand (Mohr-Coulomb, phi = 30 deg, no cohesion, no
 * dilatancy), stands free on the floor (mu = tan 30 deg) in cells of h = 1/16 m and slumps into a low
 * heap within about a second; by 2 s it is at rest. Its points then must neither grow nor move: with no
 * dilatancy and the heap at rest, a point's volume changes only elastically (its stress, a few kPa, over
 * the bulk modulus, 17 MPa: some 1e-4). Before the touching particles took the velocity the law let them move
 * with (src/contact/touching.c), the particles that had landed on the floor kept, in FLIP, the downward
 * velocity they landed with, the nodes below the floor carried it and their velocity gradient stretched
 * them without bound while they stayed put: the floor layer's largest point grew from 29 to 44 times its
 * volume between 2 and 3 s.
 *
 * Judged, from 2 s to 3 s:
 *  - the volume of the floor layer (the points whose centre lies within a cell of the floor) changes by
 *    less than 2 %: measured 0.24 %; the steady stretch above gave 18 %;
 *  - the largest point of the floor layer at 3 s is below 5 times its volume (its excess over it within
 *    4): the same block on the same obstacle lying on a grid line (no node below the floor carries
 *    material, so no such stretch) ends with its largest point of all 3.4 times its volume (4.7 before
 *    the fix), the loosening of the thin toe that FLIP leaves on any floor; measured 3.3, the broken
 *    run 44;
 *  - the heap's front (its farthest particle) moves by less than 1 % of a cell (at rest). This one the
 *    broken run passed as well: its points grew where they lay.
 */
#include "verify_util.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double H = 1.0 / 16, T_SETTLED = 2.0, T_END = 3.0;

static void make_case(pm_case *c)
{
    char text[4096];
    snprintf(text, sizeof text,
             "{ \"dimension\": 2, \"formulation\": \"plane_strain\","
             "  \"analysis\": { \"type\": \"explicit\", \"scheme\": \"musl\", \"end_time\": %g, \"cfl\": 0.2,"
             "                  \"gravity\": [0, -9.81] },"
             "  \"grid\": { \"type\": \"rectangle\", \"origin\": [0, %.17g], \"size\": [1.0, 0.5], \"cells\": [16, 8],"
             "             \"element\": \"quad4\" },"
             "  \"materials\": [ { \"name\": \"sand\", \"model\": \"mohr_coulomb\", \"density\": 1800,"
             "    \"youngs_modulus\": 2.0e7, \"poisson_ratio\": 0.3, \"cohesion\": 0, \"friction_angle\": 30,"
             "    \"dilatancy_angle\": 0 } ],"
             "  \"bodies\": [ { \"name\": \"block\", \"material\": \"sand\", \"particles_per_cell\": 2,"
             "    \"shape\": { \"type\": \"rectangle\", \"min\": [0.25, 0], \"max\": [0.75, 0.25] },"
             "    \"initial_stress\": \"geostatic\", \"k0\": 0.5, \"surface_y\": 0.25 } ],"
             "  \"obstacles\": [ { \"name\": \"floor\", \"type\": \"polyline\", \"points\": [[%.17g, 0], [%.17g, 0]],"
             "    \"material_side\": \"left\", \"friction\": %.17g, \"acts_at\": \"particles\" } ] }",
             T_END, -1.5 * H, -H, 1.0 + H, tan(M_PI / 6));
    if (pm_case_load_buffer(text, strlen(text), "floor_in_cell.json", c) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        exit(2);
    }
}

typedef struct {
    double layer;   /* volume of the points whose centre lies within a cell of the floor */
    double largest; /* their largest V / V0 */
    double front;   /* the farthest particle's x */
} floor_state;

static floor_state measure(const pm_sim *s)
{
    floor_state f = {0.0, 0.0, -INFINITY};
    for (size_t i = 0; i < s->p.n; i++) {
        f.front = fmax(f.front, s->p.x[PM_DIM * i]);
        if (s->p.x[PM_DIM * i + 1] >= H)
            continue;
        f.layer += s->p.vol[i];
        f.largest = fmax(f.largest, s->p.vol[i] / s->p.vol0[i]);
    }
    return f;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    pm_case c;
    make_case(&c);
    const double t0 = vu_now();
    pm_sim *s = vu_sim(&c, 1);
    int ok = vu_steps_until(s, T_END, T_SETTLED) == PM_OK;
    const floor_state a = measure(s);
    ok &= vu_steps_until(s, T_END, T_END) == PM_OK;
    const floor_state b = measure(s);
    const double secs = vu_now() - t0;
    if (!ok)
        fprintf(stderr, "step failed: %s\n", pm_error_message());
    printf("floor layer at %g s: volume %.6g m^2, largest V/V0 %.4g, front %.5f m; at %g s: %.6g, %.4g, %.5f m\n",
           T_SETTLED, a.layer, a.largest, a.front, T_END, b.layer, b.largest, b.front);
    const double growth = b.layer / a.layer - 1;
    ok &= vu_report("floor_in_cell", "floor layer's volume change from 2 to 3 s (relative)", growth, 0.0, growth,
                    0.02, secs);
    /* judged as its excess over the volume it started with: at most 4, i.e. below 5 times it */
    ok &= vu_report("floor_in_cell", "floor layer's largest V/V0 at 3 s", b.largest, 1.0, b.largest - 1.0, 4.0,
                    secs);
    const double creep = (b.front - a.front) / H;
    ok &= vu_report("floor_in_cell", "front's move from 2 to 3 s (cells)", creep, 0.0, creep, 0.01, secs);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return ok ? 0 : 1;
}
