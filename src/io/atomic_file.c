/* Files appear complete or not at all: everything is written to "<path>.tmp", forced to the disk
 * (fsync) and renamed over the final name (rename is atomic within one directory on POSIX file systems).
 * Without the fsync a power cut soon after the rename can leave the new name on an empty file: a
 * frame, particles.pvd or run.json that no reader can open. Its cost is in docs/performance.md. */
#include "pmech/error.h"
#include "io/output.h"
#include "io/vtu_write.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

FILE *pm_atomic_fopen(const char *path, char *tmp, size_t tmp_size)
{
    int len = snprintf(tmp, tmp_size, "%s.tmp", path);
    if (len < 0 || (size_t)len >= tmp_size) {
        pm_error_set(PM_EIO, "cannot write '%s': path too long", path);
        return NULL;
    }
    FILE *f = fopen(tmp, "wb");
    if (!f)
        pm_error_set(PM_EIO, "cannot write '%s': %s", tmp, strerror(errno));
    return f;
}

int pm_atomic_fclose(FILE *f, const char *tmp, const char *path, int ok)
{
    int err = 0;
    if (ok && fflush(f) != 0)
        err = errno;
    if (ok && !err && ferror(f))
        err = EIO;
    if (ok && !err && fsync(fileno(f)) != 0)
        err = errno;
    if (fclose(f) != 0 && ok && !err)
        err = errno;
    if (ok && !err && rename(tmp, path) != 0) {
        int e = errno;
        remove(tmp);
        return pm_error_set(PM_EIO, "cannot rename '%s' to '%s': %s", tmp, path, strerror(e));
    }
    if (!ok || err) {
        remove(tmp);
        if (!ok)
            return PM_EIO;
        return pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(err));
    }
    return PM_OK;
}

int pm_write_file_atomic(const char *path, const void *data, size_t len)
{
    char tmp[PM_PATH_MAX + 16];
    FILE *f = pm_atomic_fopen(path, tmp, sizeof tmp);
    if (!f)
        return PM_EIO;
    int ok = len == 0 || fwrite(data, 1, len, f) == len;
    int e = errno;
    if (!ok) {
        pm_atomic_fclose(f, tmp, path, 0);
        return pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(e ? e : EIO));
    }
    return pm_atomic_fclose(f, tmp, path, 1);
}

/* mkdir that accepts an existing directory. */
static int make_one(const char *dir)
{
    if (mkdir(dir, 0777) == 0)
        return PM_OK;
    int e = errno;
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return PM_OK;
        return pm_error_set(PM_EIO, "cannot create directory '%s': a file of that name exists", dir);
    }
    return pm_error_set(PM_EIO, "cannot create directory '%s': %s", dir, strerror(e));
}

int pm_mkdir_p(const char *path)
{
    if (!path || !path[0])
        return pm_error_set(PM_EIO, "cannot create a directory with an empty name");
    size_t n = strlen(path);
    char *buf = malloc(n + 1);
    if (!buf)
        return pm_error_set(PM_ENOMEM, "out of memory creating directory '%s'", path);
    memcpy(buf, path, n + 1);
    while (n > 1 && buf[n - 1] == '/')
        buf[--n] = '\0';
    int rc = PM_OK;
    /* each parent in turn: "a", "a/b", ... (leading slashes and repeated slashes are skipped) */
    for (size_t i = 1; i < n && rc == PM_OK; i++) {
        if (buf[i] == '/' && buf[i - 1] != '/') {
            buf[i] = '\0';
            rc = make_one(buf);
            buf[i] = '/';
        }
    }
    if (rc == PM_OK)
        rc = make_one(buf);
    free(buf);
    return rc;
}
