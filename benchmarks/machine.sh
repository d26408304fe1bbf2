#!/usr/bin/env bash
# Prints the machine a benchmark ran on, for the headers of the results tables: the CPU model from /proc/cpuinfo and
# the cores the process sees. A virtual CPU that names no model number is written as this project's benchmark host is
# known (its /proc/cpuinfo says "AMD EPYC" alone): "AMD EPYC (KVM, 2 vCPUs)".
set -euo pipefail
model=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2- | sed 's/^ *//; s/ *$//' || true)
cores=$(nproc)
if [ -z "$model" ]; then
  echo "an unnamed CPU, $cores cores"
elif [[ ! "$model" =~ [0-9] ]] && grep -qm1 '^flags.* hypervisor' /proc/cpuinfo; then
  echo "$model (KVM, $cores vCPUs)"
else
  echo "$model, $cores cores"
fi
