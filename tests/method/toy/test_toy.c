/* The conformance battery on a backend registered only here: toy.c, with
 * its docs page beside it (toy.md). Nothing in common/, methods/ or the
 * battery names it. */
#include "test.h"

#include <stdlib.h>

#include "conformance.h"

extern const gr_method_type toy_method;

int main(void)
{
    static const gr_method_type *const mine[] = {&toy_method, NULL};
    const char *root = getenv("GRANO_SOURCE_ROOT");
    char docs[4096];
    snprintf(docs, sizeof docs, "%s/tests/method/toy", root ? root : ".");
    conf_battery b = {"conformance-toy", mine, conf_scenes, conf_nscenes, docs};
    return conf_run(&b) ? 1 : 0;
}
