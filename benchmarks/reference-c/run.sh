#!/usr/bin/env bash
# Builds the plain C reference of the RK4 cloth step with gcc -O3 and prints ns per spring evaluation
# at n = 32, 64, 128, 256 (or at the n given as arguments). Needs gcc; no other dependency.
set -euo pipefail
cd "$(dirname "$0")"
CC=${CC:-gcc}
CFLAGS=${CFLAGS:--O3 -march=native -std=c11 -Wall -Wextra -Werror}
mkdir -p build
# shellcheck disable=SC2086 # CFLAGS is a list of flags
"$CC" $CFLAGS -o build/cloth_rk4 cloth_rk4.c -lm
echo "compiler: $("$CC" --version | head -1); flags: $CFLAGS"
if [ $# -eq 0 ]; then set -- 32 64 128 256; fi
./build/cloth_rk4 "$@"
