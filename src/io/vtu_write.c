/* VTK XML UnstructuredGrid files with binary appended (raw) data: no base64 or compression cost,
 * one fwrite per array, so a million particles take a fraction of a second. */
#include "io/vtu_write.h"
#include "io/particle_fields.h"
#include "pmech/error.h"

#include <errno.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define PM_VTU_BYTE_ORDER "BigEndian"
#else
#define PM_VTU_BYTE_ORDER "LittleEndian"
#endif

/* VTK cell type codes */
enum { VTK_VERTEX = 1, VTK_TRIANGLE = 5, VTK_QUAD = 9 };

static const char *type_name(pm_vtu_type t)
{
    switch (t) {
    case PM_VTU_I32: return "Int32";
    case PM_VTU_I64: return "Int64";
    case PM_VTU_U8: return "UInt8";
    default: return "Float64";
    }
}

size_t pm_vtu_type_size(pm_vtu_type t)
{
    switch (t) {
    case PM_VTU_I32: return 4;
    case PM_VTU_I64: return 8;
    case PM_VTU_U8: return 1;
    default: return 8;
    }
}

/* One <DataArray .../> referring to the appended block at *offset; advances *offset past it. */
static void data_array(FILE *f, const char *indent, const char *name, pm_vtu_type t, int ncomp,
                       const char *const *comp_names, size_t count, uint64_t *offset)
{
    fprintf(f, "%s<DataArray type=\"%s\" Name=\"%s\"", indent, type_name(t), name);
    if (ncomp > 1)
        fprintf(f, " NumberOfComponents=\"%d\"", ncomp);
    for (int k = 0; comp_names && k < ncomp; k++)
        fprintf(f, " ComponentName%d=\"%s\"", k, comp_names[k]);
    fprintf(f, " format=\"appended\" offset=\"%" PRIu64 "\"/>\n", *offset);
    *offset += sizeof(uint64_t) + (uint64_t)count * (uint64_t)ncomp * pm_vtu_type_size(t);
}

int pm_vtu_write_header(FILE *f, const pm_vtu_piece *pc)
{
    uint64_t off = 0;
    fprintf(f, "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"" PM_VTU_BYTE_ORDER
               "\" header_type=\"UInt64\">\n"
               "  <UnstructuredGrid>\n");
    if (pc->time)
        fprintf(f, "    <FieldData>\n"
                   "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">%.17g"
                   "</DataArray>\n"
                   "    </FieldData>\n",
                *pc->time);
    fprintf(f, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", pc->n_points, pc->n_cells);
    if (pc->n_point_data) {
        fprintf(f, "      <PointData>\n");
        for (size_t k = 0; k < pc->n_point_data; k++) {
            const pm_vtu_array *a = &pc->point_data[k];
            data_array(f, "        ", a->name, a->type, a->ncomp, a->comp_names, pc->n_points, &off);
        }
        fprintf(f, "      </PointData>\n");
    }
    fprintf(f, "      <Points>\n");
    data_array(f, "        ", "Points", PM_VTU_F64, 3, NULL, pc->n_points, &off);
    fprintf(f, "      </Points>\n      <Cells>\n");
    data_array(f, "        ", "connectivity", PM_VTU_I64, 1, NULL, pc->conn_len, &off);
    data_array(f, "        ", "offsets", PM_VTU_I64, 1, NULL, pc->n_cells, &off);
    data_array(f, "        ", "types", PM_VTU_U8, 1, NULL, pc->n_cells, &off);
    fprintf(f, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
               "  <AppendedData encoding=\"raw\">\n   _");
    return ferror(f) ? pm_error_set(PM_EIO, "%s", strerror(errno)) : PM_OK;
}

int pm_vtu_write_block(FILE *f, const void *data, size_t bytes)
{
    uint64_t h = bytes;
    if (fwrite(&h, sizeof h, 1, f) != 1 || (bytes && fwrite(data, 1, bytes, f) != bytes))
        return pm_error_set(PM_EIO, "%s", strerror(errno));
    return PM_OK;
}

int pm_vtu_write_footer(FILE *f)
{
    if (fputs("\n  </AppendedData>\n</VTKFile>\n", f) == EOF)
        return pm_error_set(PM_EIO, "%s", strerror(errno));
    return PM_OK;
}

/* Fill scratch (3 doubles per entry) with (a[2i] - b[2i], a[2i+1] - b[2i+1], 0), or (a, 0)
 * when b is NULL. */
static void fill_vec3(double *out, const double *a, const double *b, size_t n)
{
    if (b) {
        for (size_t i = 0; i < n; i++) {
            out[3 * i] = a[2 * i] - b[2 * i];
            out[3 * i + 1] = a[2 * i + 1] - b[2 * i + 1];
            out[3 * i + 2] = 0.0;
        }
    } else {
        for (size_t i = 0; i < n; i++) {
            out[3 * i] = a[2 * i];
            out[3 * i + 1] = a[2 * i + 1];
            out[3 * i + 2] = 0.0;
        }
    }
}

/* Prefix the message with the file that failed. */
static int fail_path(int rc, const char *path)
{
    return pm_error_prefix(rc, "cannot write '%s': ", path);
}

/* One scalar per particle into scratch: the derived fields of io/particle_fields.h. */
typedef enum derived { D_PRESSURE, D_Q, D_VOL_STRAIN, D_DEV_STRAIN } derived;

static void fill_derived(double *out, const pm_particles *p, derived d)
{
    for (size_t i = 0; i < p->n; i++) {
        const double *sg = p->stress + PM_NS * i;
        double v, e;
        switch (d) {
        case D_PRESSURE: out[i] = pm_pf_pressure(sg); break;
        case D_Q: out[i] = pm_pf_q(sg); break;
        default:
            pm_pf_log_strain(p->F + PM_NF * i, &v, &e);
            out[i] = d == D_VOL_STRAIN ? v : e;
            break;
        }
    }
}

int pm_vtu_write_particles(const char *path, const pm_particles *p, void *scratch, double t)
{
    static const char *const stress_names[4] = { "xx", "yy", "zz", "xy" };
    static const char *const f_names[PM_NF] = { "xx", "xy", "yx", "yy", "zz" };
    const pm_vtu_array arrays[] = {
        { "displacement", PM_VTU_F64, 3, NULL },
        { "velocity", PM_VTU_F64, 3, NULL },
        { "grid_velocity", PM_VTU_F64, 3, NULL },
        { "stress", PM_VTU_F64, PM_NS, stress_names },
        { "plastic_strain", PM_VTU_F64, 1, NULL },
        { "material", PM_VTU_I32, 1, NULL },
        { "body", PM_VTU_I32, 1, NULL },
        { "mass", PM_VTU_F64, 1, NULL },
        { "volume", PM_VTU_F64, 1, NULL },
        { "pressure", PM_VTU_F64, 1, NULL },
        { "q", PM_VTU_F64, 1, NULL },
        { "volumetric_strain", PM_VTU_F64, 1, NULL },
        { "deviatoric_strain", PM_VTU_F64, 1, NULL },
        { "deformation_gradient", PM_VTU_F64, PM_NF, f_names },
        { "half_size", PM_VTU_F64, PM_DIM, NULL },
        { "id", PM_VTU_I32, 1, NULL },
        { "material_state", PM_VTU_F64, (int)p->n_state, NULL },
    };
    const size_t n = p->n;
    /* the models' history variables (docs/materials.md names them per model); none, no array */
    const size_t n_arrays = sizeof arrays / sizeof arrays[0] - (p->n_state ? 0 : 1);
    const pm_vtu_piece pc = { n, n, n, arrays, n_arrays, &t };
    char tmp[4096];
    FILE *f = pm_atomic_fopen(path, tmp, sizeof tmp);
    if (!f)
        return PM_EIO;
    int rc = pm_vtu_write_header(f, &pc);
    if (!rc) {
        fill_vec3(scratch, p->x, p->x0, n);
        rc = pm_vtu_write_block(f, scratch, 3 * n * sizeof(double));
    }
    if (!rc) {
        fill_vec3(scratch, p->v, NULL, n);
        rc = pm_vtu_write_block(f, scratch, 3 * n * sizeof(double));
    }
    if (!rc) {
        fill_vec3(scratch, p->v_grid, NULL, n);
        rc = pm_vtu_write_block(f, scratch, 3 * n * sizeof(double));
    }
    if (!rc)
        rc = pm_vtu_write_block(f, p->stress, PM_NS * n * sizeof(double));
    if (!rc)
        rc = pm_vtu_write_block(f, p->eps_p, n * sizeof(double));
    if (!rc)
        rc = pm_vtu_write_block(f, p->material, n * sizeof(int32_t));
    if (!rc)
        rc = pm_vtu_write_block(f, p->body, n * sizeof(int32_t));
    if (!rc)
        rc = pm_vtu_write_block(f, p->mass, n * sizeof(double));
    if (!rc)
        rc = pm_vtu_write_block(f, p->vol, n * sizeof(double));
    for (int d = D_PRESSURE; !rc && d <= D_DEV_STRAIN; d++) {
        fill_derived(scratch, p, (derived)d);
        rc = pm_vtu_write_block(f, scratch, n * sizeof(double));
    }
    if (!rc)
        rc = pm_vtu_write_block(f, p->F, PM_NF * n * sizeof(double));
    if (!rc)
        rc = pm_vtu_write_block(f, p->hsize, PM_DIM * n * sizeof(double));
    if (!rc)
        rc = pm_vtu_write_block(f, p->id, n * sizeof(int32_t));
    if (!rc && p->n_state)
        rc = pm_vtu_write_block(f, p->state, p->n_state * n * sizeof(double));
    if (!rc) {
        fill_vec3(scratch, p->x, NULL, n);
        rc = pm_vtu_write_block(f, scratch, 3 * n * sizeof(double));
    }
    /* one vertex per particle: connectivity i, offsets i + 1, type VTK_VERTEX */
    if (!rc) {
        int64_t *ix = scratch;
        for (size_t i = 0; i < n; i++)
            ix[i] = (int64_t)i;
        rc = pm_vtu_write_block(f, ix, n * sizeof(int64_t));
        for (size_t i = 0; !rc && i < n; i++)
            ix[i] = (int64_t)i + 1;
        if (!rc)
            rc = pm_vtu_write_block(f, ix, n * sizeof(int64_t));
    }
    if (!rc) {
        memset(scratch, VTK_VERTEX, n);
        rc = pm_vtu_write_block(f, scratch, n);
    }
    if (!rc)
        rc = pm_vtu_write_footer(f);
    if (rc) {
        fail_path(rc, path);
        pm_atomic_fclose(f, tmp, path, 0);
        return rc;
    }
    return pm_atomic_fclose(f, tmp, path, 1);
}

/* The nodal arrays a grid frame carries, in the order of their blocks. */
static size_t grid_arrays(const pm_vtu_grid_fields *gf, pm_vtu_array *a)
{
    size_t n = 0;
    if (gf && gf->mass)
        a[n++] = (pm_vtu_array){ "mass", PM_VTU_F64, 1, NULL };
    if (gf && gf->velocity)
        a[n++] = (pm_vtu_array){ "velocity", PM_VTU_F64, 3, NULL };
    if (gf && gf->boundary)
        a[n++] = (pm_vtu_array){ "boundary", PM_VTU_U8, 1, NULL };
    if (gf && gf->contact)
        a[n++] = (pm_vtu_array){ "contact", PM_VTU_I32, 1, NULL };
    return n;
}

static int write_grid_fields(FILE *f, const pm_grid *g, const pm_vtu_grid_fields *gf, double *buf)
{
    int rc = PM_OK;
    if (gf && gf->mass)
        rc = pm_vtu_write_block(f, gf->mass, g->n_nodes * sizeof(double));
    if (!rc && gf && gf->velocity) {
        fill_vec3(buf, gf->velocity, NULL, g->n_nodes);
        rc = pm_vtu_write_block(f, buf, 3 * g->n_nodes * sizeof(double));
    }
    if (!rc && gf && gf->boundary)
        rc = pm_vtu_write_block(f, gf->boundary, g->n_nodes);
    if (!rc && gf && gf->contact)
        rc = pm_vtu_write_block(f, gf->contact, g->n_nodes * sizeof(int32_t));
    return rc;
}

int pm_vtu_write_grid(const char *path, const pm_grid *g, const pm_vtu_grid_fields *gf, void *scratch)
{
    const int has_cells = g->n_cells > 0 && g->conn && g->nodes_per_cell > 0;
    const size_t npc = has_cells ? (size_t)g->nodes_per_cell : 1;
    const size_t n_cells = has_cells ? g->n_cells : g->n_nodes;
    const size_t conn_len = n_cells * npc;
    const uint8_t ctype = !has_cells ? VTK_VERTEX : g->element == PM_TRI3 ? VTK_TRIANGLE : VTK_QUAD;
    size_t need = 3 * g->n_nodes * sizeof(double);
    if (conn_len * sizeof(int64_t) > need)
        need = conn_len * sizeof(int64_t);
    void *buf = scratch ? scratch : malloc(need ? need : 1);
    if (!buf)
        return pm_error_set(PM_ENOMEM, "cannot write '%s': out of memory (%zu bytes)", path, need);
    pm_vtu_array arrays[4];
    const pm_vtu_piece pc = { g->n_nodes, n_cells, conn_len, arrays, grid_arrays(gf, arrays),
                              gf ? gf->time : NULL };
    char tmp[4096];
    FILE *f = pm_atomic_fopen(path, tmp, sizeof tmp);
    if (!f) {
        if (!scratch)
            free(buf);
        return PM_EIO;
    }
    int rc = pm_vtu_write_header(f, &pc);
    if (!rc)
        rc = write_grid_fields(f, g, gf, buf);
    if (!rc) {
        fill_vec3(buf, g->x, NULL, g->n_nodes);
        rc = pm_vtu_write_block(f, buf, 3 * g->n_nodes * sizeof(double));
    }
    int64_t *ix = buf;
    if (!rc) {
        for (size_t i = 0; i < conn_len; i++)
            ix[i] = has_cells ? (int64_t)g->conn[i] : (int64_t)i;
        rc = pm_vtu_write_block(f, ix, conn_len * sizeof(int64_t));
    }
    if (!rc) {
        for (size_t c = 0; c < n_cells; c++)
            ix[c] = (int64_t)((c + 1) * npc);
        rc = pm_vtu_write_block(f, ix, n_cells * sizeof(int64_t));
    }
    if (!rc) {
        memset(buf, ctype, n_cells);
        rc = pm_vtu_write_block(f, buf, n_cells);
    }
    if (!rc)
        rc = pm_vtu_write_footer(f);
    if (!scratch)
        free(buf);
    if (rc) {
        fail_path(rc, path);
        pm_atomic_fclose(f, tmp, path, 0);
        return rc;
    }
    return pm_atomic_fclose(f, tmp, path, 1);
}
