/*
 * Reader of Gmsh meshes, MSH 4.1 ASCII (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format):
 * $MeshFormat, $PhysicalNames, $Entities (which physical groups each point/curve/surface belongs
 * to), $Nodes and $Elements; other sections are skipped. Element types read: 15 (point), 1 (2-node
 * line), 2 (3-node triangle), 3 (4-node quad). Second-order elements are refused.
 *
 * pmech reads the file itself instead of linking Gmsh's C API: Debian's libgmsh (18 MB) pulls in
 * OpenCASCADE, FLTK and OpenGL, keeps global state that is not thread-safe, and all a solver needs
 * is this one text format.
 */
#include "pmech/error.h"
#include "pmech/grid.h"

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

typedef struct phys_name {
    int dim, tag;
    char name[64];
} phys_name;

/* Physical tags of one entity. */
typedef struct entity {
    int dim, tag, n_phys;
    int *phys;
} entity;

typedef struct msh {
    size_t n_names;
    phys_name *names;
    size_t n_ent;
    entity *ent;
    long max_tag;
    long *tag_index;   /* node tag -> index into xy, -1 if absent */
    size_t n_nodes;
    double *xy;
    /* elements by dimension */
    size_t n_tri, n_quad, n_line, n_pt;
    long *tri, *quad, *line, *pt;          /* node tags */
    int *tri_ent, *quad_ent, *line_ent, *pt_ent;  /* entity tag of each */
    size_t cap_tri, cap_quad, cap_line, cap_pt;
} msh;

static void msh_free(msh *m)
{
    free(m->names);
    for (size_t i = 0; i < m->n_ent; i++)
        free(m->ent[i].phys);
    free(m->ent);
    free(m->tag_index);
    free(m->xy);
    free(m->tri); free(m->quad); free(m->line); free(m->pt);
    free(m->tri_ent); free(m->quad_ent); free(m->line_ent); free(m->pt_ent);
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

static int read_names(reader *r, msh *m)
{
    long n;
    pm_check(get_count(r, &n, 100000, "number of physical names"));
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
        phys_name *pn = &m->names[m->n_names++];
        pn->dim = (int)dim;
        pn->tag = (int)tag;
        memcpy(pn->name, s, len);
        pn->name[len] = '\0';
        r->p++;
    }
    return expect(r, "$EndPhysicalNames");
}

static int read_entities(reader *r, msh *m)
{
    long cnt[4];
    for (int d = 0; d < 4; d++)
        pm_check(get_count(r, &cnt[d], MAX_COUNT, "number of entities"));
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
            pm_check(get_count(r, &np, 10000, "number of physical tags"));
            entity *e = &m->ent[m->n_ent++];
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

static int read_nodes(reader *r, msh *m)
{
    long nblocks, nnodes, mintag, maxtag;
    pm_check(get_count(r, &nblocks, MAX_COUNT, "number of node blocks"));
    pm_check(get_count(r, &nnodes, MAX_COUNT, "number of nodes"));
    pm_check(get_long(r, &mintag));
    pm_check(get_long(r, &maxtag));
    if (maxtag < 0 || maxtag > 4 * MAX_COUNT || mintag < 0 || (nnodes > 0 && mintag > maxtag))
        return bad(r, "node tags out of range");
    m->max_tag = maxtag;
    m->tag_index = malloc(((size_t)maxtag + 1) * sizeof(long));
    m->xy = malloc(((size_t)nnodes + 1) * 2 * sizeof(double));
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
            if ((rc = get_double(r, &m->xy[2 * (first + k)])) || (rc = get_double(r, &m->xy[2 * (first + k) + 1])) ||
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

static int push_elem(long **nodes, int **ents, size_t *n, size_t *cap, int npe, const long *v, int ent)
{
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 1024;
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
    (*n)++;
    return PM_OK;
}

static int read_elements(reader *r, msh *m)
{
    long nblocks, nel, mn, mx;
    pm_check(get_count(r, &nblocks, MAX_COUNT, "number of element blocks"));
    pm_check(get_count(r, &nel, MAX_COUNT, "number of elements"));
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
            case 15: pm_check(push_elem(&m->pt, &m->pt_ent, &m->n_pt, &m->cap_pt, 1, v, (int)etag)); break;
            case 1: pm_check(push_elem(&m->line, &m->line_ent, &m->n_line, &m->cap_line, 2, v, (int)etag)); break;
            case 2: pm_check(push_elem(&m->tri, &m->tri_ent, &m->n_tri, &m->cap_tri, 3, v, (int)etag)); break;
            default: pm_check(push_elem(&m->quad, &m->quad_ent, &m->n_quad, &m->cap_quad, 4, v, (int)etag)); break;
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

static const entity *find_entity(const msh *m, int dim, int tag)
{
    for (size_t i = 0; i < m->n_ent; i++)
        if (m->ent[i].dim == dim && m->ent[i].tag == tag)
            return &m->ent[i];
    return NULL;
}

static void phys_label(const msh *m, int dim, int tag, char out[64])
{
    for (size_t i = 0; i < m->n_names; i++)
        if (m->names[i].dim == dim && m->names[i].tag == tag) {
            snprintf(out, 64, "%s", m->names[i].name);
            return;
        }
    snprintf(out, 64, "%d", tag);
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* Outward normal of a node set when its nodes lie on one straight line (else zero). */
static void line_normal(const pm_grid *g, const int32_t *nodes, size_t n, int32_t ea, int32_t eb, double nrm[2])
{
    nrm[0] = nrm[1] = 0;
    if (n < 2)
        return;
    /* direction from the farthest pair found from node 0 */
    const double *p0 = g->x + 2 * nodes[0];
    size_t far = 0;
    double dmax = 0;
    for (size_t i = 1; i < n; i++) {
        const double *p = g->x + 2 * nodes[i];
        double d = hypot(p[0] - p0[0], p[1] - p0[1]);
        if (d > dmax) {
            dmax = d;
            far = i;
        }
    }
    if (dmax <= 0)
        return;
    const double *p1 = g->x + 2 * nodes[far];
    double t[2] = {(p1[0] - p0[0]) / dmax, (p1[1] - p0[1]) / dmax};
    for (size_t i = 0; i < n; i++) {
        const double *p = g->x + 2 * nodes[i];
        if (fabs((p[0] - p0[0]) * t[1] - (p[1] - p0[1]) * t[0]) > 1e-9 * dmax)
            return; /* not straight */
    }
    double cand[2] = {t[1], -t[0]};
    /* orient away from a cell that has edge (ea, eb) */
    const int npc = g->nodes_per_cell;
    for (size_t c = 0; c < g->n_cells; c++) {
        const int32_t *v = g->conn + (size_t)npc * c;
        int has_a = 0, has_b = 0;
        double cx = 0, cy = 0;
        for (int k = 0; k < npc; k++) {
            has_a |= v[k] == ea;
            has_b |= v[k] == eb;
            cx += g->x[2 * v[k]] / npc;
            cy += g->x[2 * v[k] + 1] / npc;
        }
        if (has_a && has_b) {
            double mx = 0.5 * (g->x[2 * ea] + g->x[2 * eb]), my = 0.5 * (g->x[2 * ea + 1] + g->x[2 * eb + 1]);
            double s = cand[0] * (mx - cx) + cand[1] * (my - cy);
            nrm[0] = s >= 0 ? cand[0] : -cand[0];
            nrm[1] = s >= 0 ? cand[1] : -cand[1];
            return;
        }
    }
}

/* Build the grid from the parsed file. */
static int build(pm_grid *g, const msh *m, const char *path)
{
    const size_t n2d = m->n_tri + m->n_quad;
    if (n2d == 0)
        return pm_error_set(PM_EINPUT, "%s: the mesh has no triangles or quads (mesh it in 2-D: gmsh -2)", path);
    const int mixed = m->n_tri && m->n_quad;
    const pm_element el = m->n_quad && !mixed ? PM_QUAD4 : PM_TRI3;
    const int npc = el == PM_QUAD4 ? 4 : 3;
    const size_t ncells = m->n_tri + (mixed ? 2 : 1) * m->n_quad;
    int32_t *conn = malloc(ncells * (size_t)npc * sizeof(int32_t));
    long *used = malloc(m->n_nodes * sizeof(long)); /* node index -> compact index */
    double *xy = malloc(2 * m->n_nodes * sizeof(double));
    int32_t *cell_of = malloc(n2d * sizeof(int32_t)); /* first cell of each 2-D element */
    int rc = PM_OK;
    if (!conn || !used || !xy || !cell_of) {
        rc = pm_error_set(PM_ENOMEM, "out of memory reading %s", path);
        goto done;
    }
    for (size_t i = 0; i < m->n_nodes; i++)
        used[i] = -1;
    size_t nn = 0, c = 0;
#define NODE(tag) (used[m->tag_index[tag]] >= 0 ? used[m->tag_index[tag]] \
                   : (xy[2 * nn] = m->xy[2 * m->tag_index[tag]], xy[2 * nn + 1] = m->xy[2 * m->tag_index[tag] + 1], \
                      used[m->tag_index[tag]] = (long)nn++))
    for (size_t e = 0; e < m->n_tri; e++) {
        cell_of[e] = (int32_t)c;
        for (int k = 0; k < 3; k++)
            conn[3 * c + k] = (int32_t)NODE(m->tri[3 * e + k]);
        c++;
    }
    for (size_t e = 0; e < m->n_quad; e++) {
        int32_t q[4];
        for (int k = 0; k < 4; k++)
            q[k] = (int32_t)NODE(m->quad[4 * e + k]);
        cell_of[m->n_tri + e] = (int32_t)c;
        if (!mixed) {
            memcpy(conn + 4 * c, q, sizeof q);
            c++;
        } else {
            int32_t t1[3] = {q[0], q[1], q[2]}, t2[3] = {q[0], q[2], q[3]};
            memcpy(conn + 3 * c, t1, sizeof t1);
            memcpy(conn + 3 * (c + 1), t2, sizeof t2);
            c += 2;
        }
    }
#undef NODE
    rc = pm_grid_unstructured(g, nn, xy, ncells, conn, el);
    if (rc) {
        pm_error_prefix(rc, "%s: ", path);
        goto done;
    }
    /* 2-D physical groups -> cell sets */
    for (size_t ie = 0; ie < m->n_ent && !rc; ie++) {
        const entity *en = &m->ent[ie];
        if (en->dim != 2)
            continue;
        for (int q = 0; q < en->n_phys && !rc; q++) {
            char name[64];
            phys_label(m, 2, en->phys[q], name);
            pm_cell_set *set = NULL;
            for (size_t s = 0; s < g->n_cell_sets; s++)
                if (strcmp(g->cell_sets[s].name, name) == 0)
                    set = &g->cell_sets[s];
            if (!set) {
                pm_cell_set *cs = realloc(g->cell_sets, (g->n_cell_sets + 1) * sizeof *cs);
                if (!cs) {
                    rc = pm_error_set(PM_ENOMEM, "out of memory");
                    break;
                }
                g->cell_sets = cs;
                set = &g->cell_sets[g->n_cell_sets++];
                memset(set, 0, sizeof *set);
                snprintf(set->name, sizeof set->name, "%s", name);
            }
            size_t add = 0;
            for (size_t e = 0; e < n2d; e++) {
                int ent = e < m->n_tri ? m->tri_ent[e] : m->quad_ent[e - m->n_tri];
                if (ent == en->tag)
                    add += (e >= m->n_tri && mixed) ? 2 : 1;
            }
            int32_t *cells = realloc(set->cells, (set->n + add + 1) * sizeof(int32_t));
            if (!cells) {
                rc = pm_error_set(PM_ENOMEM, "out of memory");
                break;
            }
            set->cells = cells;
            for (size_t e = 0; e < n2d; e++) {
                int ent = e < m->n_tri ? m->tri_ent[e] : m->quad_ent[e - m->n_tri];
                if (ent != en->tag)
                    continue;
                set->cells[set->n++] = cell_of[e];
                if (e >= m->n_tri && mixed)
                    set->cells[set->n++] = cell_of[e] + 1;
            }
        }
    }
    /* 1-D and 0-D physical groups -> node sets */
    for (int dim = 1; dim >= 0 && !rc; dim--) {
        /* every distinct (dim, physical tag) */
        for (size_t ie = 0; ie < m->n_ent && !rc; ie++) {
            const entity *en = &m->ent[ie];
            if (en->dim != dim)
                continue;
            for (int q = 0; q < en->n_phys && !rc; q++) {
                const int ptag = en->phys[q];
                /* handle each physical group once: at its first entity */
                int seen = 0;
                for (size_t je = 0; je < ie && !seen; je++)
                    if (m->ent[je].dim == dim)
                        for (int k = 0; k < m->ent[je].n_phys; k++)
                            seen |= m->ent[je].phys[k] == ptag;
                if (seen)
                    continue;
                const size_t ne = dim == 1 ? m->n_line : m->n_pt;
                const long *vv = dim == 1 ? m->line : m->pt;
                const int *ents = dim == 1 ? m->line_ent : m->pt_ent;
                const int npe = dim == 1 ? 2 : 1;
                int32_t *nodes = malloc((ne * (size_t)npe + 1) * sizeof(int32_t));
                if (!nodes) {
                    rc = pm_error_set(PM_ENOMEM, "out of memory");
                    break;
                }
                size_t cnt = 0;
                int32_t ea = -1, eb = -1;
                for (size_t e = 0; e < ne; e++) {
                    const entity *ee = find_entity(m, dim, ents[e]);
                    int in = 0;
                    for (int k = 0; ee && k < ee->n_phys; k++)
                        in |= ee->phys[k] == ptag;
                    if (!in)
                        continue;
                    int ok = 1;
                    int32_t loc[2] = {-1, -1};
                    for (int k = 0; k < npe; k++) {
                        long u = used[m->tag_index[vv[(size_t)npe * e + k]]];
                        if (u < 0)
                            ok = 0; /* a node no cell uses */
                        else
                            nodes[cnt++] = loc[k] = (int32_t)u;
                    }
                    if (dim == 1 && ok && ea < 0) {
                        ea = loc[0];
                        eb = loc[1];
                    }
                }
                qsort(nodes, cnt, sizeof(int32_t), cmp_i32);
                size_t u = 0;
                for (size_t i = 0; i < cnt; i++)
                    if (u == 0 || nodes[i] != nodes[u - 1])
                        nodes[u++] = nodes[i];
                double nrm[2] = {0, 0};
                if (dim == 1 && ea >= 0)
                    line_normal(g, nodes, u, ea, eb, nrm);
                char name[64];
                phys_label(m, dim, ptag, name);
                int k = pm_grid_add_node_set(g, name, u, nodes, nrm);
                free(nodes);
                if (k < 0)
                    rc = k;
            }
        }
    }
    if (rc)
        pm_grid_free(g);
done:
    free(conn);
    free(used);
    free(xy);
    free(cell_of);
    return rc;
}

int pm_grid_gmsh_read(pm_grid *g, const char *path)
{
    memset(g, 0, sizeof *g);
    FILE *f = fopen(path, "rb");
    if (!f)
        return pm_error_set(PM_EIO, "%s: cannot open the mesh file: %s", path, strerror(errno));
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 65536 + 1 > cap) {
            cap = cap ? 2 * cap : 1 << 20;
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
    msh m;
    memset(&m, 0, sizeof m);
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
            rc = m.names ? bad(&r, "second $PhysicalNames section") : read_names(&r, &m);
        } else if (strcmp(w, "$Entities") == 0) {
            rc = m.ent ? bad(&r, "second $Entities section") : read_entities(&r, &m);
        } else if (strcmp(w, "$Nodes") == 0) {
            rc = have_nodes ? bad(&r, "second $Nodes section") : read_nodes(&r, &m);
            have_nodes = 1;
        } else if (strcmp(w, "$Elements") == 0) {
            rc = !have_nodes ? bad(&r, "$Elements before $Nodes")
                 : have_elems ? bad(&r, "second $Elements section") : read_elements(&r, &m);
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
    if (!rc)
        rc = build(g, &m, path);
    msh_free(&m);
    free(buf);
    return rc;
}
