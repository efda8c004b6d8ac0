/*
 * A block sliding down a slope that is the boundary of a Gmsh mesh, not aligned with the axes: the
 * mesh (cases/gmsh_incline<deg>.msh, from cases/make_gmsh_incline.py) is a strip of triangles above a
 * straight line at 25 or 35 degrees whose line elements are the 1-D physical group "slope", written
 * half of them backwards; a `friction` condition on that group (mu = 0.3) takes its normals from the
 * edges (away from the triangles that own them) and its gaps from the material's surface. Rigid-body
 * answer while it slides: the mean velocity along the slope g (sin(theta) - mu cos(theta)) t, compared
 * within 2 % at 0.2 s as for the rigid polyline (verify_incline): a wall whose normal were the mesh's
 * edge turned the wrong way, or held a cell early, or frictionless, is off by far more (at 35 degrees
 * frictionless is +76 %). At 10 degrees, below the friction angle (16.7 degrees), it must stay put: its
 * travel along the slope below 1 % of the frictionless g sin(theta) t^2 / 2. The slope's own force
 * (the laws' impulses summed over its nodes, mean over the second half, as forces.csv writes it)
 * against the statics of the rigid block within 2 % as in verify_incline: normal W cos(theta),
 * tangential mu W cos(theta) while sliding and W sin(theta) while stuck.
 */
#include "verify_util.h"

#include "contact/contact.h"
#include "pmech/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double G = 9.81, MU = 0.3, T_END = 0.2;
/* weight of the 0.2 m x 0.06 m block of density 1000 per unit thickness */
static const double W = 1000 * 0.2 * 0.06 * 9.81;
static const char *dir = ".";

/* Run to T_END: the mean velocity along the slope, the travel of the centre of mass along it, and the
 * slope's mean normal and tangential force on the block over the second half. */
static vu_slope run(int deg)
{
    pm_case c;
    vu_gmsh_incline_case(dir, deg, NULL, T_END, G, MU, &c);
    char label[32];
    snprintf(label, sizeof label, "%d deg", deg);
    const vu_slope r = vu_slope_run(&c, deg, PM_CONTACT_EDGES, label);
    pm_case_free(&c);
    return r;
}

int main(int argc, char **argv)
{
    vu_init(argc, argv);
    if (argc > 1)
        dir = argv[1];
    int ok = 1;
    const int slides[] = {25, 35};
    for (size_t k = 0; k < sizeof slides / sizeof slides[0]; k++) {
        const double th = slides[k] * M_PI / 180.0, ref = G * (sin(th) - MU * cos(th)) * T_END;
        const vu_slope r = run(slides[k]);
        const double v = r.v_along, *f = r.force, secs = r.secs;
        ok &= r.ok;
        char q[112];
        snprintf(q, sizeof q, "%d deg Gmsh slope, mu 0.3: velocity along the slope at 0.2 s (m/s)", slides[k]);
        ok &= vu_report("gmsh_incline", q, v, ref, (v - ref) / ref, 0.02, secs);
        const double fn = W * cos(th);
        snprintf(q, sizeof q, "%d deg: slope's normal force (N/m), mean over 0.1-0.2 s", slides[k]);
        ok &= vu_report("gmsh_incline", q, f[0], fn, (f[0] - fn) / fn, 0.02, secs);
        snprintf(q, sizeof q, "%d deg: slope's friction force (N/m), mean over 0.1-0.2 s", slides[k]);
        ok &= vu_report("gmsh_incline", q, f[1], MU * fn, (f[1] - MU * fn) / (MU * fn), 0.02, secs);
    }
    const double th = 10.0 * M_PI / 180.0, free_dist = 0.5 * G * sin(th) * T_END * T_END;
    const vu_slope r = run(10);
    const double u = r.travel, *f = r.force, secs = r.secs;
    ok &= r.ok;
    ok &= vu_report("gmsh_incline", "10 deg Gmsh slope, mu 0.3 (sticks): travel / frictionless travel",
                    u / free_dist, 0.0, u / free_dist, 0.01, secs);
    ok &= vu_report("gmsh_incline", "10 deg: slope's normal force (N/m), mean over 0.1-0.2 s", f[0], W * cos(th),
                    f[0] / (W * cos(th)) - 1, 0.02, secs);
    ok &= vu_report("gmsh_incline", "10 deg: slope's friction force (N/m), mean over 0.1-0.2 s", f[1], W * sin(th),
                    f[1] / (W * sin(th)) - 1, 0.02, secs);
    return ok ? 0 : 1;
}
