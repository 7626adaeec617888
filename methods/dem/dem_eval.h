/* The force evaluation's private state, shared by dem_force.c (contacts,
 * strips, colours), dem_balance.c (runs of strips per thread) and
 * dem_flow.c (how the threads share a step). */
#ifndef GR_DEM_EVAL_H
#define GR_DEM_EVAL_H

#include <stdatomic.h>
#include <stdint.h>

#include "dem.h"
#include "dem_contact.h"

/* Contacts and grains per batch of the Verlet pair loop (dem_batch.h); a
 * grain with more list pairs than DEM_BATCH goes one pair at a time. */
enum { DEM_BATCH = 128, DEM_BATCH_GRAINS = 64 };

/* What one strip's evaluation, kick and drift leave, on cache lines of the
 * strip's own. Only the thread that runs a strip writes its record (its
 * kick too: dem_flow.c), so two threads meet only on their neighbours'
 * flags. Packed per-strip arrays (one array per field) put the last
 * strips of one thread's run and the first of the next on one line of
 * each array, which both threads wrote at every step. Results and flags
 * each fill a 128-byte pair of lines (the unit the L2 prefetcher fetches,
 * common/apart.h): at 192 bytes a record's flags shared a pair with the
 * next record's results. On cores that share no cache the 5000-grain
 * flowing silo's two threads went from 1.556 to 1.597 (medians of 10 and
 * 11 runs of `grano bench dem --silo --n 5000 --settle 16000 --steps 16000
 * --scaling`, alternated, AMD EPYC, 27 Nov 2026); same bits. */
typedef struct {
    _Alignas(128) double smax; /* largest relative overlap */
    double sel;               /* elastic energy */
    long si, sj;              /* the overlap's pair (j = -1 - k for segment k) */
    double kin;               /* kinetic energy after the fused kick */
    double svmax;             /* largest speed^2 of the next drift's half kick */
    double stime;             /* smoothed wall time of its last timed runs */
    double tdrift;            /* drift time of this step (timed steps) */
    double spre[2];           /* two largest squared moves of the drift done ahead */
    double smove[2];          /* two largest squared moves of this step's drift */
    double strial[2];         /* time batched, one pair at a time (dem_force.c) */
    /* the epochs at which its drift and its colour's pushes were done
     * (the one-barrier step): the neighbours spin on this line */
    _Alignas(128) _Atomic uint64_t dflag;
    _Atomic uint64_t cflag;
} dem_strip;

/* What changes from step to step comes first, in two cache lines: the set-up
 * (gr_dem_eval_begin) stores only the words that changed, so the other
 * threads keep the rest cached. */
typedef struct {
    double *restrict x, *restrict y, *restrict fx, *restrict fy, *restrict tq;
    const double *restrict ux, *restrict uy, *restrict uw;
    uint64_t E;
    double integ;
    int kick, kick_p;   /* fused kick on, and its old buffer */
    int pre;            /* the kick also drifts the strip for the next step (buffer 2) */
    int hist_full;      /* set when a grain ran out of history slots */
    long full_i;
    gr_dem *d;
    const double *restrict rad;
    const int32_t *restrict tag;
    const uint32_t *restrict flags;
    dem_law law;
    dem_law law_w;      /* walls: their own damping (dem_damping.c) */
    double Lx, Ly;
    /* active segments at this evaluation: offset and velocity */
    const double *seg_off;
    double *seg_vy;
    const unsigned char *seg_on;
    dem_strip *st;      /* per strip results (dem_strip) */
    double *sseg;       /* per strip, per segment: fx, fy, fn */
    size_t sstride;     /* doubles per strip in sseg: whole cache lines */
    int ncol;           /* colours of strips */
    unsigned char *sway; /* per strip: 1 when the batches were the faster */
    const int *kicker;  /* per strip: the strip after whose push it is kicked */
    const int *split;   /* per colour, nth + 1 bounds in the colour's own strip order */
    int nth;            /* threads the split is for */
} dem_ctx;

/* One thread's strips in the one-barrier step, reduced by that thread at
 * the end of its run, so that the serial end of the step reads a line or
 * two per thread instead of every strip's results (dem_flow.c). Maxima
 * and the two largest moves do not depend on the order they are taken
 * in; the sums do, so only thread 0, whose strips come first, sums its
 * own (the serial end goes on from there in strip order). */
typedef struct {
    _Alignas(128) double best; /* largest overlap of its strips, the first strip's on a tie */
    long bi, bj;
    double vmax2;             /* of the strips it kicked */
    double move[2], pre[2];   /* two largest squared moves: drift, drift done ahead */
    double eel0, kin0;        /* thread 0: strips [0, its end), summed in order */
} gr_dem_tred;

/* The evaluation in progress: its context and per-strip scratch, kept
 * across steps so that a step allocates nothing. */
struct gr_dem_eval {
    _Alignas(64) dem_ctx c;
    int mode, ns, nseg;
    double t_eval;
    uint64_t E;
    size_t cap_ns, cap_seg, cap_sseg;
    double *sseg, *soff, *svy;
    unsigned char *son;
    dem_strip *st;   /* per strip; stime and strial kept across evaluations */
    double *sel, *kin; /* one-barrier step: the strips' sums, packed for the serial end */
    unsigned char *sway;
    int *kicker;     /* per strip: the strip after whose pushes it is kicked */
    int *split;      /* ncol x (nth + 1), then nth + 1 for the one-barrier step */
    size_t cap_split;
    int drifted;     /* this step's drift was done ahead: the one-barrier step skips it */
    uint64_t epoch;  /* of the one-barrier step (dem_strip's flags) */
    gr_dem_tred *tred; /* per thread, valid when tred_on: the last evaluation was */
    int tred_on, cap_tred; /* a one-barrier step (set by gr_dem_eval_flow_begin) */
    unsigned char *sstr; /* per strip: seg_strip (dem_evalrun.c) at this evaluation */
    uint64_t sstr_key;   /* list_gen + 1 that sstr is for (0: none), */
    int sstr_mode, sstr_ns, sstr_nseg; /* and for which mode, strips and segments */
    /* the one-barrier step's cut depends only on the strips' times and
     * sizes: a step right after an untimed one-barrier step on the same
     * list keeps it (flow_E, flow_gen: the last such step and its list) */
    uint64_t flow_E, flow_gen;
    int cut_keep;
};

/* dem_balance.c: cut the m strips first, first + step, ... into nth runs
 * of about equal cost (b[t] the first of run t, b[nth] = m); split every
 * colour so (ev->split). */
void gr_dem_cut_runs(const gr_dem *d, const struct gr_dem_eval *ev, int first, int step, int m,
                     int nth, int *b);
void gr_dem_split_strips(const gr_dem *d, struct gr_dem_eval *ev, int nth);

#endif
