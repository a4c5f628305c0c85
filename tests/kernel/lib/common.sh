# shellcheck shell=bash
# Progress output, apt helpers and the cache lock shared by the kernel-tier runner's steps.
# Sourced by tests/kernel/run; expects KT_CACHE to be set.

KT_STEP=0
KT_STEPS=${KT_STEPS:-10}
KT_STEP_T0=0

# step "what it does": starts a numbered step; close it with step_done / step_cached.
step() {
  KT_STEP=$((KT_STEP + 1))
  KT_STEP_T0=$(date +%s.%N)
  printf '[kernel] [%d/%d] %s ... ' "$KT_STEP" "$KT_STEPS" "$*" >&2
}
step_elapsed() { awk -v a="$KT_STEP_T0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f s", b - a }'; }
step_done() { echo "done${1:+ ($1)} [$(step_elapsed)]" >&2; }
step_cached() { echo "cached${1:+ ($1)}" >&2; }
note() { echo "[kernel]       $*" >&2; }
die() {
  echo >&2
  echo "[kernel] error: $*" >&2
  exit 2
}

# Runs a command with its output in a log file; on failure shows the log's tail and stops.
logged() {
  local log=$1
  shift
  if ! "$@" >"$log" 2>&1; then
    echo "failed" >&2
    tail -n 40 "$log" | sed 's/^/[kernel]   | /' >&2
    die "'$*' failed (full log: $log)"
  fi
}

APT=(apt-get -o DPkg::Lock::Timeout=600 -o APT::Get::Show-Versions=false)
KT_APT_UPDATED=0

apt_update_once() {
  [ "$KT_APT_UPDATED" = 1 ] && return 0
  logged "$KT_CACHE/logs/apt-update.log" "${APT[@]}" update
  KT_APT_UPDATED=1
}

# missing_packages PKG...: prints the ones that are not installed.
missing_packages() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'ok installed' || echo "$p"
  done
}

# apt_download DIR PKG[=VERSION]: downloads one .deb from Debian's archive into DIR (never installs).
# Retries once after 'apt-get update' because stale package lists name versions the archive dropped.
apt_download() {
  try_apt_download "$@" ||
    { tail -n 20 "$KT_CACHE/logs/download.log" >&2; die "apt-get download $2 failed"; }
}
# try_apt_download DIR PKG[=VERSION]: as apt_download, but returns non-zero instead of stopping.
try_apt_download() {
  local dir=$1 spec=$2
  mkdir -p "$dir"
  (cd "$dir" && "${APT[@]}" download "$spec") >"$KT_CACHE/logs/download.log" 2>&1 && return 0
  apt_update_once
  (cd "$dir" && "${APT[@]}" download "$spec") >"$KT_CACHE/logs/download.log" 2>&1
}

# The build steps write into the shared cache: one runner at a time (booting runs unlocked).
lock_cache() {
  exec {KT_LOCK_FD}>"$KT_CACHE/.lock"
  if ! flock -n "$KT_LOCK_FD"; then
    note "another runner is preparing the cache; waiting for it"
    flock "$KT_LOCK_FD"
  fi
}
unlock_cache() { flock -u "$KT_LOCK_FD"; }
