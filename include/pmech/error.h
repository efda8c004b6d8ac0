/**
 * @file error.h
 * @brief One error convention for all of pmech: functions return an int status
 *        (0 = success, negative PM_E* = failure) and leave a message describing
 *        what went wrong, naming the file, key path or particle involved.
 */
#ifndef PMECH_ERROR_H
#define PMECH_ERROR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Status codes. The CLI maps PM_EINPUT to exit code 2, PM_ESIM to exit 1, PM_EINTR to 128 + the signal. */
enum pm_status {
    PM_OK = 0,
    PM_EINPUT = -1,  /**< invalid case file, command line or parameters */
    PM_ESIM = -2,    /**< the simulation failed (NaN, inversion, divergence) */
    PM_ENOMEM = -3,  /**< allocation failed */
    PM_EIO = -4,     /**< file could not be read or written */
    PM_EINTERNAL = -5, /**< a bug: an invariant of pmech itself was broken */
    PM_EINTR = -6     /**< a run stopped on request (SIGINT, SIGTERM) after a complete step */
};

/**
 * @brief Record an error message (printf-style) for the current thread and return @p code.
 * @param code the status to return (a negative PM_E* value)
 * @param fmt printf format of the message
 * @return @p code, so that callers can write `return pm_error_set(PM_EINPUT, ...)`.
 */
int pm_error_set(int code, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/**
 * @brief Prefix the current message with more context ("while reading x: <old message>").
 * @param code the status to return
 * @param fmt printf format of the prefix
 * @return @p code
 */
int pm_error_prefix(int code, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/** @brief The last message set on this thread ("" when none). */
const char *pm_error_message(void);

/** @brief Forget the last message. */
void pm_error_clear(void);

/** @brief Map a status to the process exit code (0, 1 or 2). */
int pm_exit_code(int status);

/** Propagate a failing status to the caller (PETSc-style `PetscCall`). */
#define pm_check(call)                 \
    do {                               \
        int pm_check_rc_ = (call);     \
        if (pm_check_rc_ != 0)         \
            return pm_check_rc_;       \
    } while (0)

#ifdef __cplusplus
}
#endif
#endif
