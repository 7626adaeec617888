/* libFuzzer target: the H5MD reader and the checkpoint reader on any bytes
 * (written to a file, since both open paths). They must fail cleanly. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "ckpt.h"
#include "h5md.h"
#include "particles.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/grano-fuzz-%ld.h5", (long)getpid());
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    fwrite(data, 1, size, f);
    fclose(f);
    gr_err e = {0};
    gr_h5md_reader *r = gr_h5md_open(path, &e);
    if (r) {
        const gr_h5md_info *in = gr_h5md_info_of(r);
        gr_particles *p = gr_particles_create(0, &e);
        if (p && in && in->nframes > 0)
            gr_h5md_read_frame(r, in->nframes - 1, p, NULL, NULL, &e);
        gr_obs *obs = in && in->nobs > 0 && in->nobs < 100000 ? calloc(in->nobs, sizeof *obs) : NULL;
        if (obs)
            gr_h5md_read_obs(r, obs, &e);
        free(obs);
        gr_particles_free(p);
        gr_h5md_reader_free(r);
    }
    gr_err e2 = {0};
    gr_ckpt *ck = gr_ckpt_open(path, &e2);
    if (ck) {
        size_t n;
        if (!gr_ckpt_len(ck, "run_counters", &n, &e2) && n == 3) {
            uint64_t c[3];
            gr_ckpt_get_u64(ck, "run_counters", c, 3, &e2);
        }
        gr_ckpt_close(ck, &e2);
    }
    unlink(path);
    return 0;
}
