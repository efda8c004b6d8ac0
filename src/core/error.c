/* One message per thread: OpenMP workers can fail independently without racing on a buffer. */
#include "pmech/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static _Thread_local char pm_msg[2048];

int pm_error_set(int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pm_msg, sizeof pm_msg, fmt, ap);
    va_end(ap);
    return code;
}

int pm_error_prefix(int code, const char *fmt, ...)
{
    char prefix[1024], old[sizeof pm_msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(prefix, sizeof prefix, fmt, ap);
    va_end(ap);
    memcpy(old, pm_msg, sizeof old);
    /* truncation of an over-long message is acceptable: it stays a valid string */
    size_t np = strlen(prefix);
    if (np >= sizeof pm_msg)
        np = sizeof pm_msg - 1;
    memcpy(pm_msg, prefix, np);
    size_t room = sizeof pm_msg - 1 - np, no = strlen(old);
    if (no > room)
        no = room;
    memcpy(pm_msg + np, old, no);
    pm_msg[np + no] = '\0';
    return code;
}

const char *pm_error_message(void) { return pm_msg; }

void pm_error_clear(void) { pm_msg[0] = '\0'; }

int pm_exit_code(int status)
{
    switch (status) {
    case PM_OK: return 0;
    case PM_EINPUT: return 2;
    case PM_EINTR: return 130; /* 128 + SIGINT; pm_run records 128 + the signal it was given */
    default: return 1;
    }
}
