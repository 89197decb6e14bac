# The Python package top_sim for catkin (catkin_python_setup in cmake/ros.cmake): its sources in src/python/top_sim,
# served from the devel space next to the generated top_sim.msg and the compiled top_sim._core. Not run by hand.
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["top_sim"], package_dir={"": "src/python"}))
