"""Lab 3: progressive refinement (Southwell iteration) as a radkit solver.

Fill in step(). The check runs this class through radkit.solve, which measures the residual of
your B from F after every step, so it sees exactly how good each shot is.
"""
import numpy as np


class Southwell:
    name = "student-southwell"

    def start(self, system):
        """Initial guess B = E, all of E still unshot.

        system.F (n, n), system.area (n,) in m^2, system.reflectance and system.emission (n, 3).
        """
        self.F = system.F
        self.area = system.area
        self.rho = system.reflectance
        self.B = system.emission.copy()
        self.unshot = system.emission.copy()  # Delta B: radiosity received but not yet shot
        self.shots = 0

    def step(self):
        """One shot: the patch with the most unshot power sends it to every patch."""
        # Task 1: choose i, the patch with the largest unshot power A_i * sum over channels of
        #         Delta B_i (the first such patch when several tie).
        # Task 2: shoot it: every patch j (i itself too) receives rho_j F_ji Delta B_i, added to
        #         both B_j and Delta B_j, and patch i has nothing left to shoot. F_ji is row j of
        #         F; reciprocity gives it from row i: F_ji = F_ij A_i / A_j.
        raise NotImplementedError("Tasks 1 and 2: choose the patch and shoot it (southwell.py)")

    def radiosity(self):
        return self.B

    def sweeps(self):
        # A shot reads one row of F: 1/n of a full pass, the unit Jacobi and Gauss-Seidel use.
        return self.shots / len(self.area)
