/* run.json: what ran, how long it took and what the probes follow. */
#include "io/vtu_write.h"
#include "pmech/error.h"
#include "io/output.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A JSON string; bytes that are not valid UTF-8 (a path in another encoding) become '?'. */
static json_t *str(const char *s)
{
    if (!s)
        s = "";
    json_t *j = json_string(s);
    if (j)
        return j;
    size_t n = strlen(s);
    char *c = malloc(n + 1);
    if (!c)
        return NULL;
    for (size_t i = 0; i < n; i++)
        c[i] = (unsigned char)s[i] < 0x80 ? s[i] : '?';
    c[n] = '\0';
    j = json_string(c);
    free(c);
    return j;
}

/* JSON has no NaN or infinity: those become null. */
static json_t *real(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

static int put(json_t *o, const char *key, json_t *v)
{
    return json_object_set_new(o, key, v) == 0 ? 0 : -1;
}

int pm_run_json_write(const char *path, const pm_run_summary *s, const pm_probe_info *probes,
                      size_t n_probes, size_t frames)
{
    json_t *root = json_object();
    json_t *arr = json_array();
    int bad = !root || !arr;
    if (!bad) {
        bad |= put(root, "version", str(s->version));
        bad |= put(root, "case", str(s->case_file));
        bad |= put(root, "title", str(s->title));
        bad |= put(root, "formulation", str(s->formulation));
        if (s->grid)
            bad |= put(root, "grid", str(s->grid));
        bad |= put(root, "steps", json_integer(s->steps));
        bad |= put(root, "dt_min", real(s->dt_min));
        bad |= put(root, "dt_max", real(s->dt_max));
        bad |= put(root, "end_time", real(s->end_time));
        bad |= put(root, "wall_seconds", real(s->wall_seconds));
        bad |= put(root, "loop_seconds", real(s->loop_seconds));
        bad |= put(root, "particle_steps_per_second", real(s->particle_steps_per_second));
        bad |= put(root, "particles", json_integer((json_int_t)s->particles));
        bad |= put(root, "threads", json_integer(s->threads));
        bad |= put(root, "frames", json_integer((json_int_t)frames));
        bad |= put(root, "exit_status", json_integer(s->exit_status));
        bad |= put(root, "message", str(s->message));
        if (s->interrupted)
            bad |= put(root, "interrupted", str(s->interrupted));
        json_t *w = json_array();
        for (size_t k = 0; w && k < s->n_warnings; k++)
            bad |= json_array_append_new(w, str(s->warnings[k])) != 0;
        bad |= put(root, "warnings", w ? w : json_null());
        if (s->flow) {
            bad |= put(root, "particles_max", json_integer((json_int_t)s->particles_max));
            bad |= put(root, "particles_released", json_integer((json_int_t)s->particles_released));
            bad |= put(root, "particles_removed", json_integer((json_int_t)s->particles_removed));
            bad |= put(root, "mass_released", real(s->mass_released));
            bad |= put(root, "mass_removed", real(s->mass_removed));
        }
        if (s->implicit) {
            bad |= put(root, "newton_iterations", json_integer(s->newton_iterations));
            bad |= put(root, "step_cuts", json_integer(s->step_cuts));
            bad |= put(root, "assemble_seconds", real(s->assemble_seconds));
            bad |= put(root, "solve_seconds", real(s->solve_seconds));
        }
    }
    for (size_t k = 0; !bad && k < n_probes; k++) {
        const pm_probe_info *pi = &probes[k];
        json_t *o = json_object();
        if (!o || json_array_append_new(arr, o) != 0) {
            bad = 1;
            break;
        }
        bad |= put(o, "name", str(pi->name));
        bad |= put(o, "particle", pi->particle >= 0 ? json_integer(pi->particle) : json_null());
        bad |= put(o, "body", pi->body ? str(pi->body) : json_null());
        bad |= put(o, "quantity", str(pi->quantity));
        bad |= put(o, "initial_position",
                   json_pack("[oo]", real(pi->initial_position[0]), real(pi->initial_position[1])));
    }
    if (!bad) {
        bad = json_object_set_new(root, "probes", arr) != 0;
        arr = NULL;
    }
    char *text = bad ? NULL : json_dumps(root, JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17));
    json_decref(arr);
    json_decref(root);
    if (!text)
        return pm_error_set(PM_ENOMEM, "cannot write '%s': out of memory building JSON", path);
    size_t len = strlen(text);
    /* end with a newline like every other text file */
    char *t2 = realloc(text, len + 2);
    if (!t2) {
        free(text);
        return pm_error_set(PM_ENOMEM, "cannot write '%s': out of memory building JSON", path);
    }
    t2[len] = '\n';
    t2[len + 1] = '\0';
    int rc = pm_write_file_atomic(path, t2, len + 1);
    free(t2);
    return rc;
}
