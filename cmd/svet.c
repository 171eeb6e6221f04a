/*
 * svet.c - main() of the svet command: a table of subcommands, each in its
 * own cmd/<name>.c (declared in cmd.h), plus `svet --help` and
 * `svet help NAME`. Adding a subcommand is one line in `commands` below.
 * Tests: tests/cmd/test_svet.c (runs the built command)
 */
#include <stdio.h>
#include <string.h>

#include "cmd.h"

typedef struct {
    const char *name;
    const char *summary;                /* one line for `svet --help` */
    int (*run)(int argc, char **argv);  /* argv[0] is the subcommand name */
    void (*help)(FILE *f);              /* the text of `svet help NAME` */
} subcommand_t;

static const subcommand_t commands[] = {
    { "render", "render a scene file to a linear EXR and a tone-mapped PNG",
      cmd_render, cmd_render_help },
    { "merge", "merge the parts of a split render (--samples, --crop) "
               "into one image", cmd_merge, cmd_merge_help },
    { "diff", "compare two images (EXR, PFM, PNG, PPM): RMSE, relMSE, MAE, "
              "PSNR, max",
      cmd_diff, cmd_diff_help },
    { "converge", "error against time of a render, against a converged "
                  "reference (CSV, plot)", cmd_converge, cmd_converge_help },
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

static void usage(FILE *f)
{
    fprintf(f, "usage: svet COMMAND [options]\n"
               "       svet help COMMAND\n"
               "\n"
               "svet is the teaching renderer of \"Introduction to "
               "Photorealistic Graphics\".\n"
               "\n"
               "commands:\n");
    for (int i = 0; i < NCOMMANDS; i++)
        fprintf(f, "  %-8s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\n"
               "exit codes (every command):\n"
               "  0  success\n"
               "  1  bad command line (usage error), or an output that is "
               "the same file as\n"
               "     another output or an input\n"
               "  2  an input file is missing, unreadable or malformed, or "
               "the inputs do not fit\n"
               "     together (e.g. images of different sizes)\n"
               "  3  an output file could not be written, or is read-only "
               "(the earlier files\n"
               "     of that name are kept, all of them)\n"
               "  4  svet render: interrupted (SIGINT/SIGTERM); the last "
               "completed pass was\n"
               "     written\n"
               "  5  svet diff --fail-above: the images differ by more than "
               "the threshold;\n"
               "     svet converge --ztest: the image fails the Z-test "
               "against the reference\n"
               "  6  svet render: a pass of the render failed (out of "
               "memory, or a rendering\n"
               "     method's pass, e.g. ppm's photon maps); the passes "
               "before it were kept\n"
               "     only if --checkpoint wrote them\n"
               "\n"
               "svet help COMMAND, or svet COMMAND --help, describes one "
               "command; docs/output.md\n"
               "says how output files are written.\n");
}

static const subcommand_t *find(const char *name)
{
    for (int i = 0; i < NCOMMANDS; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

static int unknown(const char *name)
{
    fprintf(stderr, "svet: unknown command '%s'; the commands are:", name);
    for (int i = 0; i < NCOMMANDS; i++)
        fprintf(stderr, " %s", commands[i].name);
    fprintf(stderr, " (svet --help)\n");
    return SVET_EXIT_USAGE;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return SVET_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help")) {
        usage(stdout);
        return SVET_EXIT_OK;
    }
    if (!strcmp(cmd, "help")) {
        if (argc < 3) {
            usage(stdout);
            return SVET_EXIT_OK;
        }
        const subcommand_t *c = find(argv[2]);
        if (!c)
            return unknown(argv[2]);
        c->help(stdout);
        return SVET_EXIT_OK;
    }
    const subcommand_t *c = find(cmd);
    if (!c)
        return unknown(cmd);
    return c->run(argc - 1, argv + 1);
}
