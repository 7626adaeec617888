/* The options of grano plot and grano movie: long names only, values
 * range-checked, each refusal naming its flag. */
#include <math.h>
#include <string.h>

#include "opts.h"
#include "view.h"

enum { O_COLOR = 0x100, O_FIELD, O_CONTACTS, O_RANGE, O_PCT, O_FRAME, O_TIME, O_FORMAT, O_EVERY, O_FROM, O_TO, O_FPS };

#define COMMON                                                                                    \
    {"color", required_argument, NULL, O_COLOR}, {"field", required_argument, NULL, O_FIELD},     \
        {"contacts", no_argument, NULL, O_CONTACTS}, {"range", required_argument, NULL, O_RANGE}, \
        {"percentiles", required_argument, NULL, O_PCT}

static const struct option plot_opts[] = {
    COMMON, {"frame", required_argument, NULL, O_FRAME}, {"time", required_argument, NULL, O_TIME},
    {"format", required_argument, NULL, O_FORMAT}, {NULL, 0, NULL, 0}};
static const struct option movie_opts[] = {
    COMMON, {"every", required_argument, NULL, O_EVERY}, {"from", required_argument, NULL, O_FROM},
    {"to", required_argument, NULL, O_TO}, {"fps", required_argument, NULL, O_FPS}, {NULL, 0, NULL, 0}};

const struct option *vw_options(int movie)
{
    return movie ? movie_opts : plot_opts;
}

void vw_opts_init(vw_opts *o)
{
    *o = (vw_opts){.pct = {2, 98}, .every = 1, .fps = 10, .from = -INFINITY, .to = INFINITY};
}

/* "A,B": two numbers in [lo, hi], the first below the second. */
static int pair(const char *flag, const char *arg, double lo, double hi, double v[2], gr_err *err)
{
    const char *comma = strchr(arg, ',');
    char a[64], b[64];
    if (!comma || (size_t)(comma - arg) >= sizeof a || strlen(comma + 1) >= sizeof b)
        return gr_fail(err, GR_EINPUT, "%s: '%s' is not two numbers A,B", flag, arg);
    snprintf(a, sizeof a, "%.*s", (int)(comma - arg), arg);
    snprintf(b, sizeof b, "%s", comma + 1);
    if (exp_opt_double(flag, a, lo, hi, &v[0], err) || exp_opt_double(flag, b, lo, hi, &v[1], err))
        return err->code;
    if (!(v[0] < v[1]))
        return gr_fail(err, GR_EINPUT, "%s: '%s': the first must be below the second", flag, arg);
    return GR_OK;
}

int vw_option(void *ctx, int id, const char *arg, gr_err *err)
{
    vw_opts *o = ctx;
    switch (id) {
    case O_COLOR: o->color = arg; return GR_OK;
    case O_FIELD: o->field = arg; return GR_OK;
    case O_CONTACTS: o->contacts = 1; return GR_OK;
    case O_RANGE: o->has_range = 1; return pair("--range", arg, -1e300, 1e300, o->range, err);
    case O_PCT: o->has_pct = 1; return pair("--percentiles", arg, 0, 100, o->pct, err);
    case O_FRAME: o->has_frame = 1; return exp_opt_long("--frame", arg, -1000000000L, 1000000000L, &o->frame, err);
    case O_TIME: o->has_time = 1; return exp_opt_double("--time", arg, -1e300, 1e300, &o->time, err);
    case O_FORMAT:
        if (strcmp(arg, "png") && strcmp(arg, "svg") && strcmp(arg, "pdf"))
            return gr_fail(err, GR_EINPUT, "--format: '%s' is not one of png, svg, pdf", arg);
        o->format = arg;
        return GR_OK;
    case O_EVERY: return exp_opt_long("--every", arg, 1, 1000000000L, &o->every, err);
    case O_FROM: return exp_opt_double("--from", arg, -1e300, 1e300, &o->from, err);
    case O_TO: return exp_opt_double("--to", arg, -1e300, 1e300, &o->to, err);
    case O_FPS: return exp_opt_long("--fps", arg, 1, 60, &o->fps, err);
    default: return gr_fail(err, GR_EINPUT, "unknown option");
    }
}

int vw_opts_check(const vw_opts *o, int movie, gr_err *err)
{
    if (o->has_range && o->has_pct)
        return gr_fail(err, GR_EINPUT, "--range and --percentiles both set the colour scale: give one");
    if (o->color && o->field)
        return gr_fail(err, GR_EINPUT, "--color colours grains and --field draws a field: give one");
    if (o->contacts && o->field)
        return gr_fail(err, GR_EINPUT, "--contacts draws the network over grains, not over --field");
    if (!movie && o->has_frame && o->has_time)
        return gr_fail(err, GR_EINPUT, "--frame and --time both pick the frame: give one");
    if (movie && !(o->from <= o->to))
        return gr_fail(err, GR_EINPUT, "--from %g is after --to %g", o->from, o->to);
    return GR_OK;
}

void vw_usage_common(FILE *f)
{
    fprintf(f,
        "      --color Q        colour the grains by Q: speed (default), vx, vy, omega, id,\n"
        "                       species, radius, contacts (contacts per grain) or force (the\n"
        "                       sum of |fn| on the grain); the last two need contact networks\n"
        "                       in the file ([run] contacts = yes)\n"
        "      --field NAME     draw field NAME instead (what the file holds: grano info);\n"
        "                       a vector field's magnitude or NAME.x, NAME.y; a tensor's\n"
        "                       (xx + yy)/2 or NAME.xx, .xy, .yx, .yy. The lattice gas's\n"
        "                       default: packing_fraction\n"
        "      --contacts       the contact network over the grains, lines as thick as the\n"
        "                       normal force\n"
        "      --percentiles LO,HI  the colour scale from the LO-th to the HI-th percentile\n"
        "                       of the values drawn (default 2,98; beyond it the end colours)\n"
        "      --range MIN,MAX  the colour scale from MIN to MAX instead\n");
}
