"""`python -m reports.cli` runs the command line."""

import sys

from reports.cli.main import main
from reports.harness.stop import end

sys.exit(end(main()))
