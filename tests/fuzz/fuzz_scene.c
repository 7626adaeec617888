/* libFuzzer target: the scene reader on any bytes. It must return a scene
 * or GR_EINPUT with a message naming the file, never crash, hang or leak. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const extra[] = {"dem", "edmd", "cd", "dsmc", NULL};
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
