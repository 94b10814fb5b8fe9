"""The solver's limits, shared by the plain path and the compiled kernel (which imports, never restates,
them)."""

SINGULAR_RCOND = 1e-9
"""A scaled Jacobian with a reciprocal condition number below this is treated as singular."""
NEAR_SINGULAR = 1e-4
"""On a Newton failure, a smallest singular value ratio below this names the failure singular."""
JUMP_FRACTION = 0.5
JUMP_FLOOR = 1e-6
"""A converged step whose correction to the predictor exceeds JUMP_FRACTION of the predictor's reach
max_i (|h qd_i| + h^2 |qdd_i|) (and JUMP_FLOOR; scaled units) has left its branch: on a smooth path
the correction is O(h^3) against a reach O(h) (at most 0.25 of it even at 8 steps per revolution
over the catalogue), while a jump to another solution is a finite distance. Such a step is retaken
in halved steps, which either follow the branch or stop where it ends."""
ASSEMBLY_ITERATIONS = 100
"""Damped Newton iterations allowed for the assembly from the scenario's rough guess."""
BACKTRACK_HALVINGS = 30
"""Halvings of a Newton step allowed before the damped step gives up decreasing the residual."""
ROUND_OFF_ULPS = 4
"""Newton's step tolerance never goes below this many units in the last place of the largest scaled
coordinate (newton._round_off): a smaller step is not resolvable."""
