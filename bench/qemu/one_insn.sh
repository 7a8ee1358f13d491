# Sourced by the qemu benchmarks: the pieces of their two exact instruction counters.
# - plugin_build SO: builds bench/qemu/tick_plugin.c, a qemu TCG plugin (plugin API version 1),
#   with the host's cc into SO; qemu then runs with normal chaining (blocks of many instructions)
#   and calls the plugin before each executed instruction (`-plugin SO,mode=count,out=FILE`: the
#   instructions between cm_port_mark_begin and cm_port_mark_end, one line per region).
# - the one-instruction trace, when qemu cannot load the plugin: ONE_INSN, qemu-system-arm's
#   option for one instruction per translation block: -singlestep up to qemu 8.0, then -accel
#   tcg,one-insn-per-tb=on (8.1 renamed it; -singlestep was removed in 9.x), with `-d exec,nochain
#   -D FIFO`, one log line per executed instruction with its symbol, read through TRACE_FILTER:
#   it drops what the log holds besides executed instructions (under -icount an I/O instruction is
#   logged, rewound ("cpu_io_recompile: rewound execution of TB") and logged again; a block
#   entered only to leave it for an interrupt is logged before "Stopped execution of TB chain").
#   With -v stream=FILE it also writes "pc symbol" per instruction (the plugin's log=FILE
#   format), with -v limit=N it stops after N instructions.
plugin_build() {
  cc -std=c11 -O2 -fPIC -shared -fvisibility=hidden -o "$1" "$(dirname "${BASH_SOURCE[0]}")/tick_plugin.c"
}
TRACE_FILTER='function emit() { print held; n++
                  if (stream != "") { split(held, f, " "); split(f[4], pc, "/")
                                      print pc[2], (f[5] != "" ? f[5] : "[" pc[2] "]") > stream }
                  if (limit && n >= limit) { have = 0; exit } }
  /^Trace / { if (have) emit(); held = $0; have = 1; next }
  /^cpu_io_recompile: rewound execution of TB/ || /^Stopped execution of TB chain/ { have = 0 }
  END { if (have) emit() }'
# the trace's count per marked region (the plugin's mode=count): one line per region
REGION_AWK='/ cm_port_mark_begin$/ { inb = 1; c = 0; next }
            / cm_port_mark_end$/   { if (inb) print c; inb = 0; next }
            { if (inb) c++ }'

QV=$(qemu-system-arm --version | sed -n 's/.*version \([0-9]*\)\.\([0-9]*\).*/\1 \2/p')
read -r QMAJ QMIN <<< "$QV"
if [ "$QMAJ" -gt 8 ] || { [ "$QMAJ" -eq 8 ] && [ "$QMIN" -ge 1 ]; }; then
  ONE_INSN=(-accel tcg,one-insn-per-tb=on)
else
  ONE_INSN=(-singlestep)
fi
