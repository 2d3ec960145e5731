"""``python3 -m canalpath``."""
import sys

from .cli import main

sys.exit(main())
