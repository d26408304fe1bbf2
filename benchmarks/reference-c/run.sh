#!/usr/bin/env bash
# Builds the plain C references with gcc -O3 and runs one of them. Needs gcc; no other dependency.
#   run.sh [n ...]                    RK4 cloth step: ns per spring evaluation at n = 32, 64, 128, 256 (or the n given)
#   run.sh --xpbd [n ...]             xpbd, 10 substeps per 1/60 s frame: ms per simulated second and ns per projection
#   run.sh --xpbd --run STEPS n       xpbd: STEPS frames from rest, then the checksum (for callgrind)
#   run.sh --lean [n ...]             the lean xpbd (cloth_xpbd_lean.c: no damping, twelve structured batches, separate arrays)
#   run.sh --build                    only builds (build/cloth_rk4, build/cloth_xpbd, build/libcloth_xpbd.so,
#                                     build/cloth_xpbd_lean, build/libcloth_xpbd_lean.so, build/libmesh_xpbd.so,
#                                     build/libshape_matching.so)
# The xpbd build adds -fno-math-errno: sqrt then compiles to the one instruction the JIT emits, instead of the
# instruction plus a test and a call that sets errno for negative arguments; no result changes (IEEE sqrt is exact).
# build/libcloth_xpbd.so is the same program as a shared library, which the BenchmarkDotNet comparison
# (XpbdBenchmarks) calls in-process. CFLAGS overrides the flags (callgrind needs -march=x86-64-v3:
# valgrind does not decode AVX-512; build that apart, as benchmarks/README.md does, or the benchmarks load it).
set -euo pipefail
cd "$(dirname "$0")"
CC=${CC:-gcc}
CFLAGS=${CFLAGS:--O3 -march=native -std=c11 -Wall -Wextra -Werror}
XPBD_CFLAGS="$CFLAGS -fno-math-errno"
mkdir -p build
# shellcheck disable=SC2086 # CFLAGS is a list of flags
"$CC" $CFLAGS -o build/cloth_rk4 cloth_rk4.c -lm
# shellcheck disable=SC2086
"$CC" $XPBD_CFLAGS -o build/cloth_xpbd cloth_xpbd.c -lm
# shellcheck disable=SC2086
"$CC" $XPBD_CFLAGS -shared -fPIC -o build/libcloth_xpbd.so cloth_xpbd.c -lm
# shellcheck disable=SC2086
"$CC" $XPBD_CFLAGS -o build/cloth_xpbd_lean cloth_xpbd_lean.c -lm
# shellcheck disable=SC2086
"$CC" $XPBD_CFLAGS -shared -fPIC -o build/libcloth_xpbd_lean.so cloth_xpbd_lean.c -lm
# shellcheck disable=SC2086
"$CC" $XPBD_CFLAGS -shared -fPIC -o build/libmesh_xpbd.so mesh_xpbd.c -lm
# shellcheck disable=SC2086
"$CC" $XPBD_CFLAGS -shared -fPIC -o build/libshape_matching.so shape_matching.c -lm
program=cloth_rk4
flags=$CFLAGS
case "${1:-}" in
  --build) exit 0 ;;
  --xpbd) program=cloth_xpbd; flags=$XPBD_CFLAGS; shift ;;
  --lean) program=cloth_xpbd_lean; flags=$XPBD_CFLAGS; shift ;;
esac
echo "compiler: $("$CC" --version | head -1); flags: $flags"
if [ $# -eq 0 ]; then set -- 32 64 128 256; fi
./build/$program "$@"
