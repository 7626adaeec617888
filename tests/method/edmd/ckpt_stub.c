/* Stand-in for common/ckpt.c while the lead writes it: only linked when
 * that file is absent (see meson.build); every call fails. */
#include "ckpt.h"

#define STUB(name, T)                                                                  \
    int name(gr_ckpt *c, const char *n, T v, size_t k, gr_err *err)                    \
    {                                                                                  \
        (void)c, (void)n, (void)v, (void)k;                                            \
        return gr_fail(err, GR_ERUN, "checkpoints are not built yet (common/ckpt.c)"); \
    }
STUB(gr_ckpt_put_f64, const double *)
STUB(gr_ckpt_put_i64, const int64_t *)
STUB(gr_ckpt_put_u64, const uint64_t *)
STUB(gr_ckpt_put_u32, const uint32_t *)
STUB(gr_ckpt_put_bytes, const void *)
STUB(gr_ckpt_get_f64, double *)
STUB(gr_ckpt_get_i64, int64_t *)
STUB(gr_ckpt_get_u64, uint64_t *)
STUB(gr_ckpt_get_u32, uint32_t *)
STUB(gr_ckpt_get_bytes, void *)
