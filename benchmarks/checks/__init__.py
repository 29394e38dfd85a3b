"""Correctness runs too long for the tests: the soak, the cusp-contact property run and its
independent reference, D(f) tables' agreement, the rare-mover rule and CV² on stores."""
