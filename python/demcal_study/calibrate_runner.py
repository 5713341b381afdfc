"""The DEM side of a calibration: the budget, the runs spent (failed ones and verifications counted), and every point
run on specimen 1, which every decision of the searches and the verifier reads. A search asks the runner for a
round of points and whether the budget has room; it never counts runs itself."""
import math
import os

from . import calibrate_runs, curve_targets, outputs
from .calibrate_limits import FIRST_VERIFICATION_SEEDS
from .errors import load_json


class Runner:
    def __init__(self, problem, scene, out, tools, budget, tests, curves=(), quiet=False):
        self.problem, self.scene, self.out, self.tools = problem, scene, out, tools
        self.budget = budget
        self.tests = tests     # lab tests a point runs: the budget counts each
        self.curves = list(curves)
        self.quiet = quiet
        self.points = []       # every DEM point on specimen 1: {"u", "scale", "status", "outputs", "reason", "round"}
        self.runs = 0

    # -- the budget ------------------------------------------------------------------------------------------------
    def left(self):
        """Test runs the budget has left."""
        return self.budget - self.runs

    def room_for(self, points, reserve=0):
        """Whether `points` more points fit in the budget with `reserve` test runs kept back."""
        return self.runs + points * self.tests <= self.budget - reserve

    def verification_reserve(self):
        """Test runs a search keeps back for the first verification and a correction."""
        return min((FIRST_VERIFICATION_SEEDS + 10) * self.tests, self.budget // 3)

    def spend(self, seeds):
        """Count `seeds` runs of every test (a verification's)."""
        self.runs += seeds * self.tests

    # -- the points on specimen 1 ----------------------------------------------------------------------------------
    def run_round(self, label, entries):
        """entries: (coded u, scale factor). Runs as many as the budget holds on specimen 1 (rounds/LABEL, resumable),
        records them and returns the records added."""
        if not self.room_for(len(entries)):
            entries = entries[:max(self.left() // self.tests, 0)]
        if not entries:
            return []
        params = [self.problem.absolute(u, s) for u, s in entries]
        results = calibrate_runs.run_points(self.tools, self.scene, os.path.join(self.out, "rounds", label), params,
                                            self.quiet)
        self.spend(len(entries))
        added = []
        for (u, s), r in zip(entries, results):
            # A measured curve's points are read from the run's curve (curve_targets).
            measured = dict(r["outputs"], **curve_targets.point_values(r.get("curve"), self.curves))
            p = {"u": [float(x) for x in u], "scale": float(s), "status": r["status"],
                 "outputs": outputs.with_ratios(measured, self.problem.targets),
                 "reason": r["reason"], "round": label}
            self.points.append(p)
            added.append(p)
        return added

    def modelled(self, values, scale):
        """A point's modelled responses: log(stress / scale) for stress outputs, the others as they are."""
        return {o: self.problem.to_model(o, values[o], scale) for o in self.problem.modelled_outputs()}

    def usable(self):
        """(u, modelled responses in the problem's order) of every point that ran and gave them all finite."""
        rows = []
        for p in self.points:
            if p["status"] != "ok" or any(o not in p["outputs"] for o in self.problem.modelled_outputs()):
                continue
            z = self.modelled(p["outputs"], p["scale"])
            if all(math.isfinite(v) for v in z.values()):
                rows.append((p["u"], [z[o] for o in self.problem.modelled_outputs()]))
        return rows

    def point_wall_s(self, label):
        """Mean wall time of a round's points (as they ran: alone, or sharing the cores with other jobs), s;
        0 when none is stored."""
        folder = os.path.join(self.out, "rounds", label, "responses.h5.points")
        walls = []
        for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
            if name.endswith("_seed1.json"):
                wall = load_json(os.path.join(folder, name), "DEM result").get("wall_s", 0.0)
                if isinstance(wall, (int, float)) and wall > 0:
                    walls.append(float(wall))
        return sum(walls) / len(walls) if walls else 0.0
