/*
 * Frames read back (src/io/frame_read.c) and the derived particle fields written into them
 * (src/io/particle_fields.c).
 *
 * Read-back: what the VTU writer wrote comes back bit for bit (doubles are copied, integers are exact
 * in a double), the time too, and the grid_speed pictures draw grid_velocity's magnitude; files that are not frames pmech writes are refused with the file's name.
 * Derived fields against closed forms: uniaxial stress -100 Pa gives p = 100/3 and q = 100; a pure
 * shear stress tau gives q = sqrt(3) tau; F = diag(2, 1, 1) gives ln 2 volumetric and (2/3) ln 2
 * deviatoric strain; simple shear gamma gives 0 and (2/sqrt 3) asinh(gamma/2); a rotation gives 0 and
 * 0. Tolerance 1e-12 relative: the closed forms and the code differ only by rounding.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/particle_fields.h"
#include "io/vtu_write.h"
#include "pmech/error.h"
#include "pmech/frame.h"
#include "pmech/grid.h"
#include "pmech/render.h"

#define TOL 1e-12

static void near(double got, double want)
{
    if (!(fabs(got - want) <= TOL * fmax(1.0, fabs(want))))
        fail_msg("got %.17g, want %.17g", got, want);
}

static void make_particles(pm_particles *p, size_t n)
{
    assert_int_equal(pm_particles_alloc(p, n, 0), PM_OK);
    for (size_t i = 0; i < n; i++) {
        for (int d = 0; d < PM_DIM; d++) {
            p->x[PM_DIM * i + d] = 0.25 * (double)i + d;
            p->x0[PM_DIM * i + d] = 0.2 * (double)i;
            p->v[PM_DIM * i + d] = -1.5 * (double)i + 0.1 * d;
            p->v_grid[PM_DIM * i + d] = 0.75 * (double)i - 0.3 * d;
            p->hsize[PM_DIM * i + d] = 0.125;
        }
        for (int k = 0; k < PM_NS; k++)
            p->stress[PM_NS * i + k] = 1000.0 * (double)(k + 1) - 17.0 * (double)i;
        p->F[PM_NF * i + PM_FXX] = p->F[PM_NF * i + PM_FYY] = p->F[PM_NF * i + PM_FZZ] = 1.0 + 0.01 * (double)i;
        p->F[PM_NF * i + PM_FXY] = 0.1;
        p->eps_p[i] = 0.01 * (double)i;
        p->material[i] = (int32_t)(i % 3);
        p->body[i] = (int32_t)(i % 2);
        p->mass[i] = 3.0 + (double)i;
        p->vol[i] = 0.5 + (double)i;
        p->id[i] = (int32_t)(100 + 7 * i);
    }
}

static void particles_come_back_as_written(void **state)
{
    (void)state;
    pm_particles p;
    const size_t n = 7;
    make_particles(&p, n);
    double *scratch = malloc(3 * n * sizeof(double));
    assert_int_equal(pm_vtu_write_particles("frame_test.vtu", &p, scratch, 0.125), PM_OK);
    pm_frame *f = NULL;
    assert_int_equal(pm_frame_read("frame_test.vtu", &f), PM_OK);
    assert_int_equal(pm_frame_n_points(f), n);
    assert_true(pm_frame_time(f) == 0.125);
    int nc;
    const double *x = pm_frame_points(f), *v = pm_frame_array(f, "velocity", &nc);
    assert_int_equal(nc, 3);
    const double *vg = pm_frame_array(f, "grid_velocity", &nc);
    assert_int_equal(nc, 3);
    assert_non_null(vg);
    const double *s = pm_frame_array(f, "stress", &nc);
    assert_int_equal(nc, PM_NS);
    const double *body = pm_frame_array(f, "body", &nc), *F = pm_frame_array(f, "deformation_gradient", &nc);
    assert_int_equal(nc, PM_NF);
    const double *pr = pm_frame_array(f, "pressure", NULL), *q = pm_frame_array(f, "q", NULL);
    const double *hs = pm_frame_array(f, "half_size", &nc);
    assert_int_equal(nc, PM_DIM);
    const double *id = pm_frame_array(f, "id", &nc);
    assert_int_equal(nc, 1);
    assert_non_null(id);
    assert_non_null(x);
    assert_non_null(v);
    assert_non_null(s);
    assert_non_null(body);
    assert_non_null(F);
    assert_non_null(pr);
    assert_non_null(q);
    assert_non_null(hs);
    for (size_t i = 0; i < n; i++) {
        for (int d = 0; d < PM_DIM; d++) {
            assert_true(x[3 * i + d] == p.x[PM_DIM * i + d]);
            assert_true(v[3 * i + d] == p.v[PM_DIM * i + d]);
            assert_true(vg[3 * i + d] == p.v_grid[PM_DIM * i + d]);
            assert_true(hs[PM_DIM * i + d] == p.hsize[PM_DIM * i + d]);
        }
        assert_true(x[3 * i + 2] == 0);
        for (int k = 0; k < PM_NS; k++)
            assert_true(s[PM_NS * i + k] == p.stress[PM_NS * i + k]);
        for (int k = 0; k < PM_NF; k++)
            assert_true(F[PM_NF * i + k] == p.F[PM_NF * i + k]);
        assert_true(body[i] == p.body[i]);
        assert_true(id[i] == p.id[i]);
        assert_true(pr[i] == pm_pf_pressure(p.stress + PM_NS * i));
        assert_true(q[i] == pm_pf_q(p.stress + PM_NS * i));
    }
    /* grid_speed, as pictures draw it: the magnitude of grid_velocity, in m/s */
    double gs[7];
    const char *unit = NULL;
    int cat = -1;
    assert_int_equal(pm_frame_field(f, "grid_speed", gs, &unit, &cat), PM_OK);
    assert_string_equal(unit, "m/s");
    assert_int_equal(cat, 0);
    for (size_t i = 0; i < n; i++)
        near(gs[i], hypot(p.v_grid[PM_DIM * i], p.v_grid[PM_DIM * i + 1]));
    assert_null(pm_frame_array(f, "no_such_array", NULL));
    size_t names = pm_frame_n_arrays(f);
    assert_int_equal(names, 16);
    assert_string_equal(pm_frame_array_name(f, 0, &nc), "displacement");
    assert_null(pm_frame_array_name(f, names, &nc));
    pm_frame_free(f);
    free(scratch);
    pm_particles_free(&p);
    remove("frame_test.vtu");
}

/* A model's history variables come back as one array of n_state components; a run whose models
 * keep none writes no such array (above: 16 arrays). */
static void material_state_comes_back(void **state)
{
    (void)state;
    pm_particles p;
    const size_t n = 5, ns = 2;
    assert_int_equal(pm_particles_alloc(&p, n, ns), PM_OK);
    for (size_t i = 0; i < n * ns; i++)
        p.state[i] = 0.5 * (double)i - 1.25;
    double *scratch = malloc(3 * n * sizeof(double));
    assert_int_equal(pm_vtu_write_particles("state_test.vtu", &p, scratch, 0), PM_OK);
    pm_frame *f = NULL;
    assert_int_equal(pm_frame_read("state_test.vtu", &f), PM_OK);
    assert_int_equal(pm_frame_n_arrays(f), 17);
    int nc;
    const double *st = pm_frame_array(f, "material_state", &nc);
    assert_non_null(st);
    assert_int_equal(nc, (int)ns);
    for (size_t i = 0; i < n * ns; i++)
        assert_true(st[i] == p.state[i]);
    pm_frame_free(f);
    free(scratch);
    pm_particles_free(&p);
    remove("state_test.vtu");
}

static void derived_fields_against_closed_forms(void **state)
{
    (void)state;
    const double uni[4] = {-100, 0, 0, 0}, shear[4] = {0, 0, 0, 40};
    near(pm_pf_pressure(uni), 100.0 / 3.0);
    near(pm_pf_q(uni), 100.0);
    near(pm_pf_pressure(shear), 0);
    near(pm_pf_q(shear), sqrt(3.0) * 40);
    double vol, dev;
    const double stretch[PM_NF] = {[PM_FXX] = 2, [PM_FYY] = 1, [PM_FZZ] = 1};
    pm_pf_log_strain(stretch, &vol, &dev);
    near(vol, log(2.0));
    near(dev, 2.0 / 3.0 * log(2.0));
    const double g = 0.8, simple[PM_NF] = {[PM_FXX] = 1, [PM_FXY] = g, [PM_FYY] = 1, [PM_FZZ] = 1};
    pm_pf_log_strain(simple, &vol, &dev);
    near(vol, 0);
    near(dev, 2.0 / sqrt(3.0) * asinh(g / 2));
    const double a = 0.7, rot[PM_NF] = {[PM_FXX] = cos(a), [PM_FXY] = -sin(a), [PM_FYX] = sin(a), [PM_FYY] = cos(a),
                                        [PM_FZZ] = 1};
    pm_pf_log_strain(rot, &vol, &dev);
    near(vol, 0);
    near(dev, 0);
    /* axisymmetric hoop stretch only: F = diag(1, 1, 1.5) */
    const double hoop[PM_NF] = {[PM_FXX] = 1, [PM_FYY] = 1, [PM_FZZ] = 1.5};
    pm_pf_log_strain(hoop, &vol, &dev);
    near(vol, log(1.5));
    near(dev, 2.0 / 3.0 * log(1.5));
}

static void grid_fields_come_back(void **state)
{
    (void)state;
    pm_grid g;
    const double origin[PM_DIM] = {0, 0}, size[PM_DIM] = {2, 1};
    const int cells[PM_DIM] = {2, 1};
    assert_int_equal(pm_grid_rectangle(&g, origin, size, cells, PM_QUAD4), PM_OK);
    double mass[6], vel[12], t = 2.5;
    uint8_t bnd[6];
    int32_t con[6];
    for (int i = 0; i < 6; i++) {
        mass[i] = i * 0.5;
        vel[2 * i] = i;
        vel[2 * i + 1] = -i;
        bnd[i] = (uint8_t)(i % 4);
        con[i] = i == 3 ? 2 : 0;
    }
    const pm_vtu_grid_fields gf = {mass, vel, bnd, con, &t};
    assert_int_equal(pm_vtu_write_grid("grid_test.vtu", &g, &gf, NULL), PM_OK);
    pm_frame *f;
    assert_int_equal(pm_frame_read("grid_test.vtu", &f), PM_OK);
    assert_int_equal(pm_frame_n_points(f), 6);
    assert_true(pm_frame_time(f) == 2.5);
    int nc;
    const double *m = pm_frame_array(f, "mass", NULL), *v = pm_frame_array(f, "velocity", &nc);
    const double *b = pm_frame_array(f, "boundary", NULL), *c = pm_frame_array(f, "contact", NULL);
    assert_int_equal(nc, 3);
    for (int i = 0; i < 6; i++) {
        assert_true(m[i] == mass[i] && v[3 * i] == vel[2 * i] && v[3 * i + 1] == vel[2 * i + 1]);
        assert_true(b[i] == bnd[i] && c[i] == con[i]);
        assert_true(pm_frame_points(f)[3 * i] == g.x[2 * i]);
    }
    pm_frame_free(f);
    /* geometry only: no arrays, no time */
    assert_int_equal(pm_vtu_write_grid("grid_test.vtu", &g, NULL, NULL), PM_OK);
    assert_int_equal(pm_frame_read("grid_test.vtu", &f), PM_OK);
    assert_int_equal(pm_frame_n_arrays(f), 0);
    assert_true(isnan(pm_frame_time(f)));
    pm_frame_free(f);
    remove("grid_test.vtu");
    pm_grid_free(&g);
}

static void write_text(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, len, f), len);
    fclose(f);
}

static void expect_refused(const char *path, int code, const char *part)
{
    pm_frame *f = (pm_frame *)1;
    assert_int_equal(pm_frame_read(path, &f), code);
    assert_null(f);
    if (!strstr(pm_error_message(), path) || !strstr(pm_error_message(), part))
        fail_msg("message \"%s\" lacks \"%s\" or \"%s\"", pm_error_message(), path, part);
}

static void other_files_are_refused(void **state)
{
    (void)state;
    expect_refused("no_such_frame.vtu", PM_EIO, "cannot read");
    write_text("bad.vtu", "not xml at all", 14);
    expect_refused("bad.vtu", PM_EINPUT, "bad.vtu:1:");
    const char *poly = "<?xml version=\"1.0\"?><VTKFile type=\"PolyData\" byte_order=\"LittleEndian\"></VTKFile>";
    write_text("bad.vtu", poly, strlen(poly));
    expect_refused("bad.vtu", PM_EINPUT, "UnstructuredGrid");
    const char *zlib = "<?xml version=\"1.0\"?><VTKFile type=\"UnstructuredGrid\" byte_order=\"LittleEndian\" "
                       "compressor=\"vtkZLibDataCompressor\"></VTKFile>";
    write_text("bad.vtu", zlib, strlen(zlib));
    expect_refused("bad.vtu", PM_EINPUT, "compressed");
    /* a real frame cut short: its last block is missing */
    pm_particles p;
    make_particles(&p, 5);
    double scratch[15];
    assert_int_equal(pm_vtu_write_particles("bad.vtu", &p, scratch, 0), PM_OK);
    FILE *f = fopen("bad.vtu", "rb");
    char buf[16384];
    const size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    assert_true(len > 200 && len < sizeof buf);
    write_text("bad.vtu", buf, len - 200); /* the cells (not read) and part of the points */
    expect_refused("bad.vtu", PM_EINPUT, "past the end");
    pm_particles_free(&p);
    remove("bad.vtu");
}

static void a_series_lists_its_frames(void **state)
{
    (void)state;
    const char *pvd = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n"
                      "    <DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"particles_000000.vtu\"/>\n"
                      "    <DataSet timestep=\"0.5\" group=\"\" part=\"0\" file=\"particles_000001.vtu\"/>\n"
                      "  </Collection>\n</VTKFile>\n";
    write_text("series_test.pvd", pvd, strlen(pvd));
    pm_series s;
    assert_int_equal(pm_series_read("./series_test.pvd", &s), PM_OK);
    assert_int_equal(s.n, 2);
    assert_true(s.time[0] == 0 && s.time[1] == 0.5);
    assert_string_equal(s.file[1], "./particles_000001.vtu");
    pm_series_free(&s);
    const char *bad = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\"><Collection>\n"
                      "<DataSet timestep=\"x\" file=\"a.vtu\"/></Collection></VTKFile>\n";
    write_text("series_test.pvd", bad, strlen(bad));
    assert_int_equal(pm_series_read("series_test.pvd", &s), PM_EINPUT);
    assert_non_null(strstr(pm_error_message(), "series_test.pvd:3"));
    pm_series_free(&s);
    remove("series_test.pvd");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(particles_come_back_as_written),
        cmocka_unit_test(material_state_comes_back),
        cmocka_unit_test(derived_fields_against_closed_forms),
        cmocka_unit_test(grid_fields_come_back),
        cmocka_unit_test(other_files_are_refused),
        cmocka_unit_test(a_series_lists_its_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
