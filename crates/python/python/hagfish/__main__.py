"""``python -m hagfish``: the ``hagfish`` command (``hagfish._cli``)."""

from ._cli import main

if __name__ == "__main__":
    main()
