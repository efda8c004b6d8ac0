/* Reading DIR/checkpoint.h5 back into a run (checkpoint.h; the layout is docs/checkpoint.md). */
#include "io/checkpoint.h"
#include "io/checkpoint_contact.h"
#include "io/checkpoint_h5.h"
#include "io/checkpoint_lme.h"
#include "io/checkpoint_meshfree.h"
#include "io/output_internal.h"

#include "contact/contact.h"
#include "contact/multibody.h"
#include "pmech/error.h"
#include "solver/flow.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CK_PATH_MAX (PM_PATH_MAX + 64)
#define CK_LOGS_MAX 16

struct pm_checkpoint {
    ck_file f;
    char path[CK_PATH_MAX];
    char dir[PM_PATH_MAX];
    size_t n_logs;
    char log[CK_LOGS_MAX][64];  /* names of the logs in the directory */
    long log_size[CK_LOGS_MAX]; /* their lengths when the checkpoint was written */
    int aside;                  /* 1: the logs are NAME.resume until put back */
};

static int get_double(const ck_file *f, hid_t loc, const char *name, double *v)
{
    return ck_attr_read(f, loc, name, CK_DOUBLE, v);
}

static int get_long(const ck_file *f, hid_t loc, const char *name, long *v)
{
    int64_t x = 0;
    pm_check(ck_attr_read(f, loc, name, CK_INT64, &x));
    *v = (long)x;
    return PM_OK;
}

/* Run a group reader between open and close. */
typedef int (*group_reader)(pm_checkpoint *ck, hid_t g, void *arg);

static int in_group(pm_checkpoint *ck, const char *name, group_reader rd, void *arg)
{
    hid_t g = ck_group_open(&ck->f, ck->f.id, name);
    if (g < 0)
        return PM_EINPUT;
    const int rc = rd(ck, g, arg);
    H5Gclose(g);
    return rc;
}

static int read_log_list(pm_checkpoint *ck, hid_t g, void *arg)
{
    (void)arg;
    H5O_info_t info;
    if (H5Oget_info(g, &info) < 0)
        return pm_error_set(PM_EINPUT, "%s: cannot list the group 'logs'", ck->path);
    if (info.num_attrs > CK_LOGS_MAX)
        return pm_error_set(PM_EINPUT, "%s: 'logs' lists %llu files, more than a run writes", ck->path,
                            (unsigned long long)info.num_attrs);
    for (hsize_t k = 0; k < info.num_attrs; k++) {
        char *name = ck->log[ck->n_logs];
        if (H5Aget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof ck->log[0], H5P_DEFAULT) < 0 ||
            strchr(name, '/') || name[0] == '.')
            return pm_error_set(PM_EINPUT, "%s: entry %llu of 'logs' is not a file name", ck->path,
                                (unsigned long long)k);
        pm_check(get_long(&ck->f, g, name, &ck->log_size[ck->n_logs]));
        ck->n_logs++;
    }
    return PM_OK;
}

/* The identity checks: format, version, dimension, case. */
static int check_identity(pm_checkpoint *ck, const pm_sim *s)
{
    char text[PM_PATH_MAX];
    const ck_file *f = &ck->f;
    if (ck_attr_read_string(f, f->id, "format", text, sizeof text) || strcmp(text, "pmech checkpoint"))
        return pm_error_set(PM_EINPUT, "%s: not a pmech checkpoint", ck->path);
    pm_check(ck_attr_read_string(f, f->id, "pmech_version", text, sizeof text));
    if (strcmp(text, PMECH_VERSION))
        return pm_error_set(PM_EINPUT, "%s was written by pmech %s; this is pmech %s, which continues only its own "
                            "checkpoints (run the case again from the start)", ck->path, text, PMECH_VERSION);
    int32_t fmt = 0, dim = 0;
    if (ck_attr_read(f, f->id, "format_version", CK_INT32, &fmt) || fmt != PM_CHECKPOINT_FORMAT)
        return pm_error_set(PM_EINPUT, "%s has layout version %d; this pmech reads version %d only (run the case "
                            "again from the start)", ck->path, (int)fmt, PM_CHECKPOINT_FORMAT);
    pm_check(ck_attr_read(f, f->id, "dim", CK_INT32, &dim));
    if (dim != PM_DIM)
        return pm_error_set(PM_EINPUT, "%s holds a %d-D run; this pmech is built for %d-D", ck->path, (int)dim, PM_DIM);
    uint64_t h;
    pm_check(pm_checkpoint_case_hash(s->c->file, &h));
    char want[24], file[PM_PATH_MAX];
    snprintf(want, sizeof want, "%016llx", (unsigned long long)h);
    pm_check(ck_attr_read_string(f, f->id, "case_hash", text, sizeof text));
    pm_check(ck_attr_read_string(f, f->id, "case_file", file, sizeof file));
    if (strcmp(text, want))
        return pm_error_set(PM_EINPUT, "%s belongs to another case: it was written for '%s' with hash %s, and '%s' "
                            "now has hash %s (a changed case must run again from the start)", ck->path, file, text,
                            s->c->file, want);
    return PM_OK;
}

int pm_checkpoint_open(pm_checkpoint **out, const char *dir, const pm_sim *s)
{
    *out = NULL;
    pm_check(pm_checkpoint_covers(s));
    pm_checkpoint *ck = calloc(1, sizeof *ck);
    if (!ck)
        return pm_error_set(PM_ENOMEM, "out of memory opening a checkpoint");
    snprintf(ck->dir, sizeof ck->dir, "%s", dir);
    snprintf(ck->path, sizeof ck->path, "%s/" PM_CHECKPOINT_NAME, dir);
    ck->f.path = ck->path;
    ck->f.id = -1;
    struct stat st;
    int rc = PM_OK;
    if (stat(ck->path, &st) != 0)
        rc = pm_error_set(PM_EINPUT, "--restart %s: there is no %s there (a run writes one at its end, when SIGINT "
                          "or SIGTERM stops it, and every output.checkpoint_interval)", dir, PM_CHECKPOINT_NAME);
    ck_quiet();
    if (!rc && (ck->f.id = H5Fopen(ck->path, H5F_ACC_RDONLY, H5P_DEFAULT)) < 0)
        rc = pm_error_set(PM_EINPUT, "%s: not an HDF5 file, or damaged", ck->path);
    if (!rc)
        rc = check_identity(ck, s);
    if (!rc)
        rc = in_group(ck, "logs", read_log_list, NULL);
    if (rc) {
        pm_checkpoint_close(ck);
        return rc;
    }
    *out = ck;
    return PM_OK;
}

static int read_time(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_sim *s = arg;
    pm_check(get_double(&ck->f, g, "t", &s->t));
    pm_check(get_long(&ck->f, g, "step", &s->step));
    pm_check(get_double(&ck->f, g, "dt_next", &s->dt_next));
    return get_double(&ck->f, g, "max_wave", &s->max_wave);
}

static int read_particles(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_particles *p = &((pm_sim *)arg)->p;
    long n, n_state;
    pm_check(get_long(&ck->f, g, "n", &n));
    pm_check(get_long(&ck->f, g, "n_state", &n_state));
    if (n < 0 || (size_t)n > p->cap || (size_t)n_state != p->n_state)
        return pm_error_set(PM_EINPUT, "%s: %ld particles with %ld history variables each do not fit this case's "
                            "%zu with %zu", ck->path, n, n_state, p->cap, p->n_state);
    for (size_t k = 0; k < pm_particles_field_count(); k++) {
        pm_particle_field pf;
        pm_particles_field_get(p, k, &pf);
        if (pf.width == 0) /* nothing to read, whatever width the writing run gave the field */
            continue;
        pm_check(ck_read(&ck->f, g, pf.name, pf.is_int ? CK_INT32 : CK_DOUBLE, pf.data, (size_t)n, pf.width));
    }
    p->n = (size_t)n;
    return PM_OK;
}

static int read_nodes(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_sim *s = arg;
    pm_nodal *nd = &s->nd;
    const size_t n = nd->n_all;
    pm_check(ck_read(&ck->f, g, "mass", CK_DOUBLE, nd->mass, n, 1));
    const struct { const char *name; double *a; } vec[] = {
        {"momentum", nd->mom}, {"velocity", nd->vel}, {"velocity_new", nd->vel_new}, {"force", nd->force},
        {"acceleration", nd->acc}, {"prescribed_velocity", nd->vfix}};
    for (size_t k = 0; k < sizeof vec / sizeof vec[0]; k++)
        pm_check(ck_read(&ck->f, g, vec[k].name, CK_DOUBLE, vec[k].a, n, PM_DIM));
    pm_check(ck_read(&ck->f, g, "fixed", CK_UINT8, nd->fixed, n, 1));
    int32_t *done = malloc((nd->n_timed ? nd->n_timed : 1) * sizeof *done);
    if (!done)
        return pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    int rc = ck_read(&ck->f, g, "timed_condition_done", CK_INT32, done, nd->n_timed, 1);
    for (size_t k = 0; !rc && k < nd->n_timed; k++)
        nd->timed[k].done = done[k] != 0;
    free(done);
    size_t rows = 0;
    if (!rc)
        rc = ck_rows(&ck->f, g, "scatter_blocks", &rows);
    s->n_blocks = 0;
    if (!rc && rows > 1 && rows == 2 * (size_t)nd->n_threads + 1) {
        int64_t *b = malloc(rows * sizeof *b);
        int32_t ok = 0;
        rc = b ? ck_read(&ck->f, g, "scatter_blocks", CK_INT64, b, rows, 1)
               : pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
        if (!rc)
            rc = ck_attr_read(&ck->f, g, "scatter_blocks_ok", CK_INT32, &ok);
        for (size_t k = 0; !rc && k < rows; k++)
            s->blocks[k] = (size_t)b[k];
        if (!rc) {
            s->n_blocks = (int)rows - 1;
            s->blocks_ok = ok;
        }
        free(b);
    }
    return rc;
}

static int read_flow(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_flow *fl = ((pm_sim *)arg)->flow;
    int32_t changed = 0;
    long max_n;
    pm_check(ck_attr_read(&ck->f, g, "next_id", CK_INT32, &fl->next_id));
    pm_check(ck_attr_read(&ck->f, g, "changed", CK_INT32, &changed));
    pm_check(get_long(&ck->f, g, "max_n", &max_n));
    fl->changed = changed;
    fl->max_n = (size_t)max_n;
    const size_t ns = fl->n_sources, nk = fl->n_sinks, n = (ns > nk ? ns : nk) + 1;
    int64_t *iv = malloc(n * sizeof *iv);
    double *dv = malloc(n * sizeof *dv);
    int rc = iv && dv ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    static const char *const names[] = {"source_next_release", "source_released", "source_released_mass",
                                        "source_event", "source_event_time", "sink_removed", "sink_removed_mass",
                                        "sink_step_particles", "sink_step_mass"};
    for (int col = 0; !rc && col < 9; col++) {
        const int src = col < 5;
        const size_t cnt = src ? ns : nk;
        const int is_int = col == 0 || col == 1 || col == 3 || col == 5 || col == 7;
        rc = ck_read(&ck->f, g, names[col], is_int ? CK_INT64 : CK_DOUBLE, is_int ? (void *)iv : (void *)dv, cnt, 1);
        for (size_t k = 0; !rc && k < cnt; k++) {
            pm_source_run *so = src ? &fl->src[k] : NULL;
            pm_sink_run *si = src ? NULL : &fl->snk[k];
            switch (col) {
            case 0: so->next = (size_t)iv[k]; break;
            case 1: so->released = (size_t)iv[k]; break;
            case 2: so->released_mass = dv[k]; break;
            case 3: so->event = (pm_release_event)iv[k]; break;
            case 4: so->event_time = dv[k]; break;
            case 5: si->removed = (size_t)iv[k]; break;
            case 6: si->removed_mass = dv[k]; break;
            case 7: si->step_particles = (size_t)iv[k]; break;
            default: si->step_mass = dv[k]; break;
            }
        }
    }
    free(iv);
    free(dv);
    return rc;
}

#define FORCE_COLS (sizeof(pm_contact_force) / sizeof(double))



/* After the logs were opened (they start the impulses afresh): the surfaces' impulses since the last
 * forces.csv row, their last forces and the wall profiles' impulses. */
static int read_contact_logged(pm_checkpoint *ck, hid_t g, void *arg);

/* The surfaces' impulses since the last forces.csv row and their last forces. */
static int read_contact_forces(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_contact *ct = ((pm_sim *)arg)->contact;
    const size_t n = ct->n_surfaces;
    double *a = malloc((n ? n : 1) * 2 * sizeof(pm_contact_force));
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    int rc = ck_read(&ck->f, g, "impulse", CK_DOUBLE, a, n, FORCE_COLS);
    if (!rc)
        rc = ck_read(&ck->f, g, "force", CK_DOUBLE, a + n * FORCE_COLS, n, FORCE_COLS);
    for (size_t k = 0; !rc && k < n; k++) {
        memcpy(&ct->surface[k].impulse, a + k * FORCE_COLS, sizeof(pm_contact_force));
        memcpy(&ct->surface[k].f, a + (n + k) * FORCE_COLS, sizeof(pm_contact_force));
    }
    free(a);
    return rc;
}

static int read_contact(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_contact *ct = ((pm_sim *)arg)->contact;
    const size_t n = ct->n_surfaces;
    int rc = read_contact_forces(ck, g, arg);
    size_t rows = 0;
    if (!rc)
        rc = ck_rows(&ck->f, g, "held", &rows);
    if (!rc && rows > 0) { /* allocated as pm_contact_implicit_begin() would at the first implicit step */
        const size_t cnt = PM_DIM * (n * ct->n_nodes + ct->n_own_rows);
        if (!ct->held)
            ct->held = calloc(cnt, sizeof *ct->held);
        if (!ct->held_next)
            ct->held_next = calloc(cnt, sizeof *ct->held_next);
        /* a checkpoint written before the second faces of Gmsh walls' inward corners had rows of their
         * own holds the (surface, node) rows only: those faces then start from no force */
        const size_t want = rows == n * ct->n_nodes ? rows : n * ct->n_nodes + ct->n_own_rows;
        rc = ct->held && ct->held_next ? ck_read(&ck->f, g, "held", CK_DOUBLE, ct->held, want, PM_DIM)
                                       : pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    }
    return rc ? rc : pm_ck_read_points(&ck->f, ck->path, g, ct);
}

static int read_meshfree(pm_checkpoint *ck, hid_t g, void *arg)
{
    return pm_ck_read_meshfree(&ck->f, g, arg);
}

static int read_lme(pm_checkpoint *ck, hid_t g, void *arg)
{
    return pm_ck_read_lme(&ck->f, g, arg);
}

static int read_run(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_run_loop *l = arg;
    struct { const char *name; double *v; } d[] = {
        {"next_frame", &l->next_frame},     {"next_energy", &l->next_energy},   {"next_checkpoint", &l->next_checkpoint},
        {"dt_min", &l->dt_min},             {"dt_max", &l->dt_max},             {"last_frame_t", &l->last_frame_t},
        {"loop_seconds", &l->loop_seconds}, {"particle_steps", &l->particle_steps},
        {"assemble_seconds", &l->assemble_seconds}, {"solve_seconds", &l->solve_seconds}};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        pm_check(get_double(&ck->f, g, d[k].name, d[k].v));
    pm_check(get_long(&ck->f, g, "newton_iterations", &l->newton_iterations));
    return get_long(&ck->f, g, "step_cuts", &l->step_cuts);
}

int pm_checkpoint_restore_state(pm_checkpoint *ck, pm_sim *s, pm_run_loop *loop, int threads, char *warning,
                                size_t warning_len)
{
    warning[0] = '\0';
    pm_check(in_group(ck, "time", read_time, s));
    pm_check(in_group(ck, "particles", read_particles, s));
    pm_check(in_group(ck, "nodes", read_nodes, s));
    if (s->flow)
        pm_check(in_group(ck, "flow", read_flow, s));
    if (s->contact)
        pm_check(in_group(ck, "contact", read_contact, s));
    if (s->mf)
        pm_check(in_group(ck, "meshfree", read_meshfree, s));
    if (pm_checkpoint_grid_lme(s))
        pm_check(in_group(ck, "lme", read_lme, s->approx));
    pm_check(in_group(ck, "run", read_run, loop));
    int32_t stored = 0;
    pm_check(ck_attr_read(&ck->f, ck->f.id, "threads", CK_INT32, &stored));
    if (stored != threads)
        snprintf(warning, warning_len, "the run continues on %d threads from a checkpoint written on %d: its "
                 "results may differ from an uninterrupted run in the last digits (use --threads %d to continue "
                 "it exactly)", threads, (int)stored, (int)stored);
    return PM_OK;
}

static void log_path(const pm_checkpoint *ck, size_t k, const char *suffix, char *buf)
{
    snprintf(buf, CK_PATH_MAX, "%s/%s%s", ck->dir, ck->log[k], suffix);
}

int pm_checkpoint_logs_aside(pm_checkpoint *ck)
{
    char path[CK_PATH_MAX], aside[CK_PATH_MAX];
    for (size_t k = 0; k < ck->n_logs; k++) {
        log_path(ck, k, "", path);
        struct stat st;
        if (stat(path, &st) != 0)
            return pm_error_set(PM_EINPUT, "%s: missing, but the checkpoint's run had written %ld bytes of it; "
                                "the run cannot be continued exactly", path, ck->log_size[k]);
        if ((long)st.st_size < ck->log_size[k])
            return pm_error_set(PM_EINPUT, "%s: %ld bytes, shorter than the %ld the checkpoint's run had written "
                                "(changed since?); the run cannot be continued exactly", path, (long)st.st_size,
                                ck->log_size[k]);
    }
    for (size_t k = 0; k < ck->n_logs; k++) {
        log_path(ck, k, "", path);
        log_path(ck, k, ".resume", aside);
        if (rename(path, aside) != 0)
            return pm_error_set(PM_EIO, "cannot rename '%s' to '%s': %s", path, aside, strerror(errno));
    }
    ck->aside = 1;
    return PM_OK;
}

/* Every log back under its name, cut to its stored length when @p cut (a restart that failed before
 * it could continue leaves them whole). */
static int logs_back(pm_checkpoint *ck, int cut)
{
    char path[CK_PATH_MAX], aside[CK_PATH_MAX];
    int rc = PM_OK;
    for (size_t k = 0; ck->aside && k < ck->n_logs; k++) {
        log_path(ck, k, "", path);
        log_path(ck, k, ".resume", aside);
        if (rename(aside, path) != 0) {
            if (!rc)
                rc = pm_error_set(PM_EIO, "cannot rename '%s' back to '%s': %s", aside, path, strerror(errno));
        } else if (cut && truncate(path, ck->log_size[k]) != 0 && !rc) {
            rc = pm_error_set(PM_EIO, "cannot cut '%s' back to %ld bytes: %s", path, ck->log_size[k], strerror(errno));
        }
    }
    ck->aside = 0;
    return rc;
}

/* The open streams and descriptors onto the logs put back, appending. */
static int reopen_logs(pm_checkpoint *ck, pm_output *out, pm_ck_logs *logs)
{
    char path[CK_PATH_MAX];
    for (size_t k = 0; k < ck->n_logs; k++) {
        log_path(ck, k, "", path);
        csv_out *c = !strcmp(ck->log[k], "energy.csv") ? &out->energy_csv
                     : !strcmp(ck->log[k], "probes.csv") ? &out->probes_csv : NULL;
        if (c && c->fd >= 0) {
            close(c->fd);
            c->fd = open(path, O_WRONLY | O_APPEND | O_CLOEXEC);
            if (c->fd < 0)
                return pm_error_set(PM_EIO, "cannot append to '%s': %s", path, strerror(errno));
            continue;
        }
        for (size_t j = 0; j < logs->n; j++) {
            if (strcmp(logs->name[j], ck->log[k]) || !*logs->file[j])
                continue;
            *logs->file[j] = freopen(path, "a", *logs->file[j]);
            if (!*logs->file[j])
                return pm_error_set(PM_EIO, "cannot append to '%s': %s", path, strerror(errno));
        }
    }
    return PM_OK;
}

static int read_probes(pm_checkpoint *ck, hid_t g, pm_output *o)
{
    const size_t n = o->n_probes;
    int64_t *iv = malloc((n ? n : 1) * 2 * sizeof *iv);
    int32_t *jv = malloc((n ? n : 1) * 2 * sizeof *jv);
    double *pos = malloc((n ? n : 1) * 2 * sizeof *pos);
    int rc = iv && jv && pos ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    if (!rc)
        rc = ck_read(&ck->f, g, "probe_particle0", CK_INT64, iv, n, 1);
    if (!rc)
        rc = ck_read(&ck->f, g, "probe_particle", CK_INT64, iv + n, n, 1);
    if (!rc)
        rc = ck_read(&ck->f, g, "probe_id", CK_INT32, jv, n, 1);
    if (!rc)
        rc = ck_read(&ck->f, g, "probe_gone", CK_INT32, jv + n, n, 1);
    if (!rc)
        rc = ck_read(&ck->f, g, "probe_initial_position", CK_DOUBLE, pos, n, 2);
    for (size_t k = 0; !rc && k < n; k++) {
        o->pr[k].particle0 = (long)iv[k];
        o->pr[k].particle = (long)iv[n + k];
        o->pr[k].id = jv[k];
        o->pr[k].gone = jv[n + k];
        o->pr[k].init_pos[0] = pos[2 * k];
        o->pr[k].init_pos[1] = pos[2 * k + 1];
    }
    free(iv);
    free(jv);
    free(pos);
    return rc;
}

static int read_multibody(pm_checkpoint *ck, hid_t g, void *arg)
{
    pm_multibody *mb = arg;
    const size_t nf = (size_t)mb->n_fields;
    pm_check(get_double(&ck->f, g, "impulse_time", &mb->impulse_time));
    return ck_read(&ck->f, g, "pair_impulse", CK_DOUBLE, mb->pair_impulse, nf * nf, PM_DIM);
}

typedef struct output_args {
    pm_output *out;
    pm_forces_log *forces;
    double *walls_t_last;
} output_args;

static int read_output(pm_checkpoint *ck, hid_t g, void *arg)
{
    output_args *a = arg;
    pm_output *o = a->out;
    size_t n = 0;
    pm_check(ck_rows(&ck->f, g, "frame_times", &n));
    if (n > o->cap_frames) {
        double *ft = realloc(o->frame_t, n * sizeof *ft);
        if (!ft)
            return pm_error_set(PM_ENOMEM, "out of memory for the frame list");
        o->frame_t = ft;
        o->cap_frames = n;
    }
    pm_check(ck_read(&ck->f, g, "frame_times", CK_DOUBLE, o->frame_t, n, 1));
    o->n_frames = n;
    int32_t rec = 0;
    pm_check(get_double(&ck->f, g, "last_probe_t", &o->last_probe_t));
    pm_check(ck_attr_read(&ck->f, g, "probe_recorded", CK_INT32, &rec));
    o->probe_recorded = rec;
    pm_check(get_double(&ck->f, g, "last_energy_t", &o->last_energy_t));
    pm_check(read_probes(ck, g, o));
    double range[2];
    pm_check(ck_read(&ck->f, g, "picture_range", CK_DOUBLE, range, 2, 1));
    pm_check(ck_rows(&ck->f, g, "picture_ranges_used", &n));
    double(*used)[2] = malloc((n ? n : 1) * sizeof *used);
    if (!used)
        return pm_error_set(PM_ENOMEM, "out of memory reading a checkpoint");
    int rc = ck_read(&ck->f, g, "picture_ranges_used", CK_DOUBLE, used, n, 2);
    if (!rc)
        rc = pm_run_pictures_restore(o->pics, range, (const double(*)[2])used, n);
    free(used);
    pm_check(rc);
    pm_check(get_long(&ck->f, g, "forces_rows", &a->forces->rows));
    pm_check(get_double(&ck->f, g, "forces_t_last", &a->forces->t_last));
    pm_check(get_double(&ck->f, g, "forces_next", &a->forces->next));
    /* a checkpoint written before the wall profiles' time was kept: the profile starts at the stop */
    if (a->walls_t_last && H5Aexists(g, "walls_t_last") > 0)
        pm_check(get_double(&ck->f, g, "walls_t_last", a->walls_t_last));
    return PM_OK;
}

static int read_contact_logged(pm_checkpoint *ck, hid_t g, void *arg)
{
    const int rc = read_contact_forces(ck, g, arg);
    return rc ? rc : pm_ck_read_profile_impulses(&ck->f, ck->path, g, ((pm_sim *)arg)->contact);
}

int pm_checkpoint_restore_outputs(pm_checkpoint *ck, pm_sim *s, pm_output *out, pm_forces_log *forces,
                                  double *walls_t_last, pm_ck_logs *logs)
{
    output_args a = {out, forces, walls_t_last};
    int rc = in_group(ck, "output", read_output, &a);
    if (!rc && s->mb) /* after contact_forces.csv was opened, which starts the impulses afresh */
        rc = in_group(ck, "multibody", read_multibody, s->mb);
    if (!rc && s->contact) /* after forces.csv and the wall profiles were opened, which start afresh */
        rc = in_group(ck, "contact", read_contact_logged, s);
    const int rb = logs_back(ck, 1);
    if (!rc)
        rc = rb;
    if (!rc)
        rc = reopen_logs(ck, out, logs);
    return rc;
}

void pm_checkpoint_close(pm_checkpoint *ck)
{
    if (!ck)
        return;
    if (ck->aside) {
        char msg[2048];
        snprintf(msg, sizeof msg, "%s", pm_error_message());
        logs_back(ck, 0);
        pm_error_set(PM_OK, "%s", msg);
    }
    if (ck->f.id >= 0)
        H5Fclose(ck->f.id);
    free(ck);
}
