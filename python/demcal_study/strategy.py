"""The three shapes a study file takes, read from its fields: surrogates fitted on designs (the default), the
DEM in the loop ("strategy": "dem_in_the_loop", a `factors` list instead of surfaces), or a screening alone (a
`screening` and no surfaces: its range analysis and ANOVA are the result)."""

# Fields that mean nothing without an inversion, so a screening alone refuses them.
CALIBRATION_ONLY = ("targets", "surrogate", "inversion", "verification", "refinement", "seeds_per_point",
                    "stability", "compare_with", "factors")


def in_the_loop(study):
    return study.get("strategy", "surrogate") == "dem_in_the_loop"


def screening_only(study):
    return not in_the_loop(study) and "surfaces" not in study and "screening" in study
