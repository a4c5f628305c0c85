# shellcheck shell=bash
# Debian kernel for the kernel tier: resolve the version, fetch image, headers and source from
# Debian's archive (apt-get download, never installed), extract an uncompressed vmlinux, and build
# the gpio-sim and IRQ-simulator modules that Debian does not ship.
# Sourced by tests/kernel/run; sets KPKG, KPKGVER, KVER, KSERIES, KDIR.

# resolve_kernel [PACKAGE]: the image package (default: what linux-image-amd64 depends on).
resolve_kernel() {
  KPKG=${1:-}
  if [ -z "$KPKG" ]; then
    KPKG=$(apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-/ { print $2; exit }')
    if [ -z "$KPKG" ]; then
      apt_update_once
      KPKG=$(apt-cache depends linux-image-amd64 | awk '/Depends: linux-image-/ { print $2; exit }')
    fi
  fi
  [ -n "$KPKG" ] || die "cannot resolve the kernel package (apt-cache depends linux-image-amd64)"
  KPKGVER=$(apt-cache policy "$KPKG" 2>/dev/null | awk '/Candidate:/ { print $2; exit }')
  if [ -z "$KPKGVER" ] || [ "$KPKGVER" = "(none)" ]; then
    apt_update_once
    KPKGVER=$(apt-cache policy "$KPKG" | awk '/Candidate:/ { print $2; exit }')
  fi
  case $KPKGVER in '' | '(none)') die "$KPKG is not in the archive's package lists" ;; esac
  KVER=${KPKG#linux-image-}                       # e.g. 6.1.0-56-amd64: uname -r in the guest
  KSERIES=$(echo "$KVER" | cut -d. -f1-2)         # e.g. 6.1: names linux-source-6.1
  KDIR=$KT_CACHE/${KVER}_$KPKGVER
  mkdir -p "$KDIR"
}

# deb_file DIR PKG: path of the downloaded .deb for PKG in DIR (empty if none).
deb_file() { find "$1" -maxdepth 1 -name "$2_*.deb" -print -quit; }

# fetch_extract PKG[=VER] DEST: download one package and unpack its files under DEST.
fetch_extract() {
  local spec=$1 dest=$2
  apt_download "$KT_CACHE/debs" "$spec"
  extract_downloaded "${spec%%=*}" "$dest"
}
# extract_downloaded PKG DEST: unpacks the .deb of PKG that a download left in the cache's debs/.
extract_downloaded() {
  local pkg=$1 dest=$2 deb
  deb=$(deb_file "$KT_CACHE/debs" "$pkg")
  [ -n "$deb" ] || die "apt-get download $pkg produced no .deb"
  mkdir -p "$dest"
  dpkg -x "$deb" "$dest"
  rm -f "$deb"   # the extracted tree is what the cache keeps
}

kernel_image() {
  step "kernel image $KPKG ($KPKGVER)"
  if [ -f "$KDIR/.image.ok" ]; then step_cached; return; fi
  rm -rf "$KDIR/image"
  fetch_extract "$KPKG=$KPKGVER" "$KDIR/image"
  [ -f "$KDIR/image/boot/vmlinuz-$KVER" ] || die "$KPKG has no boot/vmlinuz-$KVER"
  touch "$KDIR/.image.ok"
  step_done "$(du -sh "$KDIR/image" | cut -f1) extracted"
}

# The source package supplies gpio-sim, the IRQ simulator and scripts/extract-vmlinux.
kernel_source() {
  step "kernel source linux-source-$KSERIES (gpio-sim, irq_sim, extract-vmlinux)"
  if [ -f "$KDIR/.source.ok" ]; then step_cached; return; fi
  local debs=$KT_CACHE/debs top=linux-source-$KSERIES
  apt_download "$debs" "$top=$KPKGVER"
  local deb
  deb=$(deb_file "$debs" "$top")
  rm -rf "$KDIR/src"
  mkdir -p "$KDIR/src"
  # only four files of the ~130 MB tarball are needed
  dpkg --fsys-tarfile "$deb" | tar -xO "./usr/src/$top.tar.xz" |
    tar -xJ -C "$KDIR/src" --strip-components=1 \
      "$top/drivers/gpio/gpio-sim.c" "$top/drivers/gpio/gpiolib.h" \
      "$top/kernel/irq/irq_sim.c" "$top/scripts/extract-vmlinux" ||
    die "extracting gpio-sim/irq_sim/extract-vmlinux from $deb failed"
  rm -f "$deb"
  touch "$KDIR/.source.ok"
  step_done
}

# qemu boots the ELF vmlinux through its PVH entry: under TCG that skips seconds of in-guest
# decompression of the bzImage.
kernel_vmlinux() {
  step "uncompressed vmlinux"
  if [ -f "$KDIR/.vmlinux.ok" ]; then step_cached; return; fi
  sh "$KDIR/src/scripts/extract-vmlinux" "$KDIR/image/boot/vmlinuz-$KVER" >"$KDIR/vmlinux" ||
    die "scripts/extract-vmlinux failed on vmlinuz-$KVER"
  touch "$KDIR/.vmlinux.ok"
  step_done "$(du -h "$KDIR/vmlinux" | cut -f1)"
}

kernel_headers() {
  step "kernel headers linux-headers-$KVER"
  if [ -f "$KDIR/.headers.ok" ]; then step_cached; return; fi
  rm -rf "$KDIR/headers"
  local p
  for p in "linux-headers-$KVER" $(apt-cache depends "linux-headers-$KVER" |
    awk '/Depends: linux-(headers|kbuild)-/ { print $2 }'); do
    # Same upload as the image where it exists (kbuild may be newer: it only needs to be >=). The
    # package lists may still name it after the archive replaced it (2026-11-28: linux-kbuild-6.1
    # 6.1.192-2 listed, 6.1.192-3 in the archive, the image still 6.1.192-2): then the archive's.
    if apt-cache show "$p=$KPKGVER" >/dev/null 2>&1 && try_apt_download "$KT_CACHE/debs" "$p=$KPKGVER"; then
      extract_downloaded "$p" "$KDIR/headers"
    else
      fetch_extract "$p" "$KDIR/headers"
    fi
  done
  # the flavour's Makefile includes the common headers by absolute path: point it into the cache
  sed -i "s#/usr/src/#$KDIR/headers/usr/src/#" "$KDIR/headers/usr/src/linux-headers-$KVER/Makefile"
  touch "$KDIR/.headers.ok"
  step_done
}

# gpio-sim needs CONFIG_IRQ_SIM, which Debian's kernel does not select: irq_sim.c is built as a
# module too. It calls irq_to_desc(), which is not exported to modules; generic_handle_irq() runs
# the same flow handler (handle_simple_irq, set by irq_sim) through an exported entry point.
kernel_modules() {
  step "build gpio-sim.ko + irq-sim.ko out of tree"
  if [ -f "$KDIR/.modules.ok" ]; then step_cached; return; fi
  local m=$KDIR/modbuild
  rm -rf "$m"
  mkdir -p "$m"
  cp "$KDIR/src/drivers/gpio/gpio-sim.c" "$KDIR/src/drivers/gpio/gpiolib.h" "$KDIR/src/kernel/irq/irq_sim.c" "$m/"
  sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$m/irq_sim.c"
  if grep -q 'irq_to_desc' "$m/irq_sim.c"; then
    die "irq_sim.c of $KPKGVER still calls irq_to_desc(): the generic_handle_irq() fix no longer applies"
  fi
  cat >"$m/irq-sim-module.c" <<'MODSRC'
/* irq_sim.c is built into the kernel when CONFIG_IRQ_SIM is selected; wrap it as a module. */
#include <linux/module.h>
#include "irq_sim.c"
MODULE_LICENSE("GPL");
MODSRC
  printf 'obj-m := irq-sim.o gpio-sim.o\nirq-sim-y := irq-sim-module.o\n' >"$m/Kbuild"
  # BTF for modules needs pahole and the vmlinux BTF: irrelevant for loading them
  logged "$KT_CACHE/logs/modules-$KVER.log" nice -n 10 make -j2 -C "$KDIR/headers/usr/src/linux-headers-$KVER" \
    M="$m" CONFIG_DEBUG_INFO_BTF_MODULES= modules
  local extra=$KDIR/image/lib/modules/$KVER/extra
  mkdir -p "$extra"
  cp "$m/gpio-sim.ko" "$m/irq-sim.ko" "$extra/"
  depmod -b "$KDIR/image" "$KVER"
  touch "$KDIR/.modules.ok"
  step_done
}
