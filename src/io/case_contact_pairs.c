/* contact_pairs: the laws between contact groups of bodies and sources where they meet on the grid. */
#include "io/case_internal.h"

#include "io/json_read.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const law_names[] = {"no_slip", "frictionless", "coulomb", NULL};
static const char *const separation_names[] = {"extent", "none", NULL};

/* Whether some body or source is in contact group @p name. */
static int group_exists(const pm_case *c, const char *name)
{
    for (size_t b = 0; b < c->n_bodies; b++)
        if (!strcmp(c->bodies[b].contact_group, name))
            return 1;
    for (size_t k = 0; k < c->n_sources; k++)
        if (!strcmp(c->sources[k].body.contact_group, name))
            return 1;
    return 0;
}

/* The message for a name no body or source carries: the groups there are. */
static int unknown_group(const pm_case *c, const char *path, const char *name)
{
    char list[1024] = "";
    size_t used = 0;
    const size_t n = c->n_bodies + c->n_sources;
    for (size_t j = 0; j < n && used + 70 < sizeof list; j++) {
        const pm_case_body *b = j < c->n_bodies ? &c->bodies[j] : &c->sources[j - c->n_bodies].body;
        int seen = 0;
        for (size_t i = 0; i < j && !seen; i++) {
            const pm_case_body *a = i < c->n_bodies ? &c->bodies[i] : &c->sources[i - c->n_bodies].body;
            seen = !strcmp(a->contact_group, b->contact_group);
        }
        if (!seen)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", used ? ", " : "", b->contact_group);
    }
    return pm_error_set(PM_EINPUT,
                        "%s: %s: no body or source is named or grouped \"%s\" (contact groups: %s; a body's group "
                        "is its contact_group, or its name)",
                        c->file, path, name, list);
}

static int parse_pair_groups(pm_case *c, const char *path, json_t *p, pm_case_contact_pair *pair)
{
    char bp[96];
    jr_join(bp, sizeof bp, path, "bodies");
    json_t *b = json_object_get(p, "bodies");
    if (!b)
        return pm_case_fail(c->file, bp, "required key is missing", NULL);
    if (!json_is_array(b) || json_array_size(b) != 2)
        return pm_error_set(PM_EINPUT, "%s: %s: expected a list of two contact group names, got %s", c->file, bp,
                            jr_text(b));
    for (size_t j = 0; j < 2; j++) {
        json_t *g = json_array_get(b, j);
        char gp[112];
        jr_index(gp, sizeof gp, bp, j);
        if (!json_is_string(g))
            return pm_error_set(PM_EINPUT, "%s: %s: expected a name, got %s", c->file, gp, jr_text(g));
        const char *name = json_string_value(g);
        if (strlen(name) >= sizeof pair->group[j])
            return pm_error_set(PM_EINPUT, "%s: %s: the name \"%s\" is too long (at most %zu characters)", c->file,
                                gp, name, sizeof pair->group[j] - 1);
        if (!group_exists(c, name))
            return unknown_group(c, gp, name);
        snprintf(pair->group[j], sizeof pair->group[j], "%s", name);
    }
    if (!strcmp(pair->group[0], pair->group[1]))
        return pm_error_set(PM_EINPUT,
                            "%s: %s: both entries are \"%s\"; a pair names two different contact groups (the bodies "
                            "of one group share one field and always move together)",
                            c->file, bp, pair->group[0]);
    return PM_OK;
}

static int parse_pair(pm_case *c, const char *path, json_t *p, pm_case_contact_pair *pair)
{
    jr_ctx cx = {c->file, path};
    if (!json_is_object(p))
        return pm_error_set(PM_EINPUT, "%s: %s: expected an object, got %s", c->file, path, jr_type(p));
    pm_check(jr_only_keys(&cx, p, pm_case_keys(PM_KEYS_CONTACT_PAIR)));
    pm_check(parse_pair_groups(c, path, p, pair));
    int law;
    pm_check(jr_enum(&cx, p, "law", JR_REQUIRED, law_names, 0, &law));
    pair->law = (pm_pair_law)law;
    if (pair->law == PM_PAIR_COULOMB) {
        pm_check(jr_number(&cx, p, "friction", JR_REQUIRED, 0, &pair->friction));
        pm_check(jr_range(&cx, "friction", pair->friction, 0, 0, INFINITY, 1));
    } else if (json_object_get(p, "friction")) {
        char fp[96];
        jr_join(fp, sizeof fp, path, "friction");
        return pm_error_set(PM_EINPUT, "%s: %s: a friction coefficient goes with law \"coulomb\", not \"%s\"", c->file,
                            fp, law_names[law]);
    }
    int sep;
    pm_check(jr_enum(&cx, p, "separation", 0, separation_names, 0, &sep));
    pair->extent_check = sep == 0;
    return PM_OK;
}

/* Body-body contact needs one grid field per group and explicit steps that act on each field. */
static int check_analysis(const pm_case *c)
{
    if (c->method != PM_METHOD_MPM)
        return pm_error_set(PM_EINPUT,
                            "%s: contact_pairs: body-body contact works on the background grid of method 'mpm' (GMM "
                            "and RKPM nodes move with one material); remove contact_pairs or use method 'mpm'",
                            c->file);
    if (c->analysis.type != PM_ANALYSIS_EXPLICIT)
        return pm_error_set(PM_EINPUT,
                            "%s: contact_pairs: body-body contact needs analysis.type 'explicit' (the implicit and "
                            "quasi-static solvers assemble one field and have no contact terms between fields); "
                            "remove contact_pairs or use analysis.type 'explicit'",
                            c->file);
    if (c->analysis.fbar != PM_FBAR_NONE)
        return pm_error_set(PM_EINPUT,
                            "%s: contact_pairs: analysis.fbar averages volume changes over whole cells, across the "
                            "bodies that meet in them; use analysis.fbar 'none' with contact_pairs",
                            c->file);
    return PM_OK;
}

int pm_case_parse_contact_pairs(pm_case *c, json_t *cp)
{
    if (!cp)
        return PM_OK;
    if (!json_is_array(cp))
        return pm_error_set(PM_EINPUT, "%s: contact_pairs: expected a list of pairs, got %s", c->file, jr_type(cp));
    const size_t n = json_array_size(cp);
    if (n == 0)
        return PM_OK;
    pm_check(check_analysis(c));
    c->contact_pairs = calloc(n, sizeof *c->contact_pairs);
    if (!c->contact_pairs)
        return pm_error_set(PM_ENOMEM, "out of memory");
    c->n_contact_pairs = n;
    for (size_t i = 0; i < n; i++) {
        char path[64];
        jr_index(path, sizeof path, "contact_pairs", i);
        pm_case_contact_pair *pair = &c->contact_pairs[i];
        pm_check(parse_pair(c, path, json_array_get(cp, i), pair));
        for (size_t j = 0; j < i; j++) {
            const pm_case_contact_pair *q = &c->contact_pairs[j];
            if ((!strcmp(q->group[0], pair->group[0]) && !strcmp(q->group[1], pair->group[1])) ||
                (!strcmp(q->group[0], pair->group[1]) && !strcmp(q->group[1], pair->group[0])))
                return pm_error_set(PM_EINPUT, "%s: %s.bodies: the pair \"%s\", \"%s\" is already contact_pairs[%zu]",
                                    c->file, path, pair->group[0], pair->group[1], j);
        }
    }
    return PM_OK;
}
