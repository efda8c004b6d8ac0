/*
 * Reader of Gmsh meshes, MSH 4.1 ASCII (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format):
 * $MeshFormat, $PhysicalNames, $Entities (which physical groups each point/curve/surface belongs
 * to), $Nodes and $Elements; other sections are skipped. Element types read: 15 (point), 1 (2-node
 * line), 2 (3-node triangle), 3 (4-node quad). Second-order elements are refused.
 *
 * pmech reads the file itself instead of linking Gmsh's C API: Debian's libgmsh (18 MB) pulls in
 * OpenCASCADE, FLTK and OpenGL, keeps global state that is not thread-safe, and all a solver needs
 * is this one text format.
 *
 * This file is the tokenizer and the section readers, up to the parsed file (gmsh_internal.h);
 * gmsh.c builds the grid from it.
 */
#include "mesh/gmsh_internal.h"

#include "pmech/error.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct reader {
    const char *p, *end, *path;
    int line;
} reader;

static void skip_ws(reader *r)
{
    while (r->p < r->end && isspace((unsigned char)*r->p)) {
        if (*r->p == '\n')
            r->line++;
        r->p++;
    }
}

static int bad(const reader *r, const char *what)
{
    return pm_error_set(PM_EINPUT, "%s:%d: %s", r->path, r->line, what);
}

static int get_long(reader *r, long *v)
{
    skip_ws(r);
    char *e;
    errno = 0;
    *v = strtol(r->p, &e, 10);
    if (e == r->p || errno || (e < r->end && !isspace((unsigned char)*e)))
        return bad(r, "expected an integer");
    r->p = e;
    return PM_OK;
}

static int get_double(reader *r, double *v)
{
    skip_ws(r);
    char *e;
    *v = strtod(r->p, &e);
    if (e == r->p || (e < r->end && !isspace((unsigned char)*e)) || !isfinite(*v))
        return bad(r, "expected a number");
    r->p = e;
    return PM_OK;
}

/* A whitespace-delimited word into buf. */
static int get_word(reader *r, char *buf, size_t n)
{
    skip_ws(r);
    size_t k = 0;
    while (r->p < r->end && !isspace((unsigned char)*r->p)) {
        if (k + 1 < n)
            buf[k++] = *r->p;
        r->p++;
    }
    buf[k] = '\0';
    return k ? PM_OK : bad(r, "unexpected end of file");
}

static int get_count(reader *r, long *v, long max, const char *what)
{
    pm_check(get_long(r, v));
    if (*v < 0 || *v > max) {
        char m[128];
        snprintf(m, sizeof m, "%s %ld out of range [0, %ld]", what, *v, max);
        return bad(r, m);
    }
    return PM_OK;
}

static int expect(reader *r, const char *word)
{
    char w[64];
    pm_check(get_word(r, w, sizeof w));
    if (strcmp(w, word) != 0) {
        char m[160];
        snprintf(m, sizeof m, "expected '%s', found '%.60s'", word, w);
        return bad(r, m);
    }
    return PM_OK;
}

#define MAX_COUNT 100000000L

/* Counts read from the file size arrays before their items are read: an item takes at least
 * min_chars characters of what is left, so a count the rest of the file cannot hold is refused
 * before it allocates (an 84-byte file could otherwise claim a billion nodes). */
static int get_count_fits(reader *r, long *v, long max, long min_chars, const char *what)
{
    pm_check(get_count(r, v, max, what));
    const long room = (long)((r->end - r->p) / min_chars) + 1;
    if (*v > room) {
        char m[200];
        snprintf(m, sizeof m, "%s %ld: the %ld bytes left in the file hold at most %ld", what, *v,
                 (long)(r->end - r->p), room);
        return bad(r, m);
    }
    return PM_OK;
}

void pm_msh_free(pm_msh *m)
{
    free(m->names);
    for (size_t i = 0; i < m->n_ent; i++)
        free(m->ent[i].phys);
    free(m->ent);
    free(m->tag_index);
    free(m->xy);
    free(m->tri); free(m->quad); free(m->line); free(m->pt);
    free(m->tri_ent); free(m->quad_ent); free(m->line_ent); free(m->pt_ent);
    free(m->tri_tag); free(m->quad_tag);
}

static int read_format(reader *r)
{
    char ver[32];
    long ft, ds;
    pm_check(get_word(r, ver, sizeof ver));
    pm_check(get_long(r, &ft));
    pm_check(get_long(r, &ds));
    if (strcmp(ver, "4.1") != 0) {
        char m[200];
        snprintf(m, sizeof m, "MSH version %.20s is not supported; save as MSH 4.1 ASCII (gmsh -format msh41, or "
                              "Mesh.MshFileVersion = 4.1;)", ver);
        return bad(r, m);
    }
    if (ft != 0)
        return bad(r, "binary MSH files are not supported; save as ASCII (Mesh.Binary = 0;)");
    return expect(r, "$EndMeshFormat");
}

static int read_names(reader *r, pm_msh *m)
{
    long n;
    pm_check(get_count_fits(r, &n, 100000, 8, "number of physical names"));
    m->names = calloc((size_t)n + 1, sizeof *m->names);
    if (!m->names)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (long i = 0; i < n; i++) {
        long dim, tag;
        pm_check(get_long(r, &dim));
        pm_check(get_long(r, &tag));
        skip_ws(r);
        if (r->p >= r->end || *r->p != '"')
            return bad(r, "expected a quoted physical name");
        r->p++;
        const char *s = r->p;
        while (r->p < r->end && *r->p != '"' && *r->p != '\n')
            r->p++;
        if (r->p >= r->end || *r->p != '"')
            return bad(r, "unterminated physical name");
        size_t len = (size_t)(r->p - s);
        if (len >= sizeof m->names[0].name)
            return bad(r, "physical name longer than 63 characters");
        pm_msh_name *pn = &m->names[m->n_names++];
        pn->dim = (int)dim;
        pn->tag = (int)tag;
        memcpy(pn->name, s, len);
        pn->name[len] = '\0';
        r->p++;
    }
    return expect(r, "$EndPhysicalNames");
}

static int read_entities(reader *r, pm_msh *m)
{
    long cnt[4];
    for (int d = 0; d < 4; d++)
        pm_check(get_count_fits(r, &cnt[d], MAX_COUNT, 10, "number of entities"));
    size_t total = (size_t)(cnt[0] + cnt[1] + cnt[2] + cnt[3]);
    m->ent = calloc(total + 1, sizeof *m->ent);
    if (!m->ent)
        return pm_error_set(PM_ENOMEM, "out of memory");
    for (int d = 0; d < 4; d++)
        for (long i = 0; i < cnt[d]; i++) {
            long tag, np;
            double v;
            pm_check(get_long(r, &tag));
            for (int k = 0; k < (d == 0 ? 3 : 6); k++)
                pm_check(get_double(r, &v));
            pm_check(get_count_fits(r, &np, 10000, 2, "number of physical tags"));
            pm_msh_entity *e = &m->ent[m->n_ent++];
            e->dim = d;
            e->tag = (int)tag;
            e->phys = malloc(((size_t)np + 1) * sizeof(int));
            if (!e->phys)
                return pm_error_set(PM_ENOMEM, "out of memory");
            for (long k = 0; k < np; k++) {
                long t;
                pm_check(get_long(r, &t));
                e->phys[e->n_phys++] = (int)t;
            }
            if (d > 0) {
                long nb, t;
                pm_check(get_count(r, &nb, MAX_COUNT, "number of bounding entities"));
                for (long k = 0; k < nb; k++)
                    pm_check(get_long(r, &t));
            }
        }
    return expect(r, "$EndEntities");
}

static int read_nodes(reader *r, pm_msh *m)
{
    long nblocks, nnodes, mintag, maxtag;
    pm_check(get_count(r, &nblocks, MAX_COUNT, "number of node blocks"));
    /* a node is at least a tag and three coordinates */
    pm_check(get_count_fits(r, &nnodes, MAX_COUNT, 8, "number of nodes"));
    pm_check(get_long(r, &mintag));
    pm_check(get_long(r, &maxtag));
    if (maxtag < 0 || maxtag > 4 * MAX_COUNT || mintag < 0 || (nnodes > 0 && mintag > maxtag))
        return bad(r, "node tags out of range");
    /* tags index a table as long as the largest tag: a few gaps are normal, a sparse numbering is not */
    if (maxtag > 8 * nnodes + 4096) {
        char msg[200];
        snprintf(msg, sizeof msg, "node tags up to %ld for %ld nodes: renumber the nodes in Gmsh so that tags "
                 "run from 1 to about the node count", maxtag, nnodes);
        return bad(r, msg);
    }
    m->max_tag = maxtag;
    m->tag_index = malloc(((size_t)maxtag + 1) * sizeof(long));
    m->xy = malloc(((size_t)nnodes + 1) * PM_DIM * sizeof(double));
    long *tags = malloc(((size_t)nnodes + 1) * sizeof(long));
    if (!m->tag_index || !m->xy || !tags) {
        free(tags);
        return pm_error_set(PM_ENOMEM, "out of memory for %ld nodes", nnodes);
    }
    for (long t = 0; t <= maxtag; t++)
        m->tag_index[t] = -1;
    int rc = PM_OK;
    for (long b = 0; b < nblocks && !rc; b++) {
        long edim, etag, param, n;
        if ((rc = get_long(r, &edim)) || (rc = get_long(r, &etag)) || (rc = get_long(r, &param)) ||
            (rc = get_count(r, &n, nnodes - (long)m->n_nodes, "nodes in block")))
            break;
        const int npar = param ? (int)edim : 0;
        size_t first = m->n_nodes;
        for (long k = 0; k < n && !rc; k++) {
            if ((rc = get_long(r, &tags[first + k])))
                break;
            if (tags[first + k] < 0 || tags[first + k] > maxtag)
                rc = bad(r, "node tag out of the range given in the $Nodes header");
        }
        for (long k = 0; k < n && !rc; k++) {
            double z, u;
            if ((rc = get_double(r, &m->xy[PM_DIM * (first + k)])) ||
                (rc = get_double(r, &m->xy[PM_DIM * (first + k) + 1])) ||
                (rc = get_double(r, &z)))
                break;
            for (int q = 0; q < npar && !rc; q++)
                rc = get_double(r, &u);
            m->tag_index[tags[first + k]] = (long)(first + k);
        }
        m->n_nodes += (size_t)n;
    }
    free(tags);
    if (rc)
        return rc;
    return expect(r, "$EndNodes");
}

static int push_elem(long **nodes, int **ents, long **tags, size_t *n, size_t *cap, int npe, const long *v, int ent,
                     long tag)
{
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 1024;
        if (tags) {
            long *t = realloc(*tags, nc * sizeof(long));
            if (!t)
                return pm_error_set(PM_ENOMEM, "out of memory for elements");
            *tags = t;
        }
        long *a = realloc(*nodes, nc * (size_t)npe * sizeof(long));
        if (!a)
            return pm_error_set(PM_ENOMEM, "out of memory for elements");
        *nodes = a;
        int *e = realloc(*ents, nc * sizeof(int));
        if (!e)
            return pm_error_set(PM_ENOMEM, "out of memory for elements");
        *ents = e;
        *cap = nc;
    }
    memcpy(*nodes + (size_t)npe * *n, v, (size_t)npe * sizeof(long));
    (*ents)[*n] = ent;
    if (tags)
        (*tags)[*n] = tag;
    (*n)++;
    return PM_OK;
}

static int read_elements(reader *r, pm_msh *m)
{
    long nblocks, nel, mn, mx;
    pm_check(get_count(r, &nblocks, MAX_COUNT, "number of element blocks"));
    /* an element is at least a tag and one node */
    pm_check(get_count_fits(r, &nel, MAX_COUNT, 4, "number of elements"));
    pm_check(get_long(r, &mn));
    pm_check(get_long(r, &mx));
    for (long b = 0; b < nblocks; b++) {
        long edim, etag, type, n;
        pm_check(get_long(r, &edim));
        pm_check(get_long(r, &etag));
        pm_check(get_long(r, &type));
        pm_check(get_count(r, &n, nel, "elements in block"));
        int npe;
        switch (type) {
        case 15: npe = 1; break;
        case 1: npe = 2; break;
        case 2: npe = 3; break;
        case 3: npe = 4; break;
        default: {
            char msg[200];
            snprintf(msg, sizeof msg,
                     "element type %ld is not supported (pmech reads 2-D first-order meshes: points, 2-node lines, "
                     "3-node triangles, 4-node quads; set Mesh.ElementOrder = 1)", type);
            return bad(r, msg);
        }
        }
        for (long k = 0; k < n; k++) {
            long tag, v[4];
            pm_check(get_long(r, &tag));
            for (int q = 0; q < npe; q++) {
                pm_check(get_long(r, &v[q]));
                if (v[q] < 0 || v[q] > m->max_tag || m->tag_index[v[q]] < 0)
                    return bad(r, "element refers to an undefined node");
            }
            switch (type) {
            case 15: pm_check(push_elem(&m->pt, &m->pt_ent, NULL, &m->n_pt, &m->cap_pt, 1, v, (int)etag, tag)); break;
            case 1:
                pm_check(push_elem(&m->line, &m->line_ent, NULL, &m->n_line, &m->cap_line, 2, v, (int)etag, tag));
                break;
            case 2:
                pm_check(push_elem(&m->tri, &m->tri_ent, &m->tri_tag, &m->n_tri, &m->cap_tri, 3, v, (int)etag, tag));
                break;
            default:
                pm_check(push_elem(&m->quad, &m->quad_ent, &m->quad_tag, &m->n_quad, &m->cap_quad, 4, v, (int)etag,
                                   tag));
                break;
            }
        }
    }
    return expect(r, "$EndElements");
}

static int skip_section(reader *r, const char *name)
{
    char end[96], w[80];
    snprintf(end, sizeof end, "$End%s", name + 1);
    for (;;) {
        if (get_word(r, w, sizeof w))
            return bad(r, "section not terminated");
        if (strcmp(w, end) == 0)
            return PM_OK;
    }
}

int pm_msh_parse(const char *path, pm_msh *m)
{
    memset(m, 0, sizeof *m);
    FILE *f = fopen(path, "rb");
    if (!f)
        return pm_error_set(PM_EIO, "%s: cannot open the mesh file: %s", path, strerror(errno));
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 65536 + 1 > cap) {
            cap = cap ? 2 * cap : 1 << 17; /* a small mesh in one allocation (a larger first one cost more than the parse) */
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(f);
                return pm_error_set(PM_ENOMEM, "%s: out of memory reading the mesh", path);
            }
            buf = nb;
        }
        size_t got = fread(buf + len, 1, 65536, f);
        len += got;
        if (got < 65536)
            break;
    }
    int err = ferror(f);
    fclose(f);
    if (err) {
        free(buf);
        return pm_error_set(PM_EIO, "%s: read error", path);
    }
    buf[len] = '\0';
    reader r = {buf, buf + len, path, 1};
    int rc = PM_OK, have_format = 0, have_nodes = 0, have_elems = 0;
    char w[80];
    for (;;) {
        skip_ws(&r);
        if (r.p >= r.end)
            break;
        if ((rc = get_word(&r, w, sizeof w)))
            break;
        if (strcmp(w, "$MeshFormat") == 0) {
            rc = read_format(&r);
            have_format = 1;
        } else if (!have_format) {
            rc = bad(&r, "not a Gmsh MSH file (no $MeshFormat first)");
        } else if (strcmp(w, "$PhysicalNames") == 0) {
            rc = m->names ? bad(&r, "second $PhysicalNames section") : read_names(&r, m);
        } else if (strcmp(w, "$Entities") == 0) {
            rc = m->ent ? bad(&r, "second $Entities section") : read_entities(&r, m);
        } else if (strcmp(w, "$Nodes") == 0) {
            rc = have_nodes ? bad(&r, "second $Nodes section") : read_nodes(&r, m);
            have_nodes = 1;
        } else if (strcmp(w, "$Elements") == 0) {
            rc = !have_nodes ? bad(&r, "$Elements before $Nodes")
                 : have_elems ? bad(&r, "second $Elements section") : read_elements(&r, m);
            have_elems = 1;
        } else if (w[0] == '$') {
            rc = skip_section(&r, w);
        } else {
            rc = bad(&r, "expected a section ($Name)");
        }
        if (rc)
            break;
    }
    if (!rc && (!have_nodes || !have_elems))
        rc = pm_error_set(PM_EINPUT, "%s: no %s section", path, have_nodes ? "$Elements" : "$Nodes");
    free(buf);
    return rc;
}
