"""Speed against accuracy: Gear-5 and Verlet at several steps against the reference integrator, on the
exact disc and regular polygons (n = 12 ... 480), over theta and mu. Prints a Markdown table and the
cheapest configuration per target error, writes results/accuracy.{md,parquet,png}.

    python examples/accuracy_study.py [--quick]      # the same as `restitution accuracy [--quick]`
"""

from __future__ import annotations

import sys

from restitution.cli import main

if __name__ == "__main__":
    raise SystemExit(main(["accuracy", *sys.argv[1:]]))
