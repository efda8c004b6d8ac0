/* The output directory of a run: particle frames + particles.pvd, grid.vtu, probes.csv,
 * energy.csv and run.json. VTU/PVD/JSON files are replaced atomically; the CSV files only ever
 * receive whole lines, so a run that stops at any point leaves valid files behind. */
#include "io/output.h"
#include "io/output_internal.h"
#include "pmech/error.h"
#include "io/run_pictures.h"
#include "io/vtu_write.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const quantity_names[] = { "position", "displacement", "velocity", "stress",
                                              "plastic_strain" };

/* Components of a quantity and their column suffixes. */
static int quantity_comps(pm_quantity q, const char *const **names)
{
    static const char *const pos[] = { "x", "y" }, *const disp[] = { "ux", "uy" },
                             *const vel[] = { "vx", "vy" }, *const sig[] = { "sxx", "syy", "szz", "sxy" },
                             *const eps[] = { "eps_p" };
    switch (q) {
    case PM_Q_POSITION: *names = pos; return 2;
    case PM_Q_DISPLACEMENT: *names = disp; return 2;
    case PM_Q_VELOCITY: *names = vel; return 2;
    case PM_Q_STRESS: *names = sig; return 4;
    default: *names = eps; return 1;
    }
}

/* The quantity of particle i into out[] (as many values as quantity_comps gives). */
static void particle_value(const pm_particles *p, size_t i, pm_quantity q, double *out)
{
    switch (q) {
    case PM_Q_POSITION:
        out[0] = p->x[2 * i];
        out[1] = p->x[2 * i + 1];
        break;
    case PM_Q_DISPLACEMENT:
        out[0] = p->x[2 * i] - p->x0[2 * i];
        out[1] = p->x[2 * i + 1] - p->x0[2 * i + 1];
        break;
    case PM_Q_VELOCITY:
        out[0] = p->v[2 * i];
        out[1] = p->v[2 * i + 1];
        break;
    case PM_Q_STRESS:
        for (int k = 0; k < PM_NS; k++)
            out[k] = p->stress[PM_NS * i + k];
        break;
    default:
        out[0] = p->eps_p[i];
        break;
    }
}

/* Mass-weighted mean of the quantity over the particles of body b (plain mean if they are
 * massless); returns the particle count. */
static size_t body_mean(const pm_particles *p, int b, pm_quantity q, double *out)
{
    double sum[PM_NS] = { 0 }, plain[PM_NS] = { 0 }, m = 0, v[PM_NS];
    const char *const *names;
    const int nc = quantity_comps(q, &names);
    size_t cnt = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->body[i] != b)
            continue;
        particle_value(p, i, q, v);
        for (int k = 0; k < nc; k++) {
            sum[k] += p->mass[i] * v[k];
            plain[k] += v[k];
        }
        m += p->mass[i];
        cnt++;
    }
    for (int k = 0; k < nc; k++)
        out[k] = m > 0 ? sum[k] / m : cnt ? plain[k] / (double)cnt : NAN;
    return cnt;
}

/* Index of the particle nearest to pt (ties to the lowest index), or -1 if there is none. */
static long nearest(const double *x, size_t n, const double pt[2])
{
    long best = -1;
    double bd = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double dx = x[2 * i] - pt[0], dy = x[2 * i + 1] - pt[1], d = dx * dx + dy * dy;
        if (d < bd || best < 0) {
            bd = d;
            best = (long)i;
        }
    }
    return best;
}

/* ---- CSV files ---------------------------------------------------------------------------- */

static int csv_open(csv_out *c, const char *path, const char *header)
{
    snprintf(c->path, sizeof c->path, "%s", path);
    c->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (c->fd < 0)
        return pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(errno));
    c->buf = malloc(CSV_BUF);
    c->line_cap = 256;
    c->line = malloc(c->line_cap);
    if (!c->buf || !c->line)
        return pm_error_set(PM_ENOMEM, "out of memory opening '%s'", path);
    c->len = c->line_len = 0;
    size_t n = strlen(header);
    if (write(c->fd, header, n) != (ssize_t)n)
        return pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(errno ? errno : EIO));
    return PM_OK;
}

static int write_all(int fd, const char *s, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, s, n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        s += w;
        n -= (size_t)w;
    }
    return 0;
}

static int csv_flush(csv_out *c)
{
    if (c->fd < 0 || c->len == 0)
        return PM_OK;
    int rc = write_all(c->fd, c->buf, c->len);
    c->len = 0;
    if (rc && !c->failed) {
        c->failed = 1;
        return pm_error_set(PM_EIO, "cannot write '%s': %s", c->path, strerror(errno));
    }
    return c->failed ? PM_EIO : PM_OK;
}

/* Append text to the line being built. */
static int csv_add(csv_out *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int csv_add(csv_out *c, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(c->line + c->line_len, c->line_cap - c->line_len, fmt, ap);
        va_end(ap);
        if (n < 0)
            return pm_error_set(PM_EIO, "cannot format a line of '%s'", c->path);
        if ((size_t)n < c->line_cap - c->line_len) {
            c->line_len += (size_t)n;
            return PM_OK;
        }
        size_t cap = 2 * (c->line_len + (size_t)n + 1);
        char *l = realloc(c->line, cap);
        if (!l)
            return pm_error_set(PM_ENOMEM, "out of memory writing '%s'", c->path);
        c->line = l;
        c->line_cap = cap;
    }
}

/* Finish the line being built: it joins the buffer of complete lines. */
static int csv_end_line(csv_out *c)
{
    pm_check(csv_add(c, "\n"));
    int rc = PM_OK;
    if (c->len + c->line_len > CSV_BUF)
        rc = csv_flush(c);
    if (c->line_len > CSV_BUF) {
        if (!rc && write_all(c->fd, c->line, c->line_len) != 0 && !c->failed) {
            c->failed = 1;
            rc = pm_error_set(PM_EIO, "cannot write '%s': %s", c->path, strerror(errno));
        }
    } else {
        memcpy(c->buf + c->len, c->line, c->line_len);
        c->len += c->line_len;
    }
    c->line_len = 0;
    return rc;
}

static int csv_close(csv_out *c)
{
    int rc = csv_flush(c);
    if (c->fd >= 0 && close(c->fd) != 0 && !rc)
        rc = pm_error_set(PM_EIO, "cannot write '%s': %s", c->path, strerror(errno));
    c->fd = -1;
    free(c->buf);
    free(c->line);
    c->buf = c->line = NULL;
    return rc;
}

/* ---- files in the directory --------------------------------------------------------------- */

static int join(char *buf, const char *dir, const char *name)
{
    int n = snprintf(buf, OUT_PATH_MAX, "%s/%s", dir, name);
    if (n < 0 || n >= OUT_PATH_MAX)
        return pm_error_set(PM_EIO, "cannot write '%s/%s': path too long", dir, name);
    return PM_OK;
}

/* A frame of some run: particles_<digits>.vtu, or the .png picture drawn with it, optionally
 * followed by .tmp */
static int is_frame_name(const char *s)
{
    if (strncmp(s, "grid_", 5) == 0)
        s += 5;
    else if (strncmp(s, "particles_", 10) == 0)
        s += 10;
    else
        return 0;
    const char *d = s;
    while (*s >= '0' && *s <= '9')
        s++;
    return s > d && (strcmp(s, ".vtu") == 0 || strcmp(s, ".vtu.tmp") == 0 || strcmp(s, ".png") == 0 ||
                     strcmp(s, ".png.tmp") == 0);
}

/* Remove what a previous run left that this run would not overwrite right away: old frames
 * (and their pictures), the pvd listing them, run.json, temporary files, and probes.csv when
 * there are no probes. */
static int remove_stale(const char *dir, int keep_probes)
{
    static const char *const names[] = { "particles.pvd", "run.json", "particles.pvd.tmp",
                                         "run.json.tmp", "grid.vtu.tmp", "probes.csv", "grid.pvd", "grid.pvd.tmp",
                                         "releases.csv", "removals.csv", "forces.csv", "forces.png" };
    DIR *d = opendir(dir);
    if (!d)
        return pm_error_set(PM_EIO, "cannot read directory '%s': %s", dir, strerror(errno));
    int rc = PM_OK;
    struct dirent *e;
    char path[OUT_PATH_MAX];
    while (rc == PM_OK && (e = readdir(d)) != NULL) {
        int stale = is_frame_name(e->d_name);
        for (size_t k = 0; !stale && k < sizeof names / sizeof names[0]; k++)
            stale = strcmp(e->d_name, names[k]) == 0 && !(keep_probes && k == 5);
        if (!stale)
            continue;
        rc = join(path, dir, e->d_name);
        if (!rc && unlink(path) != 0 && errno != ENOENT)
            rc = pm_error_set(PM_EIO, "cannot remove the stale file '%s': %s", path, strerror(errno));
    }
    closedir(d);
    return rc;
}

/* <prefix>.pvd listing every frame so far (files <prefix>_NNNNNN.vtu). */
static int write_pvd_of(const pm_output *o, const char *prefix)
{
    static const char head[] = "<?xml version=\"1.0\"?>\n"
                               "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
                               "  <Collection>\n";
    static const char tail[] = "  </Collection>\n</VTKFile>\n";
    const size_t per = 128;
    size_t cap = sizeof head + sizeof tail + per * o->n_frames, len = 0;
    char *buf = malloc(cap);
    if (!buf)
        return pm_error_set(PM_ENOMEM, "out of memory writing particles.pvd");
    memcpy(buf, head, sizeof head - 1);
    len = sizeof head - 1;
    for (size_t k = 0; k < o->n_frames; k++) {
        int n = snprintf(buf + len, per,
                         "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"%s_%06zu.vtu\"/>\n",
                         o->frame_t[k], prefix, k);
        if (n < 0 || (size_t)n >= per) {
            free(buf);
            return pm_error_set(PM_EINTERNAL, "%s.pvd: line %zu does not fit", prefix, k);
        }
        len += (size_t)n;
    }
    memcpy(buf + len, tail, sizeof tail - 1);
    len += sizeof tail - 1;
    char path[OUT_PATH_MAX], name[64];
    snprintf(name, sizeof name, "%s.pvd", prefix);
    int rc = join(path, o->dir, name);
    if (!rc)
        rc = pm_write_file_atomic(path, buf, len);
    free(buf);
    return rc;
}

static int write_pvd(const pm_output *o) { return write_pvd_of(o, "particles"); }

/* ---- public API --------------------------------------------------------------------------- */

static int resolve_probes(pm_output *o, const pm_case *c, const pm_particles *p)
{
    if (c->n_probes == 0)
        return PM_OK;
    o->pr = calloc(c->n_probes, sizeof *o->pr);
    if (!o->pr)
        return pm_error_set(PM_ENOMEM, "out of memory for %zu probes", c->n_probes);
    o->n_probes = c->n_probes;
    for (size_t k = 0; k < c->n_probes; k++) {
        const pm_case_probe *cp = &c->probes[k];
        probe *pr = &o->pr[k];
        snprintf(pr->name, sizeof pr->name, "%s", cp->name);
        if ((int)cp->quantity < 0 || (int)cp->quantity > PM_Q_PLASTIC_STRAIN)
            return pm_error_set(PM_EINPUT, "probes[%zu].quantity: unknown quantity %d", k, (int)cp->quantity);
        pr->quantity = cp->quantity;
        pr->body = cp->body;
        if (cp->body >= 0) {
            if ((size_t)cp->body >= c->n_bodies)
                return pm_error_set(PM_EINPUT, "probes[%zu].body: body %d does not exist (%zu bodies)", k,
                                    cp->body, c->n_bodies);
            if (body_mean(p, cp->body, PM_Q_POSITION, pr->init_pos) == 0)
                return pm_error_set(PM_EINPUT, "probes[%zu].body: body '%s' has no particle", k,
                                    c->bodies[cp->body].name);
            pr->particle0 = pr->particle = -1;
        } else {
            long i = nearest(p->x, p->n, cp->point);
            if (i < 0)
                return pm_error_set(PM_EINPUT, "probes[%zu].point: there is no particle at t = 0 to follow (a "
                                    "point probe follows a particle of the start, not one a source releases later)", k);
            pr->particle0 = pr->particle = i;
            pr->id = p->id[i];
            pr->init_pos[0] = p->x[2 * i];
            pr->init_pos[1] = p->x[2 * i + 1];
        }
    }
    if (c->n_bodies) {
        o->body_names = calloc(c->n_bodies, sizeof *o->body_names);
        if (!o->body_names)
            return pm_error_set(PM_ENOMEM, "out of memory for body names");
        for (size_t b = 0; b < c->n_bodies; b++)
            snprintf(o->body_names[b], PM_NAME_MAX, "%s", c->bodies[b].name);
    }
    return PM_OK;
}

static int open_csvs(pm_output *o)
{
    char path[OUT_PATH_MAX];
    pm_check(join(path, o->dir, "energy.csv"));
    pm_check(csv_open(&o->energy_csv, path, "time,kinetic,strain,gravity,total\n"));
    if (o->n_probes == 0)
        return PM_OK;
    pm_check(join(path, o->dir, "probes.csv"));
    csv_out *c = &o->probes_csv;
    /* the header goes through the line buffer (it can be long), then straight to the file */
    snprintf(c->path, sizeof c->path, "%s", path);
    c->line_cap = 256;
    c->line = malloc(c->line_cap);
    if (!c->line)
        return pm_error_set(PM_ENOMEM, "out of memory opening '%s'", path);
    pm_check(csv_add(c, "time"));
    for (size_t k = 0; k < o->n_probes; k++) {
        const char *const *names;
        int nc = quantity_comps(o->pr[k].quantity, &names);
        for (int j = 0; j < nc; j++)
            pm_check(csv_add(c, ",%s.%s", o->pr[k].name, names[j]));
    }
    pm_check(csv_add(c, "\n"));
    char *header = c->line;
    c->line = NULL;
    int rc = csv_open(c, path, header);
    free(header);
    return rc;
}

static int output_open(pm_output **out, const char *dir, const pm_case *c, const pm_grid *g,
                       const pm_particles *p, int resume)
{
    *out = NULL;
    if (!dir || !dir[0])
        dir = ".";
    pm_output *o = calloc(1, sizeof *o);
    if (!o)
        return pm_error_set(PM_ENOMEM, "out of memory opening the output directory '%s'", dir);
    o->probes_csv.fd = o->energy_csv.fd = -1;
    o->last_energy_t = NAN;
    int n = snprintf(o->dir, sizeof o->dir, "%s", dir);
    int rc = PM_OK;
    if (n < 0 || (size_t)n >= sizeof o->dir - 32)
        rc = pm_error_set(PM_EIO, "output directory '%s': path too long", dir);
    o->probe_interval = c->output.probe_interval;
    if (!rc)
        rc = resolve_probes(o, c, p);
    if (!rc)
        rc = pm_mkdir_p(o->dir);
    if (!rc && !resume)
        rc = remove_stale(o->dir, o->n_probes > 0);
    if (!rc && g) {
        char path[OUT_PATH_MAX];
        rc = join(path, o->dir, "grid.vtu");
        if (!rc)
            rc = pm_vtu_write_grid(path, g, NULL, NULL);
        if (!rc)
            rc = pm_run_pictures_open(&o->pics, c, o->dir, g);
    }
    if (!rc)
        rc = open_csvs(o);
    if (rc) {
        char msg[2048];
        snprintf(msg, sizeof msg, "%s", pm_error_message());
        pm_output_close(o, NULL);
        return pm_error_set(rc, "%s", msg);
    }
    *out = o;
    return PM_OK;
}

int pm_output_open(pm_output **out, const char *dir, const pm_case *c, const pm_grid *g,
                   const pm_particles *p)
{
    return output_open(out, dir, c, g, p, 0);
}

int pm_output_open_resume(pm_output **out, const char *dir, const pm_case *c, const pm_grid *g,
                          const pm_particles *p)
{
    return output_open(out, dir, c, g, p, 1);
}

int pm_output_flush(pm_output *o)
{
    const int r1 = csv_flush(&o->probes_csv), r2 = csv_flush(&o->energy_csv);
    return r1 ? r1 : r2;
}

int pm_output_frame(pm_output *o, double t, const pm_particles *p)
{
    size_t need = 3 * (p->n ? p->n : 1);
    if (need > o->scratch_n) {
        free(o->scratch);
        o->scratch = malloc(need * sizeof(double));
        o->scratch_n = o->scratch ? need : 0;
        if (!o->scratch)
            return pm_error_set(PM_ENOMEM, "out of memory writing a frame of %zu particles", p->n);
    }
    if (o->n_frames == o->cap_frames) {
        size_t cap = o->cap_frames ? 2 * o->cap_frames : 64;
        double *ft = realloc(o->frame_t, cap * sizeof *ft);
        if (!ft)
            return pm_error_set(PM_ENOMEM, "out of memory for the frame list");
        o->frame_t = ft;
        o->cap_frames = cap;
    }
    char name[64], path[OUT_PATH_MAX];
    snprintf(name, sizeof name, "particles_%06zu.vtu", o->n_frames);
    pm_check(join(path, o->dir, name));
    pm_check(pm_vtu_write_particles(path, p, o->scratch, t));
    o->frame_t[o->n_frames++] = t;
    int rc = write_pvd(o);
    if (!rc)
        rc = pm_run_pictures_frame(o->pics, o->n_frames - 1, t, p);
    /* frames are where CSV readers may look: make every line so far visible */
    int r1 = csv_flush(&o->probes_csv), r2 = csv_flush(&o->energy_csv);
    return rc ? rc : r1 ? r1 : r2;
}

int pm_output_grid_frame(pm_output *o, const pm_grid *g, const pm_vtu_grid_fields *gf)
{
    if (o->n_frames == 0)
        return pm_error_set(PM_EINTERNAL, "a grid frame before its particle frame");
    char name[64], path[OUT_PATH_MAX];
    snprintf(name, sizeof name, "grid_%06zu.vtu", o->n_frames - 1);
    pm_check(join(path, o->dir, name));
    pm_check(pm_vtu_write_grid(path, g, gf, NULL));
    return write_pvd_of(o, "grid");
}

/* Re-find a followed particle after the particle arrays were reordered, by its id; -1 once a sink
 * removed it. */
static long refind(const probe *pr, const pm_particles *p)
{
    long i = pr->particle;
    if (i >= 0 && (size_t)i < p->n && p->id[i] == pr->id)
        return i;
    for (size_t j = 0; j < p->n; j++)
        if (p->id[j] == pr->id)
            return (long)j;
    return -1;
}

int pm_output_probes(pm_output *o, double t, const pm_particles *p)
{
    if (o->n_probes == 0)
        return PM_OK;
    if (o->probe_recorded && o->probe_interval > 0) {
        /* "at least probe_interval": forgive the rounding of a time summed from many steps */
        double tol = 1e-9 * o->probe_interval + 16 * DBL_EPSILON * fabs(t);
        if (t - o->last_probe_t < o->probe_interval - tol)
            return PM_OK;
    }
    csv_out *c = &o->probes_csv;
    pm_check(csv_add(c, "%.17g", t));
    for (size_t k = 0; k < o->n_probes; k++) {
        probe *pr = &o->pr[k];
        double v[PM_NS];
        const char *const *names;
        const int nc = quantity_comps(pr->quantity, &names);
        if (pr->body >= 0) {
            body_mean(p, pr->body, pr->quantity, v);
        } else {
            pr->particle = pr->gone ? -1 : refind(pr, p);
            pr->gone = pr->particle < 0;
            if (pr->gone) { /* removed by a sink: the series ends in empty cells */
                for (int j = 0; j < nc; j++)
                    pm_check(csv_add(c, ","));
                continue;
            }
            particle_value(p, (size_t)pr->particle, pr->quantity, v);
        }
        for (int j = 0; j < nc; j++)
            pm_check(csv_add(c, ",%.17g", v[j]));
    }
    o->probe_recorded = 1;
    o->last_probe_t = t;
    return csv_end_line(c);
}

int pm_output_energy(pm_output *o, double t, double kinetic, double strain, double gravity)
{
    /* one row per time: the final frame asks again for the state the cadence just wrote */
    if (t == o->last_energy_t)
        return PM_OK;
    o->last_energy_t = t;
    csv_out *c = &o->energy_csv;
    pm_check(csv_add(c, "%.17g,%.17g,%.17g,%.17g,%.17g", t, kinetic, strain, gravity,
                     kinetic + strain + gravity));
    return csv_end_line(c);
}

long pm_output_probe_particle(const pm_output *o, size_t k)
{
    if (!o || k >= o->n_probes || o->pr[k].body >= 0)
        return -1;
    return o->pr[k].particle;
}

int pm_output_close(pm_output *o, const pm_run_summary *s)
{
    if (!o)
        return PM_OK;
    int rc = pm_run_pictures_close(o->pics);
    int r1 = csv_close(&o->probes_csv);
    if (!rc)
        rc = r1;
    int r2 = csv_close(&o->energy_csv);
    if (!rc)
        rc = r2;
    if (s) {
        pm_probe_info *info = o->n_probes ? calloc(o->n_probes, sizeof *info) : NULL;
        int r3;
        if (o->n_probes && !info) {
            r3 = pm_error_set(PM_ENOMEM, "out of memory writing run.json");
        } else {
            for (size_t k = 0; k < o->n_probes; k++) {
                const probe *pr = &o->pr[k];
                info[k].name = pr->name;
                info[k].particle = pr->particle0;
                info[k].body = pr->body >= 0 ? o->body_names[pr->body] : NULL;
                info[k].quantity = quantity_names[pr->quantity];
                info[k].initial_position[0] = pr->init_pos[0];
                info[k].initial_position[1] = pr->init_pos[1];
            }
            char path[OUT_PATH_MAX];
            r3 = join(path, o->dir, "run.json");
            if (!r3)
                r3 = pm_run_json_write(path, s, info, o->n_probes, o->n_frames);
        }
        free(info);
        if (!rc)
            rc = r3;
    }
    free(o->scratch);
    free(o->frame_t);
    free(o->pr);
    free(o->body_names);
    free(o);
    return rc;
}
