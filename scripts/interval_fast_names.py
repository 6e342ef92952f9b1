#!/usr/bin/env python3
"""Regenerates the renaming block of bench/bench_interval_ops.cpp.

The bench includes interval.h a second time in IV_FAST mode; its names
(functions, tables, types, enum constants: not macros) are renamed to F_... for that
inclusion. Run after adding or removing a name in include/interval.h:
    python3 scripts/interval_fast_names.py
With --check it only compares (make test runs it): prints `1 passed, 0
failed` when the block is current, else names the stale file and fails.
"""
import re
import sys

check = '--check' in sys.argv[1:]
args = [a for a in sys.argv[1:] if a != '--check']
root = args[0] if args else '.'
header = open(root + '/include/interval.h').read()
code = re.sub(r'/\*.*?\*/', '', header, flags=re.S)
names = set(re.findall(r'\b(iv__?\w+)\s*\(', code))
names |= set(re.findall(r'\b(iv__?\w*_t)\b', code))
names |= set(re.findall(r'\b(iv__?\w+)\s*\[', code))  # tables
names.add('iv__pair_layout_check')
for body in re.findall(r'enum\s*\w*\s*\{([^}]*)\}', code):
    names |= {c.split('=')[0].strip() for c in body.split(',') if c.strip()}
names -= set(re.findall(r'#\s*define\s+(\w+)', code))
names = sorted(n for n in names if n.startswith(('iv_', 'IV_')))

path = root + '/bench/bench_interval_ops.cpp'
bench = old = open(path).read()
head = '#define IV_FAST\n'
s = bench.index(head) + len(head)
e = bench.index('#include "interval.h"\n/* end of the renaming')
bench = bench[:s] + ''.join('#define %s F_%s\n' % (n, n) for n in names) + bench[e:]
head = '/* end of the renaming: plain names are the rigorous copy again */\n'
s = bench.index(head) + len(head)
e = bench.index('\ntypedef boost::numeric::interval<double> biv_t;')
bench = bench[:s] + ''.join('#undef %s\n' % n for n in names) + bench[e:]
if check:
    if bench == old:
        print('1 passed, 0 failed')
        sys.exit(0)
    print('%s: the IV_FAST renaming block is stale (a name was added to or removed from interval.h);'
          ' run python3 scripts/interval_fast_names.py' % path)
    print('0 passed, 1 failed')
    sys.exit(1)
open(path, 'w').write(bench)
print('%d names' % len(names))
