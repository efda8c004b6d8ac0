/*
 * docs/input.md against the case loader's key table (io/case_internal.h, the lists the parsers
 * check objects with) and the material registry: every key the loader accepts is documented in
 * the section of its object, and every key documented there is accepted.
 *
 * How docs/input.md documents keys, which this test reads:
 * - an object's section is headed by its key path in a code span (## `analysis`, ### `bodies[].shape`;
 *   the root: ## Top level) and holds one table, up to the next heading;
 * - a table whose header starts with `key` documents one key per row: the code spans of its first
 *   cell (`x`, `y` documents both);
 * - a table whose header starts with `type` documents the kinds of an object: the first cell is the
 *   value of "type", the identifier code spans of the second cell that kind's keys (besides `type`);
 * - materials[]: the prose names the keys every material takes, the `model` table a row per model
 *   with its parameters as code spans and the words "elastic pair" when it takes one.
 * Only code spans that are identifiers ([a-z_][a-z0-9_]*) count as keys, so values such as `["x"]`
 * or `{"x": value}` in those cells are not mistaken for keys.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"
#include "pmech/material.h"

#ifndef PMECH_SOURCE_DIR
#error "PMECH_SOURCE_DIR must name the source tree (tests/CMakeLists.txt sets it)"
#endif

#define MAX_NAMES 64
#define NAME_LEN 64

typedef struct names {
    int n;
    char v[MAX_NAMES][NAME_LEN];
} names;

static void add(names *s, const char *k)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->v[i], k))
            return;
    assert_true(s->n < MAX_NAMES);
    snprintf(s->v[s->n++], NAME_LEN, "%s", k);
}

static int has(const names *s, const char *k)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->v[i], k))
            return 1;
    return 0;
}

static char *doc;       /* docs/input.md */
static int problems;    /* every mismatch is printed, then the test fails once */

static void problem(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("docs/input.md: ");
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
    problems++;
}

static int setup(void **state)
{
    (void)state;
    FILE *f = fopen(PMECH_SOURCE_DIR "/docs/input.md", "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    doc = malloc((size_t)n + 1);
    assert_non_null(doc);
    assert_int_equal(fread(doc, 1, (size_t)n, f), (size_t)n);
    doc[n] = '\0';
    fclose(f);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    free(doc);
    return 0;
}

/* The identifier code spans of text [a, b) into s. */
static void spans(const char *a, const char *b, names *s)
{
    for (const char *p = a; p < b; p++) {
        if (*p != '`')
            continue;
        const char *q = memchr(p + 1, '`', (size_t)(b - p - 1));
        if (!q)
            return;
        int ident = q > p + 1 && (islower((unsigned char)p[1]) || p[1] == '_');
        for (const char *c = p + 1; c < q && ident; c++)
            ident = islower((unsigned char)*c) || isdigit((unsigned char)*c) || *c == '_';
        if (ident && q - p - 1 < NAME_LEN) {
            char k[NAME_LEN];
            snprintf(k, sizeof k, "%.*s", (int)(q - p - 1), p + 1);
            add(s, k);
        }
        p = q;
    }
}

/* The section headed by @p heading (a heading line whose text after the #s is exactly it), from
 * the line after the heading to the next heading; NULL when there is none. */
static const char *section(const char *heading, const char **end)
{
    for (const char *line = doc; *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : line + strlen(line)) {
        if (*line != '#')
            continue;
        const char *t = line;
        while (*t == '#')
            t++;
        while (*t == ' ')
            t++;
        const char *nl = strchr(t, '\n');
        size_t len = nl ? (size_t)(nl - t) : strlen(t);
        if (len != strlen(heading) || strncmp(t, heading, len) != 0)
            continue;
        const char *body = nl ? nl + 1 : t + len;
        const char *e = body;
        while (*e && !(*e == '#' && (e == doc || e[-1] == '\n')))
            e++;
        *end = e;
        return body;
    }
    return NULL;
}

/* The cells of the table row at @p line: starts and ends of up to @p max cells; returns the count. */
static int cells(const char *line, const char **start, const char **stop, int max)
{
    const char *nl = strchr(line, '\n');
    const char *e = nl ? nl : line + strlen(line);
    int n = 0;
    const char *p = line + 1;
    while (p < e && n < max) {
        const char *bar = memchr(p, '|', (size_t)(e - p));
        if (!bar)
            break;
        start[n] = p;
        stop[n] = bar;
        n++;
        p = bar + 1;
    }
    return n;
}

/* A documented table: its kind, and per row the first cell's spans and the second's. */
typedef struct table {
    int by_type;            /* header `type`: rows are kinds of the object */
    int rows;
    names first[32], second[32];
} table;

static int read_table(const char *a, const char *b, table *t)
{
    memset(t, 0, sizeof *t);
    int header = 0;
    for (const char *line = a; line < b; line = strchr(line, '\n') + 1) {
        if (*line == '|') {
            const char *s[8] = {0}, *e[8] = {0};
            int n = cells(line, s, e, 8);
            if (n == 0)
                break;
            if (!header) {
                header = 1;
                while (s[0] < e[0] && *s[0] == ' ')
                    s[0]++;
                t->by_type = !strncmp(s[0], "`type`", 6);
                if (!t->by_type && strncmp(s[0], "key", 3) != 0)
                    return 0;
                continue;
            }
            if (s[0][1] == '-')
                continue; /* the |---| line */
            assert_true(t->rows < 32);
            spans(s[0], e[0], &t->first[t->rows]);
            if (n >= 2)
                spans(s[1], e[1], &t->second[t->rows]);
            t->rows++;
        } else if (header) {
            break;
        }
        if (!strchr(line, '\n'))
            break;
    }
    return header;
}

static void heading_of(const char *path, char *out, size_t cap)
{
    if (!path[0])
        snprintf(out, cap, "Top level");
    else
        snprintf(out, cap, "`%s`", path);
}

static void every_case_key_documented_and_every_documented_key_accepted(void **state)
{
    (void)state;
    size_t n;
    const pm_case_keyset *ks = pm_case_keysets(&n);
    assert_int_equal(n, PM_KEYS_COUNT);
    for (size_t i = 0; i < n; i++) {
        /* each path once: all its lists together */
        int seen = 0;
        for (size_t j = 0; j < i; j++)
            seen |= !strcmp(ks[j].path, ks[i].path);
        if (seen)
            continue;
        const char *path = ks[i].path;
        char head[128];
        heading_of(path, head, sizeof head);
        const char *end, *sec = section(head, &end);
        if (!sec) {
            problem("no section headed %s for the keys of %s", head, path[0] ? path : "the top level");
            continue;
        }
        table t;
        if (!read_table(sec, end, &t)) {
            problem("section %s has no table of keys (header `key` or `type`)", head);
            continue;
        }
        names accepted = {0}, documented = {0}, generic = {0}, variants = {0};
        int has_generic = 0, has_variants = 0;
        for (size_t j = i; j < n; j++) {
            if (strcmp(ks[j].path, path) != 0)
                continue;
            for (const char *const *k = ks[j].keys; *k; k++) {
                add(&accepted, *k);
                add(ks[j].variant ? &variants : &generic, *k);
            }
            has_generic |= !ks[j].variant;
            has_variants |= !!ks[j].variant;
        }
        for (int r = 0; r < t.rows; r++) {
            const names *keys = t.by_type ? &t.second[r] : &t.first[r];
            for (int k = 0; k < keys->n; k++)
                add(&documented, keys->v[k]);
        }
        if (t.by_type)
            add(&documented, "type");
        for (int k = 0; k < accepted.n; k++)
            if (!has(&documented, accepted.v[k]))
                problem("%s: the loader accepts `%s`, the reference does not document it", head, accepted.v[k]);
        for (int k = 0; k < documented.n; k++)
            if (!has(&accepted, documented.v[k]))
                problem("%s: documents `%s`, which the loader refuses", head, documented.v[k]);
        /* a list for any kind besides the kinds' own lists must allow nothing they do not */
        if (has_generic && has_variants)
            for (int k = 0; k < generic.n; k++)
                if (!has(&variants, generic.v[k]))
                    problem("%s: `%s` is allowed for every kind but by no kind's own list", head, generic.v[k]);
        if (!t.by_type)
            continue;
        /* kind by kind: the row of each kind lists exactly that kind's keys */
        for (size_t j = i; j < n; j++) {
            if (strcmp(ks[j].path, path) != 0 || !ks[j].variant)
                continue;
            int row = -1;
            for (int r = 0; r < t.rows; r++)
                if (t.first[r].n == 1 && !strcmp(t.first[r].v[0], ks[j].variant))
                    row = r;
            if (row < 0) {
                problem("%s: no row for the type `%s`", head, ks[j].variant);
                continue;
            }
            names own = t.second[row];
            add(&own, "type");
            for (const char *const *k = ks[j].keys; *k; k++)
                if (!has(&own, *k))
                    problem("%s: type `%s` takes `%s`, not in its row", head, ks[j].variant, *k);
            for (int k = 0; k < own.n; k++) {
                int ok = 0;
                for (const char *const *q = ks[j].keys; *q; q++)
                    ok |= !strcmp(*q, own.v[k]);
                if (!ok)
                    problem("%s: type `%s`: its row documents `%s`, which the loader refuses", head, ks[j].variant,
                            own.v[k]);
            }
        }
    }
    fflush(stdout);
    if (problems)
        fail_msg("%d mismatches between the case loader and docs/input.md (listed above)", problems);
}

static void every_material_key_documented_and_every_documented_key_accepted(void **state)
{
    (void)state;
    problems = 0;
    const char *end, *sec = section("`materials[]`", &end);
    assert_non_null(sec);
    const char *tab = strstr(sec, "\n|");
    assert_true(tab && tab < end);
    names prose = {0};
    spans(sec, tab, &prose);
    static const char *const common[] = {"name", "model", "density", NULL};
    static const char *const pair[] = {"youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus", NULL};
    for (const char *const *k = common; *k; k++)
        if (!has(&prose, *k))
            problem("`materials[]`: every material takes `%s`; the prose above the table does not name it", *k);
    for (const char *const *k = pair; *k; k++)
        if (!has(&prose, *k))
            problem("`materials[]`: the elastic pair includes `%s`; the prose does not name it", *k);
    /* the model table: header "model", then a row per model */
    int rows = 0;
    names documented_models = {0};
    for (const char *line = tab + 1; line < end && *line == '|'; line = strchr(line, '\n') + 1) {
        const char *s[4] = {0}, *e[4] = {0};
        int nc = cells(line, s, e, 4);
        if (rows++ < 2 || nc < 2)
            continue; /* header and |---| */
        names model = {0}, params = {0};
        spans(s[0], e[0], &model);
        spans(s[1], e[1], &params);
        if (model.n != 1) {
            problem("`materials[]`: a table row without one model name in its first cell");
            continue;
        }
        add(&documented_models, model.v[0]);
        const pm_material_ops *ops = pm_material_find(model.v[0]);
        if (!ops) {
            problem("`materials[]`: documents the model `%s`, which the loader refuses", model.v[0]);
            continue;
        }
        char cell[1024];
        snprintf(cell, sizeof cell, "%.*s", (int)(e[1] - s[1]), s[1]);
        const int says_pair = strstr(cell, "elastic pair") != NULL;
        if (says_pair != !!ops->elastic_pair)
            problem("`materials[]`: `%s` %s", model.v[0],
                    ops->elastic_pair ? "takes the elastic pair; its row does not say so"
                                      : "takes no elastic pair; its row says it does");
        for (size_t k = 0; k < ops->n_params; k++)
            if (!has(&params, ops->params[k].key))
                problem("`materials[]`: the loader accepts `%s` for `%s`; its row lacks it", ops->params[k].key,
                        model.v[0]);
        for (int k = 0; k < params.n; k++)
            if (pm_material_param_index(ops, params.v[k]) < 0)
                problem("`materials[]`: documents `%s` for `%s`, which the loader refuses", params.v[k], model.v[0]);
    }
    for (const char *const *m = pm_material_names(); *m; m++)
        if (!has(&documented_models, *m))
            problem("`materials[]`: the loader accepts the model `%s`; the table has no row for it", *m);
    fflush(stdout);
    if (problems)
        fail_msg("%d mismatches between the material models and docs/input.md (listed above)", problems);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_case_key_documented_and_every_documented_key_accepted),
        cmocka_unit_test(every_material_key_documented_and_every_documented_key_accepted),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
