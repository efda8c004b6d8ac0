/*
 * Internal to src/io: typed reading of jansson values with messages that name the file, the key
 * path, the value found and what is allowed, and "did you mean" suggestions for unknown keys and
 * names. Every reader returns PM_OK or PM_EINPUT (message set).
 */
#ifndef PMECH_IO_JSON_READ_H
#define PMECH_IO_JSON_READ_H

#include <jansson.h>
#include <stddef.h>

/** Where a value sits: the file and the JSON path of its parent object ("" for the root). */
typedef struct jr_ctx {
    const char *file;
    const char *path;
} jr_ctx;

/** Flags of the readers. */
enum { JR_REQUIRED = 1 };

/** Join a parent path and a key ("analysis" + "dt" -> "analysis.dt"). */
void jr_join(char *out, size_t cap, const char *path, const char *key);

/** Join a path and an index ("materials", 2 -> "materials[2]"). */
void jr_index(char *out, size_t cap, const char *path, size_t i);

/** The closest of @p names to @p word within edit distance 2 (or a prefix match), else NULL. */
const char *jr_suggest(const char *word, const char *const *names);

/** Error: every key of @p obj must be in the NULL-terminated @p allowed list. */
int jr_only_keys(const jr_ctx *cx, json_t *obj, const char *const *allowed);

/** Error unless @p v is an object (what = name used in the message). */
int jr_expect_object(const jr_ctx *cx, const char *key, json_t *v);

/** A number (integers accepted); absent: @p def, or an error when JR_REQUIRED. */
int jr_number(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, double def, double *out);

/** A whole number in [lo, hi]. */
int jr_int(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, long def, long lo, long hi, long *out);

/** A string copied into @p out (cap bytes, must fit). */
int jr_string(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, const char *def, char *out,
              size_t cap);

/** A boolean. */
int jr_bool(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, int def, int *out);

/** A list of exactly two numbers. */
int jr_vec2(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, const double def[2], double out[2]);

/** A list of exactly @p n numbers. */
int jr_vecn(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, size_t n, double *out);

/** One of @p names (NULL-terminated); *out is its index. Absent: @p def (or error when required). */
int jr_enum(const jr_ctx *cx, json_t *obj, const char *key, unsigned flags, const char *const *names, int def,
            int *out);

/**
 * A range check on a value already read: lo/hi with open ends when lo_open/hi_open.
 * The message names the key path, the value and the interval.
 */
int jr_range(const jr_ctx *cx, const char *key, double v, double lo, int lo_open, double hi, int hi_open);

/** A short text of a JSON value for messages (static buffer per thread). */
const char *jr_text(json_t *v);

/** The JSON type of @p v in words ("a string", "an array", ...). */
const char *jr_type(json_t *v);

#endif
