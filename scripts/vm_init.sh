#!/bin/busybox sh
# The guest's /init of scripts/vm.sh (runs under busybox, PID 1, in the initramfs that
# tools/vm_initramfs.py builds). It mounts the host's / read-only (virtiofs or 9p, kernel argument
# vm.fs) under a tmpfs overlay, sets up the CAN interfaces asked for (vm.vcan=MTU: vcan0 with that
# MTU, 72 for CAN FD; vm.kvaser=N: the SJA1000 driver for qemu's kvaser_pci controllers, can0..,
# left down for the tests to configure), runs /run/vmio/cmd (written by the host) in a chroot of
# that root, writes its exit status to /run/vmio/rc and powers off.
/bin/busybox mkdir -p /bin /sbin /usr/bin /usr/sbin
/bin/busybox --install -s
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
stty -F /dev/console -onlcr 2>/dev/null

off() {
  echo 0 >/proc/sys/kernel/printk # no "reboot: Power down" after the command's output
  poweroff -f
}
die() {
  echo "vm guest: $*" >&2
  off
}
arg() { # the value of kernel argument $1, or $2
  v=$(tr ' ' '\n' </proc/cmdline | sed -n "s/^$1=//p" | tail -n 1)
  echo "${v:-$2}"
}

FS=$(arg vm.fs virtiofs)
modprobe -a virtio_pci overlay 9pnet_virtio 9p || die "cannot load the virtio/9p/overlay modules"
case "$FS" in
  virtiofs)
    modprobe virtiofs || die "cannot load virtiofs"
    mount -t virtiofs -o ro hostroot /lower || die "cannot mount the host's / (virtiofs)"
    ;;
  9p)
    mount -t 9p -o ro,trans=virtio,version=9p2000.L,msize=512000,cache=loose hostroot /lower \
      || die "cannot mount the host's / (9p)"
    ;;
  *) die "vm.fs=$FS: virtiofs or 9p" ;;
esac
mount -t 9p -o trans=virtio,version=9p2000.L,msize=512000 vmio /vmio || die "cannot mount the run folder"

mount -t tmpfs -o mode=0755 rw /rw
mkdir -p /rw/upper /rw/work
mount -t overlay -o lowerdir=/lower,upperdir=/rw/upper,workdir=/rw/work overlay /newroot \
  || die "cannot mount the overlay"
R=/newroot
mount -t proc proc $R/proc
mount -t sysfs sysfs $R/sys
mount -t devtmpfs devtmpfs $R/dev
mkdir -p $R/dev/pts $R/dev/shm
mount -t devpts devpts $R/dev/pts
mount -t tmpfs -o mode=1777 shm $R/dev/shm
# /tmp stays the overlay's (the host's, writes kept in the guest): a checkout under /tmp, e.g. a
# CI's fresh clone, is where the guest runs its commands
mount -t tmpfs -o mode=0755 run $R/run
mkdir -p $R/run/vmio
mount --bind /vmio $R/run/vmio
# the kernel's own modules where the guest's tools look for them
KVER=$(cat /kernel_version)
mkdir -p $R/lib/modules/$KVER
mount --bind /lib/modules/$KVER $R/lib/modules/$KVER
hostname forceskill-vm
ip link set lo up

# 32 MiB socket receive buffers (the default 208 KiB holds ~200 CAN frames, 0.1 s of the device's
# stream): a reader that TCG slows down falls behind and catches up instead of losing frames
echo 33554432 >/proc/sys/net/core/rmem_default
echo 33554432 >/proc/sys/net/core/rmem_max
modprobe -a can_raw can_bcm can_isotp can_gw vcan vxcan can_dev || die "cannot load the CAN modules"
MTU=$(arg vm.vcan 0)
if [ "$MTU" != 0 ]; then
  ip link add dev vcan0 type vcan || die "cannot add vcan0"
  ip link set vcan0 mtu "$MTU" || die "vcan0: MTU $MTU refused (16: classic CAN, 72: CAN FD)"
  ip link set vcan0 up
fi
if [ "$(arg vm.kvaser 0)" != 0 ]; then
  modprobe -a sja1000 kvaser_pci || die "cannot load the SJA1000 driver"
  # every controller's interrupt on CPU 0: qemu's SJA1000 keeps 64 bytes of received frames
  # (about 4) and its can-bus hands a frame to the other controller the instant one sends it, so
  # a sender whose transmit-complete interrupt runs on one vCPU while the receiver's waits on a
  # vCPU the host has descheduled overruns the receiver (a lost ISO-TP frame, a UDS answer that
  # never completes); on one CPU the receiver is drained between two frames
  for irq in $(cat /sys/class/net/can*/device/irq 2>/dev/null | sort -u); do
    echo 1 >/proc/irq/"$irq"/smp_affinity 2>/dev/null
  done
fi

chroot $R /bin/bash /run/vmio/cmd
echo $? >/vmio/rc
sync
umount $R/run/vmio 2>/dev/null
umount /vmio
off
