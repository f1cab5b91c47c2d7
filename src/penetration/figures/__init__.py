"""One module per figure or table of the paper, named after it and after its rule.

Figure modules read result files and draw; they compute nothing beyond unit
conversion. Each writes its PNG and the tidy CSV that it drew, and overlays
the paper's values where any exist.
"""
