/*
 * fuzz_scene.c - libFuzzer target for the scene file reader (scenefile.h):
 * any bytes must give SVET_OK or an error message, never a crash, a hang,
 * a leak or undefined behaviour. Bytes after the first NUL are split at
 * further NULs into command-line overrides ("spp=64") applied to the
 * parsed scene. `make fuzz-scene`; fuzz/README.md has the runs.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "render/allparts.h"
#include "render/scenefile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    const char *nul = memchr(text, '\0', size);
    size_t len = nul ? (size_t)(nul - text) : size;
    scene_t s;
    svet_error err;
    /* Mesh files resolve against tests/data/scene, where the corpus's
     * small OBJ files live (run from the top directory). */
    if (scenefile_parse_with(&s, text, len, "fuzz.scn", "tests/data/scene",
                             scene_features_all(), &err) == SVET_OK &&
        nul) {
        const char *p = nul + 1, *end = text + size;
        char setting[256];
        while (p < end) {
            const char *q = memchr(p, '\0', (size_t)(end - p));
            size_t n = (size_t)((q ? q : end) - p);
            if (n >= sizeof setting)
                n = sizeof setting - 1;
            memcpy(setting, p, n);
            setting[n] = '\0';
            scenefile_override(&s, setting, &err);
            p = q ? q + 1 : end;
        }
    }
    scene_free(&s);
    return 0;
}
