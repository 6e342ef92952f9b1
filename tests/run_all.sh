#!/usr/bin/env bash
# Runs every built test binary (normal pass, then the ASan+UBSan pass) and the
# header compile matrix, then prints the grand total as its last line:
# `N passed, M failed`. Exit status 1 when anything failed or a binary crashed.
# Usage: tests/run_all.sh BUILD_DIR SAN_BUILD_DIR [case filters...]
set -u
cd "$(dirname "$0")/.."
build=$1; san=$2; shift 2
total_pass=0; total_fail=0; log=build/test_logs; mkdir -p "$log"
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}

add_counts() { # $1 = label, $2 = output file, $3 = exit status
  local line p f
  line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$2" | tail -n 1)
  if [ -z "$line" ]; then
    echo "$1: crashed or printed no totals (exit $3); see $2" >&2; tail -n 20 "$2" >&2
    total_fail=$((total_fail + 1)); return
  fi
  p=${line%% passed*}; f=${line#*, }; f=${f%% failed*}
  if [ "$3" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; echo "$1: exit $3 with no failed check" >&2; fi
  # a whole binary that checked nothing (and was not filtered) is a defect
  if [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "${4:-0}" -eq 0 ]; then f=1; echo "$1: ran no checks" >&2; fi
  total_pass=$((total_pass + p)); total_fail=$((total_fail + f))
  printf '%-44s %s\n' "$1" "$line" >&2
}

run_one() { # $1 = binary, $2 = label, rest = case filters; writes $log/<label>_<name>.all
  local t=$1 label=$2 name start status
  shift 2
  name=$(basename "$t"); start=$(date +%s)
  "$t" "$@" > "$log/${label}_$name.log" 2> "$log/${label}_$name.err"; status=$?
  cat "$log/${label}_$name.err" "$log/${label}_$name.log" > "$log/${label}_$name.all"
  echo "$status $(( $(date +%s) - start ))" > "$log/${label}_$name.status"
}
export -f run_one
export log

run_pass() { # $1 = dir, $2 = label, rest = case filters; binaries run $jobs at a time
  local dir=$1 label=$2 t name status secs
  shift 2
  ls "$dir"/test_* 2>/dev/null | xargs -r -P "$jobs" -I{} bash -c 'run_one "$@"' _ {} "$label" "$@"
  for t in "$dir"/test_*; do
    [ -x "$t" ] || continue
    name=$(basename "$t")
    read -r status secs < "$log/${label}_$name.status" || { status=99; secs=0; }
    [ "$status" -ne 0 ] && grep -E 'FAIL|ERROR|runtime error' "$log/${label}_$name.all" | head -n 20 >&2
    add_counts "$label $name (${secs}s)" "$log/${label}_$name.all" "$status" "$#"
  done
}

echo "== header compile matrix" >&2
tests/check_headers.sh > "$log/check_headers.log" 2>&1; status=$?
grep -E '^FAIL' -A 15 "$log/check_headers.log" | head -n 40 >&2
add_counts "check-headers" "$log/check_headers.log" $status

echo "== bench sources in sync with the headers" >&2
# bench_interval_ops.cpp renames interval.h's names for its IV_FAST copy; the
# benches are not built by make test, so a stale list would only show in make bench
if command -v python3 >/dev/null 2>&1; then
  python3 scripts/interval_fast_names.py --check > "$log/fast_names.log" 2>&1; status=$?
  grep -v 'passed, ' "$log/fast_names.log" | head -n 5 >&2
  add_counts "interval fast names" "$log/fast_names.log" $status
else
  echo "python3 not found: the IV_FAST renaming check is skipped" >&2
fi

echo "== README snippets" >&2
tests/check_readme.sh > "$log/readme.log" 2>&1; status=$?
grep -v 'passed, ' "$log/readme.log" | head -n 20 >&2
add_counts "README snippets" "$log/readme.log" $status

echo "== tests" >&2
filters=("$@")
run_pass "$build" normal "${filters[@]}"
echo "== tests under ASan + UBSan (FILIGREE_TEST_SCALE=${FILIGREE_SAN_SCALE:-0.05})" >&2
FILIGREE_TEST_SCALE=${FILIGREE_SAN_SCALE:-0.05} \
ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  run_pass "$san" sanitize "${filters[@]}"

echo "== example self-tests" >&2
# examples with a --selftest: it prints `N passed, M failed`, or one
# `ok …` / `FAIL …` line per check (counted here)
for n in sharp_cube_icosphere rounded_edges; do
  e=$build/../examples/$n
  [ -f "$e" ] || { total_fail=$((total_fail + 1)); echo "selftest $n: example not built" >&2; continue; }
  "$e" --selftest > "$log/selftest_$n.all" 2>&1; status=$?
  if ! grep -qE '^[0-9]+ passed, [0-9]+ failed' "$log/selftest_$n.all"; then
    echo "$(grep -c '^ok ' "$log/selftest_$n.all") passed, $(grep -c '^FAIL' "$log/selftest_$n.all") failed" >> "$log/selftest_$n.all"
  fi
  grep '^FAIL' "$log/selftest_$n.all" | head -n 10 >&2
  add_counts "selftest $n" "$log/selftest_$n.all" "$status"
done

echo "== short fuzz runs (${FILIGREE_FUZZ_SECONDS:-20} s each)" >&2
for f in "$build"/../fuzz/fuzz_*; do
  # the fuzzers only: their corpus folders (fuzz_*.corpus, from an earlier
  # run) are executable too
  [ -f "$f" ] && [ -x "$f" ] || continue
  n=$(basename "$f"); corpus=build/fuzz/$n.corpus; mkdir -p "$corpus"
  seeds=""; [ -d tests/corpus/$n ] && seeds=tests/corpus/$n
  if "$f" -max_total_time="${FILIGREE_FUZZ_SECONDS:-20}" -print_final_stats=0 "$corpus" $seeds > "$log/$n.log" 2>&1; then
    total_pass=$((total_pass + 1)); printf '%-44s ok\n' "fuzz $n" >&2
  else
    total_fail=$((total_fail + 1)); echo "fuzz $n: crash or sanitizer report; see $log/$n.log" >&2
    grep -E 'ERROR|SUMMARY|Test unit written' "$log/$n.log" | head -n 10 >&2
  fi
done

echo "== install and pkg-config" >&2
inst=build/install_check; rm -rf "$inst"
if make --no-print-directory install PREFIX="$PWD/$inst" > "$log/install.log" 2>&1 \
   && cflags=$(PKG_CONFIG_PATH="$PWD/$inst/lib/pkgconfig" pkg-config --cflags filigree) \
   && printf '#include "interval.h"\n#include "frep.h"\n#include "rounded_edges.h"\n#include "grooves.h"\nint main(void){return 0;}\n' \
      | cc -std=c99 $cflags -x c - -o "$inst/a.out" >> "$log/install.log" 2>&1; then
  total_pass=$((total_pass + 1)); printf '%-44s ok\n' "install + pkg-config" >&2
else
  total_fail=$((total_fail + 1)); echo "install + pkg-config failed; see $log/install.log" >&2
fi

echo "$total_pass passed, $total_fail failed"
[ "$total_fail" -eq 0 ]
