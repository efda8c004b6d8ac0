/* An animation of numbered pictures, made by ffmpeg (the Debian package of that name): a GIF with a
 * palette computed from the pictures themselves, or an H.264 MP4 that browsers and slide software play.
 * ffmpeg runs as a child process with an argument vector (no shell), writes a temporary file, and
 * the animation appears under its name only when ffmpeg succeeded. */
#include "io/animate.h"

#include "pmech/error.h"

#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>

extern char **environ;

int pm_animate(const char *pattern, double fps, const char *out)
{
    const char *ext = strrchr(out, '.');
    const int gif = ext && !strcmp(ext, ".gif"), mp4 = ext && !strcmp(ext, ".mp4");
    if (!gif && !mp4)
        return pm_error_set(PM_EINPUT, "animation '%s': the name must end in .gif or .mp4", out);
    if (!(fps > 0 && fps <= 120))
        return pm_error_set(PM_EINPUT, "animation '%s': %g frames per second; allowed: (0, 120]", out, fps);
    char rate[32], tmp[4096];
    snprintf(rate, sizeof rate, "%g", fps);
    if (snprintf(tmp, sizeof tmp, "%s.tmp", out) >= (int)sizeof tmp)
        return pm_error_set(PM_EIO, "animation '%s': path too long", out);
    /* GIF: one palette for all frames, made from them; MP4: even sizes (yuv420p halves the chroma) */
    const char *gif_filter = "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=none";
    const char *mp4_filter = "pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white";
    char *argv[] = {"ffmpeg", "-y", "-nostdin", "-loglevel", "error", "-framerate", rate, "-start_number", "0",
                    "-i", (char *)pattern, "-vf", (char *)(gif ? gif_filter : mp4_filter),
                    gif ? "-f" : "-c:v", gif ? "gif" : "libx264", gif ? "-loop" : "-pix_fmt", gif ? "0" : "yuv420p",
                    gif ? tmp : "-f", gif ? NULL : "mp4", gif ? NULL : tmp, NULL};
    pid_t pid;
    int rc = posix_spawnp(&pid, "ffmpeg", NULL, NULL, argv, environ);
    if (rc != 0)
        return pm_error_set(PM_EIO, "animation '%s': cannot run ffmpeg (%s); install the Debian package ffmpeg",
                            out, strerror(rc));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return pm_error_set(PM_EIO, "animation '%s': lost the ffmpeg process: %s", out, strerror(errno));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        remove(tmp);
        if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
            return pm_error_set(PM_EIO, "animation '%s': ffmpeg is not installed (Debian package ffmpeg)", out);
        return pm_error_set(PM_EIO, "animation '%s': ffmpeg failed (status %d) on %s", out,
                            WIFEXITED(status) ? WEXITSTATUS(status) : -1, pattern);
    }
    if (rename(tmp, out) != 0) {
        const int err = errno;
        remove(tmp);
        return pm_error_set(PM_EIO, "animation '%s': %s", out, strerror(err));
    }
    return PM_OK;
}
