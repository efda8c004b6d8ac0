#!/usr/bin/env python3
"""Writes an elastic 2-D block case with about N particles (linear quad4, musl, 4 per cell)."""
import json, math, sys

n = int(float(sys.argv[1]))
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 100
scheme = sys.argv[3] if len(sys.argv) > 3 else "musl"
model = sys.argv[4] if len(sys.argv) > 4 else "linear_elastic"
cells = max(2, int(math.sqrt(n / 4)))   # square block, 2 x 2 particles per cell
h = 1.0 / cells
E, rho, nu = 1.0e7, 1000.0, 0.3
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
dt = 0.2 * h / math.sqrt(M / rho)
mat = {"name": "m", "model": model, "density": rho, "youngs_modulus": E, "poisson_ratio": nu}
if model == "mohr_coulomb":
    # weak enough that the block yields under its own weight: the plastic return is exercised
    mat.update({"cohesion": 1.0e3, "friction_angle": 20.0})
case = {
    "title": "benchmark block",
    "dimension": 2,
    "analysis": {"type": "explicit", "scheme": scheme, "end_time": steps * dt, "dt": dt,
                 "gravity": [0.0, -9.81]},
    # one empty cell row on top and at the sides so the block may move
    "grid": {"type": "rectangle", "origin": [-h, 0.0], "size": [1.0 + 2 * h, 1.0 + h],
             "cells": [cells + 2, cells + 1], "element": "quad4"},
    "materials": [mat],
    "bodies": [{"name": "block", "material": "m",
                "shape": {"type": "rectangle", "min": [0.0, 0.0], "max": [1.0, 1.0]},
                "particles_per_cell": 2}],
    "boundary_conditions": [{"type": "fixed", "boundary": "y_min", "directions": ["x", "y"]}],
    "output": {"interval": steps * dt},
}
json.dump(case, sys.stdout, indent=1)
