# shellcheck shell=bash
# Which test programs the guest runs: explicit executables, manifests, or the ctest tests of a
# build folder with a given label. Writes $SHARE/tests.list ("NAME PATH [ARGS...]").
# Sourced by tests/kernel/run.

KT_NAMES=" "

# The guest sees the host root at the same paths, but mounts its own /tmp and /run over it. A host
# folder there (a clone in /tmp, say) is listed in visible-paths: guest/init binds it back in.
keep_visible() {
  local top
  case $1 in
    /proc/* | /sys/* | /dev/*) die "$1: the guest has its own /proc, /sys and /dev" ;;
    /tmp/?* | /run/?*) top=$(echo "$1" | cut -d/ -f1-3) ;;
    *) return 0 ;;
  esac
  grep -qxF "$top" "$SHARE/visible-paths" 2>/dev/null || echo "$top" >>"$SHARE/visible-paths"
}

# add_test PATH [ARGS...]: checks PATH can run in the guest and appends it to tests.list.
add_test() {
  local path=$1
  shift
  [ -f "$path" ] || die "test program not found: $path"
  [ -x "$path" ] || die "test program is not executable: $path"
  path=$(realpath "$path")
  local name
  name=$(basename "$path" | tr -c 'A-Za-z0-9_.\n-' '_')
  local n=2 base=$name
  while [[ $KT_NAMES == *" $name "* ]]; do name=$base-$n; n=$((n + 1)); done
  KT_NAMES+="$name "
  if [ "$(head -c 4 "$path" | od -An -tx1 | tr -d ' ')" = 7f454c46 ]; then
    local machine
    machine=$(readelf -h "$path" | sed -n 's/^ *Machine: *//p')
    [[ $machine == *X86-64* ]] || die "$path is not an x86-64 program (${machine:-not readable})"
    local missing
    missing=$(ldd "$path" 2>&1 | awk '/not found/ { print $1 }' | tr '\n' ' ')
    [ -z "$missing" ] || die "$path: shared libraries not found on this host: $missing"
  fi
  keep_visible "$path"
  local a
  for a in "$@"; do
    [[ $a != *[[:space:]]* ]] || die "test arguments cannot contain blanks: '$a' (for $path)"
  done
  echo "$name $path $*" >>"$SHARE/tests.list"
}

# add_manifest FILE: one test per line, "PATH [ARGS...]"; PATH relative to the manifest's folder;
# blank lines and lines starting with # are skipped.
add_manifest() {
  local manifest=$1 dir line
  dir=$(cd "$(dirname "$manifest")" && pwd)
  while read -r line || [ -n "$line" ]; do
    case $line in '' | '#'*) continue ;; esac
    # shellcheck disable=SC2086 # split on blanks on purpose
    set -- $line
    local p=$1
    shift
    [[ $p == /* ]] || p=$dir/$p
    add_test "$p" "$@"
  done <"$manifest"
}

# add_argument ARG: an executable (ELF or #! script) is a test, any other file a manifest.
add_argument() {
  local arg=$1
  [ -e "$arg" ] || die "no such test program or manifest: $arg"
  if [ -x "$arg" ] && { [ "$(head -c 4 "$arg" | od -An -tx1 | tr -d ' ')" = 7f454c46 ] || [ "$(head -c 2 "$arg")" = '#!' ]; }; then
    add_test "$arg"
  else
    add_manifest "$arg"
  fi
}

# add_ctest_label BUILD_DIR LABEL_REGEX: every test program of the build folder with that label.
add_ctest_label() {
  local build=$1 label=$2 programs exe
  [ -f "$build/CTestTestfile.cmake" ] || die "$build is not a configured CMake build folder (no CTestTestfile.cmake)"
  programs=$(python3 "$KT_HERE/lib/ctest_programs.py" "$build" "$label" 2>"$SHARE/left-out.txt") ||
    { cat "$SHARE/left-out.txt" >&2; die "listing the ctest tests of $build failed"; }
  [ -n "$programs" ] || die "no ctest test labelled '$label' in $build (built?)"
  while read -r exe; do add_test "$exe"; done <<<"$programs"
}
