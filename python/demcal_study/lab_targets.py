"""Lab measurements as calibration targets: a mean with the lab's own scatter.

A target is written NAME=MEAN+-SD or NAME=MEAN+-SD/n=N: SD is the standard deviation over the lab's specimens (Lac du
Bonnet granite: sigma_u_MPa=200+-22, Potyondy & Cundall 2004, Table 2) and N how many specimens the mean is of (1
when not given: one specimen, its scatter the whole SD). Or the lab's specimens themselves, as a CSV with a header
`test,output,value` (and an optional `specimen` column): each output's mean, SD and N come from its rows, and where
the specimen column says which rows are one specimen, the correlation of two outputs over the specimens that have
both.

The likelihood of the DEM's seed mean against a lab mean (`gaussian_log_likelihood`) adds the two means' own
uncertainties: the lab's standard error (SD / sqrt(N), never the SD itself, which would count the scatter of a single
specimen against a mean) and the DEM mean's standard error, measured over its seeds. Outputs measured on one specimen
carry the lab's correlation; the DEM's correlation is given by its caller (its seeds measure it) or taken as none.
"""
import csv
import math
import re
from dataclasses import dataclass

import numpy as np

from .errors import fail

_UNCERTAIN = re.compile(r"^(?P<mean>[^+/]+)\+-(?P<sd>[^/]+)(?:/n=(?P<n>.+))?$")


@dataclass(frozen=True)
class LabTarget:
    """One measured output: the mean of `n` specimens and their standard deviation (None: a bare number)."""

    name: str
    mean: float
    sd: float = None
    n: int = 1

    @property
    def standard_error(self):
        """The uncertainty of the mean: SD / sqrt(n); 0 for a bare number."""
        return 0.0 if self.sd is None else self.sd / math.sqrt(self.n)

    def text(self):
        """As a user writes it."""
        if self.sd is None:
            return f"{self.name}={self.mean:g}"
        return f"{self.name}={self.mean:g}+-{self.sd:g}" + (f"/n={self.n}" if self.n != 1 else "")


def _finite(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def parse_target(part, what="--target"):
    """A LabTarget from NAME=MEAN, NAME=MEAN+-SD or NAME=MEAN+-SD/n=N, or a one-line message saying what is wrong
    (returned, not raised, so a caller can collect every problem before it stops)."""
    name, sep, value = part.partition("=")
    if not sep or not name:
        return f"{what}: \"{part}\" is not NAME=VALUE, NAME=MEAN+-SD or NAME=MEAN+-SD/n=N"
    plain = _finite(value)
    if plain is not None:
        return LabTarget(name, plain)
    match = _UNCERTAIN.match(value)
    if not match:
        return f"{what}: {name}: \"{value}\" is not a number, MEAN+-SD or MEAN+-SD/n=N"
    mean, sd = _finite(match["mean"]), _finite(match["sd"])
    if mean is None:
        return f"{what}: {name}: the mean \"{match['mean']}\" is not a finite number"
    if sd is None or not sd > 0:
        return f"{what}: {name}: the uncertainty \"{match['sd']}\" must be a number above 0 (the specimens' SD)"
    n = 1
    if match["n"] is not None:
        if not re.fullmatch(r"[0-9]+", match["n"]) or int(match["n"]) < 1:
            return f"{what}: {name}: n=\"{match['n']}\" must be a whole number of specimens, at least 1"
        n = int(match["n"])
    return LabTarget(name, mean, sd, n)


def read_specimens(path):
    """({name: LabTarget}, names, correlation matrix over those names) from a CSV of the lab's specimens. A name is the
    row's output, prefixed `TEST.` when the test column is not empty (a scene list names an output shared by several
    tests so). Fails with one line naming the file, row and field on a bad row, and on an output with fewer than 2
    specimens (no SD to take)."""
    by_name, specimen_of = _measurements(path)
    targets = {}
    for name, values in by_name.items():
        if len(values) < 2:
            fail(f"{path}: {name}: one specimen gives no scatter; give at least 2, or write --target "
                 f"{name}=MEAN+-SD/n=N")
        sd = float(np.std(values, ddof=1))
        if not sd > 0:
            fail(f"{path}: {name}: every specimen measured {values[0]:g}: no scatter to weigh it by")
        targets[name] = LabTarget(name, float(np.mean(values)), sd, len(values))
    names = list(targets)
    return targets, names, specimen_correlation(names, specimen_of)


def specimen_values(path):
    """{(name, specimen): value} of the rows of a CSV of the lab's specimens that name their specimen (read_specimens
    has checked the file)."""
    return _measurements(path)[1]


def _measurements(path):
    """({name: [values]}, {(name, specimen): value}) of a CSV of the lab's specimens; a bad file fails naming it."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
            header = rows[0].keys() if rows else None
    except OSError as e:
        fail(f"{path}: cannot read the lab's specimens: {e.strerror}")
    except (csv.Error, UnicodeDecodeError) as e:
        fail(f"{path}: not a CSV of the lab's specimens: {e}")
    if not rows:
        fail(f"{path}: no specimens (a header test,output,value and a row per measurement)")
    missing = [c for c in ("test", "output", "value") if c not in header]
    if missing:
        fail(f"{path}: the header lacks {', '.join(missing)} (columns: test,output,value[,specimen])")
    by_name, specimen_of = {}, {}
    for number, row in enumerate(rows, start=2):  # the header is line 1
        output, test = (row["output"] or "").strip(), (row["test"] or "").strip()
        if not output:
            fail(f"{path}: line {number}: output is empty")
        value = _finite((row["value"] or "").strip())
        if value is None:
            fail(f"{path}: line {number}: value \"{row['value']}\" is not a finite number")
        name = f"{test}.{output}" if test else output
        by_name.setdefault(name, []).append(value)
        specimen = (row.get("specimen") or "").strip()
        if specimen:
            key = (name, specimen)
            if key in specimen_of:
                fail(f"{path}: line {number}: specimen {specimen} has {name} twice")
            specimen_of[key] = value
    return by_name, specimen_of


def named_as_outputs(measured, outputs):
    """read_specimens' answer with each TEST.OUTPUT name that is not an output of the scene but whose OUTPUT is
    renamed OUTPUT: a scene list prefixes an output only where several of its tests give it, and a lab writes the test
    of every row."""
    by_name, names, r = measured

    def plain(name):
        test, dot, output = name.partition(".")
        return output if dot and name not in outputs and output in outputs else name
    renamed = {plain(n): LabTarget(plain(n), t.mean, t.sd, t.n) for n, t in by_name.items()}
    return renamed, [plain(n) for n in names], r


def specimen_correlation(names, specimen_of):
    """The correlation of each two outputs over the specimens that measured both (Pearson; 0 where fewer than 3
    specimens have both, too few to tell), 1 on the diagonal."""
    k = len(names)
    r = np.eye(k)
    specimens = {s for _, s in specimen_of}
    for a in range(k):
        for b in range(a + 1, k):
            shared = sorted(s for s in specimens if (names[a], s) in specimen_of and (names[b], s) in specimen_of)
            if len(shared) < 3:
                continue
            x = np.array([specimen_of[(names[a], s)] for s in shared])
            y = np.array([specimen_of[(names[b], s)] for s in shared])
            if np.std(x) > 0 and np.std(y) > 0:
                r[a, b] = r[b, a] = float(np.corrcoef(x, y)[0, 1])
    return r


def gaussian_log_likelihood(targets, dem_means, dem_standard_errors, lab_correlation=None, dem_correlation=None):
    """log p(lab means | DEM): the lab means and the DEM's seed means of the same outputs, in the order of `targets`,
    each mean with its own standard error; the covariance of their difference is the lab's (its standard errors with
    `lab_correlation`, else none) plus the DEM's (likewise with `dem_correlation`). One parameter set (means and
    standard errors of shape (k,): a float) or several at once (rows of shape (m, k): an array of m)."""
    k = len(targets)
    means = np.asarray(dem_means, dtype=float)
    dem_se = np.asarray(dem_standard_errors, dtype=float)
    single = means.ndim == 1
    means, dem_se = np.atleast_2d(means), np.atleast_2d(dem_se)
    if means.shape[1:] != (k,) or dem_se.shape != means.shape:
        raise ValueError("one DEM mean and one standard error per target")
    lab_se = np.array([t.standard_error for t in targets], dtype=float)
    lab_r = np.eye(k) if lab_correlation is None else np.asarray(lab_correlation, dtype=float)
    dem_r = np.eye(k) if dem_correlation is None else np.asarray(dem_correlation, dtype=float)
    covariance = lab_r * np.outer(lab_se, lab_se) + dem_r * (dem_se[:, :, None] * dem_se[:, None, :])
    residual = means - np.array([t.mean for t in targets], dtype=float)
    try:
        factor = np.linalg.cholesky(covariance)
    except np.linalg.LinAlgError:
        raise ValueError("the targets' covariance is not positive definite: a target without uncertainty needs the "
                         "DEM's own, measured over seeds") from None
    whitened = np.linalg.solve(factor, residual[:, :, None])[:, :, 0]
    log_det = 2.0 * np.log(np.diagonal(factor, axis1=1, axis2=2)).sum(axis=1)
    value = -0.5 * ((whitened ** 2).sum(axis=1) + log_det + k * math.log(2.0 * math.pi))
    return float(value[0]) if single else value
