/* Output files: VTU/PVD frames, grid.vtu, probes.csv, energy.csv, run.json, atomic writes and
 * the output directory's housekeeping. Everything is written into a fresh temporary directory. */
#define _XOPEN_SOURCE 700 /* nftw */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pmech/case.h"
#include "pmech/error.h"
#include "pmech/grid.h"
#include "io/output.h"
#include "pmech/particles.h"
#include "io/progress.h"

/* ---- fixtures ------------------------------------------------------------------------------ */

typedef struct fixture {
    char dir[256];   /* temporary directory (removed at teardown) */
    char out[300];   /* output directory inside it */
    pm_case *c;
    pm_grid g;
    pm_particles p;
} fixture;

static int rm_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

/* Five particles in two bodies:
 *   i  x0          body  mass
 *   0  (0.125, 0.125)  0     1
 *   1  (0.375, 0.125)  0     3
 *   2  (0.5, 0.5)      1     2
 *   3  (0.375, 0.375)  0     4
 *   4  (0.875, 0.875)  1     2
 * (binary fractions, so that equal distances are exactly equal)
 * Displaced by (0.01 i, -0.02 i); v = (i, -i); stress = (10 i + 1, 10 i + 2, 10 i + 3, 10 i + 4);
 * eps_p = 0.1 i. */
static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    *state = f;
    snprintf(f->dir, sizeof f->dir, "/tmp/pmech_test_output_XXXXXX");
    f->c = calloc(1, sizeof *f->c);
    if (!f->c || !mkdtemp(f->dir))
        return -1;
    snprintf(f->out, sizeof f->out, "%s/a/b/out", f->dir);
    f->c->n_bodies = 2;
    f->c->bodies = calloc(2, sizeof *f->c->bodies);
    if (!f->c->bodies)
        return -1;
    snprintf(f->c->bodies[0].name, PM_NAME_MAX, "left");
    snprintf(f->c->bodies[1].name, PM_NAME_MAX, "right");
    snprintf(f->c->file, PM_PATH_MAX, "case.json");
    const double origin[2] = { 0, 0 }, size[2] = { 1, 1 };
    const int cells[2] = { 2, 2 };
    if (pm_grid_rectangle(&f->g, origin, size, cells, PM_QUAD4) != PM_OK)
        return -1;
    if (pm_particles_alloc(&f->p, 5, 0) != PM_OK)
        return -1;
    const double x0[10] = { 0.125, 0.125, 0.375, 0.125, 0.5, 0.5, 0.375, 0.375, 0.875, 0.875 };
    const int body[5] = { 0, 0, 1, 0, 1 };
    const double mass[5] = { 1, 3, 2, 4, 2 };
    for (int i = 0; i < 5; i++) {
        f->p.x0[2 * i] = f->p.x[2 * i] = x0[2 * i];
        f->p.x0[2 * i + 1] = f->p.x[2 * i + 1] = x0[2 * i + 1];
        f->p.body[i] = body[i];
        f->p.material[i] = 7;
        f->p.mass[i] = mass[i];
        f->p.vol[i] = 0.01 * (i + 1);
    }
    return 0;
}

static void move_particles(pm_particles *p)
{
    for (size_t i = 0; i < p->n; i++) {
        p->x[2 * i] = p->x0[2 * i] + 0.01 * (double)i;
        p->x[2 * i + 1] = p->x0[2 * i + 1] - 0.02 * (double)i;
        p->v[2 * i] = (double)i;
        p->v[2 * i + 1] = -(double)i;
        for (int k = 0; k < PM_NS; k++)
            p->stress[PM_NS * i + (size_t)k] = 10.0 * (double)i + k + 1;
        p->eps_p[i] = 0.1 * (double)i;
    }
}

static int teardown(void **state)
{
    fixture *f = *state;
    if (!f)
        return 0;
    if (strstr(f->dir, "XXXXXX") == NULL)
        nftw(f->dir, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    if (f->c) {
        free(f->c->bodies);
        free(f->c->probes);
        free(f->c);
    }
    pm_grid_free(&f->g);
    pm_particles_free(&f->p);
    free(f);
    return 0;
}

static void add_probe(pm_case *c, const char *name, pm_quantity q, int body, double px, double py)
{
    c->probes = realloc(c->probes, (c->n_probes + 1) * sizeof *c->probes);
    pm_case_probe *pr = &c->probes[c->n_probes++];
    memset(pr, 0, sizeof *pr);
    snprintf(pr->name, sizeof pr->name, "%s", name);
    pr->quantity = q;
    pr->body = body;
    pr->point[0] = px;
    pr->point[1] = py;
}

/* ---- helpers ------------------------------------------------------------------------------- */

static char *slurp(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    size_t got = fread(buf, 1, (size_t)n, fp);
    fclose(fp);
    buf[got] = '\0';
    if (len)
        *len = got;
    return buf;
}

static char *slurp_in(const char *dir, const char *name, size_t *len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return slurp(path, len);
}

static int exists_in(const char *dir, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return access(path, F_OK) == 0;
}

/* Number of entries of dir whose name contains s. */
static int count_containing(const char *dir, const char *s)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strstr(e->d_name, s))
            n++;
    closedir(d);
    return n;
}

/* Line k (0-based) of text, without its newline, into buf. */
static const char *line_of(const char *text, int k, char *buf, size_t n)
{
    for (int i = 0; i < k && text; i++) {
        text = strchr(text, '\n');
        if (text)
            text++;
    }
    if (!text || !*text)
        return NULL;
    size_t l = strcspn(text, "\n");
    if (l >= n)
        l = n - 1;
    memcpy(buf, text, l);
    buf[l] = '\0';
    return buf;
}

/* Parse a CSV data row into vals; returns the number of values. */
static int parse_row(const char *line, double *vals, int max)
{
    int n = 0;
    const char *s = line;
    while (n < max && *s) {
        char *end;
        vals[n++] = strtod(s, &end);
        if (*end != ',')
            break;
        s = end + 1;
    }
    return n;
}

static void open_default(fixture *f, pm_output **o)
{
    int rc = pm_output_open(o, f->out, f->c, &f->g, &f->p);
    if (rc)
        fprintf(stderr, "pm_output_open: %s\n", pm_error_message());
    assert_int_equal(rc, PM_OK);
    assert_non_null(*o);
}

static pm_run_summary summary(void)
{
    pm_run_summary s = {
        .version = "9.8.7", .case_file = "case.json", .steps = 1234, .dt_min = 1e-6, .dt_max = 2.5e-6,
        .end_time = 0.125, .wall_seconds = 3.5, .loop_seconds = 2.75, .particle_steps_per_second = 0.1 + 0.2,
        .particles = 5, .exit_status = 1, .message = "step 12: particle 3 \"inverted\"", .threads = 4,
    };
    return s;
}

/* ---- VTU reading (just enough to check the layout) ----------------------------------------- */

/* Value of attribute attr in the first element after *from that contains key, e.g. the offset of
 * Name="stress". Returns a pointer to the value (up to the quote) or NULL. */
static const char *attr_after(const char *text, const char *key, const char *attr, char *buf, size_t n)
{
    const char *s = strstr(text, key);
    if (!s)
        return NULL;
    const char *end = strchr(s, '>');
    char pat[64];
    snprintf(pat, sizeof pat, " %s=\"", attr);
    /* the element starts at the last '<' before key */
    const char *start = s;
    while (start > text && *start != '<')
        start--;
    const char *a = strstr(start, pat);
    if (!a || a > end)
        return NULL;
    a += strlen(pat);
    size_t l = strcspn(a, "\"");
    if (l >= n)
        l = n - 1;
    memcpy(buf, a, l);
    buf[l] = '\0';
    return buf;
}

/* The appended block of the DataArray whose Name is name; its byte count in *bytes. */
static const unsigned char *vtu_block(const char *text, const char *name, uint64_t *bytes)
{
    char key[80], val[64];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    if (!attr_after(text, key, "offset", val, sizeof val))
        return NULL;
    const char *app = strstr(text, "<AppendedData encoding=\"raw\">");
    if (!app)
        return NULL;
    const char *us = strchr(app, '_');
    const unsigned char *blk = (const unsigned char *)us + 1 + strtoull(val, NULL, 10);
    memcpy(bytes, blk, sizeof *bytes);
    return blk + sizeof *bytes;
}

/* ---- tests --------------------------------------------------------------------------------- */

static void frames_pvd_and_grid(void **state)
{
    fixture *f = *state;
    pm_output *o;
    open_default(f, &o);
    assert_true(exists_in(f->out, "grid.vtu"));
    assert_true(exists_in(f->out, "energy.csv"));
    assert_false(exists_in(f->out, "probes.csv")); /* no probes: no file */
    assert_int_equal(pm_output_frame(o, 0.0, &f->p), PM_OK);
    char *pvd = slurp_in(f->out, "particles.pvd", NULL);
    assert_non_null(pvd);
    assert_non_null(strstr(pvd, "file=\"particles_000000.vtu\""));
    assert_null(strstr(pvd, "particles_000001.vtu"));
    free(pvd);
    move_particles(&f->p);
    assert_int_equal(pm_output_frame(o, 0.1, &f->p), PM_OK);
    assert_int_equal(pm_output_frame(o, 0.30000000000000004, &f->p), PM_OK);
    pm_run_summary s = summary();
    assert_int_equal(pm_output_close(o, &s), PM_OK);
    assert_true(exists_in(f->out, "particles_000000.vtu"));
    assert_true(exists_in(f->out, "particles_000001.vtu"));
    assert_true(exists_in(f->out, "particles_000002.vtu"));
    assert_false(exists_in(f->out, "particles_000003.vtu"));
    assert_int_equal(count_containing(f->out, "tmp"), 0);

    pvd = slurp_in(f->out, "particles.pvd", NULL);
    assert_non_null(pvd);
    assert_non_null(strstr(pvd, "<VTKFile type=\"Collection\""));
    assert_non_null(strstr(pvd, "</VTKFile>"));
    assert_non_null(strstr(pvd, "timestep=\"0\" group=\"\" part=\"0\" file=\"particles_000000.vtu\""));
    assert_non_null(strstr(pvd, "timestep=\"0.10000000000000001\" group=\"\" part=\"0\" file=\"particles_000001.vtu\""));
    /* times round-trip */
    assert_non_null(strstr(pvd, "timestep=\"0.30000000000000004\""));
    free(pvd);

    char *grid = slurp_in(f->out, "grid.vtu", NULL);
    assert_non_null(grid);
    assert_non_null(strstr(grid, "NumberOfPoints=\"9\" NumberOfCells=\"4\""));
    uint64_t bytes = 0;
    const unsigned char *types = vtu_block(grid, "types", &bytes);
    assert_non_null(types);
    assert_int_equal(bytes, 4);
    for (int k = 0; k < 4; k++)
        assert_int_equal(types[k], 9);
    const unsigned char *conn = vtu_block(grid, "connectivity", &bytes);
    assert_int_equal(bytes, 16 * sizeof(int64_t));
    for (int k = 0; k < 16; k++) {
        int64_t v;
        memcpy(&v, conn + 8 * k, 8);
        assert_int_equal(v, f->g.conn[k]);
    }
    free(grid);
}

static void vtu_arrays_hold_the_particles(void **state)
{
    fixture *f = *state;
    move_particles(&f->p);
    pm_output *o;
    open_default(f, &o);
    assert_int_equal(pm_output_frame(o, 0.5, &f->p), PM_OK);
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
    size_t len = 0;
    char *v = slurp_in(f->out, "particles_000000.vtu", &len);
    assert_non_null(v);
    assert_non_null(strstr(v, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                              "header_type=\"UInt64\">"));
    assert_non_null(strstr(v, "NumberOfPoints=\"5\" NumberOfCells=\"5\""));
    assert_non_null(strstr(v, "Name=\"stress\" NumberOfComponents=\"4\" ComponentName0=\"xx\" "
                              "ComponentName1=\"yy\" ComponentName2=\"zz\" ComponentName3=\"xy\""));
    assert_non_null(strstr(v, "type=\"Int32\" Name=\"material\""));
    assert_non_null(strstr(v, "type=\"Int32\" Name=\"body\""));
    /* the file ends right after the last block and the closing tags */
    static const char end[] = "\n  </AppendedData>\n</VTKFile>\n";
    assert_true(len > sizeof end);
    assert_memory_equal(v + len - (sizeof end - 1), end, sizeof end - 1);

    uint64_t bytes = 0;
    const unsigned char *b = vtu_block(v, "displacement", &bytes);
    assert_non_null(b);
    assert_int_equal(bytes, 5 * 3 * sizeof(double));
    for (int i = 0; i < 5; i++) {
        double d[3];
        memcpy(d, b + 24 * i, 24);
        assert_true(d[0] == f->p.x[2 * i] - f->p.x0[2 * i]);
        assert_true(d[1] == f->p.x[2 * i + 1] - f->p.x0[2 * i + 1]);
        assert_true(d[2] == 0.0);
    }
    b = vtu_block(v, "velocity", &bytes);
    assert_int_equal(bytes, 5 * 3 * sizeof(double));
    double vv[3];
    memcpy(vv, b + 24 * 3, 24);
    assert_true(vv[0] == 3.0 && vv[1] == -3.0 && vv[2] == 0.0);
    b = vtu_block(v, "stress", &bytes);
    assert_int_equal(bytes, 5 * 4 * sizeof(double));
    assert_memory_equal(b, f->p.stress, bytes);
    b = vtu_block(v, "plastic_strain", &bytes);
    assert_memory_equal(b, f->p.eps_p, 5 * sizeof(double));
    b = vtu_block(v, "material", &bytes);
    assert_int_equal(bytes, 5 * sizeof(int32_t));
    assert_memory_equal(b, f->p.material, bytes);
    b = vtu_block(v, "body", &bytes);
    assert_memory_equal(b, f->p.body, 5 * sizeof(int32_t));
    b = vtu_block(v, "mass", &bytes);
    assert_memory_equal(b, f->p.mass, 5 * sizeof(double));
    b = vtu_block(v, "volume", &bytes);
    assert_memory_equal(b, f->p.vol, 5 * sizeof(double));
    b = vtu_block(v, "Points", &bytes);
    assert_int_equal(bytes, 5 * 3 * sizeof(double));
    memcpy(vv, b + 24 * 4, 24);
    assert_true(vv[0] == f->p.x[8] && vv[1] == f->p.x[9] && vv[2] == 0.0);
    b = vtu_block(v, "offsets", &bytes);
    assert_int_equal(bytes, 5 * sizeof(int64_t));
    int64_t off;
    memcpy(&off, b + 8 * 4, 8);
    assert_int_equal(off, 5);
    b = vtu_block(v, "types", &bytes);
    assert_int_equal(bytes, 5);
    for (int i = 0; i < 5; i++)
        assert_int_equal(b[i], 1);
    free(v);
}

static void probes_follow_nearest_particle_ties_to_lowest(void **state)
{
    fixture *f = *state;
    /* (0.375, 0.25) is 0.125 from particle 1 and from particle 3: the lowest index wins */
    add_probe(f->c, "tie", PM_Q_VELOCITY, -1, 0.375, 0.25);
    add_probe(f->c, "far", PM_Q_POSITION, -1, 2.0, 2.0);     /* nearest: particle 4 */
    add_probe(f->c, "mass", PM_Q_POSITION, 0, 0, 0);         /* body 0 */
    pm_output *o;
    open_default(f, &o);
    assert_int_equal(pm_output_probe_particle(o, 0), 1);
    assert_int_equal(pm_output_probe_particle(o, 1), 4);
    assert_int_equal(pm_output_probe_particle(o, 2), -1);
    assert_int_equal(pm_output_probe_particle(o, 3), -1);
    pm_run_summary s = summary();
    assert_int_equal(pm_output_close(o, &s), PM_OK);

    /* more ties: between 2 and 3 (diagonal), between 0 and 1 */
    f->c->n_probes = 0;
    add_probe(f->c, "tie2", PM_Q_VELOCITY, -1, 0.4375, 0.4375);
    add_probe(f->c, "tie3", PM_Q_VELOCITY, -1, 0.25, 0.125);
    open_default(f, &o);
    assert_int_equal(pm_output_probe_particle(o, 0), 2);
    assert_int_equal(pm_output_probe_particle(o, 1), 0);
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
}

static void probes_csv_header_rows_and_body_means(void **state)
{
    fixture *f = *state;
    add_probe(f->c, "A", PM_Q_VELOCITY, -1, 0.31, 0.12);        /* particle 1 */
    add_probe(f->c, "B", PM_Q_DISPLACEMENT, -1, 0.9, 0.9);       /* particle 4 */
    add_probe(f->c, "C", PM_Q_STRESS, 0, 0, 0);                  /* body 0: particles 0, 1, 3 */
    add_probe(f->c, "D", PM_Q_PLASTIC_STRAIN, 1, 0, 0);          /* body 1: particles 2, 4 */
    add_probe(f->c, "E", PM_Q_POSITION, 1, 0, 0);                /* body 1 centre of mass */
    pm_output *o;
    open_default(f, &o);
    assert_int_equal(pm_output_probes(o, 0.0, &f->p), PM_OK);
    move_particles(&f->p);
    assert_int_equal(pm_output_probes(o, 0.25, &f->p), PM_OK);
    assert_int_equal(pm_output_energy(o, 0.25, 1.5, 2.25, -0.5), PM_OK);
    /* the frame makes every line so far reach the file */
    assert_int_equal(pm_output_frame(o, 0.25, &f->p), PM_OK);
    char *csv = slurp_in(f->out, "probes.csv", NULL);
    assert_non_null(csv);
    char line[1024];
    assert_string_equal(line_of(csv, 0, line, sizeof line),
                        "time,A.vx,A.vy,B.ux,B.uy,C.sxx,C.syy,C.szz,C.sxy,D.eps_p,E.x,E.y");
    double v[16];
    assert_int_equal(parse_row(line_of(csv, 1, line, sizeof line), v, 16), 12);
    /* t = 0: everything at rest, E at the centre of mass of body 1 (equal masses) */
    assert_true(v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0 && v[3] == 0.0 && v[4] == 0.0);
    assert_true(v[10] == 0.6875 && v[11] == 0.6875);
    assert_int_equal(parse_row(line_of(csv, 2, line, sizeof line), v, 16), 12);
    assert_true(v[0] == 0.25);
    assert_true(v[1] == 1.0 && v[2] == -1.0);                     /* A: velocity of particle 1 */
    assert_true(fabs(v[3] - 0.04) < 1e-15 && fabs(v[4] + 0.08) < 1e-15); /* B: displacement of 4 */
    /* C: masses 1, 3, 4 for particles 0, 1, 3; sxx = 10 i + 1 */
    double m = 1 + 3 + 4;
    assert_true(fabs(v[5] - (1 * 1 + 3 * 11 + 4 * 31) / m) < 1e-12);
    assert_true(fabs(v[6] - (1 * 2 + 3 * 12 + 4 * 32) / m) < 1e-12);
    assert_true(fabs(v[7] - (1 * 3 + 3 * 13 + 4 * 33) / m) < 1e-12);
    assert_true(fabs(v[8] - (1 * 4 + 3 * 14 + 4 * 34) / m) < 1e-12);
    /* D: particles 2 and 4, mass 2 each: eps_p 0.2 and 0.4 */
    assert_true(fabs(v[9] - 0.3) < 1e-15);
    /* E: x = (0.52 + 0.915) / 2, y = (0.46 + 0.795) / 2 */
    assert_true(fabs(v[10] - 0.7175) < 1e-15 && fabs(v[11] - 0.6275) < 1e-15);
    assert_null(line_of(csv, 3, line, sizeof line));
    free(csv);

    char *en = slurp_in(f->out, "energy.csv", NULL);
    assert_string_equal(en, "time,kinetic,strain,gravity,total\n0.25,1.5,2.25,-0.5,3.25\n");
    free(en);
    pm_run_summary s = summary();
    assert_int_equal(pm_output_close(o, &s), PM_OK);

    /* run.json: probes recorded with their particle, body and initial position */
    char path[512];
    snprintf(path, sizeof path, "%s/run.json", f->out);
    json_error_t err;
    json_t *r = json_load_file(path, 0, &err);
    assert_non_null(r);
    json_t *pr = json_object_get(r, "probes");
    assert_int_equal(json_array_size(pr), 5);
    json_t *a = json_array_get(pr, 0), *c = json_array_get(pr, 2), *e = json_array_get(pr, 4);
    assert_string_equal(json_string_value(json_object_get(a, "name")), "A");
    assert_int_equal(json_integer_value(json_object_get(a, "particle")), 1);
    assert_true(json_is_null(json_object_get(a, "body")));
    assert_string_equal(json_string_value(json_object_get(a, "quantity")), "velocity");
    json_t *ip = json_object_get(a, "initial_position");
    assert_true(json_real_value(json_array_get(ip, 0)) == 0.375);
    assert_true(json_real_value(json_array_get(ip, 1)) == 0.125);
    assert_true(json_is_null(json_object_get(c, "particle")));
    assert_string_equal(json_string_value(json_object_get(c, "body")), "left");
    assert_string_equal(json_string_value(json_object_get(c, "quantity")), "stress");
    assert_string_equal(json_string_value(json_object_get(e, "body")), "right");
    assert_string_equal(json_string_value(json_object_get(e, "quantity")), "position");
    ip = json_object_get(e, "initial_position");
    assert_true(json_real_value(json_array_get(ip, 0)) == 0.6875);
    json_decref(r);
}

static void probe_interval_thins_rows(void **state)
{
    fixture *f = *state;
    add_probe(f->c, "P", PM_Q_PLASTIC_STRAIN, -1, 0, 0);
    f->c->output.probe_interval = 0.1;
    pm_output *o;
    open_default(f, &o);
    /* steps of 0.03 s: rows at 0, 0.12 (>= 0.1 after 0), 0.24, 0.36 ... */
    double t = 0;
    for (int k = 0; k <= 10; k++, t += 0.03)
        assert_int_equal(pm_output_probes(o, t, &f->p), PM_OK);
    /* dt = interval exactly, summed with rounding: every step is recorded */
    for (int k = 0; k < 10; k++) {
        t += 0.1;
        assert_int_equal(pm_output_probes(o, t, &f->p), PM_OK);
    }
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
    char *csv = slurp_in(f->out, "probes.csv", NULL);
    assert_non_null(csv);
    char line[256];
    assert_string_equal(line_of(csv, 0, line, sizeof line), "time,P.eps_p");
    const double want[] = { 0, 0.12, 0.24 };
    for (int k = 0; k < 3; k++) {
        double v[2] = { 0, 0 };
        assert_int_equal(parse_row(line_of(csv, k + 1, line, sizeof line), v, 2), 2);
        assert_true(fabs(v[0] - want[k]) < 1e-12);
    }
    int lines = 0;
    for (const char *s = csv; *s; s++)
        lines += *s == '\n';
    /* header + 0, 0.12, 0.24 (0.27 and 0.30 are too close) + the 10 steps of 0.1 */
    assert_int_equal(lines, 1 + 3 + 10);
    /* complete lines only */
    assert_true(csv[strlen(csv) - 1] == '\n');
    free(csv);
}

static void followed_particle_survives_reordering(void **state)
{
    fixture *f = *state;
    add_probe(f->c, "Q", PM_Q_VELOCITY, -1, 0.5, 0.5); /* particle 2 */
    pm_output *o;
    open_default(f, &o);
    move_particles(&f->p);
    /* swap particles 2 and 4, as a sort by cell would */
    pm_particles *p = &f->p;
    for (int k = 0; k < 2; k++) {
        double t;
        t = p->x[4 + k], p->x[4 + k] = p->x[8 + k], p->x[8 + k] = t;
        t = p->x0[4 + k], p->x0[4 + k] = p->x0[8 + k], p->x0[8 + k] = t;
        t = p->v[4 + k], p->v[4 + k] = p->v[8 + k], p->v[8 + k] = t;
    }
    int32_t id = p->id[2];
    p->id[2] = p->id[4];
    p->id[4] = id;
    assert_int_equal(pm_output_probes(o, 1.0, &f->p), PM_OK);
    assert_int_equal(pm_output_probe_particle(o, 0), 4);
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
    char *csv = slurp_in(f->out, "probes.csv", NULL);
    assert_string_equal(csv, "time,Q.vx,Q.vy\n1,2,-2\n");
    free(csv);
}

/* A sink may take the followed particle: its series ends in empty cells, the other probes go on. */
static void removed_particle_ends_its_series(void **state)
{
    fixture *f = *state;
    add_probe(f->c, "Q", PM_Q_VELOCITY, -1, 0.5, 0.5); /* particle 2 */
    add_probe(f->c, "R", PM_Q_VELOCITY, -1, 0.875, 0.875); /* particle 4 */
    pm_output *o;
    open_default(f, &o);
    move_particles(&f->p);
    assert_int_equal(pm_output_probes(o, 1.0, &f->p), PM_OK);
    const uint8_t drop[5] = { 0, 0, 1, 0, 0 };
    assert_int_equal(pm_particles_remove(&f->p, drop), 1);
    assert_int_equal(pm_output_probes(o, 2.0, &f->p), PM_OK);
    assert_int_equal(pm_output_probe_particle(o, 0), -1);
    assert_int_equal(pm_output_probe_particle(o, 1), 3);
    assert_int_equal(pm_output_probes(o, 3.0, &f->p), PM_OK);
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
    char *csv = slurp_in(f->out, "probes.csv", NULL);
    assert_string_equal(csv, "time,Q.vx,Q.vy,R.vx,R.vy\n1,2,-2,4,-4\n2,,,4,-4\n3,,,4,-4\n");
    free(csv);
}

static void run_json_keys_and_values(void **state)
{
    fixture *f = *state;
    pm_output *o;
    open_default(f, &o);
    assert_int_equal(pm_output_frame(o, 0, &f->p), PM_OK);
    pm_run_summary s = summary();
    assert_int_equal(pm_output_close(o, &s), PM_OK);
    char path[512];
    snprintf(path, sizeof path, "%s/run.json", f->out);
    json_error_t err;
    json_t *r = json_load_file(path, 0, &err);
    assert_non_null(r);
    assert_string_equal(json_string_value(json_object_get(r, "version")), "9.8.7");
    assert_string_equal(json_string_value(json_object_get(r, "case")), "case.json");
    assert_int_equal(json_integer_value(json_object_get(r, "steps")), 1234);
    assert_true(json_real_value(json_object_get(r, "dt_min")) == 1e-6);
    assert_true(json_real_value(json_object_get(r, "dt_max")) == 2.5e-6);
    assert_true(json_real_value(json_object_get(r, "end_time")) == 0.125);
    assert_true(json_real_value(json_object_get(r, "wall_seconds")) == 3.5);
    assert_true(json_real_value(json_object_get(r, "loop_seconds")) == 2.75);
    /* 0.1 + 0.2 needs all 17 digits to round-trip */
    assert_true(json_real_value(json_object_get(r, "particle_steps_per_second")) == 0.1 + 0.2);
    assert_int_equal(json_integer_value(json_object_get(r, "particles")), 5);
    assert_int_equal(json_integer_value(json_object_get(r, "threads")), 4);
    assert_int_equal(json_integer_value(json_object_get(r, "exit_status")), 1);
    assert_string_equal(json_string_value(json_object_get(r, "message")), "step 12: particle 3 \"inverted\"");
    assert_true(json_is_array(json_object_get(r, "probes")));
    assert_int_equal(json_array_size(json_object_get(r, "probes")), 0);
    json_decref(r);
    /* pretty-printed, newline-terminated */
    char *text = slurp(path, NULL);
    assert_non_null(strstr(text, "{\n  \"version\": \"9.8.7\","));
    assert_true(text[strlen(text) - 1] == '\n');
    free(text);
    assert_int_equal(count_containing(f->out, "tmp"), 0);
}

static void stale_files_of_an_earlier_run_are_removed(void **state)
{
    fixture *f = *state;
    assert_int_equal(pm_mkdir_p(f->out), PM_OK);
    const char *stale[] = { "particles_000000.vtu", "particles_000007.vtu", "particles_1234567.vtu",
                            "particles_000003.vtu.tmp", "particles.pvd", "run.json", "probes.csv",
                            "particles_000002.png" };
    for (size_t k = 0; k < sizeof stale / sizeof stale[0]; k++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", f->out, stale[k]);
        assert_int_equal(pm_write_file_atomic(path, "old", 3), PM_OK);
    }
    char keep[512];
    snprintf(keep, sizeof keep, "%s/particles_notes.vtu", f->out);
    assert_int_equal(pm_write_file_atomic(keep, "mine", 4), PM_OK);
    pm_output *o;
    open_default(f, &o);
    for (size_t k = 0; k < sizeof stale / sizeof stale[0]; k++)
        assert_false(exists_in(f->out, stale[k]));
    assert_true(exists_in(f->out, "particles_notes.vtu"));
    assert_int_equal(pm_output_frame(o, 0, &f->p), PM_OK);
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
    assert_int_equal(count_containing(f->out, "particles_0"), 1);
    assert_true(exists_in(f->out, "particles.pvd"));
}

static void errors_name_the_path(void **state)
{
    fixture *f = *state;
    char file[512], under[600];
    snprintf(file, sizeof file, "%s/plainfile", f->dir);
    assert_int_equal(pm_write_file_atomic(file, "x", 1), PM_OK);
    snprintf(under, sizeof under, "%s/sub/out", file);
    pm_output *o = (pm_output *)1;
    assert_int_equal(pm_output_open(&o, under, f->c, &f->g, &f->p), PM_EIO);
    assert_null(o);
    assert_non_null(strstr(pm_error_message(), file));
    assert_int_equal(pm_mkdir_p(under), PM_EIO);
    assert_non_null(strstr(pm_error_message(), "plainfile"));
    char missing[600];
    snprintf(missing, sizeof missing, "%s/no/such/dir/x.txt", f->dir);
    assert_int_equal(pm_write_file_atomic(missing, "x", 1), PM_EIO);
    assert_non_null(strstr(pm_error_message(), "no/such/dir/x.txt"));
    assert_non_null(strstr(pm_error_message(), strerror(ENOENT)));
    /* a body probe on a body without particles is an input error */
    add_probe(f->c, "Z", PM_Q_VELOCITY, 1, 0, 0);
    for (int i = 0; i < 5; i++)
        f->p.body[i] = 0;
    assert_int_equal(pm_output_open(&o, f->out, f->c, &f->g, &f->p), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "probes[0]"));
    assert_non_null(strstr(pm_error_message(), "right"));
    assert_int_equal(pm_output_close(NULL, NULL), PM_OK);
}

static void atomic_write_and_mkdir(void **state)
{
    fixture *f = *state;
    char d[512], path[600];
    snprintf(d, sizeof d, "%s/x//y/z/", f->dir);
    assert_int_equal(pm_mkdir_p(d), PM_OK);
    assert_int_equal(pm_mkdir_p(d), PM_OK); /* existing is fine */
    snprintf(path, sizeof path, "%s/file.txt", d);
    assert_int_equal(pm_write_file_atomic(path, "first", 5), PM_OK);
    assert_int_equal(pm_write_file_atomic(path, "second\n", 7), PM_OK);
    char *t = slurp(path, NULL);
    assert_string_equal(t, "second\n");
    free(t);
    assert_int_equal(pm_write_file_atomic(path, "", 0), PM_OK);
    t = slurp(path, NULL);
    assert_string_equal(t, "");
    free(t);
    assert_int_equal(count_containing(d, "tmp"), 0);
}

/* A frame of a million particles is written whole. Its time is printed, not judged: a wall-clock
 * bound fails on a loaded machine (speed is measured in bench/, docs/performance.md). */
static void million_particle_frame_is_whole(void **state)
{
    fixture *f = *state;
    pm_particles big;
    const size_t n = 1000000;
    assert_int_equal(pm_particles_alloc(&big, n, 0), PM_OK);
    for (size_t i = 0; i < n; i++) {
        big.x[2 * i] = big.x0[2 * i] = (double)(i % 1000) * 1e-3;
        big.x[2 * i + 1] = big.x0[2 * i + 1] = (double)(i / 1000) * 1e-3;
        big.mass[i] = 1;
    }
    pm_output *o;
    assert_int_equal(pm_output_open(&o, f->out, f->c, &f->g, &big), PM_OK);
    assert_int_equal(pm_output_frame(o, 0, &big), PM_OK); /* first touch of the scratch */
    double w0 = pm_wall_seconds();
    assert_int_equal(pm_output_frame(o, 1, &big), PM_OK);
    double w = pm_wall_seconds() - w0;
    print_message("one frame of %zu particles: %.3f s\n", n, w);
    assert_int_equal(pm_output_close(o, NULL), PM_OK);
    /* at least the positions, three doubles per particle, must be in the file */
    char path[4096];
    snprintf(path, sizeof path, "%s/particles_000001.vtu", f->out);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_true((double)st.st_size >= 24.0 * (double)n);
    pm_particles_free(&big);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(frames_pvd_and_grid, setup, teardown),
        cmocka_unit_test_setup_teardown(vtu_arrays_hold_the_particles, setup, teardown),
        cmocka_unit_test_setup_teardown(probes_follow_nearest_particle_ties_to_lowest, setup, teardown),
        cmocka_unit_test_setup_teardown(probes_csv_header_rows_and_body_means, setup, teardown),
        cmocka_unit_test_setup_teardown(probe_interval_thins_rows, setup, teardown),
        cmocka_unit_test_setup_teardown(removed_particle_ends_its_series, setup, teardown),
        cmocka_unit_test_setup_teardown(followed_particle_survives_reordering, setup, teardown),
        cmocka_unit_test_setup_teardown(run_json_keys_and_values, setup, teardown),
        cmocka_unit_test_setup_teardown(stale_files_of_an_earlier_run_are_removed, setup, teardown),
        cmocka_unit_test_setup_teardown(errors_name_the_path, setup, teardown),
        cmocka_unit_test_setup_teardown(atomic_write_and_mkdir, setup, teardown),
        cmocka_unit_test_setup_teardown(million_particle_frame_is_whole, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
