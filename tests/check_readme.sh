#!/usr/bin/env bash
# Compiles and runs (under ASan+UBSan) every ```c snippet of README.md, so the
# drop-in snippets stay true. Lines starting with '#' go to file scope, the
# rest into main(); tests/readme_prelude.h supplies the host-side variables
# the snippets refer to (a cube mesh, a ray and its host hit).
# Prints `N passed, M failed`; exit 1 on failure.
set -u
cd "$(dirname "$0")/.."
out=build/readme; mkdir -p "$out"; rm -f "$out"/snippet_*
awk -v dir="$out" '/^```c$/ {n++; f=sprintf("%s/snippet_%d.txt", dir, n); inb=1; next}
  /^```/ {inb=0; next} inb {print > f}' README.md
# one snippet: writes $out/<n>.c, builds and runs it; its verdict goes to
# $out/<n>.verdict (the snippets build $jobs at a time)
check_snippet() {
  local s=$1 n c lines
  n=$(basename "$s" .txt); c=$out/$n.c
  { echo '#include <stdio.h>'; echo '#include <stdlib.h>'; echo '#include <string.h>'
    grep '^#' "$s"; echo '#include "readme_prelude.h"'
    echo '#include <math.h>'
    echo 'int main(void) {'; grep -v '^#' "$s"
    # claims made in a snippet's comments, asserted (tests/readme_checks/)
    [ -f tests/readme_checks/$n.inc ] && cat tests/readme_checks/$n.inc
    echo 'return 0; }'; } > "$c"
  lines=$(wc -l < "$s")
  if [ "$lines" -gt 10 ]; then echo "README $n: $lines lines (at most 10)" > "$out/$n.verdict"; return; fi
  if gcc -std=gnu11 -Wall -Wextra -Werror -Wno-unused-variable -Wno-unused-but-set-variable -g1 -O1 \
       -fsanitize=address,undefined -fno-sanitize-recover=all -Iinclude -Itests "$c" -o "$out/$n" -lm \
       > "$out/$n.log" 2>&1 && "$out/$n" >> "$out/$n.log" 2>&1; then
    echo ok > "$out/$n.verdict"
  else
    { echo "README $n failed:"; head -n 20 "$out/$n.log"; } > "$out/$n.verdict"
  fi
}
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}; running=0
for s in "$out"/snippet_*.txt; do
  [ -f "$s" ] || continue
  check_snippet "$s" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n; running=$((running - 1)); fi
done
wait
pass=0; fail=0
for s in "$out"/snippet_*.txt; do
  [ -f "$s" ] || continue
  v=$out/$(basename "$s" .txt).verdict
  if [ "$(cat "$v" 2>/dev/null)" = ok ]; then pass=$((pass + 1)); else cat "$v" 2>/dev/null || echo "README $(basename "$s" .txt): no verdict"; fail=$((fail + 1)); fi
done
[ $((pass + fail)) -gt 0 ] || { echo "README: no snippets found"; fail=1; }
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
