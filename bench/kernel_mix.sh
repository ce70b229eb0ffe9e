#!/usr/bin/env bash
# What the batch kernels are made of, from the compiled units (objdump -d): for each kernel
# function, its instructions, the floating-point operations among them (add, sub, mul, div, sqrt
# and the fused forms) and its accesses to the stack (spills and reloads). Static counts: each
# instruction once, whichever branch runs.
#   bash bench/kernel_mix.sh [BUILD_DIR] [SHAPE]     (defaults: build, Cylinder)
set -euo pipefail
build="${1:-build}"
shape="${2:-Cylinder}"
dir="$build/fast/CMakeFiles/linequad_fast.dir/src/simd"
printf '%-34s %6s %6s %6s\n' function instr fp stack
for unit in avx2:D4 avx512:D8; do
  obj="$dir/batch_${unit%%:*}.cpp.o"
  lanes="${unit##*:}"
  [ -f "$obj" ] || { echo "no $obj (built without that instruction set?)" >&2; continue; }
  objdump -d --no-show-raw-insn -C "$obj" | awk -v want="stable_lanes<linequad::detail::$lanes, linequad::$shape>" '
    /^[0-9a-f]+ <.*>:$/ {
      if (name != "") print name, n, fp, stack
      name = ""; n = fp = stack = 0
      if (index($0, want) && index($0, "void linequad::detail::stable_lanes<")) name = want
      gsub(/linequad::(detail::)?/, "", name); gsub(/, /, ",", name)
      next
    }
    name != "" && NF >= 2 {
      ++n
      if ($2 ~ /^v(add|sub|mul|div|sqrt|fmadd|fmsub|fnmadd|fnmsub)[0-9]*[ps]d$/) ++fp
      if ($0 ~ /\(%r[sb]p[,)]/) ++stack # a memory operand addressed from the stack
    }
    END { if (name != "") print name, n, fp, stack }' |
    while read -r fn n fp stack; do printf '%-34s %6s %6s %6s\n' "$fn" "$n" "$fp" "$stack"; done
done
