/*
 * Case files (docs/input.md) to pm_case. Every key is checked: unknown keys, wrong types,
 * out-of-range values and physical nonsense are errors naming the key path, the value and what is
 * allowed; JSON syntax errors name file:line:column. Counts that cannot fit in memory are refused
 * before anything is allocated. This file reads the file and the top level; each section has its
 * own parser (io/case_internal.h), called in the order their cross-checks need.
 */
#include "pmech/case.h"

#include "io/case_internal.h"
#include "io/json_read.h"
#include "pmech/approx.h"
#include "pmech/error.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const formulations[] = {"plane_strain", "plane_stress", "axisymmetric", NULL};
static const char *const methods[] = {"mpm", "gmm", "rkpm", NULL};

int pm_case_fail(const char *file, const char *path, const char *what, const char *detail)
{
    return pm_error_set(PM_EINPUT, "%s: %s: %s%s", file, path, what, detail ? detail : "");
}

/* The names and which method takes which come from the approximation registry; a method's first
 * name is its default (mpm: linear, gmm: mls, rkpm: rk_cubic). */
static int parse_shape_function(pm_case *c, const jr_ctx *cx, json_t *root)
{
    const char *all[16], *ok[16];
    pm_approx_all_names(all, sizeof all / sizeof all[0]);
    pm_approx_names_for_method(c->method, ok, sizeof ok / sizeof ok[0]);
    int v, d = 0;
    while (all[d] && ok[0] && strcmp(all[d], ok[0]) != 0)
        d++;
    pm_check(jr_enum(cx, root, "shape_function", 0, all, d, &v));
    snprintf(c->shape_function, sizeof c->shape_function, "%s", all[v]);
    if (pm_approx_serves(c->shape_function, c->method))
        return PM_OK;
    char list[256] = "";
    for (const char *const *k = ok; *k; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k == ok ? "" : ", ", *k);
    return pm_error_set(PM_EINPUT, "%s: shape_function: \"%s\" does not go with method '%s' (allowed: %s)", c->file,
                        c->shape_function, methods[c->method], list);
}

static void split_name(pm_case *c, const char *name)
{
    snprintf(c->file, sizeof c->file, "%s", name);
    const char *slash = strrchr(name, '/');
    if (slash)
        snprintf(c->dir, sizeof c->dir, "%.*s", (int)(slash - name), name);
    else
        snprintf(c->dir, sizeof c->dir, ".");
    if (!c->dir[0])
        snprintf(c->dir, sizeof c->dir, "/");
    const char *base = slash ? slash + 1 : name;
    snprintf(c->stem, sizeof c->stem, "%s", base);
    char *dot = strrchr(c->stem, '.');
    if (dot && dot != c->stem)
        *dot = '\0';
}

static int parse_root(pm_case *c, json_t *root)
{
    jr_ctx cx = {c->file, ""};
    if (!json_is_object(root))
        return pm_error_set(PM_EINPUT, "%s: the case must be a JSON object, got %s", c->file, jr_type(root));
    pm_check(jr_only_keys(&cx, root, pm_case_keys(PM_KEYS_TOP)));
    pm_check(jr_string(&cx, root, "title", 0, c->stem, c->title, sizeof c->title));
    long dim;
    json_t *jd = json_object_get(root, "dimension");
    if (jd && json_is_integer(jd) && json_integer_value(jd) == 3)
        return pm_case_fail(c->file, "dimension", "got 3: 3-D is not supported yet; allowed: 2", NULL);
    pm_check(jr_int(&cx, root, "dimension", JR_REQUIRED, 2, 2, 2, &dim));
    c->dimension = (int)dim;
    int v;
    pm_check(jr_enum(&cx, root, "formulation", 0, formulations, PM_PLANE_STRAIN, &v));
    c->formulation = (pm_formulation)v;
    pm_check(jr_enum(&cx, root, "method", 0, methods, PM_METHOD_MPM, &v));
    c->method = (pm_method)v;
    pm_check(parse_shape_function(c, &cx, root));
    pm_check(jr_number(&cx, root, "lme_gamma", 0, NAN, &c->lme_gamma));
    if (!isnan(c->lme_gamma))
        pm_check(jr_range(&cx, "lme_gamma", c->lme_gamma, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, root, "support_radius", 0, NAN, &c->support_radius));
    if (!isnan(c->support_radius))
        pm_check(jr_range(&cx, "support_radius", c->support_radius, 0, 1, INFINITY, 0));
    pm_check(jr_number(&cx, root, "max_condition", 0, NAN, &c->max_condition));
    if (!isnan(c->max_condition))
        pm_check(jr_range(&cx, "max_condition", c->max_condition, 1, 0, INFINITY, 0));
    json_t *a = json_object_get(root, "analysis");
    if (!a)
        return pm_case_fail(c->file, "analysis", "required key is missing", NULL);
    pm_check(pm_case_parse_analysis(c, a));
    json_t *g = json_object_get(root, "grid");
    if (!g)
        return pm_case_fail(c->file, "grid", "required key is missing", NULL);
    pm_check(pm_case_parse_grid(c, g));
    pm_check(pm_case_parse_materials(c, json_object_get(root, "materials")));
    pm_check(pm_case_check_strength_reduction(c));
    pm_check(pm_case_parse_sources(c, json_object_get(root, "sources")));
    pm_check(pm_case_parse_bodies(c, json_object_get(root, "bodies")));
    pm_check(pm_case_parse_bcs(c, json_object_get(root, "boundary_conditions")));
    pm_check(pm_case_parse_probes(c, json_object_get(root, "probes")));
    pm_check(pm_case_parse_output(c, json_object_get(root, "output")));
    pm_check(pm_case_parse_sinks(c, json_object_get(root, "sinks")));
    pm_check(pm_case_parse_contact_pairs(c, json_object_get(root, "contact_pairs")));
    pm_check(pm_case_parse_obstacles(c, json_object_get(root, "obstacles")));
    pm_check(pm_case_parse_loads(c, json_object_get(root, "loads")));
    return pm_case_check_sizes(c);
}

int pm_case_from_json(json_t *root, const char *name, pm_case *c)
{
    memset(c, 0, sizeof *c);
    split_name(c, name);
    c->doc = root;
    return parse_root(c, root);
}

int pm_case_load_buffer(const char *text, size_t len, const char *name, pm_case *c)
{
    memset(c, 0, sizeof *c);
    split_name(c, name);
    json_error_t err;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &err);
    if (!root)
        return pm_error_set(PM_EINPUT, "%s:%d:%d: %s", c->file, err.line, err.column, err.text);
    return pm_case_from_json(root, name, c);
}

int pm_case_load(const char *path, pm_case *c)
{
    memset(c, 0, sizeof *c);
    FILE *f = fopen(path, "rb");
    if (!f) {
        split_name(c, path);
        return pm_error_set(PM_EINPUT, "%s: cannot open the case file (does it exist?)", path);
    }
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 65536 > cap) {
            cap = cap ? 2 * cap : 131072;
            if (cap > ((size_t)1 << 30)) {
                free(buf);
                fclose(f);
                return pm_error_set(PM_EINPUT, "%s: the case file is larger than 1 GiB", path);
            }
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(f);
                return pm_error_set(PM_ENOMEM, "out of memory reading %s", path);
            }
            buf = nb;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0)
            break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return pm_error_set(PM_EIO, "%s: read error", path);
    }
    int rc = pm_case_load_buffer(buf, len, path, c);
    free(buf);
    return rc;
}

void pm_case_free(pm_case *c)
{
    for (size_t b = 0; b < c->n_bodies && c->bodies; b++)
        free(c->bodies[b].shape.points);
    free(c->bodies);
    for (size_t k = 0; k < c->n_sources && c->sources; k++) {
        free(c->sources[k].body.shape.points);
        free(c->sources[k].times);
    }
    free(c->sources);
    for (size_t k = 0; k < c->n_sinks && c->sinks; k++)
        free(c->sinks[k].shape.points);
    free(c->sinks);
    free(c->materials);
    free(c->bcs);
    pm_case_free_obstacles(c);
    pm_case_free_loads(c);
    free(c->probes);
    free(c->contact_pairs);
    json_decref(c->doc);
    memset(c, 0, sizeof *c);
}
