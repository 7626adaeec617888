/* A random stream's generator state in a checkpoint. Here rather than in
 * core/rng.c: the random streams stand below the checkpoint store, which
 * needs HDF5, particles and the scene. */
#include "ckpt.h"

#include "rng.h"

int gr_rng_save(const gr_rng *r, gr_ckpt *ck, const char *name, gr_err *err)
{
    gsl_rng *g = gr_rng_gsl((gr_rng *)r); /* only read */
    return gr_ckpt_put_bytes(ck, name, gsl_rng_state(g), gsl_rng_size(g), err);
}

int gr_rng_load(gr_rng *r, gr_ckpt *ck, const char *name, gr_err *err)
{
    gsl_rng *g = gr_rng_gsl(r);
    return gr_ckpt_get_bytes(ck, name, gsl_rng_state(g), gsl_rng_size(g), err);
}
