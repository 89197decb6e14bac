"""top_sim: a spinning top with a spherical tip on an inclined plane.

The physics core is the compiled module top_sim._core (pybind11), re-exported here; docs/python.md describes it.
top_sim.sweep runs top_sim_sweep's grid on a Dask cluster (docs/studies.md). In a catkin workspace the same
package also holds the generated ROS messages and services (top_sim.msg, top_sim.srv).
"""
from top_sim._core import *  # noqa: F401,F403 (the module's whole interface)
