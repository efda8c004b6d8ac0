/* HDF5 helpers of the checkpoint (checkpoint_h5.h). */
#include "io/checkpoint_h5.h"

#include "pmech/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static hid_t mem_type(ck_type t)
{
    switch (t) {
    case CK_INT32: return H5T_NATIVE_INT32;
    case CK_UINT8: return H5T_NATIVE_UINT8;
    case CK_INT64: return H5T_NATIVE_INT64;
    default: return H5T_NATIVE_DOUBLE;
    }
}

/* Stored types are fixed little-endian ones, so a checkpoint reads the same on any host. */
static hid_t file_type(ck_type t)
{
    switch (t) {
    case CK_INT32: return H5T_STD_I32LE;
    case CK_UINT8: return H5T_STD_U8LE;
    case CK_INT64: return H5T_STD_I64LE;
    default: return H5T_IEEE_F64LE;
    }
}

void ck_quiet(void)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

hid_t ck_group_create(const ck_file *f, hid_t loc, const char *name)
{
    hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0)
        pm_error_set(PM_EIO, "%s: cannot create the group '%s'", f->path, name);
    return g;
}

hid_t ck_group_open(const ck_file *f, hid_t loc, const char *name)
{
    hid_t g = H5Lexists(loc, name, H5P_DEFAULT) > 0 ? H5Gopen2(loc, name, H5P_DEFAULT) : -1;
    if (g < 0)
        pm_error_set(PM_EINPUT, "%s: the group '%s' is missing (not a complete pmech checkpoint)", f->path, name);
    return g;
}

int ck_write(const ck_file *f, hid_t loc, const char *name, ck_type type, const void *data, size_t rows,
             size_t cols)
{
    const hsize_t dims[2] = {rows, cols};
    hid_t space = H5Screate_simple(cols == 1 ? 1 : 2, dims, NULL);
    hid_t ds = space < 0 ? -1 : H5Dcreate2(loc, name, file_type(type), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    static const double none = 0;
    herr_t w = ds < 0 ? -1 : rows * cols == 0 ? 0 : H5Dwrite(ds, mem_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                                               data ? data : &none);
    if (ds >= 0)
        H5Dclose(ds);
    if (space >= 0)
        H5Sclose(space);
    if (w < 0)
        return pm_error_set(PM_EIO, "%s: cannot write the dataset '%s' (%zu x %zu)", f->path, name, rows, cols);
    return PM_OK;
}

/* Open dataset name and give its shape (1-D: cols = 1). */
static hid_t open_shape(const ck_file *f, hid_t loc, const char *name, hsize_t dims[2], int *rank)
{
    hid_t ds = H5Lexists(loc, name, H5P_DEFAULT) > 0 ? H5Dopen2(loc, name, H5P_DEFAULT) : -1;
    if (ds < 0) {
        pm_error_set(PM_EINPUT, "%s: the dataset '%s' is missing (not a complete pmech checkpoint)", f->path, name);
        return -1;
    }
    hid_t space = H5Dget_space(ds);
    *rank = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
    dims[0] = dims[1] = 1;
    if (*rank < 1 || *rank > 2 || H5Sget_simple_extent_dims(space, dims, NULL) < 0) {
        H5Sclose(space);
        H5Dclose(ds);
        pm_error_set(PM_EINPUT, "%s: the dataset '%s' is not a list or a table", f->path, name);
        return -1;
    }
    H5Sclose(space);
    return ds;
}

int ck_rows(const ck_file *f, hid_t loc, const char *name, size_t *rows)
{
    hsize_t dims[2];
    int rank;
    hid_t ds = open_shape(f, loc, name, dims, &rank);
    if (ds < 0)
        return PM_EINPUT;
    H5Dclose(ds);
    *rows = (size_t)dims[0];
    return PM_OK;
}

int ck_read(const ck_file *f, hid_t loc, const char *name, ck_type type, void *data, size_t rows, size_t cols)
{
    hsize_t dims[2];
    int rank;
    hid_t ds = open_shape(f, loc, name, dims, &rank);
    if (ds < 0)
        return PM_EINPUT;
    if (dims[0] != rows || (rank == 2 ? dims[1] : 1) != cols || (rank == 1) != (cols == 1)) {
        H5Dclose(ds);
        return pm_error_set(PM_EINPUT, "%s: the dataset '%s' holds %llu x %llu entries where this case has %zu x %zu",
                            f->path, name, (unsigned long long)dims[0], (unsigned long long)(rank == 2 ? dims[1] : 1),
                            rows, cols);
    }
    herr_t r = rows * cols == 0 ? 0 : H5Dread(ds, mem_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(ds);
    if (r < 0)
        return pm_error_set(PM_EINPUT, "%s: cannot read the dataset '%s'", f->path, name);
    return PM_OK;
}

int ck_attr_write(const ck_file *f, hid_t loc, const char *name, ck_type type, const void *value)
{
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(loc, name, file_type(type), space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t w = a < 0 ? -1 : H5Awrite(a, mem_type(type), value);
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(space);
    if (w < 0)
        return pm_error_set(PM_EIO, "%s: cannot write the attribute '%s'", f->path, name);
    return PM_OK;
}

int ck_attr_read(const ck_file *f, hid_t loc, const char *name, ck_type type, void *value)
{
    hid_t a = H5Aexists(loc, name) > 0 ? H5Aopen(loc, name, H5P_DEFAULT) : -1;
    herr_t r = a < 0 ? -1 : H5Aread(a, mem_type(type), value);
    if (a >= 0)
        H5Aclose(a);
    if (r < 0)
        return pm_error_set(PM_EINPUT, "%s: the attribute '%s' is missing or unreadable", f->path, name);
    return PM_OK;
}

int ck_attr_write_string(const ck_file *f, hid_t loc, const char *name, const char *value)
{
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, strlen(value) + 1);
    H5Tset_strpad(type, H5T_STR_NULLTERM);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t w = a < 0 ? -1 : H5Awrite(a, type, value);
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
    if (w < 0)
        return pm_error_set(PM_EIO, "%s: cannot write the attribute '%s'", f->path, name);
    return PM_OK;
}

int ck_attr_read_string(const ck_file *f, hid_t loc, const char *name, char *buf, size_t len)
{
    buf[0] = '\0';
    hid_t a = H5Aexists(loc, name) > 0 ? H5Aopen(loc, name, H5P_DEFAULT) : -1;
    hid_t ft = a < 0 ? -1 : H5Aget_type(a);
    const size_t size = ft < 0 || H5Tget_class(ft) != H5T_STRING || H5Tis_variable_str(ft) ? 0 : H5Tget_size(ft);
    char *tmp = size ? malloc(size + 1) : NULL;
    herr_t r = -1;
    if (tmp) {
        hid_t mt = H5Tcopy(H5T_C_S1);
        H5Tset_size(mt, size);
        r = H5Aread(a, mt, tmp);
        H5Tclose(mt);
        tmp[size] = '\0';
        if (r >= 0)
            snprintf(buf, len, "%s", tmp);
    }
    free(tmp);
    if (ft >= 0)
        H5Tclose(ft);
    if (a >= 0)
        H5Aclose(a);
    if (r < 0)
        return pm_error_set(PM_EINPUT, "%s: the text attribute '%s' is missing or unreadable", f->path, name);
    return PM_OK;
}
