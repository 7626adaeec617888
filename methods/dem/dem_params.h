/* The [dem] section as a parameter table (common/params.h), for the method
 * table and gr_dem_params_read. */
#ifndef GR_DEM_PARAMS_H
#define GR_DEM_PARAMS_H

#include "dem.h"
#include "params.h"

extern const gr_param gr_dem_param_table[];
/* Values read through the table into the backend's struct (NaN = auto
 * becomes the struct's 0 = auto). */
void gr_dem_params_from(const gr_param_values *pv, gr_dem_params *p);

#endif
