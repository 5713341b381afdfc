"""The search's limits, shared by the calibration's runner, its verifier and its searches (searches/)."""

INITIAL_RADIUS = 0.25    # coded units: +- a quarter of each coordinate's half-range (about a decade of a ratio)
SMALLEST_RADIUS = 0.01
MAX_ROUNDS = 12          # search rounds after the design, at most
