/* The window-averaged stress of the lattice gas (methods/method.h,
 * common/stress.h): its collisions are on one node and move no momentum
 * across space, so the stress is the momentum flux of propagation alone,
 * the kinetic sum of m v v over the particles, sampled once a step. On a
 * cut between rows of free-streaming nodes it is exactly the momentum
 * that crosses it (a diagonal mover crosses every other step with half
 * the vertical speed: (1/2) c (c / 2) = (c / 2)^2); in a wall node, whose
 * particles are being reflected, it is not the force on the wall. Calls
 * no other file of the backend. */
#include "lgca_int.h"

/* Every particle after the step, weighted by the step's duration. */
void lgca_stress_sample(lgca *L)
{
    if (!L->stress)
        return;
    size_t nw = (size_t)L->nw;
    double c = L->a / L->par.dt, mh = L->mass * L->par.dt;
    for (int j = 0; j < L->nj; j++)
        for (size_t k = 0; k < LGCA_CH; k++) {
            const uint64_t *x = L->lane[j] + k * nw;
            double vx = 0, vy = 0;
            if (k < 6)
                lgca_unit_velocity((int)k, &vx, &vy), vx *= c, vy *= c;
            const double mom[6] = {mh, mh * vx, mh * vy, mh * vx * vx, mh * vx * vy, mh * vy * vy};
            for (size_t w = 0; w < nw; w++)
                for (uint64_t b = x[w]; b; b &= b - 1) {
                    double px, py;
                    lgca_node_xy(L, (int)(w * 64) + __builtin_ctzll(b), j, &px, &py);
                    gr_stress_acc_kinetic(L->stress, px, py, mom);
                }
        }
}

static double now(const lgca *L) { return (double)L->step * L->par.dt; }

int lgca_stress(lgca *L, int nx, int ny, double global[4], double *cells, gr_err *err)
{
    gr_stress_acc *a = L->stress;
    if (!a || a->nx != nx || a->ny != ny) {
        gr_stress_acc_free(a);
        if (!(a = L->stress = gr_stress_acc_create(L->sc->width, L->sc->height, L->per_j, L->per_i, nx, ny,
                                                   now(L), err)))
            return err->code;
    }
    gr_stress_acc_read(a, now(L), global, cells);
    return GR_OK;
}

int lgca_stress_save(const lgca *L, gr_ckpt *ck, gr_err *err)
{
    return L->stress ? gr_stress_acc_save(L->stress, ck, "lgca_stress", err) : GR_OK;
}

int lgca_stress_load(lgca *L, gr_ckpt *ck, gr_err *err)
{
    return gr_stress_acc_load(&L->stress, ck, "lgca_stress", L->sc->width, L->sc->height, L->per_j, L->per_i, err);
}
