"""top_sim: a spinning top with a spherical tip on an inclined plane.

The physics core is the compiled module top_sim._core (pybind11), re-exported here; docs/python.md describes it.
top_sim.sweep runs top_sim_sweep's grid on a Dask cluster (docs/studies.md). In a catkin workspace the same
package also holds the generated ROS messages and services (top_sim.msg, top_sim.srv).
"""
from pkgutil import extend_path

# Every top_sim directory on sys.path: in a catkin workspace the sources (this file) and the devel space (msg, srv,
# _core) are two directories of one package, also when this file is found first (a spawned process's sys.path).
__path__ = extend_path(__path__, __name__)
del extend_path

try:
    from top_sim._core import *  # noqa: E402,F401,F403 (the module's whole interface)
except ModuleNotFoundError as e:  # built with TOP_SIM_PYTHON=OFF: top_sim.msg and top_sim.srv still import
    if e.name != "top_sim._core":
        raise
