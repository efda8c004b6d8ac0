/**
 * @file output_internal.h (internal to src/io)
 * @brief The inside of pm_output, for the checkpoint (checkpoint_write.c, checkpoint_read.c), which
 *        stores and restores the output schedule, the probes and the CSV files with the rest of a run.
 */
#ifndef PMECH_OUTPUT_INTERNAL_H
#define PMECH_OUTPUT_INTERNAL_H

#include "io/output.h"
#include "io/run_pictures.h"

#include <stdint.h>

#define OUT_PATH_MAX (PM_PATH_MAX + 64)
#define CSV_BUF 65536

/* An append-only CSV file fed whole lines; bytes reach the file only in whole lines. */
typedef struct csv_out {
    int fd;                 /* -1 when not open */
    char *buf;              /* complete lines not yet written */
    size_t len;
    char *line;             /* the line being built */
    size_t line_len, line_cap;
    int failed;             /* a write failed (reported once) */
    char path[OUT_PATH_MAX];
} csv_out;

typedef struct probe {
    char name[PM_NAME_MAX];
    pm_quantity quantity;
    int body;               /* -1: point probe */
    long particle0;         /* followed particle at t = 0 */
    long particle;          /* its index now (particles may be reordered; -1: a sink removed it) */
    int32_t id;             /* its identity (pm_particles::id), which survives reordering */
    int gone;               /* a sink removed it: its series has ended */
    double init_pos[2];     /* position (body: centre of mass) at t = 0 */
} probe;

struct pm_output {
    char dir[OUT_PATH_MAX];
    double *scratch;        /* 3 doubles per particle for the VTU blocks */
    size_t scratch_n;
    double *frame_t;        /* time of each frame written */
    size_t n_frames, cap_frames;
    csv_out probes_csv, energy_csv;
    probe *pr;
    size_t n_probes;
    char (*body_names)[PM_NAME_MAX];
    double probe_interval, last_probe_t;
    int probe_recorded;
    pm_run_pictures *pics;  /* output.pictures: a PNG per frame */
    double last_energy_t;   /* time of the last energy.csv row (NaN before the first) */
};

/**
 * @brief Make every line of probes.csv and energy.csv reach its file (a checkpoint records their sizes).
 * @return PM_OK or PM_EIO
 */
int pm_output_flush(pm_output *o);

#endif
