/*
 * Reading frames back (pmech/frame.h). A VTU file with raw appended data is XML up to the
 * AppendedData element and binary after it, so it is not a well-formed XML document: expat parses the
 * XML part and is stopped at the AppendedData start tag, whose byte position locates the binary
 * blocks; each DataArray's offset then points into them. The .pvd collection is plain XML.
 */
#include "pmech/frame.h"
#include "pmech/error.h"

#include <errno.h>
#include <expat.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define NAME_LEN 96
#define ARRAYS_MAX 64
#define FILE_MAX ((size_t)1 << 34) /* 16 GiB: far beyond any frame, and refused before allocating */

typedef enum { T_F64, T_F32, T_I32, T_I64, T_U8, T_I8, T_U32, T_U64 } elem_type;
typedef enum { SEC_NONE, SEC_POINT_DATA, SEC_POINTS, SEC_CELLS, SEC_FIELD, SEC_OTHER } section;

typedef struct array_desc {
    char name[NAME_LEN];
    elem_type type;
    int ncomp;
    uint64_t offset;
} array_desc;

struct pm_frame {
    size_t n_points;
    double time;
    double *points;
    size_t n_arrays;
    char (*names)[NAME_LEN];
    int *ncomp;
    double **values;
};

/* ---- whole files ---------------------------------------------------------------------------- */

static int slurp(const char *path, char **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return pm_error_set(PM_EIO, "cannot read '%s': %s", path, strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode) || (uint64_t)st.st_size > FILE_MAX) {
        fclose(f);
        return pm_error_set(PM_EIO, "cannot read '%s': not a regular file of at most 16 GiB", path);
    }
    const size_t n = (size_t)st.st_size;
    char *b = malloc(n + 1);
    if (!b) {
        fclose(f);
        return pm_error_set(PM_ENOMEM, "out of memory reading '%s' (%zu bytes)", path, n);
    }
    const size_t got = fread(b, 1, n, f);
    const int bad = ferror(f);
    fclose(f);
    if (bad || got != n) {
        free(b);
        return pm_error_set(PM_EIO, "cannot read '%s': read error", path);
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return PM_OK;
}

static const char *attr(const XML_Char **atts, const char *key)
{
    for (size_t k = 0; atts[k]; k += 2)
        if (!strcmp(atts[k], key))
            return atts[k + 1];
    return NULL;
}

/* ---- VTU ------------------------------------------------------------------------------------ */

typedef struct vtu_parse {
    XML_Parser xp;
    const char *path;
    int rc;       /* first error */
    int header64; /* block headers are UInt64 (else UInt32) */
    size_t n_points;
    int have_piece;
    section sec;
    array_desc arr[ARRAYS_MAX];
    size_t n_arr;
    array_desc points;
    int have_points;
    long appended_at; /* byte index of <AppendedData, -1 before */
    int time_capture; /* inside the TimeValue DataArray */
    char time_text[64];
    size_t time_len;
} vtu_parse;

static void fail(vtu_parse *v, const char *what, const char *detail)
{
    if (!v->rc)
        v->rc = pm_error_set(PM_EINPUT, "%s: %s%s (pmech reads the VTU files it writes)", v->path, what,
                             detail ? detail : "");
    XML_StopParser(v->xp, XML_FALSE);
}

static int type_of(const char *s, elem_type *t)
{
    static const struct {
        const char *name;
        elem_type t;
    } names[] = {{"Float64", T_F64}, {"Float32", T_F32}, {"Int32", T_I32},  {"Int64", T_I64},
                 {"UInt8", T_U8},    {"Int8", T_I8},     {"UInt32", T_U32}, {"UInt64", T_U64}};
    for (size_t k = 0; s && k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(s, names[k].name)) {
            *t = names[k].t;
            return 1;
        }
    return 0;
}

static size_t type_size(elem_type t)
{
    switch (t) {
    case T_F32:
    case T_I32:
    case T_U32: return 4;
    case T_U8:
    case T_I8: return 1;
    default: return 8;
    }
}

static void data_array(vtu_parse *v, const XML_Char **atts)
{
    const char *name = attr(atts, "Name"), *type = attr(atts, "type"), *fmt = attr(atts, "format");
    const char *nc = attr(atts, "NumberOfComponents"), *off = attr(atts, "offset");
    if (v->sec == SEC_FIELD) {
        v->time_capture = name && !strcmp(name, "TimeValue") && fmt && !strcmp(fmt, "ascii");
        v->time_len = 0;
        return;
    }
    if (v->sec != SEC_POINT_DATA && v->sec != SEC_POINTS)
        return;
    array_desc a;
    memset(&a, 0, sizeof a);
    if (!name && v->sec == SEC_POINTS)
        name = "Points";
    if (!name || strlen(name) >= NAME_LEN) {
        fail(v, "a DataArray without a usable Name", NULL);
        return;
    }
    snprintf(a.name, sizeof a.name, "%s", name);
    if (!type_of(type, &a.type)) {
        fail(v, "unsupported DataArray type ", type ? type : "(none)");
        return;
    }
    if (!fmt || strcmp(fmt, "appended") != 0) {
        fail(v, "DataArray not in appended format: ", name);
        return;
    }
    char *end = NULL;
    long ncomp = nc ? strtol(nc, &end, 10) : 1;
    if ((nc && *end) || ncomp < 1 || ncomp > 16) {
        fail(v, "bad NumberOfComponents of ", name);
        return;
    }
    a.ncomp = (int)ncomp;
    unsigned long long o = off ? strtoull(off, &end, 10) : 0;
    if (!off || *end) {
        fail(v, "DataArray without an offset: ", name);
        return;
    }
    a.offset = o;
    if (v->sec == SEC_POINTS) {
        if (a.ncomp != 3) {
            fail(v, "Points must have 3 components", NULL);
            return;
        }
        v->points = a;
        v->have_points = 1;
    } else if (v->n_arr == ARRAYS_MAX) {
        {
            fail(v, "too many point arrays", NULL);
            return;
        }
    } else {
        v->arr[v->n_arr++] = a;
    }
}

static void XMLCALL vtu_start(void *ud, const XML_Char *el, const XML_Char **atts)
{
    vtu_parse *v = ud;
    if (!strcmp(el, "VTKFile")) {
        const char *type = attr(atts, "type"), *bo = attr(atts, "byte_order"), *ht = attr(atts, "header_type");
        const char *comp = attr(atts, "compressor");
        if (!type || strcmp(type, "UnstructuredGrid") != 0) {
            fail(v, "not an UnstructuredGrid file", NULL);
            return;
        }
        const uint16_t probe = 1;
        const int little = *(const uint8_t *)&probe == 1;
        if (!bo || strcmp(bo, little ? "LittleEndian" : "BigEndian") != 0) {
            fail(v, "byte order differs from this machine's", NULL);
            return;
        }
        if (comp && comp[0]) {
            fail(v, "compressed data (", comp);
            return;
        }
        v->header64 = ht && !strcmp(ht, "UInt64");
        if (ht && !v->header64 && strcmp(ht, "UInt32") != 0) {
            fail(v, "unsupported header_type ", ht);
            return;
        }
    } else if (!strcmp(el, "Piece")) {
        if (v->have_piece) {
            fail(v, "more than one Piece", NULL);
            return;
        }
        const char *np = attr(atts, "NumberOfPoints");
        char *end = NULL;
        unsigned long long n = np ? strtoull(np, &end, 10) : 0;
        if (!np || *end) {
            fail(v, "Piece without NumberOfPoints", NULL);
            return;
        }
        v->n_points = (size_t)n;
        v->have_piece = 1;
    } else if (!strcmp(el, "PointData")) {
        v->sec = SEC_POINT_DATA;
    } else if (!strcmp(el, "Points")) {
        v->sec = SEC_POINTS;
    } else if (!strcmp(el, "Cells")) {
        v->sec = SEC_CELLS;
    } else if (!strcmp(el, "FieldData")) {
        v->sec = SEC_FIELD;
    } else if (!strcmp(el, "CellData")) {
        v->sec = SEC_OTHER;
    } else if (!strcmp(el, "DataArray")) {
        data_array(v, atts);
    } else if (!strcmp(el, "AppendedData")) {
        const char *enc = attr(atts, "encoding");
        if (!enc || strcmp(enc, "raw") != 0) {
            fail(v, "appended data not raw (base64 is not read)", NULL);
            return;
        }
        v->appended_at = (long)XML_GetCurrentByteIndex(v->xp);
        XML_StopParser(v->xp, XML_FALSE);
    }
}

static void XMLCALL vtu_end(void *ud, const XML_Char *el)
{
    vtu_parse *v = ud;
    if (!strcmp(el, "PointData") || !strcmp(el, "Points") || !strcmp(el, "Cells") || !strcmp(el, "FieldData") ||
        !strcmp(el, "CellData"))
        v->sec = SEC_NONE;
    else if (!strcmp(el, "DataArray"))
        v->time_capture = 0;
}

static void XMLCALL vtu_text(void *ud, const XML_Char *s, int len)
{
    vtu_parse *v = ud;
    if (!v->time_capture)
        return;
    for (int k = 0; k < len && v->time_len + 1 < sizeof v->time_text; k++)
        v->time_text[v->time_len++] = s[k];
    v->time_text[v->time_len] = '\0';
}

/* Convert one appended block to doubles. */
static int read_block(const vtu_parse *v, const char *data, size_t data_len, const array_desc *a, double *out)
{
    const size_t hs = v->header64 ? 8 : 4, es = type_size(a->type);
    const size_t count = v->n_points * (size_t)a->ncomp;
    if (a->offset > data_len || data_len - a->offset < hs)
        return pm_error_set(PM_EINPUT, "%s: array '%s' lies past the end of the file", v->path, a->name);
    uint64_t bytes = 0;
    if (v->header64) {
        memcpy(&bytes, data + a->offset, 8);
    } else {
        uint32_t b32;
        memcpy(&b32, data + a->offset, 4);
        bytes = b32;
    }
    if (bytes != (uint64_t)count * es)
        return pm_error_set(PM_EINPUT, "%s: array '%s' holds %llu bytes; %zu points x %d components need %zu", v->path,
                            a->name, (unsigned long long)bytes, v->n_points, a->ncomp, count * es);
    if (data_len - a->offset - hs < bytes)
        return pm_error_set(PM_EINPUT, "%s: array '%s' runs past the end of the file (cut short?)", v->path, a->name);
    const char *p = data + a->offset + hs;
    for (size_t i = 0; i < count; i++, p += es) {
        switch (a->type) {
        case T_F64: {
            double x;
            memcpy(&x, p, 8);
            out[i] = x;
            break;
        }
        case T_F32: {
            float x;
            memcpy(&x, p, 4);
            out[i] = x;
            break;
        }
        case T_I32: {
            int32_t x;
            memcpy(&x, p, 4);
            out[i] = x;
            break;
        }
        case T_U32: {
            uint32_t x;
            memcpy(&x, p, 4);
            out[i] = x;
            break;
        }
        case T_I64: {
            int64_t x;
            memcpy(&x, p, 8);
            out[i] = (double)x;
            break;
        }
        case T_U64: {
            uint64_t x;
            memcpy(&x, p, 8);
            out[i] = (double)x;
            break;
        }
        case T_I8: out[i] = (int8_t)*p; break;
        default: out[i] = (uint8_t)*p; break;
        }
    }
    return PM_OK;
}

void pm_frame_free(pm_frame *f)
{
    if (!f)
        return;
    for (size_t k = 0; f->values && k < f->n_arrays; k++)
        free(f->values[k]);
    free(f->values);
    free(f->names);
    free(f->ncomp);
    free(f->points);
    free(f);
}

/* Build the frame from the parsed header and the appended blocks. */
static int assemble(const vtu_parse *v, const char *buf, size_t len, pm_frame *f)
{
    if (!v->have_piece || !v->have_points)
        return pm_error_set(PM_EINPUT, "%s: no Piece with Points (pmech reads the VTU files it writes)", v->path);
    if (v->appended_at < 0)
        return pm_error_set(PM_EINPUT, "%s: no raw AppendedData (pmech reads the VTU files it writes)", v->path);
    /* the binary part starts after the '_' that follows the AppendedData start tag */
    const char *tag_end = memchr(buf + v->appended_at, '>', len - (size_t)v->appended_at);
    const char *us = tag_end ? memchr(tag_end, '_', len - (size_t)(tag_end - buf)) : NULL;
    if (!us)
        return pm_error_set(PM_EINPUT, "%s: AppendedData without its '_' marker", v->path);
    const char *data = us + 1;
    const size_t data_len = len - (size_t)(data - buf);
    f->n_points = v->n_points;
    f->time = v->time_len ? strtod(v->time_text, NULL) : NAN;
    f->n_arrays = v->n_arr;
    const size_t np = v->n_points ? v->n_points : 1;
    f->points = malloc(3 * np * sizeof *f->points);
    f->names = calloc(v->n_arr ? v->n_arr : 1, sizeof *f->names);
    f->ncomp = calloc(v->n_arr ? v->n_arr : 1, sizeof *f->ncomp);
    f->values = calloc(v->n_arr ? v->n_arr : 1, sizeof *f->values);
    if (!f->points || !f->names || !f->ncomp || !f->values)
        return pm_error_set(PM_ENOMEM, "out of memory reading '%s'", v->path);
    pm_check(read_block(v, data, data_len, &v->points, f->points));
    for (size_t k = 0; k < v->n_arr; k++) {
        memcpy(f->names[k], v->arr[k].name, NAME_LEN);
        f->ncomp[k] = v->arr[k].ncomp;
        f->values[k] = malloc((size_t)v->arr[k].ncomp * np * sizeof(double));
        if (!f->values[k])
            return pm_error_set(PM_ENOMEM, "out of memory reading '%s'", v->path);
        pm_check(read_block(v, data, data_len, &v->arr[k], f->values[k]));
    }
    return PM_OK;
}

int pm_frame_read(const char *path, pm_frame **out)
{
    *out = NULL;
    char *buf;
    size_t len;
    pm_check(slurp(path, &buf, &len));
    vtu_parse *v = calloc(1, sizeof *v);
    pm_frame *f = calloc(1, sizeof *f);
    XML_Parser xp = XML_ParserCreate(NULL);
    int rc = PM_OK;
    if (!v || !f || !xp) {
        rc = pm_error_set(PM_ENOMEM, "out of memory reading '%s'", path);
    } else {
        v->xp = xp;
        v->path = path;
        v->appended_at = -1;
        XML_SetUserData(xp, v);
        XML_SetElementHandler(xp, vtu_start, vtu_end);
        XML_SetCharacterDataHandler(xp, vtu_text);
        const int st = len > INT32_MAX ? XML_STATUS_ERROR : (int)XML_Parse(xp, buf, (int)len, 1);
        if (v->rc)
            rc = v->rc;
        else if (len > INT32_MAX && v->appended_at < 0)
            rc = pm_error_set(PM_EINPUT, "%s: larger than 2 GiB", path);
        else if (st != XML_STATUS_OK && XML_GetErrorCode(xp) != XML_ERROR_ABORTED)
            rc = pm_error_set(PM_EINPUT, "%s:%lu:%lu: %s", path, (unsigned long)XML_GetCurrentLineNumber(xp),
                              (unsigned long)XML_GetCurrentColumnNumber(xp) + 1, XML_ErrorString(XML_GetErrorCode(xp)));
        else
            rc = assemble(v, buf, len, f);
    }
    if (xp)
        XML_ParserFree(xp);
    free(v);
    free(buf);
    if (rc) {
        pm_frame_free(f);
        return rc;
    }
    *out = f;
    return PM_OK;
}

size_t pm_frame_n_points(const pm_frame *f) { return f->n_points; }
double pm_frame_time(const pm_frame *f) { return f->time; }
const double *pm_frame_points(const pm_frame *f) { return f->points; }
size_t pm_frame_n_arrays(const pm_frame *f) { return f->n_arrays; }

const char *pm_frame_array_name(const pm_frame *f, size_t k, int *ncomp)
{
    if (k >= f->n_arrays)
        return NULL;
    if (ncomp)
        *ncomp = f->ncomp[k];
    return f->names[k];
}

const double *pm_frame_array(const pm_frame *f, const char *name, int *ncomp)
{
    for (size_t k = 0; k < f->n_arrays; k++)
        if (!strcmp(f->names[k], name)) {
            if (ncomp)
                *ncomp = f->ncomp[k];
            return f->values[k];
        }
    return NULL;
}

/* ---- PVD ------------------------------------------------------------------------------------ */

typedef struct pvd_parse {
    XML_Parser xp;
    const char *path;
    char dir[4096];
    pm_series *s;
    size_t cap;
    int rc, collection;
} pvd_parse;

static void XMLCALL pvd_start(void *ud, const XML_Char *el, const XML_Char **atts)
{
    pvd_parse *p = ud;
    if (p->rc)
        return;
    if (!strcmp(el, "VTKFile")) {
        const char *type = attr(atts, "type");
        p->collection = type && !strcmp(type, "Collection");
        return;
    }
    if (strcmp(el, "DataSet") != 0)
        return;
    const char *ts = attr(atts, "timestep"), *file = attr(atts, "file");
    char *end = NULL;
    const double t = ts ? strtod(ts, &end) : NAN;
    if (!file || !ts || *end) {
        p->rc = pm_error_set(PM_EINPUT, "%s:%lu: a DataSet without a timestep number and a file", p->path,
                             (unsigned long)XML_GetCurrentLineNumber(p->xp));
        XML_StopParser(p->xp, XML_FALSE);
        return;
    }
    pm_series *s = p->s;
    if (s->n == p->cap) {
        const size_t cap = p->cap ? 2 * p->cap : 64;
        double *nt = realloc(s->time, cap * sizeof *nt);
        if (nt)
            s->time = nt;
        char **nf = nt ? realloc(s->file, cap * sizeof *nf) : NULL;
        if (nf)
            s->file = nf;
        if (!nt || !nf) {
            p->rc = pm_error_set(PM_ENOMEM, "out of memory reading '%s'", p->path);
            XML_StopParser(p->xp, XML_FALSE);
            return;
        }
        p->cap = cap;
    }
    const size_t need = strlen(p->dir) + strlen(file) + 2;
    char *full = malloc(need);
    if (!full) {
        p->rc = pm_error_set(PM_ENOMEM, "out of memory reading '%s'", p->path);
        XML_StopParser(p->xp, XML_FALSE);
        return;
    }
    if (file[0] == '/' || !p->dir[0])
        snprintf(full, need, "%s", file);
    else
        snprintf(full, need, "%s/%s", p->dir, file);
    s->time[s->n] = t;
    s->file[s->n++] = full;
}

int pm_series_read(const char *path, pm_series *s)
{
    memset(s, 0, sizeof *s);
    char pvd[4096];
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        snprintf(pvd, sizeof pvd, "%s/particles.pvd", path);
    else
        snprintf(pvd, sizeof pvd, "%s", path);
    char *buf;
    size_t len;
    pm_check(slurp(pvd, &buf, &len));
    pvd_parse p;
    memset(&p, 0, sizeof p);
    p.path = pvd;
    p.s = s;
    const char *slash = strrchr(pvd, '/');
    if (slash)
        snprintf(p.dir, sizeof p.dir, "%.*s", (int)(slash - pvd), pvd);
    if (slash && slash == pvd)
        snprintf(p.dir, sizeof p.dir, "/");
    p.xp = XML_ParserCreate(NULL);
    if (!p.xp) {
        free(buf);
        return pm_error_set(PM_ENOMEM, "out of memory reading '%s'", pvd);
    }
    XML_SetUserData(p.xp, &p);
    XML_SetStartElementHandler(p.xp, pvd_start);
    const int ok = len <= INT32_MAX && XML_Parse(p.xp, buf, (int)len, 1) == XML_STATUS_OK;
    int rc = p.rc;
    if (!rc && !ok)
        rc = pm_error_set(PM_EINPUT, "%s:%lu:%lu: %s", pvd, (unsigned long)XML_GetCurrentLineNumber(p.xp),
                          (unsigned long)XML_GetCurrentColumnNumber(p.xp) + 1, XML_ErrorString(XML_GetErrorCode(p.xp)));
    if (!rc && !p.collection)
        rc = pm_error_set(PM_EINPUT, "%s: not a VTK Collection file", pvd);
    XML_ParserFree(p.xp);
    free(buf);
    return rc;
}

void pm_series_free(pm_series *s)
{
    for (size_t k = 0; s->file && k < s->n; k++)
        free(s->file[k]);
    free(s->file);
    free(s->time);
    memset(s, 0, sizeof *s);
}
