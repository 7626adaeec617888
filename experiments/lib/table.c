/* Result tables: to the HDF5 result file and as plain .dat text. */
#include "table.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

int exp_put_result(gr_h5md *h, const char *name, size_t rows, size_t cols, const char *cols_csv,
                    const char *desc, const double *v, gr_err *err)
{
    const char *cn[16];
    char buf[512];
    size_t k = 0;
    if (cols_csv) {
        snprintf(buf, sizeof buf, "%s", cols_csv);
        for (char *s = strtok(buf, ","); s && k < 16; s = strtok(NULL, ","))
            cn[k++] = s;
    }
    gr_result_desc d = {name, rows, cols, cols_csv && k == cols ? cn : NULL, NULL, desc};
    return gr_h5md_write_result(h, &d, v, err);
}

FILE *exp_dat_open(const char *path, gr_err *err)
{
    char part[1200];
    snprintf(part, sizeof part, "%s.part", path);
    FILE *f = fopen(part, "w");
    if (!f)
        gr_fail(err, GR_ERUN, "%s: cannot write: %s", part, strerror(errno));
    return f;
}

int exp_dat_close(FILE *f, const char *path, gr_err *err)
{
    char part[1200];
    snprintf(part, sizeof part, "%s.part", path);
    int bad = ferror(f);
    if (fclose(f) || bad) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "%s: write failed", part);
    }
    if (rename(part, path)) {
        unlink(part);
        return gr_fail(err, GR_ERUN, "cannot rename %s to %s: %s", part, path, strerror(errno));
    }
    return GR_OK;
}

int exp_write_dat(const char *path, const char *header, const double *v, size_t rows, size_t cols,
                   gr_err *err)
{
    FILE *f = exp_dat_open(path, err);
    if (!f)
        return err->code;
    fprintf(f, "# %s\n", header);
    for (size_t i = 0; i < rows; i++)
        for (size_t j = 0; j < cols; j++)
            fprintf(f, "%.8g%c", v[i * cols + j], j + 1 < cols ? ' ' : '\n');
    return exp_dat_close(f, path, err);
}
