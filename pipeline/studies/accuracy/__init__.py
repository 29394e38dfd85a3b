"""The accuracy study: presets and single knobs against a reference through the real pipeline
(``study``; ``bbb accuracy``, docs/accuracy.md)."""
