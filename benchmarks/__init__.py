"""bbb's benchmarks, run as modules from the checkout's root (``python -m benchmarks.perf.kernel``).

calibrations/  the makers of every calibration a rule or the checker reads (``make calibrate``)
bits/          bit-for-bit comparisons: this checkout against another revision, a map against a scene
checks/        correctness runs too long for the tests (soak, cusp contact, agreement of tables)
perf/          speed and overheads of the kernel, the pipeline and the store (``make bench``)
studies/       what studies cost and how they scale: ``bbb plan`` against measured runs
results/       the committed outputs, each with its date and CPU
"""
