"""The limits and exit codes shared by the calibration's runner, its verifier and its searches (searches/)."""

INITIAL_RADIUS = 0.25    # coded units: +- a quarter of each coordinate's half-range (about a decade of a ratio)
SMALLEST_RADIUS = 0.01
MAX_ROUNDS = 12          # search rounds after the design, at most
FIRST_VERIFICATION_SEEDS = 5
MAX_VERIFICATION_SEEDS = 20
EXIT_MET, EXIT_UNREACHABLE, EXIT_BUDGET = 0, 3, 4
EXIT_FAILED = 4  # the runs themselves failed: nothing says the targets are out of reach
