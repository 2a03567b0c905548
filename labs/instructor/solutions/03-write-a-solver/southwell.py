"""Lab 3 reference solution: progressive refinement (Southwell iteration)."""
import numpy as np


class Southwell:
    name = "student-southwell"

    def start(self, system):
        self.F = system.F
        self.area = system.area
        self.rho = system.reflectance
        self.B = system.emission.copy()
        self.unshot = system.emission.copy()
        self.shots = 0

    def step(self):
        power = self.area * self.unshot.sum(axis=1)
        i = int(np.argmax(power))  # argmax returns the first of equal maxima
        shot = self.unshot[i].copy()
        self.unshot[i] = 0  # before distributing: light patch i sends to itself stays unshot
        f_ji = self.F[i] * self.area[i] / self.area  # F_ji by reciprocity, for every j
        received = self.rho * f_ji[:, None] * shot[None, :]
        self.B += received
        self.unshot += received
        self.shots += 1

    def radiosity(self):
        return self.B

    def sweeps(self):
        return self.shots / len(self.area)
