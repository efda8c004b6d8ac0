#!/usr/bin/env python3
"""A workload the size of seed 004's silo discharge (31,000 points, 77,000 steps, viscoplastic
Drucker-Prager, axisymmetric): a 1 m radius, 3 m high fill in a silo with a rough wall and floor
(wall friction angle 20 degrees), flowing out through a 0.2 m radius central outlet: the floor is the
grid line y = 0 from r = 0.2 m outwards, and the grid continues 1 m below it to catch the outflow.
Writes the case to stdout. Usage: silo_workload.py [steps]"""
import json, sys

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 77000
dt = 1.25 / 77000            # the paper's 1.25 s of discharge in 77,000 steps
h = 1.0 / 51                 # 51 x 153 cells x 4 points = 31,212 points in the fill
case = {
    "title": "silo discharge workload (seed 004 size)",
    "dimension": 2,
    "formulation": "axisymmetric",
    # density from particle positions, as seed 004 does for its silo flows: without it, points that
    # leave the outlet one by one expand without bound and are flung out of the grid
    "analysis": {"type": "explicit", "scheme": "musl", "end_time": steps * dt, "dt": dt,
                 "gravity": [0.0, -9.81], "density_update": "positions"},
    # below the silo floor (y = 0) an empty region receives the outflow
    "grid": {"type": "rectangle", "origin": [0.0, -1.0], "size": [1.0, 214 * h], "cells": [51, 214],
             "element": "quad4"},
    "materials": [{"name": "sand", "model": "viscoplastic_drucker_prager", "density": 1500,
                   "youngs_modulus": 1.0e6, "poisson_ratio": 0.3, "friction_angle": 25,
                   "viscosity": 50, "exponent": 1}],
    "bodies": [{"name": "fill", "material": "sand",
                "shape": {"type": "rectangle", "min": [0.0, 0.0], "max": [1.0, 3.0]},
                "particles_per_cell": 2}],
    "boundary_conditions": [
        {"type": "friction", "boundary": "x_max", "coefficient": 0.364},
        {"type": "friction", "boundary": {"y": 0.0, "from": 0.2, "normal": [0.0, -1.0]},
         "coefficient": 0.364},
        {"type": "fixed", "boundary": "y_min", "directions": ["x", "y"]}
    ],
    "output": {"interval": steps * dt / 10},
}
json.dump(case, sys.stdout, indent=1)
