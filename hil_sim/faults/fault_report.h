/* The table of `hil_sim faults` (docs/safety.md): markdown and JSON writers of the rows. */
#ifndef FAULT_REPORT_H
#define FAULT_REPORT_H

#include <stdint.h>
#include <stdio.h>

#include "fault_run.h"

/** The markdown table, the pass count and one note per row. */
void fault_write_table(FILE *f, const frow_t *rows, int n, uint64_t seed);

/** The same rows as JSON: {"seed", "hold_ms", "zero_bound_ms", "rows": [...]}. */
void fault_write_json(FILE *f, const frow_t *rows, int n, uint64_t seed);

#endif /* FAULT_REPORT_H */
