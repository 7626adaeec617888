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

static void write_body(FILE *f, const char *h5, size_t n, size_t frames, const double *times,
                       const gr_xdmf_attr *attrs, size_t nattrs)
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
    fputs(" </Domain>\n</Xdmf>\n", f);
}

int gr_xdmf_write(const char *xdmf_path, const char *h5_name, size_t n, size_t frames,
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
    write_body(f, h5_name, n, frames, times, attrs, nattrs);
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
