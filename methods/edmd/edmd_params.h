/* The [edmd] section as a parameter table (common/params.h), for the
 * method table and gr_edmd_params_read. */
#ifndef GR_EDMD_PARAMS_H
#define GR_EDMD_PARAMS_H

#include "edmd.h"
#include "params.h"

extern const gr_param gr_edmd_param_table[];
/* Values read through the table into the backend's struct; refuses what
 * the table cannot say (tree_arity 3). */
int gr_edmd_params_from(const gr_scene *sc, const gr_param_values *pv, gr_edmd_params *p,
                        gr_err *err);

#endif
