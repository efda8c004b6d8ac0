/* Writing DIR/checkpoint.h5 (checkpoint.h; the layout is docs/checkpoint.md). */
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
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CK_PATH_MAX (PM_PATH_MAX + 64)

void pm_ck_logs_add(pm_ck_logs *l, const char *name, FILE **f)
{
    if (!f || !*f || *f == stderr || l->n >= PM_CK_LOGS_MAX)
        return;
    l->name[l->n] = name;
    l->file[l->n] = f;
    l->n++;
}

int pm_checkpoint_case_hash(const char *path, uint64_t *hash)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return pm_error_set(PM_EIO, "%s: cannot read the case file to identify its checkpoints: %s", path,
                            strerror(errno));
    uint64_t h = 14695981039346656037ull;
    unsigned char buf[65536];
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, f)) > 0)
        for (size_t k = 0; k < got; k++)
            h = (h ^ buf[k]) * 1099511628211ull;
    const int bad = ferror(f);
    fclose(f);
    if (bad)
        return pm_error_set(PM_EIO, "%s: read error while identifying the case", path);
    *hash = h;
    return PM_OK;
}

int pm_checkpoint_covers(const pm_sim *s)
{
    if (s->c->analysis.strength_reduction.enabled)
        return pm_error_set(PM_EINPUT, "a strength reduction is a search of many runs: it cannot be continued "
                            "from a checkpoint");
    return PM_OK;
}

int pm_checkpoint_grid_lme(const pm_sim *s)
{
    return !s->mf && !strcmp(s->approx->ops->name, "lme");
}

static int put_double(const ck_file *f, hid_t loc, const char *name, double v)
{
    return ck_attr_write(f, loc, name, CK_DOUBLE, &v);
}

static int put_long(const ck_file *f, hid_t loc, const char *name, long v)
{
    const int64_t x = v;
    return ck_attr_write(f, loc, name, CK_INT64, &x);
}

/* Run a group writer between create and close. */
typedef int (*group_writer)(const ck_file *f, hid_t g, const pm_ck_run *r);

static int in_group(const ck_file *f, const char *name, group_writer w, const pm_ck_run *r)
{
    hid_t g = ck_group_create(f, f->id, name);
    if (g < 0)
        return PM_EIO;
    const int rc = w(f, g, r);
    H5Gclose(g);
    return rc;
}

static int write_top(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    char hash[24];
    snprintf(hash, sizeof hash, "%016llx", (unsigned long long)r->case_hash);
    const int32_t fmt = PM_CHECKPOINT_FORMAT, dim = PM_DIM, threads = r->threads;
    pm_check(ck_attr_write_string(f, g, "format", "pmech checkpoint"));
    pm_check(ck_attr_write(f, g, "format_version", CK_INT32, &fmt));
    pm_check(ck_attr_write_string(f, g, "pmech_version", PMECH_VERSION));
    pm_check(ck_attr_write_string(f, g, "case_file", r->s->c->file));
    pm_check(ck_attr_write_string(f, g, "case_hash", hash));
    pm_check(ck_attr_write(f, g, "dim", CK_INT32, &dim));
    return ck_attr_write(f, g, "threads", CK_INT32, &threads);
}

static int write_time(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_sim *s = r->s;
    pm_check(put_double(f, g, "t", s->t));
    pm_check(put_long(f, g, "step", s->step));
    pm_check(put_double(f, g, "dt_next", s->dt_next));
    return put_double(f, g, "max_wave", s->max_wave);
}

static int write_particles(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_particles *p = &r->s->p;
    pm_check(put_long(f, g, "n", (long)p->n));
    pm_check(put_long(f, g, "n_state", (long)p->n_state));
    for (size_t k = 0; k < pm_particles_field_count(); k++) {
        pm_particle_field pf;
        pm_particles_field_get(p, k, &pf);
        pm_check(ck_write(f, g, pf.name, pf.is_int ? CK_INT32 : CK_DOUBLE, pf.data, p->n, pf.width));
    }
    return PM_OK;
}

static int write_nodes(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_sim *s = r->s;
    const pm_nodal *nd = &s->nd;
    const size_t n = nd->n_all;
    pm_check(ck_write(f, g, "mass", CK_DOUBLE, nd->mass, n, 1));
    const struct { const char *name; const double *a; } vec[] = {
        {"momentum", nd->mom}, {"velocity", nd->vel}, {"velocity_new", nd->vel_new}, {"force", nd->force},
        {"acceleration", nd->acc}, {"prescribed_velocity", nd->vfix}};
    for (size_t k = 0; k < sizeof vec / sizeof vec[0]; k++)
        pm_check(ck_write(f, g, vec[k].name, CK_DOUBLE, vec[k].a, n, PM_DIM));
    pm_check(ck_write(f, g, "fixed", CK_UINT8, nd->fixed, n, 1));
    int32_t *done = malloc((nd->n_timed ? nd->n_timed : 1) * sizeof *done);
    if (!done)
        return pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    for (size_t k = 0; k < nd->n_timed; k++)
        done[k] = nd->timed[k].done;
    int rc = ck_write(f, g, "timed_condition_done", CK_INT32, done, nd->n_timed, 1);
    free(done);
    /* the colour scatter's blocks decide the order of additions into shared nodes */
    int64_t *blocks = malloc(((size_t)s->n_blocks + 1) * sizeof *blocks);
    if (!rc && !blocks)
        rc = pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    for (int k = 0; !rc && k < s->n_blocks + 1 && s->blocks; k++)
        blocks[k] = (int64_t)s->blocks[k];
    if (!rc)
        rc = ck_write(f, g, "scatter_blocks", CK_INT64, blocks, s->blocks && s->n_blocks ? (size_t)s->n_blocks + 1 : 0, 1);
    free(blocks);
    const int32_t ok = s->blocks_ok;
    if (!rc)
        rc = ck_attr_write(f, g, "scatter_blocks_ok", CK_INT32, &ok);
    return rc;
}

static int write_flow(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_flow *fl = r->s->flow;
    const int32_t changed = fl->changed;
    pm_check(ck_attr_write(f, g, "next_id", CK_INT32, &fl->next_id));
    pm_check(ck_attr_write(f, g, "changed", CK_INT32, &changed));
    pm_check(put_long(f, g, "max_n", (long)fl->max_n));
    const size_t ns = fl->n_sources, nk = fl->n_sinks, n = (ns > nk ? ns : nk) + 1;
    int64_t *iv = malloc(n * sizeof *iv);
    double *dv = malloc(n * sizeof *dv);
    int rc = iv && dv ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    /* one column per counter, so each reads as a plain list per source (sink) */
    for (int col = 0; !rc && col < 9; col++) {
        const int src = col < 5;
        const size_t cnt = src ? ns : nk;
        const char *names[] = {"source_next_release", "source_released", "source_released_mass", "source_event",
                               "source_event_time", "sink_removed", "sink_removed_mass", "sink_step_particles",
                               "sink_step_mass"};
        const int is_int = col == 0 || col == 1 || col == 3 || col == 5 || col == 7;
        for (size_t k = 0; k < cnt; k++) {
            const pm_source_run *so = src ? &fl->src[k] : NULL;
            const pm_sink_run *si = src ? NULL : &fl->snk[k];
            switch (col) {
            case 0: iv[k] = (int64_t)so->next; break;
            case 1: iv[k] = (int64_t)so->released; break;
            case 2: dv[k] = so->released_mass; break;
            case 3: iv[k] = so->event; break;
            case 4: dv[k] = so->event_time; break;
            case 5: iv[k] = (int64_t)si->removed; break;
            case 6: dv[k] = si->removed_mass; break;
            case 7: iv[k] = (int64_t)si->step_particles; break;
            default: dv[k] = si->step_mass; break;
            }
        }
        rc = ck_write(f, g, names[col], is_int ? CK_INT64 : CK_DOUBLE, is_int ? (void *)iv : (void *)dv, cnt, 1);
    }
    free(iv);
    free(dv);
    return rc;
}

/* pm_contact_force is PM_DIM + 1 + PM_DIM doubles: one row per surface. */
#define FORCE_COLS (sizeof(pm_contact_force) / sizeof(double))

static int write_contact(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_contact *ct = r->s->contact;
    const size_t n = ct->n_surfaces;
    double *a = malloc((n ? n : 1) * 2 * sizeof(pm_contact_force));
    if (!a)
        return pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    for (size_t k = 0; k < n; k++) {
        memcpy(a + k * FORCE_COLS, &ct->surface[k].impulse, sizeof(pm_contact_force));
        memcpy(a + (n + k) * FORCE_COLS, &ct->surface[k].f, sizeof(pm_contact_force));
    }
    int rc = ck_write(f, g, "impulse", CK_DOUBLE, a, n, FORCE_COLS);
    if (!rc)
        rc = ck_write(f, g, "force", CK_DOUBLE, a + n * FORCE_COLS, n, FORCE_COLS);
    free(a);
    /* implicit steps build each contact node's force on the one it held at the last step */
    if (!rc)
        rc = ck_write(f, g, "held", CK_DOUBLE, ct->held, ct->held ? n * ct->n_nodes + ct->n_own_rows : 0, PM_DIM);
    if (!rc)
        rc = pm_ck_write_points(f, g, ct);
    if (!rc)
        rc = pm_ck_write_profile_impulses(f, g, ct);
    return rc;
}

/* contact_pairs: the impulses between body fields since the last contact_forces.csv row */
static int write_multibody(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_multibody *mb = r->s->mb;
    const size_t nf = (size_t)mb->n_fields;
    pm_check(put_double(f, g, "impulse_time", mb->impulse_time));
    return ck_write(f, g, "pair_impulse", CK_DOUBLE, mb->pair_impulse, nf * nf, PM_DIM);
}

static int write_meshfree(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    return pm_ck_write_meshfree(f, g, r->s);
}

static int write_lme(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    return pm_ck_write_lme(f, g, r->s->approx);
}

static int write_run(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_run_loop *l = r->loop;
    const struct { const char *name; double v; } d[] = {
        {"next_frame", l->next_frame},     {"next_energy", l->next_energy},   {"next_checkpoint", l->next_checkpoint},
        {"dt_min", l->dt_min},             {"dt_max", l->dt_max},             {"last_frame_t", l->last_frame_t},
        {"loop_seconds", l->loop_seconds}, {"particle_steps", l->particle_steps},
        {"assemble_seconds", l->assemble_seconds}, {"solve_seconds", l->solve_seconds}};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        pm_check(put_double(f, g, d[k].name, d[k].v));
    pm_check(put_long(f, g, "newton_iterations", l->newton_iterations));
    return put_long(f, g, "step_cuts", l->step_cuts);
}

static int write_probes(const ck_file *f, hid_t g, const pm_output *o)
{
    const size_t n = o->n_probes;
    int64_t *iv = malloc((n ? n : 1) * 2 * sizeof *iv);
    int32_t *jv = malloc((n ? n : 1) * 2 * sizeof *jv);
    double *pos = malloc((n ? n : 1) * 2 * sizeof *pos);
    int rc = iv && jv && pos ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory writing a checkpoint");
    for (size_t k = 0; !rc && k < n; k++) {
        iv[k] = o->pr[k].particle0;
        iv[n + k] = o->pr[k].particle;
        jv[k] = o->pr[k].id;
        jv[n + k] = o->pr[k].gone;
        pos[2 * k] = o->pr[k].init_pos[0];
        pos[2 * k + 1] = o->pr[k].init_pos[1];
    }
    if (!rc)
        rc = ck_write(f, g, "probe_particle0", CK_INT64, iv, n, 1);
    if (!rc)
        rc = ck_write(f, g, "probe_particle", CK_INT64, iv + n, n, 1);
    if (!rc)
        rc = ck_write(f, g, "probe_id", CK_INT32, jv, n, 1);
    if (!rc)
        rc = ck_write(f, g, "probe_gone", CK_INT32, jv + n, n, 1);
    if (!rc)
        rc = ck_write(f, g, "probe_initial_position", CK_DOUBLE, pos, n, 2);
    free(iv);
    free(jv);
    free(pos);
    return rc;
}

static int write_output(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    const pm_output *o = r->out;
    pm_check(ck_write(f, g, "frame_times", CK_DOUBLE, o->frame_t, o->n_frames, 1));
    const int32_t rec = o->probe_recorded;
    pm_check(put_double(f, g, "last_probe_t", o->last_probe_t));
    pm_check(ck_attr_write(f, g, "probe_recorded", CK_INT32, &rec));
    pm_check(put_double(f, g, "last_energy_t", o->last_energy_t));
    pm_check(write_probes(f, g, o));
    double range[2] = {NAN, NAN};
    const double(*used)[2] = NULL;
    const size_t n_used = pm_run_pictures_state(o->pics, range, &used);
    pm_check(ck_write(f, g, "picture_range", CK_DOUBLE, range, 2, 1));
    pm_check(ck_write(f, g, "picture_ranges_used", CK_DOUBLE, used, n_used, 2));
    const pm_forces_log *fl = r->forces;
    pm_check(put_long(f, g, "forces_rows", fl->rows));
    pm_check(put_double(f, g, "forces_t_last", fl->t_last));
    if (r->walls_t_last)
        pm_check(put_double(f, g, "walls_t_last", *r->walls_t_last));
    return put_double(f, g, "forces_next", fl->next);
}

static int log_size(const char *dir, const char *name, long *size)
{
    char path[CK_PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    struct stat st;
    if (stat(path, &st) != 0)
        return pm_error_set(PM_EIO, "%s: cannot read its length for the checkpoint: %s", path, strerror(errno));
    *size = (long)st.st_size;
    return PM_OK;
}

/* The byte length of every log, after flushing it: a restart cuts each back to it. */
static int write_logs(const ck_file *f, hid_t g, const pm_ck_run *r)
{
    pm_check(pm_output_flush(r->out));
    const pm_output *o = r->out;
    long size;
    if (o->energy_csv.fd >= 0) {
        pm_check(log_size(o->dir, "energy.csv", &size));
        pm_check(put_long(f, g, "energy.csv", size));
    }
    if (o->probes_csv.fd >= 0) {
        pm_check(log_size(o->dir, "probes.csv", &size));
        pm_check(put_long(f, g, "probes.csv", size));
    }
    for (size_t k = 0; k < r->logs->n; k++) {
        FILE *lf = *r->logs->file[k];
        if (!lf)
            continue;
        if (fflush(lf) != 0)
            return pm_error_set(PM_EIO, "%s/%s: write failed: %s", o->dir, r->logs->name[k], strerror(errno));
        pm_check(log_size(o->dir, r->logs->name[k], &size));
        pm_check(put_long(f, g, r->logs->name[k], size));
    }
    return PM_OK;
}

static int write_all(const ck_file *f, const pm_ck_run *r)
{
    pm_check(write_top(f, f->id, r));
    pm_check(in_group(f, "time", write_time, r));
    pm_check(in_group(f, "particles", write_particles, r));
    pm_check(in_group(f, "nodes", write_nodes, r));
    if (r->s->flow)
        pm_check(in_group(f, "flow", write_flow, r));
    if (r->s->contact)
        pm_check(in_group(f, "contact", write_contact, r));
    if (r->s->mb)
        pm_check(in_group(f, "multibody", write_multibody, r));
    if (r->s->mf)
        pm_check(in_group(f, "meshfree", write_meshfree, r));
    if (pm_checkpoint_grid_lme(r->s))
        pm_check(in_group(f, "lme", write_lme, r));
    pm_check(in_group(f, "run", write_run, r));
    pm_check(in_group(f, "output", write_output, r));
    return in_group(f, "logs", write_logs, r);
}

/* The bytes of the new file reach the disk before its name replaces the old one. */
static int sync_path(const char *path)
{
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    const int rc = fsync(fd);
    close(fd);
    return rc;
}

int pm_checkpoint_write(const char *dir, const pm_ck_run *r)
{
    if (!r->out)
        return PM_OK;
    char path[CK_PATH_MAX], tmp[CK_PATH_MAX + 8];
    snprintf(path, sizeof path, "%s/" PM_CHECKPOINT_NAME, dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    ck_quiet();
    ck_file f = {.id = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), .path = tmp};
    if (f.id < 0)
        return pm_error_set(PM_EIO, "%s: cannot create the checkpoint", tmp);
    int rc = write_all(&f, r);
    if (H5Fclose(f.id) < 0 && !rc)
        rc = pm_error_set(PM_EIO, "%s: cannot finish the checkpoint", tmp);
    if (!rc && sync_path(tmp) != 0)
        rc = pm_error_set(PM_EIO, "%s: cannot sync the checkpoint: %s", tmp, strerror(errno));
    if (!rc && rename(tmp, path) != 0)
        rc = pm_error_set(PM_EIO, "cannot rename '%s' to '%s': %s", tmp, path, strerror(errno));
    if (rc)
        unlink(tmp);
    return rc;
}
