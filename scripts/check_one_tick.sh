#!/usr/bin/env bash
# One implementation of the control tick: the DMP and control-law step functions (dmp_/dmpfx_/
# pfc_/pfcfx_ step and tick), the executor (exec_tick, exec_start, exec_render_step,
# exec_vel_update) and the limiter/fault logic (lim_, saf_, flt_, sen_, wdg_) are called only
# where they are written and composed (firmware/core, fixed, control, app, safety), by their tests, and by
# the listed exceptions; and each simulator that runs the device (hil_sim run, faults, serve)
# and the Cortex-M image (hil_sim pil) calls the application's tick. Exit 1 with the offending lines otherwise. Run by scripts/test.sh.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

CALLS='\b((dmp|dmpfx|pfc|pfcfx)_(step|tick_[a-z_]+)|exec_(tick|start|render_step|vel_update)|(lim|saf|flt|sen|wdg)_[a-z0-9_]+)[[:space:]]*\('
# where the tick is written and composed, and its tests
HOME_DIRS='^(firmware/(core|fixed|control|app|safety)/|tests/|fuzz/)'
# exceptions: benchmarks that time the step functions themselves (bench/core_step, bench/peers)
EXCEPT='^bench/(core_step|peers)/'

status=0
bad=$(git grep -nE "$CALLS" -- '*.c' '*.h' | grep -vE "$HOME_DIRS" | grep -vE "$EXCEPT" || true)
if [ -n "$bad" ]; then
  echo "check_one_tick FAILED: a second implementation of the tick calls the core/limiter directly:"
  echo "$bad"
  status=1
fi
for f in hil_sim/src/sim_run.c hil_sim/faults/fault_rig.c hil_sim/bus/serve.c \
         firmware/ports/mps2/mps2_main.c; do
  if ! grep -qE '\bapp_(tick|poll)\(' "$f"; then
    echo "check_one_tick FAILED: $f does not run the application's tick (app_tick/app_poll)"
    status=1
  fi
done
n_exc=$(git grep -lE "$CALLS" -- '*.c' '*.h' | grep -cE "$EXCEPT" || true)
if [ $status -eq 0 ]; then
  echo "check_one_tick ok: one tick (firmware/app over control, core, fixed, safety); hil_sim run, faults, serve and the Cortex-M image call app_tick/app_poll; $n_exc excepted benchmark files"
fi
exit $status
