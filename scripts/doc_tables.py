#!/usr/bin/env python3
"""The tables of measured figures in README.md and docs/, written from the committed reports.

A generated table sits between two markers:

    <!-- table: NAME -->
    ...
    <!-- end table -->

and everything between them is rewritten from reports/ by the function NAME below, with the
file it comes from and the command that made it. `python3 scripts/doc_tables.py` rewrites them;
`--check` changes nothing and exits 1 naming every table that differs from its report, and every
measured figure (a time, a ratio, a percentage, a count of instructions) written outside a
table, so that no figure in the docs can go stale (the CTest test `docs_tables_match_reports`).
"""
import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
LATEST = ROOT / "reports" / "latest"
PEERS = ROOT / "reports" / "peers"
SHAPES = ["cylinder", "elliptic_cylinder", "elliptic_cone", "frustum", "sphere", "ellipsoid",
          "capsule", "plane", "quadric"]


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def relative(path):
    return path.relative_to(ROOT).as_posix()


def commented_header(path):
    """The lines a measurement file starts with (# ...): its command and machine."""
    out = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.startswith("#"):
            break
        out.append(line.lstrip("# ").rstrip())
    return out


def strip_commit(text):
    # Commits belong to the reports; the docs name the report.
    return re.sub(r",? ?commit [0-9a-f]{7,40}(\+dirty)?", "", text)


def source_line(path, command, machine=None):
    text = f"From `{relative(path)}`, made by `{strip_commit(command)}`"
    if machine:
        text += f" on {machine}"
    return text + "."


def made_by(path):
    """From a measurement file's header lines: where it is, the command and the machine."""
    head = commented_header(path)
    return source_line(path, head[0], strip_commit(head[1]) if len(head) > 1 else None)


def benchmark_medians(path):
    """Google Benchmark aggregate output: name -> (median time in ns, counters)."""
    out = {}
    units = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
    for line in path.read_text(encoding="utf-8").splitlines():
        m = re.match(r"(\S+)_median\s+([\d.]+) (ns|us|ms|s)\b", line)
        if m:
            out[m.group(1)] = float(m.group(2)) * units[m.group(3)]
    return out


def ns(value):
    if value >= 1e5:
        return f"{value / 1e3:.0f} µs"
    if value >= 1e4:
        return f"{value / 1e3:.1f} µs"
    if value >= 100:
        return f"{value:.0f} ns"
    return f"{value:.1f} ns"


def report_machine(report):
    return f"{report['machine']}, {report['compiler']}"


# What each solver promises; the measured columns come from the reports.
GUARANTEES = {
    "seed": "the seeds' formulas as written; the baseline",
    "stable": "no cancellation; p99 ≤ 32 ulps and no misclassification on generic lines",
    "certified": "a proven bound on every root; never wrong when it says certain",
    "correct": "every t, point and interval end correctly rounded",
    "seed32": "`seed` in binary32",
    "stable32": "`stable` in binary32",
    "correct32": "`correct` with binary32 as its target",
    "exact": "the oracle: exact rationals, correctly rounded",
}


def solver_rows(report):
    """Per solver over every family: cases, mismatched and t max (as the report's headline)."""
    rows = {}
    for row in report["rows"]:
        r = rows.setdefault(row["solver"], {"cases": 0, "mismatched": 0, "max": 0})
        r["cases"] += row["cases"]
        r["mismatched"] += row["cases_mismatched"]
        r["max"] = max(r["max"], row["t_ulps"]["max"])
    return rows


def headline_table(path):
    """The headline table of a report.md, as the report prints it."""
    lines = path.read_text(encoding="utf-8").splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("## Headline"))
    table = []
    for line in lines[start + 1:]:
        if line.startswith("|"):
            table.append(line)
        elif table:
            break
    return table


def count(n):
    return f"{n:,}"


def solvers():
    report = read_json(LATEST / "report.json")
    bench = benchmark_medians(LATEST / "bench.txt")
    header = commented_header(LATEST / "bench.txt")
    shapes = [s for s in SHAPES if f"{s}/seed/points" in bench]
    rows = solver_rows(report)
    out = ["Audit: " + source_line(LATEST / "report.json", report["command"],
                                   report_machine(report))
           + f" Times, median ns per solve with points: `{relative(LATEST / 'bench.txt')}`, "
           + f"made by `{header[0]}`.",
           "",
           "| solver | guarantee | mismatched (audit) | t max ulps | "
           + " | ".join(shapes) + " |",
           "|---|---|---:|---:|" + "---:|" * len(shapes)]
    for solver, what in GUARANTEES.items():
        r = rows.get(solver)
        audit = (f"{count(r['mismatched'])} of {count(r['cases'])}", f"{r['max']:.3g}") \
            if r else ("-", "-")
        times = [ns(bench[f"{s}/{solver}/points"]) if f"{s}/{solver}/points" in bench else "-"
                 for s in shapes]
        out.append(f"| `{solver}` | {what} | {audit[0]} | {audit[1]} | " + " | ".join(times)
                   + " |")
    return out


def bench():
    path = LATEST / "bench.txt"
    bench = benchmark_medians(path)
    shapes = [s for s in SHAPES if f"{s}/seed/points" in bench]
    queries = [("points", "all hits, points"), ("prepared/points", "prepared shape"),
               ("no_points", "all hits, no points"), ("nearest", "nearest"), ("any", "hit test")]
    out = [made_by(path) + " Median ns per solve:", "",
           "| solver | query | " + " | ".join(shapes) + " |",
           "|---|---|" + "---:|" * len(shapes)]
    for solver in GUARANTEES:
        for key, label in queries:
            if not any(f"{s}/{solver}/{key}" in bench for s in shapes):
                continue
            cells = [ns(bench[f"{s}/{solver}/{key}"]) if f"{s}/{solver}/{key}" in bench else "-"
                     for s in shapes]
            out.append(f"| `{solver}` | {label} | " + " | ".join(cells) + " |")
    return out


def rungs():
    """Which rung of correct's ladder answered, family by family, in the default audit."""
    report = read_json(LATEST / "report.json")
    totals = {}
    for row in report["rows"]:
        if row["solver"] != "correct" or "rungs" not in row:
            continue
        t = totals.setdefault(row["family"], {})
        for rung, n in row["rungs"].items():
            t[rung] = t.get(rung, 0) + n
    names = list(dict.fromkeys(r for t in totals.values() for r in t))
    out = [source_line(LATEST / "report.json", report["command"], report_machine(report))
           + " Cases answered by each rung of `correct` (the first that could prove its answer):", "",
           "| family | " + " | ".join(names) + " |", "|---|" + "---:|" * len(names)]
    for family in report["families"]:
        t = totals.get(family, {})
        out.append(f"| {family} | " + " | ".join(count(t.get(n, 0)) for n in names) + " |")
    return out


def headline():
    report = read_json(LATEST / "report.json")
    return [source_line(LATEST / "report.md", report["command"], report_machine(report)), ""] \
        + headline_table(LATEST / "report.md")


def peer_families(report):
    wanted = ["generic", "near_tangent", "scale", "far_origin", "rim", "inside_start", "seam"]
    return [f for f in wanted if f in report["families"]]


def peers():
    report = read_json(PEERS / "report.json")
    solvers = report["solvers"]
    totals = {}
    for row in report["rows"]:
        t = totals.setdefault((row["family"], row["solver"]), [0, 0, 0])
        t[0] += row["cases_mismatched"]
        t[1] += row["cases"]  # graded: the unrepresented and the unasked are counted apart
        t[2] += row["within_tolerance"]
    out = [source_line(PEERS / "report.json", report["command"], report_machine(report))
           + " Cases misclassified beyond each library's declared tolerance, of those each could"
           " take (and, where it declares one, how many more were within it):",
           "",
           "| family | " + " | ".join(f"`{s}`" for s in solvers) + " |",
           "|---|" + "---:|" * len(solvers)]
    for family in peer_families(report):
        cells = []
        for s in solvers:
            bad, graded, within = totals.get((family, s), [0, 0, 0])
            cell = f"{count(bad)} of {count(graded)}" if graded else "-"
            cells.append(cell + (f" (+{count(within)})" if within else ""))
        out.append(f"| {family} | " + " | ".join(cells) + " |")
    return out


def vecgeom():
    """VecGeom on elliptic sections along the axes: per solid and family, what remains beyond its
    declared tolerance, split by which way it is wrong."""
    path = PEERS / "aligned" / "report.json"
    report = read_json(path)
    rows = {(r["family"], r["shape"]): r for r in report["rows"] if r["solver"] == "vecgeom"}
    # The shapes it takes (none of its own for a capsule, a plane or a quadric).
    shapes = [s for s in SHAPES if s != "capsule" and s in report["shapes"]
              and any(r["cases"] for (_, shape), r in rows.items() if shape == s)]
    out = [source_line(path, report["command"], report_machine(report))
           + " `vecgeom` (DistanceToIn): cases misclassified beyond its declared tolerance, of those"
           " graded, and which way (invented: a hit where there is none; missed: one not found):",
           "",
           "| family | " + " | ".join(f"`{s}`" for s in shapes) + " |",
           "|---|" + "---:|" * len(shapes)]
    for family in report["families"]:
        cells = []
        for shape in shapes:
            r = rows.get((family, shape))
            if not r or not r["cases"]:
                cells.append("-")
                continue
            kinds = ", ".join(f"{k} {count(v)}" for k, v in r["mismatches"].items() if v)
            cells.append(f"{count(r['cases_mismatched'])} of {count(r['cases'])}"
                         + (f" ({kinds})" if kinds else ""))
        if any(c != "-" for c in cells):
            out.append(f"| {family} | " + " | ".join(cells) + " |")
    return out


def peer_instructions():
    path = PEERS / "instructions.txt"
    lines = path.read_text(encoding="utf-8").splitlines()
    rows = [l.split() for l in lines if l and not l.startswith("#")][1:]
    shapes = [s for s in SHAPES if any(r[1] == s for r in rows)]
    solvers = list(dict.fromkeys(r[0] for r in rows))
    got = {(r[0], r[1]): int(r[2]) for r in rows}
    out = [made_by(path) + " Instructions per solve:", "",
           "| solver | " + " | ".join(shapes) + " |", "|---|" + "---:|" * len(shapes)]
    for s in solvers:
        out.append(f"| `{s}` | " + " | ".join(
            count(got[(s, shape)]) if (s, shape) in got else "-" for shape in shapes) + " |")
    return out


def verbatim(path):
    """A measurement file as it was written, in a code block."""
    text = [strip_commit(l) for l in path.read_text(encoding="utf-8").splitlines()]
    return [f"From `{relative(path)}`:", "", "```"] + text + ["```"]


def instructions():
    return verbatim(LATEST / "instructions.txt")


def tracking_instructions():
    return verbatim(LATEST / "tracking_instructions.txt")


def python_throughput():
    return verbatim(LATEST / "python_throughput.txt")


def cells_audits():
    """Each shipped model's tracking audit: its table of rays gone wrong by tracker and family."""
    out = []
    for path in sorted((LATEST / "cells").glob("*/report.md")):
        lines = path.read_text(encoding="utf-8").splitlines()
        heading = next(i for i, l in enumerate(lines) if l.startswith("### Misclassified rays"))
        start = next(i for i in range(heading, len(lines)) if lines[i].startswith("|"))
        end = next(i for i in range(start, len(lines)) if not lines[i].startswith("|"))
        command = next(l for l in lines if l.startswith("Command: "))
        out += [f"From `{relative(path)}` ({command[len('Command: '):]}):", ""]
        out += lines[start:end] + [""]
    return out[:-1]


def instructions_closed():
    """Each shape open and closed by its discs: correct, its hit test and stable, and the ratio."""
    path = LATEST / "instructions_closed.txt"
    rows = [l.split() for l in path.read_text(encoding="utf-8").splitlines()
            if l and not l.startswith("#")][1:]
    got = {(r[0], r[1], r[2]): int(r[5]) for r in rows}
    columns = [("correct", "all", "`correct`, all hits"), ("correct", "any", "hit test"),
               ("stable", "all", "`stable`, all hits")]
    out = [made_by(path) +
           " Instructions per solve, open → closed (the same shapes and lines with `caps`):", "",
           "| shape | " + " | ".join(c[2] for c in columns) + " |", "|---|" + "---:|" * len(columns)]
    for shape in SHAPES:
        cells = []
        for solver, need, _ in columns:
            o, c = got.get((solver, shape, need)), got.get((solver, shape + "+caps", need))
            cells.append(f"{count(o)} → {count(c)} ({c / o:.2f}×)" if o and c else "-")
        if any(c != "-" for c in cells):
            out.append(f"| {shape} | " + " | ".join(cells) + " |")
    return out


def correct_vs_exact():
    return verbatim(LATEST / "correct_vs_exact.txt")


def family_instructions():
    return verbatim(LATEST / "family_instructions.txt")


def time_per_instruction():
    """Derived from the two tables above by bench/time_per_instruction.py (run, not stored)."""
    times, ir = (relative(LATEST / f) for f in ("correct_vs_exact.txt", "family_instructions.txt"))
    text = subprocess.run([sys.executable, str(ROOT / "bench" / "time_per_instruction.py"),
                           str(times), str(ir)], cwd=ROOT, check=True, capture_output=True,
                          text=True).stdout.splitlines()
    return ["From `" + times + "` and `" + ir + "`:", "", "```"] + text + ["```"]


def instructions_lanes():
    return verbatim(LATEST / "instructions_lanes.txt")


def batch():
    path = LATEST / "bench_batch.txt"
    bench = benchmark_medians(path)
    out = [made_by(path) + " Median time for 1024 generic lines against one prepared shape:", "",
           "| shape | solver | scalar loop | AVX2 | AVX-512 | AVX-512 over AVX2 |",
           "|---|---|---:|---:|---:|---:|"]
    for shape in SHAPES:
        for solver in ["stable", "correct", "correct (closed)"]:
            name = shape + "+caps" if solver.endswith("(closed)") else shape
            key = f"{name}/{solver.split()[0]}/1024_lines/"
            if key + "batch_avx2" not in bench:
                continue
            scalar = bench.get(key + "scalar_loop")
            avx2, avx512 = bench[key + "batch_avx2"], bench.get(key + "batch_avx512")
            out.append(f"| {name} | `{solver.split()[0]}` | {ns(scalar) if scalar else '-'} | "
                       f"{ns(avx2)} | "
                       + (f"{ns(avx512)} | {avx2 / avx512:.2f}× |" if avx512 else "- | - |"))
    lanes = [k for k in bench if k.startswith("machine/")]
    if lanes:
        out += ["", "The machine's ceiling, independent fused multiply-adds (same run):", "",
                "| row | median |", "|---|---:|"]
        out += [f"| `{k}` | {ns(bench[k])} |" for k in lanes]
    return out


def scenes():
    path = LATEST / "scene_bench.txt"
    bench = benchmark_medians(path)
    out = [made_by(path), "", "| benchmark | median per ray |", "|---|---:|"]
    out += [f"| `{k}` | {ns(v)} |" for k, v in bench.items()]
    return out


def plugin():
    path = LATEST / "bench_plugin.txt"
    bench = benchmark_medians(path)
    out = [made_by(path), "",
           "| cases per batch | in process | in the worker | worker over in process |",
           "|---:|---:|---:|---:|"]
    for k, v in bench.items():
        m = re.match(r"plugin/in_process/(\d+)$", k)
        if m and f"plugin/in_worker/{m.group(1)}" in bench:
            w = bench[f"plugin/in_worker/{m.group(1)}"]
            out.append(f"| {m.group(1)} | {ns(v)} | {ns(w)} | {w / v:.2f}× |")
    return out


TABLES = {f.__name__: f for f in [solvers, bench, rungs, headline, peers, vecgeom, peer_instructions, instructions, tracking_instructions,
                                  python_throughput, cells_audits,
                                  instructions_closed, instructions_lanes, correct_vs_exact,
                                  family_instructions, time_per_instruction, batch, scenes, plugin]}
BEGIN = re.compile(r"^<!-- table: (\w+) -->$")
END = "<!-- end table -->"
# A measured figure: a time, a rate, a percentage, a ratio or a count of instructions.
FIGURE = re.compile(r"\b\d[\d,]*(\.\d+)?\s?(ns|µs|ms|%|×(?!\d)|instructions\b|k/s|M/s)")


def rewrite(path, problems):
    lines = path.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    in_code = False
    while i < len(lines):
        line = lines[i]
        m = BEGIN.match(line)
        if m:
            name = m.group(1)
            end = next((j for j in range(i + 1, len(lines)) if lines[j] == END), None)
            if name not in TABLES or end is None:
                problems.append(f"{relative(path)}:{i + 1}: no table named {name!r} or no end")
                out.append(line)
                i += 1
                continue
            fresh = TABLES[name]()
            if lines[i + 1:end] != fresh:
                problems.append(f"{relative(path)}:{i + 1}: table {name} differs from its report")
            out += [line] + fresh + [END]
            i = end + 1
            continue
        if line.startswith("```"):
            in_code = not in_code
        elif not in_code:
            for f in FIGURE.finditer(line):
                problems.append(f"{relative(path)}:{i + 1}: the figure {f.group(0)!r} is written "
                                f"by hand; put it in a generated table")
        out.append(line)
        i += 1
    return "\n".join(out) + "\n"


def main(argv):
    check = "--check" in argv
    problems = []
    for path in [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md")):
        text = rewrite(path, problems)
        if not check:
            path.write_text(text, encoding="utf-8")
    figures = [p for p in problems if "by hand" in p]
    if check and problems:
        print("\n".join(problems), file=sys.stderr)
        print("python3 scripts/doc_tables.py rewrites the tables from reports/", file=sys.stderr)
        return 1
    if figures:
        print("\n".join(figures), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
