"""The shipped rviz config (rviz/top_sim.rviz) as the tour found it wanting: no fixed-size grid display (the grid is
the node's, drawn around each top), no TF display drawing overlapping world/plane labels and a second z arrow at the
stem, the camera on the follow frame, every top's markers, the control panel and the interactive markers."""
import os
import subprocess
import sys

import yaml

CONFIG = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'rviz', 'top_sim.rviz')


def test_shipped_rviz_config():
    with open(CONFIG) as f:
        config = yaml.safe_load(f)  # rviz falls back to its default config when this fails
    manager = config['Visualization Manager']
    displays = {d['Class']: d for d in manager['Displays']}
    assert 'rviz/Grid' not in displays
    tf = displays.get('rviz/TF')
    assert tf is None or not tf['Enabled'] or not tf['Show Names'], 'TF labels overlap at the origin'
    assert tf is None or not tf['Enabled'] or not tf['Show Axes'], 'a second z arrow at the stem'
    assert displays['rviz/MarkerArray']['Marker Topic'] == '/top_sim/markers'
    assert displays['rviz/InteractiveMarkers']['Update Topic'] == '/top_sim_interactive/update'
    assert manager['Views']['Current']['Target Frame'] == 'follow'
    assert any(p['Class'] == 'top_sim/ControlPanel' for p in config['Panels'])


def test_window_layout_is_rviz_layout_s_with_the_panel_docked():
    """The dock layout is scripts/rviz_layout.py's for the config's window size (Displays, Views and the Top control
    panel as tabs of the left dock, the panel on top; test/ros/test_panel_widget.cpp checks the panel fits it)."""
    with open(CONFIG) as f:
        geometry = yaml.safe_load(f)['Window Geometry']
    script = os.path.join(os.path.dirname(CONFIG), '..', 'scripts', 'rviz_layout.py')
    wanted = subprocess.run([sys.executable, script, str(geometry['Width']), str(geometry['Height'])],
                            capture_output=True, text=True, check=True).stdout.strip()
    assert geometry['QMainWindow State'] == wanted
    assert (geometry['Width'], geometry['Height']) == (1280, 800)
    assert 'Top control'.encode('utf-16-be').hex() in wanted
