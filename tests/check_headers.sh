#!/usr/bin/env bash
# The header compile matrix (make check-headers).
# For gcc and clang, as C99, C11 and C++17, under -Werror with our warning set:
#   - each header alone: declarations only; included twice; with the
#     implementation (included twice, before and after; also optimised at
#     -O2 as C99, by g++ as C++17, and with gcc at -O1 and -O3); with XX_STATIC;
#     and with the implementation for every combination of its XX_NO_* switches
#     (one switch: the whole matrix; two or more: gcc and clang as C99);
#   - all four headers together, with and without the implementations.
# XX_NO_* switches are found by grepping the header, so new ones are covered
# without editing this file. Prints one line per failure and a final
# `N passed, M failed`; exit status 1 on any failure.
set -u
cd "$(dirname "$0")/.."
out=build/check_headers
mkdir -p "$out"
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}

warn="-Wall -Wextra -Wpedantic -Werror -Wshadow -Wconversion -Wno-sign-conversion"
cwarn="$warn -Wstrict-prototypes -Wmissing-prototypes"
compilers=()
for c in gcc clang; do command -v "$c" >/dev/null && compilers+=("$c"); done
[ ${#compilers[@]} -gt 0 ] || { echo "check-headers: no C compiler (install gcc or clang)"; exit 1; }

declare -A prefix=([interval.h]=IV [frep.h]=FR [rounded_edges.h]=RE [grooves.h]=GR)
headers=()
for h in interval.h frep.h rounded_edges.h grooves.h; do [ -f include/$h ] && headers+=("$h"); done
# ONLY=grooves (a header's base name) checks that header alone and skips the
# all-headers units: a quick check while working on one module.
if [ -n "${ONLY:-}" ]; then headers=("$ONLY.h"); [ -f "include/$ONLY.h" ] || { echo "check-headers: no include/$ONLY.h"; exit 1; }; fi

# Emit one translation unit: $1 = name, rest = lines.
unit() { local name=$1; shift; printf '%s\n' "$@" > "$out/$name.c"; echo "$name"; }

cases=(); declare -A nsw # switches set in a unit
for h in "${headers[@]}"; do
  P=${prefix[$h]}; b=${h%.h}
  switches=$(grep -oE "\b${P}_NO_[A-Z0-9_]+" include/$h | sort -u)
  # optional switches that change semantics but are not NO_ (e.g. IV_FAST)
  extra=$(grep -oE "^ *# *if(def)? *!?\(? *(defined)?\(? *${P}_FAST\b" include/$h | grep -oE "${P}_FAST" | sort -u)
  cases+=("$(unit ${b}_decl "#include \"$h\"" "int filigree_check_dummy(void);" "int filigree_check_dummy(void) { return 0; }")")
  cases+=("$(unit ${b}_twice "#include \"$h\"" "#include \"$h\"" "int filigree_check_dummy(void);" "int filigree_check_dummy(void) { return 0; }")")
  cases+=("$(unit ${b}_impl "#include \"$h\"" "#define ${P}_IMPLEMENTATION" "#include \"$h\"" "#include \"$h\"")")
  cases+=("$(unit ${b}_static "#define ${P}_STATIC" "#define ${P}_IMPLEMENTATION" "#include \"$h\"")")
  # every combination of the switches (power set)
  sw=($switches $extra)
  n=${#sw[@]}
  for ((mask = 1; mask < (1 << n); mask++)); do
    lines=(); tag=""
    for ((i = 0; i < n; i++)); do
      if (( mask & (1 << i) )); then lines+=("#define ${sw[$i]}"); tag="${tag}_${sw[$i]#${P}_}"; fi
    done
    u=$(unit "${b}_impl${tag,,}" "${lines[@]}" "#define ${P}_IMPLEMENTATION" "#include \"$h\"")
    cases+=("$u"); nsw[$u]=${#lines[@]}
  done
done
all_decl=(); all_impl=()
[ -n "${ONLY:-}" ] && headers_all=() || headers_all=("${headers[@]}")
for h in "${headers_all[@]}"; do
  all_decl+=("#include \"$h\""); all_impl+=("#define ${prefix[$h]}_IMPLEMENTATION" "#include \"$h\"")
done
[ -z "${ONLY:-}" ] && cases+=("$(unit all_decl "${all_decl[@]}" "int filigree_check_dummy(void);" "int filigree_check_dummy(void) { return 0; }")")
[ -z "${ONLY:-}" ] && cases+=("$(unit all_impl "${all_impl[@]}" "${all_decl[@]}")")

# Build the job list: case x compiler x standard. gcc compiles (-c): some
# of its warnings (-Wunused-function, -Wreturn-type) come from passes that
# -fsyntax-only skips; as C11 it only parses (C11 and C99 differ in the
# front end, and the C99 unit ran those passes). clang gives every warning
# from its front end, so it parses too, except where it optimises.
joblist=$out/jobs.txt; : > "$joblist"
for c in "${cases[@]}"; do
  # the full implementation units also build optimised, as C99 and C++17:
  # some warnings (clang's -Wpass-failed, gcc's -Wmaybe-uninitialized)
  # only appear there; gcc's -Wmaybe-uninitialized differs between levels:
  # -O1 and -O3 found warnings that -O2 did not (rounded_edges.h, frep.h,
  # 2026-12-05). all_impl holds the same code: it is not optimised again.
  opt=""; case "$c" in all_impl) ;; *_impl) opt="-O2" ;; esac
  if [ -n "$opt" ] && command -v gcc >/dev/null; then
    for o in -O1 -O3; do echo "gcc -std=c99 $o $cwarn -Iinclude -c $out/$c.c -o /dev/null" >> "$joblist"; done
  fi
  # two or more switches: the code each one selects was compiled by the
  # full matrix in its one-switch unit; what is left to find is a helper
  # that only the dropped features used, or two switches' code that does
  # not fit together: gcc compiles it as C99, clang parses it as C99
  if [ "${nsw[$c]:-0}" -ge 2 ]; then
    echo "gcc -std=c99 $cwarn -Iinclude -c -o /dev/null $out/$c.c" >> "$joblist"
    echo "clang -std=c99 $cwarn -Iinclude -fsyntax-only $out/$c.c" >> "$joblist"
    continue
  fi
  for cc in "${compilers[@]}"; do
    cxx=g++; [ "$cc" = clang ] && cxx=clang++
    gen="-c -o /dev/null"; gen11="-fsyntax-only"; genxx=$gen; optxx=$opt
    [ "$cc" = clang ] && [ -z "$opt" ] && gen="-fsyntax-only"
    # as C++ the switch combinations are parsed only: the headers' C++-only
    # code is their extern "C" wrappers, and the C99 units ran gcc's passes
    # over the same code; clang optimises it as C only
    case "$c" in *_impl_*) genxx="-fsyntax-only" ;; esac
    [ "$cc" = clang ] && { genxx="-fsyntax-only"; optxx=""; }
    echo "$cc -std=c99 $opt $cwarn -Iinclude $gen $out/$c.c" >> "$joblist"
    echo "$cc -std=c11 $cwarn -Iinclude $gen11 $out/$c.c" >> "$joblist"
    echo "$cxx -x c++ -std=c++17 $optxx $warn -Iinclude $genxx $out/$c.c" >> "$joblist"
  done
done

# A compiler that crashes (seen under heavy load) is retried once; a diagnostic is not.
run_one() {
  local out try
  for try in 1 2; do
    if out=$(eval "$1" 2>&1); then echo PASS; return; fi
    grep -qE 'PLEASE submit a bug report|internal compiler error|Killed signal|Segmentation fault' <<< "$out" || break
  done
  printf 'FAIL: %s\n%s\n' "$1" "$(printf '%s\n' "$out" | head -n 15)"
}
export -f run_one
results=$(xargs -P "$jobs" -d '\n' -I{} bash -c 'run_one "$@"' _ {} < "$joblist")
# No header calls libc's allocator but through its XX_MALLOC/XX_FREE default,
# nor qsort/bsearch (glibc's qsort mallocs a buffer from 1 KiB: a query
# must not allocate, a builder only through the hooks). One result per header.
for h in "${headers[@]}"; do
  bad=$(grep -nE '\b(qsort|bsearch|malloc|calloc|realloc|free|aligned_alloc|posix_memalign)[[:space:]]*\(' "include/$h" |
        grep -vE 'define [A-Z]+_(MALLOC|FREE)\(|^[0-9]+:[[:space:]]*(/\*|\*|//)|re_free|gr_grid_free|fr_tape_free|fr_builder_free|fr_prepared_free|_free\(' || true)
  if [ -z "$bad" ]; then results+=$'\nPASS'; else results+=$'\n'"FAIL: include/$h calls libc's allocator or qsort outside its hooks:"$'\n'"$bad"; fi
done
pass=$(grep -c '^PASS$' <<< "$results")
fail=$(grep -c '^FAIL: ' <<< "$results")
grep -v '^PASS$' <<< "$results"
echo "check-headers: ${#headers[@]} headers, ${#cases[@]} units, ${#compilers[@]} compilers x 3 standards"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
