"""One module per figure or table of the paper; each registers one task.

Figure modules read result files and draw; they compute nothing beyond unit
conversion. Each writes figNN.png and the tidy figNN.csv that it drew, and
overlays the paper's values where any exist.
"""
from . import accuracy, cavity_sensitivity, cavity_sigma, fig01, fig10, fig12, fig14, fig03, fig04, fig05, fig06, fig07, fig08, fig15, fig16, tables, validation  # noqa: F401
