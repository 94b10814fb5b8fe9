"""The constraint equations, one module per group (joints, drivers, gears, cams), each composed from
reference_solver.kinematic_vectors so that C, C_q, C_t and Q_d come from one derivation."""
