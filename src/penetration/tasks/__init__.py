"""The I/O layer of the pipeline, one module per stage.

Each module holds the tasks of one stage's rules (a task is the function a
rule calls, named after the rule): it reads the rule's inputs, calls the
physics, and writes the outputs through ``penetration.pipeline.io``. Physics
decisions live in the physics modules, never here.
"""
