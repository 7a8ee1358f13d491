/* Writers of the fault table: see fault_report.h. */
#include "fault_report.h"

#include <stdbool.h>
#include <string.h>

static void fmt_ms(char *out, size_t n, double v)
{
    if (v < 0.0) {
        snprintf(out, n, "-");
    } else {
        snprintf(out, n, "%.0f", v);
    }
}

void fault_write_table(FILE *f, const frow_t *rows, int n, uint64_t seed)
{
    int passed = 0;
    fprintf(f,
            "| fault | injection | code | detection (ms) | bound (ms) | time to zero force (ms) | "
            "force at onset (N) | worst force (N) | F_max (N) | worst contact force (N) | latched "
            "1 s, no resume | clear after cause gone | lost | pass |\n");
    fprintf(f, "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---|---|---|---|\n");
    for (int i = 0; i < n; i++) {
        const frow_t *r = &rows[i];
        char d[16], z[16], code[16];
        fmt_ms(d, sizeof d, r->detect_ms);
        fmt_ms(z, sizeof z, r->zero_ms);
        if (r->code != 0) {
            snprintf(code, sizeof code, "%d", r->code);
        } else {
            snprintf(code, sizeof code, "none");
        }
        const bool storage = strcmp(r->kind, "power_loss_upload") == 0;
        const bool none = r->expect_code == 0;
        fprintf(
            f, "| %s | %s | %s | %s | %s | %s | %.1f | %.1f | %.0f | %.1f | %s | %s | %s | %s |\n",
            r->name, r->description, storage ? "-" : code, d,
            (storage || none) ? "-" : r->bound_text, z, r->force_at_onset_N, r->worst_N, r->f_max_N,
            r->contact_max_N, (storage || none) ? "n/a" : (r->latched ? "yes" : "NO"),
            (storage || none) ? "n/a" : (r->cleared ? "yes" : "NO"), r->lost ? "YES" : "no",
            r->pass ? "pass" : "FAIL");
        passed += r->pass ? 1 : 0;
    }
    fprintf(f, "\n%d/%d fault scenarios pass (seed %llu).\n", passed, n, (unsigned long long)seed);
    for (int i = 0; i < n; i++) {
        fprintf(f, "- %s: %s\n", rows[i].name, rows[i].note);
    }
}

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s != '\0'; s++) {
        if (*s == '"' || *s == '\\') {
            fputc('\\', f);
        }
        fputc(*s, f);
    }
    fputc('"', f);
}

void fault_write_json(FILE *f, const frow_t *rows, int n, uint64_t seed)
{
    fprintf(f, "{\"seed\": %llu, \"hold_ms\": %u, \"zero_bound_ms\": %u, \"rows\": [\n",
            (unsigned long long)seed, FAULT_HOLD_MS, FAULT_ZERO_BOUND_MS);
    for (int i = 0; i < n; i++) {
        const frow_t *r = &rows[i];
        fprintf(f, "  {\"name\": ");
        json_str(f, r->name);
        fprintf(f, ", \"kind\": ");
        json_str(f, r->kind);
        fprintf(
            f,
            ", \"expect_code\": %d, \"code\": %d, \"detect_ms\": %.3f, \"detect_bound_ms\": %.3f, "
            "\"zero_ms\": %.3f, \"force_at_onset_N\": %.6f, \"worst_force_N\": %.6f, \"f_max_N\": "
            "%.3f, "
            "\"contact_max_N\": %.6f, \"emcy_delay_ms\": %.3f, "
            "\"monotone\": %s, \"latched\": %s, \"cleared\": %s, \"emcy_seen\": %s, "
            "\"status_seen\": %s, \"lost\": %s, \"pass\": %s, \"note\": ",
            r->expect_code, r->code, r->detect_ms, r->detect_bound_ms, r->zero_ms,
            r->force_at_onset_N, r->worst_N, r->f_max_N, r->contact_max_N, r->emcy_delay_ms,
            r->monotone ? "true" : "false", r->latched ? "true" : "false",
            r->cleared ? "true" : "false", r->emcy_seen ? "true" : "false",
            r->status_seen ? "true" : "false", r->lost ? "true" : "false",
            r->pass ? "true" : "false");
        json_str(f, r->note);
        fprintf(f, "}%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "]}\n");
}
