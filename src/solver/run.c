/* The time loop of a whole run: steps, outputs at their cadence, progress, run.json. */
#include "sim_internal.h"
#include "solver/grid_output.h"
#include "solver/run_checks.h"
#include "solver/run_warnings.h"
#include "solver/thread_governor.h"
#include "flow.h"
#include "forces_log.h"
#include "walls_log.h"
#include "contact/multibody.h"
#include "pmech/error.h"
#include "solver/implicit.h"
#include "io/checkpoint.h"
#include "io/output.h"
#include "io/progress.h"

#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Below this many particles a run uses one thread unless --threads or OMP_NUM_THREADS says otherwise. */
#define PM_PARTICLES_PER_THREAD_MIN 5000

/* Step size for the next step: fixed, or cfl * h / (c + |v|) from the last stress update. */
static double next_dt(const pm_sim *s)
{
    const pm_case *c = s->c;
    if (c->analysis.type == PM_ANALYSIS_QUASI_STATIC)
        return c->analysis.end_time / c->analysis.load_steps;
    if (c->analysis.type == PM_ANALYSIS_IMPLICIT && c->analysis.dt <= 0)
        return pm_sim_stable_dt(s);
    if (c->analysis.dt > 0)
        return c->analysis.dt;
    if (s->step == 0 || !(s->max_wave > 0))
        return pm_sim_stable_dt(s);
    return c->analysis.cfl * s->grid.h_min / s->max_wave;
}

/* One output frame: the VTU (and PVD) and, when asked for, a PNG picture of the same state. */
static int write_frame(pm_output *out, const pm_sim *s, const char *dir, int *frame)
{
    (void)dir;
    pm_check(pm_output_frame(out, s->t, &s->p));
    pm_check(pm_sim_grid_frame(out, s));
    (*frame)++;
    return PM_OK;
}

/* Implicit runs also write newton.log (every iteration's residual) and reactions.csv (the summed
 * reaction of each fixed or velocity condition after every step). */
typedef struct implicit_files {
    FILE *log, *reactions;
    pm_implicit_report total;
} implicit_files;

static int open_implicit_files(implicit_files *f, const pm_case *c, const char *dir, int verbose)
{
    memset(f, 0, sizeof *f);
    if (c->analysis.type == PM_ANALYSIS_EXPLICIT)
        return PM_OK;
    char path[PM_PATH_MAX + 32];
    if (verbose) {
        f->log = stderr;
    } else if (dir) {
        snprintf(path, sizeof path, "%s/newton.log", dir);
        f->log = fopen(path, "w");
        if (!f->log)
            return pm_error_set(PM_EIO, "%s: cannot write", path);
    }
    if (dir) {
        snprintf(path, sizeof path, "%s/reactions.csv", dir);
        f->reactions = fopen(path, "w");
        if (!f->reactions)
            return pm_error_set(PM_EIO, "%s: cannot write", path);
        fprintf(f->reactions, "time");
        for (size_t b = 0; b < c->n_bcs; b++) {
            const pm_case_bc *bc = &c->bcs[b];
            if (bc->type == PM_BC_FRICTION)
                continue;
            char name[PM_NAME_MAX + 16];
            if (bc->line_axis >= 0)
                snprintf(name, sizeof name, "%c=%g", bc->line_axis ? 'y' : 'x', bc->line_value);
            else
                snprintf(name, sizeof name, "%s", bc->boundary);
            fprintf(f->reactions, ",%s.Rx,%s.Ry", name, name);
        }
        fprintf(f->reactions, "\n");
        fflush(f->reactions);
    }
    return PM_OK;
}

static void close_implicit_files(implicit_files *f)
{
    if (f->log && f->log != stderr)
        fclose(f->log);
    if (f->reactions)
        fclose(f->reactions);
}

static int implicit_step(pm_sim *s, double dt, implicit_files *f)
{
    pm_implicit_report rep;
    int rc = pm_implicit_step(s, dt, f->log, &rep);
    f->total.iterations += rep.iterations;
    f->total.step_cuts += rep.step_cuts;
    f->total.assemble_seconds += rep.assemble_seconds;
    f->total.solve_seconds += rep.solve_seconds;
    if (rc || !f->reactions)
        return rc;
    fprintf(f->reactions, "%.10g", s->t);
    for (size_t b = 0; b < s->c->n_bcs; b++) {
        if (s->c->bcs[b].type == PM_BC_FRICTION)
            continue;
        double R[2];
        pm_implicit_reaction(s, b, R);
        fprintf(f->reactions, ",%.10g,%.10g", R[0], R[1]);
    }
    fprintf(f->reactions, "\n");
    return fflush(f->reactions) == 0 ? PM_OK : pm_error_set(PM_EIO, "reactions.csv: write failed");
}

static int write_energy(pm_output *out, const pm_sim *s)
{
    double ke, se, ge;
    pm_sim_energy(s, &ke, &se, &ge);
    return pm_output_energy(out, s->t, ke, se, ge);
}

static const char *signal_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

static double max_displacement(const pm_particles *p)
{
    double m2 = 0;
    for (size_t i = 0; i < p->n; i++) {
        const double dx = p->x[2 * i] - p->x0[2 * i], dy = p->x[2 * i + 1] - p->x0[2 * i + 1];
        m2 = fmax(m2, dx * dx + dy * dy);
    }
    return sqrt(m2);
}

/* The next time of a cadence after time t: computed, not stepped, since adding an interval below the
 * spacing of doubles near t would leave it where it is for ever. */
static double next_time(double next, double t, double interval, double eps)
{
    next = fmax(next, interval * (floor((t + eps) / interval) + 1));
    if (next <= t + eps)
        next = t + interval > t ? t + interval : nextafter(t, INFINITY);
    return next;
}

static int write_checkpoint(pm_ck_run *r, const char *dir, const implicit_files *imf)
{
    if (!r->enabled)
        return PM_OK;
    if (pm_checkpoint_covers(r->s) != PM_OK) {
        pm_error_clear(); /* such runs write no checkpoint; --restart says why */
        return PM_OK;
    }
    pm_run_loop *loop = (pm_run_loop *)r->loop;
    loop->newton_iterations = imf->total.iterations;
    loop->step_cuts = imf->total.step_cuts;
    loop->assemble_seconds = imf->total.assemble_seconds;
    loop->solve_seconds = imf->total.solve_seconds;
    return pm_checkpoint_write(dir, r);
}

/* The case's identity for its checkpoints and, with --restart, the state they hold put back. */
static int run_resume_begin(const pm_run_opts *o, pm_sim *s, pm_checkpoint **ck, pm_run_loop *loop,
                            pm_ck_run *ckr)
{
    if (!o->restart) {
        /* a case built in memory has no file to identify it by: such runs write no checkpoint */
        ckr->enabled = pm_checkpoint_case_hash(s->c->file, &ckr->case_hash) == PM_OK;
        pm_error_clear();
        return PM_OK;
    }
    pm_check(pm_checkpoint_case_hash(s->c->file, &ckr->case_hash));
    ckr->enabled = 1;
    pm_check(pm_checkpoint_open(ck, o->restart, s));
    char warning[PM_WARNING_LEN];
    int rc = pm_checkpoint_restore_state(*ck, s, loop, s->nd.n_threads, warning, sizeof warning);
    if (!rc && warning[0] && !o->quiet)
        fprintf(stderr, "pmech: warning: %s\n", warning);
    if (!rc)
        rc = pm_checkpoint_logs_aside(*ck);
    return rc;
}

int pm_run(const pm_case *c, const pm_run_opts *o, pm_sim **out_sim)
{
    const double wall0 = pm_wall_seconds();
    if (out_sim)
        *out_sim = NULL;
    int threads = o->threads > 0 ? o->threads : omp_get_max_threads();
    pm_sim *s = NULL;
    pm_check(pm_sim_create(c, &s, threads));
    int rc = pm_run_check_start(s);
    if (rc) {
        pm_sim_destroy(s);
        return rc;
    }
    if (o->threads <= 0 && !getenv("OMP_NUM_THREADS") && s->p.n < PM_PARTICLES_PER_THREAD_MIN) {
        /* A step of a few thousand particles takes tens of microseconds: the barriers between its
         * passes would cost more than a second thread gains, and far more when another process holds
         * a core. Small runs use one thread unless the user asks for more (the column collapse, 12,800 points,
         * already runs 1.8 times faster on two idle cores). */
        threads = 1;
        s->nd.n_threads = 1;
        s->approx->n_threads = 1;
    }
    /* a thread count nobody chose is checked against one thread as the run goes (explicit runs) */
    pm_thread_gov gov;
    pm_thread_gov_init(&gov, s, o->threads <= 0 && !getenv("OMP_NUM_THREADS") &&
                                    c->analysis.type == PM_ANALYSIS_EXPLICIT);
    pm_run_warnings warn;
    pm_run_warnings_begin(&warn, c, o->quiet);
    pm_output *out = NULL;
    int frame = 0;
    const char *dir = o->restart ? o->restart : o->out_dir ? o->out_dir : c->output.directory;
    const double end = c->analysis.end_time, interval = c->output.interval;
    const double eps = 1e-12 * end, ck_every = c->output.checkpoint_interval;
    pm_run_loop loop = {.next_frame = interval, .next_energy = interval / 20, .dt_min = INFINITY,
                        .next_checkpoint = ck_every > 0 ? ck_every : INFINITY};
    pm_checkpoint *ck = NULL;
    pm_ck_run ckr = {.s = s, .loop = &loop, .threads = threads};
    if (o->write_output)
        rc = run_resume_begin(o, s, &ck, &loop, &ckr);
    if (!rc && o->write_output) {
        rc = ck ? pm_output_open_resume(&out, dir, c, pm_sim_frame_grid(s), &s->p)
                : pm_output_open(&out, dir, c, pm_sim_frame_grid(s), &s->p);
        if (!rc && !ck)
            rc = write_frame(out, s, dir, &frame);
        if (!rc && !ck)
            rc = pm_output_probes(out, 0.0, &s->p);
        if (!rc && !ck)
            rc = write_energy(out, s);
    }
    if (rc) {
        pm_checkpoint_close(ck);
        pm_output_close(out, NULL);
        pm_sim_destroy(s);
        return rc;
    }
    implicit_files imf;
    rc = open_implicit_files(&imf, c, o->write_output ? dir : NULL, o->verbose);
    imf.total.iterations = loop.newton_iterations;
    imf.total.step_cuts = loop.step_cuts;
    imf.total.assemble_seconds = loop.assemble_seconds;
    imf.total.solve_seconds = loop.solve_seconds;
    pm_flow_log flog = {0};
    if (!rc && out)
        rc = pm_flow_log_open(&flog, s, dir);
    pm_forces_log forces = {0};
    if (!rc && out)
        rc = pm_forces_log_open(&forces, s, dir);
    pm_walls_log walls = {0};
    if (!rc && out)
        rc = pm_walls_log_open(&walls, s, dir);
    if (!rc && out && s->mb)
        rc = pm_multibody_log_open(s->mb, c, dir);
    pm_ck_logs logs = {0};
    pm_ck_logs_add(&logs, "newton.log", &imf.log);
    pm_ck_logs_add(&logs, "reactions.csv", &imf.reactions);
    pm_ck_logs_add(&logs, "releases.csv", &flog.releases);
    pm_ck_logs_add(&logs, "removals.csv", &flog.removals);
    pm_ck_logs_add(&logs, "forces.csv", &forces.f);
    for (size_t w = 0; w < walls.n; w++) /* as many as the checkpoint keeps */
        if (walls.wall[w].f)
            pm_ck_logs_add(&logs, strrchr(walls.wall[w].csv, '/') + 1, &walls.wall[w].f);
    if (s->mb)
        pm_ck_logs_add(&logs, "contact_forces.csv", &s->mb->log);
    ckr.out = out;
    ckr.forces = &forces;
    ckr.walls_t_last = walls.n ? &walls.t_last : NULL;
    ckr.logs = &logs;
    if (!rc && ck)
        rc = pm_checkpoint_restore_outputs(ck, s, out, &forces, walls.n ? &walls.t_last : NULL, &logs);
    pm_checkpoint_close(ck);
    pm_progress pg;
    pm_progress_begin(&pg, stderr, end, o->quiet || o->verbose);
    while (!rc && s->t < end - eps) {
        /* the last step is cut to land on the end time: it says nothing of the run's stability, so
         * the step-size warning and the smallest-step figure follow the step the solver asked for */
        const double dt_stable = next_dt(s);
        double dt = dt_stable;
        if (s->t + dt > end)
            dt = end - s->t;
        if (!(dt > 0) || !isfinite(dt)) {
            rc = pm_error_set(PM_ESIM, "step %ld (t = %.6g s): the stable time step is %g: the run diverged",
                              s->step + 1, s->t, dt);
            break;
        }
        pm_thread_gov_before(&gov, s);
        const double w0 = pm_wall_seconds();
        const double n_before = (double)s->p.n;
        rc = c->analysis.type == PM_ANALYSIS_EXPLICIT ? pm_explicit_step(s, dt) : implicit_step(s, dt, &imf);
        const double w1 = pm_wall_seconds();
        loop.loop_seconds += w1 - w0;
        pm_thread_gov_after(&gov, w1 - w0);
        if (rc)
            break;
        loop.particle_steps += n_before; /* the count changes with sources and sinks */
        if (s->mb)
            pm_multibody_log_step(s->mb, dt);
        if (out && (rc = pm_flow_log_step(&flog, s)) != PM_OK)
            break;
        if (out && (rc = pm_forces_log_step(&forces, s, s->t >= end - eps)) != PM_OK)
            break;
        loop.dt_min = fmin(loop.dt_min, dt_stable);
        loop.dt_max = fmax(loop.dt_max, dt_stable);
        pm_run_warnings_step(&warn, s->step, s->t, dt_stable);
        if (out) {
            rc = pm_output_probes(out, s->t, &s->p);
            if (!rc && s->t >= loop.next_energy - eps) {
                rc = write_energy(out, s);
                if (!rc && s->mb)
                    rc = pm_multibody_log_row(s->mb, c, s->t);
                loop.next_energy += interval / 20;
            }
            if (!rc && s->t >= loop.next_frame - eps && s->t < end - eps) {
                rc = write_frame(out, s, dir, &frame);
                if (!rc)
                    rc = pm_walls_log_frame(&walls, s);
                loop.last_frame_t = s->t;
                loop.next_frame = next_time(loop.next_frame, s->t, interval, eps);
            }
            if (!rc && s->t >= loop.next_checkpoint - eps && s->t < end - eps) {
                loop.next_checkpoint = next_time(loop.next_checkpoint, s->t, ck_every, eps);
                rc = write_checkpoint(&ckr, dir, &imf);
            }
            if (rc)
                break;
        }
        pm_progress_update(&pg, s->step, s->t, loop.loop_seconds, loop.particle_steps);
        if (o->interrupt && *o->interrupt) {
            /* the state after a whole step: what a restart continues from */
            if (out && (rc = write_checkpoint(&ckr, dir, &imf)) != PM_OK)
                break;
            rc = pm_error_set(PM_EINTR, "interrupted by %s after step %ld (t = %.6g s)", signal_name(*o->interrupt),
                              s->step, s->t);
            break;
        }
    }
    if (!rc && out && loop.last_frame_t < s->t) {
        rc = write_frame(out, s, dir, &frame);
        /* read by the checkpoint below (through ckr.loop): a restart from it must not write this frame again */
        // cppcheck-suppress unreadVariable
        loop.last_frame_t = s->t;
        if (!rc)
            rc = pm_walls_log_frame(&walls, s);
        if (!rc)
            rc = write_energy(out, s);
    } else if (rc == PM_ESIM && out && c->analysis.type != PM_ANALYSIS_EXPLICIT && loop.last_frame_t < s->t) {
        /* A failed implicit step restores the start-of-step state, the last equilibrium found: worth a
         * frame, since it shows the mechanism that stopped the run. The error stays the run's result. */
        char msg[2048];
        snprintf(msg, sizeof msg, "%s", pm_error_message());
        if (write_frame(out, s, dir, &frame) == PM_OK)
            write_energy(out, s);
        pm_error_set(rc, "%s", msg);
    }
    if (!rc && out)
        rc = write_checkpoint(&ckr, dir, &imf);
    if (o->stats) {
        pm_run_stats *st = o->stats;
        st->t = s->t;
        st->steps = s->step;
        st->newton_iterations = imf.total.iterations;
        st->step_cuts = imf.total.step_cuts;
        st->max_displacement = max_displacement(&s->p);
        st->wall_seconds = pm_wall_seconds() - wall0;
    }
    pm_progress_end(&pg, s->step, s->t, loop.loop_seconds, loop.particle_steps);
    close_implicit_files(&imf);
    int rc_log = pm_flow_log_close(&flog);
    if (!rc && rc_log)
        rc = rc_log;
    rc_log = pm_forces_log_close(&forces);
    if (!rc && rc_log)
        rc = rc_log;
    rc_log = pm_walls_log_close(&walls);
    if (!rc && rc_log)
        rc = rc_log;
    rc_log = pm_multibody_log_close(s->mb);
    if (!rc && rc_log)
        rc = rc_log;
    pm_flow_totals ft;
    pm_flow_totals_of(s, &ft);
    pm_run_summary sum = {
        .version = PMECH_VERSION,
        .case_file = c->file,
        .title = c->title,
        .formulation = c->formulation == PM_AXISYMMETRIC ? "axisymmetric"
                       : c->formulation == PM_PLANE_STRESS ? "plane_stress" : "plane_strain",
        .grid = s->grid.structured ? "structured" : "unstructured",
        .steps = s->step,
        .dt_min = isfinite(loop.dt_min) ? loop.dt_min : 0,
        .dt_max = loop.dt_max,
        .end_time = s->t,
        .wall_seconds = pm_wall_seconds() - wall0,
        .loop_seconds = loop.loop_seconds,
        .particle_steps_per_second = loop.loop_seconds > 0 ? loop.particle_steps / loop.loop_seconds : 0,
        .particles = s->p.n,
        .flow = s->flow != NULL,
        .particles_max = ft.max_n,
        .particles_released = ft.released,
        .particles_removed = ft.removed,
        .mass_released = ft.released_mass,
        .mass_removed = ft.removed_mass,
        .exit_status = rc == PM_EINTR ? 128 + (int)*o->interrupt : pm_exit_code(rc),
        .interrupted = rc == PM_EINTR ? signal_name(*o->interrupt) : NULL,
        .message = rc ? pm_error_message() : "",
        .threads = pm_thread_gov_main_count(&gov),
        .implicit = c->analysis.type != PM_ANALYSIS_EXPLICIT,
        .newton_iterations = imf.total.iterations,
        .step_cuts = imf.total.step_cuts,
        .assemble_seconds = imf.total.assemble_seconds,
        .solve_seconds = imf.total.solve_seconds,
        .warnings = (const char(*)[PM_WARNING_LEN])warn.msg,
        .n_warnings = warn.n,
    };
    if (out) {
        char msg[2048];
        snprintf(msg, sizeof msg, "%s", pm_error_message());
        sum.message = rc ? msg : "";
        int rc2 = pm_output_close(out, &sum);
        if (!rc && rc2)
            rc = rc2;
        else if (rc)
            pm_error_set(rc, "%s", msg);
    }
    if (out_sim && !rc)
        *out_sim = s;
    else
        pm_sim_destroy(s);
    return rc;
}
