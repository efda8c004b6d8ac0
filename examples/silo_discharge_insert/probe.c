/*
 * Diagnostics of a silo discharge run (with or without the insert), one CSV row per 0.05 s window from
 * 0.1 s before the outlet opens: what leaves and from where, the state at the outlet, the insert's
 * load, and FLIP's hidden velocities.
 *
 * The hidden velocity of a point is its own velocity less the end-of-step grid velocity interpolated at
 * it, v_p - sum_I N_I(x_p) v_I. Positions move with the grid velocity, so a hidden velocity moves no
 * point until the grid it sits in changes (its neighbours leave, or it crosses into a cell of its own);
 * pure FLIP never damps it, a PIC share `flip` < 1 damps it by that factor every step, and APIC has none
 * (its particle velocity is the interpolated one). It is sampled every 10th step and reported for the
 * points at rest (grid speed below 0.02 m/s) and, among them, those within three cells of the floor.
 *
 * Columns: time after the opening; the last step; the whole silo's outflow rate W (kg/s) and the part of
 * it that started above z = 1 m (the insert's base) and beyond r = 0.4 m (outside the insert's shadow);
 * the points in the outlet's bottom cell row (r < 0.2 m): mean downward speed and density; the mean
 * density of the points in r < 0.4 m, z < 0.4 m above the outlet and their number; the hidden velocity at
 * rest (RMS, largest, largest upward), the points whose hidden speed exceeds 1 m/s, the same at rest
 * near the floor; the points rising faster than 0.5 m/s, the points above z = 0.3 m faster than 3 m/s;
 * the kinetic energy of the points' own velocities and of the interpolated ones (J, whole silo); the
 * insert's vertical force on the material (N, whole silo, mean over the window); the largest point
 * speed; the free surface's height on the axis and at the wall; the points under the insert's base
 * (r < 0.4 m, 0.8 < z < 1 m), and where the largest hidden velocity was (r, z, grid speed there).
 *
 * Build (from the top directory, after building libpmech.a in build/):
 *   cc -O2 -std=c11 -fopenmp -Iinclude -Isrc examples/silo_discharge_insert/probe.c build/libpmech.a \
 *      $(pkg-config --libs jansson cairo expat hdf5) -lumfpack -lcholmod -lsuitesparseconfig -lm -o probe
 * Run: OMP_NUM_THREADS=1 ./probe CASE.json T_END OUT.csv [T_OPEN]   (T_OPEN defaults to 1 s)
 * probe_table.py turns the CSV into the 0.2 s windows of the README.
 */
#define _DEFAULT_SOURCE /* M_PI */

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/sim.h"
#include "solver/sim_internal.h"
#include "solver/flow.h"
#include "contact/contact.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define WINDOW 0.05
#define REST 0.02
#define SAMPLE 10

/* What one particle id started as: height, radius, mass; 1 while it is in the run. */
typedef struct {
    double *z0, *r0, *m;
    char *alive, *seen;
    int32_t n;
} ledger;

/* Sums over the sampled steps of one window. */
typedef struct {
    double hid2, hidmax, hidup, floor2, floormax, out_v, out_rho, zone_rho, ke_p, ke_g, vmax, z_axis, z_wall,
        under, top, where[PM_DIM], where_g;
    long rest, hid1, floor, out, zone, up, far, samples;
} window;

static double step_size(const pm_sim *s)
{
    if (s->c->analysis.dt > 0)
        return s->c->analysis.dt;
    if (s->step == 0 || !(s->max_wave > 0))
        return pm_sim_stable_dt(s);
    return s->c->analysis.cfl * s->grid.h_min / s->max_wave;
}

/* Mass that left since the last call, and the parts that started above the insert and far out. */
static void departures(const pm_sim *s, ledger *l, double *above, double *far)
{
    for (int32_t k = 0; k < l->n; k++)
        l->seen[k] = 0;
    for (size_t i = 0; i < s->p.n; i++)
        l->seen[s->p.id[i]] = 1;
    for (int32_t k = 0; k < l->n; k++)
        if (l->alive[k] && !l->seen[k]) {
            l->alive[k] = 0;
            *above += l->z0[k] > 1.0 ? l->m[k] : 0.0;
            *far += l->r0[k] > 0.4 ? l->m[k] : 0.0;
        }
}

static void sample(pm_sim *s, window *w)
{
    if (s->approx->ops->connect(s->approx, &s->p) != PM_OK)
        return;
    const pm_particles *p = &s->p;
    const double h = s->grid.h_min;
    double z_axis = 0, z_wall = 0;
    for (size_t i = 0; i < p->n; i++) {
        pm_stencil st;
        if (pm_approx_eval(s->approx, p, i, &st) != PM_OK)
            continue;
        double vg[PM_DIM] = {0}, hid[PM_DIM], h2 = 0, g2 = 0, p2 = 0;
        for (int k = 0; k < st.n; k++)
            for (int d = 0; d < PM_DIM; d++)
                vg[d] += st.N[k] * s->nd.vel_new[PM_DIM * st.node[k] + d];
        const double *v = p->v + PM_DIM * i, *x = p->x + PM_DIM * i;
        for (int d = 0; d < PM_DIM; d++) {
            hid[d] = v[d] - vg[d];
            h2 += hid[d] * hid[d];
            g2 += vg[d] * vg[d];
            p2 += v[d] * v[d];
        }
        const double hm = sqrt(h2), speed = sqrt(p2);
        w->ke_p += 0.5 * p->mass[i] * p2;
        w->ke_g += 0.5 * p->mass[i] * g2;
        w->vmax = fmax(w->vmax, speed);
        if (sqrt(g2) < REST) {
            w->rest++;
            w->hid2 += h2;
            w->hidmax = fmax(w->hidmax, hm);
            w->hidup = fmax(w->hidup, hid[1]);
            if (x[1] < 3 * h) {
                w->floor++;
                w->floor2 += h2;
                w->floormax = fmax(w->floormax, hm);
            }
        }
        if (hm > w->top) { /* where the largest hidden speed of the window is */
            w->top = hm;
            w->where[0] = x[0];
            w->where[1] = x[1];
            w->where_g = sqrt(g2);
        }
        w->hid1 += hm > 1.0;
        w->up += v[1] > 0.5;
        w->far += speed > 3.0 && x[1] > 0.3;
        if (x[0] < 0.2 && x[1] < h) {
            w->out++;
            w->out_v -= v[1];
            w->out_rho += p->mass[i] / p->vol[i];
        }
        if (x[0] < 0.4 && x[1] < 0.4) {
            w->zone++;
            w->zone_rho += p->mass[i] / p->vol[i];
        }
        w->under += x[0] < 0.4 && x[1] > 0.8 && x[1] < 1.0;
        if (x[0] < 0.1)
            z_axis = fmax(z_axis, x[1]);
        if (x[0] > 0.9)
            z_wall = fmax(z_wall, x[1]);
    }
    w->z_axis += z_axis;
    w->z_wall += z_wall;
    w->samples++;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: probe CASE.json T_END OUT.csv [T_OPEN]\n");
        return 2;
    }
    const double t_end = atof(argv[2]), t_open = argc > 4 ? atof(argv[4]) : 1.0;
    pm_case c;
    pm_sim *s = NULL;
    if (pm_case_load(argv[1], &c) != PM_OK || pm_sim_create(&c, &s, 1) != PM_OK) {
        fprintf(stderr, "%s\n", pm_error_message());
        return 2;
    }
    FILE *o = fopen(argv[3], "w");
    ledger l = {0};
    for (size_t i = 0; i < s->p.n; i++)
        l.n = s->p.id[i] + 1 > l.n ? s->p.id[i] + 1 : l.n;
    l.z0 = calloc((size_t)l.n, sizeof *l.z0);
    l.r0 = calloc((size_t)l.n, sizeof *l.r0);
    l.m = calloc((size_t)l.n, sizeof *l.m);
    l.alive = calloc((size_t)l.n, 1);
    l.seen = calloc((size_t)l.n, 1);
    int rc = 0;
    if (!o || !l.z0 || !l.r0 || !l.m || !l.alive || !l.seen) {
        fprintf(stderr, "cannot open %s or out of memory\n", argv[3]);
        rc = 1;
        goto done;
    }
    for (size_t i = 0; i < s->p.n; i++) {
        const int32_t k = s->p.id[i];
        l.r0[k] = s->p.x[PM_DIM * i];
        l.z0[k] = s->p.x[PM_DIM * i + 1];
        l.m[k] = s->p.mass[i];
        l.alive[k] = 1;
    }
    long insert = -1; /* the case's obstacle, if any */
    for (size_t k = 0; k < pm_contact_n_surfaces(s->contact); k++)
        if (s->contact->surface[k].obstacle >= 0)
            insert = (long)k;
    fprintf(o, "t,dt,W,W_above_insert,W_r0gt04,outlet_vz,outlet_rho,zone_rho,zone_n,hid_rms_rest,hid_max_rest,"
               "hid_up_max_rest,n_hid_gt1,hid_rms_floor,hid_max_floor,n_fast_up,n_fast_far,ke_p,ke_g,insert_fy,"
               "max_speed,z_surface_axis,z_surface_wall,under_cone_n,hidmax_r,hidmax_z,hidmax_vg\n");
    double last = 0, gone = 0, above = 0, far = 0, gone0 = 0, above0 = 0, far0 = 0;
    const double tw = t_open - 2 * WINDOW;
    while (s->t < tw - 1e-12) {
        const double dt = fmin(step_size(s), tw - s->t);
        if (pm_explicit_step(s, dt) != PM_OK) {
            fprintf(stderr, "%s\n", pm_error_message());
            rc = 1;
            goto done;
        }
    }
    while (s->t < t_end - 1e-9) {
        const double t1 = s->t + WINDOW;
        window w = {0};
        double fy = 0, dt = 0;
        for (long n = 1; s->t < t1 - 1e-12; n++) {
            const size_t before = s->p.n;
            dt = fmin(step_size(s), t1 - s->t);
            if (pm_explicit_step(s, dt) != PM_OK) {
                fprintf(stderr, "%s\n", pm_error_message());
                rc = 1;
                goto done;
            }
            pm_contact_force f;
            if (insert >= 0 && pm_contact_force_of(s->contact, (size_t)insert, &f) == PM_OK)
                fy += f.force[1] * dt;
            if (s->p.n < before)
                departures(s, &l, &above, &far);
            if (n % SAMPLE == 0)
                sample(s, &w);
        }
        gone = 0;
        for (int32_t k = 0; k < l.n; k++)
            gone += l.alive[k] ? 0.0 : l.m[k];
        /* the sink counts mass per radian, as the points carry it */
        const double removed = 2 * M_PI * s->flow->snk[0].removed_mass, W = (removed - last) / WINDOW;
        const double dg = gone - gone0, ns = w.samples > 0 ? (double)w.samples : 1.0;
        fprintf(o,
                "%.3f,%.3e,%.1f,%.1f,%.1f,%.3f,%.1f,%.1f,%.0f,%.4f,%.3f,%.3f,%.1f,%.4f,%.3f,%.1f,%.1f,%.4g,%.4g,"
                "%.1f,%.2f,%.3f,%.3f,%.1f,%.3f,%.3f,%.3f\n",
                s->t - t_open, dt, W, dg > 0 ? W * (above - above0) / dg : 0.0, dg > 0 ? W * (far - far0) / dg : 0.0,
                w.out ? w.out_v / (double)w.out : 0.0, w.out ? w.out_rho / (double)w.out : 0.0,
                w.zone ? w.zone_rho / (double)w.zone : 0.0, (double)w.zone / ns,
                w.rest ? sqrt(w.hid2 / (double)w.rest) : 0.0, w.hidmax, w.hidup, (double)w.hid1 / ns,
                w.floor ? sqrt(w.floor2 / (double)w.floor) : 0.0, w.floormax, (double)w.up / ns, (double)w.far / ns,
                2 * M_PI * w.ke_p / ns, 2 * M_PI * w.ke_g / ns, 2 * M_PI * fy / WINDOW, w.vmax, w.z_axis / ns,
                w.z_wall / ns, w.under / ns, w.where[0], w.where[1], w.where_g);
        fflush(o);
        last = removed;
        gone0 = gone;
        above0 = above;
        far0 = far;
    }
done:
    if (o)
        fclose(o);
    free(l.z0);
    free(l.r0);
    free(l.m);
    free(l.alive);
    free(l.seen);
    pm_sim_destroy(s);
    pm_case_free(&c);
    return rc;
}
