"""Tests against a real one-machine SLURM cluster (conftest.py, slurm.sh)."""
