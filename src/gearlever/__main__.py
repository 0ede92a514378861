"""``python -m gearlever``: the same as the ``gearlever`` console script."""

from gearlever.cli import main

if __name__ == "__main__":
    raise SystemExit(main())
