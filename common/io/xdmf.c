/* XDMF 2 sidecar so that ParaView (and VisIt) open the trajectory of an
 * H5MD file: one Polyvertex grid per frame in a temporal collection, every
 * array a hyperslab of the HDF5 datasets (no data is copied). Rewritten
 * whole through a temporary and a rename, so a reader never sees half. */
#include "h5md_impl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void put_escaped(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
    }
}

static const char *number_type(gr_h5_type t)
{
    switch (t) {
    case GR_T_F64: return "NumberType=\"Float\" Precision=\"8\"";
    case GR_T_I64: return "NumberType=\"Int\" Precision=\"8\"";
    case GR_T_I32: return "NumberType=\"Int\" Precision=\"4\"";
    case GR_T_U32: return "NumberType=\"UInt\" Precision=\"4\"";
    case GR_T_U64: return "NumberType=\"UInt\" Precision=\"8\"";
    default: return "NumberType=\"UChar\" Precision=\"1\"";
    }
}

/* Row `frame` of the [frames][n](,[ncomp]) dataset at path. */
static void hyperslab(FILE *f, const char *h5, const char *path, gr_h5_type t, size_t frame,
                      size_t frames, size_t n, int ncomp, const char *ind)
{
    if (ncomp > 1) {
        fprintf(f, "%s<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %zu %d\" Type=\"HyperSlab\">\n", ind, n, ncomp);
        fprintf(f, "%s  <DataItem Dimensions=\"3 3\" Format=\"XML\">%zu 0 0 1 1 1 1 %zu %d</DataItem>\n",
                ind, frame, n, ncomp);
        fprintf(f, "%s  <DataItem Dimensions=\"%zu %zu %d\" %s Format=\"HDF\">", ind, frames, n, ncomp, number_type(t));
    } else {
        fprintf(f, "%s<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %zu\" Type=\"HyperSlab\">\n", ind, n);
        fprintf(f, "%s  <DataItem Dimensions=\"3 2\" Format=\"XML\">%zu 0 1 1 1 %zu</DataItem>\n",
                ind, frame, n);
        fprintf(f, "%s  <DataItem Dimensions=\"%zu %zu\" %s Format=\"HDF\">", ind, frames, n, number_type(t));
    }
    put_escaped(f, h5);
    fprintf(f, ":%s</DataItem>\n%s</DataItem>\n", path, ind);
}

static herr_t add_name(hid_t g, const char *name, const H5L_info_t *li, void *data)
{
    (void)g;
    (void)li;
    FILE *list = data;
    fprintf(list, "%s\n", name);
    return 0;
}

/* One temporal collection per field: a 3-D image one cell thick (ParaView
 * puts a 2-D CoRectMesh in the y-z plane), cells centred on z = 0 so the
 * field lies under the grains. Geometry and dimensions are z, y, x. */
static void write_field(FILE *f, const char *h5, hid_t file, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "fields/%s", name);
    hid_t g = H5Gopen2(file, path, H5P_DEFAULT);
    int grid[2], nc = 1;
    double origin[2], cell[2];
    int bad = g < 0 || gr_h5_read_attr_int(g, "grid", grid, 2) ||
              gr_h5_read_attr_f64(g, "origin", origin, 2) || gr_h5_read_attr_f64(g, "cell", cell, 2) ||
              gr_h5_read_attr_int(g, "components", &nc, 0);
    gr_h5_close(g);
    hsize_t rows = bad ? 0 : gr_h5_series_rows(file, path);
    double *t = rows ? malloc(rows * sizeof *t) : NULL;
    snprintf(path, sizeof path, "fields/%s/time", name);
    if (!t || gr_h5_read_path(file, path, GR_T_F64, 0, rows, t)) {
        free(t);
        return;
    }
    fprintf(f, "  <Grid Name=\"field %s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name);
    for (hsize_t s = 0; s < rows; s++) {
        fprintf(f, "   <Grid Name=\"%s %llu\" GridType=\"Uniform\">\n", name, (unsigned long long)s);
        fprintf(f, "    <Time Value=\"%.17g\"/>\n", t[s]);
        fprintf(f, "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"2 %d %d\"/>\n",
                grid[1] + 1, grid[0] + 1);
        fprintf(f, "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
                   "      <DataItem Dimensions=\"3\" Format=\"XML\">-0.5 %.17g %.17g</DataItem>\n"
                   "      <DataItem Dimensions=\"3\" Format=\"XML\">1 %.17g %.17g</DataItem>\n"
                   "    </Geometry>\n", origin[1], origin[0], cell[1], cell[0]);
        fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Cell\">\n", name,
                nc == 2 ? "Vector" : nc > 2 ? "Matrix" : "Scalar");
        const char *ind = "      ";
        if (nc > 1) {
            fprintf(f, "%s<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %d %d %d\" Type=\"HyperSlab\">\n",
                    ind, grid[1], grid[0], nc);
            fprintf(f, "%s  <DataItem Dimensions=\"3 4\" Format=\"XML\">%llu 0 0 0 1 1 1 1 1 %d %d %d</DataItem>\n",
                    ind, (unsigned long long)s, grid[1], grid[0], nc);
            fprintf(f, "%s  <DataItem Dimensions=\"%llu %d %d %d\" %s Format=\"HDF\">", ind,
                    (unsigned long long)rows, grid[1], grid[0], nc, number_type(GR_T_F64));
        } else {
            fprintf(f, "%s<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %d %d\" Type=\"HyperSlab\">\n",
                    ind, grid[1], grid[0]);
            fprintf(f, "%s  <DataItem Dimensions=\"3 3\" Format=\"XML\">%llu 0 0 1 1 1 1 %d %d</DataItem>\n",
                    ind, (unsigned long long)s, grid[1], grid[0]);
            fprintf(f, "%s  <DataItem Dimensions=\"%llu %d %d\" %s Format=\"HDF\">", ind,
                    (unsigned long long)rows, grid[1], grid[0], number_type(GR_T_F64));
        }
        put_escaped(f, h5);
        fprintf(f, ":/fields/%s/value</DataItem>\n%s</DataItem>\n    </Attribute>\n   </Grid>\n", name, ind);
    }
    fputs("  </Grid>\n", f);
    free(t);
}

static void write_fields(FILE *f, const char *h5, hid_t file)
{
    if (file < 0 || !gr_h5_is_group(file, "fields"))
        return;
    /* Names first (into memory), then one collection each. */
    char *buf = NULL;
    size_t len = 0;
    FILE *list = open_memstream(&buf, &len);
    if (!list)
        return;
    hid_t g = H5Gopen2(file, "fields", H5P_DEFAULT);
    hsize_t idx = 0;
    if (g >= 0)
        H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, &idx, add_name, list);
    gr_h5_close(g);
    fclose(list);
    for (char *name = buf, *nl; buf && (nl = strchr(name, '\n')); name = nl + 1) {
        *nl = '\0';
        if (gr_h5_valid_name(name))
            write_field(f, h5, file, name);
    }
    free(buf);
}

static void write_body(FILE *f, const char *h5, hid_t file, size_t n, size_t frames,
                       const double *times, const gr_xdmf_attr *attrs, size_t nattrs)
{
    fputs("<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
          "<!-- Written by grano beside its H5MD file; see docs/output-format.md. -->\n"
          "<Xdmf Version=\"2.0\">\n <Domain>\n", f);
    if (frames) {
        fputs("  <Grid Name=\"trajectory\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", f);
        const char *ind = "      ";
        for (size_t fr = 0; fr < frames; fr++) {
            fprintf(f, "   <Grid Name=\"frame %zu\" GridType=\"Uniform\">\n", fr);
            fprintf(f, "    <Time Value=\"%.17g\"/>\n", times[fr]);
            fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\" NodesPerElement=\"1\"/>\n", n);
            fputs("    <Geometry GeometryType=\"XY\">\n", f);
            hyperslab(f, h5, "/particles/trajectory/position/value", GR_T_F64, fr, frames, n, 2, ind);
            fputs("    </Geometry>\n", f);
            for (size_t a = 0; a < nattrs; a++) {
                fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n",
                        attrs[a].name, attrs[a].ncomp > 1 ? "Vector" : "Scalar");
                char path[256];
                if (attrs[a].series) {
                    snprintf(path, sizeof path, "/particles/trajectory/%s/value", attrs[a].name);
                    hyperslab(f, h5, path, attrs[a].type, fr, frames, n, attrs[a].ncomp, ind);
                } else {
                    fprintf(f, "%s<DataItem Dimensions=\"%zu\" %s Format=\"HDF\">", ind, n,
                            number_type(attrs[a].type));
                    put_escaped(f, h5);
                    fprintf(f, ":/particles/trajectory/%s</DataItem>\n", attrs[a].name);
                }
                fputs("    </Attribute>\n", f);
            }
            fputs("   </Grid>\n", f);
        }
        fputs("  </Grid>\n", f);
    }
    write_fields(f, h5, file);
    fputs(" </Domain>\n</Xdmf>\n", f);
}

int gr_xdmf_write(const char *xdmf_path, const char *h5_name, hid_t file, size_t n, size_t frames,
                  const double *times, const gr_xdmf_attr *attrs, size_t nattrs, gr_err *err)
{
    size_t len = strlen(xdmf_path);
    char *tmp = malloc(len + 5);
    if (!tmp)
        return gr_fail(err, GR_ERUN, "out of memory");
    memcpy(tmp, xdmf_path, len);
    memcpy(tmp + len, ".tmp", 5);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        int e = errno;
        free(tmp);
        return gr_fail(err, GR_EINPUT, "cannot write %s: %s", xdmf_path, strerror(e));
    }
    write_body(f, h5_name, file, n, frames, times, attrs, nattrs);
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, xdmf_path) != 0) {
        int e = errno;
        unlink(tmp);
        free(tmp);
        return gr_fail(err, GR_ERUN, "cannot write %s: %s", xdmf_path, strerror(e));
    }
    free(tmp);
    return GR_OK;
}
