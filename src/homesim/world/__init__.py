"""Homes as environment graphs (VirtualHome JSON format, with 3D boxes)."""

from homesim.world.graph import BoundingBox, Edge, EnvironmentGraph, Node
from homesim.world.homes import home_names, load_home

__all__ = ["BoundingBox", "Edge", "EnvironmentGraph", "Node", "home_names", "load_home"]
