# shellcheck shell=bash
# The guest's initramfs: static busybox, guest/init and the kernel modules the tier loads (with
# their dependencies). Everything else the tests need comes from the host root over 9p.
# Sourced by tests/kernel/run; sets INITRD.

# Loaded by guest/init in this order. configfs/9p may be built in; modprobe then does nothing.
KT_MODULES="configfs virtio_pci 9pnet_virtio 9p can can-raw vcan irq-sim gpio-sim veth sch_netem evdev uinput"

build_initramfs() {
  local here=$1
  # Keyed by what goes in: editing guest/init or the module list makes a new one.
  local key
  key=$( { cat "$here/guest/init"; echo "$KT_MODULES"; dpkg-query -W -f="\${Version}" busybox-static; } | sha256sum | cut -c1-12)
  INITRD=$KDIR/initrd-$key.cpio.gz
  step "initramfs (busybox, guest/init, modules)"
  if [ -f "$INITRD" ]; then step_cached "$(basename "$INITRD")"; return; fi
  local root=$KDIR/initramfs
  rm -rf "$root"
  mkdir -p "$root"/{bin,sbin,proc,sys,dev,tmp,share,hostroot,etc/hubrt-kernel}
  cp /bin/busybox "$root/bin/busybox"
  local applet
  for applet in $(/bin/busybox --list); do
    [ -e "$root/bin/$applet" ] || ln -s busybox "$root/bin/$applet"
  done
  local image=$KDIR/image m f dest
  for m in $KT_MODULES; do
    modprobe -d "$image" -S "$KVER" --show-depends "$m" ||
      die "module $m not found in $KPKG (nor built here)"
  done | awk '$1 == "insmod" { print $2 }' | sort -u | while read -r f; do
    dest=$root${f#"$image"}
    mkdir -p "$(dirname "$dest")"
    # busybox modprobe cannot read compressed modules (Debian's 6.12 ships .ko.xz)
    case $f in
      *.xz) xz -dc "$f" >"${dest%.xz}" ;;
      *.zst) zstd -dcq "$f" >"${dest%.zst}" ;;
      *) cp "$f" "$dest" ;;
    esac
  done
  cp "$image/lib/modules/$KVER"/modules.{builtin,builtin.modinfo,order} "$root/lib/modules/$KVER/"
  depmod -b "$root" "$KVER"
  echo "$KT_MODULES" >"$root/etc/hubrt-kernel/modules"
  install -m 755 "$here/guest/init" "$root/init"
  rm -f "$KDIR"/initrd-*.cpio.gz
  (cd "$root" && find . | cpio -o -H newc -R 0:0 --quiet | gzip -1) >"$INITRD.part"
  mv "$INITRD.part" "$INITRD"
  rm -rf "$root"
  step_done "$(du -h "$INITRD" | cut -f1)"
}
