/**
 * @file render.h
 * @brief PNG pictures of the particles (cairo), coloured by a field, for users who would rather
 *        look than read: `output.pictures` writes one per frame.
 */
#ifndef PMECH_RENDER_H
#define PMECH_RENDER_H

#include "pmech/grid.h"
#include "pmech/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Fields a picture can be coloured by. */
typedef enum {
    PM_FIELD_BODY = 0,           /**< one colour per body */
    PM_FIELD_SPEED = 1,          /**< |v| */
    PM_FIELD_PRESSURE = 2,       /**< p = -(sxx + syy + szz) / 3 */
    PM_FIELD_PLASTIC_STRAIN = 3, /**< equivalent plastic strain */
    PM_FIELD_SYY = 4,            /**< vertical stress */
    PM_FIELD_DISPLACEMENT = 5    /**< |x - x0| */
} pm_field;

/**
 * @brief Parse a field name ("body", "speed", "pressure", "plastic_strain", "syy", "displacement").
 * @return the field, or -1 for an unknown name
 */
int pm_field_from_name(const char *name);

/** @brief Name of a field. */
const char *pm_field_name(pm_field f);

/**
 * @brief Draw the particles over the grid outline and write a PNG atomically.
 * @param path PNG file to write
 * @param g grid (its bounding box frames the picture)
 * @param p particles
 * @param field colouring
 * @param width picture width in pixels (height follows the grid's aspect, at most 2 * width)
 * @param title text drawn at the top left (may be NULL)
 * @return PM_OK, or PM_EIO naming the path
 */
int pm_render_particles(const char *path, const pm_grid *g, const pm_particles *p, pm_field field, int width,
                        const char *title);

#ifdef __cplusplus
}
#endif
#endif
