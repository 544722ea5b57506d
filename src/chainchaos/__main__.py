"""``python -m chainchaos``: the ``chainchaos`` command (chainchaos.workflow.cli)."""

import sys

from chainchaos.workflow.cli import main

if __name__ == "__main__":
    sys.exit(main())
