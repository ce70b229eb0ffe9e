"""The Python module (python/), run by CTest with pytest: its answers are the C++ library's, bit
for bit, the same as the linequad program's on the same cases; bad input raises, naming the field."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import linequad

LINEQUAD = os.environ["LINEQUAD_BIN"]


def same(a, b):
    """Bit for bit: equal, and the same sign for zeros (NaN never occurs here)."""
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


def number(x):
    return float.fromhex(x) if isinstance(x, str) and "0x" in x else float(x)


def cases(families, shapes, n):
    out = subprocess.run([LINEQUAD, "cases", "--families", families, "--shapes", shapes,
                          "--cases", str(n), "--seed", "7"], check=True, capture_output=True,
                         text=True).stdout
    return [line for line in out.splitlines() if line]


def shape_of(case):
    """A case line's shape, through linequad.shape and the case's own fields."""
    skip = {"id", "shape", "L0", "v", "range", "t0", "t1", "family", "k", "note", "precision"}
    fields = {}
    for key, value in case.items():
        if key in skip:
            continue
        if isinstance(value, list):
            value = [number(x) for x in value]
        elif isinstance(value, str):
            value = number(value)
        fields[key] = value
    return linequad.shape(case["shape"], **fields)


@pytest.mark.parametrize("solver", ["correct", "exact"])
def test_correct_and_exact_equal_the_program(solver, tmp_path):
    lines = cases("generic,near_tangent,far_origin,axis_parallel",
                  "cylinder,elliptic_cone,sphere,capsule,plane,quadric", 8)
    path = tmp_path / "cases.jsonl"
    path.write_text("\n".join(lines) + "\n")
    answers = subprocess.run([LINEQUAD, "solve", "--solver", solver, str(path)], check=True,
                             capture_output=True, text=True).stdout.splitlines()
    assert len(answers) == len(lines)
    compared = 0
    for line, answer in zip(lines, answers):
        case, want = json.loads(line), json.loads(answer)
        if "error" in want or case.get("range", "line") != "line" or "t0" in case:
            continue  # the module's range is t0, t1 alone; these cases are lines
        L0 = np.array([[number(x) for x in case["L0"]]])
        v = np.array([[number(x) for x in case["v"]]])
        got = linequad.intersect(shape_of(case), L0, v, solver=solver)[0]
        assert got["error"] == 0
        assert bool(got["on_surface"]) == (want["on_surface"] is not None), line
        assert got["count"] == len(want["hits"]), line
        for k, hit in enumerate(want["hits"]):
            assert same(got["t"][k], number(hit["t"])), line
            assert linequad.hit_kinds[got["kind"][k]] == hit["kind"], line
            assert linequad.parts[got["part"][k]] == hit["part"], line
            for j in range(3):
                assert same(got["p"][k][j], number(hit["p"][j])), line
        compared += 1
    assert compared > 100


def test_float32_rays_are_answered_in_float():
    cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 10), r=5)
    L0 = np.array([[-10, 4, 2], [-10, 0.1, 3]], dtype=np.float32)
    v = np.array([[1, 0, 0], [1, 0.3, 0]], dtype=np.float32)
    got = linequad.intersect(cyl, L0, v)
    want = linequad.intersect(cyl, L0, v, solver="exact")
    assert (got["count"] == 2).all()
    for row, ref in zip(got, want):
        for k in range(2):
            assert same(row["t"][k], ref["t"][k])
            assert row["t"][k] == float(np.float32(row["t"][k]))  # a float, held in a double


def bits(rows):
    """Each field's raw bytes (not the padding between fields): equal arrays hold equal bits,
    signs of zeros and NaN payloads included."""
    return [np.ascontiguousarray(rows[name]).tobytes() for name in rows.dtype.names]


def test_many_rays_in_one_call_are_the_batch_and_equal_one_at_a_time():
    # Rays at one cylinder from a box around it (the batch's lanes), some grazing the side.
    rng = np.random.default_rng(11)
    cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 2), r=1, caps=True)
    L0 = rng.uniform(-4, 4, (999, 3))
    v = rng.uniform(-0.5, 0.5, (999, 3)) + [0, 0, 1] - L0
    v[::7, 0], v[::7, 1], L0[::7, 0] = 0, 1, 1  # tangent to the side (x = r), along y
    for solver in ["stable", "correct"]:
        many = linequad.intersect(cyl, L0, v, solver=solver)
        one = np.concatenate([linequad.intersect(cyl, L0[i:i + 1], v[i:i + 1], solver=solver)
                              for i in range(len(L0))])
        assert bits(many) == bits(one), solver
    assert bits(linequad.intersect(cyl, L0, v)) == bits(
        linequad.intersect(cyl, L0, v, solver="exact"))
    f32, d32 = L0.astype(np.float32), v.astype(np.float32)
    many = linequad.intersect(cyl, f32, d32, solver="stable")
    one = np.concatenate([linequad.intersect(cyl, f32[i:i + 1], d32[i:i + 1], solver="stable")
                          for i in range(len(L0))])
    assert bits(many) == bits(one)


def test_out_is_answered_into_and_returned():
    cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 2), r=1)
    L0, v = np.array([[-3.0, 0, 1], [-3.0, 5, 1]]), np.array([[1.0, 0, 0], [1.0, 0, 0]])
    rows = linequad.intersect(cyl, L0[::-1], v)  # other answers, to be overwritten
    got = linequad.intersect(cyl, L0, v, out=rows)
    assert got is rows
    assert bits(rows) == bits(linequad.intersect(cyl, L0, v))
    with pytest.raises(ValueError, match="out: expected a writeable array .* of 2 rows"):
        linequad.intersect(cyl, L0, v, out=rows[:1])
    with pytest.raises(ValueError, match="out: expected"):
        linequad.intersect(cyl, L0, v, out=np.zeros(2))
    rows.flags.writeable = False
    with pytest.raises(ValueError, match="out: expected a writeable"):
        linequad.intersect(cyl, L0, v, out=rows)


def test_bad_input_raises_naming_the_field():
    with pytest.raises(ValueError, match='field "rr": not a field of a cylinder case'):
        linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 1), rr=1)
    with pytest.raises(ValueError, match="radius r"):
        linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 1), r=-1)
    with pytest.raises(ValueError, match='field "C": expected an array of 3 numbers'):
        linequad.shape("cylinder", C=(0, 0), H=(0, 0, 1), r=1)
    with pytest.raises(ValueError, match='field "q"'):
        linequad.shape("quadric", q=[1, 2, 3])
    with pytest.raises(ValueError, match='field "C": expected a number or a sequence'):
        linequad.shape("cylinder", C=[[[[0]]]], H=(0, 0, 1), r=1)
    with pytest.raises(ValueError, match="not a name"):
        linequad.shape("cyl inder", r=1)
    cyl = linequad.shape("cylinder", C=(0, 0, 0), H=(0, 0, 1), r=1)
    with pytest.raises(ValueError, match=r"origins: expected an \(N, 3\) array"):
        linequad.intersect(cyl, np.zeros((2, 2)), np.zeros((2, 3)))
    with pytest.raises(ValueError, match="origins and directions: 2 rows against 3"):
        linequad.intersect(cyl, np.zeros((2, 3)), np.zeros((3, 3)))
    with pytest.raises(ValueError, match='solver "nope"'):
        linequad.intersect(cyl, np.zeros((1, 3)), np.ones((1, 3)), solver="nope")
    with pytest.raises(ValueError, match='need "some"'):
        linequad.intersect(cyl, np.zeros((1, 3)), np.ones((1, 3)), need="some")
    with pytest.raises(TypeError):
        linequad.intersect(cyl, np.zeros((1, 3), dtype=np.int64), np.ones((1, 3)))
    # A bad line is an answer with its error, not an exception: the other rows stand.
    rows = linequad.intersect(cyl, np.array([[0.0, 0, 0.5], [np.nan, 0, 0]]),
                              np.array([[1.0, 0, 0], [1.0, 0, 0]]))
    assert rows["error"][0] == 0 and rows["count"][0] == 2  # a line through the axis
    assert linequad.error_codes[rows["error"][1]] == "not_a_number"


def test_a_line_on_the_surface_and_a_miss():
    plane = linequad.shape("plane", n=(0, 0, 1), d=1)
    rows = linequad.intersect(plane, np.array([[0.0, 0, 1], [0, 0, 0]]),
                              np.array([[1.0, 0, 0], [1.0, 0, 0]]))
    assert rows["on_surface"][0] == 1 and rows["count"][0] == 0
    assert rows["s0"][0] == -math.inf and rows["s1"][0] == math.inf
    assert rows["on_surface"][1] == 0 and rows["count"][1] == 0
    assert rows["t"][1][0] == math.inf and math.isnan(rows["p"][1][0][0])


def test_cases_are_the_programs():
    got = linequad.cases(families=["generic", "far_origin"], shapes=["cylinder", "quadric"], n=3,
                         seed=5)
    lines = subprocess.run([LINEQUAD, "cases", "--families", "generic,far_origin", "--shapes",
                            "cylinder,quadric", "--cases", "3", "--seed", "5"], check=True,
                           capture_output=True, text=True).stdout.splitlines()
    assert len(got["shapes"]) == len(lines) == got["origins"].shape[0]
    for i, line in enumerate(lines):
        case = json.loads(line)
        assert got["shapes"][i].kind == case["shape"]
        assert got["family"][i] == case["family"] and got["k"][i] == case["k"]
        for j in range(3):
            assert same(got["origins"][i][j], number(case["L0"][j]))
            assert same(got["directions"][i][j], number(case["v"][j]))
        # Each case's shape answers as the program answers that case.
        row = linequad.intersect(got["shapes"][i], got["origins"][i:i + 1],
                                 got["directions"][i:i + 1], t0=got["t0"][i], t1=got["t1"][i])
        assert row["error"][0] == 0
    with pytest.raises(ValueError, match='family "nope"'):
        linequad.cases(families=["nope"])
    with pytest.raises(ValueError, match='shape "cube"'):
        linequad.cases(shapes=["cube"])


def test_audit_grades_a_python_solver_and_charges_its_failures_to_the_chunk(tmp_path):
    def exact(shapes, L0, v, t0, t1):  # linequad's own oracle as the solver under audit
        t = np.full((len(shapes), 4), np.inf)
        for i, s in enumerate(shapes):
            row = linequad.intersect(s, L0[i:i + 1], v[i:i + 1], solver="exact", t0=t0[i],
                                     t1=t1[i])[0]
            t[i, :row["count"]] = row["t"][:row["count"]]
        return t

    got = linequad.audit(exact, families=["generic", "far_origin"], shapes=["sphere"], n=20,
                         out=str(tmp_path / "report"))
    assert got["verdict"] == ["python: 100 % right of 120; t error 0 bits at worst, 0 at p99"]
    assert (tmp_path / "report" / "report.json").exists()
    assert "<h1" in (tmp_path / "report" / "report.html").read_text(encoding="utf-8")
    assert got["report"]["status"] == "complete"

    calls = []

    def flaky(shapes, L0, v, t0, t1):
        calls.append(len(shapes))
        if len(calls) == 2:
            raise RuntimeError("the second chunk fails")
        return exact(shapes, L0, v, t0, t1)

    # 20 cases a group (family, shape, range), a chunk a group: every chunk asked, the run goes on.
    got = linequad.audit(flaky, families=["generic"], shapes=["sphere"], n=20,
                         out=str(tmp_path / "flaky"))
    assert calls == [20, 20, 20]
    assert got["verdict"][0].startswith("python: 66.7 % right of 60")
    # Its worst cases replay the exact answer: linequad replay cannot run a Python callable.
    md = (tmp_path / "flaky" / "report.md").read_text(encoding="utf-8")
    assert "| linequad replay --solver 'exact'`" in md
    assert "python cannot be run by `linequad replay` (a Python callable\\: call it" in md

    def wrong_shape(shapes, L0, v, t0, t1):
        return np.zeros((len(shapes) + 1, 2))

    got = linequad.audit(wrong_shape, families=["generic"], shapes=["sphere"], n=5)
    assert got["verdict"][0].startswith("python: 0 % right of 15")


def nearest_exact(shapes, L0, v, t0, t1):
    """The oracle's nearest hit: what a ray caster answers, right."""
    t = np.full(len(shapes), np.inf)
    for i, s in enumerate(shapes):
        row = linequad.intersect(s, L0[i:i + 1].astype(np.float64),
                                 v[i:i + 1].astype(np.float64), solver="exact", need="nearest",
                                 t0=t0[i], t1=t1[i])[0]
        if row["count"]:
            t[i] = row["t"][0]
    return t


def test_audit_grades_what_the_solver_declares():
    # Right for what it declares (the nearest hit), wrong read as every hit.
    kw = dict(families=["generic"], shapes=["cylinder", "sphere"], n=10)
    got = linequad.audit(nearest_exact, answers="nearest", **kw)
    assert got["verdict"] == ["python: 100 % right of 60; t error 0 bits at worst, 0 at p99"]
    assert got["report"]["external"] == [{
        "solver": "python", "answers": "nearest hit", "parametrisation": "t along v",
        "surface": "as posed", "plugin": "",
        "not_replayable": "a Python callable: call it on the case to replay it",
        "mapping": "a Python callable, fn(shapes, origins, directions, t0, t1) -> t's, a chunk "
                   "of cases a call"}]
    assert not linequad.audit(nearest_exact, **kw)["verdict"][0].startswith("python: 100 %")
    # A float32 solver is handed float32 arrays and graded in float.
    seen = set()

    def in_float(shapes, L0, v, t0, t1):
        seen.update({L0.dtype, v.dtype, t0.dtype, t1.dtype})
        return nearest_exact(shapes, L0, v, t0, t1)

    got = linequad.audit(in_float, precision="binary32", answers="nearest", **kw)
    assert seen == {np.dtype(np.float32)}
    assert got["verdict"][0].startswith("python: 100 % right of 60")  # t's errors: in doubles
    # A declaration out of range, or an unknown one, is named.
    with pytest.raises(ValueError, match='answers "closest": expected all, nearest'):
        linequad.audit(nearest_exact, answers="closest", **kw)
    with pytest.raises(ValueError, match="tolerance_absolute must be finite and at least 0"):
        linequad.audit(nearest_exact, answers="nearest", tolerance=(-1, 0), **kw)
    with pytest.raises(ValueError, match="inside .* is for nearest or first-entry answers"):
        linequad.audit(nearest_exact, inside="no_hit", **kw)
    with pytest.raises(ValueError, match="has a character other than"):
        linequad.audit(nearest_exact, name="my solver", **kw)
    with pytest.raises(TypeError, match="fn: expected a callable"):
        linequad.audit(3, **kw)
