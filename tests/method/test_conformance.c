/* Conformance of every registered backend to methods/method.h: the battery
 * (conformance.h) on gr_method_all() over the shipped scenes, so that a
 * backend is held to the contract the moment it is in the registry. */
#include "test.h"

#include <stdlib.h>

#include "conformance.h"

int main(void)
{
    const char *root = getenv("GRANO_SOURCE_ROOT");
    char docs[4096];
    snprintf(docs, sizeof docs, "%s/docs/methods", root ? root : ".");
    conf_battery b = {"conformance", gr_method_all(), conf_scenes, conf_nscenes, docs};
    return conf_run(&b) ? 1 : 0;
}
