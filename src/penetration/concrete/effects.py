"""Effects a cavity-level scene may list that act on the HJC material (a registry by name).

Each maps to the HJC fields that switch its term off: a scene that lists
the effect keeps Table 1's term, one that leaves it out gets the fields.
Kept apart from ``hjc`` so that scenes can name them without compiling it.
"""

MATERIAL_EFFECTS = {
    "strain_rate": {"rate": False},      # the C ln(eps_dot*) rate term of Eq 17
    "damage": {"damage": False},         # damage accumulation, Eq 18
    "strength_cap": {"smax": 1e6},       # the Smax cap on the normalised strength
}
