/*
 * Strength reduction (Griffiths & Lane 1999): every trial factor is a whole run of the case from its
 * initial state, because the stress path of a plastic body depends on its strength from the first
 * load step on; continuing from the state of another factor would not be the same problem.
 */
#include "pmech/strength_reduction.h"

#include "pmech/error.h"
#include "io/output.h"
#include "io/progress.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The models that say what their strength is (pm_material_ops::reduce_strength). */
static int is_reducible(const pm_material *m)
{
    return m->ops->reduce_strength != NULL;
}

int pm_srf_reduce_material(const pm_material *m, double factor, pm_material *out)
{
    if (out != m)
        *out = *m;
    if (!is_reducible(m))
        return PM_OK;
    if (!(factor > 0) || !isfinite(factor))
        return pm_error_set(PM_EINPUT, "strength reduction factor %g: must be a number > 0", factor);
    pm_check(out->ops->reduce_strength(out, factor));
    if (out->ops->init && out->ops->init(out) != PM_OK)
        return pm_error_prefix(PM_EINPUT, "material \"%s\" reduced by F = %g: ", m->name, factor);
    return PM_OK;
}

/* The materials of one trial; the case copy points at them for the length of the run. */
typedef struct trial_case {
    pm_case c;
    pm_material *mat;
} trial_case;

/* factor > 0: strengths divided by it; factor 0: the reducible materials made linear elastic. */
static int trial_case_make(const pm_case *c, double factor, trial_case *tc)
{
    tc->c = *c;
    tc->c.analysis.strength_reduction.enabled = 0;
    tc->mat = malloc(c->n_materials * sizeof *tc->mat);
    if (!tc->mat)
        return pm_error_set(PM_ENOMEM, "out of memory for the materials of a strength reduction trial");
    tc->c.materials = tc->mat;
    const pm_material_ops *elastic = pm_material_find("linear_elastic");
    for (size_t k = 0; k < c->n_materials; k++) {
        if (factor > 0) {
            pm_check(pm_srf_reduce_material(&c->materials[k], factor, &tc->mat[k]));
            continue;
        }
        tc->mat[k] = c->materials[k];
        if (!is_reducible(&c->materials[k]))
            continue;
        if (!elastic)
            return pm_error_set(PM_EINTERNAL, "the linear_elastic model is not registered");
        tc->mat[k].ops = elastic;
        memset(tc->mat[k].param, 0, sizeof tc->mat[k].param);
        memset(tc->mat[k].derived, 0, sizeof tc->mat[k].derived);
        if (elastic->init)
            pm_check(elastic->init(&tc->mat[k]));
    }
    return PM_OK;
}

int pm_srf_judge(const pm_srf_opts *so, const pm_srf_trial *t, double elastic_displacement)
{
    return so->criterion == PM_SRF_DISPLACEMENT && elastic_displacement > 0 &&
           t->max_displacement > so->displacement_ratio * elastic_displacement;
}

/* Run one trial (factor 0: the elastic reference) into dir (NULL: no files). */
static int run_trial(const pm_case *c, double factor, double elastic_displacement, const pm_run_opts *o,
                     const char *dir, pm_srf_trial *t)
{
    memset(t, 0, sizeof *t);
    t->factor = factor;
    trial_case tc = {.mat = NULL};
    int rc = trial_case_make(c, factor, &tc);
    if (rc) {
        free(tc.mat);
        return rc;
    }
    pm_run_stats st;
    memset(&st, 0, sizeof st);
    pm_run_opts ro = *o;
    ro.out_dir = dir;
    ro.write_output = dir != NULL;
    ro.quiet = 1;
    ro.verbose = 0;
    ro.stats = &st;
    const double w0 = pm_wall_seconds();
    rc = pm_run(&tc.c, &ro, NULL);
    free(tc.mat);
    t->max_displacement = st.max_displacement;
    t->t = st.t;
    t->newton_iterations = st.newton_iterations;
    t->step_cuts = st.step_cuts;
    t->wall_seconds = pm_wall_seconds() - w0;
    if (rc == PM_ESIM) {
        /* the slope could not be brought to rest: this is the answer of the trial, not an error */
        t->failed = 1;
        t->converged = 0;
        pm_error_clear();
        return PM_OK;
    }
    if (rc)
        return pm_error_prefix(rc, "strength reduction, F = %.4f: ", factor);
    t->converged = 1;
    t->failed = pm_srf_judge(&c->analysis.strength_reduction, t, elastic_displacement);
    return PM_OK;
}

int pm_srf_trial_run(const pm_case *c, double factor, double elastic_displacement, const pm_run_opts *o,
                     pm_srf_trial *t)
{
    if (!(factor > 0))
        return pm_error_set(PM_EINPUT, "strength reduction factor %g: must be > 0", factor);
    return run_trial(c, factor, elastic_displacement, o, o->write_output ? o->out_dir : NULL, t);
}

typedef struct search {
    const pm_case *c;
    const pm_run_opts *o;
    const char *dir;   /* output directory, NULL: none */
    FILE *csv;
    pm_srf_result *r;
} search;

static int log_trial(search *sr, const pm_srf_trial *t)
{
    const pm_srf_opts *so = &sr->c->analysis.strength_reduction;
    const double el = sr->r->elastic_displacement;
    if (!sr->o->quiet) {
        char ratio[64] = "";
        if (so->criterion == PM_SRF_DISPLACEMENT && el > 0)
            snprintf(ratio, sizeof ratio, " (%.3g x elastic)", t->max_displacement / el);
        fprintf(stderr, "strength reduction: F = %.4f %s: max displacement %.4g m%s, t = %.4g, %ld Newton "
                "iterations, %ld step cuts, %.1f s\n",
                t->factor, t->failed ? "fails" : "holds", t->max_displacement, ratio, t->t, t->newton_iterations,
                t->step_cuts, t->wall_seconds);
    }
    if (!sr->csv)
        return PM_OK;
    char ratio[32] = "";
    if (el > 0)
        snprintf(ratio, sizeof ratio, "%.6g", t->max_displacement / el);
    fprintf(sr->csv, "%.6f,%s,%s,%.9g,%s,%.9g,%ld,%ld,%.4g\n", t->factor, t->converged ? "yes" : "no",
            t->failed ? "yes" : "no", t->max_displacement, ratio, t->t, t->newton_iterations, t->step_cuts,
            t->wall_seconds);
    return fflush(sr->csv) == 0 ? PM_OK : pm_error_set(PM_EIO, "%s/strength_reduction.csv: write failed", sr->dir);
}

static int try_factor(search *sr, double factor, pm_srf_trial **out)
{
    pm_srf_result *r = sr->r;
    if (r->n_trials >= PM_SRF_MAX_TRIALS)
        return pm_error_set(PM_EINTERNAL, "strength reduction: more than %d trials", PM_SRF_MAX_TRIALS);
    char sub[PM_PATH_MAX + 32];
    if (sr->dir)
        snprintf(sub, sizeof sub, "%s/srf_%.4f", sr->dir, factor);
    pm_srf_trial *t = &r->trial[r->n_trials];
    pm_check(run_trial(sr->c, factor, r->elastic_displacement, sr->o, sr->dir ? sub : NULL, t));
    r->n_trials++;
    *out = t;
    return log_trial(sr, t);
}

static int elastic_reference(search *sr)
{
    pm_srf_trial t;
    char sub[PM_PATH_MAX + 32];
    if (sr->dir)
        snprintf(sub, sizeof sub, "%s/srf_elastic", sr->dir);
    pm_check(run_trial(sr->c, 0.0, 0.0, sr->o, sr->dir ? sub : NULL, &t));
    if (t.failed || !(t.max_displacement > 0))
        return pm_error_set(PM_ESIM,
                            "strength reduction: the elastic reference run (criterion \"displacement\") %s; "
                            "it measures the displacement the ratio is taken against",
                            t.failed ? "did not come to rest" : "did not move");
    sr->r->elastic_displacement = t.max_displacement;
    if (!sr->o->quiet)
        fprintf(stderr, "strength reduction: elastic reference: max displacement %.4g m, %.1f s\n",
                t.max_displacement, t.wall_seconds);
    return PM_OK;
}

static int bisect(search *sr)
{
    const pm_srf_opts *so = &sr->c->analysis.strength_reduction;
    pm_srf_result *r = sr->r;
    pm_srf_trial *t;
    if (so->criterion == PM_SRF_DISPLACEMENT)
        pm_check(elastic_reference(sr));
    pm_check(try_factor(sr, so->min, &t));
    if (t->failed)
        return pm_error_set(PM_ESIM,
                            "strength reduction: the slope fails already at analysis.strength_reduction.min = %g "
                            "(its factor of safety is lower); lower min",
                            so->min);
    pm_check(try_factor(sr, so->max, &t));
    if (!t->failed)
        return pm_error_set(PM_ESIM,
                            "strength reduction: the slope still stands at analysis.strength_reduction.max = %g "
                            "(its factor of safety is higher); raise max",
                            so->max);
    double lo = so->min, hi = so->max;
    while (hi - lo > so->tolerance) {
        const double mid = 0.5 * (lo + hi);
        pm_check(try_factor(sr, mid, &t));
        if (t->failed)
            hi = mid;
        else
            lo = mid;
    }
    r->lo = lo;
    r->hi = hi;
    r->fos = 0.5 * (lo + hi);
    return PM_OK;
}

int pm_strength_reduction(const pm_case *c, const pm_run_opts *o, pm_srf_result *r)
{
    memset(r, 0, sizeof *r);
    if (!c->analysis.strength_reduction.enabled)
        return pm_error_set(PM_EINPUT, "%s: analysis.strength_reduction: not given", c->file);
    search sr = {.c = c, .o = o, .dir = NULL, .csv = NULL, .r = r};
    if (o->write_output) {
        sr.dir = o->out_dir ? o->out_dir : c->output.directory;
        pm_check(pm_mkdir_p(sr.dir));
        char path[PM_PATH_MAX + 32];
        snprintf(path, sizeof path, "%s/strength_reduction.csv", sr.dir);
        sr.csv = fopen(path, "w");
        if (!sr.csv)
            return pm_error_set(PM_EIO, "%s: cannot write", path);
        fprintf(sr.csv, "factor,converged,fails,max_displacement,displacement_ratio,time_reached,newton_iterations,"
                        "step_cuts,seconds\n");
    }
    int rc = bisect(&sr);
    if (sr.csv && fclose(sr.csv) != 0 && !rc)
        rc = pm_error_set(PM_EIO, "%s/strength_reduction.csv: write failed", sr.dir);
    return rc;
}
