"""A float32 ray-sphere intersection in PyTorch, written as a differentiable renderer writes it
(batched, no loop per ray), audited against linequad's exact oracle in float:

    PYTHONPATH=build/python /usr/bin/python3 examples/python/torch_sphere.py

Debian's python3-torch runs it (scripts/install-deps.sh installs it).
"""
import numpy as np
import torch

import linequad


def textbook(shapes, L0, v, t0, t1):
    """|o + t d - C|^2 = r^2 as a t^2 + b t + c = 0, in float32 tensors."""
    C = torch.tensor([s.fields["C"] for s in shapes], dtype=torch.float32)
    r = torch.tensor([s.fields["r"] for s in shapes], dtype=torch.float32)
    o, d = torch.from_numpy(L0), torch.from_numpy(v)
    oc = o - C
    a = (d * d).sum(-1)
    b = 2 * (oc * d).sum(-1)
    c = (oc * oc).sum(-1) - r * r
    disc = b * b - 4 * a * c
    root = torch.sqrt(torch.clamp(disc, min=0))
    t = torch.stack([(-b - root) / (2 * a), (-b + root) / (2 * a)], dim=-1)
    t[:, 1] = torch.where(disc == 0, torch.inf, t[:, 1])  # a touch is one hit
    lo, hi = torch.from_numpy(t0)[:, None], torch.from_numpy(t1)[:, None]
    keep = (disc >= 0)[:, None] & (t >= lo) & (t <= hi)
    return torch.where(keep, t, torch.inf).numpy()


report = linequad.audit(textbook, families=["generic", "near_tangent", "far_origin"],
                        shapes=["sphere"], n=200, precision="binary32", name="torch32")
print("\n".join(report["verdict"]))
