"""Transport on a vibro-conveyor: drift v(f) and D(f) about the drift at the paper's
parameters for a tilted floor (φ = 0°, 2°, 5°, vertical throw), an oblique throw (ψ = 60°,
30°, level floor) and both at once, from the map scene ``scenes/transport.toml`` (tilt ×
throw, one grid line per floor), and the sliding regime below lift-off on one floor under the
stick and Coulomb contact models (the map ``scenes/transport_sliding.toml``, one line per
model), and the transport map ``scenes/transport_reversal.toml``: v over (throw ψ, f) on a
floor tilted 2° against its throw, under stick and Coulomb friction, from below lift-off into
hopping, with the share of the run in flight (``reversal``: where v changes sign along f and
along ψ, each change located as an interval, and the sliding/hopping boundary against
conveyor theory's throw number Γ_v = Γ sin ψ / cos φ = 1, its threshold checked on flat
floors by ``hopping_calibration``).  The figures (``figures``) and the claims as data
(``claims``, the sign rules in ``signs``) read each line's table (``claims.line_tables``).

The interface make_figures uses: :data:`SCENES`, :func:`draw`, :func:`report_lines`.
"""

from .claims import CLAIMS, SCENES, report_lines
from .figures import CAPTIONS, draw

__all__ = ["SCENES", "CLAIMS", "CAPTIONS", "draw", "report_lines"]
