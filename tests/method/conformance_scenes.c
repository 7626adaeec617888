/* One small scene per scene feature, each runnable in a second on every
 * backend that declares the feature. */
#include "conformance.h"

#include "scene.h"


#define DOMG "[scene]\nseed = 3\n[domain]\nwidth = 20\nheight = 20\ngravity = 1\n"
#define MAT "[material]\nkn = 1e4\n"
#define SP "[species]\ncount = 40\n"
#define INIT "[init]\nkind = random\nvelocity = gaussian\nv0 = 1\n"
#define BOX "[scene]\nseed = 3\n[domain]\nwidth = 20\nheight = 20\n"

const conf_scene conf_scenes[] = {
    {"box", 0, BOX MAT SP INIT, 4.0, 2, 40},
    {"gravity", GR_FEAT_GRAVITY, DOMG MAT SP INIT, 3.0, 2, 40},
    {"restitution", GR_FEAT_RESTITUTION,
     DOMG "[material]\nkn = 1e4\nrestitution = 0.9\nwall_restitution = 0.8\n" SP INIT, 3.0, 2, 40},
    {"friction-coulomb", GR_FEAT_FRICTION,
     BOX "[material]\nkn = 1e4\ntangential = coulomb\nmu = 0.5\n" SP INIT, 4.0, 2, 40},
    {"friction-soft", GR_FEAT_SOFT_TANGENTIAL,
     BOX "[material]\nkn = 1e4\ntangential = regularised\n"
         "gamma_t = 10\nmu = 0.5\n" SP INIT,
     4.0, 2, 40},
    {"friction-rough", GR_FEAT_FRICTION,
     BOX "[material]\nkn = 1e4\ntangential_restitution = 0.4\n"
         "mu = 0.5\n" SP INIT,
     4.0, 2, 40},
    {"spring", GR_FEAT_CONTACT_HISTORY,
     DOMG "[material]\nkn = 1e4\ntangential = spring\nmu = 0.5\n" SP INIT,
     3.0, 2, 40},
    {"periodic", GR_FEAT_PERIODIC, BOX "left = periodic\nright = periodic\n" MAT SP INIT, 4.0, 2, 40},
    {"open", GR_FEAT_OPEN_SIDE, BOX "top = open\n" MAT SP INIT, 4.0, 2, 40},
    {"segments", GR_FEAT_SEGMENTS, DOMG MAT SP INIT "region = 1 6 19 19\n[wall.a]\nfrom = 0 4\nto = 20 1\n",
     3.0, 2, 40},
    {"wall-grains", GR_FEAT_WALL_GRAINS,
     DOMG MAT SP INIT "[silo]\nheight = 15\nbase = 2\norifice = 3\nwalls = grains\n", 3.0, 2, 40},
    {"gate", GR_FEAT_ORIFICE,
     DOMG MAT SP INIT "region = 4 4 16 12\n[silo]\nheight = 15\nbase = 3\norifice = 4\nopen_time = 1.5\n", 3.0, 2, 40},
    {"vibrating", GR_FEAT_VIBRATING_FLOOR,
     DOMG MAT SP INIT "region = 1 1 19 6\n[floor]\nmotion = sine\namplitude = 0.1\nomega = 10\n", 4.0, 2, 40},
    {"reinsert", GR_FEAT_REINSERT,
     DOMG MAT SP INIT "region = 4 4 16 12\n[silo]\nheight = 15\nbase = 3\norifice = 4\nopen_time = 0\nreinsert = yes\n", 6.0, 2, 40},
    {"polydisperse", GR_FEAT_POLYDISPERSE,
     BOX MAT "[species]\ncount = 40\npolydispersity = 0.1\n" INIT, 4.0, 2, 40},
    {"mixture", GR_FEAT_MIXTURE,
     BOX MAT "[species.a]\ncount = 20\n[species.b]\ncount = 20\ndiameter = 0.8\n" INIT, 4.0, 2, 40},
    {"hertz", GR_FEAT_HERTZ,
     BOX "[material]\nkn = 1e4\ngamma_n = 5\nnormal = hertz\n" SP INIT, 4.0, 2, 40},
    {"weights", GR_FEAT_WEIGHTS, BOX MAT "[species]\ncount = 40\nweight = 25\n" INIT, 4.0, 2, 40},
    {"hf-floor", GR_FEAT_HF_FLOOR,
     DOMG MAT SP INIT "region = 1 1 19 6\n[floor]\nmotion = sine-hf\namplitude = 0.01\nomega = 100\n", 4.0, 2,
     40},
    /* a lattice state: random channel occupations, granular rules with
     * dissipation and rough walls on the closed sides */
    {"lattice", GR_FEAT_LATTICE,
     "[scene]\nseed = 3\n[domain]\nwidth = 20\nheight = 20\nleft = periodic\nright = periodic\n"
     "[init]\nkind = occupation\noccupation = 0.2\nrest_occupation = 0.1\n[lgca]\np = 0.2\nb = 0.5\n",
     4.0, 3, 4000},
};
const size_t conf_nscenes = sizeof conf_scenes / sizeof conf_scenes[0];
