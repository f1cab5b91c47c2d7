"""Unit constants for converting at the edges (paper tables, axis labels).

Everything inside the package is SI; multiply a paper value by its unit to
bring it in (``48 * MPA``) and divide to print it (``depth / MM``).
"""

MM = 1e-3
CM = 1e-2
MPA = 1e6
GPA = 1e9
G0 = 9.80665  # standard gravity, m/s^2, for decelerations quoted in g
KG_PER_G_CM3 = 1e3  # 1 g/cm^3 in kg/m^3
