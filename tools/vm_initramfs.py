#!/usr/bin/env python3
"""Build the guest's initramfs of scripts/vm.sh: a static busybox, the guest's /init
(scripts/vm_init.sh) and the kernel modules it loads, taken with their dependencies from a kernel
tree unpacked from Debian's linux-image .deb (never the host's /lib/modules). Writes an
uncompressed newc cpio (nothing to decompress under TCG) atomically, and a modules.dep for
busybox's modprobe. Needs neither cpio nor kmod: the dependencies come from each module's
.modinfo "depends=" entry. With --vmlinux it also writes the kernel's uncompressed ELF image
(qemu boots it through its PVH entry: no decompression under TCG, about 8 s less per boot).

    tools/vm_initramfs.py --kernel-root build/vm/kernel --busybox /bin/busybox \\
        --init scripts/vm_init.sh -o build/vm/initramfs.cpio --vmlinux build/vm/vmlinux
"""

from __future__ import annotations

import argparse
import lzma
import os
import sys
import tempfile
from pathlib import Path

# What the guest loads, by module name: the virtio transport and the two shared-file-system
# drivers, the overlay, and Linux CAN (core, raw, bcm, ISO-TP, gateway, vcan/vxcan, the SJA1000
# driver with its Kvaser PCI glue, which qemu's kvaser_pci device is).
MODULES = (
    "virtio_pci",
    "9pnet_virtio",
    "9p",
    "virtiofs",
    "overlay",
    "can_raw",
    "can_bcm",
    "can_isotp",
    "can_gw",
    "vcan",
    "vxcan",
    "can_dev",
    "sja1000",
    "kvaser_pci",
)


def norm(name: str) -> str:
    """The kernel's module name of a file or a depends= entry (dashes are underscores)."""
    return name.removesuffix(".ko").replace("-", "_")


def index(moddir: Path) -> dict[str, Path]:
    """Module name -> path relative to moddir, for every .ko of the tree."""
    found: dict[str, Path] = {}
    for p in moddir.rglob("*.ko"):
        found[norm(p.name)] = p.relative_to(moddir)
    return found


def depends(ko: Path) -> list[str]:
    """The module's depends= entry of .modinfo (the names it needs loaded first)."""
    for field in ko.read_bytes().split(b"\0"):
        if field.startswith(b"depends="):
            value = field[len(b"depends=") :].decode()
            return [norm(d) for d in value.split(",") if d]
    return []


def closure(moddir: Path, mods: dict[str, Path], wanted: tuple[str, ...]) -> dict[str, list[str]]:
    """Every wanted module and what it needs, name -> its direct dependencies."""
    deps: dict[str, list[str]] = {}
    todo = list(wanted)
    while todo:
        name = todo.pop()
        if name in deps:
            continue
        if name not in mods:
            sys.exit(f"vm_initramfs: module {name} is not in {moddir} (a kernel without it?)")
        deps[name] = depends(moddir / mods[name])
        todo.extend(deps[name])
    return deps


def load_order(deps: dict[str, list[str]], name: str) -> list[str]:
    """name and everything it needs, each after what it needs (modules.dep lists it reversed)."""
    order: list[str] = []

    def visit(n: str) -> None:
        if n not in order:
            for d in deps[n]:
                visit(d)
            order.append(n)

    visit(name)
    return order


def cpio_entry(name: str, mode: int, data: bytes = b"", ino: int = 0) -> bytes:
    """One newc record (header, name, data, each padded to 4 bytes)."""
    fields = (ino, mode, 0, 0, 1, 0, len(data), 0, 0, 0, 0, len(name) + 1, 0)
    head = b"070701" + b"".join(b"%08X" % f for f in fields)
    out = head + name.encode() + b"\0"
    out += b"\0" * (-len(out) % 4)
    out += data + b"\0" * (-len(data) % 4)
    return out


def build(kernel_root: Path, busybox: Path, init: Path) -> bytes:
    versions = sorted((kernel_root / "lib/modules").iterdir())
    if len(versions) != 1:
        sys.exit(f"vm_initramfs: expected one kernel under {kernel_root}/lib/modules, found {len(versions)}")
    kver = versions[0].name
    moddir = versions[0]
    mods = index(moddir)
    deps = closure(moddir, mods, MODULES)
    base = f"lib/modules/{kver}"
    dirs = ["bin", "sbin", "dev", "proc", "sys", "lib", "lib/modules", base, "lower", "rw", "newroot", "vmio"]
    dirs += sorted({str(Path(base) / p).rsplit("/", 1)[0] for p in (str(mods[n]) for n in deps)})
    seen: set[str] = set()
    out = bytearray()
    ino = 1
    for d in dirs:
        for i in range(1, d.count("/") + 2):  # parents first
            part = "/".join(d.split("/")[:i])
            if part not in seen:
                seen.add(part)
                out += cpio_entry(part, 0o040755, ino=ino)
                ino += 1
    files = {
        "bin/busybox": (0o100755, busybox.read_bytes()),
        "init": (0o100755, init.read_bytes()),
    }
    dep_lines = []
    for name in sorted(deps):
        rel = mods[name]
        files[f"{base}/{rel}"] = (0o100644, (moddir / rel).read_bytes())
        dep_lines.append(f"{rel}: " + " ".join(str(mods[d]) for d in reversed(load_order(deps, name)[:-1])))
    files[f"{base}/modules.dep"] = (0o100644, ("\n".join(dep_lines) + "\n").encode())
    files["kernel_version"] = (0o100644, kver.encode() + b"\n")
    for name, (mode, data) in files.items():
        out += cpio_entry(name, mode, data, ino)
        ino += 1
    out += cpio_entry("TRAILER!!!", 0)
    return bytes(out)


def vmlinux(kernel_root: Path) -> bytes:
    """The ELF inside the xz-compressed bzImage of boot/vmlinuz-* (Debian's kernels use xz)."""
    (image,) = (kernel_root / "boot").glob("vmlinuz-*")
    data = image.read_bytes()
    at = data.find(b"\xfd7zXZ\x00")
    if at < 0:
        sys.exit(f"vm_initramfs: {image} holds no xz stream (a kernel compressed otherwise?)")
    elf = lzma.LZMADecompressor().decompress(data[at:])
    if not elf.startswith(b"\x7fELF"):
        sys.exit(f"vm_initramfs: the xz stream of {image} is not an ELF image")
    return elf


def write_atomically(path: Path, data: bytes) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name + ".")
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kernel-root", type=Path, required=True, help="the unpacked linux-image .deb")
    ap.add_argument("--busybox", type=Path, required=True, help="a statically linked busybox")
    ap.add_argument("--init", type=Path, required=True, help="the guest's /init script")
    ap.add_argument("-o", "--output", type=Path, required=True)
    ap.add_argument("--vmlinux", type=Path, help="also write the kernel's uncompressed ELF image here")
    a = ap.parse_args()
    data = build(a.kernel_root, a.busybox, a.init)
    write_atomically(a.output, data)
    print(f"vm_initramfs: {a.output} ({len(data) // 1024} KiB)")
    if a.vmlinux is not None:
        elf = vmlinux(a.kernel_root)
        write_atomically(a.vmlinux, elf)
        print(f"vm_initramfs: {a.vmlinux} ({len(elf) // 1024} KiB)")


if __name__ == "__main__":
    main()
