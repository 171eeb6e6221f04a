/*
 * fuzz_args.c - libFuzzer target for the command line of every svet
 * subcommand (cmd/): the input is split at NUL bytes into arguments, the
 * first naming the subcommand (render, diff, converge); its
 * cmd_*_parse() must give CMD_RUN or an exit code, never a crash, a leak
 * or undefined behaviour. A command line that parses then has its output
 * names checked against its inputs (cmd_check_outputs, which looks the
 * names up with stat). Nothing is rendered, read or written.
 * `make fuzz-args`; fuzz/README.md has the runs.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAX_ARGS 512

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* one copy, NUL-terminated, cut into arguments at its NULs */
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    char *argv[MAX_ARGS + 1];
    int argc = 0;
    for (char *p = text; p <= text + size && argc < MAX_ARGS;) {
        argv[argc++] = p;
        p += strlen(p) + 1;
    }
    argv[argc] = NULL;
    if (!strcmp(argv[0], "render")) {
        cmd_render_args_t a;
        if (cmd_render_parse(argc, argv, &a) == CMD_RUN) {
            /* the PNG's default name, as svet render makes it */
            char *png = a.exr && !a.png ? cmd_replace_ext(a.exr, ".png")
                                        : NULL;
            const cmd_file_t outs[] = { { a.exr, "exr" },
                                        { a.png ? a.png : png, "png" },
                                        { a.var, "variance" } };
            const cmd_file_t ins[] = { { a.scene, "scene" } };
            cmd_check_outputs("render", outs, 3, ins, 1);
            free(png);
        }
    } else if (!strcmp(argv[0], "diff")) {
        cmd_diff_args_t a;
        if (cmd_diff_parse(argc, argv, &a) == CMD_RUN) {
            const cmd_file_t outs[] = { { a.err_path, "error image" } };
            const cmd_file_t ins[] = { { a.paths[0], "A" },
                                       { a.paths[1], "B" } };
            cmd_check_outputs("diff", outs, 1, ins, 2);
        }
    } else if (!strcmp(argv[0], "converge")) {
        cmd_converge_args_t a;
        if (cmd_converge_parse(argc, argv, &a) == CMD_RUN) {
            const cmd_file_t outs[] = { { a.pvalue, "p-values" },
                                        { a.out_dir, "directory" } };
            const cmd_file_t ins[] = { { a.ztest_img, "image" },
                                       { a.ztest_var, "variance" },
                                       { a.ref, "reference" },
                                       { a.ref_var, "its variance" },
                                       { a.script, "script" } };
            cmd_check_outputs("converge", outs, 2, ins, 5);
        }
    }
    free(text);
    return 0;
}
