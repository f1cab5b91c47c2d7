"""Replication of Liu, Pi & Huang (2015), penetration of double-ogive noses.

Stages import one way: geometry -> nstar -> (inference) -> reference ->
figures; ``tasks`` is the only module that reads or writes files.
"""
__version__ = "0.1.0"
