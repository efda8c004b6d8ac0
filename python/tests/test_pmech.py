"""Tests of the Python package (run by ctest as python.package).

A falling block checks run, energy and frames against physics that does not depend on pmech: a body
in free fall under g has kinetic energy m g^2 t^2 / 2 (linear MPM moves a rigid body exactly: relative
tolerance 1e-9, summation rounding), its particles all move by g t^2 / 2 minus the rounding of the
explicit update (displacement sums v dt with v = g t, so it is g t (t + dt) / 2: checked to 1e-9
relative against that sum), the nodal mass sums to the particle mass (partition of unity, 1e-9).
Key-path changes are checked against the values a case file gives, refused values against the loader's
message, and plots against the files they write.
"""
import json
import os
import shutil
import sys
import tempfile
import unittest

import numpy as np

import pmech

G = 10.0
DT = 1e-3
T_END = 0.1

FALL = {
    "title": "fall", "dimension": 2,
    "analysis": {"type": "explicit", "end_time": T_END, "gravity": [0, -G], "dt": DT},
    "grid": {"type": "rectangle", "size": [1, 1], "cells": [10, 10]},
    "materials": [{"name": "m", "model": "mohr_coulomb", "density": 1000, "youngs_modulus": 1e6,
                   "poisson_ratio": 0.3, "friction_angle": 30, "cohesion": 1e3}],
    "bodies": [{"name": "block", "material": "m",
                "shape": {"type": "rectangle", "min": [0.3, 0.5], "max": [0.7, 0.9]}}],
    "probes": [{"name": "c", "body": "block", "quantity": "velocity"}],
    "output": {"interval": 0.05},
}


class PmechTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="pmech_py_")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def case(self, **changes):
        c = pmech.Case.from_dict(FALL, name=os.path.join(self.tmp, "fall.json"))
        for k, v in changes.items():
            c[k] = v
        return c

    def test_keys_by_path(self):
        c = self.case()
        self.assertEqual(c["materials[0].friction_angle"], 30)
        c["materials[0].friction_angle"] = 35
        self.assertEqual(c["materials[0].friction_angle"], 35)
        c["analysis.gravity"] = [0, -5]
        self.assertEqual(c.to_dict()["analysis"]["gravity"], [0, -5])
        with self.assertRaises(pmech.InputError) as e:
            c["materials[0].friction_angle"] = 95
        self.assertIn("materials[0].friction_angle", str(e.exception))
        self.assertIn("95", str(e.exception))
        self.assertEqual(c["materials[0].friction_angle"], 35)  # unchanged
        with self.assertRaises(pmech.InputError) as e:
            c["materials[0].friction_angel"] = 30
        self.assertIn("did you mean 'friction_angle'", str(e.exception))
        with self.assertRaises(KeyError):
            c["analysis.dt_typo"]
        del c["analysis.dt"]
        self.assertNotIn("analysis.dt", c)
        c.save(os.path.join(self.tmp, "saved.json"))
        again = pmech.Case(os.path.join(self.tmp, "saved.json"))
        self.assertEqual(again.to_dict(), c.to_dict())
        self.assertEqual(c.output_dir, "fall.out")
        with self.assertRaises(pmech.InputError):
            pmech.Case(os.path.join(self.tmp, "no_such.json"))

    def test_warnings(self):
        self.assertEqual(self.case().warnings, [])
        w = self.case(**{"materials[0].friction_angle": 0.5236}).warnings
        self.assertEqual(len(w), 1)
        self.assertIn("radians", w[0])

    def test_run_energy_probes_frames(self):
        out = os.path.join(self.tmp, "out")
        run = self.case().run(out, threads=1)
        info = run.info
        self.assertEqual(info["exit_status"], 0)
        mass = 1000 * 0.4 * 0.4
        e = run.energy
        self.assertEqual(e.dtype.names, ("time", "kinetic", "strain", "gravity", "total"))
        self.assertEqual(len(np.unique(e["time"])), len(e))
        np.testing.assert_allclose(e["kinetic"], 0.5 * mass * (G * e["time"]) ** 2, rtol=1e-9, atol=1e-12)
        p = run.probes
        np.testing.assert_allclose(p["c.vy"], -G * p["time"], rtol=1e-9, atol=1e-12)
        frames = run.frames
        self.assertEqual(len(frames), 3)
        np.testing.assert_allclose([t for t, _ in frames], [0.0, 0.05, 0.1], atol=1e-12)  # times summed from steps
        last = run.frame(-1)
        self.assertAlmostEqual(last.time, T_END, delta=1e-12)
        self.assertEqual(last["stress"].shape, (last.n, 4))
        self.assertEqual(last.points.shape, (last.n, 3))
        uy = last["displacement"][:, 1]
        np.testing.assert_allclose(uy, -G * T_END * (T_END + DT) / 2, rtol=1e-9)
        speed, unit = last.field("speed")
        self.assertEqual(unit, "m/s")
        np.testing.assert_allclose(speed, G * T_END, rtol=1e-9)
        with self.assertRaises(pmech.InputError):
            last.field("nonsense")
        g = run.grid_frame(-1)
        self.assertAlmostEqual(g["mass"].sum(), last["mass"].sum(), delta=1e-9 * mass)
        self.assertEqual(len(run.grid_frames), 3)

    def test_plots_and_pictures(self):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import pmech.plot
        run = self.case().run(os.path.join(self.tmp, "out"), threads=1)
        fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
        pmech.plot.history(run.energy, "kinetic", "gravity", ax=a, ylabel="energy [J/m]")
        pmech.plot.snapshot(run.frame(-1), "speed", ax=b)
        self.assertEqual(b.get_xlabel(), "x [m]")
        png = os.path.join(self.tmp, "fig.png")
        fig.savefig(png)
        self.assertGreater(os.path.getsize(png), 1000)
        n = run.render("pressure", out_dir=os.path.join(self.tmp, "pics"))
        self.assertEqual(n, 3)
        self.assertTrue(os.path.exists(os.path.join(self.tmp, "pics", "pressure_000002.png")))

    def test_factor_of_safety(self):
        # A coarse 2:1 slope: only that the search runs and brackets its answer (the physics of strength
        # reduction is verified in C: tests/verification/verify_slope_fos.c).
        slope = {
            "dimension": 2,
            "analysis": {"type": "quasi_static", "end_time": 1, "load_steps": 1, "gravity": [0, -9.81],
                         "newton": {"tolerance": 1e-8, "displacement_tolerance": 1e-4, "max_step_cuts": 4},
                         "strength_reduction": {"min": 0.5, "max": 3, "tolerance": 0.2}},
            "grid": {"type": "rectangle", "size": [34, 12], "cells": [17, 6]},
            "materials": [{"name": "soil", "model": "mohr_coulomb", "density": 2038.7,
                           "youngs_modulus": 1e8, "poisson_ratio": 0.3, "cohesion": 1e4,
                           "friction_angle": 20, "dilatancy_angle": 0}],
            "bodies": [{"name": "slope", "material": "soil", "particles_per_cell": 2,
                        "shape": {"type": "polygon", "points": [[0, 0], [32, 0], [12, 10], [0, 10]]}}],
            "boundary_conditions": [{"type": "fixed", "boundary": "y_min", "directions": ["x", "y"]},
                                    {"type": "fixed", "boundary": "x_min", "directions": ["x"]}],
        }
        c = pmech.Case.from_dict(slope, name=os.path.join(self.tmp, "slope.json"))
        fos, lo, hi = c.factor_of_safety()
        self.assertLess(lo, hi)
        self.assertTrue(lo <= fos <= hi)
        self.assertLessEqual(hi - lo, 0.2)
        del c["analysis.strength_reduction"]
        with self.assertRaises(pmech.InputError):
            c.factor_of_safety()


if __name__ == "__main__":
    unittest.main(verbosity=2)
