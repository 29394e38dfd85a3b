"""Speed: the kernel (collisions per CPU second, side by side with another revision), the
pipeline's overheads and scaling, the store's checks, the SLURM test cluster (``make bench``
runs kernel and pipeline)."""
