# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#   kernelspec:
#     name: python3
#     display_name: Python 3
# ---

# %% [markdown]
# # bbb from a notebook: run a scene, open its store, plot D(f) and a phase-space projection
#
# A jupytext "percent" script: open it in Jupyter with jupytext (`jupytext --to ipynb
# examples/notebook.py`), run its cells in IPython or VS Code, or all at once as a kernel
# would: `python -c "exec(open('examples/notebook.py').read())"` (the test suite does, so it
# cannot rot).  Not as `python examples/notebook.py`: Dask's worker processes would re-import
# a script's top level, which then starts another cluster (Python's spawn rule; a notebook
# has no such file).  It writes `runs/notebook.zarr` and two PNGs below the current directory
# and takes about 20 s on 2 cores.  Units: mm, s, Hz; D in mm²/s.

# %%
import matplotlib.pyplot as plt
import numpy as np

from pipeline import open_study, run_study

# %% [markdown]
# ## A small scene
# A workflow is TOML: parameters, frequencies, initial-condition families, accuracy and the
# observables to record (`pipeline/README.md`).  `run_study` also takes a file
# (`"workflows/smoke.toml"`), a shipped scene name (`"smoke"`), or a `distributed.Client`
# to run on an existing cluster (`client=...`).

# %%
SCENE = """
[study]
name = "notebook"
seed = 2004

[params]
preset = "klages2004"          # R = 15 mm, S = 2 mm, alpha = 0.7, beta = 0.99, A = 0.1 mm

[frequencies]
values = [58.0, 60.0, 66.0, 72.0, 78.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 16
chunk_size = 8
t_max = 20.0                   # s
sample_dt = 0.5                # s
n_resamples = 200

[observables.positions]

[observables.collisions]
record = 300                   # post-collision states per particle
record_from = 5.0              # s
"""

report = run_study(SCENE, "runs/notebook.zarr", workers=2)
print(report.summary())

# %% [markdown]
# Running it again resumes: chunks marked done are skipped, the store stays bit for bit the
# same (results depend only on parameters, frequency, family and seed).

# %%
again = run_study(SCENE, "runs/notebook.zarr", workers=2)
assert again.computed == [] and again.skipped == again.n_chunks

# %% [markdown]
# ## The store as an xarray Dataset
# Named dimensions, units in each variable's attributes; particles of chunks not marked done
# are masked (NaN).  `reduced=True` attaches `bbb reduce`'s D(f) table along `frequency`.

# %%
ds = open_study("runs/notebook.zarr", reduced=True)
print(ds[["positions", "collisions", "D", "D_lo", "D_hi"]])
print("positions in", ds.positions.attrs["units"], "| D in", ds.D.attrs["units"])

# %% [markdown]
# ## D(f) with its bootstrap 95 % confidence interval

# %%
f = ds.frequency.values
fig, ax = plt.subplots(figsize=(4, 3))
ax.errorbar(f, ds.D, yerr=[ds.D - ds.D_lo, ds.D_hi - ds.D], fmt="o-", capsize=2)
ax.set_xlabel("f (Hz)")
ax.set_ylabel("D (mm$^2$/s)")
ax.set_title(f"{int(ds.sizes['particle'])} particles x {float(ds.time[-1]):g} s, from rest")
fig.tight_layout()
fig.savefig("notebook_D.png", dpi=120)

# %% [markdown]
# ## Phase-space projection: post-collision (y, v_y⁺)
# The spiral of the paper's Fig. 3 at 72 Hz: every recorded collision of every particle.

# %%
c = ds.collisions.sel(frequency=72.0, family="rest")
y = c.sel(field="y").values.ravel()
vy = c.sel(field="vy").values.ravel()
ok = np.isfinite(y) & np.isfinite(vy)
fig, ax = plt.subplots(figsize=(4, 3))
ax.plot(y[ok], vy[ok], ".", ms=1, alpha=0.5)
ax.set_xlabel("y (mm)")
ax.set_ylabel("$v_y^+$ (mm/s)")
ax.set_title(f"f = 72 Hz: {ok.sum()} post-collision states")
fig.tight_layout()
fig.savefig("notebook_phase_space.png", dpi=120)
print(f"D(72 Hz) = {ds.D.sel(frequency=72.0).item():.0f} mm²/s; "
      f"{ok.sum()} collisions plotted")
