"""The erosion-free target: what the FE level adds to its Lagrangian step so that no element of the target is ever
deleted (BookLeaf keeps its ALE step as ``packages/ale`` beside the Lagrangian one; this is that package here).

- ``controls``: its controls (``ErosionFree``), one object on the solver's ``Controls`` (``Controls.erosion_free``,
  None on the eroding target): the only switch between the two targets the solver sees. A scene or a shot states
  its target's ``formulation`` (``spec.TargetSpec``), from which ``shot.model_for`` builds these controls.
- ``rezone``: the operator-split ALE (rezone of the mesh near the path, remap by swept faces) and the ejection of the
  lip thrown above the struck face.
- ``debris``: what an element that loses its shape is, and where it may be: ejecta, crater debris, wall debris
  behind the projectile's tail (booked, never deleted), or a stop of the run.
"""
