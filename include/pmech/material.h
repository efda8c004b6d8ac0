/**
 * @file material.h
 * @brief Constitutive models behind one interface: every solver asks `update` for the new Cauchy
 *        stress (and the consistent tangent when implicit) and never knows which model it runs.
 *
 * Conventions: stresses are Cauchy, tension positive, in Voigt order (xx, yy, zz, xy, yz, xz).
 * Deformation gradients are 3x3 row-major (F[3*i+j] = dx_i/dX_j). In 2-D, index 2 is the
 * out-of-plane (or hoop) direction. A new model is one file plus one line in material_registry.c.
 */
#ifndef PMECH_MATERIAL_H
#define PMECH_MATERIAL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of model parameters. */
#define PM_MAT_MAX_PARAMS 16
/** Largest number of derived constants a model may cache in pm_material::derived. */
#define PM_MAT_MAX_DERIVED 16
/** Largest number of history variables per point. */
#define PM_MAT_MAX_STATE 16

/** Flags of a parameter's range in pm_param_spec. */
enum {
    PM_PARAM_REQUIRED = 1,  /**< the key must be given */
    PM_PARAM_LO_OPEN = 2,   /**< value must be > lo (else >= lo) */
    PM_PARAM_HI_OPEN = 4,   /**< value must be < hi (else <= hi) */
    PM_PARAM_ANGLE = 8      /**< given in degrees in input; stored in degrees in param[] */
};

/** One model parameter as it appears in a case file. */
typedef struct pm_param_spec {
    const char *key;    /**< JSON key, e.g. "cohesion" */
    double def;         /**< default when absent and not required */
    unsigned flags;     /**< PM_PARAM_* */
    double lo, hi;      /**< allowed range (see flags for open/closed ends) */
    const char *help;   /**< one line for messages and docs */
} pm_param_spec;

typedef struct pm_material pm_material;

/** What a stress update is given. */
typedef struct pm_material_step {
    double F_incr[9];  /**< deformation gradient increment: F_new = F_incr * F_old */
    double F_old[9];   /**< total deformation gradient at the start of the step */
    double F_new[9];   /**< total deformation gradient at the end of the step */
    double dt;         /**< time step (rate-dependent models) */
} pm_material_step;

/** Operations of a constitutive model; one static table per model. */
typedef struct pm_material_ops {
    const char *name;              /**< the `model` value, e.g. "mohr_coulomb" */
    int elastic_pair;              /**< 1: takes youngs_modulus+poisson_ratio or bulk_modulus+shear_modulus */
    size_t n_params;               /**< entries in params */
    const pm_param_spec *params;   /**< model parameters besides density and the elastic pair */
    size_t n_state;                /**< history variables per point (<= PM_MAT_MAX_STATE) */
    /**
     * Check cross-parameter rules (e.g. dilatancy <= friction) and fill m->derived.
     * On failure returns PM_EINPUT with a message that names the offending key (without path;
     * the caller prefixes the key path). May be NULL.
     */
    int (*init)(pm_material *m);
    /**
     * Set history variables for a point whose initial stress is @p stress (may be NULL: zero).
     * May be NULL (state zeroed).
     */
    void (*init_state)(const pm_material *m, const double stress[6], double *state);
    /**
     * Update the Cauchy stress over one step. @p stress holds sigma_n on entry and sigma_{n+1}
     * on return; @p state likewise. When @p tangent is not NULL it receives the 6x6 row-major
     * consistent tangent d(sigma)/d(eps) relating Voigt stress increments to increments of the
     * symmetric strain (engineering shears, gamma = 2 eps) of the current configuration.
     * Returns PM_OK, or PM_ESIM if the update failed (the caller names step and particle).
     */
    int (*update)(const pm_material *m, const pm_material_step *in, double *state,
                  double stress[6], double *tangent);
    /** P-wave speed at the current state for the CFL condition; density is the current one. */
    double (*wave_speed)(const pm_material *m, const double *state, double density);
    /**
     * Viscosity (Pa s) of a stress proportional to the strain rate that a step evaluates from that
     * step's own increment (explicit in time), e.g. a bulk viscosity. NULL: none. The explicit step
     * must resolve it as well as the waves: see pm_material_signal_speed().
     */
    double (*rate_viscosity)(const pm_material *m);
    /**
     * Set the history from the density measured from the points' positions
     * (`analysis.density_update: "positions"`), @p rho_ratio = that density over the material's
     * reference density, before the step's stress update adds the step's own increment. For a model
     * whose stress follows the density (the granular pressure of seed 004 eq. 24), this makes it the
     * density the points actually have around it, not the one their own deformation gradients
     * accumulated. NULL: the model's history does not depend on the density.
     */
    void (*density_state)(const pm_material *m, double rho_ratio, double *state);
    /** Equivalent plastic strain stored in @p state (NULL: model has none, reported as 0). */
    double (*plastic_strain)(const pm_material *m, const double *state);
    /**
     * Stored (elastic) energy per unit reference volume at this state (for energy.csv).
     * NULL: the complementary energy of linear elasticity computed from the stress.
     */
    double (*strain_energy)(const pm_material *m, const pm_material_step *in,
                            const double *state, const double stress[6]);
    /**
     * Strength reduction (strength_reduction.h): divide the strength held in m->param by
     * @p factor > 0 (cohesion c / F, friction tan(phi) / F and what goes with them), leaving
     * m->derived to ops->init, which the caller runs next. NULL: the model has no strength the
     * search reduces, and strength reduction leaves it as it is.
     * Returns PM_OK, or PM_EINTERNAL when the model lacks a parameter it reduces.
     */
    int (*reduce_strength)(pm_material *m, double factor);
} pm_material_ops;

/** A material of a case: its model, name, density, elastic constants and parameters. */
struct pm_material {
    const pm_material_ops *ops;          /**< the model */
    char name[64];                       /**< the case file's `name` */
    double density;                      /**< reference density (kg/m^3) */
    double E, nu, K, G, lambda;          /**< elastic constants (when ops->elastic_pair) */
    double param[PM_MAT_MAX_PARAMS];     /**< in ops->params order, as given (angles in degrees) */
    double derived[PM_MAT_MAX_DERIVED];  /**< the model's cached constants (set by ops->init) */
};

/** @brief The model called @p name, or NULL. */
const pm_material_ops *pm_material_find(const char *name);

/** @brief Names of all models, NULL-terminated (for messages and "did you mean"). */
const char *const *pm_material_names(void);

/**
 * @brief Complete the elastic constants from any valid pair and check them.
 *        Given (E, nu) or (K, G) (pass NAN for the missing pair), sets E, nu, K, G, lambda.
 * @return PM_OK, or PM_EINPUT naming the key (youngs_modulus <= 0, poisson_ratio outside (-1, 0.5), ...)
 */
int pm_material_set_elastic(pm_material *m, double E, double nu, double K, double G);

/**
 * @brief Index of parameter @p key in m->ops->params, or -1.
 */
int pm_material_param_index(const pm_material_ops *ops, const char *key);

/** @brief Value of parameter @p key (the default if the model has it but it was not given; NAN if unknown). */
double pm_material_param(const pm_material *m, const char *key);

/**
 * @brief Default P-wave speed sqrt((K + 4G/3)/rho) from the elastic constants.
 */
double pm_material_elastic_wave_speed(const pm_material *m, const double *state, double density);

/**
 * @brief Speed that bounds the explicit step at a point of cell size @p h: dt = cfl h / (this + |v|).
 *
 * The wave speed (ops->wave_speed, or the elastic one) plus 4 eta / (rho h) for a model with a
 * rate viscosity eta (ops->rate_viscosity). A viscous stress integrated forward in time is stable only
 * for dt <= rho h^2 / (4 eta) on a 2-D grid (the highest nodal mode decays at 8 eta / (rho h^2));
 * central differences with both terms are stable when dt <= 2 / (omega + 2 xi omega), which adding
 * the two speeds guarantees.
 */
double pm_material_signal_speed(const pm_material *m, const double *state, double density, double h);

/**
 * @brief Complementary energy of isotropic linear elasticity, 1/2 sigma : C^-1 : sigma.
 */
double pm_material_elastic_energy(const pm_material *m, const pm_material_step *in,
                                  const double *state, const double stress[6]);

/**
 * @brief Rotate a Voigt stress with the incremental rotation of Hughes & Winget (1980) computed from
 *        F_incr at the mid-step configuration, and return the mid-step strain increment.
 *        Exact for rigid rotations of any size (Cayley transform of the mid-step spin).
 * @param F_incr deformation gradient increment (3x3 row-major)
 * @param stress Voigt stress, rotated in place
 * @param deps receives the symmetric strain increment in Voigt order with engineering shears
 */
void pm_hughes_winget(const double F_incr[9], double stress[6], double deps[6]);

/**
 * @brief Isotropic linear elastic stiffness (6x6 row-major, engineering shears) for K and G.
 */
void pm_elastic_stiffness(double K, double G, double D[36]);

#ifdef __cplusplus
}
#endif
#endif
