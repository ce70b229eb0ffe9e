#!/usr/bin/env python3
"""Time per instruction, correct beside the exact oracle, family by family: joins a time table
(bench/correct_vs_exact.sh) with an instruction table (bench/family_instructions.sh, the solvers
correct,exact) and says how many instructions a solve of `correct` could take, at its measured
time per instruction, for `exact` to take TARGET times as long (5 per family, 10 over all: the
targets docs/limits.md names as not yet met).

    python3 bench/time_per_instruction.py [TIMES] [INSTRUCTIONS]
    (defaults: reports/latest/correct_vs_exact.txt, reports/latest/family_instructions.txt)

The two tables count different samples of the same families (the audit's cases against 200 a
shape and range), so a row is an estimate: its time per instruction is a mean over the family's
mix of lines.
"""
import sys

times_file = sys.argv[1] if len(sys.argv) > 1 else "reports/latest/correct_vs_exact.txt"
ir_file = sys.argv[2] if len(sys.argv) > 2 else "reports/latest/family_instructions.txt"


def table(path):
    rows = {}
    for line in open(path):
        fields = line.split()
        if fields and not line.startswith("#") and fields[0] != "family":
            rows[fields[0]] = fields[1:]
    return rows


times, ir = table(times_file), table(ir_file)
# Over all families the instruction table gives only the ratio: weigh the families by their cases.
cases = {f: int(r[0]) for f, r in ir.items() if f != "all"}
n = sum(cases.values())
ir["all"] = [str(n)] + [str(sum(cases[f] * int(ir[f][1 + i]) for f in cases) // n) for i in (0, 1)]

print(f"# python3 bench/time_per_instruction.py {times_file} {ir_file}")
print(f"{'family':18} {'correct ns/kIr':>14} {'exact ns/kIr':>13} {'exact faster':>13} "
      f"{'correct Ir':>10} {'Ir for target':>13}")
for family in sorted(times, key=lambda f: (f == "all", f)):
    if family not in ir:
        continue
    c_ns, e_ns = float(times[family][0]), float(times[family][1])
    c_ir, e_ir = int(ir[family][1]), int(ir[family][2])
    c_rate, e_rate = 1000 * c_ns / c_ir, 1000 * e_ns / e_ir
    target = 10 if family == "all" else 5
    print(f"{family:18} {c_rate:14.1f} {e_rate:13.1f} {c_rate / e_rate:13.2f} {c_ir:10d} "
          f"{1000 * e_ns / target / c_rate:13.0f}")
