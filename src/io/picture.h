/**
 * @file picture.h (internal to src/, not installed)
 * @brief One particle picture drawn with cairo: the particles as their deformed areas, coloured by a
 *        field over a fixed range, axes in metres with ticks, a colour bar with the field's name and
 *        unit, a title with the time. The layout is measured with cairo's text extents so that no
 *        label is cut, whatever the domain's aspect.
 */
#ifndef PMECH_IO_PICTURE_H
#define PMECH_IO_PICTURE_H

#include <stddef.h>

/** What to draw. Point arrays are read with their stride; the picture owns none of them. */
typedef struct pm_picture {
    size_t n;               /**< points */
    const double *x;        /**< centres, x_stride per point (x, y first) */
    int x_stride;           /**< PM_DIM for particles, 3 for frames read back */
    const double *F;        /**< deformation gradient, PM_NF per point (xx, xy, yx, yy, zz), or NULL: undeformed */
    const double *hsize;    /**< initial half-size, PM_DIM per point */
    const double *value;    /**< field value per point (NaN: drawn grey), or NULL for categories */
    const double *category; /**< body (or material) per point, drawn from a palette when value is NULL */
    double lo[2], hi[2];    /**< the model region shown (the grid's bounding box), metres */
    double range[2];        /**< colour range of value (lo < hi) */
    const char *title;      /**< first part of the title (NULL: none) */
    double time;            /**< shown as "t = ... s" in the title (NaN: not shown) */
    const char *field;      /**< the field's name, under the colour bar */
    const char *unit;       /**< its SI unit ("Pa", "m/s", "m"; "" or NULL: dimensionless) */
    int axisymmetric;       /**< axes named r and z instead of x and y */
    int width;              /**< picture width in pixels (>= 200) */
} pm_picture;

/** Where things land in a picture (pixels; y down). */
typedef struct pm_picture_layout {
    int width, height;        /**< the image */
    double font;              /**< font size of labels */
    double plot_x, plot_y;    /**< top-left corner of the model region */
    double scale;             /**< pixels per metre (the same along x and y) */
    double plot_w, plot_h;    /**< size of the model region */
    double bar_x, bar_y;      /**< top-left corner of the colour bar (no bar for categories) */
    double bar_w, bar_h;      /**< its size */
    int has_bar;              /**< 1 unless coloured by category */
} pm_picture_layout;

/**
 * @brief Compute the layout of a picture without drawing it.
 * @return PM_OK, or PM_EINPUT for a region without area or a width below 200
 */
int pm_picture_layout_of(const pm_picture *pic, pm_picture_layout *lay);

/**
 * @brief Draw the picture and write it as PNG atomically (temporary name, then rename).
 * @return PM_OK, PM_EINPUT (see pm_picture_layout_of), PM_EIO naming @p png
 */
int pm_picture_write(const char *png, const pm_picture *pic);

/** @brief The viridis-like colour ramp of pictures, t in [0, 1] (clamped). */
void pm_picture_ramp(double t, double rgb[3]);

/** @brief The colour of category @p k (bodies). */
void pm_picture_category_colour(int k, double rgb[3]);

/**
 * @brief How a value of @p unit over a range up to @p max_abs is shown: a factor and a unit with an SI
 *        prefix for stresses ("Pa" -> "kPa" with factor 1e-3 above 1e3 Pa, "MPa" above 1e6 Pa, "GPa").
 * @param shown receives the unit shown (at least 8 bytes)
 * @return the factor the values are multiplied by
 */
double pm_picture_unit_scale(const char *unit, double max_abs, char *shown, size_t cap);

#endif
