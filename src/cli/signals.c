/*
 * SIGINT and SIGTERM during `pmech run`: the first asks the run to stop after the step in progress (it
 * then writes a checkpoint, closes its files and writes run.json); a second one ends the process at once.
 * Every output file is whole at any moment (frames, checkpoints and run.json are renamed into place, CSV
 * lines are written whole), so what is on disk stays readable either way. So that run.json too says what
 * happened, the second signal writes a short one, prepared in advance: a signal handler may only call
 * async-signal-safe functions (open, write, rename), not format text.
 */
#include "cli/commands.h"

#include "pmech/case.h"
#include "pmech/error.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static volatile sig_atomic_t pending;
static volatile sig_atomic_t have_note; /* 1: the notes below are ready; 0 once the run wrote its own */
/* run.json for a second SIGINT [0] or SIGTERM [1], its path and its temporary path */
static char note[2][PM_PATH_MAX + 512];
static size_t note_len[2];
static char note_path[PM_PATH_MAX + 32], note_tmp[PM_PATH_MAX + 48];

static void write_note(int sig)
{
    const int k = sig == SIGTERM;
    const int fd = open(note_tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0)
        return;
    const ssize_t w = write(fd, note[k], note_len[k]);
    close(fd);
    if (w == (ssize_t)note_len[k])
        rename(note_tmp, note_path);
    else
        unlink(note_tmp);
}

static void on_signal(int sig)
{
    if (pending) {
        if (have_note && (sig == SIGINT || sig == SIGTERM))
            write_note(sig);
        _exit(128 + sig);
    }
    pending = sig;
}

const volatile sig_atomic_t *pm_cli_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART; /* the step in progress finishes its writes */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    return &pending;
}

/* Copy s into a JSON string body (quotes and backslashes escaped, control characters dropped). */
static void json_text(char *out, size_t n, const char *s)
{
    size_t j = 0;
    for (; *s && j + 3 < n; s++) {
        if (*s == '"' || *s == '\\')
            out[j++] = '\\';
        if ((unsigned char)*s >= 0x20)
            out[j++] = *s;
    }
    out[j] = '\0';
}

void pm_cli_signals_prepare(const char *dir, const char *case_file)
{
    have_note = 0;
    if ((size_t)snprintf(note_path, sizeof note_path, "%s/run.json", dir) >= sizeof note_path ||
        (size_t)snprintf(note_tmp, sizeof note_tmp, "%s/run.json.signal.tmp", dir) >= sizeof note_tmp)
        return;
    char file[PM_PATH_MAX + 64];
    json_text(file, sizeof file, case_file);
    for (int k = 0; k < 2; k++) {
        const char *name = k ? "SIGTERM" : "SIGINT";
        const int n = snprintf(note[k], sizeof note[k],
                               "{\n  \"version\": \"%s\",\n  \"case\": \"%s\",\n  \"exit_status\": %d,\n"
                               "  \"interrupted\": \"%s\",\n  \"message\": \"a second %s stopped the run at once: "
                               "the frames listed in particles.pvd are whole, and checkpoint.h5 (if any) is the "
                               "last complete checkpoint\"\n}\n",
                               PMECH_VERSION, file, 128 + (k ? SIGTERM : SIGINT), name, name);
        if (n < 0 || (size_t)n >= sizeof note[k])
            return;
        note_len[k] = (size_t)n;
    }
    have_note = 1;
}

void pm_cli_signals_finished(void)
{
    have_note = 0;
}
