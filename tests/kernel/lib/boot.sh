# shellcheck shell=bash
# Boots the guest: qemu with the cached vmlinux + initramfs, the run's share (read-write) and the
# host root (read-only) over 9p, a hard time limit and no reboot. Sourced by tests/kernel/run.

# choose_accel auto|kvm|tcg: prints the accelerator to use.
# /dev/kvm exists on this kind of machine but is the kvm_pvm backend, where a stock Debian kernel
# crawls (tens of seconds before setup_percpu): only a KVM that is not kvm_pvm and that qemu can
# open counts as usable.
choose_accel() {
  local want=$1
  if [ "$want" != auto ]; then echo "$want"; return; fi
  if [ -w /dev/kvm ] && [ ! -d /sys/module/kvm_pvm ] &&
    echo quit | timeout 20 qemu-system-x86_64 -accel kvm -machine none -nodefaults -display none \
      -monitor stdio >/dev/null 2>&1; then
    echo kvm
  else
    echo tcg
  fi
}

# boot_guest ACCEL SERIAL_LOG: returns qemu's status (124 when the hard limit stopped it).
boot_guest() {
  local accel=$1 serial=$2 cpu
  # -arch-capabilities: nested KVM may refuse that MSR and qemu then aborts with -cpu host
  # shellcheck disable=SC2054 # commas belong to the -cpu value
  if [ "$accel" = kvm ]; then cpu=(-accel kvm -cpu host,-arch-capabilities); else cpu=(-accel tcg -cpu max); fi
  local qemu=(qemu-system-x86_64 "${cpu[@]}" -m "$KT_MEMORY" -smp "$KT_SMP"
    -nodefaults -no-reboot -display none -monitor none -serial stdio
    -kernel "$KDIR/vmlinux" -initrd "$INITRD" -append "console=ttyS0 quiet panic=-1"
    -virtfs "local,path=$SHARE,mount_tag=share,security_model=none,id=share"
    -virtfs "local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap,id=hostroot")
  local rc=0
  if [ "$KT_VERBOSE" = 1 ]; then
    echo "console follows" >&2
    timeout -k 10 "$KT_TIMEOUT" "${qemu[@]}" </dev/null 2>&1 | tee "$serial" || rc=${PIPESTATUS[0]}
  else
    timeout -k 10 "$KT_TIMEOUT" "${qemu[@]}" </dev/null >"$serial" 2>&1 || rc=$?
  fi
  return "$rc"
}
