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
pass=0; fail=0
for s in "$out"/snippet_*.txt; do
  [ -f "$s" ] || continue
  n=$(basename "$s" .txt); c=$out/$n.c
  { echo '#include <stdio.h>'; echo '#include <stdlib.h>'; echo '#include <string.h>'
    grep '^#' "$s"; echo '#include "readme_prelude.h"'
    echo '#include <math.h>'
    echo 'int main(void) {'; grep -v '^#' "$s"
    # claims made in a snippet's comments, asserted (tests/readme_checks/)
    [ -f tests/readme_checks/$n.inc ] && cat tests/readme_checks/$n.inc
    echo 'return 0; }'; } > "$c"
  lines=$(wc -l < "$s")
  if [ "$lines" -gt 10 ]; then echo "README $n: $lines lines (at most 10)"; fail=$((fail + 1)); continue; fi
  if gcc -std=gnu11 -Wall -Wextra -Werror -Wno-unused-variable -Wno-unused-but-set-variable -g -O1 \
       -fsanitize=address,undefined -fno-sanitize-recover=all -Iinclude -Itests "$c" -o "$out/$n" -lm \
       > "$out/$n.log" 2>&1 && "$out/$n" >> "$out/$n.log" 2>&1; then
    pass=$((pass + 1))
  else
    echo "README $n failed:"; head -n 20 "$out/$n.log"; fail=$((fail + 1))
  fi
done
[ $((pass + fail)) -gt 0 ] || { echo "README: no snippets found"; fail=1; }
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
