/**
 * @file checkpoint_h5.h (internal to src/io)
 * @brief The few HDF5 operations a checkpoint needs, each failing with a message that names the file
 *        and the object: datasets of rows x cols numbers (one column: a 1-D dataset, so h5dump shows a
 *        plain list), scalar attributes, and groups.
 */
#ifndef PMECH_IO_CHECKPOINT_H5_H
#define PMECH_IO_CHECKPOINT_H5_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

/** The element types a checkpoint stores. */
typedef enum { CK_DOUBLE = 0, CK_INT32 = 1, CK_UINT8 = 2, CK_INT64 = 3 } ck_type;

/** An open checkpoint file and its path (for messages). */
typedef struct ck_file {
    hid_t id;
    const char *path;
} ck_file;

/** @brief Stop HDF5 printing its own error stack: every failure is reported through pm_error_set. */
void ck_quiet(void);

/** @brief Create group @p name under @p loc (an HDF5 location of @p f). Returns its id, or < 0 with a message. */
hid_t ck_group_create(const ck_file *f, hid_t loc, const char *name);

/** @brief Open group @p name. Returns its id, or < 0 with a message naming the missing group. */
hid_t ck_group_open(const ck_file *f, hid_t loc, const char *name);

/** @brief Write dataset @p name of @p rows x @p cols entries of @p type from @p data. */
int ck_write(const ck_file *f, hid_t loc, const char *name, ck_type type, const void *data, size_t rows,
             size_t cols);

/**
 * @brief Read dataset @p name into @p data, which has room for @p rows x @p cols; the stored shape must
 *        be exactly that (PM_EINPUT otherwise, naming the dataset and both shapes).
 */
int ck_read(const ck_file *f, hid_t loc, const char *name, ck_type type, void *data, size_t rows, size_t cols);

/** @brief Rows of dataset @p name (its first dimension). */
int ck_rows(const ck_file *f, hid_t loc, const char *name, size_t *rows);

/** @brief Write a scalar attribute of @p loc. */
int ck_attr_write(const ck_file *f, hid_t loc, const char *name, ck_type type, const void *value);

/** @brief Read a scalar attribute of @p loc. */
int ck_attr_read(const ck_file *f, hid_t loc, const char *name, ck_type type, void *value);

/** @brief Write a string attribute of @p loc. */
int ck_attr_write_string(const ck_file *f, hid_t loc, const char *name, const char *value);

/** @brief Read a string attribute of @p loc into @p buf (cut to @p len - 1 characters). */
int ck_attr_read_string(const ck_file *f, hid_t loc, const char *name, char *buf, size_t len);

#endif
