/* Tests of the simulator's one TOML-subset reader (hil_sim/src/sim_toml.c) and of the two file
 * formats built on it: scenarios (sim_scenario.c, run and serve) and fault scenarios
 * (hil_sim/faults/fault_scenario.c). Every error is one whole line "file:line: message": the
 * tests compare the full text. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fault_scenario.h"
#include "sim_scenario.h"
#include "sim_toml.h"

/* Records every key the reader hands over, as "section.key=type". */
typedef struct {
    char seen[512];
} record_t;

static int record(void *user, const sim_toml_ctx_t *c, const char *section, const char *key,
                  const sim_toml_value_t *v)
{
    record_t *r = user;
    size_t used = strlen(r->seen);
    snprintf(r->seen + used, sizeof r->seen - used, "%d:%s.%s=%d;", c->line, section, key,
             (int)v->type);
    return 0;
}

static void test_reader_hands_over_keys_in_order(void **state)
{
    (void)state;
    static const char *const SECTIONS[] = {"a", "b"};
    record_t r = {""};
    char err[SIM_ERR_MAX] = "";
    const char *text = "# head\r\nx = 1 # tail\n\n[a]\ns = \"q \\\" #\"\nt = true\n[b]\n"
                       "n = [1, 2.5]\nm = [\"p\", \"q\"]\n";
    assert_int_equal(sim_toml_parse(text, "f.toml", SECTIONS, 2u, record, &r, err), 0);
    assert_string_equal(r.seen, "2:.x=0;5:a.s=1;6:a.t=2;8:b.n=3;9:b.m=4;");
}

/* The reader's own messages, whole. */
static void expect_reader_error(const char *text, const char *want)
{
    static const char *const SECTIONS[] = {"a"};
    record_t r = {""};
    char err[SIM_ERR_MAX] = "";
    assert_int_equal(sim_toml_parse(text, "f.toml", SECTIONS, 1u, record, &r, err), -1);
    if (strcmp(err, want) != 0) {
        fail_msg("got '%s', want '%s'", err, want);
    }
    assert_null(strchr(err, '\n'));
}

static void test_reader_errors_are_one_line_with_file_and_line(void **state)
{
    (void)state;
    expect_reader_error("x = 1\n[c]\n", "f.toml:2: unknown section [c] (known: a)");
    expect_reader_error("\n\n[a\n", "f.toml:3: section header without ']'");
    expect_reader_error("[a] x\n", "f.toml:1: unexpected text after the section header");
    expect_reader_error("x\n", "f.toml:1: expected 'key = value'");
    expect_reader_error("x-y = 1\n", "f.toml:1: invalid key 'x-y'");
    expect_reader_error(" = 1\n", "f.toml:1: empty key");
    expect_reader_error("x = \"abc\n", "f.toml:1: unterminated string");
    expect_reader_error("x = abc\n", "f.toml:1: expected a number, a \"string\", true or false, "
                                     "got 'abc'");
    expect_reader_error("x = 1e999\n", "f.toml:1: number out of range");
    expect_reader_error("x = [1, \"a\"]\n", "f.toml:1: array mixes numbers and strings");
    expect_reader_error("x = [1 2]\n",
                        "f.toml:1: expected ',' or ']' in array (arrays must be on one line)");
    expect_reader_error("x = [1,2,3,4,5,6,7,8,9]\n", "f.toml:1: array longer than 8 items");
    expect_reader_error("x = 1 2\n", "f.toml:1: unexpected text after the value: '2'");
}

static void test_flat_file_refuses_sections(void **state)
{
    (void)state;
    record_t r = {""};
    char err[SIM_ERR_MAX] = "";
    assert_int_equal(sim_toml_parse("x = 1\n[a]\n", "g.toml", NULL, 0u, record, &r, err), -1);
    assert_string_equal(err, "g.toml:2: unknown section [a] (this file has no sections)");
}

static void test_typed_helpers(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "";
    sim_toml_ctx_t c = {"h.toml", 7, err};
    sim_toml_value_t v;
    memset(&v, 0, sizeof v);
    v.type = SIM_TOML_NUM;
    v.num = 2.5;
    double out = 0.0;
    assert_int_equal(sim_toml_number(&c, "k", &v, 0.0, 3.0, &out), 0);
    assert_true(out == 2.5);
    assert_int_equal(sim_toml_number(&c, "k", &v, 0.0, 2.0, &out), -1);
    assert_string_equal(err, "h.toml:7: 'k' = 2.5 is outside [0, 2]");
    assert_int_equal(sim_toml_integer(&c, "k", &v, 0.0, 9.0, &out), -1);
    assert_string_equal(err, "h.toml:7: 'k' must be an integer in [0, 9], got 2.5");
    char s[4];
    assert_int_equal(sim_toml_string(&c, "k", &v, s, sizeof s), -1);
    assert_string_equal(err, "h.toml:7: 'k' must be a string, got a number");
    v.type = SIM_TOML_STR;
    snprintf(v.str, sizeof v.str, "long");
    assert_int_equal(sim_toml_string(&c, "k", &v, s, sizeof s), -1);
    assert_string_equal(err, "h.toml:7: 'k' is longer than 3 characters");
    static const char *const TWO[] = {"x", "y"};
    static const char *const FOUR[] = {"p", "q", "r", "s"};
    int i = -1;
    assert_int_equal(sim_toml_choice(&c, "k", &v, "k", TWO, 2, &i), -1);
    assert_string_equal(err, "h.toml:7: k must be \"x\" or \"y\", got \"long\"");
    assert_int_equal(sim_toml_choice(&c, "k", &v, "k", FOUR, 4, &i), -1);
    assert_string_equal(err, "h.toml:7: k must be one of p, q, r, s; got \"long\"");
    snprintf(v.str, sizeof v.str, "r");
    assert_int_equal(sim_toml_choice(&c, "k", &v, "k", FOUR, 4, &i), 0);
    assert_int_equal(i, 2);
}

static void test_scenario_and_fault_files_share_the_reader(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "";
    static sim_scenario_t sc;
    sim_scenario_defaults(&sc);
    assert_int_equal(sim_scenario_parse(&sc, "name = \"a\"\nseed = [1]\n", "s.toml", err), -1);
    assert_string_equal(err, "s.toml:2: 'seed' must be a number, got an array of numbers");
    static fscen_t fs;
    fscen_defaults(&fs);
    assert_int_equal(fscen_parse(&fs, "name = \"a\"\nseed = [1]\n", "f.toml", err), -1);
    assert_string_equal(err, "f.toml:2: unknown key 'seed'");
}

/* The fault scenario's keys and messages. */
static void expect_fault_error(const char *text, const char *want)
{
    static fscen_t fs;
    char err[SIM_ERR_MAX] = "";
    fscen_defaults(&fs);
    assert_int_equal(fscen_parse(&fs, text, "f.toml", err), -1);
    if (strcmp(err, want) != 0) {
        fail_msg("got '%s', want '%s'", err, want);
    }
    assert_null(strchr(err, '\n'));
}

#define FAULT_BASE "name = \"n\"\nplant = \"p.toml\"\nskill = \"a\"\nneighbour_skill = \"b\"\n"

static void test_fault_scenario_parse(void **state)
{
    (void)state;
    static fscen_t fs;
    char err[SIM_ERR_MAX] = "";
    fscen_defaults(&fs);
    const char *text = FAULT_BASE "kind = \"force_spike\"  # the spike\nvalue = 30.0\n"
                                  "at_s = 3.2\nexpect_code = 505\nplant_model = \"realistic\"\n";
    assert_int_equal(fscen_parse(&fs, text, "f.toml", err), 0);
    assert_string_equal(fs.kind, "force_spike");
    assert_string_equal(fs.plant_model, "realistic");
    assert_true(fs.value == 30.0 && fs.at_s == 3.2 && fs.expect_code == 505);
    assert_true(fs.goal_scale == 1.0 && fs.duration_s == 0.001 && fs.detect_bound_ms == 1.0);
}

static void test_fault_scenario_errors(void **state)
{
    (void)state;
    expect_fault_error(FAULT_BASE "kind = \"meteor\"\n",
                       "f.toml:5: kind must be one of host_silence, host_corrupt, bus_off, "
                       "force_spike, force_nan, force_stuck, encoder_jump, actuator_saturation, "
                       "host_loss, force_limit, tick_overrun, power_loss_upload; got \"meteor\"");
    expect_fault_error(FAULT_BASE "duraton_s = 0.2\n", "f.toml:5: unknown key 'duraton_s'");
    expect_fault_error(FAULT_BASE "at_s = \"3\"\n",
                       "f.toml:5: 'at_s' must be a number, got a string");
    expect_fault_error(FAULT_BASE "skill = 3\n", "f.toml:5: 'skill' must be a string, got a number");
    expect_fault_error(FAULT_BASE "expect_code = 50.5\n",
                       "f.toml:5: 'expect_code' must be an integer in [0, 65535], got 50.5");
    expect_fault_error(FAULT_BASE "plant_model = \"odd\"\n",
                       "f.toml:5: plant_model must be \"ideal\" or \"realistic\", got \"odd\"");
    expect_fault_error(FAULT_BASE "[x]\n",
                       "f.toml:5: unknown section [x] (this file has no sections)");
    expect_fault_error("name = \"n\"\nkind = \"bus_off\"\n",
                       "f.toml: needs name, plant, skill, neighbour_skill and kind");
    expect_fault_error(FAULT_BASE "kind = \"power_loss_upload\"\n",
                       "f.toml: power_loss_upload needs new_skill");
}

static void test_fault_scenario_load_names_the_file(void **state)
{
    (void)state;
    static fscen_t fs;
    char err[SIM_ERR_MAX] = "";
    assert_int_equal(fscen_load(&fs, "/nonexistent/f.toml", err), -1);
    assert_string_equal(err, "/nonexistent/f.toml: cannot open fault scenario: No such file or "
                             "directory");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reader_hands_over_keys_in_order),
        cmocka_unit_test(test_reader_errors_are_one_line_with_file_and_line),
        cmocka_unit_test(test_flat_file_refuses_sections),
        cmocka_unit_test(test_typed_helpers),
        cmocka_unit_test(test_scenario_and_fault_files_share_the_reader),
        cmocka_unit_test(test_fault_scenario_parse),
        cmocka_unit_test(test_fault_scenario_errors),
        cmocka_unit_test(test_fault_scenario_load_names_the_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
