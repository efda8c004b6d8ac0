/*
 * Changing a loaded case by key path (pm_case_set and friends). The case keeps the JSON document it was
 * read from; a change edits a copy of that document and loads the copy as a whole new case, so a value
 * set from C or Python meets every check a case file meets (one loader, no second set of rules), and a
 * refused value leaves the case as it was.
 */
#include "pmech/case.h"

#include "io/case_internal.h"
#include "pmech/error.h"

#include <ctype.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEP_MAX 32

/* One step of a key path: an object key, or a list index. */
typedef struct step {
    char key[PM_NAME_MAX]; /* "" for an index */
    size_t index;
} step;

/* Split "materials[0].friction_angle" into steps; returns the count, or -1 (message set). */
static int parse_path(const pm_case *c, const char *path, step *st)
{
    int n = 0;
    const char *p = path;
    if (!*p)
        return 0;
    for (;;) {
        if (n == STEP_MAX)
            return pm_error_set(PM_EINPUT, "%s: key path '%s': more than %d steps", c->file, path, STEP_MAX), -1;
        if (*p == '[') {
            char *end;
            if (!isdigit((unsigned char)p[1]))
                goto bad;
            unsigned long long i = strtoull(p + 1, &end, 10);
            if (*end != ']')
                goto bad;
            st[n].key[0] = '\0';
            st[n++].index = (size_t)i;
            p = end + 1;
        } else {
            size_t len = strcspn(p, ".[");
            if (len == 0 || len >= PM_NAME_MAX)
                goto bad;
            memcpy(st[n].key, p, len);
            st[n++].key[len] = '\0';
            p += len;
        }
        if (!*p)
            return n;
        if (*p == '.')
            p++;
        else if (*p != '[')
            goto bad;
    }
bad:
    pm_error_set(PM_EINPUT, "%s: '%s' is not a key path (keys joined by '.', list entries as [i], e.g. "
                 "materials[0].friction_angle)", c->file, path);
    return -1;
}

/* The path of the first k steps, for messages. */
static void path_prefix(const step *st, int k, char *out, size_t cap)
{
    out[0] = '\0';
    for (int i = 0; i < k; i++) {
        size_t len = strlen(out);
        if (st[i].key[0])
            snprintf(out + len, cap - len, "%s%s", len ? "." : "", st[i].key);
        else
            snprintf(out + len, cap - len, "[%zu]", st[i].index);
    }
}

/* The value at the first k steps of the path (borrowed), or NULL with a message. */
static json_t *walk(const pm_case *c, json_t *root, const step *st, int k, int create)
{
    json_t *cur = root;
    char where[STEP_MAX * (PM_NAME_MAX + 24)];
    for (int i = 0; i < k; i++) {
        json_t *next;
        if (st[i].key[0]) {
            if (!json_is_object(cur)) {
                path_prefix(st, i, where, sizeof where);
                pm_error_set(PM_EINPUT, "%s: %s: is not an object, so it has no key '%s'", c->file, where, st[i].key);
                return NULL;
            }
            next = json_object_get(cur, st[i].key);
            if (!next && create) {
                next = st[i + 1].key[0] ? json_object() : json_array();
                if (!next || json_object_set_new(cur, st[i].key, next) != 0) {
                    pm_error_set(PM_ENOMEM, "out of memory changing %s", c->file);
                    return NULL;
                }
            }
        } else {
            if (!json_is_array(cur)) {
                path_prefix(st, i, where, sizeof where);
                pm_error_set(PM_EINPUT, "%s: %s: is not a list, so it has no entry [%zu]", c->file, where, st[i].index);
                return NULL;
            }
            next = json_array_get(cur, st[i].index);
        }
        if (!next) {
            path_prefix(st, i + 1, where, sizeof where);
            if (st[i].key[0])
                pm_error_set(PM_EINPUT, "%s: %s: the case has no such key", c->file, where);
            else
                pm_error_set(PM_EINPUT, "%s: %s: the list has %zu %s", c->file, where, json_array_size(cur),
                             json_array_size(cur) == 1 ? "entry" : "entries");
            return NULL;
        }
        cur = next;
    }
    return cur;
}

static int need_doc(const pm_case *c)
{
    if (!c->doc)
        return pm_error_set(PM_EINPUT, "%s: this case was not loaded from a file or text, so it has no keys to change",
                            c->file[0] ? c->file : "case");
    return PM_OK;
}

/* Reload the case from @p doc (owned); on success it replaces *c, else *c stays as it was. */
static int reload(pm_case *c, json_t *doc)
{
    pm_case fresh;
    char name[PM_PATH_MAX];
    snprintf(name, sizeof name, "%s", c->file);
    int rc = pm_case_from_json(doc, name, &fresh);
    if (rc) {
        char msg[2048];
        snprintf(msg, sizeof msg, "%s", pm_error_message());
        pm_case_free(&fresh);
        return pm_error_set(rc, "%s", msg);
    }
    pm_case_free(c);
    *c = fresh;
    return PM_OK;
}

/* Put @p value (a new reference, consumed) at @p path of a copy of the document and reload. remove: take
 * the key out instead. */
static int change(pm_case *c, const char *path, json_t *value, int remove)
{
    step st[STEP_MAX];
    int rc = need_doc(c);
    const int n = rc ? -1 : parse_path(c, path, st);
    if (!rc && n == 0)
        rc = pm_error_set(PM_EINPUT, "%s: an empty key path names the whole case: give a key", c->file);
    if (rc || n <= 0) {
        json_decref(value);
        return rc ? rc : PM_EINPUT;
    }
    if (!remove && !value)
        return pm_error_set(PM_ENOMEM, "out of memory changing %s", c->file);
    json_t *doc = json_deep_copy(c->doc);
    if (!doc) {
        json_decref(value);
        return pm_error_set(PM_ENOMEM, "out of memory changing %s", c->file);
    }
    json_t *parent = walk(c, doc, st, n - 1, !remove);
    const step *last = &st[n - 1];
    char where[STEP_MAX * (PM_NAME_MAX + 24)];
    path_prefix(st, n, where, sizeof where);
    if (!parent) {
        rc = PM_EINPUT;
    } else if (last->key[0]) {
        if (!json_is_object(parent))
            rc = pm_error_set(PM_EINPUT, "%s: %s: the parent is not an object", c->file, where);
        else if (remove)
            rc = json_object_del(parent, last->key) == 0
                     ? PM_OK
                     : pm_error_set(PM_EINPUT, "%s: %s: the case has no such key to remove", c->file, where);
        else
            rc = json_object_set(parent, last->key, value) == 0 ? PM_OK
                                                                 : pm_error_set(PM_ENOMEM, "out of memory");
    } else {
        const size_t len = json_is_array(parent) ? json_array_size(parent) : 0;
        if (!json_is_array(parent))
            rc = pm_error_set(PM_EINPUT, "%s: %s: the parent is not a list", c->file, where);
        else if (remove)
            rc = json_array_remove(parent, last->index) == 0
                     ? PM_OK
                     : pm_error_set(PM_EINPUT, "%s: %s: the list has %zu entries", c->file, where, len);
        else if (last->index < len)
            rc = json_array_set(parent, last->index, value) == 0 ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory");
        else if (last->index == len)
            rc = json_array_append(parent, value) == 0 ? PM_OK : pm_error_set(PM_ENOMEM, "out of memory");
        else
            rc = pm_error_set(PM_EINPUT, "%s: %s: the list has %zu entries (an index equal to that appends)", c->file,
                              where, len);
    }
    json_decref(value);
    if (rc) {
        json_decref(doc);
        return rc;
    }
    return reload(c, doc);
}

int pm_case_set(pm_case *c, const char *path, double value)
{
    if (!isfinite(value))
        return pm_error_set(PM_EINPUT, "%s: %s: got %g; allowed: a finite number", c->file, path, value);
    /* whole numbers as integers: keys such as grid.cells accept only those, and every number key takes them */
    const int whole = value == floor(value) && fabs(value) < 9007199254740992.0;
    return change(c, path, whole ? json_integer((json_int_t)value) : json_real(value), 0);
}

int pm_case_set_string(pm_case *c, const char *path, const char *value)
{
    json_t *v = value ? json_string(value) : NULL;
    if (!v)
        return pm_error_set(PM_EINPUT, "%s: %s: the value is not a UTF-8 string", c->file, path);
    return change(c, path, v, 0);
}

int pm_case_set_json(pm_case *c, const char *path, const char *json)
{
    json_error_t err;
    json_t *v = json ? json_loads(json, JSON_DECODE_ANY | JSON_REJECT_DUPLICATES, &err) : NULL;
    if (!v)
        return pm_error_set(PM_EINPUT, "%s: %s: the value is not JSON (%s)", c->file, path,
                            json ? err.text : "no text");
    return change(c, path, v, 0);
}

int pm_case_remove(pm_case *c, const char *path) { return change(c, path, NULL, 1); }

int pm_case_get(const pm_case *c, const char *path, double *value)
{
    step st[STEP_MAX];
    pm_check(need_doc(c));
    const int n = parse_path(c, path, st);
    if (n < 0)
        return PM_EINPUT;
    const json_t *v = walk(c, c->doc, st, n, 0);
    if (!v)
        return PM_EINPUT;
    if (!json_is_number(v))
        return pm_error_set(PM_EINPUT, "%s: %s: is not a number", c->file, path);
    *value = json_number_value(v);
    return PM_OK;
}

char *pm_case_get_json(const pm_case *c, const char *path)
{
    step st[STEP_MAX];
    if (need_doc(c))
        return NULL;
    const int n = parse_path(c, path, st);
    const json_t *v = n < 0 ? NULL : walk(c, c->doc, st, n, 0);
    if (!v)
        return NULL;
    char *text = json_dumps(v, JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_ENCODE_ANY | JSON_REAL_PRECISION(17));
    if (!text)
        pm_error_set(PM_ENOMEM, "out of memory writing %s as JSON", path);
    return text;
}
