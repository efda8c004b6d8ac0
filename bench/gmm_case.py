#!/usr/bin/env python3
"""Writes the column collapse of examples/column_collapse (seed 000 section 5.3) as an explicit GMM
case: usage gmm_case.py [mls|lme|linear] [end_time] [h]. h = 0.1 gives 3,200 particles; `linear`
writes the same case for MPM, to compare against. Only the time loop is of interest: no pictures,
one output frame."""
import json, sys

shape = sys.argv[1] if len(sys.argv) > 1 else "mls"
end = float(sys.argv[2]) if len(sys.argv) > 2 else 0.3
h = float(sys.argv[3]) if len(sys.argv) > 3 else 0.1
nx, ny = round(6.0 / h), round(4.2 / h)
case = {
    "title": f"column collapse, {'mpm' if shape == 'linear' else 'gmm'} {shape}, h = {h}",
    "dimension": 2,
    "formulation": "plane_strain",
    "method": "mpm" if shape == "linear" else "gmm",
    "shape_function": shape,
    "analysis": {"type": "explicit", "scheme": "musl", "end_time": end, "cfl": 0.2,
                 "gravity": [0.0, -9.81]},
    "grid": {"type": "rectangle", "origin": [0.0, 0.0], "size": [nx * h, ny * h], "cells": [nx, ny],
             "element": "quad4"},
    "materials": [{"name": "soil", "model": "mohr_coulomb", "density": 1850,
                   "youngs_modulus": 1.8e6, "poisson_ratio": 0.3,
                   "cohesion": 5.0e3, "friction_angle": 25, "dilatancy_angle": 0}],
    "bodies": [{"name": "column", "material": "soil",
                "shape": {"type": "rectangle", "min": [0.0, 0.0], "max": [2.0, 4.0]},
                "particles_per_cell": 2,
                "initial_stress": "geostatic", "k0": 0.428571, "surface_y": 4.0}],
    "boundary_conditions": [
        {"type": "fixed", "boundary": "x_min", "directions": ["x"]},
        {"type": "fixed", "boundary": "y_min", "directions": ["x", "y"]}],
    "output": {"interval": end},
}
json.dump(case, sys.stdout, indent=1)
