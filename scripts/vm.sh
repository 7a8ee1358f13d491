#!/usr/bin/env bash
# Run one command in a Linux virtual machine that has SocketCAN (vcan, qemu's emulated SJA1000
# controllers), against this machine's own files: the guest mounts the host's / read-only
# (virtiofs, or 9p) under a tmpfs overlay, so it runs the checkout's build and .venv as they are
# and its writes vanish with it. The guest's kernel is Debian's linux-image-*-amd64, unpacked from
# its .deb under build/vm/ (the host's /boot and /lib/modules are not touched); its initramfs is a
# static busybox with the modules it needs (tools/vm_initramfs.py, /init: scripts/vm_init.sh).
#
#   scripts/vm.sh --setup                  install qemu-system-x86 and can-utils, fetch and unpack
#                                          the kernel and busybox-static, build the initramfs
#   scripts/vm.sh [options] -- CMD [ARG]...
#
# CMD runs in the caller's directory as root, with PATH, HOME=/root and the caller's FORCESKILL_*
# and CI variables; its stdout and stderr, in order, come out on stdout (the guest's serial
# console). Exit status: CMD's; 77 with one "vm: skipped: ..." line where qemu or the kernel cannot
# be had; 124 when --timeout ends the guest; 125 when the guest ends without CMD's status.
#
# Options:
#   --vcan            vcan0, up, with the CAN FD MTU (72; classic frames pass as well)
#   --vcan-mtu N      vcan0 with MTU N (16: classic CAN only)
#   --kvaser N        N kvaser_pci controllers (SJA1000) on one qemu can-bus: can0..can{N-1},
#                     driver loaded, links down (set the bit rate, then up)
#   --fs virtiofs|9p  how the guest sees the host's / (default virtiofs: python's imports run
#                     about 4x faster than over 9p under TCG; docs/hil.md)
#   --timeout S       end the guest after S seconds (default 900)
#   --env NAME=VALUE  one more variable for CMD (repeatable)
#   --smp N, --mem MB CPUs (default 2) and memory (default 2048)
#   --accel tcg|kvm   default: kvm where --setup found it boots the guest, else tcg
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VM="$ROOT/build/vm"
QEMU=qemu-system-x86_64

skip() {
  echo "vm: skipped: $*"
  exit 77
}

vm_setup() {
  local sudo="" pkgs=() p kpkg
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  command -v apt-get >/dev/null || skip "no apt-get here to install qemu-system-x86 and fetch Debian's kernel (docs/hil.md)"
  for p in qemu-system-x86 can-utils; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || pkgs+=("$p")
  done
  apt-cache show linux-image-amd64 >/dev/null 2>&1 || $sudo apt-get update -qq || skip "apt-get update failed"
  # virtiofsd: its own package where Debian has one (13 on), else qemu-system-common's
  if ! command -v virtiofsd >/dev/null && [ ! -x /usr/lib/qemu/virtiofsd ] \
    && apt-cache show virtiofsd >/dev/null 2>&1; then
    dpkg-query -W -f='${Status}' virtiofsd 2>/dev/null | grep -q "install ok installed" || pkgs+=(virtiofsd)
  fi
  if [ ${#pkgs[@]} -gt 0 ]; then
    echo "== vm: installing ${pkgs[*]}"
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${pkgs[@]}" >/dev/null \
      || skip "apt-get install ${pkgs[*]} failed"
  fi
  mkdir -p "$VM/deb"
  # the kernel the linux-image-amd64 meta package points to, unpacked, never installed
  kpkg=$(apt-cache depends linux-image-amd64 2>/dev/null | sed -n 's/^ *Depends: \(linux-image-[0-9].*\)$/\1/p' | head -n 1)
  [ -n "$kpkg" ] || skip "apt knows no linux-image-amd64 kernel"
  if [ "$(cat "$VM/kernel/.package" 2>/dev/null)" != "$kpkg" ]; then
    echo "== vm: fetching and unpacking $kpkg into build/vm/kernel"
    rm -f "$VM"/deb/linux-image-*.deb
    (cd "$VM/deb" && apt-get download -qq "$kpkg" 2>/dev/null) || skip "apt-get download $kpkg failed"
    rm -rf "$VM/kernel.new" "$VM/kernel"
    dpkg-deb -x "$VM"/deb/linux-image-*.deb "$VM/kernel.new"
    echo "$kpkg" >"$VM/kernel.new/.package"
    mv "$VM/kernel.new" "$VM/kernel"
  fi
  # a static busybox for the initramfs: the installed busybox-static, else its .deb unpacked
  if dpkg-query -W -f='${Status}' busybox-static 2>/dev/null | grep -q "install ok installed"; then
    ln -sf /bin/busybox "$VM/busybox"
  elif [ ! -x "$VM/busybox-static/bin/busybox" ]; then
    echo "== vm: fetching busybox-static into build/vm/busybox-static"
    rm -f "$VM"/deb/busybox-static_*.deb
    (cd "$VM/deb" && apt-get download -qq busybox-static 2>/dev/null) || skip "apt-get download busybox-static failed"
    dpkg-deb -x "$VM"/deb/busybox-static_*.deb "$VM/busybox-static"
    ln -sf "$VM/busybox-static/bin/busybox" "$VM/busybox"
  fi
  initramfs
  probe_kvm
  echo "vm: ready ($kpkg, $(cat "$VM/accel"))"
}

initramfs() {
  if [ ! -s "$VM/initramfs.cpio" ] || [ ! -s "$VM/vmlinux" ] || [ "$ROOT/scripts/vm_init.sh" -nt "$VM/initramfs.cpio" ] \
    || [ "$ROOT/tools/vm_initramfs.py" -nt "$VM/initramfs.cpio" ] || [ "$VM/kernel/.package" -nt "$VM/initramfs.cpio" ]; then
    python3 "$ROOT/tools/vm_initramfs.py" --kernel-root "$VM/kernel" --busybox "$VM/busybox" \
      --init "$ROOT/scripts/vm_init.sh" -o "$VM/initramfs.cpio" --vmlinux "$VM/vmlinux" >/dev/null
  fi
}

# KVM only where it really boots this guest (a /dev/kvm without hardware behind it aborts qemu)
probe_kvm() {
  [ -s "$VM/accel" ] && [ "$VM/accel" -nt "$VM/initramfs.cpio" ] && return 0
  echo tcg >"$VM/accel"
  if [ -r /dev/kvm ] && [ -w /dev/kvm ] && "$0" --accel kvm --timeout 60 -- true >/dev/null 2>&1; then
    echo kvm >"$VM/accel"
  fi
}

FS=virtiofs VCAN_MTU=0 KVASER=0 TIMEOUT=900 SMP=2 MEM=2048 ACCEL="" ENVS=()
while [ $# -gt 0 ]; do
  case "$1" in
    --setup) vm_setup; exit 0 ;;
    --vcan) VCAN_MTU=72 ;;
    --vcan-mtu) VCAN_MTU="${2:?--vcan-mtu needs a value}"; shift ;;
    --kvaser) KVASER="${2:?--kvaser needs a value}"; shift ;;
    --fs) FS="${2:?--fs needs a value}"; shift ;;
    --timeout) TIMEOUT="${2:?--timeout needs a value}"; shift ;;
    --env) ENVS+=("${2:?--env needs NAME=VALUE}"); shift ;;
    --smp) SMP="${2:?--smp needs a value}"; shift ;;
    --mem) MEM="${2:?--mem needs a value}"; shift ;;
    --accel) ACCEL="${2:?--accel needs a value}"; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    --) shift; break ;;
    *) echo "vm: unknown option $1 (scripts/vm.sh --help)" >&2; exit 2 ;;
  esac
  shift
done
[ $# -gt 0 ] || { echo "vm: no command (scripts/vm.sh [options] -- CMD)" >&2; exit 2; }
case "$FS" in virtiofs | 9p) ;; *) echo "vm: --fs must be virtiofs or 9p" >&2; exit 2 ;; esac
case "$VCAN_MTU" in 0 | 16 | 72) ;; *) echo "vm: --vcan-mtu must be 16 or 72" >&2; exit 2 ;; esac
[[ "$KVASER" =~ ^[0-4]$ ]] || { echo "vm: --kvaser must be 0..4" >&2; exit 2; }
[[ "$TIMEOUT" =~ ^[1-9][0-9]*$ ]] || { echo "vm: --timeout must be a whole number of seconds" >&2; exit 2; }
for e in "${ENVS[@]}"; do [[ "$e" =~ ^[A-Za-z_][A-Za-z0-9_]*= ]] || { echo "vm: --env needs NAME=VALUE, not $e" >&2; exit 2; }; done

command -v "$QEMU" >/dev/null || skip "no $QEMU (scripts/vm.sh --setup installs qemu-system-x86)"
[ -s "$VM/kernel/.package" ] && [ -x "$VM/busybox" ] || skip "no guest kernel in build/vm (scripts/vm.sh --setup fetches Debian's)"
initramfs
KERNEL="$VM/vmlinux"
[ -n "$ACCEL" ] || ACCEL=$(cat "$VM/accel" 2>/dev/null || echo tcg)
case "$ACCEL" in
  tcg) ACCEL_ARGS=(-accel tcg,thread=multi -cpu max) ;;
  kvm) ACCEL_ARGS=(-accel kvm -cpu host) ;;
  *) echo "vm: --accel must be tcg or kvm" >&2; exit 2 ;;
esac

RUN=$(mktemp -d "${TMPDIR:-/tmp}/forceskill-vm.XXXXXX")
VFS_PID=""
cleanup() {
  [ -n "$VFS_PID" ] && kill "$VFS_PID" 2>/dev/null && wait "$VFS_PID" 2>/dev/null
  rm -rf "$RUN"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

{
  printf 'cd %q || exit 125\n' "$PWD"
  echo 'export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 TERM=dumb'
  for e in $(compgen -e | grep -E '^(FORCESKILL_|CI$)' || true); do printf 'export %s=%q\n' "$e" "${!e}"; done
  for e in "${ENVS[@]}"; do printf 'export %s=%q\n' "${e%%=*}" "${e#*=}"; done
  printf 'exec'; printf ' %q' "$@"; echo
} >"$RUN/cmd"

ARGS=(-M pc "${ACCEL_ARGS[@]}" -smp "$SMP" -m "$MEM" -nodefaults -no-user-config -display none
  -no-reboot -chardev stdio,id=con,signal=off -serial chardev:con
  -kernel "$KERNEL" -initrd "$VM/initramfs.cpio"
  -append "console=ttyS0 quiet loglevel=1 panic=-1 tsc=reliable no_timer_check vm.fs=$FS vm.vcan=$VCAN_MTU vm.kvaser=$KVASER"
  -fsdev "local,id=io,path=$RUN,security_model=none" -device virtio-9p-pci,fsdev=io,mount_tag=vmio)
if [ "$FS" = virtiofs ]; then
  VFSD=$(command -v virtiofsd || ls /usr/libexec/virtiofsd /usr/lib/qemu/virtiofsd 2>/dev/null | head -n 1 || true)
  [ -n "$VFSD" ] || skip "no virtiofsd (scripts/vm.sh --setup; or --fs 9p)"
  # the daemon sees every mount read-only (its own mount namespace, each mount remounted ro)
  # but the run folder, where its socket goes, and a /run of its own for its lock file
  unshare -m --propagation private sh -c '
    mount --bind "$1" "$1" || exit 1
    awk "{print \$2}" /proc/self/mounts | sort -u | while read -r m; do
      [ "$m" = "$1" ] || mount -o remount,bind,ro "$m" 2>/dev/null
    done
    mount -t tmpfs vfsrun /run || exit 1
    exec "$0" --socket-path="$1/vfs.sock" -o source=/ -o cache=always -o sandbox=chroot' \
    "$VFSD" "$RUN" >"$RUN/virtiofsd.log" 2>&1 &
  VFS_PID=$!
  for _ in $(seq 100); do [ -S "$RUN/vfs.sock" ] && break; sleep 0.05; done
  [ -S "$RUN/vfs.sock" ] || { cat "$RUN/virtiofsd.log" >&2; echo "vm: virtiofsd did not start" >&2; exit 125; }
  [ -z "${VM_DEBUG:-}" ] || trap 'cat "$RUN/virtiofsd.log" >&2; cleanup' EXIT
  ARGS+=(-object "memory-backend-memfd,id=mem,size=${MEM}M,share=on" -numa node,memdev=mem
    -chardev "socket,id=vfs,path=$RUN/vfs.sock" -device vhost-user-fs-pci,chardev=vfs,tag=hostroot)
else
  ARGS+=(-fsdev local,id=hostroot,path=/,security_model=none,readonly=on,multidevs=remap
    -device virtio-9p-pci,fsdev=hostroot,mount_tag=hostroot)
fi
if [ "$KVASER" -gt 0 ]; then
  ARGS+=(-object can-bus,id=canbus0)
  for _ in $(seq "$KVASER"); do ARGS+=(-device kvaser_pci,canbus=canbus0); done
fi

set +e
timeout -k 5 "$TIMEOUT" "$QEMU" "${ARGS[@]}" </dev/null
qrc=$?
set -e
if [ -s "$RUN/rc" ]; then
  exit "$(cat "$RUN/rc")"
fi
if [ "$qrc" -eq 124 ]; then
  echo "vm: the guest ran out of time (--timeout $TIMEOUT s) and was stopped" >&2
  exit 124
fi
echo "vm: the guest ended without the command's exit status (qemu exit $qrc)" >&2
exit 125
