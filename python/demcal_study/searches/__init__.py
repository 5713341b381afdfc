"""The calibration's searches behind one protocol: a search is an object with a `name` and

    run(calibration, centre, best, label="r") -> (centre, radius, best point, converged, blocked at the bounds)

which spends DEM runs through the calibration (`calibration.run_round`, its budget, points and residual algebra)
from the coded point `centre` and the best point measured so far, storing its rounds as rounds/LABEL02, LABEL03,
... The runner (calibrate.Calibration) owns the budget and the stored runs; the verifier re-enters the trust-region
search when the scale factor leaves its bounds. `make calibrate STRATEGY=NAME` picks one; a study file's
`"search"` field likewise."""
from .bayes_search import BayesSearch
from .kriging_search import KrigingSearch
from .trust_region_search import TrustRegionSearch

SEARCHES = {s.name: s for s in (TrustRegionSearch, KrigingSearch, BayesSearch)}
NAMES = tuple(SEARCHES)


def by_name(name):
    """The search called `name` (one of NAMES)."""
    return SEARCHES[name]()
