#!/usr/bin/env python3
"""Every repository path that README.md and docs/*.md cite exists (CTest doc_paths).

A cited path is a markdown link's target (relative to its page) or a code span naming a file or
folder under one of the repository's top-level folders (`fast/src/scene/scene.cpp`,
`tests/install_consumer/`), with a `#anchor` or `:line` after it allowed. A span holding a
placeholder (<...>, *, {...}, $) is a pattern, not a path, and what the main job or a build
makes (reports/local/, build/) is not in a clone. Exits 1 naming each path that does not exist.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
TOP = sorted(p.name for p in ROOT.iterdir() if p.is_dir() and not p.name.startswith(("build", ".git")))
MADE = ("reports/local", "build")  # made by the main job or a build, not in a clone

missing = []
cited = 0
for page in PAGES:
    text = page.read_text(encoding="utf-8")
    # Code blocks hold commands, not citations: only prose is read.
    prose = re.sub(r"^```.*?^```", "", text, flags=re.M | re.S)
    targets = []
    for m in re.finditer(r"\]\(([^)\s]+)\)", prose):
        t = m.group(1)
        if not re.match(r"^[a-z]+:", t) and not t.startswith("#"):
            targets.append((page.parent, t))
    for m in re.finditer(r"`([^`\s]+)`", prose):
        t = m.group(1)
        if any(t.startswith(top + "/") for top in TOP) or t in ("README.md",):
            targets.append((ROOT, t))
        elif t.startswith("../"):  # beside the repository: not in a clone
            missing.append(f"{page.relative_to(ROOT)}: {t} (outside the repository)")
        elif re.match(r"^linequad/\w+\.(hpp|h)$", t):  # an installed header: in some include/
            if not any((ROOT / layer / "include" / t).exists()
                       for layer in ("fast", "robust", "compare")):
                missing.append(f"{page.relative_to(ROOT)}: {t} (no such header)")
            cited += 1
    for base, t in targets:
        path = re.split(r"[#]", t)[0]
        path = re.sub(r":\d+(-\d+)?$", "", path).rstrip(".,;")
        if not path or re.search(r"[<>*{}$]", path):
            continue
        rel = (base / path).resolve()
        try:
            name = rel.relative_to(ROOT).as_posix()
        except ValueError:
            missing.append(f"{page.relative_to(ROOT)}: {t} (outside the repository)")
            continue
        if any(name == m or name.startswith(m + "/") for m in MADE):
            continue
        cited += 1
        if not rel.exists():
            missing.append(f"{page.relative_to(ROOT)}: {t}")
for m in missing:
    print(f"no such path: {m}", file=sys.stderr)
print(f"doc_paths: {cited} cited paths, {len(missing)} missing")
sys.exit(1 if missing else 0)
