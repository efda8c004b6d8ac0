/**
 * @file particles.h
 * @brief Material points stored as structure-of-arrays, sized once before the time loop.
 *
 * 2-D layout: vectors are interleaved pairs (x[2*i], x[2*i+1]); the deformation gradient has
 * five entries per point (xx, xy, yx, yy, zz) and the Cauchy stress four (xx, yy, zz, xy),
 * tension positive. zz is the out-of-plane (plane strain/stress) or hoop (axisymmetric) entry.
 */
#ifndef PMECH_PARTICLES_H
#define PMECH_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Spatial dimension of the build: the stride of every vector array (x[PM_DIM * i + d]). */
#ifndef PM_DIM
#define PM_DIM 2
#endif
/** Entries of the deformation gradient per particle: the in-plane PM_DIM x PM_DIM block, plus the
 *  out-of-plane (or hoop) stretch in 2-D. */
#define PM_NF (PM_DIM * PM_DIM + (PM_DIM == 2))
/** Entries of the stress per particle: xx, yy, zz, xy in 2-D (zz out of plane); the six of a
 *  symmetric tensor in 3-D. */
#define PM_NS (PM_DIM == 2 ? 4 : 6)

/** Index of each entry of F in the per-particle block of pm_particles::F. */
enum { PM_FXX = 0, PM_FXY = 1, PM_FYX = 2, PM_FYY = 3, PM_FZZ = 4 };
/** Index of each entry of the stress in the per-particle block of pm_particles::stress. */
enum { PM_SXX = 0, PM_SYY = 1, PM_SZZ = 2, PM_SXY = 3 };

/** The material points of a simulation. All arrays have room for cap entries (times their width);
 *  the first n are the particles. Sources append particles up to cap, sinks remove them. */
typedef struct pm_particles {
    size_t n;          /**< number of particles */
    size_t cap;        /**< room allocated, >= n: particles a run may hold at once */
    size_t n_state;    /**< history variables per particle (max over the materials) */
    double *x;         /**< current position, 2 per particle */
    double *x0;        /**< initial position, 2 per particle (displacement = x - x0) */
    double *v;         /**< velocity, 2 per particle */
    double *a;         /**< acceleration, 2 per particle (predictor-corrector schemes) */
    double *v_grid;    /**< the velocity the position moved with over the last step, PM_DIM per particle: the
                            grid's velocity interpolated at the point (explicit), the step's displacement over
                            dt (implicit). Output only; unlike v it carries no FLIP velocity the grid never saw */
    double *mass;      /**< mass (per radian in axisymmetric runs) */
    double *vol;       /**< current volume */
    double *vol0;      /**< initial volume */
    double *F;         /**< deformation gradient, PM_NF per particle */
    double *stress;    /**< Cauchy stress, PM_NS per particle, tension positive */
    double *eps_p;     /**< equivalent plastic strain */
    double *state;     /**< material history, n_state per particle */
    double *hsize;     /**< initial half-size of the particle's domain (x, y), 2 per particle */
    size_t n_affine;   /**< entries of C per particle: PM_DIM x PM_DIM with APIC, 0 otherwise */
    double *C;         /**< APIC's affine velocity matrix (row-major velocity gradient of the last grid-to-particle
                            transfer), n_affine per particle: allocated by pm_particles_enable_affine() only */
    int32_t *material; /**< index into the case's material list */
    int32_t *body;     /**< index into the case's body list */
    int32_t *cell;     /**< background cell containing the particle (-1 = outside) */
    int32_t *id;       /**< identity that survives sorting, appends and removals: unique in a run */
} pm_particles;

/**
 * @brief Allocate arrays for @p n particles with @p n_state history variables each, zeroed; the ids
 *        are 0..n-1. The capacity is n.
 * @param p the struct to fill (its previous content is ignored)
 * @param n particle count
 * @param n_state history variables per particle
 * @return PM_OK, or PM_ENOMEM with a message giving the bytes requested
 */
int pm_particles_alloc(pm_particles *p, size_t n, size_t n_state);

/**
 * @brief As pm_particles_alloc(), with room for @p cap particles (cap >= n), so that particles can be
 *        appended later without allocating.
 * @return PM_OK, or PM_ENOMEM with a message giving the bytes requested
 */
int pm_particles_alloc_capacity(pm_particles *p, size_t n, size_t cap, size_t n_state);

/**
 * @brief Give every particle (all cap of them) APIC's affine matrix C, zeroed; n_affine becomes
 *        PM_DIM x PM_DIM. Without this call C holds no particle's entries (n_affine 0). Does nothing
 *        when it already has them.
 * @return PM_OK, or PM_ENOMEM with a message giving the bytes requested
 */
int pm_particles_enable_affine(pm_particles *p);

/**
 * @brief Copy @p count particles, every field, from @p src (from index @p from) into @p dst (at index
 *        @p at). Both must have the same n_state; where @p src has no affine matrices and @p dst has,
 *        the copies' are zeroed. The ranges must lie within their capacities. n of
 *        neither changes: the caller appends by raising dst->n.
 */
void pm_particles_copy(pm_particles *dst, size_t at, const pm_particles *src, size_t from, size_t count);

/**
 * @brief Remove the particles whose @p drop entry is non-zero, keeping the others in their order.
 * @param p particles
 * @param drop one flag per particle (n entries)
 * @return the number removed; p->n is lowered by it
 */
size_t pm_particles_remove(pm_particles *p, const uint8_t *drop);

/** @brief Free every array and zero the struct. Safe on a zeroed struct. */
void pm_particles_free(pm_particles *p);

/** @brief Bytes of memory one particle takes with @p n_state history variables, without APIC's affine
 *         matrix (pm_particles_enable_affine() adds PM_DIM x PM_DIM doubles). */
size_t pm_particles_bytes_per_particle(size_t n_state);

/**
 * @brief Reorder all particle arrays by @p perm (new index i takes old index perm[i]).
 * @param p particles
 * @param perm permutation of 0..n-1
 * @param scratch workspace of at least n doubles
 * @param iscratch workspace of at least n int32_t
 * @return PM_OK
 */
int pm_particles_permute(pm_particles *p, const uint32_t *perm, double *scratch, int32_t *iscratch);

/** One particle array as the field table describes it, for files that store every field. */
typedef struct pm_particle_field {
    const char *name; /**< the pm_particles member's name ("x", "F", "state", ...) */
    void *data;       /**< its array: width entries per particle, cap particles */
    size_t elem;      /**< bytes of one entry (8: double, 4: int32_t) */
    size_t width;     /**< entries per particle (n_state for "state") */
    int is_int;       /**< 1: int32_t entries, 0: double */
} pm_particle_field;

/** @brief Number of particle arrays (every field a particle has). */
size_t pm_particles_field_count(void);

/** @brief Describe array @p k (0 <= k < pm_particles_field_count()) of @p p into @p f. */
void pm_particles_field_get(const pm_particles *p, size_t k, pm_particle_field *f);

#ifdef __cplusplus
}
#endif
#endif
