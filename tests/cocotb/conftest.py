"""pytest configuration of the cocotb testbench: the test module is also imported by the
simulator (cocotb's runner), so it must be importable from this folder."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
