/* Golden vectors written by the Python reference (host/forceskill) into tests/vectors/:
 *  manifest.txt      lines "<skill file> <goal_scale> <time_scale> <rollout csv>" (paths relative
 *                    to tests/vectors, '#' comments): parse the image, roll it out as
 *                    docs/math.md section 2 says, compare with the CSV ("t,f_hat" header) within
 *                    1e-6 of max|f| (double build) or 1e-4 (float build);
 *  manifest_y.txt    lines "<skill> <goal_scale> <time_scale> <path_scale> <csv>": skills with
 *                    the y DMP, rolled out by dmp_step_xy (one step of both DMPs), compared
 *                    with "t,f_hat,y_hat" within the same tolerances (y_hat = y_start + p, error
 *                    relative to max|p|, the path's extent from its start);
 *  manifest_periodic.txt  lines "<skill> <goal_scale> <amplitude_scale> <time_scale> <cycles>
 *                    <csv>": periodic skills (format v4), rolled out by dmp_periodic_step from
 *                    dmp_periodic_reset (docs/math.md section 5), the same tolerances;
 *  manifest_periodic_y.txt  lines "<skill> <goal> <amplitude> <time> <cycles> <path_scale>
 *                    <csv>": periodic skills with the y path, rolled out by
 *                    dmp_periodic_step_xy from dmp_periodic_reset_xy against "t,f_hat,y_hat",
 *                    the same tolerances (the path's error relative to max|p|, p = y - y_start);
 *  manifest_contact.txt  lines "<skill> <goal> <amplitude> <time> <threshold_N> <tau_s> <hold_s>
 *                    <csv>": the contact wait (dmp_contact_rate) driving either DMP from the
 *                    CSV's measured force ("t,f_contact,rate,f_hat"), the same tolerances on
 *                    f_hat, on the rate and (relative) on the hold;
 *  bad/manifest.txt  lines "<file> <expected code>" (paths relative to tests/vectors/bad):
 *                    skill_parse must return exactly that code.
 * A missing manifest is a failure, not a skip. FS_VECTORS_DIR comes from CMake. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "skill.h"

#ifndef FS_VECTORS_DIR
#error "FS_VECTORS_DIR must be defined"
#endif

#ifdef FS_REAL_FLOAT
#define BUILD_NAME "float"
#define REL_TOL 1e-4
#define T_REL_TOL 1e-6 /* dt rounded to float */
#else
#define BUILD_NAME "double"
#define REL_TOL 1e-6
#define T_REL_TOL 1e-12
#endif

#define MAX_IMAGE 65536u
#define MAX_ROWS 4000000L

static uint8_t image[MAX_IMAGE];
static skill_t sk;

static long read_file(const char *path, uint8_t *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return -1;
    }
    const size_t n = fread(buf, 1, cap, f);
    const int more = (fgetc(f) != EOF);
    fclose(f);
    return more ? -2 : (long)n;
}

/* Split a manifest line into whitespace-separated fields; returns the count (0 for blank or
 * comment lines). */
static int split(char *line, char **field, int max)
{
    char *hash = strchr(line, '#');
    if (hash != NULL) {
        *hash = '\0';
    }
    int n = 0;
    char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') {
            *p++ = '\0';
        }
        if (*p == '\0') {
            return n;
        }
        if (n == max) {
            return max + 1;
        }
        field[n++] = p;
        while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n') {
            p++;
        }
    }
}

static double check_rollout(const char *dir, const char *skill_file, double goal_scale,
                            double time_scale, const char *csv_file)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", dir, skill_file);
    const long len = read_file(path, image, MAX_IMAGE);
    if (len < 0) {
        fail_msg("cannot read skill %s", path);
    }
    const fs_status_t st = skill_parse(image, (uint32_t)len, &sk);
    if (st != FS_OK) {
        fail_msg("%s: skill_parse (%s) returned %d", path, BUILD_NAME, (int)st);
    }
    snprintf(path, sizeof(path), "%s/%s", dir, csv_file);
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fail_msg("cannot read rollout %s", path);
    }
    char line[256];
    if (fgets(line, sizeof(line), f) == NULL || strncmp(line, "t,f_hat", 7) != 0) {
        fclose(f);
        fail_msg("%s: header is not 't,f_hat'", path);
    }
    const dmp_run_t run = {(fs_real_t)goal_scale, (fs_real_t)time_scale};
    assert_int_equal(dmp_run_validate(&run), FS_OK);
    const double dt = (double)sk.dmp.dt_s;
    const long n_steps = lround((double)sk.dmp.duration_s * time_scale / dt);
    dmp_state_t s;
    dmp_state_reset(&s);
    long row = 0;
    double err_max = 0.0, f_max = 0.0;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        const double t = strtod(line, &end);
        if (end == line || *end != ',') {
            fclose(f);
            fail_msg("%s: bad row %ld", path, row);
        }
        const double f_ref = strtod(end + 1, NULL);
        if (row > n_steps) {
            fclose(f);
            fail_msg("%s: more than %ld rows", path, n_steps + 1);
        }
        if (fabs(t - (double)row * dt) > T_REL_TOL * (1.0 + t)) {
            fclose(f);
            fail_msg("%s: row %ld has t = %.17g, expected %.17g", path, row, t, (double)row * dt);
        }
        const double f_c = (row == 0) ? (double)sk.dmp.force0_N
                                      : (double)dmp_step(&sk.dmp, &s, &run, NULL);
        err_max = fmax(err_max, fabs(f_c - f_ref));
        f_max = fmax(f_max, fabs(f_ref));
        row++;
    }
    fclose(f);
    if (row != n_steps + 1) {
        fail_msg("%s: %ld rows, expected %ld", path, row, n_steps + 1);
    }
    assert_true(f_max > 0.0);
    const double rel = err_max / f_max;
    printf("[%s] %s gs=%g ts=%g: %ld rows, max|f| %.4f N, max err %.3g of max|f|\n", BUILD_NAME,
           skill_file, goal_scale, time_scale, row, f_max, rel);
    if (!(rel <= REL_TOL)) {
        fail_msg("%s (%s): max error %.3g of max|f| exceeds %.1g", csv_file, BUILD_NAME, rel,
                 REL_TOL);
    }
    return rel;
}

/* Every line of the manifest `name` in tests/vectors with exactly n_fields fields through
 * check (blank and comment lines skipped, a malformed line fails); returns the worst value check
 * returned, *count the number of lines. */
static double for_each_manifest_line(const char *name, int n_fields,
                                     double (*check)(const char *dir, char *const *fld), int *count)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", FS_VECTORS_DIR, name);
    FILE *m = fopen(path, "r");
    if (m == NULL) {
        fail_msg("missing %s (the Python side writes the golden vectors)", path);
    }
    char line[1024];
    double worst = 0.0;
    *count = 0;
    while (fgets(line, sizeof(line), m) != NULL) {
        char *fld[8];
        const int n = split(line, fld, n_fields);
        if (n == 0) {
            continue;
        }
        if (n != n_fields) {
            fclose(m);
            fail_msg("%s: malformed line (%d fields)", path, n);
        }
        worst = fmax(worst, check(FS_VECTORS_DIR, fld));
        (*count)++;
    }
    fclose(m);
    return worst;
}

static double check_rollout_line(const char *dir, char *const *fld)
{
    return check_rollout(dir, fld[0], strtod(fld[1], NULL), strtod(fld[2], NULL), fld[3]);
}

/* One manifest_band line: the parsed band's points against the points CSV, then skill_band_at
 * at every row of the rollout CSV (t,f_hat,f_band_lo,f_band_hi) against its bounds; returns the
 * worst difference in N relative to the largest |bound|. */
static double check_band(const char *dir, char *const *fld)
{
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", dir, fld[0]);
    const long len = read_file(path, image, MAX_IMAGE);
    assert_true(len > 0);
    assert_int_equal(skill_parse(image, (uint32_t)len, &sk), FS_OK);
    assert_true(sk.band_n >= SKILL_BAND_MIN_POINTS);
    const double gs = strtod(fld[1], NULL);
    const double ts = strtod(fld[2], NULL);
    char line[512];
    double worst = 0.0, b_max = 0.0;
    snprintf(path, sizeof(path), "%s/%s", dir, fld[3]);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    assert_non_null(fgets(line, sizeof(line), f));
    uint32_t j = 0u;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        const double lo = strtod(line, &end);
        const double hi = strtod(end + 1, NULL);
        assert_true(j < sk.band_n);
        worst = fmax(worst,
                     fmax(fabs(lo - (double)sk.band_lo_N[j]), fabs(hi - (double)sk.band_hi_N[j])));
        b_max = fmax(b_max, fmax(fabs(lo), fabs(hi)));
        j++;
    }
    fclose(f);
    assert_int_equal(j, sk.band_n);
    snprintf(path, sizeof(path), "%s/%s", dir, fld[4]);
    f = fopen(path, "r");
    assert_non_null(f);
    assert_non_null(fgets(line, sizeof(line), f));
    assert_int_equal(strncmp(line, "t,f_hat,f_band_lo,f_band_hi", 27), 0);
    const double period = (double)sk.dmp.duration_s * ts;
    long rows = 0;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        const double t = strtod(line, &end);
        (void)strtod(end + 1, &end);
        const double lo = strtod(end + 1, &end);
        const double hi = strtod(end + 1, NULL);
        fs_real_t lo_c = FS_R(0.0), hi_c = FS_R(0.0);
        assert_int_equal(
            skill_band_at(&sk, (fs_real_t)(t / period), (fs_real_t)gs, FS_R(1.0), &lo_c, &hi_c),
            FS_OK);
        worst = fmax(worst, fmax(fabs(lo - (double)lo_c), fabs(hi - (double)hi_c)));
        rows++;
    }
    fclose(f);
    assert_true(rows > 100 && b_max > 0.0);
    const double rel = worst / b_max;
    printf("[%s] %s band of %u points, %ld rows at gs=%g ts=%g: max err %.3g of max|bound|\n",
           BUILD_NAME, fld[0], (unsigned)sk.band_n, rows, gs, ts, rel);
    if (!(rel <= REL_TOL)) {
        fail_msg("%s (%s): band error %.3g exceeds %.1g", fld[0], BUILD_NAME, rel, REL_TOL);
    }
    return rel;
}

static void test_golden_band(void **state)
{
    (void)state;
    int count = 0;
    const double worst = for_each_manifest_line("manifest_band.txt", 5, check_band, &count);
    assert_true(count >= 2);
    printf("[%s] %d band vectors, worst %.3g\n", BUILD_NAME, count, worst);
    fs_real_t lo = FS_R(0.0), hi = FS_R(0.0);
    assert_int_equal(skill_band_at(NULL, FS_R(0.5), FS_R(1.0), FS_R(1.0), &lo, &hi),
                     FS_ERR_NULL_ARG);
    sk.band_n = 0u;
    assert_int_equal(skill_band_at(&sk, FS_R(0.5), FS_R(1.0), FS_R(1.0), &lo, &hi),
                     FS_ERR_SKILL_BAND);
}

static void test_golden_rollouts(void **state)
{
    (void)state;
    int count = 0;
    const double worst = for_each_manifest_line("manifest.txt", 4, check_rollout_line, &count);
    printf("[%s] %d golden rollouts, worst error %.3g of max|f| (tolerance %.0g)\n", BUILD_NAME,
           count, worst, REL_TOL);
    assert_true(count > 0);
}

/* One manifest_y line: the force and the path of dmp_step_xy against the CSV; returns the worst
 * of the two relative errors. */
static double check_rollout_xy(const char *dir, char *const *fld)
{
    char path[1024];
    const double gs = strtod(fld[1], NULL);
    const double ts = strtod(fld[2], NULL);
    const double ps = strtod(fld[3], NULL);
    snprintf(path, sizeof(path), "%s/%s", dir, fld[0]);
    const long len = read_file(path, image, MAX_IMAGE);
    if (len < 0 || skill_parse(image, (uint32_t)len, &sk) != FS_OK || sk.dmp.has_y != 1u) {
        fail_msg("%s: not a skill with a y DMP (%s)", path, BUILD_NAME);
    }
    snprintf(path, sizeof(path), "%s/%s", dir, fld[4]);
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fail_msg("cannot read rollout %s", path);
    }
    char line[256];
    if (fgets(line, sizeof(line), f) == NULL || strncmp(line, "t,f_hat,y_hat", 13) != 0) {
        fclose(f);
        fail_msg("%s: header is not 't,f_hat,y_hat'", path);
    }
    const dmp_run_t run = {(fs_real_t)gs, (fs_real_t)ts};
    const long n_steps = lround((double)sk.dmp.duration_s * ts / (double)sk.dmp.dt_s);
    dmp_state_t s;
    dmp_state_reset(&s);
    long row = 0;
    double ef = 0.0, fm = 0.0, ey = 0.0, pm = 0.0;
    const double y0 = (double)sk.dmp.y_start_m;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        (void)strtod(line, &end);
        char *end2 = NULL;
        const double f_ref = strtod(end + 1, &end2);
        const double y_ref = strtod(end2 + 1, NULL);
        double f_c = (double)sk.dmp.force0_N;
        double p_c = 0.0;
        if (row > 0) {
            fs_real_t p = FS_R(0.0);
            f_c = (double)dmp_step_xy(&sk.dmp, &s, &run, NULL, (fs_real_t)ps, &p);
            p_c = (double)p;
        }
        ef = fmax(ef, fabs(f_c - f_ref));
        fm = fmax(fm, fabs(f_ref));
        ey = fmax(ey, fabs((y0 + p_c) - y_ref));
        pm = fmax(pm, fabs(y_ref - y0));
        row++;
    }
    fclose(f);
    if (row != n_steps + 1) {
        fail_msg("%s: %ld rows, expected %ld", path, row, n_steps + 1);
    }
    assert_true(fm > 0.0 && pm > 0.0);
    printf("[%s] %s gs=%g ts=%g ps=%g: max err force %.3g of max|f|, path %.3g of max|p| "
           "(%.3g um)\n",
           BUILD_NAME, fld[0], gs, ts, ps, ef / fm, ey / pm, ey * 1e6);
    if (!(ef / fm <= REL_TOL) || !(ey / pm <= REL_TOL)) {
        fail_msg("%s (%s): force %.3g, path %.3g exceed %.1g", fld[4], BUILD_NAME, ef / fm, ey / pm,
                 REL_TOL);
    }
    return fmax(ef / fm, ey / pm);
}

static void test_golden_rollouts_y(void **state)
{
    (void)state;
    int count = 0;
    const double worst = for_each_manifest_line("manifest_y.txt", 5, check_rollout_xy, &count);
    printf("[%s] %d golden rollouts with a y DMP, worst error %.3g (tolerance %.0g)\n", BUILD_NAME,
           count, worst, REL_TOL);
    assert_true(count > 0);
}

static void test_golden_bad_images(void **state)
{
    (void)state;
    char dir[1024];
    snprintf(dir, sizeof(dir), "%s/bad", FS_VECTORS_DIR);
    char path[1100];
    snprintf(path, sizeof(path), "%s/manifest.txt", dir);
    FILE *m = fopen(path, "r");
    if (m == NULL) {
        fail_msg("missing %s (the Python side writes the bad-image vectors)", path);
    }
    char line[1024];
    int count = 0;
    while (fgets(line, sizeof(line), m) != NULL) {
        char *fld[2];
        const int n = split(line, fld, 2);
        if (n == 0) {
            continue;
        }
        if (n != 2) {
            fclose(m);
            fail_msg("%s: malformed line (%d fields)", path, n);
        }
        char file[1200];
        snprintf(file, sizeof(file), "%s/%s", dir, fld[0]);
        const long len = read_file(file, image, MAX_IMAGE);
        if (len < 0) {
            fclose(m);
            fail_msg("cannot read %s", file);
        }
        const int want = atoi(fld[1]);
        const fs_status_t got = skill_parse(image, (uint32_t)len, &sk);
        if ((int)got != want) {
            fclose(m);
            fail_msg("%s (%s): skill_parse returned %d, expected %d", fld[0], BUILD_NAME, (int)got,
                     want);
        }
        count++;
    }
    fclose(m);
    printf("[%s] %d bad images rejected with the expected codes\n", BUILD_NAME, count);
    assert_true(count > 0);
}

/* One manifest_periodic line: the periodic rollout of the skill at its scales against the CSV;
 * returns the relative error. */
static double check_rollout_periodic(const char *dir, char *const *fld)
{
    char path[1024];
    const double gs = strtod(fld[1], NULL);
    const double as = strtod(fld[2], NULL);
    const double ts = strtod(fld[3], NULL);
    const double cycles = strtod(fld[4], NULL);
    snprintf(path, sizeof(path), "%s/%s", dir, fld[0]);
    const long len = read_file(path, image, MAX_IMAGE);
    if (len < 0 || skill_parse(image, (uint32_t)len, &sk) != FS_OK ||
        sk.kind != SKILL_KIND_PERIODIC || sk.dmp.periodic != 1u) {
        fail_msg("%s: not a periodic skill this build parses (%s)", path, BUILD_NAME);
    }
    snprintf(path, sizeof(path), "%s/%s", dir, fld[5]);
    FILE *f = fopen(path, "r");
    if (f == NULL) {
        fail_msg("cannot read rollout %s", path);
    }
    char line[256];
    if (fgets(line, sizeof(line), f) == NULL || strncmp(line, "t,f_hat", 7) != 0) {
        fclose(f);
        fail_msg("%s: header is not 't,f_hat'", path);
    }
    const dmp_run_t run = {(fs_real_t)gs, (fs_real_t)ts};
    const long n_steps = lround(cycles * (double)sk.dmp.duration_s * ts / (double)sk.dmp.dt_s);
    dmp_state_t s;
    dmp_periodic_reset(&sk.dmp, &s, (fs_real_t)as);
    long row = 0;
    double err = 0.0, f_max = 0.0;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        (void)strtod(line, &end);
        const double f_ref = strtod(end + 1, NULL);
        const double f_c = (row == 0)
                               ? (double)(sk.dmp.force0_N + (fs_real_t)gs * sk.dmp.goal_N + s.y_N)
                               : (double)dmp_periodic_step(&sk.dmp, &s, &run, (fs_real_t)as, NULL);
        err = fmax(err, fabs(f_c - f_ref));
        f_max = fmax(f_max, fabs(f_ref));
        row++;
    }
    fclose(f);
    if (row != n_steps + 1) {
        fail_msg("%s: %ld rows, expected %ld", path, row, n_steps + 1);
    }
    assert_true(f_max > 0.0);
    printf("[%s] %s gs=%g as=%g ts=%g cycles=%g: %ld rows, max err %.3g of max|f|\n", BUILD_NAME,
           fld[0], gs, as, ts, cycles, row, err / f_max);
    if (!(err / f_max <= REL_TOL)) {
        fail_msg("%s (%s): max error %.3g of max|f| exceeds %.1g", fld[5], BUILD_NAME, err / f_max,
                 REL_TOL);
    }
    return err / f_max;
}

static void test_golden_rollouts_periodic(void **state)
{
    (void)state;
    int count = 0;
    const double worst = for_each_manifest_line("manifest_periodic.txt", 6, check_rollout_periodic,
                                                &count);
    printf("[%s] %d golden periodic rollouts, worst error %.3g of max|f| (tolerance %.0g)\n",
           BUILD_NAME, count, worst, REL_TOL);
    assert_true(count > 0);
}

/* One manifest_periodic_y line: the force and the y path of dmp_periodic_step_xy against the
 * CSV; returns the worst of the two relative errors. */
static double check_rollout_periodic_xy(const char *dir, char *const *fld)
{
    char path[1024];
    const double gs = strtod(fld[1], NULL), as = strtod(fld[2], NULL);
    const double ts = strtod(fld[3], NULL), cycles = strtod(fld[4], NULL);
    const fs_real_t ps = (fs_real_t)strtod(fld[5], NULL);
    snprintf(path, sizeof(path), "%s/%s", dir, fld[0]);
    const long len = read_file(path, image, MAX_IMAGE);
    if (len < 0 || skill_parse(image, (uint32_t)len, &sk) != FS_OK || sk.dmp.periodic != 1u ||
        sk.dmp.has_y != 1u) {
        fail_msg("%s: not a periodic skill with a y path this build parses (%s)", path, BUILD_NAME);
    }
    snprintf(path, sizeof(path), "%s/%s", dir, fld[6]);
    FILE *f = fopen(path, "r");
    char line[256];
    if (f == NULL || fgets(line, sizeof(line), f) == NULL ||
        strncmp(line, "t,f_hat,y_hat", 13) != 0) {
        fail_msg("%s: missing or its header is not 't,f_hat,y_hat'", path);
    }
    const dmp_run_t run = {(fs_real_t)gs, (fs_real_t)ts};
    const long n_steps = lround(cycles * (double)sk.dmp.duration_s * ts / (double)sk.dmp.dt_s);
    dmp_state_t s;
    dmp_periodic_reset_xy(&sk.dmp, &s, (fs_real_t)as, ps);
    long row = 0;
    double ef = 0.0, fm = 0.0, ey = 0.0, pm = 0.0;
    const double y0 = (double)sk.dmp.y_start_m;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        (void)strtod(line, &end);
        char *end2 = NULL;
        const double f_ref = strtod(end + 1, &end2);
        const double y_ref = strtod(end2 + 1, NULL);
        double f_c = (double)(sk.dmp.force0_N + (fs_real_t)gs * sk.dmp.goal_N + s.y_N);
        fs_real_t p = ps * sk.dmp.goal_y_m + s.path_m;
        if (row > 0) {
            f_c = (double)dmp_periodic_step_xy(&sk.dmp, &s, &run, (fs_real_t)as, NULL, ps, &p);
        }
        ef = fmax(ef, fabs(f_c - f_ref));
        fm = fmax(fm, fabs(f_ref));
        ey = fmax(ey, fabs((y0 + (double)p) - y_ref));
        pm = fmax(pm, fabs(y_ref - y0));
        row++;
    }
    fclose(f);
    if (row != n_steps + 1) {
        fail_msg("%s: %ld rows, expected %ld", path, row, n_steps + 1);
    }
    assert_true(fm > 0.0 && pm > 0.0);
    printf("[%s] %s gs=%g as=%g ts=%g cycles=%g ps=%g: max err force %.3g of max|f|, path %.3g "
           "of max|p| (%.3g um)\n",
           BUILD_NAME, fld[0], gs, as, ts, cycles, (double)ps, ef / fm, ey / pm, ey * 1e6);
    if (!(ef / fm <= REL_TOL) || !(ey / pm <= REL_TOL)) {
        fail_msg("%s (%s): force %.3g, path %.3g exceed %.1g", fld[6], BUILD_NAME, ef / fm, ey / pm,
                 REL_TOL);
    }
    return fmax(ef / fm, ey / pm);
}

static void test_golden_rollouts_periodic_y(void **state)
{
    (void)state;
    int count = 0;
    const double worst = for_each_manifest_line("manifest_periodic_y.txt", 7,
                                                check_rollout_periodic_xy, &count);
    printf("[%s] %d golden periodic rollouts with the y path, worst error %.3g (tolerance %.0g)\n",
           BUILD_NAME, count, worst, REL_TOL);
    assert_true(count > 0);
}

/* One manifest_contact line: the contact wait's loop over the core (dmp_contact_rate, then the
 * DMP step slowed by dmp_slowdown_at_rate) driven by the CSV's measured force, against its rate
 * and f_hat and the line's hold; returns the relative error of f_hat. */
static double check_contact(const char *dir, char *const *fld)
{
    char path[1024];
    const double gs = strtod(fld[1], NULL);
    const double as = strtod(fld[2], NULL);
    const double ts = strtod(fld[3], NULL);
    const fs_real_t thr = (fs_real_t)strtod(fld[4], NULL);
    const fs_real_t tau_c = (fs_real_t)strtod(fld[5], NULL);
    const double hold_ref = strtod(fld[6], NULL);
    snprintf(path, sizeof(path), "%s/%s", dir, fld[0]);
    const long len = read_file(path, image, MAX_IMAGE);
    if (len < 0 || skill_parse(image, (uint32_t)len, &sk) != FS_OK) {
        fail_msg("%s: not a skill this build parses (%s)", path, BUILD_NAME);
    }
    snprintf(path, sizeof(path), "%s/%s", dir, fld[7]);
    FILE *f = fopen(path, "r");
    char line[256];
    if (f == NULL || fgets(line, sizeof(line), f) == NULL ||
        strncmp(line, "t,f_contact,rate,f_hat", 22) != 0) {
        fail_msg("%s: missing or its header is not 't,f_contact,rate,f_hat'", path);
    }
    const dmp_run_t run = {(fs_real_t)gs, (fs_real_t)ts};
    const fs_real_t gain = sk.dmp.dt_s / (tau_c + sk.dmp.dt_s);
    dmp_state_t s;
    if (sk.dmp.periodic != 0u) {
        dmp_periodic_reset(&sk.dmp, &s, (fs_real_t)as);
    } else {
        dmp_state_reset(&s);
    }
    fs_real_t rate = FS_R(1.0), f_prev = FS_R(0.0);
    double err = 0.0, err_rate = 0.0, f_max = 0.0, hold = 0.0;
    long row = 0;
    while (fgets(line, sizeof(line), f) != NULL) {
        char *end = NULL;
        (void)strtod(line, &end);
        const double f_c = strtod(end + 1, &end);
        const double rate_ref = strtod(end + 1, &end);
        const double f_ref = strtod(end + 1, NULL);
        rate = dmp_contact_rate(rate, f_prev, (fs_real_t)f_c, thr, gain);
        const dmp_coupling_t cp = {FS_R(0.0), dmp_slowdown_at_rate(FS_R(0.0), rate)};
        f_prev = (sk.dmp.periodic != 0u) ? dmp_periodic_step(&sk.dmp, &s, &run, (fs_real_t)as, &cp)
                                         : dmp_step(&sk.dmp, &s, &run, &cp);
        hold += (1.0 - (double)rate) * (double)sk.dmp.dt_s;
        err = fmax(err, fabs((double)f_prev - f_ref));
        err_rate = fmax(err_rate, fabs((double)rate - rate_ref));
        f_max = fmax(f_max, fabs(f_ref));
        row++;
    }
    fclose(f);
    assert_true(row > 0 && f_max > 0.0);
    printf("[%s] %s gs=%g as=%g ts=%g threshold %g N tau %g s: %ld rows, max err %.3g of max|f|, "
           "rate %.3g, hold %.6f s (reference %.6f)\n",
           BUILD_NAME, fld[0], gs, as, ts, (double)thr, (double)tau_c, row, err / f_max, err_rate,
           hold, hold_ref);
    if (!(err / f_max <= REL_TOL) || !(err_rate <= REL_TOL) ||
        !(fabs(hold - hold_ref) <= REL_TOL * hold_ref)) {
        fail_msg(
            "%s (%s): f_hat error %.3g of max|f|, rate error %.3g, hold %.9g vs %.9g (tol %.1g)",
            fld[7], BUILD_NAME, err / f_max, err_rate, hold, hold_ref, REL_TOL);
    }
    return err / f_max;
}

static void test_golden_contact_wait(void **state)
{
    (void)state;
    int count = 0;
    const double worst = for_each_manifest_line("manifest_contact.txt", 8, check_contact, &count);
    printf("[%s] %d golden contact-wait rollouts, worst error %.3g of max|f| (tolerance %.0g)\n",
           BUILD_NAME, count, worst, REL_TOL);
    assert_true(count > 0);
}

/* The periodic golden skills (manifest_periodic.txt, format v4) parse as periodic models with
 * their stored fields; a discrete skill rewritten as v4 (kind 0, the periodic fields 0) parses
 * as its v2 image. */
static void test_periodic_images(void **state)
{
    (void)state;
    static const char *const names[] = {"periodic_n20_ridge.skill", "periodic_n50_lwr.skill",
                                        "periodic_n50_ridge.skill"};
    char path[1100];
    for (size_t i = 0u; i < sizeof(names) / sizeof(names[0]); i++) {
        snprintf(path, sizeof(path), "%s/%s", FS_VECTORS_DIR, names[i]);
        const long len = read_file(path, image, MAX_IMAGE);
        assert_true(len > 0);
        assert_int_equal(skill_parse(image, (uint32_t)len, &sk), FS_OK);
        assert_int_equal(sk.kind, SKILL_KIND_PERIODIC);
        assert_int_equal(sk.dmp.periodic, 1u);
        assert_true(sk.dmp.amplitude_N > FS_R(0.0));
    }
    snprintf(path, sizeof(path), "%s/press_n10_ridge_release.skill", FS_VECTORS_DIR);
    const long len2 = read_file(path, image, MAX_IMAGE);
    assert_true(len2 > 136);
    static skill_t v2;
    assert_int_equal(skill_parse(image, (uint32_t)len2, &v2), FS_OK);
    /* v4: the v2 header, y_start_m = goal_y_m = 0, six periodic f64 = 0, kind 0, reserved 0 */
    static uint8_t v4[MAX_IMAGE];
    const uint32_t body = (uint32_t)len2 - 136u - 4u;
    memcpy(v4, image, 136u);
    memset(v4 + 136u, 0, 208u - 136u);
    memcpy(v4 + 208u, image + 136u, body);
    const uint32_t len4 = 208u + body + 4u;
    v4[4] = 4u;
    v4[5] = 0u;
    v4[6] = 208u;
    v4[7] = 0u;
    v4[8] = (uint8_t)(len4 & 0xFFu);
    v4[9] = (uint8_t)((len4 >> 8) & 0xFFu);
    v4[10] = (uint8_t)((len4 >> 16) & 0xFFu);
    v4[11] = (uint8_t)(len4 >> 24);
    const uint32_t crc = skill_crc32(0u, v4, len4 - 4u);
    for (uint32_t k = 0u; k < 4u; k++) {
        v4[len4 - 4u + k] = (uint8_t)((crc >> (8u * k)) & 0xFFu);
    }
    assert_int_equal(skill_parse(v4, len4, &sk), FS_OK);
    assert_int_equal(sk.kind, SKILL_KIND_DISCRETE);
    assert_int_equal(sk.dmp.n_kernels, v2.dmp.n_kernels);
    assert_true(sk.dmp.goal_N == v2.dmp.goal_N && sk.dmp.tau_s == v2.dmp.tau_s);
    for (uint16_t i = 0u; i < sk.dmp.n_kernels; i++) {
        assert_true(sk.dmp.weight[i] == v2.dmp.weight[i] && sk.dmp.centre[i] == v2.dmp.centre[i]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_golden_rollouts),
        cmocka_unit_test(test_golden_band),
        cmocka_unit_test(test_golden_rollouts_y),
        cmocka_unit_test(test_golden_bad_images),
        cmocka_unit_test(test_periodic_images),
        cmocka_unit_test(test_golden_rollouts_periodic),
        cmocka_unit_test(test_golden_contact_wait),
        cmocka_unit_test(test_golden_rollouts_periodic_y),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
