/*
 * test_chapters.c - the chapter programs' command lines and the CSV files
 * their figures are drawn from (chapters/chapter.h, chapters/chNN/):
 * each answers --help, refuses an unknown option or a second directory
 * with exit status 2 and writes nothing, and writes its CSV files with
 * their header rows; a few values are checked against the book. The
 * programs are the ones built beside this suite (<build>/ch01_brdf for
 * <build>/tests/test_chapters), run small.
 */
#include "testutil.h"

#include <dirent.h>
#include <libgen.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *const PROGS[] = {
    "ch01_brdf", "ch01_geometry", "ch02_colour", "ch03_estimator",
    "ch04_montecarlo", "ch05_cases", "ch06_display", "ch07_grids",
    "ch08_photons",
    "ch09_irradiance",
    "ch10_textures",
    "ch11_media",
};
#define NPROGS ((int)(sizeof PROGS / sizeof PROGS[0]))

#define PI_D 3.14159265358979323846

static char out[65536];

/* <build>/NAME, the program built beside this suite. */
static const char *prog(const char *name)
{
    static char path[1100];
    char self[1024];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    ck_assert(n > 0);
    self[n] = '\0';
    snprintf(path, sizeof path, "%s/../%s", dirname(self), name);
    ck_assert_msg(access(path, X_OK) == 0, "%s is not built (make chapters)",
                  path);
    return path;
}

/* Run `NAME ARGS` in directory cwd (NULL: the top directory) and return
 * its exit status; stdout and stderr go to out. */
static int run_in(const char *cwd, const char *name, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "%s%s%s'%s' %s 2>&1", cwd ? "cd '" : "",
             cwd ? cwd : "", cwd ? "' && " : "", prog(name), args);
    FILE *p = popen(cmd, "r");
    ck_assert_ptr_nonnull(p);
    size_t n = fread(out, 1, sizeof out - 1, p);
    out[n] = '\0';
    while (fread(cmd, 1, sizeof cmd, p) > 0) /* the rest, unread */
        ;
    int status = pclose(p);
    ck_assert(WIFEXITED(status));
    return WEXITSTATUS(status);
}

static int run(const char *name, const char *args)
{
    return run_in(NULL, name, args);
}

/* A fresh empty directory under /tmp (left for the system to clean when
 * a test fails; removed by rm_dir when it passes). */
static const char *scratch(void)
{
    static char dir[64];
    snprintf(dir, sizeof dir, "/tmp/svet-chapters-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    return dir;
}

static void rm_dir(const char *dir)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}

/* The number of entries of dir besides . and .. */
static int entries(const char *dir)
{
    DIR *d = opendir(dir);
    ck_assert_ptr_nonnull(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return n;
}

/* The CSV file dir/name: its lines, the '#' comments skipped; lines[0] is
 * the header row. Returns the number of lines (at most max). */
static char csv_buf[1 << 22];
static int read_csv(const char *dir, const char *name, char **lines, int max)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "%s was not written", path);
    size_t n = fread(csv_buf, 1, sizeof csv_buf - 1, f);
    csv_buf[n] = '\0';
    fclose(f);
    ck_assert_msg(csv_buf[0] == '#', "%s does not open with a comment", path);
    int k = 0;
    for (char *s = strtok(csv_buf, "\n"); s && k < max; s = strtok(NULL, "\n"))
        if (s[0] != '#')
            lines[k++] = s;
    ck_assert_msg(k >= 2, "%s has no data rows", path);
    return k;
}

/* Field i (from 0) of a CSV line, as a number. */
static double field(const char *line, int i)
{
    const char *p = line;
    for (int k = 0; k < i; k++) {
        p = strchr(p, ',');
        ck_assert_msg(p != NULL, "no field %d in '%s'", i, line);
        p++;
    }
    return strtod(p, NULL);
}

static char *lines[200000];

/* Run `NAME DIR EXTRA` from the top directory into a fresh directory,
 * which is returned; the run must succeed. */
static const char *run_small(const char *name, const char *extra)
{
    const char *dir = scratch();
    char args[512];
    snprintf(args, sizeof args, "%s %s", dir, extra);
    ck_assert_msg(run(name, args) == 0, "%s %s:\n%.2000s", name, args, out);
    return dir;
}

START_TEST(every_program_answers_help)
{
    const char *dir = scratch();
    for (int i = 0; i < NPROGS; i++) {
        ck_assert_msg(run_in(dir, PROGS[i], "--help") == 0,
                      "%s --help:\n%.2000s", PROGS[i], out);
        ck_assert_msg(strstr(out, "usage: ") != NULL, "%s --help:\n%.2000s",
                      PROGS[i], out);
        ck_assert_int_eq(run_in(dir, PROGS[i], "-h"), 0);
        ck_assert_msg(entries(dir) == 0, "%s --help wrote into %s", PROGS[i],
                      dir);
    }
    rm_dir(dir);
}
END_TEST

/* Every program, run with args in an empty directory, exits 2 with a
 * message that holds `named` (unless NULL) and writes nothing there. */
static void every_program_refuses(const char *args, const char *named)
{
    const char *dir = scratch();
    for (int i = 0; i < NPROGS; i++) {
        ck_assert_msg(run_in(dir, PROGS[i], args) == 2, "%s %s:\n%.2000s",
                      PROGS[i], args, out);
        ck_assert_msg(!named || strstr(out, named), "%s %s:\n%.2000s",
                      PROGS[i], args, out);
        ck_assert_msg(entries(dir) == 0, "%s %s wrote into %s", PROGS[i],
                      args, dir);
    }
    rm_dir(dir);
}

START_TEST(every_program_refuses_an_unknown_option_and_writes_nothing)
{
    every_program_refuses("--bogus", "--bogus");
    every_program_refuses("here --bogus 1", "--bogus");
    every_program_refuses("-x", "-x");
}
END_TEST

START_TEST(every_program_refuses_a_second_directory)
{
    every_program_refuses("one two", "two");
}
END_TEST

START_TEST(a_bad_value_is_refused)
{
    static const char *const bad[][3] = { /* program, option, value */
        { "ch01_brdf", "--samples", "" },
        { "ch01_brdf", "--samples", "0" },
        { "ch01_brdf", "--samples", "1e3x" },
        { "ch03_estimator", "--paths", "-1" },
        { "ch04_montecarlo", "--kmax", "11" },
        { "ch07_grids", "--width", "-4" },
        { "ch10_textures", "--size", "8" },
        { "ch09_irradiance", "--ref-spp", "0" },
    };
    const char *dir = scratch();
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char args[256];
        snprintf(args, sizeof args, "%s/sub %s %s", dir, bad[i][1], bad[i][2]);
        ck_assert_msg(run(bad[i][0], args) == 2, "%s %s:\n%.2000s",
                      bad[i][0], args, out);
        ck_assert_msg(strstr(out, bad[i][1]) != NULL, "%s %s: the message "
                      "does not name the option:\n%.2000s", bad[i][0], args,
                      out);
        ck_assert_msg(entries(dir) == 0, "%s %s wrote into %s", bad[i][0],
                      args, dir);
    }
    rm_dir(dir);
}
END_TEST

START_TEST(ch01_brdf_writes_the_lobes_and_the_schlick_curves)
{
    const char *dir = run_small("ch01_brdf", "--samples 200");

    int n = read_csv(dir, "ch01_lobe_lambert.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "theta_r_deg,f_lambert,fcos_lambert");
    ck_assert_int_eq(n, 1 + 719);
    for (int i = 1; i < n; i++) { /* Lambert (1.5): f = rho / pi */
        double t = field(lines[i], 0) * PI_D / 180;
        ck_assert_near(field(lines[i], 1), 1 / PI_D, 1e-5);
        ck_assert_near(field(lines[i], 2), cos(t) / PI_D, 1e-5);
    }
    read_csv(dir, "ch01_lobe_phong.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "theta_r_deg,f_e1,fcos_e1,f_e10,fcos_e10,"
                               "f_e100,fcos_e100");
    read_csv(dir, "ch01_lobe_ward.csv", lines, 1000);
    read_csv(dir, "ch01_lobe_ward_bounded.csv", lines, 1000);
    read_csv(dir, "ch01_lobe_ward_aniso.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "theta_r_deg,f_u,fcos_u,f_v,fcos_v");

    n = read_csv(dir, "ch01_schlick.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "theta_deg,rho_s_0.04,rho_s_0.2,rho_s_0.5,"
                               "rho_s_0.9,rho_t_0.96");
    /* (1.7) at normal incidence is rho_s(0); at grazing incidence 1 */
    const double rho0[4] = { 0.04, 0.2, 0.5, 0.9 };
    for (int k = 0; k < 4; k++) {
        ck_assert_near(field(lines[1], k + 1), rho0[k], 1e-6);
        ck_assert_near(field(lines[n - 1], k + 1), 1, 1e-6);
    }
    ck_assert_near(field(lines[1], 5), 0.96, 1e-6);

    read_csv(dir, "ch01_albedo.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "model,param,value,theta_deg,albedo,stderr");
    rm_dir(dir);
}
END_TEST

START_TEST(ch02_writes_the_diagram_the_ramp_and_the_errors)
{
    const char *dir = run_small("ch02_colour", "");
    int n = read_csv(dir, "ch02_locus.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "lambda_nm,x,y");
    ck_assert_int_eq(n, 1 + 471); /* 360 to 830 nm */
    read_csv(dir, "ch02_planck.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "T_K,x,y");
    read_csv(dir, "ch02_points.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "name,x,y");
    n = read_csv(dir, "ch02_gamut.csv", lines, 1000);
    ck_assert_int_eq(n, 1 + 4);
    ck_assert_str_eq(lines[1], lines[4]); /* the triangle is closed */
    read_csv(dir, "ch02_fill.csv", lines, 100000);
    ck_assert_str_eq(lines[0], "x,y,r,g,b");
    read_csv(dir, "ch02_blackbody.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "T_K,x,y,r,g,b");
    n = read_csv(dir, "ch02_white_balance.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "method,mean_delta_e,max_delta_e");
    ck_assert_int_eq(n, 1 + 4);
    /* Bradford (the last row) corrects better than no correction */
    ck_assert(field(lines[4], 1) < field(lines[1], 1));
    rm_dir(dir);
}
END_TEST

START_TEST(ch03_writes_its_convergence)
{
    const char *dir = run_small("ch03_estimator", "--paths 100");
    int n = read_csv(dir, "ch03_convergence.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "N,mean,stderr,sqrt_var");
    ck_assert_int_eq(n, 1 + 8); /* 1, 2, 4, ..., 64, and the last, 100 */
    ck_assert_near(field(lines[n - 1], 0), 100, 0);
    rm_dir(dir);
}
END_TEST

START_TEST(ch04_writes_the_error_against_n_and_the_roulette)
{
    const char *dir = run_small("ch04_montecarlo", "--kmax 3 --paths 1000");
    int n = read_csv(dir, "ch04_irradiance.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "N,uniform,cosine,matched,strat. uniform,"
                               "strat. cosine");
    ck_assert_int_eq(n, 1 + 4); /* N = 1, 4, 16, 64 */
    for (int i = 1; i < n; i++) /* p proportional to f: exact to rounding */
        ck_assert(field(lines[i], 3) < 1e-5);
    read_csv(dir, "ch04_sine.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "N,uniform,importance,stratified,"
                               "strat. importance");
    read_csv(dir, "ch04_roulette.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "strategy,parameter,mean,bias,variance,"
                               "variance_exact,vertices_per_path,efficiency");
    rm_dir(dir);
}
END_TEST

START_TEST(ch05_writes_its_table)
{
    const char *dir = run_small("ch05_cases", "--spp 1 --ref-factor 2 "
                                "--scale 0.05 --cases point");
    int n = read_csv(dir, "table.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "case,strategy,spp,seconds,rmse,relmse,relvar,"
                               "noise_ratio,efficiency_vs_path");
    ck_assert_int_eq(n, 1 + 3); /* bsdf, nee, path */
    ck_assert_ptr_nonnull(strstr(lines[3], "point,path,1,"));
    rm_dir(dir);
}
END_TEST

START_TEST(ch06_writes_the_curve_and_the_histogram)
{
    const char *dir = run_small("ch06_display", "");
    int n = read_csv(dir, "ch06_trc_curve.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "lw,ld_adjusted,slope_adjusted,ld_naive,"
                               "slope_naive");
    for (int i = 2; i < n; i++) /* never steeper than a linear map */
        ck_assert(field(lines[i], 2) <= 1 + 1e-6);
    read_csv(dir, "ch06_trc_bins.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "bin,lw_lo,lw_hi,raw,trimmed");
    rm_dir(dir);
}
END_TEST

START_TEST(ch07_writes_its_heat_maps_and_makes_its_directory)
{
    const char *top = scratch();
    char dir[256], args[300];
    snprintf(dir, sizeof dir, "%s/new/dir", top);
    snprintf(args, sizeof args, "%s --width 8", dir);
    ck_assert_msg(run("ch07_grids", args) == 0, "%.2000s", out);
    const char *names[4] = { "spheres_grid", "spheres_hgrid", "stadium_grid",
                             "stadium_hgrid" };
    for (int k = 0; k < 4; k++) {
        char name[64];
        snprintf(name, sizeof name, "ch07_%s_cells.csv", names[k]);
        int n = read_csv(dir, name, lines, 1000);
        ck_assert_int_eq(n, 6); /* 8 x 6 pixels, no header row: a matrix */
        for (int i = 0; i < n; i++) /* a count of cells per pixel */
            ck_assert(field(lines[i], 7) >= 0);
    }
    rm_dir(top);
}
END_TEST

START_TEST(ch09_writes_the_row_and_the_error_against_a)
{
    const char *dir = run_small("ch09_irradiance",
                                "--scale 0.05 --spp 1 --ref-spp 4");
    int n = read_csv(dir, "row.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "x,gradients,no_gradients,path");
    ck_assert_int_eq(n, 1 + 12); /* 256 x 0.05 pixels */
    n = read_csv(dir, "error.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "a,records,rel_rmse,records_no_gradients,"
                               "rel_rmse_no_gradients");
    ck_assert_int_eq(n, 1 + 5);
    /* a falls down the table, and a smaller a takes at least as many
     * records (a record is valid over a radius proportional to a) */
    for (int i = 2; i < n; i++) {
        ck_assert(field(lines[i], 0) < field(lines[i - 1], 0));
        ck_assert(field(lines[i], 1) >= field(lines[i - 1], 1));
    }
    ck_assert(field(lines[n - 1], 1) > field(lines[1], 1));
    rm_dir(dir);
}
END_TEST

START_TEST(ch10_writes_the_grazing_errors_and_the_noise)
{
    const char *dir = run_small("ch10_textures", "--size 16");
    int n = read_csv(dir, "ch10_grazing.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "row,nearest,bilinear,trilinear");
    ck_assert_int_eq(n, 1 + 64);
    n = read_csv(dir, "ch10_noise.csv", lines, 1000);
    ck_assert_str_eq(lines[0], "x,noise,dnoise_dx,central");
    /* the analytic derivative against the central difference, whose
     * rounding in float is about 1e-7 / 2e-3 = 5e-5 */
    for (int i = 1; i < n; i++)
        ck_assert(fabs(field(lines[i], 2) - field(lines[i], 3)) < 1e-3);
    rm_dir(dir);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("chapters");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, every_program_answers_help);
    tcase_add_test(tc, every_program_refuses_an_unknown_option_and_writes_nothing);
    tcase_add_test(tc, every_program_refuses_a_second_directory);
    tcase_add_test(tc, a_bad_value_is_refused);
    tcase_add_test(tc, ch01_brdf_writes_the_lobes_and_the_schlick_curves);
    tcase_add_test(tc, ch02_writes_the_diagram_the_ramp_and_the_errors);
    tcase_add_test(tc, ch03_writes_its_convergence);
    tcase_add_test(tc, ch04_writes_the_error_against_n_and_the_roulette);
    tcase_add_test(tc, ch05_writes_its_table);
    tcase_add_test(tc, ch06_writes_the_curve_and_the_histogram);
    tcase_add_test(tc, ch07_writes_its_heat_maps_and_makes_its_directory);
    tcase_add_test(tc, ch09_writes_the_row_and_the_error_against_a);
    tcase_add_test(tc, ch10_writes_the_grazing_errors_and_the_noise);
    suite_add_tcase(s, tc);
    return s;
}
