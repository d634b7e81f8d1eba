"""The ``restitution`` command line: one subcommand per common job.

Each subcommand lives in a module of :mod:`restitution.commands` exposing ``NAME``, ``HELP``,
``add_arguments(parser)`` and ``run(args) -> int``; this file only collects and dispatches them.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from typing import Sequence

from . import __version__

#: Subcommand modules, in the order ``--help`` lists them.
COMMANDS = ("fig2", "sweep", "ensemble", "calibrate", "reproduce", "accuracy", "validate", "pairs")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="restitution",
        description="Oblique particle impacts (2D DEM): restitution coefficients, spin and energy audits.",
    )
    parser.add_argument("--version", action="version", version=f"restitution {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in COMMANDS:
        module = importlib.import_module(f".commands.{name}", __package__)
        p = sub.add_parser(module.NAME, help=module.HELP, description=module.HELP)
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args._run(args))
    except ValueError as err:
        # Bad parameters are the user's to fix: one line, no traceback.
        print(f"restitution {args.command}: error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"restitution {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    raise SystemExit(main())
