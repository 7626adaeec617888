/* The programs a movie runs (gnuplot, ffmpeg) and its folder of frames. */
#ifndef GR_MOVIE_ENC_H
#define GR_MOVIE_ENC_H

#include <stddef.h>

#include "err.h"

/* An interrupt (SIGINT, SIGTERM, SIGHUP) while a movie is made is held
 * until the frames and the part file are removed: mv_catch at the start,
 * mv_caught to stop early, mv_release at the end (which then dies of it). */
void mv_catch(void);
int mv_caught(void);
void mv_release(void);
/* Run argv (argv[0] looked up on PATH), its output and errors into log:
 * GR_ERUN quoting the log's last line when it fails; an interrupt ends it. */
int mv_run(char *const argv[], const char *log, gr_err *err);
/* A new folder beside out ("<out>.frames-XXXXXX") into dir. */
int mv_tmpdir(const char *out, char *dir, size_t n, gr_err *err);
/* Remove the files of dir, then dir (accepts "": nothing). */
void mv_rmdir(const char *dir);
/* dir/f000000.png ... as an H.264 MP4 at fps frames per second into part. */
int mv_encode_mp4(const char *dir, long fps, const char *part, gr_err *err);

#endif
