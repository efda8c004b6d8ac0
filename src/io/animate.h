/**
 * @file animate.h (internal to src/, not installed)
 * @brief An animation (GIF or MP4) of numbered PNG pictures, made by running ffmpeg.
 */
#ifndef PMECH_IO_ANIMATE_H
#define PMECH_IO_ANIMATE_H

/**
 * @brief Run ffmpeg on the pictures @p pattern names (a printf pattern such as "DIR/speed_%06d.png",
 *        numbered from 0) and write the animation @p out atomically.
 * @param pattern the pictures
 * @param fps frames per second, in (0, 120]
 * @param out the animation: a name ending in .gif or .mp4
 * @return PM_OK; PM_EINPUT (another extension, bad rate); PM_EIO (ffmpeg missing or failing)
 */
int pm_animate(const char *pattern, double fps, const char *out);

#endif
