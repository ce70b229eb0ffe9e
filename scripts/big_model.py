#!/usr/bin/env python3
"""Writes a model of N planes x = 0 .. N-1 and the N slabs between them (the last cell the rest of
space), for timing how a large model loads and is tracked through:

    python3 scripts/big_model.py 100000 big.json
    echo '{"id":1,"p":[0.5,0.5,0.5],"u":[1,0.001,0]}' | /usr/bin/time -v build/compare/linequad cells big.json
"""
import json
import sys

n, out = int(sys.argv[1]), sys.argv[2]
surfaces = [{"id": i + 1, "shape": "plane", "n": [1, 0, 0], "d": i} for i in range(n)]
cells = [{"id": i + 1, "region": f"{i + 1} -{i + 2}"} for i in range(n - 1)]
cells.append({"id": n, "region": f"-1 | {n}"})
with open(out, "w", encoding="utf-8") as f:
    json.dump({"surfaces": surfaces, "cells": cells, "box": [[0, 0, 0], [n - 1, 1, 1]]}, f)
