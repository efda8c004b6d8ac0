/*
 * The output directory of `pmech run`. One run at a time writes into a directory (an advisory lock on
 * DIR/.pmech.lock, released by the kernel when the process ends however it ends, so a crash leaves no
 * stale lock), and the outputs of an earlier run are replaced only when the user asks (--overwrite):
 * a run used to delete the earlier probes.csv, run.json, frames and pictures without a word.
 */
#include "cli/commands.h"

#include "io/output.h"
#include "pmech/error.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

#define LOCK_NAME ".pmech.lock"

/* Files and directories a run (or a strength-reduction search) writes: 1 for a single file such as
 * run.json, 2 for one of a series (frames, pictures, trials), 0 for anything else. */
static int is_run_output(const char *name)
{
    static const char *const exact[] = {"run.json", "particles.pvd", "grid.pvd", "grid.vtu", "probes.csv",
                                        "energy.csv", "newton.log", "reactions.csv", "releases.csv",
                                        "removals.csv", "strength_reduction.csv", "checkpoint.h5", NULL};
    static const char *const prefixes[] = {"particles_", "grid_", "srf_", NULL};
    for (int k = 0; exact[k]; k++)
        if (!strcmp(name, exact[k]))
            return 1;
    for (int k = 0; prefixes[k]; k++)
        if (!strncmp(name, prefixes[k], strlen(prefixes[k])))
            return 2;
    return 0;
}

/* Names the earlier outputs in @p dir, "" when there are none: run.json and the other single files
 * first, then the count of the rest. */
static int earlier_outputs(const char *dir, char *list, size_t n)
{
    list[0] = '\0';
    size_t count = 0, used = 0, named = 0;
    for (int pass = 1; pass <= 2; pass++) {
        DIR *d = opendir(dir);
        if (!d)
            return pm_error_set(PM_EIO, "cannot read the output directory '%s': %s", dir, strerror(errno));
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            const int kind = is_run_output(e->d_name);
            if (kind != pass)
                continue;
            if (named < 3 && used + strlen(e->d_name) + 4 < n) {
                used += (size_t)snprintf(list + used, n - used, "%s%s", named ? ", " : "", e->d_name);
                named++;
            }
            count++;
        }
        closedir(d);
    }
    if (count > named)
        snprintf(list + used, n - used, " and %zu more", count - named);
    return PM_OK;
}

int pm_cli_claim_output(const char *dir, int overwrite, int *lock_fd)
{
    *lock_fd = -1;
    if (!dir || !dir[0])
        return pm_error_set(PM_EINPUT, "the output directory is empty: give one with -o DIR or output.directory");
    pm_check(pm_mkdir_p(dir));
    char path[PM_PATH_MAX + 32];
    if ((size_t)snprintf(path, sizeof path, "%s/" LOCK_NAME, dir) >= sizeof path)
        return pm_error_set(PM_EINPUT, "output directory '%s': path too long", dir);
    const int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        return pm_error_set(PM_EIO, "cannot create '%s': %s", path, strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int e = errno;
        char pid[32] = "";
        const ssize_t got = pread(fd, pid, sizeof pid - 1, 0);
        pid[got > 0 ? got : 0] = '\0';
        pid[strcspn(pid, "\n")] = '\0';
        close(fd);
        if (e == EWOULDBLOCK)
            return pm_error_set(PM_EINPUT, "'%s' is in use by another pmech run (process %s); wait for it or "
                                "choose another directory with -o", dir, pid[0] ? pid : "unknown");
        return pm_error_set(PM_EIO, "cannot lock '%s': %s", path, strerror(e));
    }
    char list[512];
    int rc = earlier_outputs(dir, list, sizeof list);
    if (!rc && list[0] && !overwrite)
        rc = pm_error_set(PM_EINPUT, "'%s' holds the outputs of an earlier run (%s); pmech replaces them only with "
                          "--overwrite: add it, or choose another directory with -o", dir, list);
    if (rc) {
        close(fd);
        return rc;
    }
    char pid[32];
    const int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)len, 0) != len) {
        rc = pm_error_set(PM_EIO, "cannot write '%s': %s", path, strerror(errno));
        close(fd);
        return rc;
    }
    *lock_fd = fd;
    return PM_OK;
}

void pm_cli_release_output(int lock_fd)
{
    /* the file stays: removing it would let a run that opened it just before lock a file no one else sees */
    if (lock_fd >= 0)
        close(lock_fd);
}
