"""`python -m reports.cli` runs the command line."""

import sys

from reports.cli.main import main
from reports.run import stop

sys.exit(stop.end(main()))
