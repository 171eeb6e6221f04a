/*
 * fuzz_args.c - libFuzzer target for the command line of every svet
 * subcommand (cmd/): the input is split at NUL bytes into arguments, the
 * first naming the subcommand (render, diff, converge); its
 * cmd_*_parse() must give CMD_RUN or an exit code, never a crash, a leak
 * or undefined behaviour. Nothing is rendered or read: parsing only.
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
        cmd_render_parse(argc, argv, &a);
    } else if (!strcmp(argv[0], "diff")) {
        cmd_diff_args_t a;
        cmd_diff_parse(argc, argv, &a);
    } else if (!strcmp(argv[0], "converge")) {
        cmd_converge_args_t a;
        cmd_converge_parse(argc, argv, &a);
    }
    free(text);
    return 0;
}
