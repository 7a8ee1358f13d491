# Sourced by the qemu benchmarks: ONE_INSN, qemu-system-arm's option for one instruction per
# translation block (exact instruction counts): -singlestep up to qemu 8.0, then
# -accel tcg,one-insn-per-tb=on (8.1 renamed it; -singlestep was removed in 9.x).
QV=$(qemu-system-arm --version | sed -n 's/.*version \([0-9]*\)\.\([0-9]*\).*/\1 \2/p')
read -r QMAJ QMIN <<< "$QV"
if [ "$QMAJ" -gt 8 ] || { [ "$QMAJ" -eq 8 ] && [ "$QMIN" -ge 1 ]; }; then
  ONE_INSN=(-accel tcg,one-insn-per-tb=on)
else
  ONE_INSN=(-singlestep)
fi
