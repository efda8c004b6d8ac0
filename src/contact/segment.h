/*
 * The point of a straight segment nearest to a given point: the one projection that the signed distances
 * to polylines, polygons and Gmsh walls (geometry.c) and the positions along them of the traction
 * profile (profile.c) both build on, so that a node's foot on a wall is the same point for both.
 */
#ifndef PMECH_CONTACT_SEGMENT_H
#define PMECH_CONTACT_SEGMENT_H

#include "pmech/particles.h"

#include <math.h>

/**
 * The point of segment a -> b nearest to @p x (a and b distinct): @return its parameter u in [0, 1] along
 * the segment, the point itself a + u (b - a) in @p q and its distance |x - q| in @p dist.
 */
static inline double pm_segment_nearest(const double a[PM_DIM], const double b[PM_DIM], const double x[PM_DIM],
                                        double q[PM_DIM], double *dist)
{
    double e[PM_DIM], r[PM_DIM], w[PM_DIM];
    for (int d = 0; d < PM_DIM; d++) {
        e[d] = b[d] - a[d];
        r[d] = x[d] - a[d];
    }
    double L2 = e[0] * e[0], re = r[0] * e[0];
    for (int d = 1; d < PM_DIM; d++) {
        L2 += e[d] * e[d];
        re += r[d] * e[d];
    }
    double u = re / L2;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    for (int d = 0; d < PM_DIM; d++) {
        q[d] = a[d] + u * e[d];
        w[d] = x[d] - q[d];
    }
    double w2 = w[0] * w[0];
    for (int d = 1; d < PM_DIM; d++)
        w2 += w[d] * w[d];
    *dist = sqrt(w2);
    return u;
}

#endif
