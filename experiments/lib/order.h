/* Orderings for qsort. */
#ifndef GR_EXP_ORDER_H
#define GR_EXP_ORDER_H

/* Ascending doubles (NaN compares equal to everything). */
int exp_cmp_double(const void *a, const void *b);

#endif
