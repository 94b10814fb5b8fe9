"""`python -m reports.cli` runs the command line."""

import sys

from reports.cli.main import main

sys.exit(main())
