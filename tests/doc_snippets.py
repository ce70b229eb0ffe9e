#!/usr/bin/env python3
"""Every code block of README.md and docs/*.md, compiled or run as written (CTest doc_snippets).

A fenced block's info string says what it is and how it is checked:

    ```cpp                a C++ program (statements outside a function are wrapped in main, the
                          #include lines kept above it), built against the installed package and
                          run
    ```cmake              a consumer's CMakeLists.txt, built against the installed package with
                          the next cpp block of the page as its main.cpp (app)
    ```c NAME             a file a later sh block of the page uses, written as NAME
    ```sh                 commands, run with bash -euo pipefail in a scratch folder that shows the
                          repository's folders and the build (build/compare/linequad, and
                          linequad on PATH); lines starting with "$ " are commands whose output
                          is the lines after them, up to the next "$ ", compared exactly
    ```text output        what the block before it prints, compared exactly
    ```LANG norun REASON  not run, for the reason given (the test command itself, say)

A block without an info string is not code (a diagram, a measured table) and is not checked.
Usage: doc_snippets.py ROOT BUILD PREFIX WORK (the installed package in PREFIX).
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

ROOT, BUILD, PREFIX, WORK = (pathlib.Path(a).resolve() for a in sys.argv[1:5])
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
TIMEOUT = 600  # seconds a block may run: the README's audit example takes about a minute
failures = []


class Block:
    def __init__(self, page, line, info, code):
        self.page, self.line, self.code = page, line, code
        words = info.split()
        self.lang = words[0] if words else ""
        self.args = words[1:]

    def where(self):
        return f"{self.page.relative_to(ROOT)}:{self.line}"


def blocks(page):
    out, lines = [], page.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        m = re.match(r"^(`{3,})(.*)$", lines[i])
        if not m:
            i += 1
            continue
        fence, info, start = m.group(1), m.group(2).strip(), i + 1
        i += 1
        while i < len(lines) and not lines[i].startswith(fence):
            i += 1
        out.append(Block(page, start, info, "\n".join(lines[start:i]) + "\n"))
        i += 1
    return out


def fail(block, why):
    failures.append(f"{block.where()}: {why}")


def run(argv, cwd, env=None):
    return subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=TIMEOUT)


def scratch(name):
    """A folder where the repository's folders and the build are where the docs say."""
    d = WORK / name
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    # Folders only: a file a block writes (mine.c) lands in the scratch folder, never through a
    # link into the repository.
    for entry in ROOT.iterdir():
        if entry.is_dir() and entry.name not in (".git", "build") and \
                not entry.name.startswith("build-"):
            (d / entry.name).symlink_to(entry)
    (d / "build").symlink_to(BUILD)
    return d


def shell_env():
    env = dict(os.environ)
    env["PATH"] = f"{BUILD / 'compare'}:{env['PATH']}"
    return env


def as_program(code):
    """A cpp block as a program: wrapped in main unless it has one."""
    if re.search(r"\bint main\s*\(", code):
        return code
    head = [l for l in code.splitlines() if l.startswith("#include")]
    body = [l for l in code.splitlines() if not l.startswith("#include")]
    usings = [l for l in body if l.startswith("using namespace")]
    body = [l for l in body if not l.startswith("using namespace")]
    return "\n".join(head + usings + ["int main() {"] + ["    " + l for l in body] +
                     ["    return 0;", "}", ""])


def expected_after(page_blocks, k):
    nxt = page_blocks[k + 1] if k + 1 < len(page_blocks) else None
    return nxt.code if nxt and nxt.lang == "text" and nxt.args[:1] == ["output"] else None


def compare(block, got, want):
    if got.rstrip() != want.rstrip():
        fail(block, f"printed\n{got}\ninstead of\n{want}")


def check_programs(page, page_blocks, scratch_dir):
    """The page's cmake and cpp blocks as one project against the installed package."""
    work = scratch_dir / "programs"
    work.mkdir()
    cmake = ["cmake_minimum_required(VERSION 3.18)", "project(snippets LANGUAGES CXX)",
             "set(CMAKE_CXX_STANDARD 17)", "set(CMAKE_CXX_STANDARD_REQUIRED ON)"]
    programs = []  # (block, executable, expected output)
    used_as_main = set()
    for k, b in enumerate(page_blocks):
        if b.lang != "cmake" or "norun" in b.args:
            continue
        main = next((j for j in range(k + 1, len(page_blocks)) if page_blocks[j].lang == "cpp"),
                    None)
        if main is None:
            fail(b, "a cmake block needs a cpp block after it (its main.cpp)")
            continue
        sub = work / f"cmake_{b.line}"
        sub.mkdir()
        (sub / "CMakeLists.txt").write_text(b.code)
        (sub / "main.cpp").write_text(as_program(page_blocks[main].code))
        cmake.append(f"add_subdirectory(cmake_{b.line})")
        used_as_main.add(main)
        programs.append((page_blocks[main], sub.name + "/app",
                         expected_after(page_blocks, main)))
    for k, b in enumerate(page_blocks):
        if b.lang != "cpp" or "norun" in b.args or k in used_as_main:
            continue
        name = f"cpp_{b.line}"
        (work / f"{name}.cpp").write_text(as_program(b.code))
        cmake += ["find_package(linequad REQUIRED)", f"add_executable({name} {name}.cpp)",
                  f"target_link_libraries({name} PRIVATE linequad::audit)"]
        programs.append((b, name, expected_after(page_blocks, k)))
    if not programs:
        return
    (work / "CMakeLists.txt").write_text("\n".join(cmake) + "\n")
    for step in ([ "cmake", "-S", ".", "-B", "out", f"-DCMAKE_PREFIX_PATH={PREFIX}",
                   "-DCMAKE_BUILD_TYPE=Release"],
                 ["cmake", "--build", "out", "-j2"]):
        r = run(step, work)
        if r.returncode != 0:
            fail(programs[0][0], f"{' '.join(step)} failed:\n{r.stdout}\n{r.stderr}")
            return
    for block, exe, want in programs:
        r = run([str(work / "out" / exe)], work)
        if r.returncode != 0:
            fail(block, f"exited {r.returncode}:\n{r.stdout}\n{r.stderr}")
        elif want is not None:
            compare(block, r.stdout, want)
        print(f"{block.where()}: built and ran")


def check_shell(block, work, want):
    env = shell_env()
    if re.search(r"^\$ ", block.code, re.M):
        # "$ command" (continued by trailing backslashes), then the lines it prints.
        lines, i = block.code.splitlines(), 0
        while i < len(lines):
            if not lines[i].startswith("$ "):
                i += 1
                continue
            command = lines[i][2:]
            while command.endswith("\\"):  # continued: bash reads the backslash-newline
                i += 1
                command += "\n" + lines[i]
            i += 1
            printed = []
            while i < len(lines) and not lines[i].startswith("$ "):
                printed.append(lines[i])
                i += 1
            r = run(["bash", "-euo", "pipefail", "-c", command], work, env)
            if r.returncode != 0:
                fail(block, f"$ {command}\nexited {r.returncode}:\n{r.stderr}")
            else:
                compare(block, r.stdout, "\n".join(printed))
    else:
        r = run(["bash", "-euo", "pipefail", "-c", block.code], work, env)
        if r.returncode != 0:
            fail(block, f"exited {r.returncode}:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
        elif want is not None:
            compare(block, r.stdout, want)
    print(f"{block.where()}: ran")


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    for page in PAGES:
        page_blocks = blocks(page)
        if not any(b.lang for b in page_blocks):
            continue
        work = scratch(page.stem)
        for b in page_blocks:
            if "norun" in b.args:
                reason = " ".join(b.args[b.args.index("norun") + 1:])
                if not reason:
                    fail(b, "norun without a reason")
                print(f"{b.where()}: not run: {reason}")
            elif b.lang == "c":
                if len(b.args) != 1:
                    fail(b, "a c block names the file it is (```c mine.c)")
                elif "/" in b.args[0] or b.args[0].startswith("."):
                    fail(b, "a c block's file is a plain name in the scratch folder")
                else:
                    (work / b.args[0]).write_text(b.code)
            elif b.lang not in ("", "cpp", "cmake", "sh", "text"):
                fail(b, f"no way to check a '{b.lang}' block (mark it norun REASON)")
        check_programs(page, page_blocks, work)
        for k, b in enumerate(page_blocks):
            if b.lang == "sh" and "norun" not in b.args:
                check_shell(b, work, expected_after(page_blocks, k))
    for f in failures:
        print(f"FAILED {f}", file=sys.stderr)
    print(f"doc_snippets: {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
