/* The bench of a method without a bench of its own: through gr_sim alone. */
#ifndef GR_BENCH_GENERIC_H
#define GR_BENCH_GENERIC_H

#include "method.h"

/* grano bench METHOD for any registered method: argv[0] is the method. */
int bench_generic(const gr_method_type *m, int argc, char **argv);

#endif
