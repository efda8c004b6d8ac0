/**
 * @file render.h
 * @brief PNG pictures of the particles (cairo), coloured by a field: axes in metres with ticks, a colour
 *        bar with the field's name and unit, the time in the title, each particle drawn as its deformed
 *        area. `output.pictures` draws one per frame during a run, with one colour range for the whole
 *        run; pm_render_dir() (`pmech render`) redraws any field from the frames a run wrote, and can
 *        make an animation of them.
 */
#ifndef PMECH_RENDER_H
#define PMECH_RENDER_H

#include <stddef.h>

#include "pmech/frame.h"
#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Fields a picture can be coloured by (names: pm_field_names()). */
typedef enum {
    PM_FIELD_BODY = 0,              /**< one colour per body */
    PM_FIELD_SPEED = 1,             /**< |v|, m/s */
    PM_FIELD_PRESSURE = 2,          /**< p = -(sxx + syy + szz) / 3, Pa, compression positive */
    PM_FIELD_PLASTIC_STRAIN = 3,    /**< equivalent plastic strain */
    PM_FIELD_SYY = 4,               /**< vertical (axial) stress, Pa, tension positive */
    PM_FIELD_DISPLACEMENT = 5,      /**< |x - x0|, m */
    PM_FIELD_Q = 6,                 /**< von Mises equivalent stress q = sqrt(3 J2), Pa */
    PM_FIELD_VOLUMETRIC_STRAIN = 7, /**< ln(det F), logarithmic */
    PM_FIELD_DEVIATORIC_STRAIN = 8, /**< equivalent deviatoric logarithmic strain */
    PM_FIELD_SXX = 9,               /**< horizontal (radial) stress, Pa */
    PM_FIELD_SZZ = 10,              /**< out-of-plane (hoop) stress, Pa */
    PM_FIELD_SXY = 11,              /**< shear stress, Pa */
    PM_FIELD_MATERIAL = 12,         /**< one colour per material */
    PM_FIELD_GRID_SPEED = 13        /**< |v_grid|, m/s: the speed each point's position moved with over the last
                                         step, without the FLIP velocity the grid never carried */
} pm_field;

/**
 * @brief Parse a field name ("body", "speed", "pressure", "plastic_strain", "syy", "displacement", "q",
 *        "volumetric_strain", "deviatoric_strain", "sxx", "szz", "sxy", "material", "grid_speed").
 * @return the field, or -1 for an unknown name
 */
int pm_field_from_name(const char *name);

/** @brief Name of a field. */
const char *pm_field_name(pm_field f);

/** @brief The SI unit of a field ("Pa", "m/s", "m"; "-" for strains; "" for categories). */
const char *pm_field_unit(pm_field f);

/** @brief Every field name, NULL-terminated (for messages and the case loader). */
const char *const *pm_field_names(void);

/** How a picture is drawn; a zeroed struct gives the defaults. */
typedef struct pm_render_opts {
    int width;            /**< pixels (0: 800; at least 200) */
    const double *range;  /**< colour range [lo, hi] (NULL: the values' own smallest and largest) */
    const char *title;    /**< start of the title (NULL: none) */
    int show_time;        /**< 1: the title ends with "t = <time> s" */
    double time;          /**< the time shown */
    int axisymmetric;     /**< name the axes r and z */
} pm_render_opts;

/**
 * @brief Draw particles coloured by a field and write a PNG atomically.
 * @param png file to write
 * @param g grid whose bounding box is the region shown
 * @param p particles
 * @param field the colouring
 * @param o options (NULL: defaults)
 * @return PM_OK, PM_EINPUT (bad width or range), PM_ENOMEM, or PM_EIO naming the path
 */
int pm_render_field(const char *png, const pm_grid *g, const pm_particles *p, pm_field field,
                    const pm_render_opts *o);

/**
 * @brief The smallest and largest finite value of a field over the particles.
 * @return PM_OK, or PM_EINPUT when no value is finite (or the field is a category)
 */
int pm_field_range(const pm_particles *p, pm_field field, double range[2]);

/**
 * @brief Draw particles as pm_render_field() does (kept for programs written against the first picture
 *        API): default options, the given width and title.
 */
int pm_render_particles(const char *path, const pm_grid *g, const pm_particles *p, pm_field field, int width,
                        const char *title);

/**
 * @brief The values of a field in a frame read back: a field of pm_field_names(), any scalar array of the
 *        frame ("mass"), a vector array's magnitude ("velocity"), or one component as "ARRAY.C" with C
 *        one of x, y, z for vectors and the component names of tensors ("stress.xy").
 * @param f the frame
 * @param field the name
 * @param out receives one value per point (pm_frame_n_points())
 * @param unit if not NULL, receives the field's unit ("" when not known)
 * @param category if not NULL, receives 1 for a field drawn by category (body, material)
 * @return PM_OK, or PM_EINPUT naming the field and listing the frame's arrays
 */
int pm_frame_field(const pm_frame *f, const char *field, double *out, const char **unit, int *category);

/**
 * @brief Draw a frame read back, coloured by a field (see pm_frame_field()).
 * @param png file to write
 * @param f the frame (its particles' deformation_gradient and half_size give their drawn areas)
 * @param lo lower-left corner of the region shown
 * @param hi upper-right corner
 * @param field the field's name
 * @param o options; without a range, the frame's own smallest and largest value
 * @return PM_OK, PM_EINPUT, PM_ENOMEM, PM_EIO
 */
int pm_render_frame(const char *png, const pm_frame *f, const double lo[2], const double hi[2], const char *field,
                    const pm_render_opts *o);

/** What pm_render_dir() draws. */
typedef struct pm_render_dir_opts {
    const char *field;     /**< field name (see pm_frame_field()) */
    int width;             /**< pixels (0: 800) */
    const double *range;   /**< fixed colour range (NULL: one range over all frames) */
    const char *out_dir;   /**< where the pictures go (NULL: the run's directory) */
    const char *animation; /**< if not NULL, an animation file to make of the pictures: .gif or .mp4 (ffmpeg) */
    double fps;            /**< animation frames per second (0: 10) */
    int quiet;             /**< 1: no line per picture on stderr */
} pm_render_dir_opts;

/**
 * @brief Redraw every frame of a run directory (its particles.pvd) coloured by a field, as
 *        <out_dir>/<field>_NNNNNN.png, with one colour range for all of them, and optionally make an
 *        animation. The region shown is the bounding box of the run's grid.vtu (of the particles when
 *        there is none); run.json gives the title and whether the run was axisymmetric.
 * @param dir the run's output directory
 * @param o options
 * @param n_written if not NULL, receives the number of pictures written
 * @return PM_OK; PM_EINPUT (unknown field, no frames, bad options); PM_EIO (cannot read or write, ffmpeg
 *         missing or failing)
 */
int pm_render_dir(const char *dir, const pm_render_dir_opts *o, size_t *n_written);

#ifdef __cplusplus
}
#endif
#endif
