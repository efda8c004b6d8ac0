/**
 * @file plot.h
 * @brief A tiny line-plot helper (cairo, PNG): axes with 1-2-5 ticks, tick labels, axis labels,
 *        title and legend via cairo's toy text API. For README figures and quick checks; not a
 *        plotting library.
 */
#ifndef PMECH_IO_PLOT_H
#define PMECH_IO_PLOT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** One curve. */
typedef struct pm_plot_series {
    const double *x;     /**< n abscissae */
    const double *y;     /**< n ordinates */
    size_t n;            /**< number of points (>= 1) */
    const char *label;   /**< legend text (NULL or "": not in the legend) */
    double rgb[3];       /**< colour, components in [0, 1]; all zero: automatic palette */
    int dashed;          /**< 1: dashed line (e.g. a reference value) */
    int markers;         /**< 1: draw a small circle at each point */
} pm_plot_series;

/** Figure options; zeroed fields take defaults. */
typedef struct pm_plot_opts {
    const char *title;   /**< above the plot (NULL: none) */
    const char *xlabel;  /**< below the x axis */
    const char *ylabel;  /**< left of the y axis, rotated */
    int width, height;   /**< pixels (default 800 x 560) */
    int y_from_zero;     /**< 1: the y range includes 0 */
    int legend;          /**< legend corner: 0 top left, 1 top right, 2 bottom right, 3 bottom left */
} pm_plot_opts;

/**
 * @brief Draw the series as lines into a PNG file.
 * @param png output file name
 * @param s the series
 * @param ns number of series (>= 1)
 * @param o options (may be NULL)
 * @return PM_OK, PM_EINPUT (no finite point), or PM_EIO (cairo could not write the file)
 */
int pm_plot_lines(const char *png, const pm_plot_series *s, size_t ns, const pm_plot_opts *o);

/**
 * @brief Plot columns of a CSV file with a header line (e.g. the output of `pmech material`).
 * @param csv file to read
 * @param xcol name of the x column
 * @param xscale factor applied to x (e.g. -1 to plot compression positive, 100 for percent)
 * @param ycols names of the y columns
 * @param yscale factor applied to every y column
 * @param ny number of y columns (1..8)
 * @param png output file name
 * @param o options (may be NULL; series are labelled with the column names)
 * @return PM_OK, PM_EIO (file unreadable), PM_EINPUT (column missing, no data), PM_ENOMEM
 */
int pm_plot_csv(const char *csv, const char *xcol, double xscale, const char *const *ycols,
                double yscale, size_t ny, const char *png, const pm_plot_opts *o);

/**
 * @brief Tick spacing 1, 2 or 5 times a power of ten giving about @p n intervals over [lo, hi].
 * @return the spacing (> 0 for hi > lo)
 */
double pm_plot_nice_step(double lo, double hi, int n);

/**
 * @brief A tick label: as many decimals as the spacing @p step needs, %g form for very large or small values.
 * @param v the tick value
 * @param step the spacing of the ticks
 * @param buf receives the text
 * @param n size of @p buf
 */
void pm_plot_format_tick(double v, double step, char *buf, size_t n);

#ifdef __cplusplus
}
#endif
#endif
