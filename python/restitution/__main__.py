"""``python -m restitution`` is the ``restitution`` command."""

from .cli import main

raise SystemExit(main())
