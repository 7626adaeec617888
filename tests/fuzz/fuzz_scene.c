/* libFuzzer target: the scene reader on any bytes. It must return a scene
 * or GR_EINPUT with a message naming the file, never crash, hang or leak.
 * The backends' sections are the registered names, which run_fuzz.sh takes
 * from `grano methods` into GR_FUZZ_SECTIONS ("dem,edmd,..."): this target
 * links the scene reader alone, not the registry. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#ifndef GR_FUZZ_SECTIONS
#error "build with -DGR_FUZZ_SECTIONS=\"name,name,...\" (run_fuzz.sh does)"
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char names[] = GR_FUZZ_SECTIONS;
    const char *extra[64];
    size_t k = 0;
    char *save = NULL;
    for (char *tok = strtok_r(names, ",", &save); tok && k + 1 < sizeof extra / sizeof extra[0];
         tok = strtok_r(NULL, ",", &save))
        extra[k++] = tok;
    extra[k] = NULL;
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    gr_err e = {0};
    gr_scene *sc = gr_scene_parse(text, "fuzz.ini", extra, &e);
    if (!sc && (e.code != GR_EINPUT || !strstr(e.msg, "fuzz.ini")))
        abort(); /* a refusal must be bad input and name the file */
    gr_scene_free(sc);
    free(text);
    return 0;
}
