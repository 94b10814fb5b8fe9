"""`python -m mbxval` is the `mbxval` command line."""

import sys

from reports.entry import main

sys.exit(main())
