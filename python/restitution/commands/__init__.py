"""Subcommands of the ``restitution`` CLI, one module each (see :mod:`restitution.cli`)."""
