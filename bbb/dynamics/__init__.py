"""bbb.dynamics — the time evolution of the bouncing ball billiard, one map for both floors.

The floor is a compile-time choice: ``frame`` None is the paper's level floor, a
:class:`~bbb.dynamics.options.Frame` the tilted/thrown conveyor; numba prunes the other's
branches, so each floor compiles to its own code.  Modules, one idea each:

- options: the kernel's records (Floor, Run, Frame; a contact step's Contact and Tally) and heave,
  the gravity and amplitude normal to either floor
- events: event codes, the event guard, the floor clock, recorded rows, counters
- motion: positions, floor velocity and flights (Eqs. 1-4) on either floor
- collide: the collision rule, Eqs. (5)-(6), once for both floors
- liftoff: when a particle held at rest lifts off, once for both floors
- bounds: the gap and its certificates (lower bound, start step), each rule once for both floors
- search: the certified collision search, one driver and one refine_root for both floors
- slide: the contact phase's integrator with certified events (both floors)
- static_friction: when static friction holds a particle at rest (both floors)
- contact_step: one contact step (a slip from rest, a slide, its event) and the contact
  start (enter_contact), once for both floors
- evolve: the map itself, evolve and evolve_ensemble
"""

from .evolve import evolve, evolve_ensemble
from .options import Floor, Frame, Run, frame_of

__all__ = ["Floor", "Frame", "Run", "evolve", "evolve_ensemble", "frame_of"]
