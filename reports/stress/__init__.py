"""The stress suite: cases made to break solvers, their truths, and the stability map's verdicts."""
