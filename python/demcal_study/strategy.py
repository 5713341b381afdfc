"""The shapes a study file takes, read from its fields: surrogates fitted on designs (the default), the DEM in the
loop ("strategy": "dem_in_the_loop", a `factors` list instead of surfaces), the trust region of `make calibrate`
("strategy": "trust_region": targets, a budget, optionally a space; docs/explanation/calibration_method.md), or a screening alone (a
`screening` and no surfaces: its range analysis and ANOVA are the result)."""

# Fields that mean nothing without an inversion, so a screening alone refuses them.
CALIBRATION_ONLY = ("targets", "surrogate", "inversion", "verification", "refinement", "seeds_per_point",
                    "stability", "compare_with", "factors")


# Fields of the surrogate and DEM-in-the-loop shapes that the trust region does not take (it chooses its own
# designs, specimens per point and verification seeds).
NOT_TRUST_REGION = ("screening", "surfaces", "surrogate", "inversion", "refinement", "seeds_per_point", "stability",
                    "factors", "compare_with")


def in_the_loop(study):
    return study.get("strategy", "surrogate") == "dem_in_the_loop"


def trust_region(study):
    return study.get("strategy") == "trust_region"


def screening_only(study):
    return not in_the_loop(study) and not trust_region(study) and "surfaces" not in study and "screening" in study
