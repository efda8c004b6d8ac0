#include "io/json_read.h"

#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void jr_join(char *out, size_t cap, const char *path, const char *key)
{
    if (path && path[0])
        snprintf(out, cap, "%s.%s", path, key);
    else
        snprintf(out, cap, "%s", key);
}

void jr_index(char *out, size_t cap, const char *path, size_t i) { snprintf(out, cap, "%s[%zu]", path, i); }

static size_t edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63)
        return 99;
    size_t row[64];
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

const char *jr_suggest(const char *word, const char *const *names)
{
    const char *best = NULL;
    size_t bd = 3;
    for (size_t k = 0; names[k]; k++) {
        size_t d = edit_distance(word, names[k]);
        if (d < bd) {
            bd = d;
            best = names[k];
        }
    }
    if (best)
        return best;
    size_t lw = strlen(word);
    for (size_t k = 0; names[k] && lw >= 3; k++)
        if (!strncmp(names[k], word, lw) || !strncmp(word, names[k], strlen(names[k])))
            return names[k];
    return NULL;
}

static _Thread_local char text_buf[160];

const char *jr_text(json_t *v)
{
    char *s = json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT);
    if (!s) {
        snprintf(text_buf, sizeof text_buf, "(unprintable)");
        return text_buf;
    }
    if (strlen(s) > 80)
        snprintf(text_buf, sizeof text_buf, "%.77s...", s);
    else
        snprintf(text_buf, sizeof text_buf, "%s", s);
    free(s);
    return text_buf;
}

const char *jr_type(json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "an object";
    case JSON_ARRAY: return "a list";
    case JSON_STRING: return "a string";
    case JSON_INTEGER:
    case JSON_REAL: return "a number";
    case JSON_TRUE:
    case JSON_FALSE: return "a boolean";
    default: return "null";
    }
}

static void list_names(char *out, size_t cap, const char *const *names)
{
    size_t used = 0;
    out[0] = '\0';
    for (size_t k = 0; names[k] && used + 4 < cap; k++) {
        int w = snprintf(out + used, cap - used, "%s%s", k ? ", " : "", names[k]);
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

int jr_only_keys(const jr_ctx *cx, json_t *obj, const char *const *allowed)
{
    const char *key;
    json_t *v;
    json_object_foreach(obj, key, v) {
        int ok = 0;
        for (size_t k = 0; allowed[k] && !ok; k++)
            ok = !strcmp(key, allowed[k]);
        if (ok)
            continue;
        char path[512], list[1024];
        jr_join(path, sizeof path, cx->path, key);
        list_names(list, sizeof list, allowed);
        const char *s = jr_suggest(key, allowed);
        if (s)
            return pm_error_set(PM_EINPUT, "%s: %s: unknown key; did you mean '%s'? (allowed here: %s)", cx->file, path,
                                s, list);
        return pm_error_set(PM_EINPUT, "%s: %s: unknown key (allowed here: %s)", cx->file, path, list);
    }
    return PM_OK;
}

int jr_expect_object(const jr_ctx *cx, const char *key, json_t *v)
{
    if (json_is_object(v))
        return PM_OK;
    char path[512];
    jr_join(path, sizeof path, cx->path, key);
    return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s %s", cx->file, path, jr_type(v), jr_text(v));
}

/* The value of key, NULL when absent; errors for missing required keys. */
static int get(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, json_t **v)
{
    *v = json_object_get(obj, key);
    if (!*v && (flags & JR_REQUIRED)) {
        char path[512];
        jr_join(path, sizeof path, cx->path, key);
        return pm_error_set(PM_EINPUT, "%s: %s: required key is missing", cx->file, path);
    }
    return PM_OK;
}

static int wrong_type(const jr_ctx *cx, const char *key, const char *want, json_t *v)
{
    char path[512];
    jr_join(path, sizeof path, cx->path, key);
    return pm_error_set(PM_EINPUT, "%s: %s: expected %s, got %s %s", cx->file, path, want, jr_type(v), jr_text(v));
}

int jr_number(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, double def, double *out)
{
    json_t *v;
    pm_check(get(cx, obj, key, flags, &v));
    if (!v) {
        *out = def;
        return PM_OK;
    }
    if (!json_is_number(v))
        return wrong_type(cx, key, "a number", v);
    *out = json_number_value(v);
    if (!isfinite(*out))
        return wrong_type(cx, key, "a finite number", v);
    return PM_OK;
}

int jr_int(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, long def, long lo, long hi, long *out)
{
    json_t *v;
    pm_check(get(cx, obj, key, flags, &v));
    if (!v) {
        *out = def;
        return PM_OK;
    }
    if (!json_is_integer(v))
        return wrong_type(cx, key, "a whole number", v);
    json_int_t x = json_integer_value(v);
    if (x < lo || x > hi) {
        char path[512];
        jr_join(path, sizeof path, cx->path, key);
        return pm_error_set(PM_EINPUT, "%s: %s: got %lld; allowed: a whole number from %ld to %ld", cx->file, path,
                            (long long)x, lo, hi);
    }
    *out = (long)x;
    return PM_OK;
}

int jr_string(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, const char *def, char *out,
              size_t cap)
{
    json_t *v;
    pm_check(get(cx, obj, key, flags, &v));
    if (!v) {
        snprintf(out, cap, "%s", def ? def : "");
        return PM_OK;
    }
    if (!json_is_string(v))
        return wrong_type(cx, key, "a string", v);
    const char *s = json_string_value(v);
    if (strlen(s) >= cap) {
        char path[512];
        jr_join(path, sizeof path, cx->path, key);
        return pm_error_set(PM_EINPUT, "%s: %s: the text is %zu characters long; at most %zu are allowed", cx->file,
                            path, strlen(s), cap - 1);
    }
    snprintf(out, cap, "%s", s);
    return PM_OK;
}

int jr_bool(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, int def, int *out)
{
    json_t *v;
    pm_check(get(cx, obj, key, flags, &v));
    if (!v) {
        *out = def;
        return PM_OK;
    }
    if (!json_is_boolean(v))
        return wrong_type(cx, key, "true or false", v);
    *out = json_is_true(v);
    return PM_OK;
}

int jr_vecn(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, size_t n, double *out)
{
    json_t *v;
    pm_check(get(cx, obj, key, flags, &v));
    if (!v)
        return PM_OK;
    char want[64];
    snprintf(want, sizeof want, "a list of %zu numbers", n);
    if (!json_is_array(v) || json_array_size(v) != n)
        return wrong_type(cx, key, want, v);
    for (size_t i = 0; i < n; i++) {
        json_t *e = json_array_get(v, i);
        if (!json_is_number(e) || !isfinite(json_number_value(e)))
            return wrong_type(cx, key, want, v);
        out[i] = json_number_value(e);
    }
    return PM_OK;
}

int jr_vec2(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, const double def[2], double out[2])
{
    if (def) {
        out[0] = def[0];
        out[1] = def[1];
    }
    return jr_vecn(cx, obj, key, flags, 2, out);
}

int jr_enum(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, const char *const *names, int def,
            int *out)
{
    json_t *v;
    pm_check(get(cx, obj, key, flags, &v));
    if (!v) {
        *out = def;
        return PM_OK;
    }
    char list[1024], path[512];
    list_names(list, sizeof list, names);
    jr_join(path, sizeof path, cx->path, key);
    if (!json_is_string(v))
        return pm_error_set(PM_EINPUT, "%s: %s: expected one of %s; got %s %s", cx->file, path, list, jr_type(v),
                            jr_text(v));
    const char *s = json_string_value(v);
    for (int k = 0; names[k]; k++)
        if (!strcmp(s, names[k])) {
            *out = k;
            return PM_OK;
        }
    const char *sug = jr_suggest(s, names);
    if (sug)
        return pm_error_set(PM_EINPUT, "%s: %s: unknown value \"%s\"; did you mean '%s'? (allowed: %s)", cx->file, path,
                            s, sug, list);
    return pm_error_set(PM_EINPUT, "%s: %s: unknown value \"%s\" (allowed: %s)", cx->file, path, s, list);
}

int jr_range(const jr_ctx *cx, const char *key, double v, double lo, int lo_open, double hi, int hi_open)
{
    int ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (ok)
        return PM_OK;
    char path[512], interval[128];
    jr_join(path, sizeof path, cx->path, key);
    if (isinf(hi))
        snprintf(interval, sizeof interval, "%s %g", lo_open ? ">" : ">=", lo);
    else if (isinf(lo))
        snprintf(interval, sizeof interval, "%s %g", hi_open ? "<" : "<=", hi);
    else
        snprintf(interval, sizeof interval, "%c%g, %g%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
    return pm_error_set(PM_EINPUT, "%s: %s: got %g; allowed: %s", cx->file, path, v, interval);
}
