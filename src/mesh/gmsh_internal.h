/* Internal to src/mesh: a Gmsh MSH 4.1 file as read (gmsh_read.c), before it becomes a grid (gmsh.c). */
#ifndef PMECH_MESH_GMSH_INTERNAL_H
#define PMECH_MESH_GMSH_INTERNAL_H

#include <stddef.h>

#include "pmech/particles.h"

/** One entry of $PhysicalNames. */
typedef struct pm_msh_name {
    int dim, tag;
    char name[64];
} pm_msh_name;

/** The physical tags of one entity of $Entities. */
typedef struct pm_msh_entity {
    int dim, tag, n_phys;
    int *phys;
} pm_msh_entity;

/** The sections pmech uses, as the file gives them (node tags, not indices). */
typedef struct pm_msh {
    size_t n_names;
    pm_msh_name *names;
    size_t n_ent;
    pm_msh_entity *ent;
    long max_tag;
    long *tag_index;   /**< node tag -> index into xy, -1 if absent */
    size_t n_nodes;
    double *xy;        /**< PM_DIM coordinates per node (z is dropped) */
    /* elements by dimension */
    size_t n_tri, n_quad, n_line, n_pt;
    long *tri, *quad, *line, *pt;                 /**< node tags, 3, 4, 2, 1 per element */
    int *tri_ent, *quad_ent, *line_ent, *pt_ent;  /**< entity tag of each element */
    long *tri_tag, *quad_tag;                     /**< element tags of the 2-D elements (for messages) */
    size_t cap_tri, cap_quad, cap_line, cap_pt;
} pm_msh;

/**
 * Read the MSH 4.1 ASCII file @p path into @p m (zeroed first; free with pm_msh_free() whatever
 * the result). Returns PM_OK, PM_EIO (cannot open or read), PM_ENOMEM, or PM_EINPUT naming
 * path:line and what is wrong.
 */
int pm_msh_parse(const char *path, pm_msh *m);

/** Free what pm_msh_parse() allocated. */
void pm_msh_free(pm_msh *m);

/**
 * Refuse 2-D elements that would make a wrong grid without failing later (gmsh_check.c): an element
 * with a repeated node, zero area or (quads) corners that do not all turn the same way; two elements
 * with the same nodes; two elements on the same side of one edge (overlapping); two nodes at one point
 * unless both are nodes of line elements (the two sides of a slit).
 * Returns PM_OK, PM_ENOMEM, or PM_EINPUT naming @p path and the element tags (or node tags).
 */
int pm_msh_check_elements(const pm_msh *m, const char *path);

#endif
