#include "plot.h"

#include <math.h>
#include <sys/wait.h>
#include <unistd.h>

FILE *gr_plot_open(const char *png, int w, int h, gr_err *err)
{
    /* gnuplot writes the picture to its standard output when it cannot
     * open png: never onto grano's results. */
    FILE *gp = popen("gnuplot >/dev/null", "w");
    if (!gp) {
        gr_fail(err, GR_ERUN, "%s: cannot start gnuplot (install gnuplot-nox: ./grano.sh deps)", png);
        return NULL;
    }
    fprintf(gp, "set terminal pngcairo size %d,%d enhanced font 'DejaVu Sans,11'\n", w, h);
    fprintf(gp, "set output '%s'\n", png);
    return gp;
}

int gr_plot_close(FILE *gp, const char *png, gr_err *err)
{
    fprintf(gp, "unset output\n");
    int st = pclose(gp);
    if (st == -1 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        unlink(png);
        return gr_fail(err, GR_ERUN, "%s: gnuplot failed (status %d)", png, st);
    }
    return GR_OK;
}

int gr_plot_snapshot(const char *png, const gr_particles *p, double width, double height,
                     double t, const char *title, gr_err *err)
{
    /* Pixels follow the box's aspect ratio, about 800 on the long side. */
    double s = 800.0 / (width > height ? width : height);
    int w = (int)(width * s) + 160, h = (int)(height * s) + 60;
    FILE *gp = gr_plot_open(png, w, h, err);
    if (!gp)
        return err->code;
    double vmax = 0;
    fprintf(gp, "$mobile << EOD\n");
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & (GR_PF_FIXED | GR_PF_GONE))
            continue;
        double v = hypot(p->vx[i], p->vy[i]);
        vmax = v > vmax ? v : vmax;
        fprintf(gp, "%.6g %.6g %.6g %.6g\n", p->x[i], p->y[i], p->radius[i], v);
    }
    fprintf(gp, "EOD\n$fixed << EOD\n");
    int nfixed = 0;
    for (size_t i = 0; i < p->n; i++)
        if ((p->flags[i] & GR_PF_FIXED) && !(p->flags[i] & GR_PF_GONE)) {
            fprintf(gp, "%.6g %.6g %.6g\n", p->x[i], p->y[i], p->radius[i]);
            nfixed++;
        }
    fprintf(gp, "EOD\n");
    fprintf(gp, "set title '%s, t = %.4g {/Symbol t}'\n", title, t);
    fprintf(gp, "set size ratio -1\nset xrange [0:%g]\nset yrange [0:%g]\n", width, height);
    fprintf(gp, "set xlabel 'x / d'\nset ylabel 'y / d'\n");
    fprintf(gp, "set cblabel '|v| / (g d)^{1/2}'\nset cbrange [0:%g]\n", vmax > 0 ? vmax : 1);
    fprintf(gp, "set palette defined (0 '#1a2a6c', 0.5 '#b21f1f', 1 '#fdbb2d')\n");
    fprintf(gp, "set style fill solid 1.0 noborder\n");
    fprintf(gp, "plot $mobile using 1:2:3:4 with circles lc palette notitle");
    if (nfixed)
        fprintf(gp, ", $fixed using 1:2:3 with circles lc rgb '#808080' notitle");
    fprintf(gp, "\n");
    return gr_plot_close(gp, png, err);
}
