#!/usr/bin/env python3
"""Line coverage of the headers by the tests (make coverage).

Builds every tests/test_<module>*.c (and the shared implementations,
tests/impl/*.c) with gcc --coverage (-O1, so that the
large batteries finish), runs them at FILIGREE_TEST_SCALE (default 0.05),
and prints, per header, the lines that no test ran, grouped into ranges
with the function and the first line of code. Where a test exists for a
branch these lists should hold only error messages, allocation failures
and defensive code; docs/conventions.md says how to read them.

Usage: scripts/coverage.py [module ...]   (interval frep rounded grooves)
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

MODULES = {"interval": "interval.h", "frep": "frep.h", "rounded": "rounded_edges.h", "grooves": "grooves.h"}
LIBS = ["-lembree3", "-lquadmath", "-lpthread", "-lm"]


CFLAGS = ["-std=gnu11", "-O1", "-march=native", "-g", "--coverage", "-ffp-contract=fast",
          "-Iinclude", "-Itests", "-Iexamples/common", "-w"]


def build_impl(out):
    """The headers' shared implementations (tests/impl/*.c, as the Makefile
    builds them): the tests that do not compile their own link them, and
    every run adds to the one .gcda of each."""
    objs = []
    for src in sorted(glob.glob("tests/impl/*.c")):
        obj = os.path.join(out, "impl_" + os.path.basename(src)[:-2] + ".o")
        subprocess.run(["gcc"] + CFLAGS + ["-c", src, "-o", obj], check=True)
        objs.append(obj)
    lib = os.path.join(out, "libfiligree.a")
    subprocess.run(["ar", "rcs", lib] + objs, check=True)
    return lib


def build_and_run(module, out):
    srcs = sorted(glob.glob("tests/test_%s*.c" % module)) + ["tests/test_harness.c"] # the harness includes every header
    lib = build_impl(out)
    for i, src in enumerate(srcs):
        exe = os.path.join(out, os.path.basename(src)[:-2])
        sys.stderr.write("[%d/%d] %s\n" % (i + 1, len(srcs), src))
        subprocess.run(["gcc"] + CFLAGS + [src, lib, "-o", exe] + LIBS, check=True)
        env = dict(os.environ, FILIGREE_TEST_SCALE=os.environ.get("FILIGREE_TEST_SCALE", "0.05"))
        r = subprocess.run([exe], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if r.returncode != 0:
            sys.stderr.write("  %s exited %d (its coverage still counts)\n" % (exe, r.returncode))


def never_run(out, header):
    counts, funcs = {}, {}
    for gcda in glob.glob(os.path.join(out, "*.gcda")):
        res = subprocess.run(["gcov", "--json-format", "--stdout", os.path.basename(gcda)], cwd=out,
                             capture_output=True, text=True)
        for line in res.stdout.splitlines():
            if not line.strip():
                continue
            for f in json.loads(line)["files"]:
                if not f["file"].endswith("include/" + header):
                    continue
                for ln in f["lines"]:
                    n = ln["line_number"]
                    counts[n] = counts.get(n, 0) + ln["count"]
                    funcs[n] = ln.get("function_name", "")
    return counts, funcs


def report(header, counts, funcs):
    src = open(os.path.join("include", header)).read().split("\n")
    cold = [n for n, c in sorted(counts.items()) if c == 0]
    print("%s: %d of %d lines never run" % (header, len(cold), len(counts)))
    groups = []
    for n in cold:
        if groups and n - groups[-1][-1] <= 2:
            groups[-1].append(n)
        else:
            groups.append([n])
    for g in groups:
        print("  %5d-%-5d %-28s %s" % (g[0], g[-1], funcs.get(g[0], "")[:28], src[g[0] - 1].strip()[:80]))


def main():
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    wanted = sys.argv[1:] or list(MODULES)
    for m in wanted:
        if m not in MODULES:
            sys.exit("coverage.py: unknown module %s (use %s)" % (m, " ".join(MODULES)))
    for m in wanted:
        with tempfile.TemporaryDirectory(prefix="filigree_cov_") as out:
            build_and_run(m, out)
            counts, funcs = never_run(out, MODULES[m])
            report(MODULES[m], counts, funcs)


if __name__ == "__main__":
    main()
