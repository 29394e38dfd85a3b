"""The commands of ``bbb`` (pipeline/cli.py builds the parser from them and runs one): one
module per command group -- :mod:`.run` (run, accuracy), :mod:`.store` (reduce, status,
verify, plot), :mod:`.plan` (plan, scenes) -- and :mod:`.common`, what they share (the
usage error, argument types, the workflow argument)."""
